"""Scene files: a whole model and how to run it, in TOML.

``mb.load_scene(path)`` reads one and returns a :class:`Scene` with
``.model`` (an ``mb.Model``), ``.settings`` (the keyword arguments of
``mb.simulate``) and ``.output`` (what ``lagmb run`` writes); ``scene.run()``
simulates it, and ``model, settings = mb.load_scene(path)`` unpacks it where
only the model and its settings are wanted (docs/design.md, section 7).
``mb.save_scene(model, path, settings=None, output=None)`` (also
``model.to_scene(path, ...)``) writes one that loads back into a model giving
the same results to the last bit.

A scene, with every table (all keys in SI units, angles in radians)::

    [model]
    gravity = [0.0, -9.81]          # optional: no gravity unless given

    [[bodies]]                      # one table per add_body call
    name = "crank"
    mass = 1.0
    inertia = 0.01
    position = [0.05, 0.0]          # optional, like the add_body defaults:
    angle = 0.0                     # angle, velocity, angular_velocity
    # velocity = [0.0, 0.0]
    # angular_velocity = 0.0

    [[particles]]                   # add_particle: name, mass, position, velocity
    name = "bob"
    mass = 0.5
    position = [1.0, 0.0]

    [[joints]]                      # type: revolute, translational, weld, distance,
    type = "revolute"               # pin_in_slot, gear or rack_pinion; the other
    name = "pivot"                  # keys are that add_<type> call's arguments
    body_i = "ground"
    body_j = "crank"
    at = [0.0, 0.0]

    [[drivers]]                     # type "joint": drive_joint(name, joint, f)
    type = "joint"                  # type "body": drive_body(name, body, coordinate, f)
    name = "motor"
    joint = "pivot"
    function = { type = "linear", rate = 10.0, start = 0.0 }   # or a number

    [[forces]]                      # type: spring_damper, rotational_spring_damper,
    type = "force"                  # force, torque, contact, joint_friction: add_<type>
    name = "push"
    body = "crank"
    force = [0.0, { type = "harmonic", amplitude = 2.0, omega = 3.0 }]

    [[forces]]                      # joint friction: add_joint_friction arguments
    type = "joint_friction"
    name = "pivot_friction"
    joint = "pivot"
    mu = 0.2
    pin_radius = 0.01
    enabled = false                 # any element table: read and checked, not added
                                    # (so to_scene does not write it back)

    [[stops]]                       # add_stop(name, joint, lower, upper, restitution,
    name = "limit"                  #          rest_speed): a joint limit with impacts
    joint = "pivot"
    lower = -1.0
    restitution = 0.5

    [simulation]                    # the keyword arguments of mb.simulate
    t_end = 2.0                     # t0, rtol, atol, n_out or t_out, max_step,
    rtol = 1e-8                     # max_steps, formulation, integrator, max_order
    n_out = 401                     # analysis ("auto", "dynamic", "kinematic",
                                    # "inverse_dynamics"), start ("given", "equilibrium")

    [output]                        # what `lagmb run` writes (all optional)
    file = "results.npz"            # default for -o: .npz or .csv
    reactions = ["pivot"]           # joints (or drivers) whose r.reaction goes out
    reaction_frame = "global"       # or "joint": r.reaction(name, frame="joint")
    efforts = ["motor"]             # drivers whose r.effort goes out
    energy = true                   # an energy column in the csv file
    plot = "crank.png"              # default for --plot
    animate = "crank.gif"           # default for --animate

Conventions:

- Bodies are referred to by name; ``"ground"`` is the ground. Points and
  vectors are ``[x, y]`` arrays; a time-function value (a driver's
  ``function``, a spring's ``force``, a ``torque``, each component of
  ``force = [fx, fy]``) is a number (a constant) or an inline table whose
  ``type`` is constant, linear, polynomial, harmonic, smooth_step or spline and
  whose other keys are that function's arguments (``mb.TimeFunction.to_dict``).
- Elements are added to the model in the order they appear in the file, so
  a body (or joint) must come before the elements that refer to it; that
  order also numbers the coordinates and constraint rows.
- Strict: an unknown table or key, a missing required key, a value of the
  wrong type or one the model rejects raises :class:`SceneError` (a
  ``ModelError``, so a ``ValueError``) naming the file, the line, the table
  (``joints[2] 'pin'``: the third ``[[joints]]``, counted from 0) and the key.
- Limits (to refuse what no scene means, before it costs a run): a file of
  at most 16 MiB of UTF-8, arrays and inline tables nested at most 32 deep,
  numbers within a float's range, at most 10,000,000 outputs (``n_out`` or
  ``t_out``), ``max_order`` 1 to the method's highest (5 bdf, 12 adams; lagmb.methods()); ``[output]`` plot
  and animate paths end in a format matplotlib (plot) or Pillow (animation,
  several frames: .gif, .webp, .png, ...) writes.
- ``[output]``: relative paths are relative to the current directory. In an
  ``.npz`` file, ``reactions`` / ``efforts`` default to every joint / every
  driver (``reactions = []`` writes none); a ``.csv`` file has the columns
  ``t``, the coordinates (``crank.x, crank.y, crank.angle``, a particle's
  ``.x, .y``), then ``<name>.fx, <name>.fy, <name>.torque`` for each listed
  reaction (``.f1, .f2, .torque`` with ``reaction_frame = "joint"``),
  ``<name>.effort`` for each listed effort, and ``energy`` if ``energy =
  true``; it has no reactions or efforts unless listed. Numbers are written
  in full (repr), so they read back exactly.
- Writing: ``save_scene`` writes every element with all its arguments (the
  defaults too), floats by repr, and reads the text back before writing it;
  a Python callable (as a time function or force) cannot be written.
"""

