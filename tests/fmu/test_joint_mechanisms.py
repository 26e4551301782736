"""Mechanisms of several joints (issue 41) against independent references: a double
pendulum on two rods (scipy's DOP853 on its Lagrangian equations), a four-bar linkage
driven by a motor at constant crank speed (the loop-closure solution by circle
intersection) and Newton's cradle hung on rods (the free-ball cradle's criterion).

A body that a joint holds is moved by the constraint solver's sub-steps (symplectic
Euler of h/4), not by the scene's method: the angles converge at order 1 in the step."""
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.special import ellipk

G = 9.81


def trace(s, names, stop, h):
    """The times and the outputs `names` at every communication point of steps h up to `stop`."""
    n = int(round(stop / h))
    out = np.empty((n + 1, len(names)))
    out[0] = s.get(*names)
    for k in range(n):
        s.step(h, k * h)
        out[k + 1] = s.get(*names)
    return np.arange(n + 1) * h, out


def wrapped(angle):
    """An angle (or a difference of angles) into (-pi, pi]."""
    return np.angle(np.exp(1j * np.asarray(angle)))


# ---- the double pendulum: two point-like spheres on two massless rods --------------

L1, L2, M1, M2 = 1.0, 1.0, 1.0, 1.0  # m, kg
# Both rods horizontal, at rest: over 20 s the second rod flips again and again (a
# perturbation of the start grows 1e6-fold), over the first 2 s only 1.7-fold, so that
# the comparison there measures the engine, not the chaos.
START = (math.pi / 2, math.pi / 2)  # rad, each rod from the downward vertical
STEPS = (4e-3, 2e-3, 1e-3)  # s, solver steps; the 1e-3 rad is asked at 1e-3
COMM = 0.01  # s, communication step


def double_pendulum(step):
    def ball(name, position):
        return {"name": name, "shape": {"type": "sphere", "radius": 0.05}, "mass": 1.0, "position": position,
                "collision": False}
    x1 = [L1 * math.sin(START[0]), 0.0, -L1 * math.cos(START[0])]
    x2 = [x1[0] + L2 * math.sin(START[1]), 0.0, x1[2] - L2 * math.cos(START[1])]
    centres = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]  # each rod's ends: the world's origin, the balls' centres
    return {"name": "DoublePendulum", "solver": {"method": "rk4", "step": step},
            "bodies": [ball("b1", x1), ball("b2", x2)],
            "joints": [{"name": "rod1", "type": "distance", "bodies": ["world", "b1"], "anchors": centres},
                       {"name": "rod2", "type": "distance", "bodies": ["b1", "b2"], "anchors": centres}]}


def lagrangian(t, y):
    """The double pendulum of point masses: M(theta) theta'' = f(theta, theta')."""
    a, b, wa, wb = y
    c, s = math.cos(a - b), math.sin(a - b)
    mass = np.array([[(M1 + M2) * L1 * L1, M2 * L1 * L2 * c], [M2 * L1 * L2 * c, M2 * L2 * L2]])
    f = np.array([-M2 * L1 * L2 * s * wb * wb - (M1 + M2) * G * L1 * math.sin(a),
                  M2 * L1 * L2 * s * wa * wa - M2 * G * L2 * math.sin(b)])
    return [wa, wb, *np.linalg.solve(mass, f)]


