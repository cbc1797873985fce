"""Random URDF robots with hostile mutations, loaded out of process.

Used by tests/fuzz/test_fuzz_urdf.py (issue 39); also a command-line tool:

    python3 tests/fuzz/fuzz_urdf.py --generate N [SEED]   # N cases as JSON
    python3 tests/fuzz/fuzz_urdf.py --show SEED INDEX      # one case as a script

A *robot* is a tree (or a chain) of 2-7 links with masses and inertias,
joined by revolute, continuous, prismatic, fixed, planar and floating joints
with origins, axes, limits, damping and mimics, its numbers written in the
forms XML Schema allows (signs, exponents, ".5", "5.", blanks). A *case* is
a robot with 0-3 *mutations* and load options:

- loops (a link that is the child of two joints, two links joined both
  ways beside the tree), a joint whose parent is its child;
- a long chain of mimics (up to 1,500), sometimes closed into a cycle;
- numbers in odd forms, valid ("+1.0E0", ".5") or not ("1_0", Arabic-Indic
  and full-width digits, hex, a comma, a no-break space, NaN, 1e999);
- huge and tiny values (1e200, 1.797e308, 1e-200, 5e-324) in masses,
  inertias, origins, axes, limits, damping and mimics;
- limits with lower > upper, lower == upper (0 and not);
- encodings (UTF-8, Latin-1, cp1252, UTF-16 declared and written so;
  unknown, multi-byte and codec names declared; Latin-1 bytes undeclared);
- names: duplicates of a kind, a link and a joint of one name, a joint or
  a link named ground, a joint named like the damping lagmb makes, names
  with blanks or tabs, empty names;
- a long token (a comment or an attribute of 1-3 MB), unknown tags and
  joint types, a missing mass or inertia, a zero axis;
- revolutes through one point with massless rings between them, hanging
  a link with mass: two on one line, or three that can reach a gimbal lock
  or are built at it (the loader holds what the forces do not determine);
- hostile options (limits="no", gravity="down", positions with 10**400 or
  unknown joints, package_dirs=5, hold="j1"); good ones (positions, one
  joint held).

Each case is plain data: a list of ops as tests/fuzz/fuzz_mechanisms.py runs
them (op 0 writes the file, op 1 loads it, op 2 runs the model 0.01 s), so
its worker (a subprocess with a timeout and a 4 GB address-space cap),
its grouping of findings and its reproducer scripts are the same. The
property: a case loads and runs (finite outputs, constraints held), or
lagmb refuses it with its own exception whose message names the file or
the argument; a robot without mutations and with good options must load
and run; a mutation lagmb must refuse (a loop, lower > upper, "1_0", a
duplicate name of one kind, a value past 1e150, an encoding it cannot read)
must not load. Anything else (another exception, a crash, a hang, a
silently loaded bad file) is a finding.
"""

import json
import math
import os
import random
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import fuzz_mechanisms as fm  # noqa: E402

# ---------------------------------------------------------------------------
# Numbers
# ---------------------------------------------------------------------------

#: not numbers as XML Schema writes them (Python's float() reads several)
BAD_NUMBERS = ["1_0", "\u0661", "\uff11", "0x1", "1,5", "--1", "1e", "one", "1.0.0", "", "nan", "inf", "-inf",
               "1e999", "\u00a01", "1\u00a0", "\u2003", "\u0967"]
HUGE = [1e200, -1e200, 1.797e308, 1e151, -3e160]  # past what a model can hold (1e150)
TINY = [1e-200, -1e-200, 5e-324, 1e-300, 0.0, -0.0]
NEAR = [1e150, -9.9e149, 1e100, 1e-100]


def written(x, rng):
    """A float in one of the forms XML Schema allows, read back as x (or
    as the nearest of its 17 digits)."""
    form = rng.randrange(7)
    if form == 0:
        return repr(float(x))
    if form == 1:
        return f"{x:+.17e}".replace("e", rng.choice("eE"))
    if form == 2 and 0 < abs(x) < 1:
        return repr(float(x)).replace("0.", ".", 1)
    if form == 3 and float(x).is_integer() and abs(x) < 1e15:
        return f"{int(x)}."
    if form == 4:
        return rng.choice([" ", "\t", "\n"]) + repr(float(x)) + rng.choice([" ", "\n  ", ""])
    return f"{x:.17g}"


