"""A torque-free rigid body through the FMU: conservation laws, an independent
high-precision reference, and the integrators' orders of convergence."""
import numpy as np
import pytest
from fmpy import simulate_fmu

import scenes
from reference import loglog_slope, rotation_angle_between
from rigidfmu.references.torque_free import torque_free

INERTIA = (1.0, 2.0, 3.0)
Q = [f"spinner.orientation[{i}]" for i in (1, 2, 3, 4)]
W = [f"spinner.angularVelocity[{i}]" for i in (1, 2, 3)]
L = [f"spinner.angularMomentum[{i}]" for i in (1, 2, 3)]


def cols(r, names):
    return np.column_stack([r[n] for n in names])


@pytest.fixture(scope="module")
def intermediate_axis_run(fmu_of):
    """omega0 = (0.01, 5, 0.01) rad/s near the intermediate axis: it flips every ~5.03 s."""
    fmu = fmu_of(scenes.free_spin(INERTIA, (0.01, 5.0, 0.01), method="rk4", step=1e-3))
    return simulate_fmu(str(fmu), stop_time=20.0, output_interval=0.05)


def test_intermediate_axis_conserves_energy_and_momentum(intermediate_axis_run):
    r = intermediate_axis_run
    w, Lw = cols(r, W), cols(r, L)
    energy = 0.5 * np.sum(w * Lw, axis=1)
    assert np.max(np.abs(energy / energy[0] - 1)) < 1e-9
    L0 = np.array(INERTIA) * np.array([0.01, 5.0, 0.01])
    assert np.max(np.linalg.norm(Lw - L0, axis=1)) / np.linalg.norm(L0) < 1e-12


def test_intermediate_axis_matches_high_precision_reference(intermediate_axis_run):
    r = intermediate_axis_run
    q_ref, w_body = torque_free(INERTIA, [0.01, 5.0, 0.01], [1, 0, 0, 0], r["time"])
    # the reference itself shows the physics: omega_y reverses about every 5 s
    assert np.min(w_body[:, 1]) < -4.9 and np.max(w_body[:, 1]) > 4.9
    q = cols(r, Q)
    # q and -q are one orientation: align signs, then compare component by component
    sign = np.sign(np.sum(q * q_ref, axis=1))[:, None]
    assert np.max(np.abs(q - sign * q_ref)) < 1e-7
    # as a rotation angle the error is twice that: RK4's truncation error at h = 1e-3,
    # largest at the flips (measured 1.26e-7 rad; 1.3e-8 rad at h = 5e-4)
    assert np.max(rotation_angle_between(q, q_ref)) < 1.5e-7
    # at the end time T = 20 s the rotation angle is far inside 1e-7 rad (4.4e-10)
    assert rotation_angle_between(q[-1:], q_ref[-1:])[0] < 1e-7
    assert np.max(np.abs(np.linalg.norm(q, axis=1) - 1)) < 1e-12


def orientation_error(fmu, method, h, T, omega0):
    # tolerance 0: dopri5 takes fixed steps, so that its order shows
    r = simulate_fmu(str(fmu), stop_time=T, output_interval=T,
                     start_values={"solver.method": method, "solver.step": h, "solver.tolerance": 0.0,
                                   # an order study: explicit Euler's energy gain is the point
                                   "solver.energyGainLimit": 0.0})
    q_ref, _ = torque_free(INERTIA, omega0, [1, 0, 0, 0], np.array([0.0, T]))
    return rotation_angle_between(cols(r, Q)[-1:], q_ref[-1:])[0]


