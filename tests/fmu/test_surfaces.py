"""Bodies on the seed's surfaces, through the FMU: support without sinking, static and
kinetic friction against closed forms, falling off an edge."""
import math

import numpy as np
import pytest
from fmpy import simulate_fmu

import scenes
from harness import Slave
from reference import resting_depth

G = 9.81
CUBE = 0.2  # m, edge of the test cube
STEP = 1e-3  # s, the scenes' solver step


def ramp_scene(name, theta, mus=0.5, muk=0.3, velocity=0.0, method="rk4"):
    """A 10 m ramp descending towards +x at angle theta, a cube resting on its middle
    with the ramp's orientation; body and ramp share mu_s and mu_k, so the combined
    coefficients are those values."""
    q = [math.cos(theta / 2), 0.0, math.sin(theta / 2), 0.0]
    n = np.array([math.sin(theta), 0.0, math.cos(theta)])      # ramp's top normal
    down = np.array([math.cos(theta), 0.0, -math.sin(theta)])  # down the slope
    centre = (0.5 + CUBE / 2) * n
    cube = scenes.body("cube", shape={"type": "box", "size": [CUBE] * 3}, mass=2.0,
                       position=list(centre), orientation=q, velocity=list(velocity * down),
                       staticFriction=mus, kineticFriction=muk, restitution=0.0)
    s = scenes.scene(name, [cube], method=method)
    s["surfaces"] = [{"name": "ramp", "min": [-5, -1, -0.5], "max": [5, 1, 0.5], "orientation": q,
                      "staticFriction": mus, "kineticFriction": muk, "restitution": 0.0}]
    return s, centre, down


def positions(r):
    return np.column_stack([r[f"cube.position[{i}]"] for i in (1, 2, 3)])


@pytest.mark.parametrize("method", ["rk4", "euler"])
def test_holds_below_static_limit(fmu_of, method):
    """tan(theta) = mu_s - 1e-3: static friction holds. Set down at depth 0, the cube
    slips a little while its contact takes up the load (static friction needs 99.8 % of
    it; 2.2 um seen), and from then on does not creep: below 1e-9 m from 0.5 s to 10 s."""
    s, x0, _ = ramp_scene(f"Stick_{method}", math.atan(0.5 - 1e-3), method=method)
    r = simulate_fmu(str(fmu_of(s)), stop_time=10.0, output_interval=0.5)
    x = positions(r)
    assert np.max(np.linalg.norm(x - x0, axis=1)) < 5e-6
    assert np.max(np.linalg.norm(x[1:] - x[1], axis=1)) < 1e-9


@pytest.mark.sweep("theta")
@pytest.mark.parametrize("theta", [math.atan(0.5 + 1e-3), math.radians(30.0)])
def test_slides_with_kinetic_friction_above_static_limit(fmu_of, theta):
    """tan(theta) > mu_s: it slides with a = g (sin theta - mu_k cos theta), within 0.5 %
    (a fit of the travel from 0.5 s on), having started within 50 ms (set down at depth
    0, it slides once its contact has taken up the load)."""
    s, x0, down = ramp_scene(f"Slide{round(math.degrees(theta) * 100)}", theta)
    r = simulate_fmu(str(fmu_of(s)), stop_time=2.0, output_interval=0.1)
    t = r["time"]
    travelled = (positions(r) - x0) @ down
    a = G * (math.sin(theta) - 0.3 * math.cos(theta))
    late = t >= 0.5 - 1e-9
    assert 2 * np.polyfit(t[late], travelled[late], 2)[0] == pytest.approx(a, rel=5e-3)
    assert 0.5 * a * (t[-1] - 0.05) ** 2 < travelled[-1] <= 0.5 * a * t[-1] ** 2 * (1 + 1e-3)
    # it stays on the ramp: no motion along the normal beyond the contact's resting
    # depth under g cos(theta)
    n = np.array([math.sin(theta), 0.0, math.cos(theta)])
    depth = resting_depth(G * math.cos(theta), STEP)
    along_normal = (positions(r) - x0) @ n
    assert np.max(np.abs(along_normal)) < depth + 1e-9
    np.testing.assert_allclose(along_normal[t >= 0.5 - 1e-9], -depth, rtol=0, atol=1e-9)


