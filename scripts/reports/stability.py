"""Stability stress suite of the FMU: every case run with every integration method of
the Enumeration `SolverMethod` (read from the modelDescription, so that methods added
later are run without changing this script), each run judged by the criteria written
below with the case, and the results written as a table (DIR/stability.md).

A case is a scene (a dict in the scene format), how it is driven (communication step,
stop time, start values, optionally an fmpy master that closes a loop through the
FMU's inputs) and its criteria. Every run ends in one of:

  holds        every criterion met, every step fmi2OK;
  sub-stepped  every criterion met, and the FMU took more internal steps than
               T / solver.step (output `solver.steps`, summed over the communication
               steps) or said it sub-stepped (a Warning, or a logEvents message about
               sub-steps);
  refused      fmi2Discard / fmi2Error with a message through the FMI logger (kept in
               the table), before any criterion was broken while fmi2OK;
  FAILS        a non-finite output after fmi2OK, a criterion broken while fmi2OK
               (an energy blow-up reported as fmi2OK is one), a refusal without a
               message, or non-finite outputs after a refusal.

Criteria checked at every communication point ("while OK") and at the end are listed
per case in the written table. For every run the table also gives the error against a
reference computed here (closed forms, or scipy's DOP853 at rtol 1e-12 on the problem's
own equations), the energy drift, |q| - 1 and the run time of the stepping.

usage:
  scripts/stress.sh [--out DIR]  the full suite (1e7 steps, long runs, MuJoCo beside
                                   the fast-spin case when .venv-peers is there);
                                   writes DIR/stability.md (default docs/reports/)
  scripts/stress.sh --quick [--out DIR]  every case with every method, short runs
  options: --build DIR (default $RIGIDFMU_BUILD or build/), --no-build, --only SUBSTRING
           (cases whose key contains it), --no-peers, --jobs N

Exit status 1 when any run FAILS, 0 otherwise."""
import argparse
import json
import math
import os
import pathlib
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from reports import template
from reports.fmu_build import ensure_core, package
from reports.provenance import source_state
from rigidfmu import driver
from rigidfmu.errors import ReportError
from rigidfmu.native import SOURCE_ROOT
from rigidfmu.references.heave import heave
from rigidfmu.references.quaternion import quat_axis_angle, quat_mul, rotation_angle
from rigidfmu.references.torque_free import torque_free_reference
from rigidfmu.scenes import G, body, free_spin, scene

ROOT = SOURCE_ROOT  # the source tree: its build, scripts and docs
RHO_WATER, MU_WATER = 998.2, 1.002e-3  # the "water" type (README)

OUTCOMES = ("holds", "sub-stepped", "refused", "FAILS")

# Methods known to integrate a constant force exactly (error = rounding): the
# projectile bounds below are the first-order truncation bound for every other method.
EXACT_FOR_CONSTANT_FORCE = {"rk4", "lieRk4", "splitting", "dopri5"}
ADAPTIVE_NAMES = {"dopri5", "dopri45", "rk45", "rkf45", "cashkarp", "bs23"}
QNORM_BOUND = 1e-12
# The adaptive methods run at this solver.tolerance (their default, 1e-6, is a local
# error per step: over 1e4 steps it does not give the 1e-3 energy or 1e-6 terminal
# velocity asked of every method here).
ADAPTIVE_TOLERANCE = 1e-9
REPEATS = 3  # full mode: run time = median of 3 runs (quick mode: 1 run)


# ----------------------------------------------------------------------------------
# quaternions and references

def symmetric_top(inertia, omega0, t):
    """Torque-free body with two equal principal moments (any axis a the odd one),
    identity orientation at 0 (omega0 is then also the body-frame value): regular
    precession, q(t) = rot(L, |L| t / I_perp) * rot(e_a, -Omega t),
    Omega = (I_a - I_perp) / I_perp * omega_a."""
    I = np.asarray(inertia, dtype=float)
    a = next(i for i in range(3) if I[(i + 1) % 3] == I[(i + 2) % 3])
    Ip = I[(a + 1) % 3]
    w = np.asarray(omega0, dtype=float)
    L = I * w
    Omega = (I[a] - Ip) / Ip * w[a]
    e = np.zeros(3)
    e[a] = 1.0
    return quat_mul(quat_axis_angle(L, np.linalg.norm(L) * t / Ip), quat_axis_angle(e, -Omega * t))


_HEAVE_CACHE = {}


def heave_dop853(m, size, z0, T, times):
    key = (m, tuple(size), z0, T, len(times))
    if key not in _HEAVE_CACHE:
        _HEAVE_CACHE[key] = heave(m, size, z0, times)
    return _HEAVE_CACHE[key]


# ----------------------------------------------------------------------------------
# scenes

def spinner_scene(name, inertia, omega, step=1e-3):
    return free_spin(inertia, omega, step=step, name=name, body_name="b")


# ----------------------------------------------------------------------------------
# loading FMUs (built by reports.fmu_build) and running them (rigidfmu.driver)

class Recorder(driver.Recorder):
    """The driver's logger keeping the first `cap` messages, and besides them the first
    `cap` failure messages and every message about sub-steps (counted, the first `cap`
    kept), so that a chatty FMU costs no memory."""

    SUBSTEP = re.compile(r"sub-?step|substep", re.I)

    def __init__(self, cap=50):
        super().__init__(cap)
        self.substeps = []     # sub-step messages, first `cap`
        self.substep_count = 0
        self.failures = []     # Discard / Error / Fatal messages, first `cap`

    def note(self, st, cat, msg):
        super().note(st, cat, msg)
        if st in driver.FAILED and len(self.failures) < self.cap:
            self.failures.append(msg)
        if st == "Warning" or (cat == "logEvents" and self.SUBSTEP.search(msg)):
            self.substep_count += 1
            if len(self.substeps) < self.cap:
                self.substeps.append(f"[{st}] {cat}: {msg}")


class Model(driver.Fmu):
    """One FMU: its methods, variables and one extracted copy."""

    def __init__(self, fmu, folder):
        super().__init__(fmu, folder=folder, prefix="stress-")
        self.methods = self.methods()
        self.outputs = [v.name for v in self.real_outputs()]
        self.steps_var = self.vars.get("solver.steps")
        self.categories = self.log_categories()


def discover_methods(build, folder):
    """[(name, value, description)] of the Enumeration SolverMethod, from a probe FMU."""
    probe = Model(package(build, folder, spinner_scene("Probe", (1, 2, 3), (0, 0, 1))), folder)
    if not probe.methods:
        raise ReportError("report stability: no Enumeration SolverMethod in the modelDescription")
    return probe.methods, "solver.tolerance" in probe.vars


# ----------------------------------------------------------------------------------
# one run

class Trace(driver.Trace):
    """What one run produced: outputs at every communication point reached with
    fmi2OK (row 0: after initialisation), the status of the last call and its message."""

    def __init__(self, names):
        super().__init__(names)
        self.status = "OK"
        self.message = ""
        self.failed_call = ""
        self.terminated = None
        self.last_successful = None
        self.after_failure_finite = None
        self.nonfinite = None         # (time, variable) of the first non-finite OK output
        self.steps = 0                # sum of solver.steps
        self.nominal = 0              # sum of ceil(H / solver.step)
        self.has_steps = False
        self.substep_messages = []
        self.substep_count = 0
        self.warnings = 0
        self.wall = 0.0
        self.extra = {}

    @property
    def complete(self):
        return self.status == "OK"


