"""The C++ sources sit in folders by layer, and every #include points down
(docs/design.md, section 2): a file includes from its own layer or the
layers before it, never after. CMakeLists.txt lists the layers in this
order (LAGMB_LAYERS) and builds every source of each folder."""

import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[1]
CPP = ROOT / "cpp"
INCLUDE = re.compile(r'^#include "([^"]+)"', re.M)


def layers():
    """The layers in CMakeLists.txt's order."""
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"set\(LAGMB_LAYERS ([^)]*)\)", text).group(1).split()


def layer_of(path):
    """The layer of a file: its folder under cpp/src or cpp/include/lagmb
    (element kinds are the model's layer; the basic headers the base)."""
    rel = path.relative_to(CPP)
    parts = rel.parts
    folder = parts[2] if parts[0] == "include" else parts[1]
    if parts[0] == "include" and len(parts) == 3:
        return "base"
    return "model" if folder == "elements" else folder


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
    order = layers() + ["model"]
    strays = [str(p.relative_to(ROOT)) for p in sources() if layer_of(p) not in order]
    assert strays == []
    assert [p.name for p in (CPP / "src").iterdir() if p.is_file()] == []


def test_includes_point_down():
    rank = {name: k for k, name in enumerate(layers())}
    rank["elements"] = rank["model"]
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
    # the kinds' containers come with the model; the basic headers with any
    indirect = {"lagmb/model/constraint_group.hpp", "lagmb/model/force_group.hpp", "lagmb/model/event_group.hpp",
                "lagmb/model/friction_group.hpp", "lagmb/space.hpp", "lagmb/spatial.hpp", "lagmb/sparsity.hpp",
                "lagmb/time_function.hpp", "lagmb/interrupt.hpp", "lagmb/dual.hpp"}
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
    ["_core", "_version", "errors", "progress", "registry", "_checks", "functions", "handles", "_meshes", "_rotations"],
    ["model"],
    ["result", "simulation", "simulator", "statics", "linear", "accuracy", "joints"],
    ["_drawing"],
    ["scene", "plotting", "demo", "urdf", "mjcf", "studies", "viewer"],
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


def test_no_module_reads_private_names_of_plotting():
    """What the viewer and the command line share with the pictures sits in
    its own module (lagmb._drawing, lagmb._meshes), not among plotting's
    private names."""
    import ast

    package = ROOT / "python" / "lagmb"
    found = []
    for path in sorted(package.rglob("*.py")):
        if "plotting" in path.relative_to(package).parts:
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.module and node.module.endswith("plotting"):
                found += [f"{path.relative_to(package)}: {a.name}" for a in node.names if a.name.startswith("_")]
    assert found == []
