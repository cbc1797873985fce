"""load_urdf: a URDF file's robot as a lagmb Model, in named steps: the
arguments checked, the file read (lagmb.urdf.reader), the configuration the
model is built in (joint values, mimics, joints held: _configuration), the
links grouped into bodies after the mechanism's checks (inertias, gimbal
locks, joints no mass moves with: _robot), and the model's elements added
(lagmb.urdf.elements).
"""

import collections.abc

from .. import _checks
from .._model_files import Namespace
from ..model import Model
from .elements import add_bodies, add_frames_and_shapes, add_ground_contact, add_joints, add_mimics, contact_law
from .gimbal_locks import gimbal_locks, warn_gimbal_locks
from .holding import fix, held_by_argument, hold_motionless, motionless_joints
from .inertias import check_inertias
from .joint_values import checked_positions, joint_values, mimic_followers
from .reader import Reader, UrdfError, UrdfWarning, checked_argument
from .tree import children, poses


def load_urdf(path, *, floating_base=False, limits=True, dynamics=True, package_dirs=None,
              gravity=(0.0, 0.0, -9.81), mimic=True, positions=None, hold=None, strict=False, ground=None,
              contact=None):
    """A spatial :class:`lagmb.Model` of the robot a URDF file describes.

    Links joined by fixed joints become one body, named after the first link
    of the group (the one nearest the root); the root's group is the ground
    unless ``floating_base`` (then a free body). Revolute and continuous
    joints become revolute joints, prismatic ones translational joints,
    planar ones planar joints; a floating joint leaves its child free. Each
    joint keeps the URDF's name, and its angle or slide is the URDF's joint
    value (0 in the zero configuration). The model is built in the
    configuration of ``positions`` ({joint: angle or slide}, URDF names; 0
    where not given), at rest.

    Names: lagmb has one namespace where URDF keeps links and joints apart.
    A joint named like a link is called ``NAME_joint``, and NAME is its
    alias (Model.add_joint_alias): ``r.joint(NAME)`` is the joint and
    ``r.body(NAME)`` the link's body or frame. Any other name
    already taken (a joint named ``ground``, a joint ``j_damping`` beside the
    damping of a joint ``j``) gets its kind and then a number added
    (``ground_joint``, ``j_damping_2``), and a UrdfWarning lists each change.

    ``limits=True``: a revolute's or prismatic's ``<limit lower upper>``
    becomes a stop on it (``NAME_limit``, restitution 0: an impact at the
    limit; a joint that comes to rest pressing on its limit ends the run
    with SimulationError, as stops do); a joint whose zero lies outside its
    limits starts at their middle unless ``positions`` says otherwise.
    Equal limits lock the joint at that value (it is read as a fixed joint
    there), but for 0 and 0, URDF's defaults, which files write for joints
    that turn freely (a wheel): no limits. ``lower > upper`` is an error.
    ``dynamics=True``: a revolute's, continuous's or prismatic's
    ``<dynamics damping friction>`` becomes joint friction on it
    (``NAME_damping``, or ``NAME_friction`` with a Coulomb part: viscous =
    damping, preload = friction). ``limits=False`` leaves the joints'
    position limits out; ``dynamics=False`` their damping and friction.
    ``mimic=True``: a ``<mimic joint multiplier offset>`` couples the joint
    to the one it mimics (``NAME_mimic``, a joint coupling; the follower
    starts where its leader's position puts it); ``mimic=False`` reads it
    as a joint of its own (as Pinocchio builds it by default). A mimic of a
    joint the file does not have is left out: the joint is a free joint of
    its own, and a UrdfWarning names it, its line and the missing leader.
    ``package_dirs``: directories holding the packages that ``package://``
    mesh names point into. A mesh found nowhere is left out (the dynamics
    come from ``<inertial>``) with a UrdfWarning naming its link, line and
    file.
    ``strict=False``: a body whose principal moments of inertia break the
    triangle inequality (no rigid body has them, but files hold them and
    Pinocchio runs them) is built with them and a UrdfWarning names its link
    and moments; an inertia tensor with a negative principal moment (no
    body has it, and lagmb cannot build it) is built with the nearest
    moments a rigid body has (each >= 0 and at most the sum of the other
    two, the same axes), and a UrdfWarning names its link, line and both
    sets of moments. An ``<origin>`` in a ``<link>`` is ignored with a
    UrdfWarning naming its line (as urdfdom ignores it).
    A link without mass or with a zero principal moment is a body with
    those numbers: it runs where its joints hold it (a massless link
    between two revolutes with intersecting axes). A joint whose motion no
    mass or inertia follows, in the configuration the model is built in (a
    massless finger at the end of a chain; of a motion of several joints
    that moves no mass, such as a point mass turning about the line to its
    centre on a ball of revolutes, the joint with the largest rate in it),
    is held at its initial value as a fixed joint (its limit and damping
    left out, a leader's mimics held with it), and one UrdfWarning names
    each such joint, its line and why: the joint-space mass matrix of the
    joints left free is regular (docs/modelling.md says how they are found).
    Of three revolutes in a chain whose outer axes line up at an angle of
    the middle joint (a gimbal lock) within its limits or within 1e-5 rad
    beyond one (files write pi/2 to 5 or 6 digits; any angle with
    ``limits=False`` or a continuous middle joint), where the outer joints
    turning opposite ways then moves no mass or inertia (massless links
    between them: human.urdf's neck, shoulders and hips; point masses on the
    axes: iCub's right hip), nothing is held: away from the lock the forces
    determine every joint's motion (the chain moves what it carries as a
    ball joint would), and only at the lock do they leave the outer joints'
    turning opposite ways undetermined, so a run that reaches it fails
    there. One UrdfWarning names each such middle joint, its line, the
    lock's angle and the outer joints; ``hold=[the middle joint]`` keeps
    the chain away from its lock, taking that joint's motion away.
    ``hold``: names of joints of the file (revolute, continuous or
    prismatic, not a mimic's follower) held where the model is built (at
    ``positions``) as fixed joints, their limits and damping left out, a
    leader's mimics held with it (as ``pin.buildReducedModel`` locks
    joints).
    ``strict=True`` refuses each of these instead: a triangle inequality
    broken, a negative moment, a missing mesh, a mimic of an unknown joint,
    a joint no mass moves with, a chain that can reach a gimbal lock.
    ``floating_base``, ``limits``, ``dynamics``, ``mimic`` and ``strict``
    are True or False (not strings or numbers).

    ``ground=z`` (a height, m): a plane of role "collision" on the ground
    through (0, 0, z), its outward normal +z, and a contact
    (``LINK_ground``; ``LINK_ground_2``, ... for a link's further shapes)
    between it and each collision shape of a moving body, with the values
    of ``GROUND_CONTACT`` (stiffness 1e7 N/m^1.5, restitution 0.5, friction
    0.8) updated by ``contact`` (a dict of add_contact's keywords). Links do
    not touch each other. A collision mesh that is not an STL file has no
    contact (a UrdfWarning names its link).

    Links merged into another's body (and the root's links) become frames
    (``model.frames``; ``r.body(link)``, ``r.point(link, p)``); visual and
    collision geometry is kept as shapes (``model.shapes``) for
    ``lagmb.plotting.picture``.

    Numbers are read as XML Schema writes them (``1_0`` and digits of other
    scripts are errors, not 10 and 1). Raises :class:`UrdfError` (a
    ModelError) naming the file, the line and the link or joint for
    anything lagmb does not read: an unknown tag or joint type, a link that
    is the child of two joints or of itself, a loop of joints, a file with
    no moving body (all links fixed to the root, which is the ground unless
    ``floating_base``), a mimic of itself or in a cycle, lower limit above
    the upper, a mass, length,
    inertia, joint value, mimic multiplier or offset, damping or friction
    beyond 1e150 (lagmb squares them; larger squares overflow), and (not
    built yet) damping or friction of a planar joint; and for arguments of
    the wrong kind.
    """
    floating_base, limits, dynamics, mimic, strict = (
        checked_argument(_checks.flag, value, f"load_urdf: {name}") for name, value in
        (("floating_base", floating_base), ("limits", limits), ("dynamics", dynamics), ("mimic", mimic),
         ("strict", strict)))
    gravity = checked_argument(_checks.vec3, gravity, "load_urdf: gravity")
    floor_height = None if ground is None else checked_argument(_checks.real, ground, "load_urdf: ground")
    law = contact_law(contact)
    if positions is not None and not isinstance(positions, collections.abc.Mapping):
        raise UrdfError(f"load_urdf: positions must be a dict {{joint: angle or slide}}, got {_checks.show(positions)}")
    if hold is not None and (isinstance(hold, (str, bytes, collections.abc.Mapping))
                             or not isinstance(hold, collections.abc.Iterable)):
        raise UrdfError(f"load_urdf: hold must be a list of joint names, got {_checks.show(hold)}")

    reader = Reader(path, package_dirs, strict)
    links, joints, root, _ = reader.read()
    reader.warn_missing_meshes()
    followers, value = _configuration(reader, joints, positions, hold, limits, dynamics, mimic)
    robot = _robot(reader, links, joints, root, followers, value, limits, floating_base, strict)

    model = Model(gravity=tuple(gravity), dimension=3, name=reader.root.attrib.get("name") or None)
    add_bodies(model, robot, strict)
    aliased = add_joints(model, robot, limits, dynamics)
    add_mimics(model, robot)
    touching = add_frames_and_shapes(model, robot)
    if floor_height is not None:
        add_ground_contact(model, robot, touching, floor_height, law)
    for alias, name in aliased:  # (after the frames: an alias may be a frame's name)
        model.add_joint_alias(alias, name)
    robot.space.warn(reader.path, UrdfWarning)
    return model