def run_fmu(model, method_value, T, H, start=None, master=None, stop=None, label="run"):
    """Runs one instance from 0 to T in communication steps H (the last one shortened).
    master(t, outputs dict) -> {input name: value} is called before every step;
    stop(trace) -> True ends the run early (after a step)."""
    from fmpy.fmi1 import FMICallException
    from fmpy.fmi2 import fmi2LastSuccessfulTime, fmi2Terminated
    rec = Recorder()
    instance = driver.Slave(model, label, recorder=rec, logging_on=True)
    slave = instance.slave
    tr = Trace(model.outputs)
    if "logEvents" in model.categories:
        slave.setDebugLogging(True, ["logEvents"])
    else:
        slave.setDebugLogging(False, [])
    step = float((start or {}).get("solver.step", model.vars["solver.step"].start))
    tr.has_steps = model.steps_var is not None
    steps_vr = [model.steps_var.valueReference] if tr.has_steps else None
    n = max(1, int(math.ceil(T / H - 1e-9)))

    def read(t):
        arr = tr.sample(instance, t)
        if tr.nonfinite is None and not np.all(np.isfinite(arr)):
            bad = model.outputs[int(np.argmin(np.isfinite(arr)))]
            tr.nonfinite = (t, bad)
        return arr

    call = "setup"
    try:
        instance.initialize(dict({"solver.method": method_value}, **(start or {})))
        read(0.0)
        t0 = time.perf_counter()
        for k in range(n):
            t = k * H
            h = min(H, T - t) if k == n - 1 else H
            if master is not None:
                call = f"fmi2SetReal (master's inputs at t = {t:g} s)"
                instance.set_values(master(t, dict(zip(model.outputs, tr.rows[-1]))))
            call = f"fmi2DoStep({t:g}, {h:g})"
            instance.step(h, t)
            tr.nominal += max(1, int(math.ceil(h / step - 1e-9)))
            if steps_vr:
                tr.steps += slave.getInteger(steps_vr)[0]
            read(t + h)
            if stop is not None and stop(tr):
                break
        tr.wall = time.perf_counter() - t0
    except FMICallException as e:
        tr.wall = time.perf_counter() - t0 if "t0" in locals() else 0.0
        tr.status = driver.status_name(e.status)
        tr.failed_call = call
        tr.message = rec.failures[-1] if rec.failures else ""
        try:
            tr.terminated = bool(slave.getBooleanStatus(fmi2Terminated))
        except Exception:
            tr.terminated = None
        try:
            tr.last_successful = float(slave.getRealStatus(fmi2LastSuccessfulTime))
        except Exception:
            tr.last_successful = None
        try:
            after = np.array(instance.get(*model.outputs), dtype=float)
            tr.after_failure_finite = bool(np.all(np.isfinite(after)))
        except Exception:
            tr.after_failure_finite = None
    finally:
        try:
            instance.free()
        except Exception:
            pass
    tr.substep_messages = rec.substeps
    tr.substep_count = rec.substep_count
    tr.warnings = rec.counts.get("Warning", 0)
    tr.finish()
    return tr


# ----------------------------------------------------------------------------------
# energy and conservation

def body_names(scene_dict):
    return [b["name"] for b in scene_dict["bodies"]]


def energy(tr, scene_dict, masses=None, gravity=True):
    """Kinetic (1/2 m v^2 + 1/2 omega . L) plus gravitational potential of all bodies."""
    g = np.asarray(scene_dict.get("gravity", [0, 0, -G]), dtype=float) if gravity else np.zeros(3)
    E = 0.0
    for b in scene_dict["bodies"]:
        n = b["name"]
        m = (masses or {}).get(n, b["mass"])
        v, w, L, x = (tr.vec(f"{n}.velocity"), tr.vec(f"{n}.angularVelocity"), tr.vec(f"{n}.angularMomentum"),
                      tr.vec(f"{n}.position"))
        E = E + 0.5 * m * np.sum(v * v, axis=1) + 0.5 * np.sum(w * L, axis=1) - m * (x @ g)
    return E


def rot_energy(tr, n):
    return 0.5 * np.sum(tr.vec(f"{n}.angularVelocity") * tr.vec(f"{n}.angularMomentum"), axis=1)


def qnorm_dev(tr, scene_dict):
    worst = 0.0
    for n in body_names(scene_dict):
        if f"{n}.orientation[1]" in tr.index and len(tr.t):
            worst = max(worst, float(np.max(np.abs(np.linalg.norm(tr.vec(f"{n}.orientation", 4), axis=1) - 1.0))))
    return worst


def first_time(tr, mask):
    idx = np.flatnonzero(mask)
    return float(tr.t[idx[0]]) if len(idx) else None


# ----------------------------------------------------------------------------------
# cases

class Case:
    """A scene, how to drive it, and its criteria.

    judge(tr, method) -> dict with
      'ok_violations': criteria broken at a communication point reached with fmi2OK
                       (each a string; checked on every run, also before a refusal);
      'end_violations': criteria on the whole run (checked only if it completed);
      'error': text; 'drift': float or None (energy drift, as defined by the case)."""

    def __init__(self, key, group, title, scene_dict, T, H, criteria, judge, start=None,
                 conservative=False, driver=None, step=None):
        self.key, self.group, self.title = key, group, title
        self.scene = scene_dict
        self.T, self.H = T, H
        self.criteria = criteria
        self.judge = judge
        self.start = dict(start or {})
        self.step = step if step is not None else scene_dict["solver"]["step"]
        if step is not None:
            self.start["solver.step"] = step
        self.driver = driver


def drift_check(E, E0, scale, bound, tr, label="energy", one_sided=False):
    """The drift (signed, the value of largest magnitude; for one_sided the largest
    gain) and the violation (if any) at the first point beyond bound."""
    d = (E - E0) / scale
    series = d if one_sided else np.abs(d)
    viol = []
    if not len(d):
        return 0.0, viol
    worst = float(np.max(d)) if one_sided else float(d[int(np.argmax(np.abs(d)))])
    bad = np.flatnonzero(~(series <= bound))
    if len(bad):
        k = bad[0]
        what = "gain" if one_sided else "drift"
        viol.append(f"{label} {what} {d[k]:+.3g} beyond {bound:g} at t = {tr.t[k]:g} s"
                    + (f" (worst {worst:+.3g})" if abs(worst) > abs(d[k]) else ""))
    return worst, viol


def spin_case(key, title, inertia, omega, step, T, H, reference, criteria_extra=""):
    s = spinner_scene("Spin", inertia, (0.0, 0.0, 1.0), step=1e-3)  # omega: start values
    start = {f"b.angularVelocity[{i + 1}]": omega[i] for i in range(3)}

    def judge(tr, method):
        E = rot_energy(tr, "b")
        E0 = E[0]
        drift, viol = drift_check(E, E0, E0, 1e-3, tr)
        Lw = np.linalg.norm(tr.vec("b.angularMomentum"), axis=1)
        ldrift = float(np.max(np.abs(Lw - Lw[0]) / Lw[0]))
        if not ldrift <= 1e-3:
            k = np.flatnonzero(~(np.abs(Lw - Lw[0]) / Lw[0] <= 1e-3))[0]
            viol.append(f"|L| drift {ldrift:.3g} > 0.001 at t = {tr.t[k]:g} s")
        err = "—"
        if tr.complete and len(tr.t):
            q = tr.vec("b.orientation", 4)[-1]
            err = f"θ(T) {rotation_angle(q, reference(tr.t[-1])):.3g} rad"
        return {"ok_violations": viol, "end_violations": [], "error": err, "drift": drift}

    return Case(key, "rotation", title, s, T, H,
                "no NaN/Inf; |q|−1 ≤ 1e-12; energy drift ≤ 1e-3 and |L| drift ≤ 1e-3 at every point"
                + criteria_extra + "; error: rotation angle at T against the reference", judge,
                start=start, step=step)


