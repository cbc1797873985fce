"""A looping GIF of one vibration mode of mb.modes (animate_mode): the
equilibrium moved along the mode's shape, drawn as animate draws a run."""

import math
import os

import numpy as np

from .._drawing import Scene, counted, mode_amplitude, posed
from ..errors import ModelError
from ._figures import load_matplotlib, load_pillow
from .frames import MAX_FPS, checked_setting, write_gif
from .planar import planar_drawing
from .spatial import spatial_drawing

_MODE_CYCLE = 2.0     # s: a cycle of a mode plays in 2 s (at the default frames), whatever its frequency


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
    from ..linear import Modes

    load_matplotlib()
    load_pillow()  # there before anything is drawn
    if not isinstance(modes, Modes):
        raise ModelError(f"animate_mode: modes must be what mb.modes(model) returns, got {type(modes).__name__}")
    count = len(modes)
    if isinstance(index, bool) or not isinstance(index, (int, np.integer)) or not 0 <= index < count:
        which = f"0 .. {count - 1}" if count else "none: nothing can move"
        raise ModelError(f"animate_mode: index {index!r}: there {'is' if count == 1 else 'are'} "
                         f"{counted(count, 'mode')} ({which})")
    index = int(index)
    fps = checked_setting("animate_mode: fps", fps, 0.0, MAX_FPS)
    cycles = checked_setting("animate_mode: cycles", cycles, 0, whole=True)
    frames = int(round(cycles * _MODE_CYCLE * fps)) if frames is None \
        else checked_setting("animate_mode: frames", frames, 1, whole=True)
    frames = max(frames, 2)
    equilibrium = modes.equilibrium
    shape = np.asarray(modes.shapes[index], dtype=float)
    amplitude = mode_amplitude(equilibrium, shape) if amplitude is None \
        else checked_setting("animate_mode: amplitude", amplitude, 0.0)

    kind, omega, frequency = modes.kinds[index], float(modes.omega[index]), float(modes.frequencies[index])
    if kind == "rigid-body":  # its omega is round-off about 0
        frequency = 0.0
    phase = 2.0 * math.pi * cycles * np.arange(frames) / frames
    # a vibration mode at its own times (the stamp gives t in the cycle); the others by phase
    shown = posed(equilibrium, equilibrium.q + amplitude * np.sin(phase)[:, None] * shape[None, :],
                   phase / omega if kind == "vibration" else phase)
    scene = Scene(shown)
    if scene.dimension == 3:
        drawing = spatial_drawing(scene, shown, [], size, dpi, view, 1.0)
    else:
        drawing = planar_drawing(scene, shown, [], size, dpi, 1.0)
    title = f"mode {index}: {frequency:.4g} Hz ({kind})"
    if kind != "vibration":  # no time to stamp: the title says how it moves instead
        title += "\n" + ("it moves freely" if kind == "rigid-body" else f"it grows as exp({omega:.3g} t)") \
            + "; shown back and forth"
        drawing.artists["stamp"].set_visible(False)
    drawing.fig.axes[0].set_title(title, fontsize=10)
    ends = np.round(100.0 * np.arange(1, frames + 1) / fps)  # hundredths of a second, as animate counts
    durations = (10 * np.diff(np.concatenate(([0.0], ends)))).astype(int)
    if path is not None:
        return write_gif(drawing, path, durations)
    import tempfile

    with tempfile.TemporaryDirectory() as folder:
        written = write_gif(drawing, os.path.join(folder, "mode.gif"), durations)
        with open(written, "rb") as f:
            return f.read()
