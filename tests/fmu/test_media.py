"""Media through the FMU: drag and buoyancy against closed forms (docs/reports/media.md)."""
import math

import numpy as np
import pytest
from fmpy import simulate_fmu

import scenes
from harness import Slave

G = 9.81
RHO_WATER = 998.2      # kg/m3, the "water" type's density
MU_WATER = 1.002e-3    # Pa s
SPHERE_CD = 0.47       # docs/reports/media.md


def medium(name="pool", kind="custom", lo=(-100, -100, -100), hi=(100, 100, 100), **fields):
    m = {"name": name, "type": kind, "min": list(lo), "max": list(hi)}
    m.update(fields)
    return m


def with_media(scene, *media):
    scene["media"] = list(media)
    return scene


def sphere_volume(r):
    return 4.0 / 3.0 * math.pi * r**3


def columns(result, prefix, n=3):
    return np.column_stack([result[f"{prefix}[{i}]"] for i in range(1, n + 1)])


def test_linear_drag_relaxes_exponentially_to_terminal_velocity(fmu_of):
    """Density 0, viscosity mu: m dv/dt = m g - b v with Stokes' b = 6 pi mu r, so
    v = v_T + (v0 - v_T) e^(-t/tau), tau = m/b, v_T = m g / b, in every component."""
    r, m, b = 0.1, 1.0, 2.0
    mu = b / (6 * math.pi * r)
    v0 = np.array([1.0, -0.5, 3.0])
    s = with_media(scenes.scene("LinearDrag", [scenes.body("ball", shape={"type": "sphere", "radius": r},
                                                           mass=m, velocity=list(v0))]),
                   medium(density=0.0, viscosity=mu))
    res = simulate_fmu(str(fmu_of(s)), stop_time=3.0, output_interval=0.05)
    t = res["time"][:, None]
    tau, vT = m / b, np.array([0.0, 0.0, -m * G / b])
    v = vT + (v0 - vT) * np.exp(-t / tau)
    x = vT * t + (v0 - vT) * tau * (1 - np.exp(-t / tau))
    scale_v = np.abs(v0 - vT).max()
    assert np.abs(columns(res, "ball.velocity") - v).max() <= 1e-6 * scale_v
    assert np.abs(columns(res, "ball.position") - x).max() <= 1e-6 * np.abs(x).max()
    # the run reached the terminal regime: v differs from v0 by most of (v0 - v_T)
    assert abs(res["ball.velocity[3]"][-1] - vT[2]) < 0.01 * scale_v