def projectile_bound(method, steps_h2, x):
    """Error bound on a projectile: first-order truncation 1/2 |g| sum h_k^2 for methods
    not known to be exact for a constant force, plus 1e-9 (1 + |x|) of rounding."""
    c = 0.0 if method in EXACT_FOR_CONSTANT_FORCE else 1.0
    return c * 0.5 * G * np.asarray(steps_h2)[:, None] + 1e-9 * (1.0 + np.abs(x))


def internal_h2(t_points, step):
    """sum of h_k^2 of the internal steps up to each communication point."""
    out, acc = [0.0], 0.0
    for a, b in zip(t_points[:-1], t_points[1:]):
        h = b - a
        n = max(1, int(math.ceil(h / step - 1e-9)))
        acc += (n - 1) * step**2 + (h - (n - 1) * step) ** 2
        out.append(acc)
    return np.array(out)


def cases(quick, methods):
    out = []

    # --- fast spin: symmetric top I = (2, 2, 3), omega 30 deg off the axis, h = 1e-2,
    #     1e4 steps, h |omega| in {0.1, 1, 3, 6}
    I_top = (2.0, 2.0, 3.0)
    for hw in (0.1, 1.0, 3.0, 6.0):
        h = 1e-2
        w = hw / h
        omega = (w * math.sin(math.radians(30)), 0.0, w * math.cos(math.radians(30)))
        out.append(spin_case(f"fast-spin-hw{hw:g}",
                             f"fast spin, h·|ω| = {hw:g} (symmetric top I = (2, 2, 3), ω 30° off its axis, "
                             "h = 1e-2 s, 1e4 steps)",
                             I_top, omega, h, 100.0, 1.0,
                             (lambda om: lambda t: symmetric_top(I_top, om, t))(omega)))

    # --- intermediate axis tumbling, 100 s (20 s quick)
    Tt = 20.0 if quick else 100.0
    I3, w3 = (1.0, 2.0, 3.0), (0.01, 5.0, 0.01)
    ref_cache = {}

    def dop(I, w):
        def f(t):
            key = (I, w, round(t, 9))
            if key not in ref_cache:
                ref_cache[key] = torque_free_reference(I, w, t)
            return ref_cache[key]
        return f
    out.append(spin_case("tumbling-intermediate",
                         f"intermediate-axis tumbling, I = (1, 2, 3), ω0 = (0.01, 5, 0.01) rad/s, h = 1e-3 s, {Tt:g} s",
                         I3, w3, 1e-3, Tt, 1.0, dop(I3, w3)))

    # --- needle and triangle-inequality limit
    In, wn = (1e-6, 1.0, 1.0), (2.0, 1.0, 0.0)
    out.append(spin_case("needle-inertia", "needle-like inertia (1e-6, 1, 1), ω0 = (2, 1, 0) rad/s, h = 1e-3 s, 10 s",
                         In, wn, 1e-3, 10.0, 0.1, lambda t: symmetric_top(In, wn, t)))
    Id, wd = (1.0, 1.0, 2.0), (1.0, 0.0, 2.0)
    out.append(spin_case("triangle-limit-disc",
                         "inertia at the triangle limit, I = (1, 1, 2) (flat disc), ω0 = (1, 0, 2) rad/s, "
                         "h = 1e-3 s, 10 s",
                         Id, wd, 1e-3, 10.0, 0.1, lambda t: symmetric_top(Id, wd, t)))
    Il, wl = (0.5, 1.5, 2.0), (1.0, 1.0, 1.0)
    out.append(spin_case("triangle-limit-lamina",
                         "inertia at the triangle limit, I = (0.5, 1.5, 2) (flat lamina), ω0 = (1, 1, 1) rad/s, "
                         "h = 1e-3 s, 10 s",
                         Il, wl, 1e-3, 10.0, 0.1, dop(Il, wl)))

    # --- stiff linear drag: b/m = 1e3 at h = 1e-2
    out.append(stiff_drag_case(quick))

    # --- floating box with a 1 mm draft
    for h in (1e-3, 1e-2):
        out.append(float_case(quick, h))

    # --- mass ratios: stacks and central impacts. Heavy on light beyond 1e3 is past the
    # contacts' stated limit (warned of at initialisation: the light box sinks in by
    # (M/m) g / omega^2, 9 cm at 1e6; docs/guide/surfaces-and-contacts.md, Limits)
    for top, bottom in ((1.0, 1e3), (1.0, 1e6), (1e3, 1.0)):
        out.append(stack_case(quick, top, bottom))
    for ratio in (1e3, 1e6):
        out.append(impact_case(ratio))

    # --- 100 m/s against thin plates
    for thickness in (0.01, 0.001):
        out.append(plate_case(thickness))

    # --- many steps
    out.append(long_run_case(quick))

    # --- communication steps 1e-6 s .. 10 s
    for H in (1e-6, 1e-4, 0.0105, 1.0, 10.0):
        out.append(comm_case(quick, H))

    # --- stiff spring through the force input
    out.append(spring_case(quick))

    # --- masses and lengths at 1e-6 and 1e6 of the usual
    for what, f in (("mass", 1e-6), ("mass", 1e6), ("length", 1e-6), ("length", 1e6)):
        out.append(scale_case(what, f))
    return out


def stiff_drag_case(quick):
    r, m, b = 0.1, 1.0, 1e3
    mu = b / (6 * math.pi * r)
    v0 = np.array([1.0, 0.0, 0.0])
    vT = np.array([0.0, 0.0, -m * G / b])
    s = scene("StiffDrag", [body("ball", {"type": "sphere", "radius": r}, m, velocity=list(v0))],
              step=1e-2, media=[{"name": "syrup", "type": "custom", "min": [-100, -100, -100],
                                 "max": [100, 100, 100], "density": 0.0, "viscosity": mu}])
    T = 1.0 if quick else 2.0

    def judge(tr, method):
        E = energy(tr, s)
        scale = 0.5 * m * float(v0 @ v0)
        gain, viol = drift_check(E, E[0], scale, 1e-9, tr, one_sided=True)
        v = tr.vec("ball.velocity")
        exact = vT + (v0 - vT) * np.exp(-b / m * tr.t)[:, None]
        err = np.max(np.linalg.norm(v - exact, axis=1)) / np.linalg.norm(v0 - vT) if len(v) else float("nan")
        end = []
        if tr.complete:
            rel = np.linalg.norm(v[-1] - vT) / np.linalg.norm(vT)
            if not rel <= 1e-6:
                end.append(f"terminal velocity missed: |v(T) − v_T|/|v_T| = {rel:.3g} > 1e-6")
            errtxt = f"|v−v_exact| {err:.3g} of |v0−v_T|; v(T) within {rel:.2g} of v_T"
        else:
            errtxt = f"|v−v_exact| {err:.3g} of |v0−v_T| (until refused)"
        return {"ok_violations": viol, "end_violations": end, "error": errtxt, "drift": gain}

    return Case("stiff-drag", "media",
                "stiff linear drag: sphere m = 1 kg, b = 1e3 N·s/m (b/m = 1e3 /s), h = 1e-2 s "
                "(h·b/m = 10; rk4 stable only for h·b/m < 2.785), "
                f"v0 = (1, 0, 0) m/s, {T:g} s", s, T, 0.1,
                "no NaN/Inf; |q|−1 ≤ 1e-12; mechanical energy never above its start (gain ≤ 1e-9 of ½ m v0²) "
                "at every point; "
                "|v(T) − v_T| ≤ 1e-6 |v_T|, v_T = m g / b; "
                "error: max |v − v_exact| against v_T + (v0 − v_T) e^(−b t / m)",
                judge)


