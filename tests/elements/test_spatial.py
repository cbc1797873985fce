"""Spatial mechanisms: rigid bodies with Euler parameters, checked against
closed-form motion (the heavy symmetric top), conservation laws, and the
same mechanisms built in the plane."""

import math
import warnings

import numpy as np
from scipy.spatial.transform import Rotation
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
    turn in 1 s, energy kept to its second-order error (4e-5 at h = 1 ms).
    So does the default (formulation "auto": the explicit projection method,
    whose accelerations come from the augmented system, defined at the flat
    positions): energy to 1e-6 relative, never gained, and the end where
    ALI3-P at h = 0.1 ms ends, to 1e-5 (seen 4.7e-7). The energy is lost in
    the two steps that end nearest the two flat positions the run passes,
    where Phi_q loses rank and the velocity projection takes the velocity
    along the row that is becoming dependent: how much depends on how near
    a step ends, which rounding decides (relative losses of 5e-12 to 2.5e-7
    over rtol = 0.8e-10 .. 1.25e-10, before and after the body rates of
    the augmented system's Schur complement, 2026-12-08; 4e-10 with
    Fehlberg 7(8), whose steps ended elsewhere)."""
    model = spatial_parallelogram(driven=False, rate=6.0)
    with pytest.warns(mb.RedundantConstraintWarning):
        default = mb.simulate(model, 1.0, rtol=1e-10, atol=1e-12)
        fine = mb.simulate(model, 1.0, formulation="ali3p", step=1e-4, n_out=2)
    assert default.stats["method_choice"].startswith("auto: projection-erk")
    assert np.ptp(default.energy) < 1e-6 * np.abs(default.energy).max()
    assert default.energy.max() <= default.energy[0] * (1.0 + 1e-12)
    assert np.abs(default.q[-1] - fine.q[-1]).max() < 1e-5
    with pytest.raises(mb.SimulationError, match="dead point"):  # (a failed run warns of nothing)
        mb.simulate(model, 1.0, rtol=1e-10, atol=1e-12, formulation="ggl")
    with pytest.warns(mb.RedundantConstraintWarning):
        r = mb.simulate(model, 1.0, formulation="ali3p", step=1e-3, n_out=101)
    p = r.body("crank").orientation
    assert np.unwrap(2 * np.arctan2(p[:, 3], p[:, 0]))[-1] > 2 * np.pi
    assert np.ptp(r.energy) < 1e-4 * np.abs(r.energy).max()


# --- every method, reactions ------------------------------------------------

def double_pendulum_with_spring():
    """Two bodies in general orientations: a spherical joint to the ground, a
    universal joint between them, a spring-damper to the ground."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    a = m.add_body("a", 1.0, (0.02, 0.03, 0.01), (0.3, 0.0, -0.2), orientation=about((1, 2, 3), 0.4),
                   velocity=(0.0, 1.0, 0.0), angular_velocity=(0.5, 1.0, -2.0))
    b = m.add_body("b", 0.7, (0.01, 0.02, 0.02), (0.8, 0.1, -0.5), orientation=about((0, 1, 0), 0.7))
    m.add_spherical("ball", m.ground, a, (0.0, 0.0, 0.0))
    m.add_universal("cross", a, b, (0.6, 0.05, -0.35), axis_i=(0.0, 0.0, 1.0), axis_j=(1.0, 0.0, 0.0))
    m.add_spring_damper("spring", m.ground, (0.5, 0.5, 0.0), b, (0.8, 0.1, -0.5), stiffness=50.0, damping=0.5)
    return m


@pytest.fixture(scope="module")
def double_pendulum_reference():
    return mb.simulate(double_pendulum_with_spring(), 2.0, rtol=1e-12, atol=1e-14, formulation="projection",
                       integrator="erk", n_out=11)


BOUNDS = {"ggl": 1e-6, "index3": 1e-3, "index1": 1e-6, "projection-bdf": 1e-5, "projection-adams": 1e-5,
          "projection-erk": 1e-6, "ali3p": 1e-5}


