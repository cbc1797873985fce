"""URDF files that are hostile or odd: bad values, loops, long chains of
mimics and long comments, encodings, overflowing numbers, names that
collide (issue 39), and what the robots people have carry: inertias that
break the triangle inequality, meshes not found, mimics of joints the file
does not have, origins in links (issue 41). Each is loaded or refused with
a message naming the line and the element."""

import re
import warnings

import numpy as np
import pytest

import lagmb as mb
from builders import ARM_URDF as ARM
from formats.urdf_robots import load, names, pinocchio_model, write

pin = pytest.importorskip("pinocchio", reason="the robots extra (pin) is not installed")


# --- hostile files and arguments (issue 39) --------------------------------------------------------------

def load_text(tmp_path, text, **options):
    return mb.load_urdf(write(tmp_path, text), **options)


def test_lower_limit_above_upper_is_an_error_and_equal_limits_lock_the_joint(tmp_path):
    """lower > upper (before: the limits were dropped, the joint free) is a
    UrdfError naming the joint, the line and both values. Equal limits lock
    the joint at their value: it is read as a fixed joint there (the arm
    merged into the ground, its frame turned 0.5 rad about y), a position
    given to it or a mimic of it is refused; limits=False reads it as a
    free joint. 0 and 0 (URDF's defaults, as example-robot-data's double
    pendulum writes them) are no limits: the joint turns freely."""
    with pytest.raises(mb.UrdfError) as error:
        load_text(tmp_path, ARM.replace('lower="-1" upper="1"', 'lower="1" upper="-1"'))
    assert "robot.urdf, line 6: joint 'shoulder': lower limit 1.0 is above the upper limit -1.0" in str(error.value)
    locked = ARM.replace('lower="-1" upper="1"', 'lower="0.5" upper="0.5"')
    model = load_text(tmp_path, locked)
    assert model.bodies == [] and names(model) == []
    frame = model.frames["upper"]
    assert frame.body == "ground"
    np.testing.assert_allclose(frame[2], [[np.cos(0.5), 0, np.sin(0.5)], [0, 1, 0], [-np.sin(0.5), 0, np.cos(0.5)]],
                               atol=1e-15)
    assert names(load_text(tmp_path, locked, limits=False)) == ["upper", "shoulder"]
    with pytest.raises(mb.UrdfError, match="positions: joint 'shoulder' is locked at 0.5 by its equal limits"):
        load_text(tmp_path, locked, positions={"shoulder": 0.2})
    follower = locked.replace("</robot>", """<link name="fore"><inertial><mass value="1"/>
      <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/><axis xyz="0 1 0"/>
      <mimic joint="shoulder"/></joint></robot>""")
    with pytest.raises(mb.UrdfError, match="line 10: joint 'elbow': mimics 'shoulder', which is locked at 0.5"):
        load_text(tmp_path, follower)
    free = load_text(tmp_path, ARM.replace('lower="-1" upper="1"', 'lower="0" upper="0"'))
    assert names(free) == ["upper", "shoulder"]
    assert names(load_text(tmp_path, ARM.replace('lower="-1" upper="1" ', ''))) == ["upper", "shoulder"]


@pytest.mark.parametrize("written", ["1_0", "\u0661", "0x1", "1\u00a00", "1,5", "--1", "1e", "one", "nan", "1e999"])
def test_numbers_are_read_as_xml_schema_writes_them(tmp_path, written):
    """A mass of "1_0" (Python's float() read 10), an Arabic-Indic one
    (read as 1), hex, a no-break space, a comma, NaN and a number past a
    double: each a UrdfError naming the file, the line, the link and the
    attribute as written."""
    with pytest.raises(mb.UrdfError) as error:
        load_text(tmp_path, ARM.replace('<mass value="1"/>', f'<mass value="{written}"/>'))
    assert "robot.urdf, line 3: link 'upper': <mass value=" in str(error.value)
    assert repr(written)[1:-1] in str(error.value)


