"""See the motion in a browser: ``lagmb.view(result, "run.html")`` writes one
self-contained HTML page with the mechanism in 3D (WebGL, three.js), play,
pause, a time slider, playback speed, camera orbit/zoom/pan, and time plots
of chosen outputs with a cursor at the current time.

The page needs no network: three.js (MIT licence) is inlined, read from the
``trimesh`` wheel (the ``view`` extra), which ships three.js r140 with its
TrackballControls in ``trimesh/resources/templates/viewer.zip``. The bodies'
geometry is sent once, in each body's own axes; each frame is then a pose
per body (position and quaternion, 7 float32 numbers, base64), so a page
grows with bodies x frames, not with the geometry. A test hook,
``window.lagmbViewer`` (``state()``, ``play()``, ``pause()``, ``seek(t)``,
``setFrame(k)``, ``reset()``), lets a browser test or a notebook read and
drive it.
"""

import base64
import html
import importlib.resources
import io
import json
import math
import os
import re
import zipfile
from functools import lru_cache

import numpy as np

from . import _checks, _output_names, _rotations, registry
from ._checks import show
from ._drawing import (Scene, mode_amplitude, outline_shape, posed, shape_faces, stats_line,
                       trace_points)
from .errors import MissingExtraError, ModelError

_PALETTE = [(0.12, 0.47, 0.71), (1.0, 0.50, 0.05), (0.17, 0.63, 0.17), (0.84, 0.15, 0.16), (0.58, 0.40, 0.74),
            (0.55, 0.34, 0.29), (0.89, 0.47, 0.76), (0.50, 0.50, 0.50), (0.74, 0.74, 0.13), (0.09, 0.75, 0.81)]
_JOINT = (0.2, 0.2, 0.2)
_GROUND = (0.55, 0.55, 0.58)
_FLOOR = (0.80, 0.80, 0.78)  # a plane shape: a floor


@lru_cache(maxsize=1)
def three_js():
    """three.js r140 and its TrackballControls, as the trimesh wheel ships
    them (the script of its viewer template, before the template's own code)."""
    try:
        files = importlib.resources.files("trimesh")
    except ModuleNotFoundError:
        raise MissingExtraError("lagmb.view needs three.js, which it takes from the trimesh wheel, from lagmb's "
                                "optional 'view' extra: pip install \"lagmb[view]\"", "trimesh", "view") from None
    with zipfile.ZipFile(io.BytesIO((files / "resources" / "templates" / "viewer.zip").read_bytes())) as z:
        text = z.read("viewer.html.template").decode("utf-8")
    start = text.index("<script>") + len("<script>")
    end = text.index("var camera,controls,scene,renderer,tracklight;")
    lib = text[start:end]
    if "TrackballControls" not in lib or "WebGLRenderer" not in lib:
        raise ModelError("lagmb.view: the trimesh wheel's viewer template no longer holds three.js and its "
                         "TrackballControls where lagmb reads them (trimesh 5.x does)")
    return lib.replace("</script", "<\\/script")


_FLOAT32_MAX = float(np.finfo(np.float32).max)  # the page's numbers are float32

# JSON inside <script>: the HTML tokenizer reads the script's text before
# JSON.parse does, and "<!--<script>" or "</script>" in a name would end it
# or make it swallow the closing tag; "<", ">" and "&" are written as JSON
# escapes, and so are U+2028/2029 (line ends to older JavaScript).
_SCRIPT_SAFE = {ord("<"): "\\u003c", ord(">"): "\\u003e", ord("&"): "\\u0026", 0x2028: "\\u2028",
                0x2029: "\\u2029"}
_PLACEHOLDER = re.compile(r"%%([A-Z]+)%%")


def _energy_plot(result, energy, frames):
    """The energy's plot as its change from the start, E - E(t0): drawn
    whole, a conserved energy's round-off and integration error would fill
    the plot's height as steps around a constant. Its scale (what the
    page's least span of a plot, 1e-9 of it, is measured against): the
    energy the run exchanges, its largest kinetic energy (or |E| if
    larger). The note says E(t0) and the drift (largest |E - E(t0)|, and as
    a fraction of that scale)."""
    e0 = float(energy[0])
    change = np.asarray(energy, dtype=float) - e0
    drift = float(np.max(np.abs(change)))
    core = result._core
    kinetic = max((core.kinetic_energy(result.q[k], result.v[k]) for k in frames), default=0.0)
    scale = max(float(np.max(np.abs(energy))), float(kinetic))
    share = f", {drift / scale:.1g} of the largest kinetic energy" if scale > 0.0 else ""
    return {"label": "energy change E - E(t0)", "values": _b64(change[frames]), "scale": scale,
            "note": f"E(t0) = {e0:.6g} J; drift max |E - E(t0)| = {drift:.2g} J{share}"}