@pytest.mark.parametrize("method", [m["name"] for m in mb.methods()])
def test_every_method_runs_a_spatial_mechanism(method, double_pendulum_reference):
    """Each formulation and integrator of the planar library integrates the
    spatial double pendulum (rtol 1e-8) close to a tight reference, and keeps
    the constraints, the normalization of the Euler parameters among them."""
    assert set(BOUNDS) == {m["name"] for m in mb.methods()}
    spec = next(m for m in mb.methods() if m["name"] == method)
    options = dict(formulation=spec["formulation"], integrator=spec["integrator"])
    if spec["fixed_step"]:  # no error control: a step, no tolerances
        options["step"] = 1e-4
    else:
        options.update(rtol=1e-8, atol=1e-10)
    if spec["drifts"]:
        options["baumgarte"] = (10.0, 10.0)
    r = mb.simulate(double_pendulum_with_spring(), 2.0, n_out=11, **options)
    assert np.abs(r.q - double_pendulum_reference.q).max() < BOUNDS[method]
    # a drifting method holds the constraints only to its local errors,
    # damped by Baumgarte's terms: projection-adams was seen at 4.6e-8 and,
    # after the Schur complement's sums were regrouped (rounding, a different
    # step sequence), at 1.3e-7
    assert np.abs(r.residual).max() < (3e-7 if spec["drifts"] else 1e-7)
    p = r.q[:, 3:7]
    assert np.abs(np.linalg.norm(p, axis=1) - 1.0).max() < 1e-7


def hinge_pendulum():
    """A body on a revolute with a tilted axis through (0, 0, 0)."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    m.add_body("arm", 2.0, (0.05, 0.02, 0.04), (0.4, 0.1, -0.3), orientation=about((1, 1, 1), 0.5))
    m.add_revolute("hinge", m.ground, "arm", (0.0, 0.0, 0.0), axis=(0.2, 1.0, 0.3))
    return m


def test_hinge_reaction_moves_the_body_and_has_no_moment_about_its_axis():
    """The reaction on the arm (k, 6) is its force m (a - g) and a moment about
    its centre; about the hinge point that moment has no part along the axis,
    the third of the joint's axes (frame="joint")."""
    r = mb.simulate(hinge_pendulum(), 1.0, rtol=1e-10, atol=1e-12, n_out=21)
    arm = r.body("arm")
    reaction = r.reaction("hinge")
    assert reaction.shape == (21, 6)
    assert np.abs(reaction[:, :3] - 2.0 * (arm.acceleration - (0.0, 0.0, -G))).max() < 1e-8
    couple = reaction[:, 3:] - np.cross(-arm.position, reaction[:, :3])  # moment about the hinge point
    axis = np.array([0.2, 1.0, 0.3]) / np.linalg.norm([0.2, 1.0, 0.3])
    assert np.abs(couple @ axis).max() < 1e-8 * np.abs(couple).max()
    in_joint = r.reaction("hinge", frame="joint")
    assert np.abs(np.linalg.norm(in_joint[:, :3], axis=1) - np.linalg.norm(reaction[:, :3], axis=1)).max() < 1e-10
    assert np.abs(in_joint[:, 2] - reaction[:, :3] @ axis).max() < 1e-10  # the ground's axes do not turn


