"""Robots with their own limits (issue 41): the Panda rests on its limits
with the torques of inverse dynamics (Pinocchio's RNEA), and every robot of
example-robot-data falls 5 s onto its limits, which hold."""

import os
import warnings

import numpy as np
import pytest

import lagmb as mb
from formats.urdf_robots import HUMAN_LOCKS, ROBOTS, SKIPPED, URDFS, lagmb_name, load, pinocchio_model

pin = pytest.importorskip("pinocchio", reason="the robots extra (pin) is not installed")


# --- robots with their own limits (issue 41) --------------------------------------------------------------

def pinocchio_state(model, pm, r, k):
    """At output k of a run: Pinocchio's (q, v, a) from lagmb's joint readings
    (r.joint: angle or slide, rate, acceleration; every joint of these files
    is one coordinate), and Pinocchio's joint index of each lagmb joint."""
    js = mb.JointSpace(model)
    q, v, a = np.zeros(pm.nq), np.zeros(pm.nv), np.zeros(pm.nv)
    index = {}
    for jid in range(1, pm.njoints):
        name = lagmb_name(js, pm.names[jid])
        path, i = r.joint(name), pm.joints[jid].idx_v
        q[i] = path.angle[k] if hasattr(path, "angle") else path.slide[k]
        v[i], a[i] = path.rate[k], path.acceleration[k]
        index[name] = i
    return q, v, a, index


@pytest.mark.parametrize("formulation", ["auto", "ggl"])
def test_the_panda_rests_on_its_limits_with_the_torques_of_inverse_dynamics(formulation):
    """The Panda as the file has it (limits, damping, the fingers' mimic),
    lowered by gravity from its zero configuration (joint 4 from the middle
    of its limits, which exclude 0) for 5 s with default options: the run
    ends, its energy falls from output to output, and every joint stays
    within its limits to 1e-8 rad (m) at every output. At the end, the
    equation of motion in joint space, read by Pinocchio's RNEA at the
    run's own (q, v, a):

        rnea(q, v, a) = tau_stop + tau_damping + tau_mimic,

    tau_stop = r.effort(stop) (0 on a joint off its limits), tau_damping =
    -c s' (the URDF's <dynamics damping>), tau_mimic the coupling's reaction
    (-lam on the follower, +multiplier lam on its leader: docs/modelling.md).
    Each captured stop's torque equals rnea minus the other two to 1e-8 of
    itself (1e-8 of the largest joint torque under GGL, whose accelerations
    hold to its Newton tolerance); every other joint's to 1e-8 of the
    largest. With the default method the balance holds so at every output
    (1e-8 of the largest torque there), through impacts, captures and
    releases."""
    relpath = "panda_description/urdf/panda.urdf"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mb.UrdfWarning)
        model = mb.load_urdf(os.path.join(ROBOTS, relpath))
    elements = model.elements
    stops = {kw["joint"]: kw for kind, kw in elements if kind == "add_stop"}
    damping = {kw["joint"]: kw["viscous"] for kind, kw in elements if kind == "add_joint_friction"}
    mimics = [kw for kind, kw in elements if kind == "add_joint_coupling"]
    assert len(stops) == 9 and len(mimics) == 1

    r = mb.simulate(model, 5.0, formulation=formulation)
    assert r.t[-1] == 5.0
    assert r.stats["captures"] > 0
    assert np.diff(r.energy).max() <= 0.0  # (the dampers and impacts take energy; a captured stop does no work)
    assert limits_held(model, r) == {}

    pm = pinocchio_model(relpath)
    pd = pm.createData()
    efforts = {joint: r.effort(stop["name"]) for joint, stop in stops.items()}
    reactions = {mimic["name"]: r.multipliers(mimic["name"])[:, 0] for mimic in mimics}

    def balance(k):
        """{joint: (stop torque, rnea - damping - mimic torque)} at output k, and the largest |rnea|."""
        q, v, a, index = pinocchio_state(model, pm, r, k)
        rnea = pin.rnea(pm, pd, q, v, a)
        others = {joint: -damping.get(joint, 0.0) * v[i] for joint, i in index.items()}
        for mimic in mimics:
            lam = reactions[mimic["name"]][k]
            others[mimic["joint"]] -= lam
            others[mimic["leader"]] += mimic["multiplier"] * lam
        return {joint: (efforts[joint][k], rnea[i] - others[joint]) for joint, i in index.items()}, np.abs(rnea).max()

    torques, largest = balance(-1)
    captured = [joint for joint, (stop_torque, _) in torques.items() if stop_torque != 0.0]
    assert "panda_joint2" in captured  # (the shoulder, holding the arm: some 35 N m)
    for joint, (stop_torque, expected) in torques.items():
        scale = abs(stop_torque) if joint in captured and formulation != "ggl" else largest
        assert abs(stop_torque - expected) <= 1e-8 * scale, joint
    if formulation == "auto":  # (GGL's outputs between steps balance to its integration error: 3e-5 at 0.3 s)
        for k in range(len(r.t)):
            torques, largest = balance(k)
            assert max(abs(stop - expected) for stop, expected in torques.values()) <= 1e-8 * largest, r.t[k]


