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

The file is read with the standard library's expat parser, which keeps the
line of every element, so that an error names the link or joint, the tag and
the line. A URDF library such as yourdfpy was measured and not used: it
accepts an unknown joint type and unknown tags without a word, keeps no line
numbers, and imports in about 3 s (trimesh).
"""

import math
import numbers
import os
import xml.parsers.expat

import numpy as np

from .errors import ModelError
from .model import Model

#: Tags read and left out by design, because they do not describe the
#: mechanism's dynamics (URDF parsers such as urdfdom, which Pinocchio uses,
#: skip them too): how to draw it (material), how controllers drive it
#: (transmission, ros2_control; a controller's safety_controller and
#: calibration), its sensors (sensor), settings of other simulators and
#: tools (gazebo; pybullet's contact; MoveIt's and ROS's self_filter,
#: collision_checking, verbose; Gazebo's kinematic and gravity flags and
#: contact surface in a link). Any other tag is a UrdfError.
IGNORED = {"robot": {"material", "transmission", "gazebo", "sensor", "ros2_control"},
           "joint": {"safety_controller", "calibration"},
           "link": {"contact", "self_filter", "collision_checking", "kinematic", "gravity", "surface"},
           "visual": {"material"},
           "collision": {"material", "verbose"}}

#: What each element may hold; anything else is a ModelError.
CHILDREN = {
    "robot": {"link", "joint"},
    "link": {"inertial", "visual", "collision"},
    "inertial": {"origin", "mass", "inertia"},
    "visual": {"origin", "geometry"},
    "collision": {"origin", "geometry"},
    "geometry": {"box", "cylinder", "sphere", "mesh"},
    "joint": {"origin", "parent", "child", "axis", "limit", "dynamics", "mimic"},
}
JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")


class UrdfError(ModelError):
    """A URDF file that cannot make a model: the message names the file,
    the line and the link or joint (a ModelError, so a ValueError)."""


class _Element:
    """One XML element: its tag, attributes, children and line."""

    __slots__ = ("tag", "attrib", "children", "line")

    def __init__(self, tag, attrib, line):
        self.tag, self.attrib, self.children, self.line = tag, attrib, [], line

    def all(self, tag):
        return [c for c in self.children if c.tag == tag]

    def one(self, tag):
        found = self.all(tag)
        return found[0] if found else None


def _read_xml(path):
    """The file's root element, every element with its line."""
    parser = xml.parsers.expat.ParserCreate()
    stack, root = [], []

    def start(tag, attrib):
        element = _Element(tag, attrib, parser.CurrentLineNumber)
        (stack[-1].children if stack else root).append(element)
        stack.append(element)

    parser.StartElementHandler = start
    parser.EndElementHandler = lambda tag: stack.pop()
    try:
        with open(path, "rb") as fh:
            parser.ParseFile(fh)
    except OSError as e:
        raise UrdfError(f"{path}: cannot read the file ({e.strerror})") from None
    except xml.parsers.expat.ExpatError as e:
        raise UrdfError(f"{path}, line {e.lineno}: not well-formed XML ({xml.parsers.expat.ErrorString(e.code)})") \
            from None
    return root[0]