def test_spatial_equilibrium_of_a_spring_hung_body():
    """A bar on a spherical joint held by a spring from a fixed point:
    equilibrium finds the position where, at rest, it stays at rest."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    m.add_body("bar", 1.0, (0.01, 0.08, 0.08), (0.5, 0.0, 0.0))
    m.add_spherical("pivot", m.ground, "bar", (0.0, 0.0, 0.0))
    m.add_spring_damper("spring", m.ground, (1.0, 0.0, 1.0), "bar", (1.0, 0.0, 0.0), stiffness=100.0,
                        free_length=0.5)
    eq = mb.equilibrium(m)
    qdd = mb.solve_accelerations(m, eq.q, np.zeros_like(eq.q))[0]
    assert np.abs(qdd).max() < 1e-9  # at rest it stays at rest
    assert abs(eq.q[1]) < 1e-12  # in the plane of the pivot, the anchor and gravity
    assert eq.q[2] != 0.0  # not where it started: the spring and gravity moved it


def test_spatial_equilibrium_of_a_block_on_a_bushing_is_one_newton_step():
    """A 2 kg block on a bushing of 100 N/m in each direction sags by
    m g / k = 0.1962 m; the equations are linear in its position, so Newton
    lands there at once (it used to creep 0.5 mm per iteration, the model's
    extent being 0, and give up)."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    block = m.add_body("block", 2.0, (0.1, 0.1, 0.1), position=(0.0, 0.0, -1.0))
    m.add_bushing("mount", m.ground, block, at=(0.0, 0.0, -1.0), stiffness=(100.0,) * 3,
                  rotational_stiffness=(1.0, 1.0, 1.0))
    eq = mb.equilibrium(m)
    pose = eq.body(block)
    assert pose.position.shape == (3,) and pose.orientation.shape == (4,) and pose.rotation.shape == (3, 3)
    assert np.allclose(pose.position, (0.0, 0.0, -1.0 - 2.0 * G / 100.0), atol=1e-12)
    assert np.allclose(pose.orientation, (1.0, 0.0, 0.0, 0.0), atol=1e-12)
    assert eq.iterations <= 3
    r = mb.simulate(m, 0.5, start="equilibrium")
    assert np.abs(r.body(block).position - pose.position).max() < 1e-9  # it stays there


def test_spatial_equilibrium_of_a_block_on_a_vertical_slider_with_a_spring():
    """A 2 kg block on a vertical translational joint, hung from a spring of
    100 N/m at its free length: it comes to rest m g / k lower."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    block = m.add_body("block", 2.0, (0.1, 0.1, 0.1), position=(0.0, 0.0, 1.0))
    m.add_translational("slider", m.ground, block, at=(0.0, 0.0, 1.0), axis=(0.0, 0.0, 1.0))
    m.add_spring_damper("spring", m.ground, (0.0, 0.0, 2.0), block, (0.0, 0.0, 1.0), stiffness=100.0)
    eq = mb.equilibrium(m)
    assert np.allclose(eq.body(block).position, (0.0, 0.0, 1.0 - 2.0 * G / 100.0), atol=1e-12)
    assert eq.iterations <= 3
    r = mb.simulate(m, 0.5, start="equilibrium")
    assert abs(r.body(block).position[-1, 2] - (1.0 - 2.0 * G / 100.0)) < 1e-9


# --- a revolute driver holds the angle it is given ------------------------------------
# Its row used to be sin(theta - f) = 0, whose second root theta = f - pi
# the assembly found from a start more than pi/2 away: the rod settled half
# a turn off with a residual of 1e-16.


def hinge_angle(orientation):
    """The turn about z of Euler parameters (w, 0, 0, z), in (-pi, pi]."""
    p = np.atleast_2d(orientation)
    return 2.0 * np.arctan2(p[:, 3], p[:, 0])


def wrapped(angle):
    return np.remainder(np.asarray(angle) + np.pi, 2.0 * np.pi) - np.pi


def driven_rod(f, pendulum=False):
    """A rod along +x hinged about z at the origin, its angle driven by f;
    with a pendulum on a spherical joint at its tip (a dynamic model)."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    rod = m.add_body("rod", 1.0, (1e-3, 1.0 / 12.0, 1.0 / 12.0), position=(0.5, 0.0, 0.0))
    m.add_revolute("hinge", m.ground, rod, at=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0))
    m.drive_joint("motor", "hinge", f)
    if pendulum:
        bob = m.add_body("bob", 0.5, (1e-3, 1e-3, 1e-3), position=(1.0, 0.0, -0.5))
        m.add_spherical("tip", rod, bob, at=(1.0, 0.0, 0.0))
    return m


