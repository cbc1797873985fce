"""lagmb models, scene texts and command runners shared by several test files.

Kept apart from references.py so that the references stay free of lagmb.
"""

import math
import subprocess
import sys

import lagmb as mb


def pendulum(L=1.0, m=1.0, g=9.81, angle=0.0, angular_velocity=0.0, inertia=None):
    """The pendulum of the tests (the seed pendulum with the defaults): a
    uniform rod "rod" of length L and mass m (J = m L^2/12 unless `inertia` is
    given) pinned at one end to the ground at the origin by the revolute
    "pin", its centre L/2 out at `angle` from +x, turning at
    `angular_velocity` (at rest by default); gravity (0, -g)."""
    model = mb.Model(gravity=(0.0, -g))
    inertia = m * L**2 / 12.0 if inertia is None else inertia
    c, s = math.cos(angle), math.sin(angle)
    motion = {}
    if angular_velocity:  # the centre moves on its circle about the pin
        motion = dict(velocity=(-0.5 * L * s * angular_velocity, 0.5 * L * c * angular_velocity),
                      angular_velocity=angular_velocity)
    rod = model.add_body("rod", mass=m, inertia=inertia, position=(0.5 * L * c, 0.5 * L * s), angle=angle,
                         **motion)
    model.add_revolute("pin", model.ground, rod, at=(0.0, 0.0))
    return model


def pendulum_scene(L=1.0, m=1.0, g=9.81, angle=0.0, inertia=None):
    """The scene text ([model], [[bodies]], [[joints]]) of pendulum() with the
    same arguments (at rest); a test appends the tables it needs
    ([simulation], [output], drivers, ...). Numbers are written with repr,
    so the text reads back as the same floats."""
    inertia = m * L**2 / 12.0 if inertia is None else inertia
    c, s = math.cos(angle), math.sin(angle)
    angle_line = f"angle = {angle!r}\n" if angle else ""
    return f"""\
[model]
gravity = [0.0, {-g!r}]

[[bodies]]
name = "rod"
mass = {float(m)!r}
inertia = {float(inertia)!r}
position = [{0.5 * L * c!r}, {0.5 * L * s!r}]
{angle_line}
[[joints]]
type = "revolute"
name = "pin"
body_i = "ground"
body_j = "rod"
at = [0.0, 0.0]
"""


def lagmb_command(*args, cwd=None, timeout=300, **options):
    """The `lagmb` command (python -m lagmb) run on args (str() of each) in a
    child process: the CompletedProcess, its output captured as text.
    `options` go to subprocess.run (e.g. preexec_fn)."""
    return subprocess.run([sys.executable, "-m", "lagmb", *map(str, args)], cwd=cwd, capture_output=True,
                          text=True, timeout=timeout, **options)


def lagmb_main(capsys, *args):
    """(exit status, stdout, stderr) of the lagmb command run in this process
    (lagmb.cli.main; argparse's usage errors exit through SystemExit)."""
    from lagmb import cli

    try:
        code = cli.main([str(a) for a in args])
    except SystemExit as e:
        code = e.code
    out, err = capsys.readouterr()
    return code, out, err


def rod_chain(n, L=1.0, m=1.0, g=9.81):
    """n uniform rods (length L, mass m, J = m L^2/12) lying along +x at rest:
    body "rod{k}" has its centre at ((k + 1/2) L, 0) and angle 0; revolute
    "pin0" joins the ground and rod0 at the origin, "pin{k}" joins rod{k-1}
    and rod{k} at (k L, 0).  Gravity (0, -g)."""
    model = mb.Model(gravity=(0.0, -g))
    prev = model.ground
    for k in range(n):
        body = model.add_body(f"rod{k}", mass=m, inertia=m * L**2 / 12.0,
                              position=((k + 0.5) * L, 0.0), angle=0.0)
        model.add_revolute(f"pin{k}", prev, body, at=(k * L, 0.0))
        prev = body
    return model


def hinged_rod_with_mesh(mesh, role, t_end=0.1, size=(1.0, 1.0, 1.0)):
    """A run of a 1 kg rod in space, 1 m along x from a hinge about y at the
    origin, drawn by the STL file `mesh` (a shape of `role`, scaled by `size`): 3 outputs over
    t_end (test_plotting and test_viewer read broken meshes with it)."""
    m = mb.Model(dimension=3)
    rod = m.add_body("rod", 1.0, (1e-3, 1.0 / 12, 1.0 / 12), position=(0.5, 0.0, 0.0))
    m.add_revolute("hinge", m.ground, rod, at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0))
    m.add_shape(rod, "mesh", size, mesh=str(mesh), role=role)
    return mb.simulate(m, t_end, n_out=3)


#: A one-link arm as a URDF file: hinged about y at the origin, its 1 kg centre
#: of mass 0.5 m out along x, limits -1 .. 1 rad (tests/formats/test_urdf.py, test_cli.py).
ARM_URDF = """<robot name="arm">
  <link name="base"/>
  <link name="upper"><inertial><origin xyz="0.5 0 0"/><mass value="1"/>
    <inertia ixx="0.01" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
</robot>
"""


def gif_durations(path):
    """Each frame's duration (ms) of a GIF, as Pillow reads them."""
    from PIL import Image

    with Image.open(path) as im:
        durations = []
        for k in range(im.n_frames):
            im.seek(k)
            durations.append(im.info["duration"])
    return durations
