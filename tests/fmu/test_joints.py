"""Joints (issue 41): hinges, sliders, ball joints, welds and distance joints (rods,
ropes, springs), with limits, motors and reaction outputs, solved as rows of the one
constraint solver. Closed forms: the pendulum's period (small amplitude, and at 90 deg
from the complete elliptic integral), a physical pendulum on a hinge, a hanging chain's
reactions (the weight below each joint), a motor's spin-up at tau / I, a slider
stopping at its limit and bouncing off it with the joint's restitution, a spring's
period. Mechanisms (double pendulum, four-bar, Newton's cradle) are in
test_joint_mechanisms.py."""
import math

import numpy as np
import pytest
from scipy.special import ellipk

G = 9.81


def sphere(name, position, mass=1.0, radius=0.05, **fields):
    return {"name": name, "shape": {"type": "sphere", "radius": radius}, "mass": mass, "position": position,
            "collision": False, **fields}


def box(name, size, position, mass=1.0, **fields):
    return {"name": name, "shape": {"type": "box", "size": size}, "mass": mass, "position": position,
            "collision": False, **fields}


def scene(name, bodies, joints, step=1e-3, **extra):
    return {"name": name, "solver": {"method": "rk4", "step": step}, "bodies": bodies, "joints": joints, **extra}


def run(s, names, duration, h):
    """The outputs `names` at every communication point of steps h over `duration` from
    where the slave is, and those points' times."""
    n, start = int(round(duration / h)), s.time
    out = np.empty((n + 1, len(names)))
    out[0] = s.get(*names)
    for k in range(n):
        s.step(h, start + k * h)
        out[k + 1] = s.get(*names)
    return start + np.arange(n + 1) * h, out


def crossings(t, x):
    """The instants at which x crosses zero upward (linear interpolation)."""
    k = np.where((x[:-1] < 0) & (x[1:] >= 0))[0]
    return t[k] - x[k] * (t[k + 1] - t[k]) / (x[k + 1] - x[k])


# ---- the simple pendulum: a sphere on a massless rod (a distance joint) -------------

L = 1.0  # m


def rod_pendulum():
    return scene("RodPendulum", [sphere("bob", [0, 0, -L])],
                 [{"name": "rod", "type": "distance", "bodies": ["world", "bob"], "anchors": [[0, 0, 0], [0, 0, 0]]}])


def test_a_rod_pendulum_swings_at_the_small_amplitude_period(slave):
    theta0 = 0.01  # rad: the amplitude's own correction, theta0^2 / 16, is 6e-6
    s = slave(rod_pendulum(), start={"bob.position[1]": L * math.sin(theta0), "bob.position[3]": -L * math.cos(theta0)})
    t, x = run(s, ["bob.position[1]"], 10.0, 0.001)
    period = np.mean(np.diff(crossings(t, x[:, 0])))
    assert period == pytest.approx(2 * math.pi * math.sqrt(L / G), rel=1e-3)


def test_a_rod_pendulum_from_horizontal_keeps_the_elliptic_period_and_its_energy(slave):
    """90 deg amplitude: T = 4 sqrt(L/g) K(sin^2 45 deg); over 100 periods the energy
    drifts by less than 0.1 % of m g L (rk4)."""
    s = slave(rod_pendulum(), start={"bob.position[1]": L, "bob.position[3]": 0.0})
    names = ["bob.position[1]", "bob.position[3]", "bob.velocity[1]", "bob.velocity[3]", "rod.position"]
    period = 4 * math.sqrt(L / G) * ellipk(0.5)
    t, y = run(s, names, 100 * period, 0.01)
    measured = np.diff(crossings(t, y[:, 0]))
    assert np.mean(measured) == pytest.approx(period, rel=5e-3)
    energy = 0.5 * (y[:, 2] ** 2 + y[:, 3] ** 2) + G * y[:, 1]  # per kg, zero at the start
    assert np.max(np.abs(energy)) < 1e-3 * G * L
    assert np.max(np.abs(y[:, 4] - L)) < 1e-4  # the rod's length


def test_the_rod_pulls_with_the_centripetal_force_at_the_bottom(slave):
    """From rest at 90 deg the bob passes the bottom at v^2 = 2 g L: the rod pulls with
    m (g + v^2 / L) = 3 m g."""
    s = slave(rod_pendulum(), start={"bob.position[1]": L, "bob.position[3]": 0.0})
    t, y = run(s, ["bob.position[1]", "rod.reactionForce[3]"], 0.6, 0.001)
    k = np.argmin(np.abs(y[:, 0]))
    assert y[k, 1] == pytest.approx(3 * G, rel=2e-3)


