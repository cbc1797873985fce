"""Fuzzed contacts: random bodies touching a ground plane and each other obey the laws of contact.

Hypothesis draws scenes (tests/fuzz_contacts.py: 1-3 free bodies with a
sphere, capsule, box or cylinder, sometimes two shapes, above, touching or
resting on a level or tilted plane, sometimes a sphere meeting another
body's sphere, box or capsule; random poses, velocities, masses and
inertias; stiffness 1e5..1e8, restitution 0.2..1, friction 0..1, static
friction, slip velocity; every method that places contact onsets: ggl,
index3, index1, projection-bdf, projection-adams, auto) and runs each in the
mechanism fuzzer's worker subprocess (tests/fuzz_mechanisms.py), so that a
crash or a hang fails one example, not pytest (the worker's TIMEOUT is each
op's wall-time budget). Every run either succeeds and keeps the laws of
fuzz_contacts.contact_problems (no energy gained, penetration within what
the energy allows and as the geometry shows, a stuck contact holding still
within mu_s F_n, a slipping one within mu F_n, events kept, finite readings;
and the mechanism fuzzer's result check), or raises mb.SimulationError /
mb.ModelError with a message (refusals are counted by message and printed;
most runs must succeed). A broken law is a failure of its own kind (one
exception class per set of laws), so hypothesis shrinks each to a minimal
scene and reports them all.

- test_fuzz_contacts_default: the default suite, a fixed seed,
  DEFAULT_EXAMPLES examples (about 15 s); it leaves out the features of
  fc.KNOWN_BUGS and counts (prints) the runs that break only the laws of
  fc.KNOWN_LAWS.
- test_fuzz_contacts_long: @pytest.mark.fuzz, LAGMB_FUZZ_CONTACT_EXAMPLES
  (500) examples from LAGMB_FUZZ_SEED; run with ``python3 -m pytest -m fuzz
  tests/test_fuzz_contacts.py`` or ``make test-fuzz``.
  LAGMB_FUZZ_CONTACTS_KNOWN=1 draws the known bugs' features too and fails
  on every broken law (to see whether a fix holds).
- the findings, shrunk, as explicit tests: xfail(strict=True) while the core
  breaks them (they pass, and must then lose the mark, once it is fixed;
  then drop their entry from KNOWN_BUGS or KNOWN_LAWS).

The draws are deterministic for a seed as long as the same modules are
loaded (hypothesis mixes in constants of the loaded code); the laws must
hold for every draw, so the default run passes whatever it draws.
"""

import collections
import os
import sys

import pytest
from hypothesis import HealthCheck, given, seed, settings

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fuzz_contacts as fc  # noqa: E402
import fuzz_mechanisms as fm  # noqa: E402

DEFAULT_EXAMPLES = 30
DEFAULT_SEED = 3
TIMEOUT = 60.0  # s per op: a healthy run takes well under 5 s
MIN_SUCCESS = 0.8  # of the runs: a fuzzer whose runs are refused checks nothing


class BrokenLaw(AssertionError):
    """A run broke a law of contact (a subclass per set of laws: hypothesis shrinks each apart)."""


_LAWS = {}


def _laws(problem):
    """The names of what a worker's problem broke: the laws of fuzz_contacts.check,
    or the mechanism fuzzer's kind (a crash, a hang, a foreign exception, a
    violated constraint, a non-finite result)."""
    detail = problem["detail"].split("\n")[0]
    if fc.LAWS_BROKEN in detail:
        return detail.split(fc.LAWS_BROKEN, 1)[1].split("; ")
    return [problem["key"]]


def _broken(laws):
    name = "; ".join(sorted(laws))
    if name not in _LAWS:
        _LAWS[name] = type("BrokenLaw", (BrokenLaw,), {"laws": name})
    return _LAWS[name]


def _refusal_problem(status):
    """(law, detail) if a refusal breaks a law, else None. A refusal must
    say what failed (a message of some words); and none may call the
    contacts' events Zeno behaviour: a compliant contact's touches last a
    time, so their onsets and releases cannot accumulate."""
    message = status.split(": ", 1)[1] if ": " in status else ""
    if len(message.split()) < 3:
        return "a refusal without a message", status
    if "Zeno" in message:
        return "refused as Zeno", status
    return None


def _fuzz(n, rng_seed, worker, known_bugs):
    """Run n drawn cases; -> ({refusal message: count}, {known law broken: count}, number of runs).
    Without known_bugs the laws of fc.KNOWN_LAWS are counted, not failed."""
    refused, known = collections.Counter(), collections.Counter()
    runs = [0]

    @seed(rng_seed)
    @settings(max_examples=n, database=None, deadline=None, suppress_health_check=list(HealthCheck),
              report_multiple_bugs=True)
    @given(fc.contact_cases(known_bugs=known_bugs))
    def run(case):
        problems, statuses = worker.run(case["ops"])
        runs[0] += 1
        unclear = []
        for k, status in statuses.items():
            if status.startswith("refused"):
                refused[fm._normalize(status[len("refused "):])] += 1
                why = _refusal_problem(status)
                if why:
                    unclear.append({"op": int(k), "key": why[0], "detail": f"{why[0]}: {why[1]}"})
        problems = problems + unclear
        laws = {law for p in problems for law in _laws(p)}
        new = laws if known_bugs else laws - set(fc.KNOWN_LAWS)
        if new:
            detail = "\n".join(f"-> {p['key']}\n   {p['detail']}" for p in problems)
            raise _broken(new)(fm.reproducer(case["ops"], statuses) + detail)
        known.update(laws)

    run()
    return refused, known, runs[0]


def _check(n, rng_seed):
    worker = fm.Worker(TIMEOUT)
    known_bugs = bool(os.environ.get("LAGMB_FUZZ_CONTACTS_KNOWN"))
    try:
        refused, known, runs = _fuzz(n, rng_seed, worker, known_bugs)
    finally:
        worker.close()
    total = sum(refused.values())
    print(f"\n{runs} fuzzed runs with contacts, {total} refused:")
    for message, count in refused.most_common():
        print(f"  {count:4d}  {message}")
    for law, count in known.most_common():
        print(f"  {count:4d}  runs broke a known law: {law} ({fc.KNOWN_LAWS[law]})")
    assert total <= (1.0 - MIN_SUCCESS) * runs, f"{total} of {runs} runs refused: {dict(refused)}"


def test_fuzz_contacts_default():
    """DEFAULT_EXAMPLES random scenes with contacts (seed DEFAULT_SEED), in the default suite."""
    _check(DEFAULT_EXAMPLES, DEFAULT_SEED)


@pytest.mark.fuzz
def test_fuzz_contacts_long(request):
    """LAGMB_FUZZ_CONTACT_EXAMPLES (500) random scenes with contacts, selected with -m fuzz."""
    if "fuzz" not in (request.config.getoption("markexpr", "") or ""):
        pytest.skip("long fuzz run: select it with -m fuzz")
    _check(int(os.environ.get("LAGMB_FUZZ_CONTACT_EXAMPLES", "500")),
           int(os.environ.get("LAGMB_FUZZ_SEED", "20240611")))


# --- the findings, shrunk (the core breaks them today; see fuzz_contacts.KNOWN_BUGS and KNOWN_LAWS) ---

import numpy as np  # noqa: E402

import lagmb as mb  # noqa: E402

G = 9.81


def _known(reason):
    return pytest.mark.xfail(strict=True, reason=reason)
