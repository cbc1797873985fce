"""The links' inertias: each checked to be one a body can have (else built
with the nearest moments one has), and the links of a group merged into
one body's.
"""

import warnings

import numpy as np

from .._model_files import LARGEST
from .reader import UrdfWarning


def check_inertias(reader, links, names, strict):
    """Each of these links' inertia tensor positive semi-definite (to
    round-off: 1e-9 of the largest moment, and 1e-15 kg m^2). One that is
    not (no body has it; Romeo's hips in romeo_laas_small.urdf) is refused
    with strict; else it is built with the nearest principal moments a
    rigid body can have (about the same axes), and one UrdfWarning names
    each link, its line and its moments as written and as built."""
    repaired = []
    for name in names:
        link = links[name]
        moments, axes = np.linalg.eigh(link["inertia"])
        if moments.min() >= -1e-9 * abs(moments).max() - 1e-15:
            continue
        written = f"principal moments {moments.tolist()} kg m^2"
        if strict:
            reader.fail(link["inertia_element"], f"the inertia tensor is not positive semi-definite ({written}; "
                        "strict=False builds it with the nearest moments a rigid body can have)", f"link '{name}'")
        built = nearest_rigid_moments(moments)
        link["inertia"] = axes @ np.diag(built) @ axes.T
        repaired.append(f"link '{name}', line {link['inertia_element'].line}: {written}, built with "
                        f"{built.tolist()}")
    if repaired:
        warnings.warn(UrdfWarning(
            f"{reader.path}: {len(repaired)} inertia tensor{'s are' if len(repaired) > 1 else ' is'} not positive "
            "semi-definite (no body has such a tensor), each built with the nearest principal moments a rigid body "
            "can have (each >= 0 and at most the sum of the other two; the same axes; strict=True refuses "
            f"them): {'; '.join(repaired)}"), stacklevel=4)  # (load_urdf's caller)


def nearest_rigid_moments(moments):
    """The principal moments nearest to `moments` (Euclidean) that a rigid
    body has: each >= 0 and at most the sum of the other two. The set is a
    cone cut by six planes through 0, so the nearest point is the projection
    onto the planes of one set of them (its active constraints): each of
    the 64 sets tried, the nearest feasible point kept."""
    rows = np.vstack([np.eye(3), np.ones((3, 3)) - 2 * np.eye(3)])  # (l_i >= 0; l_j + l_k - l_i >= 0)
    best, distance = np.zeros(3), np.linalg.norm(moments)
    for mask in range(1, 64):
        A = rows[[k for k in range(6) if mask >> k & 1]]
        point = moments - A.T @ np.linalg.lstsq(A @ A.T, A @ moments, rcond=None)[0]
        if np.all(rows @ point >= -1e-12 * np.abs(moments).max()) and np.linalg.norm(point - moments) < distance:
            best, distance = point, np.linalg.norm(point - moments)
    return np.maximum(best, 0.0)



def merged_inertia(reader, links, pose, members, owner):
    """The body of a group of links fixed together (`members`, the first
    its frame): (mass, centre of mass in world axes, inertia about it in
    the first link's axes, its principal moments). Each link's inertia is
    moved to the common centre (parallel axes: m (d.d 1 - d d^T)); a zero
    moment (a massless link, a point mass) is made exactly 0, not
    round-off: the body runs through the augmented system's LU where its
    joints hold it (simulate names it where they do not). UrdfError for a
    centre, mass or inertia beyond LARGEST."""
    first = members[0]
    R0, p0 = pose[first]
    mass = sum(links[m]["mass"] for m in members)
    centres = {m: pose[m][1] + pose[m][0] @ links[m]["com"] for m in members}
    for m in members:
        if links[m]["mass"] > 0 and np.abs(centres[m]).max() > LARGEST:
            reader.fail(links[m]["inertial_element"], f"its centre of mass is {np.abs(centres[m]).max():g} m from "
                        f"the root: beyond what a model can hold (at most {LARGEST:g} m)", f"link '{m}'")
    # (a massless group: its first link's origin)
    com = sum(links[m]["mass"] * centres[m] for m in members) / mass if mass > 0 else p0
    inertia = np.zeros((3, 3))
    with np.errstate(over="ignore", invalid="ignore"):  # (m d^2 may overflow: refused below)
        for m in members:  # each link's inertia about the common centre, in world axes
            R, p = pose[m]
            d = centres[m] - com
            inertia += R @ links[m]["inertia"] @ R.T + links[m]["mass"] * (d @ d * np.eye(3) - np.outer(d, d))
    if not (np.all(np.isfinite(inertia)) and np.abs(inertia).max() <= LARGEST and mass <= LARGEST):
        reader.fail(links[first]["element"], f"mass {mass:g} kg, inertia about its centre of mass up to "
                    f"{np.abs(inertia).max():g} kg m^2: beyond what a model can hold (at most {LARGEST:g})", owner)
    inertia_body = R0.T @ inertia @ R0
    moments, axes = np.linalg.eigh(0.5 * (inertia_body + inertia_body.T))
    zero = moments <= 1e-9 * abs(moments).max() + 1e-15
    if zero.any():
        moments = np.where(zero, 0.0, moments)
        inertia_body = axes @ np.diag(moments) @ axes.T
    return mass, com, 0.5 * (inertia_body + inertia_body.T), moments
