"""The FMI 3.0 Co-Simulation FMU of a scene (build_fmu.sh --fmi 3, issue 21) through
fmpy's FMI 3 support: valid, the same variables and the same run as the FMI 2 FMU of
the scene, bitwise; states that continue bitwise, in this process and in another;
reset; bad calls answered with fmi3Error and a message naming the variable or the
state, the instance still usable; in both versions, every message of a bad call names
the function the importer called."""
import ctypes
import json
import math
import pathlib
import subprocess
import sys

import numpy as np
import pytest
from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.fmi3 import FMU3Slave, fmi3Byte, fmi3Error
from fmpy.validation import validate_fmu

from rigidfmu.driver import Fmu, Slave, load_library

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = sorted(p.name for p in (ROOT / "scripts" / "scenes").glob("*.json"))


def example(name):
    return ROOT / "scripts" / "scenes" / name  # (with the mesh files beside it)


class Logged:
    """An FMI 3 logMessage callback that keeps (status, category, message)."""

    def __init__(self):
        self.messages = []

    def __call__(self, env, status, category, message):
        self.messages.append((status, category.decode(), message.decode()))

    def text(self):
        return "\n".join(m for _, _, m in self.messages)


class Fmi3:
    """One instance of an FMI 3 FMU, addressed by variable name."""

    def __init__(self, fmu, folder, name="fmi3", early_return_allowed=False):
        self.unpacked = Fmu(fmu, unzip_dir=extract(str(fmu), unzipdir=str(folder)))
        self.md = self.unpacked.md
        self.vr = {name: v.valueReference for name, v in self.unpacked.vars.items()}
        self.floats = [v.valueReference for v in self.md.modelVariables if v.type == "Float64"]
        self.log = Logged()
        self.slave = load_library(self.md, self.unpacked.dir, name)
        self.slave.instantiate(logMessage=self.log, earlyReturnAllowed=early_return_allowed)
        self.time = 0.0

    def start(self, values=None):
        for name, value in (values or {}).items():
            self.slave.setFloat64([self.vr[name]], [value])
        self.slave.enterInitializationMode(startTime=0.0)
        self.slave.exitInitializationMode()

    def step(self, h):
        result = self.slave.doStep(self.time, h)
        self.time += h
        return result

    def outputs(self):
        return self.slave.getFloat64(self.floats)

    def close(self):
        self.slave.freeInstance()


@pytest.mark.parametrize("scene", EXAMPLES)
def test_the_fmi3_fmu_is_valid_and_carries_both_platforms(scene, fmu_of):
    fmu = fmu_of(example(scene), fmi=3)
    assert validate_fmu(str(fmu)) == []
    md = read_model_description(str(fmu))
    assert md.fmiVersion == "3.0" and md.coSimulation is not None and md.modelExchange is None
    import zipfile
    names = zipfile.ZipFile(fmu).namelist()
    ident = md.coSimulation.modelIdentifier
    assert f"binaries/x86_64-linux/{ident}.so" in names
    assert f"binaries/x86_64-windows/{ident}.dll" in names
    # it speaks FMI 3 throughout: no FMI 2 name in its description
    assert "fmi2" not in zipfile.ZipFile(fmu).read("modelDescription.xml").decode()


@pytest.mark.parametrize("scene", EXAMPLES)
def test_the_same_variables_as_the_fmi2_fmu(scene, fmu_of):
    two = read_model_description(str(fmu_of(example(scene))))
    three = read_model_description(str(fmu_of(example(scene), fmi=3)))
    kinds = {"Real": "Float64", "Integer": "Int32", "Enumeration": "Enumeration"}
    assert [(v.name, v.valueReference, kinds[v.type], v.causality, v.variability, v.unit, v.description)
            for v in two.modelVariables] == \
           [(v.name, v.valueReference, v.type, v.causality, v.variability, v.unit, v.description)
            for v in three.modelVariables]
    assert two.guid == three.guid  # the instantiation token is the scene's GUID


