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

import collections.abc
import math
import os
import re
import warnings
import xml.parsers.expat

import numpy as np

from . import _checks, _rotations
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
#: Tags left out with a UrdfWarning, because the file means something by
#: them that URDF does not say: <origin> in <link> (a link is placed by its
#: parent joint; urdfdom, which Pinocchio uses, ignores it too).
WARNED = {"link": {"origin"}}

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
MOVING = ("revolute", "continuous", "prismatic")  # the joints with one coordinate

#: The largest mass (kg), length (m), moment of inertia (kg m^2), joint value,
#: mimic multiplier or offset, damping or friction a model may hold: lagmb
#: squares them (norms of constraint rows, the parallel-axis term m d^2), and
#: past about 1e154 a square overflows a double; 1e150 leaves room for sums.
LARGEST = 1e150


class UrdfError(ModelError):
    """A URDF file that cannot make a model: the message names the file,
    the line and the link or joint (a ModelError, so a ValueError)."""


class UrdfWarning(UserWarning):
    """load_urdf read an element otherwise than the file writes it, and
    the message names the file, the line and the element: another name (one
    lagmb's one namespace already holds), an <origin> in a <link> ignored,
    an inertia no rigid body has, a mesh not found, a mimic of a joint the
    file does not have, a joint held because no mass moves with it; or it
    names what the file's robot does that a run cannot follow (a chain of
    revolutes that can reach a gimbal lock). load_urdf(strict=True)
    refuses the last five instead."""


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
    """The file's root element, every element with its line. The whole
    file is given to expat in one call: fed in blocks (ParseFile), expat
    scans an unfinished token again with each block, so one long comment
    or attribute took time quadratic in its length (10 MB: 15 s)."""
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
            data = fh.read()
    except OSError as e:
        raise UrdfError(f"{path}: cannot read the file ({e.strerror or e})") from None
    except ValueError as e:  # (a name holding a NUL character)
        raise UrdfError(f"{path}: cannot read the file ({e})") from None
    try:
        parser.Parse(data, True)
    except xml.parsers.expat.ExpatError as e:
        raise UrdfError(f"{path}, line {e.lineno}: not well-formed XML ({xml.parsers.expat.ErrorString(e.code)})") \
            from None
    except (LookupError, ValueError) as e:  # an encoding Python does not know, or expat cannot take (UTF-32)
        declared = re.match(rb"\s*<\?xml[^>]*?encoding\s*=\s*[\"']([^\"']*)", data[:1000])
        named = f" {declared.group(1).decode('ascii', 'replace')!r}" if declared else ""
        raise UrdfError(f"{path}, line {parser.CurrentLineNumber}: the XML declaration's encoding{named} cannot be "
                        f"read ({e}); write the file in UTF-8") from None
    return root[0]


_XML_BLANKS = re.compile(r"[ \t\r\n]+")


