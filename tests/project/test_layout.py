"""The C++ sources sit in folders by layer, and every #include points down
(docs/design.md, section 2): a file includes from its own layer or the
layers before it, never after. CMakeLists.txt lists the layers in this
order (LAGMB_LAYERS) and builds every source of each folder."""

import pathlib
import re
import paths  # noqa: E402  (tests/paths.py)

ROOT = pathlib.Path(paths.ROOT)
CPP = ROOT / "cpp"
INCLUDE = re.compile(r'^#include "([^"]+)"', re.M)


def layers():
    """The layers in CMakeLists.txt's order."""
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"set\(LAGMB_LAYERS ([^)]*)\)", text).group(1).split()


def layer_of(path):
    """The layer of a file: its folder under cpp/src or cpp/include/lagmb
    (the basic headers, directly in lagmb/: the base)."""
    rel = path.relative_to(CPP)
    parts = rel.parts
    if parts[0] == "include" and len(parts) == 3:
        return "base"
    return parts[2] if parts[0] == "include" else parts[1]


def resolve(name, here):
    """The file an #include names: public (lagmb/...), or internal
    (relative to cpp/src); None for a header from elsewhere."""
    for base in (CPP / "include", CPP / "src", here.parent):
        path = base / name
        if path.exists():
            return path.resolve()
    return None


def sources():
    return sorted(p for p in (CPP / "src").rglob("*") if p.suffix in (".cpp", ".hpp")) + \
        sorted(p for p in (CPP / "include" / "lagmb").rglob("*.hpp"))


def test_every_source_sits_in_a_layer_folder():
    order = layers()
    strays = [str(p.relative_to(ROOT)) for p in sources() if layer_of(p) not in order]
    assert strays == []
    assert [p.name for p in (CPP / "src").iterdir() if p.is_file()] == []


def test_includes_point_down():
    rank = {name: k for k, name in enumerate(layers())}
    upward = []
    for path in sources():
        if path.name == "lagmb.hpp":  # the umbrella: everything, for users
            continue
        mine = rank[layer_of(path)]
        for name in INCLUDE.findall(path.read_text()):
            target = resolve(name, path)
            if target is None or CPP not in target.parents:
                continue
            theirs = rank[layer_of(target)]
            if theirs > mine:
                upward.append(f"{path.relative_to(ROOT)} ({layer_of(path)}) includes {name} ({layer_of(target)})")
    assert upward == []


def test_the_umbrella_header_includes_every_public_header():
    umbrella = (CPP / "include" / "lagmb" / "lagmb.hpp").read_text()
    public = {str(p.relative_to(CPP / "include")) for p in (CPP / "include" / "lagmb").rglob("*.hpp")
              if p.parent.name != "elements" and p.name != "lagmb.hpp"}
    # the kinds' containers, the bodies, gravity, the joints' coordinates and turn counters come with the
    # model; the basic headers with any
    indirect = {"lagmb/model/constraint_group.hpp", "lagmb/model/force_group.hpp", "lagmb/model/event_group.hpp",
                "lagmb/model/friction_group.hpp", "lagmb/model/joint_turns.hpp", "lagmb/model/body.hpp",
                "lagmb/model/gravity.hpp", "lagmb/model/joint_coordinate.hpp", "lagmb/model/joint_reading.hpp",
                "lagmb/space.hpp", "lagmb/spatial.hpp", "lagmb/spatial_terms.hpp", "lagmb/projected_offset.hpp",
                "lagmb/sparsity.hpp", "lagmb/time_function.hpp", "lagmb/interrupt.hpp", "lagmb/dual.hpp"}
    missing = sorted(public - indirect - set(INCLUDE.findall(umbrella)))
    assert missing == []



def test_unit_tests_include_public_headers_only():
    """The C++ unit tests (cpp/tests) check the core as its users see it:
    they include lagmb's public headers and their own helpers (check.hpp,
    models.hpp), not cpp/src's internal ones, which may move under them."""
    tests = CPP / "tests"
    internal = [f"{path.name} includes {name}" for path in sorted(tests.glob("*.[ch]pp"))
                for name in INCLUDE.findall(path.read_text())
                if not ((CPP / "include" / name).exists() or (tests / name).exists())]
    assert sorted(tests.glob("test_*.cpp")) and internal == []

def test_assemble_names_fill_matrices():
    """assemble_* names the assembly kernels (lagmb/assembly/assembly.hpp),
    which fill Data's matrices and vectors at one state; what solves for a
    state (positions on Phi = 0, a consistent start) is a solve_* of the
    analyses layer (lagmb/analyses/consistent_state.hpp). The run-level
    assemble(model, t), Python's Model.assemble(), is the one other."""
    declared = re.compile(r"^[A-Za-z][^;/()]*\b(assemble\w*)\(", re.M)
    found = sorted(f"{path.relative_to(CPP)}: {name}" for path in sources() if path.suffix == ".hpp"
                   for name in declared.findall(path.read_text()))
    stray = [f for f in found if not f.startswith("include/lagmb/assembly/assembly.hpp:")]
    assert stray == ["include/lagmb/run/simulate.hpp: assemble"]


