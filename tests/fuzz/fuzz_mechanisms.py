"""Random small mechanisms with hostile inputs, run out of process.

Used by tests/fuzz/test_fuzz_mechanisms.py (issue "Fuzzed inputs"); also a
command-line tool:

    python3 tests/fuzz/fuzz_mechanisms.py --replay FILE.py   # run one reproducer in a worker
    python3 tests/fuzz/fuzz_mechanisms.py --generate N [planar|spatial|threads]   # N cases as JSON

A *case* is plain data: a list of *ops*, each a dict

    {"code": "<python statements>", "kind": "simulate",
     "check": None | "finite:x" | "result:r1" | "equilibrium:eq"}

The strategies ``cases()`` (planar mechanisms), ``spatial_cases()``
(Model(dimension=3): spatial bodies, joints, drivers that start far from
their joints' initial coordinates and jump by pi or more in a Simulator,
bushings, forces) and ``threaded_cases()`` (a Simulator that two threads
advance at once) draw them with hypothesis in the parent process;
the code of every op is plain Python over ``mb`` (lagmb), ``np``, ``nan`` and
``inf``, so ``reproducer(ops)`` is a script that does exactly what the worker
did. The worker (a subprocess, so that a segfault, an abort or a hang in the
core fails one case instead of killing pytest) executes the ops of each case
in a fresh namespace, skips an op whose inputs were never bound (an earlier op
was refused), and reports per op one of:

- ok: the op returned and its check held;
- refused: it raised one of lagmb's own exceptions (mb.ModelError and its
  subclasses, mb.SimulationError and its subclasses, mb.SceneError);
- a problem: any other exception, non-finite numbers in a returned result,
  a successful run whose max |Phi| exceeds 1e-4 (1 + max |q|) or whose
  output times go back, or (spatial) a driver not at what it commands: a
  revolute's angle about its axis (body_j relative to body_i, 0 as built)
  must equal f modulo 2 pi, a cylindrical's or translational's slide and a
  body's coordinate must equal f, at every output (worker.driver_problems); or a
  refusal of an op marked "must succeed" (after ops that all returned):
  assembling a well-posed open chain of driven joints, which reaches any
  values of its drivers.

The parent (``Worker``) adds crashes (the worker died on op k: signal) and
hangs (op k took longer than the timeout: the worker is killed). A worker
that ran threads (two_threads_op) is replaced after the case: a crash on its
way out (a heap the threads corrupted) is that case's.
"""

import json
import math
import os
import random
import sys

try:  # the parent needs hypothesis; the worker does not
    from hypothesis import strategies as st
except ImportError:  # pragma: no cover
    st = None

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from worker import (HEADER, MUST_SUCCEED, THREADS_KIND, Findings, Worker, minimize,  # noqa: E402,F401
                    normalized_message, replay, reproducer, run_cases, script_ops)


# ---------------------------------------------------------------------------
# Rendering values as Python source
# ---------------------------------------------------------------------------

class Expr(str):
    """Python source that stands for a value (rendered verbatim)."""