@pytest.mark.parametrize("scene", EXAMPLES)
def test_simulate_fmu_gives_the_fmi2_run_bitwise(scene, fmu_of):
    """Same scene, same steps: the same outputs, to the bit (one instance logic, one step)."""
    runs = [simulate_fmu(str(fmu_of(example(scene), fmi=fmi)), stop_time=2.0, output_interval=0.01)
            for fmi in (2, 3)]
    assert runs[0].dtype.names == runs[1].dtype.names and len(runs[0]) == 201
    for name in runs[0].dtype.names:
        assert np.array_equal(runs[0][name], runs[1][name]), name


def test_start_values_and_the_enumeration_through_int64(fmu_of, tmp_path):
    fmu_file = fmu_of(example("default.json"), fmi=3)
    default = Fmi3(fmu_file, tmp_path / "default")
    default.start()
    method = default.vr["solver.method"]
    assert default.slave.getInt64([method]) == [2]  # rk4, the default
    default.close()
    fmu = Fmi3(fmu_file, tmp_path / "set")
    fmu.slave.setInt64([method], [1])  # euler, before initialisation as FMI 3 wants
    fmu.start({"ball.mass": 3.0})
    assert fmu.slave.getInt64([method]) == [1]
    assert fmu.slave.getFloat64([fmu.vr["ball.mass"]]) == [3.0]
    fmu.close()


def run_and_record(fmu, steps, h=0.01):
    rows = []
    for _ in range(steps):
        fmu.step(h)
        rows.append(fmu.outputs())
    return rows


def test_fmu_state_and_serialisation_continue_bitwise_here_and_in_another_process(fmu_of, tmp_path):
    fmu_file = fmu_of(example("default.json"), fmi=3)
    fmu = Fmi3(fmu_file, tmp_path / "a")
    fmu.start()
    run_and_record(fmu, 50)
    state = fmu.slave.getFMUState()
    blob = bytes(fmu.slave.serializeFMUState(state))
    t = fmu.time
    first = run_and_record(fmu, 50)
    fmu.slave.setFMUState(state)
    fmu.time = t
    assert run_and_record(fmu, 50) == first
    restored = fmu.slave.deserializeFMUState(blob)
    fmu.slave.setFMUState(restored)
    fmu.time = t
    assert run_and_record(fmu, 50) == first
    fmu.slave.freeFMUState(state)
    fmu.slave.freeFMUState(restored)
    fmu.close()

    # another process: a fresh instance takes the bytes and continues the same way
    (tmp_path / "state.bin").write_bytes(blob)
    child = f"""
import json, sys
sys.path.insert(0, {str(pathlib.Path(__file__).parent)!r})
from test_fmi3 import Fmi3, run_and_record
fmu = Fmi3({str(fmu_file)!r}, {str(tmp_path / "b")!r}, "child")
fmu.start()
fmu.slave.setFMUState(fmu.slave.deserializeFMUState(open({str(tmp_path / "state.bin")!r}, "rb").read()))
fmu.time = {t!r}
print(json.dumps(run_and_record(fmu, 50)))
"""
    out = subprocess.run([sys.executable, "-c", child], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout) == first


def test_reset_gives_a_fresh_instances_run(fmu_of, tmp_path):
    fmu_file = fmu_of(example("default.json"), fmi=3)
    fresh = Fmi3(fmu_file, tmp_path / "fresh")
    fresh.start()
    expected = run_and_record(fresh, 30)
    fresh.close()
    fmu = Fmi3(fmu_file, tmp_path / "reset")
    fmu.start({"ball.mass": 5.0})
    run_and_record(fmu, 40)
    fmu.slave.reset()
    fmu.time = 0.0
    fmu.start()
    assert run_and_record(fmu, 30) == expected
    fmu.close()


def status_of(call):
    try:
        call()
        return "OK"
    except FMICallException as e:
        return {fmi3Error: "Error"}.get(e.status, str(e.status))