def float_case(quick, h):
    size = [1.0, 1.0, 0.5]
    d = 1e-3
    m = RHO_WATER * 1.0 * d
    s0 = 1.5 * d
    z0 = 0.25 - s0
    s = scene("Float1mm", [body("box", {"type": "box", "size": size}, m, position=[0, 0, z0])],
              media=[{"name": "pool", "type": "water", "min": [-10, -10, -10], "max": [10, 10, 0]}])
    T = 2.0 if quick else 10.0
    H = 0.01
    rho_g_A = RHO_WATER * G * 1.0
    E_eq = m * G * (0.25 - d) + 0.5 * rho_g_A * d * d
    E_start = m * G * z0 + 0.5 * rho_g_A * s0 * s0
    heave0 = E_start - E_eq

    def judge(tr, method):
        z = tr.col("box.position[3]")
        sub = np.clip(0.25 - z, 0.0, 0.5)
        E = energy(tr, s) + 0.5 * rho_g_A * sub**2 - E_eq
        gain, viol = drift_check(E, heave0, heave0, 1e-3, tr, one_sided=True)
        other = max(float(np.max(np.abs(tr.vec("box.position")[:, :2]))),
                    float(np.max(np.abs(tr.vec("box.angularVelocity")))))
        if not other <= 1e-9:
            viol.append(f"moved off heave (|x|, |y| or |ω| = {other:.3g} > 1e-9)")
        end = []
        zref = heave_dop853(m, size, z0, float(tr.t[-1]) if len(tr.t) else 0.0, tr.t) if len(tr.t) > 1 else z
        err = float(np.max(np.abs(z - zref))) / s0 if len(z) > 1 else float("nan")
        if tr.complete:
            tail = tr.t >= 0.8 * tr.t[-1]
            draft = 0.25 - float(np.mean(z[tail]))
            if not abs(draft - d) <= 0.05 * d:
                end.append(f"mean draft over the last 20 % {draft * 1e3:.4f} mm, not within 5 % of {d * 1e3:g} mm")
            errtxt = f"max |z − z_ref| {err:.3g} of the 0.5 mm offset; mean draft {draft * 1e3:.4f} mm"
        else:
            errtxt = f"max |z − z_ref| {err:.3g} of the offset (until refused)"
        return {"ok_violations": viol, "end_violations": end, "error": errtxt, "drift": gain}

    return Case(f"float-1mm-h{h:g}", "media",
                f"floating box 1 × 1 × 0.5 m with a 1 mm draft (m = {m:.4f} kg in water, heave ω = √(g/d) = 99 rad/s), "
                f"released 0.5 mm deep, h = {h:g} s (h·ω = {h * math.sqrt(G / d):.2g}), {T:g} s",
                s, T, H,
                "no NaN/Inf; |q|−1 ≤ 1e-12; heave energy (kinetic + gravity + buoyancy potential ½ρgA s², "
                "from equilibrium) "
                "never above its start by more than 1e-3 of it; x, y, ω stay 0 (1e-9); "
                "mean draft over the last 20 % within 5 % of 1 mm; "
                "error: max |z − z_ref| against DOP853 on the heave equation (docs/reports/media.md), "
                "relative to the 0.5 mm offset",
                judge, step=h)


def stack_scene(top, bottom):
    e = 0.1
    boxes = [body("lower", {"type": "box", "size": [e] * 3}, bottom, position=[0, 0, e / 2],
                  restitution=0.2, staticFriction=0.6, kineticFriction=0.4),
             body("upper", {"type": "box", "size": [e] * 3}, top, position=[0, 0, 1.5 * e],
                  restitution=0.2, staticFriction=0.6, kineticFriction=0.4)]
    s = scene("Stack", boxes)
    s["surfaces"] = [{"name": "floor", "min": [-2, -2, -0.5], "max": [2, 2, 0],
                      "staticFriction": 0.6, "kineticFriction": 0.4, "restitution": 0.2}]
    return s


def soft_sinking(top, bottom, h=1e-3):
    """How far the stack's soft contacts let each box sink (m), the pair's overlap, and
    how far past its seat the upper box swings on its way down: a contact is a spring
    of frequency f = 0.8/h on a surface and 0.4/h between bodies, damping ratio 10,
    whose stiffness and damping are its effective mass's (the lighter body's); carrying
    a body M times heavier, its damping ratio is 10 sqrt(m/M) (0.32 at 1e3), and set
    down at depth 0 the heavy box overshoots by exp(-pi z / sqrt(1 - z^2)) of its sink
    (docs/guide/surfaces-and-contacts.md)."""
    w_floor, w_pair = 2 * math.pi * 0.8 / h, 2 * math.pi * 0.4 / h
    lower = (top + bottom) / bottom * G / w_floor ** 2
    overlap = top / min(top, bottom) * G / w_pair ** 2
    z = 10.0 * math.sqrt(min(top, bottom) / top)
    overshoot = (lower + overlap) * math.exp(-math.pi * z / math.sqrt(1 - z * z)) if z < 1 else 0.0
    return lower, lower + overlap, overlap, overshoot


