"""The example scripts and scenes a new user starts from.

Each examples/*.py script runs in a fresh interpreter (sys.executable), must
exit 0, and prints lines "label = number ...": the numbers are parsed here
and compared with closed forms derived in each test's docstring (the scripts
print their own closed forms too; the tests recompute them independently).
The examples/*.toml scenes run through mb.load_scene(path).run() when the
scene reader is available.
"""

import math
import os
import re
import subprocess
import sys

import numpy as np
import pytest
from scipy.special import ellipk

import lagmb as mb

from paths import EXAMPLES  # noqa: E402
G = 9.81

SCRIPTS = ["seed_pendulum", "double_pendulum", "slider_crank", "four_bar", "quick_return",
           "gear_train", "spring_damper", "bouncing_ball", "door_stop", "rolling_disk", "cam_follower", "panda",
           "mjcf_four_bar", "incline", "go1_drop"]

_LINE = re.compile(r"^\s*(?P<label>[^=]+?)\s*=\s*(?P<value>[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)")


def run_script(name, *args, timeout=60):
    """Run examples/<name>.py; returns (stdout, {label: first number})."""
    path = os.path.join(EXAMPLES, name + ".py")
    proc = subprocess.run([sys.executable, path, *args], capture_output=True, text=True,
                          timeout=timeout, cwd=os.path.dirname(EXAMPLES))
    assert proc.returncode == 0, f"{name}.py failed:\n{proc.stdout}\n{proc.stderr}"
    values = {}
    for line in proc.stdout.splitlines():
        m = _LINE.match(line)
        if m:
            values.setdefault(m["label"], float(m["value"]))
    return proc.stdout, values


@pytest.fixture(scope="module")
def outputs():
    """Each script run once (lazily), shared by the tests below."""
    cache = {}

    def get(name):
        if name not in cache:
            cache[name] = run_script(name)
        return cache[name]
    return get


def test_every_example_script_exists():
    """The scripts the README's users are pointed to are there."""
    for name in SCRIPTS:
        assert os.path.isfile(os.path.join(EXAMPLES, name + ".py")), name


def test_seed_pendulum(outputs):
    """Uniform rod released from horizontal: period 4 sqrt(2L/(3g)) K(m=1/2)
    = 1.9333348544 s (SciPy's ellipk here) to 1e-8 s (printed with 10
    decimals); pin force m g/4 at release and 5 m g/2 at the bottom, to 1e-6
    of m g; energy drift below 1e-6 J."""
    _, v = outputs("seed_pendulum")
    T = 4.0 * math.sqrt(2.0 / (3.0 * G)) * float(ellipk(0.5))
    assert abs(v["period closed form"] - T) <= 1e-9
    assert abs(v["period simulated"] - T) <= 1e-8
    assert abs(v["pin force at release"] - 0.25) <= 1e-6
    assert abs(v["max pin force"] - 2.5) <= 1e-6
    assert 0.0 <= v["energy drift"] <= 1e-6


def test_double_pendulum(outputs):
    """Released from horizontal at rest, the mass matrix in absolute angles
    is [[4/3, 1/2], [1/2, 1/3]] m L^2 and the gravity moments -(3/2, 1/2)
    m g L, so (theta1'', theta2'') = (-9 g / 7, 3 g / 7) / L (recomputed
    here with numpy), to 1e-8 rad/s^2.  The lower rod's tip never goes below
    2 m under the pivot; energy drift below 1e-6 J."""
    _, v = outputs("double_pendulum")
    acc = np.linalg.solve([[4 / 3, 1 / 2], [1 / 2, 1 / 3]], [-1.5 * G, -0.5 * G])
    assert np.allclose(acc, [-9 * G / 7, 3 * G / 7], rtol=1e-14)
    assert abs(v["initial angular acceleration upper"] - acc[0]) <= 1e-8
    assert abs(v["initial angular acceleration lower"] - acc[1]) <= 1e-8
    assert -2.0 - 1e-8 <= v["lowest tip height"] < -1.0
    assert 0.0 <= v["energy drift"] <= 1e-6