def lit(v):
    """Python source for a (possibly hostile) value."""
    if isinstance(v, Expr):
        return str(v)
    if isinstance(v, bool) or v is None:
        return repr(v)
    if isinstance(v, int):
        return repr(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return repr(v)
    if isinstance(v, tuple):
        inner = ", ".join(lit(x) for x in v)
        return f"({inner},)" if len(v) == 1 else f"({inner})"
    if isinstance(v, list):
        return "[" + ", ".join(lit(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{lit(k)}: {lit(x)}" for k, x in v.items()) + "}"
    raise TypeError(f"cannot render {v!r}")


def call(func, *args, **kwargs):
    parts = [lit(a) for a in args] + [f"{k}={lit(v)}" for k, v in kwargs.items()]
    return f"{func}({', '.join(parts)})"


# ---------------------------------------------------------------------------
# Hostile value pools
# ---------------------------------------------------------------------------

nan, inf = float("nan"), float("inf")
BIG = Expr("10**400")

#: numbers that are legal Python floats but extreme
EXTREME = [0.0, -0.0, 1e-300, -1e-300, 5e-324, 1e300, -1e300, 1e-12, 1e12, 1e308, -1.0, -1e6]

#: anything a careless caller might pass where a number belongs
HOSTILE_SCALARS = EXTREME + [
    nan, -nan, inf, -inf, 0, 2 ** 40, -(2 ** 40), 2 ** 63, 2 ** 64, BIG, Expr("-10**400"),
    "1.0", "abc", "", None, True, False, [1.0], [[1.0, 2.0]], (), [],
    Expr("np.float64('nan')"), Expr("np.float32(1.5)"), Expr("np.int64(3)"), Expr("np.array(1.0)"),
    Expr("np.array([1.0, 2.0])"), Expr("1+2j"), Expr("object()"), Expr("{'a': 1}"), Expr("b'1'"),
    Expr("np.float64(1e300) * 10"), Expr("np.uint64(2**64 - 1)"),
]

#: anything a careless caller might pass where a pair (x, y) belongs
HOSTILE_VEC2 = HOSTILE_SCALARS + [
    (nan, 0.0), (0.0, inf), (-inf, inf), (1e300, -1e300), (1e308, 1e308), (1e-300, 1e-300), (5e-324, 0.0),
    (0.0, 0.0), [1.0, 2.0, 3.0], [[1.0, 2.0]], [[1.0], [2.0]], "ab", ("1", "2"), (None, None),
    (True, False), (BIG, 0.0), (2 ** 40, 2 ** 40), Expr("np.array([[1.0, 2.0]])"),
    Expr("np.array([1+1j, 0])"), Expr("{1: 2, 3: 4}"), Expr("iter([1.0, 2.0])"), Expr("range(2)"),
    Expr("np.array([1.0, 2.0], dtype=object)"), Expr("np.array([np.nan, 1.0], dtype=np.float32)"),
    Expr("[np.float64(1.0), np.int64(2)]"), ([1.0], [2.0]),
]

HOSTILE_NAMES = [None, "", 5, 1.5, "b0", "j0", "ground", "x" * 5000, "\x00", "\u00e9\u00e8", b"j".decode(),
                 Expr("['j0']"), Expr("('b0',)"), True]

HOSTILE_BODIES = ["nosuch", None, 3, -1, 0, True, "", 1.5, [0], Expr("m"),
                  Expr("mb.Model().add_body('alien', mass=1.0, inertia=1.0)"), Expr("mb.Body('b0', m, 0)"),
                  Expr("mb.Body('b0', m, 99)"), Expr("mb.Body('ghost', m, -7)")]


def _chance(draw, p):
    """True with probability about p (shrinks to False)."""
    if p <= 0:
        return False
    return draw(st.integers(0, 999)) >= 1000 - int(p * 1000)  # the simplest draw (0) is False


def _round(x):
    return float(f"{x:.4g}")


def _log_uniform(draw, lo, hi):
    e = draw(st.floats(math.log10(lo), math.log10(hi)))
    return _round(10.0 ** e)


class Ctx:
    """What the generator knows while building one case."""

    def __init__(self, draw, hostility, extremity, coin):
        self.draw = draw
        self.coin = coin  # a random.Random for the many rare yes/no choices (cheaper than a draw each)
        self.h = hostility
        self.e = extremity
        self.ops = []
        self.bodies = []  # (name, var, is_particle, position, angle)
        self.joints = []  # (name, kind, initial relative angle of a revolute)
        self.drivers = []
        self.others = []  # names of other elements
        self.counter = 0
        self.dim = 2  # 3: a spatial model (bodies are then (name, var, False, position (x, y, z), None))
        self.inputs = {}  # spatial: {input name of a driver: its value now}, for jumps in a Simulator
        self.well_posed = False  # True: no callables that fail (the model must then assemble)

    # values
    def hostile(self):
        return self.h > 0 and self.coin.random() < self.h

    def num(self, nominal, pool=None):
        """A number near ``nominal`` (a float or a strategy), or extreme, or hostile."""
        if self.hostile():
            return self.draw(st.sampled_from(pool or HOSTILE_SCALARS))
        if self.e > 0 and self.coin.random() < self.e:
            return self.draw(st.sampled_from(EXTREME))
        if isinstance(nominal, (int, float)):
            return nominal
        return self.draw(nominal)

    def vec(self, x, y, spread=0.0):
        if self.hostile():
            return self.draw(st.sampled_from(HOSTILE_VEC2))
        if self.e > 0 and self.coin.random() < self.e:
            return (self.draw(st.sampled_from(EXTREME)), self.draw(st.sampled_from(EXTREME + [x, y])))
        if spread:
            x += _round(self.draw(st.floats(-spread, spread)))
            y += _round(self.draw(st.floats(-spread, spread)))
        return (_round(x), _round(y))

    def vec3(self, x, y, z, spread=0.0):
        """Spatial: a point or vector near (x, y, z), or extreme, or hostile."""
        if self.hostile():
            return self.draw(st.sampled_from(HOSTILE_VEC3))
        if self.e > 0 and self.coin.random() < self.e:
            return tuple(self.draw(st.sampled_from(EXTREME + [x, y, z])) for _ in range(3))
        if spread:
            x, y, z = (c + _round(self.draw(st.floats(-spread, spread))) for c in (x, y, z))
        return (_round(x), _round(y), _round(z))

    def axis3(self, along=None):
        """Spatial: an axis, one of AXES or the direction ``along`` (e.g. a link's), or hostile."""
        if self.hostile():
            return self.draw(st.sampled_from(HOSTILE_VEC3))
        if along is not None and self.draw(st.booleans()):
            return _fvec(along)
        return _fvec(self.draw(st.sampled_from(AXES)))

    def point_on3(self, ref):
        """Spatial: a global point near body ``ref`` (its centre of mass within 0.5), or near the origin."""
        for name, var, _, pos, _ in self.bodies:
            if ref in (Expr(var), name):
                return self.vec3(*pos, spread=0.5)
        return self.vec3(0.0, 0.0, 0.0, spread=1.0)

    def unit(self):
        if self.hostile():
            return self.draw(st.sampled_from(HOSTILE_VEC2))
        a = self.draw(st.sampled_from([0.0, math.pi / 2, math.pi / 4, -math.pi / 3, 2.0]))
        s = self.draw(st.sampled_from([1.0, 1.0, 2.5, 1e-3]))
        return (_round(s * math.cos(a)), _round(s * math.sin(a)))

    def name(self, prefix):
        self.counter += 1
        if self.hostile():
            return self.draw(st.sampled_from(HOSTILE_NAMES))
        return f"{prefix}{self.counter}"

    def body_ref(self, allow_ground=True):
        if self.hostile():
            return self.draw(st.sampled_from(HOSTILE_BODIES))
        choices = list(range(len(self.bodies))) + ([-1] if allow_ground else [])
        if not choices:
            return Expr("m.ground")
        k = self.draw(st.sampled_from(choices))
        by_name = self.draw(st.booleans())
        if k < 0:
            return "ground" if by_name else Expr("m.ground")
        name, var = self.bodies[k][0], self.bodies[k][1]
        return name if by_name else Expr(var)

    def local(self, ref, point):
        """A global point of the initial configuration in the axes of body ``ref``."""
        for name, var, particle, pos, a in self.bodies:
            if ref in (Expr(var), name):
                a = 0.0 if particle else a
                dx, dy = point[0] - pos[0], point[1] - pos[1]
                return (_round(math.cos(a) * dx + math.sin(a) * dy), _round(-math.sin(a) * dx + math.cos(a) * dy))
        return point  # the ground (or a hostile reference)

    def point_on(self, ref):
        """A global point on body ``ref`` (a particle's own position)."""
        for name, var, particle, pos, a in self.bodies:
            if ref in (Expr(var), name):
                return self.vec(*pos) if particle else self.vec(*pos, spread=1.0)
        return self.vec(0.0, 0.0, spread=2.0)

    def body_pair(self, rigid=False):
        """Two different bodies (or one and the ground)."""
        if self.hostile():
            return self.body_ref(), self.body_ref()
        pool = [k for k, b in enumerate(self.bodies) if not (rigid and b[2])] + [-1]
        i = self.draw(st.sampled_from(pool))
        j = self.draw(st.sampled_from([k for k in pool if k != i] or pool))
        ref = [Expr("m.ground") if k < 0 else Expr(self.bodies[k][1]) for k in (i, j)]
        return ref[0], ref[1]

    def joint_ref(self, kinds=None, base=False):
        """A joint name (and with base=True the joint coordinate in the initial configuration)."""
        if self.hostile():
            ref = self.draw(st.sampled_from(["nosuch", None, 3, Expr("m.ground"), "b0"] + self.drivers[:1]))
            return (ref, 0.0) if base else ref
        pool = [j for j in self.joints if kinds is None or j[1] in kinds] or self.joints
        j = self.draw(st.sampled_from(pool)) if pool else ("nosuch", "", 0.0)
        return (j[0], j[2]) if base else j[0]

    def angle_of(self, ref):
        for name, var, particle, pos, a in self.bodies:
            if ref in (Expr(var), name):
                return 0.0 if particle else a
        return 0.0

    def add(self, code, kind, check=None):
        self.ops.append({"code": code, "kind": kind, "check": check})

    def time_function(self, derivatives=True, pair=False, base=0.0, triple=False):
        """A number, an mb time function, or the source of a Python callable
        (a def op is added and its name returned). pair / triple: (x, y) /
        (x, y, z) components of forces, or a callable returning them."""
        d = self.draw
        kind = d(st.sampled_from(["number", "constant", "linear", "harmonic", "smooth_step", "polynomial",
                                  "spline", "callable", "callable", "bad_callable", "input"]))
        if kind == "bad_callable" and (not _chance(d, 0.3 + self.h) or self.well_posed):
            kind = "callable"
        if pair:
            kind = d(st.sampled_from(["pair", "callable", "bad_callable"]))
        if triple:
            kind = d(st.sampled_from(["triple", "triple", "callable", "bad_callable"]))
        if kind == "pair":
            return (self.time_function(False), self.time_function(False))
        if kind == "triple":
            return tuple(self.time_function(False) if d(st.booleans()) else self.num(_round(d(st.floats(-20, 20))))
                         for _ in range(3))
        if kind == "number":
            return self.num(base + d(st.sampled_from([0.0, 0.5, -1.0, 2.0])))
        if kind == "constant":
            return Expr(call("mb.Constant", self.num(base)))
        if kind == "input":  # set by a Simulator (_runs), at its initial value elsewhere
            name = d(st.sampled_from([None, "u", "ground", "", 3])) if self.hostile() else None
            return Expr(call("mb.Input", self.num(base)) if name is None else call("mb.Input", self.num(base), name=name))
        if kind == "linear":
            return Expr(call("mb.Linear", self.num(d(st.sampled_from([1.0, -10.0, 0.0]))), start=self.num(base)))
        if kind == "harmonic":
            return Expr(call("mb.Harmonic", self.num(0.2), self.num(d(st.sampled_from([3.0, 100.0, 1e4]))),
                             phase=self.num(0.0), offset=self.num(base)))
        if kind == "smooth_step":
            return Expr(call("mb.SmoothStep", self.num(0.0), self.num(d(st.sampled_from([0.02, 1e-9, 0.0, -0.1]))),
                             self.num(base), self.num(base + 0.5)))
        if kind == "polynomial":
            n = d(st.integers(1, 4))
            coeffs = [self.num(base)] + [self.num(_round(d(st.floats(-2, 2)))) for _ in range(n - 1)]
            if self.hostile():
                coeffs = d(st.sampled_from([[], "abc", None, [[1.0]], Expr("np.array([nan, 1.0])"), BIG]))
            return Expr(call("mb.Polynomial", coeffs))
        if kind == "spline":
            n = d(st.integers(2, 4))
            ts = [_round(0.02 * i) for i in range(n)]
            if self.hostile():
                ts = d(st.sampled_from([[0.0, 0.0], [0.1, 0.0], [nan, 1.0], [], "ab"]))
            vs = [self.num(base + _round(d(st.floats(-1, 1))) * (k > 0)) for k in range(n)]
            return Expr(call("mb.Spline", ts, vs))
        # a Python callable, defined by its own op
        self.counter += 1
        fname = f"fn{self.counter}"
        amp = _round(d(st.floats(-1, 1)))
        if derivatives:
            good = f"({base!r} + {amp} * t, {amp}, 0.0)" if base else f"({amp} * t, {amp}, 0.0)"
        elif triple:
            good = f"({amp} * t, -{amp}, 0.5)"
        elif pair:
            good = f"({amp} * t, -{amp})"
        else:
            good = f"{amp} * t"
        body = f"    return {good}\n"
        if kind == "bad_callable":
            tb = d(st.sampled_from([0.0, 0.01, 0.03]))
            bad = d(st.sampled_from([
                "raise ZeroDivisionError('boom')",
                "return nan" if not (derivatives or pair or triple) else "return (nan, 0.0, 0.0)",
                "return (inf, inf, inf)", "return None", "return 'abc'", "return (1.0,)",
                "return [1.0, 2.0, 3.0, 4.0]", "return 10**400", "return np.array([nan, nan, nan])",
                "raise ValueError('user value')", "return (1.0, 'x', 0.0)", "raise RuntimeError('user')",
                "return (1e308, 1e308, 1e308)", "raise mb.ModelError('user')",
            ]))
            body = f"    if t >= {tb}:\n        {bad}\n" + body
        self.add(f"def {fname}(t):\n{body}", "def")
        return Expr(fname)


# ---------------------------------------------------------------------------
# The case strategy
# ---------------------------------------------------------------------------

JOINT_KINDS = ["revolute", "revolute", "revolute", "translational", "weld", "distance", "pin_in_slot", "none"]
FORMULATIONS = ["ggl", "index3", "index1", "projection", "ali3p"]
HOSTILE_FORMULATIONS = ["GGL", "", None, 3, "ali3p ", "index2", Expr("['ggl']")]


def _build(ctx):
    d = ctx.draw
    # gravity
    if ctx.hostile():
        ctx.add(f"mb.Model(gravity={lit(d(st.sampled_from(HOSTILE_VEC2)))})", "Model")
    g = d(st.sampled_from([None, (0.0, -9.81), (0.0, -9.81), (3.0, -1.0)]))
    ctx.add(f"m = mb.Model(gravity={lit(g)})", "Model")

    # a chain of n bodies (and particles) from the ground at the origin,
    # each link from point p to point nxt; sometimes closed back to the ground
    n = d(st.integers(1, 5))
    closed = d(st.integers(0, 2)) < 2 if n >= 2 else d(st.integers(0, 3)) == 3
    mass_scale = d(st.sampled_from([1.0, 1.0, 1e-6, 1e6]))
    p = (0.0, 0.0)
    for i in range(n):
        L = _log_uniform(d, 0.01, 10.0) if d(st.integers(0, 3)) == 3 else 1.0
        a = _round(d(st.floats(-math.pi, math.pi)))
        nxt = (_round(p[0] + L * math.cos(a)), _round(p[1] + L * math.sin(a)))
        c = (_round((p[0] + nxt[0]) / 2), _round((p[1] + nxt[1]) / 2))
        name = var = f"b{i}"
        mass = _round(_log_uniform(d, 0.01, 100.0) * (mass_scale if i % 2 else 1.0))
        particle = d(st.integers(0, 4)) == 4
        if particle:
            # a point mass pinned at the joint point, or at the end of a distance link
            kind = d(st.sampled_from(["revolute", "revolute", "distance", "pin_in_slot", "none"]))
            if kind == "distance":
                pos = nxt
            else:
                pos = nxt = p
            code = f"{var} = " + call("m.add_particle", name, mass=ctx.num(mass), position=ctx.vec(*pos),
                                      **({"velocity": ctx.vec(0.0, 0.0, 1.0)} if d(st.booleans()) else {}))
        else:
            kinds = JOINT_KINDS if i == 0 or not ctx.bodies[i - 1][2] else ["revolute", "distance", "pin_in_slot"]
            kind = d(st.sampled_from(kinds))
            pos = c
            inertia = _round(mass * L * L / 12.0)
            kw = dict(mass=ctx.num(mass), inertia=ctx.num(inertia), position=ctx.vec(*pos), angle=ctx.num(a))
            if d(st.booleans()):
                kw["velocity"] = ctx.vec(0.0, 0.0, 1.0)
                kw["angular_velocity"] = ctx.num(_round(d(st.floats(-5, 5))))
            code = f"{var} = " + call("m.add_body", name, **kw)
        ctx.add(code, "add_particle" if particle else "add_body")
        ctx.bodies.append((name, var, particle, pos, a))
        prev = Expr("m.ground") if i == 0 else Expr(ctx.bodies[i - 1][1])
        _joint(ctx, prev, Expr(var), p, pos, kind)
        p = nxt
    if closed:
        last = Expr(ctx.bodies[-1][1])
        kinds = ["revolute", "pin_in_slot", "distance"] + ([] if ctx.bodies[-1][2] else ["translational"])
        kind = d(st.sampled_from(kinds))
        anchor = p if kind != "distance" else (_round(p[0] + 0.5), _round(p[1] - 0.5))
        _joint(ctx, Expr("m.ground"), last, anchor, p, kind)
    # couplings between bodies
    for _ in range(d(st.integers(0, 2))):
        kind = d(st.sampled_from(["gear", "rack_pinion", "joint"]))
        bi, bj = ctx.body_pair(rigid=kind != "joint")
        if kind == "joint":
            x, y = ctx.bodies[d(st.integers(0, n - 1))][3]
            at = (_round(x + d(st.floats(-0.5, 0.5))), _round(y + d(st.floats(-0.5, 0.5))))
            particles = [b for b in ctx.bodies if b[2] and Expr(b[1]) in (bi, bj)]
            if particles:  # a joint on a particle is at the particle
                at = particles[0][3]
            _joint(ctx, bi, bj, at, at, d(st.sampled_from(["revolute", "pin_in_slot"] if particles
                                                          else JOINT_KINDS[:-1])))
        elif kind == "gear":
            name = ctx.name("g")
            kw = {}
            if d(st.booleans()) or bi == Expr("m.ground"):
                kw["center_i"] = ctx.vec(0.0, 0.0, 1.0)
            if d(st.booleans()):
                kw["center_j"] = ctx.vec(0.0, 0.0, 1.0)
            ratio = ctx.num(d(st.sampled_from([-1.0, -2.0, 0.5, 3.0, 0.0])))
            ctx.add(call("m.add_gear", name, bi, bj, ratio, **kw), "add_gear")
            ctx.joints.append((name, "gear", 0.0))
        else:
            name = ctx.name("rp")
            ctx.add(call("m.add_rack_pinion", name, bi, bj, ctx.num(_log_uniform(d, 0.01, 1.0)), ctx.unit()),
                    "add_rack_pinion")
            ctx.joints.append((name, "rack_pinion", 0.0))
    # drivers: sometimes every revolute and slider of the chain (a fully driven model:
    # kinematic analysis, inverse dynamics), else a few
    if d(st.integers(0, 3)) == 3:
        for joint, kind, base in list(ctx.joints):
            if kind in ("revolute", "translational"):
                name = ctx.name("d")
                ctx.add(call("m.drive_joint", name, joint, ctx.time_function(base=base)), "drive_joint")
                ctx.drivers.append(name)
    for _ in range(d(st.integers(0, 2))):
        name = ctx.name("d")
        if d(st.booleans()):
            # the driver's function starts at the joint's initial coordinate (else assembly moves it)
            joint, base = ctx.joint_ref(("revolute", "translational"), base=True)
            ctx.add(call("m.drive_joint", name, joint, ctx.time_function(base=base)), "drive_joint")
        else:
            coord = d(st.sampled_from(["x", "y", "angle"])) if not ctx.hostile() else \
                d(st.sampled_from(["z", "X", None, 0, "", ["x"]]))
            body = ctx.body_ref(False)
            base = 0.0
            for bname, var, particle, pos, a in ctx.bodies:
                if body in (Expr(var), bname) and coord in ("x", "y", "angle"):
                    base = {"x": pos[0], "y": pos[1], "angle": a}[coord]
            ctx.add(call("m.drive_body", name, body, coord, ctx.time_function(base=base)), "drive_body")
        ctx.drivers.append(name)
    # forces, friction, stops, contacts
    for _ in range(d(st.integers(0, 4))):
        kind = d(st.sampled_from(["spring_damper", "rotational_spring_damper", "force", "torque",
                                  "joint_friction", "stop", "contact"]))
        _element(ctx, kind)


def _joint(ctx, bi, bj, p, c, kind):
    d = ctx.draw
    if kind == "none":
        return
    name = ctx.name("j")
    if kind == "revolute":
        if d(st.integers(0, 5)) == 5:
            li, lj = ctx.local(bi, p), ctx.local(bj, p)
            code = call("m.add_revolute", name, bi, bj, local_i=ctx.vec(*li), local_j=ctx.vec(*lj))
        else:
            code = call("m.add_revolute", name, bi, bj, at=ctx.vec(*p))
    elif kind in ("translational", "pin_in_slot"):
        code = call(f"m.add_{kind}", name, bi, bj, at=ctx.vec(*p), axis=ctx.unit())
    elif kind == "weld":
        code = call("m.add_weld", name, bi, bj)
    elif kind == "distance":
        kw = {}
        if d(st.integers(0, 2)) == 2:
            kw["length"] = ctx.num(_log_uniform(d, 0.01, 5.0))
        code = call("m.add_distance", name, bi, ctx.vec(*p), bj, ctx.vec(*c), **kw)
    else:
        raise AssertionError(kind)
    ctx.add(code, f"add_{kind}")
    ctx.joints.append((name, kind, ctx.angle_of(bj) - ctx.angle_of(bi) if kind == "revolute" else 0.0))


def _spring_damper_values(ctx):
    """stiffness, damping, maybe free_length and force: the same draws in the plane and in space."""
    d = ctx.draw
    kw = dict(stiffness=ctx.num(_log_uniform(d, 1e-2, 1e6)), damping=ctx.num(_log_uniform(d, 1e-3, 1e3)))
    if d(st.booleans()):
        kw["free_length"] = ctx.num(_log_uniform(d, 0.01, 3.0))
    if d(st.integers(0, 2)) == 2:
        kw["force"] = ctx.time_function(derivatives=False)
    return kw


def _rotational_spring_damper_values(ctx):
    """stiffness, damping, maybe free_angle and torque."""
    d = ctx.draw
    kw = dict(stiffness=ctx.num(_log_uniform(d, 1e-2, 1e5)), damping=ctx.num(_log_uniform(d, 1e-3, 1e2)))
    if d(st.booleans()):
        kw["free_angle"] = ctx.num(_round(d(st.floats(-3, 3))))
    if d(st.integers(0, 2)) == 2:
        kw["torque"] = ctx.time_function(derivatives=False)
    return kw


def _element(ctx, kind):
    d = ctx.draw
    name = ctx.name(kind[:2])
    if kind == "spring_damper":
        kw = _spring_damper_values(ctx)
        bi, bj = ctx.body_pair()
        code = call("m.add_spring_damper", name, bi, ctx.point_on(bi), bj, ctx.point_on(bj), **kw)
    elif kind == "rotational_spring_damper":
        kw = _rotational_spring_damper_values(ctx)
        bi, bj = ctx.body_pair(rigid=True)
        code = call("m.add_rotational_spring_damper", name, bi, bj, **kw)
    elif kind == "force":
        kw = {}
        body = ctx.body_ref(False)
        if d(st.booleans()):
            kw["point"] = ctx.point_on(body)
        if d(st.booleans()):
            kw["local"] = d(st.sampled_from([True, False, "yes", None, 0]))
        if ctx.hostile():
            force = d(st.sampled_from(HOSTILE_VEC2))
        elif d(st.booleans()):
            force = ctx.vec(0.0, 0.0, 50.0)
        else:
            force = ctx.time_function(derivatives=False, pair=True)
        code = call("m.add_force", name, body, force, **kw)
    elif kind == "torque":
        code = call("m.add_torque", name, ctx.body_ref(False), ctx.time_function(derivatives=False))
    elif kind == "joint_friction":
        kw = {}
        for key, nominal in (("mu", 0.2), ("viscous", 0.01), ("pin_radius", 0.01), ("bearing_length", 0.05),
                             ("preload", 0.1), ("slip_velocity", 1e-3), ("load_smoothing", 1e-6)):
            if d(st.booleans()):
                kw[key] = ctx.num(nominal)
        code = call("m.add_joint_friction", name, ctx.joint_ref(("revolute", "translational")), **kw)
    elif kind == "stop":
        # limits close to the joint's initial coordinate, so that impacts happen in a short run
        joint, base = ctx.joint_ref(("revolute", "translational"), base=True)
        kw = {}
        if d(st.booleans()):
            kw["lower"] = ctx.num(_round(base - d(st.sampled_from([0.003, 0.03, 0.3, 0.0, -0.1]))))
        if d(st.booleans()) or not kw:
            kw["upper"] = ctx.num(_round(base + d(st.sampled_from([0.003, 0.03, 0.3, 0.0, -0.1]))))
        if d(st.booleans()):
            kw["restitution"] = ctx.num(d(st.sampled_from([0.0, 0.5, 1.0, 1.5])))
        if d(st.booleans()):
            kw["rest_speed"] = ctx.num(1e-3)
        code = call("m.add_stop", name, joint, **kw)
    elif kind == "contact":
        k = d(st.integers(0, len(ctx.bodies) - 1))
        _, var, _, pos, _ = ctx.bodies[k]
        R = _log_uniform(d, 0.01, 0.5)
        pen = d(st.sampled_from([0.0, 1e-3, -0.05]))
        line_y = _round(pos[1] - R + pen)
        code = call("m.add_contact", name, Expr(var) if not ctx.hostile() else ctx.body_ref(), ctx.vec(*pos),
                    ctx.num(R), ctx.body_ref() if d(st.integers(0, 3)) == 3 else Expr("m.ground"),
                    ctx.vec(0.0, line_y), ctx.unit(), ctx.num(_log_uniform(d, 1e3, 1e9)),
                    ctx.num(d(st.sampled_from([0.8, 0.5, 1.0, 0.0]))),
                    **({"friction": ctx.num(0.3)} if d(st.booleans()) else {}),
                    **({"slip_velocity": ctx.num(1e-4)} if d(st.booleans()) else {}))
    else:
        raise AssertionError(kind)
    ctx.add(code, f"add_{kind}")
    ctx.others.append(name)


# ---------------------------------------------------------------------------
# Spatial mechanisms (Model(dimension=3))
# ---------------------------------------------------------------------------

#: anything a careless caller might pass where (x, y, z) belongs
HOSTILE_VEC3 = HOSTILE_SCALARS + [
    (nan, 0.0, 0.0), (0.0, 0.0, inf), (-inf, inf, 0.0), (1e300, -1e300, 1e300), (1e308, 1e308, 1e308),
    (1e-300, 1e-300, 1e-300), (5e-324, 0.0, 0.0), (0.0, 0.0, 0.0), (1.0, 2.0), [1.0, 2.0, 3.0, 4.0],
    [[1.0, 2.0, 3.0]], "abc", ("1", "2", "3"), (None, None, None), (True, False, True), (BIG, 0.0, 0.0),
    (2 ** 40, 2 ** 40, 2 ** 40), Expr("np.array([[1.0, 2.0, 3.0]])"), Expr("np.array([1+1j, 0, 0])"),
    Expr("iter([1.0, 2.0, 3.0])"), Expr("range(3)"), Expr("np.array([1.0, 2.0, 3.0], dtype=object)"),
    Expr("np.array([np.nan, 1.0, 0.0], dtype=np.float32)"), Expr("np.eye(3)"),
]
#: ... where an orientation (unit quaternion or rotation matrix) belongs
HOSTILE_ORIENTATIONS = [
    (1.0, 0.0, 0.0), (2.0, 0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0), (nan, 0.0, 0.0, 0.0), (1.0, 0.0, 0.0, inf),
    (1.0005, 0.0, 0.0, 0.0), (0.9989, 0.0, 0.0, 0.0), Expr("np.diag([1.0, 1.0, -1.0])"), Expr("np.eye(3) * 1.0001"),
    Expr("np.ones((3, 3))"), Expr("np.eye(4)"), Expr("np.full((3, 3), nan)"), ((1, 0, 0), (0, 1, 0)),
    Expr("-np.eye(3)"), [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]], "abc", None, 1.0, (1e308,) * 4,
]
#: ... where an inertia (principal moments or a 3 x 3 tensor) belongs
HOSTILE_INERTIAS = [
    (0.1, 0.1, 0.5), (-0.1, 0.1, 0.1), (0.0, 0.0, 0.0), (0.0, 0.1, 0.1), (nan, 0.1, 0.1), (inf, inf, inf),
    (1e-300, 1e-300, 1e-300), (1e300, 1e300, 1e300), ((0.1, 0.2, 0.0), (0.0, 0.1, 0.0), (0.0, 0.0, 0.1)),
    Expr("np.eye(3) * -1.0"), Expr("np.full((3, 3), 0.1)"), 0.1, (0.1, 0.1), "abc", None,
]

#: integer axes (any length is taken): exact, and perpendicular pairs stay exactly perpendicular
AXES = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0), (0, -1, 1), (1, 2, 3), (2, -1, 1), (-1, 0, 2), (3, 1, -2),
        (0, 0, -1)]
