"""Random bodies in contact in space, and the physics every run of them must obey.

Used by tests/fuzz/test_fuzz_contacts.py (contact between collision shapes in
space, docs/modelling.md "Contact between shapes in space"). A *case* is
plain data, {"ops": [...], "meta": {...}}: the ops are those of
tests/fuzz/fuzz_mechanisms.py (Python source over ``mb`` and ``np``, run op by op
in its worker subprocess, so that a crash or a hang of the core fails one
case, not pytest): one op builds the model, one runs it (``mb.simulate``, its
result checked by the mechanism fuzzer: finite, output times in order,
constraints held) and the last checks the result with ``contact_problems``,
which raises an AssertionError naming each broken law. ``meta`` says what the
checks need: the bodies (mass, inertia, initial pose and velocities), the
shapes (kind, size, initial pose), the ground plane, the contacts and their
laws, the run's tolerance and the initial energy as the builder computed it
from the drawn numbers (independently of the core).

The scenes (strategy ``contact_cases``): 0-3 free bodies, each with a
collision shape (sphere, capsule, box, cylinder, or a mesh: a box whose
bottom face is drawn down to a low vertex, a little or far under it, at its
centre or off it (a vertex extreme only in a narrow cone of directions);
sometimes off its centre of mass and turned in it; sometimes a second
shape, a sphere, on the same body), above, touching (to the last bit, or 1e-12 m off) or resting (a
little pressed in) on a ground plane, level or tilted; random orientations
(some aligned: a box flat, a cylinder lying), velocities (some at rest),
angular velocities, masses and inertias (principal moments of a mass
distribution, so the triangle inequality holds with margin; sometimes a full
tensor). Sometimes a sphere on a second body meets another body's sphere,
box or capsule (dropped on it, or thrown at it), or one fixed on the ground
(on the plane or raised above it). Each contact draws its stiffness
(1e5..1e8), restitution (0.2..1), friction (0..1), sometimes a static
friction at or above it and another slip velocity, and which shape is given
first. Every method that places contact onsets: ggl, index3, index1,
projection-bdf, projection-adams and auto; runs of 0.2-1 s at rtol
1e-7..1e-9 (atol rtol / 100), 51-201 outputs.

The laws (``contact_problems``; each line it returns starts with its law's
name), for a run that succeeds:
- "energy gained": r.energy never rises above an earlier value by more than
  the integration tolerance (ENERGY_TOL per method, per unit of rtol / 1e-8,
  times the scene's energy scale, plus the drift of the formulations that
  let constraints drift); "energy gained at the start": nor starts above the
  drawn state's energy (a stick at t0 projects the velocities: it may only
  lose energy);
- "penetration beyond the energy left": the elastic energy of the deepest
  point of every contact, sum k d^2.5 / 2.5, is at most what the energy left
  over for the contacts (the drawn initial energy less the kinetic and
  gravitational energy at that output, computed here from the bodies'
  states) allows; "... beyond the initial energy's reach": a priori, at most
  what the initial energy and gravity's work could give (with no energy
  gained, (sqrt(K0 + V0) + g t sum sqrt(2 m_i) / 2)^2 by time t);
- the readings are the geometry's ("penetration misread", "contact point off
  the plane", "contact normal not the plane's"): the penetration is the
  deepest point's (the points the docs list, computed here from the bodies'
  poses), a pressing plane contact's point lies on the plane, its normal is
  the plane's;
- forces: "a contact pulls" (normal force < 0), "an open contact pushes",
  "friction beyond its limit" (slipping: within mu F_n); "a stuck contact
  slips" (state "stick": its points slip at most STICK_SLIP v_s more than
  the body's rocking about the anchor moves them, |omega| times the deepest
  point's depth), "a stuck
  contact beyond its limit" (its friction force within mu_s F_n: the ellipse
  limit includes the torsion, the force alone must be within it); "a round
  shape sticks" (only a box or a mesh against a plane has stick rows);
- events: "events miscounted" (r.stats against r.events), "events out of
  order"; onsets less releases of a contact count its pressing points as
  the geometry shows them at every output ("onsets and releases
  miscounted"; apart: "a crossing logged twice", "a cylinder's crossings
  mislabelled", and "pressed without an onset", a contact passed within a
  step, its force never acting: the outputs it shows pressed are left out
  of the energy laws, which its readings alone would break); "stick and
  slip out of turn", "state disagrees with events" (the state reads "stick"
  exactly between a stick and its slip);
- "contact readings refused", "non-finite contact reading": a successful
  run gives finite readings;
- "pickles of contact models" (``check_pickles``, an op of its own): the
  model and its Result survive a pickle and a deep copy, the copies the
  same to the bit.
The test (tests/fuzz/test_fuzz_contacts.py) adds: the run either succeeds or
raises mb.SimulationError / mb.ModelError with a message ("a refusal without
a message"; "refused as Zeno": a compliant contact's touches last a time,
its events cannot accumulate), never another exception, a crash or a hang
(the worker's timeout is each op's wall-time budget; "a hang under index3"
and "a hang with a cylinder" apart); the mechanism fuzzer's result check
(finite arrays, output times in order, constraints held).

What the core breaks today is shrunk to xfail tests of
tests/fuzz/test_fuzz_contacts.py: KNOWN_BUGS names the features that break the
laws (``contact_cases(known_bugs=False)``, the default, leaves them out),
KNOWN_LAWS the laws broken by scenes of any kind (contact_problems names
them apart, so a run that breaks only those can be counted rather than
failed).
"""

import math
import os

try:  # the parent draws cases with hypothesis; the worker only checks results
    from hypothesis import strategies as st
except ImportError:  # pragma: no cover
    st = None

HERE = os.path.dirname(os.path.abspath(__file__))
G = 9.81
METHODS = ["ggl", "index3", "index1", "projection-bdf", "projection-adams", "auto"]
#: J per J of the scene's energy scale, per unit of rtol / 1e-8: the integration
#: error a run shows in its energy (measured on 1,500 fuzzed scenes: at most
#: 5e-8 but for index3, whose velocities are only index-2 accurate, 7e-4 at
#: rtol 1e-8 (a cylinder on its end) and typically 1e-6, as fuzz_stops'
#: 5e-4; index 1 and Adams let the Euler parameters' norms and the stick
#: rows drift, their residual's work is added apart)
ENERGY_TOL = {"index3": 5e-4}
ENERGY_TOL_DEFAULT = 1e-6
GEOMETRY_TOL = 1e-7  # m per m of the shape's size (+ the drift): readings against the geometry
STICK_SLIP = 0.5  # of v_s: the fastest a stuck contact's points may slip (beyond its rocking)
LIMIT_TOL = 1e-6  # relative: friction beyond mu F_n (or mu_s F_n while stuck)

#: What the fuzzer found the core breaking, each shrunk to an xfail(strict=True)
#: test of tests/fuzz/test_fuzz_contacts.py: {feature: that test}. contact_cases(
#: known_bugs=False) draws none of these features; known_bugs=True draws them.
KNOWN_BUGS = {
    "a cylinder standing on an end (its axis within 25 degrees of the plane's normal)":
        "test_a_cylinder_standing_on_an_end_runs",
    "index3 at rtol 1e-7": "test_index3_at_rtol_1e_7_gains_no_energy",
}
#: Laws the core breaks in scenes of any kind: contact_problems names them
#: apart; {law: the xfail test of it}.
KNOWN_LAWS = {
    "a stuck contact slips": "test_a_stuck_box_leaning_on_a_ball_does_not_slip",
    # (a cylinder drawn lying may fall flat, onto an end: KNOWN_BUGS' feature reached in the run)
    "a hang with a cylinder": "test_a_cylinder_standing_on_an_end_runs",
}