def test_slider_crank(outputs):
    """r = 0.1, l = 0.3, 10 rad/s: the slider is at r + l = 0.4 m and
    l - r = 0.2 m at the dead centres (1e-9 m), the stroke is 2r (1e-6 m,
    sampled extremes); the maximum slider speed is max |omega dx/dtheta|
    with dx/dtheta = -r sin th (1 + r cos th / sqrt(l^2 - r^2 sin^2 th)),
    evaluated here on a fine grid (1e-4 relative: the script samples 2001
    points per turn); over a whole turn the motor does no net work (below
    1e-6 J, against a peak torque of 2.4 N m)."""
    _, v = outputs("slider_crank")
    r, l, w = 0.1, 0.3, 10.0
    th = np.linspace(0.0, 2 * np.pi, 200001)
    dx = -r * np.sin(th) * (1 + r * np.cos(th) / np.sqrt(l**2 - r**2 * np.sin(th)**2))
    assert v["degrees of freedom"] == 0
    assert abs(v["slider at outer dead centre"] - (r + l)) <= 1e-9
    assert abs(v["slider at inner dead centre"] - (l - r)) <= 1e-9
    assert abs(v["stroke"] - 2 * r) <= 1e-6
    assert abs(v["max slider speed"] - w * np.abs(dx).max()) <= 1e-4 * w * np.abs(dx).max()
    assert 2.0 < v["max motor torque"] < 3.0
    assert abs(v["motor work over one turn"]) <= 1e-6


def test_four_bar(outputs):
    """Crank-rocker (1, 3.5, 3, ground 4): one degree of freedom; the crank
    keeps its given 12 rad/s at the start (the script's velocities are
    consistent, 1e-8) and turns fully, so the rocker swings between the two
    in-line positions of crank and coupler, AC = 2.5 and 4.5:
    angle ADC = acos((16 + 9 - AC^2) / 24), swing 39.960 deg (to 0.01 deg,
    sampled); the coupler keeps its length (1e-9 m); energy conserved to
    1e-7 relative."""
    _, v = outputs("four_bar")
    swing = math.degrees(math.acos((25 - 4.5**2) / 24) - math.acos((25 - 2.5**2) / 24))
    assert v["degrees of freedom"] == 1
    assert abs(v["crank speed at start"] - 12.0) <= 1e-8
    assert abs(v["crank turns"]) >= 1.0
    assert abs(v["rocker swing"] - swing) <= 0.01
    assert v["max coupler length error"] <= 1e-9
    assert v["energy drift"] <= 1e-7 * v["energy"]


def test_quick_return(outputs):
    """Whitworth: the ram turns where the lever is horizontal, i.e. where
    the crank pin is level with the lever pivot: r sin(theta) = 0.04, at
    theta = pi - asin(0.4) and 2 pi + asin(0.4), reached from pi/2 at 2 pi
    rad/s at t = (pi/2 - asin 0.4)/(2 pi) and (3 pi/2 + asin 0.4)/(2 pi)
    (1e-8 s); stroke 2 x 0.15 m (1e-7 m); time ratio
    (pi + 2 asin 0.4)/(pi - 2 asin 0.4) = 1.70995 (1e-7)."""
    _, v = outputs("quick_return")
    a = math.asin(0.4)
    assert v["degrees of freedom"] == 0
    assert abs(v["ram turns at t1"] - (math.pi / 2 - a) / (2 * math.pi)) <= 1e-8
    assert abs(v["ram turns at t2"] - (1.5 * math.pi + a) / (2 * math.pi)) <= 1e-8
    assert abs(v["stroke"] - 0.3) <= 1e-7
    assert abs(v["time ratio"] - (math.pi + 2 * a) / (math.pi - 2 * a)) <= 1e-7
    assert abs(v["working stroke time"] + v["return stroke time"] - 1.0) <= 1e-9
    assert v["max motor torque"] > 0.0


def test_gear_train(outputs):
    """Two external meshes of ratio -2: omega3/omega1 = 4 (1e-10); at
    constant speed the motor balances the load by power, tau1 = -tau3
    omega3/omega1 = 4 N m (1e-8); tooth force = load / r3 = 1 / 0.05 =
    20 N in both meshes (1e-8)."""
    _, v = outputs("gear_train")
    assert abs(v["omega2 / omega1"] + 2.0) <= 1e-10
    assert abs(v["omega3 / omega1"] - 4.0) <= 1e-10
    assert abs(v["motor torque"] - 4.0) <= 1e-8
    assert abs(v["tooth force mesh12"] - 20.0) <= 1e-8
    assert abs(v["tooth force mesh23"] - 20.0) <= 1e-8