def _configuration(reader, joints, positions, hold_names, limits, dynamics, mimic):
    """(followers, value): the mimics that couple joints ({follower: its
    <mimic>}; none without `mimic`) and each joint's value where the model
    is built (joint_values). With `limits` a joint locked by equal limits
    is fixed at their value; the joints `hold_names` names are fixed where
    they are (with their mimics). UrdfError for a position given to a
    mimic's follower, or damping or friction of a planar joint (with
    `dynamics`)."""
    if limits:  # a joint locked by equal limits is fixed at their value
        for joint in joints.values():
            if joint["locked"] is not None:
                joint.update(moves_as=joint["type"], type="fixed")
    positions = checked_positions(reader, joints, positions or {})
    followers = mimic_followers(reader, joints) if mimic else {}
    for name in positions:
        if name in followers:
            raise UrdfError(f"{reader.path}: positions: joint '{name}' mimics '{followers[name]['joint']}': give "
                            f"the position of '{followers[name]['joint']}' (or load with mimic=False)")
    value = joint_values(reader, joints, positions, followers, limits)
    if hold_names is not None:
        fix(joints, followers, held_by_argument(reader, joints, followers, hold_names), value)
    for joint in joints.values():
        owner = f"joint '{joint['name']}'"
        if dynamics and (joint["damping"] > 0 or joint["friction"] > 0) and joint["type"] == "planar":
            reader.fail(joint["elements"]["dynamics"], "damping and friction of a planar joint are not supported "
                        "(a revolute's, continuous's and prismatic's are): load with dynamics=False to leave "
                        "them out", owner)
    return followers, value


