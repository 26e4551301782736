"""Contact manifolds (up to 4 points per touching pair) through the FMU: a cube set
down on an edge falls flat, a ball rolls without slipping, a box stays seated
on another; the FMU validates; its state (the contact memory with the impulses that
warm-start the next step) saved, restored and serialised continues bitwise."""
import math

import pytest
from fmpy.validation import validate_fmu

from harness import Slave
from scenes import body, scene

H = 0.05  # s, communication step
EDGE = 1.0
TILT = math.radians(30.0)


def manifold_scene():
    s = scene("Manifold", [
        body("cube", shape={"type": "box", "size": [EDGE] * 3}, mass=1.0,
             position=[0.0, 0.0, 0.5 * EDGE * (math.cos(TILT) + math.sin(TILT))],
             orientation=[math.cos(TILT / 2), 0.0, math.sin(TILT / 2), 0.0], restitution=0.0),
        body("ball", shape={"type": "sphere", "radius": 0.1}, mass=1.0, position=[0.0, 3.0, 0.1],
             velocity=[1.0, 0.0, 0.0], angularVelocity=[0.0, 10.0, 0.0], restitution=0.0),
        body("base", shape={"type": "box", "size": [0.2, 0.2, 0.2]}, mass=2.0, position=[3.0, 0.0, 0.1],
             restitution=0.0),
        body("top", shape={"type": "box", "size": [0.1, 0.1, 0.1]}, mass=0.5, position=[3.02, 0.01, 0.25],
             restitution=0.0),
    ])
    s["surfaces"] = [{"name": "floor", "min": [-10, -10, -1], "max": [10, 10, 0],
                      "staticFriction": 0.6, "kineticFriction": 0.5, "restitution": 0.0}]
    return s


@pytest.fixture(scope="module")
def fmu(fmu_of):
    return fmu_of(manifold_scene())


def outputs(s):
    ints = [v.valueReference for v in s.md.modelVariables if v.type in ("Integer", "Enumeration")]
    return s.all_reals() + s.slave.getInteger(ints)


def drive(s, t0, t1):
    for k in range(round((t1 - t0) / H)):
        s.slave.doStep(t0 + k * H, H)
    return outputs(s)


def test_manifold_fmu_validates(fmu):
    assert validate_fmu(str(fmu)) == []


def test_bodies_tip_roll_and_rest_through_the_fmu(fmu):
    s = Slave(fmu)
    try:
        s.initialize()
        drive(s, 0.0, 2.0)
        # the cube: its centre of mass is inside the edge at 30 deg, it falls back flat
        assert s.get("cube.position[3]") == pytest.approx(0.5 * EDGE, abs=1e-3)
        w, x, y, z = s.get("cube.orientation[1]", "cube.orientation[2]", "cube.orientation[3]",
                           "cube.orientation[4]")
        assert 1.0 - 2.0 * (x * x + y * y) > math.cos(math.radians(1.0))  # R33: face down
        assert math.hypot(*s.get("cube.velocity[1]", "cube.velocity[2]", "cube.velocity[3]")) < 1e-3
        # the ball rolls without slipping: v stays 1 m/s, 2 m in 2 s
        assert s.get("ball.velocity[1]") == pytest.approx(1.0, rel=1e-2)
        assert s.get("ball.position[1]") == pytest.approx(2.0, abs=0.02)
        # the small box sits on the large one: its centre at 0.2 + 0.05 m, the soft
        # contacts' sub-micrometre seats below that
        assert s.get("top.position[3]") == pytest.approx(0.25, abs=1e-3)
        top, base = s.slave.getInteger(s.vr(["top.contacts", "base.contacts"]))
        assert top >= 4 and base >= 8  # a face on a face: four corners each
    finally:
        s.close()


def test_manifold_state_continues_bitwise(fmu):
    s = Slave(fmu)
    try:
        s.initialize()
        drive(s, 0.0, 0.5)  # the cube is falling on its edge, the stack seated
        state = s.slave.getFMUstate()
        blob = bytes(s.slave.serializeFMUstate(state))
        straight = drive(s, 0.5, 1.5)
        s.slave.setFMUstate(state)
        assert drive(s, 0.5, 1.5) == straight
        s.slave.freeFMUstate(state)
    finally:
        s.close()
    fresh = Slave(fmu)
    try:
        fresh.initialize()
        restored = fresh.slave.deSerializeFMUstate(blob)
        fresh.slave.setFMUstate(restored)
        assert drive(fresh, 0.5, 1.5) == straight
    finally:
        fresh.close()


def test_the_state_carries_the_contact_memory(fmu, fmu_of):
    """The contact memory is serialised: a state with bodies at rest on the floor is
    longer than one in free flight by the points' bytes (3 ints, 8 doubles, a flag).
    At 0.4 s: base and top, still from the start, are not yet asleep (0.5 s), which
    would add the forces they keep giving the floor."""
    s = Slave(fmu)
    try:
        s.initialize()
        before = len(bytes(s.slave.serializeFMUstate(s.slave.getFMUstate())))
        drive(s, 0.0, 0.4)
        after = len(bytes(s.slave.serializeFMUstate(s.slave.getFMUstate())))
        points = (after - before) / (3 * 4 + 8 * 8 + 1)
        assert points == int(points) and points >= 2 + 1 + 4 + 4  # cube on its edge, ball, base, top
    finally:
        s.close()