SPATIAL_JOINT_KINDS = ["revolute", "revolute", "revolute", "spherical", "spherical", "cylindrical", "translational",
                       "universal", "planar", "weld", "distance", "none"]
#: where a spatial driver starts (its joint coordinate is 0 in the initial configuration: far from 0,
#: assembly must turn or slide the joint there; the revolute's angle +-pi away from f is a known trap)
ANGLE_STARTS = [3.0, -1.7, 2.0, round(math.pi, 6), -3.0, 0.5, 0.0, 6.5, -4.4, 2.5]
SLIDE_STARTS = [0.0, 0.3, -0.5, 1.5]
#: spatial runs stop after this many steps between two outputs (max_steps is per output
#: interval): a stiff random model (a 1 mg body under a torque of newtons, 0.3 ms a step) takes
#: minutes at the default 500,000 (measured: 225,000 steps in 66 s at 2,250 per interval) and
#: would count as a hang; healthy runs of 0.05 s take a few dozen steps per interval
SPATIAL_MAX_STEPS = 500
#: a driver input's jumps in a Simulator (pi or more)
INPUT_JUMPS = [("np.pi", math.pi), ("-np.pi", -math.pi), ("3.5", 3.5), ("-4.0", -4.0), ("2 * np.pi", 2 * math.pi),
               ("7.0", 7.0), ("(np.pi + 0.25)", math.pi + 0.25)]