def _robot(reader, links, joints, root, followers, value, limits, floating_base, strict):
    """The Robot in the configuration `value`, after the mechanism's
    checks: inertias no body has repaired (or refused with strict), the
    chains of revolutes that can reach a gimbal lock named, and the joints
    no mass moves with held (the links then grouped again). UrdfError if
    nothing moves."""
    below = children(joints)
    pose, group_of, order = poses(reader, joints, root, below, value)
    ground = root if not floating_base else None
    check_inertias(reader, links, [link for link in order if group_of[link] != ground], strict)
    locks = gimbal_locks(reader, links, joints, root, below, value, limits, followers, floating_base)
    if locks:
        warn_gimbal_locks(reader, joints, locks, strict)
    held = motionless_joints(reader, links, joints, order, pose, followers, floating_base)
    if held:
        hold_motionless(reader, joints, followers, held, value, strict)
        pose, group_of, order = poses(reader, joints, root, below, value)
    groups = {}
    for link in order:
        groups.setdefault(group_of[link], []).append(link)
    if list(groups) == [ground] and not any(j.get("moves_as") for j in joints.values()):  # (locked: by choice)
        joined = f" and the links fixed to it ({', '.join(repr(m) for m in groups[root][1:])})" \
            if len(groups[root]) > 1 else ""
        reader.fail(links[root]["element"], f"nothing moves: the root link{joined} {'are' if joined else 'is'} "
                    "the ground, and no joint lets a link move against it; load with floating_base=True to make the root a free body (a "
                    "flying robot)", f"link '{root}'")
    return Robot(reader, links, joints, followers, value, pose, group_of, groups, ground)


class Robot:
    """A URDF file's robot as its model is built: the file's links and
    joints (reader.read), the mimics that couple joints (followers), each
    joint's value, the links' world poses there and their groups (links
    fixed together, in the order of a walk from the root: each group one
    body, the ground's group `ground` unless floating_base), and the
    model's names (one namespace, `space`: the links' first, then the
    joints'; lagmb.urdf.elements claims the names it makes after them)."""

    def __init__(self, reader, links, joints, followers, value, pose, group_of, groups, ground):
        self.reader, self.links, self.joints, self.followers, self.value = reader, links, joints, followers, value
        self.pose, self.group_of, self.groups, self.ground = pose, group_of, groups, ground
        self.space = Namespace()
        self.link_name = {link: "ground" if link == "ground" and group_of[link] == ground else
                          self.space.claim(link, "link", f"link '{link}'") for link in links}
        self.joint_name = {name: self.space.claim(name, "joint", f"joint '{name}'", quiet=("link",))
                           for name, joint in joints.items() if joint["type"] not in ("fixed", "floating")}

    def body(self, link):
        """The model's name of the body a link is part of."""
        group = self.group_of[link]
        return "ground" if group == self.ground else self.link_name[group]
