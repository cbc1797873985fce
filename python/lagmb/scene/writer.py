"""Writing a scene file: scene_text and save_scene.

Every element of the model is written with all its arguments (the defaults
too), floats by repr, so that the file loads back into a model giving the
same results to the last bit; save_scene reads the text back before it
writes it.
"""

import os

import numpy as np

from .._version import __version__
from ..handles import name_of
from .reader import Reader, SceneError
from .schema import elements
from .values import NotWritable, show, toml_key, toml_string, toml_value


def _table_lines(header, table):
    lines = [header]
    for key, value in table.items():
        if value is None:
            continue
        try:
            lines.append(f"{toml_key(str(key))} = {toml_value(value)}")
        except NotWritable as e:
            raise SceneError(f"{show(value)} is {e}, which a scene file cannot hold",
                             table=header, key=key) from None
    return lines


def _shared_inputs(model):
    """{id(input): the name the model knows it by} for each unnamed mb.Input
    that feeds more than one place: the scene names it in each, so that it
    reads back as one input (the reader joins inputs by name)."""
    from ..functions import Input

    places = {}  # id -> (input, [(element, parameter)])
    for _, kwargs in model.elements:
        for param, value in kwargs.items():
            parts = value if isinstance(value, tuple) and len(value) in (2, 3) else (value,)
            for k, part in enumerate(parts):
                if isinstance(part, Input) and part.name is None:
                    parameter = param if len(parts) == 1 else f"{param}.{'xyz'[k]}"
                    places.setdefault(id(part), (part, []))[1].append((kwargs["name"], parameter))
    shared = {key: where for key, (_, where) in places.items() if len(where) > 1}
    if not shared:
        return {}
    core = {(d["element"], d["parameter"]): d["name"] for d in model.compiled().inputs}
    return {key: core[where[0]] for key, where in shared.items()}


def _named(value, names):
    """value with each shared unnamed input replaced by a named copy (for writing)."""
    from ..functions import Input

    if isinstance(value, Input) and id(value) in names:
        return Input(value.initial, names[id(value)])
    if type(value) is tuple:  # (a Shape, a tuple too, holds no inputs)
        return tuple(_named(v, names) for v in value)
    return value


def scene_text(model, settings=None, output=None):
    """The scene file of a model (and settings, output) as a string."""
    out = [f"# lagmb {__version__} scene", ""]
    gravity = getattr(model, "gravity", None)
    dimension = getattr(model, "dimension", 2)
    if gravity is not None or dimension != 2:
        out += ["[model]"] + ([f"dimension = {dimension}"] if dimension != 2 else [])
        out += ([f"gravity = {toml_value(tuple(gravity))}"] if gravity is not None else []) + [""]
    kinds = elements(dimension)
    shared = _shared_inputs(model)
    for method, kwargs in model.elements:
        name = kwargs.get("name")
        if method not in kinds:
            raise SceneError(f"cannot write element {name!r}: {method} has no scene table")
        element = kinds[method]
        table = element.table
        out.append(f"[[{table}]]")
        if element.type is not None:
            out.append(f"type = {toml_string(element.type)}")
        items = sorted(kwargs.items(), key=lambda kv: kv[0] != "name")
        for arg, value in items:
            if value is None:
                continue
            key = element.renamed.get(arg, arg)
            try:
                text = toml_value(_named(value, shared))
            except NotWritable as e:
                raise SceneError(
                    f"{method}: {e} cannot go in a scene file, which holds numbers and time "
                    "functions (mb.Constant, mb.Linear, mb.Polynomial, mb.Harmonic, "
                    "mb.SmoothStep, mb.Spline, mb.Input)", table=f"{table} {name!r}", key=key) from None
            out.append(f"{key} = {text}")
        out.append("")
    if settings:
        settings = {k: (list(np.asarray(v, dtype=float).reshape(-1)) if k == "t_out" else v)
                    for k, v in settings.items() if k != "progress"}
        if settings.get("t_out") is not None:
            settings.pop("n_out", None)  # simulate ignores it when t_out is given
        out += _table_lines("[simulation]", settings) + [""]
    if output:
        output = dict(output)
        for key, accepts in (("reactions", ("joint", "driver")), ("efforts", ("driver",))):
            if isinstance(output.get(key), (list, tuple)):  # names or handles
                output[key] = [name_of(model, x, accepts, f"{key} entry", "[output]")
                               for x in output[key]]
        out += _table_lines("[output]", output) + [""]
    return "\n".join(out)


def save_scene(model, path, settings=None, output=None):
    """Write a model as a scene file that load_scene reads back into a model
    giving the same results. ``settings``: mb.simulate keyword arguments for
    [simulation]; ``output``: the [output] table (reactions and efforts as
    names or handles). Raises SceneError (a ModelError) naming the element
    if something cannot be written, e.g. a Python callable as a time
    function; nothing is written then."""
    path = os.fspath(path)
    try:
        text = scene_text(model, settings, output)
        Reader(path, text).read()  # what is written must read back
    except SceneError as e:
        where = ", ".join(x for x in (e.table, e.key and f"key '{e.key}'") if x)
        error = SceneError(f"cannot write {path}: {where + ': ' if where else ''}{e.reason}")
        error.path, error.table, error.key = path, e.table, e.key
        raise error from None
    with open(path, "w", encoding="utf-8", newline="\n") as fh:
        fh.write(text)
