"""Random mechanisms with stops, and the physics every run of them must obey.

Used by tests/fuzz/test_fuzz_stops.py (issue 41, "Joint limits and stops that
hold"). A *case* is plain data, {"ops": [...], "meta": {...}}: the ops are
those of tests/fuzz/fuzz_mechanisms.py (Python source over ``mb`` and ``np``, run
op by op in its worker subprocess, so that a crash or a hang of the core fails
one case, not pytest): one op builds the model, one runs it (``simulate``,
or a ``Simulator`` advanced in chunks while its inputs jump) and the last
checks the result with ``stop_problems``, which raises an AssertionError
naming each broken law. ``meta`` says what the checks need to know: the
stops (joint, coordinate, limits, restitution), whether the run may gain
energy (drivers, applied torques, inputs do work) or must lose it (dampers),
and the mechanism's scales.

The mechanisms (strategy ``stop_cases``): planar pendulums, chains of 2-4
links, sliders on inclined, vertical or level rails (sometimes with a
pendulum hanging from the slider), a four-bar, two alike pendulums apart
with alike stops (struck at the same instant); spatial pendulums, chains of
2-3 links on revolutes with various axes, sliders on rails; a quarter of
them without gravity, spinning faster (to 50 rad/s). Adams runs also at
rtol 1e-3 (a drift that comes apart must fail, not be restarted from). Each stopped
joint gets one or two stops with random limits (sometimes the start on a
limit, moving into it or pressed on it by gravity), restitution in 0..0.95;
optional dampers, drivers on other joints, applied torques (time functions,
or an mb.Input that jumps in a Simulator). Every formulation with events:
ggl, index1, index3, projection (BDF, Adams, explicit Runge-Kutta).

The laws (``stop_problems``), for a run that succeeds:
- no joint beyond a limit by more than POSITION_TOL (m: times the
  mechanism's length), plus the drift of the formulations that let the
  positions drift (index1, Adams);
- no energy gained: without drivers, torques or inputs, r.energy never
  rises above an earlier value by more than the integration tolerance (and
  the forces' work over that drift); with a damper it ends lower than it
  began by at least what the damper takes (c int(rate^2) dt, a lower bound
  of it from the outputs);
- no impact at (nearly) every output time (a joint sinking through its stop
  while "impacting"), and at most MAX_EVENTS events (EVENTS_PER_RELEASE
  more for each release) unless restitution is
  high; r.stats counts what r.events lists;
- between a row's capture and its release its stop's force pushes (>=
  -FORCE_TOL along the gap) and the joint sits on the limit; while open the
  stop's effort is exactly 0.

What the core breaks today is shrunk to xfail tests: KNOWN_BUGS names the
features that break the laws (``stop_cases(known_bugs=False)``, the default,
leaves them out), KNOWN_LAWS the laws broken by mechanisms of any kind
(stop_problems names them apart, so a run that breaks only those can be
counted rather than failed). Both are empty today: every feature is drawn
(inputs that jump in a Simulator among them) and no law is excused.
"""

import math
import os
import random

try:  # the parent draws cases with hypothesis; the worker only checks results
    from hypothesis import strategies as st
except ImportError:  # pragma: no cover
    st = None

HERE = os.path.dirname(os.path.abspath(__file__))
G = 9.81
RTOL, ATOL = 1e-8, 1e-10  # every run's tolerances
POSITION_TOL = 1e-8  # rad, or m per m of the mechanism's length: how far beyond a limit a joint may be
# J per J of the mechanism's energy scale: the integration error a conservative
# run shows (measured on the fuzzed mechanisms without their stops: index3's
# velocities are only index-2 accurate, up to 6e-5 there, and a chain whose
# light first rod spins at 6 rad/s gains 1.1e-5 at rtol 1e-9 and fails at
# 1e-8 (IDA's error test), 3.1e-4 with a stop on it; index 1 drifts off its
# position constraints, 1.3e-6 in 3 s on a pendulum hanging from a block on
# a rail; projection with Adams 1.4e-6 on a free pendulum; the others 1e-8)
ENERGY_TOL = {"index3": 5e-4, "index1": 5e-6, "projection": 5e-6}
ENERGY_TOL_DEFAULT = 1e-6
FORCE_TOL = 1e-6  # N (N m) per N (N m) of the mechanism's force scale: how far a closed stop's force may pull
GRAZE_DEPTH = 1e-4  # rad (or m): how deep a missed grazing crossing is at most, to be told from a sinking joint
MAX_EVENTS = 400  # events a run may log unless some restitution is >= HIGH_RESTITUTION,
EVENTS_PER_RELEASE = 20  # and more for each release (a landing's bounce series, its capture)
HIGH_RESTITUTION = 0.8
FORMULATIONS = [("ggl", {}), ("index1", {}), ("projection", {"integrator": "erk"}), ("auto", {}),
                ("projection", {"integrator": "adams"}), ("index3", {}), ("projection", {}),
                # Adams at a loose rtol drifts far: a restart must not hide a run that came apart (issue 56)
                ("projection", {"integrator": "adams", "rtol": 1e-3})]

