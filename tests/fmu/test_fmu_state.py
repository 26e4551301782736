"""FMU states: a run restored from a snapshot continues bitwise as the uninterrupted
run, also when the snapshot was serialised in another process; bad bytes are refused
with a message."""
import ctypes
import json
import os
import pathlib
import subprocess
import sys

import pytest
from fmpy.fmi2 import fmi2FMUstate, fmi2LastSuccessfulTime

from harness import Slave, status_of

ROOT = pathlib.Path(__file__).resolve().parents[2]
PLAYGROUND = json.loads((ROOT / "scripts" / "scenes" / "default.json").read_text())
H = 0.05


@pytest.fixture(scope="module")
def fmu(fmu_of):
    return fmu_of(PLAYGROUND)  # contacts, friction, media, collisions: the richest state


def outputs(s):
    ints = [v.valueReference for v in s.md.modelVariables if v.type in ("Integer", "Enumeration")]
    return s.all_reals() + s.slave.getInteger(ints)


def drive(s, t0, t1, force=None):
    n = round((t1 - t0) / H)
    for k in range(n):
        if force is not None:
            s.set_values({"slider.force[2]": force * (k % 3)})  # inputs change along the way
        s.slave.doStep(t0 + k * H, H)
    return outputs(s)


def test_restored_state_continues_bitwise(fmu):
    s = Slave(fmu)
    try:
        s.initialize()
        drive(s, 0.0, 1.0, force=2.0)
        state = s.slave.getFMUstate()
        straight = drive(s, 1.0, 2.0, force=3.0)
        s.slave.setFMUstate(state)
        assert s.get("time") == pytest.approx(1.0, abs=1e-12)
        assert drive(s, 1.0, 2.0, force=3.0) == straight
        s.slave.freeFMUstate(state)
    finally:
        s.close()


CHILD = r"""
import json
from rigidfmu.driver import Slave
from test_fmu_state import drive
s = Slave({fmu!r})
s.initialize()
drive(s, 0.0, 1.0, force=2.0)
state = s.slave.getFMUstate()
blob = bytes(s.slave.serializeFMUstate(state))
out = drive(s, 1.0, 2.0, force=3.0)
open({blob!r}, "wb").write(blob)
json.dump(out, open({out!r}, "w"))
"""


def test_state_serialised_in_another_process_continues_bitwise(fmu, tmp_path):
    blob, out = tmp_path / "state.bin", tmp_path / "out.json"
    code = CHILD.format(fmu=str(fmu), blob=str(blob), out=str(out))
    here = os.pathsep.join(p for p in (str(pathlib.Path(__file__).parent), os.environ.get("PYTHONPATH")) if p)
    subprocess.run([sys.executable, "-c", code], check=True, cwd=tmp_path, env=dict(os.environ, PYTHONPATH=here))
    s = Slave(fmu)
    try:
        state = s.slave.deSerializeFMUstate(blob.read_bytes())
        s.slave.setFMUstate(state)
        assert drive(s, 1.0, 2.0, force=3.0) == json.loads(out.read_text())
    finally:
        s.close()


def test_bad_serialisations_are_refused_with_a_message(fmu, fmu_of):
    import scenes
    s = Slave(fmu)
    other = Slave(fmu_of(scenes.projectile()))
    try:
        s.initialize()
        blob = bytearray(s.slave.serializeFMUstate(s.slave.getFMUstate()))

        def load(b):
            return status_of(lambda: s.slave.deSerializeFMUstate(bytes(b)))

        assert load(blob[:-3]) == "Error"
        assert "not the size of a state of this scene" in s.log.messages[-1][2]
        bad = bytearray(blob)
        bad[8] ^= 0x7F  # the format version
        assert load(bad) == "Error" and "version" in s.log.messages[-1][2]
        assert load(b"not a state at all") == "Error"
        other.initialize()
        foreign = bytes(other.slave.serializeFMUstate(other.slave.getFMUstate()))
        assert load(foreign) == "Error" and "another scene" in s.log.messages[-1][2]
        # and a pointer that is not one of its states
        bogus = fmi2FMUstate(ctypes.c_void_p(12345).value)
        assert status_of(lambda: s.slave.setFMUstate(bogus)) == "Error"
        assert "not an FMU state of this instance" in s.log.messages[-1][2]
        # the instance is still usable
        s.slave.doStep(0.0, H)
    finally:
        s.close()
        other.close()