import inspect
import json
import math
import numbers
import os
import re
import shutil
import sys

try:  # Python 3.11+
    import tomllib as _toml
except ImportError:  # pragma: no cover - older Pythons
    import tomli as _toml

import numpy as np

from .errors import ModelError
from .handles import Handle, name_of
from .model import Model

__all__ = ["Scene", "SceneError", "load_scene", "save_scene"]


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


# --- the format ---------------------------------------------------------------

_ELEMENT_TABLES = ("bodies", "particles", "joints", "drivers", "forces", "stops")
_TABLES = ("model",) + _ELEMENT_TABLES + ("simulation", "output")

# table -> {type: Model method}; None: the table has no `type` key
_METHODS = {
    "bodies": {None: "add_body"},
    "particles": {None: "add_particle"},
    "joints": {t: "add_" + t for t in ("revolute", "translational", "weld", "distance",
                                        "pin_in_slot", "gear", "rack_pinion")},
    "drivers": {"joint": "drive_joint", "body": "drive_body"},
    "forces": {t: "add_" + t for t in ("spring_damper", "rotational_spring_damper",
                                        "force", "torque", "joint_friction", "contact")},
    "stops": {None: "add_stop"},
}
_SINGULAR = {"bodies": "body", "particles": "particle", "joints": "joint", "drivers": "driver",
             "forces": "force", "stops": "stop"}
_TABLE_OF = {m: (table, typ) for table, types in _METHODS.items() for typ, m in types.items()}

# a method's keyword -> the scene key, where they differ
_RENAMED = {("drive_joint", "f"): "function", ("drive_body", "f"): "function"}

# what the value of a key is (by key name; (method, key) where it depends on the method)
_BODY_REF = {"body", "body_i", "body_j", "pinion", "rack", "circle_body", "line_body"}
_VEC2 = {"position", "velocity", "at", "axis", "point", "point_i", "point_j",
         "local_i", "local_j", "center_i", "center_j", "center", "direction"}
_NUMBER = {"mass", "inertia", "angle", "angular_velocity", "length", "ratio", "radius",
           "stiffness", "damping", "free_length", "free_angle",
           "mu", "viscous", "preload", "pin_radius", "bearing_length", "slip_velocity",
           "load_smoothing", "lower", "upper", "restitution", "rest_speed", "friction"}
_FUNCTION = {"f", "torque", ("add_spring_damper", "force")}
_FUNCTION_PAIR = {("add_force", "force")}
_STRING = {"name", "coordinate"}
_BOOL = {"local"}

