"""The example systems (docs/guide/systems.md): every folder of scripts/systems with a
system.ssd runs in libcosim and in fmpy to its outcome (outcome.json), and the two
masters' recordings are equal to the bit; `scripts/system.sh` says so and exits 0, and
exits 1 when the outcome fails. The lift carries its load; in the balance the ball
rolls as the equations of a ball on a tilting beam say. The controllers are valid FMUs
that refuse bad values by name."""
import json
import math
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException
from fmpy.validation import validate_fmu
from systems import __main__ as command
from systems import fmus, masters, outcome, ssd

from rigidfmu.driver import Slave

ROOT = pathlib.Path(__file__).resolve().parents[2]
SYSTEMS = sorted(p.parent for p in (ROOT / "scripts" / "systems").glob("*/system.ssd"))
LIFT = ROOT / "scripts" / "systems" / "lift"
BALANCE = ROOT / "scripts" / "systems" / "balance"
CONTROLLERS = [(LIFT, "pd_controller"), (BALANCE, "tilt_controller")]
# recorded beside the outcome's variables and the connected outputs, for the figures below
FIGURES = {BALANCE: [f"world.{body}.{v}[{i}]" for body, v in (("ball", "velocity"), ("ball", "angularVelocity"),
                                                               ("ball", "contactForce"), ("paddle", "contactForce"))
                     for i in (1, 2, 3)] + ["controller.tilt"]}


def test_the_lift_and_the_balance_are_among_the_systems():
    assert LIFT in SYSTEMS and BALANCE in SYSTEMS


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """Each system's FMUs and SSD, built once for the module."""
    cache = {}

    def get(folder):
        if folder not in cache:
            cache[folder] = fmus.build(folder, tmp_path_factory.mktemp(folder.name))
        return cache[folder]
    return get


@pytest.fixture(scope="module")
def runs(built):
    """{(folder, master): Run}, each system run once in each master."""
    cache = {}

    def get(folder, master):
        if (folder, master) not in cache:
            ssd_path = built(folder)
            names = masters.recorded(ssd.read(ssd_path), outcome.load(folder).variables() + FIGURES.get(folder, []))
            cache[(folder, master)] = masters.run(master, ssd_path, names)
        return cache[(folder, master)]
    return get


@pytest.mark.parametrize("master", masters.MASTERS)
@pytest.mark.parametrize("folder", SYSTEMS, ids=lambda p: p.name)
def test_the_outcome_holds(folder, master, runs):
    run = runs(folder, master)
    results = outcome.evaluate_all(outcome.load(folder), run)
    assert run.t[-1] == pytest.approx(run.system.stop, abs=1e-12) and len(run.t) == run.system.steps
    assert all(r.holds for r in results), "\n".join(r.describe() for r in results)


@pytest.mark.parametrize("folder", SYSTEMS, ids=lambda p: p.name)
def test_libcosim_and_fmpy_record_the_same_values_to_the_bit(folder, runs):
    a, b = runs(folder, "libcosim"), runs(folder, "fmpy")
    assert a.names == b.names and len(a.names) >= 4
    assert masters.difference(a, b) == 0.0


def test_the_lift_settles_within_a_micrometre_and_carries_its_load(runs):
    """The figures behind the lift's bands: the platform within 1e-6 m of 0.5 m from 2 s
    on (the band is 1 mm), the hook's force then the two weights, 12 kg g; the load
    pressing on the platform throughout (its contact force > 0: it never lifts off)."""
    run = runs(LIFT, "libcosim")
    late = run.t >= 2.0
    assert abs(run.col("world.platform.position[3]")[late] - 0.5).max() < 1e-6
    assert run.col("controller.force")[-1] == pytest.approx(12 * 9.81, rel=1e-9)
    assert run.col("world.load.contactForce[3]").min() > 0.0