ROT_SOURCE = '''def rot(axis, angle):
    """The rotation by angle (rad) about axis."""
    k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + np.sin(angle) * K + (1.0 - np.cos(angle)) * (K @ K)
'''


def _define_rot():
    import numpy as np

    ns = {"np": np}
    exec(ROT_SOURCE, ns)
    return ns["rot"]


# ---------------------------------------------------------------------------
# Geometry (both sides): the contact points of the collision table
# ---------------------------------------------------------------------------

def support(kind, size, axes, d):
    """How far the shape reaches from its centre along the unit vector d."""
    import numpy as np

    axes = np.asarray(axes, dtype=float)
    d = np.asarray(d, dtype=float)
    if kind == "sphere":
        return size[0]
    c = axes.T @ d  # d in the shape's axes
    if kind == "capsule":
        return size[0] + 0.5 * size[1] * abs(c[2])
    if kind == "box":
        return float(sum(0.5 * size[i] * abs(c[i]) for i in range(3)))
    if kind == "cylinder":
        return 0.5 * size[1] * abs(c[2]) + size[0] * math.sqrt(max(0.0, 1.0 - c[2] * c[2]))
    if kind == "mesh":
        return float(np.max(mesh_vertices(size) @ c))
    raise ValueError(kind)


def mesh_vertices(size):
    """(9, 3) the vertices of a mesh with a low vertex, in its own axes: a
    box of edges size[:3] whose bottom face is drawn down to a point
    size[5] under it at (size[3], size[4]) times the edges (its corners,
    then that point). Each is a vertex of its hull: a contact point."""
    import numpy as np

    lx, ly, lz, u, v, depth = size
    corners = [(x * lx, y * ly, z * lz) for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)]
    # (as the STL file holds them: single precision)
    return np.array(corners + [(u * lx, v * ly, -0.5 * lz - depth)]).astype(np.float32).astype(float)


def low_point_mesh(size):
    """The STL file of mesh_vertices(size)'s shape (its bottom face four
    triangles to the low point), written once per size in the temporary
    folder. -> its path."""
    import tempfile

    import numpy as np

    path = os.path.join(tempfile.gettempdir(), "lagmb_fuzz_mesh_" + "_".join(f"{x:.6g}" for x in size) + ".stl")
    if not os.path.exists(path):
        X = mesh_vertices(size)
        faces = [(1, 3, 7), (1, 7, 5), (0, 1, 5), (0, 5, 4), (2, 6, 7), (2, 7, 3), (0, 2, 3), (0, 3, 1),
                 (4, 5, 7), (4, 7, 6), (0, 4, 8), (4, 6, 8), (6, 2, 8), (2, 0, 8)]
        data = b"lagmb fuzz".ljust(80, b" ") + len(faces).to_bytes(4, "little") + b"".join(
            np.zeros(3, "<f4").tobytes() + X[list(f)].astype("<f4").tobytes() + b"\0\0" for f in faces)
        part = f"{path}.{os.getpid()}"
        with open(part, "wb") as f:  # (whole or not at all: workers may write it at once)
            f.write(data)
        os.replace(part, path)
    return path


def plane_gaps(kind, size, centre, axes, n, p0):
    """(gaps of the shape's contact points against the plane through p0 with
    the outward normal n (negative: penetration), the points P on the plane)."""
    import numpy as np

    centre, axes, n, p0 = (np.asarray(x, dtype=float) for x in (centre, axes, n, p0))
    if kind == "sphere":
        X, r = centre[None], size[0]
    elif kind == "capsule":
        a = axes[:, 2]
        X, r = np.array([centre + 0.5 * size[1] * a, centre - 0.5 * size[1] * a]), size[0]
    elif kind == "box":
        h = 0.5 * np.asarray(size)
        X = np.array([centre + axes @ (h * np.array(s)) for s in
                      [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]])
        r = 0.0
    elif kind == "mesh":  # every vertex of its hull
        X, r = centre[None] + mesh_vertices(size) @ axes.T, 0.0
    else:  # cylinder: on each rim its deepest point and those at 90, 180, 270 degrees
        R, L = size
        a = axes[:, 2]
        u = -(n - (n @ a) * a)
        if np.linalg.norm(u) < 1e-12:  # upright: every rim point is as deep
            u = axes[:, 0]
        u = u / np.linalg.norm(u)
        w = np.cross(a, u)
        X = np.array([c + R * s for c in (centre + 0.5 * L * a, centre - 0.5 * L * a) for s in (u, w, -u, -w)])
        r = 0.0
    g = (X - p0) @ n - r
    return g, X - (g + r)[:, None] * n[None]


def pair_gap(kind_a, size_a, centre_a, axes_a, kind_b, size_b, centre_b, axes_b):
    """The gap of a sphere (a) and a sphere, capsule or box (b)."""
    import numpy as np

    assert kind_a == "sphere"
    ca, cb, B = np.asarray(centre_a, dtype=float), np.asarray(centre_b, dtype=float), np.asarray(axes_b, dtype=float)
    R = size_a[0]
    if kind_b == "sphere":
        return float(np.linalg.norm(ca - cb)) - R - size_b[0]
    if kind_b == "capsule":
        a = B[:, 2]
        s = float(np.clip((ca - cb) @ a, -0.5 * size_b[1], 0.5 * size_b[1]))
        return float(np.linalg.norm(ca - (cb + s * a))) - R - size_b[0]
    p = B.T @ (ca - cb)
    h = 0.5 * np.asarray(size_b, dtype=float)
    if np.all(np.abs(p) <= h):  # the centre inside: the nearest face
        return -float(np.min(h - np.abs(p))) - R
    return float(np.linalg.norm(p - np.clip(p, -h, h))) - R


def _poses(r, meta):
    """{shape index: (centres (k, 3), axes (k, 3, 3))} along the run, from the
    bodies' paths and each shape's pose in its body (as drawn)."""
    import numpy as np

    out = {}
    k = len(r.t)
    for i, s in enumerate(meta["shapes"]):
        if s["body"] == "ground":
            out[i] = (np.tile(np.asarray(s["centre"], dtype=float), (k, 1)),
                      np.tile(np.asarray(s["axes"], dtype=float), (k, 1, 1)))
            continue
        b = meta["bodies"][s["body"]]
        R0, r0 = np.asarray(b["R0"]), np.asarray(b["position"])
        local = R0.T @ (np.asarray(s["centre"]) - r0)
        A = R0.T @ np.asarray(s["axes"])
        path = r.body(s["body"])
        Rk = path.rotation
        out[i] = (path.position + np.einsum("kij,j->ki", Rk, local), np.einsum("kij,jl->kil", Rk, A))
    return out


def contact_gaps(meta, c, poses, k):
    """The gaps of contact c's points at output k (the pair's points as listed
    in the docs); the points on the plane for a plane pair (else None)."""
    import numpy as np

    a, b = meta["shapes"][c["shape"]], meta["shapes"][c["other"]] if c["other"] is not None else None
    ca, Aa = poses[c["shape"]][0][k], poses[c["shape"]][1][k]
    if b is None:
        return plane_gaps(a["kind"], a["size"], ca, Aa, meta["plane"]["n"], meta["plane"]["p0"])
    cb, Ab = poses[c["other"]][0][k], poses[c["other"]][1][k]
    return np.array([pair_gap(a["kind"], a["size"], ca, Aa, b["kind"], b["size"], cb, Ab)]), None


# ---------------------------------------------------------------------------
# The laws (run in the worker, on a Result)
# ---------------------------------------------------------------------------

