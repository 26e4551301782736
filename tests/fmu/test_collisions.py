"""Body-body impacts through the FMU against closed forms: central impacts for
restitution 0, 0.5, 1 and mass ratios 1 to 1e6, conservation of momentum, the spin of
an off-centre impact from the seed's j, Newton's cradle, the collision switch."""
import numpy as np
import pytest
from fmpy import simulate_fmu

import scenes

R = 0.1


def two_spheres(name, m1, m2, v1, v2, xi, gap=0.5, **b2):
    a = scenes.body("a", shape={"type": "sphere", "radius": R}, mass=m1, position=[0, 0, 0],
                    velocity=[v1, 0, 0], restitution=xi, staticFriction=0.0, kineticFriction=0.0)
    b = scenes.body("b", shape={"type": "sphere", "radius": R}, mass=m2,
                    position=[2 * R + gap, 0, 0], velocity=[v2, 0, 0], restitution=xi,
                    staticFriction=0.0, kineticFriction=0.0, **b2)
    return scenes.scene(name, [a, b], gravity=(0, 0, 0))


# restitution zero or not takes another branch of the impulse; the mass ratio is numbers
@pytest.mark.sweep("ratio")
@pytest.mark.parametrize("ratio", (1.0, 1e3, 1e6))
@pytest.mark.parametrize("xi", (0.0, 0.5, 1.0))
def test_central_impact_matches_closed_form(fmu_of, xi, ratio):
    m1, m2, v1, v2 = 1.0, ratio, 2.0, -0.5
    s = two_spheres(f"Central{int(xi * 10)}_{int(np.log10(ratio))}", m1, m2, v1, v2, xi)
    r = simulate_fmu(str(fmu_of(s)), stop_time=1.0, output_interval=0.05)
    u1 = ((m1 - xi * m2) * v1 + (1 + xi) * m2 * v2) / (m1 + m2)
    u2 = ((m2 - xi * m1) * v2 + (1 + xi) * m1 * v1) / (m1 + m2)
    assert r["a.velocity[1]"][-1] == pytest.approx(u1, abs=1e-9)
    assert r["b.velocity[1]"][-1] == pytest.approx(u2, abs=1e-9 * max(1.0, abs(u2)))
    p = m1 * r["a.velocity[1]"] + m2 * r["b.velocity[1]"]
    p0 = m1 * v1 + m2 * v2
    assert np.max(np.abs(p - p0)) <= 1e-12 * abs(p0) + 1e-12 * m2 * 1e-3
    # the impact happened at the right place: a's position after the impact time
    t_hit = 0.5 / (v1 - v2)
    t = r["time"]
    after = t > t_hit
    x_hit = v1 * t_hit
    np.testing.assert_allclose(r["a.position[1]"][after], x_hit + u1 * (t[after] - t_hit), atol=1e-9)
    assert np.all(r["a.contacts"][t < t_hit - 1e-3] == 0)


def test_momentum_is_conserved_in_every_impact_linear_and_angular(fmu_of):
    """An oblique, off-centre impact of a box and a sphere (friction on)."""
    a = scenes.body("a", shape={"type": "box", "size": [0.4, 0.2, 0.2]}, mass=2.0,
                    position=[0, 0, 0], velocity=[1.5, 0.1, 0.0], angularVelocity=[0.0, 0.0, 0.3],
                    restitution=0.7)
    b = scenes.body("b", shape={"type": "sphere", "radius": R}, mass=0.7, position=[0.9, 0.12, 0.03],
                    velocity=[-1.0, 0.0, 0.0], restitution=0.7)
    r = simulate_fmu(str(fmu_of(scenes.scene("Oblique", [a, b], gravity=(0, 0, 0)))),
                     stop_time=1.0, output_interval=0.01)
    P = sum(m * np.column_stack([r[f"{n}.linearMomentum[{i}]"] for i in (1, 2, 3)])
            / m for n, m in (("a", 2.0), ("b", 0.7)))
    assert np.max(np.abs(P - P[0])) <= 1e-12 * np.linalg.norm(P[0])
    assert r["b.velocity[1]"][-1] > 0.0  # they did collide: b bounced back
    # angular momentum about the origin: sum of X x P + L
    L = 0
    for n in ("a", "b"):
        X = np.column_stack([r[f"{n}.position[{i}]"] for i in (1, 2, 3)])
        Pn = np.column_stack([r[f"{n}.linearMomentum[{i}]"] for i in (1, 2, 3)])
        L = L + np.cross(X, Pn) + np.column_stack([r[f"{n}.angularMomentum[{i}]"] for i in (1, 2, 3)])
    assert np.max(np.abs(L - L[0])) <= 1e-9 * np.linalg.norm(L[0]) + 1e-12


