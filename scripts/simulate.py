"""Simulates an FMU with fmpy; writes the result as CSV and the run's plots: every
body's position and velocity, the mechanical energy with what was dissipated, and the
contact events (scripts/run_plots.py)."""
import argparse
import json
import pathlib
import zipfile

import numpy as np
from fmpy import read_model_description, simulate_fmu
from fmpy.util import write_csv

from run_plots import plot_run


def scene_of(fmu):
    """The scene the FMU was built from (its resources/scene.json)."""
    with zipfile.ZipFile(fmu) as z:
        return json.loads(z.read("resources/scene.json"))


def start_values(md):
    return {v.name: float(v.start) for v in md.modelVariables if v.start is not None and v.type == "Real"}


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("fmu")
    parser.add_argument("--stop-time", type=float, default=5.0)
    parser.add_argument("--output-interval", type=float, default=0.01)
    parser.add_argument("--out", default="out")
    args = parser.parse_args()
    out_dir = pathlib.Path(args.out)
    out_dir.mkdir(parents=True, exist_ok=True)
    md = read_model_description(args.fmu)
    scene = scene_of(args.fmu)
    start = start_values(md)
    masses = {b["name"]: start[f"{b['name']}.mass"] for b in scene["bodies"]}
    g = np.array([start[f"gravity[{i}]"] for i in (1, 2, 3)])
    name = pathlib.Path(args.fmu).stem
    result = simulate_fmu(args.fmu, stop_time=args.stop_time, output_interval=args.output_interval)
    csv = out_dir / f"{name}.csv"
    write_csv(str(csv), result)
    files = plot_run(result, scene, masses, g, out_dir, name)
    print(f"{md.modelName}: simulated {args.stop_time} s, {len(scene['bodies'])} bodies")
    for f in [csv, *files]:
        print(f"  wrote {f}")


if __name__ == "__main__":
    main()