def _script_json(data):
    """data as JSON text that is safe inside a <script> element."""
    try:
        text = json.dumps(data, allow_nan=False)
    except ValueError:  # the checks of view() name what is not finite; this is their backstop
        raise ModelError("lagmb.view: the page's data holds a number that is not finite") from None
    return text.translate(_SCRIPT_SAFE)


def _fill(template, values):
    """The template with each %%NAME%% replaced by values[NAME], in one pass:
    the values (user text among them) are never searched for placeholders."""
    return _PLACEHOLDER.sub(lambda m: values[m.group(1)], template)


def _drawable(values, what, t):
    """values, one row per frame at the times t, as the page draws them
    (float32): a ModelError names what and the first time where one is not
    finite or past float32's range."""
    v = np.asarray(values, dtype=float).reshape(len(t), -1)
    bad = ~(np.abs(v) <= _FLOAT32_MAX)
    if bad.any():
        k = int(np.flatnonzero(bad.any(axis=1))[0])
        shown = ", ".join(f"{x:g}" for x in v[k])
        why = ("is not finite" if not np.all(np.isfinite(v[k]))
               else f"is too large to draw (the page's float32 numbers end at {_FLOAT32_MAX:.3g})")
        raise ModelError(f"lagmb.view: {what} at t = {t[k]:g} {why}: " + (f"({shown})" if v.shape[1] > 1 else shown))


def _b64(array, dtype="<f4"):
    return base64.b64encode(np.ascontiguousarray(array, dtype=dtype).tobytes()).decode("ascii")


def _quaternion_z(angle):
    """(x, y, z, w) of a turn by angle about z."""
    return [0.0, 0.0, math.sin(0.5 * angle), math.cos(0.5 * angle)]


def _quaternion_of(R):
    """(x, y, z, w), three.js's order, of a rotation matrix."""
    w, x, y, z = _rotations.quaternion(R)
    return [float(x), float(y), float(z), float(w)]


def _bar(a, b, width, colour, z=0.0):
    """A box from a to b (planar points, body axes), width wide."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    d = b - a
    length = float(np.hypot(*d))
    return {"type": "box", "size": [length + width, width, 0.5 * width], "position": [*(0.5 * (a + b)), z],
            "quaternion": _quaternion_z(math.atan2(d[1], d[0])), "colour": colour}


def _rod3(a, b, radius, colour):
    """A cylinder from a to b (points in 3D, body axes)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    d = b - a
    length = float(np.linalg.norm(d))
    if length <= 0.0:
        return None
    z = d / length
    helper = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    x = np.cross(helper, z)
    x /= np.linalg.norm(x)
    R = np.column_stack([x, np.cross(z, x), z])
    return {"type": "cylinder", "radius": radius, "length": length, "position": list(0.5 * (a + b)),
            "quaternion": _quaternion_of(R), "colour": colour}


def _mesh(faces, shape, colour):
    """A shape's faces (polygons in its own axes) as a triangle mesh in its
    body's axes."""
    R = np.asarray(shape.rotation, dtype=float)
    p = np.asarray(shape.position, dtype=float)
    vertices, triangles = [], []
    for face in faces:
        face = np.asarray(face, dtype=float) @ R.T + p
        first = len(vertices)
        vertices.extend(face)
        triangles.extend((first, first + k, first + k + 1) for k in range(1, len(face) - 1))
    if not np.all(np.abs(np.asarray(vertices)) <= _FLOAT32_MAX):
        raise ModelError(f"lagmb.view: the {shape.kind} shape of body {shape.body!r}"
                         + (f" ({shape.mesh!r})" if shape.kind == "mesh" else "")
                         + f" reaches past what the page draws (float32, up to {_FLOAT32_MAX:.3g}): size "
                         f"{show(tuple(shape.size))}")
    return {"type": "mesh", "vertices": _b64(np.array(vertices)), "faces": _b64(np.array(triangles), "<u4"),
            "colour": colour}


def _planar_parts(scene, body, colour, width):
    parts = []
    if body in scene.particles:
        return [{"type": "sphere", "radius": 1.5 * width, "colour": colour}]
    points, closed = outline_shape(scene.drawn_outline(body))
    if len(points) == 0:
        parts.append({"type": "sphere", "radius": 1.5 * width, "colour": colour})
    for k in range(len(points) - (0 if closed else 1)):
        parts.append(_bar(points[k], points[(k + 1) % len(points)], width, colour))
    return parts


