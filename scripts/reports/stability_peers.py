"""MuJoCo beside the stress suite's fast-spin case (scripts/reports/stability.py): the same torque-free
symmetric top, principal inertia (2, 2, 3) kg m^2, omega0 30 deg off its axis with
|omega| = (h |omega|) / h, h = 1e-2 s, 1e4 steps, no gravity, for h |omega| in
{0.1, 1, 3, 6}, with MuJoCo's Euler, RK4 and implicit integrators. Per run: energy drift
max |E - E0| / E0 (1/2 omega_b . I omega_b, every 100 steps), max | |q| - 1 |, the
rotation angle at T against the closed-form regular precession, whether MuJoCo warned
(mjWARN_BADQACC: it then resets the state by itself) or produced a non-finite state,
and the wall time. Run with the peers' venv (.venv-peers/bin/python); writes JSON for
stress.py: {case key: {rigidfmu method: text}, "_about": text, "runs": [...]}.

usage: python -m reports.stability_peers --out FILE [--quick]"""
import argparse
import json
import math
import time

import mujoco
import numpy as np

from reports.mujoco_free_body import free_body_model
from rigidfmu.references.quaternion import quat_axis_angle, quat_mul
from rigidfmu.references.quaternion import rotation_angle as angle

I = np.array([2.0, 2.0, 3.0])
H = 1e-2
STEPS = 10000
LEVELS = (0.1, 1.0, 3.0, 6.0)
INTEGRATORS = ("Euler", "RK4", "implicit")
# which rigidfmu method's row a MuJoCo integrator is shown beside
BESIDE = {"Euler": ("euler", "symplecticEuler"), "RK4": ("rk4", "lieRk4"),
          "implicit": ("rosenbrock",)}


def symmetric_top(w, t):
    L = I * w
    Omega = (I[2] - I[0]) / I[0] * w[2]
    return quat_mul(quat_axis_angle(L, np.linalg.norm(L) * t / I[0]), quat_axis_angle([0, 0, 1], -Omega * t))


def run(integrator, hw):
    model = free_body_model(I, H, integrator)
    data = mujoco.MjData(model)
    w = hw / H * np.array([math.sin(math.radians(30)), 0.0, math.cos(math.radians(30))])
    data.qvel[3:6] = w  # body frame (= world at t = 0)
    E0 = 0.5 * float(w @ (I * w))
    drift, qdev, finite = 0.0, 0.0, True
    start = time.perf_counter()
    for k in range(1, STEPS + 1):
        mujoco.mj_step(model, data)
        if k % 100 == 0:
            wb = np.array(data.qvel[3:6])
            q = np.array(data.qpos[3:7])
            if not (np.all(np.isfinite(wb)) and np.all(np.isfinite(q))):
                finite = False
                break
            drift = max(drift, abs(0.5 * float(wb @ (I * wb)) - E0) / E0)
            qdev = max(qdev, abs(float(np.linalg.norm(q)) - 1.0))
    seconds = time.perf_counter() - start
    warnings = int(data.warning[mujoco.mjtWarning.mjWARN_BADQACC].number)
    err = angle(np.array(data.qpos[3:7]), symmetric_top(w, STEPS * H)) if finite else float("nan")
    return {"integrator": integrator, "hw": hw, "drift": drift, "qnorm": qdev, "error": err,
            "finite": finite, "badqacc_warnings": warnings, "seconds": seconds,
            "version": mujoco.__version__}


def text(r):
    s = f"MuJoCo {r['integrator']}: drift {r['drift']:.2g}, θ(T) {r['error']:.3g} rad, {r['seconds'] * 1e3:.0f} ms"
    if not r["finite"]:
        s += ", non-finite state"
    if r["badqacc_warnings"]:
        s += f", {r['badqacc_warnings']} bad-acceleration warnings (state reset)"
    return s


def main(argv=None, prog=None):
    p = argparse.ArgumentParser(prog=prog, description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", required=True)
    p.add_argument("--quick", action="store_true", help="accepted for symmetry; the runs are short anyway")
    args = p.parse_args(argv)
    runs = [run(i, hw) for hw in LEVELS for i in INTEGRATORS]
    out = {"runs": runs}
    for r in runs:
        key = f"fast-spin-hw{r['hw']:g}"
        for method in BESIDE[r["integrator"]]:
            out.setdefault(key, {})[method] = text(r)
    lines = [f"MuJoCo {mujoco.__version__} (PyPI, `.venv-peers`) on the fast-spin case: the same symmetric top, "
             f"h = {H:g} s, {STEPS} steps (`scripts/reports/stability_peers.py`). "
             "MuJoCo integrates the free joint's quaternion by the exact exponential of the body angular "
             "velocity and keeps it unit; its Euler is semi-implicit (velocity first). "
             "Shown beside the rigidfmu method of the same family (Euler beside euler and symplecticEuler, "
             "RK4 beside rk4 and lieRk4, implicit beside rosenbrock when the FMU has it).", "",
             "| h·\\|ω\\| | integrator | energy drift | max \\|q\\|−1 | θ(T) (rad) | finite "
             "| bad-acceleration warnings | run time |",
             "|---:|---|---:|---:|---:|---|---:|---:|"]
    for r in runs:
        lines.append(f"| {r['hw']:g} | {r['integrator']} | {r['drift']:.2g} | {r['qnorm']:.2g} | {r['error']:.3g} | "
                     f"{'yes' if r['finite'] else 'no'} | {r['badqacc_warnings']} | {r['seconds'] * 1e3:.0f} ms |")
    out["_about"] = "\n".join(lines)
    with open(args.out, "w") as f:
        json.dump(out, f, indent=1)
    for r in runs:
        print(text(r) + f" (h·|ω| = {r['hw']:g})")


if __name__ == "__main__":
    main()
