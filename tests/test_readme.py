"""The README's Python blocks run as written, and the slider-crank example in
it gives a motor torque equal to the one the same mechanism gives in
examples/slider_crank.toml (same geometry, same drive), to 1e-3 N m (the
README rounds its coordinates to 4 digits)."""

import os
import re

import numpy as np

import lagmb as mb

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def test_readme_python_blocks_run():
    text = open(os.path.join(ROOT, "README.md")).read()
    code = "\n".join(re.findall(r"```python\n(.*?)```", text, re.S))
    ns = {}
    exec(compile(code, "README.md", "exec"), ns)
    r = ns["r"]
    scene = mb.load_scene(os.path.join(ROOT, "examples", "slider_crank.toml"))
    ref = mb.simulate(scene.model, t_out=r.t, rtol=1e-8)
    assert np.abs(r.effort("motor") - ref.effort("motor")).max() < 1e-3
