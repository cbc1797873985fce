"""A scene as an FMI 3.0 co-simulation FMU for this platform (``lagmb fmu``).

The FMU holds the model as text (resources/model.lagmb: the elements, the
simulation options, the reactions and efforts to output), lagmb's FMU runtime
(liblagmb_fmu.so, built with the package: a ``lagmb::CoSimulation`` behind
plain C) with every shared library it loads beyond the C and C++ runtimes
(SuiteSparse, BLAS, LAPACK and theirs, copied from where they are installed
here: the FMU runs where they are not), and the FMI 3.0 functions
(``fmi3.c``), compiled here against the FMI headers that FMPy ships (the
``fmu`` extra) with the system's C compiler.
Variables (docs/modelling.md, "FMU"): the time; the scene's inputs; every
number given to an element as a fixed parameter, settable until
initialization ends; the body coordinates, their rates, and the reactions and
efforts the scene's ``[output]`` asks for as outputs, each with its unit.
"""

import os
import platform
import re
import shutil
import subprocess
import tempfile
import uuid
import zipfile
from xml.sax.saxutils import quoteattr

from . import _core
from ._version import __version__
from .errors import ModelError

RUNTIME = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fmu_runtime")
PLATFORM = "x86_64-linux"


def fmi_headers():
    """The folder of FMPy's FMI 3.0 headers; ModelError if FMPy is missing."""
    try:
        import fmpy
    except ImportError:
        raise ModelError("building an FMU needs the FMI 3.0 headers that FMPy ships: "
                         "pip install 'lagmb[fmu]' (or fmpy)") from None
    path = os.path.join(os.path.dirname(fmpy.__file__), "c-code")
    if not os.path.exists(os.path.join(path, "fmi3Functions.h")):
        raise ModelError(f"FMPy at {os.path.dirname(fmpy.__file__)} has no FMI 3.0 headers (c-code/fmi3Functions.h)")
    return path


def _compiler():
    for name in (os.environ.get("CC"), "cc", "gcc", "clang"):
        if name and shutil.which(name):
            return name
    raise ModelError("building an FMU needs a C compiler (cc, gcc or clang; or set CC)")


# what every Linux machine has: the C and C++ runtimes and the loader (an
# FMU carries every other library its binaries need)
_SYSTEM_RUNTIME = re.compile(r"^(linux-vdso|linux-gate|ld-linux(-x86-64)?|libc|libm|libdl|libpthread|librt|"
                             r"libstdc\+\+|libgcc_s)\.so")


def runtime_libraries(runtime):
    """The shared libraries ``runtime`` loads beyond the system runtime
    (SuiteSparse, BLAS, LAPACK and what they load in turn), as (file name,
    path) pairs, from ``ldd``; ModelError naming any that is not found."""
    try:
        listed = subprocess.run(["ldd", runtime], capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        raise ModelError(f"an FMU carries the libraries its runtime needs, found with ldd: {e}") from None
    libraries, missing = [], []
    for line in listed.splitlines():
        parts = line.split()
        if len(parts) < 3 or parts[1] != "=>" or _SYSTEM_RUNTIME.match(parts[0]):
            continue
        if parts[2] == "not":
            missing.append(parts[0])
        else:
            libraries.append((parts[0], os.path.realpath(parts[2])))
    if missing:
        raise ModelError(f"lagmb's FMU runtime {runtime} needs {', '.join(missing)}, not found on this machine")
    return libraries


def _identifier(name):
    """A C identifier and file name from the model's name."""
    ident = re.sub(r"\W", "_", name)
    return ident if ident and not ident[0].isdigit() else "lagmb_" + ident


def setup_text(scene):
    """The text the FMU carries: the scene's model, its run options and
    outputs (CoSimulationSetup). ModelError for what an FMU cannot hold."""
    from ._run_options import DEFAULTS, run_options

    settings = dict(scene.settings)
    analysis = settings.pop("analysis", "auto")
    if analysis not in ("auto", "dynamic"):
        raise ModelError(f"an FMU integrates the equations of motion: analysis {analysis!r} is not for an FMU")
    for key in ("t_end", "t_out", "n_out"):  # the importer sets the time span and the steps
        settings.pop(key, None)
    options = run_options(**{key: settings.get(key, default) for key, default in (
        ("t0", DEFAULTS["t0"]), ("rtol", DEFAULTS["rtol"]), ("atol", DEFAULTS["atol"]),
        ("formulation", DEFAULTS["formulation"]), ("integrator", None), ("max_step", None), ("step", None),
        ("max_order", None), ("baumgarte", None), ("max_steps", DEFAULTS["max_steps"]),
        ("start", DEFAULTS["start"]), ("newton_rtol", DEFAULTS["newton_rtol"]),
        ("newton_atol", DEFAULTS["newton_atol"]), ("method", None))})
    output = getattr(scene, "output", None) or {}
    reactions = [str(r) for r in output.get("reactions", [])]
    efforts = [str(e) for e in output.get("efforts", [])]
    return _core.cosimulation_setup(scene.model._spec, options, reactions, efforts)


def model_description(name, identifier, token, variables, description=""):
    """modelDescription.xml of the variables (value reference = index)."""
    units = sorted({v["unit"] for v in variables if v["unit"]})
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             f'<fmiModelDescription fmiVersion="3.0" modelName={quoteattr(name)} '
             f'instantiationToken={quoteattr(token)} generationTool="lagmb {__version__}" '
             f'description={quoteattr(description)} variableNamingConvention="flat">',
             f'  <CoSimulation modelIdentifier={quoteattr(identifier)} '
             'canHandleVariableCommunicationStepSize="true" canGetAndSetFMUState="true" '
             'canSerializeFMUState="false" hasEventMode="false"/>']
    if units:
        lines.append("  <UnitDefinitions>")
        lines += [f"    <Unit name={quoteattr(u)}/>" for u in units]
        lines.append("  </UnitDefinitions>")
    lines.append('  <LogCategories><Category name="logStatusError" description="errors"/>'
                 '<Category name="logAll" description="everything"/></LogCategories>')
    lines.append("  <ModelVariables>")
    for vr, v in enumerate(variables):
        attrs = [f"name={quoteattr(v['name'])}", f'valueReference="{vr}"',
                 f'causality="{v["causality"]}"', f'variability="{v["variability"]}"']
        if v["causality"] in ("input", "parameter"):
            attrs.append(f'start="{v["start"]!r}"')
        if v["unit"]:
            attrs.append(f"unit={quoteattr(v['unit'])}")
        if v["description"]:
            attrs.append(f"description={quoteattr(v['description'])}")
        lines.append(f"    <Float64 {' '.join(attrs)}/>")
    lines.append("  </ModelVariables>")
    lines.append("  <ModelStructure>")
    outputs = [vr for vr, v in enumerate(variables) if v["causality"] == "output"]
    lines += [f'    <Output valueReference="{vr}"/>' for vr in outputs]
    lines += [f'    <InitialUnknown valueReference="{vr}"/>' for vr in outputs]
    lines.append("  </ModelStructure>")
    lines.append("</fmiModelDescription>")
    return "\n".join(lines) + "\n"