def test_bad_calls_are_refused_with_a_message_and_the_instance_goes_on(fmu_of, tmp_path):
    fmu = Fmi3(fmu_of(example("default.json"), fmi=3), tmp_path)
    s, vr = fmu.slave, fmu.vr
    assert status_of(lambda: s.doStep(0.0, 0.01)) == "Error"
    assert "fmi3DoStep: not allowed in state Instantiated" in fmu.log.text()
    fmu.start()
    assert status_of(lambda: s.setFloat64([vr["slider.force[1]"]], [math.nan])) == "Error"
    assert "slider.force[1]: must be finite, got nan" in fmu.log.text()
    assert status_of(lambda: s.getFloat64([4000000000])) == "Error"
    assert "fmi3GetFloat64: unknown value reference 4000000000" in fmu.log.text()
    assert status_of(lambda: s.getInt32([vr["ball.mass"]])) == "Error"
    assert "(ball.mass) is not an Int32: it is a Float64, use fmi3Get/SetFloat64" in fmu.log.text()
    assert status_of(lambda: s.getInt64([vr["ball.mass"]])) == "Error"
    assert status_of(lambda: s.setFloat64([vr["ball.mass"]], [-1.0])) == "Error"  # a fixed parameter, running
    assert status_of(lambda: s.enterEventMode()) == "Error"
    assert "fmi3EnterEventMode: not supported" in fmu.log.text()
    assert status_of(lambda: s.doStep(0.0, -0.01)) == "Error"
    assert "fmi3DoStep: communicationStepSize must be > 0" in fmu.log.text()
    assert status_of(lambda: s.doStep(0.5, 0.01)) == "Error"
    assert "fmi3DoStep: currentCommunicationPoint 0.5 is not the FMU's time 0" in fmu.log.text()
    assert status_of(lambda: s.setFMUState(None)) == "Error"
    # NULL value references with a count: refused, not read through
    values = (ctypes.c_double * 1)()
    assert status_of(lambda: s.fmi3GetFloat64(s.component, None, 1, values, 1)) == "Error"
    assert "fmi3GetFloat64: valueReferences is NULL but nValueReferences = 1" in fmu.log.text()
    assert status_of(lambda: s.fmi3SetFloat64(s.component, None, 1, values, 1)) == "Error"
    # every message names the function the importer called, none the FMI 2 function
    # that answers it inside the FMU
    assert "fmi2" not in fmu.log.text(), fmu.log.text()
    # a refused call leaves the instance as it was: it steps on
    event, terminate, early, reached = fmu.step(0.01)
    assert (event, terminate, early) == (False, False, False) and reached == pytest.approx(0.01, abs=1e-15)
    assert all(math.isfinite(x) for x in fmu.outputs())
    fmu.close()


def bad_calls_fmi2(s, vr):
    """Bad calls on an FMI 2 instance: before and after initialisation, each as (the
    function the importer calls, the call, what its message says)."""
    out, method, buffer = vr["ball.position[1]"], vr["solver.method"], ctypes.create_string_buffer(8)
    before = [("fmi2DoStep", lambda: s.doStep(0.0, 0.01), "not allowed in state Instantiated"),
              ("fmi2ExitInitializationMode", s.exitInitializationMode, "not allowed in state Instantiated")]
    after = [
        ("fmi2EnterInitializationMode", s.enterInitializationMode, "not allowed in state StepComplete"),
        ("fmi2SetReal", lambda: s.setReal([vr["slider.force[1]"]], [math.nan]), "slider.force[1]: must be finite"),
        ("fmi2GetReal", lambda: s.getReal([4000000000]), "unknown value reference 4000000000"),
        ("fmi2SetReal", lambda: s.setReal([4000000000], [1.0]), "unknown value reference 4000000000"),
        ("fmi2DoStep", lambda: s.doStep(0.0, -0.01), "communicationStepSize must be > 0"),
        ("fmi2GetInteger", lambda: s.getInteger([vr["ball.mass"]]), "(ball.mass) is a Real, use fmi2Get/SetReal"),
        ("fmi2SetReal", lambda: s.setReal([method], [1.0]),
         "(solver.method) is an Integer or Enumeration, use fmi2Get/SetInteger"),
        ("fmi2SetReal", lambda: s.setReal([vr["ball.mass"]], [2.0]), "ball.mass: only inputs and tunable"),
        ("fmi2GetDirectionalDerivative", lambda: s.getDirectionalDerivative([out], [method], [1.0]),
         "(solver.method) is an Integer or Enumeration, use fmi2Get/SetInteger"),
        ("fmi2SerializeFMUstate", lambda: s.fmi2SerializeFMUstate(s.component, s.getFMUstate(), buffer, 8),
         "(fmi2SerializedFMUstateSize)")]
    return before, after


