"""Rotations in Python, in one place: Euler parameters (a unit quaternion,
components (w, x, y, z) as the core and add_body take them), rotation
matrices and the E(p) of lagmb/spatial.hpp. The core binds none of this
math, so the Python layer (results, joint space, URDF, pictures, viewer)
reads it from here; three.js's (x, y, z, w) order is the viewer's own."""

import math

import numpy as np


def matrix(p):
    """A(p), body axes into global axes, of unit Euler parameters p: (3, 3)
    of p (4,), (k, 3, 3) of p (k, 4)."""
    p = np.asarray(p, dtype=float)
    w, x, y, z = p[..., 0], p[..., 1], p[..., 2], p[..., 3]
    rows = [[w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z]]
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)


def E(p):
    """E(p), omega = 2 E(p) p' in global axes (lagmb/spatial.hpp): (3, 4) of
    p (4,), (k, 3, 4) of p (k, 4)."""
    p = np.asarray(p, dtype=float)
    w, x, y, z = p[..., 0], p[..., 1], p[..., 2], p[..., 3]
    rows = [[-x, w, -z, y], [-y, z, w, -x], [-z, -y, x, w]]
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)


def quaternion(R):
    """The unit quaternion (w, x, y, z) of a rotation matrix, w >= 0
    (Shepperd: from the largest of 4 w^2, 4 x^2, 4 y^2, 4 z^2 and the
    off-diagonal sums, so that no component comes from the square root of a
    difference that cancels)."""
    R = np.asarray(R, dtype=float)
    t = np.array([1.0 + R[0, 0] + R[1, 1] + R[2, 2], 1.0 + R[0, 0] - R[1, 1] - R[2, 2],
                  1.0 - R[0, 0] + R[1, 1] - R[2, 2], 1.0 - R[0, 0] - R[1, 1] + R[2, 2]])
    k = int(np.argmax(t))
    s = 2.0 * np.sqrt(t[k])
    if k == 0:
        p = [s / 4, (R[2, 1] - R[1, 2]) / s, (R[0, 2] - R[2, 0]) / s, (R[1, 0] - R[0, 1]) / s]
    elif k == 1:
        p = [(R[2, 1] - R[1, 2]) / s, s / 4, (R[0, 1] + R[1, 0]) / s, (R[0, 2] + R[2, 0]) / s]
    elif k == 2:
        p = [(R[0, 2] - R[2, 0]) / s, (R[0, 1] + R[1, 0]) / s, s / 4, (R[1, 2] + R[2, 1]) / s]
    else:
        p = [(R[1, 0] - R[0, 1]) / s, (R[0, 2] + R[2, 0]) / s, (R[1, 2] + R[2, 1]) / s, s / 4]
    p = np.array(p)
    return (p if p[0] >= 0 else -p) / np.linalg.norm(p)


def turn(axis, angle):
    """Rotation by `angle` about the unit `axis` (Rodrigues)."""
    K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1.0 - math.cos(angle)) * (K @ K)


def from_rpy(rpy):
    """R = Rz(yaw) Ry(pitch) Rx(roll): URDF's fixed-axis roll, pitch, yaw."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def turned(p, p0):
    """The angle (rad, in [0, pi]) of the rotation from Euler parameters p0
    (4,) to each row of p (k, 4): that of p0* p."""
    cos_half = np.abs(np.asarray(p) @ np.asarray(p0))  # the w of p0* p
    return 2.0 * np.arccos(np.clip(cos_half, 0.0, 1.0))
