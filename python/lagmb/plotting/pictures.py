"""A still picture of a run at one output (picture): a spatial model with
its shapes (boxes, cylinders, spheres and STL meshes at the bodies' poses,
shaded), a planar one as animate draws its frames, with traced paths."""

import numpy as np

from .._checks import real, show, vec2
from .._drawing import Scene, shape_faces, trace_points
from ..errors import ModelError
from ._figures import cycle_colour, new_figure, load_matplotlib, save_figure
from .frames import resample
from .planar import planar_drawing


def picture(result, path, *, time=None, role="collision", view=(20.0, -50.0), size=(640, 640), dpi=100,
            title=None, trace=None):
    """A still picture of a model at one output of a run (``time``: the
    output nearest it; default the last), written to ``path`` (PNG).

    A planar model (dimension 2) is drawn as :func:`animate` draws a frame
    (bodies through their attachment points, joints, springs, contacts'
    circles and lines), with the paths of the ``trace`` points travelled
    until then (a body, an element, a (body, local point) pair or
    "body:x,y"; one or a list, as animate takes them); returns the number
    of bodies drawn. ``role`` and ``view`` do not apply to it.

    A spatial model (dimension 3): the shapes of ``role`` ("visual" or
    "collision"; Model.add_shape, as load_urdf keeps a robot's) at their
    bodies' poses, shaded by their facing to the light, each body in its
    colour, over the bodies' lines to their joints (as animate draws them),
    seen from ``view`` = (elevation, azimuth) in degrees. Meshes are drawn
    from STL files; a shape in another format (COLLADA .dae, OBJ) is left
    out and counted in the caption. Returns the number of shapes drawn;
    ``trace`` is for planar models only."""
    model = result.model
    if getattr(model, "dimension", 2) != 3:
        return _planar_picture(result, path, time, size, dpi, title, trace)
    if trace is not None:
        raise ModelError("plotting.picture: trace draws paths in planar pictures; this model is spatial")
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    if role not in ("visual", "collision"):
        raise ModelError(f"plotting.picture: role must be 'visual' or 'collision', got {show(role)}")
    view = vec2(view, "plotting.picture: view (elevation, azimuth in degrees)")
    t = np.asarray(result.t)
    k = len(t) - 1 if time is None else int(np.argmin(np.abs(t - real(time, "plotting.picture: time"))))
    scene = Scene(result)
    fig = new_figure((size[0] / dpi, size[1] / dpi), dpi=dpi)
    ax = fig.add_subplot(projection="3d")
    ax.view_init(elev=float(view[0]), azim=float(view[1]))
    light = np.array([0.4, -0.5, 0.8]) / np.linalg.norm([0.4, -0.5, 0.8])
    drawn, skipped, points = 0, 0, []
    bodies = list(scene.bodies)
    for b in bodies:  # (where the bodies are: a plane's floor spans them)
        points.append(np.asarray(result.body(b).position[k])[None, :])
    shapes = [sh for sh in model.shapes if sh.role == role]
    planes = [sh for sh in shapes if sh.kind == "plane"]
    if planes:  # drawn floor first, then the shapes by their height (up: against gravity)
        ax.computed_zorder = False
        g = np.asarray(getattr(model, "gravity", None) or (0.0, 0.0, -1.0), dtype=float)
        up = -g / np.linalg.norm(g) if np.linalg.norm(g) > 0 else np.array([0.0, 0.0, 1.0])
    for shape in [sh for sh in shapes if sh.kind != "plane"] + planes:  # (the planes after: they span the rest)
        if shape.kind == "plane":
            pts = np.concatenate(points) if points else np.zeros((1, 3))
            middle = 0.5 * (pts.min(axis=0) + pts.max(axis=0))
            under = np.asarray(shape.rotation).T @ (middle - np.asarray(shape.position))  # (a plane is on the ground)
            faces = shape_faces(shape, half=0.6 * max(float(np.max(np.ptp(pts, axis=0))), 0.1), centre=under[:2])
        else:
            faces = shape_faces(shape)
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
        base = np.array(_rgb(cycle_colour(bodies.index(shape.body)) if shape.body in bodies else
                             "0.85" if shape.kind == "plane" else "0.6"))
        colours = [(*(base * (0.45 + 0.55 * s)), 1.0) for s in shade]
        # one collection per polygon size: matplotlib pads ragged polygons (a
        # cylinder's caps beside its side quads) with unset values that its
        # autoscaling read as limits (seen once: an infinite z limit)
        for count in sorted({len(f) for f in world}):
            picked = [i for i, f in enumerate(world) if len(f) == count]
            polygons = Poly3DCollection([world[i] for i in picked], facecolors=[colours[i] for i in picked],
                                        edgecolors="none")
            if planes:  # (mplot3d orders whole collections by depth: a floor would cover what stands on it)
                polygons.set_zorder(0.0 if shape.kind == "plane" else
                                    1.0 + float(np.mean([world[i] for i in picked], axis=(0, 1)) @ up))
            ax.add_collection3d(polygons)
        if world and shape.kind != "plane":  # (an STL of no triangles draws nothing; a floor sets no limits)
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
    ax.set_title(title or f"lagmb: {scene.heading()}", fontsize=10)
    ax.text2D(0.02, 0.02, caption, transform=ax.transAxes, fontsize=8)
    save_figure(fig, path)
    return drawn


def _planar_picture(result, path, time, size, dpi, title, trace):
    """picture() of a planar model: animate's drawing of one frame, at the
    output nearest ``time``, the traced paths up to it."""
    load_matplotlib()
    t = np.asarray(result.t)
    if len(t) == 0:
        raise ModelError("plotting.picture: the result has no outputs")
    k = len(t) - 1 if time is None else int(np.argmin(np.abs(t - real(time, "plotting.picture: time"))))
    scene = Scene(result)
    traced = trace_points(result.model, trace, "plotting.picture: trace")
    drawing = planar_drawing(scene, resample(result, t[k:k + 1]), traced, size, dpi, 1.0)
    drawing.update(0)
    if title:
        drawing.fig.axes[0].set_title(title, fontsize=10)
    save_figure(drawing.fig, path)
    return len(scene.bodies)


def _rgb(colour):
    from matplotlib.colors import to_rgb

    return to_rgb(colour)
