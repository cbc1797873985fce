"""Reading a scene file: load_scene, Scene, SceneElement and SceneError.

The reader checks the parsed TOML against the schema (schema.py), value by
value, and builds the model by calling the Model method of each element in
file order; every error names the file, the line (lines.py), the table and
the key.
"""

import math
import os
import re
import shutil
import sys

try:  # Python 3.11+
    import tomllib as _toml
except ImportError:  # pragma: no cover - older Pythons
    import tomli as _toml

from ..errors import ModelError
from ..model import Model
from .lines import Lines
from .schema import (BODY, BOOL, CHOICES, ELEMENT_TABLES, FUNCTION, FUNCTION_PAIR, FUNCTION_TRIPLE,
                     INERTIA, INTEGER, JOINT, SHAPE, MAX_NESTING, MAX_OUTPUTS, MAX_SCENE_BYTES, MAX_STEPS,
                     NUMBER, NUMBERS, ORIENTATION, OUTPUT_FILE_TYPES, SETTINGS, STRING, STRINGS,
                     TABLES, VEC2, VEC3, VECTOR, elements, methods)
from .values import show, toml_type


class SceneError(ModelError):
    """A scene file that cannot make a model (a ModelError, so a ValueError).

    Attributes: path (the file), line (1-based, or None), table (e.g.
    ``"joints[2] 'pin'"``), key (or None); the message names all of them.
    """

    def __init__(self, message, path=None, line=None, table=None, key=None):
        where = []
        if path is not None:
            where.append(str(path))
        if line is not None:
            where.append(f"line {line}")
        what = table or ""
        if key is not None:
            what = f"{what}, key '{key}'" if what else f"key '{key}'"
        text = ", ".join(where)
        if what:
            text = f"{text}: {what}" if text else what
        super().__init__(f"{text}: {message}" if text else message)
        self.path, self.line, self.table, self.key = path, line, table, key
        self.reason = message


class _Where:
    """Where a table is, to name it in errors."""

    def __init__(self, path, lines, table_path, label, inputs=None):
        self.path, self.lines, self.table_path, self.label = path, lines, tuple(table_path), label
        self.inputs = {} if inputs is None else inputs  # the scene's named inputs: name -> mb.Input

    def line(self, key=None):
        return self.lines.line(self.table_path + ((key,) if key is not None else ()))

    def error(self, message, key=None):
        return SceneError(message, self.path, self.line(key), self.label, key)


def _number(where, key, value):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise where.error(f"must be a number, got {toml_type(value)} ({show(value)})", key)
    return _float(where, key, value)


def _float(where, key, value):
    try:
        return float(value)
    except OverflowError:
        raise where.error(f"{show(value)} is too large for a float (at most about 1.8e308)",
                          key) from None


def _integer(where, key, value):
    if isinstance(value, bool) or not isinstance(value, int):
        raise where.error(f"must be an integer, got {toml_type(value)} ({show(value)})", key)
    return value


def _string(where, key, value):
    if not isinstance(value, str):
        raise where.error(f"must be a string, got {toml_type(value)} ({show(value)})", key)
    return value


def _bool(where, key, value):
    if not isinstance(value, bool):
        raise where.error(f"must be true or false, got {toml_type(value)} ({show(value)})", key)
    return value


def _vec2(where, key, value):
    if (not isinstance(value, list) or len(value) != 2
            or any(isinstance(x, bool) or not isinstance(x, (int, float)) for x in value)):
        raise where.error(f"must be a pair of numbers [x, y], got {toml_type(value)} "
                          f"({show(value)})", key)
    return (_float(where, key, value[0]), _float(where, key, value[1]))


def _numbers(where, key, value, count, what):
    if (not isinstance(value, list) or len(value) != count
            or any(isinstance(x, bool) or not isinstance(x, (int, float)) for x in value)):
        raise where.error(f"must be {what}, got {toml_type(value)} ({show(value)})", key)
    return tuple(_float(where, key, x) for x in value)


