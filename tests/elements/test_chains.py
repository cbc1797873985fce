"""Chains of uniform rods against a minimal-coordinate SciPy reference.

N rods (L = 1 m, m = 1 kg, J = m L^2/12) lie along +x at rest: rod k has
its centre at (k + 1/2, 0); "pin0" joins the ground and rod0 at the origin,
"pin{k}" joins rod{k-1} and rod{k} at (k, 0); gravity (0, -9.81).

The reference (references.RodChain) integrates the Lagrange equations in
absolute angles theta_i (CCW from +x):

    sum_j M_ij thetadd_j + sum_j m L^2 S_ij sin(theta_i - theta_j) thetadot_j^2
        = -m g L cos(theta_i) sum_k c_ki,
    M_ij = m L^2 S_ij cos(theta_i - theta_j) + J delta_ij,
    S_ij = sum_k c_ki c_kj,  c_ki = 1 (i < k), 1/2 (i = k), 0 (i > k),

with DOP853 at rtol = atol = 1e-12 (derivation in references.py; checked in
test_references.py by energy conservation, the N = 1 closed form and the
Cartesian augmented system).  Centres follow as r_k = L sum_i c_ki e(theta_i)
and the body angle phi_k equals theta_k.
"""

import numpy as np
import pytest

import lagmb as mb
from references import RodChain

T_OUT = [0.0, 0.5, 1.0]


def _wrap(a):
    """Angle difference folded into (-pi, pi]."""
    return np.angle(np.exp(1j * np.asarray(a)))


@pytest.fixture(scope="module", params=[2, 5], ids=["N=2", "N=5"])
def chain_runs(request):
    """lagmb (rtol 1e-10, atol 1e-12) and the reference at t = 0, 0.5, 1 s."""
    from builders import rod_chain

    n = request.param
    r = mb.simulate(rod_chain(n), t_end=1.0, t_out=T_OUT, rtol=1e-10, atol=1e-12)
    ref = RodChain(n)
    theta, thetadot = ref.solve(T_OUT)
    return n, r, ref, theta, thetadot


def test_model_size(rod_chain):
    """N planar bodies: 3N coordinates; N revolutes: 2N equations; an open
    chain has N degrees of freedom."""
    for n in (2, 5):
        m = rod_chain(n)
        assert m.n_coordinates == 3 * n
        assert m.n_constraints == 2 * n
        assert m.degrees_of_freedom() == n


def test_coordinate_layout(chain_runs):
    """r.q stores (x, y, phi) per body in the order the bodies were added;
    r.body(name) reads the same numbers (to 1e-14)."""
    n, r, _, _, _ = chain_runs
    assert r.q.shape == (len(T_OUT), 3 * n)
    assert r.lam.shape == (len(T_OUT), 2 * n)
    for k in range(n):
        b = r.body(f"rod{k}")
        assert np.abs(b.position - r.q[:, 3 * k:3 * k + 2]).max() <= 1e-14
        assert np.abs(b.angle - r.q[:, 3 * k + 2]).max() <= 1e-14


def test_centres_and_angles_match_minimal_reference(chain_runs):
    """Every rod's centre of mass and angle at t = 0.5 s and 1 s agree with
    the minimal-coordinate reference to 1e-6 m and 1e-6 rad (the chain is
    not yet chaotic at 1 s: a 1e-9 perturbation of the state grows to
    < 5e-9 in position)."""
    n, r, ref, theta, _ = chain_runs
    centres = ref.centres(theta)  # (3, n, 2)
    for k in range(n):
        b = r.body(f"rod{k}")
        assert np.abs(b.position[1:] - centres[1:, k]).max() <= 1e-6, f"rod{k}"
        assert np.abs(_wrap(b.angle[1:] - theta[1:, k])).max() <= 1e-6, f"rod{k}"


def test_velocities_match_minimal_reference(chain_runs):
    """The Cartesian velocities follow from the reference by
    v_k = L sum_i c_ki thetadot_i (-sin theta_i, cos theta_i), phidot_k =
    thetadot_k; agreement at 1 s to 1e-6 (m/s, rad/s)."""
    n, r, ref, theta, thetadot = chain_runs
    _, v_ref = ref.cartesian_state(theta[-1], thetadot[-1])
    assert np.abs(r.v[-1] - v_ref).max() <= 1e-6


def test_chain_energy_conserved(chain_runs):
    """No dissipation: r.energy at 0.5 s and 1 s equals its initial value to
    1e-8 of the potential-energy scale of the chain, m g L sum_k (k + 1/2)
    = m g L N^2/2 (the drop of the centres from horizontal to hanging)."""
    n, r, _, _, _ = chain_runs
    E = np.asarray(r.energy)
    assert np.abs(E - E[0]).max() <= 1e-8 * 9.81 * n**2 / 2