def test_the_command_prints_the_outcome_and_exits_0(tmp_path):
    env = dict(os.environ, RIGIDFMU_SKIP_SETUP="1")
    done = subprocess.run([str(ROOT / "scripts" / "system.sh"), str(LIFT), "--out", str(tmp_path)],
                          capture_output=True, text=True, env=env, cwd=ROOT)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "lift in libcosim: 10000 steps of 0.001 s to 10 s" in done.stdout
    assert done.stdout.count("  holds: ") == 3 and done.stdout.rstrip().endswith("the outcome holds")
    assert (tmp_path / "libcosim.csv").read_text().startswith("time,controller.force,")


def test_a_failed_outcome_exits_1(tmp_path, capsys):
    folder = tmp_path / "lift"
    shutil.copytree(LIFT, folder)
    wanted = json.loads((folder / "outcome.json").read_text())
    wanted["checks"][0]["band"] = 1e-12  # the platform's last deviations are larger
    (folder / "outcome.json").write_text(json.dumps(wanted))
    assert command.main([str(folder), "--master", "fmpy", "--out", str(tmp_path / "out")]) == 1
    out = capsys.readouterr().out
    assert "FAILS: the platform at the target height" in out and "the outcome does NOT hold" in out


def test_a_check_in_a_frame_reads_the_vector_in_the_moving_frame():
    """A frame at (1, 2, 3) turned by a quarter turn about z: the point (1, 3, 3) is 1 m
    along its x axis; a frame's value must name a vector's element."""
    system = ssd.System(pathlib.Path("system.ssd"), "frame", {}, [], step_ns=1_000_000)
    values = {"w.p.position[1]": 1.0, "w.p.position[2]": 3.0, "w.p.position[3]": 3.0, "c.f.position[1]": 1.0,
              "c.f.position[2]": 2.0, "c.f.position[3]": 3.0, "c.f.orientation[1]": math.sqrt(0.5),
              "c.f.orientation[2]": 0.0, "c.f.orientation[3]": 0.0, "c.f.orientation[4]": math.sqrt(0.5)}
    run = masters.Run("fmpy", system, list(values), np.array([0.001]), np.array([list(values.values())]), 0.0)
    along = [outcome.Check("x", f"w.p.position[{i}]", 0.0, 1e-12, frame="c.f") for i in (1, 2, 3)]
    assert [outcome.evaluate(c, run, system).last for c in along] == pytest.approx([1.0, 0.0, 0.0], abs=1e-15)
    with pytest.raises(ValueError, match="a vector's element NAME"):
        outcome.Check("x", "w.p.speed", 0.0, 1.0, frame="c.f").variables()


def test_a_misspelt_parameter_is_refused_before_the_run(built):
    ssd_path = built(LIFT)
    system = ssd.read(ssd_path)
    system.parameters["controller"]["targt"] = 0.5
    with pytest.raises(fmus.BuildError, match=r"controller\.targt must be a Real parameter or input"):
        fmus.check_names(system, ssd_path.parent)


# ---- the balance: a ball rolling on a paddle that the controller tilts ------------------

G, M, R = 9.81, 0.2, 0.05  # the ball's mass (kg) and radius (m)
D = 0.06  # m: the ball's centre above the pivot, the paddle's half thickness 0.01 m + R


def rk4(f, y, h):
    k1 = f(y)
    k2 = f(y + h / 2 * k1)
    k3 = f(y + h / 2 * k2)
    k4 = f(y + h * k3)
    return y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


