"""Independent references computed in the tests, not by the code under test (the
shared ones live in rigidfmu.references)."""
import numpy as np

from rigidfmu.references.quaternion import quat_mul


def rotation_angle_between(q1, q2):
    """Angle (rad) of the rotation taking q2 to q1, for arrays of unit quaternions."""
    # 2 acos(|q1 . q2|) loses precision near 1: use 2 asin(|vector part of q2^-1 q1|).
    q1, q2 = np.atleast_2d(q1), np.atleast_2d(q2)
    conj = q2 * np.array([1, -1, -1, -1])
    rel = np.array([quat_mul(c, q) for c, q in zip(conj, q1)])
    return 2 * np.arcsin(np.minimum(1.0, np.linalg.norm(rel[:, 1:], axis=1)))


def loglog_slope(h, err):
    return np.polyfit(np.log(h), np.log(err), 1)[0]


def resting_depth(normal_acceleration, h, on_surface=True):
    """Depth (m) at which a contact holds a body at rest under a steady normal
    acceleration (m/s^2): the contact is a damped spring whose natural frequency is
    0.8/h against a surface and 0.4/h between two bodies (h the solver step; the guide's
    "How contacts are solved"), so the body sinks by a / (2 pi f)^2."""
    f = (0.8 if on_surface else 0.4) / h
    return normal_acceleration / (2 * np.pi * f) ** 2