def _vec3(where, key, value):
    return _numbers(where, key, value, 3, "three numbers [x, y, z]")


def _vector(where, key, value):
    """[x, y] or [x, y, z]: the model checks it against its dimension."""
    count = len(value) if isinstance(value, list) and len(value) in (2, 3) else 2
    return _numbers(where, key, value, count, "[x, y] (planar) or [x, y, z] (spatial)")


def _vector_or_matrix(length, what):
    """[a, b, ...] of `length` numbers, or a 3 x 3 matrix [[...], [...], [...]]."""
    def check(where, key, value):
        if isinstance(value, list) and value and all(isinstance(row, list) for row in value):
            if len(value) != 3:
                raise where.error(f"must be {what}, got {show(value)}", key)
            return tuple(_numbers(where, key, row, 3, f"{what} (each row three numbers)") for row in value)
        return _numbers(where, key, value, length, what)
    return check


def _list_of(where, key, value, check, what):
    if not isinstance(value, list):
        raise where.error(f"must be an array of {what}, got {toml_type(value)} "
                          f"({show(value)})", key)
    return [check(where, key, x) for x in value]


def _function_pair(where, key, value):
    if not isinstance(value, list) or len(value) != 2:
        raise where.error("must be a pair [fx, fy] of numbers or time functions, got "
                          f"{toml_type(value)} ({show(value)})", key)
    return tuple(_time_function(where, key, x) for x in value)


def _function_triple(where, key, value):
    if not isinstance(value, list) or len(value) != 3:
        raise where.error("must be [fx, fy, fz], three numbers or time functions, got "
                          f"{toml_type(value)} ({show(value)})", key)
    return tuple(_time_function(where, key, x) for x in value)


def _time_function(where, key, value):
    """A number (kept as a number: the model reads it as a Constant) or an
    inline table {type = ..., ...} made into a TimeFunction."""
    if isinstance(value, bool) or not isinstance(value, (int, float, dict)):
        raise where.error("must be a number or a time function "
                          "{ type = \"linear\", rate = ..., ... }, got "
                          f"{toml_type(value)} ({show(value)})", key)
    if not isinstance(value, dict):
        number = _float(where, key, value)
        if not math.isfinite(number):  # a constant force or motion of inf has no meaning
            raise where.error(f"must be finite, got {number!r}", key)
        return number
    if "type" not in value:
        raise where.error("a time function needs a 'type' (constant, linear, polynomial, "
                          "harmonic, smooth_step, spline or input)", key)
    try:
        from ..functions import time_function_from_dict
    except ImportError:
        raise where.error("this lagmb has no time functions (lagmb.functions)", key) from None
    try:
        f = time_function_from_dict(dict(value))
    except (ValueError, TypeError, KeyError, OverflowError) as e:
        raise where.error(f"{_message(e)} (in {show(value)})", key) from None
    unknown = sorted(set(value) - set(f.to_dict()))
    if unknown:
        raise where.error(f"unknown key '{unknown[0]}' in a {value['type']!r} time function; "
                          f"its keys: {', '.join(f.to_dict())}", key)
    if f.to_dict()["type"] == "input" and getattr(f, "name", None) is not None:
        # one input feeding several elements: each place names it
        known = where.inputs.setdefault(f.name, f)
        if known.initial != f.initial:
            raise where.error(f"input {f.name!r} is given again with another initial value ({f.initial!r}; "
                              f"first {known.initial!r}): one name is one input", key)
        return known
    return f


def _shape(where, key, value):
    """An inline table holding a collision shape (Shape.to_dict; the model
    checks its values)."""
    if not isinstance(value, dict):
        raise where.error("must be a shape { body = ..., kind = ..., size = [...], position = [...], "
                          f"rotation = [[...], [...], [...]] }}, got {toml_type(value)} ({show(value)})", key)
    return dict(value)