# ---- the physical pendulum: a box on a hinge -----------------------------------------

def hinged_box(**hinge):
    """A box 0.1 x 0.1 x 1 m hanging from a hinge about y at its top end."""
    return scene("HingedBox", [box("leaf", [0.1, 0.1, 1.0], [0, 0, -0.5], mass=2.0)],
                 [{"name": "hinge", "type": "revolute", "bodies": ["world", "leaf"], "anchor": [0, 0, 0],
                   "axis": [0, 1, 0], **hinge}])


def test_a_box_on_a_hinge_swings_at_the_physical_pendulum_period(slave):
    theta0 = 0.01
    s = slave(hinged_box(), start={"leaf.position[1]": 0.5 * math.sin(theta0),
                                   "leaf.position[3]": -0.5 * math.cos(theta0),
                                   "leaf.orientation[1]": math.cos(theta0 / 2),
                                   "leaf.orientation[3]": -math.sin(theta0 / 2)})
    t, y = run(s, ["leaf.position[1]", "hinge.position"], 10.0, 0.001)
    m, d = 2.0, 0.5
    inertia = m * (0.1 ** 2 + 1.0 ** 2) / 12 + m * d * d  # about the hinge
    period = 2 * math.pi * math.sqrt(inertia / (m * G * d))
    assert np.mean(np.diff(crossings(t, y[:, 0]))) == pytest.approx(period, rel=1e-3)


# ---- a hanging chain: every joint carries the weight below it -------------------------

LINKS, LINK, LINK_MASS = 20, 0.1, 0.1  # links, m long, kg


def chain():
    """Twenty links hanging straight down from the world on ball joints, at rest."""
    links = [box(f"link{k}", [0.02, 0.02, LINK], [0, 0, -(k + 0.5) * LINK], mass=LINK_MASS) for k in range(LINKS)]
    joints = [{"name": f"ball{k}", "type": "spherical", "bodies": ["world" if k == 0 else f"link{k - 1}", f"link{k}"],
               "anchor": [0, 0, -k * LINK]} for k in range(LINKS)]
    return scene("Chain", links, joints)


def rotate(q, v):
    """The vectors v (rows) turned by the unit quaternions q (rows, w first)."""
    w, u = q[:, :1], q[:, 1:]
    return v + 2 * w * np.cross(u, v) + 2 * np.cross(u, np.cross(u, v))


def test_a_hanging_chain_keeps_its_links_together_and_each_joint_carries_the_weight_below(slave):
    s = slave(chain())
    for _ in range(200):
        s.step(0.01)
    pos = np.array([s.get(*[f"link{k}.position[{i}]" for i in (1, 2, 3)]) for k in range(LINKS)])
    quat = np.array([s.get(*[f"link{k}.orientation[{i}]" for i in (1, 2, 3, 4)]) for k in range(LINKS)])
    top = pos + rotate(quat, np.tile([0, 0, LINK / 2], (LINKS, 1)))
    bottom = pos + rotate(quat, np.tile([0, 0, -LINK / 2], (LINKS, 1)))
    drift = np.linalg.norm(top - np.vstack([[0, 0, 0], bottom[:-1]]), axis=1)
    assert np.max(drift) < 1e-3
    for k in range(LINKS):
        force = s.get(*[f"ball{k}.reactionForce[{i}]" for i in (1, 2, 3)])
        weight_below = (LINKS - k) * LINK_MASS * G
        assert force[2] == pytest.approx(weight_below, rel=1e-6), k
        assert np.hypot(force[0], force[1]) < 1e-6 * weight_below, k


def test_a_joints_load_is_its_own_reaction_not_the_bodys_contact_force(slave):
    """A swinging box on a hinge, 1 m above a floor, touches nothing: its contact force
    stays zero (to rounding) while the hinge carries it."""
    swinging = hinged_box()
    swinging["bodies"][0]["collision"] = True
    swinging["surfaces"] = [{"name": "floor", "min": [-5, -5, -3], "max": [5, 5, -2]}]
    s = slave(swinging, start={"leaf.angularVelocity[2]": 2.0})
    t, y = run(s, ["leaf.contactForce[1]", "leaf.contactForce[3]", "leaf.contactTorque[2]",
                   "hinge.reactionForce[3]"], 1.0, 0.01)
    assert np.max(np.abs(y[:, :3])) < 1e-9 * 2.0 * G
    assert np.min(y[1:, 3]) > 0.5 * 2.0 * G


