"""lagmb modes SCENE: the vibration modes about the static equilibrium
(lagmb.statics.equilibrium, lagmb.linear.modes), as a table or a GIF."""

import math

from ..errors import ModelError, SimulationError
from ._common import (FAILED, OK, USAGE, Exit, load, need_matplotlib, number, output_path, robot_options, viewpoint,
                      whole)


def add_parser(sub):
    """lagmb modes's parser."""
    modes = sub.add_parser("modes", help="vibration modes about the static equilibrium",
                           description="Find the scene's static equilibrium (mb.equilibrium; an unstable "
                                       "one too) and its vibration modes about it (mb.modes); print each "
                                       "mode's kind, frequency, damping ratio and the coordinate it moves "
                                       "most, lowest frequency first; --gif animates one.")
    modes.add_argument("scene", help="the scene file (.toml), or a robot's URDF file (.urdf)")
    modes.add_argument("--at-time", type=number, metavar="T",
                       help="the time the equilibrium holds at, for drivers and forces that depend on time "
                            "(default the scene's t0, else 0)")
    modes.add_argument("--count", type=whole, metavar="K", help="list the K lowest modes only (default all)")
    modes.add_argument("--gif", metavar="GIF",
                       help="animate a mode: its shape about the equilibrium (lagmb.plotting.animate_mode)")
    modes.add_argument("--mode", type=whole, metavar="I",
                       help="the mode --gif animates, by its number in the table (default the first "
                            "vibration mode)")
    modes.add_argument("--view", metavar="ELEV,AZIM",
                       help="viewpoint of a spatial model's --gif, degrees (default: [output] view, else 25,-60)")
    robot_options(modes)


def handle(args):
    """Prints the modes' table; --gif animates one of them."""
    from ..errors import EquilibriumError
    from ..linear import modes as vibration_modes
    from ..scene.reader import animation_format_problem
    from ..statics import equilibrium

    scene = load(args.scene, args)
    # the options first: a mistake there costs no analysis
    t = float(scene.settings.get("t0", 0.0)) if args.at_time is None else args.at_time
    if not math.isfinite(t):
        raise Exit(USAGE, f"--at-time {args.at_time:g}: must be a finite time (s)")
    if args.count is not None and args.count < 1:
        raise Exit(USAGE, f"--count {args.count}: must be at least 1")
    if args.mode is not None and args.mode < 0:
        raise Exit(USAGE, f"--mode {args.mode}: must be the number of a mode in the table, 0 or more")
    gif = None
    if args.gif:
        need_matplotlib("--gif")
        gif = output_path(scene, args.gif, "--gif", "animate", animation_format_problem)
    else:
        given = [(option, value) for option, value in (("--mode", args.mode), ("--view", args.view))
                 if value is not None]
        if given:
            option, value = given[0]
            raise Exit(USAGE, f"{option} {value}: there is no animation to apply it to; give --gif GIF")
    view = viewpoint(scene, args.view)

    try:
        at = equilibrium(scene.model, t, allow_unstable=True)
        found = vibration_modes(scene.model, at)
    except EquilibriumError as e:  # none nearby (a free body under gravity), or a force function failed
        raise Exit(FAILED, f"{scene.path}: {e}") from None
    except ModelError as e:  # the scene as a whole (non-conservative forces: no real modes)
        raise Exit(USAGE, f"{scene.path}: {e}") from None
    except SimulationError as e:  # the joints cannot be closed
        raise Exit(FAILED, f"{scene.path}: the equilibrium cannot be found: {e}") from None
    n = len(found)
    index = None
    if gif:
        if args.mode is not None and args.mode >= n:
            raise Exit(USAGE, f"--mode {args.mode}: the scene has {n} mode{'' if n == 1 else 's'}"
                              + (f" (0 .. {n - 1})" if n else ""))
        if not n:
            raise Exit(USAGE, f"--gif {gif}: the scene has no modes to animate (nothing can move)")
        index = args.mode if args.mode is not None else \
            next((i for i, kind in enumerate(found.kinds) if kind == "vibration"), 0)

    for line in _modes_table(scene, found, t, args.count):
        print(line)
    if gif:
        try:
            from .. import plotting

            plotting.animate_mode(found, index, gif, view=view)
        except OSError as e:
            raise Exit(USAGE, f"cannot write {e.filename or gif}: {e.strerror or e}") from None
        print(f"  mode {index} ({found.kinds[index]}) animated in {gif}")
    return OK


def _modes_table(scene, found, t, count=None):
    """The lines lagmb modes prints: what the modes are about, then one row
    a mode (the first count): its number, kind, frequency (Hz), omega
    (rad/s), damping ratio and the coordinate its shape moves most."""
    n = len(found)
    state = {True: "stable", False: "unstable", None: "static"}[found.equilibrium.stable]
    lines = [f"{scene.path}: {n} mode{'' if n == 1 else 's'} about the {state} equilibrium at t = {t:g} s"]
    if not n:
        return lines + ["  no modes: every degree of freedom is driven, nothing can move"]
    head = ("mode", "kind", "frequency (Hz)", "omega (rad/s)", "growth (1/s)", "damping ratio", "moves most")
    rows = []
    for i in range(n if count is None else min(count, n)):
        kind, zeta = found.kinds[i], found.damping_ratios[i]
        # a vibration has a frequency; an unstable mode a growth rate (exp(rate t)), not a
        # frequency; a rigid-body mode neither (its omega: round-off about 0)
        vibrates, grows = kind == "vibration", kind == "unstable"
        rows.append((str(i), kind, f"{found.frequencies[i]:.6g}" if vibrates else "-",
                     f"{found.omega[i]:.6g}" if vibrates else "-", f"{found.omega[i]:.6g}" if grows else "-",
                     "-" if math.isnan(zeta) or not vibrates else f"{zeta:.4g}", found.moves_most(i)))
    width = [max(len(r[k]) for r in rows + [head]) for k in range(len(head))]
    right = (True, False, True, True, True, True, False)
    for r in [head] + rows:
        lines.append("  " + "  ".join(c.rjust(w) if ok else c.ljust(w) for c, w, ok in zip(r, width, right)).rstrip())
    if len(rows) < n:
        lines.append(f"  the {len(rows)} lowest of {n} modes (--count)")
    if "unstable" in found.kinds[:len(rows)]:
        lines.append("  unstable: the equilibrium is unstable in this mode: it grows as exp(growth t), it does not "
                     "vibrate")
    if "rigid-body" in found.kinds[:len(rows)]:
        lines.append("  rigid-body: a motion nothing resists (no frequency, no growth)")
    return lines
