"""Spatial mechanisms: rigid bodies with Euler parameters, checked against
closed-form motion (the heavy symmetric top), conservation laws, and the
same mechanisms built in the plane."""

import numpy as np
import pytest

import lagmb as mb

G = 9.81


def about(axis, angle):
    """Euler parameters (w, x, y, z) of a turn by `angle` about `axis`."""
    axis = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    return (float(np.cos(angle / 2)), *(float(c) for c in np.sin(angle / 2) * axis))


# --- the heavy symmetric top -------------------------------------------------
# Mass m, centre of mass at l from the fixed tip along the symmetry axis k,
# moments I1 (transverse, about the centre of mass) and I3 (axial); tilt
# theta from the vertical. Steady precession at rate Omega about the
# vertical with spin w3 = omega . k needs (Goldstein, "Classical Mechanics",
# sec. 5.7) m g l = Omega (I3 w3 - I1' Omega cos theta), I1' = I1 + m l^2 the
# transverse moment about the tip: the slow root below.
TOP = dict(m=1.0, l=0.1, I1=0.002, I3=0.004, theta=0.5)


def top_model(omega_about_vertical, w3, theta=TOP["theta"]):
    """The top tilted by theta in the x-z plane, turning with omega = Omega z
    + (w3 - Omega cos theta) k; its tip on a spherical joint at the origin."""
    m, l, I1, I3 = TOP["m"], TOP["l"], TOP["I1"], TOP["I3"]
    k = np.array([np.sin(theta), 0.0, np.cos(theta)])
    omega = omega_about_vertical * np.array([0.0, 0.0, 1.0]) + (w3 - omega_about_vertical * np.cos(theta)) * k
    model = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    top = model.add_body("top", m, (I1, I1, I3), tuple(l * k), orientation=about((0, 1, 0), theta),
                         velocity=tuple(np.cross(omega, l * k)), angular_velocity=tuple(omega))
    model.add_spherical("tip", model.ground, top, at=(0.0, 0.0, 0.0))
    return model


def steady_precession_rate(w3, theta=TOP["theta"]):
    m, l, I1, I3 = TOP["m"], TOP["l"], TOP["I1"], TOP["I3"]
    a, b, c = (I1 + m * l * l) * np.cos(theta), -I3 * w3, m * G * l
    return (-b - np.sqrt(b * b - 4 * a * c)) / (2 * a)


def symmetry_axis(result):
    return result.body("top").rotation[:, :, 2]


@pytest.mark.parametrize("formulation, integrator, rtol", [("projection", "erk", 1e-10), ("ggl", None, 1e-11)])
def test_steady_precession_keeps_its_tilt(formulation, integrator, rtol):
    """At the closed-form rate the tilt stays at theta within 1e-8 rad for
    10 s (about 4 precessions, 160 turns of spin), and the axis turns about
    the vertical at that rate."""
    w3 = 100.0
    Omega = steady_precession_rate(w3)
    r = mb.simulate(top_model(Omega, w3), 10.0, rtol=rtol, atol=1e-2 * rtol, formulation=formulation,
                    integrator=integrator, n_out=401)
    k = symmetry_axis(r)
    tilt = np.arccos(np.clip(k[:, 2], -1.0, 1.0))
    assert np.abs(tilt - TOP["theta"]).max() < 1e-8
    heading = np.unwrap(np.arctan2(k[:, 1], k[:, 0]))
    assert heading[-1] == pytest.approx(Omega * 10.0, rel=1e-8)


def test_precession_rate_off_the_closed_form_nutates():
    """The same top started without precession does not keep its tilt: the
    steady test above is not trivially satisfied."""
    r = mb.simulate(top_model(0.0, 100.0), 1.0, rtol=1e-10, atol=1e-12, formulation="projection",
                    integrator="erk")
    tilt = np.arccos(symmetry_axis(r)[:, 2])
    assert np.ptp(tilt) > 1e-3