# kind of value (schema.py) -> its check: (where, key, value) -> the value to use
_CHECKS = {
    NUMBER: _number,
    INTEGER: _integer,
    STRING: _string,
    BOOL: _bool,
    VEC2: _vec2,
    VEC3: _vec3,
    VECTOR: _vector,
    ORIENTATION: _vector_or_matrix(4, "a unit quaternion [w, x, y, z] or a rotation matrix [[...], [...], [...]]"),
    INERTIA: _vector_or_matrix(3, "principal moments [Ixx, Iyy, Izz] or an inertia tensor [[...], [...], [...]]"),
    FUNCTION: _time_function,
    FUNCTION_PAIR: _function_pair,
    FUNCTION_TRIPLE: _function_triple,
    SHAPE: _shape,
    NUMBERS: lambda where, key, value: _list_of(where, key, value, _number, "numbers"),
    STRINGS: lambda where, key, value: _list_of(where, key, value, _string, "strings"),
}


def _message(e):
    text = str(e)
    if isinstance(e, KeyError) and e.args:
        text = f"missing {e.args[0]!r}"
    return text


def _parameters(method_name, dimension=2):
    """(all keyword names, required names) of a Model method in a model of
    this dimension, or None."""
    from ..registry import BY_METHOD, SPATIAL_BY_METHOD, signature

    kind = (BY_METHOD if dimension == 2 else SPATIAL_BY_METHOD).get(method_name)
    if kind is None or getattr(Model, method_name, None) is None:
        return None
    params = list(signature(kind).parameters.values())[1:]  # without self
    names = [p.name for p in params if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]
    required = [p.name for p in params
                if p.default is p.empty and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]
    return names, required


# "[model], [[bodies]], ... and [output]": the tables, for the message about an unknown one
_HEADERS = [f"[[{t}]]" if t in ELEMENT_TABLES else f"[{t}]" for t in TABLES]
_TABLE_LIST = ", ".join(_HEADERS[:-1]) + " and " + _HEADERS[-1]


def _place(path):
    """(table label, key) of a path of keys and indices as Lines records it."""
    path = tuple(path)
    if not path:
        return None, None
    if path[0] not in TABLES:
        return None, ".".join(map(str, path))
    if len(path) > 1 and isinstance(path[1], int):
        table, rest = f"{path[0]}[{path[1]}]", path[2:]
    else:
        table, rest = f"[{path[0]}]", path[1:]
    return table, ".".join(map(str, rest)) or None


def _long_integer(text):
    """(line, digits) of the first integer longer than Python converts, or None."""
    limit = getattr(sys, "get_int_max_str_digits", lambda: 0)()
    if not limit:
        return None
    for number, line in enumerate(text.split("\n"), 1):
        for m in re.finditer(r"[0-9][0-9_]*", line):
            digits = len(m.group().replace("_", ""))
            if digits > limit:
                return number, digits
    return None


