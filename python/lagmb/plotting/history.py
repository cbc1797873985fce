"""Time histories of a run (plot_result): coordinates, reactions, drivers'
efforts, energy and the constraint residual, one subplot under the other."""

import numpy as np

from .. import _rotations
from .._drawing import Scene, stats_line
from ._figures import cycle_colour, new_figure, add_legend, load_matplotlib, save_figure

_MAX_LINES = 8    # lines (legend entries) per subplot
_MAX_BODIES = 6   # bodies in the coordinate plots (their legend adds the x / y keys)
_PANELS = ("coordinates", "reactions", "efforts", "energy", "residual")


# --- time histories ------------------------------------------------------


def plot_result(result, path=None, *, what=_PANELS, dpi=120):
    """Time histories of a run, one subplot under the other on a shared time axis.

    ``what`` picks among "coordinates" (centre-of-mass x, y (z) in m, and the
    angles in rad, on two subplots; in space the angle each body has turned
    from its initial orientation; a spatial model with revolute,
    translational or cylindrical joints that say how every body moves (a
    robot from a URDF file) shows its joints instead: their angles (rad),
    slides (m) and rates, as ``r.joint(name)`` reads them, and a floating
    base's centre of mass), "reactions" (magnitude of each joint's
    reaction force, N), "efforts" (the drivers' forces or torques, and
    the stops' along their joints: 0 while a joint is off its limits),
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
    load_matplotlib()
    scene = Scene(result)
    t = np.asarray(result.t)

    panels = []  # functions that draw one subplot each
    moving = _joint_coordinates(scene) if scene.dimension == 3 else []
    if "coordinates" in what and moving:  # a robot: its joints, as its user reads it
        free = [b for b in scene.bodies if b not in {str(kw["body_j"]) for _, kw in scene.elements if "body_j" in kw}]
        if free:  # a floating base: where it is
            panels.append(lambda ax: _positions(ax, result, scene, free))
        paths = {n: p for n, p in ((n, _quiet(lambda: result.joint(n))) for n, _ in moving) if p is not None}
        angles = {n: paths[n].angle for n, slide in moving if not slide and n in paths}
        slides = {n: paths[n].slide for n, slide in moving if slide and n in paths}
        rates = {n + (" (m/s)" if slide else ""): paths[n].rate for n, slide in moving if n in paths}
        if angles:
            panels.append(lambda ax: _lines(ax, t, dict(list(angles.items())[:_MAX_LINES]), len(angles), "joints",
                                            "joint angle (rad)"))
        if slides:
            panels.append(lambda ax: _lines(ax, t, dict(list(slides.items())[:_MAX_LINES]), len(slides), "joints",
                                            "joint slide (m)"))
        if rates:
            rate_unit = "rad/s" if angles else "m/s"  # (a slide's in its name where both are)
            rates = rates if angles else {n.removesuffix(" (m/s)"): y for n, y in rates.items()}
            panels.append(lambda ax, label=f"joint rate ({rate_unit})": _lines(
                ax, t, dict(list(rates.items())[:_MAX_LINES]), len(rates), "joints", label))
    elif "coordinates" in what and scene.bodies:
        panels.append(lambda ax: _positions(ax, result, scene))
        if any(b not in scene.particles for b in scene.bodies):
            panels.append(lambda ax: _angles(ax, result, scene))
    if "reactions" in what:
        reactions = _series(scene.joints, lambda n: np.hypot(*result.reaction(n)[:, :2].T) if scene.dimension == 2
                            else np.linalg.norm(result.reaction(n)[:, :3], axis=1))
        if reactions:
            panels.append(lambda ax: _lines(ax, t, reactions, len(scene.joints), "joints",
                                            "reaction |F| (N)"))
    exerting = scene.drivers + scene.by_role["stop"]
    if "efforts" in what and exerting:
        efforts = _series(exerting, lambda n: _effort(result, n))
        if efforts:
            units = {scene.effort_unit(n) for n in efforts}
            unit = units.pop() if len(units) == 1 else None
            labelled = {n if unit else f"{n} ({scene.effort_unit(n)})": y
                        for n, y in efforts.items()}
            panels.append(lambda ax: _lines(ax, t, labelled, len(exerting), "drivers and stops",
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

    fig = new_figure((8.5, 1.2 + 2.0 * len(panels)), constrained_layout=True)
    if hasattr(fig, "get_layout_engine"):  # matplotlib >= 3.6: a little air at the edges
        fig.get_layout_engine().set(w_pad=0.1, h_pad=0.06)
    axes = fig.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    for ax, draw in zip(axes, panels):
        draw(ax)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("time t (s)")
    if len(t) > 1:
        axes[-1].set_xlim(t[0], t[-1])
    title = scene.heading()
    stats = stats_line(getattr(result, "stats", None))
    fig.suptitle(f"lagmb: {title}" + (f"\n{stats}, {len(t)} outputs" if stats else ""),
                 fontsize=11)
    if path is not None:
        save_figure(fig, path, dpi=dpi)
    return fig


def _joint_coordinates(scene):
    """[(name, slide?)] of the joints that have an angle or a slide
    (revolute, translational, cylindrical: its angle), in the order added,
    where they say how every body moves: each body is the second body of
    one of them, or of no joint (a free base, drawn apart); else [] (a
    body on a ball joint has no joint coordinate to show)."""
    out, moved, held = [], set(), set()
    for method, kw in scene.elements:
        kind = scene.kinds.get(method)
        if kind is None or kind.role != "joint" or "body_j" not in kw:
            continue
        coordinates = set(kind.coordinates)
        held.add(str(kw["body_j"]))
        if coordinates & {"angle", "slide"}:
            out.append((kw["name"], "angle" not in coordinates))
            moved.add(str(kw["body_j"]))
    return out if out and held <= moved else []


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


def _shown(names, total, what):
    """Legend title saying that only some are drawn."""
    return f"first {len(names)} of {total} {what}" if total > len(names) else None


def _positions(ax, result, scene, bodies=None):
    from matplotlib.lines import Line2D

    bodies = scene.bodies if bodies is None else bodies
    shown = bodies[:_MAX_BODIES]
    handles = []
    styles = ("-", "--", ":")[:scene.dimension]
    for i, b in enumerate(shown):
        pos = result.body(b).position
        for axis, style in enumerate(styles):
            ax.plot(result.t, pos[:, axis], color=cycle_colour(i), lw=1.4, ls=style)
        handles.append(Line2D([], [], color=cycle_colour(i), lw=2, label=b))
    handles += [Line2D([], [], color="0.3", lw=1.4, ls=style, label="xyz"[axis])
                for axis, style in enumerate(styles)]
    ax.set_ylabel("centre of mass\n" + ", ".join("xyz"[:scene.dimension]) + " (m)")
    add_legend(ax, _shown(shown, len(bodies), "bodies"), handles)


def _angles(ax, result, scene):
    rigid = [(i, b) for i, b in enumerate(scene.bodies) if b not in scene.particles]
    shown = rigid[:_MAX_BODIES]
    for i, b in shown:
        ax.plot(result.t, _angle(result, b), color=cycle_colour(i), lw=1.4, label=b)
    ax.set_ylabel("angle φ (rad)" if scene.dimension == 2 else "turned from the start\n(rad)")
    add_legend(ax, _shown(shown, len(rigid), "bodies"))


def _angle(result, body):
    """A planar body's angle; a spatial body's angle of turn from its
    initial orientation (that of the relative rotation p0* p, in [0, pi])."""
    b = result.body(body)
    if not hasattr(b, "orientation"):
        return b.angle
    return _rotations.turned(b.orientation, b.orientation[0])


def _lines(ax, t, series, total, what, ylabel):
    for i, (name, y) in enumerate(series.items()):
        ax.plot(t, y, color=cycle_colour(i), lw=1.4, label=name)
    ax.set_ylabel(ylabel)
    _least_span(ax, list(series.values()))
    add_legend(ax, _shown(list(series), total, what))


def _least_span(ax, ys, fraction=1e-9):
    """Values that stay within ``fraction`` of max(1, their size) of each
    other (a finger joint that never moves, at 1e-16 m of round-off) are
    drawn flat in a span of that size, not magnified to fill the plot."""
    values = np.concatenate([np.asarray(y, dtype=float).ravel() for y in ys]) if ys else np.empty(0)
    values = values[np.isfinite(values)]
    if not len(values):
        return
    low, high = float(values.min()), float(values.max())
    least = fraction * max(1.0, float(np.abs(values).max()))
    if high - low < least:
        middle = 0.5 * (low + high)
        ax.set_ylim(middle - least, middle + least)


def _energy(ax, t, energy):
    e0 = energy[0] if np.isfinite(energy[0]) else energy[np.isfinite(energy)][0]
    ax.plot(t, energy - e0, color="C3", lw=1.4, label=f"E(0) = {e0:.6g} J")
    ax.set_ylabel("energy change\nE − E(0) (J)")
    ax.ticklabel_format(axis="y", style="sci", scilimits=(-3, 4), useOffset=False)
    add_legend(ax)


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
