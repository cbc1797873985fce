"""Hostile scene files and options: `lagmb run` and `lagmb info` answer every
bad input with one line on stderr naming the file, table, key and line (or
the command-line option) and exit status 2; never a traceback, a crash or a
hang. Every case runs the command in a subprocess, so a crash of the
interpreter fails its test instead of killing pytest.

- The fuzzer's reproducers: an integer too large for a float, arrays nested
  a thousand deep, an integer of 5,000 digits, n_out = 3000000000 and
  max_order = 101 in [simulation], --plot out.xyz and --animate a.mp4
  (refused before running), /dev/zero, a file over the size limit, non-UTF-8
  bytes, scenes without bodies (empty, only comments, truncated before the
  first body).
- Wrong types and values for the keys, duplicate tables, unknown keys, bad
  paths, bad command-line values.
- Seeded mutations of examples/*.toml (lines deleted, duplicated, values
  swapped or replaced by huge, negative, non-finite, zero, string, table or
  deeply nested values, garbage bytes, truncation) through `lagmb info` and
  a short `lagmb run`: every outcome is exit 0, or exit 2 (bad scene) or 1
  (the documented "simulation failed", e.g. joints that no longer assemble)
  with one line naming the file. ~40 mutations by default; hundreds with
  ``pytest -m fuzz``.
"""

import glob
import json
import os
import random
import re
import resource
import subprocess
import sys
import textwrap

import pytest

from builders import lagmb_command, pendulum_scene
import paths  # noqa: E402  (tests/paths.py)

EXAMPLES = sorted(glob.glob(os.path.join(paths.EXAMPLES, "*.toml")))
MEMORY_LIMIT = 2 << 30  # a regression reading /dev/zero fails here, not in the OOM killer


def _limit_memory():
    # not under AddressSanitizer (make test-asan): its shadow memory reserves
    # terabytes of address space at start
    if "libasan" not in os.environ.get("LD_PRELOAD", ""):
        resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))


def lagmb(*args, cwd=None, timeout=120):
    return lagmb_command(*args, cwd=cwd, timeout=timeout, preexec_fn=_limit_memory)


def assert_one_line_error(p, *names):
    """Exit 2, one line on stderr (no traceback) that contains every name."""
    assert "Traceback" not in p.stderr, p.stderr
    assert p.returncode == 2, (p.returncode, p.stderr)
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1, p.stderr
    for name in names:
        assert name in lines[0], (name, lines[0])
    return lines[0]


PENDULUM = pendulum_scene() + """
[simulation]
t_end = 0.05
n_out = 11

[output]
reactions = ["pin"]
"""


def line_of(text, needle):
    return next(i for i, line in enumerate(text.splitlines(), 1) if needle in line)


def write(tmp_path, text, name="scene.toml"):
    path = tmp_path / name
    if isinstance(text, bytes):
        path.write_bytes(text)
    else:
        path.write_text(text)
    return path


def test_pendulum_runs(tmp_path):
    # the base of the cases below is a good scene
    path = write(tmp_path, PENDULUM)
    for command in ("info", "run"):
        p = lagmb(command, path, cwd=tmp_path)
        assert p.returncode == 0 and "Traceback" not in p.stderr, p.stderr



def scene_with(tmp_path, old, new, name="scene.toml"):
    """PENDULUM with old replaced by new: (path, line of the change)."""
    assert old in PENDULUM
    text = PENDULUM.replace(old, new)
    return write(tmp_path, text, name), line_of(text, new.split("\n")[0])


# --- the fuzzer's reproducers ---------------------------------------------------

@pytest.mark.parametrize("command", ["info", "run"])
def test_integer_too_large_for_a_float(tmp_path, command):
    path, line = scene_with(tmp_path, "position = [0.5, 0.0]", f"position = [{10**400}, 0.0]")
    message = assert_one_line_error(lagmb(command, path, cwd=tmp_path), str(path),
                                    f"line {line}", "bodies[0] 'rod'", "key 'position'")
    assert "too large for a float" in message and "401 digits" in message


