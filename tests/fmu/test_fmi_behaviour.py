"""The FMU as an FMI 2.0 citizen: state machine, bad arguments, discard, reset,
resource locations, GUID check, independent instances."""
import pathlib
import shutil
import tempfile
import threading
import traceback
import urllib.parse

import numpy as np
import pytest
from fmpy import extract
from fmpy.fmi2 import fmi2LastSuccessfulTime, fmi2Terminated

import scenes
from harness import Slave, status_of

POS = ["ball.position[1]", "ball.position[2]", "ball.position[3]"]


@pytest.fixture(scope="module")
def fmu(fmu_of):
    return fmu_of(scenes.projectile())


@pytest.fixture
def slave(fmu):
    s = Slave(fmu)
    yield s
    s.close()


def last_error(s):
    errors = [m for st, c, m in s.log.messages if st in ("Error", "Discard")]
    assert errors, "no message reached the FMI logger"
    return errors[-1]


# ---- state machine --------------------------------------------------------------------

def test_do_step_before_initialisation_is_refused(slave):
    assert status_of(lambda: slave.slave.doStep(0.0, 0.1)) == "Error"
    assert "fmi2DoStep: not allowed in state Instantiated" in last_error(slave)


def test_get_before_initialisation_mode_is_refused(slave):
    assert status_of(lambda: slave.get("ball.position[1]")) == "Error"
    assert "not allowed in state Instantiated" in last_error(slave)


def test_exit_initialisation_without_enter_is_refused(slave):
    assert status_of(lambda: slave.slave.exitInitializationMode()) == "Error"
    assert "fmi2ExitInitializationMode" in last_error(slave)


def test_setup_experiment_after_initialisation_is_refused(slave):
    slave.initialize()
    assert status_of(lambda: slave.slave.setupExperiment(startTime=0.0)) == "Error"
    assert "state StepComplete" in last_error(slave)


def test_outputs_and_fixed_parameters_cannot_be_set_while_stepping(slave):
    slave.initialize()
    assert status_of(lambda: slave.set_values({"ball.position[1]": 1.0})) == "Error"
    assert "ball.position[1]" in last_error(slave)
    assert status_of(lambda: slave.set_values({"ball.mass": 2.0})) == "Error"
    assert "ball.mass" in last_error(slave)
    assert status_of(lambda: slave.set_values({"solver.method": 1})) == "Error"
    # a tunable parameter can: gravity changes between steps
    assert status_of(lambda: slave.set_values({"gravity[3]": -1.0})) == "OK"


def test_calculated_outputs_have_no_start_value_to_set(slave):
    assert status_of(lambda: slave.set_values({"ball.linearMomentum[1]": 1.0})) == "Error"
    assert "ball.linearMomentum[1]" in last_error(slave)


def test_terminate_then_step_is_refused(slave):
    slave.initialize()
    slave.step(0.1)
    slave.slave.terminate()
    assert status_of(lambda: slave.slave.doStep(0.1, 0.1)) == "Error"
    assert "state Terminated" in last_error(slave)
    assert slave.get("ball.position[1]") == pytest.approx(1.0 + 0.3, abs=1e-12)


# ---- bad arguments --------------------------------------------------------------------

def test_unknown_value_reference(slave):
    slave.initialize()
    bad = len(slave.md.modelVariables) + 7
    assert status_of(lambda: slave.slave.getReal([bad])) == "Error"
    assert f"unknown value reference {bad}" in last_error(slave)
    assert status_of(lambda: slave.slave.setReal([bad], [1.0])) == "Error"
    assert status_of(lambda: slave.slave.getBoolean([0])) == "Error"
    assert status_of(lambda: slave.slave.getInteger(slave.vr(["ball.mass"]))) == "Error"
    assert "ball.mass" in last_error(slave)


@pytest.mark.parametrize("value", [float("nan"), float("inf"), -float("inf")])
def test_non_finite_values_are_refused(slave, value):
    slave.initialize()
    assert status_of(lambda: slave.set_values({"ball.force[1]": value})) == "Error"
    assert "ball.force[1]: must be finite" in last_error(slave)
    slave.step(0.1)  # the refused value did not reach the state
    assert np.all(np.isfinite(slave.get(*POS)))


