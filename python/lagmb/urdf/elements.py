"""The model's elements of a URDF robot (lagmb.urdf.build's Robot): a body
per group of links, the joints with their limits (stops), damping and
friction and mimics (couplings), the links merged into others' bodies as
frames, the visual and collision shapes, and the ground contact of
``ground=``. Names are claimed in this order in the robot's namespace: the
first to claim a name keeps it.
"""

import warnings

from .._model_files import GROUND_CONTACT
from ..errors import ModelError
from .inertias import merged_inertia
from .reader import UrdfError, UrdfWarning


def _added(reader, method, element, owner, *args, **kwargs):
    """method(*args, **kwargs), the core's checks naming the file's element
    and line (a UrdfError)."""
    try:
        return method(*args, **kwargs)
    except ModelError as e:
        reader.fail(element, str(e), owner)


def add_bodies(model, robot, strict):
    """A body per group of links that moves, at its centre of mass, its
    axes the first link's (inertias.merged_inertia). Principal moments that
    break the triangle inequality are built as written with a UrdfWarning
    (strict: the core refuses them)."""
    reader, links = robot.reader, robot.links
    for first, members in robot.groups.items():
        if first == robot.ground:
            continue
        owner = f"link '{first}'" + (f" (with {', '.join(repr(m) for m in members[1:])})" if len(members) > 1 else "")
        mass, com, inertia, moments = merged_inertia(reader, links, robot.pose, members, owner)
        # (the core's test, to the same 1e-9: with strict it refuses them itself)
        rigid = strict or moments[2] <= (moments[0] + moments[1]) * (1.0 + 1e-9)
        if not rigid:
            reader.warn(links[first]["inertia_element"] or links[first]["element"],
                        f"its principal moments of inertia {moments.tolist()} kg m^2 break the triangle inequality "
                        "(no rigid body has them: the largest is more than the sum of the other two); built with "
                        "them, as Pinocchio builds them (strict=True refuses them)", owner, stacklevel=4)
        _added(reader, model.add_body, links[first]["element"], owner, robot.link_name[first], mass, inertia,
               position=tuple(com), orientation=robot.pose[first][0], rigid_inertia=rigid)


def add_joints(model, robot, limits, dynamics):
    """A revolute, translational or planar joint for each moving joint of
    the file, at its value; with `dynamics` its damping and friction
    (NAME_damping or NAME_friction), with `limits` its limits (a stop,
    NAME_limit). Returns [(the file's name, the model's)] of the joints
    named like a link (their aliases, added after the frames)."""
    reader, pose, space = robot.reader, robot.pose, robot.space
    aliased = []
    for joint in robot.joints.values():
        if joint["type"] in ("fixed", "floating"):
            continue
        R_parent, p_parent = pose[joint["parent"]]
        at = p_parent + R_parent @ joint["p"]
        axis = R_parent @ joint["R"] @ joint["axis"]
        parent, child = robot.body(joint["parent"]), robot.body(joint["child"])
        name, owner, element = robot.joint_name[joint["name"]], f"joint '{joint['name']}'", joint["element"]
        x = robot.value.get(joint["name"], 0.0)
        if joint["type"] in ("revolute", "continuous"):
            _added(reader, model.add_revolute, element, owner, name, parent, child, at=tuple(at), axis=tuple(axis),
                   angle=x)
        elif joint["type"] == "prismatic":
            _added(reader, model.add_translational, element, owner, name, parent, child, at=tuple(at),
                   axis=tuple(axis), slide=x)
        else:
            _added(reader, model.add_planar, element, owner, name, parent, child, at=tuple(at), normal=tuple(axis))
        if name != joint["name"] and robot.link_name.get(joint["name"]) == joint["name"]:  # (named like a link)
            aliased.append((joint["name"], name))
        if dynamics and (joint["damping"] > 0 or joint["friction"] > 0):  # (not planar: refused by build)
            kind = "friction" if joint["friction"] > 0 else "damping"
            _added(reader, model.add_joint_friction, joint["elements"]["dynamics"], owner,
                   space.claim(f"{name}_{kind}", kind, f"the {kind} of joint '{joint['name']}'", made=True),
                   joint=name, viscous=joint["damping"], preload=joint["friction"])
        if limits and joint["limit"] is not None:  # (revolute and prismatic joints only)
            _added(reader, model.add_stop, joint["elements"]["limit"], owner,
                   space.claim(f"{name}_limit", "limit", f"the limit of joint '{joint['name']}'", made=True),
                   joint=name, lower=joint["limit"][0], upper=joint["limit"][1])
    return aliased