# ---------------------------------------------------------------------------
# Robots: links and joints as elements [tag, {attribute: value}, children]
# ---------------------------------------------------------------------------

def element(tag, attributes=None, *children):
    return [tag, dict(attributes or {}), list(children)]


def _round(x):
    return float(f"{x:.6g}")


def _inertial(rng):
    mass = _round(rng.uniform(0.2, 5.0))
    a, b, c = (_round(rng.uniform(0.01, 0.5)) for _ in range(3))
    # (moments that keep the triangle inequality: a + b > c etc.)
    a, b, c = sorted((a, b, c))
    c = min(c, _round(a + b - 0.005))
    off = _round(0.1 * min(a, b, c) * rng.uniform(-1, 1))
    return element("inertial", {}, element("origin", {"xyz": [_round(rng.uniform(-0.3, 0.3)) for _ in range(3)],
                                                      "rpy": [_round(rng.uniform(-3, 3)) for _ in range(3)]}),
                   element("mass", {"value": [mass]}),
                   element("inertia", {"ixx": [a], "iyy": [b], "izz": [c], "ixy": [off], "ixz": [0.0], "iyz": [0.0]}))


def _visual(rng):
    kind = rng.choice(["box", "sphere", "cylinder"])
    sizes = {"box": {"size": [_round(rng.uniform(0.01, 0.3)) for _ in range(3)]},
             "sphere": {"radius": [_round(rng.uniform(0.01, 0.2))]},
             "cylinder": {"radius": [_round(rng.uniform(0.01, 0.1))], "length": [_round(rng.uniform(0.05, 0.5))]}}
    return element(rng.choice(["visual", "collision"]), {},
                   element("origin", {"xyz": [_round(rng.uniform(-0.2, 0.2)) for _ in range(3)]}),
                   element("geometry", {}, element(kind, sizes[kind])))


def _axis(rng):
    axis = [0.0, 0.0, 0.0]
    if rng.random() < 0.6:
        axis[rng.randrange(3)] = rng.choice([1.0, -1.0])
    else:
        axis = [_round(rng.uniform(-1, 1)) for _ in range(3)]
        if max(abs(x) for x in axis) < 0.1:
            axis[2] = 1.0
    return axis


JOINT_KINDS = ["revolute", "revolute", "continuous", "prismatic", "fixed", "planar", "floating"]


def robot(rng):
    """A random robot: links l0.. (a chain or a tree), each with mass and
    inertia, joined by joints j1..; at least one joint moves. Returns
    (links, joints), each a list of elements."""
    n = rng.randint(2, 7)
    chain = rng.random() < 0.4
    links = [element("link", {"name": f"l{k}"}, _inertial(rng), *[_visual(rng) for _ in range(rng.randrange(2))])
             for k in range(n)]
    joints = []
    movable = []
    for k in range(1, n):
        kind = rng.choice(JOINT_KINDS)
        if k == n - 1 and not movable:
            kind = "revolute"
        parent = k - 1 if chain else rng.randrange(k)
        children = [element("parent", {"link": f"l{parent}"}), element("child", {"link": f"l{k}"}),
                    element("origin", {"xyz": [_round(rng.uniform(-0.5, 0.5)) for _ in range(3)],
                                       "rpy": [_round(rng.uniform(-3.2, 3.2)) for _ in range(3)]}),
                    element("axis", {"xyz": _axis(rng)})]
        if kind in ("revolute", "prismatic"):
            lower, upper = _round(rng.uniform(-2.5, -0.1)), _round(rng.uniform(0.1, 2.5))
            children.append(element("limit", {"lower": [lower], "upper": [upper], "effort": [10.0], "velocity": [1.0]}))
        if kind in ("revolute", "continuous", "prismatic") and rng.random() < 0.3:
            children.append(element("dynamics", {"damping": [_round(rng.uniform(0, 0.5))],
                                                 "friction": [_round(rng.uniform(0, 0.2)) if rng.random() < 0.5
                                                              else 0.0]}))
        if kind == "continuous" and movable and rng.random() < 0.3:  # (a follower without limits)
            children.append(element("mimic", {"joint": rng.choice(movable), "multiplier": [_round(rng.uniform(-2, 2))],
                                              "offset": [_round(rng.uniform(-0.3, 0.3))]}))
        joints.append(element("joint", {"name": f"j{k}", "type": kind}, *children))
        if kind in ("revolute", "continuous", "prismatic"):
            movable.append(f"j{k}")
    return links, joints