@pytest.mark.parametrize("name,value,limit", [("ball.mass", -1.0, "must be > 0"),
                                              ("ball.restitution", 1.5, "must be in [0, 1]"),
                                              ("solver.step", 0.0, "must be > 0"),
                                              ("solver.method", 99, "must be one of 1 (euler), 2 (rk4)")])
def test_parameter_limits(slave, name, value, limit):
    assert status_of(lambda: slave.set_values({name: value})) == "Error"
    assert f"{name}: {limit}" in last_error(slave)


@pytest.mark.parametrize("h", [-0.1, 0.0, float("nan")])
def test_bad_communication_step_is_refused(slave, h):
    slave.initialize()
    assert status_of(lambda: slave.slave.doStep(0.0, h)) == "Error"
    assert "communicationStepSize must be > 0" in last_error(slave)


def test_communication_point_must_match_but_jitter_is_accepted(slave):
    slave.initialize()
    slave.slave.doStep(0.0, 0.1)
    assert status_of(lambda: slave.slave.doStep(0.2, 0.1)) == "Error"
    assert "is not the FMU's time" in last_error(slave)
    slave.slave.doStep(0.1 + 1e-17, 0.1)  # a master that accumulates time
    slave.slave.doStep(0.2 - 3e-17, 0.1)
    t = 0.30000000000000004
    assert slave.get("ball.position[3]") == pytest.approx(10 + 4 * t - 4.905 * t * t, abs=1e-12)


def test_last_internal_step_is_shortened(fmu_of):
    """Euler on free fall loses g h_k^2/2 per internal step h_k. A communication step of
    10.5 ms with solver.step 1 ms is 10 steps of 1 ms and one of 0.5 ms."""
    s = Slave(fmu_of(scenes.projectile()))
    try:
        s.initialize({"solver.method": 1, "solver.step": 1e-3})
        for n in range(100):
            s.slave.doStep(n * 0.0105, 0.0105)
        T = 1.05
        sum_h2 = 100 * (10 * 1e-3**2 + 0.5e-3**2)
        expected = 10 + 4 * T - 4.905 * T * T + 4.905 * sum_h2
        assert s.get("ball.position[3]") == pytest.approx(expected, abs=1e-10)
    finally:
        s.close()


# ---- non-finite results: fmi2Discard ----------------------------------------------------

def test_overflow_gives_discard_with_last_successful_time(fmu):
    s = Slave(fmu)
    try:
        s.initialize()
        s.set_values({"ball.force[1]": 5e11})  # x leaves the 1e12 m a state may reach after 2 s
        assert status_of(lambda: s.slave.doStep(0.0, 10.0)) == "Discard"
        assert "ball" in last_error(s) and "not finite or beyond 1e12 m" in last_error(s)
        assert s.slave.getBooleanStatus(fmi2Terminated) is True
        t_last = s.slave.getRealStatus(fmi2LastSuccessfulTime)
        assert 0.0 < t_last < 10.0
        values = s.all_reals()
        assert np.all(np.isfinite(values))
        assert s.get("time") == t_last
        assert status_of(lambda: s.slave.doStep(t_last, 0.1)) == "Error"
        s.slave.reset()  # usable again
        s.initialize()
        s.step(1.0)
        assert s.get("ball.position[1]") == pytest.approx(4.0, abs=1e-12)
    finally:
        s.close()


# ---- reset ---------------------------------------------------------------------------

def run(s, steps=10, h=0.1, start=None):
    s.initialize(start)
    s.set_values({"ball.force[2]": 0.5, "ball.torque[1]": 0.01})
    for _ in range(steps):
        s.step(h)
    return s.all_reals()


def test_reset_restores_the_just_instantiated_state(fmu):
    fresh = Slave(fmu)
    used = Slave(fmu)
    try:
        expected = run(fresh)
        run(used, start={"ball.mass": 3.0, "gravity[3]": -1.0, "ball.velocity[1]": 9.0})
        used.slave.reset()
        assert run(used) == expected  # bitwise
    finally:
        fresh.close()
        used.close()