DRIVER_MOTIONS = {
    "constant 3": mb.Constant(3.0),
    "constant -1.7": mb.Constant(-1.7),
    "constant 4 (past pi)": mb.Constant(4.0),
    "ramp from 2": mb.Linear(1.0, start=2.0),
    "harmonic about 2.5": mb.Harmonic(0.5, 3.0, offset=2.5),
    "spline from 2": mb.Spline([0.0, 0.05, 0.1], [2.0, 2.2, 2.1]),
}


@pytest.mark.parametrize("motion", DRIVER_MOTIONS.values(), ids=DRIVER_MOTIONS.keys())
def test_a_revolute_driver_holds_its_angle_from_any_start(motion):
    with pytest.warns(mb.AssemblyWarning, match="'rod' by"):  # it starts at 0 rad, the driver elsewhere
        r = mb.simulate(driven_rod(motion), 0.1, n_out=11)
    commanded = np.array([motion(t)[0] for t in r.t])
    assert np.abs(wrapped(hinge_angle(r.body("rod").orientation) - commanded)).max() < 1e-9


@pytest.mark.parametrize("formulation, integrator", [("ggl", None), ("projection", "erk")])
@pytest.mark.filterwarnings("ignore::lagmb.AssemblyWarning")  # the rod starts at 0 rad, the driver at 2
def test_a_revolute_driver_holds_its_angle_in_a_dynamic_run(formulation, integrator):
    motion = mb.Linear(1.0, start=2.0)
    r = mb.simulate(driven_rod(motion, pendulum=True), 0.2, n_out=11, formulation=formulation,
                    integrator=integrator, rtol=1e-8)
    assert r.stats["steps"] > 0
    assert np.abs(wrapped(hinge_angle(r.body("rod").orientation) - (2.0 + r.t))).max() < 1e-6


def test_a_revolute_driver_input_jumping_by_pi_or_more_is_followed():
    sim = mb.Simulator(driven_rod(mb.Input(0.0, name="angle"), pendulum=True), rtol=1e-8)
    sim.advance(0.01)
    for value in (3.0, 3.5, -3.0, 6.5, -0.2):  # jumps of 3, 0.5, 6.5, 9.5 and 6.7 rad
        sim.set_input("angle", value)
        sim.advance(sim.t + 0.01)
        assert abs(wrapped(hinge_angle(sim.body("rod").orientation)[0] - value)) < 1e-9, value


def test_a_driven_angle_no_configuration_reaches_is_an_assembly_error():
    m = driven_rod(mb.Constant(1.0))
    m.add_spherical("locked", m.ground, "rod", at=(1.0, 0.0, 0.0))  # the tip held where it is
    with pytest.raises(mb.AssemblyError):
        mb.simulate(m, 0.1)


# --- bad input ----------------------------------------------------------------

