"""Functions of time for drivers and actuators, evaluated in C++ with exact
first and second derivatives (docs/modelling.md, "Time functions")."""

import numbers
import shlex
import weakref

from . import _core
from ._checks import real
from .errors import ModelError


class TimeFunction:
    """Base of the built-in time functions. ``f(t)`` returns (y, dy, ddy)."""

    _type = None
    _fields = ()

    def __init__(self, *args):
        for name, value in zip(self._fields, args):
            setattr(self, name, value)
        self._impl = self._build()

    def _build(self):
        raise NotImplementedError

    def __call__(self, t):
        return self._impl(float(t))

    def __reduce__(self):  # pickled and copied by its fields; the C++ function is built anew
        return type(self), tuple(getattr(self, name) for name in self._fields)

    def to_dict(self):
        """Plain data, e.g. {"type": "linear", "rate": 1.0, "start": 0.0}."""
        out = {"type": self._type}
        for name in self._fields:
            value = getattr(self, name)
            out[name] = list(value) if isinstance(value, (list, tuple)) else value
        return out

    def __eq__(self, other):
        return type(self) is type(other) and self.to_dict() == other.to_dict()

    def __repr__(self):
        args = ", ".join(f"{n}={getattr(self, n)!r}" for n in self._fields)
        return f"{type(self).__name__}({args})"


def _num(value, what):
    return real(value, what)


def _nums(values, what):
    try:
        values = list(values)
    except TypeError:
        raise ModelError(f"{what} must be a list of numbers, got {values!r}") from None
    return [_num(v, what) for v in values]


class Constant(TimeFunction):
    """f(t) = c"""

    _type, _fields = "constant", ("c",)

    def __init__(self, c):
        super().__init__(_num(c, "Constant: c"))

    def _build(self):
        return _core.constant(self.c)


class Linear(TimeFunction):
    """f(t) = start + rate t"""

    _type, _fields = "linear", ("rate", "start")

    def __init__(self, rate, start=0.0):
        super().__init__(_num(rate, "Linear: rate"), _num(start, "Linear: start"))

    def _build(self):
        return _core.linear(self.rate, self.start)


class Polynomial(TimeFunction):
    """f(t) = c0 + c1 t + c2 t^2 + ..."""

    _type, _fields = "polynomial", ("coeffs",)

    def __init__(self, coeffs):
        super().__init__(tuple(_nums(coeffs, "Polynomial: coeffs")))

    def _build(self):
        return _core.polynomial(list(self.coeffs))


class Harmonic(TimeFunction):
    """f(t) = offset + amplitude sin(omega t + phase)"""

    _type, _fields = "harmonic", ("amplitude", "omega", "phase", "offset")

    def __init__(self, amplitude, omega, phase=0.0, offset=0.0):
        super().__init__(_num(amplitude, "Harmonic: amplitude"), _num(omega, "Harmonic: omega"),
                         _num(phase, "Harmonic: phase"), _num(offset, "Harmonic: offset"))

    def _build(self):
        return _core.harmonic(self.amplitude, self.omega, self.phase, self.offset)


class SmoothStep(TimeFunction):
    """y0 before t0, y1 after t1, a quintic with zero velocity and
    acceleration at both ends in between."""

    _type, _fields = "smooth_step", ("t0", "t1", "y0", "y1")

    def __init__(self, t0, t1, y0, y1):
        super().__init__(_num(t0, "SmoothStep: t0"), _num(t1, "SmoothStep: t1"),
                         _num(y0, "SmoothStep: y0"), _num(y1, "SmoothStep: y1"))

    def _build(self):
        return _core.smooth_step(self.t0, self.t1, self.y0, self.y1)


class Spline(TimeFunction):
    """Natural cubic spline through (times, values); linear beyond the ends."""

    _type, _fields = "spline", ("times", "values")

    def __init__(self, times, values):
        super().__init__(tuple(_nums(times, "Spline: times")), tuple(_nums(values, "Spline: values")))

    def _build(self):
        return _core.spline(list(self.times), list(self.values))


