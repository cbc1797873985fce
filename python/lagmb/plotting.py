"""Pictures of a run: time histories (plot_result) and a GIF of the mechanism (animate).

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

import numpy as np

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

    def attachments(self, name):
        """[(body, local point)] where one element attaches."""
        return self._attachments.get(name, [])

    def path(self, body, local, index=slice(None)):
        """(k, 2) global path of a body's local point (fixed for the ground);
        (k, 3) in space."""
        if body == "ground":
            return np.broadcast_to(np.asarray(local, dtype=float), (len(self.result.t), self.dimension))[index]
        return self.result.point(body, local)[index]

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
    (max |Phi| on a log scale). Subplots with nothing to show are left out.
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


def _frame_indices(k, max_frames):
    """At most max_frames indices spread evenly over 0..k-1, both ends included."""
    n = max(1, min(int(max_frames), k))
    if n == 1:
        return np.array([0])
    return np.unique(np.round(np.linspace(0, k - 1, n)).astype(int))


def _time_format(times):
    dt = np.diff(times)
    dt = dt[dt > 0]
    digits = 2 if not len(dt) else int(np.clip(math.ceil(-math.log10(dt.min())) + 1, 2, 9))
    return f"t = {{:.{digits}f}} s"


def animate(result, path, *, fps=30, max_frames=300, trace=None, size=(640, 480), dpi=100, view=(25.0, -60.0)):
    """Write a GIF of the mechanism moving.

    A spatial model (dimension 3) is drawn in perspective by matplotlib's
    mplot3d, seen from ``view`` = (elevation, azimuth) in degrees (see
    _animate_spatial); what follows is the planar drawing.

    Each body is drawn through the points where its joints and forces attach
    (``model.outline(body)``): a line for two points, a shaded convex polygon
    for three or more, a line from the centre of mass to a single point, a
    disc for none (a square block if it slides in a translational joint); a
    dot marks each centre of mass, white circles the revolute
    joints, triangles the joints to the ground, zig-zags the spring-dampers,
    dashed lines the slide axes fixed to the ground.
    ``trace``: a list of (body, local point) pairs (or one pair; the body by
    its handle or name) whose paths are drawn as they are travelled (faint
    ahead); a traced point also joins its body's shape (so a pendulum's free
    tip is drawn). The axes are fixed to cover the whole motion, with equal
    scales, in m.

    Frames are the output times of the result, evenly subsampled to at most
    ``max_frames``; they play at ``fps`` frames per second. ``size`` is the
    picture in pixels. Returns the path written.
    """
    _matplotlib()
    try:
        from matplotlib.animation import PillowWriter  # noqa: F401 - there before anything is drawn
        from matplotlib.patches import Polygon
    except ImportError as e:
        raise ImportError(_HINT) from e
    if fps <= 0 or max_frames < 1:
        raise ValueError(f"animate: fps and max_frames must be positive, got {fps}, {max_frames}")
    t = np.asarray(result.t)
    if len(t) == 0:
        raise ValueError("animate: the result has no outputs")
    scene = _Scene(result)
    frames = _frame_indices(len(t), max_frames)
    if trace is not None and len(trace) == 2 and isinstance(trace[0], (str, Handle)) \
            and np.ndim(trace[1]) == 1:
        trace = [trace]  # one (body, point) pair
    trace = [(name_of(result.model, b, ("body",), "body", "animate: trace"),
              np.asarray(p, dtype=float).reshape(scene.dimension)) for b, p in (trace or [])]
    if scene.dimension == 3:
        return _animate_spatial(scene, path, frames, trace, fps, size, dpi, view)

    # global paths of everything drawn, over all outputs (for the limits);
    # traced points belong to their bodies' shapes too (a pendulum's free tip)
    outlines = {b: list(scene.outlines[b]) for b in scene.bodies}
    for b, p in trace:
        if b in outlines and all(np.hypot(*(p - u)) > 1e-12 for u in outlines[b]):
            outlines[b].append(p)
    shapes = {b: _shape(outlines[b]) for b in scene.bodies}
    body_paths = {b: [scene.path(b, p) for p in shapes[b][0]] for b in scene.bodies}
    centres = {b: result.body(b).position for b in scene.bodies}
    traces = [scene.path(b, p) for b, p in trace]
    pins, supports, guides, links, sliders = [], [], [], [], set()
    for kind, kw in scene.elements:
        if kind == "add_translational":
            sliders.add(kw.get("body_j"))
        att = scene.attachments(kw["name"])
        if kind == "add_revolute" and att:
            moving = [(b, p) for b, p in att if b != "ground"]
            fixed = [p for b, p in att if b == "ground"]
            if moving:
                pins.append(scene.path(*moving[-1]))
            if fixed:
                supports.append(fixed[0])
        elif kind in ("add_translational", "add_pin_in_slot") and kw.get("axis") is not None:
            if kw.get("body_i") == "ground" and kw.get("at") is not None:
                guides.append((np.asarray(kw["at"], float), np.asarray(kw["axis"], float)))
            moving = [(b, p) for b, p in att if b != "ground"]
            if moving and kind == "add_pin_in_slot":
                pins.append(scene.path(*moving[-1]))
        elif kind in ("add_spring_damper", "add_distance") and len(att) == 2:
            links.append((kind, scene.path(*att[0]), scene.path(*att[1])))
    clouds = [c for paths in body_paths.values() for c in paths] + list(centres.values()) \
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
    ax.set_title(f"lagmb: {scene.summary()}", fontsize=10)

    # fixed things: slide guides, supports
    for at, axis in guides:
        u = axis / max(np.hypot(*axis), 1e-300)
        ax.plot(*np.array([at - 4 * span * u, at + 4 * span * u]).T, color="0.5", lw=1,
                ls=(0, (6, 3)), zorder=1)
    for p in supports:
        tri = np.array([p, p + (-0.6 * mark, -mark), p + (0.6 * mark, -mark)])
        ax.add_patch(Polygon(tri, closed=True, facecolor="0.75", edgecolor="0.2", lw=1,
                             zorder=2))
        ax.plot([p[0] - mark, p[0] + mark], [p[1] - mark] * 2, color="0.2", lw=1.5, zorder=2)

    # moving things, updated per frame
    trace_full, trace_done = [], []
    for n, ((b, _), path_) in enumerate(zip(trace, traces)):
        c = _colour(scene.bodies.index(b)) if b in scene.bodies else "k"
        trace_full.append(ax.plot(*path_.T, color=c, lw=1, alpha=0.2, zorder=1)[0])
        trace_done.append(ax.plot([], [], color=c, lw=1.3, zorder=1)[0])
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
    stamp_format = _time_format(t[frames])

    def draw(k):
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
        for art, path_ in zip(trace_done, traces):
            art.set_data(path_[:k + 1, 0], path_[:k + 1, 1])
        stamp.set_text(stamp_format.format(t[k]))

    return _write_gif(fig, path, frames, draw, fps, dpi)


def _write_gif(fig, path, frames, draw, fps, dpi):
    """Draws each frame k (draw(k)) of fig into a GIF at path; returns the path."""
    from matplotlib.animation import PillowWriter

    path = os.fspath(path)
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    writer = PillowWriter(fps=fps)
    with writer.saving(fig, path, dpi):
        for k in frames:
            draw(k)
            writer.grab_frame()
    return path


def _animate_spatial(scene, path, frames, trace, fps, size, dpi, view):
    """The spatial drawing: each body as lines from its centre of mass to the
    points where elements attach to it (a dot alone if none), white circles
    at the joints, triangles at joints to the ground, grey lines for
    spring-dampers and distance links, traced points' paths; equal scales on
    the three axes, in m, seen from view = (elevation, azimuth) in degrees."""
    result = scene.result
    t = np.asarray(result.t)
    elevation, azimuth = (float(x) for x in view)
    outlines = {b: list(scene.outlines[b]) + [p for tb, p in trace if tb == b] for b in scene.bodies}
    centres = {b: result.body(b).position for b in scene.bodies}
    spokes = {b: [scene.path(b, p) for p in outlines[b]] for b in scene.bodies}
    traces = [scene.path(b, p) for b, p in trace]
    joints, supports, links = [], [], []
    for kind, kw in scene.elements:
        att = scene.attachments(kw["name"])
        if kind in ("add_spring_damper", "add_distance") and len(att) == 2:
            links.append((scene.path(*att[0]), scene.path(*att[1])))
        elif scene.kind_of.get(kw["name"]) and kw["name"] in scene.joints and att:
            moving = [(b, p) for b, p in att if b != "ground"]
            if moving:
                joints.append(scene.path(*moving[-1]))
            supports += [p for b, p in att if b == "ground"]
    clouds = list(centres.values()) + [s for paths in spokes.values() for s in paths] + traces + joints \
        + [p for link in links for p in link] + [np.asarray(p)[None, :] for p in supports]
    pts = np.concatenate([np.asarray(c).reshape(-1, 3) for c in clouds]) if clouds else np.zeros((1, 3))
    pts = pts[np.isfinite(pts).all(axis=1)]
    centre = 0.5 * (pts.min(axis=0) + pts.max(axis=0)) if len(pts) else np.zeros(3)
    half = 0.55 * max(float(np.max(np.ptp(pts, axis=0))) if len(pts) else 0.0, 1e-3)

    fig = _figure((size[0] / dpi, size[1] / dpi), dpi=dpi)
    ax = fig.add_subplot(projection="3d")
    ax.view_init(elev=elevation, azim=azimuth)
    for axis, set_lim, label in zip(range(3), (ax.set_xlim, ax.set_ylim, ax.set_zlim), "xyz"):
        set_lim(centre[axis] - half, centre[axis] + half)
        getattr(ax, f"set_{label}label")(f"{label} (m)")
    if hasattr(ax, "set_box_aspect"):
        ax.set_box_aspect((1, 1, 1))
    ax.set_title(f"lagmb: {scene.summary()}", fontsize=10)
    if supports:
        s = np.array(supports, dtype=float)
        ax.plot(s[:, 0], s[:, 1], s[:, 2], "^", ms=9, color="0.75", mec="0.2")
    for n, ((b, _), path_) in enumerate(zip(trace, traces)):
        c = _colour(scene.bodies.index(b)) if b in scene.bodies else "k"
        ax.plot(*path_.T, color=c, lw=1, alpha=0.2)
    trace_done = [ax.plot([], [], [], color=_colour(scene.bodies.index(b)) if b in scene.bodies else "k",
                          lw=1.3)[0] for b, _ in trace]
    link_art = [ax.plot([], [], [], color="0.35", lw=1.2)[0] for _ in links]
    body_art = [ax.plot([], [], [], color=_colour(i), lw=4, solid_capstyle="round")[0]
                for i, _ in enumerate(scene.bodies)]
    centre_art = ax.plot([], [], [], "o", ms=3.5, color="0.1")[0]
    joint_art = ax.plot([], [], [], "o", ms=5.5, mfc="white", mec="0.15", mew=1.2)[0]
    stamp = ax.text2D(0.02, 0.97, "", transform=ax.transAxes, ha="left", va="top", fontsize=9,
                      family="monospace")
    stamp_format = _time_format(t[frames])

    def draw(k):
        for b, art in zip(scene.bodies, body_art):
            c = centres[b][k]
            xyz = np.array([c] + [p for s in spokes[b] for p in (s[k], c)]) if spokes[b] else c[None, :]
            art.set_data_3d(xyz[:, 0], xyz[:, 1], xyz[:, 2])
            art.set_marker("" if spokes[b] else "o")
        c = np.array([centres[b][k] for b in scene.bodies]).reshape(-1, 3)
        centre_art.set_data_3d(c[:, 0], c[:, 1], c[:, 2])
        j = np.array([p[k] for p in joints]).reshape(-1, 3)
        joint_art.set_data_3d(j[:, 0], j[:, 1], j[:, 2])
        for art, (p, q) in zip(link_art, links):
            xyz = np.array([p[k], q[k]])
            art.set_data_3d(xyz[:, 0], xyz[:, 1], xyz[:, 2])
        for art, path_ in zip(trace_done, traces):
            art.set_data_3d(path_[:k + 1, 0], path_[:k + 1, 1], path_[:k + 1, 2])
        stamp.set_text(stamp_format.format(t[k]))

    return _write_gif(fig, path, frames, draw, fps, dpi)


# --- a still picture of a spatial model with its shapes -------------------


def _read_stl(path):
    """The triangles (n, 3, 3) of an STL file, binary or ASCII (m)."""
    with open(path, "rb") as f:
        data = f.read()
    if len(data) >= 84:
        count = int(np.frombuffer(data, dtype="<u4", count=1, offset=80)[0])
        if 84 + 50 * count == len(data):  # binary: 80-byte header, count, 50 bytes per triangle
            records = np.frombuffer(data, dtype=np.dtype([("normal", "<f4", 3), ("vertices", "<f4", (3, 3)),
                                                          ("attribute", "<u2")]), count=count, offset=84)
            return records["vertices"].astype(float)
    words = data.decode("ascii", errors="replace").split()
    vertices = [float(words[i + k]) for i, w in enumerate(words) if w == "vertex" for k in (1, 2, 3)]
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
    t = np.asarray(result.t)
    k = len(t) - 1 if time is None else int(np.argmin(np.abs(t - float(time))))
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
