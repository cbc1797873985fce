"""URDF robot descriptions as lagmb models: ``mb.load_urdf``.

What each URDF element becomes is in docs/modelling.md ("Robots and model
files"). In short: the links joined by fixed joints are one rigid body
(masses, centres of mass and inertias combined, in the frame of the first
link of the group); the root link, unless ``floating_base``, is the ground;
revolute and continuous joints become spatial revolute joints, prismatic ones
translational joints, planar ones planar joints, floating ones leave the
child body free. Joint angles and slides are then lagmb's joint coordinates
(0 in the URDF's zero configuration, positive by the right-hand rule about
the axis or along it), the same numbers as the URDF's.

A module per job: ``reader`` (the XML, its tags, the links and joints),
``tree`` (the links' poses and groups), ``joint_values`` (positions, limits'
middles, mimic chains), ``mass_matrix`` (the joint-space mass matrix, CRBA),
``holding`` (joints no mass moves with; ``hold=``), ``gimbal_locks``,
``inertias`` (checked, repaired, merged), ``build`` (load_urdf, in steps)
and ``elements`` (the model's bodies, joints, limits, mimics, frames,
shapes and ground contact).
"""

from .._model_files import GROUND_CONTACT, LARGEST
from .build import load_urdf
from .gimbal_locks import LOCK_REACHED
from .mass_matrix import MOTIONLESS
from .reader import CHILDREN, IGNORED, JOINT_TYPES, MOVING, WARNED, UrdfError, UrdfWarning

__all__ = ["load_urdf", "UrdfError", "UrdfWarning", "GROUND_CONTACT", "LARGEST", "IGNORED", "WARNED", "CHILDREN",
           "JOINT_TYPES", "MOVING", "MOTIONLESS", "LOCK_REACHED"]
