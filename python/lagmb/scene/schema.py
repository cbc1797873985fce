"""What a scene may contain: its tables, the Model method behind each kind of
element, the kind of value each key takes, and the limits.

Data only (docs/scene-format.md describes the same for users): the reader
checks a file against it, the writer names tables and keys by it. An
element kind is one entry of ELEMENTS, so that a registry of element kinds
can generate them; the keys an element may have and which it needs are the
Model method's arguments (the reader asks the method's signature), ELEMENTS
gives their kinds of value.
"""

from types import MappingProxyType
from typing import Mapping, NamedTuple, Optional

# The kinds of value a key takes (the reader's checks, reader._CHECKS)
BODY = "body"  # the name of a body or particle given earlier in the file, or "ground"
JOINT = "joint"  # the name of a joint given earlier in the file
NUMBER = "number"  # an integer or float, within a float's range
INTEGER = "integer"
STRING = "string"
BOOL = "bool"
VEC2 = "vec2"  # [x, y], two numbers
FUNCTION = "function"  # a number or a time function { type = "linear", rate = ..., ... }
FUNCTION_PAIR = "function_pair"  # [fx, fy], two numbers or time functions
NUMBERS = "numbers"  # an array of numbers
STRINGS = "strings"  # an array of strings

# The tables of elements, in the order messages list them, with what one
# entry is called in messages. Each entry is one call of a Model method,
# chosen by the table and its `type` key.
ELEMENT_TABLES = {"bodies": "body", "particles": "particle", "joints": "joint",
                  "drivers": "driver", "forces": "force", "stops": "stop"}


class Element(NamedTuple):
    """One kind of element: its table, the `type` that selects it there
    (None: the table has one kind and no `type` key), the kind of value of
    each argument of its Model method, and the scene key of an argument
    where the two differ."""

    table: str
    type: Optional[str]
    arguments: Mapping[str, str]
    renamed: Mapping[str, str] = MappingProxyType({})


# Model method -> Element. A table's types are listed in messages in this order.
ELEMENTS = {
    "add_body": Element("bodies", None, dict(
        name=STRING, mass=NUMBER, inertia=NUMBER, position=VEC2, angle=NUMBER, velocity=VEC2,
        angular_velocity=NUMBER)),
    "add_particle": Element("particles", None, dict(
        name=STRING, mass=NUMBER, position=VEC2, velocity=VEC2)),
    "add_revolute": Element("joints", "revolute", dict(
        name=STRING, body_i=BODY, body_j=BODY, at=VEC2, local_i=VEC2, local_j=VEC2)),
    "add_translational": Element("joints", "translational", dict(
        name=STRING, body_i=BODY, body_j=BODY, at=VEC2, axis=VEC2)),
    "add_weld": Element("joints", "weld", dict(
        name=STRING, body_i=BODY, body_j=BODY)),
    "add_distance": Element("joints", "distance", dict(
        name=STRING, body_i=BODY, point_i=VEC2, body_j=BODY, point_j=VEC2, length=NUMBER)),
    "add_pin_in_slot": Element("joints", "pin_in_slot", dict(
        name=STRING, body_i=BODY, body_j=BODY, at=VEC2, axis=VEC2)),
    "add_gear": Element("joints", "gear", dict(
        name=STRING, body_i=BODY, body_j=BODY, ratio=NUMBER, center_i=VEC2, center_j=VEC2)),
    "add_rack_pinion": Element("joints", "rack_pinion", dict(
        name=STRING, pinion=BODY, rack=BODY, radius=NUMBER, axis=VEC2)),
    "drive_joint": Element("drivers", "joint", dict(
        name=STRING, joint=JOINT, f=FUNCTION), {"f": "function"}),
    "drive_body": Element("drivers", "body", dict(
        name=STRING, body=BODY, coordinate=STRING, f=FUNCTION), {"f": "function"}),
    "add_spring_damper": Element("forces", "spring_damper", dict(
        name=STRING, body_i=BODY, point_i=VEC2, body_j=BODY, point_j=VEC2, stiffness=NUMBER,
        damping=NUMBER, free_length=NUMBER, force=FUNCTION)),
    "add_rotational_spring_damper": Element("forces", "rotational_spring_damper", dict(
        name=STRING, body_i=BODY, body_j=BODY, stiffness=NUMBER, damping=NUMBER,
        free_angle=NUMBER, torque=FUNCTION)),
    "add_force": Element("forces", "force", dict(
        name=STRING, body=BODY, force=FUNCTION_PAIR, point=VEC2, local=BOOL)),
    "add_torque": Element("forces", "torque", dict(
        name=STRING, body=BODY, torque=FUNCTION)),
    "add_joint_friction": Element("forces", "joint_friction", dict(
        name=STRING, joint=JOINT, mu=NUMBER, viscous=NUMBER, pin_radius=NUMBER,
        bearing_length=NUMBER, preload=NUMBER, slip_velocity=NUMBER, load_smoothing=NUMBER)),
    "add_contact": Element("forces", "contact", dict(
        name=STRING, circle_body=BODY, center=VEC2, radius=NUMBER, line_body=BODY, point=VEC2,
        direction=VEC2, stiffness=NUMBER, restitution=NUMBER, friction=NUMBER,
        slip_velocity=NUMBER)),
    "add_stop": Element("stops", None, dict(
        name=STRING, joint=JOINT, lower=NUMBER, upper=NUMBER, restitution=NUMBER,
        rest_speed=NUMBER)),
}

# The other tables: key -> kind, in the order messages list them. [simulation]
# holds keyword arguments of mb.simulate ("step": the fixed step of
# formulation "ali3p"), [output] what `lagmb run` writes.
SETTINGS = {
    "model": {"gravity": VEC2},
    "simulation": {
        "t_end": NUMBER, "t0": NUMBER, "rtol": NUMBER, "atol": NUMBER, "n_out": INTEGER,
        "t_out": NUMBERS, "max_step": NUMBER, "max_steps": INTEGER, "formulation": STRING,
        "integrator": STRING, "max_order": INTEGER, "step": NUMBER, "analysis": STRING,
        "start": STRING,
    },
    "output": {
        "file": STRING, "reactions": STRINGS, "efforts": STRINGS, "reaction_frame": STRING,
        "energy": BOOL, "plot": STRING, "animate": STRING,
    },
}
# keys that take one of a few strings (formulation and integrator: lagmb.methods())
CHOICES = {
    ("simulation", "analysis"): ("auto", "dynamic", "kinematic", "inverse_dynamics"),
    ("simulation", "start"): ("given", "equilibrium"),
    ("output", "reaction_frame"): ("global", "joint"),
}
OUTPUT_FILE_TYPES = (".npz", ".csv")

TABLES = ("model",) + tuple(ELEMENT_TABLES) + ("simulation", "output")
# table -> {type: Model method}, from ELEMENTS
METHODS = {table: {e.type: method for method, e in ELEMENTS.items() if e.table == table}
           for table in ELEMENT_TABLES}

# simulate's choices (simulate.cpp checks them too, but only when a run starts)
MAX_OUTPUTS = 10_000_000  # n_out, len(t_out): each output holds q, v, a and lam
MAX_STEPS = 10**12  # max_steps travels as a C long; a bound this high is no bound
MAX_SCENE_BYTES = 16 << 20  # larger is no hand-written scene (and /dev/zero never ends)
MAX_NESTING = 32  # arrays and inline tables; a scene needs 3 (tomllib recurses per level)
