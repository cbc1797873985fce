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

from .reader import Scene, SceneElement, SceneError, load_scene
from .schema import MAX_OUTPUTS, MAX_SCENE_BYTES
from .writer import save_scene, scene_text

__all__ = ["Scene", "SceneError", "load_scene", "save_scene"]

# the public classes belong to lagmb.scene (as tracebacks and pickles name them),
# wherever in the package they are defined
for _cls in (Scene, SceneElement, SceneError):
    _cls.__module__ = __name__
del _cls