def tilting_beam(parameters, h, steps, s0=0.2):
    """The ball's world x after each communication step by the equations of a ball rolling
    without slipping on a beam tilted by theta about a pivot D below the ball's centre
    (Lagrange, s along the beam, I = 2/5 M R^2):

        7/5 s'' = g sin theta + s theta'^2 - (D + 2/5 R) theta'',   x = s cos theta + D sin theta,

    closed by the tilt controller's law as the masters sample it: the rate constant over
    each step (so theta'' is an impulse where it changes), computed from the ball's x and
    x' at the step's start. RK4 at the communication step (ten sub-steps change it by
    1e-15 m)."""
    kp, kd, tau, target = (parameters[n] for n in ("Kp", "Kd", "timeConstant", "target"))
    y = np.array([s0, 0.0, 0.0])  # s, s', theta
    x, v, rate_before = s0, 0.0, 0.0
    rate = (kp * (target - x) - kd * v) / tau  # out of initialisation, theta = 0
    out = []
    for _ in range(steps):
        y[1] -= 5 / 7 * (D + 0.4 * R) * (rate - rate_before)
        y = rk4(lambda y: np.array([y[1], 5 / 7 * (G * math.sin(y[2]) + y[0] * rate * rate), rate]), y, h)
        s, ds, theta = y
        read = (x, v)  # what the controller steps on: the ball at the step's start
        x = s * math.cos(theta) + D * math.sin(theta)
        v = (ds + D * rate) * math.cos(theta) - s * rate * math.sin(theta)
        rate_before, rate = rate, (kp * (target - read[0]) - kd * read[1] - theta) / tau
        out.append(x)
    return np.array(out)


def test_the_ball_rolls_as_on_a_tilting_beam(runs):
    """Within 1e-4 m of the equations over the 10 s (3.0e-5 m measured, the first-order
    motion of bodies in contact: 7.5e-6 m at a quarter of the solver step); leaving the
    pivot's offset D out of them would be 7.6e-4 m off."""
    run = runs(BALANCE, "libcosim")
    x = tilting_beam(run.system.parameters["controller"], run.system.step, run.system.steps)
    assert np.abs(run.col("world.ball.position[1]") - x).max() < 1e-4


def test_the_ball_settles_without_overshoot_and_the_paddle_carries_its_weight(runs):
    """From 5 s on the ball stays within 0.2 mm of the centre (0.151 mm measured; the band
    says 2 cm) and the paddle's contact force has the mean -M g to 1e-8 (7e-10 measured);
    critically damped, the ball never crosses the centre; the ball's and the paddle's
    contact forces are opposite throughout, to 1e-12 N."""
    run = runs(BALANCE, "libcosim")
    x, late = run.col("world.ball.position[1]"), run.t >= 5.0
    assert np.abs(x[late]).max() < 2e-4 and x.min() > 0.0
    assert run.col("world.paddle.contactForce[3]")[late].mean() == pytest.approx(-M * G, rel=1e-8)
    for i in (1, 2, 3):
        ball, paddle = run.col(f"world.ball.contactForce[{i}]"), run.col(f"world.paddle.contactForce[{i}]")
        assert np.abs(ball + paddle).max() < 1e-12


def test_the_ball_rolls_without_slipping_on_the_tilting_paddle(runs):
    """The ball's contact point moves with the paddle's surface under it: their velocities
    differ by less than 1e-4 m/s (2.6e-5 measured, the ball rolling at up to 0.138 m/s),
    the paddle turning at the rate of the step just ended about the pivot (the origin);
    and it never lifts off: its centre stays D from the pivot along the paddle's normal
    to 1e-6 m (0.44 um measured, the soft contact's sink; the outcome's band is 1 mm)."""
    run = runs(BALANCE, "libcosim")
    height = next(c for c in outcome.load(BALANCE).checks if c.frame and c.value.endswith("[3]"))
    assert outcome.evaluate(height, run, run.system).worst < 1e-6
    col = run.col
    theta = col("controller.tilt")
    normal = np.stack([np.sin(theta), 0 * theta, np.cos(theta)], 1)
    contact = np.stack([col(f"world.ball.position[{i}]") for i in (1, 2, 3)], 1) - R * normal
    omega = np.stack([col(f"world.ball.angularVelocity[{i}]") for i in (1, 2, 3)], 1)
    ball = np.stack([col(f"world.ball.velocity[{i}]") for i in (1, 2, 3)], 1) + np.cross(omega, -R * normal)
    rate = col("controller.paddle.angularVelocity[2]")[:-1]  # over the step to the next point
    surface = np.cross(np.stack([0 * rate, rate, 0 * rate], 1), contact[1:])
    assert np.abs(ball[1:] - surface).max() < 1e-4