def energy_tol(method, rtol):
    return ENERGY_TOL.get(method, ENERGY_TOL_DEFAULT) * (rtol / 1e-8)


def _method(r):
    method = r.stats.get("method")
    if method:
        return method
    form = r.stats.get("formulation")
    return "projection-" + r.stats.get("integrator", "bdf") if form == "projection" else form


def _kinetic_and_gravity(r, meta):
    """(k,) kinetic energy and (k,) gravity's potential, from the bodies' paths."""
    import numpy as np

    K = np.zeros(len(r.t))
    V = np.zeros(len(r.t))
    for name, b in meta["bodies"].items():
        path = r.body(name)
        m, I = b["mass"], np.asarray(b["inertia_matrix"])
        w = path.angular_velocity
        Rk = path.rotation
        Iw = np.einsum("kij,jl,kml,km->ki", Rk, I, Rk, w)  # R I R^T w
        K += 0.5 * m * np.sum(path.velocity ** 2, axis=1) + 0.5 * np.sum(w * Iw, axis=1)
        V += m * G * path.position[:, 2]
    return K, V


def _near_events(t, events):
    import numpy as np

    times = np.array([x["t"] for x in events])
    if not len(times):
        return np.zeros(len(t), bool)
    near = np.min(np.abs(t[:, None] - times[None, :]), axis=1) <= 1e-9 * (1.0 + np.abs(t))
    return near & (t > t[0])


def contact_problems(r, meta):
    """The laws the run's result r breaks, as lines of text (empty: none)."""
    import numpy as np

    bad = []
    t = np.asarray(r.t)
    events = list(r.events)
    method = _method(r)
    # index1 holds the Euler parameters' norms and the stick rows at
    # acceleration level only, and CVODE cannot project Adams steps: their
    # residual (m) is how far positions drifted; its work is the forces' over it
    drifts = method in ("index1", "projection-adams")
    residual = float(np.max(np.asarray(r.residual))) if drifts and np.asarray(r.residual).size else 0.0
    drift = 10.0 * residual
    tol_E = energy_tol(method, meta["rtol"]) * meta["energy_scale"] + drift * meta["force"]

    readings = {}
    for c in meta["contacts"]:
        try:
            readings[c["name"]] = r.contact(c["name"])
        except Exception as e:  # noqa: BLE001 - a successful run must give its readings
            bad.append(f"contact readings refused: r.contact({c['name']!r}) raised {type(e).__name__}: {e}")
    for name, x in readings.items():
        for attr in ("normal_force", "friction_force", "point", "normal", "penetration", "slip_speed"):
            if not np.all(np.isfinite(np.asarray(getattr(x, attr), dtype=float))):
                bad.append(f"non-finite contact reading: r.contact({name!r}).{attr}")
    if bad:
        return bad

    # events: counted as listed, in time order
    if r.stats.get("events") is not None and r.stats["events"] != len(events):
        bad.append(f"events miscounted: r.stats['events'] = {r.stats['events']}, r.events lists {len(events)}")
    times = np.array([x["t"] for x in events])
    if len(times) and np.any(np.diff(times) < 0):
        k = int(np.flatnonzero(np.diff(times) < 0)[0])
        bad.append(f"events out of order: event {k + 1} at t = {times[k + 1]!r} after event {k} at {times[k]!r}")
    near_event = _near_events(t, events)

    # each contact's points (the docs' pairs, from the bodies' poses) and its
    # onsets and releases: a point pressed without an onset (a contact passed
    # through within a step: its force never acted) masks the outputs it
    # shows pressed from the laws of energy, which it would break by its
    # reading alone
    poses = _poses(r, meta)
    gaps, unseen = {}, np.zeros(len(t), bool)
    for c in meta["contacts"]:
        gaps[c["name"]] = [contact_gaps(meta, c, poses, k) for k in range(len(t))]
        mine = [e for e in events if e["element"] == c["name"]]
        shape = meta["shapes"][c["shape"]]
        if shape["kind"] == "capsule" and shape["size"][1] == 0.0:
            continue  # (a capsule of length 0 against a plane: its two points coincide, or are one; not counted)
        # (events are found at the steps' ends: a point leaving its plane by
        # less than the run's position error, 10 rtol times the shape's size,
        # and back within one step may go unseen)
        unresolved = drift + 10.0 * meta["rtol"] * max(shape["size"])
        found, through = _onsets_and_releases(c, mine, [g for g, _ in gaps[c["name"]]], t, unresolved, shape["kind"])
        bad += found
        if through:
            unseen |= np.array([bool(np.any(g < 0.0)) for g, _ in gaps[c["name"]]])
    seen = ~unseen

    # energy: the contacts' damping and friction take it, a stick's projection
    # takes it; nothing gives it
    E = np.asarray(r.energy)
    idx = np.flatnonzero(seen)
    if len(idx):
        Es = E[idx]
        rise = Es - np.minimum.accumulate(Es)
        if np.max(rise) > tol_E:
            k = int(np.argmax(rise))
            j = int(np.argmin(Es[:k + 1]))
            bad.append(f"energy gained: r.energy rose from {Es[j]:.12g} J at t = {t[idx[j]]:.6g} to {Es[k]:.12g} J "
                       f"at t = {t[idx[k]]:.6g} (+{rise[k]:.3g} J, tolerance {tol_E:.3g} J)")
    if E[0] > meta["energy0"] + tol_E:
        bad.append(f"energy gained at the start: r.energy[0] = {E[0]:.12g} J, the drawn state has "
                   f"{meta['energy0']:.12g} J (+{E[0] - meta['energy0']:.3g} J, tolerance {tol_E:.3g} J)")

    # penetration: what the energy left for the contacts allows
    K, Vg = _kinetic_and_gravity(r, meta)
    elastic = np.zeros(len(t))
    for c in meta["contacts"]:
        d = np.maximum(readings[c["name"]].penetration, 0.0)
        elastic += c["stiffness"] * d ** 2.5 / 2.5
    left = meta["energy0"] + tol_E - K - Vg
    over = np.where(seen, elastic - left, 0.0)
    if np.max(over) > 0.0:
        k = int(np.argmax(over))
        worst = max(meta["contacts"], key=lambda c: readings[c["name"]].penetration[k])
        bad.append(f"penetration beyond the energy left: at t = {t[k]:.6g} the deepest points hold "
                   f"{elastic[k]:.6g} J (contact {worst['name']!r} {readings[worst['name']].penetration[k]:.6g} m "
                   f"deep), the energy left for them is {left[k]:.6g} J (the drawn {meta['energy0']:.6g} J less "
                   f"kinetic {K[k]:.6g} J and gravity's {Vg[k]:.6g} J)")
    A = meta["kinetic0"] + meta["elastic0"] + tol_E
    S = G * sum(math.sqrt(2.0 * b["mass"]) for b in meta["bodies"].values())
    reach = (math.sqrt(A) + 0.5 * S * (t - t[0])) ** 2
    for c in meta["contacts"]:
        d = np.maximum(readings[c["name"]].penetration, 0.0)
        over = np.where(seen, c["stiffness"] * d ** 2.5 / 2.5 - reach, 0.0)
        if np.max(over) > 0.0:
            k = int(np.argmax(over))
            bad.append(f"penetration beyond the initial energy's reach: contact {c['name']!r} {d[k]:.6g} m deep at "
                       f"t = {t[k]:.6g} holds {c['stiffness'] * d[k] ** 2.5 / 2.5:.6g} J, more than the initial "
                       f"energy and gravity's work could give ({reach[k]:.6g} J)")

    # the readings against the geometry, and the friction limits
    n_plane = np.asarray(meta["plane"]["n"])
    p0 = np.asarray(meta["plane"]["p0"])
    for c in meta["contacts"]:
        x = readings[c["name"]]
        a = meta["shapes"][c["shape"]]
        size = max(a["size"])
        tol_geo = GEOMETRY_TOL * (1.0 + size) + drift
        deepest = np.array([-float(np.min(g)) for g, _ in gaps[c["name"]]])
        pressing = x.normal_force > 0.0
        # (while the bounding spheres are apart a reading may be theirs: compared near contact only)
        near = deepest > -0.01 * size
        off = np.where(near & ~near_event, np.abs(x.penetration - deepest), 0.0)
        if np.max(off) > tol_geo:
            k = int(np.argmax(off))
            bad.append(f"penetration misread: contact {c['name']!r} reads {x.penetration[k]:.9g} m at t = {t[k]:.6g}, "
                       f"its deepest point is {deepest[k]:.9g} m in (tolerance {tol_geo:.3g})")
        if c["other"] is None:
            sign = -1.0 if c["plane_first"] else 1.0
            on = pressing & ~near_event
            if np.any(on):
                height = np.abs((x.point[on] - p0) @ n_plane)
                turned = np.linalg.norm(x.normal[on] - sign * n_plane[None], axis=1)
                if np.max(height) > tol_geo:
                    k = int(np.flatnonzero(on)[np.argmax(height)])
                    bad.append(f"contact point off the plane: contact {c['name']!r}'s point {x.point[k].tolist()} is "
                               f"{np.max(height):.3g} m from the plane at t = {t[k]:.6g}")
                if np.max(turned) > 1e-9 + drift:
                    k = int(np.flatnonzero(on)[np.argmax(turned)])
                    bad.append(f"contact normal not the plane's: contact {c['name']!r} reads {x.normal[k].tolist()} "
                               f"at t = {t[k]:.6g}, the plane's is {(sign * n_plane).tolist()}")
        # forces: never pulling, 0 while open, within their limits
        if np.min(x.normal_force) < 0.0:
            k = int(np.argmin(x.normal_force))
            bad.append(f"a contact pulls: contact {c['name']!r} normal_force {x.normal_force[k]:.6g} N at "
                       f"t = {t[k]:.6g}")
        state = np.asarray(x.state)
        ft = np.linalg.norm(np.asarray(x.friction_force), axis=1)
        opened = (state == "open") & ~near_event
        if np.any(opened & ((x.normal_force != 0.0) | (ft != 0.0))):
            k = int(np.flatnonzero(opened & ((x.normal_force != 0.0) | (ft != 0.0)))[0])
            bad.append(f"an open contact pushes: contact {c['name']!r} is open at t = {t[k]:.6g} with normal force "
                       f"{x.normal_force[k]:.6g} N, friction {ft[k]:.6g} N")
        slipping = (state == "slip") & ~near_event
        # (the friction reading is the force less its normal part: rounding of 1e-16 of the force)
        rounding = 1e-9 + 1e-12 * np.abs(x.normal_force)
        excess = np.where(slipping, ft - c["friction"] * x.normal_force * (1.0 + LIMIT_TOL) - rounding, 0.0)
        if np.max(excess) > 0.0:
            k = int(np.argmax(excess))
            bad.append(f"friction beyond its limit: contact {c['name']!r} slipping at t = {t[k]:.6g} with friction "
                       f"{ft[k]:.9g} N > mu F_n = {c['friction']} x {x.normal_force[k]:.9g} N")
        stuck = (state == "stick") & ~near_event
        mine = [e for e in events if e["element"] == c["name"]]
        if np.any(state == "stick") or any(e["kind"] == "friction" for e in mine):
            if not c["can_stick"]:
                k = int(np.flatnonzero(state == "stick")[0]) if np.any(state == "stick") else None
                bad.append(f"a round shape sticks: contact {c['name']!r} ({a['kind']}"
                           f"{' against ' + meta['shapes'][c['other']]['kind'] if c['other'] is not None else ''}) "
                           + (f"reads 'stick' at t = {t[k]:.6g}" if k is not None else "logs friction events"))
        if np.any(stuck):
            # (a body rocking about its anchor moves its pressing vertices,
            # deeper or shallower than the anchor by at most the deepest's
            # depth, at omega times that: the rows hold one point and the turn)
            omega = np.linalg.norm(np.asarray(r.body(a["body"]).angular_velocity), axis=1)
            fast = np.where(stuck, x.slip_speed - omega * np.abs(x.penetration), 0.0)
            if np.max(fast) > STICK_SLIP * c["slip_velocity"] + drift:
                k = int(np.argmax(fast))
                bad.append(f"a stuck contact slips: contact {c['name']!r} reads 'stick' at t = {t[k]:.6g} slipping at "
                           f"{fast[k]:.3g} m/s (v_s = {c['slip_velocity']})")
            excess = np.where(stuck, ft - c["static_friction"] * x.normal_force * (1.0 + LIMIT_TOL) - rounding, 0.0)
            if np.max(excess) > 0.0:
                k = int(np.argmax(excess))
                bad.append(f"a stuck contact beyond its limit: contact {c['name']!r} stuck at t = {t[k]:.6g} holds "
                           f"friction {ft[k]:.9g} N > mu_s F_n = {c['static_friction']} x {x.normal_force[k]:.9g} N")
        bad += _stick_and_slip(c, mine, state, t, near_event)
    return bad