def test_spring_damper(outputs):
    """k = 100, c = 2, m = 1: omega_n = 10, zeta = 0.1; damped period
    2 pi / (omega_n sqrt(1 - zeta^2)) = 0.631484 s (1e-6 relative, the
    script refines the turning points by one Newton step); successive
    swings shrink by exp(-zeta omega_n T_d) (1e-6 relative); the static
    deflection is m g / k; the energy lost equals the damper's integral of
    c ldot^2 (trapezoid over 3001 outputs, 1e-5 relative)."""
    _, v = outputs("spring_damper")
    Td = 2 * math.pi / (10.0 * math.sqrt(1 - 0.01))
    assert abs(v["static deflection"] - G / 100.0) <= 1e-12
    assert abs(v["damped period"] - Td) <= 1e-6 * Td
    assert abs(v["decay per period"] - math.exp(-1.0 * Td)) <= 1e-6
    lost, damper = v["energy lost"], v["energy dissipated by the damper"]
    assert lost > 0.4
    assert abs(lost - damper) <= 1e-5 * lost


def test_plot_option(tmp_path):
    """--plot PATH writes a PNG through lagmb.plotting (skipped without
    matplotlib): the file exists and starts with the PNG signature."""
    pytest.importorskip("matplotlib")
    out = tmp_path / "pendulum.png"
    stdout, _ = run_script("seed_pendulum", "--plot", str(out))
    assert out.is_file()
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert str(out) in stdout


# --------------------------------------------------------------------------
# Scenes
# --------------------------------------------------------------------------

SCENES = sorted(f[:-5] for f in os.listdir(EXAMPLES) if f.endswith(".toml"))


@pytest.mark.parametrize("name", SCENES)
def test_scene_runs(name):
    """Every examples/*.toml loads and runs with its own settings: outputs
    cover [0, t_end] and the constraints hold (max |Phi| below 1e-6 m)."""
    if not hasattr(mb, "load_scene"):
        pytest.skip("mb.load_scene not available yet")
    scene = mb.load_scene(os.path.join(EXAMPLES, name + ".toml"))
    r = scene.run()
    assert len(r.t) >= 2 and r.t[0] == 0.0
    assert r.residual.max() <= 1e-6


def test_scene_slider_crank_matches_closed_form():
    """The slider-crank scene (crank 0.1 m from 90 deg at 10 rad/s, rod
    0.3 m): slider x = r cos th + sqrt(l^2 - r^2 sin^2 th) at every output,
    to 1e-6 m at the scene's own tolerances (rtol 1e-8)."""
    if not hasattr(mb, "load_scene"):
        pytest.skip("mb.load_scene not available yet")
    r = mb.load_scene(os.path.join(EXAMPLES, "slider_crank.toml")).run()
    th = math.pi / 2 + 10.0 * r.t
    x = 0.1 * np.cos(th) + np.sqrt(0.09 - 0.01 * np.sin(th)**2)
    assert np.abs(r.body("slider").position[:, 0] - x).max() <= 1e-6


def test_scene_gear_train_motor_torque():
    """The gear-train scene: motor torque 4 N m and omega3 = 4 omega1 (as
    the Python example), to 1e-6."""
    if not hasattr(mb, "load_scene"):
        pytest.skip("mb.load_scene not available yet")
    r = mb.load_scene(os.path.join(EXAMPLES, "gear_train.toml")).run()
    assert np.abs(r.effort("motor") - 4.0).max() <= 1e-6
    assert np.abs(r.body("g3").angular_velocity - 20.0).max() <= 1e-6


# --------------------------------------------------------------------------
# Contact examples (circle-line contact, events at onset and release)
# --------------------------------------------------------------------------


def test_bouncing_ball(outputs):
    """Drop from a 0.9 m gap: first touch at sqrt(2 h / g) = 0.42835 s (1e-7 s,
    printed to 8 decimals) at sqrt(2 g h) (1e-7 m/s); the rebound ratio is
    below e = 0.8 by at most 2.5e-3 of it (measured 1.7e-3: gravity presses
    the ball down during the contact, tests/elements/test_contact.py); five bounces
    in 2.5 s (10 events)."""
    _, v = outputs("bouncing_ball")
    h = 0.9
    assert abs(v["first touch time"] - math.sqrt(2 * h / G)) <= 1e-7
    assert abs(v["first impact speed"] - math.sqrt(2 * G * h)) <= 1e-7
    assert -2.5e-3 * 0.8 <= v["effective restitution"] - 0.8 < 0.0
    assert v["contact events"] == 10


