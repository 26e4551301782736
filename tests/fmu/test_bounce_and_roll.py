"""Impacts on a surface located inside the step, and friction at the contact point of
round bodies (issue 4), through the FMU against closed forms."""
import math

import numpy as np
import pytest
from fmpy import simulate_fmu

import scenes
from reference import resting_depth

G = 9.81
R = 0.1


def floor(xi=0.8, mus=0.5, muk=0.3):
    return [{"name": "floor", "min": [-50, -5, -1], "max": [50, 5, 0],
             "staticFriction": mus, "kineticFriction": muk, "restitution": xi}]


def drop_scene(h, xi=0.8, h0=1.0):
    ball = scenes.body("ball", shape={"type": "sphere", "radius": R}, mass=1.0,
                       position=[0, 0, R + h0], restitution=xi)
    s = scenes.scene(f"Drop{round(h * 1e4)}", [ball], step=h)
    s["surfaces"] = floor(xi)
    return s


@pytest.mark.sweep("h")
@pytest.mark.parametrize("h", [1e-3, 1e-2])
def test_bounce_apex_heights_follow_restitution_at_any_step(fmu_of, h):
    """Apex n = e^(2n) h0 within 1 % (never above) for n = 1..4, at h = 1e-3 and 1e-2;
    at rest (|v| < 1e-3 m/s) after t_inf = t1 (1 + e) / (1 - e)."""
    e, h0 = 0.8, 1.0
    r = simulate_fmu(str(fmu_of(drop_scene(h, e, h0))), stop_time=6.0, output_interval=h)
    t, z, v = r["time"], r["ball.position[3]"] - R, r["ball.velocity[3]"]
    t1 = math.sqrt(2 * h0 / G)
    # the n-th flight lies between impacts at t1 + 2 t1 (e + ... + e^(n-1)) and the next;
    # within it every sample gives the apex z + v^2 / 2g
    impacts = [t1 + 2 * t1 * sum(e ** k for k in range(1, n + 1)) for n in range(0, 6)]
    for n in range(1, 5):
        mid = 0.5 * (impacts[n - 1] + impacts[n])
        i = np.argmin(np.abs(t - mid))
        apex = z[i] + v[i] ** 2 / (2 * G)
        target = e ** (2 * n) * h0
        assert apex == pytest.approx(target, rel=0.01), (n, apex, target)
        assert apex <= target * (1 + 1e-9), (n, apex, target)
    t_inf = t1 * (1 + e) / (1 - e)
    rest = t > t_inf
    assert np.max(np.abs(v[rest])) < 1e-3
    # at rest on the floor: the last hops, too slow to bounce (below 2 g h), are held at
    # their gap as they land, and the ball settles at the contact's resting depth
    depth = resting_depth(G, h)
    assert np.max(np.abs(z[rest])) < depth * (1 + 1e-6)
    assert z[-1] == pytest.approx(-depth, abs=1e-9)


def test_sliding_sphere_ends_rolling_without_slipping(fmu_of):
    """v0 = 2 m/s, no spin, mu_k = 0.3: friction at the contact point slows it and spins
    it up until v = omega r = 5/7 v0 at t = 2 v0 / (7 mu_k g); then it rolls. The ball
    rests at the contact's depth d, its contact point in the middle of the overlap: the
    lever is r = R - d/2."""
    v0 = 2.0
    ball = scenes.body("ball", shape={"type": "sphere", "radius": R}, mass=1.0,
                       position=[0, 0, R], velocity=[v0, 0, 0], staticFriction=0.5,
                       kineticFriction=0.3, restitution=0.0)
    s = scenes.scene("Roll", [ball])
    s["surfaces"] = floor(0.0)
    r = simulate_fmu(str(fmu_of(s)), stop_time=2.0, output_interval=0.01)
    t, v, w = r["time"], r["ball.velocity[1]"], r["ball.angularVelocity[2]"]
    t_roll = 2 * v0 / (7 * 0.3 * G)
    depth = resting_depth(G, 1e-3)
    lever = R - depth / 2
    sliding = t < t_roll - 0.01
    np.testing.assert_allclose(v[sliding], v0 - 0.3 * G * t[sliding], rtol=0, atol=1e-9)
    spin_up = 2.5 * 0.3 * G * lever / R ** 2  # rad/s^2
    settled = sliding & (t > 0.05)
    assert np.polyfit(t[settled], w[settled], 1)[0] == pytest.approx(spin_up, rel=1e-9)
    # the first milliseconds, as the ball sinks to its resting depth, add under 1e-6 rad/s
    np.testing.assert_allclose(w[sliding], spin_up * t[sliding], rtol=0, atol=1e-6)
    rolling = t > t_roll + 0.01
    assert np.all(np.abs(v[rolling] - 5 / 7 * v0) < 1e-3 * v0)
    assert np.all(np.abs(w[rolling] * lever - v[rolling]) < 1e-9)
    z = r["ball.position[3]"]
    assert np.all((z <= R) & (z >= R - depth * (1 + 1e-6)))
    assert np.all(np.abs(z[t > 0.05] - (R - depth)) < 1e-9)


def test_contact_count_output(fmu_of):
    """b.contacts: contact points at the end of the last step, 0 in flight, 1 at rest."""
    from harness import Slave
    s = Slave(fmu_of(drop_scene(1e-3, xi=0.0, h0=0.2)))
    try:
        s.initialize()
        vr = s.vr(["ball.contacts"])
        assert s.slave.getInteger(vr) == [0]
        s.step(0.1)
        assert s.slave.getInteger(vr) == [0]        # still falling (lands at 0.2 s)
        s.step(0.5)
        assert s.slave.getInteger(vr) == [1]        # resting on the floor
        assert s.get("ball.position[3]") == pytest.approx(R - resting_depth(G, 1e-3), abs=1e-9)
    finally:
        s.close()