def _rotation_rpy(rpy):
    """R = Rz(yaw) Ry(pitch) Rx(roll): URDF's fixed-axis roll, pitch, yaw."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


class _Reader:
    """Reads one URDF file into links, joints and the tree they make."""

    def __init__(self, path, package_dirs):
        self.path = os.fspath(path)
        # (one directory given as a string is one directory, not its letters)
        self.package_dirs = [package_dirs] if isinstance(package_dirs, (str, os.PathLike)) else \
            [os.fspath(d) for d in (package_dirs or [])]
        self.root = _read_xml(self.path)
        if self.root.tag != "robot":
            self.fail(self.root, f"the root element is <{self.root.tag}>, not <robot>")

    def fail(self, element, what, owner=None):
        where = f"{self.path}, line {element.line}"
        raise UrdfError(f"{where}: {owner + ': ' if owner else ''}{what}")

    def check_children(self, element, owner, deep=True):
        """ModelError for a tag this element (and, if deep, what it holds) may
        not hold (IGNORED ones pass)."""
        allowed, ignored = CHILDREN.get(element.tag, set()), IGNORED.get(element.tag, set())
        for child in element.children:
            if child.tag in ignored:
                continue
            if child.tag not in allowed:
                self.fail(child, f"<{child.tag}> in <{element.tag}> is not supported (lagmb reads "
                                 f"{', '.join('<' + a + '>' for a in sorted(allowed)) or 'nothing'} there)", owner)
            if deep and child.tag in CHILDREN:
                self.check_children(child, owner)

    def numbers(self, element, key, count, owner, default=None):
        text = element.attrib.get(key)
        if text is None:
            if default is None:
                self.fail(element, f"<{element.tag}> needs the attribute {key}", owner)
            return np.array(default, dtype=float)
        try:
            values = np.array([float(x) for x in text.split()])
        except ValueError:
            self.fail(element, f"<{element.tag} {key}=\"{text}\">: not {count} number(s)", owner)
        if values.size != count or not np.all(np.isfinite(values)):
            self.fail(element, f"<{element.tag} {key}=\"{text}\">: needs {count} finite number(s)", owner)
        return values

    def origin(self, element, owner):
        """(R, p) of an <origin> (identity if absent)."""
        o = element.one("origin") if element is not None else None
        if o is None:
            return np.eye(3), np.zeros(3)
        return (_rotation_rpy(self.numbers(o, "rpy", 3, owner, (0.0, 0.0, 0.0))),
                self.numbers(o, "xyz", 3, owner, (0.0, 0.0, 0.0)))

    def link(self, element):
        name = element.attrib.get("name")
        if not name:
            self.fail(element, "a <link> needs a name")
        owner = f"link '{name}'"
        self.check_children(element, owner)
        link = dict(name=name, element=element, mass=0.0, com=np.zeros(3), inertia=np.zeros((3, 3)),
                    shapes=[], inertia_element=None)
        inertial = element.one("inertial")
        if inertial is not None:
            R, p = self.origin(inertial, owner)
            mass_element = inertial.one("mass")
            if mass_element is None:
                self.fail(inertial, "<inertial> needs <mass>", owner)
            mass = float(self.numbers(mass_element, "value", 1, owner)[0])
            if mass < 0:
                self.fail(mass_element, f"mass {mass} kg is negative", owner)
            I = np.zeros((3, 3))
            tensor = inertial.one("inertia")
            if tensor is not None:
                get = {k: float(self.numbers(tensor, k, 1, owner, (0.0,))[0])
                       for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
                I = np.array([[get["ixx"], get["ixy"], get["ixz"]],
                              [get["ixy"], get["iyy"], get["iyz"]],
                              [get["ixz"], get["iyz"], get["izz"]]])
                link["inertia_element"] = tensor
            elif mass > 0:
                self.fail(inertial, "<inertial> has a mass but no <inertia>", owner)
            link.update(mass=mass, com=p, inertia=R @ I @ R.T)
        for kind in ("visual", "collision"):
            for shape in element.all(kind):
                link["shapes"].append(self.shape(shape, kind, owner))
        return link

    def shape(self, element, kind, owner):
        """A visual or collision shape: (kind, geometry, parameters, R, p)."""
        R, p = self.origin(element, owner)
        geometry = element.one("geometry")
        if geometry is None or len(geometry.children) != 1:
            self.fail(element, f"<{kind}> needs a <geometry> with one shape", owner)
        g = geometry.children[0]
        if g.tag == "box":
            values = dict(size=self.numbers(g, "size", 3, owner))
        elif g.tag == "cylinder":
            values = dict(radius=float(self.numbers(g, "radius", 1, owner)[0]),
                          length=float(self.numbers(g, "length", 1, owner)[0]))
        elif g.tag == "sphere":
            values = dict(radius=float(self.numbers(g, "radius", 1, owner)[0]))
        else:
            filename = g.attrib.get("filename")
            if not filename:
                self.fail(g, "<mesh> needs a filename", owner)
            values = dict(filename=self.resolve(filename, g, owner),
                          scale=self.numbers(g, "scale", 3, owner, (1.0, 1.0, 1.0)))
        return dict(kind=kind, geometry=g.tag, R=R, p=p, **values)

    def resolve(self, filename, element, owner):
        """The file a mesh names: package://PKG/PATH in package_dirs (each
        holding packages, or being the package), then in the directories
        above the URDF named PKG and ROS_PACKAGE_PATH; file:// and relative
        names from the URDF's directory."""
        here = os.path.dirname(os.path.abspath(self.path))
        if filename.startswith("package://"):
            # (package:///PKG/PATH, with a third slash, is read as package://PKG/PATH, as urdfdom does)
            package, _, rest = filename[len("package://"):].lstrip("/").partition("/")
            roots = list(self.package_dirs) + os.environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep)
            candidates = []
            for root in filter(None, roots):
                candidates += [os.path.join(root, package, rest)]
                if os.path.basename(os.path.normpath(root)) == package:
                    candidates.append(os.path.join(root, rest))
            up = here
            while True:
                if os.path.basename(up) == package:
                    candidates.append(os.path.join(up, rest))
                parent = os.path.dirname(up)
                if parent == up:
                    break
                up = parent
        else:
            path = filename[len("file://"):] if filename.startswith("file://") else filename
            candidates = [path if os.path.isabs(path) else os.path.join(here, path)]
        for candidate in candidates:
            if os.path.isfile(candidate):
                return os.path.normpath(candidate)
        self.fail(element, f"mesh '{filename}' not found (looked in "
                           f"{', '.join(candidates) if candidates else 'no package directory'}; "
                           "give package_dirs=[...] holding the package)", owner)

    def joint(self, element):
        name = element.attrib.get("name")
        if not name:
            self.fail(element, "a <joint> needs a name")
        owner = f"joint '{name}'"
        self.check_children(element, owner)
        kind = element.attrib.get("type")
        if kind not in JOINT_TYPES:
            self.fail(element, f"type \"{kind}\" is not a URDF joint type lagmb reads ({', '.join(JOINT_TYPES)})",
                      owner)
        ends = {}
        for end in ("parent", "child"):
            e = element.one(end)
            if e is None or not e.attrib.get("link"):
                self.fail(element, f"<{end} link=\"...\"> is missing", owner)
            ends[end] = e.attrib["link"]
        R, p = self.origin(element, owner)
        axis_element = element.one("axis")
        axis = self.numbers(axis_element, "xyz", 3, owner) if axis_element is not None else np.array([1.0, 0, 0])
        if kind in ("revolute", "continuous", "prismatic", "planar"):
            norm = np.linalg.norm(axis)
            if not norm > 0:
                self.fail(axis_element, "the axis is zero", owner)
            axis = axis / norm
        joint = dict(name=name, element=element, type=kind, parent=ends["parent"], child=ends["child"], R=R, p=p,
                     axis=axis, limit=None, damping=0.0, friction=0.0, mimic=None, elements={})
        limit = element.one("limit")
        if limit is not None and kind in ("revolute", "prismatic"):
            lower = float(self.numbers(limit, "lower", 1, owner, (0.0,))[0])
            upper = float(self.numbers(limit, "upper", 1, owner, (0.0,))[0])
            if lower < upper:
                joint["limit"] = (lower, upper)
            joint["elements"]["limit"] = limit
        dynamics = element.one("dynamics")
        if dynamics is not None:
            joint["damping"] = float(self.numbers(dynamics, "damping", 1, owner, (0.0,))[0])
            joint["friction"] = float(self.numbers(dynamics, "friction", 1, owner, (0.0,))[0])
            if joint["damping"] < 0 or joint["friction"] < 0:
                self.fail(dynamics, "damping and friction must be >= 0", owner)
            joint["elements"]["dynamics"] = dynamics
        mimic = element.one("mimic")
        if mimic is not None:
            leader = mimic.attrib.get("joint")
            if not leader:
                self.fail(mimic, "<mimic> needs the joint it mimics (joint=\"...\")", owner)
            joint["mimic"] = dict(element=mimic, joint=leader,
                                  multiplier=float(self.numbers(mimic, "multiplier", 1, owner, (1.0,))[0]),
                                  offset=float(self.numbers(mimic, "offset", 1, owner, (0.0,))[0]))
        return joint

    def read(self):
        links, joints = {}, {}
        self.check_children(self.root, None, deep=False)  # links and joints check their own
        for element in self.root.all("link"):
            link = self.link(element)
            if link["name"] in links:
                self.fail(element, f"a second link named '{link['name']}'")
            links[link["name"]] = link
        for element in self.root.all("joint"):
            joint = self.joint(element)
            if joint["name"] in joints:
                self.fail(element, f"a second joint named '{joint['name']}'")
            for end in ("parent", "child"):
                if joint[end] not in links:
                    self.fail(element, f"its {end} link '{joint[end]}' is not a link of the file", f"joint '{joint['name']}'")
            joints[joint["name"]] = joint
        if not links:
            self.fail(self.root, "the robot has no links")
        parent_joint = {}
        for joint in joints.values():
            child = joint["child"]
            if child in parent_joint:
                self.fail(joint["element"],
                          f"link '{child}' is already the child of joint '{parent_joint[child]['name']}': a URDF "
                          "describes a tree (a closed loop is a joint added to the model after loading, or an "
                          "MJCF equality constraint)", f"joint '{joint['name']}'")
            parent_joint[child] = joint
        roots = [name for name in links if name not in parent_joint]
        if len(roots) != 1:
            where = "no link is" if not roots else f"links {', '.join(repr(r) for r in roots)} are"
            raise UrdfError(f"{self.path}: {where} without a parent joint; a URDF tree has one root "
                            "(a loop of joints leaves none)")
        return links, joints, roots[0], parent_joint


