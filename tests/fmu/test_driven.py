"""Driven bodies and moving surfaces (issue 40): a body whose pose and velocities are
inputs, moved by another model, infinitely heavy to the contacts. Closed forms: a
platform accelerating upward at a lifts a box with m (g + a); a box on a platform
that moves sideways rides along; a pusher at constant speed feels mu_k m g; a
turntable carries a box around its circle. A jump is pushed through and logged; a
quaternion that is not one is refused; FMU states carry the inputs."""
import math

import numpy as np
import pytest

G = 9.81
H = 0.01  # s, the communication step
M = 2.0   # kg, the free box


def box(name, size, **fields):
    return {"name": name, "shape": {"type": "box", "size": size}, **fields}


def platform_scene(**platform):
    """A box of M on a driven platform, nothing else: the platform carries it all."""
    return {"name": "Platform", "solver": {"method": "rk4", "step": 0.001},
            "bodies": [box("load", [0.2, 0.2, 0.2], mass=M, position=[0, 0, 0.1], staticFriction=0.5,
                           kineticFriction=0.4),
                       box("platform", [1, 1, 0.1], motion="driven", position=[0, 0, -0.05], **platform)]}


def pusher_scene():
    return {"name": "Pusher", "solver": {"method": "rk4", "step": 0.001},
            "bodies": [box("load", [0.2, 0.2, 0.2], mass=M, position=[0, 0, 0.1], staticFriction=0.5,
                           kineticFriction=0.3),
                       box("pusher", [0.1, 0.4, 0.1], motion="driven", position=[-0.3, 0, 0.1],
                           staticFriction=0.0, kineticFriction=0.0, restitution=0.0)],
            "surfaces": [{"name": "floor", "min": [-5, -5, -1], "max": [5, 5, 0], "staticFriction": 0.5,
                          "kineticFriction": 0.3}]}


def drive(s, name, t, position, velocity, acceleration=None):
    """Sets a driven body's position and velocity at the communication point t (and the
    velocity's input derivative), then steps."""
    values = {f"{name}.position[{i + 1}]": position[i] for i in range(3)}
    values.update({f"{name}.velocity[{i + 1}]": velocity[i] for i in range(3)})
    s.set_values(values)
    if acceleration is not None:
        s.slave.setRealInputDerivatives(s.vr([f"{name}.velocity[{i + 1}]" for i in range(3)]), [1, 1, 1],
                                        list(acceleration))
    s.step(H, t)


def test_a_platform_accelerating_upward_lifts_a_box_with_m_g_plus_a(slave):
    s = slave(platform_scene())
    z0, a = -0.05, 2.0
    for k in range(50):  # at rest first: the box's weight
        drive(s, "platform", k * H, [0, 0, z0], [0, 0, 0])
    assert s.get("load.contactForce[3]") == pytest.approx(M * G, rel=1e-6)
    t0 = 50 * H
    for k in range(100):
        t = k * H
        drive(s, "platform", t0 + t, [0, 0, z0 + 0.5 * a * t * t], [0, 0, a * t], acceleration=[0, 0, a])
        if k >= 10:  # once the contact has taken the new load
            assert s.get("load.contactForce[3]") == pytest.approx(M * (G + a), rel=1e-6), k
            assert s.get("platform.contactForce[3]") == pytest.approx(-M * (G + a), rel=1e-6), k
    T = 100 * H
    assert s.get("load.position[3]") == pytest.approx(0.1 + 0.5 * a * T * T, abs=1e-5)


