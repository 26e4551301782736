"""Friction, a surface's restitution and a medium's density as FMU parameters (issue
18), through fmpy against closed forms: set before initialisation and mid-run, bad
values refused with a message naming the variable and the limit."""
import math

import pytest
from fmpy import simulate_fmu

import scenes
from harness import Slave, status_of

G = 9.81
EDGE = 0.2
V0 = 2.0  # m/s, the box's start velocity along x


def sliding_box():
    """A cube sliding on a floor at V0. The cube's friction is 1, so a pair's
    coefficient is sqrt(1 * the floor's) (geometric mean)."""
    return scenes.cube_on_floor("SlidingBox", EDGE, floor_friction=0.6, mass=1.0, velocity=[V0, 0, 0],
                                staticFriction=1.0, kineticFriction=1.0)


@pytest.fixture(scope="module")
def box_fmu(fmu_of):
    return fmu_of(sliding_box())


def test_floor_friction_set_before_the_run_sets_the_stopping_distance(box_fmu):
    """floor.kineticFriction = floor.staticFriction = 0.25: mu = sqrt(1 * 0.25) = 0.5,
    the cube stops after v0^2 / (2 mu g) = 0.4077 m."""
    mu = math.sqrt(0.25)
    r = simulate_fmu(str(box_fmu), stop_time=1.0, output_interval=0.01,
                     start_values={"floor.staticFriction": 0.25, "floor.kineticFriction": 0.25})
    x = r["box.position[1]"]
    assert x[-1] == pytest.approx(V0 ** 2 / (2 * mu * G), abs=1e-3)
    assert abs(r["box.velocity[1]"][-1]) < 1e-3


def test_floor_friction_changed_mid_run_acts_from_the_next_step(box_fmu):
    """mu = sqrt(0.6) for 0.1 s, then the floor's coefficients set to 0.04 (mu = 0.2):
    the cube then decelerates at 0.2 g and stops v(0.1)^2 / (2 0.2 g) further on."""
    mu1, mu2, t1 = math.sqrt(0.6), 0.2, 0.1
    s = Slave(box_fmu)
    try:
        s.initialize()
        for k in range(10):
            s.slave.doStep(k * 0.01, 0.01)
        x1, v1 = s.get("box.position[1]", "box.velocity[1]")
        assert v1 == pytest.approx(V0 - mu1 * G * t1, abs=1e-3)
        # both in one call: the pair is checked when it takes effect, at the next step
        s.set_values({"floor.staticFriction": 0.04, "floor.kineticFriction": 0.04})
        for k in range(10, 200):
            s.slave.doStep(k * 0.01, 0.01)
        assert s.get("box.position[1]") - x1 == pytest.approx(v1 ** 2 / (2 * mu2 * G), abs=2e-3)
    finally:
        s.close()


def test_a_lighter_pool_lets_a_box_float_deeper(fmu_of):
    """pool.density = 800 kg/m3: a 1 x 1 x 0.5 m box of 250 kg floats at draft
    m / (rho A) = 0.3125 m (the scene's water would give 0.2505 m)."""
    m, rho = 250.0, 800.0
    s = scenes.scene("FloatParameter", [scenes.body("box", shape={"type": "box", "size": [1.0, 1.0, 0.5]},
                                                    mass=m, position=[0, 0, 0.25 - 0.3])])
    s["media"] = [{"name": "pool", "type": "water", "min": [-10, -10, -10], "max": [10, 10, 0]}]
    r = simulate_fmu(str(fmu_of(s)), stop_time=60.0, output_interval=0.01, start_values={"pool.density": rho})
    t, z = r["time"], r["box.position[3]"]
    draft = 0.25 - z[t >= 50.0].mean()
    assert draft == pytest.approx(m / (rho * 1.0), abs=1e-3)


