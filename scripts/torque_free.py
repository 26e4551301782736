"""The independent reference for a torque-free rigid body: Euler's equations in the
body frame with q' = 1/2 q (0, omega_body), integrated by scipy's DOP853 at rtol 1e-12
(atol 1e-14), identity orientation at t = 0 (so omega0 is also the body-frame value).
numpy and scipy only, so that the accuracy report, the stress suite, the benchmarks
and the peers' script (in its own venv) share it."""
import numpy as np
from scipy.integrate import solve_ivp

from quaternion import quat_mul


def torque_free_reference(inertia, omega0, T):
    """Unit quaternion (w, x, y, z) at time T of a body of principal inertia `inertia`."""
    I = np.asarray(inertia, dtype=float)

    def rhs(t, y):
        w, q = y[:3], y[3:]
        return np.r_[np.cross(I * w, w) / I, 0.5 * quat_mul(q, np.r_[0.0, w])]

    sol = solve_ivp(rhs, (0.0, T), np.r_[omega0, 1.0, 0, 0, 0], method="DOP853",
                    rtol=1e-12, atol=1e-14)
    q = sol.y[3:, -1]
    return q / np.linalg.norm(q)
