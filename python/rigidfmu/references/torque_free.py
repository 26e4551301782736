"""The independent reference for a torque-free rigid body: Euler's equations in the
body frame with q' = 1/2 q (0, omega_body), integrated by scipy's DOP853 at rtol 1e-12
(atol 1e-14). numpy and scipy only, so that the tests, the accuracy report, the stress
suite, the benchmarks and the peers' script (in its own venv) share it."""
import numpy as np
from scipy.integrate import solve_ivp

from rigidfmu.references.quaternion import quat_mul


def torque_free(inertia, omega_body0, q0, times):
    """q(t) (unit, w, x, y, z) and omega_body(t) at `times` (increasing, the last the
    end) of a body of principal inertia `inertia` starting at q0, omega_body0."""
    I = np.asarray(inertia, dtype=float)
    times = np.atleast_1d(np.asarray(times, dtype=float))

    def rhs(t, y):
        w, q = y[:3], y[3:]
        return np.r_[np.cross(I * w, w) / I, 0.5 * quat_mul(q, np.r_[0.0, w])]

    sol = solve_ivp(rhs, (0.0, float(times[-1])), np.r_[omega_body0, q0], method="DOP853",
                    rtol=1e-12, atol=1e-14, t_eval=times)
    if not sol.success:
        raise RuntimeError(f"torque-free reference: {sol.message}")
    q = sol.y[3:].T
    return q / np.linalg.norm(q, axis=1)[:, None], sol.y[:3].T


def torque_free_reference(inertia, omega0, T):
    """The unit quaternion at time T from the identity orientation (so omega0 is also
    the body-frame value)."""
    q, _ = torque_free(inertia, omega0, [1.0, 0.0, 0.0, 0.0], [T])
    return q[-1]
