"""The element kinds of lagmb, as the C++ core declares them.

Each kind (a body, a joint, a driver, a force, ...) is declared once, in C++
next to its equations (cpp/src/elements/*.cpp, lagmb/model/registry.hpp): its
name, the Model method that adds it, its scene table and type, its role,
and each parameter's type, default, unit and one-line documentation. This
module reads that declaration and derives from it what Python needs: the
signature and docstring of each Model.add_* / drive_* method, the scene
schema (lagmb.scene.schema), the roles handles and drawings count, and the
element reference of docs/modelling.md (``lagmb info --kinds``). What an
element of a compiled model is (a driver, a joint with an angle or a slide)
is read from its Kind (:func:`kind_of`), never from its kind's name.
"""

import inspect
import textwrap
from typing import NamedTuple, Optional, Tuple

from . import _core


class Param(NamedTuple):
    """One parameter of an element kind (see registry.hpp, struct Param)."""

    name: str
    type: str  # text, real, vec2, bool, body, joint, choice, motion, function, function_pair,
    # vec3, orientation, inertia, function_triple
    required: bool
    default: object  # None, a float, a tuple or a bool
    unit: str
    doc: str
    choices: Tuple[str, ...]
    on: Tuple[str, ...]  # a point: the body parameters it attaches to
    local: bool  # a point in its body's axes (else global, initial configuration)
    keyword_only: bool
    scene_key: str


class Kind(NamedTuple):
    """One element kind: its name, Model method, scene table and type, role,
    documentation and parameters (after the element's name)."""

    name: str
    method: str
    table: str
    type: Optional[str]
    role: str
    doc: str
    params: Tuple[Param, ...]
    dimension: int  # 2: planar models, 3: spatial ones
    coordinate: str = ""  # a joint's scalar coordinate: "angle", "slide", "angle and slide"; "" none
    effort: str = ""  # what Result.effort reads of one (a line with its unit); "" none
    effort_components: Tuple[str, ...] = ()  # its columns where it has several ("x", "y", ...)

    @property
    def what(self):
        """How messages call one: "revolute", "joint driver", ..."""
        return self.name.replace("_", " ")

    @property
    def coordinates(self):
        """The joint coordinates it has, of "angle" and "slide": ("angle",)
        for a revolute, ("angle", "slide") for a cylindrical joint, () for
        a kind without one."""
        return tuple(self.coordinate.split(" and ")) if self.coordinate else ()


def _read():
    kinds = []
    for k in _core.kinds():
        params = tuple(Param(**p) for p in k.pop("params"))
        kinds.append(Kind(params=params, **k))
    return tuple(kinds)


#: Every element kind of planar models, in the order scenes, messages and docs list them.
ALL_KINDS = _read()
KINDS = tuple(k for k in ALL_KINDS if k.dimension == 2)
#: The kinds of spatial models (Model(dimension=3)).
SPATIAL_KINDS = tuple(k for k in ALL_KINDS if k.dimension == 3)
BY_METHOD = {k.method: k for k in KINDS}
SPATIAL_BY_METHOD = {k.method: k for k in SPATIAL_KINDS}
BY_NAME = {k.name: k for k in ALL_KINDS}

#: What an element may stand for, and how a summary counts each role.
ROLES = ("body", "joint", "driver", "force", "friction", "stop", "contact")
ROLE_WORDS = {"body": ("body", "bodies"), "joint": ("joint", "joints"), "driver": ("driver", "drivers"),
              "force": ("force element", "force elements"),
              "friction": ("joint friction", "joint frictions"), "stop": ("stop", "stops"),
              "contact": ("contact", "contacts")}


def kind_of(core, name):
    """The Kind body or element `name` of a compiled model (core) was added
    as, or None for one the model made itself; ModelError (from the core)
    if it has no such name. What an element is, its role and coordinates,
    is read here, never from the name of its kind."""
    kind = core.given_kind(name)
    return None if kind is None else BY_NAME[kind]


def is_driver(core, name):
    """Whether element `name` of a compiled model is a driver (its kind's role)."""
    kind = kind_of(core, name)
    return kind is not None and kind.role == "driver"



def signature(kind):
    """The Python signature of the kind's Model method (self, name, params)."""
    P = inspect.Parameter
    out = [P("self", P.POSITIONAL_OR_KEYWORD), P("name", P.POSITIONAL_OR_KEYWORD)]
    for p in kind.params:
        how = P.KEYWORD_ONLY if p.keyword_only else P.POSITIONAL_OR_KEYWORD
        out.append(P(p.name, how) if p.required else P(p.name, how, default=p.default))
    return inspect.Signature(out)


# what a parameter of each type takes, in the words of the core's table of types
_TYPE_WORDS = {t["name"]: t["takes"] for t in _core.param_types()}


def describe(param):
    """One line: what the parameter takes, its unit and default."""
    kind = _TYPE_WORDS[param.type]
    if param.type == "choice":
        kind += " " + ", ".join(repr(c) for c in param.choices)
    unit = f", {param.unit}" if param.unit else ""
    default = "" if param.required else f"; default {param.default!r}"
    return f"{param.doc} ({kind}{unit}{default})"


def docstring(kind):
    """The docstring of the kind's Model method, from the declaration."""
    lines = [textwrap.fill(kind.doc, 76), "", "Parameters:", "  name: the element's unique name"]
    lines += [f"  {p.name}: {describe(p)}" for p in kind.params]
    lines += ["", "Returns the element's handle."]
    return "\n".join(lines)


def markdown():
    """The parameter tables of docs/modelling.md ("Element reference"):
    the planar kinds, then the spatial ones."""
    out = []
    for k in ALL_KINDS:
        where = f"[[{k.table}]]" + (f" type = \"{k.type}\"" if k.type else "")
        space = "" if k.dimension == 2 else "spatial "
        out += [f"### {space}`{k.method}` ({k.name}: {k.role}; {space}scene `{where}`)", "", k.doc, ""]
        if k.effort:
            columns = f" (columns {', '.join(k.effort_components)})" if k.effort_components else ""
            out += [f"`r.effort(name)`{columns}: {k.effort}.", ""]
        out += ["| parameter | takes | unit | default | meaning |", "|---|---|---|---|---|"]
        for p in k.params:
            takes = _TYPE_WORDS[p.type] + (" " + ", ".join(f"`{c}`" for c in p.choices) if p.choices else "")
            default = "required" if p.required else f"`{p.default!r}`"
            key = p.name if p.scene_key == p.name else f"{p.name} (scene: {p.scene_key})"
            cells = (key, takes, p.unit or "-", default, p.doc)
            out.append("| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |")
        out.append("")
    return "\n".join(out)


def effort_unit(elements, kinds, name):
    """The unit of a driver's, stop's or servo's effort (Result.effort):
    "N m" along an angle, "N" along a slide or a body's x, y (z), from the
    kind of what it drives (``elements``: Model.elements; ``kinds``: the
    registry's Model method -> Kind of the model's dimension); "N or N m"
    where it cannot be told."""
    method_of = {kw["name"]: method for method, kw in elements}
    kw = next((k for c, k in elements if k.get("name") == name), {})
    if method_of.get(name) == "drive_body":
        return "N m" if kw.get("coordinate") == "angle" else "N"
    if "joint" in kw:  # a joint's driver or stop: along its coordinate
        joint = kinds.get(method_of.get(str(kw["joint"])))
        return "N" if joint is not None and "slide" in joint.coordinates else "N m"  # (a cylindrical's driver slides)
    return "N or N m"
