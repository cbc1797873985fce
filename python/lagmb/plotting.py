"""Pictures of a run: time histories (plot_result) and a GIF of the mechanism
(animate); a GIF of a vibration mode of mb.modes (animate_mode).

matplotlib is an optional extra (``pip install 'lagmb[plot]'``); it is imported
only when a function here is called, so ``import lagmb`` never needs it.
Figures are drawn on matplotlib's Agg canvas without pyplot: nothing here
changes the backend or the figure registry of the caller's session.

    from lagmb.plotting import plot_result, animate
    plot_result(r, "run.png")
    animate(r, "run.gif", trace=[("coupler", (0.0, 0.5))])

What the pictures show of the model comes from ``model.elements()`` (the
add_* and drive_* calls with their arguments, counted by the role the
registry of element kinds gives each) and, from the compiled model the run
used, the local points where elements attach to the bodies (the core's
outline and attachments).
"""

import math
import os
import re

import numpy as np

from ._checks import decimal, real, show, vec2
from .errors import ModelError
from .handles import Handle, name_of
from .registry import BY_METHOD, ROLE_WORDS, ROLES, SPATIAL_BY_METHOD

_HINT = "lagmb plotting needs matplotlib: pip install 'lagmb[plot]'"

_MAX_LINES = 8    # lines (legend entries) per subplot
_MAX_BODIES = 6   # bodies in the coordinate plots (their legend adds the x / y keys)
_PANELS = ("coordinates", "reactions", "efforts", "energy", "residual")


def _matplotlib():
    """The matplotlib pieces used here, or an ImportError with the install hint."""
    try:
        import matplotlib  # noqa: F401
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError as e:
        raise ImportError(_HINT) from e
    return Figure, FigureCanvasAgg


def _figure(figsize, **kwargs):
    """A Figure on an Agg canvas, outside pyplot (closing it is dropping it)."""
    Figure, FigureCanvasAgg = _matplotlib()
    fig = Figure(figsize=figsize, **kwargs)
    FigureCanvasAgg(fig)
    return fig


def _save(fig, path, **kwargs):
    path = os.fspath(path)
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    fig.savefig(path, **kwargs)


# --- what the model holds ------------------------------------------------


class _Scene:
    """What the model says about a result, for drawing it: the bodies, the
    elements by role (lagmb.registry), and where each element attaches to
    its bodies (as points in each body's own axes)."""

    def __init__(self, result):
        self.result = result
        model, core = result.model, result._core  # core: the compiled model the run used
        self.dimension = getattr(model, "dimension", 2)
        kinds = BY_METHOD if self.dimension == 2 else SPATIAL_BY_METHOD
        # what the run simulated: the model may have grown since
        self.elements = [(method, kw) for method, kw in model.elements() if core.has(kw["name"])]
        bodies = [b for b in model.bodies if core.has(b.name)]
        self.bodies = [b.name for b in bodies]
        self.kind_of = {kw["name"]: method for method, kw in self.elements}
        self.particles = {b.name for b in bodies if b.kind == "particle"}
        self.by_role = {role: [kw["name"] for method, kw in self.elements if kinds[method].role == role]
                        for role in ROLES}
        self.joints, self.drivers = self.by_role["joint"], self.by_role["driver"]
        names = ["ground"] + self.bodies  # by core body index + 1
        self._attachments = {
            kw["name"]: [(names[b + 1], np.array(point, dtype=float)) for b, *point in core.attachments(kw["name"])]
            for method, kw in self.elements if kinds[method].role != "body"}
        self.outlines = {b.name: [np.asarray(p, dtype=float) for p in core.outline(b.index)] for b in bodies}
        # mass and inertia about the centre of mass (body axes) as given to add_body
        self.mass = {kw["name"]: float(kw.get("mass") or 0.0) for method, kw in self.elements
                     if kinds[method].role == "body"}
        self.inertia = {kw["name"]: _inertia_tensor(kw.get("inertia"), self.dimension)
                        for method, kw in self.elements if kinds[method].role == "body"}

    def attachments(self, name):
        """[(body, local point)] where one element attaches."""
        return self._attachments.get(name, [])

    def path(self, body, local, index=slice(None), result=None):
        """(k, 2) global path of a body's local point (fixed for the ground);
        (k, 3) in space. Of this scene's result, or of ``result`` (the frames)."""
        result = self.result if result is None else result
        if body == "ground":
            return np.broadcast_to(np.asarray(local, dtype=float), (len(result.t), self.dimension))[index]
        return result.point(body, local)[index]

    def second_moment(self, body):
        """The body's second moment of mass about its centre, S = sum m x x^T
        in its own axes: (2, 2) or (3, 3), from the inertia given to add_body
        (S = tr(J)/2 - J in space; in the plane only I = S_xx + S_yy is
        known, and S is taken as I along every direction: the body as a rod)."""
        mass, J = self.mass.get(body, 0.0), self.inertia.get(body)
        if J is None or not mass > 0.0:
            return None
        if self.dimension == 2:
            return J * np.eye(2)
        return 0.5 * np.trace(J) * np.eye(3) - J

    def half_length(self, body, direction):
        """Half the length of the uniform rod along ``direction`` (body axes)
        that has the body's mass and second moment along it: sqrt(3 S_uu / m)
        (a rod of length L has S_uu = m L^2 / 12). 0 for a particle."""
        S = self.second_moment(body)
        if S is None:
            return 0.0
        u = np.asarray(direction, dtype=float)
        u = u / np.linalg.norm(u)
        return math.sqrt(3.0 * max(float(u @ S @ u), 0.0) / self.mass[body])

    def drawn_outline(self, body):
        """The local points a body is drawn through: where its elements attach
        (its outline). A body attached at one point only, off its centre of
        mass (a pendulum's rod pinned at one end), is drawn whole: as the
        uniform rod through that point and the centre with the body's mass
        and inertia (half_length); a rod of length L pinned at its end
        reaches L/2 beyond the centre. A point mass (no inertia) keeps the
        line from the point to its centre."""
        points = list(self.outlines.get(body, []))
        distinct = {tuple(np.round(p, 12)) for p in points}
        if len(distinct) != 1 or np.linalg.norm(points[0]) <= 1e-12:
            return points  # two or more points, or pinned at its centre (a cam, a wheel)
        p = points[0]
        d = float(np.linalg.norm(p))
        u = p / d
        h = self.half_length(body, u)
        if h <= 1e-9 * d:
            return points
        return [p] + ([h * u] if h > d * (1.0 + 1e-9) else []) + [-h * u]

    def box(self, body):
        """(8, 3) corners, in body axes, of the uniform box with the body's
        mass and second moment (its principal axes, half extents sqrt(3 s_i /
        m)): what shows a spatial body's orientation; None for a particle or
        a body without inertia."""
        S = self.second_moment(body)
        if S is None or self.dimension != 3:
            return None
        s, V = np.linalg.eigh(0.5 * (S + S.T))
        half = np.sqrt(3.0 * np.clip(s, 0.0, None) / self.mass[body])
        if not half.max() > 0.0:
            return None
        signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float)
        return (signs * half) @ V.T

    def summary(self):
        """"2 bodies, 1 joint, 1 stop": each role that has elements."""
        return ", ".join(_count(len(names), *ROLE_WORDS[role]) for role, names in self.by_role.items()
                         if names or role == "body")

    def effort_unit(self, name):
        kind = self.kind_of.get(name)
        kw = next((k for c, k in self.elements if k.get("name") == name), {})
        if kind == "drive_body":
            return "N m" if kw.get("coordinate") == "angle" else "N"
        if kind == "drive_joint":
            return "N" if self.kind_of.get(kw.get("joint")) in ("add_translational", "add_cylindrical") else "N m"
        return "N or N m"


def _inertia_tensor(inertia, dimension):
    """add_body's inertia as given: a number in the plane; (Ixx, Iyy, Izz)
    or a 3 x 3 tensor in space (None for a particle)."""
    if inertia is None:
        return None
    J = np.asarray(inertia, dtype=float)
    if dimension == 2:
        return float(J.reshape(-1)[0]) if J.size else None
    return np.diag(J) if J.shape == (3,) else J.reshape(3, 3)


def _count(n, one, many=None):
    return f"{n} {one if n == 1 else (many or one + 's')}"


def _stats_line(stats):
    if not stats:
        return ""
    wall = stats.get("wall_time")
    parts = []
    if stats.get("formulation"):
        parts.append(f"{stats['formulation']}/{stats.get('integrator', '?')}")
    if "steps" in stats:
        parts.append(f"{stats['steps']} steps")
    if wall is not None:
        parts.append(f"{wall * 1e3:.1f} ms wall" if wall < 1.0 else f"{wall:.2f} s wall")
    return ", ".join(parts)


def _colour(i):
    return f"C{i % 10}"


# --- time histories ------------------------------------------------------


