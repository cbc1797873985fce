"""Response plots of a parameter study (plot_sweep): each output against
the varied parameters, as lines, bands, points or a heat map."""

import os

import numpy as np

from ._figures import cycle_colour, new_figure, add_legend, load_matplotlib, save_figure

_SWEEP_RECORDS = ("status", "warnings", "steps", "wall_time", "q")  # what every case records
_SWEEP_LINES = 8  # values of a second parameter drawn as lines; more: a heat map


def sweep_outputs(ds, outputs=None):
    """The outputs plot_sweep draws: those named (checked), else every
    output with one number per case."""
    def scalar(name):
        return ds[name].dims == ("case",) and np.issubdtype(ds[name].dtype, np.number)

    found = [name for name in ds.data_vars if name not in _SWEEP_RECORDS and scalar(name)]
    if outputs is None:
        if not found:
            raise ValueError("plot_sweep: the study has no outputs to draw (mb.sweep's outputs=, lagmb sweep's "
                             "--output)")
        return found
    outputs = [outputs] if isinstance(outputs, str) else list(outputs)
    if not outputs:
        raise ValueError("plot_sweep: outputs is empty; give the names of outputs to draw, or None for all")
    for name in outputs:
        if name not in ds.data_vars or name in ("status", "warnings", "q"):
            raise ValueError(f"plot_sweep: no output {name!r}; the study's outputs are "
                             f"{', '.join(found) or 'none'} (and steps, wall_time)")
        if not scalar(name):
            raise ValueError(f"plot_sweep: {name!r} is not one number per case (dimensions {ds[name].dims})")
    return outputs


class _Varied:
    """A parameter of a study: its values per case, its distinct values in
    order and where each goes on an axis (numbers as they are, else in
    order: a text such as a method's name)."""

    def __init__(self, name, values, unit=None):
        self.name = name
        self.label = f"{name} ({unit})" if unit else name
        self.numeric = np.issubdtype(values.dtype, np.number)
        if self.numeric:
            self.values = values.astype(float)
            self.distinct = sorted(set(self.values[np.isfinite(self.values)].tolist()))
        else:
            self.values = np.array([str(v) for v in values], dtype=object)
            self.distinct = sorted(set(self.values.tolist()))
        self.log = (self.numeric and len(self.distinct) > 2 and self.distinct[0] > 0
                    and self.distinct[-1] / self.distinct[0] >= 100.0)

    def positions(self, values=None):
        values = self.values if values is None else values
        if self.numeric:
            return np.asarray(values, dtype=float)
        index = {v: i for i, v in enumerate(self.distinct)}
        return np.array([index.get(v, np.nan) for v in values], dtype=float)

    def text(self, v):
        return f"{v:.4g}" if self.numeric else str(v)

    def axis(self, ax, which="x"):
        """Label (and scale, or the texts' ticks) of the x or y axis."""
        getattr(ax, f"set_{which}label")(self.label)
        if self.log:
            getattr(ax, f"set_{which}scale")("log")
        if not self.numeric:
            getattr(ax, f"set_{which}ticks")(range(len(self.distinct)), [str(v) for v in self.distinct])


def _sweep_parameters(ds):
    """([_Varied, ...] in the grid's order, {name: value} of the parameters
    with one value in every case)."""
    import json

    grid = json.loads(ds.attrs.get("grid") or "[]")
    names = [g[0] for g in grid if g[0] in ds.coords]
    names += [c for c in ds.coords if c not in names and c != "case" and ds[c].dims == ("case",)]
    varied, fixed = [], {}
    for name in names:
        p = _Varied(name, ds[name].values, ds[name].attrs.get("units"))
        if len(p.distinct) > 1:
            varied.append(p)
        elif p.distinct:
            fixed[name] = p.text(p.distinct[0])
    return varied, fixed


