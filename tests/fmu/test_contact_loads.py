"""The loads as outputs (issue 18), through fmpy against statics and the impulse of a
bounce: b.contactForce / b.contactTorque and the surface's NAME.force, the contact
impulses of the last communication step over its length."""
import math

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu

import scenes
from harness import Slave

G = 9.81
H = 0.1  # s, the communication step


def stack():
    """Cubes of 2 kg (lower) and 3 kg (upper) set down on a floor."""
    s = scenes.cube_on_floor("LoadedStack", 0.2, mass=2.0)
    s["bodies"].append(scenes.body("top", shape={"type": "box", "size": [0.2] * 3}, mass=3.0,
                                   position=[0, 0, 0.3], restitution=0.0))
    return s


def vec(s, name):
    return np.array(s.get(*(f"{name}[{i}]" for i in (1, 2, 3))))


def test_a_resting_stack_reports_its_weights_awake_and_asleep(fmu_of):
    s = Slave(fmu_of(stack()))
    try:
        s.initialize()
        for k in range(20):  # 2 s: asleep from 0.5 s on
            s.slave.doStep(k * H, H)
            if k in (2, 19):  # awake at 0.3 s, asleep at 2 s
                for name, weight in (("box", 2.0 * G), ("top", 3.0 * G)):
                    assert np.abs(vec(s, f"{name}.contactForce") - [0, 0, weight]).max() < 1e-6 * weight, (k, name)
                    assert np.abs(vec(s, f"{name}.contactTorque")).max() < 1e-6 * weight
                assert np.abs(vec(s, "floor.force") - [0, 0, -5.0 * G]).max() < 1e-6 * 5.0 * G, k
        assert list(vec(s, "box.velocity")) == [0.0, 0.0, 0.0]  # asleep indeed
    finally:
        s.close()


def test_a_sliding_box_reports_kinetic_friction_against_its_motion(fmu_of):
    mu = 0.3  # both sides: the pair's coefficient is 0.3
    sc = scenes.cube_on_floor("LoadedSlide", 0.2, floor_friction=mu, mass=1.0, velocity=[2.0, 0, 0],
                              staticFriction=mu, kineticFriction=mu)
    s = Slave(fmu_of(sc))
    try:
        s.initialize()
        s.slave.doStep(0.0, H)
        s.slave.doStep(H, H)  # the second step: sliding throughout (it stops at 0.68 s)
        assert np.abs(vec(s, "box.contactForce") - [-mu * G, 0, G]).max() < 1e-6 * G
        assert np.abs(vec(s, "floor.force") - [mu * G, 0, -G]).max() < 1e-6 * G
    finally:
        s.close()


def test_a_bounce_shows_as_its_impulse_over_the_step(fmu_of):
    """Dropped from 1 m, xi = 0.8: the step that holds the impact (t = 0.4515 s) reports
    m (1 + xi) v / H, v = sqrt(2 g H0); the steps in flight report nothing."""
    m, xi, h0, r = 1.5, 0.8, 1.0, 0.1
    ball = scenes.body("ball", shape={"type": "sphere", "radius": r}, mass=m, position=[0, 0, r + h0],
                       restitution=xi)
    sc = scenes.scene("LoadedBounce", [ball])
    sc["surfaces"] = [scenes.floor(0.5, 0.3, xi)]
    res = simulate_fmu(str(fmu_of(sc)), stop_time=0.6, output_interval=H)
    f = res["ball.contactForce[3]"]
    t1 = math.sqrt(2 * h0 / G)
    k = int(t1 // H) + 1  # the output at the end of the step that holds t1
    # the impact is located in time: exact to rounding (5e-15 measured; the issue asks 1 %)
    assert f[k] * H == pytest.approx(m * (1 + xi) * math.sqrt(2 * G * h0), rel=1e-9)
    assert np.all(f[:k] == 0.0) and f[k + 1] == 0.0
    assert res["floor.force[3]"][k] == pytest.approx(-f[k], rel=1e-12)


def test_no_contact_no_loads_and_outputs_lists_leave_them_out(fmu_of):
    names = {v.name for v in read_model_description(str(fmu_of(scenes.projectile()))).modelVariables}
    assert not any("contactForce" in n or "contactTorque" in n for n in names)
    sc = stack()
    sc["name"] = "LeanLoads"
    sc["bodies"][0]["outputs"] = ["position", "contactForce"]
    sc["surfaces"][0]["outputs"] = []
    names = {v.name for v in read_model_description(str(fmu_of(sc))).modelVariables}
    assert "box.contactForce[1]" in names and "box.contactTorque[1]" not in names
    assert "top.contactTorque[1]" in names and "floor.force[1]" not in names
