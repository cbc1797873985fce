"""The matplotlib pieces every picture of lagmb.plotting uses: matplotlib
imported only when a picture is drawn (with the install hint when it is
missing), a Figure on an Agg canvas outside pyplot, writing it, colours and
legends."""

import os

from ..errors import extra_module


def load_matplotlib():
    """The matplotlib pieces used here, or MissingExtraError (an ImportError) naming the 'plot' extra."""
    extra_module("matplotlib", "plot", "lagmb plotting")
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    return Figure, FigureCanvasAgg


def load_pillow():
    """Pillow, which writes the GIFs, or MissingExtraError naming the 'plot' extra."""
    extra_module("PIL.Image", "plot", "lagmb plotting (a GIF)")


def new_figure(figsize, **kwargs):
    """A Figure on an Agg canvas, outside pyplot (closing it is dropping it)."""
    Figure, FigureCanvasAgg = load_matplotlib()
    fig = Figure(figsize=figsize, **kwargs)
    FigureCanvasAgg(fig)
    return fig


def save_figure(fig, path, **kwargs):
    path = os.fspath(path)
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    fig.savefig(path, **kwargs)


def cycle_colour(i):
    return f"C{i % 10}"


def add_legend(ax, title=None, handles=None, ncol=1):
    kwargs = {"handles": handles} if handles is not None else {}
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, fontsize=8,
              title=title, title_fontsize=8, frameon=False, ncol=ncol, **kwargs)