@pytest.mark.parametrize("old, key", [
    ("position = [0.5, 0.0]", "position"),
    ("gravity = [0.0, -9.81]", "gravity"),
    ("n_out = 11", "t_out"),
    ('reactions = ["pin"]', "reactions"),
])
def test_arrays_nested_a_thousand_deep(tmp_path, old, key):
    path, line = scene_with(tmp_path, old, f"{key} = " + "[" * 1000 + "]" * 1000)
    message = assert_one_line_error(lagmb("info", path), str(path), f"line {line}",
                                    f"key '{key}'")
    assert "nested more than" in message


def test_nesting_split_over_lines_is_found_at_its_line(tmp_path):
    path, _ = scene_with(tmp_path, "n_out = 11", "t_out = [\n" + "[\n" * 1000 + "]" * 1001)
    text = path.read_text()
    deep = line_of(text, "t_out") + 32  # the bracket that opens level 33
    assert_one_line_error(lagmb("info", path), f"line {deep}", "[simulation]", "key 't_out'")


def test_integer_of_5000_digits(tmp_path):
    path, line = scene_with(tmp_path, "mass = 1.0", "mass = " + "7" * 5000)
    message = assert_one_line_error(lagmb("info", path), str(path), f"line {line}",
                                    "bodies[0]", "key 'mass'")
    assert "5000 digits" in message


@pytest.mark.parametrize("command", ["info", "run"])
@pytest.mark.parametrize("old, new, key, words", [
    ("n_out = 11", "n_out = 3000000000", "n_out", "at most 10,000,000"),
    ("n_out = 11", "n_out = 11\nmax_order = 101", "max_order", "1..5 for method 'auto'"),
    ("n_out = 11", 'n_out = 11\nformulation = "projection"\nintegrator = "adams"\n'
                   "max_order = 13", "max_order", "1..12 for method 'projection-adams'"),
    ("n_out = 11", "n_out = 11\nmax_steps = 100000000000000000000", "max_steps", "at most"),
])
def test_simulation_settings_out_of_range(tmp_path, command, old, new, key, words):
    path, _ = scene_with(tmp_path, old, new)
    line = line_of(path.read_text(), f"{key} =")
    message = assert_one_line_error(lagmb(command, path, cwd=tmp_path), str(path),
                                    f"line {line}", "[simulation]", f"key '{key}'")
    assert words in message and "Invoked with" not in message


@pytest.mark.parametrize("option, value, formats", [
    ("--plot", "out.xyz", ".png"),
    ("--plot", "out", ".png"),          # savefig would write out.png, not out
    ("--animate", "a.mp4", ".gif"),
])
def test_output_format_refused_before_running(tmp_path, option, value, formats):
    pytest.importorskip("matplotlib")
    path = write(tmp_path, PENDULUM.replace("t_end = 0.05", "t_end = 1000.0"))  # a long run
    p = lagmb("run", path, "-o", "x.npz", option, value, cwd=tmp_path, timeout=30)
    message = assert_one_line_error(p, f"{option} {value}", formats)
    assert not (tmp_path / "x.npz").exists()  # written after a run: there was none
    if option == "--animate":
        assert ".mp4" in message  # says that video is not written


@pytest.mark.parametrize("key, value", [("plot", "p.xyz"), ("animate", "a.mp4")])
def test_output_format_in_the_scene(tmp_path, key, value):
    pytest.importorskip("matplotlib")
    path, line = scene_with(tmp_path, 'reactions = ["pin"]', f'{key} = "{value}"')
    for command in ("info", "run"):
        assert_one_line_error(lagmb(command, path, cwd=tmp_path), str(path), f"line {line}",
                              "[output]", f"key '{key}'")


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="no /dev/zero")
@pytest.mark.parametrize("command", ["info", "run"])
def test_dev_zero(command):
    assert_one_line_error(lagmb(command, "/dev/zero", timeout=60), "/dev/zero", "16 MiB")


def test_file_over_the_size_limit(tmp_path):
    path = tmp_path / "huge.toml"
    with open(path, "wb") as fh:  # sparse: costs no disk
        fh.write(PENDULUM.encode())
        fh.truncate(17 << 20)
    assert_one_line_error(lagmb("info", path), str(path), "more than 16 MiB")