def _shapes_reach(body, meshes):
    """How far from a body's centre the shapes the page draws for it reach
    (the visual ones, else the collision ones lagmb reads: as
    _spatial_parts picks), or None where it has none to draw. ``meshes``:
    [(shape, its faces or None)], each file read once for the page."""
    mine = [(s, f) for s, f in meshes if s.body == body]
    for role in ("visual", "collision"):
        reach = None
        for shape, faces in ((s, f) for s, f in mine if s.role == role):
            if faces:
                points = np.concatenate([np.asarray(f, dtype=float) for f in faces])
                placed = np.asarray(shape.position, dtype=float) + points @ np.asarray(shape.rotation, dtype=float).T
                reach = max(reach or 0.0, float(np.max(np.linalg.norm(placed, axis=1))))
        if reach is not None:
            return reach
    return None


def _spatial_parts(scene, body, colour, width, meshes):
    parts = []
    mine = [(s, f) for s, f in meshes if s.body == body]
    for role in ("visual", "collision"):  # the visual shapes, or else the collision ones lagmb reads (STL)
        for shape, faces in ((s, f) for s, f in mine if s.role == role):
            if faces:
                parts.append(_mesh(faces, shape, colour))
        if parts:
            break
    if not parts:
        S = scene.second_moment(body)
        if S is not None:
            s, V = np.linalg.eigh(0.5 * (S + S.T))
            half = np.sqrt(3.0 * np.clip(s, 0.0, None) / scene.mass[body])
            if np.linalg.det(V) < 0:
                V[:, 0] = -V[:, 0]
            if half.max() > 0.0:
                parts.append({"type": "box", "size": list(2.0 * np.maximum(half, 0.05 * half.max())),
                              "quaternion": _quaternion_of(V), "colour": colour})
                parts.append({"type": "axes", "length": float(1.5 * half.max())})
        for point in scene.outlines.get(body, []):  # links to where its joints attach
            rod = _rod3(np.zeros(3), point, 0.4 * width, colour)
            if rod:
                parts.append(rod)
    if not parts:
        parts.append({"type": "sphere", "radius": 1.5 * width, "colour": colour})
    return parts


def _texts(value, name):
    """A list of strings given as one string or an iterable of them."""
    if isinstance(value, str):
        return [value]
    try:
        items = list(value)
    except TypeError:
        raise ModelError(f"{name} must be a list of strings, got {show(value)}") from None
    return [_checks.text(item, f"{name}[{k}]") for k, item in enumerate(items)]


def _output_series(result, name):
    """(values (k,), unit) of one output by name."""
    model = result.model
    coords = model.coordinate_names
    out = _output_names.parse(name)
    if name in ("energy", "residual", "velocity_residual"):
        return np.asarray(getattr(result, name), dtype=float), {"energy": "J", "residual": "", "velocity_residual": ""}[name]
    if out.base in coords:
        j = coords.index(out.base)
        unit = model.compiled().coordinate_units()[j]
        return np.asarray((result.v if out.rate else result.q)[:, j], dtype=float), unit + ("/s" if out.rate and unit else "")
    element, what, core = out.element, out.what, result._core
    if element and core.has(element):
        c = out.reaction_component
        if not out.rate and c is not None:
            components = _output_names.REACTION_COMPONENTS[model.dimension]
            if c in components:
                k = components.index(c)
                return np.asarray(result.reaction(element)[:, k], dtype=float), "N m" if c.startswith("torque") else "N"
        if not out.rate and what == "effort" and registry.is_driver(core, element):
            kinds = registry.BY_METHOD if model.dimension == 2 else registry.SPATIAL_BY_METHOD
            return np.asarray(result.effort(element), dtype=float), registry.effort_unit(model.elements, kinds, element)
        if what in _output_names.JOINT_COORDINATES and core.joint_coordinate(element) is not None:
            path = result.joint(element)
            values = path.rate if out.rate else getattr(path, what, None)
            if values is not None:
                return np.asarray(values, dtype=float), ("rad" if what == "angle" else "m") + ("/s" if out.rate else "")
    raise ModelError(f"lagmb.view: no output {name!r}; outputs are energy, residual, velocity_residual, the "
                     f"coordinates ({', '.join(coords[:60])}{f', ... ({len(coords)} in all)' if len(coords) > 60 else ''}) "
                     "and their "
                     "der(...), '<joint>.reaction.x' (.y, .torque; in space .z, .torque.x ...), "
                     "'<driver>.effort', '<joint>.angle' or '<joint>.slide'")


def _path(path, name):
    """A file name given as str or os.PathLike, as a str."""
    try:
        path = os.fspath(path)
    except TypeError:
        raise ModelError(f"{name} must be a file name (str or os.PathLike), got {show(path)}") from None
    if not isinstance(path, str):
        raise ModelError(f"{name} must be a file name as text, got {show(path)}")
    return path