def test_nutating_top_conserves_energy_vertical_momentum_and_spin():
    """Started spinning about its tilted axis only, the top nutates (its
    tilt swings by about 0.39 rad); energy, the angular momentum about the
    vertical through the tip and the spin omega . k stay constant to 1e-8."""
    r = mb.simulate(top_model(0.0, 60.0), 10.0, rtol=1e-11, atol=1e-13, formulation="projection",
                    integrator="erk", n_out=401)
    b = r.body("top")
    k = symmetry_axis(r)
    assert np.ptp(np.arccos(k[:, 2])) > 0.3
    J = np.diag([TOP["I1"], TOP["I1"], TOP["I3"]])
    H = np.einsum("kij,jl,kml,km->ki", b.rotation, J, b.rotation, b.angular_velocity)
    H += TOP["m"] * np.cross(b.position, b.velocity)
    spin = np.einsum("ki,ki->k", b.angular_velocity, k)
    for conserved in (r.energy, H[:, 2], spin):
        assert np.abs(conserved - conserved[0]).max() <= 1e-8 * np.abs(conserved[0])


def test_torque_free_body_keeps_its_angular_momentum():
    """A free asymmetric body in free fall: its centre of mass falls with
    g t^2 / 2, and its angular momentum A J' A^T omega stays fixed in space
    while omega itself wanders. (GGL: its outputs between steps come from
    BDF's own interpolant, accurate to the tolerance; the explicit method's
    quintic Hermite outputs are off by O(h^6), about 1e-8 here.)"""
    model = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    J = np.diag([0.1, 0.2, 0.3])
    body = model.add_body("b", 2.0, (0.1, 0.2, 0.3), (0.0, 0.0, 1.0), orientation=about((1, 1, 0), 0.4),
                          angular_velocity=(1.0, 2.0, 3.0))
    r = mb.simulate(model, 2.0, rtol=1e-11, atol=1e-13)
    b = r.body(body)
    assert np.abs(b.position[:, 2] - (1.0 - 0.5 * G * r.t**2)).max() < 1e-9
    H = np.einsum("kij,jl,kml,km->ki", b.rotation, J, b.rotation, b.angular_velocity)
    assert np.abs(H - H[0]).max() < 1e-9 * np.abs(H[0]).max()
    assert np.abs(b.angular_velocity - b.angular_velocity[0]).max() > 0.1


# --- planar mechanisms built from spatial parts ----------------------------
# Each body: (name, mass, J, position, angle, velocity, angular velocity);
# each joint: (kind, name, body_i, body_j, point[, axis]). The spatial copy
# puts everything at z = 0 with revolute axes along z and inertia (J, J, J).

CHAIN = ([(f"l{k}", 1.0 + 0.1 * k, 0.1, (0.5 + k, 0.0), 0.0, (0.0, 0.0), 0.0) for k in range(5)],
         [("revolute", "j0", "ground", "l0", (0.0, 0.0))] +
         [("revolute", f"j{k}", f"l{k - 1}", f"l{k}", (float(k), 0.0)) for k in range(1, 5)])
SLIDER_CRANK = ([("crank", 1.0, 0.01, (0.15, 0.0), 0.0, (0.0, 0.0), 0.0),
                 ("rod", 2.0, 0.2, (0.8, 0.0), 0.0, (0.0, 0.0), 0.0),
                 ("slider", 1.5, 0.01, (1.3, 0.0), 0.0, (0.0, 0.0), 0.0)],
                [("revolute", "o", "ground", "crank", (0.0, 0.0)), ("revolute", "a", "crank", "rod", (0.3, 0.0)),
                 ("revolute", "b", "rod", "slider", (1.3, 0.0)),
                 ("translational", "t", "ground", "slider", (1.3, 0.0), (1.0, 0.0))])
_A, _B, _C, _D = (np.array(p) for p in ((0.0, 0.0), (0.0, 0.5), (1.3, 0.8), (1.4, 0.0)))
FOUR_BAR = ([("crank", 1.0, 0.02, tuple((_A + _B) / 2), 0.0, (0.0, 0.0), 0.0),
             ("coupler", 2.0, 0.3, tuple((_B + _C) / 2), 0.0, (0.0, 0.0), 0.0),
             ("rocker", 1.5, 0.1, tuple((_C + _D) / 2), 0.0, (0.0, 0.0), 0.0)],
            [("revolute", "o", "ground", "crank", tuple(_A)), ("revolute", "b", "crank", "coupler", tuple(_B)),
             ("revolute", "c", "coupler", "rocker", tuple(_C)), ("revolute", "d", "rocker", "ground", tuple(_D))])