def _round9(x):
    return float(f"{x:.9g}")


def _fvec(v):
    return tuple(float(c) for c in v)


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _rotation(axis, angle):
    """(quaternion (w, x, y, z), rotation matrix as rows) of a turn by angle about axis."""
    n = math.sqrt(sum(c * c for c in axis))
    x, y, z = (c / n for c in axis)
    c, s = math.cos(angle / 2), math.sin(angle / 2)
    w, x, y, z = c, s * x, s * y, s * z
    R = ((w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)),
         (2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)),
         (2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z))
    return (w, x, y, z), R


def _orientation(ctx):
    """A body's orientation: None (the default, identity), a quaternion to a
    few digits (lagmb normalizes within 1e-3), a rotation matrix to 9 digits,
    or hostile."""
    d = ctx.draw
    if ctx.hostile():
        return d(st.sampled_from(HOSTILE_ORIENTATIONS))
    how = d(st.sampled_from(["identity", "quaternion", "quaternion", "matrix"]))
    if how == "identity":
        return None
    p, R = _rotation(d(st.sampled_from(AXES)), _round(d(st.floats(-math.pi, math.pi))))
    if how == "quaternion":
        return tuple(_round(c) for c in p)
    return tuple(tuple(_round9(c) for c in row) for row in R)