def stack_case(quick, top, bottom):
    e = 0.1
    s = stack_scene(top, bottom)
    T = 1.0 if quick else 5.0
    ratio = max(top, bottom) / min(top, bottom)
    which = "light on heavy" if top < bottom else "heavy on light"
    scale = (top + bottom) * G * e
    sink_lower, sink_upper, overlap, overshoot = soft_sinking(top, bottom)
    # heavy on light, the light box's corners, solved in turn under the load, tilt it a
    # little as the heavy one sinks in, and the heavy box slips sideways by up to about a
    # millimetre (1.1 mm at 1e3): the mass-ratio limit of the guide
    allowed = 2e-3 if top > bottom else 1e-3

    def judge(tr, method):
        viol = []
        E = energy(tr, s)
        # 1e-5 of (m1 + m2) g edge: 1 um of the heavier box's height (set down at depth 0,
        # the boxes only sink into their seats, which lowers the energy)
        gain, v = drift_check(E, E[0], scale, 1e-5, tr, one_sided=True)
        viol += v
        worst_pen, worst_drift = 0.0, 0.0
        # each box goes down from where it was set to where the soft contacts hold it (its
        # seat): the drift is its motion sideways and above or below that way down
        for n, z0, sink in (("lower", e / 2, sink_lower), ("upper", 1.5 * e, sink_upper)):
            X = tr.vec(f"{n}.position")
            z = X[:, 2]
            outside = np.maximum(np.maximum(z - z0, z0 - sink - overshoot - z), 0.0)
            worst_drift = max(worst_drift, float(np.max(np.hypot(np.linalg.norm(X[:, :2], axis=1), outside))))
        gap = tr.col("upper.position[3]") - tr.col("lower.position[3]")
        lower_in = float(np.max(e / 2 - tr.col("lower.position[3]")))
        worst_pen = max(float(np.max(e - gap)) - overlap - overshoot, lower_in - sink_lower, 0.0)
        if not worst_pen <= 1e-3:
            viol.append(f"penetration {worst_pen:.3g} m > 1 mm beyond the soft contact's")
        if not worst_drift <= allowed:
            viol.append(f"a box moved {worst_drift:.3g} m > {allowed * 1e3:g} mm from its way down to its seat")
        end = []
        if tr.complete:
            speed = max(float(np.linalg.norm(tr.vec(f"{n}.velocity")[-1])) for n in ("lower", "upper"))
            if not speed <= 1e-3:
                end.append(f"still moving at the end: {speed:.3g} m/s > 1e-3")
        return {"ok_violations": viol, "end_violations": end,
                "error": f"drift {worst_drift:.2g} m, penetration {worst_pen:.2g} m", "drift": gain}

    return Case(f"stack-{which.replace(' ', '-')}-{ratio:.0e}", "mass ratios",
                f"stack {which}, mass ratio {ratio:.0e} (boxes of 0.1 m: {top:g} kg on {bottom:g} kg, on a floor), "
                f"h = 1e-3 s, {T:g} s",
                s, T, 0.01,
                f"no NaN/Inf; |q|−1 ≤ 1e-12; penetration ≤ 1 mm and drift ≤ {allowed * 1e3:g} mm at every point "
                f"beyond the soft contacts' seats (the pair overlaps (M/m) g/ω² = {overlap * 1e3:.2g} mm, the "
                f"upper box sinks {sink_upper * 1e3:.2g} mm, swinging {overshoot * 1e3:.2g} mm past it); "
                "energy never above its start "
                "(gain ≤ 1e-5 of (m1+m2) g·edge: 1 µm of the heavier box); speeds ≤ 1e-3 m/s at the end; "
                "error: worst drift and penetration",
                judge)


def impact_case(ratio):
    R = 0.1
    m1, m2, v1, v2 = 1.0, ratio, 2.0, -0.5
    def mk(n, m, x, v):
        return body(n, {"type": "sphere", "radius": R}, m, position=[x, 0, 0], velocity=[v, 0, 0],
                    restitution=1.0, staticFriction=0.0, kineticFriction=0.0)

    s = scene("Impact", [mk("a", m1, 0.0, v1), mk("b", m2, 2 * R + 0.5, v2)], gravity=(0, 0, 0))
    u1 = ((m1 - m2) * v1 + 2 * m2 * v2) / (m1 + m2)
    u2 = ((m2 - m1) * v2 + 2 * m1 * v1) / (m1 + m2)

    def judge(tr, method):
        viol = []
        E = energy(tr, s)
        drift, v = drift_check(E, E[0], E[0], 1e-9, tr)
        viol += v
        p = m1 * tr.col("a.velocity[1]") + m2 * tr.col("b.velocity[1]")
        p0 = m1 * v1 + m2 * v2
        dp = float(np.max(np.abs(p - p0)))
        if not dp <= 1e-12 * abs(p0) + 1e-12 * m2 * 1e-3:
            viol.append(f"momentum changed by {dp:.3g}")
        gap = tr.col("b.position[1]") - tr.col("a.position[1]")
        pen = float(np.max(2 * R - gap))
        if not pen <= 1e-9:
            viol.append(f"penetration {pen:.3g} m at a communication point")
        end, err = [], "—"
        if tr.complete:
            e1 = abs(tr.col("a.velocity[1]")[-1] - u1)
            e2 = abs(tr.col("b.velocity[1]")[-1] - u2)
            if not (e1 <= 1e-9 and e2 <= 1e-9 * max(1.0, abs(u2))):
                end.append(f"velocities after the impact off the closed form by {e1:.3g}, {e2:.3g} m/s")
            err = f"|u1−u1*| {e1:.2g}, |u2−u2*| {e2:.2g} m/s"
        return {"ok_violations": viol, "end_violations": end, "error": err, "drift": drift}

    return Case(f"impact-ratio-{ratio:.0e}", "mass ratios",
                f"central elastic impact, mass ratio {ratio:.0e} (spheres 1 kg at 2 m/s and {ratio:g} kg at −0.5 m/s, "
                "ξ = 1, no friction), h = 1e-3 s, 1 s",
                s, 1.0, 0.05,
                "no NaN/Inf; |q|−1 ≤ 1e-12; kinetic energy within 1e-9 and momentum within 1e-12 at every point; "
                "no overlap at the "
                "communication points; velocities after the impact within 1e-9 of the closed form; "
                "error: velocities after against the closed form",
                judge)


def plate_case(thickness):
    r, m, mp, v0 = 0.005, 0.004, 50.0, 100.0
    s = scene("Plate", [body("ball", {"type": "sphere", "radius": r}, m, position=[-0.445, 0, 0],
                             velocity=[v0, 0, 0], restitution=0.5),
                        body("plate", {"type": "box", "size": [thickness, 1.0, 1.0]}, mp, position=[0, 0, 0],
                             restitution=0.5)], gravity=(0, 0, 0))

    def judge(tr, method):
        viol = []
        E = energy(tr, s)
        gain, v = drift_check(E, E[0], E[0], 1e-9, tr, one_sided=True)
        viol += v
        xb, xp = tr.col("ball.position[1]"), tr.col("plate.position[1]")
        pen = float(np.max(xb + r - (xp - thickness / 2)))
        if np.any(xb >= xp):
            viol.append(f"the ball passed the plate's middle at t = {first_time(tr, xb >= xp):g} s")
        if not pen <= 1e-4:
            viol.append(f"penetration {pen:.3g} m > 0.1 mm at a communication point")
        p = m * tr.col("ball.velocity[1]") + mp * tr.col("plate.velocity[1]")
        dp = float(np.max(np.abs(p - m * v0)))
        if not dp <= 1e-9 * m * v0:
            viol.append(f"momentum changed by {dp:.3g} N·s")
        end = []
        if tr.complete and not tr.col("ball.velocity[1]")[-1] < 0:
            end.append("the ball did not bounce back")
        return {"ok_violations": viol, "end_violations": end,
                "error": f"penetration {max(pen, 0.0):.2g} m; v_ball(T) {tr.col('ball.velocity[1]')[-1]:.4g} m/s",
                "drift": gain}

    return Case(f"thin-plate-{thickness * 1e3:g}mm", "impacts",
                f"100 m/s sphere (r = 5 mm, 4 g) against a {thickness * 1e3:g} mm plate (50 kg), "
                "h = 1e-3 s (10 cm per step), 0.05 s",
                s, 0.05, 1e-3,
                "no NaN/Inf; |q|−1 ≤ 1e-12; never beyond the plate's middle; penetration ≤ 0.1 mm, "
                "momentum within 1e-9, "
                "no energy gain (1e-9) at every point; bounced back at the end; "
                "error: penetration and final velocity",
                judge)


def long_run_case(quick):
    I, w = (2.0, 2.0, 3.0), (0.6, 0.0, 2.0)
    steps = 100000 if quick else 10000000
    T = steps * 1e-3
    c = spin_case("steps-1e5" if quick else "steps-1e7",
                  f"{steps:.0e} steps: symmetric top I = (2, 2, 3), ω0 = (0.6, 0, 2) rad/s, h = 1e-3 s, {T:g} s"
                  + (" (1e7 in the full suite)" if quick else ""),
                  I, w, 1e-3, T, 1.0 if quick else 10.0, lambda t: symmetric_top(I, w, t))
    c.key = "many-steps"
    c.group = "long runs"
    return c


