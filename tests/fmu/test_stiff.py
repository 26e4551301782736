"""Stiff and extreme cases (issue 7): the L-stable method on stiff drag, automatic
sub-stepping of explicit methods outside their stability region, and refusal with a
message naming the cause and a step that would work."""
import math
import re

import numpy as np
import pytest
from fmpy import simulate_fmu
from fmpy.fmi2 import fmi2LastSuccessfulTime, fmi2Terminated

import scenes
from harness import Slave, status_of

R, M = 0.1, 1.0


def stiff_drag_scene(b_over_m, method, step):
    """A sphere in a viscous custom medium (density 0: linear drag only) with
    b/m = b_over_m: Stokes b = 6 pi mu r."""
    mu = b_over_m * M / (6 * math.pi * R)
    s = scenes.scene(f"StiffDrag_{method}", [scenes.body("ball", shape={"type": "sphere", "radius": R},
                                                         mass=M, velocity=[5.0, 0, 0])],
                     method=method, step=step)
    s["media"] = [{"name": "syrup", "type": "custom", "density": 0.0, "viscosity": mu,
                   "min": [-1e3, -1e3, -1e3], "max": [1e3, 1e3, 1e3]}]
    return s


def test_rosenbrock_is_stable_on_stiff_drag_and_reaches_terminal_velocity(fmu_of):
    """b/m = 1e3 at h = 1e-2 (h b/m = 10; explicit RK4 needs h < 2.8e-3): the
    L-stable method takes the step as it is and lands on v_T = g m / b within 1e-6."""
    r = simulate_fmu(str(fmu_of(stiff_drag_scene(1e3, "rosenbrock", 1e-2))), stop_time=1.0,
                     output_interval=0.1, output=["ball.velocity[1]", "ball.velocity[3]", "solver.steps"])
    vT = -9.81 / 1e3
    assert r["ball.velocity[3]"][-1] == pytest.approx(vT, rel=1e-6)
    assert abs(r["ball.velocity[1]"][-1]) < 1e-6 * 5.0
    assert list(r["solver.steps"][1:]) == [10] * 10  # no sub-stepping needed


def test_explicit_rk4_sub_steps_stiff_drag_and_says_so(fmu_of):
    """The same case with rk4: sub-stepped automatically so that h times the fastest
    drag rate is at most 0.9 * 2.785 (RK4's real stability limit with a margin),
    reported in solver.steps and in the log, and the answer is right. The fastest rate
    is the sphere's angular drag: 8 pi mu r^3 / (2/5 m r^2) = 10/3 of the linear b/m."""
    s = Slave(fmu_of(stiff_drag_scene(1e3, "rk4", 1e-2)))
    try:
        s.initialize()
        s.step(0.1)
        steps = s.slave.getInteger(s.vr(["solver.steps"]))[0]
        assert steps == 10 * math.ceil(1e-2 * 1e3 * 10 / 3 / (0.9 * 2.785))
        assert any("stability region (drag)" in m for _, _, m in s.log.messages), s.log.text()
        for _ in range(9):
            s.step(0.1)
        assert s.get("ball.velocity[3]") == pytest.approx(-9.81e-3, rel=1e-6)
    finally:
        s.close()


@pytest.mark.parametrize("method", ["euler", "rk4", "symplecticEuler"])
def test_fast_spin_is_sub_stepped_not_lost(fmu_of, method):
    """h |omega| = 6: explicit fixed-step methods sub-step (rk4 to h |omega| <= 0.1,
    where it keeps a free rotation's energy; symplecticEuler, which turns q as splitting
    does, to 0.15; explicit Euler to 0.05); the spin stays what it was (torque-free,
    symmetric body)."""
    w = 6.0 / 1e-2
    s = scenes.scene(f"FastSpin_{method}", [scenes.body("ball", shape={"type": "sphere", "radius": R},
                                                        angularVelocity=[0, 0, w])],
                     gravity=(0, 0, 0), method=method, step=1e-2)
    r = simulate_fmu(str(fmu_of(s)), stop_time=0.1, output_interval=0.1,
                     output=["ball.angularVelocity[3]", "ball.orientation[1]", "ball.orientation[4]", "solver.steps"])
    assert r["solver.steps"][-1] == 10 * {"rk4": 60, "symplecticEuler": 40, "euler": 120}[method]
    assert r["ball.angularVelocity[3]"][-1] == pytest.approx(w, rel=1e-12)
    angle = 2 * math.atan2(r["ball.orientation[4]"][-1], r["ball.orientation[1]"][-1])
    expected = math.remainder(w * 0.1, 2 * math.pi)
    q_norm = math.hypot(r["ball.orientation[1]"][-1], r["ball.orientation[4]"][-1])
    assert abs(q_norm - 1) < 1e-12
    # accuracy per sub-step: symplectic Euler turns a symmetric body exactly; RK4
    # at h |omega| = 0.1 loses ~1e-7 rad per sub-step; Euler turns 2 atan(0.025) rad
    # instead of 0.05 per sub-step: stable, but not accurate (no claim)
    tolerance = {"symplecticEuler": 1e-9, "rk4": 1e-4}.get(method)
    if tolerance:
        assert abs(math.remainder(angle - expected, 2 * math.pi)) < tolerance