def _inertia(ctx, mass, L):
    """Principal moments (a, b, c) that meet the triangle inequalities, or a
    3 x 3 tensor (a turned diagonal, exactly symmetric), or hostile."""
    d = ctx.draw
    if ctx.hostile():
        return d(st.sampled_from(HOSTILE_INERTIAS))
    base = mass * L * L / 12.0 if ctx.coin.random() > ctx.e else d(st.sampled_from(EXTREME))
    a = _round(base * d(st.sampled_from([1.0, 0.5, 0.2])))
    b = _round(base * d(st.sampled_from([1.0, 0.8, 0.3])))
    c = d(st.sampled_from([max(a, b), max(a, b) + 0.5 * min(a, b), a + b]))  # a + b: a flat plate
    moments = (a, b, c)
    if d(st.integers(0, 3)) < 3:
        return moments
    moments = (a, b, max(a, b) + 0.5 * min(a, b))  # (turned and rounded, a flat plate's may break the inequality)
    _, R = _rotation(d(st.sampled_from(AXES)), _round(d(st.floats(-math.pi, math.pi))))
    J = [[sum(R[i][k] * moments[k] * R[j][k] for k in range(3)) for j in range(3)] for i in range(3)]
    return tuple(tuple(_round9(J[min(i, j)][max(i, j)]) for j in range(3)) for i in range(3))


def _build3(ctx, driven_chain=None):
    """A spatial chain of 1-4 bodies from the ground at the origin (each link
    from point p to point nxt, its body at the middle), sometimes closed back
    to the ground, couplings between bodies, drivers that start far from the
    joints' initial coordinates, and forces. driven_chain (None: one in three)
    builds an open chain with every revolute, cylindrical and translational
    joint driven and nothing else constraining it."""
    d = ctx.draw
    ctx.dim = 3
    if ctx.hostile():
        ctx.add(f"mb.Model(dimension=3, gravity={lit(d(st.sampled_from(HOSTILE_VEC3)))})", "Model")
    g = d(st.sampled_from([None, (0.0, 0.0, -9.81), (0.0, 0.0, -9.81), (0.0, -9.81, 0.0), (1.0, 2.0, -9.0)]))
    ctx.add(f"m = mb.Model(dimension=3, gravity={lit(g)})", "Model")
    if driven_chain is None:
        driven_chain = d(st.integers(0, 2)) == 2
    n = d(st.integers(1, 4))
    closed = d(st.integers(0, 2)) == 2 if n >= 2 and not driven_chain else False
    mass_scale = d(st.sampled_from([1.0, 1.0, 1e-6, 1e6]))
    kinds = SPATIAL_JOINT_KINDS if not driven_chain else \
        ["revolute", "revolute", "revolute", "cylindrical", "translational", "spherical", "universal"]
    p = (0.0, 0.0, 0.0)
    for i in range(n):
        L = _log_uniform(d, 0.01, 10.0) if d(st.integers(0, 3)) == 3 else 1.0
        u = _fvec(d(st.sampled_from(AXES)))
        norm = math.sqrt(sum(c * c for c in u))
        nxt = tuple(_round(p[k] + L * u[k] / norm) for k in range(3))
        c = tuple(_round((p[k] + nxt[k]) / 2) for k in range(3))
        name = var = f"b{i}"
        mass = _round(_log_uniform(d, 0.01, 100.0) * (mass_scale if i % 2 else 1.0))
        orientation = _orientation(ctx)
        kw = dict(mass=ctx.num(mass), inertia=_inertia(ctx, mass, L), position=ctx.vec3(*c))
        if orientation is not None:
            kw["orientation"] = orientation
        if d(st.booleans()):
            kw["velocity"] = ctx.vec3(0.0, 0.0, 0.0, spread=1.0)
            kw["angular_velocity"] = ctx.vec3(0.0, 0.0, 0.0, spread=5.0)
        ctx.add(f"{var} = " + call("m.add_body", name, **kw), "add_body")
        ctx.bodies.append((name, var, False, c, None))
        prev = Expr("m.ground") if i == 0 else Expr(ctx.bodies[i - 1][1])
        _joint3(ctx, prev, Expr(var), p, c, d(st.sampled_from(kinds)), along=u)
        p = nxt
    if closed:
        _joint3(ctx, Expr("m.ground"), Expr(ctx.bodies[-1][1]), p, ctx.bodies[-1][3],
                d(st.sampled_from(["spherical", "distance", "revolute", "universal", "cylindrical"])))
    # couplings between bodies
    for _ in range(d(st.integers(0, 2)) if not driven_chain else 0):
        bi, bj = ctx.body_pair()
        k = d(st.integers(0, n - 1))
        at = ctx.bodies[k][3]
        at = tuple(_round(x + d(st.floats(-0.5, 0.5))) for x in at)
        _joint3(ctx, bi, bj, at, at, d(st.sampled_from(["spherical", "distance", "revolute", "universal",
                                                         "planar", "cylindrical"])))
    # drivers: sometimes every revolute, cylindrical and translational joint
    # (a fully driven model: kinematic analysis, inverse dynamics), else a few
    drivable = [j for j in ctx.joints if j[1] in ("revolute", "cylindrical", "translational")]
    if driven_chain or d(st.integers(0, 2)) == 2:
        ctx.well_posed = driven_chain and ctx.h == 0 and ctx.e == 0
        for joint, kind, _ in drivable:
            _drive_joint3(ctx, joint, kind)
        drivable = []
        if ctx.well_posed:
            # an open chain reaches any value of its drivers: assembly must not refuse it
            ctx.ops.append({"code": f"st0 = m.assemble()  {MUST_SUCCEED}\n", "kind": "assemble (open driven chain)",
                            "check": "finite:st0", "must_succeed": True})
            ctx.well_posed = False
    for _ in range(d(st.integers(0, 2)) if not driven_chain else 0):
        if d(st.booleans()) and drivable:  # (a joint driven twice: seldom, and then from all drivable joints)
            joint = d(st.sampled_from(drivable))
            drivable.remove(joint)
            _drive_joint3(ctx, joint[0], joint[1])
        else:
            name = ctx.name("d")
            coord = d(st.sampled_from(["x", "y", "z"])) if not ctx.hostile() else \
                d(st.sampled_from(["angle", "X", None, 0, "", ["x"], "w"]))
            body = ctx.body_ref(False)
            base = 0.0
            for bname, var, _, pos, _ in ctx.bodies:
                if body in (Expr(var), bname) and coord in ("x", "y", "z"):
                    base = pos["xyz".index(coord)]
            base = _round(base + d(st.sampled_from([0.0, 0.0, 0.0, 0.2, -1.0])))
            ctx.add(call("m.drive_body", name, body, coord, _drive_function(ctx, name, base)), "drive_body")
            ctx.drivers.append(name)
    # forces
    for _ in range(d(st.integers(0, 4))):
        _element3(ctx, d(st.sampled_from(["spring_damper", "rotational_spring_damper", "bushing", "bushing",
                                          "force", "torque"])))