@pytest.mark.parametrize("call, message", [
    (lambda m: m.add_body("b", 1.0, (0.1, 0.1, 0.1), orientation=(1.0, 0.1, 0.0, 0.0)), "unit quaternion"),
    (lambda m: m.add_body("b", 1.0, (0.1, 0.1, 0.1), orientation=np.diag([1.0, 1.0, -1.0])), "rotation matrix"),
    (lambda m: m.add_body("b", 1.0, (0.1, 0.1, 0.1), orientation=(1.0, 0.0, 0.0)), "unit quaternion"),
    (lambda m: m.add_body("b", 1.0, (0.1, 0.1, 0.5)), "triangle inequality"),
    (lambda m: m.add_body("b", 1.0, (-0.1, 0.1, 0.1)), "positive semi-definite"),
    (lambda m: m.add_body("b", 1.0, ((0.1, 0.2, 0.0), (0.0, 0.1, 0.0), (0.0, 0.0, 0.1))), "symmetric"),
    (lambda m: m.add_body("b", -1.0, (0.1, 0.1, 0.1)), "mass must be positive"),
    (lambda m: m.add_body("b", 1.0, (0.1, 0.1, 0.1), position=(0.0, 0.0)), r"three numbers \(x, y, z\)"),
    (lambda m: m.add_body("b", 1.0, (0.1, 0.1, 0.1), velocity=(0.0, np.nan, 0.0)), "not finite"),
    (lambda m: m.add_revolute("r", m.ground, "a", (0.0, 0.0, 0.0), axis=(0.0, 0.0, 0.0)), "non-zero vector"),
    (lambda m: m.add_universal("u", m.ground, "a", (0.0, 0.0, 0.0), axis_i=(1.0, 0.0, 0.0),
                               axis_j=(1.0, 1.0, 0.0)), "perpendicular"),
    (lambda m: m.add_distance("d", m.ground, (1.0, 0.0, 0.0), "a", (1.0, 0.0, 0.0)), "length must be positive"),
    (lambda m: m.drive_joint("motor", "ball", 0.0), "not a revolute, cylindrical or translational joint"),
    (lambda m: m.add_rotational_spring_damper("t", "nothing", stiffness=1.0), "not a joint of this model"),
    (lambda m: m.add_force("f", "a", (1.0, 2.0)), r"\(x, y, z\) components"),
    (lambda m: m.add_bushing("bu", m.ground, "a", (0.0, 0.0, 0.0), stiffness=(-1.0, 0.0, 0.0)), "must be >= 0"),
    (lambda m: m.add_revolute("r", "a", "a", (0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0)), "to itself"),
])
def test_bad_spatial_input_is_a_model_error_naming_it(call, message):
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    m.add_body("a", 1.0, (0.1, 0.1, 0.1), (0.0, 0.0, -1.0))
    m.add_spherical("ball", m.ground, "a", (0.0, 0.0, 0.0))
    with pytest.raises(mb.ModelError, match=message):
        call(m)
    assert [kw["name"] for _, kw in m.elements] == ["a", "ball"]  # nothing half added


@pytest.mark.parametrize("kwargs, message", [
    (dict(dimension=4), "dimension must be 2"), (dict(dimension=True), "dimension must be 2"),
    (dict(dimension=3, gravity=(0.0, -9.81)), r"three numbers \(x, y, z\)"),
    (dict(gravity=(0.0, -9.81, 0.0)), "pair of numbers"),
])
def test_bad_model_dimension_or_gravity(kwargs, message):
    with pytest.raises(mb.ModelError, match=message):
        mb.Model(**kwargs)


# --- a long chain -----------------------------------------------------------