def test_runs_know_formulations_by_their_interface():
    """The run (cpp/src/run) takes its formulations through DaeFormulation
    and the methods table (formulations/dae.hpp, integrators/methods.hpp),
    never a concrete one by name: a new formulation touches no run code."""
    concrete = re.compile(r"\b(?!Dae)[A-Z]\w*Formulation\b(?!::)")
    named = [f"{path.name}: {name}" for path in sorted((CPP / "src" / "run").glob("*.[ch]pp"))
             for name in concrete.findall(path.read_text())]
    assert named == []


def test_a_runs_data_are_made_of_the_runs():
    """Every Data of a run (each formulation's, the event runner's, the
    checks') is made of the run's Data by Data's constructor, which shares
    the run's values: no site joins one by hand, so none can forget to
    and read stale inputs."""
    joined = [f"{path.relative_to(CPP)}" for path in sources() + sorted((CPP / "tests").glob("*.[ch]pp"))
              if re.search(r"\b(join_run|share_values)\b", path.read_text())]
    assert joined == []


# --- the Python package -------------------------------------------------------

#: The Python modules by layer, lowest first (docs/design.md, section 2):
#: each imports only from its own layer or the ones before, at the top of a
#: file or inside a function alike (a late import is still a dependency).
PYTHON_LAYERS = [
    ["_core", "_version", "errors", "progress", "registry", "_checks", "functions", "handles", "_meshes", "_rotations",
     "_output_names"],
    ["model", "_poses", "joints"],
    ["result", "_deep_start", "_run_options", "simulation", "simulator", "statics", "linear", "accuracy"],
    ["_drawing"],
    ["scene", "plotting", "demo", "_model_files", "urdf", "mjcf", "studies", "viewer"],
    ["fmu", "cli", "__main__", "__init__"],
]


def python_imports(path, package):
    """The lagmb modules a file imports (relative imports, resolved; the
    first part below lagmb: 'scene' for lagmb.scene.reader)."""
    import ast

    here = list(path.relative_to(package).with_suffix("").parts[:-1])
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.level > 0:
            base = here[:len(here) - (node.level - 1)] if node.level > 1 else here
            names = (base + node.module.split(".")) if node.module else None
            for target in ([names] if names else [base + [a.name] for a in node.names]):
                found.add(target[0] if target else "__init__")
    return found


def test_python_imports_point_down():
    package = ROOT / "python" / "lagmb"
    rank = {name: k for k, layer in enumerate(PYTHON_LAYERS) for name in layer}
    modules = sorted(package.rglob("*.py"))
    unplaced = [str(p.relative_to(package)) for p in modules if p.relative_to(package).parts[0].removesuffix(".py")
                not in rank]
    assert unplaced == []
    upward = []
    for path in modules:
        mine = path.relative_to(package).parts[0].removesuffix(".py")
        for target in python_imports(path, package):
            if target != mine and rank[target] > rank[mine]:
                upward.append(f"{path.relative_to(package)} imports {target}")
    assert upward == []


def private_names_read(path, package):
    """The private names (one leading underscore) that a module of the
    package reads from another module: ``from .x import _name`` (relative
    or ``lagmb.``), or ``x._name`` of a module it imported. A private
    *module* (``from . import _checks``, lagmb._core, a package's
    ``_figures``) is not one: it may be imported anywhere in the package;
    what it holds for others it names publicly."""
    import ast

    here = path.relative_to(package).parent
    found, modules = [], set()
    for node in ast.walk(ast.parse(path.read_text())):
        if not isinstance(node, ast.ImportFrom):
            continue
        if node.level:
            base = package / here
            for _ in range(node.level - 1):
                base = base.parent
        elif (node.module or "").split(".")[0] == "lagmb":
            base = package.parent
        else:
            continue
        target = base.joinpath(*(node.module or "").split(".")) if node.module else base
        for alias in node.names:
            is_module = (target / f"{alias.name}.py").exists() or (target / alias.name).is_dir() or \
                (target == package and alias.name == "_core")  # (the compiled core)
            if is_module:
                modules.add(alias.asname or alias.name)
            elif alias.name.startswith("_") and not alias.name.startswith("__"):
                found.append(f"{path.relative_to(package)}:{node.lineno}: imports {alias.name} from "
                             f"{'.' * node.level}{node.module or ''}")
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in modules \
                and node.attr.startswith("_") and not node.attr.startswith("__"):
            found.append(f"{path.relative_to(package)}:{node.lineno}: reads {node.value.id}.{node.attr}")
    return found