def flat_scene(name, v0=0.0, muk=0.3, half=5.0):
    cube = scenes.body("cube", shape={"type": "box", "size": [CUBE] * 3}, mass=1.5,
                       position=[0.0, 0.0, CUBE / 2], velocity=[v0, 0.0, 0.0],
                       staticFriction=0.5, kineticFriction=muk, restitution=0.0)
    s = scenes.scene(name, [cube])
    s["surfaces"] = [{"name": "floor", "min": [-half, -half, -1.0], "max": [half, half, 0.0],
                      "staticFriction": 0.5, "kineticFriction": muk, "restitution": 0.0}]
    return s


@pytest.mark.sweep("v0")
@pytest.mark.parametrize("v0", [1.0, 3.0])
def test_sliding_box_stops_after_closed_form_distance_and_stays(fmu_of, v0):
    r = simulate_fmu(str(fmu_of(flat_scene(f"Stop{int(v0)}", v0))), stop_time=3.0,
                     output_interval=0.01)
    x, v = r["cube.position[1]"], r["cube.velocity[1]"]
    assert x[-1] == pytest.approx(v0 ** 2 / (2 * 0.3 * G), rel=5e-3)
    stopped = r["time"] > v0 / (0.3 * G) + 0.05
    # at rest, no sign chatter and no creep: the velocity the stopping step leaves (below
    # 1e-8 m/s) decays, and the cube does not move
    assert np.all(np.abs(v[stopped]) < 1e-8)
    assert np.all(np.diff(np.abs(v[stopped])) <= 1e-15)
    assert np.ptp(x[stopped]) < 1e-10
    # friction never pushed it back: sliding, the cube pitches forward on its soft
    # contacts (the front corners carry mu_k m g more, and sink 2 mu_k d deeper over its
    # edge a); levelling as it stops moves its centre (a/2 above the floor) back by at
    # most mu_k d
    assert np.all(np.diff(x) >= -0.3 * resting_depth(G, STEP))


def test_resting_box_neither_sinks_nor_jitters(fmu_of):
    """Set down on the floor: it settles at the contact's resting depth under g within
    0.1 s, and there it stays."""
    r = simulate_fmu(str(fmu_of(flat_scene("Rest"))), stop_time=10.0, output_interval=0.1)
    z = r["cube.position[3]"]
    depth = resting_depth(G, STEP)
    assert np.max(np.abs(z - CUBE / 2)) < depth * (1 + 1e-6)
    np.testing.assert_allclose(z[1:], CUBE / 2 - depth, rtol=0, atol=1e-12)
    assert np.max(np.abs(r["cube.velocity[3]"])) < 1e-9


def test_box_pushed_over_the_edge_falls(fmu_of):
    s = Slave(fmu_of(flat_scene("Edge", half=1.0)))
    try:
        s.initialize()
        s.set_values({"cube.force[1]": 20.0})   # well above mu_s m g = 7.4 N
        z = []
        for _ in range(150):
            s.step(0.01)
            z.append(s.get("cube.position[3]"))
        x = s.get("cube.position[1]")
        assert x > 1.0                          # past the edge at x = 1 m
        assert z[-1] < CUBE / 2 - 0.1           # and falling
        # on the floor before (edge at ~0.44 s): pushed along at the contact's resting
        # depth under g
        assert min(z[:40]) == pytest.approx(CUBE / 2 - resting_depth(G, STEP), abs=1e-9)
    finally:
        s.close()


def test_dropped_box_lands_and_rests(fmu_of):
    s = flat_scene("Drop")
    s["bodies"][0]["position"] = [0.0, 0.0, 1.0]
    r = simulate_fmu(str(fmu_of(s)), stop_time=2.0, output_interval=0.01)
    late = r["time"] > 1.0
    # landed flat, seated at the contact's resting depth under g, and still
    z = r["cube.position[3]"][late]
    np.testing.assert_allclose(z, CUBE / 2 - resting_depth(G, STEP), rtol=0, atol=1e-9)
    assert np.ptp(z) < 1e-12
    assert np.all(np.abs(r["cube.velocity[3]"][late]) < 1e-9)