class _Reader:
    """Reads one URDF file into links, joints and the tree they make."""

    def __init__(self, path, package_dirs, strict=False):
        self.strict = strict
        self.missing_meshes = []  # (link, line, file name) of each mesh not found (strict=False)
        if not isinstance(path, (str, bytes, os.PathLike)):
            raise UrdfError(f"load_urdf: path must be a file name (a str or os.PathLike), got {_checks.show(path)}")
        self.path = os.fsdecode(path)
        # (one directory given as a string is one directory, not its letters)
        try:
            dirs = [package_dirs] if isinstance(package_dirs, (str, bytes, os.PathLike)) else \
                [] if package_dirs is None else list(package_dirs)
        except TypeError:
            dirs = None
        if dirs is None or not all(isinstance(d, (str, bytes, os.PathLike)) for d in dirs):
            raise UrdfError(f"load_urdf: package_dirs must be a directory or a list of directories, got "
                            f"{_checks.show(package_dirs)}")
        self.package_dirs = [os.fsdecode(d) for d in dirs]
        self.root = _read_xml(self.path)
        if self.root.tag != "robot":
            self.fail(self.root, f"the root element is <{self.root.tag}>, not <robot>")

    def fail(self, element, what, owner=None):
        raise UrdfError(self.at(element, what, owner))

    def warn(self, element, what, owner=None):
        warnings.warn(UrdfWarning(self.at(element, what, owner)), stacklevel=3)

    def at(self, element, what, owner):
        """A message naming the file, the element's line and its owner."""
        return f"{self.path}, line {element.line}: {owner + ': ' if owner else ''}{what}"

    def check_children(self, element, owner, deep=True):
        """ModelError for a tag this element (and, if deep, what it holds) may
        not hold (IGNORED ones pass)."""
        allowed, ignored = CHILDREN.get(element.tag, set()), IGNORED.get(element.tag, set())
        for child in element.children:
            if child.tag in WARNED.get(element.tag, ()):
                self.warn(child, f"<{child.tag}> in <{element.tag}> is ignored (URDF does not read it there; "
                                 "urdfdom ignores it too)", owner)
                continue
            if child.tag in ignored:
                continue
            if child.tag not in allowed:
                self.fail(child, f"<{child.tag}> in <{element.tag}> is not supported (lagmb reads "
                                 f"{', '.join('<' + a + '>' for a in sorted(allowed)) or 'nothing'} there)", owner)
            if deep and child.tag in CHILDREN:
                self.check_children(child, owner)

    def numbers(self, element, key, count, owner, default=None, largest=LARGEST):
        """`count` finite numbers of an attribute, each within `largest`
        (None: any finite number), written as XML Schema writes them."""
        text = element.attrib.get(key)
        if text is None:
            if default is None:
                self.fail(element, f"<{element.tag}> needs the attribute {key}", owner)
            return np.array(default, dtype=float)
        written = f"<{element.tag} {key}={_checks.show(text)}>"
        try:  # (a list is split at XML's blanks only: "1\u00a02" is no pair)
            values = np.array([_checks.decimal(word, written) for word in _XML_BLANKS.split(text.strip(" \t\r\n"))
                               if word])
        except ModelError as e:
            self.fail(element, str(e), owner)
        if values.size != count or not np.all(np.isfinite(values)):
            self.fail(element, f"{written}: needs {count} finite number{'s' if count > 1 else ''}", owner)
        if largest is not None and np.abs(values).max() > largest:
            self.fail(element, f"{written}: {np.abs(values).max():g} is beyond what a model can hold (at most "
                               f"{largest:g}: lagmb squares masses, lengths and inertias, and larger squares "
                               "overflow)", owner)
        return values

    def origin(self, element, owner):
        """(R, p) of an <origin> (identity if absent)."""
        o = element.one("origin") if element is not None else None
        if o is None:
            return np.eye(3), np.zeros(3)
        return (_rotations.from_rpy(self.numbers(o, "rpy", 3, owner, (0.0, 0.0, 0.0), largest=None)),
                self.numbers(o, "xyz", 3, owner, (0.0, 0.0, 0.0)))

    def link(self, element):
        name = element.attrib.get("name")
        if not name:
            self.fail(element, "a <link> needs a name")
        owner = f"link '{name}'"
        self.check_children(element, owner)
        link = dict(name=name, element=element, mass=0.0, com=np.zeros(3), inertia=np.zeros((3, 3)),
                    shapes=[], inertia_element=None, inertial_element=None)
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
            link.update(mass=mass, com=p, inertia=R @ I @ R.T, inertial_element=inertial)
        for kind in ("visual", "collision"):
            for shape in element.all(kind):
                read = self.shape(shape, kind, owner)
                if read is not None:
                    link["shapes"].append(read)
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
            scale = self.numbers(g, "scale", 3, owner, (1.0, 1.0, 1.0))
            found = self.resolve(filename, g, owner)
            if found is None:  # (strict=False: the shape is left out, listed in one warning)
                return None
            values = dict(filename=found, scale=scale)
        return dict(kind=kind, geometry=g.tag, R=R, p=p, element=g, **values)

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
        looked = f"looked in {', '.join(candidates) if candidates else 'no package directory'}"
        if self.strict:
            self.fail(element, f"mesh '{filename}' not found ({looked}; give package_dirs=[...] holding the "
                               "package, or load with strict=False to leave the shape out)", owner)
        self.missing_meshes.append((owner, element.line, filename, looked))
        return None

    def warn_missing_meshes(self):
        """One UrdfWarning naming each mesh not found (strict=False): the
        link, the line and the file; the shapes are left out, and the
        dynamics, which the links' <inertial> give, are the same."""
        if not self.missing_meshes:
            return
        count = len(self.missing_meshes)
        listed = "; ".join(f"{owner}, line {line}: '{filename}'" for owner, line, filename, _ in self.missing_meshes)
        warnings.warn(UrdfWarning(
            f"{self.path}: {count} mesh{'es' if count > 1 else ''} not found, {'their' if count > 1 else 'its'} "
            f"<visual>/<collision> shape{'s' if count > 1 else ''} left out (the links' <inertial> give the "
            f"dynamics, so the motion is the same): {listed} (the first {self.missing_meshes[0][3]}; give "
            "package_dirs=[...] holding the package; strict=True refuses a missing mesh)"), stacklevel=3)

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
        if ends["parent"] == ends["child"]:
            self.fail(element, f"link '{ends['child']}' is both its parent and its child", owner)
        R, p = self.origin(element, owner)
        axis_element = element.one("axis")
        axis = self.numbers(axis_element, "xyz", 3, owner, largest=None) if axis_element is not None else \
            np.array([1.0, 0, 0])
        if kind in ("revolute", "continuous", "prismatic", "planar"):
            # a direction: scaled by its largest component first, so that 1e200 or 1e-200 neither
            # overflows nor underflows in the norm
            largest = np.abs(axis).max()
            if not largest > 0:
                self.fail(axis_element, "the axis is zero", owner)
            axis = axis / largest
            axis = axis / np.linalg.norm(axis)
        joint = dict(name=name, element=element, type=kind, parent=ends["parent"], child=ends["child"], R=R, p=p,
                     axis=axis, limit=None, locked=None, damping=0.0, friction=0.0, mimic=None, elements={})
        limit = element.one("limit")
        if limit is not None and kind in ("revolute", "prismatic"):
            lower = float(self.numbers(limit, "lower", 1, owner, (0.0,), largest=None)[0])
            upper = float(self.numbers(limit, "upper", 1, owner, (0.0,), largest=None)[0])
            if lower > upper:
                self.fail(limit, f"lower limit {lower!r} is above the upper limit {upper!r}", owner)
            if lower < upper:
                joint["limit"] = (lower, upper)
            elif lower != 0.0:  # (0 and 0, URDF's defaults, are written for joints that move freely)
                joint["locked"] = lower
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
                self.fail(element, f"a second link named '{link['name']}' (the first is on line "
                                   f"{links[link['name']]['element'].line})")
            links[link["name"]] = link
        for element in self.root.all("joint"):
            joint = self.joint(element)
            if joint["name"] in joints:
                self.fail(element, f"a second joint named '{joint['name']}' (the first is on line "
                                   f"{joints[joint['name']]['element'].line})")
            for end in ("parent", "child"):
                if joint[end] not in links:
                    self.fail(element, f"its {end} link '{joint[end]}' is not a link of the file",
                              f"joint '{joint['name']}'")
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
        reached, stack, children = {roots[0]}, [roots[0]], _children(joints)
        while stack:
            for joint in children.get(stack.pop(), []):
                reached.add(joint["child"])
                stack.append(joint["child"])
        for name in links:  # a link the root does not reach hangs below a loop of joints: find the loop
            if name not in reached:
                seen, at = set(), name
                while at not in seen:  # (up its parents until one repeats: that one is in the loop)
                    seen.add(at)
                    at = parent_joint[at]["parent"]
                loop, start = [], at
                while not loop or at != start:
                    loop.append(parent_joint[at])
                    at = parent_joint[at]["parent"]
                loop.reverse()  # (parents first)
                self.fail(loop[0]["element"], "joints " + " -> ".join(repr(j["name"]) for j in loop) +
                          f" make a loop that the root link '{roots[0]}' does not reach: a URDF describes a tree "
                          "(a closed loop is a joint added to the model after loading)", f"joint '{loop[0]['name']}'")
        return links, joints, roots[0], parent_joint


def _children(joints):
    out = {}
    for joint in joints.values():
        out.setdefault(joint["parent"], []).append(joint)
    return out


class _Namespace:
    """lagmb's one namespace for the names of a file that keeps several
    (URDF: links and joints; MJCF: bodies, joints and equalities) and for
    the names lagmb makes (NAME_limit): a name is kept while free, else a
    file's element gets its kind added (NAME_joint), then a number
    (NAME_joint_2, ...; NAME_limit_2 for a made name), first claimed first
    served. Each change is listed in `renamed` for a warning, but for the
    documented one (`quiet`: a joint named like a link or body is
    NAME_joint)."""

    def __init__(self):
        self.holder = {"ground": ("ground", "the ground")}
        self.renamed = []

    def claim(self, wanted, kind, what, quiet=(), made=False):
        """The model's name for `what` ("joint 'arm'", of `kind` "joint"),
        which the file (or lagmb, `made`) calls `wanted`; `quiet`: the
        kinds whose holding `wanted` makes NAME_KIND without a warning."""
        name = wanted
        if name in self.holder and not made:
            name = f"{wanted}_{kind}"
        base, k = name, 2
        while name in self.holder:
            name, k = f"{base}_{k}", k + 1
        if name != wanted and not (name == f"{wanted}_{kind}" and self.holder[wanted][0] in quiet):
            self.renamed.append(f"{what} is '{name}' ({self.holder[wanted][1]} has the name '{wanted}')")
        self.holder[name] = (kind, what)
        return name

    def warn(self, path, category):
        if self.renamed:
            warnings.warn(category(f"{path}: lagmb keeps one namespace for all names, so: " +
                                   "; ".join(self.renamed)), stacklevel=3)


def _argument(check, value, name):
    """An argument checked by lagmb._checks, its ModelError a UrdfError."""
    try:
        return check(value, name)
    except ModelError as e:
        raise UrdfError(str(e)) from None