def test_hopeless_step_is_refused_with_cause_and_a_step_that_works(fmu_of):
    """A spin that would need more than 1e6 sub-steps in one internal step: fmi2Discard
    naming the cause and a working step; fmi2Terminated and fmi2LastSuccessfulTime."""
    s = scenes.scene("Hopeless", [scenes.body("ball", shape={"type": "sphere", "radius": R},
                                              angularVelocity=[0, 0, 1e8])],
                     gravity=(0, 0, 0), method="rk4", step=1.0)
    slave = Slave(fmu_of(s))
    try:
        slave.initialize()
        assert status_of(lambda: slave.slave.doStep(0.0, 1.0)) == "Discard"
        msg = [m for st, _, m in slave.log.messages if st == "Discard"][-1]
        # rk4: h |omega| <= 0.1 at omega = 1e8 rad/s: a step of 1e-9 s would work
        assert "stability region (spin)" in msg
        assert re.search(r"solver\.step of (1e-09|1\.0+\d*e-09|9\.9+\d*e-10) s", msg), msg
        assert slave.slave.getBooleanStatus(fmi2Terminated) is True
        assert slave.slave.getRealStatus(fmi2LastSuccessfulTime) == 0.0
    finally:
        slave.close()


def tumble_until_refused(fmu, step, stop=10.0, H=0.05):
    """Explicit Euler tumbling near the intermediate axis: the time of the refused step
    (None if it ran to `stop`), the refusal message and the largest relative energy gain
    seen at the communication points, computed here from omega and L."""
    s = Slave(fmu)
    try:
        s.initialize({"solver.step": step})
        W = [f"spinner.angularVelocity[{i}]" for i in (1, 2, 3)]
        L = [f"spinner.angularMomentum[{i}]" for i in (1, 2, 3)]
        E0 = np.dot(s.get(*W), s.get(*L))
        worst = 0.0
        for k in range(round(stop / H)):
            st = status_of(lambda: s.slave.doStep(k * H, H))
            if st != "OK":
                assert st == "Discard"
                assert s.slave.getBooleanStatus(fmi2Terminated) is True
                msg = [m for stat, _, m in s.log.messages if stat == "Discard"][-1]
                return s.slave.getRealStatus(fmi2LastSuccessfulTime), msg, worst
            worst = max(worst, np.dot(s.get(*W), s.get(*L)) / E0 - 1)
        return None, "", worst
    finally:
        s.close()


def test_explicit_euler_energy_gain_is_refused_with_a_step_that_works(fmu_of):
    """Explicit Euler adds energy to a free rotation (Lie-Euler: ~(h |omega|)^2 a step).
    The energy audit refuses the step that takes the gain beyond solver.energyGainLimit
    (default 1e-3): fmi2Discard naming the body, the limit and a smaller step; until then
    every OK output is within the limit. Rerun with that step, the same time passes
    within the limit (the gain is proportional to h)."""
    fmu = fmu_of(scenes.free_spin(method="euler", name="EulerTumble"))
    t_refused, msg, worst = tumble_until_refused(fmu, 1e-3)
    assert t_refused is not None and 0.5 < t_refused < 10.0, (t_refused, worst)
    assert worst <= 1e-3
    assert "body spinner" in msg and "solver.energyGainLimit = 0.001" in msg, msg
    step = float(re.search(r"a solver\.step of ([0-9.e+-]+) s would have kept it", msg).group(1))
    assert 1e-4 < step < 1e-3, msg
    t_again, _, worst_again = tumble_until_refused(fmu, step, stop=math.ceil(t_refused / 0.05) * 0.05)
    assert t_again is None, (t_again, worst_again)
    assert worst_again <= 0.6e-3, worst_again  # about half the limit, as announced


def test_energy_audit_off_lets_euler_run_and_splitting_never_trips_it(fmu_of):
    """solver.energyGainLimit = 0 turns the audit off (Euler then gains > 1e-3 and says
    nothing); splitting keeps the energy and runs 10 s under the default limit."""
    fmu = fmu_of(scenes.free_spin(method="euler", name="EulerTumble"))
    s = Slave(fmu)
    try:
        s.initialize({"solver.energyGainLimit": 0.0})
        for k in range(100):
            assert status_of(lambda: s.slave.doStep(k * 0.05, 0.05)) == "OK"
    finally:
        s.close()
    t, _, worst = tumble_until_refused(fmu_of(scenes.free_spin(method="splitting", name="SplitTumble")), 1e-3)
    assert t is None and abs(worst) < 1e-4, (t, worst)