#: What the fuzzer found the core breaking (issue 41), each shrunk to an
#: xfail(strict=True) test of tests/fuzz/test_fuzz_stops.py: {feature: that test}.
#: stop_cases(known_bugs=False) draws none of these features, so that the
#: default suite checks what holds; known_bugs=True draws them all.
KNOWN_BUGS = {}
#: Laws the core breaks in mechanisms of any kind (not a feature to leave out):
#: stop_problems names them apart; {law: the xfail test of it}.
KNOWN_LAWS = {}


# ---------------------------------------------------------------------------
# The laws (run in the worker, on a Result)
# ---------------------------------------------------------------------------

def _closed_intervals(events, stop, label):
    """[(t_capture, t_release)] of one row of a stop from the run's events
    (a row still closed at the end: release at +inf)."""
    out, start = [], None
    for x in events:
        if x["element"] != stop or x["label"] != label:
            continue
        if x["kind"] == "capture" and start is None:
            start = x["t"]
        elif x["kind"] == "release" and start is not None:
            out.append((start, x["t"]))
            start = None
    if start is not None:
        out.append((start, math.inf))
    return out


def _grazing(t, gap, tol, events, stop):
    """True if every output beyond the limit is a lone one, less than
    GRAZE_DEPTH deep, between outputs inside it and with no event of the
    stop between them: a crossing in and out within one step that the root
    finding (which compares the gap's signs at the step's ends) did not see."""
    import numpy as np

    out = np.flatnonzero(gap < -tol)
    times = np.array([x["t"] for x in events if x["element"] == stop])
    for k in out:
        if k == 0 or k == len(t) - 1 or gap[k - 1] < -tol or gap[k + 1] < -tol or -gap[k] > GRAZE_DEPTH:
            return False
        if np.any((times >= t[k - 1]) & (times <= t[k + 1])):
            return False
    return True