def _words(text):
    return set(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", text))


class Reader:
    def __init__(self, path, text):
        self.path = path
        self.dimension = 2  # until [model] says otherwise (read_model)
        self.lines = Lines(text)  # first: it finds the nesting that tomllib recurses into
        if self.lines.too_deep is not None:
            line, key = self.lines.too_deep
            raise self.located(f"arrays or inline tables nested more than {MAX_NESTING} deep",
                               line, key)
        try:
            self.data = _toml.loads(text)
        except _toml.TOMLDecodeError as e:
            m = re.search(r"\(at line (\d+), column (\d+)\)", str(e))
            line = int(m.group(1)) if m else None
            reason = re.sub(r"\s*\(at line \d+, column \d+\)", "", str(e)) if m else str(e)
            raise SceneError(f"not valid TOML: {reason}" + (f" (column {m.group(2)})" if m else ""),
                             path, line) from None
        except ValueError as e:  # tomllib's int() past Python's limit on decimal digits
            found = _long_integer(text)
            if found is None:
                raise SceneError(f"not valid TOML: {e}", path) from None
            line, digits = found
            raise self.located(f"an integer of {digits} digits (Python reads at most "
                               f"{sys.get_int_max_str_digits()}; a float has 309)",
                               line, self.lines.key_at(line)) from None
        except RecursionError:  # nesting the check above did not see
            raise SceneError("values nested too deeply to read", path) from None
        self.names = {}  # element or body name -> (label, line)
        self.inputs = {}  # input name -> mb.Input: one name is one input, wherever it feeds
        self.bodies = {"ground"}
        self.joints = set()
        self.elements = []

    def located(self, message, line, key_path):
        """A SceneError at a line, before there is data to name the table by."""
        table, key = _place(key_path)
        return SceneError(message, self.path, line, table, key)

    def where(self, table_path, label):
        return _Where(self.path, self.lines, table_path, label, self.inputs)

    def read(self):
        data = self.data
        for key, value in data.items():
            if key not in TABLES:
                w = self.where((key,), None)
                if isinstance(value, dict):
                    msg = f"unknown table [{key}]"
                elif isinstance(value, list) and value and all(isinstance(x, dict) for x in value):
                    msg = f"unknown table [[{key}]]"
                else:
                    msg = f"unknown top-level key '{key}'"
                raise SceneError(f"{msg}; a scene has the tables {_TABLE_LIST}", self.path,
                                 w.line(), None, key)
        for key in SETTINGS:
            if key in data and not isinstance(data[key], dict):
                raise SceneError(f"'{key}' must be a table [{key}], got {toml_type(data[key])}",
                                 self.path, self.lines.line((key,)), None, key)
        for key in ELEMENT_TABLES:
            value = data.get(key, [])
            if not isinstance(value, list) or not all(isinstance(x, dict) for x in value):
                raise SceneError(f"'{key}' must be an array of tables [[{key}]], got "
                                 f"{toml_type(value)}", self.path, self.lines.line((key,)),
                                 None, key)

        model = self.read_model(data.get("model", {}))
        order = []
        for rank, table in enumerate(ELEMENT_TABLES):
            for i, entry in enumerate(data.get(table, [])):
                line = self.lines.line((table, i)) or 0
                order.append((line, rank, i, table, entry))
        order.sort(key=lambda x: x[:3])
        for _, _, i, table, entry in order:
            self.add(model, table, i, entry)
        settings = self.read_settings(data.get("simulation", {}))
        output = self.read_output(data.get("output", {}))
        if self.path and model.name is None:  # (what pictures and pages call it)
            model.name = os.path.splitext(os.path.basename(str(self.path)))[0]
        return Scene(model, settings, output, self.path, self.elements, self.lines)

    def read_model(self, table):
        w = self.where(("model",), "[model]")
        kwargs = self.read_keys(w, "model", table)
        try:
            model = Model(**kwargs)
        except ModelError as e:  # the dimension or gravity
            raise w.error(str(e), "dimension" if "dimension" in str(e) else "gravity") from None
        self.dimension = model.dimension
        return model

    @staticmethod
    def read_keys(w, name, table):
        """The keys of [model], [simulation] or [output], each value checked
        for its kind."""
        kinds = SETTINGS[name]
        out = {}
        for key, value in table.items():
            if key not in kinds:
                raise w.error(f"unknown key; [{name}] has: " + ", ".join(kinds), key)
            out[key] = _CHECKS[kinds[key]](w, key, value)
        return out

    def label(self, table, i, entry):
        name = entry.get("name")
        return f"{table}[{i}]" + (f" {name!r}" if isinstance(name, str) else "")

    def add(self, model, table, i, entry):
        w = self.where((table, i), self.label(table, i, entry))
        enabled = True
        if "enabled" in entry:  # any element table: false reads and checks it, adds nothing
            enabled = _bool(w, "enabled", entry["enabled"])
            entry = {k: v for k, v in entry.items() if k != "enabled"}
        types = methods(self.dimension)[table]
        if not types:
            raise w.error(f"a {'planar' if self.dimension == 3 else 'spatial'} table: a scene of dimension "
                          f"{self.dimension} has no [[{table}]]")
        if None in types:
            typ, method_name = None, types[None]
            if "type" in entry:
                raise w.error(f"unknown key: [[{table}]] has no type", "type")
        else:
            if "type" not in entry:
                raise w.error(f"missing required key ({', '.join(types)})", "type")
            typ = _string(w, "type", entry["type"])
            if typ not in types:
                raise w.error(f"unknown {ELEMENT_TABLES[table]} type {typ!r}; known: "
                              f"{', '.join(types)}", "type")
            method_name = types[typ]
        params = _parameters(method_name, self.dimension)
        if params is None:
            raise w.error(f"this lagmb has no Model.{method_name}", "type" if typ else None)
        names, required = params
        what = f"a {typ.replace('_', ' ')} {ELEMENT_TABLES[table]}" if typ else f"[[{table}]]"
        renamed = elements(self.dimension)[method_name].renamed
        scene_key = {arg: renamed.get(arg, arg) for arg in names}
        arg_of = {k: a for a, k in scene_key.items()}
        for key in entry:
            if key != "type" and key not in arg_of:
                raise w.error(f"unknown key for {what}; its keys: "
                              + ", ".join(scene_key[a] for a in names), key)
        for arg in required:
            if scene_key[arg] not in entry:
                raise w.error(f"missing required key for {what}", scene_key[arg])

        kwargs = {}
        for key, value in entry.items():
            if key == "type":
                continue
            arg = arg_of[key]
            kwargs[arg] = self.convert(w, method_name, arg, key, value)

        name = kwargs["name"]
        if name in self.names:
            other, line = self.names[name]
            raise w.error(f"duplicate name {name!r}: already used by {other}"
                          + (f" (line {line})" if line else ""), "name")
        if not enabled:
            return  # not in the model at all: a disabled element costs nothing
        try:
            getattr(model, method_name)(**kwargs)
        except (ValueError, TypeError, OverflowError) as e:
            raise w.error(str(e), self.blame(entry, str(e))) from None
        self.names[name] = (w.label, w.line())
        if table in ("bodies", "particles"):
            self.bodies.add(name)
        elif table == "joints":
            self.joints.add(name)
        self.elements.append(SceneElement(table, typ, name, w.line(), i))

    def blame(self, entry, message):
        """The key a model error is about: the first (other than name and
        type) whose name the message mentions, besides as the element's name."""
        name = entry.get("name")
        if isinstance(name, str):
            message = message.replace(f"'{name}'", "")
        words = _words(message)
        for key in entry:
            if key not in ("name", "type") and key in words:
                return key
        return "name" if "name" in words else None  # e.g. an empty or reserved name

    def later(self, table_names, name):
        """Where a name that is not (yet) in the model is defined in the file,
        if it is: (table[i], line, why), why saying it is disabled or later."""
        for table in table_names:
            for i, entry in enumerate(self.data.get(table, [])):
                if entry.get("name") == name:
                    why = "disabled" if entry.get("enabled", True) is False else "later"
                    return f"{table}[{i}]", self.lines.line((table, i)), why
        return None

    @staticmethod
    def unavailable(what, name, found, hint):
        if found[2] == "disabled":
            return (f"{what} {name!r} is disabled ({found[0]}, line {found[1]}: enabled = false); "
                    f"disable the elements that use it too")
        return f"{what} {name!r} is defined later ({found[0]}, line {found[1]}); {hint}"

    def convert(self, w, method, arg, key, value):
        kind = elements(self.dimension)[method].arguments.get(arg)
        if kind == BODY:
            name = _string(w, key, value)
            if name not in self.bodies:
                found = self.later(("bodies", "particles"), name)
                if found:
                    raise w.error(self.unavailable("body", name, found,
                                                   "define bodies before the elements that use them"), key)
                raise w.error(f"no body named {name!r} (bodies: "
                              f"{', '.join(sorted(self.bodies))})", key)
            return name
        if kind == JOINT:
            name = _string(w, key, value)
            if name not in self.joints:
                found = self.later(("joints",), name)
                if found:
                    raise w.error(self.unavailable("joint", name, found,
                                                   "define joints before the drivers and stops that use them"), key)
                known = ", ".join(sorted(self.joints)) or "none"
                raise w.error(f"no joint named {name!r} (joints: {known})", key)
            return name
        if kind is None:
            return value  # an argument this reader does not know: the model checks it
        return _CHECKS[kind](w, key, value)

    def read_settings(self, table):
        w = self.where(("simulation",), "[simulation]")
        out = self.read_keys(w, "simulation", table)
        if "t_out" in out and "n_out" in out:
            raise w.error("give n_out or t_out, not both", "t_out")
        for key in ("analysis", "start"):
            allowed = CHOICES["simulation", key]
            if key in out and out[key] not in allowed:
                raise w.error(f"must be one of {', '.join(map(repr, allowed))}, got {out[key]!r}", key)
        method = self.method(w, out)
        t0 = out.get("t0", 0.0)
        if not math.isfinite(t0):
            raise w.error(f"must be finite, got {t0!r}", "t0")
        if "t_end" in out:
            if not math.isfinite(out["t_end"]) or out["t_end"] <= t0:
                raise w.error(f"must be finite and greater than t0 = {t0!r}, "
                              f"got {out['t_end']!r}", "t_end")
        for key in ("rtol", "atol", "max_step", "step", "newton_rtol", "newton_atol"):
            if key in out and not (math.isfinite(out[key]) and out[key] > 0):
                raise w.error(f"must be positive and finite, got {out[key]!r}", key)
        # integers travel to C as int (n_out, max_order) or long (max_steps)
        if "n_out" in out and not 2 <= out["n_out"] <= MAX_OUTPUTS:
            raise w.error(f"must be at least 2 and at most {MAX_OUTPUTS:,}, got "
                          f"{show(out['n_out'])}", "n_out")
        if "max_steps" in out and not 1 <= out["max_steps"] <= MAX_STEPS:
            raise w.error(f"must be at least 1 and at most {MAX_STEPS:.0e}, got "
                          f"{show(out['max_steps'])}", "max_steps")
        if "max_order" in out and not 1 <= out["max_order"] <= method["max_order"]:
            raise w.error(f"must be in 1..{method['max_order']} for method {method['name']!r}, got "
                          f"{show(out['max_order'])}", "max_order")
        if "t_out" in out:
            t = out["t_out"]
            if not t or not all(math.isfinite(x) for x in t) or any(
                    b <= a for a, b in zip(t, t[1:])):
                raise w.error("must be a non-empty, strictly increasing array of finite times",
                              "t_out")
            if len(t) > MAX_OUTPUTS:
                raise w.error(f"has {len(t):,} times, more than {MAX_OUTPUTS:,}", "t_out")
            if t[0] < t0 or t[-1] > out.get("t_end", t[-1]):
                raise w.error(f"must lie in t0 .. t_end = {t0!r} .. {out.get('t_end', t[-1])!r}, "
                              f"got {t[0]!r} .. {t[-1]!r}", "t_out")
        return out

    @staticmethod
    def method(w, settings):
        """The entry of lagmb.methods() the settings choose: `method` (a
        listed name, any case), or formulation (which may be such a name)
        and integrator (absent: the formulation's first). For "auto", the
        default, which the run resolves: no integrator, and max_order
        within what every variable-step method takes (the smallest of their
        highest orders)."""
        from .._run_options import method_options
        from ..simulation import methods

        try:
            formulation, integrator = method_options(settings.get("method"), settings.get("formulation", "auto"),
                                                     settings.get("integrator"))
        except ModelError as e:
            raise w.error(str(e), "method" if "method" in settings else "formulation") from None
        table = methods()
        if formulation == "auto":
            if integrator:
                raise w.error(f"does not go with formulation 'auto', which chooses the method: give a "
                              f"formulation or a method, got {settings['integrator']!r}", "integrator")
            return {"name": "auto", "max_order": min(m["max_order"] for m in table if not m["fixed_step"])}
        theirs = [m for m in table if m["formulation"] == formulation]
        if not theirs:
            names = list(dict.fromkeys(["auto"] + [m["formulation"] for m in table]))
            raise w.error(f"must be one of {', '.join(map(repr, names))}, got {settings['formulation']!r}",
                          "formulation")
        if not integrator:
            return theirs[0]
        for m in theirs:
            if m["integrator"] == integrator:
                return m
        raise w.error(f"must be one of {', '.join(repr(m['integrator']) for m in theirs)} for formulation "
                      f"{formulation!r}, got {settings['integrator']!r}", "integrator")

    def read_output(self, table):
        w = self.where(("output",), "[output]")
        out = self.read_keys(w, "output", table)
        for key in ("file", "plot", "animate"):
            if "\0" in out.get(key, ""):  # no file system takes it (open raises ValueError)
                raise w.error("a file name cannot contain a NUL character", key)
        if "file" in out and os.path.splitext(out["file"])[1].lower() not in OUTPUT_FILE_TYPES:
            raise w.error(f"must end in .npz or .csv, got {out['file']!r}", "file")
        for key, problem in (("plot", plot_format_problem),
                             ("animate", animation_format_problem)):
            reason = problem(out[key]) if key in out else None
            if reason:
                raise w.error(f"{out[key]!r} {reason}", key)
        if "view" in out and (len(out["view"]) != 2 or not all(math.isfinite(x) for x in out["view"])):
            raise w.error(f"must be [elevation, azimuth] in degrees (the 3D animation's viewpoint), got "
                          f"{show(out['view'])}", "view")
        frames = CHOICES["output", "reaction_frame"]
        if out.get("reaction_frame", frames[0]) not in frames:
            names = " or ".join(f'"{x}"' for x in frames)
            raise w.error(f"must be {names}, got {out['reaction_frame']!r}", "reaction_frame")
        joints = [e.name for e in self.elements if e.table in ("joints", "drivers")]
        drivers = [e.name for e in self.elements if e.table == "drivers"]
        for key, known, what in (("reactions", joints, "joint or driver"),
                                 ("efforts", drivers, "driver")):
            for name in out.get(key, []):
                if name not in known:
                    raise w.error(f"no {what} named {name!r} (known: "
                                  f"{', '.join(known) or 'none'})", key)
        return out


def plot_format_problem(path):
    """Why matplotlib would refuse to save a plot to path (by its extension, as
    savefig decides), or None; None too without matplotlib (the CLI says so)."""
    try:
        import matplotlib
        from matplotlib.backend_bases import FigureCanvasBase
    except ImportError:
        return None
    formats = sorted(FigureCanvasBase.get_supported_filetypes())
    ext = os.path.splitext(path)[1].lower()[1:]
    if ext not in formats:
        return ("must end in one of the formats matplotlib writes: "
                + ", ".join("." + f for f in formats))
    if ext == "pgf":  # typeset by a TeX system, which savefig only looks for at the end
        tex = matplotlib.rcParams["pgf.texsystem"]
        if shutil.which(tex) is None:
            return f"needs {tex} (matplotlib's pgf output is typeset by it), which is not installed"
    return None


def animation_format_problem(path):
    """Why the animation (matplotlib's PillowWriter: the formats Pillow saves
    with several frames) cannot go to path, by its extension, or None."""
    try:
        from PIL import Image
    except ImportError:
        return None
    Image.init()
    several = getattr(Image, "SAVE_ALL", {"GIF": None})
    exts = sorted(e for e, f in Image.registered_extensions().items() if f in several)
    if os.path.splitext(path)[1].lower() not in exts:
        return ("must end in one of the animation formats Pillow writes: " + ", ".join(exts)
                + " (video formats such as .mp4 are not written)")
    return None


class SceneElement:
    """One element of a scene: its table, type (None for bodies and
    particles), name, line in the file and index in its table."""

    __slots__ = ("table", "type", "name", "line", "index")

    def __init__(self, table, type, name, line, index=None):  # noqa: A002 - the scene key
        self.table, self.type, self.name, self.line = table, type, name, line
        self.index = index

    def __repr__(self):
        return f"SceneElement({self.table!r}, {self.type!r}, {self.name!r}, line={self.line})"


class Scene:
    """A model read from a scene file, with its settings.

    Attributes:

    - model: the mb.Model.
    - settings: dict of mb.simulate keyword arguments from [simulation].
    - output: dict from [output] (only the keys the file gives).
    - path: the file.
    - elements: list of SceneElement (table, type, name, line), in file order.

    ``model, settings = scene`` unpacks the two.
    """

    def __init__(self, model, settings=None, output=None, path=None, elements=(), lines=None):
        self.model = model
        self.settings = dict(settings or {})
        self.output = dict(output or {})
        self.path = path
        self.elements = list(elements)
        self._lines = lines

    def __iter__(self):
        yield self.model
        yield self.settings

    def names(self, table):
        """Names of the elements of one table ("joints", "drivers", ...)."""
        return [e.name for e in self.elements if e.table == table]

    def output_error(self, key, message):
        """A SceneError about a key of [output], at its line."""
        w = _Where(self.path, self._lines or Lines(""), ("output",), "[output]")
        return w.error(message, key)

    def run(self, **overrides):
        """``mb.simulate(model, **(settings | overrides))``. Overriding t_end
        keeps the file's t_out times up to the new t_end; giving n_out drops
        its t_out. A bad setting from the file raises SceneError at its line."""
        from ..simulation import simulate

        kwargs = dict(self.settings)
        if "n_out" in overrides and "t_out" not in overrides:
            kwargs.pop("t_out", None)
        if "t_out" in overrides and "n_out" not in overrides:
            kwargs.pop("n_out", None)
        if "t_end" in overrides and "t_out" in kwargs and "t_out" not in overrides:
            t_end = overrides["t_end"]
            kept = [t for t in kwargs["t_out"] if t <= t_end]
            if kept:
                kwargs["t_out"] = kept
            else:
                kwargs.pop("t_out")
        kwargs.update(overrides)
        try:
            return simulate(self.model, **kwargs)
        except ModelError as e:
            if isinstance(e, SceneError):
                raise
            # a setting from the file that the message names, the first named
            message, words = str(e), _words(str(e))
            if any(k in words for k in overrides):
                raise
            lines = self._lines or Lines("")
            named = [k for k in self.settings if k in words]
            if named:
                key = min(named, key=message.find)
                w = _Where(self.path, lines, ("simulation",), "[simulation]")
                raise w.error(message, key) from None
            # else an element of the file that it names (e.g. a massless body)
            element = next((x for x in self.elements if x.index is not None
                            and f"'{x.name}'" in message), None)
            if element is None:
                raise
            where = (element.table, element.index)
            keys = sorted((line, path[2]) for path, line in lines.at.items()
                          if len(path) == 3 and path[:2] == where)
            words = _words(message.replace(f"'{element.name}'", ""))
            key = next((k for _, k in keys if k not in ("name", "type") and k in words), None)
            w = _Where(self.path, lines, where, f"{element.table}[{element.index}] "
                                                f"{element.name!r}")
            raise w.error(message, key) from None

    def __repr__(self):
        return f"<lagmb.Scene {self.path!r}: {self.model!r}, settings={self.settings}>"


def load_scene(path):
    """Read a scene file: returns a Scene (.model, .settings, .output, .run()).

    Raises SceneError (a ModelError) naming the file, line, table and key for
    anything the file gets wrong (also for a file over MAX_SCENE_BYTES), and
    OSError if it cannot be read.
    """
    path = os.fspath(path)
    with open(path, "rb") as fh:
        raw = fh.read(MAX_SCENE_BYTES + 1)  # a pipe or device may never end
    if len(raw) > MAX_SCENE_BYTES:
        raise SceneError(f"more than {MAX_SCENE_BYTES >> 20} MiB: too large for a scene file",
                         path)
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as e:
        line = raw[:e.start].count(b"\n") + 1
        raise SceneError("not UTF-8 text", path, line) from None
    return Reader(path, text).read()

