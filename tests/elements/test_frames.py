"""Frames and shapes: named places and geometry fixed in spatial bodies
(Model.add_frame, Model.add_shape), read by results and pictures, no part of
the equations."""
import copy
import pickle

import numpy as np
import pytest

import lagmb as mb


def spinning_rod():
    """A rod on a hinge about z at the origin, spinning at 2 rad/s, its
    centre at (0.5, 0, 0); a frame at its tip, turned a quarter turn about x."""
    m = mb.Model(dimension=3)
    rod = m.add_body("rod", 1.0, (1e-3, 1.0 / 12, 1.0 / 12), position=(0.5, 0.0, 0.0), velocity=(0.0, 1.0, 0.0),
                     angular_velocity=(0.0, 0.0, 2.0))
    m.add_revolute("hinge", m.ground, rod, at=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0))
    quarter = ((1.0, 0.0, 0.0), (0.0, 0.0, -1.0), (0.0, 1.0, 0.0))
    m.add_frame("tip", rod, position=(1.0, 0.0, 0.0), orientation=quarter)
    m.add_shape(rod, "cylinder", (0.02, 1.0), position=(0.5, 0.0, 0.0), orientation=((0, 0, 1), (0, 1, 0), (-1, 0, 0)))
    return m


def test_a_frame_moves_with_its_body():
    """The tip of the rod turning at w = 2 rad/s: position (cos 2t, sin 2t,
    0), velocity w (-sin, cos, 0), acceleration -w^2 (cos, sin, 0), axes the
    body's turn times the frame's own; a point given in the frame's axes."""
    r = mb.simulate(spinning_rod(), 1.0, rtol=1e-10, atol=1e-12, n_out=11)
    tip = r.body("tip")
    c, s = np.cos(2 * r.t), np.sin(2 * r.t)
    zero = np.zeros_like(r.t)
    assert tip.position == pytest.approx(np.column_stack([c, s, zero]), abs=1e-8)
    assert tip.velocity == pytest.approx(2 * np.column_stack([-s, c, zero]), abs=1e-7)
    assert tip.acceleration == pytest.approx(-4 * np.column_stack([c, s, zero]), abs=1e-6)
    turn = np.array([[[ck, -sk, 0], [sk, ck, 0], [0, 0, 1]] for ck, sk in zip(c, s)])
    quarter = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])
    assert tip.rotation == pytest.approx(turn @ quarter, abs=1e-8)
    # 0.1 m along the frame's y axis is 0.1 m along global z (its y is turned onto z)
    assert r.point("tip", (0.0, 0.1, 0.0)) == pytest.approx(np.column_stack([c, s, zero + 0.1]), abs=1e-8)


def test_frames_and_shapes_travel_with_the_model():
    """Copies, pickles and deep copies keep the frames and shapes."""
    m = spinning_rod()
    for other in (m.copy(), pickle.loads(pickle.dumps(m)), copy.deepcopy(m)):
        assert other.frames["tip"].body == "rod"
        assert other.frames["tip"].position == pytest.approx([0.5, 0.0, 0.0])
        assert [(s.body, s.kind, s.size, s.role) for s in other.shapes] == [("rod", "cylinder", (0.02, 1.0), "visual")]
        assert other.shapes[0].position == pytest.approx([0.0, 0.0, 0.0])


def test_bad_frames_and_shapes_are_refused_by_name():
    m = spinning_rod()
    with pytest.raises(mb.ModelError, match="frame 'hinge': the name is taken"):
        m.add_frame("hinge", "rod", (0.0, 0.0, 0.0))
    with pytest.raises(mb.ModelError, match="frame 'tip': the name is taken"):
        m.add_frame("tip", "rod", (0.0, 0.0, 0.0))
    with pytest.raises(mb.ModelError, match="no body named 'arm'"):
        m.add_frame("elbow", "arm", (0.0, 0.0, 0.0))
    with pytest.raises(mb.ModelError, match="orientation is not a rotation matrix"):
        m.add_frame("skew", "rod", (0.0, 0.0, 0.0), orientation=np.diag([1.0, 1.0, -1.0]))
    with pytest.raises(mb.ModelError, match="kind must be one of box, cylinder, sphere, capsule, plane, mesh, got 'cone'"):
        m.add_shape("rod", "cone", (1.0, 1.0))
    with pytest.raises(mb.ModelError, match="a sphere's size must be positive"):
        m.add_shape("rod", "sphere", (-0.1,))
    with pytest.raises(mb.ModelError, match="a mesh names its file"):
        m.add_shape("rod", "mesh", (1.0, 1.0, 1.0))
    with pytest.raises(mb.ModelError, match="frames are spatial only"):
        mb.Model().add_frame("x", "ground", (0.0, 0.0, 0.0))
