"""The same results in every importer (issue 40): importers reach a communication point
in different ways, fmpy's simulate_fmu (t0 + n h, its step the difference of two such
points), a loop of doStep(k h, h), one that sums t += h, one that steps by (t + h) - t.
They differ in the last bits, and a resting contact would make those bits into
different forces and positions. The FMU keeps its own time on its grid
(fmu/communication_clock.h), so all four give the same outputs, bitwise, FMI 2 and 3."""
import os
import pathlib

import numpy as np
import pytest
from fmpy import extract, instantiate_fmu, read_model_description, simulate_fmu

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = sorted(p.name for p in (ROOT / "scripts" / "scenes").glob("*.json"))
H = 0.01  # s: not a binary fraction, so that the schemes' times differ in their last bits
STOP = 2.0  # s
# Under the sanitizers (scripts/sanitize.sh) the resting scene alone: this is arithmetic, not memory.
SANITIZED = os.environ.get("RIGIDFMU_SANITIZED") == "1"

# A box resting on a floor and a ball rolling on it: resting contacts, whose forces
# turn a step's last bits into visible differences.
RESTING = {
    "name": "Resting",
    "solver": {"method": "rk4", "step": 0.001},
    "bodies": [
        {"name": "box", "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "mass": 2.0,
         "position": [0, 0, 0.1]},
        {"name": "ball", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1.0,
         "position": [1, 0, 0.1], "velocity": [0.3, 0, 0]},
    ],
    "surfaces": [{"name": "floor", "min": [-5, -5, -1], "max": [5, 5, 0]}],
}


def step_by_grid(k, t):
    return k * H, H


def step_by_sum(k, t):
    return t, H


def step_by_difference(k, t):
    return t, (t + H) - t


SCHEMES = {"doStep(k*h, h)": step_by_grid, "t += h": step_by_sum, "(t+h) - t": step_by_difference}


def run_loop(fmu, scheme, fmi):
    """Every Real output at every communication point of a loop that steps as `scheme`."""
    md = read_model_description(str(fmu))
    outputs = [v.valueReference for v in md.modelVariables if v.causality == "output" and v.type in ("Real", "Float64")]
    unzipped = extract(str(fmu))
    slave = instantiate_fmu(unzipped, md, fmi_type="CoSimulation")
    try:
        if fmi == 2:
            slave.setupExperiment(startTime=0.0)
            slave.enterInitializationMode()
        else:
            slave.enterInitializationMode(startTime=0.0)
        slave.exitInitializationMode()
        get = slave.getReal if fmi == 2 else slave.getFloat64
        rows, t = [get(outputs)], 0.0
        for k in range(round(STOP / H)):
            tc, h = scheme(k, t)
            slave.doStep(tc, h)
            t = tc + h
            rows.append(get(outputs))
        return np.array(rows)
    finally:
        slave.terminate()
        slave.freeInstance()


def run_simulate_fmu(fmu):
    """The same outputs as fmpy's simulate_fmu records them."""
    md = read_model_description(str(fmu))
    names = [v.name for v in md.modelVariables if v.causality == "output" and v.type in ("Real", "Float64")]
    result = simulate_fmu(str(fmu), stop_time=STOP, output_interval=H, output=names)
    return np.column_stack([result[n] for n in names])


def scenes():
    examples = [] if SANITIZED else EXAMPLES
    return [(name, ROOT / "scripts" / "scenes" / name) for name in examples] + [
        ("resting", RESTING)]


@pytest.mark.parametrize("fmi", [2, 3])
@pytest.mark.parametrize("name,scene", scenes(), ids=[name for name, _ in scenes()])
def test_every_way_of_stepping_gives_the_same_outputs_bitwise(name, scene, fmi, fmu_of):
    fmu = fmu_of(scene, fmi=fmi)
    runs = {label: run_loop(fmu, scheme, fmi) for label, scheme in SCHEMES.items()}
    runs["simulate_fmu"] = run_simulate_fmu(fmu)
    reference = runs["doStep(k*h, h)"]
    assert np.isfinite(reference).all()
    for label, run in runs.items():
        assert run.shape == reference.shape, label
        differ = np.flatnonzero((run.view(np.uint64) != reference.view(np.uint64)).any(axis=1))
        assert differ.size == 0, (
            f"{name}, FMI {fmi}: {label} first differs from doStep(k*h, h) at t = {differ[0] * H:.2f} s, "
            f"by up to {np.abs(run - reference).max():.3g}")


def test_the_schemes_do_send_different_steps():
    """The schemes are not all the same numbers (else the test above shows nothing)."""
    steps = {label: [] for label in SCHEMES}
    for label, scheme in SCHEMES.items():
        t = 0.0
        for k in range(round(STOP / H)):
            tc, h = scheme(k, t)
            steps[label].append((tc, h))
            t = tc + h
    grid, summed, differenced = (np.array(steps[label]) for label in SCHEMES)
    assert (grid[:, 0] != summed[:, 0]).any()
    assert (grid[:, 1] != differenced[:, 1]).any()
