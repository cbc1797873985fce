"""Python values as TOML text: for the writer, and for error messages that
quote a value or name its TOML type."""

import math
import numbers

import numpy as np

from ..handles import Handle
from .lines import BARE_KEY


def toml_type(value):
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


def show(value):
    """A value as it looks in TOML, short."""
    if _huge(value):  # str() of it is slow, or refused past 4300 digits
        return f"an integer of {_digits(value)} digits"
    try:
        text = toml_value(value)
    except Exception:  # noqa: BLE001 - only for messages
        try:
            text = repr(value)
        except Exception:  # noqa: BLE001 - e.g. a list holding a huge integer
            text = toml_type(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _huge(value):
    return isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 200


def _digits(value):
    """Decimal digits of an integer, without converting it to a string."""
    n = abs(value)
    digits = max(1, int(n.bit_length() * math.log10(2)))
    return digits + (n >= 10 ** digits)


_ESCAPES = {'"': '\\"', "\\": "\\\\", "\b": "\\b", "\t": "\\t", "\n": "\\n", "\f": "\\f",
            "\r": "\\r"}


def toml_string(s):
    out = []
    for ch in s:
        if ch in _ESCAPES:
            out.append(_ESCAPES[ch])
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04x}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def toml_key(k):
    return k if BARE_KEY.fullmatch(k) else toml_string(k)


class NotWritable(Exception):
    pass


def toml_value(v):
    """A Python value as TOML text; floats by repr, so they read back exactly."""
    if isinstance(v, (bool, np.bool_)):
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):
        return str(int(v))
    if isinstance(v, numbers.Real):
        return repr(float(v))  # inf, -inf and nan are TOML too
    if isinstance(v, str):
        return toml_string(v)
    if hasattr(v, "to_dict") and callable(v.to_dict):  # a TimeFunction
        d = v.to_dict()
        if d.get("type") == "constant":  # a number where a function goes: as it was given
            return toml_value(d["c"])
        return toml_value(d)
    if isinstance(v, Handle):  # elements() holds names; a handle is written as one
        return toml_string(v.name)
    if isinstance(v, dict):
        items = (f"{toml_key(str(k))} = {toml_value(x)}" for k, x in v.items())
        return "{ " + ", ".join(items) + " }"
    if isinstance(v, (list, tuple, np.ndarray)):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if callable(v):
        raise NotWritable("a Python callable")
    raise NotWritable(f"a {type(v).__name__}")

