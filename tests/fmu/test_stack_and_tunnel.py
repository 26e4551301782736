"""Resting contact in a stack, and a fast body against a thin one (issue 4)."""
import numpy as np
from fmpy import simulate_fmu

import scenes

EDGE = 0.1


def stack_scene(n=10):
    boxes = [scenes.body(f"box{k}", shape={"type": "box", "size": [EDGE] * 3}, mass=1.0,
                         position=[0, 0, EDGE / 2 + k * EDGE], restitution=0.2,
                         staticFriction=0.6, kineticFriction=0.4) for k in range(n)]
    s = scenes.scene("Stack", boxes)
    s["surfaces"] = [{"name": "floor", "min": [-2, -2, -0.5], "max": [2, 2, 0],
                      "staticFriction": 0.6, "kineticFriction": 0.4, "restitution": 0.2}]
    return s


def test_stack_of_ten_boxes_stays_still(fmu_of):
    """10 s: drift below 1 mm, penetration below 1 mm, speeds below 1e-3 m/s at the end."""
    r = simulate_fmu(str(fmu_of(stack_scene())), stop_time=10.0, output_interval=0.1)
    for k in range(10):
        X = np.column_stack([r[f"box{k}.position[{i}]"] for i in (1, 2, 3)])
        start = np.array([0, 0, EDGE / 2 + k * EDGE])
        assert np.max(np.linalg.norm(X - start, axis=1)) < 1e-3, k
        V = np.array([r[f"box{k}.velocity[{i}]"][-1] for i in (1, 2, 3)])
        assert np.linalg.norm(V) < 1e-3, k
    for k in range(9):  # overlap of neighbours: centres closer than an edge
        gap = r[f"box{k + 1}.position[3]"] - r[f"box{k}.position[3]"]
        assert np.min(gap) > EDGE - 1e-3, k
    assert np.min(r["box0.position[3]"]) > EDGE / 2 - 1e-3


def test_fast_small_sphere_does_not_pass_through_a_thin_plate(fmu_of):
    """A 1 cm sphere at 100 m/s against a 1 cm plate at h = 1e-3: it travels 10 cm per
    step, ten times the plate's thickness; it starts where no end of a step finds it
    overlapping the plate (x = -0.045 then +0.055)."""
    ball = scenes.body("ball", shape={"type": "sphere", "radius": 0.005}, mass=0.004,
                       position=[-0.445, 0, 0], velocity=[100.0, 0, 0], restitution=0.5)
    plate = scenes.body("plate", shape={"type": "box", "size": [0.01, 1.0, 1.0]}, mass=50.0,
                        position=[0.0, 0, 0], restitution=0.5)
    r = simulate_fmu(str(fmu_of(scenes.scene("Tunnel", [ball, plate], gravity=(0, 0, 0)))),
                     stop_time=0.05, output_interval=1e-3)
    assert np.all(r["ball.position[1]"] < 0.0)     # never on the far side
    assert r["ball.velocity[1]"][-1] < 0.0          # it bounced back