def _sweep_label(name, unit=None):
    """An axis label for an output, with its unit: the one the sweep
    recorded (attrs["units"]), else from the name lagmb sweep gave it."""
    if unit:
        return f"{name} ({unit})"
    if name.startswith("peak_reaction_"):
        return f"{name} (N)"
    if name == "energy_drift":
        return f"{name} (J)"
    if name == "wall_time":
        return f"{name} (s)"
    if name.startswith("final_"):
        coordinate = name[len("final_"):]
        rate = coordinate.startswith("der(")
        which = coordinate.rstrip(")").rpartition(".")[2]
        unit = {"x": "m", "y": "m", "z": "m", "angle": "rad"}.get(which)
        if unit:
            return f"{name} ({unit}/s)" if rate else f"{name} ({unit})"
    return name


def plot_sweep(ds, path=None, outputs=None, *, dpi=120):
    """Response plots of a parameter study (``mb.sweep``'s Dataset, or the
    path of its store): one subplot per output, one under the other.

    Against the one varied parameter: a line. Two varied parameters: a line
    against the first for each value of the second (up to 8 values; else
    the parameter with fewer values makes the lines, and with more than 8
    of each a heat map of the grid). More than two: against the first, a
    line through the mean over the others and a band from their minimum to
    their maximum (named in the title). A study that is not a grid (a table
    or a design) with two or more varied parameters: points against the
    first, coloured by the second. Parameters with one value in every case
    are noted in the title; a parameter spanning a factor of 100 or more
    (rtol) gets a log axis.

    ``outputs``: the outputs to draw (names of the Dataset's variables),
    default every output with one number per case (``steps`` and
    ``wall_time`` may be asked for). Failed cases (``status`` not "ok")
    are left out of the lines and counted in the title.

    Returns the matplotlib Figure (drawn on the Agg canvas, outside
    pyplot). With ``path``, the figure is also written there, its format
    from the extension (.png, .pdf, .svg, ...).
    """
    if isinstance(ds, (str, os.PathLike)):
        from ..studies import open_store

        ds = open_store(ds)
    if "case" not in ds.dims or "status" not in ds:
        raise ValueError("plot_sweep: not a parameter study: give mb.sweep's Dataset or the path of its store")
    names = sweep_outputs(ds, outputs)
    load_matplotlib()
    varied, fixed = _sweep_parameters(ds)
    ok = ds["status"].values == "ok"
    n = ds.sizes["case"]
    grid = bool(ds.attrs.get("grid"))

    heat = False
    if len(varied) == 2 and grid:
        first, second = varied
        if len(second.distinct) > _SWEEP_LINES:
            if len(first.distinct) <= _SWEEP_LINES:
                varied = [second, first]  # the one with fewer values makes the lines
            else:
                heat = True
    fig = new_figure((8.5, 1.3 + (2.9 if heat else 2.4) * len(names)), constrained_layout=True)
    if hasattr(fig, "get_layout_engine"):
        fig.get_layout_engine().set(w_pad=0.1, h_pad=0.06)
    axes = fig.subplots(len(names), 1, sharex=True, squeeze=False)[:, 0]
    note = ""
    for k, (ax, name) in enumerate(zip(axes, names)):
        y = np.asarray(ds[name].values, dtype=float)
        use = ok & np.isfinite(y)
        if not varied:
            ax.plot(ds["case"].values[use], y[use], "o", ms=5, color=cycle_colour(0))
            ax.set_xlabel("case")
        elif len(varied) == 1 or (len(varied) == 2 and grid and not heat):
            note = _sweep_lines(ax, varied, y, use, legend=k == 0)
        elif heat:
            _sweep_heat(fig, ax, varied, y, use, name, ds[name].attrs.get("units"))
        elif grid:
            note = _sweep_band(ax, varied, y, use, legend=k == 0)
        else:
            note = _sweep_points(fig, ax, varied, y, use, name)
        if not heat:
            ax.set_ylabel(_sweep_label(name, ds[name].attrs.get("units")))
            _sweep_flat(ax, y[use])
            ax.grid(alpha=0.3)
    if varied:
        varied[0].axis(axes[-1])
    failed = int((~ok).sum())
    if grid:
        shape = " x ".join(f"{p.name} ({len(p.distinct)})" for p in varied)
    else:  # a table or a design: its values are not a grid's
        shape = ", ".join(p.name for p in varied) + (" varied" if varied else "")
    shape = shape or "no parameter varied"
    lines = [f"lagmb sweep: {n:,} case{'' if n == 1 else 's'}, {shape}",
             "all ok" if not failed else f"{failed:,} failed case{'' if failed == 1 else 's'} left out"]
    if note:
        lines[1] += f"; {note}"
    if fixed:
        lines.append(", ".join(f"{name} = {value}" for name, value in fixed.items()))
    fig.suptitle("\n".join(lines), fontsize=10)
    if path is not None:
        save_figure(fig, path, dpi=dpi)
    return fig