def test_no_module_reads_another_modules_private_names():
    """A name with a leading underscore is private to its module: no other
    module of lagmb imports it or reads it off the module. What modules
    share is public in the module whose job it is (the run options in
    lagmb._run_options for simulate, Simulator and the FMU; a failed run's
    partial Result in lagmb.result; what URDF and MJCF share in
    lagmb._model_files; the pictures' matplotlib set-up in
    lagmb.plotting._figures). A leading underscore on a *module* (lagmb._checks,
    lagmb._rotations, lagmb._core) keeps it out of the public API, not out
    of the package: its public names are for lagmb's other modules."""
    package = ROOT / "python" / "lagmb"
    found = [line for path in sorted(package.rglob("*.py")) for line in private_names_read(path, package)]
    assert found == []


def test_the_private_name_rule_sees_both_ways_of_reading_a_name(tmp_path):
    """private_names_read finds `from .x import _name` and `x._name`, and
    passes a private module and its public names."""
    package = tmp_path / "lagmb"
    (package / "plotting").mkdir(parents=True)
    for name in ("__init__.py", "_checks.py", "viewer.py", "plotting/__init__.py", "plotting/_figures.py"):
        (package / name).write_text("")
    (package / "plotting" / "history.py").write_text(
        "from . import _figures\nfrom ._figures import new_figure, _colour\nfrom .. import viewer, _checks\n"
        "viewer._three_js()\n_checks.show(1)\n_figures.new_figure()\n")
    assert private_names_read(package / "plotting" / "history.py", package) == [
        "plotting/history.py:2: imports _colour from ._figures", "plotting/history.py:4: reads viewer._three_js"]


#: The longest a Python module of lagmb may be (lines): past it, a module
#: holds more than one job (docs/design.md; HELPERS: files under 900 lines).
MAX_MODULE_LINES = 900


def test_no_python_module_is_over_900_lines():
    package = ROOT / "python" / "lagmb"
    long = {str(p.relative_to(package)): n for p in sorted(package.rglob("*.py"))
            if (n := len(p.read_text().splitlines())) > MAX_MODULE_LINES}
    assert long == {}


# --- the layers as docs/design.md lists them -------------------------------------


def design_layer_tables():
    """The two tables of docs/design.md section 2.0: the C++ layer folders
    (first column) and the Python layers (the modules of each row)."""
    text = (ROOT / "docs" / "design.md").read_text()
    section = text.split("### 2.0 Layers", 1)[1].split("\n### ", 1)[0]
    tables, rows = [], None
    for line in section.splitlines():
        if line.startswith("|"):
            if rows is None:
                rows = []
                tables.append(rows)
            cells = [c.strip() for c in line.strip("|").split("|")]
            if set(cells[0]) <= set("-: "):  # the rule under the head
                continue
            rows.append(cells)
        else:
            rows = None
    cpp, python = (table[1:] for table in tables)  # without the heads
    return ([re.fullmatch(r"`(\w+)`", row[0]).group(1) for row in cpp],
            [re.findall(r"`(\w+)`", row[1]) for row in python])


def test_design_lists_the_layers_the_tests_enforce():
    """docs/design.md names every C++ layer folder, in CMake's order, and
    each Python layer with the modules test_python_imports_point_down
    places in it, so the document cannot drift from the code."""
    cpp, python = design_layer_tables()
    assert cpp == layers()
    assert sorted(cpp) == sorted(p.name for p in (CPP / "src").iterdir() if p.is_dir())
    assert python == PYTHON_LAYERS


def test_design_names_every_public_header_of_each_layer():
    """Each row of the C++ layer table names the public headers of its layer
    (lagmb/<layer>/*.hpp; the base's directly in lagmb/), but the elements,
    which the row describes as one header per kind: a header added to a
    layer must be added to its row."""
    text = (ROOT / "docs" / "design.md").read_text()
    section = text.split("### 2.0 Layers", 1)[1].split("\n### ", 1)[0]
    rows = {m.group(1): m.group(2) for m in re.finditer(r"^\| `(\w+)` \| ([^|]*) \|", section, re.M)}
    include = CPP / "include" / "lagmb"
    missing = []
    for layer in layers():
        if layer == "elements":
            continue
        folder = include if layer == "base" else include / layer
        for header in sorted(folder.glob("*.hpp")):
            if header.stem != "lagmb" and not re.search(rf"\b{header.stem}\b", rows[layer]):
                missing.append(f"{layer}: {header.name}")
    assert missing == []