def _escape(text):
    return (text.replace("&", "&amp;").replace("<", "&lt;").replace('"', "&quot;").replace("\t", "&#9;")
            .replace("\n", "&#10;"))


def render(links, joints, rng, numbers="plain"):
    """The URDF text: numbers written as written() writes them ("odd") or
    by repr ("plain"); a string value is written as it is (a mutation's)."""
    def attribute(value):
        if isinstance(value, str):
            return value
        return " ".join(written(x, rng) if numbers == "odd" else repr(float(x)) for x in value)

    def one(e, depth):
        tag, attributes, children = e
        head = f"<{tag}" + "".join(f' {k}="{_escape(attribute(v))}"' for k, v in attributes.items())
        if not children:
            return "  " * depth + head + "/>"
        inner = "\n".join(one(c, depth + 1) for c in children)
        return "  " * depth + head + ">\n" + inner + "\n" + "  " * depth + f"</{tag}>"

    items = links + joints
    if rng.random() < 0.5:
        rng.shuffle(items)  # (a URDF may list its joints before its links)
    return '<robot name="fuzz">\n' + "\n".join(one(e, 1) for e in items) + "\n</robot>\n"


# ---------------------------------------------------------------------------
# Mutations: each changes (links, joints, case) and says whether lagmb must
# refuse the result ("refuse"), may do either ("either"), or must load it
# ("load", only as clean as the rest of the case)
# ---------------------------------------------------------------------------

def _joint(joints, rng, kinds=None):
    found = [j for j in joints if kinds is None or j[1]["type"] in kinds]
    return rng.choice(found) if found else None


def _child(e, tag):
    found = [c for c in e[2] if c[0] == tag]
    return found[0] if found else None


def _new_link(name, rng):
    return element("link", {"name": name}, _inertial(rng))


def _new_joint(name, kind, parent, child, rng):
    return element("joint", {"name": name, "type": kind}, element("parent", {"link": parent}),
                   element("child", {"link": child}), element("axis", {"xyz": _axis(rng)}))


def m_second_parent(links, joints, case, rng):
    """A link that is already a joint's child gets a second parent."""
    child = rng.randrange(1, len(links))
    joints.append(_new_joint("again", "revolute", f"l{rng.randrange(len(links))}", f"l{child}", rng))
    return "refuse"


def m_detached_loop(links, joints, case, rng):
    """Two links joined both ways, beside the tree (its root still has none)."""
    links += [_new_link("la", rng), _new_link("lb", rng), _new_link("lc", rng)]
    joints += [_new_joint("ab", "revolute", "la", "lb", rng), _new_joint("ba", "continuous", "lb", "la", rng),
               _new_joint("bc", "fixed", "lb", "lc", rng)]
    return "refuse"


def m_self_parent(links, joints, case, rng):
    k = rng.randrange(len(links))
    joints.append(_new_joint("self", rng.choice(["fixed", "revolute"]), f"l{k}", f"l{k}", rng))
    return "refuse"


def m_mimic_chain(links, joints, case, rng):
    """A chain of up to 1,500 continuous joints below l0, each mimicking the
    one before (multiplier near 1); sometimes closed into a cycle."""
    n = rng.choice([20, 200, 1500])
    for k in range(n):
        links.append(_new_link(f"m{k}", rng))
        joint = _new_joint(f"mj{k}", "continuous", f"m{k - 1}" if k else "l0", f"m{k}", rng)
        if k:
            joint[2].append(element("mimic", {"joint": f"mj{k - 1}", "multiplier": [rng.choice([1.0, -1.0, 1.001])],
                                              "offset": [0.0]}))
        joints.append(joint)
    if rng.random() < 0.4:
        joints[-n][2].append(element("mimic", {"joint": f"mj{n - 1}"}))
        return "refuse" if case["options"].get("mimic", True) is True else "either"
    return "either"


