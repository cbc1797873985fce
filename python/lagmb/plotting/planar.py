"""The drawing of a planar run's frames: bodies through their attachment
points, joints, supports, springs, slide axes, contacts (the circle and
its line) and traced paths."""

import numpy as np

from .._drawing import outline_shape
from ._figures import cycle_colour, new_figure
from .frames import Drawing, speed_words, time_format

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


def planar_drawing(scene, shown, trace, size, dpi, speed):
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
    shapes = {b: outline_shape(outlines[b]) for b in scene.bodies}
    body_paths = {b: [scene.path(b, p, result=shown) for p in shapes[b][0]] for b in scene.bodies}
    centres = {b: shown.body(b).position for b in scene.bodies}
    traces = [scene.path(b, p) for b, p in trace]
    trace_frames = [scene.path(b, p, result=shown) for b, p in trace]
    reached = np.searchsorted(np.asarray(result.t), t, side="right")  # outputs up to each frame
    pins, supports, guides, links, sliders = [], [], [], [], set()
    # contacts: the circle (its centre's path, its radius) and the line (a
    # point's path and its direction's, on the line's body)
    circles, lines = [], []
    for kind, kw in scene.elements:
        if kind != "add_contact":
            continue
        centre = scene.planar_local(kw["circle_body"], kw["center"])
        point = scene.planar_local(kw["line_body"], kw["point"])
        ahead = scene.planar_local(kw["line_body"], np.asarray(kw["point"], float) + np.asarray(kw["direction"], float)
                                   / max(np.hypot(*kw["direction"]), 1e-300))
        circles.append((kw["circle_body"], scene.path(kw["circle_body"], centre, result=shown), float(kw["radius"])))
        lines.append((scene.path(kw["line_body"], point, result=shown), scene.path(kw["line_body"], ahead, result=shown)))
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
        + [q for _, p, q in links] + [p for _, p, q in links] \
        + [c + sign * R for _, c, R in circles for sign in (-1.0, 1.0)] + [p for p, _ in lines]
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

    fig = new_figure((size[0] / dpi, size[1] / dpi), dpi=dpi)
    ax = fig.add_axes(rect)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.grid(alpha=0.25)
    ax.set_title(f"lagmb: {scene.heading()}{speed_words(speed)}", fontsize=10)

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
    trace_colours = [cycle_colour(scene.bodies.index(b)) if b in scene.bodies else "k" for b, _ in trace]
    for c, path_ in zip(trace_colours, traces):
        ax.plot(*path_.T, color=c, lw=1, alpha=0.2, zorder=1)

    # moving things, updated per frame
    from matplotlib.patches import Circle
    line_art = [ax.plot([], [], color="0.3", lw=2.0, zorder=2)[0] for _ in lines]
    circle_art = []
    for b, c, R in circles:
        colour = cycle_colour(scene.bodies.index(b)) if b in scene.bodies else "0.3"
        art = Circle((0.0, 0.0), R, fill=False, edgecolor=colour, lw=2.0, zorder=4)
        ax.add_patch(art)
        circle_art.append(art)
    trace_done = [ax.plot([], [], color=c, lw=1.3, zorder=1)[0] for c in trace_colours]
    link_art = [ax.plot([], [], color="0.35", lw=1.0 if kind == "add_spring_damper" else 1.8,
                        zorder=2)[0] for kind, _, _ in links]
    body_art = []
    for i, b in enumerate(scene.bodies):
        local, closed = shapes[b]
        c = cycle_colour(i)
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
    stamp_format = time_format(t)

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
        for art, (_, c, _) in zip(circle_art, circles):
            art.set_center(c[k])
        for art, (p, ahead) in zip(line_art, lines):
            u = ahead[k] - p[k]
            u = u / max(np.hypot(*u), 1e-300)
            xy = np.array([p[k] - 4 * span * u, p[k] + 4 * span * u])
            art.set_data(xy[:, 0], xy[:, 1])
        for art, path_, at in zip(trace_done, traces, trace_frames):
            xy = np.concatenate([path_[:reached[k]], at[k][None, :]])
            art.set_data(xy[:, 0], xy[:, 1])
        stamp.set_text(stamp_format.format(t[k]))

    # in the order of their zorder: each frame draws them one by one, in this order
    artists = {"traces": trace_done, "lines": line_art, "links": link_art, "bodies": body_art,
               "circles": circle_art, "pins": pin_art, "centres": centre_art, "stamp": stamp}
    return Drawing(fig, artists, update)