def test_door_stop(outputs):
    """A door (I = m w^2 / 3 = 8.1 kg m^2) let go at 1.2 rad, pulled shut by
    a constant 20 N m onto a stop with e = 0.5: uniform angular acceleration
    alpha = 20 / 8.1 between impacts, so the first impact at t1 = sqrt(2
    theta0 / alpha) = 0.98590 s with speed alpha t1, each flight 2 e^k t1,
    every impact on its closed-form time to 1e-9 s and arrival speed e^k
    alpha t1 to 1e-9 rad/s; the stop captures the door at the
    bounces' accumulation point T = t1 (1 + e) / (1 - e) within its
    capture_time (1e-6 s: the remaining bounces' total), after some 20
    impacts (not one at every output). At rest on the stop the door stays
    at 0 (never below it by more than 1e-10 rad), its stop torque is the
    closer's 20 N m to 1e-9 relative, and the impacts took all of the
    closer's work, 20 x 1.2 = 24 J, to 1e-8 relative (what was left at the
    capture is below the capture_time's bounces)."""
    _, v = outputs("door_stop")
    inertia = 30.0 * 0.9 ** 2 / 3.0
    alpha = 20.0 / inertia
    t1 = math.sqrt(2.0 * 1.2 / alpha)
    rest = t1 * 1.5 / 0.5
    assert abs(v["first impact time"] - t1) <= 1e-9
    assert abs(v["first impact speed"] - alpha * t1) <= 1e-9
    assert abs(v["impact 2: t"] - t1 * (1.0 + 2.0 * 0.5)) <= 1e-9
    assert v["largest impact time error"] <= 1e-9 and v["largest impact speed error"] <= 1e-9
    assert abs(v["rest time closed form"] - rest) <= 1e-9
    assert 0.0 <= rest - v["capture time"] <= 1e-6
    assert 10 <= v["impacts"] <= 40
    assert v["lowest angle"] >= -1e-10 and abs(v["angle at 4 s"]) <= 1e-10
    assert abs(v["stop torque at 4 s"] - 20.0) <= 1e-9 * 20.0
    assert v["kinetic energy at 4 s"] <= 1e-12
    assert abs(v["energy the impacts took"] - 24.0) <= 1e-8 * 24.0


def test_rolling_disk(outputs):
    """Centre acceleration (2/3) g sin 20 deg to 3 d0 / R = 1.05e-4 relative
    (compliant rolling radius R - d0, d0 = (m g cos a / k)^(2/3) recomputed
    here) and the compliant form g sin a / (1 + R^2 / (2 (R - d0)^2)) to
    1e-8 relative; slip below the smoothing velocity 1e-4 m/s; no events."""
    _, v = outputs("rolling_disk")
    a, R = math.radians(20.0), 0.2
    d0 = (2.0 * G * math.cos(a) / 1e9) ** (2.0 / 3.0)
    rigid = 2.0 / 3.0 * G * math.sin(a)
    compliant = G * math.sin(a) / (1.0 + 0.5 * R * R / (R - d0) ** 2)
    assert abs(v["static penetration"] - d0) <= 1e-12
    assert abs(v["acceleration"] - rigid) <= 3 * d0 / R * rigid
    assert abs(v["acceleration"] - compliant) <= 1e-8 * compliant
    assert v["max slip speed"] < 1e-4
    assert v["contact events"] == 0