def test_a_box_on_a_platform_moving_sideways_rides_along(slave):
    # both start at 1 m/s along x; then the platform accelerates at 1 m/s^2, which
    # friction (mu_s g = 4.9 m/s^2) can give the box: it never slips
    scene = platform_scene(velocity=[1, 0, 0])
    scene["name"] = "Ride"
    scene["bodies"][0]["velocity"] = [1, 0, 0]
    s = slave(scene)
    a = 1.0
    for k in range(200):
        t = k * H
        x = t + (0.5 * a * (t - 1.0) ** 2 if t > 1.0 else 0.0)
        v = 1.0 + (a * (t - 1.0) if t > 1.0 else 0.0)
        drive(s, "platform", t, [x, 0, -0.05], [v, 0, 0], acceleration=[a if t >= 1.0 else 0.0, 0, 0])
        t1 = t + H
        x1 = t1 + (0.5 * a * (t1 - 1.0) ** 2 if t1 > 1.0 else 0.0)
        assert s.get("load.position[1]") - x1 == pytest.approx(0.0, abs=1e-6), t1
        if t >= 1.1:
            assert s.get("load.contactForce[1]") == pytest.approx(M * a, rel=1e-6), t1


def test_a_pusher_at_constant_speed_feels_mu_k_m_g(slave):
    s = slave(pusher_scene())
    v, muk = 0.5, 0.3
    for k in range(200):
        t = k * H
        drive(s, "pusher", t, [-0.3 + v * t, 0, 0.1], [v, 0, 0])
        if t >= 1.0:  # long after the pusher met the box (at 0.4 s)
            assert s.get("load.velocity[1]") == pytest.approx(v, rel=1e-6)
            assert s.get("pusher.contactForce[1]") == pytest.approx(-muk * M * G, rel=1e-6)
            assert s.get("floor.force[1]") == pytest.approx(muk * M * G, rel=1e-6)


def test_a_turntable_carries_a_box_around_its_circle(slave):
    omega, r = 1.0, 0.3
    scene = platform_scene(angularVelocity=[0, 0, omega])
    scene["name"] = "Turntable"
    scene["bodies"][0].update(position=[r, 0, 0.1], velocity=[0, omega * r, 0], angularVelocity=[0, 0, omega],
                              staticFriction=1.0, kineticFriction=0.8)
    s = slave(scene)
    for k in range(150):
        t = k * H
        angle = omega * (t + H)
        s.set_values({"platform.orientation[1]": math.cos(omega * t / 2),
                      "platform.orientation[4]": math.sin(omega * t / 2)})
        s.step(H, t)
        x, y = s.get("load.position[1]", "load.position[2]")
        # the radius creeps out by (omega r h_sub)^2 / (2 r) a solver sub-step (each moves
        # the box along a tangent; no contact row corrects positions along the surface):
        # 3.7e-5 m/s here, 5.6e-5 m after 1.5 s
        assert math.hypot(x, y) == pytest.approx(r, abs=1e-4), t
        assert math.atan2(y, x) == pytest.approx(angle, abs=1e-4), t
    # the centripetal force m omega^2 r, toward the axis
    x, y = s.get("load.position[1]", "load.position[2]")
    fx, fy = s.get("load.contactForce[1]", "load.contactForce[2]")
    assert fx * x + fy * y == pytest.approx(-M * omega ** 2 * r * r, rel=1e-3)


def test_a_moving_surface_is_a_driven_box_named_after_the_surface(slave):
    scene = {"name": "Elevator", "bodies": [box("load", [0.2, 0.2, 0.2], mass=M, position=[0, 0, 0.1])],
             "surfaces": [{"name": "floor", "motion": "driven", "min": [-1, -1, -0.1], "max": [1, 1, 0]},
                          {"name": "wall", "min": [2, -1, 0], "max": [2.1, 1, 1]}]}
    s = slave(scene)
    assert "floor.position[3]" in s.vars and "floor.contactForce[3]" in s.vars and "wall.force[1]" in s.vars
    assert s.vars["floor.position[3]"].causality == "input"
    assert float(s.vars["floor.position[3]"].start) == -0.05
    v = 0.3
    for k in range(100):
        t = k * H
        drive(s, "floor", t, [0, 0, -0.05 + v * t], [0, 0, v])
    assert s.get("load.position[3]") == pytest.approx(0.1 + v * 1.0, abs=1e-4)
    assert s.get("floor.contactForce[3]") == pytest.approx(-M * G, rel=1e-6)


