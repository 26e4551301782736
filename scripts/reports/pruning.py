"""Cost of absent features: ns per body-step of one free body (rk4, h = 1 ms)
- in the bare integrator (C++, no FMI, no optional module): the baseline,
- in a gravity-only FMU (the pruned binary),
- in an FMU whose scene has every feature (surface, medium, collisions) present but
  far away from the body,
run side by side in one process and printed as ratios to the baseline. The FMUs are
stepped with 1 s communication steps (1000 internal steps) so that the FMI call is
amortised. Figures only: nothing here is asserted.

usage: scripts/report.sh pruning [--quick] [--build BUILD_DIR]"""
import argparse
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile

from reports.fmu_timing import seconds_per_internal_step
from rigidfmu.native import SOURCE_ROOT

ROOT = SOURCE_ROOT  # the source tree: its build, scripts and docs

BODY = {"name": "ball", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1.0,
        "position": [0, 0, 1000.0], "velocity": [1, 2, 3], "angularVelocity": [0.1, 2, 0.3]}


def scenes():
    bare = {"name": "GravityOnly", "solver": {"method": "rk4", "step": 1e-3}, "bodies": [BODY]}
    far = json.loads(json.dumps(bare))
    far["name"] = "EverythingFarAway"
    far["surfaces"] = [{"name": "floor", "min": [-5e4, -5e4, -5e4 - 1], "max": [-4e4, -4e4, -5e4]}]
    far["media"] = [{"name": "pool", "type": "water", "min": [4e4, 4e4, -5e4], "max": [5e4, 5e4, -4e4]}]
    return {"gravity-only FMU": bare, "every feature, far away": far}


def build(scene, folder, build_dir):
    path = pathlib.Path(folder, scene["name"] + ".json")
    path.write_text(json.dumps(scene))
    fmu = pathlib.Path(folder, scene["name"] + ".fmu")
    subprocess.run([str(ROOT / "scripts" / "build_fmu.sh"), str(path), str(fmu)], check=True,
                   stdout=subprocess.DEVNULL, env=dict(os.environ, RIGIDFMU_SKIP_SETUP="1",
                                                      RIGIDFMU_BUILD=str(build_dir)))
    return fmu


def fmu_ns_per_step(fmu, seconds, repeats):
    return seconds_per_internal_step(fmu, 1.0, seconds, repeats) * 1e9


def bare_ns_per_step(build_dir, steps, repeats):
    runs = []
    for _ in range(repeats):
        out = subprocess.run([str(build_dir / "rigid-bench-step"), str(steps)], check=True,
                             capture_output=True, text=True).stdout
        runs.append(float(out.split()[0]))
    return statistics.median(runs)


def main(argv=None, prog=None):
    p = argparse.ArgumentParser(prog=prog, description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true", help="short runs (for the test suite)")
    p.add_argument("--build", default=os.environ.get("RIGIDFMU_BUILD", ROOT / "build"))
    args = p.parse_args(argv)
    build_dir = pathlib.Path(args.build)
    subprocess.run(["/usr/bin/cmake", "--build", str(build_dir), "--target", "rigid-bench-step"],
                   check=True, stdout=subprocess.DEVNULL)
    seconds, steps, repeats = (2, 200000, 3) if args.quick else (20, 2000000, 7)
    with tempfile.TemporaryDirectory() as folder:
        fmus = {label: build(s, folder, build_dir) for label, s in scenes().items()}
        base = bare_ns_per_step(build_dir, steps, repeats)
        rows = [("bare integrator (C++)", base)]
        rows += [(label, fmu_ns_per_step(f, seconds, repeats)) for label, f in fmus.items()]
    print(f"one free body, rk4, h = 1 ms; median of {repeats} runs")
    print(f"{'':28s} {'ns/body-step':>13s} {'ratio':>7s}")
    for label, ns in rows:
        print(f"{label:28s} {ns:13.1f} {ns / base:7.3f}")
    print("target: gravity-only FMU within 1.10 of the bare integrator")
    return 0


if __name__ == "__main__":
    sys.exit(main(prog="scripts/report.sh pruning"))
