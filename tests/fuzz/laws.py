"""The one runner of the law fuzzers (test_fuzz_stops, test_fuzz_contacts).

Hypothesis draws cases from a strategy; the mechanism fuzzer's worker
subprocess (fuzz_mechanisms.Worker) runs each, so that a crash or a hang
fails one case, not pytest. A run either succeeds and keeps the laws its
fuzzer checks in the worker (a broken one reported after LAWS_BROKEN in a
problem's detail), or is refused by one of lagmb's exceptions; refusals
are counted by message and printed, and most runs must succeed. A broken
law is a failure of its own class (one per set of laws), so hypothesis
shrinks each apart and reports them all. Laws a fuzzer lists as known
(KNOWN_LAWS: the core breaks them today) are counted, not failed, unless
the known bugs are drawn too (then every broken law fails: to see whether
a fix holds).
"""

import collections

from hypothesis import HealthCheck, given, seed, settings

import fuzz_mechanisms as fm

MIN_SUCCESS = 0.8  # of the runs: a fuzzer whose runs are refused checks nothing


class BrokenLaw(AssertionError):
    """A run broke a law (a subclass per set of laws: hypothesis shrinks each apart)."""


_BROKEN = {}


def broken(laws):
    """The BrokenLaw subclass of this set of laws (one class per set)."""
    name = "; ".join(sorted(laws))
    if name not in _BROKEN:
        _BROKEN[name] = type("BrokenLaw", (BrokenLaw,), {"laws": name})
    return _BROKEN[name]


def laws_of(problem, laws_broken):
    """The names of what a worker's problem broke: the fuzzer's laws (after
    the marker laws_broken in its detail), or the mechanism fuzzer's kind
    (a crash, a hang, a foreign exception, a violated joint)."""
    detail = problem["detail"].split("\n")[0]
    if laws_broken in detail:
        return detail.split(laws_broken, 1)[1].split("; ")
    return [problem["key"]]


def fuzz(cases, n, rng_seed, worker, fuzzer, known_bugs, review=None):
    """Run n cases drawn from the strategy `cases` (seeded) in worker; ->
    ({refusal message: count}, {known law broken: count}, number of runs).
    fuzzer: the module with LAWS_BROKEN and KNOWN_LAWS. review(case,
    problems, statuses) -> problems, if given, adds or renames problems
    (a refusal that breaks a law, a hang that is a known law)."""
    refused, known = collections.Counter(), collections.Counter()
    runs = [0]

    @seed(rng_seed)
    @settings(max_examples=n, database=None, deadline=None, suppress_health_check=list(HealthCheck),
              report_multiple_bugs=True)
    @given(cases)
    def run(case):
        problems, statuses = worker.run(case["ops"])
        runs[0] += 1
        for status in statuses.values():
            if status.startswith("refused"):
                refused[fm.normalized_message(status[len("refused "):])] += 1
        if review:
            problems = review(case, problems, statuses)
        laws = {law for p in problems for law in laws_of(p, fuzzer.LAWS_BROKEN)}
        new = laws if known_bugs else laws - set(fuzzer.KNOWN_LAWS)
        if new:
            detail = "\n".join(f"-> {p['key']}\n   {p['detail']}" for p in problems)
            raise broken(new)(fm.reproducer(case["ops"], statuses) + detail)
        known.update(laws)

    run()
    return refused, known, runs[0]


def check(cases, n, rng_seed, timeout, fuzzer, known_bugs, what, review=None):
    """fuzz() in a fresh worker (timeout: seconds per op); prints the
    refusals and the known laws broken, and asserts that at least
    MIN_SUCCESS of the runs were not refused. what: "runs with stops"."""
    worker = fm.Worker(timeout)
    try:
        refused, known, runs = fuzz(cases, n, rng_seed, worker, fuzzer, known_bugs, review)
    finally:
        worker.close()
    total = sum(refused.values())
    print(f"\n{runs} fuzzed {what}, {total} refused:")
    for message, count in refused.most_common():
        print(f"  {count:4d}  {message}")
    for law, count in known.most_common():
        print(f"  {count:4d}  runs broke a known law: {law} ({fuzzer.KNOWN_LAWS[law]})")
    assert total <= (1.0 - MIN_SUCCESS) * runs, f"{total} of {runs} runs refused: {dict(refused)}"
