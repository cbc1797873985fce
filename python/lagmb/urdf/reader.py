"""A URDF file read: its XML with the line of every element (expat), the
tags lagmb reads, and the links and joints checked into the tree they make.

The file is read with the standard library's expat parser, which keeps the
line of every element, so that an error names the link or joint, the tag and
the line. A URDF library such as yourdfpy was measured and not used: it
accepts an unknown joint type and unknown tags without a word, keeps no line
numbers, and imports in about 3 s (trimesh).
"""

import os
import re
import warnings
import xml.parsers.expat

import numpy as np

from .. import _checks, _rotations
from .._model_files import LARGEST
from ..errors import ModelError
from .tree import children

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


class Element:
    """One XML element: its tag, attributes, children and line."""

    __slots__ = ("tag", "attrib", "children", "line")

    def __init__(self, tag, attrib, line):
        self.tag, self.attrib, self.children, self.line = tag, attrib, [], line

    def all(self, tag):
        return [c for c in self.children if c.tag == tag]

    def one(self, tag):
        found = self.all(tag)
        return found[0] if found else None


def read_xml(path):
    """The file's root element, every element with its line. The whole
    file is given to expat in one call: fed in blocks (ParseFile), expat
    scans an unfinished token again with each block, so one long comment
    or attribute took time quadratic in its length (10 MB: 15 s)."""
    parser = xml.parsers.expat.ParserCreate()
    stack, root = [], []

    def start(tag, attrib):
        element = Element(tag, attrib, parser.CurrentLineNumber)
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


class Reader:
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
        self.root = read_xml(self.path)
        if self.root.tag != "robot":
            self.fail(self.root, f"the root element is <{self.root.tag}>, not <robot>")

    def fail(self, element, what, owner=None):
        raise UrdfError(self.at(element, what, owner))

    def warn(self, element, what, owner=None, stacklevel=3):
        warnings.warn(UrdfWarning(self.at(element, what, owner)), stacklevel=stacklevel)

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
        reached, stack, below = {roots[0]}, [roots[0]], children(joints)
        while stack:
            for joint in below.get(stack.pop(), []):
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



def checked_argument(check, value, name):
    """An argument checked by lagmb._checks, its ModelError a UrdfError."""
    try:
        return check(value, name)
    except ModelError as e:
        raise UrdfError(str(e)) from None