def _turn(axis, angle):
    """Rotation by `angle` about the unit `axis` (Rodrigues)."""
    K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1.0 - math.cos(angle)) * (K @ K)


def _children(joints):
    out = {}
    for joint in joints.values():
        out.setdefault(joint["parent"], []).append(joint)
    return out


def load_urdf(path, *, floating_base=False, limits=True, dynamics=True, package_dirs=None,
              gravity=(0.0, 0.0, -9.81), mimic=True, positions=None):
    """A spatial :class:`lagmb.Model` of the robot a URDF file describes.

    Links joined by fixed joints become one body, named after the first link
    of the group (the one nearest the root); the root's group is the ground
    unless ``floating_base`` (then a free body). Revolute and continuous
    joints become revolute joints, prismatic ones translational joints,
    planar ones planar joints; a floating joint leaves its child free. Each
    joint keeps the URDF's name, and its angle or slide is the URDF's joint
    value (0 in the zero configuration). The model is built in the
    configuration of ``positions`` ({joint: angle or slide}, URDF names; 0
    where not given), at rest. A joint named like a link (URDF keeps the two
    apart, lagmb has one namespace) is called ``NAME_joint``.

    ``limits=True``: a revolute's or prismatic's ``<limit lower upper>``
    becomes a stop on it (``NAME_limit``, restitution 0: an impact at the
    limit; a joint that comes to rest pressing on its limit ends the run
    with SimulationError, as stops do); a joint whose zero lies outside its
    limits starts at their middle unless ``positions`` says otherwise.
    ``dynamics=True``: a revolute's, continuous's or prismatic's
    ``<dynamics damping friction>`` becomes joint friction on it
    (``NAME_damping``, or ``NAME_friction`` with a Coulomb part: viscous =
    damping, preload = friction). ``limits=False`` leaves the joints'
    position limits out; ``dynamics=False`` their damping and friction.
    ``mimic=True``: a ``<mimic joint multiplier offset>`` couples the joint
    to the one it mimics (``NAME_mimic``, a joint coupling; the follower
    starts where its leader's position puts it); ``mimic=False`` reads it
    as a joint of its own (as Pinocchio builds it by default).
    ``package_dirs``: directories holding the packages that ``package://``
    mesh names point into. Every mesh a link names must exist.

    Links merged into another's body (and the root's links) become frames
    (``model.frames``; ``r.body(link)``, ``r.point(link, p)``); visual and
    collision geometry is kept as shapes (``model.shapes``) for
    ``lagmb.plotting.picture``.

    Raises :class:`UrdfError` (a ModelError) naming the file, the line and
    the link or joint for anything lagmb does not read: an unknown tag or
    joint type, a link that is the child of two joints, a body without mass
    or inertia, a missing mesh, a mimic of an unknown joint (or of itself,
    or in a cycle), and (not built yet) revolute limits a full turn or more
    apart and damping or friction of a planar joint.
    """
    reader = _Reader(path, package_dirs)
    links, joints, root, _ = reader.read()
    positions = dict(positions or {})
    for name, value in positions.items():
        if name not in joints or joints[name]["type"] not in ("revolute", "continuous", "prismatic"):
            movable = [j["name"] for j in joints.values() if j["type"] in ("revolute", "continuous", "prismatic")]
            raise UrdfError(f"{reader.path}: positions: '{name}' is not a revolute, continuous or prismatic joint "
                            f"of the file (those are: {', '.join(movable)})")
        if isinstance(value, bool) or not (isinstance(value, numbers.Real) and math.isfinite(value)):
            raise UrdfError(f"{reader.path}: positions: joint '{name}' must be a finite number, got {value!r}")
    children = _children(joints)
    followers = _followers(reader, joints) if mimic else {}
    for name in positions:
        if name in followers:
            raise UrdfError(f"{reader.path}: positions: joint '{name}' mimics '{followers[name]['joint']}': give "
                            f"the position of '{followers[name]['joint']}' (or load with mimic=False)")
    value = _joint_values(joints, positions, followers, limits)
    for joint in joints.values():
        owner = f"joint '{joint['name']}'"
        if limits and joint["limit"] is not None and joint["type"] == "revolute" and \
                not joint["limit"][1] - joint["limit"][0] < 2 * math.pi:
            reader.fail(joint["elements"]["limit"], f"position limits {joint['limit']} span a full turn or more: "
                        "a stop reads a joint angle within one turn, so it cannot hold them yet; load with "
                        "limits=False to leave them out", owner)
        if dynamics and (joint["damping"] > 0 or joint["friction"] > 0) and joint["type"] == "planar":
            reader.fail(joint["elements"]["dynamics"], "damping and friction of a planar joint are not supported "
                        "(a revolute's, continuous's and prismatic's are): load with dynamics=False to leave "
                        "them out", owner)

    # world poses of the links in the configuration of `positions`, and their groups
    pose = {root: (np.eye(3), np.zeros(3))}
    group_of = {root: root}
    order, stack = [], [root]
    while stack:
        link = stack.pop()
        order.append(link)
        for joint in reversed(children.get(link, [])):
            R_parent, p_parent = pose[link]
            R_joint, p_joint = R_parent @ joint["R"], p_parent + R_parent @ joint["p"]  # the joint's frame
            x = value.get(joint["name"], 0.0)
            if joint["type"] in ("revolute", "continuous"):
                R_joint = R_joint @ _turn(joint["axis"], x)
            elif joint["type"] == "prismatic":
                p_joint = p_joint + R_joint @ (x * joint["axis"])
            pose[joint["child"]] = (R_joint, p_joint)
            group_of[joint["child"]] = group_of[link] if joint["type"] == "fixed" else joint["child"]
            stack.append(joint["child"])
    groups = {}
    for link in order:
        groups.setdefault(group_of[link], []).append(link)

    model = Model(gravity=tuple(float(g) for g in gravity), dimension=3)
    ground = root if not floating_base else None
    for first, members in groups.items():
        if first == ground:
            continue
        R0, p0 = pose[first]
        for m in members:  # (the links of the ground are not read beyond their names and frames)
            moments = np.linalg.eigvalsh(links[m]["inertia"])
            # (round-off in the file: 1e-9 of the largest moment, and 1e-15 kg m^2)
            if moments.min() < -1e-9 * abs(moments).max() - 1e-15:
                reader.fail(links[m]["inertia_element"], "the inertia tensor is not positive semi-definite "
                            f"(principal moments {moments.tolist()} kg m^2)", f"link '{m}'")
        mass = sum(links[m]["mass"] for m in members)
        owner = f"link '{first}'" + (f" (with {', '.join(repr(m) for m in members[1:])})" if len(members) > 1 else "")
        if not mass > 0:
            reader.fail(links[first]["element"],
                        "has no mass: a body of lagmb needs mass and inertia (give the link an <inertial>, or join "
                        "it to a body by a fixed joint)", owner)
        com = sum(links[m]["mass"] * (pose[m][1] + pose[m][0] @ links[m]["com"]) for m in members) / mass
        inertia = np.zeros((3, 3))
        for m in members:  # each link's inertia about the common centre, in world axes
            R, p = pose[m]
            d = p + R @ links[m]["com"] - com
            inertia += R @ links[m]["inertia"] @ R.T + links[m]["mass"] * (d @ d * np.eye(3) - np.outer(d, d))
        inertia_body = R0.T @ inertia @ R0
        moments = np.linalg.eigvalsh(inertia_body)
        if not moments.min() > 1e-12 * max(moments.max(), 1e-300):
            reader.fail(links[first]["element"],
                        f"its principal moments of inertia {moments.tolist()} kg m^2 are not all positive: a "
                        "body of lagmb needs every moment > 0", owner)
        try:
            model.add_body(first, mass, 0.5 * (inertia_body + inertia_body.T), position=tuple(com), orientation=R0)
        except ModelError as e:  # (the core's checks of a body: name the file's link and line)
            reader.fail(links[first]["element"], str(e), owner)

    def body(link):
        group = group_of[link]
        return "ground" if group == ground else group

    names = {}  # URDF joint name -> its name in the model

    for joint in joints.values():
        if joint["type"] in ("fixed", "floating"):
            continue
        R_parent, p_parent = pose[joint["parent"]]
        at = p_parent + R_parent @ joint["p"]
        axis = R_parent @ joint["R"] @ joint["axis"]
        parent, child = body(joint["parent"]), body(joint["child"])
        name = joint["name"]
        if name in links:  # one namespace in lagmb, two in URDF
            name = f"{name}_joint"
            if name in links or name in joints:
                reader.fail(joint["element"], f"has the name of a link, and so has '{name}'", f"joint '{joint['name']}'")
        names[joint["name"]] = name
        x = value.get(joint["name"], 0.0)
        if joint["type"] in ("revolute", "continuous"):
            model.add_revolute(name, parent, child, at=tuple(at), axis=tuple(axis), angle=x)
        elif joint["type"] == "prismatic":
            model.add_translational(name, parent, child, at=tuple(at), axis=tuple(axis), slide=x)
        else:
            model.add_planar(name, parent, child, at=tuple(at), normal=tuple(axis))
        if dynamics and (joint["damping"] > 0 or joint["friction"] > 0):  # (not planar: refused above)
            model.add_joint_friction(f"{name}_friction" if joint["friction"] > 0 else f"{name}_damping", joint=name,
                                     viscous=joint["damping"], preload=joint["friction"])
        if limits and joint["limit"] is not None:  # (revolute and prismatic joints only)
            model.add_stop(f"{name}_limit", joint=name, lower=joint["limit"][0], upper=joint["limit"][1])
    for follower, m in followers.items():  # (after every joint: a leader may come later in the file)
        model.add_joint_coupling(f"{names[follower]}_mimic", joint=names[follower], leader=names[m["joint"]],
                                 multiplier=m["multiplier"], offset=m["offset"])
    taken = {kw["name"] for _, kw in model.elements()}
    for first, members in groups.items():
        for link in members:
            R, p = pose[link]
            # (a group's first link is its body; a root link called ground is the ground)
            if (link != first or first == ground) and not (link == "ground" and first == ground):
                if link in taken:
                    reader.fail(links[link]["element"], f"its frame would take the name of the model's '{link}'",
                                f"link '{link}'")
                model.add_frame(link, body(link), position=tuple(p), orientation=R)
            for shape in links[link]["shapes"]:
                size = {"box": lambda: shape.get("size"), "cylinder": lambda: (shape["radius"], shape["length"]),
                        "sphere": lambda: (shape["radius"],), "mesh": lambda: shape["scale"]}[shape["geometry"]]()
                model.add_shape(body(link), shape["geometry"], size, position=tuple(p + R @ shape["p"]),
                                orientation=R @ shape["R"], mesh=shape.get("filename"), role=shape["kind"])
    return model