def test_incline(outputs):
    """Three bodies on a 20 degree incline (k = 1e8): the sphere rolls with
    g sin a / (1 + 2 R^2 / (5 (R - d0)^2)), d0 = (m g cos a / k)^(2/3)
    recomputed here, to 1e-7 (5/7 g sin a to 3 d0 / R); the cube with mu
    0.5 > tan a sticks (moves less than 1e-9 m after settling, holds m g
    sin a to 1e-8 N, reads "stick"); the cube with mu 0.2 slides at g (sin
    a - mu cos a) to 1e-7."""
    _, v = outputs("incline")
    a, R = math.radians(20.0), 0.1
    d0 = (G * math.cos(a) / 1e8) ** (2.0 / 3.0)
    compliant = G * math.sin(a) / (1 + 2 * R * R / (5 * (R - d0) ** 2))
    assert abs(v["sphere acceleration"] - compliant) <= 1e-7 * compliant
    assert abs(v["sphere acceleration"] - 5 / 7 * G * math.sin(a)) <= 3 * d0 / R * G * math.sin(a)
    assert v["stuck cube moved after 0.1 s"] < 1e-9
    assert abs(v["stuck cube friction"] - G * math.sin(a)) <= 1e-8
    out, _ = outputs("incline")
    assert "stuck cube state at 1 s = stick" in out
    slide = G * (math.sin(a) - 0.2 * math.cos(a))
    assert abs(v["slider acceleration"] - slide) <= 1e-7 * slide


def test_go1_drop(outputs):
    """Unitree Go1 dropped 0.35 m onto the floor (load_urdf(ground=...)):
    13 bodies, 38 contacts (every collision shape of a moving body); at
    3 s every speed is below 1e-3, the floor carries the weight (normal
    forces / m g to 1e-6) and no shape is deeper than (m g / k)^(2/3)."""
    from formats import urdf_robots  # (skips without Pinocchio and example-robot-data)

    assert urdf_robots.ROBOTS
    _, v = outputs("go1_drop")
    assert v["bodies"] == 13 and v["contacts"] == 38
    assert v["largest speed at 3 s"] < 1e-3
    assert abs(v["normal forces / weight"] - 1.0) <= 1e-6
    assert v["deepest at rest"] <= v["whole weight on one point"]


def test_cam_follower(outputs):
    """Flat face on an eccentric cam (e = 0.02 m): lift 2 e (1e-5 m: the
    penetration varies with the load) and the face follows e sin(omega t)
    to 1e-5 m; it never separates (no events)."""
    _, v = outputs("cam_follower")
    assert abs(v["lift"] - 0.04) <= 1e-5
    assert v["max deviation from e sin(omega t)"] <= 1e-5
    assert v["contact events"] == 0


def test_scene_cart_pole_is_the_script_s_model_with_its_input_held_at_zero():
    """examples/cart_pole.toml is examples/cart_pole.py's model: the same
    run to the bit with the input "push" at its initial 0 N, in which the
    pole falls past 1 rad from the vertical at 0.78 s (its header)."""
    sys.path.insert(0, EXAMPLES)
    import cart_pole as cp

    scene = mb.load_scene(os.path.join(EXAMPLES, "cart_pole.toml"))
    settings = {k: v for k, v in scene.settings.items() if k != "t_end"}
    from_scene = mb.simulate(scene.model, 2.0, **settings)
    from_script = mb.simulate(cp.cart_pole(), 2.0, **settings)
    assert np.array_equal(from_scene.q, from_script.q)
    assert [(i["name"], i["initial"]) for i in scene.model.compiled().inputs] == [("push", 0.0)]
    tilt = np.abs(from_scene.body("pole").angle - np.pi / 2)
    assert abs(from_scene.t[np.argmax(tilt > 1.0)] - 0.78) < 0.011  # (outputs every 0.01 s)


def test_scene_heavy_top_conserves_energy_and_spin():
    """examples/heavy_top.toml: a spatial scene; no torque acts about the
    top's axis, so its spin stays at 100 rad/s, and its energy stays put."""
    r = mb.load_scene(os.path.join(EXAMPLES, "heavy_top.toml")).run()
    top = r.body("top")
    spin = np.einsum("ki,ki->k", top.angular_velocity, top.rotation[:, :, 2])
    assert np.abs(spin - 100.0).max() < 1e-6
    assert np.ptp(r.energy) < 1e-7 * np.abs(r.energy).max()
    assert r.reaction("tip").shape == (len(r), 6)