def joint_values(model, r, joint):
    """(k,) a joint's angle (rad) or slide (m) at the outputs, continued from
    its initial value: r.joint's angle is continuous from output to output
    but starts within pi of 0, so a joint built beyond pi (a middle of
    limits at 3.14) is put back by whole turns onto its value in the model."""
    path = r.joint(joint)
    if not hasattr(path, "angle"):
        return path.slide
    start = next(kw.get("angle", 0.0) for kind, kw in model.elements if kw["name"] == joint)
    return path.angle + 2 * np.pi * np.round((start - path.angle[0]) / (2 * np.pi))


def limits_held(model, r, tolerance=1e-8):
    """{stop: how far (rad or m) its joint went beyond a limit} for the stops
    whose joint went beyond one by more than `tolerance` at an output."""
    beyond = {}
    for kind, stop in model.elements:
        if kind == "add_stop":
            s = joint_values(model, r, stop["joint"])
            excursion = max(float(np.max(stop["lower"] - s)), float(np.max(s - stop["upper"])))
            if excursion > tolerance:
                beyond[stop["name"]] = excursion
    return beyond


#: The files of example-robot-data that do not load and fall 5 s onto their
#: limits with every limit held to 1e-8, and the words of the error that
#: says why (bench/robots/robot_survey.py --t-end 5 finds the same).
NOT_FALLING = {
    **SKIPPED,
}


#: What a file needs beyond load_urdf's defaults to fall 5 s: human.urdf's
#: chains reach their gimbal locks (with nothing held its run stopped at
#: 0.489 s, IDA failing to converge where the neck's X joint reached its lock
#: while Y rested on its limit), so their middle joints are held.
FALL_OPTIONS = {"human_description/robots/human.urdf": dict(hold=HUMAN_LOCKS)}


def fall_onto_limits(relpath, t_end=5.0):
    """The robot as the file has it (limits, damping, mimic; FALL_OPTIONS),
    fallen for t_end under gravity with default options; AssertionError
    naming the stops whose joint went beyond a limit by more than 1e-8 at
    an output."""
    model = load(relpath, limits=True, dynamics=True, mimic=True, **FALL_OPTIONS.get(relpath, {}))
    r = mb.simulate(model, t_end)
    assert r.t[-1] == t_end
    beyond = limits_held(model, r)
    if beyond:
        raise AssertionError(f"limits not held: {beyond}")
    return model, r


@pytest.mark.slow
@pytest.mark.parametrize("relpath", URDFS)
def test_each_robot_falls_5_s_onto_its_limits_and_they_hold(relpath):
    """Each URDF of example-robot-data with load_urdf's defaults, falling
    under gravity for 5 s (default options): the run ends and every joint
    stays within its limits to 1e-8 rad (m) at every output, or the file is
    in NOT_FALLING and fails with its reason. So the count is the run's: a
    file of the list that starts to pass fails here until it leaves the
    list. Today 69 files: 66 fall 5 s with every limit held (issue 41's
    target: 66; the list says why not the other 3). human.urdf does with
    the middle joints of its neck, shoulders and hips held (FALL_OPTIONS:
    they reach a gimbal lock within their limits)."""
    if relpath in NOT_FALLING:
        with pytest.raises((mb.UrdfError, mb.ModelError, mb.SimulationError, AssertionError),
                           match=NOT_FALLING[relpath].replace("(", r"\(").replace(")", r"\)")):
            fall_onto_limits(relpath)
        return
    fall_onto_limits(relpath)