def spatial_chain(n, link=0.1):
    """n links along x, a spherical joint at the ground and universal joints
    between links, each link's own z axis along it."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    previous = m.ground
    for k in range(n):
        body = m.add_body(f"l{k}", 0.1, (1e-4, 1e-4, 1e-5), ((k + 0.5) * link, 0.0, 0.0),
                          orientation=about((0, 1, 0), np.pi / 2))
        if k == 0:
            m.add_spherical("j0", previous, body, (0.0, 0.0, 0.0))
        else:
            m.add_universal(f"j{k}", previous, body, (k * link, 0.0, 0.0), axis_i=(0.0, 1.0, 0.0),
                            axis_j=(0.0, 0.0, 1.0))
        previous = body
    return m


def test_a_thousand_body_spatial_chain_costs_the_same_per_body():
    """What a step costs, counted: the Cholesky factor of the range-space
    system grows by the same 26 entries per link from 100 to 1,000 links
    (35 while S held each body's normalization row, before 2026-12-08), and
    an explicit run evaluates each element the same number of times per
    right-hand side. (Times per step and link: bench/performance/spatial_chain.py.)"""
    runs = {n: mb.simulate(spatial_chain(n), 0.005, formulation="projection", integrator="erk", n_out=2)
            for n in (100, 1000)}
    nonzeros = {n: r.stats["factor_nonzeros"] for n, r in runs.items()}
    assert nonzeros[1000] - nonzeros[100] == 26 * 900
    per_element = {n: r.stats["element_evaluations"] / (r.stats["residual_evals"] * (3 * n)) for n, r in runs.items()}
    assert per_element[1000] == pytest.approx(per_element[100], rel=0.05)
    z = runs[1000].body("l999").position[-1, 2]
    assert z == pytest.approx(-0.5 * G * 0.005**2, rel=1e-3)  # the free end falls freely at first


def test_ggl_newton_factors_grow_linearly_on_a_revolute_chain():
    """KLU's LU of GGL's Newton matrix on a chain of spatial revolutes (axes
    alternating between y and z) keeps the same nonzeros per link from 20 to
    80 links: the ordering holds the fill down. (Declaring the revolute's dot
    rows without their zero position columns once made these factors fill
    so that 128 links ran 60 times slower.)"""
    def chain(n):
        m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
        previous = m.ground
        for k in range(n):
            body = m.add_body(f"l{k}", 1.0, (1e-4, 1 / 12, 1 / 12), ((k + 0.5), 0.0, 0.0))
            m.add_revolute(f"j{k}", previous, body, at=(float(k), 0.0, 0.0),
                           axis=(0.0, 1.0, 0.0) if k % 2 == 0 else (0.0, 0.0, 1.0))
            previous = body
        return m

    per_link = {n: mb.simulate(chain(n), 0.01, formulation="ggl", n_out=2).stats["lu_nonzeros"] / n for n in (20, 80)}
    assert per_link[80] == pytest.approx(per_link[20], rel=0.05)
    assert per_link[80] < 1500  # (1,300 seen: about 50 per unknown)


def test_work_precision_of_a_spatial_mechanism():
    """The work-precision sweep runs on a spatial model: each method's error
    against the shared reference falls as the tolerance does."""
    # (5 outputs: the explicit method steps to every output, and at 101 of
    # them its steps, not the tolerance, would set its error)
    wp = mb.work_precision(double_pendulum_with_spring(), 1.0, methods=["ggl", "projection-erk"],
                           tolerances=[1e-4, 1e-6, 1e-8], n_out=5)
    for method in ("ggl", "projection-erk"):
        errors = [row["error"] for row in wp.rows if row["method"] == method]
        assert len(errors) == 3 and errors[2] < 1e-2 * errors[0]


def test_random_spatial_input_is_taken_or_refused_by_name_never_crashes():
    """Every spatial add_* and drive_* method with random values (finite,
    huge, NaN, zero vectors, wrong shapes): each call adds its element or
    raises ModelError; what was added compiles and starts (or is refused by
    an AssemblyError / SimulationError naming why), never anything else."""
    from lagmb.registry import SPATIAL_KINDS

    rng = np.random.default_rng(20261124)
    junk = [np.nan, np.inf, 1e308, -1.0, 0.0, (0.0, 0.0, 0.0), (1.0, 2.0), "x", None, ((1, 0, 0), (0, 1, 0)),
            ((1, 0, 0), (0, 1, 0), (0, 0, 1)), (1.0, 0.0, 0.0, 0.0)]

    def value(param, bodies, joints):
        if param.type == "body":
            return rng.choice(["ground"] + bodies) if bodies else "ground"
        if param.type == "joint":
            return rng.choice(joints) if joints else "none"
        if rng.random() < 0.1:
            return junk[rng.integers(len(junk))]
        if param.type in ("vec3", "inertia"):
            return tuple(rng.uniform(0.01, 1.0, 3))
        if param.type == "orientation":
            q = rng.standard_normal(4)
            return tuple(q / np.linalg.norm(q))
        if param.type == "function_triple":
            return tuple(rng.uniform(-1, 1, 3))
        if param.type == "choice":
            return rng.choice(param.choices)
        if param.type == "bool":
            return bool(rng.integers(2))
        return float(rng.uniform(0.01, 2.0))

    outcomes = {"added": 0, "refused": 0}
    for trial in range(40):
        m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
        bodies, joints = [], []
        for i in range(12):
            kind = SPATIAL_KINDS[rng.integers(len(SPATIAL_KINDS))] if i >= 3 else SPATIAL_KINDS[0]
            args = {p.name: value(p, bodies, joints) for p in kind.params if p.required or rng.random() < 0.5}
            try:
                getattr(m, kind.method)(f"e{i}", **args)
            except mb.ModelError:
                outcomes["refused"] += 1
                continue
            outcomes["added"] += 1
            if kind.role == "body":
                bodies.append(f"e{i}")
            elif kind.role == "joint":
                joints.append(f"e{i}")
        try:
            with warnings.catch_warnings():  # random loops repeat equations and start far from closed: fine here
                warnings.simplefilter("ignore", mb.RedundantConstraintWarning)
                warnings.simplefilter("ignore", mb.AssemblyWarning)
                mb.simulate(m, 0.01, n_out=2, max_steps=2000)
        except (mb.ModelError, mb.SimulationError):
            pass  # refused by name (AssemblyError is a SimulationError): not a crash
    assert outcomes["added"] > 100 and outcomes["refused"] > 50


# --- hard cases -------------------------------------------------------------

def test_stiff_bushing_settles_at_its_static_deflection():
    """A 2 kg block on a bushing of 1e8 N/m (and 1e6 N m/rad), damped near
    critically: the stiff, implicit case. It settles at m g / k below its
    start, with no tilt (the bushing's point is its centre of mass)."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    m.add_body("block", 2.0, (0.01, 0.02, 0.03), (0.0, 0.0, 0.0))
    k, c = 1e8, 2 * np.sqrt(1e8 * 2.0)
    m.add_bushing("mount", m.ground, "block", (0.0, 0.0, 0.0), stiffness=(k, k, k), damping=(c, c, c),
                  rotational_stiffness=(1e6, 1e6, 1e6), rotational_damping=(1e3, 1e3, 1e3))
    r = mb.simulate(m, 0.05, rtol=1e-8, atol=1e-12)
    assert r.body("block").position[-1, 2] == pytest.approx(-2.0 * G / k, rel=1e-6)
    assert np.abs(r.body("block").orientation[-1] - (1.0, 0.0, 0.0, 0.0)).max() < 1e-12
    assert r.stats["steps"] < 2000  # BDF steps over the fast mode once it has died out


def test_extreme_mass_ratio_double_pendulum_conserves_energy():
    """A 1 g body hanging from a 1 t body on spherical joints (mass ratio
    1e6): the light one swings fast, the heavy one slowly; energy stays put
    to 1e-6 of the total at rtol 1e-10 (measured 2.2e-7; the planar model of
    the same pendulum drifts by 3.9e-7 at that tolerance)."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    m.add_body("heavy", 1e3, (10.0, 10.0, 10.0), (0.5, 0.0, 0.0), velocity=(0.0, 0.1, 0.0))
    m.add_body("light", 1e-3, (1e-6, 1e-6, 1e-6), (1.5, 0.0, 0.0))
    m.add_spherical("top", m.ground, "heavy", (0.0, 0.0, 0.0))
    m.add_spherical("link", "heavy", "light", (1.0, 0.0, 0.0))
    r = mb.simulate(m, 2.0, rtol=1e-10, atol=1e-12)
    assert np.ptp(r.energy) < 1e-6 * np.abs(r.energy).max()
    assert np.ptp(r.body("light").position[:, 2]) > 0.1


def test_a_body_without_a_moment_about_one_axis_is_refused_for_dynamics():
    """A thin rod given no moment about its own axis leaves that spin
    undetermined: a dynamic run refuses it by name (it may still be moved by
    drivers in a kinematic analysis)."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    m.add_body("rod", 1.0, (0.0, 0.1, 0.1), (1.0, 0.0, 0.0))
    m.add_spherical("pivot", m.ground, "rod", (0.0, 0.0, 0.0))
    with pytest.raises(mb.ModelError, match=r"the motion is not determined by the forces.*massless: 'rod' \(mass 1, "
                                            r"principal moments \(0, 0.1, 0.1\)\)"):
        mb.simulate(m, 0.1)


def test_attachments_of_a_spatial_element_are_three_dimensional():
    """Model.attachments gives each body's local point (x, y, z) in space:
    a hinge at the origin sits at the rod's -0.5 m end along its axis x."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -G))
    rod = m.add_body("rod", mass=1.0, inertia=(1e-4, 1 / 12, 1 / 12), position=(0.5, 0.0, 0.0))
    m.add_revolute("hinge", m.ground, rod, at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0))
    assert m.attachments("hinge") == [("ground", (0.0, 0.0, 0.0)), ("rod", (-0.5, 0.0, 0.0))]


def test_a_joint_built_at_an_angle_or_slide_reads_it():
    """A revolute given angle=0.7 and a translational given slide=0.25 read
    those values in the initial configuration (the rod hangs 0.7 rad down
    from level about y; the block sits 0.25 m along the rail from `at`): a
    driver holding 0.7 does nothing there (effort = the rod's weight's
    moment m g r cos 0.7), and the rail's slide stays 0.25 with the rail
    level."""
    m = mb.Model(dimension=3, gravity=(0.0, 0.0, -9.81))
    c, s = math.cos(0.7), math.sin(0.7)
    # turned 0.7 about +y: the rod's axis x goes to (cos, 0, -sin)
    rod = m.add_body("rod", 1.0, (1e-3, 1 / 12, 1 / 12), position=(0.5 * c, 0.0, -0.5 * s),
                     orientation=((c, 0.0, s), (0.0, 1.0, 0.0), (-s, 0.0, c)))
    m.add_revolute("hinge", m.ground, rod, at=(0.0, 0.0, 0.0), axis=(0.0, 1.0, 0.0), angle=0.7)
    m.drive_joint("hold", "hinge", 0.7)
    block = m.add_body("block", 2.0, (0.1, 0.1, 0.1), position=(2.25, 0.0, 0.0))
    m.add_translational("rail", m.ground, block, at=(2.0, 0.0, 0.0), axis=(1.0, 0.0, 0.0), slide=0.25)
    r = mb.simulate(m, 0.2, n_out=3, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(r.joint("hinge").angle, 0.7, atol=1e-10)
    np.testing.assert_allclose(r.joint("rail").slide, 0.25, atol=1e-10)
    np.testing.assert_allclose(r.effort("hold"), -9.81 * 0.5 * c, rtol=1e-8)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_a_zero_principal_moment_given_in_other_axes_is_zero(seed):
    """A rod (1 kg, moments 0.1, 0.1, 0 kg m^2 about its centre 0.5 m from
    a ball joint) given once by its tensor turned to the world's axes (its
    zero moment then reads as +-1e-17) and once by its principal moments
    with the body turned: the same body, the same fall (1e-8 m at rtol
    1e-10). Found in the URDF work: a moment of +7e-18 passed as inertia,
    and its inverse, 1e17, made the start non-finite or IDA fail; a moment
    within 1e-12 of the largest is now 0 (the body runs on the augmented
    system's LU) wherever the core asks."""
    rotation = Rotation.random(random_state=seed)
    R = rotation.as_matrix()
    x, y, z, w = rotation.as_quat()

    def rod(inertia, orientation):
        m = mb.Model(dimension=3, gravity=(0.0, 0.0, -9.81))
        body = m.add_body("rod", mass=1.0, inertia=inertia, position=(0.5, 0.0, 0.0), orientation=orientation)
        m.add_spherical("ball", m.ground, body, at=(0.0, 0.0, 0.0))
        return mb.simulate(m, t_end=0.5, n_out=6, rtol=1e-10, atol=1e-12)

    turned = rod(R @ np.diag([0.1, 0.1, 0.0]) @ R.T, (1.0, 0.0, 0.0, 0.0))
    principal = rod((0.1, 0.1, 0.0), (w, x, y, z))
    assert np.all(np.isfinite(turned.q))
    assert np.max(np.abs(turned.q[:, :3] - principal.q[:, :3])) <= 1e-8
    assert turned.q[-1, 2] < -0.04  # it fell