def _joint3(ctx, bi, bj, p, c, kind, along=None):
    """A spatial joint between bi and bj at point p (c: a point on bj, the far end of a distance)."""
    d = ctx.draw
    if kind == "none":
        return
    name = ctx.name("j")
    if kind == "spherical":
        code = call("m.add_spherical", name, bi, bj, at=ctx.vec3(*p))
    elif kind in ("revolute", "cylindrical", "translational"):
        code = call(f"m.add_{kind}", name, bi, bj, at=ctx.vec3(*p), axis=ctx.axis3(along))
    elif kind == "universal":
        axis_i = d(st.sampled_from(AXES))
        axis_j = _cross(axis_i, d(st.sampled_from([a for a in AXES if any(_cross(axis_i, a))])))
        hostile = ctx.hostile()
        code = call("m.add_universal", name, bi, bj, at=ctx.vec3(*p),
                    axis_i=d(st.sampled_from(HOSTILE_VEC3)) if hostile else _fvec(axis_i), axis_j=_fvec(axis_j))
    elif kind == "planar":
        code = call("m.add_planar", name, bi, bj, at=ctx.vec3(*p), normal=ctx.axis3(along))
    elif kind == "weld":
        code = call("m.add_weld", name, bi, bj)
    elif kind == "distance":
        kw = {}
        if d(st.integers(0, 2)) == 2:
            kw["length"] = ctx.num(_log_uniform(d, 0.01, 5.0))
        code = call("m.add_distance", name, bi, ctx.vec3(*p), bj, ctx.vec3(*c), **kw)
    else:
        raise AssertionError(kind)
    ctx.add(code, f"add_{kind}")
    ctx.joints.append((name, kind, 0.0))


def _drive_function(ctx, name, base):
    """What a spatial driver prescribes, starting at ``base``: often an
    mb.Input (a Simulator then makes it jump), else any time function."""
    if ctx.draw(st.integers(0, 2)) == 2:
        f = Expr(call("mb.Input", ctx.num(base)))
    else:
        f = ctx.time_function(base=base)
    if isinstance(f, Expr) and f.startswith("mb.Input(") and "name=" not in f:
        ctx.inputs[name] = base  # the input is named after the driver
    return f


def _drive_joint3(ctx, joint, kind):
    name = ctx.name("d")
    base = ctx.draw(st.sampled_from(ANGLE_STARTS if kind == "revolute" else SLIDE_STARTS))
    ctx.add(call("m.drive_joint", name, joint if not ctx.hostile() else ctx.joint_ref(),
                 _drive_function(ctx, name, base)), "drive_joint")
    ctx.drivers.append(name)


def _element3(ctx, kind):
    d = ctx.draw
    name = ctx.name(kind[:2])
    if kind == "spring_damper":
        kw = _spring_damper_values(ctx)
        bi, bj = ctx.body_pair()
        code = call("m.add_spring_damper", name, bi, ctx.point_on3(bi), bj, ctx.point_on3(bj), **kw)
    elif kind == "rotational_spring_damper":
        kw = _rotational_spring_damper_values(ctx)
        code = call("m.add_rotational_spring_damper", name, ctx.joint_ref(("revolute", "cylindrical")), **kw)
    elif kind == "bushing":
        bi, bj = ctx.body_pair()
        kw = {}
        for key, lo, hi in (("stiffness", 1.0, 1e8), ("damping", 1e-2, 1e4), ("rotational_stiffness", 1e-1, 1e6),
                            ("rotational_damping", 1e-3, 1e3)):
            if d(st.integers(0, 3)) < 3:
                kw[key] = ctx.vec3(*(_log_uniform(d, lo, hi) if d(st.integers(0, 4)) else 0.0 for _ in range(3)))
        code = call("m.add_bushing", name, bi, bj, ctx.point_on3(bi), **kw)
    elif kind in ("force", "torque"):
        body = ctx.body_ref(False)
        kw = {}
        if kind == "force" and d(st.booleans()):
            kw["point"] = ctx.point_on3(body)
        if d(st.booleans()):
            kw["local"] = d(st.sampled_from([True, False])) if not ctx.hostile() else \
                d(st.sampled_from(["yes", None, 0, 2]))
        if d(st.booleans()):
            value = ctx.vec3(0.0, 0.0, 0.0, spread=50.0 if kind == "force" else 5.0)
        else:
            value = ctx.time_function(derivatives=False, triple=True)
        code = call(f"m.add_{kind}", name, body, value, **kw)
    else:
        raise AssertionError(kind)
    ctx.add(code, f"add_{kind}")
    ctx.others.append(name)


def _maybe(ctx, kw, key, good, pool, p_present=0.5):
    """Put kw[key] = a good value (drawn from the strategy) or a hostile one."""
    d = ctx.draw
    if ctx.hostile():
        kw[key] = d(st.sampled_from(pool))
    elif d(st.integers(0, 999)) >= 1000 - p_present * 1000:
        kw[key] = d(good)


HOSTILE_TOL = [nan, 0.0, -1e-6, "1e-6", 2 ** 40, BIG, 1e-300, 5e-324, 1e300, inf, None, True, [1e-6, nan], [],
               [[1e-6]], Expr("np.float32(1e-6)")]
HOSTILE_COUNT = [0, 1, -3, 2.5, "10", nan, True, 2 ** 40, BIG, None, inf, Expr("np.int64(5)"), 1e9]
HOSTILE_STEP = [0.0, -1.0, nan, inf, "0.01", 2 ** 40, 1e-20, 1e-300, 5e-324, True, BIG, [0.01]]
HOSTILE_TIME = [nan, -1.0, 0.0, inf, "0.05", None, 1e-300, 5e-324, True, BIG, [0.05], -inf]


def _runs(ctx):
    d = ctx.draw
    bodies = [b[0] for b in ctx.bodies]
    n_sim = 0
    ops = d(st.lists(st.sampled_from(["dof", "assemble", "solve", "simulate", "simulate", "simulate",
                                      "equilibrium", "rank", "simulator"] +
                                     ([] if ctx.dim == 2 else ["simulator", "equilibrium"])), min_size=1, max_size=4))
    if "simulate" not in ops:
        ops.append("simulate")
    for what in ops:
        if what == "dof":
            ctx.add("dof = m.degrees_of_freedom()", "degrees_of_freedom", check="finite:dof")
        elif what == "rank":
            ctx.add("rk = m.rank()", "rank", check="finite:rk")
        elif what == "assemble":
            t = ctx.num(0.0, HOSTILE_TIME) if d(st.booleans()) else None
            ctx.add("st0 = m.assemble()" if t is None else f"st0 = m.assemble(t={lit(t)})", "assemble",
                    check="finite:st0")
        elif what == "solve":
            src = d(st.sampled_from(["assembled", "zeros", "hostile"]))
            if src == "assembled":
                ctx.add("st1 = m.assemble()", "assemble", check="finite:st1")
                q, v = Expr("st1[0]"), Expr("st1[1]")
                if d(st.booleans()):
                    v = Expr(f"st1[1] + {ctx.num(1.0)!r}")
            elif src == "zeros":
                q, v = Expr("np.zeros(m.n_coordinates)"), Expr("np.ones(m.n_coordinates)")
            else:
                pool = [Expr("np.full(m.n_coordinates, nan)"), Expr("np.full(m.n_coordinates, 1e300)"),
                        Expr("[0.0] * (m.n_coordinates + 1)"), [], "abc", None, Expr("np.zeros((m.n_coordinates, 1))"),
                        Expr("[None] * m.n_coordinates"), Expr("np.full(m.n_coordinates, 10**400)"),
                        Expr("np.zeros(m.n_coordinates, dtype=complex)")]
                q, v = d(st.sampled_from(pool)), d(st.sampled_from(pool))
            kw = {}
            if d(st.booleans()):
                kw["t"] = ctx.num(0.01, HOSTILE_TIME)
            ctx.add(f"acc = {call('mb.solve_accelerations', Expr('m'), q, v, **kw)}", "solve_accelerations", check="finite:acc")
        elif what == "simulate":
            n_sim += 1
            var = f"r{n_sim}"
            kw = {}
            formulation = d(st.sampled_from(FORMULATIONS)) if not ctx.hostile() else \
                d(st.sampled_from(HOSTILE_FORMULATIONS))
            t_end = d(st.sampled_from(HOSTILE_TIME + [1e12])) if ctx.hostile() else \
                d(st.sampled_from([0.05, 0.05, 0.02, 0.1]))
            kw["t_end"] = t_end
            if formulation != "ggl" or d(st.booleans()):
                kw["formulation"] = formulation
            if formulation == "projection" and d(st.booleans()):
                kw["integrator"] = "adams"
            elif ctx.hostile():
                kw["integrator"] = d(st.sampled_from(["ADAMS", None, 1, "rk4"]))
            _maybe(ctx, kw, "rtol", st.builds(lambda e: _round(10.0 ** e), st.floats(-9, -3)), HOSTILE_TOL)
            _maybe(ctx, kw, "atol", st.builds(lambda e: _round(10.0 ** e), st.floats(-12, -4)), HOSTILE_TOL)
            _maybe(ctx, kw, "n_out", st.integers(2, 30), HOSTILE_COUNT)
            _maybe(ctx, kw, "max_step", st.sampled_from([1e-3, 5e-3, 0.02]), HOSTILE_STEP, 0.3)
            _maybe(ctx, kw, "max_steps", st.sampled_from([1, 5, 50, 2000]), HOSTILE_COUNT, 0.2)
            if formulation == "ali3p":
                _maybe(ctx, kw, "step", st.sampled_from([1e-3, 1e-4, 5e-3]), HOSTILE_STEP, 0.7)
            elif ctx.hostile():
                kw["step"] = 1e-3
            _maybe(ctx, kw, "max_order", st.integers(1, 5), HOSTILE_COUNT + [0, 99], 0.15)
            if formulation in ("index1", "projection") or ctx.hostile():
                _maybe(ctx, kw, "baumgarte", st.sampled_from([(10.0, 10.0), (0.0, 100.0)]),
                       [(nan, 1.0), (1e300, 1e300), (-10.0, -10.0), "ab", (1.0,), None, 5.0, (BIG, 1.0)], 0.3)
            _maybe(ctx, kw, "analysis", st.sampled_from(["auto", "dynamic", "kinematic", "inverse_dynamics"]),
                   ["AUTO", None, 1, ""], 0.2)
            _maybe(ctx, kw, "start", st.sampled_from(["given", "equilibrium"]), ["eq", None, True],
                   0.2 if ctx.dim == 2 else 0.4)
            _maybe(ctx, kw, "t0", st.sampled_from([0.0, 0.01, -0.02]), HOSTILE_TIME, 0.1)
            _maybe(ctx, kw, "t_out", st.sampled_from([[0.0, 0.01, 0.05], [0.03]]),
                   [[0.05, 0.01], [nan], [], "abc", [[0.01, 0.02]], [0.0, 0.0], [0.0, inf], [0.0, 1e300]], 0.1)
            if isinstance(t_end, (int, float)) and not isinstance(t_end, bool) and abs(t_end) > 1 \
                    and "max_steps" not in kw:
                kw["max_steps"] = 100  # a huge t_end must still stop within max_steps
            if ctx.dim == 3 and "max_steps" not in kw:
                kw["max_steps"] = SPATIAL_MAX_STEPS
            ctx.add(f"{var} = {call('mb.simulate', Expr('m'), **kw)}", "simulate", check=f"result:{var}")
            for _ in range(d(st.integers(0, 3))):
                _accessor(ctx, var, bodies)
        elif what == "simulator":
            _simulator(ctx)
        elif what == "equilibrium":
            kw = {}
            _maybe(ctx, kw, "t", st.sampled_from([0.0, 0.02]), HOSTILE_TIME, 0.2)
            _maybe(ctx, kw, "tol", st.sampled_from([1e-12, 1e-8, 1e-4]), HOSTILE_TOL, 0.2)
            _maybe(ctx, kw, "max_iterations", st.sampled_from([1, 5, 100]), HOSTILE_COUNT, 0.2)
            _maybe(ctx, kw, "allow_unstable", st.booleans(), ["no", None, 2, nan], 0.5)
            ctx.add(f"eq = {call('mb.equilibrium', Expr('m'), **kw)}", "equilibrium", check="equilibrium:eq")
            if d(st.booleans()):
                b = ctx.body_ref(allow_ground=False)
                ctx.add(f"x = eq.body({lit(b)}).position", "eq.body", check="finite:x")
            if d(st.booleans()):
                ctx.add(f"x = eq.reaction({lit(ctx.joint_ref())})", "eq.reaction",
                        check="finite:x")