#: The contact between the ground and each collision shape that
#: load_urdf(ground=z) adds, unless ``contact`` says otherwise: a stiffness
#: that lets a 12 kg quadruped on four 2 cm feet sink 0.2 mm, restitution
#: 0.5 and friction 0.8 (rubber on a floor).
GROUND_CONTACT = {"stiffness": 1e7, "restitution": 0.5, "friction": 0.8}


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
        _argument(_checks.flag, value, f"load_urdf: {name}") for name, value in
        (("floating_base", floating_base), ("limits", limits), ("dynamics", dynamics), ("mimic", mimic),
         ("strict", strict)))
    gravity = _argument(_checks.vec3, gravity, "load_urdf: gravity")
    # (the name `ground` is the root link's below)
    floor_height = None if ground is None else _argument(_checks.real, ground, "load_urdf: ground")
    law = dict(GROUND_CONTACT)
    if contact is not None:
        if not isinstance(contact, dict):
            raise UrdfError(f"load_urdf: contact must be a dict of add_contact's keywords, got {contact!r}")
        unknown = sorted(set(contact) - {"stiffness", "restitution", "friction", "static_friction", "slip_velocity"})
        if unknown:
            raise UrdfError(f"load_urdf: contact has no keyword {unknown[0]!r} (stiffness, restitution, friction, "
                            "static_friction, slip_velocity)")
        law.update(contact)
    if positions is not None and not isinstance(positions, collections.abc.Mapping):
        raise UrdfError(f"load_urdf: positions must be a dict {{joint: angle or slide}}, got {_checks.show(positions)}")
    if hold is not None and (isinstance(hold, (str, bytes, collections.abc.Mapping))
                             or not isinstance(hold, collections.abc.Iterable)):
        raise UrdfError(f"load_urdf: hold must be a list of joint names, got {_checks.show(hold)}")
    reader = _Reader(path, package_dirs, strict)
    links, joints, root, _ = reader.read()
    reader.warn_missing_meshes()
    if limits:  # a joint locked by equal limits is fixed at their value
        for joint in joints.values():
            if joint["locked"] is not None:
                joint.update(moves_as=joint["type"], type="fixed")
    positions = _positions(reader, joints, positions or {})
    children = _children(joints)
    followers = _followers(reader, joints) if mimic else {}
    for name in positions:
        if name in followers:
            raise UrdfError(f"{reader.path}: positions: joint '{name}' mimics '{followers[name]['joint']}': give "
                            f"the position of '{followers[name]['joint']}' (or load with mimic=False)")
    value = _joint_values(reader, joints, positions, followers, limits)
    if hold is not None:
        _fix(joints, followers, _held_by_argument(reader, joints, followers, hold), value)
    for joint in joints.values():
        owner = f"joint '{joint['name']}'"
        if dynamics and (joint["damping"] > 0 or joint["friction"] > 0) and joint["type"] == "planar":
            reader.fail(joint["elements"]["dynamics"], "damping and friction of a planar joint are not supported "
                        "(a revolute's, continuous's and prismatic's are): load with dynamics=False to leave "
                        "them out", owner)

    # world poses of the links in the configuration of `positions`, and their groups
    pose, group_of, order = _poses(reader, joints, root, children, value)
    ground = root if not floating_base else None
    _check_inertias(reader, links, [link for link in order if group_of[link] != ground], strict)
    locks = _gimbal_locks(reader, links, joints, root, children, value, limits, followers, floating_base)
    if locks:
        _warn_gimbal_locks(reader, joints, locks, strict)
    held = _held_joints(reader, links, joints, order, pose, followers, floating_base)
    if held:
        _hold(reader, joints, followers, held, value, strict)
        pose, group_of, order = _poses(reader, joints, root, children, value)
    groups = {}
    for link in order:
        groups.setdefault(group_of[link], []).append(link)
    if list(groups) == [ground] and not any(j.get("moves_as") for j in joints.values()):  # (locked: by choice)
        joined = f" and the links fixed to it ({', '.join(repr(m) for m in groups[root][1:])})" \
            if len(groups[root]) > 1 else ""
        reader.fail(links[root]["element"], f"nothing moves: the root link{joined} {'are' if joined else 'is'} "
                    "the ground, and no joint lets a link move against it; load with floating_base=True to make the root a free body (a "
                    "flying robot)", f"link '{root}'")

    # names: the links', then the joints', then those lagmb makes
    space = _Namespace()
    link_name = {link: "ground" if link == "ground" and group_of[link] == ground else
                 space.claim(link, "link", f"link '{link}'") for link in links}
    joint_name = {name: space.claim(name, "joint", f"joint '{name}'", quiet=("link",))
                  for name, joint in joints.items() if joint["type"] not in ("fixed", "floating")}

    def body(link):
        group = group_of[link]
        return "ground" if group == ground else link_name[group]

    def add(method, element, owner, *args, **kwargs):  # (the core's checks, naming the file's element and line)
        try:
            return method(*args, **kwargs)
        except ModelError as e:
            reader.fail(element, str(e), owner)

    model = Model(gravity=tuple(gravity), dimension=3, name=reader.root.attrib.get("name") or None)
    aliased = []  # (the file's name, the model's) of each joint named like a link
    for first, members in groups.items():
        if first == ground:
            continue
        R0, p0 = pose[first]
        mass = sum(links[m]["mass"] for m in members)
        owner = f"link '{first}'" + (f" (with {', '.join(repr(m) for m in members[1:])})" if len(members) > 1 else "")
        centres = {m: pose[m][1] + pose[m][0] @ links[m]["com"] for m in members}
        for m in members:
            if links[m]["mass"] > 0 and np.abs(centres[m]).max() > LARGEST:
                reader.fail(links[m]["inertial_element"], f"its centre of mass is {np.abs(centres[m]).max():g} m from "
                            f"the root: beyond what a model can hold (at most {LARGEST:g} m)", f"link '{m}'")
        # (a massless group: its first link's origin)
        com = sum(links[m]["mass"] * centres[m] for m in members) / mass if mass > 0 else pose[first][1]
        inertia = np.zeros((3, 3))
        with np.errstate(over="ignore", invalid="ignore"):  # (m d^2 may overflow: refused below)
            for m in members:  # each link's inertia about the common centre, in world axes
                R, p = pose[m]
                d = centres[m] - com
                inertia += R @ links[m]["inertia"] @ R.T + links[m]["mass"] * (d @ d * np.eye(3) - np.outer(d, d))
        if not (np.all(np.isfinite(inertia)) and np.abs(inertia).max() <= LARGEST and mass <= LARGEST):
            reader.fail(links[first]["element"], f"mass {mass:g} kg, inertia about its centre of mass up to "
                        f"{np.abs(inertia).max():g} kg m^2: beyond what a model can hold (at most {LARGEST:g})", owner)
        inertia_body = R0.T @ inertia @ R0
        moments, axes = np.linalg.eigh(0.5 * (inertia_body + inertia_body.T))
        # a zero moment (a massless link, a point mass) as exactly 0, not round-off: the body runs through the
        # augmented system's LU where its joints hold it (simulate names it where they do not)
        zero = moments <= 1e-9 * abs(moments).max() + 1e-15
        if zero.any():
            moments = np.where(zero, 0.0, moments)
            inertia_body = axes @ np.diag(moments) @ axes.T
        # (the core's test, to the same 1e-9: with strict it refuses them itself)
        rigid = strict or moments[2] <= (moments[0] + moments[1]) * (1.0 + 1e-9)
        if not rigid:
            reader.warn(links[first]["inertia_element"] or links[first]["element"],
                        f"its principal moments of inertia {moments.tolist()} kg m^2 break the triangle inequality "
                        "(no rigid body has them: the largest is more than the sum of the other two); built with "
                        "them, as Pinocchio builds them (strict=True refuses them)", owner)
        add(model.add_body, links[first]["element"], owner, link_name[first], mass,
            0.5 * (inertia_body + inertia_body.T), position=tuple(com), orientation=R0, rigid_inertia=rigid)

    for joint in joints.values():
        if joint["type"] in ("fixed", "floating"):
            continue
        R_parent, p_parent = pose[joint["parent"]]
        at = p_parent + R_parent @ joint["p"]
        axis = R_parent @ joint["R"] @ joint["axis"]
        parent, child = body(joint["parent"]), body(joint["child"])
        name, owner, element = joint_name[joint["name"]], f"joint '{joint['name']}'", joint["element"]
        x = value.get(joint["name"], 0.0)
        if joint["type"] in ("revolute", "continuous"):
            add(model.add_revolute, element, owner, name, parent, child, at=tuple(at), axis=tuple(axis), angle=x)
        elif joint["type"] == "prismatic":
            add(model.add_translational, element, owner, name, parent, child, at=tuple(at), axis=tuple(axis),
                slide=x)
        else:
            add(model.add_planar, element, owner, name, parent, child, at=tuple(at), normal=tuple(axis))
        if name != joint["name"] and link_name.get(joint["name"]) == joint["name"]:  # (named like a link)
            aliased.append((joint["name"], name))
        if dynamics and (joint["damping"] > 0 or joint["friction"] > 0):  # (not planar: refused above)
            kind = "friction" if joint["friction"] > 0 else "damping"
            add(model.add_joint_friction, joint["elements"]["dynamics"], owner,
                space.claim(f"{name}_{kind}", kind, f"the {kind} of joint '{joint['name']}'", made=True), joint=name,
                viscous=joint["damping"], preload=joint["friction"])
        if limits and joint["limit"] is not None:  # (revolute and prismatic joints only)
            add(model.add_stop, joint["elements"]["limit"], owner,
                space.claim(f"{name}_limit", "limit", f"the limit of joint '{joint['name']}'", made=True), joint=name,
                lower=joint["limit"][0], upper=joint["limit"][1])
    for follower, m in followers.items():  # (after every joint: a leader may come later in the file)
        add(model.add_joint_coupling, m["element"], f"joint '{follower}'",
            space.claim(f"{joint_name[follower]}_mimic", "mimic", f"the mimic of joint '{follower}'", made=True),
            joint=joint_name[follower], leader=joint_name[m["joint"]], multiplier=m["multiplier"], offset=m["offset"])
    touching = []  # (link, its collision shape on a moving body)
    for first, members in groups.items():
        for link in members:
            R, p = pose[link]
            # (a group's first link is its body; a root link called ground is the ground)
            if (link != first or first == ground) and link_name[link] != "ground":
                add(model.add_frame, links[link]["element"], f"link '{link}'", link_name[link], body(link),
                    position=tuple(p), orientation=R)
            for shape in links[link]["shapes"]:
                size = {"box": lambda: shape.get("size"), "cylinder": lambda: (shape["radius"], shape["length"]),
                        "sphere": lambda: (shape["radius"],), "mesh": lambda: shape["scale"]}[shape["geometry"]]()
                try:
                    made = model.add_shape(body(link), shape["geometry"], size, position=tuple(p + R @ shape["p"]),
                                           orientation=R @ shape["R"], mesh=shape.get("filename"), role=shape["kind"])
                except ModelError as e:  # (the model names the body the shape is on; the file, its link)
                    reader.fail(shape["element"], f"<{shape['kind']}> " +
                                str(e).removeprefix(f"shape on '{body(link)}': "), f"link '{link}'")
                if shape["kind"] == "collision" and body(link) != "ground":
                    touching.append((link, made))
    if floor_height is not None:
        floor = model.add_shape("ground", "plane", (), position=(0.0, 0.0, floor_height), role="collision")
        count = {}
        for link, shape in touching:
            if shape.kind == "mesh" and not str(shape.mesh).lower().endswith(".stl"):
                warnings.warn(UrdfWarning(f"{reader.path}: link '{link}': its collision mesh {shape.mesh!r} is not "
                                          "an STL file (lagmb reads STL only): it has no contact with the ground"),
                              stacklevel=2)
                continue
            count[link] = count.get(link, 0) + 1
            wanted = f"{link_name[link]}_ground" + (f"_{count[link]}" if count[link] > 1 else "")
            name = space.claim(wanted, "contact", f"the ground contact of link '{link}'", made=True)
            model.add_contact(name, shape, floor, **law)
    for alias, name in aliased:  # (after the frames: an alias may be a frame's name)
        model.add_joint_alias(alias, name)
    space.warn(reader.path, UrdfWarning)
    return model