def test_off_centre_impact_spin_follows_the_seeds_j(fmu_of):
    """A sphere hits a resting box off its centre line; with no friction the impulse is
    along the box face normal (x). j from the seed's formula, computed here."""
    m_box, size, m_s, v = 3.0, np.array([0.2, 0.6, 0.2]), 0.5, 2.0
    offset = 0.2  # m, along y from the box centre
    xi = 0.6
    box = scenes.body("box", shape={"type": "box", "size": list(size)}, mass=m_box,
                      position=[0, 0, 0], restitution=xi, staticFriction=0.0, kineticFriction=0.0)
    ball = scenes.body("ball", shape={"type": "sphere", "radius": R}, mass=m_s,
                       position=[-0.5, offset, 0], velocity=[v, 0, 0], restitution=xi,
                       staticFriction=0.0, kineticFriction=0.0)
    r = simulate_fmu(str(fmu_of(scenes.scene("OffCentre", [ball, box], gravity=(0, 0, 0)))),
                     stop_time=0.5, output_interval=0.01)
    Izz = m_box / 12 * (size[0] ** 2 + size[1] ** 2)
    ra = np.array([-size[0] / 2, offset, 0.0])  # box: contact point from its centre
    n = np.array([1.0, 0, 0])                    # from ball to box
    k = 1 / m_s + 1 / m_box + n @ np.cross(np.cross(ra, n) / Izz * np.array([0, 0, 1]), ra)
    j = (1 + xi) * v / k
    assert r["box.velocity[1]"][-1] == pytest.approx(j / m_box, rel=1e-9)
    assert r["ball.velocity[1]"][-1] == pytest.approx(v - j / m_s, rel=1e-9)
    wz = np.cross(ra, j * n)[2] / Izz
    assert r["box.angularVelocity[3]"][-1] == pytest.approx(wz, rel=1e-6)


def test_newtons_cradle(fmu_of):
    """Five touching balls, xi = 1; the first hits at v0: the last leaves at v0 (1 %),
    the others keep below 1 % of v0."""
    v0 = 1.0
    balls = [scenes.body(f"b{k}", shape={"type": "sphere", "radius": R}, mass=1.0,
                         position=[k * 2 * R, 0, 0], restitution=1.0, staticFriction=0.0,
                         kineticFriction=0.0) for k in range(1, 5)]
    first = scenes.body("b0", shape={"type": "sphere", "radius": R}, mass=1.0,
                        position=[-0.3, 0, 0], velocity=[v0, 0, 0], restitution=1.0,
                        staticFriction=0.0, kineticFriction=0.0)
    r = simulate_fmu(str(fmu_of(scenes.scene("Cradle", [first] + balls, gravity=(0, 0, 0)))),
                     stop_time=1.0, output_interval=0.05)
    assert r["b4.velocity[1]"][-1] == pytest.approx(v0, rel=0.01)
    for k in range(4):
        assert abs(r[f"b{k}.velocity[1]"][-1]) < 0.01 * v0


def test_collision_switch(fmu_of):
    s = two_spheres("Ghost", 1.0, 1.0, 2.0, 0.0, 1.0)
    s["bodies"][1]["collision"] = False
    r = simulate_fmu(str(fmu_of(s)), stop_time=1.0, output_interval=0.05)
    np.testing.assert_allclose(r["a.position[1]"], 2.0 * r["time"], atol=1e-12)  # passes through
    assert np.all(r["a.contacts"] == 0)


def test_ball_bounces_off_the_side_of_a_surface(fmu_of):
    """Surfaces are boxes: their sides stop bodies too (FCL), with the seed's impulse."""
    ball = scenes.body("ball", shape={"type": "sphere", "radius": R}, mass=1.0,
                       position=[0, 0, 1.0], velocity=[5.0, 0, 0], restitution=0.5,
                       staticFriction=0.0, kineticFriction=0.0)
    s = scenes.scene("Wall", [ball], gravity=(0, 0, 0))
    s["surfaces"] = [{"name": "wall", "min": [1.0, -1, 0], "max": [1.2, 1, 2],
                      "staticFriction": 0.0, "kineticFriction": 0.0, "restitution": 0.5}]
    r = simulate_fmu(str(fmu_of(s)), stop_time=0.5, output_interval=0.01)
    assert np.max(r["ball.position[1]"]) <= 1.0 - R + 1e-9
    assert r["ball.velocity[1]"][-1] == pytest.approx(-0.5 * 5.0, abs=1e-9)


def mass_ratio_warnings(fmu_of, start=None, **b2):
    """The warnings of an initialisation of two spheres, 1 kg and 2000 kg (start values
    `start`), the heavy one with the body fields b2."""
    from harness import Slave
    scene = two_spheres("Ratio" + "".join(sorted(b2)), 1.0, 2000.0, 0.0, 0.0, 0.0, **b2)
    scene["gravity"] = [0.0, 0.0, -9.81]
    s = Slave(fmu_of(scene))
    try:
        s.initialize(start or {})
        return [m for status, _, m in s.log.messages if status == "Warning"]
    finally:
        s.close()


def test_a_mass_ratio_above_a_thousand_is_warned_of_at_initialisation(fmu_of):
    """Colliding bodies whose masses differ by more than 1e3 (the guide's limit) are
    warned of, with the sinking (M/m) g / omega^2 that the ratio gives at the step
    (omega = 2 pi 0.4 / h, h = 1 ms); a ratio within the limit, or a heavy body out of
    collisions, is not. The masses are parameters: the start values count."""
    sink = 2000 * 9.81 / (2 * np.pi * 0.4 / 1e-3) ** 2
    (warning,) = mass_ratio_warnings(fmu_of)
    assert "bodies b (2000 kg) and a (1 kg)" in warning and "mass ratio of 2000" in warning
    assert f"sink in by up to {sink:.3g} m" in warning
    assert mass_ratio_warnings(fmu_of, {"b.mass": 1000.0}) == []
    assert mass_ratio_warnings(fmu_of, collision=False) == []
    (warning,) = mass_ratio_warnings(fmu_of, {"a.mass": 0.5, "b.mass": 1000.0})
    assert "mass ratio of 2000" in warning and f"{sink:.3g} m" in warning