def test_not_utf8(tmp_path):
    path = write(tmp_path, PENDULUM.replace('name = "rod"', 'name = "r\udcf6d"').encode(
        "utf-8", "surrogateescape"))
    assert_one_line_error(lagmb("info", path), str(path), f"line {line_of(PENDULUM, 'rod')}",
                          "not UTF-8")


NO_BODIES = {
    "empty": "",
    "whitespace": "  \n\t\n\n",
    "comments": "# only comments\n\n# and blank lines\n",
    "truncated": PENDULUM[:PENDULUM.index("[[bodies]]")],  # before its first body
    "disabled": "[[bodies]]\nname = 'rod'\nmass = 1.0\ninertia = 1.0\nenabled = false\n",
}


@pytest.mark.parametrize("case", list(NO_BODIES))
def test_info_without_bodies(tmp_path, case):
    path = write(tmp_path, NO_BODIES[case])
    assert_one_line_error(lagmb("info", path), str(path), "no bodies")  # not a SIGFPE


@pytest.mark.parametrize("case", ["empty", "truncated"])
def test_run_without_bodies(tmp_path, case):
    path = write(tmp_path, NO_BODIES[case])
    assert_one_line_error(lagmb("run", path, "--t-end", "0.1"), str(path), "no bodies")


# --- wrong types and values: one harness run for the table ------------------------

# (PENDULUM text replaced, its replacement, the key named, a word of the reason)
WRONG = {
    "string for a number": ("mass = 1.0", 'mass = "heavy"', "mass", "must be a number"),
    "boolean for a number": ("mass = 1.0", "mass = true", "mass", "must be a number"),
    "table for a point": ("position = [0.5, 0.0]", "position = { x = 0.5 }", "position",
                          "pair of numbers"),
    "three numbers for a point": ("at = [0.0, 0.0]", "at = [0.0, 0.0, 0.0]", "at",
                                  "pair of numbers"),
    "nan in a point": ("at = [0.0, 0.0]", "at = [nan, 0.0]", "at", "finite"),
    "inf inertia": ("inertia = 0.08333333333333333", "inertia = inf", "inertia", "finite"),
    "1e400 is inf": ("mass = 1.0", "mass = -1e400", "mass", "finite"),
    "huge integer gravity": ("gravity = [0.0, -9.81]", f"gravity = [0, -{10**309}]",
                             "gravity", "too large"),
    "negative mass": ("mass = 1.0", "mass = -1.0", "mass", "positive"),
    "number for a name": ('name = "rod"', "name = 5", "name", "must be a string"),
    "empty name": ('name = "pin"', 'name = ""', "name", "non-empty"),
    "array for a body": ('body_j = "rod"', 'body_j = ["rod"]', "body_j", "must be a string"),
    "unknown key": ("mass = 1.0", "mass = 1.0\nmasss = 1.0", "masss", "unknown key"),
    "unknown type": ('type = "revolute"', 'type = "hinge"', "type", "hinge"),
    "zero n_out": ("n_out = 11", "n_out = 0", "n_out", "at least 2"),
    "negative n_out": ("n_out = 11", "n_out = -5", "n_out", "at least 2"),
    "float n_out": ("n_out = 11", "n_out = 1e3", "n_out", "must be an integer"),
    "zero max_steps": ("n_out = 11", "n_out = 11\nmax_steps = 0", "max_steps", "at least 1"),
    "zero max_order": ("n_out = 11", "n_out = 11\nmax_order = 0", "max_order", "1..5"),
    "nan t_end": ("t_end = 0.05", "t_end = nan", "t_end", "finite"),
    "inf t0": ("t_end = 0.05", "t_end = 0.05\nt0 = inf", "t0", "finite"),
    "string rtol": ("n_out = 11", 'n_out = 11\nrtol = "1e-6"', "rtol", "must be a number"),
    "zero step": ("n_out = 11", 'n_out = 11\nformulation = "ali3p"\nstep = 0.0', "step",
                  "positive"),
    "string in t_out": ("n_out = 11", 't_out = [0.0, "a"]', "t_out", "must be a number"),
    "t_out past t_end": ("n_out = 11", "t_out = [0.0, 1.0]", "t_out", "t_end"),
    "unknown formulation": ("n_out = 11", 'n_out = 11\nformulation = 3', "formulation",
                            "must be a string"),
    "unknown integrator": ("n_out = 11", 'n_out = 11\nintegrator = "rk4"', "integrator", "rk4"),
    "string for reactions": ('reactions = ["pin"]', 'reactions = "pin"', "reactions",
                             "array of strings"),
    "unknown reaction": ('reactions = ["pin"]', 'reactions = ["pen"]', "reactions", "pen"),
    "string for energy": ('reactions = ["pin"]', 'energy = "yes"', "energy", "true or false"),
    "NUL in a file name": ('reactions = ["pin"]', 'file = "a\\u0000.npz"', "file", "NUL"),
    "output file type": ('reactions = ["pin"]', 'file = "a.txt"', "file", ".npz or .csv"),
    "datetime for a number": ("mass = 1.0", "mass = 1979-05-27T07:32:00Z", "mass",
                              "must be a number"),
    "model as an array": ("[model]", "[[model]]", "model", "must be a table"),
    "bodies as a table": ("[[bodies]]", "[bodies]", "bodies", "array of tables"),
    "unknown top-level key": ("[model]", "speed = 3\n[model]", "speed", "unknown top-level"),
}
# only a line: TOML itself refuses these
NOT_TOML = {
    "duplicate table": ("[output]", "[simulation]\n[output]", "[simulation]\n[output]"),
    "duplicate key": ("mass = 1.0", "mass = 1.0\nmass = 2.0", "mass = 2.0"),
    "truncated array": ("at = [0.0, 0.0]", "at = [0.0, 0.0", "[simulation]"),
    "NUL byte": ("mass = 1.0", "mass = 1.0\0", "mass = 1.0"),
}