class View:
    """A page written by :func:`view`: ``path`` (None when kept in memory),
    ``size`` (bytes) and, in a notebook, the page itself inline
    (``_repr_html_``: an iframe holding it)."""

    def __init__(self, page, path):
        self.path, self.size = path, len(page.encode("utf-8"))
        self._page = page

    def _repr_html_(self):
        return ('<iframe style="width: 100%; height: 560px; border: 1px solid #ddd" '
                f'srcdoc="{html.escape(self._page, quote=True)}"></iframe>')

    def __repr__(self):
        where = self.path if self.path else "in memory"
        return f"<lagmb.View: {where}, {self.size / 1e6:.2f} MB>"


def view_mode(modes, index=0, path="mode.html", *, amplitude=None, frames=100):
    """A vibration mode as a looping page (:func:`view`): the equilibrium
    pose plus amplitude sin(omega t) times the mode's shape over one period
    (a rigid-body or unstable mode: back and forth over one cycle of phase),
    the amplitude as :func:`lagmb.plotting.animate_mode` chooses it unless
    given (a finite number); ``frames``: frames per period, 1 .. 100000.
    ModelError for a bad index (naming how many modes there are) or a bad
    amplitude or frame count (naming it)."""
    from .linear import Modes

    if not isinstance(modes, Modes):
        raise ModelError(f"lagmb.view_mode: modes must be what mb.modes(model) returns, got {type(modes).__name__}")
    count = len(modes)
    if isinstance(index, bool) or not isinstance(index, (int, np.integer)) or not 0 <= index < count:
        raise ModelError(f"lagmb.view_mode: index {index!r}: there are {count} modes"
                         + (f" (0 .. {count - 1})" if count else " (nothing can move)"))
    index = int(index)
    frames = _checks.integer(frames, "lagmb.view_mode: frames", 1, 100_000)
    if amplitude is not None:
        amplitude = _checks.real(amplitude, "lagmb.view_mode: amplitude")
    equilibrium = modes.equilibrium
    shape = np.asarray(modes.shapes[index], dtype=float)
    if amplitude is None:
        amplitude = mode_amplitude(equilibrium, shape)
    kind, omega = modes.kinds[index], float(modes.omega[index])
    phase = 2.0 * math.pi * np.arange(frames + 1) / frames
    times = phase / omega if kind == "vibration" and omega > 0 else phase / (2.0 * math.pi)
    shown = posed(equilibrium, equilibrium.q + amplitude * np.sin(phase)[:, None] * shape[None, :], times)
    frequency = 0.0 if kind == "rigid-body" else float(modes.frequencies[index])
    return view(shown, path, outputs=[], title=f"mode {index}: {frequency:.4g} Hz ({kind})", loop=True,
                lines=[f"mode {index} of {count}: {kind}, {frequency:.6g} Hz, omega {omega:.6g} rad/s"
                       + ("" if kind == "vibration" else " (shown back and forth over one cycle of phase)"),
                       f"amplitude {amplitude:.3g} times the shape (largest coordinate +1)"])