# ---- a motor, a limit and a spring ------------------------------------------------------

def wheel(**motor):
    """A disc (cylinder about body z) of I = m r^2 / 2 = 0.04 kg m^2 on a hinge about z."""
    return scene("MotorWheel", [{"name": "wheel", "shape": {"type": "cylinder", "radius": 0.2, "length": 0.05},
                                 "mass": 2.0, "position": [0, 0, 0], "collision": False}],
                 [{"name": "axle", "type": "revolute", "bodies": ["world", "wheel"], "anchor": [0, 0, 0],
                   "axis": [0, 0, 1], "motor": motor}])


def test_a_hinge_motor_spins_a_wheel_up_at_its_torque_over_inertia_and_holds_the_speed(slave):
    inertia, torque, target = 0.04, 0.2, 10.0  # kg m^2, N m, rad/s: t* = target I / torque = 2 s
    s = slave(wheel(speed=target, maxTorque=torque))
    h = 0.01
    t, y = run(s, ["axle.speed", "wheel.angularVelocity[3]", "axle.reactionTorque[3]"], 3.0, h)
    spinning = t < 2.0 - h
    np.testing.assert_allclose(y[spinning, 0], torque / inertia * t[spinning], rtol=0, atol=1e-6 * target)
    np.testing.assert_allclose(y[spinning, 1], y[spinning, 0], rtol=0, atol=1e-12 * target)
    np.testing.assert_allclose(y[spinning & (t > 0), 2], torque, rtol=1e-6)  # the load cell reads the motor
    holding = t > 2.0 + h
    np.testing.assert_allclose(y[holding, 0], target, rtol=1e-6)
    np.testing.assert_allclose(y[holding, 2], 0.0, atol=1e-6 * torque)


def test_the_motors_speed_and_torque_are_an_input_and_a_tunable_parameter(slave):
    s = slave(wheel(speed=10.0, maxTorque=0.2), start={"axle.maxMotorTorque": 0.4, "axle.motorSpeed": -4.0})
    run(s, [], 0.1, 0.01)  # 0.4 / 0.04 = 10 rad/s^2: -1 rad/s after 0.1 s
    assert s.get("axle.speed") == pytest.approx(-1.0, rel=1e-6)
    s.set_values({"axle.motorSpeed": 2.0})
    run(s, [], 0.5, 0.01)  # from -1 up to 2 in 0.3 s, then held
    assert s.get("axle.speed") == pytest.approx(2.0, rel=1e-6)


def test_a_motor_speed_with_a_derivative_ramps_over_the_step(slave):
    """fmi2SetRealInputDerivatives on the motor's speed: over one communication step of
    0.5 s the target ramps from 0 at 10 rad/s^2 (each internal step of 1 ms holds its
    midpoint's value), and a strong motor follows it to 5 rad/s; the next step, given no
    derivative, holds the input the master set."""
    s = slave(wheel(speed=0.0, maxTorque=100.0))
    s.slave.setRealInputDerivatives(s.vr(["axle.motorSpeed"]), [1], [10.0])
    s.step(0.5, 0.0)
    assert s.get("axle.speed") == pytest.approx(10.0 * (0.5 - 0.0005), abs=1e-6)
    assert s.get("axle.motorSpeed") == 0.0
    s.step(0.1)
    assert s.get("axle.speed") == pytest.approx(0.0, abs=1e-6)


def slider(**joint):
    """A box on a vertical slider from the world, at rest at its anchor."""
    return scene("Slider", [box("carriage", [0.1, 0.1, 0.1], [0, 0, 0], mass=3.0)],
                 [{"name": "rail", "type": "prismatic", "bodies": ["world", "carriage"], "anchor": [0, 0, 0],
                   "axis": [0, 0, 1], **joint}])


def test_a_slider_stops_its_body_at_the_limit(slave):
    """Falling 0.5 m along the rail onto its lower limit: it stops there without a
    bounce (restitution 0) and the rail carries the weight."""
    s = slave(slider(limits=[-0.5, 0.5]))
    t, y = run(s, ["rail.position", "carriage.position[3]", "rail.speed", "rail.reactionForce[3]"], 1.5, 0.001)
    hit = math.sqrt(2 * 0.5 / G)  # s: free fall until then
    falling = t < hit - 0.01
    # free fall, to the first-order error of the sub-steps that move jointed bodies
    np.testing.assert_allclose(y[falling, 0], -0.5 * G * t[falling] ** 2, atol=0.5 * G * hit * 0.001)
    after = t > hit + 0.01
    assert np.max(np.abs(y[after, 0] + 0.5)) < 1e-3
    assert np.max(np.abs(y[after, 1] + 0.5)) < 1e-3
    assert np.max(y[after, 0]) < -0.5 + 1e-3  # no bounce
    assert y[-1, 3] == pytest.approx(3.0 * G, rel=1e-6)


