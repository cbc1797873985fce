"""A sweep's results as an ``xarray.Dataset`` indexed by case, with the
units of its variables and its grid (``as_grid`` reshapes it).
"""

import json
import numbers

import numpy as np

from ..errors import ModelError


def dataset(cases, records, names, outputs, grid, t_out, coordinate_names, indices=None, units=None):
    """The cases' records as an xarray.Dataset indexed by case; each varied
    parameter's and output's unit (``units``: {name: unit}) in its
    ``attrs["units"]``."""
    import xarray as xr

    indices = list(range(len(cases))) if indices is None else list(indices)
    k = len(indices)
    data = {
        "status": ("case", np.array([records[i]["status"] for i in indices], dtype=object)),
        "warnings": ("case", np.array([records[i]["warnings"] for i in indices], dtype=object)),
        "steps": ("case", np.array([records[i]["steps"] for i in indices], dtype=np.int64)),
        "wall_time": ("case", np.array([records[i]["wall_time"] for i in indices], dtype=float)),
    }
    for name in outputs:
        shape = next((records[i]["outputs"][name].shape for i in indices if name in records[i]["outputs"]), ())
        values = np.full((k,) + shape, np.nan)
        for row, i in enumerate(indices):
            v = records[i]["outputs"].get(name)
            if v is not None:
                if v.shape != shape:
                    raise ModelError(f"sweep: output {name!r} gave shape {v.shape} in case {i} and {shape} in "
                                     "another: an output must have one shape in every case")
                values[row] = v
        data[name] = (("case",) + tuple(f"{name}_dim{d}" for d in range(len(shape))), values)
    coords = {"case": np.array(indices, dtype=np.int64)}
    for name in names:
        column = [cases[i].get(name, np.nan) for i in indices]
        try:
            coords[name] = ("case", np.array(column, dtype=float))
        except (TypeError, ValueError):
            coords[name] = ("case", np.array([str(c) for c in column], dtype=object))
    if t_out is not None:
        coords["time"] = np.asarray(t_out, dtype=float)
        coords["coordinate"] = np.array(coordinate_names, dtype=object)
        q = np.full((k, len(t_out), len(coordinate_names)), np.nan)
        for row, i in enumerate(indices):
            h = records[i]["history"]
            if h is not None and h.shape[0] == len(t_out):
                q[row] = h
        data["q"] = (("case", "time", "coordinate"), q)
    ds = xr.Dataset(data, coords=coords)
    for name, unit in (units or {}).items():
        if unit and name in ds.variables:
            ds[name].attrs["units"] = unit
    ds.attrs["grid"] = grid_text(grid)
    return ds


def grid_text(grid):
    """A grid [(name, values), ...] as JSON, as a Dataset's attrs["grid"]
    and a store keep it (as_grid reads it); "" for cases of no grid."""
    return json.dumps([[name, [float(v) if isinstance(v, numbers.Real) else str(v) for v in values]]
                       for name, values in grid]) if grid else ""


def as_grid(ds):
    """A grid sweep's Dataset reshaped to its dimensions (one per varied
    parameter, in the order given), instead of indexed by case."""
    grid = json.loads(ds.attrs.get("grid") or "[]")
    if not grid:
        raise ModelError("sweep.as_grid: this sweep was not a grid (a table or a design has no dimensions)")
    names = [g[0] for g in grid]
    return ds.set_index(case=names).unstack("case")

