"""The drawing of a spatial run's frames in perspective (mplot3d): bodies
with shapes (a robot's meshes) as those shapes, shaded; the others as lines
to their attachment points, their inertia boxes and turning axes; over the
floor a plane shape on the ground makes."""

import numpy as np

from ._figures import cycle_colour, new_figure
from .frames import Drawing, speed_words, time_format

_TRIAD_COLOURS = ("#d62728", "#2ca02c", "#1f77b4")  # body axes x, y, z: red, green, blue
_POKE = 1.2  # a body's axes reach this far past its inertia box
_LIGHT = np.array([0.4, -0.5, 0.8]) / np.linalg.norm([0.4, -0.5, 0.8])  # as picture() lights shapes


def _body_shapes(model, bodies):
    """{body: (k, 3, 3) triangles in its own axes} of the shapes drawn in
    its place (the collision role where the model has drawable collision
    shapes, else the visual: a URDF's meshes), and the ground's, not its
    planes (a floor). Polygons of more than 3 corners are fanned into
    triangles; meshes lagmb does not read (not STL) are left out."""
    from .._drawing import shape_faces

    faces = [(sh, shape_faces(sh)) for sh in getattr(model, "shapes", []) if sh.kind != "plane"]  # (read once)
    drawable = {role: [(sh, f) for sh, f in faces if sh.role == role and f is not None]
                for role in ("collision", "visual")}
    chosen = drawable["collision"] or drawable["visual"]
    out = {}
    for sh, shape_faces_ in chosen:
        if sh.body != "ground" and sh.body not in bodies:
            continue
        R, r = np.asarray(sh.rotation, dtype=float), np.asarray(sh.position, dtype=float)
        triangles = []
        for face in shape_faces_:
            face = np.asarray(face, dtype=float)
            triangles += [face[[0, i, i + 1]] for i in range(1, len(face) - 1)]
        if triangles:
            out.setdefault(sh.body, []).append(r + np.array(triangles) @ R.T)
    return {b: np.concatenate(parts) for b, parts in out.items()}


def _shaded(triangles, rgb):
    """Face colours: the body's colour darkened by each triangle's facing away from the light."""
    n = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    facing = np.abs(n @ _LIGHT) / np.maximum(np.linalg.norm(n, axis=1), 1e-300)
    colours = np.empty((len(triangles), 4))
    colours[:, :3] = np.asarray(rgb)[None, :] * (0.45 + 0.55 * facing)[:, None]
    colours[:, 3] = 1.0
    return colours


def _box_edges(corners):
    """(36, 3) the 12 edges of a box with corners (8, 3) (index bits z y x)
    as one polyline, NaN between edges."""
    pairs = [(a, b) for a in range(8) for b in range(a + 1, 8) if bin(a ^ b).count("1") == 1]
    gap = np.full(3, np.nan)
    return np.array([p for a, b in pairs for p in (corners[a], corners[b], gap)])