def _number_slots(links, joints):
    """(element, attribute, bounded, must_read) of numbers lagmb reads:
    bounded ones may not pass 1e150."""
    slots = []
    for link in links:
        inertial = _child(link, "inertial")
        if inertial is not None:
            for c in inertial[2]:
                for key in c[1]:
                    slots.append((c, key, key != "rpy"))
        for shape in link[2]:
            if shape[0] in ("visual", "collision"):
                origin = _child(shape, "origin")
                if origin is not None:
                    slots.append((origin, "xyz", True))
    for joint in joints:
        for c in joint[2]:
            if c[0] == "origin":
                slots += [(c, k, k == "xyz") for k in c[1]]
            elif c[0] == "axis":
                slots.append((c, "xyz", False))
            elif c[0] == "limit" and joint[1]["type"] in ("revolute", "prismatic"):
                slots += [(c, k, False) for k in ("lower", "upper")]
            elif c[0] in ("dynamics", "mimic"):
                slots += [(c, k, True) for k in c[1] if k != "joint"]
    return slots


def m_bad_number(links, joints, case, rng):
    e, key, _ = rng.choice(_number_slots(links, joints))
    values = [repr(float(x)) for x in e[1][key]] if not isinstance(e[1][key], str) else [e[1][key]]
    values[rng.randrange(len(values))] = rng.choice(BAD_NUMBERS)
    e[1][key] = " ".join(values)
    return "refuse"


def m_odd_numbers(links, joints, case, rng):
    """Every number in a valid but unusual form."""
    case["numbers"] = "odd"
    return "load"


def m_extreme_number(links, joints, case, rng):
    e, key, bounded = rng.choice(_number_slots(links, joints))
    values = list(e[1][key]) if not isinstance(e[1][key], str) else [1.0]
    k = rng.randrange(len(values))
    values[k] = rng.choice(HUGE + TINY + NEAR)
    e[1][key] = values
    return "refuse" if bounded and abs(values[k]) > 1e150 else "either"


def m_limits(links, joints, case, rng):
    limited = [j for j in joints if j[1]["type"] in ("revolute", "prismatic") and _child(j, "limit") is not None]
    if not limited:
        return "either"
    limit = _child(rng.choice(limited), "limit")
    lower = _round(rng.uniform(-1, 1))
    form = rng.randrange(3)
    limit[1]["lower"], limit[1]["upper"] = ([lower], [lower - 0.5]) if form == 0 else \
        ([lower], [lower]) if form == 1 else ([0.0], [0.0])
    return "refuse" if form == 0 else "either"


ENCODINGS = [  # (declared, written in, must lagmb refuse)
    ("UTF-8", "utf-8", "load"), ("ISO-8859-1", "latin-1", "load"), ("windows-1252", "cp1252", "load"),
    ("UTF-16", "utf-16", "either"), (None, "utf-8", "load"), ("klingon", "utf-8", "refuse"),
    ("utf-32", "utf-32", "refuse"), ("rot13", "utf-8", "refuse"), ("shift_jis", "utf-8", "refuse"),
    (None, "latin-1", "refuse"), ("ascii", "utf-8", "refuse"),
]


def m_encoding(links, joints, case, rng):
    declared, codec, verdict = rng.choice(ENCODINGS)
    case.update(declared=declared, codec=codec)
    old = links[-1][1]["name"]  # (made non-ASCII, so that the encoding matters)
    new = old + "\u00fc"
    links[-1][1]["name"] = new
    for j in joints:
        for c in j[2]:
            if c[0] in ("parent", "child") and c[1]["link"] == old:
                c[1]["link"] = new
    return verdict