@pytest.mark.parametrize("method,steps,order,tol", [
    (2, [0.02, 0.01, 0.005, 0.0025], 4.0, 0.4),  # rk4 (h |omega| within its spin limit 0.1)
    (1, [4e-3, 2e-3, 1e-3, 5e-4], 1.0, 0.2),     # euler
    # symplecticEuler: without torque the kick is nil and the drift is the splitting's
    # free rotation, second order (its first order shows with forces: test_stiff.py)
    (3, [0.02, 0.01, 0.005, 0.0025], 2.0, 0.2),
    (4, [0.02, 0.01, 0.005, 0.0025], 2.0, 0.2),  # splitting
    (5, [0.02, 0.01, 0.005, 0.0025], 4.0, 0.4),  # lieRk4
    (6, [0.08, 0.04, 0.02, 0.01], 5.0, 0.5),     # dopri5 with fixed steps
], ids=["rk4", "euler", "symplecticEuler", "splitting", "lieRk4", "dopri5"])
def test_convergence_order(fmu_of, method, steps, order, tol):
    """Smooth case: a spin close to the major axis. Error at T against DOP853."""
    omega0 = (0.4, 0.3, 3.0)
    fmu = fmu_of(scenes.free_spin(INERTIA, omega0, name="SmoothSpin"))
    errors = [orientation_error(fmu, method, h, 2.0, omega0) for h in steps]
    slope = loglog_slope(np.array(steps), np.array(errors))
    assert abs(slope - order) < tol, (errors, slope)


def test_splitting_keeps_L_exact_and_energy_bounded(fmu_of):
    """Near the intermediate axis at h = 1e-2 for 200 s: |L| (world L, in fact) is kept
    to rounding and the energy error stays bounded: no drift between the first and
    the last 50 s."""
    fmu = fmu_of(scenes.free_spin(INERTIA, (0.01, 5.0, 0.01), method="splitting", step=1e-2,
                                  name="SplitSpin"))
    r = simulate_fmu(str(fmu), stop_time=200.0, output_interval=0.5)
    w, Lw = cols(r, W), cols(r, L)
    L0 = np.array(INERTIA) * np.array([0.01, 5.0, 0.01])
    assert np.max(np.linalg.norm(Lw - L0, axis=1)) <= 1e-13 * np.linalg.norm(L0)
    rel = np.abs(0.5 * np.sum(w * Lw, axis=1) / (0.5 * L0 @ (L0 / np.array(INERTIA))) - 1)
    early, late = rel[r["time"] <= 50], rel[r["time"] >= 150]
    assert np.max(rel) < 1e-2
    assert np.max(late) < 2 * np.max(early) + 1e-12


def test_dopri5_meets_its_tolerance_and_reports_truthfully(fmu_of):
    """Adaptive Dormand-Prince: the error at T follows the tolerance down; the
    solver.errorEstimate output stays within the tolerance and solver.steps counts the
    accepted steps (more for a tighter tolerance)."""
    omega0 = (0.4, 0.3, 3.0)
    fmu = fmu_of(scenes.free_spin(INERTIA, omega0, method="dopri5", step=0.5, name="AdaptiveSpin"))
    q_ref, _ = torque_free(INERTIA, omega0, [1, 0, 0, 0], np.array([0.0, 2.0]))
    errors, steps = [], []
    for tol in (1e-5, 1e-7, 1e-9):
        r = simulate_fmu(str(fmu), stop_time=2.0, output_interval=0.5,
                         start_values={"solver.tolerance": tol},
                         output=Q + ["solver.steps", "solver.errorEstimate"])
        errors.append(rotation_angle_between(cols(r, Q)[-1:], q_ref[-1:])[0])
        steps.append(int(r["solver.steps"][-1]))
        assert 0.0 < r["solver.errorEstimate"][-1] <= tol
    assert errors[0] > errors[1] > errors[2]
    assert errors[2] < 1e-7
    assert steps[0] < steps[1] < steps[2]
    # a fixed-step method reports its internal steps too: 0.5 s of 1 ms
    r = simulate_fmu(str(fmu), stop_time=1.0, output_interval=0.5,
                     start_values={"solver.method": 2, "solver.step": 1e-3},
                     output=["solver.steps", "solver.errorEstimate"])
    assert list(r["solver.steps"][1:]) == [500, 500]
    assert np.all(r["solver.errorEstimate"] == 0.0)


def test_rosenbrock_is_second_order(fmu_of):
    omega0 = (0.4, 0.3, 3.0)
    fmu = fmu_of(scenes.free_spin(INERTIA, omega0, name="SmoothSpin"))
    steps = [0.02, 0.01, 0.005, 0.0025]
    errors = [orientation_error(fmu, 7, h, 2.0, omega0) for h in steps]
    assert abs(loglog_slope(np.array(steps), np.array(errors)) - 2.0) < 0.3, errors
