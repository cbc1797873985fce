"""A reaction's torque about the joint (Result.reaction(..., about="joint")):
M_P = M_G + (r_G - r_P) x F, the moment Adams and Inventor report at a
joint, beside the default about the second body's centre of mass; checked
on a door's hinge and on pendulums, whose pins carry no torque (issue 56)."""

import math

import numpy as np
import pytest

import lagmb as mb

G = 9.81


def door(mass=30.0, lever=0.45):
    """A door hung on a hinge about the vertical z axis at the origin, its
    centre of mass `lever` m out along x: gravity cannot turn it, and the
    hinge holds its weight and the couple m g d that keeps it from tipping."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    m.add_body("door", mass=mass, inertia=(2.0, 3.0, 1.5), position=(lever, 0.0, 0.0))
    m.add_revolute("hinge", "ground", "door", at=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0))
    return m


def test_a_doors_hinge_holds_its_weights_couple():
    """At rest: the force on the door is m g up; about its centre of mass the
    hinge's torque is 0 (gravity acts there), about the hinge it is the
    weight's couple, (0, -m g d, 0) = 132.4 N m for 30 kg at 0.45 m (to
    1e-9 N m), in global and in the joint's axes (whose third is the hinge's
    axis: no torque about it); equilibrium reads the same."""
    mass, lever = 30.0, 0.45
    r = mb.simulate(door(mass, lever), 0.5, n_out=6)
    F = r.reaction("hinge")
    assert F[:, :3] == pytest.approx(np.tile([0.0, 0.0, mass * G], (6, 1)), abs=1e-9)
    assert np.max(np.abs(F[:, 3:])) <= 1e-9
    about = r.reaction("hinge", about="joint")
    assert about[:, :3] == pytest.approx(F[:, :3], abs=0)
    assert about[:, 3:] == pytest.approx(np.tile([0.0, -mass * G * lever, 0.0], (6, 1)), abs=1e-9)
    assert np.linalg.norm(about[0, 3:]) == pytest.approx(132.4, abs=0.1)
    local = r.reaction("hinge", frame="joint", about="joint")
    assert np.linalg.norm(local[:, 3:], axis=1) == pytest.approx(np.full(6, mass * G * lever), abs=1e-9)
    assert np.max(np.abs(local[:, 5])) <= 1e-9
    eq = mb.equilibrium(door(mass, lever), stability=False)  # (it turns freely about its hinge)
    assert eq.reaction("hinge", about="joint")[3:] == pytest.approx([0.0, -mass * G * lever, 0.0], abs=1e-9)
    assert eq.reaction("hinge", about="center of mass")[3:] == pytest.approx([0.0, 0.0, 0.0], abs=1e-9)


def test_a_swinging_planar_pendulums_pin_carries_no_torque():
    """A rod swinging on a pin: the pin's force acts at the pin, so its torque
    about the pin is 0 at every output (to 1e-12 N m) while about the rod's
    centre of mass it is (r_P - r_G) x F, nonzero; at rest both are 0."""
    m = mb.Model(gravity=(0.0, -G))
    m.add_body("rod", mass=2.0, inertia=2.0 / 12, position=(0.5, 0.0))
    m.add_revolute("pin", "ground", "rod", at=(0.0, 0.0))
    r = mb.simulate(m, 2.0, n_out=41, rtol=1e-10, atol=1e-12)
    F = r.reaction("pin")
    assert np.max(np.abs(r.reaction("pin", about="joint")[:, 2])) <= 1e-12
    # (the pin is at the origin; the rod's own pin point is off it by the constraint residual, ~1e-13 m,
    # which times |F| ~ 25 N reads up to 1.5e-12 N m here)
    G_from_P = r.body("rod").position
    assert F[:, 2] == pytest.approx(-(G_from_P[:, 0] * F[:, 1] - G_from_P[:, 1] * F[:, 0]), abs=1e-10)
    assert np.max(np.abs(F[:, 2])) > 1.0
    hanging = mb.Model(gravity=(0.0, -G))
    hanging.add_body("rod", mass=2.0, inertia=2.0 / 12, position=(0.0, -0.5), angle=-math.pi / 2)
    hanging.add_revolute("pin", "ground", "rod", at=(0.0, 0.0))
    rest = mb.simulate(hanging, 1.0, n_out=3).reaction("pin", about="joint")
    assert rest == pytest.approx(np.tile([0.0, 2.0 * G, 0.0], (3, 1)), abs=1e-12)


def test_a_spatial_pendulums_hinge_has_no_torque_about_its_axis():
    """A spatial rod swinging on a hinge about y, its centre of mass off the
    hinge's plane (so the hinge also holds a couple across its axis): about
    the hinge the torque along the axis is 0 (to 1e-10), about the centre
    of mass it is not; the two differ by (r_G - r_P) x F."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    m.add_body("rod", mass=1.5, inertia=(0.05, 0.06, 0.01), position=(0.4, 0.2, 0.0))
    m.add_revolute("hinge", "ground", "rod", at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0))
    r = mb.simulate(m, 1.5, n_out=31, rtol=1e-10, atol=1e-12)
    local = r.reaction("hinge", frame="joint", about="joint")
    assert np.max(np.abs(local[:, 5])) <= 1e-10
    assert np.max(np.abs(r.reaction("hinge", frame="joint")[:, 5])) > 0.1
    G_from_P = r.body("rod").position
    F = r.reaction("hinge")
    moved = F[:, 3:] + np.cross(G_from_P, F[:, :3])
    assert r.reaction("hinge", about="joint")[:, 3:] == pytest.approx(moved, abs=1e-12)


def test_a_weld_reads_about_body_js_centre_and_what_has_no_point_is_refused():
    """A weld's point is body_j's centre of mass (its rows hold it there): both
    readings agree. A driver has no point of its own: about="joint" names
    it; another `about` is refused."""
    m = mb.Model(gravity=(0.0, -G))
    m.add_body("beam", mass=3.0, inertia=0.2, position=(0.6, 0.0))
    m.add_weld("wall", "ground", "beam")
    r = mb.simulate(m, 0.2, n_out=3)
    assert np.array_equal(r.reaction("wall", about="joint"), r.reaction("wall"))
    assert r.reaction("wall")[0] == pytest.approx([0.0, 3.0 * G, 0.0], abs=1e-9)

    c = mb.Model(gravity=(0.0, -G))
    c.add_body("crank", mass=1.0, inertia=0.1, position=(0.5, 0.0))
    pin = c.add_revolute("pin", "ground", "crank", at=(0.0, 0.0))
    c.drive_joint("motor", pin, mb.Linear(1.0))
    r = mb.simulate(c, 0.5, n_out=3)
    with pytest.raises(mb.ModelError, match=r"'motor' \(joint driver\) has no point of its own .* about its "
                                            "second body's centre of mass"):
        r.reaction("motor", about="joint")
    with pytest.raises(mb.ModelError, match="about must be 'centre of mass' .* or 'joint'"):
        r.reaction("pin", about="pin")