def _simulator(ctx, threads=False):
    """A Simulator advanced in chunks, its inputs set (by the names of any
    element: most are not inputs), its state saved and restored. Spatial:
    driver inputs also jump by pi or more. threads: two threads also advance
    it at once (_two_threads), at a random point of the sequence or last.
    Spatial: also many short advances in a row."""
    d = ctx.draw
    kw = {}
    formulation = d(st.sampled_from(FORMULATIONS)) if not ctx.hostile() else d(st.sampled_from(HOSTILE_FORMULATIONS))
    if formulation != "ggl":
        kw["formulation"] = formulation
    if formulation == "ali3p":
        kw["step"] = d(st.sampled_from([1e-3, 5e-3]))
    _maybe(ctx, kw, "rtol", st.builds(lambda e: _round(10.0 ** e), st.floats(-9, -3)), HOSTILE_TOL)
    _maybe(ctx, kw, "output_interval", st.sampled_from([0.01, 0.004]), HOSTILE_STEP + [-0.01], 0.3)
    kw["max_steps"] = 2000  # per advance: a huge time must still stop
    ctx.add(f"sim = {call('mb.Simulator', Expr('m'), **kw)}", "Simulator")
    names = ctx.drivers + ctx.others + ["nosuch"]
    t, saved = 0.0, False
    whats = ["advance", "advance", "set_input", "state", "restore"]
    if ctx.dim == 3:
        whats += ["advance_many"] + (["jump", "jump"] if ctx.inputs else [])
    if threads:
        whats += ["two_threads"]
    n_steps = d(st.integers(1, 5))
    threaded = False
    for k in range(n_steps + 1):
        if k == n_steps:  # one more step: the two threads a threaded case is for
            if not threads or threaded:
                break
            what = "two_threads"
        else:
            what = d(st.sampled_from(whats))
        if what == "restore" and not saved:
            what = "state"
        saved = saved or what == "state"
        if what == "jump":
            name = d(st.sampled_from(sorted(ctx.inputs)))
            now, (jump, size) = ctx.inputs[name], d(st.sampled_from(INPUT_JUMPS))
            if isinstance(now, float):
                ctx.inputs[name] = now + size
                ctx.add(f"sim.set_input({name!r}, {now!r} + {jump})", "Simulator.set_input (jump)")
            continue
        if what == "two_threads":
            threaded = True
            t = _two_threads(ctx, t)
            continue
        if what == "advance_many":  # many short advances: outputs inside steps, up to breakpoints
            n, dt = d(st.sampled_from([20, 50])), d(st.sampled_from([1e-4, 1e-3]))
            ctx.add(f"for _ in range({n}):\n    sim.advance(sim.t + {dt!r})", "Simulator.advance (many)")
            t = _round(t + n * dt + dt)
            continue
        if what == "advance":
            t = _round(t + d(st.sampled_from([0.005, 0.01, 0.02])))
            target = d(st.sampled_from(HOSTILE_TIME + [1e6])) if ctx.hostile() else t
            ctx.add(f"sim.advance({lit(target)})", "Simulator.advance")
        elif what == "set_input":
            value = ctx.num(d(st.sampled_from([0.0, 1.0, -5.0])))
            ctx.add(f"sim.set_input({lit(d(st.sampled_from(names)))}, {lit(value)})", "Simulator.set_input")
        elif what == "state":
            ctx.add("saved = sim.state()", "Simulator.state")
        else:
            ctx.add("sim.set_state(saved)", "Simulator.set_state")
    ctx.add("x = np.concatenate([sim.q, sim.v, sim.a, sim.lam, [sim.t]])", "Simulator.state_now", check="finite:x")
    ctx.add("rs = sim.result()", "Simulator.result", check="result:rs")


#: the functions the threads of _two_threads run (one def op)
THREAD_HELPERS = '''import threading


def advance_repeatedly(sim, dt, n, errors, jumps=()):
    """n times sim.advance(sim.t + dt); every 10th time also each (input,
    step) of jumps: sim.set_input(input, sim.input(input) + step). A call
    the other thread overtook (sim.t already past its target) is refused
    by lagmb: that is fine. Any other exception ends the thread, kept in
    errors."""
    try:
        for k in range(n):
            target = sim.t + dt
            try:
                sim.advance(target)
            except mb.ModelError:
                if not sim.t > target:
                    raise
            if k % 10 == 5:
                for name, step in jumps:
                    sim.set_input(name, sim.input(name) + step)
    except BaseException as e:
        errors.append(e)


def read_repeatedly(sim, n, errors):
    """n times what a monitor reads while the simulator runs: the state now and the result so far."""
    try:
        for _ in range(n):
            np.concatenate([sim.q, sim.v, sim.a, sim.lam, [sim.t]])
            len(sim.result())
    except BaseException as e:
        errors.append(e)
'''


def two_threads_op(n, dt, jumps=(), reader=False):
    """The op in which two threads advance ``sim`` at once, each by
    sim.advance(sim.t + dt), n times (the second also adds each (input, step)
    of jumps to that input every 10th time; with reader, a third thread reads
    the state meanwhile). It raises what a thread raised, and asserts that
    together they advanced sim by at least n dt. Needs THREAD_HELPERS."""
    targets = [f"threading.Thread(target=advance_repeatedly, args=(sim, {dt!r}, {n}, errors))",
               f"threading.Thread(target=advance_repeatedly, args=(sim, {dt!r}, {n}, errors"
               + (f", {lit(list(jumps))}))" if jumps else "))")]
    if reader:
        targets.append(f"threading.Thread(target=read_repeatedly, args=(sim, {n}, errors))")
    code = ("errors = []\n"
            "threads = [" + ",\n           ".join(targets) + "]\n"
            "t_before = sim.t\n"
            "for th in threads:\n"
            "    th.start()\n"
            "for th in threads:\n"
            "    th.join()\n"
            "if errors:\n"
            "    raise errors[0]\n"
            f"assert sim.t >= t_before + {n} * {dt!r} * (1 - 1e-9), "
            f"f'two threads advanced by {n} x {dt!r} each, but the simulator went from t = {{t_before}} "
            f"only to {{sim.t}}'\n")
    return {"code": code, "kind": THREADS_KIND, "check": None}