def m_names(links, joints, case, rng):
    form = rng.randrange(9)
    joint = _joint(joints, rng)
    if form == 0:  # two links of one name
        links.append(_new_link(links[0][1]["name"], rng))
        return "refuse"
    if form == 1:  # two joints of one name
        joints.append(_new_joint(joint[1]["name"], "fixed", "l0", "extra", rng))
        links.append(_new_link("extra", rng))
        return "refuse"
    if form == 2:  # a joint named like a link
        joint[1]["name"] = links[rng.randrange(len(links))][1]["name"]
        _rename_mimics(joints, joint)
        return "load"
    if form == 3:  # a joint named ground
        joint[1]["name"] = "ground"
        _rename_mimics(joints, joint)
        return "load"
    if form == 4:  # a link (the last) named ground
        _rename_link(links, joints, links[-1][1]["name"], "ground")
        return "load"
    if form == 5:  # a joint named like the damping lagmb makes for another
        damped = _joint(joints, rng, ("revolute", "continuous", "prismatic"))
        if damped is None:
            return "either"
        if _child(damped, "dynamics") is None:
            damped[2].append(element("dynamics", {"damping": [0.1]}))
        links.append(_new_link("extra", rng))
        joints.append(_new_joint(f"{damped[1]['name']}_damping", "revolute", "l0", "extra", rng))
        return "load"
    if form == 6:  # names with blanks or a tab (XML keeps &#9;)
        joint[1]["name"] = rng.choice([" j", "j ", "a\tb", "a b"])
        _rename_mimics(joints, joint)
        return "either"
    if form == 7:  # an empty name
        (joint if rng.random() < 0.5 else links[-1])[1]["name"] = ""
        return "refuse"
    _rename_link(links, joints, "l0", "x" * 5000)
    return "load"


def _rename_mimics(joints, joint):
    """(a mutation renamed `joint`: the mimics of it follow)"""
    for j in joints:
        for c in j[2]:
            if c[0] == "mimic" and c[1].get("joint") not in {x[1]["name"] for x in joints}:
                c[1]["joint"] = joint[1]["name"]


def _rename_link(links, joints, old, new):
    for link in links:
        if link[1]["name"] == old:
            link[1]["name"] = new
    for j in joints:
        for c in j[2]:
            if c[0] in ("parent", "child") and c[1]["link"] == old:
                c[1]["link"] = new


def m_long_token(links, joints, case, rng):
    case["long"] = (rng.choice(["comment", "attribute"]), rng.choice([1, 3]) * 1_000_000)
    return "load"


def m_missing(links, joints, case, rng):
    form = rng.randrange(6)
    joint = _joint(joints, rng)
    if form == 0:  # an unknown tag
        joint[2].append(element("spring", {"k": [1.0]}))
        return "refuse"
    if form == 1:
        joint[1]["type"] = rng.choice(["screw", "Revolute", "", "ball"])
        return "refuse"
    if form == 2:  # a zero axis of a joint that moves
        moving = _joint(joints, rng, ("revolute", "continuous", "prismatic", "planar"))
        if moving is None:
            return "either"
        _child(moving, "axis")[1]["xyz"] = [0.0, 0.0, 0.0]
        return "refuse"
    inertial = _child(links[rng.randrange(len(links))], "inertial")
    if form == 3:
        inertial[2] = [c for c in inertial[2] if c[0] != "mass"]
        return "refuse"
    if form == 4:
        inertial[2] = [c for c in inertial[2] if c[0] != "inertia"]
        return "refuse"
    _child(inertial, "mass")[1]["value"] = [-1.0]
    return "refuse"


