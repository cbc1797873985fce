"""The mechanism fuzzers' worker: runs cases (lists of ops, each Python
source over ``mb``, ``np``, ``nan`` and ``inf``) op by op in a subprocess,
so that a segfault, an abort or a hang in the core fails one case instead
of killing pytest, and checks what each op returns (fuzz_mechanisms' module
docstring says what is a problem). Also what the parent does with it:
Worker (the subprocess, with its crashes and hangs), run_cases, minimize,
Findings, reproducer (a case as a standalone script), replay and
script_ops (a script back into ops).

    python3 tests/fuzz/worker.py --worker   # the worker itself (reads cases on stdin)
"""

import json
import math
import os
import re
import selectors
import signal
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
RESIDUAL_BOUND = 1e-4  # a "successful" run must keep max |Phi| <= RESIDUAL_BOUND * (1 + max |q|)

HEADER = ("import numpy as np\n"
          "import lagmb as mb\n"
          "from math import nan, inf\n")

#: marks an op that lagmb must not refuse (a reproducer keeps it, script_ops reads it)
MUST_SUCCEED = "# must succeed"
#: the kind of the op two threads run (a worker that ran one is replaced after the case)
THREADS_KIND = "Simulator.advance (2 threads)"

def _indent(code, n=4):
    return "".join(" " * n + ln + "\n" for ln in code.rstrip("\n").split("\n"))


def reproducer(ops, statuses=None, outcome=None):
    """A standalone script for the ops. With the statuses of a run: ops that
    were skipped are left out and ops that lagmb refused are wrapped in
    try/except, so the script runs to the op of interest; ``outcome`` is
    appended as a comment."""
    statuses = statuses or {}
    text = HEADER + "\n"
    for k, op in enumerate(ops):
        s = statuses.get(str(k), statuses.get(k))
        if s == "skipped":
            continue
        if s and s.startswith("refused"):
            text += "try:\n" + _indent(op["code"]) + \
                "except (mb.ModelError, mb.SimulationError) as e:  # refused by lagmb: fine\n" + \
                "    print(type(e).__name__, e)\n"
        else:
            text += op["code"].rstrip("\n") + "\n"
    if outcome:
        text += "# -> " + outcome.replace("\n", "\n#    ") + "\n"
    return text


# ---------------------------------------------------------------------------
# The worker (runs in a subprocess)
# ---------------------------------------------------------------------------

def _finite_problems(value, path="value", out=None):
    import numpy as np

    out = [] if out is None else out
    if isinstance(value, dict):
        for k, v in value.items():
            _finite_problems(v, f"{path}[{k!r}]", out)
    elif isinstance(value, (list, tuple)):
        for k, v in enumerate(value):
            _finite_problems(v, f"{path}[{k}]", out)
    elif isinstance(value, (float, int, np.ndarray, np.generic)) and not isinstance(value, bool):
        a = np.asarray(value)
        if a.dtype.kind in "fc" and not np.all(np.isfinite(a)):
            out.append(path)
    return out


