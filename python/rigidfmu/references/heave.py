"""The floating box's heave as an independent reference (docs/reports/media.md's model written
again here, solved by scipy), shared by the accuracy report and the stress suite."""
import math

from scipy.integrate import solve_ivp

G = 9.81
RHO_WATER, MU_WATER = 998.2, 1.002e-3


def heave(m, size, z0, times):
    """z at `times` of an upright box in water whose surface is z = 0, released at rest:
    m z'' = -m g + rho g V_sub - f (mu beta + 1/2 rho C_d A |v|) v with V_sub = A d,
    d = clamp(lz/2 - z, 0, lz), f = V_sub / V_b, A = lx ly, C_d 1.05,
    beta = 6 pi (r_n/3 + 2 r_s/3), r_n = sqrt(A/pi), r_s = sqrt(S/(4 pi)) (Leith).
    DOP853 at rtol 1e-12 (the drag is C1 at v = 0; the step control copes)."""
    lx, ly, lz = size
    A, Vb = lx * ly, lx * ly * lz
    S = 2 * (lx * ly + ly * lz + lx * lz)
    beta = 6 * math.pi * (math.sqrt(A / math.pi) / 3 + 2 * math.sqrt(S / (4 * math.pi)) / 3)

    def rhs(t, y):
        z, v = y
        d = min(max(lz / 2 - z, 0.0), lz)
        f = A * d / Vb
        drag = -f * (MU_WATER * beta + 0.5 * RHO_WATER * 1.05 * A * abs(v)) * v
        return [v, -G + (RHO_WATER * G * A * d + drag) / m]

    sol = solve_ivp(rhs, (0.0, float(times[-1])), [z0, 0.0], method="DOP853", rtol=1e-12,
                    atol=1e-15, t_eval=times)
    return sol.y[0]