def test_the_tilt_moves_at_the_rate_the_paddle_was_given(runs):
    """The controller's outputs agree with each other: the tilt at each point is the last
    one moved by a step at the last rate, the orientation is its quaternion about y, and
    the pivot stays put."""
    run = runs(BALANCE, "fmpy")
    theta, rate = run.col("controller.tilt"), run.col("controller.paddle.angularVelocity[2]")
    assert np.allclose(theta[1:], theta[:-1] + run.system.step * rate[:-1], rtol=0, atol=1e-15)
    assert np.array_equal(run.col("controller.paddle.orientation[1]"), np.cos(theta / 2))
    assert np.array_equal(run.col("controller.paddle.orientation[3]"), np.sin(theta / 2))
    for i in (1, 2, 3):
        assert not run.col(f"controller.paddle.position[{i}]").any()


# ---- the controllers, C FMUs of this repository ------------------------------------------


@pytest.mark.parametrize("folder, controller", CONTROLLERS, ids=lambda c: getattr(c, "name", c))
def test_the_controller_is_a_valid_fmu_with_its_declared_start_values(built, folder, controller):
    fmu = built(folder).parent / f"{controller}.fmu"
    assert validate_fmu(str(fmu)) == []
    slave = Slave(fmu)
    try:
        for v in slave.md.modelVariables:
            if v.start is not None:
                assert slave.get(v.name) == float(v.start), v.name
    finally:
        slave.close()


def test_the_controller_refuses_bad_values_by_name(built):
    slave = Slave(built(LIFT).parent / "pd_controller.fmu")
    try:
        with pytest.raises(FMICallException):
            slave.set_values({"position": float("nan")})
        assert "position must be finite" in slave.log.last()[2]
        with pytest.raises(FMICallException):
            slave.set_values({"Kd": -1.0})
        assert "Kd must be >= 0" in slave.log.last()[2]
        slave.initialize({"Kp": 10.0, "target": 1.0})
        with pytest.raises(FMICallException):
            slave.set_values({"Kp": 20.0})
        assert "Kp is a fixed parameter" in slave.log.last()[2]
        slave.set_values({"position": 0.25, "velocity": 0.5, "load": 3.0})
        slave.step(0.001)
        # 10 (1 - 0.25) - 200 0.5 + 0 9.81 + 3: the law of the inputs held over the step
        assert slave.get("force") == pytest.approx(10 * 0.75 - 200 * 0.5 + 3.0, rel=1e-15)
    finally:
        slave.close()


def test_the_tilt_controller_follows_its_law_and_refuses_a_zero_time_constant(built):
    slave = Slave(built(BALANCE).parent / "tilt_controller.fmu")
    try:
        with pytest.raises(FMICallException):
            slave.set_values({"timeConstant": 0.0})
        assert "timeConstant must be >= 0.001" in slave.log.last()[2]
        slave.initialize({"Kp": 0.5, "Kd": 0.25, "timeConstant": 0.1, "pivot[3]": 0.3, "ball.position": 0.2,
                          "ball.velocity": -0.1})
        rate0 = slave.get("paddle.angularVelocity[2]")  # out of initialisation, from tilt 0
        assert slave.get("tilt") == 0.0
        assert rate0 == pytest.approx((0.5 * -0.2 - 0.25 * -0.1) / 0.1, rel=1e-15)
        slave.step(0.001)
        theta = 0.001 * rate0
        assert slave.get("tilt") == pytest.approx(theta, rel=1e-15)
        assert slave.get("paddle.angularVelocity[2]") == pytest.approx((-0.075 - theta) / 0.1, rel=1e-15)
        assert slave.get("paddle.orientation[3]") == pytest.approx(math.sin(theta / 2), rel=1e-15)
        assert slave.get("paddle.position[3]") == 0.3
    finally:
        slave.close()