def _stick_and_slip(c, mine, state, t, near_event):
    """Stick and slip events alternate, and the state reads "stick" exactly between them."""
    import numpy as np

    intervals, start = [], None
    for e in mine:
        if e["kind"] != "friction":
            continue
        if e["label"] == "stick":
            if start is not None:
                return [f"stick and slip out of turn: contact {c['name']!r} sticks at t = {e['t']!r}, stuck since "
                        f"{start!r}"]
            start = e["t"]
        elif e["label"] == "slip":
            if start is None:
                return [f"stick and slip out of turn: contact {c['name']!r} lets go at t = {e['t']!r} without "
                        f"sticking"]
            intervals.append((start, e["t"]))
            start = None
    if start is not None:
        intervals.append((start, math.inf))
    inside = np.zeros(len(t), bool)
    edge = np.zeros(len(t), bool)
    for t1, t2 in intervals:
        inside |= (t > t1) & (t < t2)
        inside |= (t == t[0]) & (t1 == t[0]) & (t2 > t[0])
        edge |= (np.abs(t - t1) <= 1e-12 * (1.0 + abs(t1))) | (np.abs(t - t2) <= 1e-12 * (1.0 + abs(t2)))
    disagree = ((state == "stick") != inside) & ~edge & ~near_event
    if np.any(disagree):
        k = int(np.flatnonzero(disagree)[0])
        return [f"state disagrees with events: contact {c['name']!r} reads {state[k]!r} at t = {t[k]:.6g}, its "
                f"stick/slip events say {'stuck' if inside[k] else 'not stuck'}"]
    return []


DUPLICATE_DT = 1e-6  # s: the same crossing logged again this soon (a point's second onset or release)
GAP_AMBIGUOUS = 1e-8  # m: a point this near its plane or shape may be either side (an event's time is approximate)