def test_a_slider_spring_oscillates_at_its_natural_period(slave):
    """A spring of k = 100 N/m toward 0.1 m across a horizontal rail: the carriage (3 kg)
    swings between 0 and 0.2 m with T = 2 pi sqrt(m / k)."""
    s = scene("SpringSlider", [box("carriage", [0.1, 0.1, 0.1], [0, 0, 0], mass=3.0)],
              [{"name": "rail", "type": "prismatic", "bodies": ["world", "carriage"], "anchor": [0, 0, 0],
                "axis": [1, 0, 0], "spring": {"stiffness": 100.0, "target": 0.1}}])
    t, y = run(slave(s), ["rail.position"], 10.0, 0.001)
    period = 2 * math.pi * math.sqrt(3.0 / 100.0)
    assert np.mean(np.diff(crossings(t, y[:, 0] - 0.1))) == pytest.approx(period, rel=1e-3)
    # the implicit spring of the solver's rows loses a little energy, never gains any
    peaks = [np.max(y[(t >= k * period) & (t < (k + 1) * period), 0]) for k in range(int(t[-1] / period))]
    assert np.all(np.diff(peaks) <= 1e-12) and peaks[0] <= 0.2 + 1e-6
    assert peaks[-1] > 0.19


def test_a_spring_on_a_hinge_is_a_position_servo_on_its_target_input(slave):
    """A torsion spring of 50 N m/rad and 5 N m s/rad on the wheel's axle, its target
    set to 1 rad between steps: the wheel turns there and holds it, the axle's torque
    back to zero."""
    s = slave(scene("Servo", wheel(speed=0.0, maxTorque=1.0)["bodies"],
                    [{"name": "axle", "type": "revolute", "bodies": ["world", "wheel"], "anchor": [0, 0, 0],
                      "axis": [0, 0, 1], "spring": {"stiffness": 50.0, "damping": 5.0}}]))
    s.set_values({"axle.targetPosition": 1.0})
    t, y = run(s, ["axle.position", "axle.reactionTorque[3]"], 3.0, 0.01)
    assert np.max(y[:, 0]) < 1.0 + 1e-3  # over-damped (zeta 1.77): no overshoot
    assert y[-1, 0] == pytest.approx(1.0, abs=1e-6)
    assert abs(y[-1, 1]) < 1e-6


def test_a_weld_holds_a_cantilever_and_reads_its_moment(slave):
    """A beam of 1 m and 2 kg welded to the world at one end: it stays, and the weld
    carries its weight m g and the moment m g L/2 about its anchor."""
    m, length = 2.0, 1.0
    s = slave(scene("Cantilever", [box("beam", [length, 0.1, 0.1], [length / 2, 0, 0], mass=m)],
                    [{"name": "weld", "type": "fixed", "bodies": ["world", "beam"], "anchor": [0, 0, 0]}]))
    t, y = run(s, ["beam.position[1]", "beam.position[3]", "weld.reactionForce[3]", "weld.reactionTorque[2]"],
               2.0, 0.01)
    assert np.max(np.abs(y[:, 0] - length / 2)) < 1e-3
    assert np.max(np.abs(y[:, 1])) < 1e-3
    assert y[-1, 2] == pytest.approx(m * G, rel=1e-6)
    # gravity's moment about the anchor is (L/2) x (-m g z) = +m g L/2 about y; the weld's undoes it
    assert y[-1, 3] == pytest.approx(-m * G * length / 2, rel=1e-6)


# ---- collision between jointed bodies: off by default, on by a flag -------------------

def roped_pair(**flag):
    """Two balls of radius 0.1 overlapping (centres 0.1 apart) on a rope of 0.3 m, no gravity."""
    balls = [{**sphere(n, [x, 0, 0], radius=0.1), "collision": True} for n, x in (("left", 0.0), ("right", 0.1))]
    return scene("RopedPair", balls, [{"name": "rope", "type": "distance", "bodies": ["left", "right"],
                                      "anchors": [[0, 0, 0], [0, 0, 0]], "length": 0.3, "rope": True, **flag}],
                 gravity=[0, 0, 0])