@pytest.fixture(scope="module")
def wrong_results(tmp_path_factory):
    """{case: (exit code, stderr, crash)} for `info` on each scene of WRONG and
    NOT_TOML, and `run` on those with a [simulation] mistake."""
    folder = tmp_path_factory.mktemp("wrong")
    cases = []
    for k, (name, (old, new, *_)) in enumerate({**WRONG, **NOT_TOML}.items()):
        assert old in PENDULUM, name
        path = write(folder, PENDULUM.replace(old, new), f"w{k}.toml")
        cases.append({"id": f"info {name}", "argv": ["info", str(path)]})
        cases.append({"id": f"run {name}", "argv": ["run", str(path), "-q"]})
    return folder, run_cases(cases, folder)


@pytest.mark.parametrize("command", ["info", "run"])
@pytest.mark.parametrize("case", list(WRONG))
def test_wrong_value(wrong_results, case, command):
    folder, results = wrong_results
    old, new, key, words = WRONG[case]
    code, stderr, crash = results[f"{command} {case}"]
    assert crash is None, crash
    text = PENDULUM.replace(old, new)
    changed = new.split("\n")[-1] if new.startswith(old) else new.split("\n")[0]
    p = subprocess.CompletedProcess([], code, "", stderr)
    assert_one_line_error(p, ".toml", f"line {line_of(text, changed)}", f"key '{key}'", words)


@pytest.mark.parametrize("case", list(NOT_TOML))
def test_not_toml(wrong_results, case):
    folder, results = wrong_results
    old, new, at = NOT_TOML[case]
    code, stderr, crash = results[f"info {case}"]
    assert crash is None, crash
    text = PENDULUM.replace(old, new)
    line = line_of(text, at) if case != "duplicate table" else text.splitlines().index(
        "[simulation]", line_of(text, "[simulation]")) + 1
    p = subprocess.CompletedProcess([], code, "", stderr)
    assert_one_line_error(p, ".toml", f"line {line}", "not valid TOML")


def test_massless_body_at_run_time_names_the_body(tmp_path):
    # mass 0 is allowed, so the reader takes it; a rod without mass or inertia on a pin turns with nothing
    # to follow it, and the run refuses it (issue 41: a massless body runs where its joints hold it)
    # (`lagmb info` of this scene fails too: its position solve in the M-metric needs M > 0)
    path, line = scene_with(tmp_path, "mass = 1.0\ninertia = 0.08333333333333333", "mass = 0.0\ninertia = 0.0")
    assert_one_line_error(lagmb("run", path, cwd=tmp_path), str(path), f"line {line}",
                          "bodies[0] 'rod'", "key 'mass'", "massless")