def _poses(reader, joints, root, children, value):
    """The world pose (R, p) of each link in the configuration `value`, the
    first link of the group of links fixed together that each belongs to,
    and the links in the order of a walk from the root (parents first)."""
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
            moves_as = joint.get("moves_as", joint["type"])
            if moves_as in ("revolute", "continuous"):
                R_joint = R_joint @ _rotations.turn(joint["axis"], x)
            elif moves_as == "prismatic":
                p_joint = p_joint + R_joint @ (x * joint["axis"])
            if np.abs(p_joint).max() > LARGEST:  # (origins within LARGEST each, but many in a chain)
                reader.fail(joint["element"], f"puts link '{joint['child']}' {np.abs(p_joint).max():g} m from the "
                            f"root: beyond what a model can hold (at most {LARGEST:g} m: lagmb squares lengths, and "
                            "larger squares overflow)", f"joint '{joint['name']}'")
            pose[joint["child"]] = (R_joint, p_joint)
            group_of[joint["child"]] = group_of[link] if joint["type"] == "fixed" else joint["child"]
            stack.append(joint["child"])
    return pose, group_of, order


def _check_inertias(reader, links, names, strict):
    """Each of these links' inertia tensor positive semi-definite (to
    round-off: 1e-9 of the largest moment, and 1e-15 kg m^2). One that is
    not (no body has it; Romeo's hips in romeo_laas_small.urdf) is refused
    with strict; else it is built with the nearest principal moments a
    rigid body can have (about the same axes), and one UrdfWarning names
    each link, its line and its moments as written and as built."""
    repaired = []
    for name in names:
        link = links[name]
        moments, axes = np.linalg.eigh(link["inertia"])
        if moments.min() >= -1e-9 * abs(moments).max() - 1e-15:
            continue
        written = f"principal moments {moments.tolist()} kg m^2"
        if strict:
            reader.fail(link["inertia_element"], f"the inertia tensor is not positive semi-definite ({written}; "
                        "strict=False builds it with the nearest moments a rigid body can have)", f"link '{name}'")
        built = _nearest_rigid_moments(moments)
        link["inertia"] = axes @ np.diag(built) @ axes.T
        repaired.append(f"link '{name}', line {link['inertia_element'].line}: {written}, built with "
                        f"{built.tolist()}")
    if repaired:
        warnings.warn(UrdfWarning(
            f"{reader.path}: {len(repaired)} inertia tensor{'s are' if len(repaired) > 1 else ' is'} not positive "
            "semi-definite (no body has such a tensor), each built with the nearest principal moments a rigid body "
            "can have (each >= 0 and at most the sum of the other two; the same axes; strict=True refuses "
            f"them): {'; '.join(repaired)}"), stacklevel=3)


def _nearest_rigid_moments(moments):
    """The principal moments nearest to `moments` (Euclidean) that a rigid
    body has: each >= 0 and at most the sum of the other two. The set is a
    cone cut by six planes through 0, so the nearest point is the projection
    onto the planes of one set of them (its active constraints): each of
    the 64 sets tried, the nearest feasible point kept."""
    rows = np.vstack([np.eye(3), np.ones((3, 3)) - 2 * np.eye(3)])  # (l_i >= 0; l_j + l_k - l_i >= 0)
    best, distance = np.zeros(3), np.linalg.norm(moments)
    for mask in range(1, 64):
        A = rows[[k for k in range(6) if mask >> k & 1]]
        point = moments - A.T @ np.linalg.lstsq(A @ A.T, A @ moments, rcond=None)[0]
        if np.all(rows @ point >= -1e-12 * np.abs(moments).max()) and np.linalg.norm(point - moments) < distance:
            best, distance = point, np.linalg.norm(point - moments)
    return np.maximum(best, 0.0)