def build(dimension, bodies, joints):
    m = mb.Model(dimension=dimension, gravity=(0.0, -G) if dimension == 2 else (0.0, -G, 0.0))
    for name, mass, J, position, angle, velocity, spin in bodies:
        if dimension == 2:
            m.add_body(name, mass, J, position, angle=angle, velocity=velocity, angular_velocity=spin)
        else:
            m.add_body(name, mass, (J, J, J), (*position, 0.0), orientation=about((0, 0, 1), angle),
                       velocity=(*velocity, 0.0), angular_velocity=(0.0, 0.0, spin))
    for kind, name, body_i, body_j, at, *axis in joints:
        if dimension == 2:
            getattr(m, f"add_{kind}")(name, body_i, body_j, at, *axis)
        else:
            direction = (*axis[0], 0.0) if axis else (0.0, 0.0, 1.0)
            getattr(m, f"add_{kind}")(name, body_i, body_j, (*at, 0.0), direction)
    return m


def planar_path(r, body):
    """(x, y, angle) of a body's run, planar or spatial (angle about z)."""
    p = r.body(body)
    if r.model.dimension == 2:
        return np.column_stack([p.position, p.angle])
    assert np.abs(p.position[:, 2]).max() == 0.0  # nothing leaves the plane
    w, z = p.orientation[:, 0], p.orientation[:, 3]
    return np.column_stack([p.position[:, :2], np.unwrap(2 * np.arctan2(z, w))])


@pytest.mark.parametrize("mechanism", ["chain", "slider_crank", "four_bar"])
def test_planar_mechanism_from_spatial_parts_moves_as_in_the_plane(mechanism):
    """A five-link pendulum chain, a slider-crank and a four-bar falling
    under gravity for 2 s: the spatial copy follows the planar model to 1e-9
    (both at rtol 1e-13). In space the closed loops are overconstrained
    (every revolute also holds its axis): their 3 redundant equations are
    found and named, and dropped."""
    bodies, joints = {"chain": CHAIN, "slider_crank": SLIDER_CRANK, "four_bar": FOUR_BAR}[mechanism]
    runs = {}
    for dimension in (2, 3):
        model = build(dimension, bodies, joints)
        if dimension == 3 and mechanism != "chain":
            with pytest.warns(mb.RedundantConstraintWarning, match="3 constraint equation"):
                runs[3] = mb.simulate(model, 2.0, rtol=1e-13, atol=1e-15, formulation="projection",
                                      integrator="erk", n_out=21)
            assert len(runs[3].redundant_rows) == 3
        else:
            runs[dimension] = mb.simulate(model, 2.0, rtol=1e-13, atol=1e-15, formulation="projection",
                                          integrator="erk", n_out=21)
    for body in bodies:
        assert np.abs(planar_path(runs[3], body[0]) - planar_path(runs[2], body[0])).max() < 1e-9


# --- a spatial slider-crank driven at constant speed -----------------------
# The crank turns about the x axis at the origin (pin at R (0, cos th, sin th)),
# the slider runs along x on the line y = Y, z = Z, and the rod of length L
# joins them by a spherical joint at the crank and a universal joint at the
# slider (Haug's spatial slider-crank): 1 degree of freedom, taken by the
# driver. Closed form: s(th) = sqrt(L^2 - (R cos th - Y)^2 - (R sin th - Z)^2).
R_CRANK, L_ROD, Y_LINE, Z_LINE, RATE = 0.2, 1.0, 0.05, 0.1, 2 * np.pi
INERTIA = {"crank": (0.5, (0.002, 0.0005, 0.002)), "rod": (1.2, (0.1, 0.1, 0.001)),
           "slider": (2.0, (0.01, 0.01, 0.01))}