def stop_problems(r, meta):
    """The laws the run's result r breaks, as lines of text (empty: none)."""
    import numpy as np

    bad = []
    t = np.asarray(r.t)
    L = meta["length"]
    events = list(r.events)
    t0 = t[0]
    event_times = np.array([x["t"] for x in events])
    # outputs at an event's instant may show either side of it (except t0,
    # recorded after the events there)
    near_event = np.zeros(len(t), bool)
    if len(event_times):
        near_event = np.min(np.abs(t[:, None] - event_times[None, :]), axis=1) <= 1e-12 * (1.0 + np.abs(t))
        near_event &= t > t0
    max_e = max((s["restitution"] for s in meta["stops"]), default=0.0)

    # events: counted as listed, not piled up at the output times
    kinds = [x["kind"] for x in events]
    for kind in ("impact", "capture", "release"):
        if r.stats.get(kind + "s") != kinds.count(kind):
            bad.append(f"events miscounted: r.stats['{kind}s'] = {r.stats.get(kind + 's')}, r.events lists "
                       f"{kinds.count(kind)}")
    impacts = np.array([x["t"] for x in events if x["kind"] == "impact"])
    if len(impacts) and len(t) > 10:
        nearest = np.min(np.abs(impacts[:, None] - t[None, 1:]), axis=1)
        at_outputs = int(np.sum(nearest <= 1e-9 * (1.0 + np.abs(impacts))))
        if at_outputs >= max(5, 0.2 * (len(t) - 1)):
            bad.append(f"impacts at the output times: {at_outputs} of {len(impacts)} impacts fall on one of "
                       f"the {len(t) - 1} outputs after t0")
    # (a joint that lands and lifts off again and again, a block shaken by a
    # spinning bob, logs a bounce series each time: EVENTS_PER_RELEASE more)
    releases = sum(1 for x in events if x["kind"] == "release")
    allowed = MAX_EVENTS + EVENTS_PER_RELEASE * releases
    if len(events) > allowed and max_e < HIGH_RESTITUTION:
        times = np.sort(event_times)
        # the densest microsecond: a pile of impacts at one instant or a chatter over time
        piled = int(np.max(np.searchsorted(times, times + 1e-6) - np.arange(len(times))))
        law = "impacts piled at one instant" if piled >= 0.5 * len(times) else "too many events"
        bad.append(f"{law}: {len(events)} events (more than {allowed}, with {releases} releases; {piled} within "
                   f"1 us) with restitution at most {max_e}")

    # limits, and each row's force while closed or open
    force_tol = FORCE_TOL * meta["force"]
    # index1 holds its joints (and a closed stop) at acceleration level only,
    # and CVODE cannot project Adams steps (docs/methods.md): positions drift
    # by the integration error; the joints' residual (m) shows how far, an
    # angle's drift over a link of 0.25 m or more is some times it, and the
    # energy's is the forces' work over it
    drifts = r.stats.get("formulation") == "index1" or r.stats.get("integrator") == "adams"
    drift = 10.0 * float(np.max(r.residual)) if drifts else 0.0
    for s in meta["stops"]:
        name, joint = s["name"], s["joint"]
        tol = POSITION_TOL * (L if s["coordinate"] == "slide" else 1.0) + drift
        x = np.asarray(getattr(r.joint(joint), s["coordinate"]))
        effort = np.asarray(r.effort(name))
        closed = np.zeros(len(t), bool)
        switching = np.zeros(len(t), bool)
        for label, limit, sign in (("lower", s["lower"], 1.0), ("upper", s["upper"], -1.0)):
            if limit is None:
                continue
            gap = sign * (x - limit)
            if np.min(gap) < -tol:
                k = int(np.argmin(gap))
                law = "a grazing crossing missed" if _grazing(t, gap, tol, events, name) else "beyond its limit"
                bad.append(f"{law}: joint {joint!r} ({s['coordinate']}) at {float(x[k])!r}, {-gap[k]:.3g} past "
                           f"stop {name!r}'s {label} limit {limit!r} at t = {t[k]:.6g} (tolerance {tol:.3g})")
            for start, end in _closed_intervals(events, name, label):
                on = (t > start) & (t < end) & ~near_event
                if start == t0:
                    on |= (t == t0) & (end > t0)
                closed |= on
                # (an output at the instant a row switches may show either side:
                # captured and released at t0, the first output has the held
                # row's force, 0 to rounding)
                switching |= (t == start) | (t == end)
                if not np.any(on):
                    continue
                pull = np.min(sign * effort[on])
                if pull < -force_tol:
                    k = int(np.flatnonzero(on)[np.argmin(sign * effort[on])])
                    bad.append(f"a closed stop pulls: stop {name!r} ({label}) closed from t = {start:.6g} to {end:.6g} "
                               f"has effort {effort[k]:.6g} at t = {t[k]:.6g} (tolerance {force_tol:.3g})")
                off = np.max(np.abs(gap[on]))
                if off > tol:
                    k = int(np.flatnonzero(on)[np.argmax(np.abs(gap[on]))])
                    bad.append(f"a closed stop off its limit: joint {joint!r} at {float(x[k])!r}, {gap[k]:.3g} from "
                               f"stop {name!r}'s {label} limit {limit!r} at t = {t[k]:.6g}, closed from {start:.6g} "
                               f"to {end:.6g}")
        open_ = ~closed & ~near_event & ~switching
        if np.any(effort[open_] != 0.0):
            k = int(np.flatnonzero(open_ & (effort != 0.0))[0])
            bad.append(f"an open stop's effort is not 0: stop {name!r} has effort {effort[k]:.6g} at t = {t[k]:.6g}")

    # energy: only the impacts and the dampers take it; nothing gives it
    if meta["energy"] in ("conserved", "damped"):
        E = np.asarray(r.energy)
        # (a run at a looser rtol than RTOL: its error, that much larger)
        loose = max(meta.get("rtol", RTOL) / RTOL, 1.0)
        tol = loose * ENERGY_TOL.get(r.stats.get("formulation"), ENERGY_TOL_DEFAULT) * meta["energy_scale"] + \
            drift * meta["force"]
        lowest = np.minimum.accumulate(E)
        rise = E - lowest
        if np.max(rise) > tol:
            k = int(np.argmax(rise))
            j = int(np.argmin(E[:k + 1]))
            bad.append(f"energy gained: r.energy rose from {E[j]:.12g} J at t = {t[j]:.6g} to {E[k]:.12g} J at "
                       f"t = {t[k]:.6g} (+{rise[k]:.3g} J, tolerance {tol:.3g} J)")
        if meta["energy"] == "damped":
            # the damper takes c int(rate^2) dt (the impacts more: the energy
            # ends lower by at least that, less the integration error); from
            # the outputs, a lower bound: between two outputs with one sign of
            # the rate, the smaller rate^2 (a fast decay between outputs far
            # apart makes the trapezoids several times too large), halved
            joint, coordinate, c = meta["damper"]
            rate = np.asarray(r.joint(joint).rate)
            same = np.sign(rate[1:]) == np.sign(rate[:-1])
            taken = 0.5 * c * float(np.sum(np.where(same, np.minimum(rate[1:] ** 2, rate[:-1] ** 2), 0.0) * np.diff(t)))
            if not E[0] - E[-1] >= taken - tol:
                bad.append(f"energy kept by a damper: r.energy {E[0]:.12g} J at t0, {E[-1]:.12g} J at the end, "
                           f"its damper (c = {c} on joint {joint!r}) taking {taken:.3g} J")
    return bad


