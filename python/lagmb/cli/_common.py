"""What the subcommands of the lagmb command share: the exit codes, the
Exit exception a handler raises to end with one line and a code, argparse
types for numbers, reading a scene (or a robot's URDF file) and checking an
output path before the run that fills it."""

import argparse
import math
import os

from ..errors import ModelError
from ..scene.schema import elements

OK, FAILED, USAGE, INTERNAL = 0, 1, 2, 3


class Exit(Exception):
    def __init__(self, code, message):
        super().__init__(message)
        self.code = code


def number(text):
    """argparse type: a number as TOML and XML Schema write it
    (lagmb._checks.decimal; float() would read '1_0' as 10)."""
    from .._checks import decimal

    try:
        return decimal(text, "number")
    except ModelError as e:
        raise argparse.ArgumentTypeError(str(e).partition(": ")[2]) from None


def whole(text):
    """argparse type: a whole number, written as number() reads it (its
    range is the option's own check, which names the limit)."""
    try:
        value = number(text)
    except argparse.ArgumentTypeError:
        value = math.nan
    if not (math.isfinite(value) and value.is_integer()):
        raise argparse.ArgumentTypeError(f"{text.strip()!r} is not a whole number")
    return int(value)


def need_matplotlib(what):
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        raise Exit(USAGE, f"{what} needs matplotlib: pip install 'lagmb[plot]'") from None


def robot_options(command):
    """The options of mb.load_urdf, for a .urdf given as the scene."""
    robot = command.add_argument_group("a URDF file (mb.load_urdf)")
    robot.add_argument("--floating-base", action="store_true", help="the root link is a free body")
    robot.add_argument("--no-limits", action="store_true", help="leave the joints' position limits out")
    robot.add_argument("--no-dynamics", action="store_true", help="leave the joints' damping and friction out")
    robot.add_argument("--no-mimic", action="store_true", help="read mimic joints as joints of their own")


def load_robot(args):
    """A Scene of the robot in a URDF file: its model, no settings (the
    command line gives them), its elements listed by table."""
    from ..scene import Scene, SceneElement
    from ..urdf import load_urdf

    try:
        model = load_urdf(args.scene, floating_base=args.floating_base, limits=not args.no_limits,
                          dynamics=not args.no_dynamics, mimic=not args.no_mimic)
    except ModelError as e:
        raise Exit(USAGE, str(e)) from None
    kinds = elements(3)
    listed = [SceneElement(kinds[method].table, kinds[method].type, values["name"], None)
              for method, values in model.elements]
    if not model.bodies:
        raise Exit(USAGE, f"{args.scene}: no bodies: every link is fixed to the root (give --floating-base to "
                          "let the root move)")
    return Scene(model, path=args.scene, elements=listed)


def load(path, args=None):
    from ..scene import load_scene

    if str(path).lower().endswith(".urdf") and args is not None:
        return load_robot(args)
    try:
        scene = load_scene(path)
    except ModelError as e:
        raise Exit(USAGE, str(e)) from None
    except OSError as e:
        raise Exit(USAGE, f"cannot read {path}: {e.strerror or e}") from None
    if not scene.names("bodies") and not scene.names("particles"):
        # nothing moves, and the core is not asked about an empty model
        raise Exit(USAGE, f"{path}: no bodies: a scene needs at least one [[bodies]] or "
                          "[[particles]] table (enabled)")
    return scene


def option_number(option, value, above):
    """A command-line number, if given, must be finite and greater than above."""
    if value is not None and not (math.isfinite(value) and value > above):
        raise Exit(USAGE, f"{option} {value:g}: must be finite and greater than {above:g}")


def output_path(scene, given, option, key, problem):
    """The path of an output: the option's (given) or else the scene's [output]
    key. Checked before the run that fills it: its format (problem(path) says
    why not, or None) and that its folder can take it."""
    path = given or scene.output.get(key)
    if not path:
        return None

    def refuse(reason):
        if given:
            raise Exit(USAGE, f"{option} {path}: {reason}")
        raise Exit(USAGE, str(scene.output_error(key, f"{path!r}: {reason}")))

    reason = problem(path)
    if reason:
        refuse(reason)
    if os.path.isdir(path):
        refuse("is a directory")
    folder = os.path.dirname(os.path.abspath(path))
    while not os.path.lexists(folder):  # missing folders are made when writing
        folder = os.path.dirname(folder)
    if not os.path.isdir(folder):
        refuse(f"{folder} is not a folder")
    target = path if os.path.exists(path) else folder
    why = cannot_write(target)
    if why:
        refuse(why)
    return path


def cannot_write(target):
    """Why a file cannot be written (target a file) or made (target a
    folder), or None: tried, not read from the permission bits, which root
    passes everywhere (a folder such as /proc refuses it all the same)."""
    import tempfile

    where = f"cannot make a file in {target}" if os.path.isdir(target) else f"cannot write {target}"
    try:
        if os.path.isdir(target):
            fd, probe = tempfile.mkstemp(dir=target, prefix=".lagmb-probe-")
            os.close(fd)
            os.remove(probe)
        elif os.path.isfile(target):
            with open(target, "ab"):  # opened to append, nothing written: the file is left as it is
                pass
        elif not os.access(target, os.W_OK):  # a device or a pipe: not opened (a pipe would wait)
            return f"{where}: permission denied"
    except OSError as e:
        return f"{where}: {e.strerror or e}"
    return None


def viewpoint(scene, given):
    """The viewpoint of a spatial animation: --view ELEV,AZIM, else the
    scene's [output] view, else (25, -60)."""
    view = tuple(scene.output.get("view", (25.0, -60.0)))
    if given is not None:
        try:
                view = tuple(number(x) for x in given.split(","))
        except argparse.ArgumentTypeError:
            view = ()
        if len(view) != 2 or not all(math.isfinite(x) for x in view):
            raise Exit(USAGE, f"--view {given}: must be two numbers ELEV,AZIM (degrees)")
    return view