def bad_calls_fmi3(s, vr):
    """The same bad calls on an FMI 3 instance, through the FMI 3 functions."""
    out, method, buffer = vr["ball.position[1]"], vr["solver.method"], ctypes.create_string_buffer(8)
    before = [("fmi3DoStep", lambda: s.doStep(0.0, 0.01), "not allowed in state Instantiated"),
              ("fmi3ExitInitializationMode", s.exitInitializationMode, "not allowed in state Instantiated")]
    after = [
        ("fmi3EnterInitializationMode", s.enterInitializationMode, "not allowed in state StepComplete"),
        ("fmi3SetFloat64", lambda: s.setFloat64([vr["slider.force[1]"]], [math.nan]),
         "slider.force[1]: must be finite"),
        ("fmi3GetFloat64", lambda: s.getFloat64([4000000000]), "unknown value reference 4000000000"),
        ("fmi3SetFloat64", lambda: s.setFloat64([4000000000], [1.0]), "unknown value reference 4000000000"),
        ("fmi3DoStep", lambda: s.doStep(0.0, -0.01), "communicationStepSize must be > 0"),
        ("fmi3GetInt32", lambda: s.getInt32([vr["ball.mass"]]), "it is a Float64, use fmi3Get/SetFloat64"),
        ("fmi3SetFloat64", lambda: s.setFloat64([method], [1.0]), "it is an Enumeration, use fmi3Get/SetInt64"),
        ("fmi3SetFloat64", lambda: s.setFloat64([vr["ball.mass"]], [2.0]), "ball.mass: only inputs and tunable"),
        ("fmi3GetDirectionalDerivative", lambda: s.getDirectionalDerivative([out], [method], [1.0]),
         "(solver.method) is an Enumeration, use fmi3Get/SetInt64"),
        ("fmi3SerializeFMUState", lambda: s.fmi3SerializeFMUState(
            s.component, s.getFMUState(), ctypes.cast(buffer, ctypes.POINTER(fmi3Byte)), 8),
         "(fmi3SerializedFMUStateSize)")]
    return before, after


def refusals(log, calls):
    """Makes each bad call; returns (function, status, the messages it logged, says)."""
    out = []
    for function, call, says in calls:
        first = len(log.messages)
        out.append((function, status_of(call), [m for _, _, m in log.messages[first:]], says))
    return out


def test_every_message_of_a_bad_call_names_the_function_called_in_either_version(fmu_of, tmp_path):
    """The FMI 2 and FMI 3 FMUs of one scene, one version-neutral instance behind both:
    the same bad calls (wrong state, NaN into an input, unknown references on get and
    set, a negative step, a variable of the wrong type, a fixed parameter mid-run, a
    short state buffer) are refused, and every message names the very function the
    importer called, never one of the other version."""
    scene = example("default.json")
    two = Slave(fmu_of(scene), folder=str(tmp_path))
    three = Fmi3(fmu_of(scene, fmi=3), tmp_path / "fmi3")
    found = []
    try:
        for fmu, s, calls, start in ((two, two.slave, bad_calls_fmi2, two.initialize),
                                     (three, three.slave, bad_calls_fmi3, three.start)):
            vr = {v.name: v.valueReference for v in fmu.md.modelVariables}
            before, after = calls(s, vr)
            found += refusals(fmu.log, before)
            start()
            found += refusals(fmu.log, after)
        for function, status, messages, says in found:
            assert status == "Error", (function, says, status)
            assert messages, f"{function} ({says}) logged nothing"
            assert all(m.startswith(function + ": ") for m in messages), (function, messages)
            assert any(says in m for m in messages), (function, says, messages)
        assert {f[:4] for f, *_ in found} == {"fmi2", "fmi3"} and len(found) == 24
        assert "fmi2" not in three.log.text(), three.log.text()
        assert "fmi3" not in two.log.text(), two.log.text()
    finally:
        two.close()
        three.close()