# --- paths and options ------------------------------------------------------------

def test_bad_scene_paths(tmp_path):
    assert_one_line_error(lagmb("info", tmp_path), "cannot read", str(tmp_path), "directory")
    missing = tmp_path / "nowhere.toml"
    assert_one_line_error(lagmb("run", missing), "cannot read", str(missing))
    if os.geteuid() != 0:  # root reads anything
        locked = write(tmp_path, PENDULUM, "locked.toml")
        locked.chmod(0)
        assert_one_line_error(lagmb("info", locked), "cannot read", str(locked))


def test_unwritable_outputs_refused_before_running(tmp_path):
    path = write(tmp_path, PENDULUM)
    (tmp_path / "a_file").write_text("")
    (tmp_path / "folder.npz").mkdir()
    for option, target, words in [
            ("-o", tmp_path / "a_file" / "x.npz", "not a folder"),
            ("-o", tmp_path / "folder.npz", "is a directory"),
            ("--plot", tmp_path / "a_file" / "deeper" / "p.png", "not a folder")]:
        if option == "--plot":
            pytest.importorskip("matplotlib")
        p = lagmb("run", path, option, target, cwd=tmp_path)
        assert_one_line_error(p, f"{option} {target}", words)
        assert p.stdout == ""  # no run summary: it never ran
    path.write_text(PENDULUM + 'file = "a_file/x.npz"\n')
    assert_one_line_error(lagmb("run", path, cwd=tmp_path), str(path),
                          f"line {line_of(path.read_text(), 'file =')}", "key 'file'",
                          "not a folder")


@pytest.mark.parametrize("option, value, words", [
    ("--n-out", "3000000000", "at most 10,000,000"),
    ("--n-out", "1", "at least 2"),
    ("--t-end", "nan", "finite"),
    ("--t-end", "inf", "finite"),
    ("--t-end", "-1", "greater than 0"),
    ("--rtol", "0", "greater than 0"),
    ("--rtol", "1e-20", "rtol"),         # the core's bound, at run time
])
def test_bad_options(tmp_path, option, value, words):
    path = write(tmp_path, PENDULUM)
    p = lagmb("run", path, option, value, "-q", cwd=tmp_path)
    assert_one_line_error(p, option, words)


# --- seeded mutations of the examples ---------------------------------------------

# values a mutation puts in place of a number or of a whole value
HOSTILE = [
    "1" + "0" * 400,            # an integer too large for a float
    "9" * 5000,                 # over Python's int-string-conversion limit
    "-1", "-1.0e300", "0", "0.0", "-0.0", "5e-324", "1e400", "nan", "inf", "-inf",
    "3000000000", "9223372036854775808",   # over C int, over C long
    '"x"', '""', "true", "{}", "[]", "[1.0, 2.0, 3.0]", "[[0.0, 1.0]]",
    "[" * 1000 + "]" * 1000, "{ type = \"linear\" }", "1979-05-27T07:32:00Z",
]
GARBAGE = [b"\xff", b"\xc3", b"\x00", b"\"", b"[", b"{", b"=", b"\n", b"'''", b"\\", b"\r"]
_KEY_LINE = re.compile(r"^(\s*)([A-Za-z0-9_.\"-]+)(\s*=\s*)(.*?)(\s+#.*)?$")
_NUMBER = re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?(?![\w.])")


def _key_lines(lines):
    return [i for i, line in enumerate(lines) if _KEY_LINE.match(line)]