def _sweep_lines(ax, varied, y, use, legend):
    """y against the first parameter: one line, or one per value of the second."""
    first = varied[0]
    x = first.positions()
    if len(varied) == 1:
        order = np.argsort(x[use], kind="stable")
        ax.plot(x[use][order], y[use][order], "o-", ms=3.5, lw=1.5, color=cycle_colour(0))
        return ""
    second = varied[1]
    for i, v in enumerate(second.distinct):
        mask = use & (second.values == v)
        if not mask.any():
            continue  # every case failed: not in the legend either
        order = np.argsort(x[mask], kind="stable")
        ax.plot(x[mask][order], y[mask][order], "o-", ms=3.5, lw=1.5, color=cycle_colour(i), label=second.text(v))
    if legend:
        add_legend(ax, title=second.label)
    return ""


def _sweep_band(ax, varied, y, use, legend):
    """y against the first parameter: the mean over the other parameters'
    values and the band from the least to the largest."""
    first = varied[0]
    x = first.positions()
    xs, mean, low, high = [], [], [], []
    for v in first.positions(first.distinct):
        mask = use & (x == v)
        if mask.any():
            xs.append(v), mean.append(y[mask].mean()), low.append(y[mask].min()), high.append(y[mask].max())
    ax.fill_between(xs, low, high, color=cycle_colour(0), alpha=0.2, lw=0, label="min to max")
    ax.plot(xs, mean, "o-", ms=3.5, lw=1.5, color=cycle_colour(0), label="mean")
    others = ", ".join(p.name for p in varied[1:])
    if legend:
        add_legend(ax, title=f"over {others}")
    return f"mean and range over {others}"


def _sweep_points(fig, ax, varied, y, use, name):
    """y against the first parameter, a point per case coloured by the second."""
    first, second = varied[0], varied[1]
    from matplotlib.colors import LogNorm

    colours = second.positions()
    dots = ax.scatter(first.positions()[use], y[use], c=colours[use], s=14, cmap="viridis",
                      norm=LogNorm() if second.log else None)
    bar = fig.colorbar(dots, ax=ax, pad=0.01)
    bar.set_label(second.label)
    if not second.numeric:
        bar.set_ticks(range(len(second.distinct)), labels=[str(v) for v in second.distinct])
    others = ", ".join(p.name for p in varied[2:])
    return f"also varied: {others}" if others else ""


def _sweep_heat(fig, ax, varied, y, use, name, unit):
    """The grid of two parameters as a heat map of y."""
    first, second = varied
    xs, ys = first.positions(first.distinct), second.positions(second.distinct)
    z = np.full((len(ys), len(xs)), np.nan)
    col = {v: i for i, v in enumerate(xs)}
    row = {v: j for j, v in enumerate(ys)}
    for xv, yv, value in zip(first.positions()[use], second.positions()[use], y[use]):
        z[row[yv], col[xv]] = value
    mesh = ax.pcolormesh(xs, ys, np.ma.masked_invalid(z), shading="nearest", cmap="viridis")
    bar = fig.colorbar(mesh, ax=ax, pad=0.01)
    bar.set_label(_sweep_label(name, unit))
    second.axis(ax, "y")
    ax.set_title(name, fontsize=9)


def _sweep_flat(ax, y):
    """An output the parameters do not change (to round-off) is drawn flat
    about its value, not as round-off magnified around an offset."""
    if not len(y):
        return
    low, high = float(y.min()), float(y.max())
    middle = 0.5 * (low + high)
    if high - low <= 1e-9 * max(abs(middle), 1e-300):
        pad = 0.05 * abs(middle) or 1.0
        ax.set_ylim(middle - pad, middle + pad)
        ax.ticklabel_format(axis="y", useOffset=False)
