"""Simulates an FMU with fmpy; writes the result as CSV and, on request, the run's
plots (every body's position and velocity, the mechanical energy with what was
dissipated, the contact events: rigidfmu.plots). The CSV holds every output and the
driven bodies' pose inputs (rigidfmu.driven), so that the replay draws them where they
are; without a master those stay at their start values."""
import json
import pathlib
import zipfile

import numpy as np
from fmpy import read_model_description, simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.util import write_csv

from rigidfmu import driven
from rigidfmu.errors import SimulationError


def scene_of(fmu) -> dict:
    """The scene the FMU was built from (its resources/scene.json)."""
    with zipfile.ZipFile(fmu) as z:
        return json.loads(z.read("resources/scene.json"))


def start_values(md) -> dict:
    return {v.name: float(v.start) for v in md.modelVariables if v.start is not None and v.type == "Real"}


def recorded(md, scene) -> list:
    """The variables the CSV holds, in the model description's order: every output and
    the driven bodies' pose inputs."""
    poses = set(driven.pose_inputs(scene))
    return [v.name for v in md.modelVariables if v.causality == "output" or v.name in poses]


def masses_of(md, scene) -> dict:
    """kg, of the free bodies: a driven body has none."""
    start = start_values(md)
    return {b["name"]: start[f"{b['name']}.mass"] for b in scene["bodies"] if not driven.is_driven(b)}


def simulate(fmu: pathlib.Path, out_dir: pathlib.Path, stop_time: float = 5.0, output_interval: float = 0.01,
             plot: bool = False) -> list[pathlib.Path]:
    """Runs the FMU from 0 to stop_time; returns the files written (CSV first)."""
    out_dir.mkdir(parents=True, exist_ok=True)
    md = read_model_description(str(fmu))
    scene = scene_of(fmu)
    try:
        result = simulate_fmu(str(fmu), stop_time=stop_time, output_interval=output_interval,
                              output=recorded(md, scene) or None)
    except FMICallException as e:
        raise SimulationError(f"{fmu.name}: {e}") from e
    csv = out_dir / f"{fmu.stem}.csv"
    write_csv(str(csv), result)
    files = [csv]
    if plot:
        from rigidfmu.plots import plot_run  # matplotlib only when plots are wanted

        start = start_values(md)
        g = np.array([start[f"gravity[{i}]"] for i in (1, 2, 3)])
        files += plot_run(result, scene, masses_of(md, scene), g, out_dir, fmu.stem)
    return files
