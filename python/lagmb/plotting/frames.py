"""The frames of an animation, shared by animate and animate_mode: their
times and durations (a GIF's 10 ms clock), the run resampled at them, the
settings checked, and the GIF written."""

import math
import os

import numpy as np

from .._checks import decimal
from .._drawing import unit_orientations
from ..errors import ModelError

DEFAULT_FPS = 25  # default frames per second: 40 ms a frame, four ticks of a GIF's 10 ms clock
MAX_FPS = 50   # GIF viewers show a frame of 10 ms for 100 ms: 20 ms is the shortest kept
MAX_FRAMES = 1000  # unless asked: Pillow holds every frame until the GIF is written (0.3 MB at 640 x 480)


def frame_plan(t, fps, speed, frames=None):
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
    n = min(n, int(math.floor(playing * MAX_FPS + 1e-9)))  # no frame shorter than 20 ms
    if frames is not None:
        n = min(n, int(frames))
    n = max(n, 1)
    times = t0 + span * np.arange(n) / n
    if n == 1:  # one picture: its duration does not matter
        return times, np.array([max(10 * round(100.0 / fps), 20)])
    ends = np.round(100.0 * playing * np.arange(1, n + 1) / n)  # hundredths of a second
    return times, (10 * np.diff(np.concatenate(([0.0], ends)))).astype(int)


def resample(result, times):
    """The result at the frame times, as a Result (q and v; a and lam zero):
    q by cubic Hermite interpolation between the outputs around each time
    (q and q' = v at both; exact at the outputs), linear where an event
    (impact) lies between them; each spatial body's Euler parameters
    normalised."""
    from ..result import Result

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
    unit_orientations(result.model, core, qf)
    lam = getattr(result, "_lam", np.zeros((len(t), 0)))
    raw = {"t": times, "q": qf, "v": vf, "a": np.zeros_like(qf), "lam": np.zeros((len(times), lam.shape[1])),
           "stats": result.stats}
    return Result(result.model, core, raw)


def time_format(times):
    dt = np.diff(times)
    dt = dt[dt > 0]
    digits = 2 if not len(dt) else int(np.clip(math.ceil(-math.log10(dt.min())) + 1, 2, 9))
    return f"t = {{:.{digits}f}} s"


def speed_words(speed):
    """What the title says of the speed: nothing in real time."""
    if speed == 1.0:
        return ""
    return f", played at {speed:.3g} × real time"


def checked_setting(name, value, low, high=None, whole=False):
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
        reason = " (GIF viewers show a frame shorter than 20 ms for 100 ms)" if high == MAX_FPS else ""
        shown = value if name.startswith("--") else repr(value)
        raise ModelError(f"{name} {shown}: must be {words}{reason}")
    return int(number) if whole else number


class Drawing:
    """A figure of a run's frames: ``update(k)`` sets the ``animated``
    artists to frame k; everything else is drawn once. ``artists`` names
    the animated ones (for tests)."""

    def __init__(self, fig, artists, update):
        self.fig, self.artists, self.update = fig, artists, update
        self.animated = [a for v in artists.values() for a in (v if isinstance(v, list) else [v])]


def write_gif(drawing, path, durations, progress=None):
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