@pytest.mark.parametrize("collide", [False, True])
def test_jointed_bodies_collide_only_when_the_joint_says_so(slave, collide):
    s = slave(roped_pair(collide=collide))
    t, y = run(s, ["left.position[1]", "right.position[1]", "rope.position"], 1.0, 0.01)
    apart = y[:, 1] - y[:, 0]
    if collide:
        assert np.min(apart[t > 0.5]) > 0.2 - 1e-3  # pushed out of each other...
        assert np.max(y[:, 2]) < 0.3 + 1e-3  # ...and held by the rope
    else:
        np.testing.assert_allclose(apart, 0.1, atol=1e-12)  # left overlapping


# ---- joints in the FMU state -------------------------------------------------------------

def mechanism():
    """A hinged leaf with a limit and a spring, a motor wheel, and a ball on a rope that
    swings into the leaf (contacts and joints in one state)."""
    leaf = {**box("leaf", [0.1, 0.1, 1.0], [0, 0, -0.5]), "collision": True}
    ball = {**sphere("ball", [0.6, 0, -0.6], radius=0.1), "collision": True}
    disc = {"name": "wheel", "shape": {"type": "cylinder", "radius": 0.2, "length": 0.05}, "mass": 2.0,
            "position": [3, 0, 0], "collision": False}
    return scene("Mechanism", [leaf, ball, disc], [
        {"name": "hinge", "type": "revolute", "bodies": ["world", "leaf"], "anchor": [0, 0, 0], "axis": [0, 1, 0],
         "limits": [-0.3, 0.3], "spring": {"stiffness": 5.0, "damping": 0.1}},
        {"name": "rope", "type": "distance", "bodies": ["world", "ball"], "anchors": [[1.2, 0, -0.6], [0, 0, 0]],
         "rope": True},
        {"name": "axle", "type": "revolute", "bodies": ["world", "wheel"], "anchor": [3, 0, 0], "axis": [0, 0, 1],
         "motor": {"speed": 3.0, "maxTorque": 0.5}}])


def drive_mechanism(s, t0, t1, h=0.01):
    """Steps from t0 to t1, turning the motor's input on the way; every Real at the end."""
    for k in range(round((t1 - t0) / h)):
        s.set_values({"axle.motorSpeed": 3.0 - 0.5 * (k % 7)})
        s.step(h, t0 + k * h)
    return s.all_reals()


def test_joints_come_back_bitwise_from_a_state_its_bytes_and_a_reset(slave):
    s = slave(mechanism())
    first = drive_mechanism(s, 0.0, 1.0)
    state = s.slave.getFMUstate()
    blob = bytes(s.slave.serializeFMUstate(state))
    straight = drive_mechanism(s, 1.0, 2.0)
    assert any(v != 0.0 for v in s.get("rope.reactionForce[1]", "hinge.reactionTorque[2]"))
    s.set_values({"axle.maxMotorTorque": 9.0, "hinge.stiffness": 1.0, "hinge.upper": 0.1})
    s.slave.setFMUstate(state)  # the tunables come back too
    assert s.get("axle.maxMotorTorque", "hinge.stiffness", "hinge.upper") == [0.5, 5.0, 0.3]
    assert drive_mechanism(s, 1.0, 2.0) == straight
    s.slave.setFMUstate(s.slave.deSerializeFMUstate(blob))
    assert drive_mechanism(s, 1.0, 2.0) == straight
    s.slave.reset()
    s.initialize()
    assert drive_mechanism(s, 0.0, 1.0) == first


@pytest.mark.parametrize("restitution", [0.0, 0.5, 1.0])
def test_a_stop_gives_back_its_restitution_of_the_approach_speed(slave, restitution):
    """A carriage at 1 m/s along a level rail strikes its upper limit, 0.3 m ahead: it
    leaves at -e m/s (e = 0 by default), as a body leaves a wall."""
    rail = {"limits": [-0.5, 0.3]} | ({"restitution": restitution} if restitution else {})
    s = scene("BouncingSlider", [box("carriage", [0.1, 0.1, 0.1], [0, 0, 0], mass=3.0, velocity=[1, 0, 0])],
              [{"name": "rail", "type": "prismatic", "bodies": ["world", "carriage"], "anchor": [0, 0, 0],
                "axis": [1, 0, 0], **rail}])
    t, y = run(slave(s), ["rail.position", "rail.speed"], 0.6, 0.001)
    before, after = t < 0.3 - 0.002, t > 0.3 + 0.002
    np.testing.assert_allclose(y[before, 1], 1.0, rtol=1e-12)
    np.testing.assert_allclose(y[after, 1], -restitution, atol=1e-9)
    assert np.max(y[:, 0]) < 0.3 + 1e-3


