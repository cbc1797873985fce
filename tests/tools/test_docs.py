"""The documentation site builds with warnings as errors, as `make docs`
does, so a renamed or removed function, a docstring reST cannot read or a
broken link between pages fails the suite; its key pages are there; every
public name of lagmb is in the API reference; the tour's Python blocks run
as written.

The build goes into a temporary folder. The gallery (sphinx-gallery running
examples/*.py) keeps its outputs in docs/gallery/ and reruns only the
scripts whose gallery source changed: the first build of a clone runs them
all (about half a minute more), later ones reuse them. `make docs` starts
from scratch.
"""

import importlib.util
import inspect
import os
import re
import subprocess
import sys

import pytest

import lagmb as mb

from paths import ROOT  # noqa: E402
DOCS = os.path.join(ROOT, "docs")
EXAMPLES = os.path.join(ROOT, "examples")

MISSING = [m for m in ("sphinx", "myst_parser", "sphinx_gallery", "furo") if importlib.util.find_spec(m) is None]
needs_sphinx = pytest.mark.skipif(bool(MISSING), reason=f"the docs extra is not installed ({', '.join(MISSING)}): "
                                                        "pip install '.[docs]' (Python >= 3.11)")


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """(the finished sphinx-build process, the HTML folder)."""
    html = tmp_path_factory.mktemp("docs") / "html"
    proc = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html", DOCS, str(html)],
                          capture_output=True, text=True, timeout=900, cwd=ROOT)
    return proc, html


def read(html, page):
    path = html / page
    assert path.is_file(), f"{page} was not built"
    return path.read_text(encoding="utf-8")


@needs_sphinx
def test_build_has_no_warnings(site):
    proc, _ = site
    assert proc.returncode == 0, f"sphinx-build -W failed:\n{proc.stdout[-4000:]}\n{proc.stderr[-8000:]}"


@needs_sphinx
def test_api_reference_pages(site):
    """The API page links every entry; simulate's page holds its signature
    and its docstring's first line; a Model method from the element
    registry shows its parameters."""
    _, html = site
    api = read(html, "api.html")
    for name in ("lagmb.simulate", "lagmb.Model", "lagmb.Result", "lagmb.load_urdf", "lagmb.plotting.plot_result"):
        assert name in api, name
    page = read(html, "generated/lagmb.simulate.html")
    assert 'id="lagmb.simulate"' in page
    assert "Integrate a model from its initial state" in page
    model = read(html, "generated/lagmb.Model.html")
    assert 'id="lagmb.Model.add_revolute"' in model
    assert "In a spatial model" in model
    # the Model page leads with its building methods, then what reads, copies and compiles it
    assert model.index('id="lagmb.Model.add_body"') < model.index('id="lagmb.Model.add_contact"') \
        < model.index("Reading, copying and compiling") < model.index('id="lagmb.Model.copy"')
    assert "The solver could not go on" in read(html, "generated/lagmb.SimulationError.html")


def test_every_error_and_warning_class_says_what_it_is():
    """The API reference's errors and warnings: each public one has a
    docstring (its summary on the page), its own, not its base's."""
    classes = [getattr(mb, n) for n in dir(mb) if isinstance(getattr(mb, n), type)
               and issubclass(getattr(mb, n), (Exception, Warning))]
    assert len(classes) >= 10
    for cls in classes:
        doc = cls.__dict__.get("__doc__") or ""
        assert doc.strip(), f"{cls.__name__} has no docstring"


@needs_sphinx
def test_gallery_pages_show_the_examples(site):
    """One page per examples/*.py, with what it printed and a figure it
    drew (its mechanism or its time histories: no page, and so no
    thumbnail, without one); the seed pendulum's page shows the figure its
    --plot wrote."""
    _, html = site
    index = read(html, "gallery/index.html")
    assert "no_image" not in index  # sphinx-gallery's placeholder thumbnail
    for script in sorted(os.listdir(EXAMPLES)):
        if script.endswith(".py"):
            stem = script[:-3]
            assert f"{stem}.html" in index, stem
            figures = re.findall(r'<img [^>]*src="([^"]+\.png)"', read(html, f"gallery/{stem}.html"))
            assert figures, f"the gallery page of {stem}.py shows no figure"
    page = read(html, "gallery/seed_pendulum.html")
    assert "period closed form = 1.9333348544" in page
    images = re.findall(r'<img [^>]*src="([^"]+\.png)"', page)
    assert images, "no figure on the seed pendulum's page"
    assert (html / "gallery" / images[0]).resolve().is_file()


