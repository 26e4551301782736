"""Bodies under gravity and external loads, through the FMU, against closed forms."""
import numpy as np
import pytest
from fmpy import simulate_fmu

import scenes
from harness import Slave

G = np.array([0.0, 0.0, -9.81])
POS = ["ball.position[1]", "ball.position[2]", "ball.position[3]"]
VEL = ["ball.velocity[1]", "ball.velocity[2]", "ball.velocity[3]"]


def columns(result, names):
    return np.column_stack([result[n] for n in names])


def test_projectile_matches_closed_form_with_rk4(fmu_of):
    """rk4 integrates a quadratic trajectory exactly, up to rounding: 1e-9 m."""
    r = simulate_fmu(str(fmu_of(scenes.projectile())), stop_time=2.0, output_interval=0.05)
    t = r["time"][:, None]
    x0, v0 = np.array([1.0, 2.0, 10.0]), np.array([3.0, -2.0, 4.0])
    np.testing.assert_allclose(columns(r, POS), x0 + v0 * t + 0.5 * G * t**2, rtol=0, atol=1e-9)
    np.testing.assert_allclose(columns(r, VEL), v0 + G * t, rtol=0, atol=1e-9)


def test_free_fall_from_rest(fmu_of):
    s = scenes.scene("FreeFall", [scenes.body("ball", position=[0, 0, 100.0])])
    r = simulate_fmu(str(fmu_of(s)), stop_time=3.0, output_interval=0.1)
    np.testing.assert_allclose(r["ball.position[3]"], 100.0 - 0.5 * 9.81 * r["time"]**2,
                               rtol=0, atol=1e-9)


def test_euler_has_its_closed_form_error(fmu_of):
    """Explicit Euler on free fall: x_N = x0 + v0 T + g T^2/2 - g h T/2 exactly, so the
    solver.method and solver.step parameters are seen in the result."""
    fmu = str(fmu_of(scenes.projectile()))
    T = 1.0
    for h in (1e-3, 4e-3):
        r = simulate_fmu(fmu, stop_time=T, output_interval=0.1,
                         start_values={"solver.method": 1, "solver.step": h})
        z = r["ball.position[3]"][-1]
        assert z == pytest.approx(10.0 + 4.0 * T - 0.5 * 9.81 * T**2 + 0.5 * 9.81 * h * T,
                                  abs=1e-9)


def test_gravity_parameter_changes_the_fall(fmu_of):
    g = (1.0, -2.0, -3.5)
    r = simulate_fmu(str(fmu_of(scenes.projectile())), stop_time=1.0, output_interval=0.1,
                     start_values={"gravity[1]": g[0], "gravity[2]": g[1], "gravity[3]": g[2]})
    t = r["time"][:, None]
    expected = np.array([1.0, 2.0, 10.0]) + np.array([3.0, -2.0, 4.0]) * t + 0.5 * np.array(g) * t**2
    np.testing.assert_allclose(columns(r, POS), expected, rtol=0, atol=1e-9)


def test_force_input_gives_a_equals_F_over_m_and_mass_parameter_counts(fmu_of):
    s = scenes.scene("Pushed", [scenes.body("ball", mass=2.0)], gravity=(0, 0, 0))
    F = np.array([2.0, -1.0, 3.0])
    slave = Slave(fmu_of(s))
    try:
        slave.initialize({"ball.mass": 4.0})
        slave.set_values({"ball.force[1]": F[0], "ball.force[2]": F[1], "ball.force[3]": F[2]})
        for _ in range(20):
            slave.step(0.05)
        t = 1.0
        np.testing.assert_allclose(slave.get(*POS), 0.5 * F / 4.0 * t**2, rtol=0, atol=1e-12)
        np.testing.assert_allclose(slave.get(*VEL), F / 4.0 * t, rtol=0, atol=1e-12)
        P = slave.get("ball.linearMomentum[1]", "ball.linearMomentum[2]", "ball.linearMomentum[3]")
        np.testing.assert_allclose(P, F * t, rtol=0, atol=1e-12)
    finally:
        slave.close()


def test_inputs_hold_over_a_step_and_change_between_steps(fmu_of):
    """Force on for 0.5 s, off for 0.5 s: v and x follow the piecewise closed form."""
    s = scenes.scene("Pulse", [scenes.body("ball", mass=1.0)], gravity=(0, 0, 0))
    slave = Slave(fmu_of(s))
    try:
        slave.initialize()
        slave.set_values({"ball.force[1]": 2.0})
        for _ in range(5):
            slave.step(0.1)
        slave.set_values({"ball.force[1]": 0.0})
        for _ in range(5):
            slave.step(0.1)
        x, v = slave.get("ball.position[1]", "ball.velocity[1]")
        assert v == pytest.approx(1.0, abs=1e-12)            # 2 N * 0.5 s / 1 kg
        assert x == pytest.approx(0.25 + 1.0 * 0.5, abs=1e-12)  # a t^2/2, then coasting
    finally:
        slave.close()


@pytest.mark.parametrize("shape,axis", [({"type": "sphere", "radius": 0.2}, 0),
                                        ({"type": "box", "size": [0.6, 0.4, 0.2]}, 2)])
def test_torque_about_a_principal_axis_spins_up_linearly(fmu_of, shape, axis):
    """A constant torque T about a principal axis: L = T t and omega = T t / I_axis."""
    m = 3.0
    if shape["type"] == "sphere":
        I_axis = 0.4 * m * 0.2**2
    else:
        I_axis = m / 12.0 * (0.6**2 + 0.4**2)
    s = scenes.scene(f"Torqued{axis}", [scenes.body("ball", shape=shape, mass=m)], gravity=(0, 0, 0))
    slave = Slave(fmu_of(s))
    try:
        slave.initialize()
        T = 0.7
        slave.set_values({f"ball.torque[{axis + 1}]": T})
        for _ in range(10):
            slave.step(0.1)
        t = 1.0
        L = slave.get(*[f"ball.angularMomentum[{i}]" for i in (1, 2, 3)])
        w = slave.get(*[f"ball.angularVelocity[{i}]" for i in (1, 2, 3)])
        expected_L = np.zeros(3)
        expected_L[axis] = T * t
        np.testing.assert_allclose(L, expected_L, rtol=0, atol=1e-12)
        np.testing.assert_allclose(w, expected_L / I_axis, rtol=1e-12, atol=1e-12)
        # the angle turned is T t^2 / (2 I): check through the quaternion
        q = slave.get(*[f"ball.orientation[{i}]" for i in (1, 2, 3, 4)])
        angle = T * t**2 / (2 * I_axis)
        assert q[0] == pytest.approx(np.cos(angle / 2), abs=1e-9)
        assert q[1 + axis] == pytest.approx(np.sin(angle / 2), abs=1e-9)
    finally:
        slave.close()
