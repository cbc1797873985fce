"""lagmb info SCENE | --methods | --kinds: a scene's size, rank and degrees
of freedom; the methods; the element kinds."""

from ..errors import ModelError, SimulationError
from ..registry import BY_METHOD, SPATIAL_BY_METHOD, markdown
from ..scene.schema import ELEMENT_TABLES, elements, methods
from ._common import FAILED, OK, USAGE, Exit, load, robot_options


def add_parser(sub):
    """lagmb info's parser."""
    info = sub.add_parser("info", help="bodies, coordinates, constraints and degrees of freedom",
                          description="Load a scene and report its size, the rank of its "
                                      "constraint Jacobian at the assembled initial position, "
                                      "its degrees of freedom and any redundant equations; "
                                      "or, with --methods, the integration methods; with --kinds, "
                                      "the element kinds.")
    info.add_argument("scene", nargs="?", help="the scene file (.toml), or a robot's URDF file (.urdf)")
    info.add_argument("--methods", action="store_true",
                      help="list the integration methods (formulation, integrator, what each supports)")
    info.add_argument("--kinds", action="store_true",
                      help="the element kinds and their parameters (Markdown; docs/modelling.md)")
    info.add_argument("--parameters", action="store_true",
                      help="also list the scene's run-time parameters (the names simulate(..., "
                           "parameters=...), sweeps and the FMU take), with value, unit and meaning")
    robot_options(info)


def _methods_table():
    """lagmb.methods() as a table: name, formulation, integrator, support, description."""
    from ..simulation import methods

    rows = []
    for m in methods():
        notes = [f"order <= {m['max_order']}", "fixed step" if m["fixed_step"] else "error control"]
        notes += [w for w, has in (("no events", not m["events"]), ("no contact", m["events"] and not m["contact"]),
                                   ("no friction", not m["friction"]),
                                   ("baumgarte", m["baumgarte"]), ("drifts", m["drifts"])) if has]
        rows.append((m["name"], m["formulation"], m["integrator"], ", ".join(notes), m["description"]))
    head = ("method", "formulation", "integrator", "supports", "")
    width = [max(len(r[k]) for r in rows + [head]) for k in range(4)]
    return ["  ".join(c.ljust(w) for c, w in zip(r[:4], width)) + "  " + r[4] for r in [head] + rows]


def handle(args):
    """Prints the scene's report, or the methods, or the kinds."""
    if args.kinds:
        if args.scene or args.methods:
            raise Exit(USAGE, "--kinds lists the element kinds of lagmb; give no scene or --methods with it")
        print(markdown(), end="")
        return OK
    if args.methods:
        if args.scene:
            raise Exit(USAGE, "--methods lists the methods of lagmb; give no scene with it")
        for line in _methods_table():
            print(line.rstrip())
        return OK
    if not args.scene:
        raise Exit(USAGE, "give a scene file, or --methods")
    scene = load(args.scene, args)
    model = scene.model
    say = print

    def listing(table):
        names = scene.names(table)
        return f"{len(names)}" + (f" ({', '.join(names)})" if names else "")

    def kinds(table):
        els = [e for e in scene.elements if e.table == table]
        counts = {}
        for e in els:
            counts[e.type] = counts.get(e.type, 0) + 1
        return f"{len(els)}" + (" (" + ", ".join(f"{k} {n}" for k, n in counts.items()) + ")"
                                if els else "")

    gravity = getattr(model, "gravity", None)
    dimension = getattr(model, "dimension", 2)
    kinds_here, methods_here = elements(dimension), methods(dimension)
    by_method = BY_METHOD if dimension == 2 else SPATIAL_BY_METHOD
    say(f"scene: {scene.path}")
    if dimension != 2:
        say(f"dimension: {dimension}")
    say(f"gravity: {'none' if gravity is None else tuple(float(g) for g in gravity)}")
    for table in ELEMENT_TABLES:  # from the registry of element kinds
        if not methods_here[table]:
            continue  # no such elements in this dimension
        typed = any(e.table == table and e.type for e in kinds_here.values())
        say(f"{table}: {kinds(table) if typed else listing(table)}")
    try:
        core = model.compiled()
        say(f"coordinates: {core.n_coordinates}")
        stop_rows = len(core.unilateral_rows)
        say(f"constraint equations: {core.n_constraints - stop_rows}" + (
            f" (and {stop_rows} rows of stops, held only while a joint rests on a limit)" if stop_rows else ""))
        inputs = core.inputs
        say(f"inputs: {len(inputs)}" + (" (" + ", ".join(
            f"{i['name']} {i['initial']:g}" + (f" {i['unit']}" if i["unit"] else "") for i in inputs) + ")"
            if inputs else ""))
        parameters = model.parameter_info
        say(f"parameters: {len(parameters)}" + ("" if args.parameters else " (--parameters lists them)"))
        if args.parameters:
            width = max((len(p["name"]) for p in parameters), default=0)
            for p in parameters:
                value = f"{p['value']:.10g}" + (f" {p['unit']}" if p["unit"] else "")
                say(f"  {p['name']:<{width}}  {value:<18}  {p['doc']}")
        rank = model.rank()
    except ModelError as e:
        raise Exit(USAGE, f"{scene.path}: {e}") from None
    except SimulationError as e:
        raise Exit(FAILED, f"{scene.path}: the initial position cannot be assembled: {e}") from None
    say(f"rank of the constraint Jacobian: {rank['rank']}")
    say(f"degrees of freedom: {rank['degrees_of_freedom']}")
    dependent = list(rank.get("dependent_rows", []))
    if not dependent:
        say("redundant equations: none")
    else:
        say(f"redundant equations: {len(dependent)}")
        owners = []
        for e in scene.elements:
            if by_method[methods_here[e.table][e.type]].role in ("joint", "driver"):  # they have rows
                row0, rows = core.constraint_rows(e.name)
                owners.append((row0, rows, e))
        for row in dependent:
            for row0, rows, e in owners:
                if row0 <= row < row0 + rows:
                    say(f"  row {row}: {e.table[:-1]} {e.name!r} ({e.type}, equation "
                        f"{row - row0 + 1} of {rows}" + (f"; line {e.line})" if e.line else ")"))
                    break
            else:
                say(f"  row {row}")
    if scene.settings:
        say("simulation: " + ", ".join(f"{k} = {v!r}" for k, v in scene.settings.items()))
    return OK