def _result_problems(mb, np, r, m, allowed):
    """Non-finite arrays or a silently violated constraint in a Result. A
    quantity lagmb refuses to give (e.g. r.lam of a kinematic-only run) is
    skipped; any other exception propagates (a finding)."""
    bad = []

    def get(f):
        try:
            return np.asarray(f(), dtype=float)
        except allowed:
            return None

    arrays = {"t": get(lambda: r.t), "q": get(lambda: r.q), "v": get(lambda: r.v), "a": get(lambda: r.a),
              "lam": get(lambda: r.lam), "energy": get(lambda: r.energy), "residual": get(lambda: r.residual)}
    for method, kw in m.elements:
        if method.startswith(("add_revolute", "add_translational", "add_weld", "add_distance",
                              "add_pin_in_slot", "add_gear", "add_rack_pinion", "drive_")):
            for frame in ("global", "joint"):
                arrays[f"reaction(frame={frame!r})"] = get(lambda: r.reaction(kw["name"], frame=frame))
    for name, a in arrays.items():
        if a is not None and not np.all(np.isfinite(a)):
            bad.append(("nonfinite", "." + name))
    if arrays["t"] is not None and len(arrays["t"]) == 0:
        bad.append(("empty", "t"))
    if arrays["t"] is not None and np.any(np.diff(arrays["t"]) < 0):
        k = int(np.flatnonzero(np.diff(arrays["t"]) < 0)[0])
        bad.append(("t decreasing", f"r.t[{k + 1}] = {arrays['t'][k + 1]:.6g} < r.t[{k}] = {arrays['t'][k]:.6g}"))
    res, q = arrays["residual"], arrays["q"]
    # index1 integrates Phi'' = 0 only, and CVODE cannot project Adams steps: their drift is documented
    # (docs/methods.md, formulations; a drift that came apart fails the run at its next event)
    drifts = r.stats.get("formulation") == "index1" or r.stats.get("integrator") == "adams"
    if not drifts and res is not None and q is not None and res.size and np.all(np.isfinite(res)) and np.all(np.isfinite(q)):
        bound = RESIDUAL_BOUND * (1.0 + (np.max(np.abs(q)) if q.size else 0.0))
        worst = float(np.max(res))
        if worst > bound:
            k = int(np.argmax(res))
            bad.append(("residual", f"max |Phi| = {worst:.3g} > {bound:.3g} at t = {float(r.t[k]):.4g}"))
    if not drifts and not bad and m.dimension == 3:
        bad += driver_problems(np, m, r._core, r.t, r.q, r.input)
    return bad


def _equilibrium_problems(np, eq):
    bad = []
    if eq.model.dimension == 3 and math.isfinite(eq.constraint_residual) and \
            eq.constraint_residual <= RESIDUAL_BOUND * (1.0 + float(np.max(np.abs(eq.q), initial=0.0))):
        initial = {d["name"]: d["initial"] for d in eq._core.inputs}
        bad += driver_problems(np, eq.model, eq._core, np.array([eq.t]), eq.q[None],
                                lambda name: np.array([initial[name]]))
    for name in ("q", "lam", "stiffness_eigenvalues", "softest_mode"):
        if not np.all(np.isfinite(getattr(eq, name))):
            bad.append(("nonfinite", "." + name))
    for name in ("force_residual", "constraint_residual"):
        if not math.isfinite(getattr(eq, name)):
            bad.append(("nonfinite", "." + name))
    q = eq.q
    if np.all(np.isfinite(q)) and math.isfinite(eq.constraint_residual):
        bound = RESIDUAL_BOUND * (1.0 + (float(np.max(np.abs(q))) if q.size else 0.0))
        if eq.constraint_residual > bound:
            bad.append(("residual", f"constraint_residual = {eq.constraint_residual:.3g} > {bound:.3g}"))
    return bad


def rotations(p):
    """(k, 3, 3) rotation matrices (body axes into global axes) of Euler parameters p (k, 4), normalized."""
    import numpy as np

    p = np.asarray(p, dtype=float)
    w, x, y, z = (p / np.linalg.norm(p, axis=1)[:, None]).T
    return np.stack([
        np.stack([w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)], axis=1),
        np.stack([2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)], axis=1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z], axis=1)], axis=1)


def _commanded(f, times, input_values):
    """(k,) what a driver's f commands at times: input_values for an mb.Input,
    else f(t) (a number, a time function or a callable t -> (y, dy, ddy));
    None if it cannot be told (a callable that fails or returns junk)."""
    import numpy as np

    if input_values is not None:
        return np.asarray(input_values, dtype=float)
    if isinstance(f, (int, float)) and not isinstance(f, bool):
        return np.full(len(times), float(f))
    try:
        out = []
        for t in times:
            y = f(float(t))
            out.append(float(y[0] if isinstance(y, (tuple, list, np.ndarray)) else y))
        out = np.asarray(out)
    except Exception:  # noqa: BLE001 - a bad callable: nothing to compare with
        return None
    return out if np.all(np.isfinite(out)) else None


