"""Sphinx configuration of lagmb's documentation (make docs).

The user guide is Markdown (myst-parser): docs/*.md. The API reference is
generated from the docstrings of the installed package (autosummary). The
gallery runs examples/*.py through sphinx-gallery (docs/gallery_sources.py
says how).
"""

import os
import re
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import lagmb  # noqa: E402  (the installed package: its docstrings and version)

from lagmb import registry  # noqa: E402

import gallery_sources  # noqa: E402

project = "lagmb"
author = "the lagmb developers"
copyright = "2026, the lagmb developers"
version = release = lagmb.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx_gallery.gen_gallery",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "_templates", "gallery/*.ipynb", "gallery/*.py", "gallery/*.zip", "gallery/*.json",
                    "gallery/*.md5", "**/*.codeobj.json"]
# docstrings write a norm as |Phi| (plain text); reST would read a substitution
rst_prolog = r"""
.. |Phi| replace:: \|Phi\|
"""

# --- user guide (Markdown) -------------------------------------------------
myst_enable_extensions = ["dollarmath"]
# anchors for headings, as GitHub makes them: modelling.md#joints, methods.md#choosing-the-analysis
myst_heading_anchors = 4

# --- API reference ------------------------------------------------------------
# autosummary writes a page per name into generated/ at every build; a page
# left from a name no longer listed would be a warning, so start empty
shutil.rmtree(os.path.join(HERE, "generated"), ignore_errors=True)
autosummary_generate = True
# the pages' template: docs/_templates/entry.rst (api.rst's ":template: entry.rst")
templates_path = ["_templates"]
autosummary_imported_members = True
autodoc_default_options = {"members": True}
autodoc_member_order = "bysource"
autodoc_typehints = "none"


def _model_page_groups():
    """The Model page's members in two groups, the building methods first
    (add_* and drive_*: the elements of the registry in its order, then
    frames, shapes and joint aliases), then what reads, copies and compiles
    a model; (name, "method" or "property") each."""
    members = [n for n in vars(lagmb.Model) if not n.startswith("_")]
    kind = {n: "property" if isinstance(vars(lagmb.Model)[n], property) else "method" for n in members}
    extra = ("add_frame", "add_shape", "add_joint_alias")
    building = [n for n in members if n.startswith(("add_", "drive_")) and n not in extra] + list(extra)
    rest = [n for n in members if n not in building]
    return [(n, kind[n]) for n in building], [(n, kind[n]) for n in rest]


_building, _reading = _model_page_groups()
autosummary_context = {"model_building": _building, "model_reading": _reading}



def _escape(text):
    """Plain text as reST shows it."""
    return re.sub(r"([\\`*|_])", r"\\\1", text)


def registry_docstring(app, what, name, obj, options, lines):
    """The Model.add_* / drive_* methods take their docstring from the
    element registry as plain text (what help() shows); here it becomes reST
    from the same declarations: the kind's description and its parameters."""
    method = name.rsplit(".", 1)[-1]
    if what != "method" or ".Model." not in name:
        return
    kinds = [k for k in (registry.BY_METHOD.get(method), registry.SPATIAL_BY_METHOD.get(method)) if k]
    if not kinds:
        return
    out = []
    for k in kinds:
        if len(kinds) > 1:
            out += [f"**In a {'planar' if k.dimension == 2 else 'spatial'} model** (``dimension={k.dimension}``):", ""]
        out += [_escape(k.doc), "", "- ``name``: the element's unique name"]
        out += [f"- ``{p.name}``: {_escape(registry.describe(p))}" for p in k.params]
        out += ["", "Returns the element's handle.", ""]
    lines[:] = out


def setup(app):
    app.connect("autodoc-process-docstring", registry_docstring)


# --- gallery ------------------------------------------------------------------
sphinx_gallery_conf = gallery_sources.configuration(HERE)

# --- HTML ---------------------------------------------------------------------
html_theme = "furo"
html_title = f"lagmb {release}"
html_static_path = ["_static"]
html_css_files = ["lagmb.css"]
html_show_sourcelink = False