def test_numbers_in_every_decimal_form_are_read(tmp_path):
    """Signs, exponents, a leading or trailing point, blanks and line
    breaks around and between numbers are XML Schema's decimals."""
    text = ARM.replace('<mass value="1"/>', '<mass value=" +1.0E0 "/>').replace(
        '<origin xyz="0.5 0 0"/>', '<origin xyz="\n .5\t0.  -0e-3 "/>')
    model = load_text(tmp_path, text, limits=False)
    assert model.elements[0][1]["mass"] == 1.0
    assert model.compiled().initial_state()[0][:3] == pytest.approx([0.5, 0.0, 0.0])


@pytest.mark.parametrize("option, value", [("limits", "no"), ("floating_base", 1), ("dynamics", None),
                                           ("mimic", "False"), ("limits", np.array([True]))])
def test_true_or_false_options_take_only_true_or_false(tmp_path, option, value):
    """limits="no" loaded the limits (Python's truth of a string): each
    True-or-False option refuses anything but a bool (numpy's bool too)."""
    path = write(tmp_path, ARM)
    with pytest.raises(mb.UrdfError, match=f"load_urdf: {option} must be True or False, got"):
        mb.load_urdf(path, **{option: value})
    assert names(mb.load_urdf(path, **{option: np.bool_(False)}))


@pytest.mark.parametrize("arguments, words", [
    (dict(positions={"shoulder": 10**400}), "positions: joint 'shoulder' is too large for a float"),
    (dict(positions={"shoulder": 1e200}), "positions: joint 'shoulder' = 1e+200 is beyond what a model can hold"),
    (dict(positions={"shoulder": "0.1"}), "positions: joint 'shoulder' must be a number, got '0.1'"),
    (dict(positions="shoulder"), "load_urdf: positions must be a dict {joint: angle or slide}, got 'shoulder'"),
    (dict(positions={5: 0.1}), "positions: 5 is not a revolute, continuous or prismatic joint of the file"),
    (dict(gravity="down"), "load_urdf: gravity must be three finite numbers (x, y, z), got 'down'"),
    (dict(gravity=None), "load_urdf: gravity must be three numbers (x, y, z), got None"),
    (dict(gravity=(0, 0, float("nan"))), "load_urdf: gravity is not finite"),
    (dict(package_dirs=5), "load_urdf: package_dirs must be a directory or a list of directories, got 5"),
    (dict(package_dirs=[None]), "load_urdf: package_dirs must be a directory or a list of directories"),
])
def test_bad_arguments_are_named(tmp_path, arguments, words):
    """Arguments of the wrong kind or size (before: OverflowError,
    ValueError, TypeError): a UrdfError naming the argument and the value."""
    with pytest.raises(mb.UrdfError) as error:
        mb.load_urdf(write(tmp_path, ARM), **arguments)
    assert words in str(error.value)


@pytest.mark.parametrize("path", [5, None, "bad\0name.urdf", "/nowhere/robot.urdf"])
def test_a_path_that_is_no_file_is_named(path):
    with pytest.raises(mb.UrdfError, match="path must be a file name|cannot read the file"):
        mb.load_urdf(path)


def test_a_loop_of_joints_and_a_link_that_is_its_own_parent_are_named(tmp_path):
    """Links a and b joined both ways beside a tree that has its root (and
    a chain hanging below the loop), and a joint whose parent is its child:
    before, KeyError; now a UrdfError naming the joints of the loop and the
    line."""
    loop = ARM.replace("</robot>", """<link name="a"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1"/>
      </inertial></link><link name="b"/><link name="c"/>
      <joint name="ab" type="revolute"><parent link="a"/><child link="b"/></joint>
      <joint name="ba" type="revolute"><parent link="b"/><child link="a"/></joint>
      <joint name="bc" type="fixed"><parent link="b"/><child link="c"/></joint></robot>""")
    with pytest.raises(mb.UrdfError, match="line 9: joint 'ab': joints 'ab' -> 'ba' make a loop that the root link "
                                           "'base' does not reach"):
        load_text(tmp_path, loop)
    itself = ARM.replace("</robot>", '<joint name="aa" type="fixed"><parent link="upper"/><child link="upper"/>'
                                     '</joint></robot>')
    with pytest.raises(mb.UrdfError, match="line 7: joint 'aa': link 'upper' is both its parent and its child"):
        load_text(tmp_path, itself)