def _count_problem(c, crossings, gaps, t, drift, may_skip=()):
    """None if the crossings (onsets, releases) keep a consistent count of
    contact c's pressing points: starting at the geometry's, within 0..its
    points, equal to the geometry's at every output not at a crossing's
    instant (a point whose gap is 0 to GAP_AMBIGUOUS may be either), each of
    the crossings numbered in may_skip counted or not; else (fewer, what breaks
    it): "fewer" if the crossings leave no point pressing where the geometry
    shows some."""
    import numpy as np

    tol = GAP_AMBIGUOUS + drift

    def possible(g):  # the counts of pressing points the gaps g allow
        sure = int(np.sum(g < -tol))
        return set(range(sure, sure + int(np.sum(np.abs(g) <= tol)) + 1))

    n = len(gaps[0])
    counts = possible(gaps[0])
    start = sorted(counts)
    crossing_t = np.array([e["t"] for e in crossings])
    j = onsets = 0
    for k in range(1, len(t)):
        while j < len(crossings) and crossings[j]["t"] <= t[k]:
            e = crossings[j]
            step = 1 if e["label"] == "onset" else -1
            onsets += step > 0
            counts = {x + step for x in counts if 0 <= x + step <= n} | (counts if j in may_skip else set())
            j += 1
            if not counts:
                return False, (f"contact {c['name']!r} has no count of its {n} points pressing left after its "
                               f"{e['label']} at t = {e['t']!r} ({start[0]}..{start[-1]} at t0, {onsets} onsets "
                               f"and {j - onsets} releases since)")
        if len(crossing_t) and np.min(np.abs(crossing_t - t[k])) <= 1e-9 * (1.0 + t[k]):
            continue
        geometry = possible(gaps[k])
        if not counts & geometry:
            # (the crossings account for no point pressing where the geometry shows some: passed unseen)
            fewer = counts == {0} and min(geometry) > 0
            return fewer, (f"at t = {t[k]:.9g} the geometry shows {min(geometry)}..{max(geometry)} of contact "
                           f"{c['name']!r}'s {n} points pressing (deepest {-float(np.min(gaps[k])):.3g} m), its "
                           f"{onsets} onsets and {j - onsets} releases leave {sorted(counts)} (from "
                           f"{start[0]}..{start[-1]} at t0)")
        counts &= geometry
    return None


def _onsets_and_releases(c, mine, gaps, t, drift, kind):
    """Contact c's onsets less its releases count its pressing points
    (_count_problem). -> (problems, whether a point pressed without an onset).

    Broken apart: a count kept only if some crossings logged within
    DUPLICATE_DT after another of the same label (at another time: points
    crossing together are logged at one time) are taken as that one logged
    again ("a crossing logged twice"); a cylinder's against a plane (its
    rim points at 90 and 270 degrees from the deepest have one gap: they
    cross together, the same way, yet may be logged an onset and a release
    at one instant); points pressing where the crossings account for none
    ("pressed without an onset": a contact passed within a step, its force
    never acting); else "onsets and releases miscounted" (one of several
    points crossing together unlogged, or logged twice)."""
    crossings = [e for e in mine if e["kind"] == "restart"]
    problem = _count_problem(c, crossings, gaps, t, drift)
    if problem is None:
        return [], False
    again = {i for i, e in enumerate(crossings)
             if any(x["label"] == e["label"] and 0.0 < e["t"] - x["t"] <= DUPLICATE_DT for x in crossings[:i])}
    if again and _count_problem(c, crossings, gaps, t, drift, again) is None:
        e = crossings[min(again)]
        first = [x for x in crossings if x["label"] == e["label"] and x["t"] < e["t"]][-1]
        return [f"a crossing logged twice: contact {c['name']!r} logs an {e['label']} at t = {first['t']!r} "
                f"(gap rate {first['speed_before']:.9g} m/s) and at t = {e['t']!r} ({e['speed_before']:.9g} m/s); "
                f"{len(again)} of its {len(crossings)} crossings follow one of their kind within {DUPLICATE_DT} s "
                f"({problem[1]})"], False
    if kind == "cylinder" and c["other"] is None:
        # (its rim points move along the rims: a crossing's label, from the
        # rate of the body's material point there, need not be the gap's)
        mixed = ""
        for e in crossings:
            other = [x for x in crossings if abs(x["t"] - e["t"]) <= DUPLICATE_DT and x["label"] != e["label"]]
            if other:
                mixed = (f"; it logs an {e['label']} (gap rate {e['speed_before']:.6g} m/s) and an "
                         f"{other[0]['label']} (gap rate {other[0]['speed_before']:.6g} m/s) at one instant "
                         f"(t = {e['t']!r}, {other[0]['t']!r})")
                break
        return [f"a cylinder's crossings mislabelled: {problem[1]}{mixed}"], False
    fewer, detail = _count_problem(c, crossings, gaps, t, drift, again) or problem
    if fewer:
        return ["pressed without an onset: " + detail], True
    return ["onsets and releases miscounted: " + detail], False


LAWS_BROKEN = "laws broken: "


def check(r, meta):
    """Raise an AssertionError whose first line names the broken laws (LAWS_BROKEN, then
    the laws' names joined by "; "), the problems one a line after it."""
    bad = contact_problems(r, meta)
    if bad:
        laws = sorted({line.split(":")[0] for line in bad})
        raise AssertionError(LAWS_BROKEN + "; ".join(laws) + "\n" + "\n".join(bad))


def check_pickles(m, r):
    """"pickles of contact models": the scene's model and its Result survive
    a pickle and a deep copy (issue 56: a Shape could not be unpickled): the
    same description and shapes, and the copied Result's arrays and contact
    readings the original's, bit for bit. AssertionError as check's."""
    import copy
    import pickle

    import numpy as np

    bad = []
    for how, model in (("pickled", pickle.loads(pickle.dumps(m))), ("deep-copied", copy.deepcopy(m))):
        if model.to_text() != m.to_text() or model.shapes != m.shapes:
            bad.append(f"pickles of contact models: the {how} model differs")
    again = pickle.loads(pickle.dumps(r))
    if not (np.array_equal(again.q, r.q) and again.events == r.events):
        bad.append("pickles of contact models: the unpickled Result's q or events differ")
    for kind, kw in m.elements:
        if kind == "add_contact":
            mine, theirs = r.contact(kw["name"]), again.contact(kw["name"])
            if not (np.array_equal(mine.normal_force, theirs.normal_force) and
                    list(mine.state) == list(theirs.state)):
                bad.append(f"pickles of contact models: '{kw['name']}' reads otherwise in the unpickled Result")
    if bad:
        raise AssertionError(LAWS_BROKEN + "pickles of contact models\n" + "\n".join(bad))


# ---------------------------------------------------------------------------
# Drawing scenes (the parent side)
# ---------------------------------------------------------------------------

def _r(x):
    return float(f"{x:.6g}")


def _v(*xs):
    return tuple(_r(x) for x in xs)


AXES = [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (1.0, 1.0, 0.0), (1.0, -2.0, 1.0), (0.0, 1.0, 1.0),
        (2.0, 1.0, -3.0)]
TILT_AXES = [(0.0, 1.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0)]
SIZES = {"sphere": [(0.05,), (0.1,), (0.2,)],
         "capsule": [(0.03, 0.1), (0.05, 0.2), (0.1, 0.4), (0.05, 0.0)],
         "box": None, "cylinder": [(0.05, 0.1), (0.1, 0.2), (0.2, 0.05), (0.03, 0.4)]}