#: A joint coordinate moves no mass or inertia where its diagonal entry of
#: the joint-space mass matrix is at most this fraction of the largest
#: diagonal entry; a combination of coordinates does where the mass matrix
#: scaled to a unit diagonal has an eigenvalue at most this fraction of its
#: largest (the core's test of the augmented matrix at the start is 1e-12
#: of the largest eigenvalue too).
MOTIONLESS = 1e-12

#: A gimbal lock of three revolutes at most this far (rad) beyond the middle
#: joint's limit counts as within it: files write pi/2 to 5 or 6 digits
#: (human.urdf's 1.5708, 3.7e-6 beyond; 1.570795, 1.3e-6 short), and with
#: the middle joint on such a limit the outer joints' turning opposite ways
#: has about angle^2 / 2 (5e-11 here) of the inertia of turning one of them.
LOCK_REACHED = 1e-5


def _mass_matrix(links, joints, order, pose, followers, floating_base):
    """The joint-space mass matrix M (Sum over links of m J_c^T J_c +
    J_w^T I J_w, with each independent coordinate's twist at its joint) in
    the configuration of `pose`, and the joint of each of its columns (None:
    a planar, floating or base coordinate); (None, columns) where no column
    is a joint that can be held or M is not finite.

    Summed as the composite-rigid-body algorithm sums it: with s_k the
    unit twists (angular velocity, velocity of the point at the world
    origin) of the coordinates, and S_k the spatial inertia about the
    origin of every link that s_k moves, [[J_O, [h]x], [[h]x^T, m 1]]
    (mass m, first moment h, inertia J_O about the origin, summed from the
    leaves up), each pair of twists i above (or at) k adds s_i^T S_k s_k to
    M[c_i, c_k] and M[c_k, c_i] (a mimic's follower adds to its leader's
    column): time linear in the links times the depth of the tree, where
    summing the links' m J_c^T J_c would be cubic in a long chain."""
    columns = {}  # independent coordinate -> its column
    holdable = []  # the joint of each column that may be held (None: a planar, floating or base coordinate)
    twists = {}  # joint -> [(column, twist (angular, velocity of the point at the world origin))]
    leaders = _leaders(followers)

    def column(key, joint):
        if key not in columns:
            columns[key] = len(holdable)
            holdable.append(joint)
        return columns[key]

    def free_twists(key, origin):
        out = []
        for k, e in enumerate(np.eye(3)):
            out.append((column((key, k), None), np.concatenate([np.zeros(3), e])))
            out.append((column((key, 3 + k), None), np.concatenate([e, np.cross(origin, e)])))
        return out

    for joint in joints.values():
        kind = joint["type"]
        if kind == "fixed":
            continue
        R_parent, p_parent = pose[joint["parent"]]
        at = p_parent + R_parent @ joint["p"]
        axis = R_parent @ joint["R"] @ joint["axis"]
        if kind in MOVING:
            leader, factor = leaders.get(joint["name"], (joint["name"], 1.0))
            twist = np.concatenate([axis, np.cross(at, axis)]) if kind in ("revolute", "continuous") else \
                np.concatenate([np.zeros(3), axis])
            twists[joint["name"]] = [(column(leader, leader), factor * twist)]
        elif kind == "planar":
            u = np.linalg.svd(axis[None, :])[2][1:]  # (two directions in the plane)
            twists[joint["name"]] = [(column((joint["name"], k), None), np.concatenate([np.zeros(3), u[k]]))
                                     for k in (0, 1)] + \
                [(column((joint["name"], 2), None), np.concatenate([axis, np.cross(at, axis)]))]
        else:  # floating
            twists[joint["name"]] = free_twists(joint["name"], pose[joint["child"]][1])
    root = order[0]
    base = free_twists(("base",), pose[root][1]) if floating_base else []
    n = len(holdable)
    if not any(h is not None for h in holdable):
        return None, holdable
    parent_joint = {joint["child"]: joint for joint in joints.values()}
    M = np.zeros((n, n))
    below = {}  # link -> the spatial inertia of it and the links below it
    for link, (m, h, J) in _subtree_inertias(links, joints, order, pose).items():
        h = np.cross(np.eye(3), h)  # ([h]x: its rows e_i x h)
        below[link] = np.block([[J, h], [h.T, m * np.eye(3)]])
    with np.errstate(all="ignore"):  # (values beyond what a model holds: refused when the bodies are built)
        # the twists above each link, walked in `order` (parents first, each subtree in turn): a link's
        # ancestors' twists are the first `depth[parent]` rows, which its siblings' subtrees leave alone
        rows = len(base) + sum(len(t) for t in twists.values())
        path, path_columns, depth = np.zeros((rows, 6)), np.zeros(rows, dtype=int), {}

        def add(link, moving, start):
            for q, (c, twist) in enumerate(moving):
                path[start + q], path_columns[start + q] = twist, c
                values = path[:start + q + 1] @ (below[link] @ twist)
                np.add.at(M, (path_columns[:start + q + 1], c), values)
                np.add.at(M, (c, path_columns[:start + q]), values[:-1])
            depth[link] = start + len(moving)

        add(root, base, 0)
        for link in order[1:]:
            joint = parent_joint[link]
            add(link, twists.get(joint["name"], ()), depth[joint["parent"]])
    if not np.all(np.isfinite(M)):
        return None, holdable
    return 0.5 * (M + M.T), holdable


def _zero_modes(M):
    """How many motions of the coordinates move no mass or inertia: the
    coordinates whose diagonal entry of M is at most MOTIONLESS of the
    largest, and the eigenvalues of the rest, scaled to a unit diagonal, at
    most MOTIONLESS of the largest."""
    diagonal = np.diag(M)
    zero = diagonal <= MOTIONLESS * diagonal.max()
    rest = np.flatnonzero(~zero)
    if rest.size == 0:
        return int(zero.sum())
    scale = 1.0 / np.sqrt(diagonal[rest])
    values = np.linalg.eigvalsh(M[np.ix_(rest, rest)] * np.outer(scale, scale))
    return int(zero.sum()) + int(np.sum(values <= MOTIONLESS * values.max()))