def mimic_chain(n):
    """n revolute joints j1..jn in a chain, each j(k+1) mimicking jk
    (x1.001, +0.001)."""
    parts = ['<robot name="chain"><link name="l0"/>']
    for k in range(1, n + 1):
        mimic = f'<mimic joint="j{k - 1}" multiplier="1.001" offset="0.001"/>' if k > 1 else ""
        parts.append(f'<link name="l{k}"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1"/></inertial>'
                     f'</link><joint name="j{k}" type="revolute"><parent link="l{k - 1}"/><child link="l{k}"/>'
                     f'<axis xyz="0 0 1"/>{mimic}</joint>')
    return "\n".join(parts + ["</robot>"])


def mimic_visits(monkeypatch):
    """A Counter, {joint: how often the loader read which joint its <mimic>
    names}, filled by the loads that follow: each follow of a link of a
    chain of mimics reads it once."""
    import collections

    import lagmb.urdf

    visits = collections.Counter()

    class Visited(dict):
        def __init__(self, name, mimic):
            super().__init__(mimic)
            self.name = name

        def __getitem__(self, key):
            if key == "joint":
                visits[self.name] += 1
            return super().__getitem__(key)

    read = lagmb.urdf.reader.Reader.read

    def counting_read(reader):
        links, joints, root, rest = read(reader)
        for name, joint in joints.items():
            if joint["mimic"] is not None:
                joint["mimic"] = Visited(name, joint["mimic"])
        return links, joints, root, rest

    monkeypatch.setattr(lagmb.urdf.reader.Reader, "read", counting_read)
    return visits


def test_a_long_chain_of_mimics_loads_in_linear_time(tmp_path, monkeypatch):
    """1,200 joints each mimicking the one before (before: RecursionError
    from 1,200; the cycle check, and then the mass matrix's walk from each
    follower to its leader, took time quadratic in the chain: 28 s for
    3,000): the model loads with each follower where its leader puts it,
    and a cycle closed at the end of the chain is named. Linear time,
    counted: the loader reads each mimic as often in a chain of 1,200 as
    in one of 30 (a walk from each follower would read the first ones
    about 2,400 times), and the cycle check reads each once or twice."""
    visits = mimic_visits(monkeypatch)
    load_text(tmp_path, mimic_chain(30), positions={"j1": 0.1})
    short = max(visits.values())
    visits.clear()
    model = load_text(tmp_path, mimic_chain(1200), positions={"j1": 0.1})
    assert len(visits) == 1199 and max(visits.values()) == short <= 10
    expected = 0.1
    for _ in range(2, 1201):
        expected = 1.001 * expected + 0.001
    assert model.elements[-1][1]["name"] == "j1200_mimic"
    angles = [kw["angle"] for method, kw in model.elements if method == "add_revolute"]
    assert angles[-1] == pytest.approx(expected, rel=1e-12)
    cycle = mimic_chain(1200).replace('<axis xyz="0 0 1"/></joint>', '<axis xyz="0 0 1"/><mimic joint="j1200"/>'
                                      '</joint>', 1)  # (j1's: j1 mimics j1200)
    visits.clear()
    with pytest.raises(mb.UrdfError, match=r"line 2: joint 'j1': mimics in a cycle of 1200 joints \(j1 -> j1200 -> "
                                           r"j1199 -> j1198 -> j1197 -> j1196 -> \.\.\. -> j3 -> j2 -> j1\)"):
        load_text(tmp_path, cycle)
    assert len(visits) == 1200 and max(visits.values()) <= 2


