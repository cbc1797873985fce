"""What a scene may contain: its tables, the Model method behind each kind of
element, the kind of value each key takes, and the limits.

Data only (docs/scene-format.md describes the same for users): the reader
checks a file against it, the writer names tables and keys by it. The
element tables come from the registry of element kinds (lagmb.registry):
an element's keys are its kind's parameters, which are also the arguments
of its Model method (the reader asks the method's signature).
"""

from types import MappingProxyType
from typing import Mapping, NamedTuple, Optional

from .. import _core
from ..registry import KINDS, SPATIAL_KINDS

# The kinds of value a key takes (the reader's checks, reader._CHECKS)
BODY = "body"  # the name of a body or particle given earlier in the file, or "ground"
JOINT = "joint"  # the name of a joint given earlier in the file
NUMBER = "number"  # an integer or float, within a float's range
INTEGER = "integer"
STRING = "string"
BOOL = "bool"
VEC2 = "vec2"  # [x, y], two numbers
VEC3 = "vec3"  # [x, y, z], three numbers
VECTOR = "vector"  # [x, y] or [x, y, z] (gravity: by the model's dimension)
ORIENTATION = "orientation"  # [w, x, y, z] (a unit quaternion) or [[...], [...], [...]] (a rotation matrix)
INERTIA = "inertia"  # [Ixx, Iyy, Izz] or [[...], [...], [...]] (an inertia tensor)
FUNCTION_TRIPLE = "function_triple"  # [fx, fy, fz], three numbers or time functions
FUNCTION = "function"  # a number or a time function { type = "linear", rate = ..., ... }
FUNCTION_PAIR = "function_pair"  # [fx, fy], two numbers or time functions
SHAPE = "shape"  # { body = ..., kind = ..., size = [...], position = [...], rotation = [[...]] } (body axes)
NUMBERS = "numbers"  # an array of numbers
STRINGS = "strings"  # an array of strings


class Element(NamedTuple):
    """One kind of element: its table, the `type` that selects it there
    (None: the table has one kind and no `type` key), the kind of value of
    each argument of its Model method, and the scene key of an argument
    where the two differ."""

    table: str
    type: Optional[str]
    arguments: Mapping[str, str]
    renamed: Mapping[str, str] = MappingProxyType({})


# the kind of value a scene key takes, by the type of its parameter
_VALUE_OF = {"text": STRING, "real": NUMBER, "vec2": VEC2, "bool": BOOL, "body": BODY, "joint": JOINT,
             "choice": STRING, "motion": FUNCTION, "function": FUNCTION, "function_pair": FUNCTION_PAIR,
             "vec3": VEC3, "orientation": ORIENTATION, "inertia": INERTIA, "function_triple": FUNCTION_TRIPLE,
             "shape": SHAPE}


def _element(kind):
    return Element(kind.table, kind.type, {"name": STRING, **{p.name: _VALUE_OF[p.type] for p in kind.params}},
                   MappingProxyType({p.name: p.scene_key for p in kind.params if p.scene_key != p.name}))


def _entry_word(table):
    return table[:-3] + "y" if table.endswith("ies") else table[:-1]


# Model method -> Element, from the registry of element kinds: planar
# scenes (ELEMENTS) and spatial ones ([model] dimension = 3). A table's
# types are listed in messages in this order.
ELEMENTS = {kind.method: _element(kind) for kind in KINDS}
SPATIAL_ELEMENTS = {kind.method: _element(kind) for kind in SPATIAL_KINDS}
# The tables of elements, in the order messages list them, with what one
# entry is called in messages. Each entry is one call of a Model method,
# chosen by the table and its `type` key.
ELEMENT_TABLES = {e.table: _entry_word(e.table)
                  for e in list(ELEMENTS.values()) + list(SPATIAL_ELEMENTS.values())}

# The other tables: key -> kind, in the order messages list them. [simulation]
# holds keyword arguments of mb.simulate ("step": the fixed step of
# formulation "ali3p"; "method": a name lagmb.methods() lists), [output]
# what `lagmb run` writes.
SETTINGS = {
    "model": {"dimension": INTEGER, "gravity": VECTOR},
    "simulation": {
        "t_end": NUMBER, "t0": NUMBER, "rtol": NUMBER, "atol": NUMBER, "n_out": INTEGER,
        "t_out": NUMBERS, "max_step": NUMBER, "max_steps": INTEGER, "formulation": STRING,
        "integrator": STRING, "method": STRING, "max_order": INTEGER, "step": NUMBER, "analysis": STRING,
        "start": STRING, "newton_rtol": NUMBER, "newton_atol": NUMBER,
    },
    "output": {
        "file": STRING, "reactions": STRINGS, "efforts": STRINGS, "reaction_frame": STRING,
        "energy": BOOL, "plot": STRING, "animate": STRING, "view": NUMBERS,
    },
}
# keys that take one of a few strings (formulation and integrator: lagmb.methods();
# the others as the core names them, lagmb/options.hpp)
CHOICES = {
    ("simulation", "analysis"): _core.choices()["analysis"],
    ("simulation", "start"): _core.choices()["start"],
    ("output", "reaction_frame"): ("global", "joint"),
}
OUTPUT_FILE_TYPES = (".npz", ".csv")

TABLES = ("model",) + tuple(ELEMENT_TABLES) + ("simulation", "output")
# table -> {type: Model method}, from ELEMENTS (a table with no kind in a
# dimension is empty there: [[particles]] in a spatial scene)
METHODS = {table: {e.type: method for method, e in ELEMENTS.items() if e.table == table}
           for table in ELEMENT_TABLES}
SPATIAL_METHODS = {table: {e.type: method for method, e in SPATIAL_ELEMENTS.items() if e.table == table}
                   for table in ELEMENT_TABLES}


def elements(dimension):
    """Model method -> Element in a scene of this dimension."""
    return ELEMENTS if dimension == 2 else SPATIAL_ELEMENTS


def methods(dimension):
    """table -> {type: Model method} in a scene of this dimension."""
    return METHODS if dimension == 2 else SPATIAL_METHODS

# simulate's choices (simulate.cpp checks them too, but only when a run starts)
MAX_OUTPUTS = 10_000_000  # n_out, len(t_out): each output holds q, v, a and lam
MAX_STEPS = 10**12  # max_steps travels as a C long; a bound this high is no bound
MAX_SCENE_BYTES = 16 << 20  # larger is no hand-written scene (and /dev/zero never ends)
MAX_NESTING = 32  # arrays and inline tables; a scene needs 3 (tomllib recurses per level)