def _held_joints(reader, links, joints, order, pose, followers, floating_base):
    """The joints whose motion no mass or inertia follows, in the
    configuration the model is built in: [(joint, partners)], partners None
    for a joint whose coordinate alone moves no mass or inertia (a massless
    finger), else [(joint, rate)] of a motion of several joints that moves
    none (icub's point-mass head, turning about the line from the neck to
    its centre of mass) in which this joint takes part (rates scaled to at
    most 1). Only revolute, continuous and prismatic joints that mimic none
    are held; a mimic's follower is held with its leader.

    The joint-space mass matrix M (Sum over links of m J_c^T J_c +
    J_w^T I J_w, with each independent coordinate's twist at its joint) is
    read first on its diagonal: a coordinate that moves no mass is held;
    then the rest, scaled to a unit diagonal, by its eigenvalues: for each
    (numerically) zero one a joint of its null space is held, the one with
    the largest rate in what is left of it (a QR with column pivoting of
    the null space in joint rates), so that the joints that stay free have a
    regular mass matrix."""
    M, holdable = _mass_matrix(links, joints, order, pose, followers, floating_base)
    if M is None:
        return []
    n = len(holdable)
    diagonal = np.diag(M).copy()
    largest = diagonal.max()
    zero = diagonal <= MOTIONLESS * largest
    held = [(holdable[c], None) for c in range(n) if zero[c] and holdable[c] is not None]
    rest = np.flatnonzero(~zero)
    if rest.size == 0:
        return held
    scale = 1.0 / np.sqrt(diagonal[rest])
    scaled = M[np.ix_(rest, rest)] * np.outer(scale, scale)
    values = np.linalg.eigvalsh(scaled)  # (the vectors, several times the work, only where needed)
    if not np.any(values <= MOTIONLESS * values.max()):
        return held
    values, vectors = np.linalg.eigh(scaled)
    null = vectors[:, values <= MOTIONLESS * values.max()]
    if null.shape[1] == 0:
        return held
    rates = np.linalg.qr(null * scale[:, None])[0]  # (the null space in joint rates, orthonormal)
    left = rates.copy()
    can = np.array([holdable[c] is not None for c in rest])
    for _ in range(null.shape[1]):  # pivoted: the joint with the largest rate in what is left of the null space
        norms = np.where(can, np.linalg.norm(left, axis=1), 0.0)
        k = int(np.argmax(norms))
        if norms[k] <= 1e-6:  # (what is left moves no joint that can be held: simulate names it)
            break
        direction = left[k] / norms[k]
        v = left @ direction  # the motion of what is left where this joint's rate is largest
        left = left - np.outer(v, direction)
        can[k] = False
        v = v / np.abs(v).max()
        partners = [(holdable[rest[i]] if holdable[rest[i]] is not None else "a planar or floating joint",
                     float(v[i])) for i in np.argsort(-np.abs(v)) if abs(v[i]) > 1e-6]
        held.append((holdable[rest[k]], partners))
    return held


def _gimbal_locks(reader, links, joints, root, children, value, limits, followers, floating_base):
    """The middle joints of chains of three revolutes that lock within
    their limits: [(middle, reason)]. A revolute (or continuous) joint J2
    whose parent link's group hangs from a revolute J1 and whose child's
    group carries a revolute J3 is the middle of such a chain where, at
    some angle of J2 (the lock), J3's axis lies on J1's line, and the
    joint-space mass matrix with J2 at the allowed angle nearest the lock
    (within its limits with `limits`, else the lock itself; the other
    joints where the model is built) has more motions that move no mass
    (_zero_modes) than where the model is built: J1 and J3 turning opposite
    ways moves nothing through massless links (human.urdf's neck, Z-X-Y
    with X limited to +-1.5708, 3.7e-6 rad past the lock at -pi/2). Only
    there is that motion undetermined (elsewhere the three joints move what
    J3 carries as a ball joint would), so nothing is held for it: the
    caller warns. Joints that mimic others are not J2."""
    turning = ("revolute", "continuous")
    pose, group_of, order = _poses(reader, joints, root, children, value)
    built = None  # (the motions that move no mass where the model is built: counted at the first lock found)
    parts = _subtree_inertias(links, joints, order, pose)
    coupled = set(followers) | {leader for leader, _ in _leaders(followers).values()}
    hanging = {joint["child"]: joint for joint in joints.values()}
    carried = {}  # group -> the revolutes on its links (each J2's candidates for J3: linear, not a scan of all)
    for joint in joints.values():
        if joint["type"] in turning:
            carried.setdefault(group_of[joint["parent"]], []).append(joint)
    found = []
    for j2 in joints.values():
        if j2["type"] not in turning or j2["name"] in followers:
            continue
        j1 = hanging.get(group_of[j2["parent"]])
        if j1 is None or j1["type"] not in turning:
            continue
        # J1's line and J3's in J2's frame at angle 0 (J3's turned by J2's angle theta about a2)
        R1, p1 = pose[j1["child"]]
        R_parent, p_parent = pose[j2["parent"]]
        R2, p2 = R_parent @ j2["R"], p_parent + R_parent @ j2["p"]
        a2 = j2["axis"] / np.linalg.norm(j2["axis"])
        b = R2.T @ (R1 @ j1["axis"])
        b = b / np.linalg.norm(b)
        c = R2.T @ (p1 - p2)
        R_child, p_child = pose[j2["child"]]  # (J2's frame turned by its initial angle)
        for j3 in carried.get(j2["child"], ()):
            R3, p3 = pose[j3["parent"]]
            u = R_child.T @ (R3 @ j3["R"] @ j3["axis"])
            u = u / np.linalg.norm(u)
            q3 = R_child.T @ (p3 + R3 @ j3["p"] - p_child)
            # b . turn(a2, theta) u = C + A cos(theta) + B sin(theta): +-1 where the axes line up
            C = (b @ a2) * (a2 @ u)
            A, B = b @ u - C, b @ np.cross(a2, u)
            r = np.hypot(A, B)
            if r < 1e-9:  # (the angle between the axes does not change with J2)
                continue
            for lock in (np.arctan2(B, A), np.arctan2(B, A) + np.pi):
                if abs(C + r * np.cos(lock - np.arctan2(B, A))) < 1.0 - 1e-9:
                    continue
                R = _rotations.turn(a2, lock)
                if np.linalg.norm(np.cross(R @ q3 - c, b)) > 1e-9 * (1.0 + np.linalg.norm(c) + np.linalg.norm(q3)):
                    continue  # (parallel axes apart: turning opposite ways moves the links beyond)
                if limits and j2["limit"] is not None:
                    lower, upper = j2["limit"]
                    turns = np.round((np.clip(lock, lower, upper) - lock) / (2 * np.pi))
                    near = min((lock + 2 * np.pi * k for k in (turns - 1, turns, turns + 1)),
                               key=lambda x: abs(np.clip(x, lower, upper) - x))
                    beyond = abs(float(np.clip(near, lower, upper)) - near)
                    if beyond > LOCK_REACHED:
                        continue
                else:
                    near, beyond = lock + 2 * np.pi * np.round((value[j2["name"]] - lock) / (2 * np.pi)), 0.0
                if not {j1["name"], j2["name"], j3["name"]} & coupled:
                    # a first look that costs no mass matrix (a long chain of revolutes through one point has a
                    # lock at each joint): the energy of J1 and J3 turning opposite ways at 1 rad/s at the lock,
                    # the links between J2 and J3 turned there (the line turned back instead), against J3's
                    # (no motion that moves this much can be one the count below finds)
                    axis1 = R1 @ j1["axis"] / np.linalg.norm(j1["axis"])
                    turned = _rotations.turn(R2 @ a2, float(near) - value[j2["name"]])
                    moved = _turning_inertia(_less(parts[j1["child"]], parts[j2["child"]]), axis1, p1) + \
                        _turning_inertia(_less(parts[j2["child"]], parts[j3["child"]]), turned.T @ axis1,
                                         p2 + turned.T @ (p1 - p2))
                    axis3 = R3 @ j3["R"] @ j3["axis"]
                    carried_by_j3 = _turning_inertia(parts[j3["child"]], axis3 / np.linalg.norm(axis3),
                                                     p3 + R3 @ j3["p"])
                    whole = parts[j1["child"]]
                    with np.errstate(all="ignore"):
                        slack = 1e-10 * (np.trace(whole[2]) + whole[0] * (p1 @ p1))  # (round-off of the sums)
                    if moved > 1e-6 * (moved + 2 * carried_by_j3) + slack:
                        continue
                at = _joint_values(reader, joints, {name: x for name, x in value.items() if name not in followers}
                                   | {j2["name"]: float(near)}, followers, False)  # (J2's mimics with it)
                if built is None:
                    M, _ = _mass_matrix(links, joints, order, pose, followers, floating_base)
                    if M is None:
                        return []
                    built = _zero_modes(M)
                pose_at, _, order_at = _poses(reader, joints, root, children, at)
                M, _ = _mass_matrix(links, joints, order_at, pose_at, followers, floating_base)
                if M is None or _zero_modes(M) <= built:
                    continue
                if not (limits and j2["limit"] is not None):
                    where = "(no limits)"
                elif beyond == 0.0:
                    where = f"within its limits [{j2['limit'][0]:.10g}, {j2['limit'][1]:.10g}]"
                else:
                    where = f"{beyond:.2g} rad beyond its limit {float(np.clip(near, *j2['limit'])):.10g}"
                found.append((j2["name"], f"at {near:.6g} rad, {where}, the axes of '{j1['name']}' and "
                              f"'{j3['name']}' line up (a gimbal lock) and their turning opposite ways moves no "
                              "mass or inertia"))
                break
            if found and found[-1][0] == j2["name"]:
                break
    return found