class Builder:
    """What one case knows while it is drawn: its source lines and the
    numbers the checks need (as written in the source)."""

    def __init__(self, draw, known_bugs):
        import numpy as np

        self.np = np
        self.rot = _define_rot()
        self.draw = draw
        self.known_bugs = known_bugs
        self.lines = []
        self.bodies = {}  # name -> dict(mass, inertia_matrix, position, R0, velocity, angular_velocity)
        self.shapes = []  # dict(body, kind, size, centre, axes, var)
        self.contacts = []
        self.plane_n = np.array([0.0, 0.0, 1.0])

    def add(self, line):
        self.lines.append(line)

    def pick(self, options):
        return self.draw(st.sampled_from(options))

    def orientation(self, aligned_ok=True):
        """(source, matrix) of a drawn orientation: identity, a quarter turn, or a turn about an axis."""
        d = self.draw
        how = self.pick(["identity", "quarter", "turn", "turn", "turn"] if aligned_ok else ["turn"])
        if how == "identity":
            return None, self.np.eye(3)
        if how == "quarter":
            axis = self.pick(AXES[:3])
            k = d(st.integers(1, 3))
            src = f"rot({axis!r}, {k} * np.pi / 2)"
            return src, self.rot(axis, k * self.np.pi / 2)
        axis = self.pick(AXES)
        k = d(st.integers(-15, 16))
        src = f"rot({axis!r}, {k} * np.pi / 16)"
        return src, self.rot(axis, k * self.np.pi / 16)


def _inertia(b, kind, size, mass):
    """(source value, matrix in body axes) of a drawn inertia: the shape's
    own (uniform), a random mass distribution's principal moments, or such
    turned into a full tensor. Each satisfies the triangle inequality with
    margin (2 m c^2 for the smallest spread c >= 0.01 m)."""
    np = b.np
    how = b.pick(["shape", "spread", "spread", "tensor"])
    if how == "shape":
        if kind == "sphere":
            a = b_ = c = math.sqrt(0.2) * size[0]
        elif kind in ("box", "mesh"):  # (a mesh: as its box)
            a, b_, c = (s / math.sqrt(12.0) for s in size[:3])
        else:  # capsule, cylinder: a solid cylinder of its length (the capsule's caps ignored)
            R, L = size
            a = b_ = 0.5 * R
            c = max(L, 0.02) / math.sqrt(12.0)
        spread = (max(a, 0.01), max(b_, 0.01), max(c, 0.01))
    else:
        spread = tuple(b.pick([0.01, 0.03, 0.1, 0.2]) for _ in range(3))
    a, b_, c = spread
    moments = [mass * (b_ * b_ + c * c), mass * (a * a + c * c), mass * (a * a + b_ * b_)]
    moments = [_r(x) for x in moments]
    if how != "tensor":
        return tuple(moments), np.diag(moments)
    _, R = b.orientation(aligned_ok=False)
    tensor = R @ np.diag(moments) @ R.T
    tensor = 0.5 * (tensor + tensor.T)
    rows = tuple(tuple(float(f"{x:.9g}") for x in row) for row in tensor)
    M = np.array(rows)
    M = 0.5 * (M + M.T)
    return tuple(tuple(float(x) for x in row) for row in M), M


def _shape_kind(b, only=None):
    """(kind, size) of a drawn shape (a capsule of length 0 among them: a
    sphere; a mesh: a box with a low vertex, mesh_vertices' size)."""
    kind = b.pick(only or ["sphere", "capsule", "box", "cylinder", "mesh"])
    if kind == "box":
        size = tuple(b.pick([0.05, 0.1, 0.2, 0.4]) for _ in range(3))
    elif kind == "mesh":  # the low vertex under the bottom face, a little or far
        edges = tuple(b.pick([0.1, 0.2, 0.4, 1.0]) for _ in range(3))
        where = tuple(b.pick([0.0, 0.1, -0.2, 0.4]) for _ in range(2))
        size = edges + where + (_r(min(edges[:2]) * b.pick([0.01, 0.03, 0.1, 0.3])),)
    else:
        size = b.pick(SIZES[kind])
    return kind, size


def _velocities(b, rest):
    d = b.draw
    if rest:
        return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
    v = tuple(b.pick([0.0, 0.0, 0.1, -0.1, 0.5, -0.5, 2.0, -2.0]) for _ in range(3))
    w = tuple(b.pick([0.0, 0.0, 0.5, -0.5, 3.0, -3.0, 10.0]) for _ in range(3))
    if d(st.integers(0, 3)) == 0:
        w = (0.0, 0.0, 0.0)
    return v, w


def _law(b):
    d = b.draw
    k = _r(10.0 ** (d(st.integers(10, 16)) / 2.0))
    e = _r(d(st.integers(2, 10)) / 10.0)
    mu = b.pick([0.0, 0.1, 0.3, 0.5, 0.8, 1.0])
    law = {"stiffness": k, "restitution": e, "friction": mu}
    extra = {}
    if d(st.integers(0, 2)) == 0:
        extra["static_friction"] = _r(mu + b.pick([0.0, 0.1, 0.3, 0.5]))
    if d(st.integers(0, 3)) == 0:
        extra["slip_velocity"] = b.pick([1e-3, 1e-2, 1e-5])
    return law, extra


def _add_contact(b, name, shape, other, plane_first=False):
    """A contact between shape and other (an index, or None: the floor)."""
    law, extra = _law(b)
    s = b.shapes[shape]
    va = s["var"]
    vb = "floor" if other is None else b.shapes[other]["var"]
    first, second = (vb, va) if plane_first else (va, vb)
    kw = ", ".join(f"{k}={v!r}" for k, v in {**law, **extra}.items())
    b.add(f"m.add_contact({name!r}, {first}, {second}, {kw})")
    mu = law["friction"]
    b.contacts.append({"name": name, "shape": shape, "other": other, "plane_first": plane_first,
                       "stiffness": law["stiffness"], "restitution": law["restitution"], "friction": mu,
                       "static_friction": extra.get("static_friction", mu),
                       "slip_velocity": extra.get("slip_velocity", 1e-4),
                       "can_stick": other is None and s["kind"] in ("box", "mesh")})


def _body(b, name, kind, size, place, R, velocity, angular_velocity, src_R, exact=False):
    """A body with one shape, of axes R @ its turn in the body, centred at
    place(those axes) (global); the body's centre of mass is off the shape's
    centre sometimes. -> the shape's index."""
    np = b.np
    d = b.draw
    mass = b.pick([0.1, 0.5, 1.0, 2.0, 5.0])
    inertia, I = _inertia(b, kind, size, mass)
    # the shape sits off the centre of mass (in body axes), sometimes turned in it
    offset = (0.0, 0.0, 0.0)
    if d(st.integers(0, 3)) == 0:
        scale = 0.3 * max(size)
        offset = tuple(scale * b.pick([0.0, 0.5, -1.0]) for _ in range(3))
    turn_src, turn = (None, np.eye(3))
    if d(st.integers(0, 4)) == 0:
        turn_src, turn = b.orientation(aligned_ok=True)
    axes = R @ turn
    n = b.plane_n
    if kind == "cylinder" and not b.known_bugs and abs(axes[:, 2] @ n) > math.cos(math.radians(25.0)):
        # (standing on an end, or nearly: KNOWN_BUGS) laid on its side instead
        turn_src = f"{turn_src} @ rot((1.0, 0.0, 0.0), np.pi / 2)" if turn_src else "rot((1.0, 0.0, 0.0), np.pi / 2)"
        turn = turn @ b.rot((1.0, 0.0, 0.0), np.pi / 2)
        axes = R @ turn
    # (exact: the coordinates to the last bit, so that a shape placed touching touches to rounding)
    rounded = (lambda *x: tuple(float(v) for v in x)) if exact else _v
    centre = rounded(*place(axes))
    position = rounded(*(np.asarray(centre) - R @ np.asarray(offset)))
    args = f"mass={mass!r}, inertia={inertia!r}, position={position!r}"
    if src_R:
        args += f", orientation={src_R}"
    if any(velocity):
        args += f", velocity={tuple(velocity)!r}"
    if any(angular_velocity):
        args += f", angular_velocity={tuple(angular_velocity)!r}"
    b.add(f"m.add_body({name!r}, {args})")
    b.bodies[name] = {"mass": mass, "inertia_matrix": I.tolist(), "position": list(position), "R0": R.tolist(),
                      "velocity": [float(x) for x in velocity],
                      "angular_velocity": [float(x) for x in angular_velocity]}
    shape_axes_src = src_R if turn_src is None else (f"{src_R} @ {turn_src}" if src_R else turn_src)
    var = f"s{len(b.shapes)}"
    # (a mesh: its file, written by the worker)
    if kind == "mesh" and "import fuzz_contacts" not in b.lines:
        b.add("import fuzz_contacts")
    given = f"'mesh', (1.0, 1.0, 1.0)" if kind == "mesh" else f"{kind!r}, {size!r}"
    b.add(f"{var} = m.add_shape({name!r}, {given}, {centre!r}" + (f", {shape_axes_src}" if shape_axes_src else "")
          + (f", mesh=fuzz_contacts.low_point_mesh({size!r})" if kind == "mesh" else "") + ", role='collision')")
    b.shapes.append({"body": name, "kind": kind, "size": list(size), "centre": list(centre), "axes": axes.tolist(),
                     "var": var})
    return len(b.shapes) - 1