def _mutate_once(text, rng):
    """One mutation of a scene's text: (new text or bytes, what was done)."""
    lines = text.split("\n")
    keyed = _key_lines(lines)
    what = rng.choice(["delete line", "duplicate line", "swap values", "hostile number",
                       "hostile value", "rename key", "truncate", "duplicate table",
                       "garbage"])
    if what == "delete line":
        i = rng.randrange(len(lines))
        return "\n".join(lines[:i] + lines[i + 1:]), f"{what} {i + 1}"
    if what == "duplicate line":
        i = rng.randrange(len(lines))
        j = rng.randrange(len(lines) + 1)
        return "\n".join(lines[:j] + [lines[i]] + lines[j:]), f"{what} {i + 1} at {j + 1}"
    if what == "swap values" and len(keyed) >= 2:
        i, j = rng.sample(keyed, 2)
        a, b = _KEY_LINE.match(lines[i]), _KEY_LINE.match(lines[j])
        lines[i] = a.group(1) + a.group(2) + a.group(3) + b.group(4)
        lines[j] = b.group(1) + b.group(2) + b.group(3) + a.group(4)
        return "\n".join(lines), f"{what} of lines {i + 1} and {j + 1}"
    if what == "hostile number":
        spots = [(i, m) for i in keyed for m in _NUMBER.finditer(lines[i])
                 if m.start() > lines[i].index("=")]
        if spots:
            i, m = rng.choice(spots)
            value = rng.choice(HOSTILE)
            lines[i] = lines[i][:m.start()] + value + lines[i][m.end():]
            return "\n".join(lines), f"{what} {value[:20]!r} on line {i + 1}"
    if what in ("hostile value", "hostile number") and keyed:
        i = rng.choice(keyed)
        m = _KEY_LINE.match(lines[i])
        value = rng.choice(HOSTILE)
        lines[i] = m.group(1) + m.group(2) + m.group(3) + value
        return "\n".join(lines), f"hostile value {value[:20]!r} on line {i + 1}"
    if what == "rename key" and keyed:
        i = rng.choice(keyed)
        m = _KEY_LINE.match(lines[i])
        other = _KEY_LINE.match(lines[rng.choice(keyed)]).group(2)
        key = rng.choice([m.group(2) + "_x", other, ""])
        lines[i] = m.group(1) + key + m.group(3) + m.group(4)
        return "\n".join(lines), f"{what} on line {i + 1} to {key!r}"
    if what == "duplicate table":
        headers = [i for i, line in enumerate(lines) if line.startswith("[")]
        if headers:
            k = rng.randrange(len(headers))
            start = headers[k]
            end = headers[k + 1] if k + 1 < len(headers) else len(lines)
            block = lines[start:end] if rng.random() < 0.5 else lines[start:start + 1]
            j = rng.randrange(len(lines) + 1)
            return "\n".join(lines[:j] + block + lines[j:]), f"{what} line {start + 1} at {j + 1}"
    if what == "garbage":
        raw = text.encode()
        i = rng.randrange(len(raw) + 1)
        junk = rng.choice(GARBAGE)
        return raw[:i] + junk + raw[i:], f"{what} {junk!r} at byte {i}"
    cut = rng.randrange(len(text) + 1)
    return text[:cut], f"truncate at {cut}"


def mutate(text, rng):
    """One to three mutations: (bytes, description)."""
    done = []
    for _ in range(rng.choice([1, 1, 1, 2, 3])):
        if isinstance(text, bytes):
            text = text.decode("utf-8", errors="replace")
        text, what = _mutate_once(text, rng)
        done.append(what)
    return (text if isinstance(text, bytes) else text.encode()), "; ".join(done)


# Runs the cases (argv lists) through lagmb.cli.main in one interpreter: the
# import is paid once. A case over its time budget is stopped by SIGALRM (the
# core checks signals between steps); a crash of the interpreter shows as a
# case started without a result.
HARNESS = textwrap.dedent(r'''
    import contextlib, io, json, signal, sys, traceback

    class OverBudget(BaseException):
        pass

    def stop(signum, frame):
        raise OverBudget()

    cases_path, results_path, budget = sys.argv[1], sys.argv[2], float(sys.argv[3])
    from lagmb.cli import main
    signal.signal(signal.SIGALRM, stop)
    with open(cases_path) as fh:
        cases = json.load(fh)
    with open(results_path, "a") as out:
        for case in cases:
            out.write(json.dumps({"id": case["id"]}) + "\n")
            out.flush()
            err, code, crash = io.StringIO(), None, None
            signal.setitimer(signal.ITIMER_REAL, budget)
            try:
                with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
                    try:
                        code = main(case["argv"])
                    except SystemExit as e:
                        code = e.code
            except OverBudget:
                crash = f"over its budget of {budget} s"
            except BaseException:
                crash = traceback.format_exc()
            finally:
                signal.setitimer(signal.ITIMER_REAL, 0)
            out.write(json.dumps({"id": case["id"], "code": code, "stderr": err.getvalue(),
                                  "crash": crash}) + "\n")
            out.flush()
''')