def test_a_long_comment_loads_in_linear_time(tmp_path, monkeypatch):
    """A 2 MB comment (before: 10 MB took 15 s, expat rescanning the
    unfinished token at each block that ParseFile fed it): the file goes
    to expat whole, in one call (counted), and errors after the comment
    still name their line."""
    import xml.parsers.expat

    calls = []
    create = xml.parsers.expat.ParserCreate

    class Counted:  # (expat's parser type cannot be subclassed: a proxy that counts the feeds)
        def __init__(self, *args, **kwargs):
            object.__setattr__(self, "parser", create(*args, **kwargs))

        def __getattr__(self, name):
            return getattr(self.parser, name)

        def __setattr__(self, name, value):
            setattr(self.parser, name, value)

        def Parse(self, data, final=False):
            calls.append(("Parse", len(data), final))
            return self.parser.Parse(data, final)

        def ParseFile(self, file):
            calls.append(("ParseFile", None, None))
            return self.parser.ParseFile(file)

    monkeypatch.setattr(xml.parsers.expat, "ParserCreate", Counted)
    comment = "<!--" + "x" * 2_000_000 + "\n-->"
    text = ARM.replace('<robot name="arm">', '<robot name="arm">' + comment)
    assert load_text(tmp_path, text).bodies
    assert calls == [("Parse", len(text.encode()), True)]
    with pytest.raises(mb.UrdfError, match="line 4: link 'upper': <mass value='-'>"):
        load_text(tmp_path, text.replace('value="1"', 'value="-"'))


@pytest.mark.parametrize("encoding", ["klingon", "utf-32", "rot13"])
def test_an_encoding_that_cannot_be_read_is_named(tmp_path, encoding):
    """An encoding Python does not know, or that expat cannot take (before:
    LookupError, ValueError)."""
    with pytest.raises(mb.UrdfError, match=f"line 1: the XML declaration's encoding '{encoding}' cannot be read"):
        load_text(tmp_path, f'<?xml version="1.0" encoding="{encoding}"?>\n' + ARM)
    latin = tmp_path / "latin.urdf"
    latin.write_bytes(b'<?xml version="1.0" encoding="ISO-8859-1"?>\n' +
                      ARM.replace("upper", "\xfcpper").encode("latin-1"))
    assert [b.name for b in mb.load_urdf(latin, limits=False).bodies] == ["\xfcpper"]


@pytest.mark.parametrize("change, words", [
    (('<axis xyz="0 1 0"/>', '<axis xyz="0 1 0"/><origin xyz="1.797e308 0 0"/>'),
     "line 5: joint 'shoulder': <origin xyz='1.797e308 0 0'>: 1.797e+308 is beyond what a model can hold"),
    (('<origin xyz="0.5 0 0"/>', '<origin xyz="1e200 0 0"/>'),
     "line 3: link 'upper': <origin xyz='1e200 0 0'>: 1e+200 is beyond"),
    (('<mass value="1"/>', '<mass value="1e300"/>'), "line 3: link 'upper': <mass value='1e300'>: 1e+300 is beyond"),
    (('iyy="0.1"', 'iyy="1e300"'), "line 4: link 'upper': <inertia iyy='1e300'>: 1e+300 is beyond"),
    (('<axis xyz="0 1 0"/>', '<axis xyz="0 1 0"/><dynamics damping="1e300"/>'),
     "line 5: joint 'shoulder': <dynamics damping='1e300'>: 1e+300 is beyond"),
    (('</robot>', '<link name="heavy"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1"/></inertial>'
      '</link><joint name="weld" type="fixed"><parent link="upper"/><child link="heavy"/><origin xyz="2e80 0 0"/>'
      '</joint></robot>'),
     "line 3: link 'upper' (with 'heavy'): mass 2 kg, inertia about its centre of mass up to 2e+160 kg m^2: "
     "beyond what a model can hold"),
])
def test_values_too_large_for_a_model_are_refused_at_load(tmp_path, change, words):
    """A number past 1e150 (a square of it overflows; before: LinAlgError,
    or "constraint_rank: q and t must be finite" in the first run), or a
    body whose inertia m d^2 grows past it (two links 2e80 m apart): a
    UrdfError naming the element."""
    with pytest.raises(mb.UrdfError) as error:
        load_text(tmp_path, ARM.replace(*change), limits=False)
    assert words in str(error.value)


