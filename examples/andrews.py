"""Andrews' squeezing mechanism: seven rigid bodies, one closed-loop DAE.

    python examples/andrews.py [--rtol 1e-10] [--atol 1e-11] [--scene PATH] [--picture PATH]

The multibody test problem of Hairer & Wanner, "Solving Ordinary
Differential Equations II", section VII.7, and problem "andrews" of the Test
Set for IVP Solvers (F. Mazzia, C. Magherini et al., University of Bari,
https://archimede.uniba.it/~testset/). A motor torque mom = 0.033 N m turns
a short crank (body 1) about O; through body 2 it drives the joint E shared
with three more links: body 3 (pivoted on the ground at B, carrying the
spring) and the two dyads 4-5 and 6-7, both pivoted on the ground at A.
No gravity. Started at rest, the crank reaches ~1100 rad/s within 0.03 s.

Data (used as published; the code here is our own):

- masses m1..m7, inertias I1..I7, lengths, fixed points, c0 = 4530 N/m,
  l0 = 0.07785 m, mom = 0.033 N m: the test set's Fortran source
  ``src/problems/andrews.f`` ($Id: andrews.F,v 1.2 2006/10/02$, subroutine
  ``andfunc``); the same numbers are in its drivers and in the R package
  deTestSet (``pkg/deTestSet/R/ex_andrews.R``, r-forge repository bvpsolve).
- consistent initial angles (30 digits, Theta = 0, Omega = -Phi, at rest):
  the test set's initial values (subroutine ``INITIAL`` of its drivers,
  ``yini`` of deTestSet), as in Hairer & Wanner.
- reference angles at t = 0.03 s: ``andsoln`` in andrews.f, computed with
  PSIDE at rtol = atol = 1e-14 on a Cray C90, 16 significant digits.

Hairer & Wanner's coordinates are seven angles; with E the joint shared by
bodies 2, 3, 4 and 6, their six loop equations (the test set's ``g``) say

    E = rr (cos b, sin b) - d (cos(b + Th), sin(b + Th))               bodies 1, 2
      = B + ss (sin g, -cos g)                                           body 3
      = A + zt (cos de, sin de) + e (sin(Ph + de), -cos(Ph + de))        bodies 5, 4
      = A + u (sin ep, -cos ep) + zf (cos(Om + ep), sin(Om + ep))        bodies 7, 6

so beta, gamma, delta, epsilon are absolute angles of bodies 1, 3, 5, 7 and
Theta, Phi, Omega are the angles of bodies 2, 4, 6 relative to bodies 1, 5,
7. Here every body gets as its lagmb angle the absolute angle of its link
in that notation (body 2: b + Th, body 4: Ph + de, body 6: Om + ep), so no
offsets are needed: beta = phi1, Theta = phi2 - phi1, gamma = phi3,
Phi = phi4 - phi5, delta = phi5, Omega = phi6 - phi7, epsilon = phi7.
Angles are not wrapped: beta turns through 15.8 rad by t = 0.03 s.

Centres of mass follow from the test set's mass matrix, whose entries fix
them: body 1 at ra from O (on the crank line), body 2 at da from the crank
joint towards E, body 4 at ea from E towards its joint H with body 5, body 6
at fa from E towards its joint K with body 7. Bodies 3, 5 and 7 only turn
about fixed pivots, and only the distance of their centres from the pivot
enters (m3 (sa^2 + sb^2) + I3 etc.; there is no gravity), so the direction
is a choice: sa, ta, ua along the pivot's link, sb, tb, ub across it. The
spring acts between D = B + sd (cos g, sin g) + sc (sin g, -cos g) on body 3
and the fixed point C = (xc, yc). At t = 0 lagmb's consistent accelerations
reproduce the test set's beta'' = 14222.44..., Theta'' = -10666.83... and
its multipliers (98.567, -6.123) N as the force of joint "E3" on body 3.

Counting: 7 bodies, 21 coordinates; 10 revolutes (O, crank-rod "P", B, A
for body 5, A for body 7, H, K and three at E) give 20 equations of full
rank: 21 - 20 = 1 degree of freedom, as 7 angles with 6 loop equations in
Hairer & Wanner's description.

Tolerances: atol is one number for every coordinate, velocity and
multiplier, and the velocities reach ~1100 rad/s, whose rounding is
~2.5e-13. With atol = 1e-12 (or below) lagmb's IDA run stops with a
corrector convergence failure where some velocity component passes through
zero (e.g. at t = 0.01205, delta' = 0, for rtol = 1e-10); atol = 1e-11 runs
for every rtol from 1e-13 to 1e-8, hence the default here.
"""