def driver_problems(np, model, core, times, Q, input_of):
    """Spatial drivers hold what they command, at every output (times (k,),
    coordinates Q (k, n)): a revolute's angle about its axis (0 in the initial
    configuration, body_j relative to body_i) equals f modulo 2 pi; a
    cylindrical's or translational's slide along its axis, and a driven
    coordinate of a body, equal f. input_of(name) -> (k,) values of an input.
    -> [(tag, detail)], the first output that misses of each driver."""
    bad = []
    if model.dimension != 3 or Q.ndim != 2 or len(times) == 0 or not np.all(np.isfinite(Q)):
        return bad
    elements = {kw["name"]: (method, kw) for method, kw in model.elements}
    inputs = {d["element"]: d["name"] for d in core.inputs if d["parameter"] == "f"}
    q0 = np.asarray(core.initial_state()[0], dtype=float)
    tol = RESIDUAL_BOUND * (1.0 + float(np.max(np.abs(Q))))
    k_out = len(times)

    def frame(body, q):  # (rotations (k, 3, 3), positions (k, 3)) of a body along rows q
        if body == "ground":
            return np.broadcast_to(np.eye(3), (len(q), 3, 3)), np.zeros((len(q), 3))
        first, _ = core.body_coordinates(body)
        return rotations(q[:, first + 3:first + 7]), q[:, first:first + 3]

    for name, (method, kw) in elements.items():
        if method not in ("drive_joint", "drive_body"):
            continue
        f = _commanded(kw["f"], times, input_of(inputs[name]) if name in inputs else None)
        if f is None:
            continue
        if method == "drive_body":
            _, r = frame(kw["body"], Q)
            what, value = f"{kw['coordinate']} of body '{kw['body']}'", r[:, "xyz".index(kw["coordinate"])]
            off = value - f
            tag = "body driver"
        else:
            jmethod, j = elements[kw["joint"]]
            Ai, ri = frame(j["body_i"], Q)
            Aj, rj = frame(j["body_j"], Q)
            Ai0, ri0 = (x[0] for x in frame(j["body_i"], q0[None]))
            Aj0, rj0 = (x[0] for x in frame(j["body_j"], q0[None]))
            axis = np.asarray(j["axis"], dtype=float)
            axis_i = Ai0.T @ (axis / np.linalg.norm(axis))  # fixed in body i
            if core.element_kind(kw["joint"]) == "spatial_revolute":
                # the turn of body j relative to body i since the initial configuration, in body i's axes
                D = np.einsum("kji,kjl->kil", Ai, Aj) @ (Ai0.T @ Aj0).T
                sin = np.stack([D[:, 2, 1] - D[:, 1, 2], D[:, 0, 2] - D[:, 2, 0], D[:, 1, 0] - D[:, 0, 1]], 1) / 2
                value = np.arctan2(sin @ axis_i, (np.trace(D, axis1=1, axis2=2) - 1) / 2)
                off = np.mod(value - f + np.pi, 2 * np.pi) - np.pi
                what, tag = f"angle of revolute '{kw['joint']}'", "revolute driver"
            else:
                at = np.asarray(j["at"], dtype=float)
                si, sj = Ai0.T @ (at - ri0), Aj0.T @ (at - rj0)
                d = (rj + Aj @ sj) - (ri + Ai @ si)
                value = np.einsum("ki,ki->k", Ai @ axis_i, d)
                off = value - f
                what, tag = f"slide of {jmethod[4:]} '{kw['joint']}'", "slide driver"
        miss = np.flatnonzero(~(np.abs(off) <= tol))
        if miss.size:
            k = int(miss[0])
            by_pi = tag == "revolute driver" and abs(abs(off[k]) - np.pi) < 1e-3
            bad.append((tag + (" off by pi" if by_pi else " off"),
                        f"driver '{name}': {what} = {value[k]:.6g} at t = {float(times[k]):.4g} (output {k} of "
                        f"{k_out}), commanded {f[k]:.6g}{' (mod 2 pi)' if tag == 'revolute driver' else ''}: "
                        f"off by {off[k]:.3g}"))
    return bad