def comm_case(quick, H):
    x0, v0 = np.array([1.0, 2.0, 10.0]), np.array([3.0, -2.0, 4.0])
    g = np.array([0, 0, -G])
    s = scene("Projectile",
              [body("ball", {"type": "sphere", "radius": 0.1}, 1.0, position=list(x0), velocity=list(v0))])
    calls = 2000 if quick else 10000
    T = min(20.0, calls * H)
    T = max(T, 2 * H)

    def judge(tr, method):
        t = tr.t
        X = tr.vec("ball.position")
        exact = x0 + v0 * t[:, None] + 0.5 * g * t[:, None] ** 2
        h2 = internal_h2(t, 1e-3)
        err = np.abs(X - exact)
        bound = projectile_bound(method, h2, exact)
        viol = []
        bad = np.flatnonzero(np.any(~(err <= bound), axis=1))
        if len(bad):
            k = bad[0]
            viol.append(f"position off the closed form by {err[k].max():.3g} m > bound {bound[k].max():.3g} m "
                        f"at t = {t[k]:g} s")
        E = energy(tr, s)
        scale = 0.5 * float(v0 @ v0) + G * x0[2]
        drift = float(np.max(np.abs(E - E[0]))) / scale
        return {"ok_violations": viol, "end_violations": [],
                "error": f"max |x − x_exact| {err.max():.3g} m", "drift": drift}

    return Case(f"comm-step-{H:g}", "communication steps",
                f"projectile, communication step {H:g} s, solver.step 1e-3 s, {T:g} s ({int(round(T / H))} steps)",
                s, T, H,
                "no NaN/Inf; |q|−1 ≤ 1e-12; position within the closed form x0 + v0 t + ½ g t² at every point: "
                "to 1e-9 (1 + |x|) for methods "
                "exact for a constant force (rk4, lieRk4, splitting, dopri5), "
                "else within the first-order bound ½ |g| Σ h_k² more "
                "(h_k: the internal steps, the last of each communication step shortened) — "
                "the same result whatever the communication step",
                judge)


def scale_case(what, f):
    m, sc = (f, 1.0) if what == "mass" else (1.0, f)
    r, l = 0.1 * sc, 0.3 * sc
    I_perp, I_ax = m * (3 * r * r + l * l) / 12, m * r * r / 2
    I = (I_perp, I_perp, I_ax)
    w = (1.0, 0.5, 3.0)
    x0, v0 = np.array([0.0, 0.0, 0.0]), np.array([1.0, 0.0, 2.0])
    g = np.array([0, 0, -G])
    s = scene("Scaled", [body("b", {"type": "cylinder", "radius": r, "length": l}, m,
                              position=list(x0), velocity=list(v0), angularVelocity=list(w))])

    def judge(tr, method):
        viol = []
        E = rot_energy(tr, "b")
        drift, v = drift_check(E, E[0], E[0], 1e-3, tr, label="rotational energy")
        viol += v
        Lw = np.linalg.norm(tr.vec("b.angularMomentum"), axis=1)
        ld = float(np.max(np.abs(Lw - Lw[0]) / Lw[0]))
        if not ld <= 1e-3:
            viol.append(f"|L| drift {ld:.3g} > 1e-3")
        t = tr.t
        X = tr.vec("b.position")
        exact = x0 + v0 * t[:, None] + 0.5 * g * t[:, None] ** 2
        err = np.abs(X - exact)
        bound = projectile_bound(method, internal_h2(t, 1e-3), exact)
        bad = np.flatnonzero(np.any(~(err <= bound), axis=1))
        if len(bad):
            k = bad[0]
            viol.append(f"position off the closed form by {err[k].max():.3g} m > {bound[k].max():.3g} m "
                        f"at t = {t[k]:g} s")
        th = "—"
        if tr.complete:
            th = f"{rotation_angle(tr.vec('b.orientation', 4)[-1], symmetric_top(I, w, t[-1])):.3g} rad"
        return {"ok_violations": viol, "end_violations": [],
                "error": f"|x − x_exact| {err.max():.3g} m; θ(T) {th}", "drift": drift}

    label = f"{what} ×{f:g}"
    return Case(f"scale-{what}-{f:.0e}", "scales",
                f"free-falling spinning cylinder, {label} of the usual (m = {m:g} kg, r = {r:g} m, l = {l:g} m), "
                "v0 = (1, 0, 2) m/s, ω0 = (1, 0.5, 3) rad/s, h = 1e-3 s, 2 s",
                s, 2.0, 0.05,
                "no NaN/Inf; |q|−1 ≤ 1e-12; position within the projectile bound of comm-step cases; "
                "rotational energy and |L| "
                "within 1e-3 at every point; error: position against the closed form, "
                "orientation at T against the symmetric top's precession",
                judge)


# ----------------------------------------------------------------------------------
# the stiff spring closed by an fmpy master

SPRING_ZETA = 0.2
SPRING_X0 = 0.1


def spring_map_radius(k, m, c, H, method):
    """Spectral radius of the master's loop over one communication step H with the force
    F = -k x - c v held (zero-order hold): the sampled-data map of the method's one
    internal step (H = solver.step)."""
    a = -k / m
    b = -c / m
    if method == "euler":
        A = np.array([[1.0, H], [H * a, 1 + H * b]])
    elif method == "symplecticEuler":
        A = np.array([[1 + H * H * a, H + H * H * b], [H * a, 1 + H * b]])
    else:  # exact for a constant force
        A = np.array([[1 + 0.5 * H * H * a, H + 0.5 * H * H * b], [H * a, 1 + H * b]])
    return float(np.max(np.abs(np.linalg.eigvals(A))))


def predicted_break(m, H, method):
    ks = np.logspace(0, 14, 1401)
    for k in ks:
        c = 2 * SPRING_ZETA * math.sqrt(k * m)
        if spring_map_radius(k, m, c, H, method) > 1.0:
            return float(k)
    return None


def spring_case(quick):
    m = 1.0
    s = scene("Spring", [body("mass", {"type": "sphere", "radius": 0.05}, m,
                              position=[SPRING_X0, 0, 0])], gravity=(0, 0, 0))
    H = 1e-3
    T = 0.2 if quick else 1.0

    T_long = 10.0 if quick else 50.0

    def driver(model, method_name, method_value, start):
        results = []
        total = 0.0
        k = 1e2
        final = None
        while k <= 1e12:
            c = 2 * SPRING_ZETA * math.sqrt(k * m)

            def master(t, out, k=k, c=c):
                return {"mass.force[1]": -k * out["mass.position[1]"] - c * out["mass.velocity[1]"]}

            tr = run_fmu(model, method_value, T, H, start=start, master=master, label="spring")
            total += tr.wall
            x = np.abs(tr.col("mass.position[1]")) if len(tr.t) else np.array([0.0])
            grown = bool(np.any(x > 2 * SPRING_X0)) or not tr.complete
            results.append((k, tr, grown))
            if tr.nonfinite is not None or grown:
                final = (k, tr)
                if tr.complete and tr.nonfinite is None:
                    # the diverging loop, on until the FMU refuses (overflow) or T_long
                    tr2 = run_fmu(model, method_value, T_long, H, start=start, master=master, label="spring")
                    total += tr2.wall
                    results.append((k, tr2, True))
                    final = (k, tr2)
                break
            k *= 10
        return results, final, total

    return Case("stiff-spring", "co-simulation",
                f"stiff spring closed through the force input by an fmpy master: F = −k x − c v (ζ = {SPRING_ZETA}) "
                "set at every communication "
                f"point (H = 1e-3 s = solver.step), x(0) = {SPRING_X0} m, k = 1e2, 1e3, … until the loop diverges, "
                f"{T:g} s each",
                s, T, H,
                "no NaN/Inf in any fmi2OK output at any k; when the loop diverges the FMU either stays finite "
                "or refuses (fmi2Discard / "
                "fmi2Error with a message); the k at which the explicit co-simulation loop breaks "
                "is the master's instability (its "
                "zero-order hold), reported beside the k where the sampled-data map's spectral radius passes 1",
                None, driver=driver)