@needs_sphinx
def test_user_guide_and_version(site):
    _, html = site
    for page in ("install", "tour", "modelling", "scene-format", "methods", "cpp", "validation", "benchmarks",
                 "internals", "design", "changelog"):
        read(html, f"{page}.html")
    assert f"lagmb {mb.__version__}" in read(html, "index.html")
    # each benchmark says when its results file was committed
    assert len(re.findall(r"committed \d{4}-\d{2}-\d{2}", read(html, "benchmarks.html"))) >= 10


def public_names():
    """What `import lagmb` offers a user: its names without a leading
    underscore, modules left out."""
    return sorted(n for n in dir(mb) if not n.startswith("_") and not inspect.ismodule(getattr(mb, n)))


def test_every_public_name_is_in_the_api_reference():
    """A new public name needs an entry in docs/api.rst (and a renamed one
    fails the build above)."""
    text = open(os.path.join(DOCS, "api.rst"), encoding="utf-8").read()
    listed = set(re.findall(r"^   (\w+)$", text, re.M)) | set(re.findall(r"^\.\. data:: (\w+)$", text, re.M))
    assert [n for n in public_names() if n not in listed] == []


def test_tour_python_blocks_run():
    """Each Python block of docs/tour.md runs on its own, imports included."""
    text = open(os.path.join(DOCS, "tour.md"), encoding="utf-8").read()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) >= 4
    for k, code in enumerate(blocks):
        exec(compile(code, f"docs/tour.md, block {k + 1}", "exec"), {})


def test_every_example_draws_its_mechanism_first():
    """Each examples/*.py takes --picture PATH (the mechanism at one moment,
    lagmb.plotting.picture) and the gallery runs it with that first, so a
    page's first figure and thumbnail show the mechanism, not a stack of
    time histories (which follow, where a script has --plot)."""
    import sys

    sys.path.insert(0, os.path.join(os.path.dirname(EXAMPLES), "docs"))
    try:
        import gallery_sources
    finally:
        sys.path.pop(0)
    for script in sorted(os.listdir(EXAMPLES)):
        if script.endswith(".py"):
            stem = script[:-3]
            with open(os.path.join(EXAMPLES, script)) as f:
                argv = gallery_sources.argv_for(f.read(), stem)
            assert argv[:1] == ["--picture"], (stem, argv)


#: What needs an optional extra, as the README and docs write it in their blocks.
EXTRA_FEATURES = {
    "sweep": r"mb\.sweep\b|lagmb sweep|open_store|view_sweep",
    "view": r"mb\.view(_mode|_sweep)?\(|lagmb\.view\(|--html",
    "plot": r"plotting\.|--plot|--picture|--gif|--animate",
    "mjcf": r"load_mjcf\(",
    "fmu": r"lagmb fmu",
}


def code_blocks(lines):
    """(first, end) line indices of the fenced and indented blocks of a Markdown page."""
    i = 0
    while i < len(lines):
        if lines[i].startswith("```"):
            j = i + 1
            while j < len(lines) and not lines[j].startswith("```"):
                j += 1
            yield i, j + 1
            i = j + 1
        elif lines[i].startswith("    ") and (i == 0 or not lines[i - 1].strip()):
            j = i
            while j < len(lines) and (lines[j].startswith("    ") or not lines[j].strip()):
                j += 1
            yield i, j
            i = j
        else:
            i += 1


def test_every_block_that_needs_an_extra_names_it():
    """Issue 56: README blocks needed extras they did not name (mb.sweep
    without xarray failed bare; "Seeing a run" needs `view`). A block of the
    README or docs/*.md that uses what an extra gives names the extra in
    itself or in the text that introduces it (from the heading or the block
    before): `sweep` extra, extra `sweep`, lagmb[sweep]."""
    unnamed = []
    for page in ["README.md"] + [os.path.join("docs", f) for f in sorted(os.listdir(DOCS)) if f.endswith(".md")]:
        lines = open(os.path.join(ROOT, page), encoding="utf-8").read().splitlines()
        after = 0  # the end of the last block
        for first, end in code_blocks(lines):
            intro = next((k for k in range(first - 1, after - 1, -1) if lines[k].startswith("#")), after)
            block, context = "\n".join(lines[first:end]), "\n".join(lines[intro:end])
            for extra, uses in EXTRA_FEATURES.items():
                named = rf"lagmb\[[a-z,]*\b{extra}\b[a-z,]*\]|`{extra}` extra|'{extra}' extra|extra `{extra}`"
                if re.search(uses, block) and not re.search(named, context):
                    unnamed.append(f"{page}:{first + 1}: the '{extra}' extra: {lines[first].strip()[:70]}")
            after = end
    assert unnamed == []