def build_fmu(scene, path, name=None):
    """Write the FMU of ``scene`` (a Scene or a scene file) to ``path``;
    returns the path. ModelError for a scene an FMU cannot hold (a Python
    callable, a kinematic analysis), a missing FMPy or C compiler, or a
    failed compilation (with the compiler's message)."""
    if platform.system() != "Linux" or platform.machine() not in ("x86_64", "AMD64"):
        raise ModelError(f"lagmb builds FMUs for x86_64 Linux; this is {platform.system()} {platform.machine()}")
    if isinstance(scene, (str, os.PathLike)):
        from .scene import load_scene

        source = os.fspath(scene)
        scene = load_scene(source)
        name = name or os.path.splitext(os.path.basename(source))[0]
    name = name or "lagmb_model"
    setup = setup_text(scene)
    variables = _core.CoSimulation(setup).variables  # the model compiles: its variables
    identifier = _identifier(name)
    token = "{" + str(uuid.uuid4()) + "}"
    headers, cc = fmi_headers(), _compiler()
    runtime = os.path.join(RUNTIME, "liblagmb_fmu.so")
    if not os.path.exists(runtime):
        raise ModelError(f"lagmb's FMU runtime is missing ({runtime}): reinstall lagmb")
    with tempfile.TemporaryDirectory(prefix="lagmb-fmu-") as tmp:
        library = os.path.join(tmp, identifier + ".so")
        command = [cc, "-std=c99", "-O2", "-fPIC", "-shared", "-fvisibility=hidden", "-Wall", "-Wextra",
                   f"-I{headers}", f"-I{RUNTIME}", f'-DLAGMB_FMU_TOKEN="{token}"',
                   os.path.join(RUNTIME, "fmi3.c"), "-o", library, f"-L{RUNTIME}", "-llagmb_fmu",
                   "-Wl,--disable-new-dtags,-rpath,$ORIGIN", "-Wl,--no-undefined"]
        compiled = subprocess.run(command, capture_output=True, text=True)
        if compiled.returncode != 0:
            raise ModelError(f"compiling the FMU's FMI functions failed:\n{compiled.stderr.strip()}")
        description = f"lagmb model '{name}' ({len(variables)} variables)"
        with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as fmu:
            fmu.writestr("modelDescription.xml", model_description(name, identifier, token, variables, description))
            fmu.write(library, f"binaries/{PLATFORM}/{identifier}.so")
            fmu.write(runtime, f"binaries/{PLATFORM}/liblagmb_fmu.so")
            for file_name, library_path in runtime_libraries(runtime):
                fmu.write(library_path, f"binaries/{PLATFORM}/{file_name}")
            fmu.writestr("resources/model.lagmb", setup)
    return path
