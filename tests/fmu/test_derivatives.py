"""Smooth coupling: first-order input derivatives (canInterpolateInputs) and output
derivatives (MaxOutputDerivativeOrder = 1)."""
import math

import numpy as np
import pytest
from fmpy import read_model_description

import scenes
from harness import Slave, status_of

M, K, C = 1.0, 400.0, 2.0  # kg, N/m, N s/m: omega = 20 rad/s


def oscillator(fmu, h, T, with_derivatives):
    """An fmpy master closes a spring-damper through the force input,
    F = -k x - c v at each communication point; with derivatives it also passes
    dF/dt = -k v - c a, with a from the FMU's output derivative of the velocity."""
    s = Slave(fmu)
    try:
        s.initialize({"ball.position[1]": 0.1})
        vr_f, vr_v = s.vr(["ball.force[1]"]), s.vr(["ball.velocity[1]"])
        t = 0.0
        for _ in range(round(T / h)):
            x, v = s.get("ball.position[1]", "ball.velocity[1]")
            s.set_values({"ball.force[1]": -K * x - C * v})
            if with_derivatives:
                a = s.slave.getRealOutputDerivatives(vr_v, [1])[0]
                s.slave.setRealInputDerivatives(vr_f, [1], [-K * v - C * a])
            s.slave.doStep(t, h)
            t += h
        return s.get("ball.position[1]")
    finally:
        s.close()


def exact(T, x0=0.1):
    w0 = math.sqrt(K / M)
    zeta = C / (2 * math.sqrt(K * M))
    wd = w0 * math.sqrt(1 - zeta**2)
    return x0 * math.exp(-zeta * w0 * T) * (math.cos(wd * T) + zeta * w0 / wd * math.sin(wd * T))


@pytest.fixture(scope="module")
def fmu(fmu_of):
    return fmu_of(scenes.scene("Coupled", [scenes.body("ball", mass=M)], gravity=(0, 0, 0)))


def test_capabilities_are_declared(fmu):
    cs = read_model_description(str(fmu)).coSimulation
    assert cs.canInterpolateInputs is True and cs.maxOutputDerivativeOrder == 1


def test_stiff_coupling_is_more_accurate_with_derivatives(fmu):
    """Same communication step (h omega = 0.4): the interpolated inputs cut the error."""
    T, h = 2.0, 0.02
    without = abs(oscillator(fmu, h, T, False) - exact(T))
    with_d = abs(oscillator(fmu, h, T, True) - exact(T))
    assert with_d < without / 3, (with_d, without)


def test_output_derivatives_are_the_state_derivatives(fmu):
    s = Slave(fmu)
    try:
        s.initialize({"ball.velocity[1]": 2.0, "ball.angularVelocity[3]": 3.0})
        s.set_values({"ball.force[2]": 4.0})
        s.slave.doStep(0.0, 0.1)
        names = ["ball.position[1]", "ball.velocity[2]", "ball.linearMomentum[2]", "ball.orientation[1]"]
        d = s.slave.getRealOutputDerivatives(s.vr(names), [1] * 4)
        q = s.get("ball.orientation[1]", "ball.orientation[4]")
        assert d[0] == pytest.approx(2.0, abs=1e-12)       # dx/dt = v
        assert d[1] == pytest.approx(4.0 / M, abs=1e-12)   # dv/dt = F/m
        assert d[2] == pytest.approx(4.0, abs=1e-12)       # dP/dt = F
        assert d[3] == pytest.approx(-0.5 * 3.0 * q[1], abs=1e-12)  # dw/dt of q = -1/2 omega_z q_z
        assert status_of(lambda: s.slave.getRealOutputDerivatives(s.vr(names[:1]), [2])) == "Error"
        assert status_of(lambda: s.slave.setRealInputDerivatives(s.vr(["ball.force[1]"]), [2], [1.0])) == "Error"
        assert status_of(lambda: s.slave.setRealInputDerivatives(s.vr(["ball.mass"]), [1], [1.0])) == "Error"
    finally:
        s.close()


def test_input_ramp_gives_the_exact_impulse(fmu):
    """F(t) = 3 t N over one 1 s step, split into internal steps held at their midpoints:
    v(1) = 1.5 m/s exactly, and the derivative is spent after the step."""
    s = Slave(fmu)
    try:
        s.initialize()
        s.slave.setRealInputDerivatives(s.vr(["ball.force[1]"]), [1], [3.0])
        s.slave.doStep(0.0, 1.0)
        assert s.get("ball.velocity[1]") == pytest.approx(1.5, abs=1e-12)
        assert s.get("ball.force[1]") == 0.0
        s.slave.doStep(1.0, 1.0)
        assert s.get("ball.velocity[1]") == pytest.approx(1.5, abs=1e-12)
    finally:
        s.close()