def plot_result(result, path=None, *, what=_PANELS, dpi=120):
    """Time histories of a run, one subplot under the other on a shared time axis.

    ``what`` picks among "coordinates" (centre-of-mass x, y (z) in m, and the
    angles in rad, on two subplots; in space the angle each body has turned
    from its initial orientation), "reactions" (magnitude of each joint's
    reaction force, N), "efforts" (the drivers' forces or torques),
    "energy" (change E - E(0) in J, with E(0) given) and "residual"
    (max ``|Phi|`` on a log scale). Subplots with nothing to show are left out.
    Up to 6 bodies and 8 joints or drivers are drawn; the legend says when
    there are more.

    Returns the matplotlib Figure (drawn on the Agg canvas, outside pyplot).
    With ``path``, the figure is also written there, its format from the
    extension (.png, .pdf, .svg, ...).
    """
    if isinstance(what, str):
        what = (what,)
    if getattr(result, "stats", {}).get("analysis") == "kinematic":  # no multipliers computed
        what = tuple(w for w in what if w not in ("reactions", "efforts"))
    unknown = [w for w in what if w not in _PANELS]
    if unknown:
        raise ValueError(f"plot_result: unknown panel(s) {unknown}; choose from {list(_PANELS)}")
    _matplotlib()
    scene = _Scene(result)
    t = np.asarray(result.t)

    panels = []  # functions that draw one subplot each
    if "coordinates" in what and scene.bodies:
        panels.append(lambda ax: _positions(ax, result, scene))
        if any(b not in scene.particles for b in scene.bodies):
            panels.append(lambda ax: _angles(ax, result, scene))
    if "reactions" in what:
        reactions = _series(scene.joints, lambda n: np.hypot(*result.reaction(n)[:, :2].T) if scene.dimension == 2
                            else np.linalg.norm(result.reaction(n)[:, :3], axis=1))
        if reactions:
            panels.append(lambda ax: _lines(ax, t, reactions, len(scene.joints), "joints",
                                            "reaction |F| (N)"))
    if "efforts" in what and scene.drivers:
        efforts = _series(scene.drivers, lambda n: _effort(result, n))
        if efforts:
            units = {scene.effort_unit(n) for n in efforts}
            unit = units.pop() if len(units) == 1 else None
            labelled = {n if unit else f"{n} ({scene.effort_unit(n)})": y
                        for n, y in efforts.items()}
            panels.append(lambda ax: _lines(ax, t, labelled, len(scene.drivers), "drivers",
                                            f"effort ({unit or 'N, N m'})"))
    if "energy" in what:
        energy = _quiet(lambda: np.asarray(result.energy, dtype=float))
        if energy is not None and len(energy) and np.isfinite(energy).any():
            panels.append(lambda ax: _energy(ax, t, energy))
    if "residual" in what:
        residual = _quiet(lambda: np.asarray(result.residual, dtype=float))
        if residual is not None and len(residual):
            panels.append(lambda ax: _residual(ax, t, residual))
    if not panels:
        raise ValueError(f"plot_result: nothing to plot for what={tuple(what)}")

    fig = _figure((8.5, 1.2 + 2.0 * len(panels)), constrained_layout=True)
    if hasattr(fig, "get_layout_engine"):  # matplotlib >= 3.6: a little air at the edges
        fig.get_layout_engine().set(w_pad=0.1, h_pad=0.06)
    axes = fig.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    for ax, draw in zip(axes, panels):
        draw(ax)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("time t (s)")
    if len(t) > 1:
        axes[-1].set_xlim(t[0], t[-1])
    title = scene.summary()
    stats = _stats_line(getattr(result, "stats", None))
    fig.suptitle(f"lagmb: {title}" + (f"\n{stats}, {len(t)} outputs" if stats else ""),
                 fontsize=11)
    if path is not None:
        _save(fig, path, dpi=dpi)
    return fig


def _quiet(f):
    try:
        return f()
    except Exception:  # noqa: BLE001 - a quantity the model cannot give is left out
        return None


def _series(names, f):
    """{name: f(name)} for the names where f works (up to the line limit)."""
    out = {}
    for n in names:
        if len(out) == _MAX_LINES:
            break
        y = _quiet(lambda: np.asarray(f(n), dtype=float).reshape(-1))
        if y is not None:
            out[n] = y
    return out


def _effort(result, name):
    if hasattr(result, "effort"):
        return result.effort(name)
    return -result.multipliers(name)[:, 0]


def _legend(ax, title=None, handles=None, ncol=1):
    kwargs = {"handles": handles} if handles is not None else {}
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, fontsize=8,
              title=title, title_fontsize=8, frameon=False, ncol=ncol, **kwargs)


def _shown(names, total, what):
    """Legend title saying that only some are drawn."""
    return f"first {len(names)} of {total} {what}" if total > len(names) else None


def _positions(ax, result, scene):
    from matplotlib.lines import Line2D

    shown = scene.bodies[:_MAX_BODIES]
    handles = []
    styles = ("-", "--", ":")[:scene.dimension]
    for i, b in enumerate(shown):
        pos = result.body(b).position
        for axis, style in enumerate(styles):
            ax.plot(result.t, pos[:, axis], color=_colour(i), lw=1.4, ls=style)
        handles.append(Line2D([], [], color=_colour(i), lw=2, label=b))
    handles += [Line2D([], [], color="0.3", lw=1.4, ls=style, label="xyz"[axis])
                for axis, style in enumerate(styles)]
    ax.set_ylabel("centre of mass\n" + ", ".join("xyz"[:scene.dimension]) + " (m)")
    _legend(ax, _shown(shown, len(scene.bodies), "bodies"), handles)


def _angles(ax, result, scene):
    rigid = [(i, b) for i, b in enumerate(scene.bodies) if b not in scene.particles]
    shown = rigid[:_MAX_BODIES]
    for i, b in shown:
        ax.plot(result.t, _angle(result, b), color=_colour(i), lw=1.4, label=b)
    ax.set_ylabel("angle φ (rad)" if scene.dimension == 2 else "turned from the start\n(rad)")
    _legend(ax, _shown(shown, len(rigid), "bodies"))


def _angle(result, body):
    """A planar body's angle; a spatial body's angle of turn from its
    initial orientation (that of the relative rotation p0* p, in [0, pi])."""
    b = result.body(body)
    if not hasattr(b, "orientation"):
        return b.angle
    p = b.orientation
    cos_half = np.abs(p @ p[0])  # the w of p0* p
    return 2.0 * np.arccos(np.clip(cos_half, 0.0, 1.0))


def _lines(ax, t, series, total, what, ylabel):
    for i, (name, y) in enumerate(series.items()):
        ax.plot(t, y, color=_colour(i), lw=1.4, label=name)
    ax.set_ylabel(ylabel)
    _legend(ax, _shown(list(series), total, what))


def _energy(ax, t, energy):
    e0 = energy[0] if np.isfinite(energy[0]) else energy[np.isfinite(energy)][0]
    ax.plot(t, energy - e0, color="C3", lw=1.4, label=f"E(0) = {e0:.6g} J")
    ax.set_ylabel("energy change\nE − E(0) (J)")
    ax.ticklabel_format(axis="y", style="sci", scilimits=(-3, 4), useOffset=False)
    _legend(ax)


def _residual(ax, t, residual):
    positive = residual > 0
    ax.set_ylabel("constraint residual\nmax |Φ| (m)")
    if not positive.any():
        ax.plot(t, residual, color="C7", lw=1.4)
        ax.text(0.5, 0.5, "|Φ| = 0 at every output", transform=ax.transAxes,
                ha="center", va="center", fontsize=9)
        return
    ax.semilogy(t, np.where(positive, residual, np.nan), color="C7", lw=1.2)


# --- animation -----------------------------------------------------------


def _hull(points):
    """Convex hull of 2-D points, counter-clockwise (Andrew's monotone chain)."""
    pts = sorted({(round(p[0], 12), round(p[1], 12)) for p in points})
    if len(pts) <= 2:
        return np.array(pts)

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1])


def _shape(outline):
    """(local points to draw, closed?) for a body's outline: nothing (a dot at
    the centre of mass), a segment from the centre to the one point, a
    segment, or the convex polygon around three or more points."""
    if all(np.hypot(*p) <= 1e-12 for p in outline):  # only the centre: no extent
        return np.zeros((0, 2)), False
    if len(outline) == 1:
        return np.array([np.zeros(2), outline[0]]), False
    if len(outline) == 2:
        return np.array(outline), False
    hull = _hull(outline)
    if len(hull) >= 3:
        area = 0.5 * abs(np.sum(hull[:, 0] * np.roll(hull[:, 1], -1)
                                - np.roll(hull[:, 0], -1) * hull[:, 1]))
        span = np.ptp(hull, axis=0).max()
        if area > 1e-6 * span**2:
            return hull, True
    # collinear: the segment between the two points furthest apart
    pts = np.array(outline)
    d = np.linalg.norm(pts[:, None, :] - pts[None, :, :], axis=2)
    a, b = np.unravel_index(np.argmax(d), d.shape)
    return pts[[a, b]], False


def _zigzag(p, q, width, coils=6):
    """Points of a spring drawn from p to q."""
    d = q - p
    length = np.hypot(*d)
    if length < 1e-12:
        return np.array([p, q])
    u = d / length
    n = np.array([-u[1], u[0]])
    s = np.concatenate(([0.0, 0.15], 0.15 + 0.7 * (np.arange(2 * coils) + 0.5) / (2 * coils),
                        [0.85, 1.0]))
    offset = np.zeros_like(s)
    offset[2:-2] = width * np.where(np.arange(2 * coils) % 2, -1.0, 1.0)
    return p + np.outer(s * length, u) + np.outer(offset, n)


_FPS = 25       # default frames per second: 40 ms a frame, four ticks of a GIF's 10 ms clock
_MAX_FPS = 50   # GIF viewers show a frame of 10 ms for 100 ms: 20 ms is the shortest kept
_MAX_FRAMES = 1000  # unless asked: Pillow holds every frame until the GIF is written (0.3 MB at 640 x 480)


def _frame_plan(t, fps, speed, frames=None):
    """(times (n,), durations in ms (n,)) of the frames of a run with output
    times t: n frames spread evenly from the first output on, frame i showing
    t0 + i * span / n, so that the GIF plays the span in span / speed s.
    n is span * fps / speed, rounded (at most ``frames``; at least 1). A GIF
    counts frame durations in whole hundredths of a second: the ends of the
    frames are rounded to them, so that every frame lasts the same where
    100 / frame rate is whole (fps 10, 20, 25, 50) and otherwise one tick
    more or less (30 or 40 ms at 30 frames/s), the whole always right to
    10 ms."""
    t0, t1 = float(t[0]), float(t[-1])
    span = t1 - t0
    playing = span / speed
    n = int(round(span * fps / speed)) if span > 0 else 1
    n = min(n, int(math.floor(playing * _MAX_FPS + 1e-9)))  # no frame shorter than 20 ms
    if frames is not None:
        n = min(n, int(frames))
    n = max(n, 1)
    times = t0 + span * np.arange(n) / n
    if n == 1:  # one picture: its duration does not matter
        return times, np.array([max(10 * round(100.0 / fps), 20)])
    ends = np.round(100.0 * playing * np.arange(1, n + 1) / n)  # hundredths of a second
    return times, (10 * np.diff(np.concatenate(([0.0], ends)))).astype(int)


