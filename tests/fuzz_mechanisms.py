"""Random small mechanisms with hostile inputs, run out of process.

Used by tests/test_fuzz_mechanisms.py (issue "Fuzzed inputs"); also a
command-line tool:

    python3 tests/fuzz_mechanisms.py --worker          # the worker (reads cases on stdin)
    python3 tests/fuzz_mechanisms.py --replay FILE.py   # run one reproducer in a worker

A *case* is plain data: a list of *ops*, each a dict

    {"code": "<python statements>", "kind": "simulate",
     "check": None | "finite:x" | "result:r1" | "equilibrium:eq"}

The strategy ``cases()`` draws them with hypothesis in the parent process;
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
  or a successful run whose max |Phi| exceeds 1e-4 (1 + max |q|).

The parent (``Worker``) adds crashes (the worker died on op k: signal) and
hangs (op k took longer than the timeout: the worker is killed).
"""

import json
import math
import os
import random
import re
import selectors
import signal
import subprocess
import sys
import tempfile
import time

try:  # the parent needs hypothesis; the worker does not
    from hypothesis import strategies as st
except ImportError:  # pragma: no cover
    st = None

HERE = os.path.dirname(os.path.abspath(__file__))
RESIDUAL_BOUND = 1e-4  # a "successful" run must keep max |Phi| <= RESIDUAL_BOUND * (1 + max |q|)

HEADER = ("import numpy as np\n"
          "import lagmb as mb\n"
          "from math import nan, inf\n")


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

    def time_function(self, derivatives=True, pair=False, base=0.0):
        """A number, an mb time function, or the source of a Python callable
        (a def op is added and its name returned)."""
        d = self.draw
        kind = d(st.sampled_from(["number", "constant", "linear", "harmonic", "smooth_step", "polynomial",
                                  "spline", "callable", "callable", "bad_callable", "input"]))
        if kind == "bad_callable" and not _chance(d, 0.3 + self.h):
            kind = "callable"
        if pair:
            kind = d(st.sampled_from(["pair", "callable", "bad_callable"]))
        if kind == "pair":
            return (self.time_function(False), self.time_function(False))
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
        elif pair:
            good = f"({amp} * t, -{amp})"
        else:
            good = f"{amp} * t"
        body = f"    return {good}\n"
        if kind == "bad_callable":
            tb = d(st.sampled_from([0.0, 0.01, 0.03]))
            bad = d(st.sampled_from([
                "raise ZeroDivisionError('boom')", "return nan" if not (derivatives or pair) else "return (nan, 0.0, 0.0)",
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


def _element(ctx, kind):
    d = ctx.draw
    name = ctx.name(kind[:2])
    if kind == "spring_damper":
        kw = dict(stiffness=ctx.num(_log_uniform(d, 1e-2, 1e6)), damping=ctx.num(_log_uniform(d, 1e-3, 1e3)))
        if d(st.booleans()):
            kw["free_length"] = ctx.num(_log_uniform(d, 0.01, 3.0))
        if d(st.integers(0, 2)) == 2:
            kw["force"] = ctx.time_function(derivatives=False)
        bi, bj = ctx.body_pair()
        code = call("m.add_spring_damper", name, bi, ctx.point_on(bi), bj, ctx.point_on(bj), **kw)
    elif kind == "rotational_spring_damper":
        kw = dict(stiffness=ctx.num(_log_uniform(d, 1e-2, 1e5)), damping=ctx.num(_log_uniform(d, 1e-3, 1e2)))
        if d(st.booleans()):
            kw["free_angle"] = ctx.num(_round(d(st.floats(-3, 3))))
        if d(st.integers(0, 2)) == 2:
            kw["torque"] = ctx.time_function(derivatives=False)
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
                                      "equilibrium", "rank", "simulator"]), min_size=1, max_size=4))
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
            _maybe(ctx, kw, "start", st.sampled_from(["given", "equilibrium"]), ["eq", None, True], 0.2)
            _maybe(ctx, kw, "t0", st.sampled_from([0.0, 0.01, -0.02]), HOSTILE_TIME, 0.1)
            _maybe(ctx, kw, "t_out", st.sampled_from([[0.0, 0.01, 0.05], [0.03]]),
                   [[0.05, 0.01], [nan], [], "abc", [[0.01, 0.02]], [0.0, 0.0], [0.0, inf], [0.0, 1e300]], 0.1)
            if isinstance(t_end, (int, float)) and not isinstance(t_end, bool) and abs(t_end) > 1 \
                    and "max_steps" not in kw:
                kw["max_steps"] = 100  # a huge t_end must still stop within max_steps
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


