"""A progress bar for long runs: pass ``Progress(t0, t_end)`` as
``simulate(..., progress=...)``.

Nothing shows for the first second of wall time, so short runs stay quiet;
after that, a tqdm bar if tqdm is installed, or else one stderr line that
rewrites itself. Off when ``enabled`` is False or stderr is not a terminal.
"""

import shutil
import sys
import time


class Progress:
    """Callable progress(t) for simulate; close() when the run ends."""

    def __init__(self, t0, t_end, enabled=True, delay=1.0, stream=None, label=None, unit="s"):
        self.stream = sys.stderr if stream is None else stream
        # what t counts: seconds of a run ("s"), or items ("cases": a sweep's count)
        self.unit = unit
        # what is counted in t: the bar's "simulated" unless told (animate: "drawn")
        self.label = label
        isatty = getattr(self.stream, "isatty", None)
        self.enabled = bool(enabled) and isatty is not None and isatty()
        self.t0, self.t_end = float(t0), float(t_end)
        self.delay = delay
        self.start = time.monotonic()
        self._bar = None
        self._line = False
        self._shown = 0.0
        self._width = 0  # the longest line written (a shorter one pads over it)

    def __call__(self, t):
        if not self.enabled:
            return
        try:
            self._show(t)
        except Exception:  # noqa: BLE001 - a broken bar must not stop the run
            self.enabled = False

    def _show(self, t):
        elapsed = time.monotonic() - self.start
        if elapsed < self.delay:
            return
        span = max(self.t_end - self.t0, 1e-300)
        done = min(max(float(t) - self.t0, 0.0), span)
        if self._bar is None and not self._line:
            try:
                from tqdm import tqdm
            except ImportError:
                self._line = True
            else:
                self._shown = done
                # a size, for terminals that do not tell theirs (tqdm shows nothing in 0 x 0)
                size = shutil.get_terminal_size((80, 24))
                unit = "" if self.unit != "s" else " s"
                self._bar = tqdm(total=span, unit=self.unit, unit_scale=False, file=self.stream,
                                 desc=self.label or "simulated", leave=False, mininterval=0.0,
                                 ncols=size.columns, nrows=size.lines, initial=done,
                                 bar_format="{desc} {n:.4g}/{total:.4g}" + unit + " |{bar}| "
                                            "{percentage:3.0f}% [{elapsed}<{remaining}]")
        if self._bar is not None:
            self._bar.update(done - self._shown)
            self._shown = done
        else:
            label = f"{self.label}: " if self.label else ""
            if self.unit == "s":
                where = f"t = {self.t0 + done:.6g} of {self.t_end:.6g} s"
            else:
                where = f"{self.t0 + done:.0f} of {self.t_end:.0f} {self.unit}"
            text = (f"\r  {label}{where} ({100.0 * done / span:3.0f}%), {elapsed:.1f} s elapsed"
                    f"{_left(elapsed, done, span)} ")
            self._width = max(self._width, len(text))
            self.stream.write(text.ljust(self._width))
            self.stream.flush()

    def close(self):
        """Clear the bar (the summary that follows says how the run went)."""
        if self._bar is not None:
            self._bar.close()
            self._bar = None
        elif self._line:
            self.stream.write("\r" + " " * max(70, self._width) + "\r")
            self.stream.flush()
            self._line = False

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


def _left(elapsed, done, span):
    """", about 12 s left": the time still to go at the pace so far (a
    run's steps may speed up or slow down: an estimate, said as one);
    nothing before a tenth of the span is done (too early to tell)."""
    if not done >= 0.1 * span or done >= span:
        return ""
    left = elapsed * (span - done) / done
    if left < 90.0:
        return f", about {left:.0f} s left"
    if left < 5400.0:
        return f", about {left / 60.0:.0f} min left"
    return f", about {left / 3600.0:.1f} h left"