def spatial_drawing(scene, shown, trace, size, dpi, view, speed):
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
    solids = _body_shapes(result.model, scene.bodies)  # drawn as their shapes, not as lines and boxes
    outlines = {b: ([] if b in solids else scene.drawn_outline(b)) + [p for tb, p in trace if tb == b]
                for b in scene.bodies}
    centres = {b: shown.body(b).position for b in scene.bodies}
    spokes = {b: [scene.path(b, p, result=shown) for p in outlines[b]] for b in scene.bodies}
    rotations = {b: getattr(shown.body(b), "rotation", None) for b in scene.bodies}
    corners = {b: scene.box(b) for b in scene.bodies if rotations[b] is not None and b not in solids}
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
    for b, triangles in solids.items():  # each body's shapes: its path widened by their reach
        if b == "ground":
            everywhere.append(triangles.reshape(-1, 3))
            continue
        reach = float(np.max(np.linalg.norm(triangles.reshape(-1, 3), axis=1)))
        path_ = result.body(b).position
        everywhere += [path_ - reach, path_ + reach]
    clouds = everywhere + list(centres.values()) + [s for paths in spokes.values() for s in paths] + traces \
        + joints + [p for link in links for p in link] + [np.asarray(p)[None, :] for p in supports]
    pts = np.concatenate([np.asarray(c).reshape(-1, 3) for c in clouds]) if clouds else np.zeros((1, 3))
    pts = pts[np.isfinite(pts).all(axis=1)]
    centre = 0.5 * (pts.min(axis=0) + pts.max(axis=0)) if len(pts) else np.zeros(3)
    half = 0.55 * max(float(np.max(np.ptp(pts, axis=0))) if len(pts) else 0.0, 1e-3)
    # the body axes drawn: poking out of the box along them, at least a 25th of the scene
    turning = [b for b in scene.bodies if rotations[b] is not None and b not in solids]
    triad = {b: np.maximum(0.08 * half, _POKE * np.abs(corners[b]).max(axis=0) if b in corners else 0.0)
             for b in turning}

    fig = new_figure((size[0] / dpi, size[1] / dpi), dpi=dpi)
    ax = fig.add_subplot(projection="3d")
    ax.view_init(elev=elevation, azim=azimuth)
    for axis, set_lim, label in zip(range(3), (ax.set_xlim, ax.set_ylim, ax.set_zlim), "xyz"):
        set_lim(centre[axis] - half, centre[axis] + half)
        getattr(ax, f"set_{label}label")(f"{label} (m)")
    if hasattr(ax, "set_box_aspect"):
        ax.set_box_aspect((1, 1, 1))
    ax.set_title(f"lagmb: {scene.heading()}{speed_words(speed)}", fontsize=10)
    floors = [sh for sh in getattr(result.model, "shapes", []) if sh.body == "ground" and sh.kind == "plane"]
    if floors:  # a plane on the ground: a floor under everything (drawn first, whatever its depth)
        from mpl_toolkits.mplot3d.art3d import Poly3DCollection

        from .._drawing import shape_faces

        ax.computed_zorder = False
        floor_faces = []
        for floor in floors:
            R, r = np.asarray(floor.rotation, dtype=float), np.asarray(floor.position, dtype=float)
            faces = [r + f @ R.T for f in shape_faces(floor, half=0.9 * half, centre=(R.T @ (centre - r))[:2])]
            floor_faces += faces
            ax.add_collection3d(Poly3DCollection(faces, facecolors=[(0.82, 0.82, 0.80, 0.6)], edgecolors="0.6",
                                                 zorder=0))
    solid_art = None
    if solids:
        from matplotlib.colors import to_rgb
        from mpl_toolkits.mplot3d.art3d import Poly3DCollection

        if "ground" in solids:  # the ground's shapes stay where they are
            still = solids["ground"]
            ax.add_collection3d(Poly3DCollection(list(still), facecolors=_shaded(still, to_rgb("0.6")),
                                                 edgecolors="none"))
        moving = [b for b in scene.bodies if b in solids]
        tint = {b: to_rgb(cycle_colour(scene.bodies.index(b))) for b in moving}
        # one collection for all the bodies' triangles: mplot3d orders polygons by depth within one
        solid_art = Poly3DCollection([np.zeros((3, 3))], edgecolors="none")
        ax.add_collection3d(solid_art)
    if supports:
        s = np.array(supports, dtype=float)
        ax.plot(s[:, 0], s[:, 1], s[:, 2], "^", ms=9, color="0.75", mec="0.2")
    trace_colours = [cycle_colour(scene.bodies.index(b)) if b in scene.bodies else "k" for b, _ in trace]
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
    box_art = {b: ax.plot([], [], [], color=cycle_colour(scene.bodies.index(b)), lw=1.0, alpha=0.8)[0]
               for b in boxes}
    body_art = [ax.plot([], [], [], color=cycle_colour(i), lw=4, solid_capstyle="round")[0]
                for i, _ in enumerate(scene.bodies)]
    triad_art = [ax.plot([], [], [], color=c, lw=1.6)[0] for c in _TRIAD_COLOURS] if turning else []
    centre_art = ax.plot([], [], [], "o", ms=3.5, color="0.1")[0]
    joint_art = ax.plot([], [], [], "o", ms=5.5, mfc="white", mec="0.15", mew=1.2)[0]
    stamp = ax.text2D(0.02, 0.97, "", transform=ax.transAxes, ha="left", va="top", fontsize=9,
                      family="monospace")
    stamp_format = time_format(t)

    now = {}  # what the last update placed (for tests)

    def update(k):
        if solid_art is not None:
            placed = [centres[b][k] + solids[b] @ rotations[b][k].T for b in moving]
            triangles = np.concatenate(placed)
            now["triangles"] = triangles
            solid_art.set_verts(list(triangles))
            solid_art.set_facecolor(np.concatenate([_shaded(p, tint[b]) for p, b in zip(placed, moving)]))
            # mplot3d projects collections when the axes draw, not when blitted (and before a
            # first draw there is no projection to apply)
            if getattr(ax, "M", None) is not None:
                solid_art.do_3d_projection()
        for b, art in zip(scene.bodies, body_art):
            c = centres[b][k]
            xyz = np.array([c] + [p for s in spokes[b] for p in (s[k], c)]) if spokes[b] else c[None, :]
            if b in solids:  # (its shapes show it)
                xyz = np.empty((0, 3))
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

    artists = {"traces": trace_done, "links": link_art, "boxes": list(box_art.values()),
               "solids": [solid_art] if solid_art is not None else [], "bodies": body_art,
               "triad": triad_art, "centres": centre_art, "joints": joint_art, "stamp": stamp}
    drawing = Drawing(fig, artists, update)
    drawing.triad_lengths = triad  # {body: (3,) m}
    drawing.now = now  # {"triangles": (k, 3, 3) m} the shapes as the last frame placed them
    drawing.floors = floor_faces if floors else []  # [(4, 3)] the floors' squares (m)
    return drawing