def _subtree_inertias(links, joints, order, pose):
    """{link: (mass, first moment, inertia about the world origin) of it and
    every link below it} in the configuration of `pose` (`order`: parents
    first): sums, so one subtree's less another's within it are the links
    between."""
    parent = {joint["child"]: joint["parent"] for joint in joints.values()}
    out = {}
    with np.errstate(all="ignore"):  # (values beyond what a model holds: refused when the bodies are built)
        for link in reversed(order):  # (children first: each has added itself to its link when it comes)
            data = links[link]
            R, p = pose[link]
            m, c = data["mass"], p + R @ data["com"]
            own = (m, m * c, R @ data["inertia"] @ R.T + m * (c @ c * np.eye(3) - np.outer(c, c)))
            out[link] = _plus(out[link], own) if link in out else own
            if link in parent:
                up = parent[link]
                out[up] = _plus(out[up], out[link]) if up in out else out[link]
    return out


def _plus(part, other):
    return part[0] + other[0], part[1] + other[1], part[2] + other[2]


def _less(part, other):
    return part[0] - other[0], part[1] - other[1], part[2] - other[2]


def _turning_inertia(part, axis, point):
    """The moment of inertia of `part` (mass m, first moment h, inertia
    J_O about the world origin) about the line through `point` along the
    unit `axis`: a . J_O a - 2 (a x h) . (a x point) + m |a x point|^2
    (twice the kinetic energy of its turning at 1 rad/s about the line)."""
    m, h, J = part
    ap = np.cross(axis, point)
    with np.errstate(all="ignore"):
        return float(axis @ J @ axis - 2 * np.cross(axis, h) @ ap + m * ap @ ap)


def _hold(reader, joints, followers, held, value, strict):
    """Each joint of `held` (and the followers of its mimics) fixed at its
    value, with one UrdfWarning naming each joint, its line and why; with
    strict a UrdfError naming the first."""
    def why(name, partners):
        if partners is None:
            return "no mass or inertia moves with it"
        others = [(other, rate) for other, rate in partners if other != name]
        shown = ", ".join(f"'{other}' {rate:.3g}" for other, rate in others)
        rate = dict(partners)[name]
        return (f"turned at {rate:.3g} with {shown} (rad/s, m/s for a prismatic), it moves no mass or inertia"
                if others else "no mass or inertia moves with it")

    if strict:
        name, partners = held[0]
        more = f" ({len(held)} joints in all: {', '.join(repr(h) for h, _ in held)})" if len(held) > 1 else ""
        reader.fail(joints[name]["element"], f"{why(name, partners)}, so the forces do not determine its motion"
                    f"{more}; strict=True refuses this: give the links it moves mass and inertia, or load with "
                    "strict=False to hold it at its initial position", f"joint '{name}'")
    mimics = _mimics(followers)
    shown = []
    for name, partners in held:
        also = f", with its mimic{'s' if len(mimics[name]) > 1 else ''} {', '.join(repr(f) for f in mimics[name])}" \
            if mimics.get(name) else ""
        shown.append(f"joint '{name}' (line {joints[name]['element'].line}{also}): {why(name, partners)}")
    _fix(joints, followers, [name for name, _ in held], value)
    count = len(held)
    warnings.warn(UrdfWarning(
        f"{reader.path}: {count} joint{'s are' if count > 1 else ' is'} held at {'their' if count > 1 else 'its'} "
        f"initial position{'s' if count > 1 else ''} (as a fixed joint, {'their' if count > 1 else 'its'} limits "
        f"and damping left out), because the forces would not determine {'their' if count > 1 else 'its'} "
        "motion: " + "; ".join(shown) + ". Give the links they move mass and inertia to let them move "
        "(strict=True refuses such a file)"), stacklevel=3)


def _fix(joints, followers, names, value):
    """The joints `names` (leaders or joints that mimic none) and the
    followers of their mimics made fixed joints at their values: their
    child links merge into their parents' bodies; `moves_as` keeps what
    they were for the poses."""
    mimics = _mimics(followers)
    for name in names:
        for joint in [name, *mimics.get(name, ())]:
            joints[joint].update(moves_as=joints[joint]["type"], type="fixed", locked=value[joint], held=True)
            followers.pop(joint, None)


def _warn_gimbal_locks(reader, joints, locks, strict):
    """One UrdfWarning naming each chain's middle joint, its line and its
    lock (nothing is held: away from the lock the forces determine every
    joint's motion); with strict a UrdfError naming the first."""
    if strict:
        name, reason = locks[0]
        reader.fail(joints[name]["element"], f"{reason}, so there the forces do not determine their motion and a run "
                    f"that reaches the lock fails; strict=True refuses this: give the links between them mass and "
                    f"inertia off their axes, or load with strict=False (hold=['{name}'] keeps the chain away "
                    "from the lock)", f"joint '{name}'")
    count = len(locks)
    shown = "; ".join(f"joint '{name}' (line {joints[name]['element'].line}): {reason}" for name, reason in locks)
    names = ", ".join(repr(name) for name, _ in locks)
    chains = "the chains away from their locks, taking those joints'" if count > 1 else \
        "the chain away from the lock, taking that joint's"
    warnings.warn(UrdfWarning(
        f"{reader.path}: {count} chain{'s' if count > 1 else ''} of revolutes can reach a gimbal lock: {shown}. "
        "Nothing is held (away from a lock the forces determine every joint's motion); at the lock they do not "
        f"determine that turning, and a run that reaches it fails there. hold=[{names}] keeps {chains} motion "
        "away; mass and inertia off the outer joints' axes in the links between them remove the lock "
        "(strict=True refuses such a file)"), stacklevel=3)