def test_kinds_are_known_by_their_registry_entry_not_their_name():
    """What an element is (a driver; a joint with an angle or a slide) is
    read from its kind's entry (lagmb.registry: role, coordinates), so a new
    kind needs nothing in Python: no module names a driver or joint kind to
    decide it. Outside the rule: urdf and mjcf (their formats' own joint
    types) and plotting (a kind's picture is drawing, not semantics)."""
    import ast

    from lagmb import registry

    named = {"_driver"} | {name for k in registry.ALL_KINDS if k.role == "driver" or k.coordinate
                           for name in (k.name, k.method)} - {"drive_joint", "drive_body"}
    package = ROOT / "python" / "lagmb"
    found = []
    for path in sorted(package.rglob("*.py")):
        where = path.relative_to(package)
        if where.parts[0] in ("urdf", "mjcf.py", "plotting"):
            continue
        found += [f"{where}:{node.lineno}: {node.value!r}" for node in ast.walk(ast.parse(path.read_text()))
                  if isinstance(node, ast.Constant) and node.value in named]
    assert found == []


def test_each_subcommand_of_the_command_line_stands_alone():
    """lagmb.cli is a module per subcommand (add_parser, handle) and the
    package's __init__ that dispatches by its table: a subcommand's module
    imports, of lagmb.cli, only the shared lagmb.cli._common."""
    import ast

    cli = ROOT / "python" / "lagmb" / "cli"
    found = []
    for path in sorted(cli.glob("*.py")):
        if path.name in ("__init__.py", "__main__.py", "_common.py"):
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level == 1 and node.module != "_common":
                found.append(f"{path.name} imports .{node.module or ''}")
        names = {n.name for n in ast.parse(path.read_text()).body if isinstance(n, ast.FunctionDef)}
        if not {"add_parser", "handle"} <= names:
            found.append(f"{path.name} lacks add_parser or handle")
    assert found == []


def test_the_fuzzers_helpers_point_down():
    """The fuzzers' helpers (tests/fuzz/ but its test_*.py: fuzz_*.py, the
    worker, the law runner) stand below the tests: none imports a test
    module or conftest; the worker, which runs every fuzzer's cases
    (fuzz_stops' checks import fuzz_stops by name in the worker), and the
    mechanism fuzzer import none of the other fuzzers."""
    import ast

    tests = ROOT / "tests" / "fuzz"
    helpers = sorted(p for p in tests.glob("*.py") if not p.name.startswith(("test_", "__")))
    wrong = []
    for path in helpers:
        names = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                names |= {a.name.split(".")[0] for a in node.names}
            elif isinstance(node, ast.ImportFrom) and node.module and not node.level:
                names.add(node.module.split(".")[0])
        wrong += [f"{path.name} imports {n}" for n in sorted(names) if n.startswith("test_") or n == "conftest"]
        if path.name in ("fuzz_mechanisms.py", "worker.py"):
            wrong += [f"{path.name} imports {n}" for n in sorted(names) if n.startswith("fuzz_")]
    assert {"fuzz_mechanisms.py", "worker.py", "laws.py"} <= {p.name for p in helpers} and wrong == []


#: the test folders, each after the part of lagmb it checks
TEST_FOLDERS = {
    "elements": "the kinds: joints, drivers, forces, stops, contacts (cpp/src/elements, collision)",
    "analyses": "kinematics, statics, linearization, modes, derivatives, sensitivities (cpp/src/analyses)",
    "integrators": "formulations, methods, drift, effect costs, run state (cpp/src/formulations, integrators)",
    "api": "the Python Model, registry, handles, Simulator, errors and hostile calls (python/lagmb)",
    "formats": "scene files, URDF, MJCF, FMU (python/lagmb/scene, urdf, mjcf, fmu)",
    "tools": "the command line, sweeps, plots, the viewer, examples, docs, README",
    "project": "the layout, the C++ library and unit tests, the wheel and the clean room",
    "fuzz": "the fuzzers, their worker and their runner",
    "hard": "hard cases that must stay numerically stable",
}


def test_the_tests_stand_in_folders_after_the_code_they_check():
    """Every test file is in one of TEST_FOLDERS (a package, so that test
    modules of one name in two folders cannot collide), but
    test_references.py, which checks the references beside it; the shared
    helpers (builders, references, paths, browser) stay in tests/. No test
    file is over 1,500 lines."""
    tests = ROOT / "tests"
    loose = sorted(p.name for p in tests.glob("test_*.py"))
    assert loose == ["test_references.py"]
    folders = sorted(p.name for p in tests.iterdir() if p.is_dir() and any(p.glob("test_*.py")))
    assert folders == sorted(TEST_FOLDERS)
    assert all((tests / f / "__init__.py").exists() for f in TEST_FOLDERS)
    long = [f"{p.relative_to(tests)}: {n}" for p in sorted(tests.rglob("*.py"))
            if (n := len(p.read_text().splitlines())) > 1500]
    assert long == []