LAWS_BROKEN = "laws broken: "


def check(r, meta):
    """Raise an AssertionError whose first line names the broken laws (LAWS_BROKEN, then
    the laws' names joined by "; "), the problems one a line after it."""
    bad = stop_problems(r, meta)
    if bad:
        laws = sorted({line.split(":")[0] for line in bad})
        raise AssertionError(LAWS_BROKEN + "; ".join(laws) + "\n" + "\n".join(bad))


# ---------------------------------------------------------------------------
# Drawing mechanisms (the parent side)
# ---------------------------------------------------------------------------

def _r(x):
    return float(f"{x:.6g}")


def _v(*xs):
    return tuple(_r(x) for x in xs)


class Builder:
    """What one case knows while it is drawn: its source lines, its joints
    that can take a stop, bodies, the scales and what does work."""

    def __init__(self, draw, dim, known_bugs):
        self.draw = draw
        self.known_bugs = known_bugs  # draw the features of KNOWN_BUGS too
        self.dim = dim
        self.lines = []
        self.joints = []  # (name, coordinate "angle"/"slide", value at the start (planar; 0 in space), body_i, body_j)
        self.bodies = []  # names
        self.stops = []
        self.length = 1.0
        self.weight = 0.0  # sum of m g
        self.kinetic = 0.0  # a bound on the initial kinetic energy
        self.work = False  # drivers, torques or inputs do work
        self.damped = False
        self.inputs = []  # (name, value now, scale of its jumps)
        self.driven = set()  # joints a driver moves
        self.rigid = False  # a closed loop: drivers would leave nothing free
        self.rail_axis = None  # a slider's
        self.spinning = False  # no gravity (faster spins drawn)
        self.twins = False  # two alike pendulums, alike stops
        self.rtol = RTOL  # the run's

    def add(self, line):
        self.lines.append(line)

    def pick(self, options):
        return self.draw(st.sampled_from(options))

    def body(self, name, mass, position, inertia, **kw):
        self.bodies.append(name)
        self.weight += mass * G
        args = ", ".join(f"{k}={v!r}" for k, v in kw.items())
        self.add(f"{name} = m.add_body({name!r}, mass={mass!r}, inertia={inertia!r}, position={position!r}"
                 + (", " + args if args else "") + ")")


# --- planar ------------------------------------------------------------------

