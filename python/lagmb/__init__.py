"""lagmb: planar and spatial multibody dynamics with Lagrange multipliers.

Bodies keep Cartesian coordinates; joints add constraints Phi(q, t) = 0;
the equations M qdd + Phi_q^T lam = Q are integrated with SUNDIALS (IDAS,
CVODE or ARKODE; docs/methods.md says which method a model gets).

    import lagmb as mb
    m = mb.Model(gravity=(0.0, -9.81))
    rod = m.add_body("rod", mass=1.0, inertia=1/12, position=(0.5, 0.0))
    pin = m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    r = mb.simulate(m, t_end=2.0)
    r.reaction(pin)   # every add_* / drive_* returns a handle; names work too
"""

from . import _core
from .accuracy import METHODS, WorkPrecision, work_precision
from .errors import (AssemblyError, AssemblyWarning, DeepContactWarning, ModelError, RedundantConstraintWarning,
                     SimulationError)
from .functions import (Constant, Harmonic, Input, Linear, Polynomial, SmoothStep, Spline, TimeFunction,
                        time_function_from_dict)
from .handles import Body, Handle
from .model import Model
from ._poses import Pose, Poses
from .result import BodyPath, ContactPath, Result, Sensitivity
from .scene import Scene, SceneError, load_scene, save_scene
from .simulation import methods, simulate, solve_accelerations
from .simulator import Simulator
from .errors import EquilibriumError, KinematicOnlyError, MissingExtraError
from .statics import Equilibrium, equilibrium
from .linear import Descriptor, LinearSystem, Modes, linearize, modes
from .joints import JointSpace, inverse_dynamics
from .urdf import UrdfError, UrdfWarning, load_urdf
from .mjcf import MjcfError, MjcfWarning, load_mjcf
from .studies import sweep
from .viewer import View, view, view_mode, view_sweep

from ._version import __version__  # noqa: F401
SUNDIALS_VERSION = _core.sundials_version

__all__ = [
    "AssemblyError",
    "Body",
    "BodyPath",
    "ContactPath",
    "Constant",
    "Handle",
    "Harmonic",
    "Input",
    "Linear",
    "METHODS",
    "Model",
    "ModelError",
    "Polynomial",
    "RedundantConstraintWarning",
    "AssemblyWarning",
    "DeepContactWarning",
    "Result",
    "Sensitivity",
    "Scene",
    "SceneError",
    "SimulationError",
    "Simulator",
    "SmoothStep",
    "Spline",
    "TimeFunction",
    "WorkPrecision",
    "load_scene",
    "save_scene",
    "methods",
    "simulate",
    "solve_accelerations",
    "time_function_from_dict",
    "work_precision",
    "Equilibrium",
    "EquilibriumError",
    "KinematicOnlyError",
    "MissingExtraError",
    "equilibrium",
    "modes",
    "Modes", "LinearSystem", "Descriptor", "linearize",
    "sweep",
    "view",
    "view_mode",
    "view_sweep",
    "View",
    "JointSpace",
    "Pose",
    "Poses",
    "inverse_dynamics",
    "UrdfError",
    "UrdfWarning",
    "load_urdf",
    "MjcfError",
    "MjcfWarning",
    "load_mjcf",
    "SUNDIALS_VERSION",
]
