"""A GIF of a run (animate): the frames planned, then drawn in the plane
(planar.py) or in space (spatial.py)."""

import numpy as np

from .._drawing import Scene, trace_points
from ..errors import ModelError
from ._figures import load_matplotlib, load_pillow
from .frames import DEFAULT_FPS, MAX_FPS, MAX_FRAMES, checked_setting, frame_plan, resample, write_gif
from .planar import planar_drawing
from .spatial import spatial_drawing

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
    fixed to the ground; a contact (add_contact) is drawn as its circle, in
    its body's colour, and its line, grey, each moving with its body. The
    axes are fixed to cover the whole motion, with equal scales, in m.

    A spatial model (dimension 3) is drawn in perspective by matplotlib's
    mplot3d, seen from ``view`` = (elevation, azimuth) in degrees. A body
    with shapes (Model.add_shape; a URDF robot's meshes, STL: the collision
    shapes where the model has them, else the visual) is drawn as those
    shapes, shaded; any other body as lines from its centre of mass to its
    attachment points, the edges of its inertia box (the uniform box with
    its mass and inertia) and its axes (x red, y green, z blue, reaching a
    fifth past the box), which turn with it, so that spin and orientation
    show.

    ``trace``: points whose paths are drawn as they are travelled (faint
    ahead): a body (its centre of mass), an element (a joint: where it is),
    a (body, local point) pair or "body:x,y" (see trace_points); one or a
    list. A traced (body, point) also joins its body's shape. ``size`` is
    the picture in pixels. Returns the path written.
    """
    load_matplotlib()
    load_pillow()  # there before anything is drawn
    if max_frames is not None:
        if frames is not None:
            raise ModelError("animate: give frames or its old name max_frames, not both")
        frames = max_frames
    fps = DEFAULT_FPS if fps is None else checked_setting("animate: fps", fps, 0.0, MAX_FPS)
    if speed is not None:
        speed = checked_setting("animate: speed", speed, 0.0)
    frames = MAX_FRAMES if frames is None else checked_setting("animate: frames", frames, 0, whole=True)
    t = np.asarray(result.t)
    if len(t) == 0:
        raise ModelError("animate: the result has no outputs")
    if speed is None:  # real time, or 1 s for a shorter run
        span = float(t[-1] - t[0])
        speed = span if 0.0 < span < 1.0 else 1.0
    scene = Scene(result)
    trace = trace_points(result.model, trace)
    times, durations = frame_plan(t, fps, speed, frames)
    shown = resample(result, times)
    if scene.dimension == 3:
        drawing = spatial_drawing(scene, shown, trace, size, dpi, view, speed)
    else:
        drawing = planar_drawing(scene, shown, trace, size, dpi, speed)
    from ..progress import Progress

    with Progress(times[0], t[-1], enabled=bool(progress), label="drawn") as bar:
        return write_gif(drawing, path, durations, lambda k: bar(times[k]))
