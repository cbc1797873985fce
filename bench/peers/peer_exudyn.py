"""Exudyn on the peer chain: redundant coordinates with Lagrange multipliers
(the formulation lagmb uses) and, as a second model, Exudyn's minimal-
coordinate kinematic tree.

Redundant model ("redundant"): per rod a NodeRigidBody2D (x, y, phi of the
centre; reference coordinates (k + 0.5, 0, 0), at rest) with an
ObjectRigidBody2D (m = 1 kg, J = 1/12 kg m^2 about the centre); an
ObjectJointRevolute2D between MarkerBodyPosition points (ground origin to
rod 0's left end (-0.5, 0); rod k-1's right end (0.5, 0) to rod k's left
end); gravity as LoadMassProportional (0, -9.81, 0) on a MarkerBodyMass of
every rod. The stiff variant adds Exudyn's rotational spring-damper,
TorsionalSpringDamper, between MarkerBodyRigid markers of consecutive rods
(torque -k (phi_k - phi_{k-1}) - c (phi_k' - phi_{k-1}'): the rods'
reference angles are all 0, so the rest angle is the initial relative angle
0). Sparse linear solver (EigenSparse), one thread. Solvers, fixed step
h = 1/steps with steps = 25 * 2^j:
  - TrapezoidalIndex2: trapezoidal rule (Newmark, no numerical damping) on
    the index-2 (velocity-level) constraints;
  - GeneralizedAlpha: Exudyn's default implicit solver (index-3
    constraints, spectral radius 0.9);
  - RK44: an explicit solver, tried once to record that Exudyn's explicit
    solvers refuse the revolute joints' algebraic constraints.
Newton tolerances are Exudyn's defaults (1e-8 relative; tighter ones gave
the same errors down to 4e-8 at N = 32 and cost 20 % more time).

Kinematic tree ("tree", N <= 128 only: Exudyn evaluates its mass matrix
densely, 0.8 s per RK67 step at N = 512): ObjectKinematicTree with N
RevoluteZ joints (relative angles; joint offsets (1, 0, 0) after the first),
link masses 1, link centres (0.5, 0, 0), link inertias diag(1e-3, 1/12,
1/12) about the centre; the springs of the stiff variant as its joint
P/D control (tau_i = P_i (0 - q_i) + D_i (0 - q_i'), P = k, D = c, zero at
joint 0). Explicit solvers RK67 (fixed step) and DOPRI5 (adaptive,
tolerances swept as lagmb's rtol, atol = 1e-2 rtol, first step 1e-4 s:
with Exudyn's default first step the stiff chain's state blows up before
the step control can reject it, "mass matrix singular"). The tip position
follows from the relative angles by summing them (forward kinematics in
the plane).

Time: the SolveDynamic call (includes Exudyn's solver initialisation, e.g.
initial accelerations; no output is written). The model is built once per
N and re-solved from its initial values.

    /tmp/peers-venv/bin/python bench/peers/peer_exudyn.py [--n 8] [--stiff]
"""

import contextlib
import os
import sys
import time
import warnings

import numpy as np

if not __package__:  # run as a file: the repository root on the path, for `import bench` (bench/README.md)
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

NAME = "exudyn"
STEPS = tuple(25 * 2 ** j for j in range(13))
RTOLS = tuple(10.0 ** (-k / 2) for k in range(6, 23))
TREE_MAX_N = 128


def available():
    try:
        import exudyn
    except ImportError as e:
        return False, f"not importable: {e}"
    return True, f"exudyn {exudyn.__version__}"


def build_redundant(n, k=0.0, c=0.0):
    import exudyn as exu
    from exudyn.itemInterface import (LoadMassProportional, MarkerBodyMass, MarkerBodyPosition, MarkerBodyRigid,
                                      NodeRigidBody2D, ObjectGround, ObjectJointRevolute2D, ObjectRigidBody2D,
                                      TorsionalSpringDamper)

    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    ground = mbs.AddObject(ObjectGround(referencePosition=[0.0, 0.0, 0.0]))
    prev = mbs.AddMarker(MarkerBodyPosition(bodyNumber=ground, localPosition=[0.0, 0.0, 0.0]))
    nodes, rigid = [], []
    for i in range(n):
        nd = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[i + 0.5, 0.0, 0.0], initialVelocities=[0.0, 0.0, 0.0]))
        body = mbs.AddObject(ObjectRigidBody2D(mass=1.0, inertia=1.0 / 12.0, nodeNumber=nd))
        left = mbs.AddMarker(MarkerBodyPosition(bodyNumber=body, localPosition=[-0.5, 0.0, 0.0]))
        mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[prev, left]))
        mass = mbs.AddMarker(MarkerBodyMass(bodyNumber=body))
        mbs.AddLoad(LoadMassProportional(markerNumber=mass, loadVector=[0.0, -9.81, 0.0]))
        prev = mbs.AddMarker(MarkerBodyPosition(bodyNumber=body, localPosition=[0.5, 0.0, 0.0]))
        if k or c:
            rigid.append(mbs.AddMarker(MarkerBodyRigid(bodyNumber=body, localPosition=[0.0, 0.0, 0.0])))
            if i > 0:
                mbs.AddObject(TorsionalSpringDamper(markerNumbers=[rigid[-2], rigid[-1]], stiffness=k, damping=c))
        nodes.append(nd)
    mbs.Assemble()
    return sc, mbs, nodes


