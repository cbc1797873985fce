"""The planar N-link pendulum chain most benchmarks run: N uniform rods
(L = 1 m, m = 1 kg, J = 1/12 kg m^2) in Cartesian body coordinates, rod k
centred at (k + 1/2, 0) (released horizontal at rest), pinned to the ground
at the origin and each to the next by a revolute (Lagrange multipliers),
gravity 9.81 m/s^2 in -y. lagmb is imported by the call, so that the peer
comparison (bench/peers/) runs and reports lagmb missing in an environment
without it."""


def chain(n):
    import lagmb as mb

    m = mb.Model(gravity=(0.0, -9.81))
    prev = m.ground
    for k in range(n):
        rod = m.add_body(f"rod{k}", mass=1.0, inertia=1.0 / 12.0, position=(k + 0.5, 0.0))
        m.add_revolute(f"pin{k}", prev, rod, at=(float(k), 0.0))
        prev = rod
    return m


def stiff_chain(n, k=0.0, c=0.0):
    """The chain plus a rotational spring-damper between consecutive rods
    (torque on rod j -k (phi_j - phi_i - 0) - c (phi_j' - phi_i'), rest
    angle = the initial relative angle 0; none at the ground pin): the
    stiff chain of bench/peers/ with k and c of bench/peers/reference.py."""
    m = chain(n)
    if k or c:
        for i in range(1, n):
            m.add_rotational_spring_damper(f"sd{i}", f"rod{i - 1}", f"rod{i}", stiffness=k, damping=c)
    return m