import argparse
import math
import time

import numpy as np

import lagmb as mb

# --- data: Test Set for IVP Solvers, andrews.f (SI units) -------------------
M1, M2, M3, M4, M5, M6, M7 = 0.04325, 0.00365, 0.02373, 0.00706, 0.07050, 0.00706, 0.05498
I1, I2, I3, I4, I5, I6, I7 = 2.194e-6, 4.410e-7, 5.255e-6, 5.667e-7, 1.169e-5, 5.667e-7, 1.912e-5
XA, YA = -0.06934, -0.00227
XB, YB = -0.03635, 0.03273
XC, YC = 0.014, 0.072
C0, L0, MOM = 4530.0, 0.07785, 0.033
D, DA, E, EA = 28e-3, 115e-4, 2e-2, 1421e-5
RR, RA = 7e-3, 92e-5
SS, SA, SB, SC, SD = 35e-3, 1874e-5, 1043e-5, 18e-3, 2e-2
TA, TB = 2308e-5, 916e-5
U, UA, UB = 4e-2, 1228e-5, 449e-5
ZF, ZT, FA = 2e-2, 4e-2, 1421e-5

NAMES = ("beta", "Theta", "gamma", "Phi", "delta", "Omega", "epsilon")

# consistent initial angles (the test set's drivers, subroutine INITIAL; at rest)
INITIAL = (
    -0.0617138900142764496358948458001,
    0.0,
    0.455279819163070380255912382449,
    0.222668390165885884674473185609,
    0.487364979543842550225598953530,
    -0.222668390165885884674473185609,
    1.23054744454982119249735015568,
)

# reference angles at t = 0.03 s (andrews.f, andsoln: PSIDE, rtol = atol = 1e-14)
T_END = 0.03
REFERENCE_TEXT = (
    "0.1581077119629904e+2",
    "-0.1575637105984298e+2",
    "0.4082224013073101e-1",
    "-0.5347301163226948e+0",
    "0.5244099658805304e+0",
    "0.5347301163226948e+0",
    "0.1048080741042263e+1",
)
REFERENCE = tuple(float(x) for x in REFERENCE_TEXT)

BODIES = ("b1", "b2", "b3", "b4", "b5", "b6", "b7")