def _resample(result, times):
    """The result at the frame times, as a Result (q and v; a and lam zero):
    q by cubic Hermite interpolation between the outputs around each time
    (q and q' = v at both; exact at the outputs), linear where an event
    (impact) lies between them; each spatial body's Euler parameters
    normalised."""
    from .result import Result

    t = np.asarray(result.t, dtype=float)
    q, v = np.asarray(result.q, dtype=float), np.asarray(result.v, dtype=float)
    times = np.asarray(times, dtype=float)
    if len(t) == len(times) and np.array_equal(t, times):
        return result
    if len(t) == 1:
        qf, vf = np.repeat(q, len(times), axis=0), np.repeat(v, len(times), axis=0)
    else:
        k = np.clip(np.searchsorted(t, times, side="right") - 1, 0, len(t) - 2)
        h = t[k + 1] - t[k]
        s = np.clip(np.divide(times - t[k], h, out=np.zeros_like(h), where=h > 0), 0.0, 1.0)[:, None]
        hh = h[:, None]
        h00, h10 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s
        h01, h11 = -2 * s**3 + 3 * s**2, s**3 - s**2
        qf = h00 * q[k] + h10 * hh * v[k] + h01 * q[k + 1] + h11 * hh * v[k + 1]
        linear = (1 - s) * q[k] + s * q[k + 1]
        jumps = np.zeros(len(t), dtype=bool)  # intervals (t_j, t_j+1] with an event
        for e in getattr(result, "events", []):
            j = int(np.searchsorted(t, float(e.get("t", np.nan)), side="left")) - 1
            if 0 <= j < len(t) - 1:
                jumps[j] = True
        rough = jumps[k] | ~np.isfinite(qf).all(axis=1)
        qf[rough] = linear[rough]
        vf = (1 - s) * v[k] + s * v[k + 1]
    core = result._core
    _unit_orientations(result.model, core, qf)
    lam = getattr(result, "_lam", np.zeros((len(t), 0)))
    raw = {"t": times, "q": qf, "v": vf, "a": np.zeros_like(qf), "lam": np.zeros((len(times), lam.shape[1])),
           "stats": result.stats}
    return Result(result.model, core, raw)


def _unit_orientations(model, core, q):
    """Normalises, in place, each spatial body's Euler parameters in the rows of q (k, n)."""
    for body in model.bodies:
        if not core.has(body.name):
            continue
        first, count = core.body_coordinates(body.name)
        if count == 7:
            p = q[:, first + 3:first + 7]
            q[:, first + 3:first + 7] = p / np.linalg.norm(p, axis=1, keepdims=True)


def _time_format(times):
    dt = np.diff(times)
    dt = dt[dt > 0]
    digits = 2 if not len(dt) else int(np.clip(math.ceil(-math.log10(dt.min())) + 1, 2, 9))
    return f"t = {{:.{digits}f}} s"


def _speed_words(speed):
    """What the title says of the speed: nothing in real time."""
    if speed == 1.0:
        return ""
    return f", played at {speed:.3g} × real time"


def _checked(name, value, low, high=None, whole=False):
    """An animation setting: a number (whole if asked) above low and at most
    high, else a ModelError naming it and the value as given ("animate: fps
    0: must be ..."; from the command line "--fps 0: ...")."""
    words = f"a whole number, at least {low + 1}" if whole else f"a number above {low:g}"
    if high is not None:
        words += f" and at most {high:g}"
    try:
        # a string as the command line gives it, read as TOML writes numbers ("1_0" is no 10)
        number = decimal(value, name) if isinstance(value, str) else float(value)
        good = not isinstance(value, bool) and math.isfinite(number) and number > low \
            and (high is None or number <= high) and (not whole or number == int(number))
    except (TypeError, ValueError, OverflowError, ModelError):
        good = False
    if not good:
        reason = " (GIF viewers show a frame shorter than 20 ms for 100 ms)" if high == _MAX_FPS else ""
        shown = value if name.startswith("--") else repr(value)
        raise ModelError(f"{name} {shown}: must be {words}{reason}")
    return int(number) if whole else number


def trace_points(model, trace, context="animate: trace"):
    """The traced points as [(body name, local point)] from what ``animate``
    and ``lagmb run --trace`` take: a body (handle or name: its centre of
    mass), an element (a joint, force, spring: by handle or name; the point
    where it attaches to its moving body, the last it names), a pair
    (body, local point), or "body:x,y" ("body:x,y,z" in space); one of them
    or a list. A ModelError names what cannot be traced, after ``context``."""
    size = getattr(model, "dimension", 2)

    def said(item):
        return str(item) if context.startswith("--") else repr(item)

    if trace is None:
        return []
    if isinstance(trace, (str, Handle)) or (isinstance(trace, (tuple, list)) and len(trace) == 2
                                             and isinstance(trace[0], (str, Handle)) and np.ndim(trace[1]) == 1):
        trace = [trace]  # one of them
    try:
        trace = list(trace)
    except TypeError:
        raise ModelError(f"{context}: expected a body, an element, (body, point), "
                         f"'body:{'x,y' if size == 2 else 'x,y,z'}' or a list of them, got {show(trace)}") from None
    bodies = [b.name for b in model.bodies]

    def body_named(body, item):
        body = name_of(model, body, ("body",), "body", context)
        if body not in bodies:
            raise ModelError(f"{context} {said(item)}: no body named {body!r}; the bodies are " + ", ".join(bodies))
        return body

    out = []
    for item in trace:
        if isinstance(item, (tuple, list)) and len(item) == 2:
            body, point = body_named(item[0], item), item[1]
        elif isinstance(item, str) and ":" in item:
            body, text = item.split(":", 1)
            point = [decimal(x, f"{context} {said(item)}") for x in text.split(",")]
            if len(point) != size:
                raise ModelError(f"{context} {said(item)}: a point on a body is body:{'x,y' if size == 2 else 'x,y,z'} "
                                 "(m, in the body's own axes)")
            body = body_named(body, item)
        elif isinstance(item, Handle) and item.role == "body":
            out.append((body_named(item, item), np.zeros(size)))
            continue
        elif isinstance(item, (str, Handle)):
            if item in bodies:
                out.append((item, np.zeros(size)))
                continue
            try:
                attached = model.attachments(item)
            except ModelError:
                raise ModelError(f"{context} {said(item)}: no body or element of that name; the bodies are "
                                 + ", ".join(bodies)) from None
            moving = [(b, p) for b, p in attached if b != "ground"]
            if not moving:
                raise ModelError(f"{context} {said(item)}: it attaches to no moving body")
            out.append((moving[-1][0], np.asarray(moving[-1][1], dtype=float)))
            continue
        else:
            raise ModelError(f"{context}: expected a body, an element, (body, point) or 'body:x,y', got {item!r}")
        try:
            point = np.asarray(point, dtype=float).reshape(size)
        except (TypeError, ValueError):
            raise ModelError(f"{context} point {point!r}: must be {size} numbers") from None
        if not np.all(np.isfinite(point)):
            raise ModelError(f"{context} point {tuple(point.tolist())}: must be finite")
        out.append((body, point))
    return out


def animate(result, path, *, fps=None, speed=None, frames=None, trace=None, size=(640, 480), dpi=100,
            view=(25.0, -60.0), progress=True, max_frames=None):
    """Write a GIF of the mechanism moving, in real time by default.

    Timing: the GIF plays the run's span in span / ``speed`` seconds (speed
    1: a 1 s run lasts 1 s; 0.1: ten times slower) at ``fps`` frames per
    second (default 25, at most 50). The default speed is 1, real time,
    except for a run shorter than 1 s, which is slowed down to last 1 s (an
    impact of 30 ms would be one frame); the title says the speed whenever
    it is not 1. A GIF counts a frame's duration in whole hundredths of a
    second: at 10, 20, 25 or 50 frames/s every frame lasts the same (100,
    50, 40, 20 ms); at another rate frames last one tick more or less (30
    or 40 ms at 30 frames/s) so that the whole still lasts span / speed, to
    10 ms. ``frames`` caps the number of frames (default 1000, 40 s at 25
    frames/s: Pillow holds them all until the GIF is written); the frames
    then last longer and the GIF keeps its duration. With n frames, frame i
    shows the mechanism at t0 + i * span / n; states between outputs are
    interpolated (cubic, from the positions and velocities), so frames need
    not fall on output times. ``max_frames`` is the old name of ``frames``.

    ``progress``: a line (or tqdm bar) on a terminal's stderr while the
    frames are drawn, after the first second (lagmb.progress.Progress).

    The drawing: each body is drawn through the points where its joints and
    forces attach (``model.outline(body)``): a line for two points, a
    shaded convex polygon for three or more, a disc for none (a square
    block if it slides in a translational joint). A body attached at one
    point only, off its centre (a pendulum's rod), is drawn whole: as the
    uniform rod with its mass and inertia, from that point through the
    centre of mass (a rod pinned at its end reaches as far beyond the
    centre); a point mass from the point to its centre. A dot marks each
    centre of mass, white circles the revolute joints, triangles the joints
    to the ground, zig-zags the spring-dampers, dashed lines the slide axes
    fixed to the ground. The axes are fixed to cover the whole motion, with
    equal scales, in m.

    A spatial model (dimension 3) is drawn in perspective by matplotlib's
    mplot3d, seen from ``view`` = (elevation, azimuth) in degrees: each
    body as lines from its centre of mass to its attachment points, the
    edges of its inertia box (the uniform box with its mass and inertia)
    and its axes (x red, y green, z blue, reaching a fifth past the box),
    which turn with it, so that spin and orientation show.

    ``trace``: points whose paths are drawn as they are travelled (faint
    ahead): a body (its centre of mass), an element (a joint: where it is),
    a (body, local point) pair or "body:x,y" (see trace_points); one or a
    list. A traced (body, point) also joins its body's shape. ``size`` is
    the picture in pixels. Returns the path written.
    """
    _matplotlib()
    try:
        from PIL import Image  # noqa: F401 - there before anything is drawn
    except ImportError as e:
        raise ImportError(_HINT) from e
    if max_frames is not None:
        if frames is not None:
            raise ModelError("animate: give frames or its old name max_frames, not both")
        frames = max_frames
    fps = _FPS if fps is None else _checked("animate: fps", fps, 0.0, _MAX_FPS)
    if speed is not None:
        speed = _checked("animate: speed", speed, 0.0)
    frames = _MAX_FRAMES if frames is None else _checked("animate: frames", frames, 0, whole=True)
    t = np.asarray(result.t)
    if len(t) == 0:
        raise ModelError("animate: the result has no outputs")
    if speed is None:  # real time, or 1 s for a shorter run
        span = float(t[-1] - t[0])
        speed = span if 0.0 < span < 1.0 else 1.0
    scene = _Scene(result)
    trace = trace_points(result.model, trace)
    times, durations = _frame_plan(t, fps, speed, frames)
    shown = _resample(result, times)
    if scene.dimension == 3:
        drawing = _spatial_drawing(scene, shown, trace, size, dpi, view, speed)
    else:
        drawing = _planar_drawing(scene, shown, trace, size, dpi, speed)
    from .progress import Progress

    with Progress(times[0], t[-1], enabled=bool(progress), label="drawn") as bar:
        return _write_gif(drawing, path, durations, lambda k: bar(times[k]))