def test_quadratic_drag_with_buoyancy_follows_tanh(fmu_of):
    """Viscosity 0, density rho_f: m dv/dt = m g' - 1/2 rho_f Cd A v^2 with
    g' = g (1 - rho_f/rho_b): v = v_T tanh(g' t / v_T), v_T = sqrt(2 m g'/(rho_f Cd A))."""
    r, m, rho_f = 0.1, 10.0, 100.0
    s = with_media(scenes.scene("QuadDrag", [scenes.body("ball", shape={"type": "sphere", "radius": r},
                                                         mass=m, position=[0, 0, 50.0])]),
                   medium(density=rho_f, viscosity=0.0))
    res = simulate_fmu(str(fmu_of(s)), stop_time=4.0, output_interval=0.05)
    t = res["time"]
    g1 = G * (1 - rho_f * sphere_volume(r) / m)
    vT = math.sqrt(2 * m * g1 / (rho_f * SPHERE_CD * math.pi * r**2))
    v = -vT * np.tanh(g1 * t / vT)
    z = 50.0 - vT**2 / g1 * np.log(np.cosh(g1 * t / vT))
    np.testing.assert_allclose(res["ball.velocity[3]"], v, rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(res["ball.position[3]"], z, rtol=1e-6)
    assert res["ball.velocity[3]"][-1] < -0.9 * vT   # close to terminal: the drag term is tested
    assert np.abs(columns(res, "ball.velocity")[:, :2]).max() == 0.0


def test_floating_box_settles_at_its_draft(fmu_of):
    """A 1 x 1 x 0.5 m box of density 500 in water floats at draft
    d = m / (rho_w A) = 0.5 * 500 / 998.2 = 0.25045 m; released at draft 0.15 m, the
    heave is damped by the drag; after 60 s its mean draft is within 1 mm."""
    size, rho_b = [1.0, 1.0, 0.5], 500.0
    m = rho_b * 0.5
    d = m / (RHO_WATER * 1.0)
    s = with_media(scenes.scene("Float", [scenes.body("box", shape={"type": "box", "size": size},
                                                      mass=m, position=[0, 0, 0.25 - 0.15])]),
                   medium(kind="water", lo=(-10, -10, -10), hi=(10, 10, 0)))
    res = simulate_fmu(str(fmu_of(s)), stop_time=60.0, output_interval=0.01)
    t, z = res["time"], res["box.position[3]"]
    last = t >= 50.0
    draft = 0.25 - z[last].mean()
    print(f"floating box: mean draft {draft:.6f} m (closed form {d:.6f} m), "
          f"heave amplitude {0.5 * np.ptp(z[last]) * 1e3:.2f} mm over the last 10 s")
    assert abs(draft - d) < 1e-3
    assert abs(draft - 0.25) < 1e-3
    assert np.ptp(z[last]) < 0.2 * np.ptp(z[t < 2.0])  # the heave was damped
    # upright and still in the other directions
    assert np.abs(columns(res, "box.position")[:, :2]).max() < 1e-12
    assert np.abs(columns(res, "box.angularVelocity")).max() < 1e-12


def test_submerged_light_sphere_rises_with_buoyant_acceleration(fmu_of):
    """Fully under water, rho_b < rho_w: a = g (rho_w/rho_b - 1) upward before drag
    matters. Drag only slows it, by at most int (k v^2 + b v)/m dt with v <= a t."""
    r, rho_b = 0.1, 500.0
    m = rho_b * sphere_volume(r)
    s = with_media(scenes.scene("Rise", [scenes.body("ball", shape={"type": "sphere", "radius": r},
                                                     mass=m, position=[0, 0, -5.0])]),
                   medium(kind="water", lo=(-10, -10, -10), hi=(10, 10, 0)))
    a = G * (RHO_WATER / rho_b - 1)
    k = 0.5 * RHO_WATER * SPHERE_CD * math.pi * r**2
    b = 6 * math.pi * MU_WATER * r
    slave = Slave(fmu_of(s))
    try:
        slave.initialize()
        for i in range(1, 6):
            slave.step(1e-3)
            t = i * 1e-3
            v = slave.get("ball.velocity[3]")
            drag_bound = (k * a**2 * t**3 / 3 + b * a * t**2 / 2) / m
            assert v <= a * t + 1e-12
            assert a * t - v <= drag_bound + 1e-12, (t, v, a * t, drag_bound)
            assert drag_bound < 1e-3 * a * t  # so the check resolves buoyancy to 0.1 %
    finally:
        slave.close()


def test_body_outside_the_medium_falls_freely(fmu_of):
    """Above the pool, and beside it (5 cm from its wall, through its height range)."""
    pool = medium(kind="water", lo=(-1, -1, -10), hi=(1, 1, 0))
    s = with_media(scenes.scene("Outside", [
        scenes.body("above", position=[0, 0, 10.0]),
        scenes.body("beside", position=[1.15, 0, 0.5]),
    ]), pool)
    res = simulate_fmu(str(fmu_of(s)), stop_time=1.0, output_interval=0.05)
    t = res["time"]
    np.testing.assert_allclose(res["above.position[3]"], 10.0 - 0.5 * G * t**2, rtol=0, atol=1e-9)
    np.testing.assert_allclose(res["beside.position[3]"], 0.5 - 0.5 * G * t**2, rtol=0, atol=1e-9)
    assert res["beside.position[3]"][-1] < -4.0  # it did pass the pool's height


def roll_angle(res, name):
    return 2 * np.arctan2(res[f"{name}.orientation[2]"], res[f"{name}.orientation[1]"])


def test_heeled_floating_box_rolls_back_upright(fmu_of):
    """The 1 x 1 x 0.5 m box of density 500 at its draft, heeled 10 deg about x: the
    wall-sided righting moment rho g V GZ, GZ = sin(th)(GM + BM tan^2(th)/2), gives the
    initial angular acceleration; it then rolls through upright after about a quarter
    of the small-angle period 2 pi sqrt(I / (rho g V GM)), and the roll decays."""
    m, th = 250.0, math.radians(10.0)
    d = m / RHO_WATER
    s = with_media(scenes.scene("Heeled", [scenes.body(
        "box", shape={"type": "box", "size": [1.0, 1.0, 0.5]}, mass=m,
        position=[0, 0, 0.25 - d], orientation=[math.cos(th / 2), math.sin(th / 2), 0, 0])]),
        medium(kind="water", lo=(-10, -10, -10), hi=(10, 10, 0)))
    fmu = str(fmu_of(s))
    V = d * 1.0
    BM, KB, KG = 1.0 / (12 * d), d / 2, 0.25
    GM = KB + BM - KG
    GZ = math.sin(th) * (GM + 0.5 * BM * math.tan(th)**2)
    Ixx = m * (1.0 + 0.25) / 12
    alpha = -RHO_WATER * G * V * GZ / Ixx
    early = simulate_fmu(fmu, stop_time=0.01, output_interval=0.01)
    w = early["box.angularVelocity[1]"][-1]
    assert w / 0.01 == pytest.approx(alpha, rel=1e-2)

    res = simulate_fmu(fmu, stop_time=6.0, output_interval=0.01)
    t, roll = res["time"], roll_angle(res, "box")
    quarter = 0.25 * 2 * math.pi * math.sqrt(Ixx / (RHO_WATER * G * V * GM))
    first_zero = t[np.argmax(roll <= 0.0)]
    print(f"heeled box: first upright at {first_zero:.3f} s (small-angle quarter period "
          f"{quarter:.3f} s), roll amplitude after 5 s {math.degrees(np.abs(roll[t >= 5]).max()):.2f} deg")
    assert roll.min() < 0.0                      # it rolled back through upright
    assert first_zero == pytest.approx(quarter, rel=0.1)
    assert np.abs(roll[t >= 5.0]).max() < 0.5 * th  # and the roll is being damped


def test_box_entering_the_water_is_slowed_only_once_inside(fmu_of):
    """Falling from 1 m: exact free fall until its bottom touches the surface at
    t_c = sqrt(2 * 0.9 / g); slowed (buoyancy twice its weight, drag) after."""
    h = 0.1
    s = with_media(scenes.scene("Entry", [scenes.body(
        "box", shape={"type": "box", "size": [2 * h] * 3}, mass=500.0 * (2 * h)**3,
        position=[0, 0, 1.0])]), medium(kind="water", lo=(-5, -5, -5), hi=(5, 5, 0)))
    res = simulate_fmu(str(fmu_of(s)), stop_time=1.0, output_interval=0.01)
    t, z, v = res["time"], res["box.position[3]"], res["box.velocity[3]"]
    t_c = math.sqrt(2 * (1.0 - h) / G)
    before = t < t_c - 0.005
    np.testing.assert_allclose(z[before], 1.0 - 0.5 * G * t[before]**2, rtol=0, atol=1e-9)
    np.testing.assert_allclose(v[before], -G * t[before], rtol=0, atol=1e-9)
    after = t > t_c + 0.05
    assert (v[after] > -G * t[after] + 0.1).all()  # slower than free fall by > 0.1 m/s
    assert v[-1] > v[after][0]                       # and decelerating