# ----------------------------------------------------------------------------------
# judging

def classify(case, tr, method):
    """(outcome, detail dict)."""
    res = {"error": "—", "drift": None, "qnorm": qnorm_dev(tr, case.scene), "time": tr.wall,
           "steps": tr.steps if tr.has_steps else None, "nominal": tr.nominal, "note": ""}
    fails = []
    if tr.nonfinite is not None:
        fails.append(f"non-finite {tr.nonfinite[1]} returned after fmi2OK at t = {tr.nonfinite[0]:g} s")
    if tr.status != "OK" and tr.after_failure_finite is False:
        fails.append("outputs not finite after the refusal")
    if tr.nonfinite is None and len(tr.t):
        if not res["qnorm"] <= QNORM_BOUND:
            fails.append(f"|q| − 1 = {res['qnorm']:.3g} > 1e-12")
        try:
            j = case.judge(tr, method)
        except Exception as exc:  # a judge that cannot evaluate is a failure of the case
            j = {"ok_violations": [f"judge failed: {exc!r}"], "end_violations": [], "error": "—", "drift": None}
        res["error"], res["drift"] = j["error"], j["drift"]
        fails += [v + " (fmi2OK)" for v in j["ok_violations"]]
        if tr.complete:
            fails += [v + " (fmi2OK)" for v in j["end_violations"]]
    substepped = (tr.has_steps and tr.steps > tr.nominal) or tr.substep_count > 0
    if tr.has_steps and tr.nominal:
        res["ratio"] = tr.steps / tr.nominal
    if fails:
        outcome = "FAILS"
        res["note"] = "; ".join(fails)
    elif tr.status != "OK":
        if not tr.message:
            outcome = "FAILS"
            res["note"] = f"{tr.failed_call} returned fmi2{tr.status} without a message"
        else:
            outcome = "refused"
            res["note"] = (f"{tr.failed_call} → fmi2{tr.status}: “{tr.message}”"
                           + (f"; terminated = {tr.terminated}, last successful t = {tr.last_successful:g} s"
                              if tr.last_successful is not None else ""))
    else:
        outcome = "sub-stepped" if substepped else "holds"
    if substepped and outcome != "FAILS":
        bits = []
        if tr.has_steps and tr.steps > tr.nominal:
            bits.append(f"{tr.steps} internal steps for {tr.nominal} nominal (×{tr.steps / tr.nominal:.4g})")
        if tr.substep_messages:
            bits.append(f"log: “{tr.substep_messages[0]}”"
                        + (f" (+{tr.substep_count - 1} more)" if tr.substep_count > 1 else ""))
        res["note"] = "; ".join([b for b in [res["note"]] + bits if b])
    elif substepped:
        res["note"] += (f"; sub-stepped ×{tr.steps / tr.nominal:.3g}"
                        if tr.has_steps and tr.nominal and tr.steps > tr.nominal else "")
    return outcome, res


def classify_spring(case, method, results, final, total):
    m = 1.0
    pred = predicted_break(m, case.H, method)
    res = {"error": "—", "drift": None, "qnorm": 0.0, "time": total, "steps": None, "nominal": None, "note": ""}
    fails, notes = [], []
    substepped = False
    for k, tr, grown in results:
        res["qnorm"] = max(res["qnorm"], qnorm_dev(tr, case.scene))
        if tr.nonfinite is not None:
            fails.append(f"k = {k:g}: non-finite {tr.nonfinite[1]} after fmi2OK at t = {tr.nonfinite[0]:g} s")
        if tr.status != "OK" and not tr.message:
            fails.append(f"k = {k:g}: {tr.failed_call} returned fmi2{tr.status} without a message")
        if tr.status != "OK" and tr.after_failure_finite is False:
            fails.append(f"k = {k:g}: outputs not finite after the refusal")
        if (tr.has_steps and tr.steps > tr.nominal) or tr.substep_count:
            substepped = True
    if not res["qnorm"] <= QNORM_BOUND:
        fails.append(f"|q| − 1 = {res['qnorm']:.3g} > 1e-12")
    stable = [k for k, tr, grown in results if not grown]
    if final is None:
        res["error"] = f"loop stable up to k = {results[-1][0]:g}"
    else:
        kb, tr = final
        res["error"] = (f"loop breaks at k = {kb:g} (ZOH map: ρ > 1 from k ≈ {pred:.2g})" if pred
                        else f"loop breaks at k = {kb:g}")
        xmax = float(np.max(np.abs(tr.col('mass.position[1]')))) if len(tr.t) else float("nan")
        if tr.status != "OK":
            notes.append(f"at k = {kb:g} |x| grew to {xmax:.3g} m with every output finite and fmi2OK, "
                         "then the FMU refused: "
                         f"{tr.failed_call} → fmi2{tr.status}: “{tr.message}”")
        else:
            notes.append(f"at k = {kb:g} |x| grew to {xmax:.3g} m by t = {tr.t[-1]:g} s, "
                         "every output finite with fmi2OK")
        notes.append("the divergence is the master's explicit coupling, not the FMU's")
    if stable:
        notes.insert(0, f"stable for k ≤ {max(stable):g}")
    if fails:
        outcome = "FAILS"
        notes = fails + notes
    else:
        outcome = "sub-stepped" if substepped else "holds"
    res["note"] = "; ".join(notes)
    return outcome, res


# ----------------------------------------------------------------------------------
# running everything

def run_case(args):
    """Runs one case with every method (in a worker process). Returns a list of rows."""
    case_index, quick, build, folder, methods = args
    case = cases(quick, methods)[case_index]
    model = Model(package(build, folder, case.scene), folder)
    names = {v for _, v, _ in model.methods}
    rows = []
    for name, value, description in methods:
        adaptive = "solver.tolerance" in model.vars and (name in ADAPTIVE_NAMES or "adaptive" in description.lower())
        start = {"solver.tolerance": ADAPTIVE_TOLERANCE} if adaptive else {}
        if value not in names:
            rows.append({"case": case.key, "method": name, "outcome": "FAILS", "error": "—", "drift": None,
                         "qnorm": None,
                         "time": 0.0, "note": "method missing from this FMU's SolverMethod"})
            continue
        if case.driver is not None:
            results, final, total = case.driver(model, name, value, start)
            outcome, res = classify_spring(case, name, results, final, total)
        else:
            tr = run_fmu(model, value, case.T, case.H, start=dict(case.start, **start), label=case.key)
            outcome, res = classify(case, tr, name)
            if not quick and tr.complete:  # the run time: median of REPEATS runs
                walls = [tr.wall] + [run_fmu(model, value, case.T, case.H, start=dict(case.start, **start),
                                             label=case.key).wall for _ in range(REPEATS - 1)]
                res["time"] = statistics.median(walls)
        res.update({"case": case.key, "method": name, "outcome": outcome})
        rows.append(res)
        print(f"  {case.key:28s} {name:16s} {outcome:12s} {res['error']}  {res['note'][:160]}", flush=True)
    return case_index, rows