def add_mimics(model, robot):
    """A joint coupling (NAME_mimic) for each follower of a mimic, after
    every joint: a leader may come later in the file."""
    joint_name = robot.joint_name
    for follower, m in robot.followers.items():
        _added(robot.reader, model.add_joint_coupling, m["element"], f"joint '{follower}'",
               robot.space.claim(f"{joint_name[follower]}_mimic", "mimic", f"the mimic of joint '{follower}'",
                                 made=True),
               joint=joint_name[follower], leader=joint_name[m["joint"]], multiplier=m["multiplier"],
               offset=m["offset"])


def add_frames_and_shapes(model, robot):
    """A frame for each link that is not its group's body (the root's
    links too; a root link called ground is the ground), and each link's
    visual and collision shapes. Returns [(link, shape)] of the collision
    shapes on moving bodies (those ``ground=`` gives a contact)."""
    reader, links = robot.reader, robot.links
    touching = []
    for first, members in robot.groups.items():
        for link in members:
            R, p = robot.pose[link]
            body = robot.body(link)
            if (link != first or first == robot.ground) and robot.link_name[link] != "ground":
                _added(reader, model.add_frame, links[link]["element"], f"link '{link}'", robot.link_name[link], body,
                       position=tuple(p), orientation=R)
            for shape in links[link]["shapes"]:
                size = {"box": lambda: shape.get("size"), "cylinder": lambda: (shape["radius"], shape["length"]),
                        "sphere": lambda: (shape["radius"],), "mesh": lambda: shape["scale"]}[shape["geometry"]]()
                try:
                    made = model.add_shape(body, shape["geometry"], size, position=tuple(p + R @ shape["p"]),
                                           orientation=R @ shape["R"], mesh=shape.get("filename"), role=shape["kind"])
                except ModelError as e:  # (the model names the body the shape is on; the file, its link)
                    reader.fail(shape["element"], f"<{shape['kind']}> " +
                                str(e).removeprefix(f"shape on '{body}': "), f"link '{link}'")
                if shape["kind"] == "collision" and body != "ground":
                    touching.append((link, made))
    return touching


def contact_law(contact):
    """The ground contact's keywords: GROUND_CONTACT updated by load_urdf's
    ``contact`` (a dict of add_contact's keywords)."""
    law = dict(GROUND_CONTACT)
    if contact is not None:
        if not isinstance(contact, dict):
            raise UrdfError(f"load_urdf: contact must be a dict of add_contact's keywords, got {contact!r}")
        unknown = sorted(set(contact) - {"stiffness", "restitution", "friction", "static_friction", "slip_velocity"})
        if unknown:
            raise UrdfError(f"load_urdf: contact has no keyword {unknown[0]!r} (stiffness, restitution, friction, "
                            "static_friction, slip_velocity)")
        law.update(contact)
    return law


def add_ground_contact(model, robot, touching, height, law):
    """``ground=height``: a plane of role "collision" on the ground through
    (0, 0, height), normal +z, and a contact (LINK_ground, LINK_ground_2,
    ...) with each collision shape of `touching`; a mesh that is not STL
    has none (a UrdfWarning names its link)."""
    floor = model.add_shape("ground", "plane", (), position=(0.0, 0.0, height), role="collision")
    count = {}
    for link, shape in touching:
        if shape.kind == "mesh" and not str(shape.mesh).lower().endswith(".stl"):
            warnings.warn(UrdfWarning(f"{robot.reader.path}: link '{link}': its collision mesh {shape.mesh!r} is not "
                                      "an STL file (lagmb reads STL only): it has no contact with the ground"),
                          stacklevel=3)
            continue
        count[link] = count.get(link, 0) + 1
        wanted = f"{robot.link_name[link]}_ground" + (f"_{count[link]}" if count[link] > 1 else "")
        name = robot.space.claim(wanted, "contact", f"the ground contact of link '{link}'", made=True)
        model.add_contact(name, shape, floor, **law)
