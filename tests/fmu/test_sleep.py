"""Sleeping islands through the FMU: a box at rest sleeps with its velocities exactly
zero; a change of a tunable parameter (gravity) wakes it and it moves as the closed form
says; an FMU state taken while it falls asleep continues bitwise, also serialised."""
import pytest

import scenes
from harness import Slave

EDGE = 0.2
H = 0.01  # s, the communication step


def resting_box():
    return scenes.cube_on_floor("SleepingBox", EDGE, mass=2.0)


@pytest.fixture(scope="module")
def fmu(fmu_of):
    return fmu_of(resting_box())


def run(s, t0, t1):
    for k in range(round((t1 - t0) / H)):
        s.slave.doStep(t0 + k * H, H)
    return s.all_reals()


def test_a_box_at_rest_sleeps_and_a_tunable_gravity_wakes_it(fmu):
    s = Slave(fmu)
    try:
        s.initialize()
        run(s, 0.0, 1.0)  # still from the start: asleep after 0.5 s
        v = s.get("box.velocity[1]", "box.velocity[2]", "box.velocity[3]")
        w = s.get("box.angularVelocity[1]", "box.angularVelocity[2]", "box.angularVelocity[3]")
        assert list(v) == [0.0, 0.0, 0.0] and list(w) == [0.0, 0.0, 0.0]
        z0 = s.get("box.position[3]")
        assert z0 == pytest.approx(EDGE / 2, abs=1e-4)  # on its seat (the soft contact's sinking)
        assert run(s, 1.0, 2.0) == run(s, 2.0, 2.0) and s.get("box.position[3]") == z0
        # gravity turned upwards: the box leaves the floor at a = 2 m/s^2 (rk4 is exact
        # on a constant force), from rest at z0
        s.set_values({"gravity[3]": 2.0})
        run(s, 2.0, 2.5)
        assert s.get("box.position[3]") - z0 == pytest.approx(0.5 * 2.0 * 0.5 ** 2, abs=1e-6)
        assert s.get("box.velocity[3]") == pytest.approx(2.0 * 0.5, abs=1e-6)
    finally:
        s.close()


def push(s, t0, t1):
    """Runs with a push that comes at 1.5 s (the box asleep by then) and stays."""
    out = []
    for k in range(round((t1 - t0) / H)):
        t = t0 + k * H
        s.set_values({"box.force[1]": 15.0 if t >= 1.5 - 1e-9 else 0.0})
        s.slave.doStep(t, H)
        out.append(s.all_reals())
    return out


def test_a_state_taken_while_falling_asleep_continues_bitwise(fmu):
    s = Slave(fmu)
    try:
        s.initialize()
        push(s, 0.0, 0.3)  # still for 0.3 s of the 0.5 s that put it to sleep
        state = s.slave.getFMUstate()
        blob = bytes(s.slave.serializeFMUstate(state))
        straight = push(s, 0.3, 2.0)
        assert straight[-1] != straight[100]  # it slept, then the push moved it
        s.slave.setFMUstate(state)
        assert push(s, 0.3, 2.0) == straight
        s.slave.setFMUstate(s.slave.deSerializeFMUstate(blob))
        assert push(s, 0.3, 2.0) == straight
        s.slave.freeFMUstate(state)
    finally:
        s.close()