def test_sums_and_products_too_large_for_a_model_are_refused_at_load(tmp_path):
    """Origins each within 1e150 that add up past it down a chain, and a
    chain of mimics whose values grow past it: the joint that puts a link
    too far, the mimic that puts a joint too far."""
    far = "".join(f'<link name="l{k}"/><joint name="f{k}" type="fixed"><parent link="l{k - 1}"/><child link="l{k}"/>'
                  f'<origin xyz="9e149 0 0"/></joint>' for k in range(1, 3))
    with pytest.raises(mb.UrdfError, match="joint 'f2': puts link 'l2' 1.8e\\+150 m from the root: beyond"):
        load_text(tmp_path, f'<robot name="far"><link name="l0"/>{far}</robot>')
    growing = mimic_chain(3).replace('multiplier="1.001"', 'multiplier="1e100"')
    with pytest.raises(mb.UrdfError, match="line 4: joint 'j3': puts it at 1e\\+200 .*: beyond what a model can hold"):
        load_text(tmp_path, growing, positions={"j1": 1.0})


@pytest.mark.parametrize("axis", ["0 1e200 0", "0 1e-200 0", "0 5e-324 0", "0 1.7e308 0"])
def test_an_axis_is_a_direction_at_any_scale(tmp_path, axis):
    """Components 1e200 or 1e-200 (before: refused as "got (0, 0, 0)", or
    as zero) are the direction y, as "0 1 0"; "0 0 0" stays an error."""
    model = load_text(tmp_path, ARM.replace('<axis xyz="0 1 0"/>', f'<axis xyz="{axis}"/>'), limits=False)
    assert model.elements[1][1]["axis"] == (0.0, 1.0, 0.0)
    with pytest.raises(mb.UrdfError, match="line 5: joint 'shoulder': the axis is zero"):
        load_text(tmp_path, ARM.replace('<axis xyz="0 1 0"/>', '<axis xyz="0 0 0"/>'), limits=False)


def test_names_lagmb_makes_do_not_collide_with_the_files(tmp_path):
    """URDF keeps links and joints apart, lagmb has one namespace: a joint
    named like a link is NAME_joint (quietly, as documented); a joint
    'ground', a non-root link 'ground', the damping of 'shoulder' beside a
    joint 'shoulder_damping' (before: a bare ModelError without file or
    line) get their kind or a number added, and one UrdfWarning lists each
    change."""
    from lagmb.urdf import UrdfWarning

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert names(load_text(tmp_path, ARM.replace('name="shoulder"', 'name="upper"'))) == \
            ["upper", "upper_joint", "upper_joint_limit"]
    text = ARM.replace('name="shoulder"', 'name="ground"').replace('<axis xyz="0 1 0"/>',
                                                                   '<axis xyz="0 1 0"/><dynamics damping="0.1"/>')
    text = text.replace("</robot>", """<link name="x"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1"/>
      </inertial></link><joint name="ground_joint_damping" type="revolute"><parent link="upper"/>
      <child link="x"/></joint></robot>""")
    with pytest.warns(UrdfWarning) as caught:
        model = load_text(tmp_path, text)
    assert names(model) == ["upper", "x", "ground_joint", "ground_joint_damping_2", "ground_joint_limit",
                            "ground_joint_damping"]
    message = str(caught[0].message)
    assert "robot.urdf: lagmb keeps one namespace for all names" in message
    assert "joint 'ground' is 'ground_joint' (the ground has the name 'ground')" in message
    assert ("the damping of joint 'ground' is 'ground_joint_damping_2' (joint 'ground_joint_damping' has the name "
            "'ground_joint_damping')") in message
    with pytest.warns(UrdfWarning, match="link 'ground' is 'ground_link'"):
        model = load_text(tmp_path, ARM.replace('"upper"', '"ground"'))
    assert [b.name for b in model.bodies] == ["ground_link"]