def test_state_holds_inputs_parameters_and_machine_state(fmu):
    s = Slave(fmu)
    try:
        s.initialize()
        s.set_values({"gravity[3]": -5.0, "ball.force[1]": 7.0})
        state = s.slave.getFMUstate()
        s.set_values({"gravity[3]": -1.0, "ball.force[1]": 0.0})
        s.slave.doStep(0.0, H)
        s.slave.terminate()
        s.slave.setFMUstate(state)  # back to stepping, at t = 0
        assert s.get("gravity[3]", "ball.force[1]", "time") == [-5.0, 7.0, 0.0]
        s.slave.doStep(0.0, H)  # allowed again
    finally:
        s.close()


def test_state_holds_the_energy_audit_and_the_last_step(fmu_of, tmp_path):
    """The energy audit's sums are part of the state: explicit Euler tumbling, restored
    from bytes serialised at t = 1 s into a fresh instance, is refused at the same step
    as the uninterrupted run (a state without the sums would restart them at 0 and run
    on). The last communication step, which directional derivatives use, is too."""
    import scenes
    fmu = fmu_of(scenes.free_spin(method="euler", name="EulerTumble"))

    def until_refused(s, t0):
        for k in range(400):
            if status_of(lambda: s.slave.doStep(t0 + k * H, H)) != "OK":
                return s.slave.getRealStatus(fmi2LastSuccessfulTime)
        return None

    straight, restored = Slave(fmu), Slave(fmu)
    try:
        straight.initialize()
        for k in range(round(1.0 / H)):
            straight.slave.doStep(k * H, H)
        blob = bytes(straight.slave.serializeFMUstate(straight.slave.getFMUstate()))
        dv = straight.slave.getDirectionalDerivative(straight.vr(["spinner.angularVelocity[1]"]),
                                                     straight.vr(["spinner.torque[1]"]), [1.0])
        refused_at = until_refused(straight, 1.0)
        assert refused_at is not None and refused_at > 1.0
        state = restored.slave.deSerializeFMUstate(blob)
        restored.slave.setFMUstate(state)
        assert restored.slave.getDirectionalDerivative(restored.vr(["spinner.angularVelocity[1]"]),
                                                       restored.vr(["spinner.torque[1]"]), [1.0]) == dv
        assert until_refused(restored, 1.0) == refused_at
    finally:
        straight.close()
        restored.close()


def test_a_conveyors_belt_its_rate_and_start_value_are_in_the_state(fmu_of):
    """On a conveyor (the belt's start value set before initialisation, the belt turned
    and its input derivative set mid-run, the box sliding towards the new belt speed), a
    state restored, and one serialised and read into a fresh instance, continue bitwise;
    the state holds the belt's input, the rate the next step spends, and its start value.
    fmi2Reset returns the belt to the scene's value."""
    import scenes
    fmu = fmu_of(scenes.conveyor("Conveyor", [1.0, 0.0, 0.0]))
    belt = [f"belt.beltVelocity[{i}]" for i in (1, 2, 3)]

    def run(s, t0):
        for k in range(20):
            if k % 5 == 4:
                s.set_values({"belt.beltVelocity[3]": 0.1 * k})  # the belt's normal part: no effect
            s.slave.doStep(t0 + k * H, H)
        return outputs(s)

    s, fresh = Slave(fmu), Slave(fmu)
    try:
        s.initialize({"belt.beltVelocity[2]": 0.25})
        for k in range(6):
            s.slave.doStep(k * H, H)
        s.set_values({"belt.beltVelocity[1]": -0.5})
        s.slave.setRealInputDerivatives(s.vr(["belt.beltVelocity[2]"]), [1], [2.0])
        state = s.slave.getFMUstate()
        blob = bytes(s.slave.serializeFMUstate(state))
        straight = run(s, 6 * H)
        s.slave.setFMUstate(state)
        assert s.get(*belt) == [-0.5, 0.25, 0.0]
        assert run(s, 6 * H) == straight
        fresh.slave.setFMUstate(fresh.slave.deSerializeFMUstate(blob))
        assert run(fresh, 6 * H) == straight
        s.slave.reset()
        s.initialize()
        assert s.get(*belt) == [1.0, 0.0, 0.0]  # the scene's start value, not the one set
    finally:
        s.close()
        fresh.close()
