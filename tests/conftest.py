"""Shared pytest setup for the lagmb suite.

The reference solutions (``references.py``, no lagmb import) and the model
builders (``builders.py``) live next to the tests.  Make them importable
whatever pytest import mode the project configures (``prepend`` already puts
this directory on sys.path; ``importlib`` does not).
"""

import os
import sys

import pytest

_HERE = os.path.dirname(os.path.abspath(__file__))
if _HERE not in sys.path:
    sys.path.insert(0, _HERE)


@pytest.fixture
def rod_chain():
    """Factory fixture: ``rod_chain(n, L=1.0, m=1.0, g=9.81) -> mb.Model``.

    n uniform rods released horizontal along +x, pinned to the ground at the
    origin; see builders.rod_chain for the naming of bodies and joints.
    """
    from builders import rod_chain as build

    return build
