"""docs/scene-format.md agrees with the code: its example loads, runs and
writes back; the key tables of every element kind, of [simulation] and of
[output] list exactly the keys the reader takes, with the kind of value the
schema gives them and the defaults of the Model methods and of simulate."""

import inspect
import os
import re

import numpy as np
import pytest

try:  # Python 3.11+
    import tomllib
except ImportError:  # pragma: no cover - older Pythons
    import tomli as tomllib

import lagmb as mb
from lagmb.scene import schema

from paths import ROOT  # noqa: E402
DOC = open(os.path.join(ROOT, "docs", "scene-format.md"), encoding="utf-8").read()

# how the document names each kind of value
WORDS = {
    schema.NUMBER: "number", schema.INTEGER: "integer", schema.STRING: "string",
    schema.BOOL: "true or false", schema.VEC2: "[x, y]", schema.BODY: "body name",
    schema.JOINT: "joint name", schema.FUNCTION: "time function", schema.FUNCTION_PAIR: "[fx, fy]",
    schema.NUMBERS: "array of numbers", schema.STRINGS: "array of strings",
    schema.VEC3: "[x, y, z]", schema.VECTOR: "[x, y] or [x, y, z]", schema.ORIENTATION: "orientation",
    schema.INERTIA: "inertia", schema.FUNCTION_TRIPLE: "[fx, fy, fz]", schema.SHAPE: "shape",
}


def key_table(heading):
    """{key: (value, default)} of the first key table after the heading
    that contains the given text, up to the next heading."""
    lines = DOC.split("\n")
    start = next(i for i, line in enumerate(lines) if line.startswith("#") and heading in line)
    rows = {}
    for line in lines[start + 1:]:
        if line.startswith("#"):
            break
        m = re.match(r"\| `(\w+)` \| ([^|]+) \| ([^|]+) \|", line)
        if m:
            rows[m.group(1)] = (m.group(2).strip(), m.group(3).strip())
    assert rows, f"no key table after the heading with {heading!r}"
    return rows


def check_default(where, text, param):
    if text == "required":
        assert param.default is param.empty, f"{where}: has a default, {param.default!r}"
        return
    assert param.default is not param.empty, f"{where}: is required"
    m = re.fullmatch(r"`([^`]+)`", text)
    if m is None:  # in words: worked out (None), or no bound
        assert param.default is None, f"{where}: the default is {param.default!r}, not {text!r}"
        return
    written = tomllib.loads(f"x = {m.group(1)}")["x"]
    default = list(param.default) if isinstance(param.default, tuple) else param.default
    assert written == default and type(written) is type(default), \
        f"{where}: the default is {param.default!r}, not {text}"


def test_the_example_loads_runs_and_writes_back(tmp_path):
    text = re.search(r"```toml\n(.*?)```", DOC, re.S).group(1)
    path = tmp_path / "pendulum.toml"
    path.write_text(text)
    scene = mb.load_scene(path)
    assert scene.names("bodies") == ["arm"] and scene.names("forces") == ["bearing", "push"]
    r = scene.run(t_end=0.2, n_out=5)
    assert r.residual.max() < 1e-8
    copy = tmp_path / "copy.toml"
    mb.save_scene(scene.model, copy, scene.settings, scene.output)
    again = mb.load_scene(copy)
    assert again.settings == scene.settings and again.output == scene.output
    assert np.array_equal(again.run(t_end=0.2, n_out=5).q, r.q)


def test_the_kinds_of_value_are_explained():
    for kind, word in WORDS.items():
        assert f"\n| {word} | " in DOC, f"no row for {word!r} in the table of kinds of value"


@pytest.mark.parametrize("method", list(schema.ELEMENTS))
def test_every_element_kind_has_its_key_table(method):
    element = schema.ELEMENTS[method]
    rows = key_table(f"`{method}`")
    params = list(inspect.signature(getattr(mb.Model, method)).parameters.values())[1:]
    assert list(rows) == [element.renamed.get(p.name, p.name) for p in params]
    for p in params:
        key = element.renamed.get(p.name, p.name)
        value, default = rows[key]
        assert value == WORDS[element.arguments[p.name]], f"{method} {key}: the schema says " \
            f"{WORDS[element.arguments[p.name]]!r}"
        check_default(f"{method} {key}", default, p)
    heading = next(line for line in DOC.split("\n") if line.startswith("#") and f"`{method}`" in line)
    assert f"[[{element.table}]]" in heading or f'type = "{element.type}"' in heading


@pytest.mark.parametrize("method", list(schema.SPATIAL_ELEMENTS))
def test_every_spatial_element_kind_has_its_key_table(method):
    from lagmb.registry import SPATIAL_BY_METHOD, signature

    element = schema.SPATIAL_ELEMENTS[method]
    rows = key_table(f"spatial `{method}`")
    params = list(signature(SPATIAL_BY_METHOD[method]).parameters.values())[1:]
    assert list(rows) == [element.renamed.get(p.name, p.name) for p in params]
    for p in params:
        key = element.renamed.get(p.name, p.name)
        value, default = rows[key]
        assert value == WORDS[element.arguments[p.name]], f"{method} {key}"
        check_default(f"spatial {method} {key}", default, p)
    heading = next(line for line in DOC.split("\n") if line.startswith("#") and f"spatial `{method}`" in line)
    assert f"[[{element.table}]]" in heading and (element.type is None or f'type = "{element.type}"' in heading)


def test_the_spatial_example_loads_and_runs(tmp_path):
    text = DOC.split("## Spatial scenes")[1].split("```toml\n")[1].split("```")[0]
    path = tmp_path / "top.toml"
    path.write_text(text)
    scene = mb.load_scene(path)
    assert scene.model.dimension == 3
    r = scene.run(t_end=0.1)
    assert r.body("top").position.shape[1] == 3


def test_simulation_keys_and_defaults():
    rows = key_table("## Simulation")
    kinds = schema.SETTINGS["simulation"]
    assert list(rows) == list(kinds)
    params = inspect.signature(mb.simulate).parameters
    for key, (value, default) in rows.items():
        assert value == WORDS[kinds[key]], key
        check_default(f"[simulation] {key}", default, params[key])


def test_output_keys():
    rows = key_table("## Output")
    kinds = schema.SETTINGS["output"]
    assert list(rows) == list(kinds)
    for key, (value, _) in rows.items():
        assert value == WORDS[kinds[key]], key