def test_a_wrong_instantiation_token_or_model_exchange_is_refused(fmu_of, tmp_path):
    fmu_file = fmu_of(example("spinner.json"), fmi=3)
    md = read_model_description(str(fmu_file))
    unzip = extract(str(fmu_file), unzipdir=str(tmp_path))
    log = Logged()
    s = FMU3Slave(guid="{not-the-token}", unzipDirectory=unzip, modelIdentifier=md.coSimulation.modelIdentifier,
                  instanceName="bad")
    with pytest.raises(Exception, match="Failed to instantiate"):
        s.instantiate(logMessage=log)
    assert "fmi3InstantiateCoSimulation: GUID {not-the-token} does not match" in log.text()


G, XI, H, R = 9.81, 0.8, 1.0, 0.1  # m/s^2, restitution, drop height of the ball's bottom, radius


def ball_drop():
    return {"name": "Drop", "gravity": [0, 0, -G], "solver": {"method": "rk4", "step": 0.001},
            "bodies": [{"name": "ball", "shape": {"type": "sphere", "radius": R}, "mass": 1.0,
                        "position": [0, 0, R + H], "restitution": XI, "staticFriction": 0.5,
                        "kineticFriction": 0.3}],
            "surfaces": [{"name": "floor", "min": [-5, -5, -1], "max": [5, 5, 0], "staticFriction": 0.5,
                          "kineticFriction": 0.3, "restitution": XI}]}


def test_early_return_at_the_impact_when_the_master_allows_it(fmu_of, tmp_path):
    """A ball dropped from H with a communication step of 1 s: fmi3DoStep returns at
    t* = sqrt(2H/g) (free fall, exact under rk4; the impact located by bisection) with
    earlyReturn, lastSuccessfulTime = t*, and the velocity already reversed by xi (both
    restitutions 0.8: their geometric mean 0.8). The master's next step starts there."""
    fmu = Fmi3(fmu_of(ball_drop(), fmi=3), tmp_path, early_return_allowed=True)
    fmu.start()
    t_star = math.sqrt(2 * H / G)
    event, terminate, early, reached = fmu.slave.doStep(0.0, 1.0)
    assert (event, terminate, early) == (False, False, True)
    assert abs(reached - t_star) < 1e-9, reached - t_star
    assert fmu.slave.getFloat64([fmu.vr["time"]]) == [reached]
    vz, z = fmu.slave.getFloat64([fmu.vr["ball.velocity[3]"], fmu.vr["ball.position[3]"]])
    assert vz == pytest.approx(XI * G * t_star, rel=1e-9)  # up, xi times the landing speed
    assert z == pytest.approx(R, abs=1e-9)
    # on from t*: the ball flies up and is in the air at 1 s (next landing at t* + 2 vz / g)
    event, terminate, early, reached = fmu.slave.doStep(reached, 1.0 - reached)
    assert (early, reached) == (False, 1.0)
    assert fmu.slave.getFloat64([fmu.vr["ball.velocity[3]"]])[0] == pytest.approx(
        XI * G * t_star - G * (1.0 - t_star), rel=1e-9)
    fmu.close()


