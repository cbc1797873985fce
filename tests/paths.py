"""Where things are, for every test: the checkout's root, its examples,
the tests' own data. Tests live in folders by layer (tests/<layer>/), so a
path is never computed from a test file's own place."""

import os

TESTS = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(TESTS)
EXAMPLES = os.path.join(ROOT, "examples")
DATA = os.path.join(TESTS, "data")