def test_a_bad_shape_names_its_link_and_line(tmp_path):
    """A sphere of radius -1 on the root link (before: "shape on 'ground'")
    and on the arm: the link and the line of the shape."""
    sphere = '<visual><geometry><sphere radius="-1"/></geometry></visual>'
    for old, new, words in (('<link name="base"/>', f'<link name="base">{sphere}</link>', "line 2: link 'base'"),
                            ('<link name="upper">', f'<link name="upper">{sphere}', "line 3: link 'upper'")):
        with pytest.raises(mb.UrdfError) as error:
            load_text(tmp_path, ARM.replace(old, new), limits=False)
        assert f"{words}: <visual> a sphere's size must be positive" in str(error.value)


def test_names_that_still_collide_or_that_lagmb_cannot_hold_name_both_lines(tmp_path):
    """Two links (or two joints) of one name: the second's line and the
    first's; a joint name lagmb's names cannot take (a leading blank, a
    tab): the core's refusal with the file, the line and the joint."""
    second = ARM.replace("</robot>", '<link name="upper"/></robot>')
    with pytest.raises(mb.UrdfError, match="line 7: a second link named 'upper' \\(the first is on line 3\\)"):
        load_text(tmp_path, second)
    second = ARM.replace("</robot>", '<link name="x"/><joint name="shoulder" type="fixed"><parent link="upper"/>'
                                     '<child link="x"/></joint></robot>')
    with pytest.raises(mb.UrdfError, match="line 7: a second joint named 'shoulder' \\(the first is on line 5\\)"):
        load_text(tmp_path, second)
    for name in (" shoulder", "a&#9;b"):
        with pytest.raises(mb.UrdfError, match="line 5: joint '.*': .*name"):
            load_text(tmp_path, ARM.replace('name="shoulder"', f'name="{name}"'))


# --- the robots people have (issue 41) -------------------------------------------------------------------

def test_an_inertia_that_breaks_the_triangle_inequality_runs_with_a_warning(tmp_path):
    """Moments (0.01, 0.3, 0.01) kg m^2: I_yy is more than I_xx + I_zz, which
    no rigid body has, but files hold such numbers and Pinocchio runs them.
    The arm loads with a UrdfWarning naming the link, its line and its
    moments, and swings about y with the angular acceleration
    m g r / (I_yy + m r^2) of the moment as written; strict=True refuses it."""
    text = ARM.replace('iyy="0.1" izz="0.1"', 'iyy="0.3" izz="0.01"')
    with pytest.warns(mb.UrdfWarning) as caught:
        model = load_text(tmp_path, text, limits=False)
    message = str(caught[0].message)
    assert "robot.urdf, line 4: link 'upper': its principal moments of inertia [0.01, 0.01, 0.3" in message
    assert "break the triangle inequality" in message and "strict=True refuses them" in message
    r = mb.simulate(model, 0.1, n_out=3, rtol=1e-10, atol=1e-12)
    assert r.joint("shoulder").acceleration[0] == pytest.approx(9.81 * 0.5 / (0.3 + 0.25), rel=1e-12)
    with pytest.raises(mb.UrdfError, match="line 3: link 'upper': .*break the triangle inequality"):
        load_text(tmp_path, text, limits=False, strict=True)
    with pytest.raises(mb.UrdfError, match="strict"):
        load_text(tmp_path, text, strict="yes")
    with pytest.raises(mb.ModelError, match="triangle inequality .*rigid_inertia=False accepts them"):
        mb.Model(dimension=3).add_body("b", 1.0, (0.01, 0.3, 0.01))