def test_a_jump_pushes_what_it_meets_out_and_says_so(slave):
    s = slave(pusher_scene())
    s.step(H, 0.0)
    drive(s, "pusher", H, [0.3, 0, 0.1], [0, 0, 0])  # from -0.3 m through the box at 0, in one step
    warning = s.log.text()
    assert "pusher.position: the inputs moved the body by 0.6" in warning and "pushing what it meets" in warning
    x = s.get("load.position[1]")
    assert x - 0.1 >= 0.3 + 0.05 - 1e-3, "the box is left inside the pusher"
    for k in range(20):
        drive(s, "pusher", (k + 2) * H, [0.3, 0, 0.1], [0, 0, 0])
    assert s.get("load.position[1]") - 0.1 >= 0.35 - 1e-3


def test_an_orientation_that_is_no_quaternion_is_refused_naming_it(slave):
    s = slave(pusher_scene())
    s.set_values({"pusher.orientation[1]": 0.5})
    with pytest.raises(Exception):
        s.step(H, 0.0)
    assert "pusher.orientation: must be a unit quaternion (its norm within 0.001 of 1" in s.log.text()
    assert "got norm 0.5" in s.log.text()


def test_a_nearly_unit_orientation_is_normalised(slave):
    s = slave(pusher_scene())
    s.set_values({"pusher.orientation[1]": 1.0 + 1e-4})
    s.step(H, 0.0)
    assert np.isfinite(s.all_reals()).all()


def test_fmu_states_and_reset_carry_the_driven_inputs(slave):
    s = slave(pusher_scene())

    def run(k0, k1):
        out = []
        for k in range(k0, k1):
            t = k * H
            drive(s, "pusher", t, [-0.3 + 0.5 * t, 0, 0.1], [0.5, 0, 0], acceleration=[0.1 * (k % 3), 0, 0])
            out.append(s.all_reals())
        return out
    first = run(0, 60)
    state = s.slave.getFMUstate()
    blob = s.slave.serializeFMUstate(state)
    straight = run(60, 100)
    s.slave.setFMUstate(state)
    assert run(60, 100) == straight
    s.slave.setFMUstate(s.slave.deSerializeFMUstate(blob))
    assert run(60, 100) == straight
    s.slave.reset()
    s.initialize()
    assert s.get("pusher.position[1]") == -0.3
    assert run(0, 60) == first


def test_a_turntable_spun_up_by_its_inputs_carries_a_box_and_is_never_refused(slave):
    # angular acceleration alpha as the angular velocity's input derivative: the energy
    # audit, which refuses rotational energy that a torque-free body gains, must leave
    # a driven body's given turning alone
    alpha, omega0, r = 2.0, 0.5, 0.3
    scene = platform_scene(angularVelocity=[0, 0, omega0])
    scene["name"] = "SpinUp"
    scene["bodies"][0].update(position=[r, 0, 0.1], velocity=[0, omega0 * r, 0], angularVelocity=[0, 0, omega0],
                              staticFriction=1.0, kineticFriction=0.8)
    s = slave(scene)
    vr = s.vr(["platform.angularVelocity[3]"])
    for k in range(100):
        t = k * H
        half = 0.5 * (omega0 * t + 0.5 * alpha * t * t)
        s.set_values({"platform.orientation[1]": math.cos(half), "platform.orientation[4]": math.sin(half),
                      "platform.angularVelocity[3]": omega0 + alpha * t})
        s.slave.setRealInputDerivatives(vr, [1], [alpha])
        s.step(H, t)
    x, y = s.get("load.position[1]", "load.position[2]")
    assert math.atan2(y, x) == pytest.approx(omega0 + 0.5 * alpha, abs=1e-3)
    assert math.hypot(x, y) == pytest.approx(r, abs=1e-4)