def m_aligned_joints(links, joints, case, rng):
    """Revolutes through one point with massless rings between them hang a
    new link with mass from a link of the robot: two on one line (the forces
    never determine their turning opposite ways: one of them is held), or
    three whose outer axes line up at +-pi/2 of the middle one (a gimbal
    lock, limited to +-1.5708 or not: named, nothing held), sometimes built
    at the lock (one of the outer two held there). Each must load and run."""
    parent = links[rng.randrange(len(links))][1]["name"]
    links += [element("link", {"name": "g_ring1"}), element("link", {"name": "g_ring2"}), _new_link("g_end", rng)]
    place = element("origin", {"xyz": [_round(rng.uniform(-0.3, 0.3)) for _ in range(3)],
                               "rpy": [_round(rng.uniform(-3, 3)) for _ in range(3)]})

    def revolute(name, parent, child, axis, *more):
        kind = rng.choice(["revolute", "continuous"])
        limit = [element("limit", {"lower": [-1.5708], "upper": [1.5708], "effort": [1.0], "velocity": [1.0]})] \
            if kind == "revolute" else []
        return element("joint", {"name": name, "type": kind}, element("parent", {"link": parent}),
                       element("child", {"link": child}), *more, element("axis", {"xyz": axis}), *limit)

    if rng.random() < 0.3:  # (on one line: the second 0.05 m along the first's axis)
        joints += [revolute("ga", parent, "g_ring1", [0.0, 0.0, 1.0], place),
                   element("joint", {"name": "g_weld", "type": "fixed"}, element("parent", {"link": "g_ring1"}),
                           element("child", {"link": "g_ring2"})),
                   revolute("gc", "g_ring2", "g_end", [0.0, 0.0, 1.0], element("origin", {"xyz": [0.0, 0.0, 0.05]}))]
        return "load"
    at_lock = rng.random() < 0.3  # (gc's frame turned so that its axis lies on ga's at gb = 0)
    joints += [revolute("ga", parent, "g_ring1", [0.0, 0.0, 1.0], place),
               revolute("gb", "g_ring1", "g_ring2", [1.0, 0.0, 0.0]),
               revolute("gc", "g_ring2", "g_end", [0.0, 1.0, 0.0],
                        element("origin", {"xyz": [0.0, 0.0, 0.0], "rpy": [math.pi / 2 if at_lock else 0.0, 0.0,
                                                                            0.0]}))]
    return "load"


MUTATIONS = {"second parent": m_second_parent, "detached loop": m_detached_loop, "self parent": m_self_parent,
             "mimic chain": m_mimic_chain, "bad number": m_bad_number, "odd numbers": m_odd_numbers,
             "extreme number": m_extreme_number, "limits": m_limits, "encoding": m_encoding, "names": m_names,
             "long token": m_long_token, "missing": m_missing, "aligned joints": m_aligned_joints}

#: options that must be refused, by name
HOSTILE_OPTIONS = {
    "limits": ["no", 1, None, fm.Expr("np.array([True])")], "floating_base": ["yes", 0],
    "dynamics": [None, "False"], "mimic": [1.0],
    "gravity": ["down", None, (0.0, 0.0), (0.0, 0.0, math.nan), fm.Expr("10**400")],
    "package_dirs": [5, [None], fm.Expr("object()")],
    "positions": ["j1", [("j1", 0.1)], {"nosuch": 0.1}, {"j1": fm.BIG}, {"j1": "0.1"}, {"j1": math.nan},
                  {"j1": 1e200}, {5: 0.1}],
    "hold": ["j1", 5, ["nosuch"], [5], {"j1": 0.1}],
}