def test_scene_heavy_top_nutates_between_its_release_tilt_and_the_closed_form_turning_tilt():
    """What examples/heavy_top.toml's header says. Let go at tilt theta0
    with no precession, a symmetric top on its tip keeps p_psi = I3 w3 and
    p_phi = I3 w3 cos(theta0); where theta' = 0, energy gives, with u = cos
    theta and I1 about the tip (I1c + m l^2),
        2 I1 m g l (1 - u^2) = (I3 w3)^2 (u0 - u),
    so the tilt swings between theta0 and that root, and the precession
    rate I3 w3 (u0 - u) / (I1 sin^2 theta) never changes sign. Sampled every
    0.5 ms over 2 s (ten nutations); the mean precession rate is near a fast
    top's m g l / (I3 w3)."""
    scene = mb.load_scene(os.path.join(EXAMPLES, "heavy_top.toml"))
    settings = {k: v for k, v in scene.settings.items() if k not in ("t_end", "n_out", "t_out")}
    r = mb.simulate(scene.model, 2.0, n_out=4001, **settings)
    axis = r.body("top").rotation[:, :, 2]
    tilt = np.arccos(np.clip(axis[:, 2], -1.0, 1.0))
    azimuth = np.unwrap(np.arctan2(axis[:, 1], axis[:, 0]))
    m, g, l, I3, w3, theta0 = 1.0, 9.81, 0.1, 0.004, 100.0, 0.5
    I1 = 0.002 + m * l * l
    a, b, u0 = 2.0 * I1 * m * g * l, (I3 * w3) ** 2, np.cos(theta0)
    turning = np.arccos((b - np.sqrt(b * b - 4.0 * a * (b * u0 - a))) / (2.0 * a))
    assert abs(turning - 0.5874) < 1e-4  # (the header's 0.587 rad)
    assert abs(tilt.min() - theta0) < 1e-8
    assert abs(tilt.max() - turning) < 1e-6
    assert np.diff(azimuth).min() > -1e-9  # one way round
    mean_rate = (azimuth[-1] - azimuth[0]) / 2.0
    assert abs(mean_rate - 2.6) < 0.05 and abs(mean_rate / (m * g * l / (I3 * w3)) - 1.0) < 0.1


def test_panda(outputs):
    """examples/panda.py: the Panda from example-robot-data, with its URDF
    limits, falls for 2 s with 0.5 N m s/rad at each arm joint: 9 bodies and
    9 joints (the hand merged into link 7). Its shoulder (joint 2) swings
    onto its upper limit and is captured there (restitution 0: an impact
    and a capture); no joint goes beyond a limit by more than
    1e-8 rad (m). The shoulder's stop torque equals the torque inverse
    dynamics needs for the run's own joint motion to 1e-8 relative. Energy:
    the arm loses the dampers' work plus what the impact took (> 0), and
    after the impact, where the captured stop does no work, what it loses
    equals the dampers' work to 1e-7 relative."""
    from formats import urdf_robots  # (skips without Pinocchio and example-robot-data)

    assert urdf_robots.ROBOTS
    _, v = outputs("panda")
    assert v["bodies"] == 9 and v["joints"] == 9
    assert v["impacts"] >= 1 and v["captures"] >= 1  # (today one of each: the shoulder's, and no release)
    assert 0.4 < v["shoulder captured on its limit at t"] < 0.6
    assert v["largest excursion beyond a limit"] <= 1e-8
    torque = v["shoulder stop torque at 2 s"]
    assert torque < -10.0  # (the upper limit pushes down the joint's coordinate)
    assert abs(torque - v["inverse dynamics shoulder torque"]) <= 1e-8 * abs(torque)
    assert v["energy lost"] > 10.0 and v["impact losses"] > 1.0
    assert abs(v["energy lost"] - v["damper work"] - v["impact losses"]) <= 1e-8
    after = v["energy lost after the last impact"]
    assert abs(after - v["damper work after the last impact"]) <= 1e-7 * after


def test_mjcf_four_bar(outputs):
    """examples/mjcf_four_bar.py: the four-bar of an MJCF file, its loop
    closed by <connect>, falls 2 s without friction: the loop stays closed
    (max |Phi| 1e-9 m), its energy stays put (1e-6 J, of about 10 J) and
    the one equation the parallel hinges and the ball repeat is dropped."""
    pytest.importorskip("mujoco", reason="the mjcf extra (mujoco) is not installed")
    _, v = outputs("mjcf_four_bar")
    assert v["bodies"] == 3
    assert v["max loop residual"] <= 1e-9
    assert v["energy drift"] <= 1e-6
    assert v["redundant equations"] == 1
