"""MuJoCo on the torque-free body of the accuracy report: principal inertia (1, 2, 3)
kg m^2, omega0 = (0.01, 5, 0.01) rad/s (near the intermediate axis), T = 20 s, no
gravity. For each of MuJoCo's integrators and time steps: the orientation error at T
(rotation angle, rad) against scipy's DOP853 at rtol 1e-12 on Euler's equations, and
the wall time per step and per simulated second (median of 5 runs). Writes JSON for
report_accuracy.py to put on its diagrams.

usage: python -m reports.accuracy_peers [--quick] [--out FILE]"""
import argparse
import json
import pathlib
import statistics
import time

import mujoco
import numpy as np

from reports.mujoco_free_body import free_body_model
from rigidfmu.native import SOURCE_ROOT
from rigidfmu.references.quaternion import rotation_angle as angle
from rigidfmu.references.torque_free import torque_free_reference

I = np.array([1.0, 2.0, 3.0])
W0 = np.array([0.01, 5.0, 0.01])
T = 20.0

def run(integrator, dt):
    model = free_body_model(I, dt, integrator)
    data = mujoco.MjData(model)
    data.qvel[3:6] = W0  # a free joint's angular velocity is in the body frame (= world at t = 0)
    n = round(T / dt)
    start = time.perf_counter()
    for _ in range(n):
        mujoco.mj_step(model, data)
    seconds = time.perf_counter() - start
    return np.array(data.qpos[3:7]), seconds / n


def main(argv=None, prog=None):
    p = argparse.ArgumentParser(prog=prog, description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true")
    p.add_argument("--out", default=str(SOURCE_ROOT / "docs" / "reports" / "peers.json"))
    args = p.parse_args(argv)
    q_ref = torque_free_reference(I, W0, T)
    rows = []
    steps = (1e-2, 1e-3) if not args.quick else (1e-2,)
    repeats = 1 if args.quick else 5
    for integrator in ("RK4", "Euler", "implicitfast"):
        for dt in steps:
            runs = [run(integrator, dt) for _ in range(repeats)]
            q = runs[0][0]
            per_step = statistics.median(r[1] for r in runs)
            rows.append({"engine": f"MuJoCo {mujoco.__version__}", "method": integrator,
                         "problem": "torque-free, intermediate axis", "dt": dt, "error": float(angle(q, q_ref)),
                         "us_per_step": per_step * 1e6, "s_per_simulated_s": per_step / dt})
            print(f"MuJoCo {integrator:12s} dt={dt:g}: error {rows[-1]['error']:.3g} rad, "
                  f"{per_step * 1e6:.2f} us/step, {per_step / dt:.3g} s per simulated s")
    pathlib.Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    pathlib.Path(args.out).write_text(json.dumps(rows, indent=1))
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