def _where(tb):
    """The innermost traceback frame inside lagmb (file:function), if any."""
    import traceback

    frames = traceback.extract_tb(tb)
    for fr in reversed(frames):
        if os.sep + "lagmb" + os.sep in fr.filename:
            return f"{os.path.basename(fr.filename)}:{fr.name}"
    return frames[-1].name if frames else "?"


def normalized_message(msg):
    msg = msg.splitlines()[0] if msg else ""
    msg = re.sub(r"'[^']*'", "'…'", msg)
    msg = re.sub(r"\"[^\"]*\"", "'…'", msg)
    msg = re.sub(r"\([^()]*\)", "(…)", msg)
    msg = re.sub(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?", "#", msg)
    msg = re.sub(r"\b(nan|inf)\b", "#", msg)
    return msg[:70]


def _names(code):
    """(names an op assigns or defines, names it reads)."""
    import ast

    tree = ast.parse(code)
    stores, loads = set(), set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Name):
            (stores if isinstance(node.ctx, ast.Store) else loads).add(node.id)
        elif isinstance(node, ast.FunctionDef):
            stores.add(node.name)
        elif isinstance(node, ast.arg):
            stores.add(node.arg)
    return stores, loads


def worker_main():
    """Read cases (JSON lines) on stdin; run each; report on the protocol fd:
    "S k" before op k, "E k status" after it, "R [problems]" at the end."""
    import resource
    import warnings

    proto = os.fdopen(os.dup(1), "w", buffering=1)
    os.dup2(2, 1)  # anything the library or a callable prints goes to stderr
    # no address-space limit under AddressSanitizer (make test-asan): its
    # shadow memory reserves terabytes of address space at start
    if "libasan" not in os.environ.get("LD_PRELOAD", ""):
        try:
            limit = 4 * 1024 ** 3
            resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
        except (ValueError, OSError):
            pass
    warnings.simplefilter("ignore")
    import numpy as np

    np.seterr(all="ignore")
    import lagmb as mb

    allowed = tuple(getattr(mb, n) for n in ("ModelError", "SimulationError", "SceneError"))
    proto.write("READY\n")
    for line in sys.stdin:
        case = json.loads(line)
        problems = []
        ns = {"mb": mb, "np": np, "nan": math.nan, "inf": math.inf, "__name__": "__fuzz__"}
        all_ok = True  # every op so far returned (a "must succeed" op is well posed only then)
        names = [_names(op["code"]) for op in case["ops"]]
        own = set().union(*(s for s, _ in names)) if names else set()
        for k, op in enumerate(case["ops"]):
            # an op that reads a variable an earlier (refused) op never bound is skipped
            if any(n not in ns for n in (names[k][1] & own) - names[k][0]):
                proto.write(f"E {k} skipped\n")
                continue
            proto.write(f"S {k}\n")
            kind, status, t_start = op["kind"], "ok", time.monotonic()
            try:
                exec(compile(op["code"], f"<op {k}>", "exec"), ns)
                check = op.get("check")
                if check:
                    what, var = check.split(":")
                    value = ns[var]
                    if what == "finite":
                        found = [("nonfinite", p) for p in _finite_problems(value, "")]
                    elif what == "result":
                        found = _result_problems(mb, np, value, value.model, allowed)
                        form = re.search(r"formulation='(\w+)'", op["code"])
                        if kind != "Simulator.result":
                            kind = f"simulate[{form.group(1) if form else 'ggl'}]"
                    else:
                        found = _equilibrium_problems(np, value)
                    for tag, detail in found:
                        status = "problem"
                        # the key names which array is non-finite or empty; other tags carry numbers
                        keyed = tag in ("nonfinite", "empty")
                        problems.append({"op": k, "key": f"{kind}: {tag}" + (f" {detail}" if keyed else ""),
                                         "detail": f"{tag}: {var}{detail}" if tag == "nonfinite" else
                                         f"{tag}: {detail}"})
            except allowed as e:
                status = "refused " + type(e).__name__ + ": " + " ".join(str(e).split())[:150]
                if op.get("must_succeed") and all_ok:  # a well-posed call: a refusal is a wrong result
                    status = "problem"
                    problems.append({"op": k, "key": f"{kind}: refused ({type(e).__name__}) though well posed",
                                     "detail": f"{type(e).__name__} in {kind}: {str(e)[:300]}"})
            except BaseException as e:  # noqa: B902 - everything else is a finding
                status = "problem"
                typ = f"{type(e).__module__}.{type(e).__qualname__}".replace("builtins.", "")
                msg = str(e)
                problems.append({"op": k, "key": f"{typ} @ {_where(e.__traceback__)}: {normalized_message(msg)}",
                                 "detail": f"{typ} in {op['kind']}: {msg[:300]}"})
            all_ok = all_ok and status == "ok"
            proto.write(f"T {k} {time.monotonic() - t_start:.4f}\n")
            proto.write(f"E {k} {status}\n")
        proto.write("R " + json.dumps(problems) + "\n")


