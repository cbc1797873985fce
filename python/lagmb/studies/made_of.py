"""What a sweep is made of, as its store keeps it (the store's
fingerprint): digests of its model, cases, settings and output times, and
what each output computes. A sweep run again with a store resumes only if
all of them are the same.
"""

import functools
import hashlib
import inspect
import json
import marshal
import pickle

from .outputs import BUILT_IN


def _digest(data):
    return hashlib.sha256(data).hexdigest()[:16]


def _pickled(value):
    """A digest of value's pickle (of its type's name, if it has none)."""
    try:
        return _digest(pickle.dumps(value, protocol=4))
    except Exception:  # noqa: BLE001 - any pickling failure: the type is what is known
        return _digest(f"{type(value).__module__}.{type(value).__qualname__}".encode())


def _what(f):
    """What an output computes, as its store records it: a built-in's kind
    and argument; a function's module and qualified name with a digest of
    its code (its source; the bytecode if it has none), defaults, closure
    and bound object; a partial's function and arguments; another
    callable's class and pickle. A function changed under the same name is
    another output."""
    if isinstance(f, BUILT_IN):
        return repr(f)
    if isinstance(f, functools.partial):
        return f"partial({_what(f.func)}, {_pickled((f.args, f.keywords))})"
    func = getattr(f, "__func__", f)  # a bound method: its function, and its object below
    code = getattr(func, "__code__", None)
    if code is None:  # a callable object
        return f"{type(f).__module__}.{type(f).__qualname__} ({_pickled(f)})"
    try:
        text = inspect.getsource(func).encode()
    except (OSError, TypeError):  # made by exec or at a prompt: its bytecode
        text = marshal.dumps(code)
    closure = []
    for cell in func.__closure__ or ():
        try:
            closure.append(cell.cell_contents)
        except ValueError:  # a cell not filled yet
            closure.append(None)
    state = _digest(" ".join(_pickled(v) for v in [func.__defaults__, func.__kwdefaults__,
                                                    getattr(f, "__self__", None)] + closure).encode())
    return f"{func.__module__}.{func.__qualname__} ({_digest(text)} {state})"


def made_of(text, cases, settings, outputs, t_out):
    """What a sweep is made of, as its store keeps it: a digest of the
    model, the cases, the run settings and the output times, and what each
    output computes (_what)."""
    def digest(value):
        return _digest(json.dumps(value, sort_keys=True, default=str).encode())

    return {"model": digest(text), "cases": digest(cases), "settings": digest(settings),
            "histories": digest(None if t_out is None else list(map(float, t_out))),
            "outputs": {name: _what(f) for name, f in outputs.items()}}

