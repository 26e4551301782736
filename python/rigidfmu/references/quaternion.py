"""Quaternion arithmetic (w, x, y, z) for the scripts' and tests' independent
references: written once here, never taken from the code under test."""
import math

import numpy as np


def quat_mul(a, b):
    """Hamilton product a b."""
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return np.array([aw * bw - ax * bx - ay * by - az * bz,
                     aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx,
                     aw * bz + ax * by - ay * bx + az * bw])


def rotation_matrix(q):
    """R of the quaternion (w, x, y, z), normalised: body -> world."""
    w, x, y, z = np.asarray(q, dtype=float) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def quat_axis_angle(axis, angle):
    """The rotation by `angle` (rad) about `axis`; identity for a zero axis."""
    axis = np.asarray(axis, dtype=float)
    n = np.linalg.norm(axis)
    if n == 0.0:
        return np.array([1.0, 0, 0, 0])
    return np.r_[math.cos(angle / 2), math.sin(angle / 2) * axis / n]


def rotation_angle(q1, q2):
    """Angle (rad) of the rotation between two quaternions: 2 asin |vec(q2* q1)|
    (accurate near 0, where 2 acos |q1.q2| is not)."""
    q1 = np.asarray(q1, dtype=float) / np.linalg.norm(q1)
    q2 = np.asarray(q2, dtype=float) / np.linalg.norm(q2)
    rel = quat_mul(q2 * np.array([1, -1, -1, -1]), q1)
    return 2 * math.asin(min(1.0, float(np.linalg.norm(rel[1:]))))