def test_an_inertia_no_body_has_is_built_with_the_nearest_a_body_has(tmp_path):
    """Moments (-0.01, 0.1, 0.15) kg m^2 (about x, y, z): negative, and
    0.15 > -0.01 + 0.1. The nearest moments a rigid body has (each >= 0 and
    at most the sum of the other two) lie on the plane I_xx + I_yy = I_zz,
    a third of the excess 0.06 from each: (0.01, 0.12, 0.13). The arm
    loads with a UrdfWarning naming the link, its line and both sets of
    moments, and swings about y with m g r / (0.12 + m r^2); strict=True
    refuses the tensor."""
    text = ARM.replace('ixx="0.01" iyy="0.1" izz="0.1"', 'ixx="-0.01" iyy="0.1" izz="0.15"')
    with pytest.warns(mb.UrdfWarning) as caught:
        model = load_text(tmp_path, text, limits=False)
    message = str(caught[0].message)
    assert "1 inertia tensor is not positive semi-definite" in message
    assert "link 'upper', line 4: principal moments [-0.01, 0.1, 0.15" in message
    built = [float(x) for x in re.search(r"built with \[([^]]*)\]", message).group(1).split(",")]
    assert built == pytest.approx([0.01, 0.12, 0.13], abs=1e-15)
    inertia = [kw["inertia"] for kind, kw in model.elements if kind == "add_body"][0]
    np.testing.assert_allclose(inertia, np.diag([0.01, 0.12, 0.13]), atol=1e-15)
    r = mb.simulate(model, 0.1, n_out=3, rtol=1e-10, atol=1e-12)
    assert r.joint("shoulder").acceleration[0] == pytest.approx(9.81 * 0.5 / (0.12 + 0.25), rel=1e-12)
    with pytest.raises(mb.UrdfError, match=r"line 4: link 'upper': the inertia tensor is not positive semi-definite "
                                           r"\(principal moments \[-0.01"):
        load_text(tmp_path, text, limits=False, strict=True)


def test_a_mesh_not_found_is_left_out_with_a_warning(tmp_path):
    """A mesh the file names but no directory holds: the shape is left out
    with one UrdfWarning naming the link, the line and the file name; the
    model is the one without the shape (its dynamics come from <inertial>).
    strict=True refuses it, naming where it looked."""
    text = ARM.replace('<link name="upper">', '<link name="upper"><visual><geometry>'
                       '<mesh filename="package://nowhere/m.stl"/></geometry></visual>')
    with pytest.warns(mb.UrdfWarning, match=r"robot.urdf: 1 mesh not found, its <visual>/<collision> shape left out "
                                            r"\(the links' <inertial> give the dynamics.*link 'upper', line 3: "
                                            r"'package://nowhere/m.stl'"):
        model = load_text(tmp_path, text)
    assert model.shapes == [] and model.elements == load_text(tmp_path, ARM).elements
    with pytest.raises(mb.UrdfError, match=r"line 3: link 'upper': mesh 'package://nowhere/m.stl' not found "
                                           r"\(looked in .*strict=False"):
        load_text(tmp_path, text, strict=True)


def test_a_mimic_of_a_joint_the_file_does_not_have_is_a_joint_of_its_own(tmp_path):
    """<mimic joint="wrist"> where the file has no joint 'wrist' (Alex's
    hands name their fingers' leaders without the Left_/Right_ of their
    joints): one UrdfWarning names the joint, the line and the missing
    leader, and the elbow is an ordinary joint, free, as with mimic=False;
    strict=True refuses it."""
    text = ARM.replace("</robot>", """<link name="fore"><inertial><mass value="0.5"/>
      <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/>
      <origin xyz="0.3 0 0"/><axis xyz="0 1 0"/><mimic joint="wrist"/></joint></robot>""")
    with pytest.warns(mb.UrdfWarning, match=r"robot.urdf: 1 mimic of a joint the file does not have, each joint read "
                                            r"as a joint of its own that moves freely \(not coupled.*joint 'elbow', "
                                            r"line 10: mimics 'wrist'"):
        model = load_text(tmp_path, text, limits=False)
    assert model.elements == load_text(tmp_path, text, limits=False, mimic=False).elements
    assert "add_joint_coupling" not in [kind for kind, _ in model.elements]
    with pytest.raises(mb.UrdfError, match="line 10: joint 'elbow': mimics 'wrist', which is not a joint of the file"):
        load_text(tmp_path, text, limits=False, strict=True)


