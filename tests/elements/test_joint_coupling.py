"""A joint coupling (add_joint_coupling, a URDF <mimic>): one joint's angle
or slide follows another's, s_b = m s_a + s0, as one equation over the
bodies of both joints."""
import numpy as np
import pytest
from scipy.integrate import solve_ivp

import lagmb as mb

G = 9.81


def geared_rods():
    """Two rods hinged to the ground about z, rod b turning twice as far as
    rod a the other way (m = -2): one degree of freedom x = theta_a with
    J x'' = -dV/dx, J = (I_a + m_a r^2) + 4 (I_b + m_b r^2), V = m_a g r
    sin x + m_b g r cos 2x (rod a starts along +x, rod b along +y, r = 0.5)."""
    m = mb.Model(dimension=3, gravity=(0.0, -G, 0.0))
    a = m.add_body("a", 1.0, (0.06, 0.05, 0.1), position=(0.5, 0.0, 0.0))
    b = m.add_body("b", 2.0, (0.2, 0.1, 0.3), position=(0.0, 0.5, 0.0))
    m.add_revolute("ja", m.ground, a, at=(0, 0, 0), axis=(0, 0, 1))
    m.add_revolute("jb", m.ground, b, at=(0, 0, 0), axis=(0, 0, 1))
    m.add_joint_coupling("gears", "jb", leader="ja", multiplier=-2.0)
    return m


def test_geared_rods_follow_the_one_degree_of_freedom_equation():
    J = (0.1 + 1.0 * 0.25) + 4.0 * (0.3 + 2.0 * 0.25)

    def rhs(t, y):
        x, xd = y
        dV = 1.0 * G * 0.5 * np.cos(x) - 2.0 * 2.0 * G * 0.5 * np.sin(2.0 * x)
        return [xd, -dV / J]

    t = np.linspace(0.0, 1.0, 11)
    exact = solve_ivp(rhs, (0, 1), [0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-12, t_eval=t).y[0]
    for formulation in ("ggl", "projection", "index3"):
        r = mb.simulate(geared_rods(), 1.0, rtol=1e-10, atol=1e-10, t_out=t, formulation=formulation)
        # (index 3, no velocity error control: 3.7e-7 to 1.1e-6 rad as rtol moves by 10 %)
        assert r.joint("ja").angle == pytest.approx(exact, abs=3e-6 if formulation == "index3" else 1e-6), formulation
        assert r.joint("jb").angle == pytest.approx(-2.0 * r.joint("ja").angle, abs=1e-8), formulation


def test_fingers_on_a_moving_hand_share_its_body():
    """A hand slides freely along x; two fingers slide along y on it, the
    second mirroring the first (m = -1), so the hand is in both halves of
    the coupling's equation. With gravity -y: s'' = g (m_2 - m_1) / (m_1 +
    m_2) exactly, the hand does not move, and the coupling pushes finger 2
    along y with F = m_2 (g - s'') (its reaction; finger 1 gets m F = -F
    along its slide, which for the mirror is the same push along y)."""
    m = mb.Model(dimension=3, gravity=(0.0, -G, 0.0))
    hand = m.add_body("hand", 3.0, (0.1, 0.1, 0.1), position=(0.0, 0.0, 0.0))
    f1 = m.add_body("f1", 0.5, (0.01, 0.01, 0.01), position=(0.1, 0.0, 0.0))
    f2 = m.add_body("f2", 0.2, (0.01, 0.01, 0.01), position=(-0.1, 0.0, 0.0))
    m.add_translational("rail", m.ground, hand, at=(0, 0, 0), axis=(1, 0, 0))
    m.add_translational("finger1", hand, f1, at=(0.1, 0, 0), axis=(0, 1, 0))
    m.add_translational("finger2", hand, f2, at=(-0.1, 0, 0), axis=(0, 1, 0))
    m.add_joint_coupling("mirror", "finger2", leader="finger1", multiplier=-1.0)
    r = mb.simulate(m, 0.5, rtol=1e-10, atol=1e-12, n_out=6)
    sdd = G * (0.2 - 0.5) / 0.7
    assert r.joint("finger1").slide == pytest.approx(0.5 * sdd * r.t ** 2, abs=1e-9)
    assert r.joint("finger2").slide == pytest.approx(-0.5 * sdd * r.t ** 2, abs=1e-9)
    assert r.joint("rail").slide == pytest.approx(np.zeros_like(r.t), abs=1e-12)
    force = 0.2 * (G - sdd)  # on finger 2 along +y: m_2 y_2'' = -m_2 g + F, y_2'' = -s''
    assert force == pytest.approx(2.0 * G * 0.5 * 0.2 / 0.7)  # = 0.5 (g + s''): finger 1 feels it too
    assert r.reaction("mirror")[:, 1] == pytest.approx(np.full(r.t.size, force), rel=1e-8)


def test_a_coupling_is_refused_by_name():
    m = geared_rods()
    c = m.add_body("c", 1.0, (0.06, 0.05, 0.1), position=(0.0, 0.0, 1.0))
    m.add_cylindrical("screw", m.ground, c, at=(0, 0, 1), axis=(0, 0, 1))
    with pytest.raises(mb.ModelError, match="'loop': joint and leader are both 'ja'"):
        m.add_joint_coupling("loop", "ja", leader="ja")
    with pytest.raises(mb.ModelError, match="'screw' turns and slides"):
        m.add_joint_coupling("nut", "screw", leader="ja")
    with pytest.raises(mb.ModelError, match="'nowhere' is not a joint of this model"):
        m.add_joint_coupling("lost", "ja", leader="nowhere")
    with pytest.raises(mb.ModelError, match="multiplier must be finite and nonzero, got 0"):
        m.add_joint_coupling("idle", "jb", leader="ja", multiplier=0.0)
    with pytest.raises(mb.ModelError, match="planar only|spatial only"):
        mb.Model().add_joint_coupling("x", "a", leader="b")