def _held_by_argument(reader, joints, followers, hold):
    """The joints of load_urdf's `hold`: names of joints of the file with
    one coordinate that follow no mimic (a leader's mimics are held with
    it)."""
    names = []
    for name in hold:
        joint = joints.get(name) if isinstance(name, str) else None
        if joint is not None and joint.get("moves_as"):
            raise UrdfError(f"{reader.path}: hold: joint '{name}' is locked at {joint['locked']!r} by its equal limits "
                            "already")
        if joint is None or joint["type"] not in MOVING:
            movable = [j["name"] for j in joints.values() if j["type"] in MOVING]
            raise UrdfError(f"{reader.path}: hold: {_checks.show(name)} is not a revolute, continuous or prismatic "
                            f"joint of the file (those are: {', '.join(movable)})")
        if name in followers:
            raise UrdfError(f"{reader.path}: hold: joint '{name}' mimics '{followers[name]['joint']}': hold "
                            f"'{_leader(followers, name)}' (its mimics are held with it), or load with mimic=False")
        if name not in names:
            names.append(name)
    return names


def _mimics(followers):
    """{leader: [the joints whose chains of mimics end at it]}."""
    out = {}
    for name, (leader, _) in _leaders(followers).items():
        out.setdefault(leader, []).append(name)
    return out


def _leaders(followers):
    """{follower: (the joint its chain of mimics ends at, the product of the
    multipliers along it)}, each chain walked once (linear in the number of
    followers, where walking each follower's chain would be quadratic)."""
    out = {}
    for name in followers:
        path, at = [], name
        while at in followers and at not in out:
            path.append(at)
            at = followers[at]["joint"]
        leader, factor = out.get(at, (at, 1.0))
        for joint in reversed(path):  # (nearest the leader first)
            factor *= followers[joint]["multiplier"]
            out[joint] = (leader, factor)
    return out


def _leader(followers, name):
    """The joint a chain of mimics from `name` ends at."""
    while name in followers:
        name = followers[name]["joint"]
    return name


def _positions(reader, joints, positions):
    """{URDF joint: finite value} of the argument `positions`, each naming
    a joint with one coordinate."""
    out = {}
    for name, value in positions.items():
        joint = joints.get(name) if isinstance(name, str) else None
        if joint is not None and joint.get("moves_as"):
            raise UrdfError(f"{reader.path}: positions: joint '{name}' is locked at {joint['locked']!r} by its equal "
                            "limits (load with limits=False to move it)")
        if joint is None or joint["type"] not in MOVING:
            movable = [j["name"] for j in joints.values() if j["type"] in MOVING]
            raise UrdfError(f"{reader.path}: positions: {_checks.show(name)} is not a revolute, continuous or "
                            f"prismatic joint of the file (those are: {', '.join(movable)})")
        out[name] = _argument(_checks.real, value, f"{reader.path}: positions: joint '{name}'")
        if abs(out[name]) > LARGEST:
            raise UrdfError(f"{reader.path}: positions: joint '{name}' = {out[name]:g} is beyond what a model can "
                            f"hold (at most {LARGEST:g})")
    return out


def _followers(reader, joints):
    """{joint: its <mimic>} for the joints that mimic another: both must
    have a coordinate (revolute, continuous, prismatic). A mimic of a joint
    the file does not have is left out with one UrdfWarning naming each
    (the joint moves freely), or with strict refused. A fixed joint's
    <mimic> couples nothing (it has no coordinate) and is passed over
    (Talos's gripper has such elements); a joint locked by its limits
    cannot mimic nor be mimicked."""
    out, unknown = {}, []
    for joint in joints.values():
        m = joint["mimic"]
        owner = f"joint '{joint['name']}'"
        if m is None or (joint["type"] == "fixed" and not joint.get("moves_as")):
            continue
        if joint.get("moves_as"):
            reader.fail(m["element"], f"is locked at {joint['locked']!r} by its equal limits and mimics "
                        f"'{m['joint']}' (load with limits=False or mimic=False)", owner)
        if joint["type"] not in MOVING:
            reader.fail(m["element"], f"a {joint['type']} joint cannot mimic (only revolute, continuous and "
                        "prismatic joints have one coordinate)", owner)
        leader = joints.get(m["joint"])
        if leader is None:
            if reader.strict:
                reader.fail(m["element"], f"mimics '{m['joint']}', which is not a joint of the file (load with "
                            "strict=False to read it as a joint of its own)", owner)
            unknown.append(f"{owner}, line {m['element'].line}: mimics '{m['joint']}'")
            continue
        if leader.get("moves_as"):
            reader.fail(m["element"], f"mimics '{m['joint']}', which is locked at {leader['locked']!r} by its equal "
                        "limits (load with limits=False or mimic=False)", owner)
        if leader["type"] not in MOVING:
            reader.fail(m["element"], f"mimics '{m['joint']}', a {leader['type']} joint (a leader must be revolute, "
                        "continuous or prismatic)", owner)
        if leader["name"] == joint["name"]:
            reader.fail(m["element"], "mimics itself", owner)
        out[joint["name"]] = m
    done = set()  # followers known to lead, through their leaders, to a joint that mimics none
    for name in out:  # a cycle of mimics has no leader (each follower walked once: linear)
        path, on_path, at = [], set(), name
        while at in out and at not in done:
            if at in on_path:
                cycle = path[path.index(at):] + [at]
                shown = cycle if len(cycle) <= 12 else cycle[:6] + ["..."] + cycle[-3:]
                size = f" of {len(cycle) - 1} joints" if len(cycle) > 12 else ""
                reader.fail(out[at]["element"], f"mimics in a cycle{size} ({' -> '.join(shown)})", f"joint '{at}'")
            path.append(at)
            on_path.add(at)
            at = out[at]["joint"]
        done.update(path)
    if unknown:
        warnings.warn(UrdfWarning(
            f"{reader.path}: {len(unknown)} mimic{'s' if len(unknown) > 1 else ''} of a joint the file does not "
            f"have, each joint read as a joint of its own that moves freely (not coupled; strict=True refuses "
            f"such a mimic): {'; '.join(unknown)}"), stacklevel=3)
    return out


def _joint_values(reader, joints, positions, followers, limits):
    """Each joint's angle or slide in the configuration the model is built
    in: `positions`; where not given 0, or with `limits` the middle of the
    joint's limits if 0 lies outside them (the Panda's fourth joint), or
    where equal limits lock it; a mimic's multiplier x + offset of its
    leader's value (a chain of mimics followed without recursion)."""
    def own(name):
        joint = joints[name]
        if name in positions:
            return positions[name]
        if joint.get("moves_as"):
            return joint["locked"]
        limit = joint["limit"]
        if limits and limit is not None and not limit[0] <= 0.0 <= limit[1]:
            return 0.5 * (limit[0] + limit[1])
        return 0.0

    value = {}
    for name in joints:
        chain, at = [], name
        while at not in value and at in followers:
            chain.append(at)
            at = followers[at]["joint"]
        if at not in value:
            value[at] = own(at)
        for follower in reversed(chain):
            m = followers[follower]
            x = m["multiplier"] * value[m["joint"]] + m["offset"]  # (floats: inf past a double, no error)
            if not abs(x) <= LARGEST:
                reader.fail(m["element"], f"puts it at {x:g} (multiplier x the value {value[m['joint']]:g} of "
                            f"'{m['joint']}' + offset): beyond what a model can hold (at most {LARGEST:g})",
                            f"joint '{follower}'")
            value[follower] = x
    for name, joint in joints.items():  # (a locked joint's value is its limits', not bounded by the reader)
        if joint.get("moves_as") and abs(value[name]) > LARGEST:
            reader.fail(joint["elements"]["limit"], f"locks the joint at {value[name]:g}: beyond what a model can "
                        f"hold (at most {LARGEST:g})", f"joint '{name}'")
    return value