def spatial_slider_crank():
    s0 = np.sqrt(L_ROD**2 - (R_CRANK - Y_LINE) ** 2 - Z_LINE**2)
    pin, cross = np.array([0.0, R_CRANK, 0.0]), np.array([s0, Y_LINE, Z_LINE])
    along = (cross - pin) / L_ROD
    across = np.cross((0.0, 0.0, 1.0), along)
    across /= np.linalg.norm(across)
    rod_axes = np.column_stack([np.cross(across, along), across, along])  # rod's own z along it
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    crank = m.add_body("crank", *INERTIA["crank"], tuple(pin / 2))
    m.add_body("rod", *INERTIA["rod"], tuple((pin + cross) / 2), orientation=rod_axes)
    m.add_body("slider", *INERTIA["slider"], tuple(cross))
    m.add_revolute("main", m.ground, crank, (0.0, 0.0, 0.0), axis=(1.0, 0.0, 0.0))
    m.add_spherical("pin", crank, "rod", tuple(pin))
    m.add_universal("cross", "slider", "rod", tuple(cross), axis_i=(0.0, 0.0, 1.0), axis_j=tuple(across))
    m.add_translational("guide", m.ground, "slider", tuple(cross), axis=(1.0, 0.0, 0.0))
    m.drive_joint("motor", "main", mb.Linear(RATE))
    return m


@pytest.mark.parametrize("analysis, rtol", [("auto", 1e-6), ("dynamic", 1e-11)])
def test_spatial_slider_crank_follows_closed_form_kinematics(analysis, rtol):
    """Slider and crank pin against the closed form to 1e-8 m over two turns:
    by kinematic analysis (0 degrees of freedom) and by integrating the DAE."""
    model = spatial_slider_crank()
    assert model.degrees_of_freedom() == 0
    r = mb.simulate(model, 2.0, analysis=analysis, rtol=rtol, atol=1e-2 * rtol, n_out=201)
    assert r.stats["analysis"] == ("inverse_dynamics" if analysis == "auto" else "dynamic")
    th = RATE * r.t
    s = np.sqrt(L_ROD**2 - (R_CRANK * np.cos(th) - Y_LINE) ** 2 - (R_CRANK * np.sin(th) - Z_LINE) ** 2)
    slider = r.body("slider").position
    assert np.abs(slider[:, 0] - s).max() < 1e-8
    assert np.abs(slider[:, 1:] - (Y_LINE, Z_LINE)).max() < 1e-8
    pin = r.point("crank", (0.0, R_CRANK / 2, 0.0))  # the crank's centre is half way to the pin
    assert np.abs(pin - R_CRANK * np.column_stack([0 * th, np.cos(th), np.sin(th)])).max() < 1e-8


@pytest.mark.parametrize("analysis, rtol", [("auto", 1e-6), ("dynamic", 1e-11)])
def test_spatial_slider_crank_driver_torque_is_the_virtual_power(analysis, rtol):
    """The motor's torque times the crank's rate is the power the bodies
    take: sum of m v . (a - g) + omega . (I omega') (joints do no work), to
    1e-6 relative."""
    r = mb.simulate(spatial_slider_crank(), 2.0, analysis=analysis, rtol=rtol, atol=1e-2 * rtol, n_out=201)
    power = np.zeros(len(r))
    gravity = np.array([0.0, 0.0, -G])
    for name, (mass, moments) in INERTIA.items():
        b = r.body(name)
        inertia = np.einsum("kij,j,klj->kil", b.rotation, moments, b.rotation)  # A J' A^T
        power += mass * np.einsum("ki,ki->k", b.velocity, b.acceleration - gravity)
        power += np.einsum("ki,kij,kj->k", b.angular_velocity, inertia, b.angular_acceleration)
    torque = r.effort("motor")
    assert np.abs(torque - power / RATE).max() <= 1e-6 * np.abs(torque).max()


# --- a redundantly constrained loop -----------------------------------------