def _two_threads(ctx, t):
    """Two threads on one Simulator at once (two_threads_op), n advances of dt
    each; sometimes the second also makes the driver inputs jump, or a third
    reads the state meanwhile. Expected: the calls are serialized (no crash,
    no foreign exception) and together they advance it by at least n dt.
    -> an upper bound of sim.t after it."""
    d = ctx.draw
    if not any(op["code"] == THREAD_HELPERS for op in ctx.ops):
        ctx.add(THREAD_HELPERS, "def")
    n = d(st.sampled_from([50, 100, 200]))
    dt = d(st.sampled_from([1e-4, 1e-3, 5e-3]))
    jumps = []
    if ctx.inputs and d(st.booleans()):
        jumps = [(name, d(st.sampled_from(INPUT_JUMPS))[1]) for name in sorted(ctx.inputs)]
    ctx.ops.append(two_threads_op(n, dt, jumps, reader=d(st.integers(0, 3)) == 3))
    return _round(t + 2 * n * dt + dt)


def _scene(ctx):
    """Write the model as a scene file, load it back and run it."""
    ctx.add("import os, tempfile\nscene_path = os.path.join(tempfile.mkdtemp(), 'fuzz.toml')", "setup")
    settings = None
    if ctx.draw(st.booleans()):
        settings = ctx.draw(st.sampled_from([{"t_end": 0.05}, {"t_end": 0.05, "formulation": "index1"},
                                             {"t_end": 0.02, "n_out": 5, "rtol": 1e-8}]))
        if ctx.hostile():
            settings = ctx.draw(st.sampled_from([{"t_end": nan}, {"t_end": "x"}, {"nonsense": 1}, {"t_end": BIG},
                                                 {"t_end": 0.05, "n_out": 2 ** 40}, {"t_end": None}]))
    if ctx.dim == 3 and settings is not None and "t_end" in settings:
        settings = dict(settings, max_steps=SPATIAL_MAX_STEPS)
    ctx.add(f"mb.save_scene(m, scene_path{'' if settings is None else ', settings=' + lit(settings)})\n"
            "written = scene_path", "save_scene")
    ctx.add("scene = mb.load_scene(written)", "load_scene")  # only if it was written
    bound = "" if ctx.dim == 2 else f", max_steps={SPATIAL_MAX_STEPS}"
    ctx.add("r9 = scene.run()" if settings is not None else f"r9 = mb.simulate(scene.model, t_end=0.05{bound})",
            "scene.run", check="result:r9")


def _accessor(ctx, var, bodies):
    d = ctx.draw
    what = d(st.sampled_from(["reaction", "reaction_joint", "energy", "residual", "point", "body", "effort",
                              "friction", "velocity_residual", "multipliers"]))
    if what == "reaction":
        code, kind = f"x = {var}.reaction({lit(ctx.joint_ref())})", "r.reaction"
    elif what == "reaction_joint":
        frame = "joint" if not ctx.hostile() else d(st.sampled_from(["JOINT", None, 1]))
        code, kind = f"x = {var}.reaction({lit(ctx.joint_ref())}, frame={lit(frame)})", "r.reaction"
    elif what == "energy":
        code, kind = f"x = {var}.energy", "r.energy"
    elif what == "residual":
        code, kind = f"x = {var}.residual", "r.residual"
    elif what == "velocity_residual":
        code, kind = f"x = {var}.velocity_residual", "r.velocity_residual"
    elif what == "point":
        body = ctx.body_ref(allow_ground=False)
        local = ctx.vec(0.5, 0.0) if ctx.dim == 2 else ctx.vec3(0.5, 0.0, 0.0)
        code, kind = f"x = {var}.point({lit(body)}, {lit(local)})", "r.point"
    elif what == "body":
        attr = d(st.sampled_from(["position", "angle", "velocity", "angular_acceleration"] if ctx.dim == 2 else
                                 ["position", "orientation", "rotation", "angular_velocity", "angular_acceleration"]))
        code, kind = f"x = {var}.body({lit(ctx.body_ref(allow_ground=False))}).{attr}", "r.body"
    elif what == "effort":
        ref = d(st.sampled_from(ctx.drivers)) if ctx.drivers and not ctx.hostile() else ctx.joint_ref()
        code, kind = f"x = {var}.effort({lit(ref)})", "r.effort"
    elif what == "multipliers":
        code, kind = f"x = {var}.multipliers({lit(ctx.joint_ref())})", "r.multipliers"
    else:
        code, kind = f"x = {var}.friction({lit(ctx.draw(st.sampled_from(ctx.others or ['nosuch'])))})", "r.friction"
    ctx.add(code, kind, check="finite:x")


if st is not None:
    @st.composite
    def cases(draw):
        """A case: the ops that build a random mechanism and run it."""
        hostility = draw(st.sampled_from([0.0, 0.0, 0.0, 0.01, 0.04, 0.12]))
        extremity = draw(st.sampled_from([0.0, 0.0, 0.03, 0.1]))
        coin = random.Random(draw(st.integers(0, 2 ** 32 - 1)))
        ctx = Ctx(draw, hostility, extremity, coin)
        _build(ctx)
        _runs(ctx)
        if draw(st.integers(0, 3)) == 3:
            # change the model after a run (it is rebuilt), then run again
            for _ in range(draw(st.integers(1, 2))):
                _element(ctx, draw(st.sampled_from(["spring_damper", "force", "torque", "stop", "joint_friction",
                                                    "contact", "rotational_spring_damper"])))
            _runs(ctx)
        if draw(st.integers(0, 4)) == 4:
            _scene(ctx)
        return ctx.ops

    @st.composite
    def spatial_cases(draw):
        """A case: the ops that build a random spatial mechanism (Model(dimension=3)) and run it."""
        hostility = draw(st.sampled_from([0.0, 0.0, 0.0, 0.0, 0.01, 0.04]))
        extremity = draw(st.sampled_from([0.0, 0.0, 0.0, 0.03]))
        coin = random.Random(draw(st.integers(0, 2 ** 32 - 1)))
        ctx = Ctx(draw, hostility, extremity, coin)
        _build3(ctx)
        _runs(ctx)
        if draw(st.integers(0, 4)) == 4:
            for _ in range(draw(st.integers(1, 2))):
                _element3(ctx, draw(st.sampled_from(["spring_damper", "bushing", "force", "torque",
                                                     "rotational_spring_damper"])))
            _runs(ctx)
        if draw(st.integers(0, 5)) == 5:
            _scene(ctx)
        return ctx.ops

    @st.composite
    def threaded_cases(draw):
        """A case: a random mechanism (3 in 4 spatial, half of them open driven
        chains; no hostile values) and a Simulator of it that two threads
        advance at once."""
        ctx = Ctx(draw, 0.0, 0.0, random.Random(draw(st.integers(0, 2 ** 32 - 1))))
        if draw(st.integers(0, 3)) == 3:
            _build(ctx)
        else:
            _build3(ctx, driven_chain=True if draw(st.booleans()) else None)
        _simulator(ctx, threads=True)
        return ctx.ops

    FAMILIES = {"planar": cases, "spatial": spatial_cases, "threads": threaded_cases}


def generate(n, derandomize, rng_seed=None, family="planar"):
    """n cases drawn by hypothesis (generation only: they are plain data);
    family: "planar" (cases), "spatial" (spatial_cases) or "threads"
    (threaded_cases)."""
    from hypothesis import HealthCheck, Phase, given, seed, settings

    drawn = []

    def collect(case):
        drawn.append(case)

    test = given(FAMILIES[family]())(collect)
    test = settings(max_examples=n, derandomize=derandomize, database=None, deadline=None,
                    phases=[Phase.generate], suppress_health_check=list(HealthCheck))(test)
    if rng_seed is not None:
        test = seed(rng_seed)(test)
    test()
    return drawn


if __name__ == "__main__":
    if len(sys.argv) in (3, 4) and sys.argv[1] == "--generate":  # deterministic, as JSON
        json.dump(generate(int(sys.argv[2]), derandomize=True, family=(sys.argv[3:] or ["planar"])[0]), sys.stdout)
    elif len(sys.argv) == 3 and sys.argv[1] == "--replay":
        problems, _ = replay(sys.argv[2])
        for p in problems:
            print(p["key"], "--", p["detail"])
        if not problems:
            print("no problem")
    else:
        print(__doc__)