def _simulator(ctx):
    """A Simulator advanced in chunks, its inputs set (by the names of any
    element: most are not inputs), its state saved and restored."""
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
    for _ in range(d(st.integers(1, 5))):
        what = d(st.sampled_from(["advance", "advance", "set_input", "state", "restore"]))
        if what == "restore" and not saved:
            what = "state"
        saved = saved or what == "state"
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
    ctx.add(f"m.to_scene(scene_path{'' if settings is None else ', settings=' + lit(settings)})\n"
            "written = scene_path", "to_scene")
    ctx.add("scene = mb.load_scene(written)", "load_scene")  # only if it was written
    ctx.add("r9 = scene.run()" if settings is not None else "r9 = mb.simulate(scene.model, t_end=0.05)",
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
        code, kind = f"x = {var}.point({lit(ctx.body_ref(allow_ground=False))}, {lit(ctx.vec(0.5, 0.0))})", "r.point"
    elif what == "body":
        attr = d(st.sampled_from(["position", "angle", "velocity", "angular_acceleration"]))
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
    for method, kw in m.elements():
        if method.startswith(("add_revolute", "add_translational", "add_weld", "add_distance",
                              "add_pin_in_slot", "add_gear", "add_rack_pinion", "drive_")):
            for frame in ("global", "joint"):
                arrays[f"reaction(frame={frame!r})"] = get(lambda: r.reaction(kw["name"], frame=frame))
    for name, a in arrays.items():
        if a is not None and not np.all(np.isfinite(a)):
            bad.append(("nonfinite", "." + name))
    if arrays["t"] is not None and len(arrays["t"]) == 0:
        bad.append(("empty", "t"))
    res, q = arrays["residual"], arrays["q"]
    # index1 integrates Phi'' = 0 only: its drift is documented (README, formulations)
    drifts = r.stats.get("formulation") == "index1"
    if not drifts and res is not None and q is not None and res.size and np.all(np.isfinite(res)) and np.all(np.isfinite(q)):
        bound = RESIDUAL_BOUND * (1.0 + (np.max(np.abs(q)) if q.size else 0.0))
        worst = float(np.max(res))
        if worst > bound:
            k = int(np.argmax(res))
            bad.append(("residual", f"max |Phi| = {worst:.3g} > {bound:.3g} at t = {float(r.t[k]):.4g}"))
    return bad


def _equilibrium_problems(np, eq):
    bad = []
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


def _where(tb):
    """The innermost traceback frame inside lagmb (file:function), if any."""
    import traceback

    frames = traceback.extract_tb(tb)
    for fr in reversed(frames):
        if os.sep + "lagmb" + os.sep in fr.filename:
            return f"{os.path.basename(fr.filename)}:{fr.name}"
    return frames[-1].name if frames else "?"


def _normalize(msg):
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
                        kind = f"simulate[{form.group(1) if form else 'ggl'}]"
                    else:
                        found = _equilibrium_problems(np, value)
                    for tag, detail in found:
                        status = "problem"
                        problems.append({"op": k, "key": f"{kind}: {tag}" + (f" {detail}" if tag != "residual" else ""),
                                         "detail": f"{tag}: {var}{detail}" if tag == "nonfinite" else
                                         f"{tag}: {detail}"})
            except allowed as e:
                status = "refused " + type(e).__name__ + ": " + " ".join(str(e).split())[:150]
            except BaseException as e:  # noqa: B902 - everything else is a finding
                status = "problem"
                typ = f"{type(e).__module__}.{type(e).__qualname__}".replace("builtins.", "")
                msg = str(e)
                problems.append({"op": k, "key": f"{typ} @ {_where(e.__traceback__)}: {_normalize(msg)}",
                                 "detail": f"{typ} in {op['kind']}: {msg[:300]}"})
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
        self.proc = subprocess.Popen([sys.executable, os.path.join(HERE, "fuzz_mechanisms.py"), "--worker"],
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
                return json.loads(line[2:]), statuses


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
    occurs, within budget_s seconds. -> (ops, statuses, problem)."""
    start = time.monotonic()

    def hit(trial):
        problems, statuses = worker.run(trial)
        for p in problems:
            if p["key"] == key:
                return trial[:p["op"] + 1] if p["op"] is not None else trial, statuses, p
        return None

    found = hit(ops)
    if found is None:
        return None
    ops = found[0]
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
    import ast

    with open(path) as f:
        text = f.read()
    tree = ast.parse(text)
    lines = text.splitlines()
    ops = []
    for node in tree.body:
        code = "\n".join(lines[node.lineno - 1:node.end_lineno]) + "\n"
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            continue
        if isinstance(node, ast.Try):  # a refused op, as written by reproducer()
            node = node.body[0]
            code = "\n".join(ln[4:] for ln in lines[node.lineno - 1:node.end_lineno]) + "\n"
        check = None
        m = re.match(r"(\w+) = mb\.(simulate|equilibrium)\(", code)
        if m:
            check = ("result:" if m.group(2) == "simulate" else "equilibrium:") + m.group(1)
        kind = re.sub(r"^\w+ = ", "", code).split("(")[0].strip()
        ops.append({"code": code, "kind": kind, "check": check})
    w = Worker(timeout)
    try:
        return w.run(ops)
    finally:
        w.close()


def generate(n, derandomize, rng_seed=None):
    """n cases drawn by hypothesis (generation only: they are plain data)."""
    from hypothesis import HealthCheck, Phase, given, seed, settings

    drawn = []

    def collect(case):
        drawn.append(case)

    test = given(cases())(collect)
    test = settings(max_examples=n, derandomize=derandomize, database=None, deadline=None,
                    phases=[Phase.generate], suppress_health_check=list(HealthCheck))(test)
    if rng_seed is not None:
        test = seed(rng_seed)(test)
    test()
    return drawn


if __name__ == "__main__":
    if sys.argv[1:] == ["--worker"]:
        worker_main()
    elif len(sys.argv) == 3 and sys.argv[1] == "--generate":  # deterministic, as JSON
        json.dump(generate(int(sys.argv[2]), derandomize=True), sys.stdout)
    elif len(sys.argv) == 3 and sys.argv[1] == "--replay":
        problems, _ = replay(sys.argv[2])
        for p in problems:
            print(p["key"], "--", p["detail"])
        if not problems:
            print("no problem")
    else:
        print(__doc__)