def _planar_chain(b, n, lengths, angles, rates):
    """A chain of uniform rods from the ground pin at the origin, rod k along
    the absolute angle angles[k] turning at rates[k] (velocities consistent)."""
    p, v = (0.0, 0.0), (0.0, 0.0)
    for k in range(n):
        L, a, w = lengths[k], angles[k], rates[k]
        u, un = (math.cos(a), math.sin(a)), (-math.sin(a), math.cos(a))
        c = _v(p[0] + 0.5 * L * u[0], p[1] + 0.5 * L * u[1])
        vc = _v(v[0] + 0.5 * L * w * un[0], v[1] + 0.5 * L * w * un[1])
        mass = b.pick([1.0, 0.5, 2.0])
        b.body(f"b{k}", mass, c, _r(mass * L * L / 12.0), angle=_r(a), velocity=vc, angular_velocity=_r(w))
        b.kinetic += 0.5 * mass * (vc[0] ** 2 + vc[1] ** 2) + 0.5 * mass * L * L / 12.0 * w * w
        prev = "m.ground" if k == 0 else f"b{k - 1}"
        b.add(f"m.add_revolute('j{k}', {prev}, b{k}, at={_v(*p)!r})")
        b.joints.append((f"j{k}", "angle", _r(a) - (_r(angles[k - 1]) if k else 0.0), prev, f"b{k}"))
        p = (p[0] + L * u[0], p[1] + L * u[1])
        v = (v[0] + L * w * un[0], v[1] + L * w * un[1])
    b.length = sum(lengths[:n])


def _gravity(b):
    """9.81 m/s^2, or none (a body spinning freely: its accelerations depend
    on its angle alone, a quadrature that Fehlberg 7(8)'s error estimate did
    not see, issue 56); without gravity the joints spin faster."""
    g = b.pick([G, G, G, 0.0])
    b.spinning = g == 0.0
    return g


def _planar(b):
    kind = b.pick(["pendulum", "chain", "slider", "fourbar", "twins"])
    g = _gravity(b)
    b.add(f"m = mb.Model(gravity=(0.0, {-g!r}))")
    d = b.draw
    angle = lambda: _r(d(st.integers(-16, 16)) * math.pi / 16)  # noqa: E731
    rates = [0.0, 0.0, 2.0, -3.0, 6.0] + ([20.0, -50.0] if b.spinning else [])
    rate = lambda: b.pick(rates)  # noqa: E731
    if kind == "twins":  # two pendulums apart, alike: their stops (alike too) struck at the same instant
        a, w, L = angle(), rate(), b.pick([1.0, 0.5])
        for k, x in enumerate([0.0, 2.0]):
            u = (math.cos(a), math.sin(a))
            b.body(f"b{k}", 1.0, _v(x + 0.5 * L * u[0], 0.5 * L * u[1]), _r(L * L / 12.0), angle=_r(a),
                   velocity=_v(-0.5 * L * w * u[1], 0.5 * L * w * u[0]), angular_velocity=_r(w))
            b.kinetic += 0.5 * (0.25 * L * L * w * w) + 0.5 * L * L / 12.0 * w * w
            b.add(f"m.add_revolute('j{k}', m.ground, b{k}, at={_v(x, 0.0)!r})")
            b.joints.append((f"j{k}", "angle", _r(a), "m.ground", f"b{k}"))
        b.length = L
        b.twins = True
    elif kind in ("pendulum", "chain"):
        n = 1 if kind == "pendulum" else d(st.integers(2, 4))
        _planar_chain(b, n, [b.pick([1.0, 0.5, 2.0]) for _ in range(n)], [angle() for _ in range(n)],
                      [rate() for _ in range(n)])
    elif kind == "slider":
        alpha = b.pick([math.pi / 2, math.pi / 6, -math.pi / 4, 0.0, -math.pi / 2])
        u = _v(math.cos(alpha), math.sin(alpha))
        speed = b.pick([0.0, 1.0, -2.0])
        mass = b.pick([2.0, 0.5])
        b.body("block", mass, (0.0, 0.0), 0.1, velocity=_v(speed * u[0], speed * u[1]))
        b.kinetic += 0.5 * mass * speed * speed
        b.add(f"m.add_translational('rail', m.ground, block, at=(0.0, 0.0), axis={u!r})")
        b.rail_axis = u
        b.joints.append(("rail", "slide", 0.0, "m.ground", "block"))
        if d(st.booleans()):  # a pendulum hanging from the block
            a = angle()
            L = b.pick([1.0, 0.5])
            b.body("bob", 1.0, _v(0.5 * L * math.cos(a), 0.5 * L * math.sin(a)), _r(L * L / 12.0), angle=a)
            b.add("m.add_revolute('hinge', block, bob, at=(0.0, 0.0))")
            b.joints.append(("hinge", "angle", a, "block", "bob"))
        b.length = 1.0
    else:  # a four-bar: crank 1, coupler 2, rocker 2, ground 2 (tests/elements/test_stop_rest.py's)
        w = rate()
        b.body("crank", 1.0, (0.0, 0.5), _r(1.0 / 12.0), angle=_r(math.pi / 2), angular_velocity=w)
        b.body("coupler", 2.0, (1.0, 1.0), _r(2.0 * 4.0 / 12.0))
        b.body("rocker", 2.0, (2.0, 0.0), _r(2.0 * 4.0 / 12.0), angle=_r(math.pi / 2))
        b.kinetic += 20.0 * w * w  # a bound: the loop's kinetic energy at crank rate w
        b.add("m.add_revolute('A', m.ground, crank, at=(0.0, 0.0))")
        b.add("m.add_revolute('B', crank, coupler, at=(0.0, 1.0))")
        b.add("m.add_revolute('C', coupler, rocker, at=(2.0, 1.0))")
        b.add("m.add_revolute('D', rocker, m.ground, at=(2.0, -1.0))")
        b.joints += [("A", "angle", _r(math.pi / 2), "m.ground", "crank"),
                     ("B", "angle", _r(-math.pi / 2), "crank", "coupler"),
                     ("D", "angle", _r(-math.pi / 2), "rocker", "m.ground")]
        b.length = 2.0
        b.rigid = True