def test_bad_values_are_refused_naming_the_variable_and_the_limit(box_fmu):
    s = Slave(box_fmu)
    try:
        s.slave.setupExperiment(startTime=0.0)
        s.slave.enterInitializationMode()
        for name, value, says in (("floor.kineticFriction", -0.1, "floor.kineticFriction: must be >= 0"),
                                  ("box.staticFriction", float("nan"), "box.staticFriction: must be finite"),
                                  ("floor.restitution", 1.5, "floor.restitution: must be in [0, 1], got 1.5")):
            assert status_of(lambda: s.set_values({name: value})) == "Error", name
            assert says in s.log.last()[2], s.log.text()
        # mu_k above mu_s: refused when the pair takes effect
        s.set_values({"floor.kineticFriction": 0.7})
        assert status_of(s.slave.exitInitializationMode) == "Error"
        assert "floor.kineticFriction: must be <= floor.staticFriction (0.59999999999999998), got 0.69999999999999996" \
            in s.log.last()[2], s.log.text()
    finally:
        s.close()
    s = Slave(box_fmu)
    try:
        s.initialize()
        s.slave.doStep(0.0, 0.01)
        s.set_values({"floor.kineticFriction": 0.7})  # mid-run: the next step refuses it
        assert status_of(lambda: s.slave.doStep(0.01, 0.01)) == "Error"
        assert "fmi2DoStep: floor.kineticFriction: must be <=" in s.log.last()[2], s.log.text()
    finally:
        s.close()


def test_an_fmu_state_holds_the_parameters_set_mid_run(box_fmu):
    s = Slave(box_fmu)
    try:
        s.initialize()
        s.slave.doStep(0.0, 0.01)
        s.set_values({"floor.staticFriction": 0.3, "floor.kineticFriction": 0.2, "box.kineticFriction": 0.9})
        state = s.slave.getFMUstate()
        blob = bytes(s.slave.serializeFMUstate(state))
        names = ("floor.staticFriction", "floor.kineticFriction", "box.kineticFriction", "box.position[1]")
        s.slave.doStep(0.01, 0.01)
        after = s.get(*names)
        s.set_values({"floor.staticFriction": 0.6, "floor.kineticFriction": 0.6, "box.kineticFriction": 1.0})
        for restore in (lambda: state, lambda: s.slave.deSerializeFMUstate(blob)):
            s.slave.setFMUstate(restore())
            assert list(s.get(*names[:3])) == [0.3, 0.2, 0.9]
            s.slave.doStep(0.01, 0.01)
            assert s.get(*names) == after  # the restored run continues bitwise
        s.slave.freeFMUstate(state)
    finally:
        s.close()


def test_the_other_parameters_change_the_motion_as_the_closed_forms_say(fmu_of, box_fmu):
    """box.kineticFriction = box.staticFriction = 0.36 on the scene's floor of 0.6:
    mu = sqrt(0.36 * 0.6), stopping distance v0^2 / (2 mu g). floor.restitution = 0.64
    under a ball of xi = 1: xi = sqrt(0.64) = 0.8, first apex 0.64 H. pool.viscosity
    (density 0): Stokes' b = 6 pi mu r, terminal velocity m g / b."""
    mu = math.sqrt(0.36 * 0.6)
    r = simulate_fmu(str(box_fmu), stop_time=1.0, output_interval=0.01,
                     start_values={"box.staticFriction": 0.36, "box.kineticFriction": 0.36})
    assert r["box.position[1]"][-1] == pytest.approx(V0 ** 2 / (2 * mu * G), abs=1e-3)

    h0, radius = 1.0, 0.1
    ball = scenes.body("ball", shape={"type": "sphere", "radius": radius}, mass=1.0,
                       position=[0, 0, radius + h0], restitution=1.0)
    drop = scenes.scene("ParameterDrop", [ball])
    drop["surfaces"] = [scenes.floor(0.5, 0.3, 1.0)]
    r = simulate_fmu(str(fmu_of(drop)), stop_time=1.2, output_interval=1e-3,
                     start_values={"floor.restitution": 0.64})
    t1 = math.sqrt(2 * h0 / G)
    after = r["time"] > t1 + 0.01
    assert r["ball.position[3]"][after].max() - radius == pytest.approx(0.64 * h0, rel=1e-3)

    b, m = 2.0, 1.0
    sink = scenes.scene("ParameterStokes", [scenes.body("ball", shape={"type": "sphere", "radius": radius}, mass=m)])
    sink["media"] = [{"name": "pool", "type": "custom", "density": 0.0, "viscosity": 1.0,
                      "min": [-100, -100, -100], "max": [100, 100, 100]}]
    r = simulate_fmu(str(fmu_of(sink)), stop_time=5.0, output_interval=0.1,
                     start_values={"pool.viscosity": b / (6 * math.pi * radius)})
    tau = m / b
    assert r["ball.velocity[3]"][-1] == pytest.approx(-m * G / b * (1 - math.exp(-5.0 / tau)), rel=1e-6)
