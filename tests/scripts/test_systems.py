"""The example systems (docs/guide/systems.md): every folder of scripts/systems with a
system.ssd runs in libcosim and in fmpy to its outcome (outcome.json), and the two
masters' recordings are equal to the bit; `scripts/system.sh` says so and exits 0, and
exits 1 when the outcome fails. The lift's controller is a valid FMU that refuses bad
values by name."""
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


def test_the_lift_is_among_the_systems():
    assert LIFT in SYSTEMS


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
            names = masters.recorded(ssd.read(ssd_path), outcome.load(folder).variables())
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


# ---- the lift's controller, a C FMU of this repository ----------------------------------


def test_the_controller_is_a_valid_fmu_with_its_declared_start_values(built):
    fmu = built(LIFT).parent / "pd_controller.fmu"
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
