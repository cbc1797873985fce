"""What a scene may contain: its tables, the Model method behind each
element table and type, the kinds of value its keys take, and the limits.

Data only (docs/scene-format.md describes the same for users): the reader
checks a file against it, the writer names tables and keys by it.
"""

ELEMENT_TABLES = ("bodies", "particles", "joints", "drivers", "forces", "stops")
TABLES = ("model",) + ELEMENT_TABLES + ("simulation", "output")

# table -> {type: Model method}; None: the table has no `type` key
METHODS = {
    "bodies": {None: "add_body"},
    "particles": {None: "add_particle"},
    "joints": {t: "add_" + t for t in ("revolute", "translational", "weld", "distance",
                                        "pin_in_slot", "gear", "rack_pinion")},
    "drivers": {"joint": "drive_joint", "body": "drive_body"},
    "forces": {t: "add_" + t for t in ("spring_damper", "rotational_spring_damper",
                                        "force", "torque", "joint_friction", "contact")},
    "stops": {None: "add_stop"},
}
SINGULAR = {"bodies": "body", "particles": "particle", "joints": "joint", "drivers": "driver",
            "forces": "force", "stops": "stop"}
TABLE_OF = {m: (table, typ) for table, types in METHODS.items() for typ, m in types.items()}

# a method's keyword -> the scene key, where they differ
RENAMED = {("drive_joint", "f"): "function", ("drive_body", "f"): "function"}

# what the value of a key is (by key name; (method, key) where it depends on the method)
BODY_REF = {"body", "body_i", "body_j", "pinion", "rack", "circle_body", "line_body"}
VEC2 = {"position", "velocity", "at", "axis", "point", "point_i", "point_j",
        "local_i", "local_j", "center_i", "center_j", "center", "direction"}
NUMBER = {"mass", "inertia", "angle", "angular_velocity", "length", "ratio", "radius",
          "stiffness", "damping", "free_length", "free_angle",
          "mu", "viscous", "preload", "pin_radius", "bearing_length", "slip_velocity",
          "load_smoothing", "lower", "upper", "restitution", "rest_speed", "friction"}
FUNCTION = {"f", "torque", ("add_spring_damper", "force")}
FUNCTION_PAIR = {("add_force", "force")}
STRING = {"name", "coordinate"}
BOOL = {"local"}

SIMULATION = {  # key -> kind
    "t_end": "number", "t0": "number", "rtol": "number", "atol": "number",
    "n_out": "integer", "t_out": "numbers", "max_step": "number", "max_steps": "integer",
    "formulation": "string", "integrator": "string", "max_order": "integer",
    "step": "number",  # the fixed step of formulation "ali3p"
}
SIMULATION.update({"analysis": "string", "start": "string"})  # what to compute, where to start
OUTPUT = {
    "file": "string", "reactions": "strings", "efforts": "strings",
    "reaction_frame": "string", "energy": "bool", "plot": "string", "animate": "string",
}
OUTPUT_FILE_TYPES = (".npz", ".csv")

# simulate's choices (simulate.cpp checks them too, but only when a run starts)
MAX_OUTPUTS = 10_000_000  # n_out, len(t_out): each output holds q, v, a and lam
MAX_STEPS = 10**12  # max_steps travels as a C long; a bound this high is no bound
MAX_SCENE_BYTES = 16 << 20  # larger is no hand-written scene (and /dev/zero never ends)
MAX_NESTING = 32  # arrays and inline tables; a scene needs 3 (tomllib recurses per level)