# ---------------------------------------------------------------------------
# The parent side
# ---------------------------------------------------------------------------

class Worker:
    """A worker subprocess. run(ops) -> (problems, statuses); a crash or a
    hang of the worker is a problem of the op it was on."""

    def __init__(self, timeout=5.0):
        self.timeout = timeout
        self.proc = None
        self.restarts = 0

    def _start(self):
        env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", PYTHONFAULTHANDLER="1")
        self._err = tempfile.TemporaryFile()
        self.proc = subprocess.Popen([sys.executable, os.path.join(HERE, "worker.py"), "--worker"],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=self._err,
                                     cwd=tempfile.gettempdir(), env=env)
        self._buf = b""
        self._sel = selectors.DefaultSelector()
        self._sel.register(self.proc.stdout, selectors.EVENT_READ)
        line = self._readline(60.0)
        if line != "READY":
            raise RuntimeError(f"fuzz worker did not start: {line!r} {self._stderr_tail()}")

    def _stderr_tail(self):
        try:
            self._err.seek(0, os.SEEK_END)
            size = self._err.tell()
            self._err.seek(max(0, size - 3000))
            data = self._err.read().decode(errors="replace")
        except (OSError, ValueError):
            return ""
        # the library's or the C runtime's last words, without faulthandler's Python stack
        noise = ("File ", "Current thread", "Thread 0x", "Stack (most recent", "Extension modules", "<no Python")
        lines = [ln.strip() for ln in data.splitlines() if ln.strip() and not ln.strip().startswith(noise)]
        return " | ".join(lines[-4:])[-500:]

    def _readline(self, timeout):
        deadline = time.monotonic() + timeout
        while b"\n" not in self._buf:
            left = deadline - time.monotonic()
            if left <= 0 or not self._sel.select(left):
                return None  # timeout
            chunk = os.read(self.proc.stdout.fileno(), 65536)
            if not chunk:
                return ""  # EOF: the worker died
            self._buf += chunk
        line, self._buf = self._buf.split(b"\n", 1)
        return line.decode()

    def close(self):
        if self.proc is not None:
            try:
                self.proc.stdin.close()
            except OSError:
                pass
            try:
                self.proc.wait(5)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
            self._sel.close()
            self._err.close()
            self.proc = None

    def run(self, ops):
        if self.proc is None:
            self._start()
        try:
            self.proc.stdin.write((json.dumps({"ops": ops}) + "\n").encode())
            self.proc.stdin.flush()
        except BrokenPipeError:
            self.close()
            self._start()
            return self.run(ops)
        current, statuses = None, {}
        self.times = {}
        while True:
            line = self._readline(self.timeout)
            if line is None or line == "":
                if line is None:  # hang
                    self.proc.kill()
                    self.proc.wait()
                    what = f"hang (> {self.timeout:g} s)"
                else:  # crash
                    rc = self.proc.wait()
                    what = f"crash (signal {signal.Signals(-rc).name})" if rc < 0 else f"crash (exit status {rc})"
                tail = self._stderr_tail()
                self.close()
                self.restarts += 1
                kind = ops[current]["kind"] if current is not None else "?"
                if current is not None:
                    statuses[str(current)] = "problem"
                return ([{"op": current, "key": f"{kind}: {what}",
                          "detail": what + (f"; stderr: {tail}" if tail and line == "" else "")}], statuses)
            if line.startswith("S "):
                current = int(line[2:])
            elif line.startswith("T "):
                _, k, dt = line.split(" ")
                self.times[k] = float(dt)
            elif line.startswith("E "):
                _, k, s = line.split(" ", 2)
                statuses[k] = s
            elif line.startswith("R "):
                problems = json.loads(line[2:])
                threaded = [k for k, op in enumerate(ops)
                            if op["kind"] == THREADS_KIND and statuses.get(str(k), "skipped") != "skipped"]
                if threaded:
                    # threads racing in the core may have corrupted the heap: a fresh worker
                    # for the next case, and a crash on the way out is this case's
                    problems += self._exit(ops, threaded[-1])
                return problems, statuses

    def _exit(self, ops, k):
        """Stop the worker; [a crash of op k] if it died of a signal on the way out."""
        self.proc.stdin.close()
        try:
            rc = self.proc.wait(10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            rc = self.proc.wait()
        tail = self._stderr_tail()
        self.close()
        if rc >= 0:
            return []
        what = f"crash at exit (signal {signal.Signals(-rc).name})"
        return [{"op": k, "key": f"{ops[k]['kind']}: {what}", "detail": what + (f"; stderr: {tail}" if tail else "")}]


def run_cases(cases_, timeout, n_workers=2):
    """Run every case on n_workers workers (threads); -> [(problems, statuses)]."""
    import threading

    out = [None] * len(cases_)
    lock = threading.Lock()
    todo = list(range(len(cases_)))

    def loop():
        w = Worker(timeout)
        try:
            while True:
                with lock:
                    if not todo:
                        return
                    i = todo.pop(0)
                out[i] = w.run(cases_[i])
        finally:
            w.close()

    threads = [threading.Thread(target=loop) for _ in range(max(1, n_workers))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return out


def _crashlike(key):
    return ": crash (" in key or ": hang (" in key


def minimize(worker, ops, key, budget_s):
    """Drop ops one at a time (from the end) while the same problem key still
    occurs, and no other problem before it (a NameError where a dropped op
    bound a name), within budget_s seconds. -> (ops, statuses, problem)."""
    start = time.monotonic()
    had = set()  # (op code, key) of the problems of the whole case

    def hit(trial):
        problems, statuses = worker.run(trial)
        for p in problems:
            if p["key"] == key:
                new = [o for o in problems if o["op"] is not None and p["op"] is not None and o["op"] < p["op"]
                       and (trial[o["op"]]["code"], o["key"]) not in had]
                if new:
                    return None
                return trial[:p["op"] + 1] if p["op"] is not None else trial, statuses, p
        return None

    problems, _ = worker.run(ops)
    had.update((ops[p["op"]]["code"], p["key"]) for p in problems if p["op"] is not None)
    found = hit(ops)
    if found is None:
        return None
    ops = found[0]
    if ops[-1].get("must_succeed"):
        return found  # without the ops before it, it may no longer be well posed
    i = len(ops) - 2  # the last op is the one that fails
    while i >= 0 and time.monotonic() - start < budget_s:
        again = hit(ops[:i] + ops[i + 1:])
        if again is not None:
            found = again
            ops = found[0]
        i -= 1
    return found


class Findings:
    """Problems grouped by key, with the shortest case of each kind."""

    def __init__(self):
        self.kinds = {}  # key -> dict(count, ops, statuses, problem)

    def add(self, ops, problems, statuses):
        for p in problems:
            cut = ops if p["op"] is None else ops[:p["op"] + 1]
            k = self.kinds.setdefault(p["key"], {"count": 0, "ops": None})
            k["count"] += 1
            if k["ops"] is None or len(reproducer(cut)) < len(reproducer(k["ops"])):
                k.update(ops=cut, statuses=statuses, problem=p, minimized=False)

    def __len__(self):
        return len(self.kinds)

    def minimize_all(self, timeout, budget_s):
        """Shrink each kind's reproducer within a total time budget (hangs last)."""
        start = time.monotonic()
        w = Worker(timeout)
        try:
            keys = sorted(self.kinds, key=lambda k: (_crashlike(k), len(self.kinds[k]["ops"])))
            for n, key in enumerate(keys):
                left = budget_s - (time.monotonic() - start)
                if left <= 0:
                    break
                found = minimize(w, self.kinds[key]["ops"], key, left / (len(keys) - n))
                if found is not None:
                    ops, statuses, p = found
                    self.kinds[key].update(ops=ops, statuses=statuses, problem=p, minimized=True)
        finally:
            w.close()

    def script(self, key):
        k = self.kinds[key]
        return reproducer(k["ops"], k["statuses"], k["problem"]["detail"])

    def report(self):
        lines = [f"{len(self.kinds)} distinct problem kind(s):"]
        for key, k in sorted(self.kinds.items()):
            lines.append("")
            lines.append(f"=== {key}   [{k['count']} occurrence(s)]")
            lines.append(self.script(key))
        return "\n".join(lines)

    def to_json(self):
        return {key: {"count": k["count"], "detail": k["problem"]["detail"], "minimized": k["minimized"],
                      "reproducer": self.script(key)} for key, k in sorted(self.kinds.items())}


def replay(path, timeout=30.0):
    """Run a reproducer script (as printed in a report) op by op in a worker:
    each top-level statement is an op; simulate/equilibrium results are
    checked as in the fuzz run."""
    with open(path) as f:
        ops = script_ops(f.read())
    w = Worker(timeout)
    try:
        return w.run(ops)
    finally:
        w.close()


def script_ops(text):
    """The ops of a script: each top-level statement one op (the header's
    imports left out, a try: block of a refused op unwrapped); the results of
    mb.simulate, mb.equilibrium and sim.result() are checked as in the fuzz
    run."""
    import ast

    tree = ast.parse(text)
    lines = text.splitlines()
    ops = []
    for node in tree.body:
        code = "\n".join(lines[node.lineno - 1:node.end_lineno]) + "\n"
        if isinstance(node, (ast.Import, ast.ImportFrom)) and code in HEADER:
            continue
        if isinstance(node, ast.Try):  # a refused op, as written by reproducer()
            node = node.body[0]
            code = "\n".join(ln[4:] for ln in lines[node.lineno - 1:node.end_lineno]) + "\n"
        check = None
        m = re.match(r"(\w+) = (mb\.simulate|mb\.equilibrium|sim\.result)\(", code)
        if m:
            check = ("equilibrium:" if m.group(2) == "mb.equilibrium" else "result:") + m.group(1)
        kind = re.sub(r"^\w+ = ", "", code).split("(")[0].strip()
        kind = {"sim.result": "Simulator.result"}.get(kind, kind)
        ops.append({"code": code, "kind": kind, "check": check})
        if MUST_SUCCEED in code:
            ops[-1]["must_succeed"] = True
    return ops


if __name__ == "__main__":
    if sys.argv[1:] == ["--worker"]:
        worker_main()
    else:
        print(__doc__)