class Input(TimeFunction):
    """A value set from outside while the model runs: give ``mb.Input(initial)``
    where a force, torque, actuator or driver takes a function of time, then
    set it with :meth:`lagmb.Simulator.set_input` (by ``name``, or by the
    element's name when not given; ``"<element>.<parameter>.x"`` where an
    element has several inputs). It holds its value between changes; a
    change is a jump, where the integrator restarts. :func:`lagmb.simulate`
    runs it at its initial value."""

    _type, _fields = "input", ("initial", "name")

    def __init__(self, initial=0.0, name=None):
        if name is not None and (not isinstance(name, str) or not name):
            raise ModelError(f"Input: name must be a non-empty string or None, got {name!r}")
        super().__init__(_num(initial, "Input: initial"), name)

    def _build(self):
        impl = _core.input(self.initial, self.name or "")
        _INPUTS[impl.identity] = self  # the model's spec gives it back as this object
        return impl

    def to_dict(self):
        out = {"type": self._type, "initial": self.initial}
        if self.name is not None:
            out["name"] = self.name
        return out

    def __eq__(self, other):  # one input is one object: two with the same values are two inputs
        return self is other

    __hash__ = object.__hash__


_TYPES = {cls._type: cls for cls in (Constant, Linear, Polynomial, Harmonic, SmoothStep, Spline, Input)}

#: The mb.Input behind each core input that lives (an input is one object).
_INPUTS = weakref.WeakValueDictionary()


def from_core(f, memo=None):
    """What a core time function of a model's spec stands for, as it was
    given: the Python callable it calls, the mb.Input it is, or the built-in
    read back from its text (exact: numbers to 17 digits). ``memo`` (a dict)
    keeps one object per core input within one reading."""
    if f.callable is not None:
        return f.callable
    if f.identity in _INPUTS:
        return _INPUTS[f.identity]
    memo = {} if memo is None else memo
    if f.identity in memo:
        return memo[f.identity]
    words = shlex.split(f.text)
    kind, args = words[0], words[1:]
    if kind == "input":
        out = Input(float(args[0]), args[1] or None)
    elif kind in ("polynomial", "spline"):  # a count, then the lists
        n = int(float(args[0]))
        numbers_ = [float(x) for x in args[1:]]
        out = Polynomial(numbers_) if kind == "polynomial" else Spline(numbers_[:n], numbers_[n:])
    else:
        out = _TYPES[kind](*(float(x) for x in args))
    memo[f.identity] = out
    return out


def time_function_from_dict(d):
    """Inverse of TimeFunction.to_dict()."""
    if not isinstance(d, dict) or "type" not in d:
        raise ModelError(f"a time function needs a 'type', got {d!r}")
    kind = d["type"]
    if kind not in _TYPES:
        raise ModelError(f"unknown time function type '{kind}' (known: {', '.join(sorted(_TYPES))})")
    cls = _TYPES[kind]
    args = {k: v for k, v in d.items() if k != "type"}
    unknown = set(args) - set(cls._fields)
    if unknown:
        raise ModelError(f"time function '{kind}': unknown key(s) {', '.join(sorted(unknown))}")
    try:
        return cls(**args)
    except TypeError as e:
        raise ModelError(f"time function '{kind}': {e}") from None


def as_time_function(value, where, derivatives=True, component=-1, components=2):
    """The C++ time function for a number, a TimeFunction or a callable.

    A callable is f(t) -> (y, dy, ddy) when derivatives are needed (drivers),
    else f(t) -> y, or f(t) -> (fx, fy) with component 0 or 1 (forces), or
    f(t) -> (x, y, z) with component 0, 1 or 2 and components=3."""
    if isinstance(value, TimeFunction):
        return value._impl
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return Constant(real(value, where))._impl  # (a non-finite number named as the argument it is)
    if callable(value):
        return _core.python_function(value, where, derivatives, component, components)
    raise ModelError(f"{where}: expected a number, a time function or a callable, got {value!r}")
