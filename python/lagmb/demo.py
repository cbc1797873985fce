"""The seed pendulum: a uniform rod pinned at one end, released from horizontal.

Closed forms used to check the run (theta = angle below the horizontal):
    thetadot^2 = 3 g sin(theta) / L,   thetaddot = 3 g cos(theta) / (2 L)
    pin force on the rod: m g / 4 upward at release, 5 m g / 2 at the bottom
    period T = 4 sqrt(2 L / (3 g)) K(sin(theta0 / 2)), theta0 = pi / 2
"""

import math

import numpy as np

from .model import Model
from .simulation import simulate


def seed_pendulum(length=1.0, mass=1.0, g=9.81):
    """The lecture's pendulum: a rod of the given length (m) and mass (kg),
    J = m L^2 / 12, centre at (L/2, 0), pinned to the ground at the origin."""
    m = Model(gravity=(0.0, -g))
    rod = m.add_body("rod", mass=mass, inertia=mass * length**2 / 12.0,
                     position=(0.5 * length, 0.0), angle=0.0)
    m.add_revolute("pin", m.ground, rod, at=(0.0, 0.0))
    return m


def elliptic_k(k):
    """Complete elliptic integral of the first kind K(k), modulus k, by the
    arithmetic-geometric mean: K = pi / (2 AGM(1, sqrt(1 - k^2)))."""
    a, b = 1.0, math.sqrt(1.0 - k * k)
    while abs(a - b) > 1e-15 * a:
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return math.pi / (2.0 * a)


def pendulum_period(length=1.0, g=9.81, theta0=math.pi / 2):
    """Period (s) of a uniform rod pinned at one end, amplitude theta0."""
    return 4.0 * math.sqrt(2.0 * length / (3.0 * g)) * elliptic_k(math.sin(theta0 / 2.0))


def turning_times(t, omega, alpha):
    """Times where the angular velocity changes sign, each refined by one
    Newton step on omega with the angular acceleration."""
    out = []
    for k in np.nonzero(np.sign(omega[:-1]) * np.sign(omega[1:]) < 0)[0]:
        j = k if abs(omega[k]) < abs(omega[k + 1]) else k + 1
        out.append(t[j] - omega[j] / alpha[j])
    return np.array(out)


def run(plot=None, t_end=5.0, rtol=1e-8, atol=1e-10, out=print):
    """Simulate the seed pendulum, print a summary, optionally plot; returns
    the Result."""
    L, mass, g = 1.0, 1.0, 9.81
    model = seed_pendulum(L, mass, g)
    r = simulate(model, t_end=t_end, rtol=rtol, atol=atol, n_out=2001)
    rod = r.body("rod")
    turns = turning_times(r.t, rod.angular_velocity, rod.angular_acceleration)
    T = pendulum_period(L, g)
    F = r.reaction("pin")
    mg = mass * g
    out("lagmb demo: uniform rod (L = 1 m, m = 1 kg) pinned at one end, released from horizontal")
    out(f"  period, closed form        T = {T:.10f} s")
    periods = np.diff(turns[1::2]) if len(turns) > 2 else []
    if len(turns) >= 2:
        out(f"  period, simulated          T = {turns[1]:.10f} s (first return)"
            + "".join(f", {p:.10f}" for p in periods))
    out(f"  pin force at release       {F[0, 1] / mg:.8f} m g upward (closed form 0.25)")
    out(f"  max pin force              {np.max(np.hypot(F[:, 0], F[:, 1])) / mg:.8f} m g "
        "(closed form 2.5, at the lowest point)")
    out(f"  max |Phi|                  {r.residual.max():.2e} m")
    out(f"  energy drift               {np.ptp(r.energy):.2e} J")
    s = r.stats
    out(f"  method {s['method']}: {s['steps']} steps, "
        f"{s['residual_evals']} residual evaluations, {s['jacobian_evals']} Jacobians, "
        f"{s['lu_factorizations']} LU factorizations, {1e3 * s['wall_time']:.1f} ms")
    if plot:
        _plot(r, F / mg, plot)
        out(f"  plot written to {plot}")
    return r


def _plot(r, F, path):
    import os

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    theta = -r.body("rod").angle
    th = np.linspace(0.0, math.pi, 400)
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 6), sharex=False, constrained_layout=True)
    a1.plot(r.t, np.degrees(theta), color="C0")
    a1.set_xlabel("time t (s)")
    a1.set_ylabel("angle below horizontal (deg)")
    a1.set_title("Seed pendulum: rod released from horizontal")
    a1.grid(alpha=0.3)
    # closed form of the pin force along the swing, as a function of theta
    ax_cf = 0.5 * (-np.sin(th) * 1.5 * np.cos(th) - np.cos(th) * 3.0 * np.sin(th))
    ay_cf = 0.5 * (-np.cos(th) * 1.5 * np.cos(th) + np.sin(th) * 3.0 * np.sin(th))
    a2.plot(np.degrees(th), ax_cf, "k-", lw=3, alpha=0.25, label="closed form")
    a2.plot(np.degrees(th), ay_cf + 1.0, "k-", lw=3, alpha=0.25)
    a2.plot(np.degrees(theta), F[:, 0], ".", ms=2, color="C1", label="lagmb: horizontal")
    a2.plot(np.degrees(theta), F[:, 1], ".", ms=2, color="C2", label="lagmb: vertical")
    a2.set_xlabel("angle below horizontal (deg)")
    a2.set_ylabel("pin force on rod / (m g)")
    a2.legend()
    a2.grid(alpha=0.3)
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig.savefig(path, dpi=120)
    plt.close(fig)