_SIMULATION = {  # key -> kind
    "t_end": "number", "t0": "number", "rtol": "number", "atol": "number",
    "n_out": "integer", "t_out": "numbers", "max_step": "number", "max_steps": "integer",
    "formulation": "string", "integrator": "string", "max_order": "integer",
    "step": "number",  # the fixed step of formulation "ali3p"
}
_SIMULATION.update({"analysis": "string", "start": "string"})  # what to compute, where to start
_OUTPUT = {
    "file": "string", "reactions": "strings", "efforts": "strings",
    "reaction_frame": "string", "energy": "bool", "plot": "string", "animate": "string",
}
_OUTPUT_FILE_TYPES = (".npz", ".csv")

# simulate's choices (simulate.cpp checks them too, but only when a run starts)
MAX_OUTPUTS = 10_000_000  # n_out, len(t_out): each output holds q, v, a and lam
_MAX_STEPS = 10**12  # max_steps travels as a C long; a bound this high is no bound
MAX_SCENE_BYTES = 16 << 20  # larger is no hand-written scene (and /dev/zero never ends)
_MAX_NESTING = 32  # arrays and inline tables; a scene needs 3 (tomllib recurses per level)


def _toml_type(value):
    if isinstance(value, bool):
        return "a boolean"
    if isinstance(value, int):
        return "an integer"
    if isinstance(value, float):
        return "a float"
    if isinstance(value, str):
        return "a string"
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, list):
        return "an array"
    return type(value).__name__