def spatial_parallelogram(driven=True, rate=0.0):
    """Crank A-B, coupler B-C and rocker C-D of a parallelogram in the plane
    z = 0 (A = 0, B = (0, 0.5), C = (1, 0.5), D = (1, 0)), joined by four
    revolutes with parallel axes along z: in space each revolute also holds
    its axis, so 3 of the 20 equations repeat others. Driven, the crank
    swings by +-1 rad about the upright, short of the flat (singular)
    positions at +-pi/2."""
    m = mb.Model(dimension=3, gravity=(0.0, -G, 0.0))
    for name, mass, centre, moments, spin, speed in (
            ("crank", 1.0, (0.0, 0.25, 0.0), (0.03, 0.001, 0.03), rate, 0.25 * rate),
            ("coupler", 2.0, (0.5, 0.5, 0.0), (0.001, 0.2, 0.2), 0.0, 0.5 * rate),
            ("rocker", 1.5, (1.0, 0.25, 0.0), (0.04, 0.001, 0.04), rate, 0.25 * rate)):
        m.add_body(name, mass, moments, centre, velocity=(-speed, 0.0, 0.0), angular_velocity=(0.0, 0.0, spin))
    z = (0.0, 0.0, 1.0)
    m.add_revolute("a", m.ground, "crank", (0.0, 0.0, 0.0), axis=z)
    m.add_revolute("b", "crank", "coupler", (0.0, 0.5, 0.0), axis=z)
    m.add_revolute("c", "coupler", "rocker", (1.0, 0.5, 0.0), axis=z)
    m.add_revolute("d", "rocker", m.ground, (1.0, 0.0, 0.0), axis=z)
    if driven:
        m.drive_joint("motor", "a", mb.Harmonic(1.0, RATE))
    return m


def test_redundant_spatial_parallelogram_is_found_named_and_runs():
    """rank() finds the 3 dependent equations at the start and names their
    joint; the run drops them (a warning names them), the coupler translates
    without turning as a parallelogram's must, and the reactions from the
    ground add up to what moves the bodies: sum m (a - g)."""
    model = spatial_parallelogram()
    rank = model.rank()
    assert len(rank["dependent_rows"]) == 3 and rank["degrees_of_freedom"] == 0
    named = {model.compiled().constraint_name_of_row(row) for row in rank["dependent_rows"]}
    assert named <= {"a", "b", "c", "d"}
    with pytest.warns(mb.RedundantConstraintWarning, match="3 constraint equation"):
        r = mb.simulate(model, 1.0, n_out=101)
    assert sorted(r.redundant_rows) == sorted(rank["dependent_rows"])
    th = np.sin(RATE * r.t)
    B = 0.5 * np.column_stack([-np.sin(th), np.cos(th), 0 * th])
    assert np.abs(r.body("coupler").position - (B + (0.5, 0.0, 0.0))).max() < 1e-9
    assert np.abs(r.body("coupler").orientation - (1.0, 0.0, 0.0, 0.0)).max() < 1e-9
    moving = sum(mass * (r.body(name).acceleration - (0.0, -G, 0.0))
                 for name, mass in (("crank", 1.0), ("coupler", 2.0), ("rocker", 1.5)))
    from_ground = r.reaction("a")[:, :3] - r.reaction("d")[:, :3]  # "d": the force on the ground
    assert np.abs(from_ground - moving).max() < 1e-9 * np.abs(moving).max()


def test_free_redundant_parallelogram_turns_through_its_flat_positions():
    """Undriven and started with the crank turning at 6 rad/s, the same loop
    goes over the top and through its flat (singular) positions. GGL at a
    tight tolerance stops at the first and names the dependent equations; ALI3-P with a
    fixed step (what that message advises) runs through: more than a full
    turn in 1 s, energy kept to its second-order error (4e-5 at h = 1 ms)."""
    model = spatial_parallelogram(driven=False, rate=6.0)
    with pytest.raises(mb.SimulationError, match="dead point"):  # (a failed run warns of nothing)
        mb.simulate(model, 1.0, rtol=1e-10, atol=1e-12)
    with pytest.warns(mb.RedundantConstraintWarning):
        r = mb.simulate(model, 1.0, formulation="ali3p", step=1e-3, n_out=101)
    p = r.body("crank").orientation
    assert np.unwrap(2 * np.arctan2(p[:, 3], p[:, 0]))[-1] > 2 * np.pi
    assert np.ptp(r.energy) < 1e-4 * np.abs(r.energy).max()
