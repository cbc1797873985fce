"""What the benchmarks take from the repository's tests/ and examples/ (the
chains and references the tests check, the tests' browser driver, example
models): the one place that knows which module holds each, so that moving a
test or an example is a change of its line in FROM.

    from bench.common.repo import RodChain, spatial_chain

Each is imported when first asked for (importing browser or test_spatial
costs what they import)."""

import importlib
import sys

from bench.common.paths import EXAMPLES, TESTS

# name -> the module (on tests/ or examples/) that defines it; a module's
# own name gives the module
FROM = {
    "spatial_chain": "elements.test_spatial",  # tests/elements/test_spatial.py
    "RodChain": "references",  # tests/references.py
    "chain_coefficients": "references",
    "browser": "browser",  # tests/browser.py, the DevTools driver
    "cart_pole": "cart_pole",  # examples/cart_pole.py
    "n_four_bar": "n_four_bar",  # examples/n_four_bar.py
    "andrews_model": "andrews",  # examples/andrews.py
    "panda": "panda",  # examples/panda.py
}

for _folder in (EXAMPLES, TESTS):
    if _folder not in sys.path:
        sys.path.insert(0, _folder)


def __getattr__(name):
    if name not in FROM:
        raise AttributeError(f"bench.common.repo has no {name!r} (add it to FROM)")
    module = importlib.import_module(FROM[name])
    return module if name == FROM[name] else getattr(module, name)