def test_an_elastic_rope_pulls_only_while_stretched(slave):
    """A 1 kg ball on a rope of 1 m and 100 N/m, dropped from 0.1 m below the anchor:
    free fall while the rope is slack, then the stretch x that energy gives,
    m g (0.9 + x) = k x^2 / 2; the rope never pushes."""
    m, k = 1.0, 100.0
    s = scene("Bungee", [sphere("ball", [0, 0, -0.1], mass=m)],
              [{"name": "cord", "type": "distance", "bodies": ["world", "ball"], "anchors": [[0, 0, 0], [0, 0, 0]],
                "length": 1.0, "rope": True, "spring": {"stiffness": k}}])
    t, y = run(slave(s), ["ball.position[3]", "cord.reactionForce[3]"], 1.5, 0.001)
    slack = t < math.sqrt(2 * 0.9 / G) - 0.002
    fall = -0.1 - 0.5 * G * t[slack] ** 2
    assert np.all(np.abs(y[slack, 0] - fall) <= 0.5 * G * t[slack] * 0.001 + 1e-12)  # the sub-steps' error
    assert np.max(np.abs(y[slack, 1])) < 1e-12
    stretch = (m * G + math.sqrt((m * G) ** 2 + 2 * k * m * G * 0.9)) / k
    assert -np.min(y[:, 0]) - 1.0 == pytest.approx(stretch, rel=1e-2)
    assert np.min(y[:, 1]) > -1e-9


@pytest.mark.sweep("ratio")
@pytest.mark.parametrize("ratio,stretch", [(100, 1e-3), (1000, 1e-2)])
def test_a_light_link_holds_a_load_a_thousand_times_heavier(slave, ratio, stretch):
    """A double pendulum of a 1 kg link and a load `ratio` times heavier, swinging for
    10 s: the soft rows stay stable, and the rods give by less than `stretch` (the
    softer the heavier the load they hold, as a soft contact under a heavy body)."""
    centres = [[0, 0, 0], [0, 0, 0]]
    s = slave(scene("HeavyLoad", [sphere("link", [0, 0, -0.5]), sphere("load", [0.3, 0, -1.0], mass=float(ratio))],
                    [{"name": "rod1", "type": "distance", "bodies": ["world", "link"], "anchors": centres},
                     {"name": "rod2", "type": "distance", "bodies": ["link", "load"], "anchors": centres}]))
    t, y = run(s, ["rod1.position", "rod2.position", "load.velocity[1]"], 10.0, 0.005)
    assert np.all(np.isfinite(y))
    assert np.max(np.abs(y[:, 0] - 0.5)) < stretch
    assert np.max(np.abs(y[:, 1] - math.hypot(0.3, 0.5))) < stretch


def test_an_inelastic_strike_on_a_hinged_rod_gives_the_articulated_closed_form(slave):
    """A 1 kg ball at 1 m/s strikes a 1 kg rod of 1 m, hinged at one end, 0.8 m from
    the hinge, without bounce (no gravity, no friction): the ball and the rod's point
    there leave together at m v / (m + I_h / r^2), the rod's inertia about the hinge
    seen at the strike (the impact's impulse and the hinge's rows, solved together)."""
    free = {"restitution": 0.0, "staticFriction": 0.0, "kineticFriction": 0.0, "collision": True}
    rod = {**box("rod", [1.0, 0.05, 0.05], [0.5, 0, 0]), **free}
    ball = {**sphere("ball", [0.8, 0.2, 0], velocity=[0, -1, 0]), **free}
    s = slave(scene("StruckRod", [rod, ball], [{"name": "hinge", "type": "revolute", "bodies": ["world", "rod"],
                                                "anchor": [0, 0, 0], "axis": [0, 0, 1]}], gravity=[0, 0, 0]))
    run(s, [], 0.4, 0.01)
    r, m = 0.8, 1.0
    inertia = m * (1.0 + 0.05 ** 2) / 12 + m * 0.5 ** 2
    v = m * 1.0 / (m + inertia / r ** 2)
    assert -s.get("ball.velocity[2]") == pytest.approx(v, rel=2e-3)
    assert -s.get("hinge.speed") * r == pytest.approx(v, rel=2e-3)