def test_the_list_of_robots_that_do_not_fall_onto_their_limits_is_of_files_that_exist():
    """NOT_FALLING names files of example-robot-data; 69 - 3 = 66 fall 5 s
    with their limits held (the slow test above checks each)."""
    assert set(NOT_FALLING) <= set(URDFS)
    assert (len(URDFS), len(URDFS) - len(NOT_FALLING)) == (69, 66)


def test_a_robot_is_named_as_its_file_names_it(tmp_path):
    """load_urdf's model carries the <robot name=...> (what the viewer's
    page and pictures are titled by); pickling keeps it."""
    import pickle

    from builders import ARM_URDF

    path = tmp_path / "arm.urdf"
    path.write_text(ARM_URDF)
    model = mb.load_urdf(str(path))
    assert model.name == "arm"
    assert pickle.loads(pickle.dumps(model)).name == "arm"


def test_the_explicit_method_recovers_from_a_trial_step_too_long_for_the_panda():
    """The Panda as users load it (9 stops, the fingers resting open on
    theirs), a servo on each arm joint tracking q0 + 0.3 sin(pi t) (with its
    feed-forward) and gravity compensated by +m g at every body: at rest the
    first-step rule gives a step of 0.98 s at rtol 1e-8, one of its stages
    lands where the augmented matrix is singular, and ERKStep gave up at
    once (a right-hand side that fails in a recoverable manner is a failure
    to it): auto ran the 2 s again with GGL from t = 0. The step is now
    tried again from its start, 4 times shorter: the explicit method runs
    the 2 s, as close to a reference (the explicit method at rtol 1e-11
    with steps of at most 0.05 s, which never tries such a step) as the
    tolerance asks. (Whether a stage of that step lands on a singular
    matrix depends on rounding: the gains are computed as the bench
    computes them, with which the old code gave up.)"""
    q0 = {"panda_joint1": 0.0, "panda_joint2": -0.785, "panda_joint3": 0.0, "panda_joint4": -2.356,
          "panda_joint5": 0.0, "panda_joint6": 1.571, "panda_joint7": 0.785}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mb.UrdfWarning)
        m = mb.load_urdf(os.path.join(ROBOTS, "panda_description/urdf/panda.urdf"), positions=q0)
    # gains scaled to the joint-space inertia at q0 (as bench/robots/control_loop.py):
    # kp = (10 rad/s)^2 M_ii, kd = 2 0.5 (10 rad/s) M_ii
    path = os.path.join(ROBOTS, "panda_description/urdf/panda.urdf")
    pm = pin.buildModelFromUrdf(path)
    q_pin = np.zeros(pm.nq)
    q_pin[:7] = list(q0.values())
    inertia = np.diag(pin.crba(pm, pm.createData(), q_pin))[:7]
    kp, kd = 10.0 ** 2 * inertia, 2 * 0.5 * 10.0 * inertia
    for (name, q), p, d in zip(q0.items(), kp, kd):
        m.add_servo(f"{name}_servo", name, target=mb.Harmonic(0.3, np.pi, 0.0, float(q)), kp=float(p), kd=float(d),
                    feedforward=mb.Harmonic(-float(d) * 0.3 * np.pi, np.pi, np.pi / 2))
    for kind, data in list(m.elements):
        if kind == "add_body":
            m.add_force(f"{data['name']}_lift", data["name"], force=(0.0, 0.0, 9.81 * data["mass"]))
    js = mb.JointSpace(m)

    def angles(r):
        return np.array([js.motion(name, r.q, r.v)[-1, 0] for name in q0])

    reference = mb.simulate(m, 2.0, n_out=2, method="projection-erk", rtol=1e-11, atol=1e-13, max_step=0.05)
    r = mb.simulate(m, 2.0, n_out=2, rtol=1e-8, atol=1e-10)
    assert r.stats["method"] == "projection-erk" and "GGL took over" not in r.stats["method_choice"]
    assert np.max(np.abs(angles(r) - angles(reference))) <= 1e-8
    explicit = mb.simulate(m, 2.0, n_out=2, method="projection-erk", rtol=1e-8, atol=1e-10)
    assert np.max(np.abs(angles(explicit) - angles(reference))) <= 1e-8
