"""The README's Python blocks run as written, and the slider-crank example in
it gives a motor torque equal to the one the same mechanism gives in
examples/slider_crank.toml (same geometry, same drive), to 1e-3 N m (the
README rounds its coordinates to 4 digits). Its links lead to files that
exist, and its example table names every example. The rest of the user's
documentation is in docs/ (tests/tools/test_docs.py)."""

import os
import re

import numpy as np
import pytest

import lagmb as mb

from paths import ROOT  # noqa: E402


def test_readme_python_blocks_run():
    # (its parameter study returns an xarray Dataset and a pandas table: the 'sweep' extra)
    for module in ("xarray", "pandas"):
        pytest.importorskip(module, reason="the README's parameter study needs the 'sweep' extra")
    text = open(os.path.join(ROOT, "README.md")).read()
    code = "\n".join(re.findall(r"```python\n(.*?)```", text, re.S))
    ns = {}
    exec(compile(code, "README.md", "exec"), ns)
    r = ns["r"]
    scene = mb.load_scene(os.path.join(ROOT, "examples", "slider_crank.toml"))
    ref = mb.simulate(scene.model, t_out=r.t, rtol=1e-8)
    assert np.abs(r.effort("motor") - ref.effort("motor")).max() < 1e-3


def test_readme_links_exist():
    """Every relative link of README.md (docs pages, LICENSE, ...) is a file."""
    text = open(os.path.join(ROOT, "README.md")).read()
    links = [t.split("#")[0] for t in re.findall(r"\]\(([^)]+)\)", text) if "://" not in t]
    assert links
    assert [t for t in links if t and not os.path.isfile(os.path.join(ROOT, t))] == []


def test_readme_lists_every_example():
    """The example table names every script and scene in examples/."""
    text = open(os.path.join(ROOT, "README.md")).read()
    names = [f for f in os.listdir(os.path.join(ROOT, "examples")) if f.endswith((".py", ".toml", ".xml"))]
    assert [f for f in sorted(names) if f"`{f}`" not in text] == []