def view_sweep(ds, model, folder="sweep_view", *, cases=None, outputs=None):
    """A sweep's cases, selectable: ``folder/index.html`` holds a list of
    the cases (their parameters and status) and shows the chosen one's page
    (:func:`view`, one ``case_NNNN.html`` beside it, each of the model built
    with that case's parameters, so a length a case changes is drawn so).
    Needs the sweep's time histories (``mb.sweep(..., histories=[...])``:
    the coordinates ``q`` on a time grid). ``cases``: which (default all,
    at most 200); ``outputs``: the plots of each page, as :func:`view`
    takes them (coordinates and energy: a history holds positions only).
    ModelError for a Dataset without histories or a model that is not the
    sweep's (other coordinates)."""
    from .result import Result

    if "q" not in getattr(ds, "data_vars", {}):
        raise ModelError("lagmb.view_sweep: the sweep has no time histories: run mb.sweep(..., histories=[times])")
    names = model.coordinate_names
    if list(ds["coordinate"].values) != names:
        raise ModelError("lagmb.view_sweep: the sweep's coordinates are not this model's: give the model it ran")
    all_cases = [int(c) for c in ds["case"].values]
    if cases is None:
        chosen = all_cases
    elif isinstance(cases, (str, bytes)) or not hasattr(cases, "__iter__"):
        raise ModelError(f"lagmb.view_sweep: cases must be a list of case numbers, got {show(cases)}")
    else:
        chosen = [_checks.integer(c, f"lagmb.view_sweep: cases[{k}]", 0, _checks.INT_MAX) for k, c in enumerate(cases)]
    unknown = [c for c in chosen if c not in all_cases]
    if unknown:
        raise ModelError(f"lagmb.view_sweep: no case {unknown[0]} in the sweep (cases {all_cases[0]} .. {all_cases[-1]})")
    if len(chosen) > 200:
        raise ModelError(f"lagmb.view_sweep: {len(chosen)} cases: choose at most 200 (cases=[...]); each is a page")
    folder = _path(folder, "lagmb.view_sweep: folder")
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as e:
        raise ModelError(f"lagmb.view_sweep: cannot make {folder!r}: {e.strerror or e}") from None
    parameters = [c for c in ds.coords if c not in ("case", "time", "coordinate")]
    known = set(model.parameters)
    t = np.asarray(ds["time"].values, dtype=float)
    entries = []
    for case in chosen:
        row = ds.sel(case=case)
        values = {p: row[p].item() for p in parameters}
        label = ", ".join(f"{p} = {v:g}" if isinstance(v, float) else f"{p} = {v}" for p, v in values.items()
                          if not (isinstance(v, float) and math.isnan(v)))
        status = str(row["status"].item())
        page = f"case_{case:04d}.html"
        if status == "ok":
            params = {p: float(v) for p, v in values.items() if p in known and not math.isnan(float(v))}
            core = model.compiled().with_parameters(params) if params else model.compiled()
            q = np.asarray(row["q"].values, dtype=float)
            zero = np.zeros_like(q)
            raw = {"t": t, "q": q, "v": zero, "a": zero, "lam": np.zeros((len(t), core.n_constraints)),
                   "stats": {"steps": int(row["steps"].item())}}
            view(Result(model, core, raw), os.path.join(folder, page), outputs=[] if outputs is None else outputs,
                 title=f"case {case}: {label}", lines=[label, f"{len(t)} frames from the sweep's histories"])
        entries.append({"case": case, "label": label or f"case {case}", "status": status,
                        "page": page if status == "ok" else None})
    index = _fill(_SWEEP_INDEX, {"DATA": _script_json(entries)})
    with open(os.path.join(folder, "index.html"), "w", encoding="utf-8") as f:
        f.write(index)
    return os.path.join(folder, "index.html")


_SWEEP_INDEX = """<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>lagmb sweep</title>
<style>
  html, body { margin: 0; height: 100%; font: 13px system-ui, sans-serif; }
  #app { display: flex; height: 100%; }
  #cases { width: 280px; overflow-y: auto; border-right: 1px solid #ddd; }
  #cases div { padding: 4px 8px; cursor: pointer; border-bottom: 1px solid #f0f0f0; }
  #cases div.selected { background: #dbe8f6; }
  #cases div.failed { color: #a33; cursor: default; }
  iframe { flex: 1; border: 0; height: 100%; }
</style></head>
<body><div id="app"><div id="cases"></div><iframe id="case"></iframe></div>
<script type="application/json" id="lagmb-cases">%%DATA%%</script>
<script>
"use strict";
const entries = JSON.parse(document.getElementById("lagmb-cases").textContent);
const list = document.getElementById("cases"), frame = document.getElementById("case");
let selected = null;
function choose(k) {
  const e = entries[k];
  if (!e.page) return;
  selected = k;
  frame.src = e.page;
  for (const [i, div] of [...list.children].entries()) div.classList.toggle("selected", i === k);
}
entries.forEach((e, k) => {
  const div = document.createElement("div");
  div.textContent = "case " + e.case + ": " + e.label + (e.page ? "" : " (" + e.status.split(":")[0] + ")");
  if (!e.page) { div.className = "failed"; div.title = e.status; }
  div.addEventListener("click", () => choose(k));
  list.appendChild(div);
});
const first = entries.findIndex((e) => e.page);
if (first >= 0) choose(first);
window.lagmbSweep = { cases: () => entries.length, selected: () => selected, choose: choose,
                      page: () => frame.getAttribute("src") };
</script></body></html>
"""