def run_cases(cases, folder, budget=20.0):
    """{case id: (exit code, stderr, crash or None)}; a case that kills the
    interpreter gets the signal as its crash and the rest run in a new one."""
    results, todo = {}, list(cases)
    script = folder / "harness.py"
    script.write_text(HARNESS)
    while todo:
        cases_path, results_path = folder / "cases.json", folder / "results.jsonl"
        cases_path.write_text(json.dumps(todo))
        results_path.write_text("")
        p = subprocess.run([sys.executable, str(script), str(cases_path), str(results_path),
                            str(budget)], cwd=folder, capture_output=True, text=True,
                           timeout=budget * len(todo) + 60, preexec_fn=_limit_memory,
                           env={**os.environ, "LAGMB_TRACEBACK": "1"})  # a bug shows where
        started = None
        for line in results_path.read_text().splitlines():
            r = json.loads(line)
            if "code" in r:
                results[r["id"]] = (r["code"], r["stderr"], r["crash"])
                started = None
            else:
                started = r["id"]
        if started is not None:  # the interpreter died in this case
            results[started] = (p.returncode, p.stderr, f"interpreter died ({p.returncode})")
        elif p.returncode != 0:
            raise AssertionError(f"harness failed: {p.stderr}")
        todo = [c for c in todo if c["id"] not in results]
    return results


def fuzz_cases(folder, n, seed):
    """n mutated examples written to folder: the `info` and `run` cases, and
    each case's description."""
    rng = random.Random(seed)
    cases, described = [], {}
    originals = {path: open(path, encoding="utf-8").read() for path in EXAMPLES}
    for k in range(n):
        source = rng.choice(EXAMPLES)
        data, what = mutate(originals[source], rng)
        path = folder / f"m{k:04d}_{os.path.basename(source)}"
        path.write_bytes(data)
        name = os.path.basename(source)
        described[f"info {k}"] = described[f"run {k}"] = f"{path.name}: {what} of {name}"
        cases.append({"id": f"info {k}", "argv": ["info", str(path)]})
        out = folder / f"m{k:04d}.{rng.choice(['npz', 'csv'])}"
        cases.append({"id": f"run {k}", "argv": ["run", str(path), "--t-end", "0.01",
                                                 "--n-out", "5", "-q", "-o", str(out)]})
    return cases, described


def check_fuzz(tmp_path, n, seed):
    cases, described = fuzz_cases(tmp_path, n, seed)
    results = run_cases(cases, tmp_path)
    bad = []
    for case in cases:
        code, stderr, crash = results[case["id"]]
        scene = os.path.basename(case["argv"][1])
        # warnings (e.g. redundant joints) come first, one line each
        lines = [x for x in stderr.strip().splitlines() if "Warning: " not in x]
        if crash is not None:
            bad.append(f"{case['id']} ({described[case['id']]}): {crash}")
        elif code not in (0, 1, 2):
            bad.append(f"{case['id']} ({described[case['id']]}): exit {code}: {stderr}")
        elif code != 0 and (len(lines) != 1 or scene not in lines[0]
                            or "Traceback" in stderr):
            bad.append(f"{case['id']} ({described[case['id']]}): exit {code}, "
                       f"not one line naming the file: {stderr}")
    assert not bad, f"{len(bad)} of {len(cases)} cases:\n" + "\n".join(bad)
    return results


def test_fuzzed_examples(tmp_path):
    check_fuzz(tmp_path, 100, "lagmb fuzz")


@pytest.mark.fuzz
def test_fuzzed_examples_long(tmp_path):
    check_fuzz(tmp_path, 2000, "lagmb fuzz long")