def _rot(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([c, s]), np.array([-s, c])   # the body's x and y axes


def hw_constraints(angles):
    """Hairer & Wanner's six loop equations g(angles) (the test set's g), in m."""
    b, th, ga, ph, de, om, ep = angles
    ex = RR * math.cos(b) - D * math.cos(b + th)
    ey = RR * math.sin(b) - D * math.sin(b + th)
    return np.array([
        ex - SS * math.sin(ga) - XB,
        ey + SS * math.cos(ga) - YB,
        ex - E * math.sin(ph + de) - ZT * math.cos(de) - XA,
        ey + E * math.cos(ph + de) - ZT * math.sin(de) - YA,
        ex - ZF * math.cos(om + ep) - U * math.sin(ep) - XA,
        ey - ZF * math.sin(om + ep) + U * math.cos(ep) - YA,
    ])


def geometry(angles):
    """Pose of each body and its joint points, from the seven angles.

    Returns {body: (centre, angle, {point name: local point})}: each body's
    centre of mass is placed from its own chain of links out of a fixed
    point (O for bodies 1, 2; B for 3; A for 4-7), so with inconsistent
    angles the joints at E do not close, and lagmb's assembly has work to do.
    Local points are in the body's axes relative to its centre of mass.
    """
    b, th, ga, ph, de, om, ep = angles
    A, B = np.array([XA, YA]), np.array([XB, YB])
    out = {}
    # body 1: crank about O, axis along the crank; joint P with body 2 at rr
    x1, _ = _rot(b)
    out["b1"] = (RA * x1, b, {"O": (-RA, 0.0), "P": (RR - RA, 0.0)})
    # body 2: axis (cos(b + Th), sin(b + Th)); E = P - d x2, centre P - da x2
    x2, _ = _rot(b + th)
    out["b2"] = (RR * x1 - DA * x2, b + th, {"P": (DA, 0.0), "E": (DA - D, 0.0)})
    # body 3: about B; E = B - ss y3, D = B + sd x3 - sc y3; centre B + sb x3 - sa y3
    x3, y3 = _rot(ga)
    out["b3"] = (B + SB * x3 - SA * y3, ga,
                 {"B": (-SB, SA), "E": (-SB, SA - SS), "D": (SD - SB, SA - SC)})
    # body 5: about A; H = A + zt x5; centre A + ta x5 + tb y5
    x5, y5 = _rot(de)
    H = A + ZT * x5
    out["b5"] = (A + TA * x5 + TB * y5, de, {"A": (-TA, -TB), "H": (ZT - TA, -TB)})
    # body 4: axis angle Ph + de; E = H - e y4, centre H - (e - ea) y4
    _, y4 = _rot(ph + de)
    out["b4"] = (H - (E - EA) * y4, ph + de, {"H": (0.0, E - EA), "E": (0.0, -EA)})
    # body 7: about A; K = A - u y7; centre A + ub x7 - ua y7
    x7, y7 = _rot(ep)
    K = A - U * y7
    out["b7"] = (A + UB * x7 - UA * y7, ep, {"A": (-UB, UA), "K": (-UB, UA - U)})
    # body 6: axis angle Om + ep; E = K + zf x6, centre K + (zf - fa) x6
    x6, _ = _rot(om + ep)
    out["b6"] = (K + (ZF - FA) * x6, om + ep, {"K": (FA - ZF, 0.0), "E": (FA, 0.0)})
    return out


def global_point(pose, local):
    """Global position of a local point of a body with pose (centre, angle)."""
    x, y = _rot(pose[1])
    return pose[0] + local[0] * x + local[1] * y


MASSES = {"b1": (M1, I1), "b2": (M2, I2), "b3": (M3, I3), "b4": (M4, I4),
          "b5": (M5, I5), "b6": (M6, I6), "b7": (M7, I7)}

# (name, body_i, point on i, body_j, point on j); ground points are global
JOINTS = (
    ("O", "ground", (0.0, 0.0), "b1", "O"),
    ("P", "b1", "P", "b2", "P"),
    ("B", "ground", (XB, YB), "b3", "B"),
    ("A5", "ground", (XA, YA), "b5", "A"),
    ("A7", "ground", (XA, YA), "b7", "A"),
    ("H", "b5", "H", "b4", "H"),
    ("K", "b7", "K", "b6", "K"),
    ("E3", "b2", "E", "b3", "E"),
    ("E4", "b2", "E", "b4", "E"),
    ("E6", "b2", "E", "b6", "E"),
)


def andrews_model(angles=INITIAL, theta=None):
    """The squeezer as an mb.Model, started at rest at the given seven angles
    (default: the test set's consistent initial values).

    Joints are given by local points (link dimensions exact), so angles that
    do not close the loops are allowed: lagmb assembles them by least change,
    which also moves the one free coordinate (a 1e-3 rad error in the
    angles leaves beta and Theta ~1e-3 off, and beta(0.03) 0.05 rad off).
    ``theta``: if not None, a driver holds Theta (the crank-rod angle,
    joint "P") at that constant, removing the degree of freedom; assembling
    that model finds the unique nearby configuration with that Theta, the
    way the published consistent values are defined (Theta = 0).
    """
    geo = geometry(angles)
    m = mb.Model()   # no gravity
    for name in BODIES:
        centre, angle, _ = geo[name]
        mass, inertia = MASSES[name]
        m.add_body(name, mass=mass, inertia=inertia, position=tuple(centre), angle=angle)
    for name, bi, pi, bj, pj in JOINTS:
        li = pi if bi == "ground" else geo[bi][2][pi]
        m.add_revolute(name, bi, bj, local_i=li, local_j=geo[bj][2][pj])
    # spring-damper points are global in the initial configuration: D from body 3's own pose
    D3 = global_point(geo["b3"][:2], geo["b3"][2]["D"])
    m.add_spring_damper("spring", "b3", tuple(D3), "ground", (XC, YC), stiffness=C0, free_length=L0)
    m.add_torque("motor", "b1", MOM)
    if theta is not None:
        m.drive_joint("hold_theta", "P", mb.Constant(theta))
    return m


def _angles_from_phi(phi):
    """(beta, Theta, gamma, Phi, delta, Omega, epsilon) from the body angles
    phi1..phi7 (last axis)."""
    p1, p2, p3, p4, p5, p6, p7 = np.moveaxis(np.asarray(phi, dtype=float), -1, 0)
    return np.stack([p1, p2 - p1, p3, p4 - p5, p5, p6 - p7, p7], axis=-1)


def andrews_angles(result):
    """Hairer & Wanner's seven angles at every output of a Result, (k, 7)."""
    return _angles_from_phi(np.stack([result.body(b).angle for b in BODIES], axis=-1))


def angles_from_q(model, q):
    """The seven angles of one coordinate vector q of an andrews_model."""
    core = model.compiled()
    phi = [q[core.body_coordinates(b)[0] + 2] for b in BODIES]
    return _angles_from_phi(phi)


def consistent_angles(approx, theta=0.0):
    """Consistent angles near ``approx`` with Theta = theta, by lagmb's
    assembly (Newton least-change projection) of the model with Theta held."""
    m = andrews_model(approx, theta=theta)
    q = m.assemble()[0]
    return angles_from_q(m, q)


def run(angles=INITIAL, rtol=1e-10, atol=1e-11, n_out=2):
    """Simulate to t = 0.03 s; returns (result, angles at the end, wall time)."""
    m = andrews_model(angles)
    t0 = time.perf_counter()
    r = mb.simulate(m, t_end=T_END, rtol=rtol, atol=atol, n_out=n_out)
    wall = time.perf_counter() - t0
    return r, andrews_angles(r)[-1], wall


def draw(result, path, **kwargs):
    """The mechanism at one output with a traced path (lagmb.plotting.picture, needs matplotlib)."""
    from lagmb.plotting import picture
    picture(result, path, size=(640, 480), **kwargs)
    print(f"picture written to {path}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rtol", type=float, default=1e-10)
    parser.add_argument("--atol", type=float, default=1e-11)
    parser.add_argument("--scene", metavar="PATH", help="also write the model as a TOML scene")
    parser.add_argument("--picture", metavar="PATH", help="draw the mechanism at t = 0.03 s with the paths of "
                        "the crank's tip P and the joint E to PATH (.png)")
    args = parser.parse_args(argv)

    model = andrews_model()
    q0 = model.compiled().initial_state()[0]
    print("Andrews' squeezing mechanism (Hairer & Wanner VII.7, Bari test set 'andrews')")
    print(f"degrees of freedom = {model.degrees_of_freedom()} (21 coordinates, 20 equations)")
    print(f"initial loop closure = {np.abs(model.compiled().constraint_values(q0)[0]).max():.3e} m")
    r, final, wall = run(rtol=args.rtol, atol=args.atol)
    print(f"t = {T_END} s, rtol = {args.rtol:g}, atol = {args.atol:g}")
    print(f"{'angle':>8} {'lagmb':>22} {'reference':>22} {'difference':>11}")
    for name, x, text in zip(NAMES, final, REFERENCE_TEXT):
        print(f"{name:>8} {x:22.15e} {text:>22} {x - float(text):11.2e}")
    print(f"max difference = {np.abs(final - np.array(REFERENCE)).max():.3e} rad")
    print(f"max |Phi| = {r.residual.max():.3e} m")
    print(f"steps = {r.stats['steps']}")
    print(f"wall time = {wall:.3f} s")
    if args.picture:
        shown, _, _ = run(rtol=args.rtol, atol=args.atol, n_out=601)  # (outputs for the paths)
        draw(shown, args.picture, trace=["P", "E3"],
             title="Andrews' squeezer at 0.03 s: the paths of P and E")
    if args.scene:
        mb.save_scene(model, args.scene, settings={"t_end": T_END, "rtol": args.rtol, "atol": args.atol,
                                             "n_out": 301})
        print(f"scene written to {args.scene}")


if __name__ == "__main__":
    main()