# --- spatial -------------------------------------------------------------------

AXES3 = [(0.0, 1.0, 0.0), (0.0, 1.0, 1.0), (0.0, 0.0, 1.0), (0.0, 2.0, -1.0)]  # each perpendicular to x


def _turn_x(axis, a):
    """The unit x turned by a about axis (a unit vector perpendicular to x)."""
    n = math.sqrt(sum(c * c for c in axis))
    k = [c / n for c in axis]
    kx = (0.0, k[2], -k[1])  # k x (1, 0, 0)
    return tuple(math.cos(a) * (1.0 if i == 0 else 0.0) + math.sin(a) * kx[i] for i in range(3))


def _spatial(b):
    kind = b.pick(["pendulum", "chain", "slider"])
    g = _gravity(b)
    b.add(f"m = mb.Model(dimension=3, gravity=(0.0, 0.0, {-g!r}))")
    d = b.draw
    if kind in ("pendulum", "chain"):
        n = 1 if kind == "pendulum" else d(st.integers(2, 3))
        p = (0.0, 0.0, 0.0)
        for k in range(n):
            L, mass = b.pick([1.0, 0.5, 2.0]), b.pick([1.0, 0.5, 2.0])
            axis = b.pick(AXES3)
            u = _turn_x(axis, d(st.integers(-8, 8)) * math.pi / 8)
            c = _v(*(p[i] + 0.5 * L * u[i] for i in range(3)))
            w = b.pick([0.0, 0.0, 3.0, -5.0] + ([20.0, -50.0] if b.spinning else [])) if k == 0 else 0.0
            n_axis = math.sqrt(sum(x * x for x in axis))
            kw = {"angular_velocity": _v(*(w * x / n_axis for x in axis))} if w else {}
            if w:  # the centre moves on its circle about the first joint's axis
                k_unit = [x / n_axis for x in axis]
                kw["velocity"] = _v(*(w * x for x in _cross(k_unit, [c[i] - p[i] for i in range(3)])))
                b.kinetic += 0.5 * mass * L * L / 3.0 * w * w
            b.body(f"b{k}", mass, c, _v(mass * L * L / 12.0, mass * L * L / 12.0, mass * L * L / 12.0), **kw)
            prev = "m.ground" if k == 0 else f"b{k - 1}"
            b.add(f"m.add_revolute('j{k}', {prev}, b{k}, at={_v(*p)!r}, axis={axis!r})")
            b.joints.append((f"j{k}", "angle", 0.0, prev, f"b{k}"))
            p = tuple(p[i] + L * u[i] for i in range(3))
            b.length += L
        b.length -= 1.0
    else:
        u = b.pick([(0.0, 0.0, 1.0), (1.0, 0.0, 1.0), (1.0, 0.0, 0.0), (0.0, 1.0, -1.0)])
        mass = b.pick([2.0, 0.5])
        b.body("block", mass, (0.0, 0.0, 0.0), (0.1, 0.1, 0.1))
        b.add(f"m.add_translational('rail', m.ground, block, at=(0.0, 0.0, 0.0), axis={u!r})")
        b.rail_axis = u
        b.joints.append(("rail", "slide", 0.0, "m.ground", "block"))
        if d(st.booleans()):
            b.body("bob", 1.0, (0.5, 0.0, 0.0), (0.01, 0.1, 0.1))
            b.add("m.add_revolute('hinge', block, bob, at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0))")
            b.joints.append(("hinge", "angle", 0.0, "block", "bob"))


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