def view(result, path="run.html", *, outputs=None, trace=None, title=None, max_frames=5000, loop=False,
         lines=None, forces=False):
    """Writes the run as one self-contained HTML page (see the module's
    docstring) and returns a :class:`View`; ``path=None`` keeps it in memory
    (a notebook shows it inline).

    ``outputs``: names of the time plots beside the 3D view: "energy" (drawn
    as its change from the start, E - E(t0), with E(t0) and the drift
    written under its name),
    "residual", "velocity_residual", coordinates ("rod.angle") and their
    "der(...)", "<joint>.reaction.x" (".y", ".torque"; in space ".z",
    ".torque.x" ...), "<driver>.effort", "<joint>.angle" / ".slide". Default:
    the energy and each driver's effort. Clicking a plot jumps to that time.
    ``trace``: points drawn as lines up to the current time, as
    :func:`lagmb.plotting.animate` takes them ((body, local point), a body,
    an element, "body:x,y", or a list). ``title``: the page's (default: the
    model's name, Model.name, else its bodies and elements counted).
    ``max_frames``: outputs beyond it are thinned evenly (the page holds 7
    float32 numbers per body per frame). ``loop``:
    playing starts again at the end (:func:`view_mode`); ``lines``: the
    text under the title (default: the bodies, the method and its counts).
    ``forces=True``: each contact's force on its first shape (normal and
    friction, r.contact) as an arrow at its point, the largest over the
    run a tenth of the scene long (the scale under the title).
    Names and titles are shown as text, whatever characters they hold.

    Planar models are drawn in their plane (x, y), bodies as bars between
    their joints, a contact as its circle (a disc on its body) and its line
    (a long bar); spatial ones with their shapes (a URDF's meshes, STL) or
    else the box of their inertia and axes. ModelError for a Result without
    its model, an unknown output (the names listed), a bad argument (named
    with its value), a path that cannot be written, an STL file that
    cannot be read (named, with what is wrong), or what the page cannot
    draw: a position, output or traced point that is not finite or past
    float32's range (named, with the time).
    """
    from .result import Result

    if not isinstance(result, Result):
        raise ModelError(f"lagmb.view: give a Result (from mb.simulate or a Simulator), got {type(result).__name__}")
    if getattr(result, "model", None) is None or getattr(result, "_core", None) is None:
        raise ModelError("lagmb.view: this Result has no model (it was made without the model it ran): run "
                         "mb.simulate(model, ...) and view its Result")
    if len(result.t) == 0:
        raise ModelError("lagmb.view: the Result has no outputs to show")
    path = None if path is None else _path(path, "lagmb.view: path")
    max_frames = _checks.integer(max_frames, "lagmb.view: max_frames", 1, _checks.INT_MAX)
    loop = _checks.flag(loop, "lagmb.view: loop")
    forces = _checks.flag(forces, "lagmb.view: forces")
    if title is not None:
        _checks.text(title, "lagmb.view: title")
    if outputs is not None:
        outputs = _texts(outputs, "lagmb.view: outputs")
    if lines is not None:
        lines = _texts(lines, "lagmb.view: lines")
    model = result.model
    scene = Scene(result)
    if title is None:  # the model's name (a robot's, a scene file's), else what it is made of
        title = model.name or f"lagmb: {scene.summary()}"
    dimension = scene.dimension
    k_all = len(result.t)
    frames = np.arange(k_all) if k_all <= max_frames else np.unique(np.linspace(0, k_all - 1, max_frames).round()
                                                                   .astype(int))
    t = np.asarray(result.t, dtype=float)[frames]
    bad = np.flatnonzero(~(np.abs(t) <= _FLOAT32_MAX))
    if len(bad):
        raise ModelError(f"lagmb.view: the time of output {frames[bad[0]]} is {t[bad[0]]!r}: the page draws "
                         f"finite times within float32's range ({_FLOAT32_MAX:.3g})")
    bodies = scene.bodies

    # the size of the scene, from every frame's body positions and attachment points
    points = [result.body(b).position[frames] for b in bodies]
    for body, p in zip(bodies, points):
        _drawable(p, f"the position of body {body!r}", t)
    for name in scene.joints + scene.drivers:
        for body, local in scene.attachments(name):
            if body == "ground":
                points.append(np.atleast_2d(local))
    points = [np.pad(np.asarray(p, dtype=float), ((0, 0), (0, 3 - np.shape(p)[1]))) for p in points]
    # each body's path widened by how far its own drawing reaches from its
    # centre (not every body's by the farthest reach of any: one inflated
    # inertia box made a robot small in a large frame)
    shapes = list(getattr(model, "shapes", []) or [])
    # the bodies' shapes with their faces, each mesh file read once (for the framing and the drawing)
    meshes = [(sh, shape_faces(sh)) for sh in shapes if sh.kind != "plane" and sh.body != "ground"] \
        if dimension == 3 else []
    for i, body in enumerate(bodies):
        reach = max([float(np.linalg.norm(p)) for p in scene.outlines.get(body, [])], default=0.0)
        drawn = _shapes_reach(body, meshes) if dimension == 3 else None
        S = scene.second_moment(body) if dimension == 3 and drawn is None else None
        if drawn is not None:  # drawn as its meshes: as far as they reach, not its inertia box
            reach = max(reach, drawn)
        elif S is not None:
            reach = max(reach, float(np.sqrt(3.0 * max(np.trace(S), 0.0) / scene.mass[body])))
        if reach > 0.0:
            points[i] = np.vstack([points[i] - reach, points[i] + reach])
    cloud = np.vstack(points)
    low, high = cloud.min(axis=0), cloud.max(axis=0)
    size = float(max(np.linalg.norm(high - low), 1e-3))
    width = 0.02 * size
    center = 0.5 * (low + high)

    # geometry, once, in each body's axes
    body_data = []
    for i, body in enumerate(bodies):
        colour = _PALETTE[i % len(_PALETTE)]
        parts = (_planar_parts(scene, body, colour, width) if dimension == 2
                 else _spatial_parts(scene, body, colour, width, meshes))
        for name in scene.joints + scene.drivers:  # the joints: dots where they hold the body
            for b, local in scene.attachments(name):
                if b == body:
                    position = [*local, 0.6 * width] if dimension == 2 else list(local)
                    parts.append({"type": "sphere", "radius": 0.9 * width, "position": position, "colour": _JOINT})
        body_data.append({"name": body, "parts": parts})
    ground_parts = []
    # a planar contact: its circle a disc on its body, its line a long bar on its own (or the ground)
    parts_of = {entry["name"]: entry["parts"] for entry in body_data}
    for method, kw in scene.elements if dimension == 2 else []:
        if method != "add_contact":
            continue
        centre = scene.planar_local(kw["circle_body"], kw["center"])
        colour = _PALETTE[bodies.index(kw["circle_body"]) % len(_PALETTE)] if kw["circle_body"] in bodies else _GROUND
        disc = {"type": "cylinder", "radius": float(kw["radius"]), "length": 0.3 * width,
                "position": [*centre, -0.3 * width], "colour": colour}
        parts_of.get(kw["circle_body"], ground_parts).append(disc)
        u = np.asarray(kw["direction"], dtype=float)
        u = u / max(float(np.hypot(*u)), 1e-300)
        a = scene.planar_local(kw["line_body"], np.asarray(kw["point"], float) - size * u)
        b = scene.planar_local(kw["line_body"], np.asarray(kw["point"], float) + size * u)
        parts_of.get(kw["line_body"], ground_parts).append(_bar(a, b, 0.5 * width, _GROUND, z=-0.5 * width))
    for name in scene.joints + scene.drivers:
        for b, local in scene.attachments(name):
            if b == "ground":
                position = [*local, 0.0] if dimension == 2 else list(local)
                ground_parts.append({"type": "box", "size": [2.5 * width] * 3, "position": position,
                                     "colour": _GROUND})
    # the ground's shapes (a plane: a floor, the square of the scene's size under it)
    ground_shapes = [sh for sh in shapes if sh.body == "ground"]
    seen = any(sh.role == "visual" for sh in ground_shapes)  # (the visual ones, else the collision ones; planes always)
    for shape in ground_shapes:
        if shape.role == ("collision" if seen else "visual") and shape.kind != "plane":
            continue
        R = np.asarray(shape.rotation, dtype=float)
        under = R.T @ (np.asarray(center, dtype=float) - np.asarray(shape.position, dtype=float))
        faces = shape_faces(shape, half=size, centre=under[:2])
        if faces:
            ground_parts.append(_mesh(faces, shape, _FLOOR if shape.kind == "plane" else _GROUND))

    # poses: (frames, bodies, 7) = position and quaternion (x, y, z, w)
    poses = np.zeros((len(frames), len(bodies), 7), dtype=float)
    for i, body in enumerate(bodies):
        motion = result.body(body)
        if dimension == 2:
            poses[:, i, 0:2] = motion.position[frames]
            angle = np.asarray(motion.angle, dtype=float)[frames]
            _drawable(angle, f"the angle of body {body!r}", t)
            poses[:, i, 5] = np.sin(0.5 * angle)
            poses[:, i, 6] = np.cos(0.5 * angle)
        else:
            poses[:, i, 0:3] = motion.position[frames]
            p = np.asarray(motion.orientation, dtype=float)[frames]
            _drawable(p, f"the orientation (Euler parameters) of body {body!r}", t)
            p = p / np.linalg.norm(p, axis=1, keepdims=True)
            poses[:, i, 3:6] = p[:, 1:4]
            poses[:, i, 6] = p[:, 0]

    # traces and plots
    traces = []
    for j, (body, local) in enumerate(trace_points(model, trace, "lagmb.view: trace")):
        p = np.asarray(result.point(body, local), dtype=float)[frames]
        _drawable(p, f"the traced point {show(tuple(float(x) for x in local))} of body {body!r}", t)
        if dimension == 2:
            p = np.column_stack([p, np.zeros(len(p))])
        traces.append({"points": _b64(p), "colour": list(_PALETTE[(j + 3) % len(_PALETTE)])})
    arrows = []
    contacts = [kw["name"] for method, kw in scene.elements if method == "add_contact"] if forces else []
    if contacts:  # each contact's force on its first shape, at its point
        readings = [result.contact(name) for name in contacts]
        vectors = [np.column_stack([c.normal_force]) * np.asarray(c.normal) + np.asarray(c.friction_force)
                   for c in readings]
        largest = max(float(np.max(np.linalg.norm(v, axis=1))) for v in vectors)
        scale = 0.1 * size / largest if largest > 0.0 else 0.0
        for j, (c, v) in enumerate(zip(readings, vectors)):
            pad = (lambda x: np.column_stack([x, np.zeros(len(x))])) if dimension == 2 else (lambda x: x)
            point, vector = pad(np.asarray(c.point, dtype=float)[frames]), pad(scale * v[frames])
            _drawable(point, f"the point of contact {contacts[j]!r}", t)
            arrows.append({"points": _b64(point), "vectors": _b64(vector), "colour": [0.85, 0.1, 0.1]})
        force_line = f"contact forces: {largest:.4g} N drawn {0.1 * size:.3g} m long"
    if outputs is None:
        outputs = ["energy"] + [f"{d}.effort" for d in scene.drivers][:3]
    plots = []
    for name in outputs:
        values, unit = _output_series(result, name)
        _drawable(values[frames], f"output {name!r}", t)
        plot = {"name": name, "unit": unit, "values": _b64(values[frames])}
        if name == "energy":  # what can be judged: the change from the start, and the drift in numbers
            plot.update(_energy_plot(result, values, frames))
        plots.append(plot)

    # the camera and the ground
    if dimension == 2:
        up, normal = [0.0, 1.0, 0.0], np.array([0.0, 0.0, 1.0])
        grid_center = [float(center[0]), float(center[1]), float(-width)]
        camera = list(center + np.array([0.0, 0.0, 1.8 * size]))
    else:
        g = np.asarray(model.gravity if model.gravity else (0.0, 0.0, -1.0), dtype=float)
        normal = -g / np.linalg.norm(g) if np.linalg.norm(g) > 0 else np.array([0.0, 0.0, 1.0])
        up = list(normal)
        lowest = float(np.min(cloud @ normal))
        grid_center = list(center - (float(center @ normal) - lowest) * normal)
        side = np.cross(normal, [1.0, 0.0, 0.0] if abs(normal[0]) < 0.9 else [0.0, 1.0, 0.0])
        side /= np.linalg.norm(side)
        front = np.cross(side, normal)
        camera = list(center + size * (0.95 * front + 0.55 * side + 0.6 * normal))
    grid_normal = normal
    stats = dict(result.stats)
    def count(n, word):
        return f"{n} {word}{'' if n == 1 else 's'}" if n else ""

    lines = lines if lines is not None else [", ".join(filter(None, [count(len(bodies), "body").replace("bodys", "bodies"),
                                     count(len(scene.joints), "joint"), count(len(scene.drivers), "driver")])),
             f"method {stats.get('method', stats.get('formulation', '?'))}: {stats_line(stats)}",
             f"t = {t[0]:g} .. {t[-1]:g} s, {len(frames)} frames",
             # (the camera frames every body over the whole run, not the start alone: say so)
             f"framed: the whole motion, {size:.2g} m across (drag to turn, scroll to zoom)"]
    if contacts:
        lines = list(lines) + [force_line]
    data = {
        "title": title, "lines": lines, "dimension": dimension, "size": size, "up": up,
        "grid": {"size": float(2.0 * size), "divisions": 20, "center": [float(x) for x in grid_center],
                 "normal": [float(x) for x in grid_normal]},
        "camera": {"target": [float(x) for x in center], "position": [float(x) for x in camera]},
        "bodies": body_data, "ground_parts": ground_parts, "traces": traces, "arrows": arrows, "plots": plots,
        "times": _b64(t),
        "loop": bool(loop),
    }
    template = (importlib.resources.files("lagmb") / "viewer.html").read_text(encoding="utf-8")
    page = _fill(template, {"TITLE": html.escape(title), "THREE": three_js(),
                            "DATA": _script_json(data), "POSES": _b64(poses)})
    if path is None:
        return View(page, None)
    try:
        with open(path, "w", encoding="utf-8") as f:
            f.write(page)
    except OSError as e:
        raise ModelError(f"lagmb.view: cannot write {path!r}: {e.strerror or e}") from None
    return View(page, path)