def test_without_permission_a_step_runs_to_its_end_as_the_fmi2_fmus(fmu_of, tmp_path):
    scene = ball_drop()
    fmu3 = fmu_of(scene, fmi=3)
    assert read_model_description(str(fmu3)).coSimulation.mightReturnEarlyFromDoStep is True
    fmu = Fmi3(fmu3, tmp_path, early_return_allowed=False)
    fmu.start()
    event, terminate, early, reached = fmu.step(1.0)
    assert (event, terminate, early, reached) == (False, False, False, 1.0)
    ours = dict(zip(fmu.floats, fmu.outputs()))
    fmu.close()
    two = simulate_fmu(str(fmu_of(scene)), stop_time=1.0, output_interval=1.0)
    md = read_model_description(str(fmu3))
    compared = 0
    for v in md.modelVariables:
        if v.type == "Float64" and v.name in two.dtype.names:
            assert ours[v.valueReference] == two[v.name][-1], v.name
            compared += 1
    assert compared > 10


def fuzz(fmu_file, folder, seed, calls=400):
    """Random FMI 3 calls on one instance, the argument values drawn from normal ones,
    edge ones (0, negative, NaN, Inf, huge) and unknown references. Returns the calls
    whose answers broke a rule: a crash ends the child process instead."""
    rng = np.random.default_rng(seed)
    fmu = Fmi3(fmu_file, folder, f"fuzz{seed}", early_return_allowed=bool(seed % 2))
    s, floats = fmu.slave, fmu.floats
    method = fmu.vr["solver.method"]
    numbers = [0.0, 1.0, -1.0, 1e-3, 0.01, 1e300, -1e300, math.nan, math.inf, -math.inf, 0.5, 2.0]
    states, blobs, broken = [], [], []

    def number():
        return numbers[rng.integers(len(numbers))] if rng.random() < 0.5 else float(rng.normal(0, 3))

    def vref():
        return int(rng.choice(floats)) if rng.random() < 0.9 else int(rng.integers(len(floats), 2**32))

    actions = {
        "init": lambda: (s.enterInitializationMode(startTime=0.0), s.exitInitializationMode()),
        "step": lambda: s.doStep(fmu.time, number()),
        "step_ok": lambda: s.doStep(fmu.time, 0.01),
        "set": lambda: s.setFloat64([vref()], [number()]),
        "get": lambda: s.getFloat64(floats),
        "method": lambda: s.setInt64([method], [int(rng.integers(-2, 10))]),
        "terminate": lambda: s.terminate(),
        "reset": lambda: s.reset(),
        "get_state": lambda: states.append(s.getFMUState()),
        "set_state": lambda: states and s.setFMUState(states[rng.integers(len(states))]),
        "serialize": lambda: states and blobs.append(bytes(s.serializeFMUState(states[-1]))),
        "deserialize": lambda: s.deserializeFMUState(
            blobs[-1] if blobs and rng.random() < 0.7 else bytes(rng.integers(0, 256, 64, dtype=np.uint8))),
    }
    names = list(actions)
    for n in range(calls):
        name = names[rng.integers(len(names))]
        try:
            result = actions[name]()
        except FMICallException:
            continue  # refused: fine, if the instance lives on
        if name == "get" and not all(math.isfinite(x) for x in result):
            broken.append(f"call {n}: fmi3GetFloat64 OK with a non-finite value")
        if name in ("step", "step_ok") and result is not None:
            fmu.time = result[3]  # lastSuccessfulTime: where the next step starts
    fmu.close()
    return broken


@pytest.mark.parametrize("seed", [1, 2, 3, 4])
def test_random_calls_never_crash_and_never_answer_ok_with_nonsense(seed, fmu_of, tmp_path):
    """The abuse suite's random calls on the FMI 3 FMU, in a child process (a crash is
    a failed test, not a lost run); under scripts/sanitize.sh the child runs with the
    sanitizer runtimes too."""
    fmu_file = fmu_of(example("default.json"), fmi=3)
    child = f"""
import json, sys
sys.path.insert(0, {str(pathlib.Path(__file__).parent)!r})
from test_fmi3 import fuzz
print(json.dumps(fuzz({str(fmu_file)!r}, {str(tmp_path)!r}, {seed})))
"""
    out = subprocess.run([sys.executable, "-c", child], capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, f"exit {out.returncode}\n{out.stderr[-3000:]}"
    assert json.loads(out.stdout.strip().splitlines()[-1]) == []