# --- stops, dampers, drivers, torques ------------------------------------------

def _limits(b, s0, coordinate, second):
    """(lower, upper) about the start s0: a range around it, a lone limit, or
    the start on a limit (gravity may press on it, or the motion carry into it).
    A joint's second stop does not start on a limit (the first may)."""
    d = b.draw
    scale = 1.0 if coordinate == "angle" else 0.5 * b.length
    spread = lambda: _r(scale * d(st.integers(1, 30)) / 20.0)  # noqa: E731
    shapes = ["both", "lower", "upper", "at lower", "at upper", "both at lower", "both at upper"]
    if second:
        shapes = [x for x in shapes if "at" not in x]
    shape = b.pick(shapes)
    lower = upper = None
    if shape in ("both", "lower", "both at upper"):
        lower = _r(s0 - spread())
    if shape in ("both", "upper", "both at lower"):
        upper = _r(s0 + spread())
    if shape.endswith("at lower"):
        lower = s0
    if shape.endswith("at upper"):
        upper = s0
    return lower, upper


def _stops(b):
    d = b.draw
    n_joints = d(st.integers(1, len(b.joints)))
    stopped = d(st.permutations(range(len(b.joints))))[:n_joints]
    if b.twins:  # both, and alike
        stopped = [0, 1]
    drawn = []  # (kw) of the first stopped joint's stops: the twin's are the same
    for n, k in enumerate(stopped):
        joint, coordinate, s0 = b.joints[k][:3]
        count = d(st.integers(1, 2)) if not (b.twins and n) else len(drawn)
        for second in range(count):
            if b.twins and n:
                kw = drawn[second]
            else:
                lower, upper = _limits(b, s0, coordinate, second)
                e = _r(d(st.integers(0, 19)) * 0.05)
                kw = {"lower": lower, "upper": upper, "restitution": e}
                extra = b.pick([None, None, None, "rest_speed", "capture_time"])
                if extra == "rest_speed":
                    kw["rest_speed"] = b.pick([0.01, 0.1])
                elif extra == "capture_time":
                    kw["capture_time"] = b.pick([1e-4, 1e-8])
                drawn.append(kw)
            name = f"stop{len(b.stops)}"
            args = ", ".join(f"{key}={v!r}" for key, v in kw.items() if v is not None)
            b.add(f"m.add_stop({name!r}, {joint!r}, {args})")
            b.stops.append({"name": name, "joint": joint, "coordinate": coordinate, "lower": kw["lower"],
                            "upper": kw["upper"], "restitution": kw["restitution"]})
    return [b.joints[k] for k in stopped]