def build_tree(n, k=0.0, c=0.0):
    import exudyn as exu
    from exudyn.itemInterface import NodeGenericODE2, ObjectKinematicTree

    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    zeros = [0.0] * n
    node = mbs.AddNode(NodeGenericODE2(referenceCoordinates=zeros, initialCoordinates=zeros,
                                       initialCoordinates_t=zeros, numberOfODE2Coordinates=n))
    extra = {}
    if k or c:
        extra = {"jointPControlVector": [0.0] + [k] * (n - 1), "jointDControlVector": [0.0] + [c] * (n - 1),
                 "jointPositionOffsetVector": zeros, "jointVelocityOffsetVector": zeros}
    mbs.AddObject(ObjectKinematicTree(
        nodeNumber=node, gravity=[0.0, -9.81, 0.0], baseOffset=[0.0, 0.0, 0.0],
        jointTypes=[exu.JointType.RevoluteZ] * n, linkParents=list(range(-1, n - 1)),
        jointTransformations=exu.Matrix3DList([np.eye(3)] * n),
        jointOffsets=exu.Vector3DList([[0.0, 0.0, 0.0]] + [[1.0, 0.0, 0.0]] * (n - 1)),
        linkInertiasCOM=exu.Matrix3DList([np.diag([1e-3, 1.0 / 12.0, 1.0 / 12.0])] * n),
        linkCOMs=exu.Vector3DList([[0.5, 0.0, 0.0]] * n), linkMasses=[1.0] * n, **extra))
    mbs.Assemble()
    return sc, mbs, node


@contextlib.contextmanager
def quiet_stdout():
    """Exudyn's C++ prints a banner on every failed solve; send fd 1 to
    /dev/null meanwhile (outside the timed region)."""
    sys.stdout.flush()
    saved, null = os.dup(1), os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, 1)
    try:
        yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)
        os.close(null)


def tip_from_relative(q):
    """Rod N-1's centre from relative joint angles: absolute angle of rod i is
    sum_{j <= i} q_j; the centre is sum_{i < N-1} e_i + e_{N-1} / 2."""
    th = np.cumsum(q)
    e = np.stack([np.cos(th), np.sin(th)], axis=1)
    return e[:-1].sum(axis=0) + 0.5 * e[-1]


class Engine:
    name = NAME

    def __init__(self, n, k=0.0, c=0.0):
        import exudyn as exu

        self.exu = exu
        self.n = n
        self.k, self.c = k, c
        self.red = build_redundant(n, k, c)
        self.tree = build_tree(n, k, c) if n <= TREE_MAX_N else None

    def methods(self, stiff):
        return [
            {"method": "redundant TrapezoidalIndex2", "kind": "steps", "levels": STEPS},
            {"method": "redundant GeneralizedAlpha", "kind": "steps", "levels": STEPS},
            {"method": "redundant RK44", "kind": "steps", "levels": (100,)},
            {"method": "tree RK67", "kind": "steps", "levels": STEPS, "max_n": TREE_MAX_N},
            {"method": "tree DOPRI5", "kind": "rtol", "levels": RTOLS, "max_n": TREE_MAX_N},
        ]

    def _settings(self, solver, level):
        exu = self.exu
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DeprecationWarning)
            s = exu.SimulationSettings()
            ti = s.timeIntegration
            ti.startTime, ti.endTime = 0.0, 1.0
            ti.verboseMode = 0
            ti.adaptiveStep = False
            s.solutionSettings.writeSolutionToFile = False
            s.solutionSettings.writeInitialValues = False
            s.linearSolverType = exu.LinearSolverType.EigenSparse
            s.parallel.numberOfThreads = 1
            if solver == "DOPRI5":
                ti.numberOfSteps = 10  # largest step 0.1 s
                ti.initialStepSize = 1e-4  # the default first step blows up on the stiff chain
                ti.automaticStepSize = True
                ti.relativeTolerance = level
                ti.absoluteTolerance = 1e-2 * level
            else:
                ti.numberOfSteps = int(level)
                ti.automaticStepSize = False
            if solver == "GeneralizedAlpha":
                ti.generalizedAlpha.spectralRadius = 0.9
                ti.generalizedAlpha.useIndex2Constraints = False
                ti.generalizedAlpha.useNewmark = False
            if solver in ("RK67", "DOPRI5"):
                ti.explicitIntegration.computeEndOfStepAccelerations = False
        return s

    def run(self, method, level):
        exu = self.exu
        model, solver = method.split()
        s = self._settings(solver, level)
        if model == "redundant":
            _, mbs, nodes = self.red
        else:
            if self.tree is None:
                raise RuntimeError(f"kinematic tree not run above N = {TREE_MAX_N}")
            _, mbs, node = self.tree
        kind = getattr(exu.DynamicSolverType, solver)
        with quiet_stdout():
            t0 = time.perf_counter()
            ok = mbs.SolveDynamic(s, solverType=kind)
            wall = time.perf_counter() - t0
        t_end = mbs.systemData.GetTime()
        if not ok or abs(t_end - 1.0) > 1e-9:
            raise RuntimeError(f"solver stopped at t = {t_end}")
        if model == "redundant":
            tip = np.asarray(mbs.GetNodeOutput(nodes[-1], exu.OutputVariableType.Position))[:2]
        else:
            tip = tip_from_relative(np.asarray(mbs.GetNodeOutput(node, exu.OutputVariableType.Coordinates)))
        it = mbs.sys["dynamicSolver"].it  # counters of the solver SolveDynamic kept (storeSolver)
        return {"tip": [float(tip[0]), float(tip[1])], "time": wall, "steps": int(it.currentStepIndex) - 1,
                "newton_iterations": int(it.newtonStepsCount), "jacobians": int(it.newtonJacobiCount)}


if __name__ == "__main__":
    from bench.peers.selfcheck import selfcheck

    selfcheck(sys.modules[__name__])
