"""Independent references computed in the tests, not by the code under test."""
import numpy as np
from scipy.integrate import solve_ivp

from quaternion import quat_mul  # scripts/quaternion.py (tests/conftest.py puts scripts/ on the path)


def torque_free(inertia, omega_body0, q0, times):
    """Euler's equations in the body frame with q' = 1/2 q (0, omega_body), by scipy's
    DOP853 at rtol 1e-12. Returns q(t) (w, x, y, z) and omega_body(t) at `times`."""
    I = np.asarray(inertia, dtype=float)

    def rhs(t, y):
        w = y[:3]
        q = y[3:]
        dw = np.cross(I * w, w) / I
        dq = 0.5 * quat_mul(q, np.r_[0.0, w])
        return np.r_[dw, dq]

    sol = solve_ivp(rhs, (0.0, float(times[-1])), np.r_[omega_body0, q0], method="DOP853",
                    rtol=1e-12, atol=1e-14, t_eval=times)
    assert sol.success
    q = sol.y[3:].T
    return q / np.linalg.norm(q, axis=1)[:, None], sol.y[:3].T


def rotation_angle_between(q1, q2):
    """Angle (rad) of the rotation taking q2 to q1, for arrays of unit quaternions."""
    d = np.abs(np.sum(np.asarray(q1) * np.asarray(q2), axis=-1))
    # 2 acos(d) loses precision near d = 1: use 2 asin(|vector part of q2^-1 q1|).
    q1, q2 = np.atleast_2d(q1), np.atleast_2d(q2)
    conj = q2 * np.array([1, -1, -1, -1])
    rel = np.array([quat_mul(c, q) for c, q in zip(conj, q1)])
    return 2 * np.arcsin(np.minimum(1.0, np.linalg.norm(rel[:, 1:], axis=1)))


def loglog_slope(h, err):
    return np.polyfit(np.log(h), np.log(err), 1)[0]
