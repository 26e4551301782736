"""Conveyors through the FMU: a surface whose scene gives "beltVelocity" has the input
NAME.beltVelocity[1..3] (m/s), and friction acts against the slip relative to its belt.
A box set on a belt moving at u accelerates at mu_k g, reaches u after u / (mu_k g)
having slid u^2 / (2 mu_k g) on the belt, then rides at u; the belt changed mid-run as an
input, or ramped by its input derivative, carries it along in the same way."""
import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu

import scenes
from harness import Slave

G = 9.81
MUK = 0.4  # the box's and the belt's, so the pair's
H = 1e-3  # s, the communication step: every internal step is seen
U = 1.0  # m/s, the belt's speed in the scene


@pytest.fixture(scope="module")
def fmu(fmu_of):
    return str(fmu_of(scenes.conveyor("Conveyor", [U, 0.0, 0.0])))


def stick_time(t, v, target, scale):
    """The first communication point at which the velocity is `target` within 1e-3 of
    `scale`: the slide has ended (the step it ends in lands within 1e-4; the step before
    is mu_k g h = 3.9e-3 m/s short)."""
    close = np.linalg.norm(v - target, axis=1) < 1e-3 * scale
    return t[np.argmax(close)]


def test_the_belt_velocity_is_an_input_with_the_scenes_value_as_start(fmu):
    variables = read_model_description(fmu).modelVariables
    belt = {v.name: v for v in variables if ".beltVelocity[" in v.name}
    assert list(belt) == [f"belt.beltVelocity[{i}]" for i in (1, 2, 3)]
    assert [float(v.start) for v in belt.values()] == [U, 0.0, 0.0]
    assert {(v.causality, v.variability, v.unit) for v in belt.values()} == {("input", "continuous", "m/s")}
    assert variables[-1].name == "belt.beltVelocity[3]"  # after every other variable


def test_a_box_set_on_a_conveyor_reaches_its_speed_after_the_closed_form_time_and_slide(fmu):
    """u = 1 m/s, mu_k = 0.4: u / (mu_k g) = 0.2548 s, u^2 / (2 mu_k g) = 0.1274 m, each
    within 1 %; from 0.5 s on the box rides at u exactly (friction static, no creep)."""
    u = U
    r = simulate_fmu(fmu, stop_time=1.5, output_interval=H,
                     output=["box.position[1]", "box.velocity[1]", "box.velocity[2]"])
    t, x = r["time"], r["box.position[1]"]
    v = np.column_stack([r["box.velocity[1]"], r["box.velocity[2]"]])
    reached = stick_time(t, v, [u, 0.0], u)
    slid = u * t - x  # the belt's travel less the box's: its slide on the belt
    print(f"reached u after {reached:.4f} s (closed form {u / (MUK * G):.4f} s), "
          f"slid {slid[-1]:.5f} m on the belt (closed form {u * u / (2 * MUK * G):.5f} m)")
    assert reached == pytest.approx(u / (MUK * G), rel=0.01)
    assert slid[-1] == pytest.approx(u * u / (2 * MUK * G), rel=0.01)
    riding = t >= 0.5
    assert np.max(np.abs(v[riding] - [u, 0.0])) < 1e-12
    assert np.ptp(slid[riding]) < 1e-12


def test_the_belt_changed_mid_run_takes_the_box_to_its_new_velocity_at_mu_k_g(fmu):
    """The belt, an input, turned at 0.5 s from u1 to u2 (another direction): the box
    reaches u2 after |u2 - u1| / (mu_k g) within 1 % and rides there."""
    u1, u2 = np.array([U, 0.0, 0.0]), np.array([-0.5, 0.8, 0.0])
    s = Slave(fmu)
    try:
        s.initialize()
        for _ in range(500):
            s.step(H)
        assert s.get("box.velocity[1]", "box.velocity[2]") == pytest.approx(u1[:2], abs=1e-12)
        s.set_values({f"belt.beltVelocity[{i + 1}]": u2[i] for i in range(3)})
        t, v = [], []
        for _ in range(1000):
            s.step(H)
            t.append(s.time - 0.5)
            v.append(s.get("box.velocity[1]", "box.velocity[2]"))
        reached = stick_time(np.array(t), np.array(v), u2[:2], np.linalg.norm(u2 - u1))
        expected = np.linalg.norm(u2 - u1) / (MUK * G)
        print(f"reached u2 after {reached:.4f} s (closed form {expected:.4f} s)")
        assert reached == pytest.approx(expected, rel=0.01)
        assert np.max(np.abs(np.array(v[-300:]) - u2[:2])) < 1e-12
    finally:
        s.close()


def test_a_belt_ramped_by_its_input_derivative_carries_the_box_along(fmu):
    """Over one communication step of 0.1 s the belt's input derivative speeds it up at
    1 m/s^2, below mu_s g: the box rides along, held at each internal step's midpoint
    value (the inputs' rule), and ends the step at u + a (h - solver.step / 2) (within
    1e-5 m/s: it leans on its soft contacts as it is pulled); after the step the input is
    again the value the master set, and the box slides back to it."""
    u, a, h = U, 1.0, 0.1
    s = Slave(fmu)
    try:
        s.initialize()
        for _ in range(10):
            s.step(0.1)
        assert s.get("box.velocity[1]") == pytest.approx(u, abs=1e-12)
        s.slave.setRealInputDerivatives(s.vr(["belt.beltVelocity[1]"]), [1], [a])
        s.step(h)
        assert s.get("box.velocity[1]") == pytest.approx(u + a * (h - 0.5e-3), abs=1e-5)
        assert s.get("belt.beltVelocity[1]") == u
        for _ in range(5):  # the derivative is spent: the belt is back at u
            s.step(h)
        assert s.get("box.velocity[1]") == pytest.approx(u, abs=1e-12)
    finally:
        s.close()


def test_a_box_asleep_on_a_still_belt_wakes_when_the_belt_starts_and_never_sleeps_on_it(fmu):
    """Started on a belt at rest (the input's start value set before initialisation), the
    box falls asleep (its velocities exactly zero); set moving at half solver.sleepSpeed,
    the belt wakes it at the next step, static friction takes it up within that step, and
    it rides at the belt's speed from then on, never asleep."""
    s = Slave(fmu)
    try:
        s.initialize({"belt.beltVelocity[1]": 0.0})
        for _ in range(10):
            s.step(0.1)
        assert s.get("box.velocity[1]", "box.velocity[2]", "box.velocity[3]") == [0.0, 0.0, 0.0]  # asleep
        slow = 0.005  # m/s
        s.set_values({"belt.beltVelocity[1]": slow})
        speeds = []
        for _ in range(30):
            s.step(0.1)
            speeds.append(s.get("box.velocity[1]"))
        assert np.max(np.abs(np.array(speeds) - slow)) < 1e-9
    finally:
        s.close()