def _show(value):
    """A value as it looks in TOML, short."""
    if _huge(value):  # str() of it is slow, or refused past 4300 digits
        return f"an integer of {_digits(value)} digits"
    try:
        text = _value(value)
    except Exception:  # noqa: BLE001 - only for messages
        try:
            text = repr(value)
        except Exception:  # noqa: BLE001 - e.g. a list holding a huge integer
            text = _toml_type(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _huge(value):
    return isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 200


def _digits(value):
    """Decimal digits of an integer, without converting it to a string."""
    n = abs(value)
    digits = max(1, int(n.bit_length() * math.log10(2)))
    return digits + (n >= 10 ** digits)


# --- line numbers -------------------------------------------------------------

_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")


def _read_key(s, pos):
    """The dotted key starting at s[pos]: (list of parts, position after it)."""
    parts = []
    n = len(s)
    while True:
        while pos < n and s[pos] in " \t":
            pos += 1
        if pos >= n:
            return parts, pos
        if s[pos] == '"':
            j = pos + 1
            while j < n and s[j] != '"':
                j += 2 if s[j] == "\\" else 1
            try:
                parts.append(json.loads(s[pos:j + 1]))
            except ValueError:
                parts.append(s[pos + 1:j])
            pos = j + 1
        elif s[pos] == "'":
            j = s.find("'", pos + 1)
            j = n if j < 0 else j
            parts.append(s[pos + 1:j])
            pos = j + 1
        else:
            m = _BARE_KEY.match(s, pos)
            if m is None:
                return parts, pos
            parts.append(m.group())
            pos = m.end()
        while pos < n and s[pos] in " \t":
            pos += 1
        if pos < n and s[pos] == ".":
            pos += 1
            continue
        return parts, pos


class _Lines:
    """Line numbers of the tables and keys of a TOML text (which tomllib has
    already accepted): ``line(path)`` for a path of keys and array indices as
    in the parsed data, e.g. ("joints", 2, "at"), or of its nearest parent."""

    def __init__(self, text):
        self.at = {}
        self._arrays = {}  # path of an array of tables -> entries so far
        self._table = ()
        self._depth = 0  # open [ and { of a value spanning lines
        self._string = None  # delimiter of an open multi-line string
        self._number = 0  # the line being scanned
        self._key = ()  # the path of the key whose value is being scanned
        self.too_deep = None  # (line, key path) where values nest deeper than _MAX_NESTING
        try:
            self._scan(text)
        except Exception:  # noqa: BLE001 - line numbers are a help, never a failure
            pass

    def line(self, path):
        path = tuple(path)
        while path:
            if path in self.at:
                return self.at[path]
            path = path[:-1]
        return None

    def key_at(self, line):
        """The path of the key (or table) given last on or before a line, for
        errors found before the data exists (tomllib's, the nesting check)."""
        best = ()
        for path, number in self.at.items():
            if number <= line and (not best or (number, len(path)) >= (self.at[best], len(best))):
                best = path
        return best

    def _resolve(self, parts):
        out = ()
        for p in parts:
            out += (p,)
            if out in self._arrays:
                out += (self._arrays[out] - 1,)
        return out

    def _scan(self, text):
        for number, line in enumerate(text.split("\n"), 1):
            self._number = number
            if line.endswith("\r"):
                line = line[:-1]
            if self._string is not None or self._depth > 0:
                self._scan_value(line, 0)
                continue
            s = line.lstrip(" \t")
            if not s or s[0] == "#":
                continue
            if s.startswith("[["):
                parts, _ = _read_key(s, 2)
                array = self._resolve(parts[:-1]) + (parts[-1],)
                self.at.setdefault(array, number)
                self._arrays[array] = self._arrays.get(array, 0) + 1
                self._table = array + (self._arrays[array] - 1,)
                self.at[self._table] = number
            elif s[0] == "[":
                parts, _ = _read_key(s, 1)
                self._table = self._resolve(parts)
                for k in range(1, len(self._table) + 1):
                    self.at.setdefault(self._table[:k], number)
            else:
                parts, pos = _read_key(s, 0)
                for k in range(1, len(parts) + 1):
                    self.at.setdefault(self._table + tuple(parts[:k]), number)
                self._key = self._table + tuple(parts)
                eq = s.find("=", pos)
                self._scan_value(s, eq + 1 if eq >= 0 else len(s))

    def _scan_value(self, s, i):
        """Follow strings, comments and brackets to the end of the line."""
        n = len(s)
        while i < n:
            if self._string is not None:
                if self._string == '"""' and s[i] == "\\":
                    i += 2
                elif s.startswith(self._string, i):
                    i += 3
                    while i < n and s[i] == self._string[0]:
                        i += 1
                    self._string = None
                else:
                    i += 1
                continue
            c = s[i]
            if c == "#":
                return
            if s.startswith('"""', i) or s.startswith("'''", i):
                self._string = s[i:i + 3]
                i += 3
            elif c == '"':
                i += 1
                while i < n and s[i] != '"':
                    i += 2 if s[i] == "\\" else 1
                i += 1
            elif c == "'":
                j = s.find("'", i + 1)
                i = n if j < 0 else j + 1
            else:
                if c in "[{":
                    self._depth += 1
                    if self._depth > _MAX_NESTING and self.too_deep is None:
                        self.too_deep = (self._number, self._key)
                elif c in "]}":
                    self._depth -= 1
                i += 1


# --- reading ------------------------------------------------------------------

class _Where:
    """Where a table is, to name it in errors."""

    def __init__(self, path, lines, table_path, label):
        self.path, self.lines, self.table_path, self.label = path, lines, tuple(table_path), label

    def line(self, key=None):
        return self.lines.line(self.table_path + ((key,) if key is not None else ()))

    def error(self, message, key=None):
        return SceneError(message, self.path, self.line(key), self.label, key)


def _number(where, key, value):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise where.error(f"must be a number, got {_toml_type(value)} ({_show(value)})", key)
    return _float(where, key, value)


def _float(where, key, value):
    try:
        return float(value)
    except OverflowError:
        raise where.error(f"{_show(value)} is too large for a float (at most about 1.8e308)",
                          key) from None


def _integer(where, key, value):
    if isinstance(value, bool) or not isinstance(value, int):
        raise where.error(f"must be an integer, got {_toml_type(value)} ({_show(value)})", key)
    return value


def _string(where, key, value):
    if not isinstance(value, str):
        raise where.error(f"must be a string, got {_toml_type(value)} ({_show(value)})", key)
    return value


def _bool(where, key, value):
    if not isinstance(value, bool):
        raise where.error(f"must be true or false, got {_toml_type(value)} ({_show(value)})", key)
    return value


def _vec2(where, key, value):
    if (not isinstance(value, list) or len(value) != 2
            or any(isinstance(x, bool) or not isinstance(x, (int, float)) for x in value)):
        raise where.error(f"must be a pair of numbers [x, y], got {_toml_type(value)} "
                          f"({_show(value)})", key)
    return (_float(where, key, value[0]), _float(where, key, value[1]))


def _list_of(where, key, value, check, what):
    if not isinstance(value, list):
        raise where.error(f"must be an array of {what}, got {_toml_type(value)} "
                          f"({_show(value)})", key)
    return [check(where, key, x) for x in value]


def _time_function(where, key, value):
    """A number (kept as a number: the model reads it as a Constant) or an
    inline table {type = ..., ...} made into a TimeFunction."""
    if isinstance(value, bool) or not isinstance(value, (int, float, dict)):
        raise where.error("must be a number or a time function "
                          "{ type = \"linear\", rate = ..., ... }, got "
                          f"{_toml_type(value)} ({_show(value)})", key)
    if not isinstance(value, dict):
        number = _float(where, key, value)
        if not math.isfinite(number):  # a constant force or motion of inf has no meaning
            raise where.error(f"must be finite, got {number!r}", key)
        return number
    if "type" not in value:
        raise where.error("a time function needs a 'type' (constant, linear, polynomial, "
                          "harmonic, smooth_step or spline)", key)
    try:
        from .functions import time_function_from_dict
    except ImportError:
        raise where.error("this lagmb has no time functions (lagmb.functions)", key) from None
    try:
        f = time_function_from_dict(dict(value))
    except (ValueError, TypeError, KeyError, OverflowError) as e:
        raise where.error(f"{_message(e)} (in {_show(value)})", key) from None
    unknown = sorted(set(value) - set(f.to_dict()))
    if unknown:
        raise where.error(f"unknown key '{unknown[0]}' in a {value['type']!r} time function; "
                          f"its keys: {', '.join(f.to_dict())}", key)
    return f


def _message(e):
    text = str(e)
    if isinstance(e, KeyError) and e.args:
        text = f"missing {e.args[0]!r}"
    return text


def _parameters(method_name):
    """(all keyword names, required names) of a Model method, or None."""
    method = getattr(Model, method_name, None)
    if method is None:
        return None
    params = list(inspect.signature(method).parameters.values())[1:]  # without self
    names = [p.name for p in params if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]
    required = [p.name for p in params
                if p.default is p.empty and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]
    return names, required


def _kind(method, arg):
    if arg in _BODY_REF:
        return "body"
    if arg == "joint":
        return "joint"
    if (method, arg) in _FUNCTION_PAIR:
        return "function_pair"
    if arg in _FUNCTION or (method, arg) in _FUNCTION:
        return "function"
    if arg in _VEC2:
        return "vec2"
    if arg in _NUMBER:
        return "number"
    if arg in _STRING:
        return "string"
    if arg in _BOOL:
        return "bool"
    return None


def _place(path):
    """(table label, key) of a path of keys and indices as _Lines records it."""
    path = tuple(path)
    if not path:
        return None, None
    if path[0] not in _TABLES:
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


class _Reader:
    def __init__(self, path, text):
        self.path = path
        self.lines = _Lines(text)  # first: it finds the nesting that tomllib recurses into
        if self.lines.too_deep is not None:
            line, key = self.lines.too_deep
            raise self.located(f"arrays or inline tables nested more than {_MAX_NESTING} deep",
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
        self.bodies = {"ground"}
        self.joints = set()
        self.elements = []

    def located(self, message, line, key_path):
        """A SceneError at a line, before there is data to name the table by."""
        table, key = _place(key_path)
        return SceneError(message, self.path, line, table, key)

    def where(self, table_path, label):
        return _Where(self.path, self.lines, table_path, label)

    def read(self):
        data = self.data
        for key, value in data.items():
            if key not in _TABLES:
                w = self.where((key,), None)
                if isinstance(value, dict):
                    msg = f"unknown table [{key}]"
                elif isinstance(value, list) and value and all(isinstance(x, dict) for x in value):
                    msg = f"unknown table [[{key}]]"
                else:
                    msg = f"unknown top-level key '{key}'"
                raise SceneError(f"{msg}; a scene has the tables [model], [[bodies]], "
                                 "[[particles]], [[joints]], [[drivers]], [[forces]], "
                                 "[[stops]], [simulation] and [output]", self.path, w.line(), None, key)
        for key in ("model", "simulation", "output"):
            if key in data and not isinstance(data[key], dict):
                raise SceneError(f"'{key}' must be a table [{key}], got {_toml_type(data[key])}",
                                 self.path, self.lines.line((key,)), None, key)
        for key in _ELEMENT_TABLES:
            value = data.get(key, [])
            if not isinstance(value, list) or not all(isinstance(x, dict) for x in value):
                raise SceneError(f"'{key}' must be an array of tables [[{key}]], got "
                                 f"{_toml_type(value)}", self.path, self.lines.line((key,)),
                                 None, key)

        model = self.read_model(data.get("model", {}))
        order = []
        for table in _ELEMENT_TABLES:
            for i, entry in enumerate(data.get(table, [])):
                line = self.lines.line((table, i)) or 0
                order.append((line, _ELEMENT_TABLES.index(table), i, table, entry))
        order.sort(key=lambda x: x[:3])
        for _, _, i, table, entry in order:
            self.add(model, table, i, entry)
        settings = self.read_settings(data.get("simulation", {}))
        output = self.read_output(data.get("output", {}))
        return Scene(model, settings, output, self.path, self.elements, self.lines)

    def read_model(self, table):
        w = self.where(("model",), "[model]")
        gravity = None
        for key, value in table.items():
            if key == "gravity":
                gravity = _vec2(w, key, value)
            else:
                raise w.error("unknown key; [model] has: gravity", key)
        try:
            return Model(gravity=gravity)
        except ModelError as e:
            raise w.error(str(e), "gravity") from None

    def label(self, table, i, entry):
        name = entry.get("name")
        return f"{table}[{i}]" + (f" {name!r}" if isinstance(name, str) else "")

    def add(self, model, table, i, entry):
        w = self.where((table, i), self.label(table, i, entry))
        enabled = True
        if "enabled" in entry:  # any element table: false reads and checks it, adds nothing
            enabled = _bool(w, "enabled", entry["enabled"])
            entry = {k: v for k, v in entry.items() if k != "enabled"}
        types = _METHODS[table]
        if None in types:
            typ, method_name = None, types[None]
            if "type" in entry:
                raise w.error(f"unknown key: [[{table}]] has no type", "type")
        else:
            if "type" not in entry:
                raise w.error(f"missing required key ({', '.join(types)})", "type")
            typ = _string(w, "type", entry["type"])
            if typ not in types:
                raise w.error(f"unknown {_SINGULAR[table]} type {typ!r}; known: {', '.join(types)}",
                              "type")
            method_name = types[typ]
        params = _parameters(method_name)
        if params is None:
            raise w.error(f"this lagmb has no Model.{method_name}", "type" if typ else None)
        names, required = params
        what = f"a {typ.replace('_', ' ')} {_SINGULAR[table]}" if typ else f"[[{table}]]"
        scene_key = {arg: _RENAMED.get((method_name, arg), arg) for arg in names}
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
        kind = _kind(method, arg)
        if kind == "body":
            name = _string(w, key, value)
            if name not in self.bodies:
                found = self.later(("bodies", "particles"), name)
                if found:
                    raise w.error(self.unavailable("body", name, found,
                                                   "define bodies before the elements that use them"), key)
                raise w.error(f"no body named {name!r} (bodies: "
                              f"{', '.join(sorted(self.bodies))})", key)
            return name
        if kind == "joint":
            name = _string(w, key, value)
            if name not in self.joints:
                found = self.later(("joints",), name)
                if found:
                    raise w.error(self.unavailable("joint", name, found,
                                                   "define joints before the drivers and stops that use them"), key)
                known = ", ".join(sorted(self.joints)) or "none"
                raise w.error(f"no joint named {name!r} (joints: {known})", key)
            return name
        if kind == "vec2":
            return _vec2(w, key, value)
        if kind == "number":
            return _number(w, key, value)
        if kind == "string":
            return _string(w, key, value)
        if kind == "bool":
            return _bool(w, key, value)
        if kind == "function":
            return _time_function(w, key, value)
        if kind == "function_pair":
            if not isinstance(value, list) or len(value) != 2:
                raise w.error("must be a pair [fx, fy] of numbers or time functions, got "
                              f"{_toml_type(value)} ({_show(value)})", key)
            return tuple(_time_function(w, key, x) for x in value)
        return value  # an argument this reader does not know: the model checks it

    def read_settings(self, table):
        w = self.where(("simulation",), "[simulation]")
        out = {}
        for key, value in table.items():
            kind = _SIMULATION.get(key)
            if kind is None:
                raise w.error("unknown key; [simulation] has: " + ", ".join(_SIMULATION), key)
            out[key] = _setting(w, key, value, kind)
        if "t_out" in out and "n_out" in out:
            raise w.error("give n_out or t_out, not both", "t_out")
        for key, allowed in (("analysis", ("auto", "dynamic", "kinematic", "inverse_dynamics")),
                             ("start", ("given", "equilibrium"))):
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
        for key in ("rtol", "atol", "max_step", "step"):
            if key in out and not (math.isfinite(out[key]) and out[key] > 0):
                raise w.error(f"must be positive and finite, got {out[key]!r}", key)
        # integers travel to C as int (n_out, max_order) or long (max_steps)
        if "n_out" in out and not 2 <= out["n_out"] <= MAX_OUTPUTS:
            raise w.error(f"must be at least 2 and at most {MAX_OUTPUTS:,}, got "
                          f"{_show(out['n_out'])}", "n_out")
        if "max_steps" in out and not 1 <= out["max_steps"] <= _MAX_STEPS:
            raise w.error(f"must be at least 1 and at most {_MAX_STEPS:.0e}, got "
                          f"{_show(out['max_steps'])}", "max_steps")
        if "max_order" in out and not 1 <= out["max_order"] <= method["max_order"]:
            raise w.error(f"must be in 1..{method['max_order']} for method {method['name']!r}, got "
                          f"{_show(out['max_order'])}", "max_order")
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
        """The entry of lagmb.methods() the settings choose (formulation,
        integrator: None for the formulation's first)."""
        from .simulation import methods

        table = methods()
        formulation = settings.get("formulation", table[0]["formulation"])
        theirs = [m for m in table if m["formulation"] == formulation]
        if not theirs:
            names = list(dict.fromkeys(m["formulation"] for m in table))
            raise w.error(f"must be one of {', '.join(map(repr, names))}, got {formulation!r}", "formulation")
        if "integrator" not in settings:
            return theirs[0]
        for m in theirs:
            if m["integrator"] == settings["integrator"]:
                return m
        raise w.error(f"must be one of {', '.join(repr(m['integrator']) for m in theirs)} for formulation "
                      f"{formulation!r}, got {settings['integrator']!r}", "integrator")

    def read_output(self, table):
        w = self.where(("output",), "[output]")
        out = {}
        for key, value in table.items():
            kind = _OUTPUT.get(key)
            if kind is None:
                raise w.error("unknown key; [output] has: " + ", ".join(_OUTPUT), key)
            out[key] = _setting(w, key, value, kind)
        for key in ("file", "plot", "animate"):
            if "\0" in out.get(key, ""):  # no file system takes it (open raises ValueError)
                raise w.error("a file name cannot contain a NUL character", key)
        if "file" in out and os.path.splitext(out["file"])[1].lower() not in _OUTPUT_FILE_TYPES:
            raise w.error(f"must end in .npz or .csv, got {out['file']!r}", "file")
        for key, problem in (("plot", _plot_format_problem),
                             ("animate", _animation_format_problem)):
            reason = problem(out[key]) if key in out else None
            if reason:
                raise w.error(f"{out[key]!r} {reason}", key)
        if out.get("reaction_frame", "global") not in ("global", "joint"):
            raise w.error(f"must be \"global\" or \"joint\", got {out['reaction_frame']!r}",
                          "reaction_frame")
        joints = [e.name for e in self.elements if e.table in ("joints", "drivers")]
        drivers = [e.name for e in self.elements if e.table == "drivers"]
        for key, known, what in (("reactions", joints, "joint or driver"),
                                 ("efforts", drivers, "driver")):
            for name in out.get(key, []):
                if name not in known:
                    raise w.error(f"no {what} named {name!r} (known: "
                                  f"{', '.join(known) or 'none'})", key)
        return out


def _plot_format_problem(path):
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


def _animation_format_problem(path):
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


def _setting(w, key, value, kind):
    if kind == "number":
        return _number(w, key, value)
    if kind == "integer":
        return _integer(w, key, value)
    if kind == "string":
        return _string(w, key, value)
    if kind == "bool":
        return _bool(w, key, value)
    if kind == "numbers":
        return _list_of(w, key, value, _number, "numbers")
    if kind == "strings":
        return _list_of(w, key, value, _string, "strings")
    raise AssertionError(kind)


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
        model: the mb.Model.
        settings: dict of mb.simulate keyword arguments from [simulation].
        output: dict from [output] (only the keys the file gives).
        path: the file.
        elements: list of SceneElement (table, type, name, line), in file order.

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
        w = _Where(self.path, self._lines or _Lines(""), ("output",), "[output]")
        return w.error(message, key)

    def run(self, **overrides):
        """mb.simulate(model, **(settings | overrides)). Overriding t_end
        keeps the file's t_out times up to the new t_end; giving n_out drops
        its t_out. A bad setting from the file raises SceneError at its line."""
        from .simulation import simulate

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
            lines = self._lines or _Lines("")
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
    return _Reader(path, text).read()


# --- writing --------------------------------------------------------------------

_ESCAPES = {'"': '\\"', "\\": "\\\\", "\b": "\\b", "\t": "\\t", "\n": "\\n", "\f": "\\f",
            "\r": "\\r"}


def _string_value(s):
    out = []
    for ch in s:
        if ch in _ESCAPES:
            out.append(_ESCAPES[ch])
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04x}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def _key(k):
    return k if _BARE_KEY.fullmatch(k) else _string_value(k)


class _NotWritable(Exception):
    pass


def _value(v):
    """A Python value as TOML text; floats by repr, so they read back exactly."""
    if isinstance(v, (bool, np.bool_)):
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):
        return str(int(v))
    if isinstance(v, numbers.Real):
        return repr(float(v))  # inf, -inf and nan are TOML too
    if isinstance(v, str):
        return _string_value(v)
    if hasattr(v, "to_dict") and callable(v.to_dict):  # a TimeFunction
        return _value(v.to_dict())
    if isinstance(v, Handle):  # elements() holds names; a handle is written as one
        return _string_value(v.name)
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(str(k))} = {_value(x)}" for k, x in v.items()) + " }"
    if isinstance(v, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if callable(v):
        raise _NotWritable("a Python callable")
    raise _NotWritable(f"a {type(v).__name__}")


def _table_lines(header, table):
    lines = [header]
    for key, value in table.items():
        if value is None:
            continue
        try:
            lines.append(f"{_key(str(key))} = {_value(value)}")
        except _NotWritable as e:
            raise SceneError(f"{_show(value)} is {e}, which a scene file cannot hold",
                             table=header, key=key) from None
    return lines


def scene_text(model, settings=None, output=None):
    """The scene file of a model (and settings, output) as a string."""
    from . import __version__

    out = [f"# lagmb {__version__} scene", ""]
    gravity = getattr(model, "gravity", None)
    if gravity is not None:
        out += ["[model]", f"gravity = {_value(tuple(gravity))}", ""]
    for method, kwargs in model.elements():
        name = kwargs.get("name")
        if method not in _TABLE_OF:
            raise SceneError(f"cannot write element {name!r}: {method} has no scene table")
        table, typ = _TABLE_OF[method]
        out.append(f"[[{table}]]")
        if typ is not None:
            out.append(f"type = {_string_value(typ)}")
        items = sorted(kwargs.items(), key=lambda kv: kv[0] != "name")
        for arg, value in items:
            if value is None:
                continue
            key = _RENAMED.get((method, arg), arg)
            try:
                text = _value(value)
            except _NotWritable as e:
                raise SceneError(
                    f"{method}: {e} cannot go in a scene file, which holds numbers and time "
                    "functions (mb.Constant, mb.Linear, mb.Polynomial, mb.Harmonic, "
                    "mb.SmoothStep, mb.Spline)", table=f"{table} {name!r}", key=key) from None
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
        _Reader(path, text).read()  # what is written must read back
    except SceneError as e:
        where = ", ".join(x for x in (e.table, e.key and f"key '{e.key}'") if x)
        error = SceneError(f"cannot write {path}: {where + ': ' if where else ''}{e.reason}")
        error.path, error.table, error.key = path, e.table, e.key
        raise error from None
    with open(path, "w", encoding="utf-8", newline="\n") as fh:
        fh.write(text)
