"""Constraint drift over a long run of a chaotic double pendulum.

Two uniform rods (L = 1 m, m = 1 kg, J = 1/12 kg m^2) released horizontal
along +x, pinned to the ground at the origin ("pin0") and to each other at
(1, 0) ("pin1"), gravity (0, -9.81), integrated for 100 s at rtol 1e-8,
atol 1e-10 with 2001 outputs (every 50 ms).

The default GGL formulation enforces both Phi = 0 and Phi_q v = 0 at every
step, so neither the position nor the velocity constraints may drift, however
long the run.  Written out for the revolutes (local points s, A the rotation):

    Phi_k     = (r_j + A_j s_j) - (r_i + A_i s_i)
    Phi_q v   = (v_j + phidot_j B_j s_j) - (v_i + phidot_i B_i s_i),
                B = dA/dphi,
with pin0: ground point (0, 0), rod0 at (-1/2, 0); pin1: rod0 at (1/2, 0),
rod1 at (-1/2, 0).  The velocity-level drift is computed here from r.q and
r.v, independently of the library's residual.
"""

import numpy as np
import pytest

import lagmb as mb
from references import RodChain, revolute_residuals, revolute_velocity_residuals

T_END = 100.0
RTOL, ATOL = 1e-8, 1e-10


@pytest.fixture(scope="module")
def run():
    from builders import rod_chain

    return mb.simulate(rod_chain(2), t_end=T_END, n_out=2001, rtol=RTOL, atol=ATOL)


JOINTS = RodChain(2).joints()


def test_position_constraints_do_not_drift(run):
    """max |Phi| over 100 s, as reported (r.residual) and as recomputed from
    r.q with the hand-written joints, stays below 1e-7 m."""
    assert run.t.shape == (2001,)
    assert abs(run.t[-1] - T_END) <= 1e-12
    assert run.residual.max() < 1e-7
    assert np.abs(revolute_residuals(run.q, JOINTS)).max() < 1e-7


def test_velocity_constraints_do_not_drift(run):
    """max |Phi_q v| (computed here) stays below 1e-6 m/s over 100 s, and it
    does not grow: its maximum over the last 10 s is at most 10 times its
    maximum over the first 10 s.  Values below atol (1e-10) are treated as
    atol in that ratio, so round-off level noise cannot fail it."""
    drift = np.abs(revolute_velocity_residuals(run.q, run.v, JOINTS)).max(axis=1)
    assert drift.max() < 1e-6
    first = drift[run.t <= 10.0].max()
    last = drift[run.t >= T_END - 10.0].max()
    assert last <= 10.0 * max(first, ATOL)