def case(rng):
    """One case: (ops, mutation names)."""
    links, joints = robot(rng)
    info = {"options": {}, "numbers": "plain", "declared": "UTF-8", "codec": "utf-8", "long": None}
    options = info["options"]
    for flag in ("floating_base", "limits", "dynamics", "mimic"):
        if rng.random() < 0.3:
            options[flag] = rng.random() < 0.5
    hostile = rng.random() < 0.15
    if hostile:
        key = rng.choice(sorted(HOSTILE_OPTIONS))
        options[key] = rng.choice(HOSTILE_OPTIONS[key])
    elif rng.random() < 0.3:  # positions within the limits, of joints that mimic none
        movable = [j for j in joints if j[1]["type"] in ("revolute", "continuous", "prismatic")
                   and _child(j, "mimic") is None]
        options["positions"] = {j[1]["name"]: _round(rng.uniform(-0.09, 0.09)) for j in movable
                                if rng.random() < 0.5}
        if len(movable) >= 2 and rng.random() < 0.3:  # (one held: another leader still moves)
            options["hold"] = [rng.choice(movable)[1]["name"]]
    mutations = rng.sample(sorted(MUTATIONS), rng.choice([0, 1, 1, 1, 2, 3]))
    if "mimic chain" in mutations and "aligned joints" in mutations:
        # (a body without mass makes the run take the augmented system (GGL), which with a chain of 200
        # couplings took minutes for 0.01 s: the core's speed, not the loader's; issue 56's report)
        mutations.remove("aligned joints")
    verdicts = [MUTATIONS[name](links, joints, info, rng) for name in mutations]
    if "positions" in options and isinstance(options["positions"], dict) and not hostile:
        names = {j[1]["name"] for j in joints}  # (a mutation may have renamed a joint)
        options["positions"] = {k: v for k, v in options["positions"].items() if k in names}
        if "hold" in options:
            options["hold"] = [k for k in options["hold"] if k in names]
    text = render(links, joints, rng, info["numbers"])
    return _ops(text, info, options, verdict="load" if not hostile and set(verdicts) <= {"load"} else
                "refuse" if "refuse" in verdicts or hostile else "either"), mutations


def _ops(text, info, options, verdict):
    """op 0 writes the file, op 1 loads it (a refusal must name the file or
    the argument; "refuse": loading is a finding; "load": refusing is),
    op 2 runs it."""
    if info["declared"]:
        text = f'<?xml version="1.0" encoding="{info["declared"]}"?>\n' + text
    data = text.encode(info["codec"], errors="replace")
    parts = [repr(data)]
    where, size = info["long"] or (None, 0)
    marker = b"<robot" if where == "comment" else b'name="fuzz"'
    if where and marker in data:  # (not in UTF-16 or UTF-32 bytes: no long token there)
        head, tail = data.split(marker, 1)
        filler = ("b'<!--' + b'x' * %d + b'-->'" % size) if where == "comment" else \
            ("b'name=\"' + b'y' * %d + b'\"'" % size)
        parts = [repr(head), filler, repr((b"<robot" if where == "comment" else b"") + tail)]
    write = ("import os, tempfile\n"
             "folder = tempfile.TemporaryDirectory()\n"
             "path = os.path.join(folder.name, 'robot.urdf')\n"
             "with open(path, 'wb') as f:\n"
             f"    f.write({' + '.join(parts)})\n")
    call = fm.call("mb.load_urdf", fm.Expr("path"), **options)
    load = ("try:\n"
            f"    model = {call}{'  ' + fm.MUST_SUCCEED if verdict == 'load' else ''}\n"
            "except mb.ModelError as e:  # a refusal names the file or the argument\n"
            "    assert 'robot.urdf' in str(e) or 'load_urdf' in str(e), str(e)\n"
            "    raise\n")
    if verdict == "refuse":
        load += "else:\n    raise AssertionError('loaded a file or arguments lagmb must refuse')\n"
    run = f"r = mb.simulate(model, 0.01, n_out=3){'  ' + fm.MUST_SUCCEED if verdict == 'load' else ''}\n"
    ops = [{"code": write, "kind": "write"}, {"code": load, "kind": "load_urdf"},
           {"code": run, "kind": "simulate", "check": "result:r"}]
    if verdict == "load":
        ops[1]["must_succeed"] = ops[2]["must_succeed"] = True
    return ops


def cases(n, seed):
    """n cases, the same for the same seed: [(ops, mutation names)]."""
    rng = random.Random(seed)
    return [case(rng) for _ in range(n)]


if __name__ == "__main__":
    if len(sys.argv) in (3, 4) and sys.argv[1] == "--generate":
        json.dump([ops for ops, _ in cases(int(sys.argv[2]), int((sys.argv[3:] or ["0"])[0]))], sys.stdout)
    elif len(sys.argv) == 4 and sys.argv[1] == "--show":
        ops, mutations = cases(int(sys.argv[3]) + 1, int(sys.argv[2]))[-1]
        print(f"# mutations: {', '.join(mutations) or 'none'}")
        print(fm.reproducer(ops))
    else:
        print(__doc__)