# ---- instantiation: GUID and resource locations --------------------------------------------

def instantiate(s, guid=None, uri=None):
    resources = pathlib.Path(s.dir, "resources")
    return s.slave.fmi2Instantiate(b"x", 1, (guid or s.md.guid).encode(),
                                   (uri or resources.as_uri()).encode(),
                                   s.log.callbacks, 0, 0)


def test_wrong_guid_is_refused_with_a_message(fmu):
    s = Slave(fmu, instantiate=False)
    try:
        assert not instantiate(s, guid="{00000000-0000-0000-0000-000000000000}")
        assert "GUID" in last_error(s) and s.md.guid in last_error(s)
    finally:
        shutil.rmtree(s.dir, ignore_errors=True)


def test_resource_location_forms(fmu):
    base = pathlib.Path(tempfile.mkdtemp(prefix="rigid fmu %"))  # space and percent
    try:
        unzip = extract(str(fmu), unzipdir=str(base / "unzipped"))
        s = Slave(fmu, unzip_dir=unzip, instantiate=False)
        resources = pathlib.Path(unzip, "resources")
        encoded = urllib.parse.quote(str(resources))
        for uri in ["file://" + encoded, "file:" + encoded, "file://" + encoded + "/",
                    "file:///" + encoded.lstrip("/"), "file:////" + encoded.lstrip("/"),
                    "file://localhost" + encoded]:
            c = instantiate(s, uri=uri)
            assert c, (uri, s.log.text())
            s.slave.fmi2FreeInstance(c)
        assert not instantiate(s, uri="http://example.invalid/resources")
        assert "resource location" in last_error(s)
        assert not instantiate(s, uri="file://" + urllib.parse.quote(str(base / "nowhere")))
        assert "scene" in last_error(s)
    finally:
        shutil.rmtree(base, ignore_errors=True)


def test_bad_scene_in_resources_is_refused_through_the_logger(fmu):
    s = Slave(fmu, instantiate=False)
    try:
        scene = pathlib.Path(s.dir, "resources", "scene.json")
        scene.write_text(scene.read_text().replace('"mass": 1.0', '"mass": -1.0'))
        assert not instantiate(s)
        assert "bodies[0].mass: must be > 0, got -1" in last_error(s)
    finally:
        shutil.rmtree(s.dir, ignore_errors=True)


# ---- independent instances -------------------------------------------------------------

def test_two_instances_in_one_process_stay_independent(fmu):
    a, b = Slave(fmu, "a"), Slave(fmu, "b")
    try:
        a.initialize({"gravity[3]": -1.0})
        b.initialize({"gravity[3]": -20.0, "ball.velocity[1]": 0.0})
        for _ in range(10):
            a.step(0.1)
            b.step(0.1)
        assert a.get("ball.position[3]") == pytest.approx(10 + 4 - 0.5, abs=1e-12)
        assert b.get("ball.position[3]") == pytest.approx(10 + 4 - 10.0, abs=1e-12)
        assert a.get("ball.position[1]") == pytest.approx(4.0, abs=1e-12)
        assert b.get("ball.position[1]") == pytest.approx(1.0, abs=1e-12)
    finally:
        a.close()
        b.close()


def test_instances_in_threads_give_the_serial_results(fmu):
    starts = [{"gravity[3]": -9.81 + k, "ball.velocity[2]": 0.1 * k} for k in range(4)]

    def job(k, out):
        s = Slave(fmu, f"t{k}")
        try:
            out[k] = run(s, steps=50, h=0.02, start=starts[k])
        finally:
            s.close()

    serial, threaded, errors = {}, {}, []
    for k in range(4):
        job(k, serial)

    def threaded_job(k):
        try:
            job(k, threaded)
        except BaseException:  # a thread's exception would otherwise be lost
            errors.append(traceback.format_exc())

    threads = [threading.Thread(target=threaded_job, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors[0]
    assert threaded == serial