def test_directional_derivatives_over_a_step_match_closed_form(fmu):
    """Outputs after a step of h (the last one's length) against inputs held over it:
    dx/dF = h^2 / 2m, dv/dF = h / m, no cross-talk between axes."""
    s = Slave(fmu)
    try:
        s.initialize({"ball.velocity[1]": 1.0})
        h = 0.1
        s.slave.doStep(0.0, h)
        outs = s.vr(["ball.position[1]", "ball.velocity[1]", "ball.position[2]", "ball.linearMomentum[1]"])
        d = s.slave.getDirectionalDerivative(outs, s.vr(["ball.force[1]"]), [1.0])
        assert d[0] == pytest.approx(h * h / (2 * M), rel=1e-6)
        assert d[1] == pytest.approx(h / M, rel=1e-6)
        assert abs(d[2]) < 1e-12
        assert d[3] == pytest.approx(h, rel=1e-6)
        # the instance did not move while it was asked
        assert s.get("time") == pytest.approx(h, abs=1e-15)
        assert s.get("ball.position[1]") == pytest.approx(h * 1.0, abs=1e-12)
    finally:
        s.close()


def test_directional_derivative_matches_the_masters_finite_difference(fmu_of):
    """On the Playground (contacts, friction, drag): the FMU's derivative of the slider's
    position after a step with respect to its force, against a master's own central
    difference through FMU states."""
    import json
    import pathlib
    root = pathlib.Path(__file__).resolve().parents[2]
    scene = json.loads((root / "scripts" / "scenes" / "default.json").read_text())
    s = Slave(fmu_of(scene))
    try:
        s.initialize()
        for k in range(10):
            s.slave.doStep(k * 0.05, 0.05)
        t = 0.5
        out = s.vr(["slider.position[1]", "slider.velocity[1]"])
        inp = s.vr(["slider.force[1]"])
        d = s.slave.getDirectionalDerivative(out, inp, [1.0])
        state = s.slave.getFMUstate()
        eps, values = 1e-2, []
        for sign in (1, -1):
            s.slave.setFMUstate(state)
            s.slave.setReal(inp, [sign * eps])
            s.slave.doStep(t, 0.05)
            values.append(s.slave.getReal(out))
        fd = [(p - m) / (2 * eps) for p, m in zip(*values)]
        assert d == pytest.approx(fd, rel=1e-3, abs=1e-9)
        assert d[1] > 0.0  # pushing along +x speeds it up along +x
    finally:
        s.close()


@pytest.fixture(scope="module")
def spinner_fmu(fmu_of):
    return fmu_of(scenes.free_spin(inertia=(1.0, 2.0, 3.0), omega=(0.4, 2.0, -0.7)))


def test_angular_velocity_derivative_is_eulers_equation(spinner_fmu):
    """d omega/dt of a torqued asymmetric body, in the world frame, against Euler's
    equation I(t)^-1 (T - omega x L) formed here from the outputs (q, omega) and the
    scene's Ibody: the gyroscopic term is what a wrong inertia would miss."""
    Ibody = np.diag([1.0, 2.0, 3.0])
    T = np.array([0.3, -0.2, 0.5])
    s = Slave(spinner_fmu)
    try:
        s.initialize()
        names = [f"spinner.torque[{k}]" for k in (1, 2, 3)]
        s.set_values(dict(zip(names, T)))
        s.slave.doStep(0.0, 0.25)  # the body has turned: world and body frames differ
        omega_names = [f"spinner.angularVelocity[{k}]" for k in (1, 2, 3)]
        got = np.array(s.slave.getRealOutputDerivatives(s.vr(omega_names), [1, 1, 1]))
        w, x, y, z = s.get(*[f"spinner.orientation[{k}]" for k in (1, 2, 3, 4)])
        R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                      [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                      [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
        omega = np.array(s.get(*omega_names))
        I = R @ Ibody @ R.T
        expected = np.linalg.solve(I, T - np.cross(omega, I @ omega))
        assert np.abs(R.T @ R - np.eye(3)).max() < 1e-12
        assert np.abs(got - expected).max() < 1e-9 * np.abs(expected).max(), (got, expected)
        assert np.abs(np.cross(omega, I @ omega)).max() > 0.5  # the gyroscopic term matters here
    finally:
        s.close()
