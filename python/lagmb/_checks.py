"""Argument checks shared by the Python API: each returns the value in the
form the core takes, or raises ModelError naming the argument. Python's
numbers reach past a double (10**400) and past what repr() prints (an int
of 5,000 digits); neither may escape as OverflowError or ValueError."""

import math
import re
import numbers

import numpy as np

from .errors import ModelError

INT_MAX = 2**31 - 1  # outputs, orders: C int in the core
_FLOATS = (float, np.float64)


def show(value):
    """repr(value), short, and safe for any value (a huge int has no repr)."""
    if isinstance(value, numbers.Integral) and not isinstance(value, bool) and abs(int(value)).bit_length() > 200:
        digits = max(1, int(abs(int(value)).bit_length() * math.log10(2)))
        return f"an integer of about {digits} digits"
    try:
        text = repr(value)
    except Exception:  # noqa: BLE001 - e.g. a list holding a huge integer
        text = f"a {type(value).__name__}"
    return text if len(text) <= 80 else text[:77] + "..."


def real(value, name):
    """A finite number given as `name`, as a float."""
    if type(value) in _FLOATS and math.isfinite(value):  # (the common case, without the ABC checks)
        return float(value)
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ModelError(f"{name} must be a number, got {show(value)}")
    try:
        value = float(value)
    except OverflowError:
        raise ModelError(f"{name} is too large for a float: {show(value)}") from None
    if not math.isfinite(value):
        raise ModelError(f"{name} must be finite, got {value!r}")
    return value


def parameters(model, values, who):
    """The compiled model `model` runs with the parameter values `values`
    ({name: number}, model.parameters names them): model.compiled() for
    None or {}, else the compiled model built with those values (the core
    checks each as add_* does; an unknown name is a ModelError listing the
    parameters)."""
    core = model.compiled()
    if values is None:
        return core
    if not isinstance(values, dict):
        raise ModelError(f"{who}: parameters must be a dict {{name: value}}, got {show(values)}")
    checked = {}
    for name, value in values.items():
        if not isinstance(name, str):
            raise ModelError(f"{who}: a parameter's name must be a string, got {show(name)}")
        checked[name] = real(value, f"{who}: parameter {name!r}")
    return core.with_parameters(checked) if checked else core


def positive(value, name):
    value = real(value, name)
    if not value > 0:
        raise ModelError(f"{name} must be positive and finite, got {value!r}")
    return value


def integer(value, name, low, high):
    """An integer in [low, high] (an integral float is accepted)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ModelError(f"{name} must be an integer, got {show(value)}")
    if not isinstance(value, numbers.Integral):
        if not (math.isfinite(value) and float(value).is_integer()):
            raise ModelError(f"{name} must be an integer, got {value!r}")
    value = int(value)
    if not low <= value <= high:
        raise ModelError(f"{name} must be in {low}..{high}, got {show(value)}")
    return value


def array(value, name):
    """A 1-D array of finite floats."""
    try:
        x = np.asarray(value, dtype=float).reshape(-1)
    except (TypeError, ValueError, OverflowError):
        raise ModelError(f"{name} must be a sequence of finite numbers, got {show(value)}") from None
    if not np.all(np.isfinite(x)):
        raise ModelError(f"{name} must hold finite numbers, got {show(value)}")
    return x


def _vector(value, name, n, what, count):
    """n finite numbers as a float array; what names them in the messages
    ("a pair of", "three ... (x, y, z)"), count alone where the shape is wrong."""
    try:
        x = np.asarray(value, dtype=float).reshape(-1)
    except (TypeError, ValueError, OverflowError):
        raise ModelError(f"{name} must be {what}, got {show(value)}") from None
    if x.shape != (n,):
        raise ModelError(f"{name} must be {count}, got {show(value)}")
    if not np.all(np.isfinite(x)):
        raise ModelError(f"{name} is not finite: {show(value)}")
    return x


def vec2(value, name):
    """A pair of finite numbers (x, y) as a float array."""
    return _vector(value, name, 2, "a pair of finite numbers", "a pair of numbers")


def vec3(value, name):
    """Three finite numbers (x, y, z) as a float array."""
    return _vector(value, name, 3, "three finite numbers (x, y, z)", "three numbers (x, y, z)")


def matrix_or_vector(value, name, length, what):
    """A vector of `length` finite numbers or a 3 x 3 matrix, as a float
    array of that shape (the core checks what the numbers mean)."""
    try:
        x = np.asarray(value, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise ModelError(f"{name} must be {what}, got {show(value)}") from None
    if x.shape not in ((length,), (3, 3)):
        raise ModelError(f"{name} must be {what}, got {show(value)}")
    if not np.all(np.isfinite(x)):
        raise ModelError(f"{name} is not finite: {show(value)}")
    return x


def flag(value, name):
    """True or False: a bool or numpy's bool (not a string, a number or an
    array, whose truth Python would guess: "False" is true)."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise ModelError(f"{name} must be True or False, got {show(value)}")


def text(value, name):
    if not isinstance(value, str):
        raise ModelError(f"{name} must be a string, got {show(value)}")
    return value


# A number as XML Schema (xsd:double) and TOML write it in ASCII: no "1_0"
# (Python's float() reads it as 10), no digits of other scripts (float()
# reads the Arabic-Indic one as 1), no hex, no surrounding words.
_DECIMAL = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_SPECIAL = {"inf": math.inf, "+inf": math.inf, "-inf": -math.inf, "nan": math.nan}


def decimal(text, name):
    """The float a decimal number written as text means (surrounding blanks
    ignored; also 'inf', '-inf' and 'nan', which callers that need finite
    values then refuse); ModelError naming `name` and the text otherwise.
    A number past a double's range is an error, not inf."""
    word = str(text).strip(" \t\r\n")
    if word.lower() in _SPECIAL:
        return _SPECIAL[word.lower()]
    if not _DECIMAL.fullmatch(word):
        raise ModelError(f"{name}: {show(word)} is not a decimal number")
    value = float(word)
    if math.isinf(value):
        raise ModelError(f"{name}: {show(word)} is too large for a float")
    return value


def string_list(value, who, what):
    """A list of strings given as a list (or tuple, ...) of them; None: []."""
    if value is None:
        return []
    if isinstance(value, (str, bytes)) or not hasattr(value, "__iter__"):
        raise ModelError(f"{who} must be a list of {what}, got {show(value)}")
    value = list(value)
    for x in value:
        if not isinstance(x, str):
            raise ModelError(f"{who} must be a list of {what}, got {show(x)} among them")
    return value
