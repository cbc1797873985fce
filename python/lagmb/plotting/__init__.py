"""Pictures of a run: time histories (plot_result) and a GIF of the mechanism
(animate); a GIF of a vibration mode of mb.modes (animate_mode); a still
picture of a spatial model's shapes (picture); response plots of a
parameter study (plot_sweep).

matplotlib is an optional extra (``pip install 'lagmb[plot]'``); it is imported
only when a function here is called, so ``import lagmb`` never needs it.
Figures are drawn on matplotlib's Agg canvas without pyplot: nothing here
changes the backend or the figure registry of the caller's session.

    from lagmb.plotting import plot_result, animate
    plot_result(r, "run.png")
    animate(r, "run.gif", trace=[("coupler", (0.0, 0.5))])

One module per picture: history (plot_result), animation (animate, drawn
by planar or spatial), modes (animate_mode), pictures (picture), sweeps
(plot_sweep); frames plans and writes the GIFs and _figures holds the
matplotlib set-up they share. What a drawing shows of the model is
lagmb._drawing (shared with the browser viewer)."""

from .._drawing import trace_points
from .animation import animate
from .history import plot_result
from .modes import animate_mode
from .pictures import picture
from .sweeps import plot_sweep

__all__ = ["animate", "animate_mode", "picture", "plot_result", "plot_sweep", "trace_points"]