def _place(b, kind, size, axes, plane, at_s, at_u, lift):
    """The centre of a shape whose lowest point is lift above the plane (negative: pressed in), at (s, u) along it."""
    n, t1, t2 = plane["n"], plane["t1"], plane["t2"]
    h = support(kind, size, axes, -n)
    return at_s * t1 + at_u * t2 + (lift + h) * n


def _lift(b, kind, mass, k_guess=1e7):
    """How far above the plane a shape starts: resting (pressed in about its
    static depth), touching, a little or well above. -> (lift, at rest?, exact coordinates?)"""
    how = b.pick(["resting", "touching", "touching", "gap", "gap", "high"])
    if how == "resting":
        depth = (mass * G / k_guess) ** (2.0 / 3.0)
        return -_r(depth * b.pick([0.1, 0.5, 1.0, 2.0])), True, False
    if how == "touching":  # to rounding (exact), or a hair above or in
        lift = b.pick([0.0, 0.0, 1e-12, -1e-12, 1e-9])
        return lift, b.draw(st.booleans()), True
    if how == "gap":
        return b.pick([1e-4, 1e-3, 0.01, 0.05]), False, False
    return b.pick([0.1, 0.3, 0.5]), False, False


def _initial_energy(b, plane):
    """(kinetic, gravity's potential, the contacts' elastic energy) of the drawn state."""
    np = b.np
    K = Vg = 0.0
    for body in b.bodies.values():
        v, w = np.asarray(body["velocity"]), np.asarray(body["angular_velocity"])
        R, I = np.asarray(body["R0"]), np.asarray(body["inertia_matrix"])
        K += 0.5 * body["mass"] * v @ v + 0.5 * w @ (R @ I @ R.T) @ w
        Vg += body["mass"] * G * body["position"][2]
    elastic = 0.0
    for c in b.contacts:
        s = b.shapes[c["shape"]]
        if c["other"] is None:
            g, _ = plane_gaps(s["kind"], s["size"], s["centre"], s["axes"], plane["n"], plane["p0"])
        else:
            o = b.shapes[c["other"]]
            g = np.array([pair_gap(s["kind"], s["size"], s["centre"], s["axes"], o["kind"], o["size"], o["centre"],
                                   o["axes"])])
        dd = np.maximum(-g, 0.0)
        elastic += c["stiffness"] * float(np.sum(dd ** 2.5)) / 2.5
    return K, Vg, elastic


if st is not None:
    @st.composite
    def contact_cases(draw, known_bugs=False):
        """A case {"ops", "meta"}: a random scene of bodies in contact and a run
        of it (known_bugs: with the features of KNOWN_BUGS too)."""
        b = Builder(draw, known_bugs)
        np = b.np
        b.add(ROT_SOURCE.rstrip("\n"))
        b.add("m = mb.Model(dimension=3, gravity=(0.0, 0.0, -9.81))")
        # the ground plane, level or tilted about a horizontal axis
        tilt = b.pick([0, 0, 0, 1, 3, 5, 8])  # x pi / 36 (5 degrees)
        axis = b.pick(TILT_AXES)
        if tilt:
            P = b.rot(axis, tilt * np.pi / 36)
            b.add(f"floor = m.add_shape('ground', 'plane', (), (0.0, 0.0, 0.0), rot({axis!r}, {tilt} * np.pi / 36), "
                  "role='collision')")
        else:
            P = np.eye(3)
            b.add("floor = m.add_shape('ground', 'plane', (), role='collision')")
        plane = {"n": P[:, 2], "t1": P[:, 0], "t2": P[:, 1], "p0": np.zeros(3)}
        b.plane_n = plane["n"]

        obstacle = draw(st.integers(0, 3)) == 0  # a sphere dropped on, or thrown at, a shape fixed on the ground
        n_bodies = draw(st.integers(0 if obstacle else 1, 3))
        pair = None
        if draw(st.integers(0, 2)) == 0:  # a sphere meets another body's sphere, box or capsule
            pair = (b.pick(["sphere", "box", "capsule"]), b.pick(["drop", "throw"]))
            n_bodies = max(n_bodies, 2)
        k_guess = 1e7
        for i in range(n_bodies):
            name = f"b{i}"
            if pair is not None and i == 1:
                # the sphere of body 1 meets body 0's shape
                target = b.shapes[0]
                kind, size = "sphere", b.pick(SIZES["sphere"])
                src_R, R = b.orientation()
                gap = b.pick([0.0, 1e-3, 0.02, 0.1])
                c0, A0 = np.asarray(target["centre"]), np.asarray(target["axes"])
                v0 = np.asarray(b.bodies["b0"]["velocity"])
                if pair[1] == "drop":
                    side = np.array([draw(st.integers(-2, 2)), draw(st.integers(-2, 2)), 0.0]) * 0.25
                    side = side[0] * plane["t1"] * support(target["kind"], target["size"], A0, plane["t1"]) + \
                        side[1] * plane["t2"] * support(target["kind"], target["size"], A0, plane["t2"])
                    up = np.array([0.0, 0.0, 1.0])
                    centre = c0 + side + (support(target["kind"], target["size"], A0, up) + size[0] + gap) * up
                    velocity, w = _velocities(b, rest=draw(st.booleans()))
                else:
                    direction = b.pick([plane["t1"], plane["t2"], -plane["t1"]])
                    centre = c0 + (support(target["kind"], target["size"], A0, direction) + size[0] + gap) * direction
                    # (not below the plane)
                    lowest = (centre - plane["p0"]) @ plane["n"] - size[0]
                    if lowest < 0.0:
                        centre = centre + (b.pick([0.0, 1e-3, 0.05]) - lowest) * plane["n"]
                    speed = b.pick([0.5, 1.0, 3.0])
                    velocity = _v(*(v0 - speed * direction))
                    _, w = _velocities(b, rest=draw(st.booleans()))
                s = _body(b, name, kind, size, lambda axes, c=centre: c, R, velocity, w, src_R)
                # the sphere-X pair: the sphere given first, or second
                _pair_contact(b, "touch", s, 0, swap=draw(st.integers(0, 3)) == 0)
                _add_contact(b, f"floor{i}", s, None, plane_first=draw(st.integers(0, 4)) == 0)
                continue
            if pair is not None and i == 0:
                kind, size = _shape_kind(b, only=[pair[0]])
            else:
                kind, size = _shape_kind(b)
            src_R, R = b.orientation()
            mass_guess = 1.0
            lift, rest, exact = _lift(b, kind, mass_guess, k_guess)
            at_s = 1.5 * i - 1.5 + 0.1 * draw(st.integers(-2, 2))
            at_u = 0.1 * draw(st.integers(-3, 3))
            # the shape's axes: the body's turned by the shape's turn in it (drawn in _body; placed afterwards)
            v, w = _velocities(b, rest=rest and draw(st.booleans()))
            s = _body(b, name, kind, size, lambda axes: _place(b, kind, size, axes, plane, at_s, at_u, lift), R, v, w,
                      src_R, exact=exact)
            _add_contact(b, f"floor{i}", s, None, plane_first=draw(st.integers(0, 4)) == 0)
            if draw(st.integers(0, 6)) == 0:  # a second shape on the body: a sphere at one end, its own contact
                _second_shape(b, name, plane)
                _add_contact(b, f"floor{i}b", len(b.shapes) - 1, None)

        if obstacle:
            _obstacle(b, plane, f"b{n_bodies}", 1.5 * n_bodies - 1.5)

        method = b.pick(METHODS)
        rtol = b.pick([1e-7, 1e-8, 1e-8, 1e-9] if method != "index3" or known_bugs else [1e-8, 1e-8, 1e-9])
        t_end = b.pick([0.2, 0.5, 1.0])
        n_out = b.pick([51, 101, 201])
        run = f"r = mb.simulate(m, t_end={t_end!r}, n_out={n_out}, rtol={rtol!r}, atol={rtol * 1e-2!r}, " \
              f"method={method!r})"
        K0, V0, C0 = _initial_energy(b, plane)
        weight = sum(x["mass"] for x in b.bodies.values()) * G
        meta = {"bodies": b.bodies, "shapes": [{k: v for k, v in s.items() if k != "var"} for s in b.shapes],
                "contacts": b.contacts, "plane": {"n": plane["n"].tolist(), "p0": plane["p0"].tolist()},
                "rtol": rtol, "method": method, "t_end": t_end,
                "kinetic0": float(K0), "elastic0": float(C0), "energy0": float(K0 + V0 + C0),
                "energy_scale": _r(weight * 1.0 + K0 + C0 + 1.0), "force": _r(weight + 20.0)}
        return {"ops": case_ops("\n".join(b.lines), run, meta), "meta": meta}