def _extras(b, stopped):
    """Dampers on stopped joints; a driver on a joint without stops; torques."""
    d = b.draw
    if d(st.integers(0, 3)) == 3:  # a spring-damper on a stopped joint (its spring stays within its limits' span)
        joint, coordinate, s0, bi, bj = stopped[0]
        k, c = b.pick([0.0, 5.0]), b.pick([0.5, 2.0])
        if coordinate == "angle":
            target = repr(joint) if b.dim == 3 else f"{bi}, {bj}"
            b.add(f"m.add_rotational_spring_damper('damper', {target}, stiffness={k!r}, damping={c!r})")
        else:
            n = math.sqrt(sum(x * x for x in b.rail_axis))
            back = _v(*(-x / n for x in b.rail_axis))  # 1 m behind the block along its rail
            centre = (0.0,) * b.dim
            b.add(f"m.add_spring_damper('damper', m.ground, {back!r}, block, {centre!r}, stiffness={k!r}, "
                  f"damping={c!r})")
        b.damped = (joint, coordinate, c)
    free = [j for j in b.joints if j not in stopped]
    if free and not b.rigid and d(st.integers(0, 3)) == 3:  # a driver on a joint without stops
        joint, coordinate, s0 = free[0][:3]
        f = b.pick(["harmonic", "input"])
        if f == "harmonic":
            amp, omega = b.pick([0.3, 1.0]), b.pick([2.0, 5.0])
            b.add(f"m.drive_joint('driver', {joint!r}, mb.Harmonic({amp!r}, {omega!r}, offset={s0!r}))")
        else:
            b.add(f"m.drive_joint('driver', {joint!r}, mb.Input({s0!r}))")
            b.inputs.append(("driver", s0, 0.3 if coordinate == "angle" else 0.1))
        b.driven.add(joint)
        b.work = True
    if d(st.integers(0, 2)) == 2:  # a torque (or a force along a rail's body) from a time function or an input
        body = b.pick(b.bodies)
        size = b.pick([1.0, 5.0, 20.0])
        f = b.pick(["constant", "ramp", "input", "harmonic"])
        value = {"constant": repr(size), "harmonic": f"mb.Harmonic({size!r}, 4.0)",
                 "ramp": f"mb.SmoothStep(0.2, 0.6, 0.0, {size!r})", "input": "mb.Input(0.0, name='u')"}[f]
        if f == "input":
            b.inputs.append(("u", 0.0, size))
        vector = value if b.dim == 2 else f"(0.0, {value}, 0.0)"
        b.add(f"m.add_torque('torque', {body}, {vector})")
        b.work = True


def _run(b, formulation, options):
    """The run: simulate, or a Simulator whose inputs jump (with inputs always)."""
    d = b.draw
    options = dict(options)
    b.rtol = options.pop("rtol", RTOL)
    kw = f"rtol={b.rtol!r}, atol={ATOL!r}, formulation={formulation!r}" + \
        "".join(f", {k}={v!r}" for k, v in options.items())
    t_end = b.pick([1.5, 0.8, 3.0])
    if not b.inputs and d(st.integers(0, 3)) < 3:
        n_out = b.pick([151, 61, 301])
        return f"r = mb.simulate(m, t_end={t_end!r}, n_out={n_out}, {kw})", "simulate"
    lines = [f"sim = mb.Simulator(m, {kw}, output_interval=0.01)"]
    coin = random.Random(d(st.integers(0, 1000)))
    t = 0.0
    for _ in range(d(st.integers(1, 5))):
        t = _r(t + t_end / 5.0 * coin.choice([0.5, 1.0, 1.5]))
        lines.append(f"sim.advance({t!r})")
        for name, value, jump in b.inputs:
            lines.append(f"sim.set_input({name!r}, {_r(value + jump * coin.choice([-1.0, 1.0, 2.0, -0.5]))!r})")
    lines.append(f"sim.advance({_r(t + t_end / 5.0)!r})")
    lines.append("r = sim.result()")
    return "\n".join(lines), "Simulator.result"


def _meta(b):
    energy = "work" if b.work else ("damped" if b.damped else "conserved")
    scale = b.weight * max(b.length, 1.0) + b.kinetic + 1.0
    return {"stops": b.stops, "length": max(b.length, 1.0), "energy": energy, "energy_scale": _r(scale),
            "rtol": b.rtol,
            "damper": b.damped or None,
            "force": _r(b.weight * max(b.length, 1.0) + 20.0)}


def case_ops(code, run, run_kind, meta):
    """The worker's ops of a case: build, run (its result checked by the
    mechanism fuzzer's result check), and the laws of the stops."""
    return [{"code": code + "\n", "kind": "build", "check": None},
            {"code": run + "\n", "kind": run_kind, "check": "result:r"},
            {"code": f"import fuzz_stops\nfuzz_stops.check(r, {meta!r})\n", "kind": "stop laws", "check": None}]


if st is not None:
    @st.composite
    def stop_cases(draw, known_bugs=False):
        """A case {"ops", "meta"}: a random mechanism with stops and a run of
        it (known_bugs: with the features of KNOWN_BUGS too)."""
        dim = draw(st.sampled_from([2, 3]))
        b = Builder(draw, dim, known_bugs)
        (_planar if dim == 2 else _spatial)(b)
        stopped = _stops(b)
        _extras(b, stopped)
        formulation, options = draw(st.sampled_from(FORMULATIONS))
        run, run_kind = _run(b, formulation, options)
        meta = _meta(b)
        return {"ops": case_ops("\n".join(b.lines), run, run_kind, meta), "meta": meta}