def fmt(x, digits=2):
    if x is None:
        return "—"
    if isinstance(x, str):
        return x
    if x == 0:
        return "0"
    return f"{x:+.{digits}g}" if x < 0 else f"{x:.{digits}g}"


def fmt_time(s):
    if s is None:
        return "—"
    return f"{s * 1e3:.1f} ms" if s < 1 else f"{s:.2f} s"


def cell(o, res):
    if o == "sub-stepped" and res.get("ratio") and res["ratio"] > 1:
        return f"sub-stepped ×{res['ratio']:.4g}"
    return o


def summary_table(all_cases, names, by):
    lines = ["| case | " + " | ".join(names) + " |", "|---|" + "---|" * len(names)]
    for c in all_cases:
        cells = [cell(by[(c.key, n)]["outcome"], by[(c.key, n)]) if (c.key, n) in by else "not run" for n in names]
        lines.append(f"| `{c.key}` | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def runs_table(all_cases, names, by, peers):
    lines = ["| case | method | outcome | error | energy drift | max \\|q\\|−1 | run time | peers | details |",
             "|---|---|---|---|---:|---:|---:|---|---|"]
    for c in all_cases:
        for n in names:
            r = by.get((c.key, n))
            if not r:
                continue
            peer = peers.get(c.key, {}).get(n, "") if peers else ""
            note = r["note"].replace("|", "\\|").replace("\n", " ")
            err = r["error"].replace("|", "\\|")
            lines.append(f"| `{c.key}` | {n} | {cell(r['outcome'], r)} | {err} | {fmt(r['drift'])} | "
                         f"{fmt(r['qnorm'])} | {fmt_time(r['time'])} | {peer or '—'} | {note or '—'} |")
    return "\n".join(lines)


def write_table(path, all_cases, methods, rows, quick, peers, elapsed):
    """docs/reports/stability.md: templates/stability.md filled with the runs' figures."""
    by = {(r["case"], r["method"]): r for r in rows}
    names = [n for n, _, _ in methods]
    fails = [r for r in rows if r["outcome"] == "FAILS"]
    text = template.fill("stability", {
        "mode_flag": " --quick" if quick else "",
        "source": source_state(),
        "case_count": len(all_cases), "method_count": len(names), "method_names": ", ".join(names),
        "elapsed": f"{elapsed:.0f}",
        "mode": ("Quick mode: shorter runs (1e5 instead of 1e7 steps, 20 s instead of 100 s of tumbling, "
                 "fewer communication steps)." if quick else "Full mode."),
        "summary_table": summary_table(all_cases, names, by),
        "verdict": f"**{len(fails)} of {len(rows)} runs FAIL.**" if fails else f"No run fails ({len(rows)} runs).",
        "failing_runs": ("## Runs that FAIL\n\n" + "".join(f"- `{r['case']}` / {r['method']}: {r['note']}\n"
                                                           for r in fails) + "\n") if fails else "",
        "repeats": REPEATS,
        "runs_table": runs_table(all_cases, names, by, peers),
        "criteria": "\n".join(f"- **`{c.key}`** — {c.title}. *Criteria:* {c.criteria}." for c in all_cases),
        "peers_section": f"## Peers\n\n{peers['_about']}\n\n" if peers and peers.get("_about") else "",
    })
    pathlib.Path(path).parent.mkdir(parents=True, exist_ok=True)
    pathlib.Path(path).write_text(text)


def run_peers(quick, out_json):
    """MuJoCo on the fast-spin case (scripts/reports/stability_peers.py in .venv-peers): a dict
    {case key: {method name: text}, '_about': text}, or None when unavailable."""
    py = ROOT / ".venv-peers" / "bin" / "python"
    if not py.exists():
        try:
            subprocess.run([str(ROOT / "scripts" / "peers.sh"), "--quick", "--out", str(out_json) + ".peers.json"],
                           check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                           env=dict(os.environ, RIGIDFMU_SKIP_SETUP="1"), timeout=900)
        except Exception as exc:
            print(f"stress: peers unavailable ({exc})")
            return None
    try:
        subprocess.run([str(py), "-m", "reports.stability_peers", "--out", str(out_json)]
                       + (["--quick"] if quick else []), check=True, timeout=900)
        return json.loads(pathlib.Path(out_json).read_text())
    except Exception as exc:
        print(f"stress: peers unavailable ({exc})")
        return None


def main(argv=None, prog=None):
    p = argparse.ArgumentParser(prog=prog, description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true")
    p.add_argument("--out", default=str(ROOT / "docs" / "reports"))
    p.add_argument("--build", default=os.environ.get("RIGIDFMU_BUILD", str(ROOT / "build")))
    p.add_argument("--no-build", action="store_true")
    p.add_argument("--only", default=None)
    p.add_argument("--no-peers", action="store_true")
    p.add_argument("--jobs", type=int, default=min(2, os.cpu_count() or 1))
    args = p.parse_args(argv)
    build = pathlib.Path(args.build).resolve()
    ensure_core(build, args.no_build, "report stability")
    start = time.perf_counter()
    folder = tempfile.mkdtemp(prefix="rigidfmu-stress-")
    try:
        methods, _ = discover_methods(build, folder)
        print(f"methods: {', '.join(f'{n}={v}' for n, v, _ in methods)}")
        all_cases = cases(args.quick, methods)
        chosen = [i for i, c in enumerate(all_cases) if not args.only or args.only in c.key]
        # package every scene first (sequentially: the packager shares a build tree)
        for i in chosen:
            package(build, folder, all_cases[i].scene)
        jobs = [(i, args.quick, str(build), folder, methods) for i in chosen]
        # long cases first, so that two workers finish together
        jobs.sort(key=lambda j: (-all_cases[j[0]].T / max(all_cases[j[0]].step, 1e-12)
                                 if all_cases[j[0]].driver is None else 0))
        rows_by_case = {}
        if args.jobs > 1 and len(jobs) > 1:
            with ProcessPoolExecutor(args.jobs) as pool:
                for i, rows in pool.map(run_case, jobs):
                    rows_by_case[i] = rows
        else:
            for j in jobs:
                i, rows = run_case(j)
                rows_by_case[i] = rows
        rows = [r for i in sorted(rows_by_case) for r in rows_by_case[i]]
        peers = None
        if not args.quick and not args.no_peers:
            peers = run_peers(args.quick, pathlib.Path(folder) / "stress_peers.json")
        out = pathlib.Path(args.out) / "stability.md"
        write_table(out, [all_cases[i] for i in chosen], methods, rows, args.quick, peers,
                    time.perf_counter() - start)
        fails = [r for r in rows if r["outcome"] == "FAILS"]
        print(f"wrote {out}: {len(rows)} runs, {len(fails)} FAIL")
        for r in fails:
            print(f"FAILS {r['case']} / {r['method']}: {r['note']}")
        return 1 if fails else 0
    finally:
        shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main(prog="scripts/stress.sh"))
