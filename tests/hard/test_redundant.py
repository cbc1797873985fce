"""Redundant constraints that are there all the time (issue 5, case 3).

A parallelogram linkage with a third parallel crank has 12 constraint
equations of rank 11; a chain with a duplicated joint repeats 2 equations.
lagmb detects the dependent rows where a run starts (rank-revealing sparse
QR of Phi_q^T at the assembled position, confirmed at nearby positions so a
singular start is not taken for a redundancy), warns naming the joints,
drops them (they read 0 = 0, their multipliers are 0), simulates on and
checks the dropped equations at every output.

What is unique is checked against closed-form kinematics or a model without
the redundancy: the motion, and the sum of the reactions over the redundant
set (e.g. the total force the ground exerts through the parallel cranks).
How it is split among the redundant joints is not unique; lagmb's documented
choice is that the dropped equations carry nothing.
"""

import math
import warnings

import numpy as np
import pytest

import lagmb as mb

G = 9.81
ANGLE = math.radians(60.0)  # crank angle
OMEGA = 3.0  # initial crank speed, rad/s


def parallelogram(third_crank):
    """Cranks of 1 m pinned to the ground at x = 0, 2 (and 1), all at 60 deg,
    joined by a 2 m coupler: a parallelogram, 1 degree of freedom.
    Crank: 1 kg, J = 1/12; coupler: 2 kg, J = 2 * 4 / 12."""
    m = mb.Model(gravity=(0.0, -G))
    u = np.array([math.cos(ANGLE), math.sin(ANGLE)])
    xs = [0.0, 2.0, 1.0] if third_crank else [0.0, 2.0]
    cranks = []
    for k, x in enumerate(xs):
        c = m.add_body(f"crank{k}", 1.0, 1.0 / 12.0, position=(x + 0.5 * u[0], 0.5 * u[1]), angle=ANGLE,
                       velocity=tuple(0.5 * OMEGA * np.array([-u[1], u[0]])), angular_velocity=OMEGA)
        m.add_revolute(f"ground{k}", m.ground, c, at=(x, 0.0))
        cranks.append(c)
    v_top = OMEGA * np.array([-u[1], u[0]])
    cp = m.add_body("coupler", 2.0, 2.0 * 4.0 / 12.0, position=(1.0 + u[0], u[1]), angle=0.0,
                    velocity=tuple(v_top))
    for k, (c, x) in enumerate(zip(cranks, xs)):
        m.add_revolute(f"top{k}", c, cp, at=(x + u[0], u[1]))
    return m


def run(model):
    # 0.5 s: the cranks stay above the horizontal, where the parallelogram
    # would reach its singular (all pins collinear) position; singular
    # passages are a separate case (issue 5, cases 2 and 4)
    return mb.simulate(model, t_end=0.5, n_out=101, rtol=1e-9, atol=1e-11)


def test_the_third_crank_is_detected_and_named():
    """12 equations of rank 11: one redundant row, named in a
    RedundantConstraintWarning; still one degree of freedom."""
    with pytest.warns(mb.RedundantConstraintWarning, match=r"redundant.*'(ground|top)\d'"):
        m = parallelogram(third_crank=True)
        m.assemble()
    info = m.rank()
    assert (info["equations"], info["rank"], info["degrees_of_freedom"]) == (12, 11, 1)
    assert len(info["dependent_rows"]) == 1
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the plain parallelogram warns nothing
        assert parallelogram(third_crank=False).degrees_of_freedom() == 1


def test_motion_follows_the_parallelogram_kinematics():
    """With the redundant crank the mechanism still moves as a parallelogram:
    all crank angles equal theta, the coupler stays level with its centre at
    (1 + cos theta, sin theta) (closed form), |Phi| stays below 1e-9 and
    energy is conserved to 1e-7 relative. Tolerances 1e-9."""
    with pytest.warns(mb.RedundantConstraintWarning):
        r = run(parallelogram(third_crank=True))
    th = r.body("crank0").angle
    for k in (1, 2):
        assert np.abs(r.body(f"crank{k}").angle - th).max() < 1e-9
    cp = r.body("coupler").position
    assert np.abs(cp[:, 0] - (1.0 + np.cos(th))).max() < 1e-9
    assert np.abs(cp[:, 1] - np.sin(th)).max() < 1e-9
    assert np.abs(r.body("coupler").angle).max() < 1e-9
    assert r.residual.max() < 1e-9
    # energy is conserved (no friction): kinetic + potential, 1e-7 relative
    assert np.ptp(r.energy) < 1e-7 * np.abs(r.energy).max()


def test_total_ground_reaction_is_unique():
    """The total force the ground exerts through the three cranks is unique:
    it equals (sum of m a) - (sum of m) g over all bodies, from the motion
    (1e-6 relative to the total weight). The split among the cranks is
    lagmb's choice (the dropped equation carries nothing); every share stays
    bounded (below 10 times the total weight)."""
    with pytest.warns(mb.RedundantConstraintWarning):
        r = run(parallelogram(third_crank=True))
    total = sum(r.reaction(f"ground{k}")[:, :2] for k in range(3))
    mass = {"crank0": 1.0, "crank1": 1.0, "crank2": 1.0, "coupler": 2.0}
    expected = sum(m * r.body(b).acceleration for b, m in mass.items()) - sum(mass.values()) * np.array([0.0, -G])
    weight = sum(mass.values()) * G
    assert np.abs(total - expected).max() < 1e-6 * weight
    for k in range(3):
        assert np.abs(r.reaction(f"ground{k}")[:, :2]).max() < 10 * weight


def chain(duplicate):
    """Two uniform rods released from horizontal; with duplicate=True the
    elbow joint is given twice ("elbow" and "elbow_again")."""
    m = mb.Model(gravity=(0.0, -G))
    a = m.add_body("upper", 1.0, 1.0 / 12.0, position=(0.5, 0.0))
    b = m.add_body("lower", 1.0, 1.0 / 12.0, position=(1.5, 0.0))
    m.add_revolute("shoulder", m.ground, a, at=(0.0, 0.0))
    m.add_revolute("elbow", a, b, at=(1.0, 0.0))
    if duplicate:
        m.add_revolute("elbow_again", a, b, at=(1.0, 0.0))
    return m


def test_duplicated_joint_gives_the_same_motion_and_summed_reaction():
    """With the elbow given twice (2 redundant rows, named), positions equal
    the plain double pendulum's to 1e-8 (two separate integrations at rtol
    1e-11, each within ~1e-10 of the truth) and the two elbow reactions sum
    to the plain elbow reaction to 1e-6 relative to m g; one of the two
    carries it all (the dropped rows carry zero)."""
    with pytest.warns(mb.RedundantConstraintWarning, match="elbow"):
        m2 = chain(duplicate=True)
        m2.assemble()
    assert len(m2.rank()["dependent_rows"]) == 2
    tight = dict(t_end=2.0, n_out=201, rtol=1e-11, atol=1e-13)
    with pytest.warns(mb.RedundantConstraintWarning, match="elbow_again"):
        r2 = mb.simulate(m2, **tight)      # each run decides and says so
    r1 = mb.simulate(chain(duplicate=False), **tight)
    assert np.abs(r2.q - r1.q).max() < 1e-8
    total = r2.reaction("elbow") + r2.reaction("elbow_again")
    assert np.abs(total - r1.reaction("elbow")).max() < 1e-6 * G
    shares = [np.abs(r2.reaction(j)).max() for j in ("elbow", "elbow_again")]
    assert min(shares) == 0.0