def _followers(reader, joints):
    """{joint: its <mimic>} for the joints that mimic another: both must
    have a coordinate (revolute, continuous, prismatic). A fixed joint's
    <mimic> couples nothing (it has no coordinate) and is passed over
    (Talos's gripper has such elements)."""
    moving = ("revolute", "continuous", "prismatic")
    out = {}
    for joint in joints.values():
        m = joint["mimic"]
        if m is None or joint["type"] == "fixed":
            continue
        owner = f"joint '{joint['name']}'"
        if joint["type"] not in moving:
            reader.fail(m["element"], f"a {joint['type']} joint cannot mimic (only revolute, continuous and "
                        "prismatic joints have one coordinate)", owner)
        leader = joints.get(m["joint"])
        if leader is None:
            reader.fail(m["element"], f"mimics '{m['joint']}', which is not a joint of the file", owner)
        if leader["type"] not in moving:
            reader.fail(m["element"], f"mimics '{m['joint']}', a {leader['type']} joint (a leader must be revolute, "
                        "continuous or prismatic)", owner)
        if leader["name"] == joint["name"]:
            reader.fail(m["element"], "mimics itself", owner)
        out[joint["name"]] = m
    for name in out:  # a cycle of mimics has no leader
        seen, at = [name], out[name]["joint"]
        while at in out:
            if at in seen:
                reader.fail(out[name]["element"], f"mimics in a cycle ({' -> '.join(seen + [at])})",
                            f"joint '{name}'")
            seen.append(at)
            at = out[at]["joint"]
    return out


def _joint_values(joints, positions, followers, limits):
    """Each joint's angle or slide in the configuration the model is built
    in: `positions`; where not given 0, or with `limits` the middle of the
    joint's limits if 0 lies outside them (the Panda's fourth joint); a
    mimic's multiplier x + offset of its leader's value."""
    def of(name):
        if name in followers:
            m = followers[name]
            return m["multiplier"] * of(m["joint"]) + m["offset"]
        if name in positions:
            return float(positions[name])
        limit = joints[name]["limit"]
        if limits and limit is not None and not limit[0] <= 0.0 <= limit[1]:
            return 0.5 * (limit[0] + limit[1])
        return 0.0
    return {name: of(name) for name in joints}