class _Drawing:
    """A figure of a run's frames: ``update(k)`` sets the ``animated``
    artists to frame k; everything else is drawn once. ``artists`` names
    the animated ones (for tests)."""

    def __init__(self, fig, artists, update):
        self.fig, self.artists, self.update = fig, artists, update
        self.animated = [a for v in artists.values() for a in (v if isinstance(v, list) else [v])]


def _write_gif(drawing, path, durations, progress=None):
    """Draws each frame of drawing into a GIF at path, frame k lasting
    durations[k] ms; returns the path. The fixed part of the figure is drawn
    once and copied under each frame (blitting); the frame's pixels go from
    Agg's buffer to Pillow, on one palette for all frames (made from the
    first, middle and last frames)."""
    from PIL import Image

    path = os.fspath(path)
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig = drawing.fig
    canvas = fig.canvas
    for art in drawing.animated:
        art.set_animated(True)
    canvas.draw()
    background = canvas.copy_from_bbox(fig.bbox)

    def picture(k):
        canvas.restore_region(background)
        drawing.update(k)
        for art in drawing.animated:
            fig.draw_artist(art)
        width, height = canvas.get_width_height(physical=True)
        return Image.frombuffer("RGBA", (width, height), canvas.buffer_rgba(), "raw", "RGBA", 0, 1).convert("RGB")

    n = len(durations)
    samples = [picture(k) for k in sorted({0, n // 2, n - 1})]
    strip = Image.new("RGB", (samples[0].width, samples[0].height * len(samples)))
    for i, im in enumerate(samples):
        strip.paste(im, (0, i * im.height))
    palette = strip.quantize(colors=255, method=Image.Quantize.MEDIANCUT)
    pictures = []
    for k in range(n):
        pictures.append(picture(k).quantize(palette=palette, dither=Image.Dither.NONE))
        if progress is not None:
            progress(k)
    pictures[0].save(path, save_all=True, append_images=pictures[1:], duration=[int(d) for d in durations],
                     loop=0)
    return path


def _planar_drawing(scene, shown, trace, size, dpi, speed):
    """The planar drawing of the frames ``shown`` (a Result at the frame
    times) of scene's run (see animate)."""
    from matplotlib.patches import Polygon

    result = scene.result
    t = np.asarray(shown.t)
    # global paths of everything drawn, over all outputs (for the limits) and
    # at the frames; traced points belong to their bodies' shapes too (a
    # pendulum's free tip)
    outlines = {b: scene.drawn_outline(b) for b in scene.bodies}
    for b, p in trace:
        if b in outlines and all(np.hypot(*(p - u)) > 1e-12 for u in outlines[b]) and np.hypot(*p) > 1e-12:
            outlines[b].append(p)
    shapes = {b: _shape(outlines[b]) for b in scene.bodies}
    body_paths = {b: [scene.path(b, p, result=shown) for p in shapes[b][0]] for b in scene.bodies}
    centres = {b: shown.body(b).position for b in scene.bodies}
    traces = [scene.path(b, p) for b, p in trace]
    trace_frames = [scene.path(b, p, result=shown) for b, p in trace]
    reached = np.searchsorted(np.asarray(result.t), t, side="right")  # outputs up to each frame
    pins, supports, guides, links, sliders = [], [], [], [], set()
    for kind, kw in scene.elements:
        if kind == "add_translational":
            sliders.add(kw.get("body_j"))
        att = scene.attachments(kw["name"])
        if kind == "add_revolute" and att:
            moving = [(b, p) for b, p in att if b != "ground"]
            fixed = [p for b, p in att if b == "ground"]
            if moving:
                pins.append(scene.path(*moving[-1], result=shown))
            if fixed:
                supports.append(fixed[0])
        elif kind in ("add_translational", "add_pin_in_slot") and kw.get("axis") is not None:
            if kw.get("body_i") == "ground" and kw.get("at") is not None:
                guides.append((np.asarray(kw["at"], float), np.asarray(kw["axis"], float)))
            moving = [(b, p) for b, p in att if b != "ground"]
            if moving and kind == "add_pin_in_slot":
                pins.append(scene.path(*moving[-1], result=shown))
        elif kind in ("add_spring_damper", "add_distance") and len(att) == 2:
            links.append((kind, scene.path(*att[0], result=shown), scene.path(*att[1], result=shown)))
    everywhere = [scene.path(b, p) for b in scene.bodies for p in shapes[b][0]] \
        + [result.body(b).position for b in scene.bodies]
    clouds = everywhere + [c for paths in body_paths.values() for c in paths] + list(centres.values()) \
        + traces + pins + [p[None, :] for p in supports] \
        + [q for _, p, q in links] + [p for _, p, q in links]
    pts = np.concatenate([np.asarray(c).reshape(-1, 2) for c in clouds]) if clouds \
        else np.zeros((1, 2))
    pts = pts[np.isfinite(pts).all(axis=1)]
    lo, hi = (pts.min(axis=0), pts.max(axis=0)) if len(pts) else (np.zeros(2), np.zeros(2))
    span = max(float(np.max(hi - lo)), 1e-3)
    mark = 0.035 * span  # size of supports, springs
    lo, hi = lo - 0.08 * span - mark, hi + 0.08 * span
    lo[1] -= mark  # room for the triangles under the supports
    # widen the shorter side so that 1 m is as long across as up
    rect = (0.13, 0.11, 0.83, 0.79)
    box = np.array([rect[2] * size[0], rect[3] * size[1]])
    scale = max((hi - lo) / box)
    centre = 0.5 * (lo + hi)
    lo, hi = centre - 0.5 * scale * box, centre + 0.5 * scale * box

    fig = _figure((size[0] / dpi, size[1] / dpi), dpi=dpi)
    ax = fig.add_axes(rect)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.grid(alpha=0.25)
    ax.set_title(f"lagmb: {scene.summary()}{_speed_words(speed)}", fontsize=10)

    # fixed things: slide guides, supports, the paths ahead
    for at, axis in guides:
        u = axis / max(np.hypot(*axis), 1e-300)
        ax.plot(*np.array([at - 4 * span * u, at + 4 * span * u]).T, color="0.5", lw=1,
                ls=(0, (6, 3)), zorder=1)
    for p in supports:
        tri = np.array([p, p + (-0.6 * mark, -mark), p + (0.6 * mark, -mark)])
        ax.add_patch(Polygon(tri, closed=True, facecolor="0.75", edgecolor="0.2", lw=1,
                             zorder=2))
        ax.plot([p[0] - mark, p[0] + mark], [p[1] - mark] * 2, color="0.2", lw=1.5, zorder=2)
    trace_colours = [_colour(scene.bodies.index(b)) if b in scene.bodies else "k" for b, _ in trace]
    for c, path_ in zip(trace_colours, traces):
        ax.plot(*path_.T, color=c, lw=1, alpha=0.2, zorder=1)

    # moving things, updated per frame
    trace_done = [ax.plot([], [], color=c, lw=1.3, zorder=1)[0] for c in trace_colours]
    link_art = [ax.plot([], [], color="0.35", lw=1.0 if kind == "add_spring_damper" else 1.8,
                        zorder=2)[0] for kind, _, _ in links]
    body_art = []
    for i, b in enumerate(scene.bodies):
        local, closed = shapes[b]
        c = _colour(i)
        if closed:
            art = Polygon(np.zeros((len(local), 2)), closed=True, facecolor=c, alpha=0.35,
                          edgecolor=c, lw=2.5, zorder=3)
            ax.add_patch(art)
        elif len(local):
            art = ax.plot([], [], color=c, lw=4, solid_capstyle="round", zorder=3)[0]
        else:  # no extent: a block (on a slide) or a disc at the centre of mass
            marker = "s" if b in sliders else "o"
            art = ax.plot([], [], marker, color=c, ms=11, mec="0.2", zorder=3)[0]
        body_art.append(art)
    centre_art = ax.plot([], [], "o", ms=3.5, color="0.1", zorder=5)[0]
    pin_art = ax.plot([], [], "o", ms=5.5, mfc="white", mec="0.15", mew=1.2, zorder=4)[0]
    stamp = ax.text(0.02, 0.97, "", transform=ax.transAxes, ha="left", va="top", fontsize=9,
                    family="monospace", zorder=6,
                    bbox={"facecolor": "white", "edgecolor": "0.8", "alpha": 0.85})
    stamp_format = _time_format(t)

    def update(k):
        for b, art in zip(scene.bodies, body_art):
            if body_paths[b]:
                xy = np.array([p[k] for p in body_paths[b]])
            else:
                xy = centres[b][k][None, :]
            if hasattr(art, "set_xy"):
                art.set_xy(xy)
            else:
                art.set_data(xy[:, 0], xy[:, 1])
        if scene.bodies:
            c = np.array([centres[b][k] for b in scene.bodies if body_paths[b]]).reshape(-1, 2)
            centre_art.set_data(c[:, 0], c[:, 1])
        if pins:
            p = np.array([pin[k] for pin in pins])
            pin_art.set_data(p[:, 0], p[:, 1])
        for art, (kind, p, q) in zip(link_art, links):
            xy = _zigzag(p[k], q[k], 0.4 * mark) if kind == "add_spring_damper" \
                else np.array([p[k], q[k]])
            art.set_data(xy[:, 0], xy[:, 1])
        for art, path_, at in zip(trace_done, traces, trace_frames):
            xy = np.concatenate([path_[:reached[k]], at[k][None, :]])
            art.set_data(xy[:, 0], xy[:, 1])
        stamp.set_text(stamp_format.format(t[k]))

    # in the order of their zorder: each frame draws them one by one, in this order
    artists = {"traces": trace_done, "links": link_art, "bodies": body_art, "pins": pin_art,
               "centres": centre_art, "stamp": stamp}
    return _Drawing(fig, artists, update)


_TRIAD_COLOURS = ("#d62728", "#2ca02c", "#1f77b4")  # body axes x, y, z: red, green, blue
_POKE = 1.2  # a body's axes reach this far past its inertia box


def _box_edges(corners):
    """(36, 3) the 12 edges of a box with corners (8, 3) (index bits z y x)
    as one polyline, NaN between edges."""
    pairs = [(a, b) for a in range(8) for b in range(a + 1, 8) if bin(a ^ b).count("1") == 1]
    gap = np.full(3, np.nan)
    return np.array([p for a, b in pairs for p in (corners[a], corners[b], gap)])


def _spatial_drawing(scene, shown, trace, size, dpi, view, speed):
    """The spatial drawing of the frames ``shown``: each body as lines from
    its centre of mass to the points where elements attach to it (a rod
    pinned at one end drawn whole, as in the plane; a dot alone if none),
    the edges of its inertia box (the uniform box with its mass and
    inertia, Scene.box) and its axes (a triad: x red, y green, z blue,
    reaching a fifth past the box, at least a 25th of the scene) that turn
    with it, so that spin shows;
    white circles at the joints, triangles at joints to the ground, grey
    lines for spring-dampers and distance links, traced points' paths;
    equal scales on the three axes, in m, seen from view = (elevation,
    azimuth) in degrees."""
    result = scene.result
    t = np.asarray(shown.t)
    elevation, azimuth = (float(x) for x in view)
    outlines = {b: scene.drawn_outline(b) + [p for tb, p in trace if tb == b] for b in scene.bodies}
    centres = {b: shown.body(b).position for b in scene.bodies}
    spokes = {b: [scene.path(b, p, result=shown) for p in outlines[b]] for b in scene.bodies}
    rotations = {b: getattr(shown.body(b), "rotation", None) for b in scene.bodies}
    corners = {b: scene.box(b) for b in scene.bodies if rotations[b] is not None}
    corners = {b: c for b, c in corners.items() if c is not None}
    boxes = {b: _box_edges(c) for b, c in corners.items()}
    traces = [scene.path(b, p) for b, p in trace]
    trace_frames = [scene.path(b, p, result=shown) for b, p in trace]
    reached = np.searchsorted(np.asarray(result.t), t, side="right")
    joints, supports, links = [], [], []
    for kind, kw in scene.elements:
        att = scene.attachments(kw["name"])
        if kind in ("add_spring_damper", "add_distance") and len(att) == 2:
            links.append((scene.path(*att[0], result=shown), scene.path(*att[1], result=shown)))
        elif scene.kind_of.get(kw["name"]) and kw["name"] in scene.joints and att:
            moving = [(b, p) for b, p in att if b != "ground"]
            if moving:
                joints.append(scene.path(*moving[-1], result=shown))
            supports += [p for b, p in att if b == "ground"]
    # the limits: everything drawn, over all outputs and frames
    everywhere = [result.body(b).position for b in scene.bodies] \
        + [scene.path(b, p) for b in scene.bodies for p in outlines[b]]
    for b, c in corners.items():  # with the axes that poke out of the box
        everywhere.append((result.body(b).position[:, None, :]
                           + np.einsum("kij,nj->kni", result.body(b).rotation, _POKE * c)).reshape(-1, 3))
    clouds = everywhere + list(centres.values()) + [s for paths in spokes.values() for s in paths] + traces \
        + joints + [p for link in links for p in link] + [np.asarray(p)[None, :] for p in supports]
    pts = np.concatenate([np.asarray(c).reshape(-1, 3) for c in clouds]) if clouds else np.zeros((1, 3))
    pts = pts[np.isfinite(pts).all(axis=1)]
    centre = 0.5 * (pts.min(axis=0) + pts.max(axis=0)) if len(pts) else np.zeros(3)
    half = 0.55 * max(float(np.max(np.ptp(pts, axis=0))) if len(pts) else 0.0, 1e-3)
    # the body axes drawn: poking out of the box along them, at least a 25th of the scene
    turning = [b for b in scene.bodies if rotations[b] is not None]
    triad = {b: np.maximum(0.08 * half, _POKE * np.abs(corners[b]).max(axis=0) if b in corners else 0.0)
             for b in turning}

    fig = _figure((size[0] / dpi, size[1] / dpi), dpi=dpi)
    ax = fig.add_subplot(projection="3d")
    ax.view_init(elev=elevation, azim=azimuth)
    for axis, set_lim, label in zip(range(3), (ax.set_xlim, ax.set_ylim, ax.set_zlim), "xyz"):
        set_lim(centre[axis] - half, centre[axis] + half)
        getattr(ax, f"set_{label}label")(f"{label} (m)")
    if hasattr(ax, "set_box_aspect"):
        ax.set_box_aspect((1, 1, 1))
    ax.set_title(f"lagmb: {scene.summary()}{_speed_words(speed)}", fontsize=10)
    if supports:
        s = np.array(supports, dtype=float)
        ax.plot(s[:, 0], s[:, 1], s[:, 2], "^", ms=9, color="0.75", mec="0.2")
    trace_colours = [_colour(scene.bodies.index(b)) if b in scene.bodies else "k" for b, _ in trace]
    for c, path_ in zip(trace_colours, traces):
        ax.plot(*path_.T, color=c, lw=1, alpha=0.2)

    # per frame: the lines of every body's box, axes, spokes in one array each
    box_frames = {b: centres[b][:, None, :] + np.einsum("kij,nj->kni", rotations[b], edges)
                  for b, edges in boxes.items()}
    gap = np.full((len(t), 1, 3), np.nan)
    triad_frames = []
    for axis in range(3):
        parts = []
        for b in turning:
            c = centres[b][:, None, :]
            parts += [c, c + triad[b][axis] * rotations[b][:, None, :, axis], gap]
        triad_frames.append(np.concatenate(parts, axis=1) if parts else np.zeros((len(t), 0, 3)))

    trace_done = [ax.plot([], [], [], color=c, lw=1.3)[0] for c in trace_colours]
    link_art = [ax.plot([], [], [], color="0.35", lw=1.2)[0] for _ in links]
    box_art = {b: ax.plot([], [], [], color=_colour(scene.bodies.index(b)), lw=1.0, alpha=0.8)[0]
               for b in boxes}
    body_art = [ax.plot([], [], [], color=_colour(i), lw=4, solid_capstyle="round")[0]
                for i, _ in enumerate(scene.bodies)]
    triad_art = [ax.plot([], [], [], color=c, lw=1.6)[0] for c in _TRIAD_COLOURS] if turning else []
    centre_art = ax.plot([], [], [], "o", ms=3.5, color="0.1")[0]
    joint_art = ax.plot([], [], [], "o", ms=5.5, mfc="white", mec="0.15", mew=1.2)[0]
    stamp = ax.text2D(0.02, 0.97, "", transform=ax.transAxes, ha="left", va="top", fontsize=9,
                      family="monospace")
    stamp_format = _time_format(t)

    def update(k):
        for b, art in zip(scene.bodies, body_art):
            c = centres[b][k]
            xyz = np.array([c] + [p for s in spokes[b] for p in (s[k], c)]) if spokes[b] else c[None, :]
            art.set_data_3d(xyz[:, 0], xyz[:, 1], xyz[:, 2])
            art.set_marker("" if spokes[b] else "o")
        for b, art in box_art.items():
            xyz = box_frames[b][k]
            art.set_data_3d(xyz[:, 0], xyz[:, 1], xyz[:, 2])
        for art, xyz in zip(triad_art, triad_frames):
            art.set_data_3d(xyz[k, :, 0], xyz[k, :, 1], xyz[k, :, 2])
        c = np.array([centres[b][k] for b in scene.bodies]).reshape(-1, 3)
        centre_art.set_data_3d(c[:, 0], c[:, 1], c[:, 2])
        j = np.array([p[k] for p in joints]).reshape(-1, 3)
        joint_art.set_data_3d(j[:, 0], j[:, 1], j[:, 2])
        for art, (p, q) in zip(link_art, links):
            xyz = np.array([p[k], q[k]])
            art.set_data_3d(xyz[:, 0], xyz[:, 1], xyz[:, 2])
        for art, path_, at in zip(trace_done, traces, trace_frames):
            xyz = np.concatenate([path_[:reached[k]], at[k][None, :]])
            art.set_data_3d(xyz[:, 0], xyz[:, 1], xyz[:, 2])
        stamp.set_text(stamp_format.format(t[k]))

    artists = {"traces": trace_done, "links": link_art, "boxes": list(box_art.values()), "bodies": body_art,
               "triad": triad_art, "centres": centre_art, "joints": joint_art, "stamp": stamp}
    drawing = _Drawing(fig, artists, update)
    drawing.triad_lengths = triad  # {body: (3,) m}
    return drawing


# --- a vibration mode ------------------------------------------------------


_MODE_CYCLE = 2.0     # s: a cycle of a mode plays in 2 s (at the default frames), whatever its frequency
_MODE_REACH = 0.1     # the default amplitude moves the mechanism's points by up to this much of its size


def _posed(equilibrium, q, t=None):
    """A Result of the equilibrium's model at rest in the poses q (k, n) at
    the times t (default 0 .. k - 1), each spatial body's Euler parameters
    normalised."""
    from .result import Result

    q = np.array(q, dtype=float)
    core = equilibrium._core
    _unit_orientations(equilibrium.model, core, q)
    zero = np.zeros_like(q)
    t = np.arange(len(q), dtype=float) if t is None else np.asarray(t, dtype=float)
    raw = {"t": t, "q": q, "v": zero, "a": zero,
           "lam": np.zeros((len(q), len(equilibrium.lam))), "stats": {}}
    return Result(equilibrium.model, core, raw)


def _drawn_points(scene, result):
    """(k, p, d): the points the drawing goes through in each pose of result:
    the bodies' centres of mass, the points where elements attach (a pinned
    rod drawn whole) and, in space, the corners of the inertia boxes; the
    points fixed to the ground too."""
    k = len(result.t)
    paths = []
    for b in scene.bodies:
        paths.append(result.body(b).position)
        paths += [scene.path(b, p, result=result) for p in scene.drawn_outline(b)]
        corners = scene.box(b)
        if corners is not None:
            paths += [scene.path(b, c, result=result) for c in corners]
    for kind, kw in scene.elements:
        paths += [np.broadcast_to(p, (k, scene.dimension)) for b, p in scene.attachments(kw["name"])
                  if b == "ground"]
    return np.stack(paths, axis=1)


def _mode_amplitude(equilibrium, shape):
    """The default amplitude of a mode's shape (its largest entry 1: m or
    rad): what moves the drawn points by up to _MODE_REACH of the
    mechanism's size (the largest extent of those points at equilibrium),
    from the points' motion along the shape (a difference quotient)."""
    step = 1e-6
    shown = _posed(equilibrium, [equilibrium.q, equilibrium.q + step * shape])
    points = _drawn_points(_Scene(shown), shown)
    size = float(np.max(np.ptp(points[0], axis=0))) if points.shape[1] else 0.0
    if not size > 1e-9:
        size = 1.0  # a point alone: 1 m
    moved = float(np.max(np.linalg.norm(points[1] - points[0], axis=1))) / step if points.shape[1] else 0.0
    if not moved > 1e-9:
        return _MODE_REACH  # the shape moves no drawn point: 0.1 of whatever it moves
    return _MODE_REACH * size / moved


def animate_mode(modes, index=0, path=None, *, amplitude=None, cycles=2, fps=25, frames=None,
                 size=(640, 480), dpi=100, view=(25.0, -60.0)):
    """Write a looping GIF of one vibration mode of ``mb.modes``: the
    mechanism at its equilibrium moved along the mode's shape,
    q = q_eq + amplitude sin(phase) shape, the phase running through
    ``cycles`` whole cycles (so that the loop has no seam). Drawn as
    :func:`animate` draws a run (planar or spatial); each spatial body's
    Euler parameters are normalised after the shape is added. The title
    says "mode I: f Hz (kind)".

    ``modes``: what ``mb.modes(model)`` returned; ``index``: the mode, 0 to
    ``len(modes) - 1`` (their order: frequency ascending). A vibration mode
    is shown in its own time, the phase omega t, the stamp giving t (a
    cycle plays in 2 s at the default frames, whatever its period). A
    rigid-body mode (nothing resists it) or an unstable one
    (it grows as exp(omega t)) is not an oscillation: it is shown as the
    same slow back-and-forth along its shape, and the title says which.

    ``amplitude``: the multiple of the shape added (the shape's largest
    entry is 1, so amplitude is in the unit of that coordinate, m or rad).
    By default the one that moves the points drawn (centres of mass, joint
    points, the corners of spatial bodies' inertia boxes) by up to a tenth
    of the mechanism's size: visible, and small enough to look linear.
    ``fps`` frames per second (at most 50); ``frames``: the number of
    frames (default ``cycles`` times 2 s at ``fps``: 100 at the defaults;
    pictures that come out the same one after the other, the turning points
    of a mode shown without a time stamp, Pillow keeps as one longer frame).
    ``size`` in pixels, ``view`` = (elevation, azimuth) in degrees for a
    spatial model, as for animate.

    Writes the GIF to ``path`` and returns the path; with ``path`` None,
    returns the GIF's bytes (``IPython.display.Image(data=...)`` shows them
    in a notebook). ModelError for a bad index (naming it and how many
    modes there are) or setting.
    """
    from .linear import Modes

    _matplotlib()
    try:
        from PIL import Image  # noqa: F401 - there before anything is drawn
    except ImportError as e:
        raise ImportError(_HINT) from e
    if not isinstance(modes, Modes):
        raise ModelError(f"animate_mode: modes must be what mb.modes(model) returns, got {type(modes).__name__}")
    count = len(modes)
    if isinstance(index, bool) or not isinstance(index, (int, np.integer)) or not 0 <= index < count:
        which = f"0 .. {count - 1}" if count else "none: nothing can move"
        raise ModelError(f"animate_mode: index {index!r}: there {'is' if count == 1 else 'are'} "
                         f"{_count(count, 'mode')} ({which})")
    index = int(index)
    fps = _checked("animate_mode: fps", fps, 0.0, _MAX_FPS)
    cycles = _checked("animate_mode: cycles", cycles, 0, whole=True)
    frames = int(round(cycles * _MODE_CYCLE * fps)) if frames is None \
        else _checked("animate_mode: frames", frames, 1, whole=True)
    frames = max(frames, 2)
    equilibrium = modes.equilibrium
    shape = np.asarray(modes.shapes[index], dtype=float)
    amplitude = _mode_amplitude(equilibrium, shape) if amplitude is None \
        else _checked("animate_mode: amplitude", amplitude, 0.0)

    kind, omega, frequency = modes.kinds[index], float(modes.omega[index]), float(modes.frequencies[index])
    if kind == "rigid-body":  # its omega is round-off about 0
        frequency = 0.0
    phase = 2.0 * math.pi * cycles * np.arange(frames) / frames
    # a vibration mode at its own times (the stamp gives t in the cycle); the others by phase
    shown = _posed(equilibrium, equilibrium.q + amplitude * np.sin(phase)[:, None] * shape[None, :],
                   phase / omega if kind == "vibration" else phase)
    scene = _Scene(shown)
    if scene.dimension == 3:
        drawing = _spatial_drawing(scene, shown, [], size, dpi, view, 1.0)
    else:
        drawing = _planar_drawing(scene, shown, [], size, dpi, 1.0)
    title = f"mode {index}: {frequency:.4g} Hz ({kind})"
    if kind != "vibration":  # no time to stamp: the title says how it moves instead
        title += "\n" + ("it moves freely" if kind == "rigid-body" else f"it grows as exp({omega:.3g} t)") \
            + "; shown back and forth"
        drawing.artists["stamp"].set_visible(False)
    drawing.fig.axes[0].set_title(title, fontsize=10)
    ends = np.round(100.0 * np.arange(1, frames + 1) / fps)  # hundredths of a second, as animate counts
    durations = (10 * np.diff(np.concatenate(([0.0], ends)))).astype(int)
    if path is not None:
        return _write_gif(drawing, path, durations)
    import tempfile

    with tempfile.TemporaryDirectory() as folder:
        written = _write_gif(drawing, os.path.join(folder, "mode.gif"), durations)
        with open(written, "rb") as f:
            return f.read()


# --- a still picture of a spatial model with its shapes -------------------


def _read_stl(path):
    """The triangles (n, 3, 3) of an STL file, binary or ASCII (m). A
    ModelError names the file and what is wrong with it: a binary file whose
    size is not its triangle count's (cut short, or a count past its end),
    an ASCII one cut short or holding a word where a keyword or a number
    belongs, a vertex that is not finite."""
    who = f"STL file {os.fspath(path)!r}"
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise ModelError(f"{who}: cannot read it: {e.strerror or e}") from None
    count = int.from_bytes(data[80:84], "little") if len(data) >= 84 else None
    if count is not None and 84 + 50 * count == len(data):  # binary: 80-byte header, count, 50 bytes per triangle
        records = np.frombuffer(data, dtype=np.dtype([("normal", "<f4", 3), ("vertices", "<f4", (3, 3)),
                                                      ("attribute", "<u2")]), count=count, offset=84)
        triangles = records["vertices"].astype(float)
        bad = np.flatnonzero(~np.isfinite(triangles).all(axis=(1, 2)))
        if len(bad):
            raise ModelError(f"{who}: triangle {bad[0] + 1} of {count} has a vertex that is not finite: "
                             f"{show(triangles[bad[0]].tolist())}")
        return triangles
    # ASCII starts with "solid"; so do some binary headers, but binary floats hold zero bytes
    if data.lstrip()[:5].lower() == b"solid" and b"\0" not in data:
        return _read_ascii_stl(data.decode("ascii", errors="replace"), who)
    if count is None:
        raise ModelError(f"{who}: {len(data)} bytes: too short for a binary STL (80 bytes of header and a "
                         "triangle count) and not an ASCII one (which starts with 'solid')")
    raise ModelError(f"{who}: a binary STL of {count} triangles (as its bytes 80..83 say) is 84 + 50 x {count} = "
                     f"{84 + 50 * count} bytes long; the file has {len(data)} bytes"
                     + (" (cut short, or a wrong count?)" if len(data) < 84 + 50 * count else ""))


# One facet of an ASCII STL, word by word (None: a number): its normal (not
# used), then its three vertices.
_FACET = ("facet", "normal", None, None, None, "outer", "loop", "vertex", None, None, None, "vertex", None, None,
          None, "vertex", None, None, None, "endloop", "endfacet")


def _read_ascii_stl(text, who):
    """The triangles of an ASCII STL's text: solids ('solid' name ...
    'endsolid' name) of facets as _FACET spells them."""
    # a solid's name is the rest of its line (it may hold any word)
    text = re.sub(r"(?im)^([ \t]*(?:end)?solid)\b[^\n]*", r"\1", text)
    words = text.split()
    n = len(words)

    def where(i):  # the line of word i: worked out only for a message
        seen = 0
        for line, words_in in enumerate(text.split("\n"), 1):
            seen += len(words_in.split())
            if seen > i:
                return f"{who}, line {line}"
        return who

    def wrong(i, wanted):
        if i >= n:
            return ModelError(f"{who}: ends (line {len(text.rstrip().split(chr(10)))}) where {wanted} belongs "
                              "(cut short?)")
        return ModelError(f"{where(i)}: {show(words[i])} where {wanted} belongs")

    def number(i):
        try:
            return decimal(words[i], who)
        except ModelError:
            return decimal(words[i], where(i))  # raises again, its message naming the line

    def keyword(i, wanted):
        if i >= n or (words[i] != wanted and words[i].lower() != wanted):
            raise wrong(i, repr(wanted))

    vertices = []
    i = 0
    while i < n:
        keyword(i, "solid")
        i += 1
        while i >= n or words[i].lower() != "endsolid":
            if i >= n or words[i].lower() != "facet":
                raise wrong(i, "'facet' or 'endsolid'")
            for j, wanted in enumerate(_FACET):
                if wanted is not None:
                    keyword(i + j, wanted)
                elif i + j >= n:
                    raise wrong(i + j, "a number")
                else:
                    x = number(i + j)
                    if j > 4:  # a vertex's coordinate
                        if not math.isfinite(x):
                            raise ModelError(f"{where(i + j)}: a vertex coordinate {show(words[i + j])} is not finite")
                        vertices.append(x)
            i += len(_FACET)
        i += 1
    return np.array(vertices, dtype=float).reshape(-1, 3, 3)


def _box_faces(size):
    half = 0.5 * np.asarray(size, dtype=float)
    corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * half
    quads = [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5)]
    return [corners[list(q)] for q in quads]


def _cylinder_faces(radius, length, segments=24):
    a = np.linspace(0.0, 2 * np.pi, segments + 1)
    ring = np.column_stack([radius * np.cos(a), radius * np.sin(a)])
    faces = [np.array([[*ring[k], -0.5 * length], [*ring[k + 1], -0.5 * length], [*ring[k + 1], 0.5 * length],
                       [*ring[k], 0.5 * length]]) for k in range(segments)]
    faces += [np.column_stack([ring, np.full(len(ring), z)]) for z in (-0.5 * length, 0.5 * length)]
    return faces


def _sphere_faces(radius, segments=12):
    u = np.linspace(0.0, 2 * np.pi, 2 * segments + 1)
    v = np.linspace(0.0, np.pi, segments + 1)

    def at(i, j):
        return radius * np.array([np.cos(u[i]) * np.sin(v[j]), np.sin(u[i]) * np.sin(v[j]), np.cos(v[j])])

    return [np.array([at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
            for i in range(2 * segments) for j in range(segments)]


def _shape_faces(shape):
    """The faces of one shape in its own axes, or None (a mesh lagmb does
    not read: only STL files are drawn)."""
    if shape.kind == "box":
        return _box_faces(shape.size)
    if shape.kind == "cylinder":
        return _cylinder_faces(*shape.size)
    if shape.kind == "sphere":
        return _sphere_faces(shape.size[0])
    if not shape.mesh.lower().endswith(".stl") or not os.path.isfile(shape.mesh):
        return None
    return list(_read_stl(shape.mesh) * np.asarray(shape.size))


def picture(result, path, *, time=None, role="collision", view=(20.0, -50.0), size=(640, 640), dpi=100,
            title=None):
    """A still picture of a spatial model at one output of a run: the
    shapes of ``role`` ("visual" or "collision"; Model.add_shape, as
    load_urdf keeps a robot's) at their bodies' poses, shaded by their
    facing to the light, each body in its colour, over the bodies' lines to
    their joints (as animate draws them). ``time``: the output nearest it
    (default the last). Meshes are drawn from STL files; a shape in
    another format (COLLADA .dae, OBJ) is left out and counted in the
    caption. Returns the number of shapes drawn."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    model = result.model
    if getattr(model, "dimension", 2) != 3:
        raise ModelError("plotting.picture draws spatial models (dimension 3); this one is planar")
    if role not in ("visual", "collision"):
        raise ModelError(f"plotting.picture: role must be 'visual' or 'collision', got {show(role)}")
    view = vec2(view, "plotting.picture: view (elevation, azimuth in degrees)")
    t = np.asarray(result.t)
    k = len(t) - 1 if time is None else int(np.argmin(np.abs(t - real(time, "plotting.picture: time"))))
    scene = _Scene(result)
    fig = _figure((size[0] / dpi, size[1] / dpi), dpi=dpi)
    ax = fig.add_subplot(projection="3d")
    ax.view_init(elev=float(view[0]), azim=float(view[1]))
    light = np.array([0.4, -0.5, 0.8]) / np.linalg.norm([0.4, -0.5, 0.8])
    drawn, skipped, points = 0, 0, []
    bodies = list(scene.bodies)
    for shape in model.shapes:
        if shape.role != role:
            continue
        faces = _shape_faces(shape)
        if faces is None:
            skipped += 1
            continue
        if shape.body == "ground":
            R_body, r_body = np.eye(3), np.zeros(3)
        else:
            b = result.body(shape.body)
            R_body, r_body = b.rotation[k], b.position[k]
        R = R_body @ shape.rotation
        r = r_body + R_body @ shape.position
        world = [r + f @ R.T for f in faces]
        normals = [np.cross(f[1] - f[0], f[2] - f[0]) for f in world]
        shade = np.array([abs(n @ light) / (np.linalg.norm(n) or 1.0) for n in normals])
        base = np.array(_rgb(_colour(bodies.index(shape.body)) if shape.body in bodies else "0.6"))
        colours = [(*(base * (0.45 + 0.55 * s)), 1.0) for s in shade]
        # one collection per polygon size: matplotlib pads ragged polygons (a
        # cylinder's caps beside its side quads) with unset values that its
        # autoscaling read as limits (seen once: an infinite z limit)
        for count in sorted({len(f) for f in world}):
            picked = [i for i, f in enumerate(world) if len(f) == count]
            ax.add_collection3d(Poly3DCollection([world[i] for i in picked],
                                                 facecolors=[colours[i] for i in picked], edgecolors="none"))
        if world:  # an STL of no triangles draws nothing
            points += [np.concatenate(world)]
        drawn += 1
    for i, b in enumerate(bodies):  # the skeleton: centre of mass to joint points
        c = result.body(b).position[k]
        spokes = [scene.path(b, p)[k] for p in scene.outlines[b]]
        xyz = np.array([c] + [p for s in spokes for p in (s, c)])
        ax.plot(xyz[:, 0], xyz[:, 1], xyz[:, 2], color="0.15", lw=1.0, alpha=0.6)
        points.append(xyz)
    pts = np.concatenate(points) if points else np.zeros((1, 3))
    centre = 0.5 * (pts.min(axis=0) + pts.max(axis=0))
    half = 0.55 * max(float(np.max(np.ptp(pts, axis=0))), 1e-3)
    for axis, set_lim, label in zip(range(3), (ax.set_xlim, ax.set_ylim, ax.set_zlim), "xyz"):
        set_lim(centre[axis] - half, centre[axis] + half)
        getattr(ax, f"set_{label}label")(f"{label} (m)")
    if hasattr(ax, "set_box_aspect"):
        ax.set_box_aspect((1, 1, 1))
    caption = f"t = {t[k]:.3g} s, {drawn} {role} shapes" + (f" ({skipped} meshes not STL, not drawn)"
                                                             if skipped else "")
    ax.set_title(title or f"lagmb: {scene.summary()}", fontsize=10)
    ax.text2D(0.02, 0.02, caption, transform=ax.transAxes, fontsize=8)
    _save(fig, path)
    return drawn


def _rgb(colour):
    from matplotlib.colors import to_rgb

    return to_rgb(colour)


# --- parameter studies (mb.sweep) -------------------------------------------

_SWEEP_RECORDS = ("status", "warnings", "steps", "wall_time", "q")  # what every case records
_SWEEP_LINES = 8  # values of a second parameter drawn as lines; more: a heat map


def _sweep_outputs(ds, outputs=None):
    """The outputs plot_sweep draws: those named (checked), else every
    output with one number per case."""
    def scalar(name):
        return ds[name].dims == ("case",) and np.issubdtype(ds[name].dtype, np.number)

    found = [name for name in ds.data_vars if name not in _SWEEP_RECORDS and scalar(name)]
    if outputs is None:
        if not found:
            raise ValueError("plot_sweep: the study has no outputs to draw (mb.sweep's outputs=, lagmb sweep's "
                             "--output)")
        return found
    outputs = [outputs] if isinstance(outputs, str) else list(outputs)
    if not outputs:
        raise ValueError("plot_sweep: outputs is empty; give the names of outputs to draw, or None for all")
    for name in outputs:
        if name not in ds.data_vars or name in ("status", "warnings", "q"):
            raise ValueError(f"plot_sweep: no output {name!r}; the study's outputs are "
                             f"{', '.join(found) or 'none'} (and steps, wall_time)")
        if not scalar(name):
            raise ValueError(f"plot_sweep: {name!r} is not one number per case (dimensions {ds[name].dims})")
    return outputs


class _Varied:
    """A parameter of a study: its values per case, its distinct values in
    order and where each goes on an axis (numbers as they are, else in
    order: a text such as a method's name)."""

    def __init__(self, name, values):
        self.name = name
        self.numeric = np.issubdtype(values.dtype, np.number)
        if self.numeric:
            self.values = values.astype(float)
            self.distinct = sorted(set(self.values[np.isfinite(self.values)].tolist()))
        else:
            self.values = np.array([str(v) for v in values], dtype=object)
            self.distinct = sorted(set(self.values.tolist()))
        self.log = (self.numeric and len(self.distinct) > 2 and self.distinct[0] > 0
                    and self.distinct[-1] / self.distinct[0] >= 100.0)

    def positions(self, values=None):
        values = self.values if values is None else values
        if self.numeric:
            return np.asarray(values, dtype=float)
        index = {v: i for i, v in enumerate(self.distinct)}
        return np.array([index.get(v, np.nan) for v in values], dtype=float)

    def text(self, v):
        return f"{v:.4g}" if self.numeric else str(v)

    def axis(self, ax, which="x"):
        """Label (and scale, or the texts' ticks) of the x or y axis."""
        getattr(ax, f"set_{which}label")(self.name)
        if self.log:
            getattr(ax, f"set_{which}scale")("log")
        if not self.numeric:
            getattr(ax, f"set_{which}ticks")(range(len(self.distinct)), [str(v) for v in self.distinct])


def _sweep_parameters(ds):
    """([_Varied, ...] in the grid's order, {name: value} of the parameters
    with one value in every case)."""
    import json

    grid = json.loads(ds.attrs.get("grid") or "[]")
    names = [g[0] for g in grid if g[0] in ds.coords]
    names += [c for c in ds.coords if c not in names and c != "case" and ds[c].dims == ("case",)]
    varied, fixed = [], {}
    for name in names:
        p = _Varied(name, ds[name].values)
        if len(p.distinct) > 1:
            varied.append(p)
        elif p.distinct:
            fixed[name] = p.text(p.distinct[0])
    return varied, fixed


def _sweep_label(name):
    """An axis label for an output as lagmb sweep names them, with its unit."""
    if name.startswith("peak_reaction_"):
        return f"{name} (N)"
    if name == "energy_drift":
        return f"{name} (J)"
    if name == "wall_time":
        return f"{name} (s)"
    if name.startswith("final_"):
        coordinate = name[len("final_"):]
        rate = coordinate.startswith("der(")
        which = coordinate.rstrip(")").rpartition(".")[2]
        unit = {"x": "m", "y": "m", "z": "m", "angle": "rad"}.get(which)
        if unit:
            return f"{name} ({unit}/s)" if rate else f"{name} ({unit})"
    return name


def plot_sweep(ds, path=None, outputs=None, *, dpi=120):
    """Response plots of a parameter study (``mb.sweep``'s Dataset, or the
    path of its store): one subplot per output, one under the other.

    Against the one varied parameter: a line. Two varied parameters: a line
    against the first for each value of the second (up to 8 values; else
    the parameter with fewer values makes the lines, and with more than 8
    of each a heat map of the grid). More than two: against the first, a
    line through the mean over the others and a band from their minimum to
    their maximum (named in the title). A study that is not a grid (a table
    or a design) with two or more varied parameters: points against the
    first, coloured by the second. Parameters with one value in every case
    are noted in the title; a parameter spanning a factor of 100 or more
    (rtol) gets a log axis.

    ``outputs``: the outputs to draw (names of the Dataset's variables),
    default every output with one number per case (``steps`` and
    ``wall_time`` may be asked for). Failed cases (``status`` not "ok")
    are left out of the lines and counted in the title.

    Returns the matplotlib Figure (drawn on the Agg canvas, outside
    pyplot). With ``path``, the figure is also written there, its format
    from the extension (.png, .pdf, .svg, ...).
    """
    if isinstance(ds, (str, os.PathLike)):
        from .studies import open_store

        ds = open_store(ds)
    if "case" not in ds.dims or "status" not in ds:
        raise ValueError("plot_sweep: not a parameter study: give mb.sweep's Dataset or the path of its store")
    names = _sweep_outputs(ds, outputs)
    _matplotlib()
    varied, fixed = _sweep_parameters(ds)
    ok = ds["status"].values == "ok"
    n = ds.sizes["case"]
    grid = bool(ds.attrs.get("grid"))

    heat = False
    if len(varied) == 2 and grid:
        first, second = varied
        if len(second.distinct) > _SWEEP_LINES:
            if len(first.distinct) <= _SWEEP_LINES:
                varied = [second, first]  # the one with fewer values makes the lines
            else:
                heat = True
    fig = _figure((8.5, 1.3 + (2.9 if heat else 2.4) * len(names)), constrained_layout=True)
    if hasattr(fig, "get_layout_engine"):
        fig.get_layout_engine().set(w_pad=0.1, h_pad=0.06)
    axes = fig.subplots(len(names), 1, sharex=True, squeeze=False)[:, 0]
    note = ""
    for k, (ax, name) in enumerate(zip(axes, names)):
        y = np.asarray(ds[name].values, dtype=float)
        use = ok & np.isfinite(y)
        if not varied:
            ax.plot(ds["case"].values[use], y[use], "o", ms=5, color=_colour(0))
            ax.set_xlabel("case")
        elif len(varied) == 1 or (len(varied) == 2 and grid and not heat):
            note = _sweep_lines(ax, varied, y, use, legend=k == 0)
        elif heat:
            _sweep_heat(fig, ax, varied, y, use, name)
        elif grid:
            note = _sweep_band(ax, varied, y, use, legend=k == 0)
        else:
            note = _sweep_points(fig, ax, varied, y, use, name)
        if not heat:
            ax.set_ylabel(_sweep_label(name))
            _sweep_flat(ax, y[use])
            ax.grid(alpha=0.3)
    if varied:
        varied[0].axis(axes[-1])
    failed = int((~ok).sum())
    if grid:
        shape = " x ".join(f"{p.name} ({len(p.distinct)})" for p in varied)
    else:  # a table or a design: its values are not a grid's
        shape = ", ".join(p.name for p in varied) + (" varied" if varied else "")
    shape = shape or "no parameter varied"
    lines = [f"lagmb sweep: {n:,} case{'' if n == 1 else 's'}, {shape}",
             "all ok" if not failed else f"{failed:,} failed case{'' if failed == 1 else 's'} left out"]
    if note:
        lines[1] += f"; {note}"
    if fixed:
        lines.append(", ".join(f"{name} = {value}" for name, value in fixed.items()))
    fig.suptitle("\n".join(lines), fontsize=10)
    if path is not None:
        _save(fig, path, dpi=dpi)
    return fig


def _sweep_lines(ax, varied, y, use, legend):
    """y against the first parameter: one line, or one per value of the second."""
    first = varied[0]
    x = first.positions()
    if len(varied) == 1:
        order = np.argsort(x[use], kind="stable")
        ax.plot(x[use][order], y[use][order], "o-", ms=3.5, lw=1.5, color=_colour(0))
        return ""
    second = varied[1]
    for i, v in enumerate(second.distinct):
        mask = use & (second.values == v)
        if not mask.any():
            continue  # every case failed: not in the legend either
        order = np.argsort(x[mask], kind="stable")
        ax.plot(x[mask][order], y[mask][order], "o-", ms=3.5, lw=1.5, color=_colour(i), label=second.text(v))
    if legend:
        _legend(ax, title=second.name)
    return ""


def _sweep_band(ax, varied, y, use, legend):
    """y against the first parameter: the mean over the other parameters'
    values and the band from the least to the largest."""
    first = varied[0]
    x = first.positions()
    xs, mean, low, high = [], [], [], []
    for v in first.positions(first.distinct):
        mask = use & (x == v)
        if mask.any():
            xs.append(v), mean.append(y[mask].mean()), low.append(y[mask].min()), high.append(y[mask].max())
    ax.fill_between(xs, low, high, color=_colour(0), alpha=0.2, lw=0, label="min to max")
    ax.plot(xs, mean, "o-", ms=3.5, lw=1.5, color=_colour(0), label="mean")
    others = ", ".join(p.name for p in varied[1:])
    if legend:
        _legend(ax, title=f"over {others}")
    return f"mean and range over {others}"


def _sweep_points(fig, ax, varied, y, use, name):
    """y against the first parameter, a point per case coloured by the second."""
    first, second = varied[0], varied[1]
    from matplotlib.colors import LogNorm

    colours = second.positions()
    dots = ax.scatter(first.positions()[use], y[use], c=colours[use], s=14, cmap="viridis",
                      norm=LogNorm() if second.log else None)
    bar = fig.colorbar(dots, ax=ax, pad=0.01)
    bar.set_label(second.name)
    if not second.numeric:
        bar.set_ticks(range(len(second.distinct)), labels=[str(v) for v in second.distinct])
    others = ", ".join(p.name for p in varied[2:])
    return f"also varied: {others}" if others else ""


def _sweep_heat(fig, ax, varied, y, use, name):
    """The grid of two parameters as a heat map of y."""
    first, second = varied
    xs, ys = first.positions(first.distinct), second.positions(second.distinct)
    z = np.full((len(ys), len(xs)), np.nan)
    col = {v: i for i, v in enumerate(xs)}
    row = {v: j for j, v in enumerate(ys)}
    for xv, yv, value in zip(first.positions()[use], second.positions()[use], y[use]):
        z[row[yv], col[xv]] = value
    mesh = ax.pcolormesh(xs, ys, np.ma.masked_invalid(z), shading="nearest", cmap="viridis")
    bar = fig.colorbar(mesh, ax=ax, pad=0.01)
    bar.set_label(_sweep_label(name))
    second.axis(ax, "y")
    ax.set_title(name, fontsize=9)


def _sweep_flat(ax, y):
    """An output the parameters do not change (to round-off) is drawn flat
    about its value, not as round-off magnified around an offset."""
    if not len(y):
        return
    low, high = float(y.min()), float(y.max())
    middle = 0.5 * (low + high)
    if high - low <= 1e-9 * max(abs(middle), 1e-300):
        pad = 0.05 * abs(middle) or 1.0
        ax.set_ylim(middle - pad, middle + pad)
        ax.ticklabel_format(axis="y", useOffset=False)