def test_an_origin_in_a_link_is_ignored_with_a_warning(tmp_path):
    """<origin> directly in <link> means nothing in URDF (a link is placed by
    its parent joint); urdfdom ignores it, and so does lagmb, with a
    UrdfWarning naming the file, the line and the link: the arm swings as
    without it."""
    text = ARM.replace('<link name="upper">', '<link name="upper"><origin xyz="1 2 3"/>')
    with pytest.warns(mb.UrdfWarning, match="robot.urdf, line 3: link 'upper': <origin> in <link> is ignored"):
        model = load_text(tmp_path, text, limits=False)
    assert model.elements == load_text(tmp_path, ARM, limits=False).elements


def test_a_joint_and_a_link_of_one_name_are_each_found(tmp_path):
    """URDF keeps links and joints apart: a joint 'upper' turning the link
    'upper' is the model's joint upper_joint, and 'upper' its alias, so
    r.joint('upper') (and r.reaction, a stop's joint) is the joint while
    r.body('upper') is the link. The hinge's vertical force on the arm
    released at rest is m (g - r alpha) (r = 0.5 m, alpha = m g r /
    (I_yy + m r^2)): gravity less the force that accelerates its centre."""
    text = ARM.replace('name="shoulder"', 'name="upper"')
    model = load_text(tmp_path, text, limits=False)
    assert names(model) == ["upper", "upper_joint"]
    r = mb.simulate(model, 0.05, n_out=3, rtol=1e-10, atol=1e-12)
    np.testing.assert_array_equal(r.joint("upper").angle, r.joint("upper_joint").angle)
    np.testing.assert_array_equal(r.reaction("upper"), r.reaction("upper_joint"))
    assert r.body("upper").position[0] == pytest.approx([0.5, 0.0, 0.0])
    alpha = 9.81 * 0.5 / (0.1 + 0.25)
    assert r.reaction("upper")[0, 2] == pytest.approx(9.81 - 0.5 * alpha, rel=1e-9)
    model.add_stop("upper_stop", joint="upper", lower=-0.5, upper=0.5)  # (the alias where a joint is asked for)
    assert model.elements[-1][1]["joint"] == "upper_joint"
    with pytest.raises(mb.ModelError, match="an alias is a body's or frame's name"):
        model.add_joint_alias("somewhere", "upper_joint")


def test_so100s_gripper_link_and_gripper_joint_are_each_found():
    """so100.urdf has a link and a joint both named 'gripper': r.joint and
    r.body each find their own, and the joint's acceleration equals
    Pinocchio's ABA for its joint 'gripper'."""
    relpath = "so_arm_description/urdf/so100.urdf"
    model = load(relpath)
    pm = pinocchio_model(relpath)
    pd = pm.createData()
    r = mb.simulate(model, 0.01, n_out=2, rtol=1e-10, atol=1e-12)
    expected = pin.aba(pm, pd, pin.neutral(pm), np.zeros(pm.nv), np.zeros(pm.nv))
    gripper = pm.joints[pm.getJointId("gripper")].idx_v
    assert r.joint("gripper").acceleration[0] == pytest.approx(expected[gripper], rel=1e-9, abs=1e-12)
    added = {kw["name"]: kw for method, kw in model.elements if method == "add_body"}
    assert r.body("gripper").position[0] == pytest.approx(added["gripper"]["position"], abs=1e-12)


def test_a_file_where_nothing_moves_suggests_a_floating_base(tmp_path):
    """A flying robot's single link on a fixed base has nothing to move: a
    UrdfError says so and suggests floating_base=True, with which the link
    falls freely (z = -g t^2 / 2)."""
    text = '<robot name="drone"><link name="frame"><inertial><mass value="2"/>' \
           '<inertia ixx="0.1" iyy="0.1" izz="0.2"/></inertial></link></robot>'
    with pytest.raises(mb.UrdfError, match="line 1: link 'frame': nothing moves: .*floating_base=True"):
        load_text(tmp_path, text)
    r = mb.simulate(load_text(tmp_path, text, floating_base=True), 0.5, n_out=2, rtol=1e-10, atol=1e-12)
    assert r.body("frame").position[-1] == pytest.approx([0.0, 0.0, -9.81 * 0.5 ** 2 / 2], abs=1e-10)