def test_a_double_pendulum_follows_its_lagrangian_equations_and_keeps_its_energy(slave):
    """Over the first 2 s both angles stay within 1e-3 rad of the reference at the step
    1e-3 s, and the error falls with the step; over 20 s the energy stays within 0.5 %
    of what the pendulum holds above its rest. The rods pull at the balls' centres: the
    balls never spin, so their rotational inertia (2/5 m r^2) plays no part and the
    point masses' equations hold."""
    t_ref = np.arange(0.0, 2.0 + COMM / 2, COMM)
    ref = solve_ivp(lagrangian, (0.0, 2.0), [*START, 0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-12,
                    t_eval=t_ref).y[:2].T
    above_rest = M1 * G * L1 * (1 - math.cos(START[0])) + M2 * G * (L1 * (1 - math.cos(START[0])) +
                                                                     L2 * (1 - math.cos(START[1])))
    names = ["b1.position[1]", "b1.position[3]", "b2.position[1]", "b2.position[3]",
             "b1.velocity[1]", "b1.velocity[3]", "b2.velocity[1]", "b2.velocity[3]",
             "b1.angularVelocity[1]", "b1.angularVelocity[2]", "b1.angularVelocity[3]",
             "b2.angularVelocity[1]", "b2.angularVelocity[2]", "b2.angularVelocity[3]"]
    errors, drifts = {}, {}
    for step in STEPS:
        t, y = trace(slave(double_pendulum(step)), names, 20.0, COMM)
        x1, z1, x2, z2 = y[:, 0], y[:, 1], y[:, 2], y[:, 3]
        angles = np.column_stack([np.arctan2(x1, -z1), np.arctan2(x2 - x1, -(z2 - z1))])
        errors[step] = np.max(np.abs(wrapped(angles[:len(t_ref)] - ref)))
        energy = (0.5 * M1 * (y[:, 4] ** 2 + y[:, 5] ** 2) + 0.5 * M2 * (y[:, 6] ** 2 + y[:, 7] ** 2) +
                  G * (M1 * z1 + M2 * z2))
        drifts[step] = np.max(np.abs(energy - energy[0])) / above_rest
        assert np.max(np.abs(y[:, 8:])) < 1e-12, step  # no spin: the spheres' inertia is out of it
    print("\ndouble pendulum, from both rods horizontal: max angle error over 2 s, energy drift over 20 s")
    for step in STEPS:
        print(f"  h = {step:.0e} s: {errors[step]:.2e} rad, {drifts[step]:.2e}")
    assert errors[1e-3] < 1e-3
    assert errors[4e-3] > errors[2e-3] > errors[1e-3]
    for step in STEPS:
        assert drifts[step] < 5e-3, step


# ---- the four-bar linkage: a crank driven by a motor, a coupler, a rocker ----------

# Link lengths (m): crank, coupler, rocker, ground. Grashof (0.1 + 0.4 <= 0.35 + 0.3)
# with the shortest link the crank: a crank-rocker, whose crank turns through whole
# turns while the rocker swings between -7 and +33 deg of its start, never in line
# with the coupler (no singularity).
CRANK, COUPLER, ROCKER, GROUND = 0.1, 0.35, 0.3, 0.4
OMEGA = 2 * math.pi  # rad/s, the motor's speed: a turn a second
AXIS = np.array([0.0, -1.0, 0.0])  # every hinge's: the linkage turns in the vertical x-z plane, counterclockwise


def loop_closure(crank):
    """The joints' points (plane coordinates (x, z), the crank's pivot at the origin and the
    rocker's at (GROUND, 0)) and the coupler's and rocker's angles for a crank angle: the
    coupler's far end where the circle about the crank's end meets the one about the
    rocker's pivot, on the branch above the line from the crank's end to the pivot."""
    a = np.array([CRANK * math.cos(crank), CRANK * math.sin(crank)])
    d = np.array([GROUND, 0.0]) - a
    e = np.linalg.norm(d)
    u = d / e
    along = (COUPLER ** 2 - ROCKER ** 2 + e * e) / (2 * e)
    b = a + along * u + math.sqrt(COUPLER ** 2 - along ** 2) * np.array([-u[1], u[0]])
    return a, b, math.atan2(b[1] - a[1], b[0] - a[0]), math.atan2(b[1], b[0] - GROUND)


def loop_rates(crank, coupler, rocker, omega):
    """The coupler's and rocker's angular speeds, from the loop closure differentiated:
    CRANK w2 e^(i th2) + COUPLER w3 e^(i th3) = ROCKER w4 e^(i th4) (times i)."""
    m = np.array([[-COUPLER * math.sin(coupler), ROCKER * math.sin(rocker)],
                  [COUPLER * math.cos(coupler), -ROCKER * math.cos(rocker)]])
    return np.linalg.solve(m, CRANK * omega * np.array([math.sin(crank), -math.cos(crank)]))


def four_bar():
    """The linkage at crank angle 0, already moving at the motor's speed (the velocities
    of the loop closure), so that the crank turns at constant speed from the start."""
    a, b, coupler, rocker = loop_closure(0.0)
    w3, w4 = loop_rates(0.0, coupler, rocker, OMEGA)
    pivot = np.array([GROUND, 0.0])

    def world(p):
        return [float(p[0]), 0.0, float(p[1])]

    def moving(w, r):  # the velocity of a point at r from a centre of turn at w
        return np.array([-w * r[1], w * r[0]])

    def link(name, p, q, length, velocity, w):  # a thin box from p to q, its body x along it
        phi = math.atan2(q[1] - p[1], q[0] - p[0])
        return {"name": name, "shape": {"type": "box", "size": [length, 0.02, 0.02]}, "mass": 0.2,
                "position": world((p + q) / 2), "orientation": [math.cos(phi / 2), *(math.sin(phi / 2) * AXIS)],
                "velocity": world(velocity), "angularVelocity": list(w * AXIS), "collision": False}

    def hinge(name, bodies, anchors, **more):
        return {"name": name, "type": "revolute", "bodies": bodies, "anchors": anchors, "axis": list(AXIS), **more}
    return {"name": "FourBar", "solver": {"method": "rk4", "step": 1e-3},
            "bodies": [link("crank", np.zeros(2), a, CRANK, moving(OMEGA, a / 2), OMEGA),
                       link("coupler", a, b, COUPLER, moving(OMEGA, a) + moving(w3, (b - a) / 2), w3),
                       link("rocker", pivot, b, ROCKER, moving(w4, (b - pivot) / 2), w4)],
            "joints": [hinge("drive", ["world", "crank"], [[0, 0, 0], [-CRANK / 2, 0, 0]],
                             motor={"speed": OMEGA, "maxTorque": 100.0}),
                       hinge("elbow", ["crank", "coupler"], [[CRANK / 2, 0, 0], [-COUPLER / 2, 0, 0]]),
                       hinge("knee", ["coupler", "rocker"], [[COUPLER / 2, 0, 0], [ROCKER / 2, 0, 0]]),
                       hinge("pivot", ["world", "rocker"], [world(pivot), [-ROCKER / 2, 0, 0]])]}


def test_a_four_bar_linkage_follows_its_loop_closure_over_a_turn(slave):
    """Under gravity, at the step 1e-3 s, the motor turns the crank at OMEGA; over one
    turn the rocker's hinge angle is the loop closure's for the crank's angle (both
    counted from the start) within 1e-4 rad."""
    period = 2 * math.pi / OMEGA
    t, y = trace(slave(four_bar()), ["drive.position", "pivot.position"], period, period / 200)
    crank, rocker = y[:, 0], y[:, 1]
    assert crank[-1] == pytest.approx(2 * math.pi, abs=1e-3)  # a turn
    assert np.max(np.abs(crank - OMEGA * t)) < 1e-3  # at the motor's speed
    start = loop_closure(0.0)[3]
    expected = np.array([loop_closure(c)[3] - start for c in crank])
    assert np.ptp(expected) > math.radians(39)  # the rocker's whole swing was seen
    assert np.max(np.abs(rocker - expected)) < 1e-4


# ---- Newton's cradle of five balls, each on a rod ----------------------------------

R, ROD = 0.05, 1.0  # m
PULL = math.radians(30)  # the first ball's rod from the vertical, at the release


def hung_cradle():
    """Five balls touching in a row along x, each on a rod from a point straight above
    its rest; the first pulled aside by PULL in the x-z plane. Restitution 1, no friction."""
    bodies, joints = [], []
    for k in range(5):
        top = [2 * R * k, 0.0, 0.0]
        position = [top[0] - ROD * math.sin(PULL), 0.0, -ROD * math.cos(PULL)] if k == 0 else [top[0], 0.0, -ROD]
        bodies.append({"name": f"b{k}", "shape": {"type": "sphere", "radius": R}, "mass": 1.0, "position": position,
                       "restitution": 1.0, "staticFriction": 0.0, "kineticFriction": 0.0})
        joints.append({"name": f"rod{k}", "type": "distance", "bodies": ["world", f"b{k}"],
                       "anchors": [top, [0.0, 0.0, 0.0]]})
    return {"name": "HungCradle", "solver": {"method": "rk4", "step": 1e-3}, "bodies": bodies, "joints": joints}


def test_newtons_cradle_on_rods_passes_the_momentum_down_the_row(slave):
    """The first ball reaches the row after a quarter of the pendulum's period (the
    complete elliptic integral) at v0 = sqrt(2 g L (1 - cos PULL)); right after the
    impact the last ball leaves at v0 and the others stay at rest, with the free-ball
    cradle's criterion (test_collisions.test_newtons_cradle): v0 within 1 %, the others
    below 1 % of v0. The impacts are answered by the contact solver pass after pass
    down the row; the rods, vertical at the impact, take no part in them. The last
    ball then swings up to the height the first fell from (1 %)."""
    dt = 1e-3
    quarter = math.sqrt(ROD / G) * ellipk(math.sin(PULL / 2) ** 2)
    v0 = math.sqrt(2 * G * ROD * (1 - math.cos(PULL)))
    names = [f"b{k}.velocity[1]" for k in range(5)] + ["b4.position[3]"]
    # up to past the last ball's highest point, before it comes back
    t, y = trace(slave(hung_cradle()), names, 2 * quarter + 0.1, dt)
    hit = int(np.argmax(y[:, 4] > 0.01 * v0))  # the first point after the impact
    assert hit > 0 and abs(t[hit] - quarter) < 2 * dt
    assert y[hit - 1, 0] == pytest.approx(v0, rel=0.01)  # the first ball, just before
    assert y[hit, 4] == pytest.approx(v0, rel=0.01)
    for k in range(4):  # at rest from the impact on
        assert np.max(np.abs(y[hit:, k])) < 0.01 * v0, k
    assert np.max(y[:, 5]) + ROD == pytest.approx(ROD * (1 - math.cos(PULL)), rel=0.01)