def _obstacle(b, plane, name, at_s):
    """A sphere, box or capsule fixed on the ground (on the plane, or raised
    above it) at at_s along it, and a sphere (body name) dropped on it from
    above or thrown at it along the plane; the sphere's contacts with it and
    with the floor."""
    np = b.np
    d = b.draw
    kind, size = _shape_kind(b, only=["sphere", "box", "capsule"])
    src, axes = b.orientation()
    # on the plane (a little sunk in it), or raised above it (a shape on a post)
    raised = b.pick([-0.2 * min(size), -0.2 * min(size), 0.3, 1.0])
    centre = _v(*_place(b, kind, size, axes, plane, at_s, 0.0, raised))
    var = f"s{len(b.shapes)}"
    b.add(f"{var} = m.add_shape('ground', {kind!r}, {size!r}, {centre!r}" + (f", {src}" if src else "")
          + ", role='collision')")
    b.shapes.append({"body": "ground", "kind": kind, "size": list(size), "centre": list(centre),
                     "axes": axes.tolist(), "var": var})
    target = len(b.shapes) - 1
    R_ball = b.pick(SIZES["sphere"])
    gap = b.pick([0.0, 1e-3, 0.05, 0.3, 1.0])
    c0 = np.asarray(centre)
    if d(st.booleans()):  # dropped from above, on its centre or a little off it
        off = 0.5 * support(kind, size, axes, plane["t1"]) * b.pick([0, 0, 1, -1, 2])
        up = np.array([0.0, 0.0, 1.0])
        at = c0 + off * plane["t1"] + (support(kind, size, axes, up) + R_ball[0] + gap) * up
        velocity, w = _velocities(b, rest=d(st.booleans()))
    else:  # thrown at it along the plane, from the side
        direction = b.pick([plane["t1"], plane["t2"], -plane["t2"]])
        at = c0 + (support(kind, size, axes, direction) + R_ball[0] + gap) * direction
        lowest = (at - plane["p0"]) @ plane["n"] - R_ball[0]
        if lowest < 0.0:
            at = at + (b.pick([0.0, 1e-3, 0.05]) - lowest) * plane["n"]
        velocity = _v(*(-b.pick([0.5, 2.0, 5.0]) * direction))
        _, w = _velocities(b, rest=d(st.booleans()))
    src_R, R = b.orientation()
    s = _body(b, name, "sphere", R_ball, lambda axes, c=at: c, R, velocity, w, src_R)
    _pair_contact(b, "obstacle", s, target, swap=d(st.integers(0, 3)) == 0)
    _add_contact(b, f"floor{name[1:]}", s, None)


def _second_shape(b, name, plane):
    """A sphere on body name, at one end of its first shape along the shape's own x."""
    np = b.np
    first = [s for s in b.shapes if s["body"] == name][0]
    A = np.asarray(first["axes"])
    R = b.pick([0.03, 0.05])
    reach = support(first["kind"], first["size"], A, A[:, 0])
    centre = np.asarray(first["centre"]) + reach * A[:, 0]
    low = (centre - plane["p0"]) @ plane["n"] - R
    if low < 0.0:
        centre = centre - low * plane["n"]
    centre = _v(*centre)
    var = f"s{len(b.shapes)}"
    b.add(f"{var} = m.add_shape({name!r}, 'sphere', ({R!r},), {centre!r}, role='collision')")
    b.shapes.append({"body": name, "kind": "sphere", "size": [R], "centre": list(centre), "axes": np.eye(3).tolist(),
                     "var": var})


def _pair_contact(b, name, sphere, other, swap=False):
    """The contact of a sphere (shape index) with another body's shape."""
    law, extra = _law(b)
    va, vb = b.shapes[sphere]["var"], b.shapes[other]["var"]
    first, second = (vb, va) if swap else (va, vb)
    kw = ", ".join(f"{k}={v!r}" for k, v in {**law, **extra}.items())
    b.add(f"m.add_contact({name!r}, {first}, {second}, {kw})")
    mu = law["friction"]
    b.contacts.append({"name": name, "shape": sphere, "other": other, "plane_first": False, "swapped": swap,
                       "stiffness": law["stiffness"], "restitution": law["restitution"], "friction": mu,
                       "static_friction": extra.get("static_friction", mu),
                       "slip_velocity": extra.get("slip_velocity", 1e-4), "can_stick": False})


def case_ops(code, run, meta):
    """The worker's ops of a case: build, run (its result checked by the
    mechanism fuzzer's result check), the laws of contact, and the pickles
    of the model and its Result (check_pickles)."""
    return [{"code": code + "\n", "kind": "build", "check": None},
            {"code": run + "\n", "kind": "simulate", "check": "result:r"},
            {"code": f"import fuzz_contacts\nfuzz_contacts.check(r, {meta!r})\n", "kind": "contact laws",
             "check": None},
            {"code": "import fuzz_contacts\nfuzz_contacts.check_pickles(m, r)\n", "kind": "pickles",
             "check": None}]


#: the rotation the cases' code defines (ROT_SOURCE), so that the builder's numbers are the code's to the bit
rot = _define_rot()
