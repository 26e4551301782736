"""Accuracy report of the FMU's integration methods: work-precision diagrams and
measured orders of convergence on reference problems with independent references.

Every method of the Enumeration `SolverMethod` (read from the modelDescription, so that
new methods are picked up without changing this script) is run through the FMU (fmpy's
FMU2Slave, no simulate_fmu) over a range of steps `solver.step` — or, for an adaptive
method when the FMU has a `solver.tolerance` parameter, over a range of tolerances —
and its error at the end time T is measured against a reference computed here, not by
the code under test (closed forms, or scipy's DOP853 at rtol 1e-12 on the problem's own
equations written below). Wall time per simulated second: median of the timed runs of
the stepping alone (one instance per configuration, fmi2Reset between runs,
communication steps of 0.5 s).

usage:
  scripts/report_accuracy.sh [--out DIR] [--runs N]          the full report: DIR/accuracy.md and
                                                     DIR/accuracy/*.png (default DIR docs/reports/)
  scripts/report_accuracy.sh --quick [--out DIR]             a few steps per method, 1 run each,
                                                     the smooth problems only; exit status 1
                                                     when a measured order is off
  scripts/report_accuracy.sh --scene SCENE.json --tolerance TOL [--stop-time T]
                                                     recommends the cheapest method and step
                                                     whose error on that scene is below TOL

The core is built in --build (default $RIGIDFMU_BUILD or build/) like build_fmu.sh does,
unless --no-build; a directory holding rigidfmu-describe and the rigidfmu_fmi2_*.so
binaries but no CMakeCache.txt is used as prebuilt (packaging only)."""
import argparse
import functools
import json
import math
import os
import pathlib
import shutil
import statistics
import sys
import tempfile
import time

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

# Expected orders of the methods this script knows (error vs step; the adaptive method's
# error vs tolerance is expected near 1) and the tolerance on the measured slope.
EXPECTED_ORDER = {"euler": 1.0, "symplecticEuler": 1.0, "splitting": 2.0, "rk4": 4.0,
                  "lieRk4": 4.0, "dopri5": 5.0, "rosenbrock": 2.0}
ORDER_TOLERANCE = {"euler": 0.25, "symplecticEuler": 0.3, "splitting": 0.4, "rk4": 0.5,
                   "lieRk4": 0.5, "dopri5": 0.8, "rosenbrock": 0.4}
ADAPTIVE_ORDER, ADAPTIVE_TOLERANCE = 1.0, 0.4
# A body in contact moves by the constraint solver's sub-steps (symplectic Euler of h/4,
# docs/guide/surfaces-and-contacts.md): first order, whichever method integrates the rest.
CONTACT_ORDER = 1.0
# Without forces symplecticEuler's kick is nil and its drift is the splitting's free
# rotation (Strang-composed): second order on the torque-free problems.
TORQUE_FREE_ORDERS = {"symplecticEuler": 2.0}
ADAPTIVE_NAMES = {"dopri5", "dopri45", "rk45", "rkf45", "cashkarp", "bs23"}

COMM = 0.5  # s, communication step of the runs (every step below divides it)
SPIN_STEPS = {1: 8, 2: 4}  # the spins (omega up to 5 rad/s) need 8x finer steps at order 1


# ----------------------------------------------------------------------------------
# quaternions and independent references

def symmetric_top_closed_form(I1, I3, omega0, T):
    """Torque-free symmetric top (I1 = I2), identity orientation at 0: regular precession,
    q(t) = rot(L/|L|, |L| t / I1) * rot(e3, -Omega t), Omega = (I3 - I1)/I1 * omega3
    (the body-frame omega turns about the axis at Omega; the axis cones about L)."""
    w = np.asarray(omega0, dtype=float)
    L = np.array([I1 * w[0], I1 * w[1], I3 * w[2]])
    Omega = (I3 - I1) / I1 * w[2]
    return quat_mul(quat_axis_angle(L, np.linalg.norm(L) * T / I1),
                    quat_axis_angle([0, 0, 1], -Omega * T))


def bounce_height(t, h0, e):
    """Height of the lowest point of a ball dropped from h0 onto a floor with
    restitution e (impacts instantaneous): the piecewise parabola."""
    t_hit = math.sqrt(2 * h0 / G)
    if t <= t_hit:
        return h0 - 0.5 * G * t * t
    v = e * G * t_hit  # upward speed after the first impact
    start = t_hit
    while True:
        flight = 2 * v / G
        if t <= start + flight:
            s = t - start
            return v * s - 0.5 * G * s * s
        start += flight
        v *= e


# Fluids (docs/scene-format.md / docs/reports/media.md): water 998.2 kg/m3, 1.002e-3 Pa s; box C_d 1.05,
# sphere C_d 0.47; Stokes b = 6 pi mu r for a sphere, Leith's 6 pi (r_n/3 + 2 r_s/3) mu
# for other shapes.


# ----------------------------------------------------------------------------------
# reference problems: a scene, an end time, a reference and an error measure

def vec(out, prefix, n=3):
    return np.array([out[f"{prefix}[{i}]"] for i in range(1, n + 1)])


class Problem:
    """key, title, scene, T, error(outputs) -> float, unit, what it tests, reference,
    scale (saturation and rounding floor of the order fit are relative to it), steps
    per expected order, smooth (run in --quick and judged)."""

    def __init__(self, key, title, scene, T, error, unit, tests, reference, scale,
                 smooth=True, step_scale=None, not_asymptotic=(), unjudged=None, note="",
                 orders=None, contact=False):
        self.key, self.title, self.scene, self.T = key, title, scene, T
        self.error, self.unit, self.tests, self.reference = error, unit, tests, reference
        self.scale, self.smooth = scale, smooth
        self.step_scale = step_scale or {}  # order class (1, 2, 4) -> factor on 1/h
        # methods not expected in their asymptotic range ("*": any method whose slope
        # is off); their orders are reported, not judged
        self.not_asymptotic = set(not_asymptotic)
        self.unjudged = unjudged  # reason why no order is judged on this problem
        self.note = note          # findings worth a paragraph in the report
        self.orders = orders or {}  # expected orders that differ on this problem
        # its body rests on a surface: the constraint solver moves it by sub-steps of the
        # solver step, first order whatever the method, and no tolerance changes them
        self.contact = contact
        if contact:
            self.orders = {method: CONTACT_ORDER for method in EXPECTED_ORDER}


def spin_problem(name, inertia, omega0):
    """A torque-free body with principal inertia diag(inertia), identity orientation (so
    world and body frames coincide at t = 0), no gravity."""
    return free_spin(inertia, omega0, name=name, outputs=["orientation"], inputs=[])


def problems():
    P = []

    # (a) torque-free near the intermediate axis
    inertia, w0, T = (1.0, 2.0, 3.0), (0.01, 5.0, 0.01), 20.0
    q_ref_a = torque_free_reference(inertia, w0, T)
    P.append(Problem(
        "intermediate_axis", "torque-free body near the intermediate axis",
        spin_problem("IntermediateAxis", inertia, w0), T,
        lambda o, q=q_ref_a: rotation_angle(vec(o, "spinner.orientation", 4), q), "rad",
        "Free rotation, principal inertia (1, 2, 3) kg m2, omega0 = (0.01, 5, 0.01) rad/s, "
        "no gravity, T = 20 s: the body flips every ~5 s (Dzhanibekov effect). Close to "
        "the separatrix the orientation is very sensitive to the integrator's error "
        "(tests the rotational update q' = 1/2 omega q with omega = I(t)^-1 L).",
        "scipy DOP853 (rtol 1e-12, atol 1e-14) on Euler's equations in the body frame "
        "with q' = 1/2 q (0, omega_body); error = rotation angle between q(T) and q_ref(T).",
        1.0, step_scale=SPIN_STEPS, not_asymptotic={"*"}, orders=TORQUE_FREE_ORDERS,
        note="Near the separatrix the error at T is not a clean power of h for any "
             "method: explicit Euler crosses the separatrix (O(1) error at every practical "
             "step); rk4's error is of order 4 only until the first flip (t < 4 s) and "
             "behaves like h^5 after it at every step above the rounding floor (measured "
             "at every 0.5 s from 0 to 20 s with h = 7.8, 3.9 and 2.0 ms), its h^4 term "
             "being overtaken by one that the flips amplify. Orders here are reported, "
             "not judged; (b) and (c) are the smooth rotation cases."))

    # (b) torque-free near the major axis
    w0b = (0.4, 0.3, 3.0)
    q_ref_b = torque_free_reference(inertia, w0b, T)
    P.append(Problem(
        "major_axis", "torque-free body near the major axis",
        spin_problem("MajorAxis", inertia, w0b), T,
        lambda o, q=q_ref_b: rotation_angle(vec(o, "spinner.orientation", 4), q), "rad",
        "Free rotation, inertia (1, 2, 3) kg m2, omega0 = (0.4, 0.3, 3.0) rad/s, T = 20 s: "
        "a stable wobble about the major axis, the smooth case of free rotation.",
        "scipy DOP853 (rtol 1e-12) on Euler's equations, as in (a); error = rotation angle.",
        1.0, step_scale=SPIN_STEPS, orders=TORQUE_FREE_ORDERS))

    # (c) symmetric top, regular precession
    I1, I3, w0c = 1.0, 2.0, (0.5, 0.2, 4.0)
    q_ref_c = symmetric_top_closed_form(I1, I3, w0c, T)
    P.append(Problem(
        "symmetric_top", "symmetric top (regular precession, closed form)",
        spin_problem("SymmetricTop", (I1, I1, I3), w0c), T,
        lambda o, q=q_ref_c: rotation_angle(vec(o, "spinner.orientation", 4), q), "rad",
        "Torque-free symmetric top I1 = I2 = 1, I3 = 2 kg m2 spinning at 4 rad/s about its "
        "axis with omega0 = (0.5, 0.2, 4) rad/s off the axis, T = 20 s: regular "
        "precession, the axis cones about L while the body-frame omega turns about the "
        "axis at Omega = (I3 - I1)/I1 omega3. Not a heavy top: the FMU has no fixed pivot "
        "and gravity acts at the centre of mass, so a gravity torque about a pivot could "
        "only come through the torque input, which holds its value over a communication "
        "step — the error would then be the master's zero-order hold, not the method's.",
        "closed form q(t) = rot(L/|L|, |L| t / I1) rot(e3, -Omega t); error = rotation "
        "angle at T.", 1.0, step_scale=SPIN_STEPS, orders=TORQUE_FREE_ORDERS))

    # (d) linear drag
    r, m, b = 0.1, 1.0, 2.0
    mu = b / (6 * math.pi * r)
    v0, Td = np.array([1.0, -0.5, 3.0]), 3.0
    tau, vT = m / b, np.array([0.0, 0.0, -m * G / b])
    x_ref_d = vT * Td + (v0 - vT) * tau * (1 - math.exp(-Td / tau))
    P.append(Problem(
        "linear_drag", "projectile with linear drag",
        scene("LinearDrag", [body("ball", {"type": "sphere", "radius": r}, m, velocity=list(v0),
                                  outputs=["position"], inputs=[])],
              media=[{"name": "fluid", "type": "custom", "density": 0.0, "viscosity": mu,
                      "min": [-100, -100, -100], "max": [100, 100, 100]}]), Td,
        lambda o, x=x_ref_d: float(np.linalg.norm(vec(o, "ball.position") - x)), "m",
        "Sphere r = 0.1 m, m = 1 kg, wholly inside a custom medium of density 0 and "
        "viscosity mu = b/(6 pi r) (Stokes drag b = 2 N s/m, no buoyancy), v0 = (1, -0.5, 3) "
        "m/s, gravity, T = 3 s (6 relaxation times): the medium's force stage, smooth.",
        "closed form x = v_T t + (v0 - v_T) tau (1 - e^(-t/tau)), tau = m/b, v_T = m g/b; "
        "error = |x(T) - x_ref(T)|.", 10.0))

    # (e) quadratic drag, vertical fall from rest
    r, m, rho = 0.1, 10.0, 100.0
    g1 = G * (1 - rho * 4 / 3 * math.pi * r**3 / m)
    vTe = math.sqrt(2 * m * g1 / (rho * 0.47 * math.pi * r**2))
    Te, z0 = 3.0, 50.0
    z_ref_e = z0 - vTe**2 / g1 * math.log(math.cosh(g1 * Te / vTe))
    P.append(Problem(
        "quadratic_drag", "fall with quadratic drag and buoyancy",
        scene("QuadraticDrag", [body("ball", {"type": "sphere", "radius": r}, m,
                                     position=[0, 0, z0], outputs=["position"], inputs=[])],
              media=[{"name": "fluid", "type": "custom", "density": rho, "viscosity": 0.0,
                      "min": [-100, -100, -100], "max": [100, 100, 100]}]), Te,
        lambda o, z=z_ref_e: float(np.linalg.norm(vec(o, "ball.position") - [0, 0, z])), "m",
        "Sphere r = 0.1 m, m = 10 kg falling from rest in a custom medium of density "
        "100 kg/m3 and viscosity 0: buoyancy and Newton drag 1/2 rho C_d A v^2 "
        "(C_d 0.47, A = pi r^2), T = 3 s (close to the terminal speed 11.3 m/s).",
        "closed form z = z0 - v_T^2/g' ln cosh(g' t / v_T), g' = g (1 - rho V / m), "
        "v_T = sqrt(2 m g' / (rho C_d A)); error = |x(T) - x_ref(T)|.", 10.0))

    # (f) block sliding down an incline
    theta, mus, muk, cube = math.radians(30.0), 0.5, 0.3, 0.2
    q = [math.cos(theta / 2), 0.0, math.sin(theta / 2), 0.0]
    n = np.array([math.sin(theta), 0.0, math.cos(theta)])
    down = np.array([math.cos(theta), 0.0, -math.sin(theta)])
    x0 = (0.5 + cube / 2) * n
    Tf = 2.0
    a = G * (math.sin(theta) - muk * math.cos(theta))
    x_ref_f = x0 + 0.5 * a * Tf**2 * down
    P.append(Problem(
        "incline", "block sliding down a 30 degree incline",
        scene("Incline", [body("cube", {"type": "box", "size": [cube] * 3}, 2.0,
                               position=list(x0), orientation=q, staticFriction=mus,
                               kineticFriction=muk, restitution=0.0,
                               outputs=["position"], inputs=[])],
              surfaces=[{"name": "ramp", "min": [-5, -1, -0.5], "max": [5, 1, 0.5],
                         "orientation": q, "staticFriction": mus, "kineticFriction": muk,
                         "restitution": 0.0}]), Tf,
        lambda o, x=x_ref_f: float(np.linalg.norm(vec(o, "cube.position") - x)), "m",
        "A 0.2 m cube (2 kg) released on a 30 degree ramp, mu_s 0.5, mu_k 0.3, T = 2 s: "
        "support and kinetic friction from the constraint solver, whose sub-steps (symplectic "
        "Euler of h/4) move a body in contact: first order whatever the method, ahead of the "
        "closed form by a (h/4) t / 2.",
        "closed form: x0 + 1/2 a t^2 along the slope, a = g (sin theta - mu_k cos theta); "
        "error = |x(T) - x_ref(T)|.", 5.0, smooth=False, contact=True))

    # (g) bouncing ball
    R, e, h0, Tg = 0.1, 0.8, 1.0, 1.5
    z_ref_g = R + bounce_height(Tg, h0, e)
    P.append(Problem(
        "bounce", "ball bouncing on a floor",
        scene("Bounce", [body("ball", {"type": "sphere", "radius": R}, 1.0,
                              position=[0, 0, R + h0], restitution=e,
                              outputs=["position"], inputs=[])],
              surfaces=[{"name": "floor", "min": [-50, -5, -1], "max": [50, 5, 0],
                         "staticFriction": 0.5, "kineticFriction": 0.3, "restitution": e}]),
        Tg,
        lambda o, z=z_ref_g: float(np.linalg.norm(vec(o, "ball.position") - [0, 0, z])), "m",
        "Ball r = 0.1 m dropped from 1 m on a floor, restitution 0.8 (ball and floor), "
        "T = 1.5 s, in the flight after the second impact: impacts located inside the "
        "step, the impulse, and the rest of the step integrated after it.",
        "closed form: the piecewise parabola with impacts at t1 = sqrt(2 h0/g), "
        "t_(n+1) = t_n + 2 e^n t1; error = |x(T) - x_ref(T)|.", 1.0, smooth=False,
        unjudged="the impact handling limits every method",
        note="The impact is located inside the step, but the error after it is of order "
             "h^1 to h^1.3 whatever the method (rk4, exact on each parabola, shows it "
             "alone), and not monotonic in h: for some steps it sits on a plateau. The "
             "accuracy of a bouncing body is set by the impact handling, not by the "
             "integration method."))

    # (h) floating box, heave
    size, mb, zh0, Th = (1.0, 1.0, 0.5), 250.0, 0.1, 2.0
    z_ref_h = heave(mb, size, zh0, [0.0, Th])[-1]
    P.append(Problem(
        "heave", "floating box: heave in water",
        scene("Heave", [body("box", {"type": "box", "size": list(size)}, mb,
                             position=[0, 0, zh0], outputs=["position"], inputs=[])],
              media=[{"name": "pool", "type": "water", "min": [-10, -10, -10],
                      "max": [10, 10, 0]}]), Th,
        lambda o, z=z_ref_h: float(np.linalg.norm(vec(o, "box.position") - [0, 0, z])), "m",
        "A 1 x 1 x 0.5 m box of density 500 released upright at draft 0.15 m in water "
        "(equilibrium draft m/(rho_w A) = 0.2505 m), T = 2 s (two heave periods): "
        "buoyancy of the clipped volume and drag scaled by the submerged fraction. "
        "The quadratic drag |v| v is only C1 where the heave turns (v = 0).",
        "scipy DOP853 (rtol 1e-12) on the 1-DOF heave equation with the buoyancy and "
        "drag of docs/reports/media.md (Leith's linear and C_d 1.05 quadratic drag, scaled by the "
        "submerged fraction); error = |x(T) - x_ref(T)|.", 0.1, smooth=False,
        not_asymptotic={"*"},
        note="The drag |v| v has a discontinuous second derivative at the turning points, "
             "so methods of order above 2 may show irregular convergence here; slopes "
             "off their expected value are reported as not in the asymptotic range."))
    return P


# ----------------------------------------------------------------------------------
# running an FMU (built by reports.fmu_build)

class Model(driver.Fmu):
    """One FMU: its methods (from the modelDescription), its variables, one extracted copy."""

    def __init__(self, fmu, folder):
        super().__init__(fmu, folder=folder, prefix="acc-")
        self.methods = self.methods()  # (name, value, description)
        if not self.methods:
            raise ReportError("report accuracy: no Enumeration SolverMethod in the modelDescription")
        self.has_tolerance = "solver.tolerance" in self.vars
        self.steps_var = self.vars.get("solver.steps")
        self.outputs = self.real_outputs()

    def is_adaptive(self, name, description):
        return self.has_tolerance and (name in ADAPTIVE_NAMES or "adaptive" in description.lower())

    def run(self, method_value, T, step=None, tolerance=None, runs=1, comm=COMM):
        """(outputs at T, median wall seconds per simulated second or None, internal steps
        or None, failure message or None). One instance; an untimed run reads the outputs
        (and solver.steps after every communication step), then `runs` timed runs."""
        # fmpy's own logger (recorder=False): it prints what the FMU says
        instance = driver.Slave(self, "accuracy", recorder=False)
        slave = instance.slave
        n_comm = max(1, round(T / comm))
        H = T / n_comm
        values = {"solver.method": method_value}
        if step is not None:
            values["solver.step"] = step
        if tolerance is not None and self.has_tolerance:
            values["solver.tolerance"] = tolerance
        if "solver.energyGainLimit" in self.vars:
            # This report measures each method's error, so the energy audit (which
            # refuses explicit Euler's energy gain on a free rotation) is off here.
            values["solver.energyGainLimit"] = 0.0

        def start():
            instance.initialize(values)

        outputs, internal, times, failure = None, None, [], None
        try:
            start()
            count = self.steps_var is not None
            total = 0
            for k in range(n_comm):
                slave.doStep(k * H, H)
                if count:
                    vr = [self.steps_var.valueReference]
                    total += (slave.getInteger(vr)[0] if self.steps_var.type == "Integer"
                              else slave.getReal(vr)[0])
            internal = int(total) if count else None
            outputs = instance.get_values([v.name for v in self.outputs])
            for _ in range(runs):
                slave.terminate()
                slave.reset()
                start()
                t0 = time.perf_counter()
                for k in range(n_comm):
                    slave.doStep(k * H, H)
                times.append((time.perf_counter() - t0) / T)
        except Exception as exc:  # fmi2Discard (not finite, tolerance not met) or error
            failure = f"{type(exc).__name__}: {exc}"
        finally:
            try:
                instance.free()
            except Exception:
                pass
        return outputs, (statistics.median(times) if times else None), internal, failure


# ----------------------------------------------------------------------------------
# sweeps and orders

def order_class(order):
    if order is None:
        return 2
    return 1 if order <= 1.5 else 2 if order <= 3 else 4


def step_list(order, quick, scale=1.0):
    """Steps h = COMM / N for a method of the given expected order: from a coarse step
    where the error is a few per cent to one where it nears rounding."""
    cls = order_class(order)
    if cls == 1:
        Ns = [50, 100, 200, 400, 800, 1600, 3200] if not quick else [200, 400, 800]
    elif cls == 2:
        Ns = [10, 20, 40, 80, 160, 320, 640] if not quick else [40, 80, 160]
    elif order < 4.5:
        Ns = [4, 8, 16, 32, 64, 128, 256] if not quick else [16, 32, 64]
    else:
        Ns = [2, 4, 8, 16, 32, 64, 128] if not quick else [4, 8, 16]
    return [COMM / max(1, round(N * scale)) for N in Ns]


def tolerance_list(quick):
    return [1e-4, 1e-6, 1e-8] if quick else [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11]


def fit_order(xs, errs, scale):
    """Least-squares slope of log error vs log x over the points in the asymptotic range:
    below the saturation (3 % of the problem's scale) and above the rounding floor
    (1e-12 of the scale, and points from where the error stops falling once below 1e-8
    of it).
    Returns (slope or None, indices used, status)."""
    pts = sorted((x, e, i) for i, (x, e) in enumerate(zip(xs, errs)) if e is not None
                 and np.isfinite(e))[::-1]  # coarse to fine
    if not pts:
        return None, [], "failed"
    floor = 1e-12 * scale
    if all(e <= floor for _, e, _ in pts):
        return None, [], "exact"
    used, prev = [], None
    for x, e, i in pts:
        if e <= floor:
            break
        if prev is not None and e < 1e-8 * scale:
            ratio = prev[0] / x  # > 1
            if e > prev[1] / ratio**0.5:  # no longer falling: rounding
                break
        if e < 0.03 * scale:
            used.append(i)
        prev = (x, e)
    if len(used) < 2:
        finite = [e for _, e, _ in pts]
        if len(finite) >= 3 and finite[-1] > 0.5 * finite[0] and finite[-1] >= 0.03 * scale:
            return None, used, "no convergence"
        return None, used, "not in its asymptotic range"
    slope = float(np.polyfit(np.log([xs[i] for i in used]), np.log([errs[i] for i in used]), 1)[0])
    return slope, used, "ok"


def expectation(method, adaptive, fixed_variant, problem):
    if adaptive and not fixed_variant:
        return ADAPTIVE_ORDER, ADAPTIVE_TOLERANCE
    return problem.orders.get(method, EXPECTED_ORDER.get(method)), ORDER_TOLERANCE.get(method)


def sweep(model, problem, quick, runs, log):
    """Every method (and the adaptive one in fixed-step use too) over its steps or
    tolerances. Returns a list of curve dicts."""
    curves = []
    for name, value, desc in model.methods:
        adaptive = model.is_adaptive(name, desc)
        variants = [(False, name)]
        if adaptive:
            variants = [(False, name), (True, f"{name} (fixed step, tolerance 0)")]
        for fixed, label in variants:
            expected, tol = expectation(name, adaptive, fixed, problem)
            if adaptive and not fixed:
                xs, kind = tolerance_list(quick), "tolerance"
            else:
                xs, kind = step_list(expected, quick, problem.step_scale.get(order_class(expected), 1.0)), "step"
            rows = []
            for x in xs:
                if kind == "tolerance":
                    out, wall, internal, fail = model.run(value, problem.T, step=COMM,
                                                          tolerance=x, runs=runs)
                else:
                    out, wall, internal, fail = model.run(
                        value, problem.T, step=x, tolerance=0.0 if adaptive else None, runs=runs)
                err = problem.error(out) if out is not None else None
                if internal is None and kind == "step":
                    internal = round(problem.T / x)
                rows.append({"x": x, "error": err, "wall": wall, "internal": internal,
                             "failure": fail})
                log(f"  {problem.key:18s} {label:32s} {kind} {x:9.3g}  error "
                    f"{'failed' if err is None else f'{err:.3e}'}"
                    f"{'' if wall is None else f'  {wall * 1e3:8.3f} ms/s'}")
            # Steps: the order is fitted against the mean internal step (T / solver.steps),
            # which differs from h where the FMU sub-steps (spin, drag, heave limits).
            xs = [problem.T / r["internal"] if kind == "step" and r["internal"] else r["x"] for r in rows]
            slope, used, status = fit_order(xs, [r["error"] for r in rows], problem.scale)
            refused = all(r["failure"] and "(discard)" in str(r["failure"]) for r in rows)
            verdict = judge(name, adaptive, fixed, slope, status, expected, tol, problem, refused)
            curves.append({"method": name, "label": label, "kind": kind, "rows": rows,
                           "slope": slope, "used": used, "status": status,
                           "expected": expected, "tol": tol, "verdict": verdict})
    return curves


def judge(name, adaptive, fixed, slope, status, expected, tol, problem, refused=False):
    """'pass', 'FAIL...', or why it is not judged."""
    if expected is None:
        return "unknown method: not judged"
    if status == "exact":
        return "exact to rounding"
    if status == "failed" and refused:
        # the FMU refused every run with fmi2Discard and a logged cause (e.g. explicit
        # Euler on a buoyant heave, where no step is stable)
        return "refused by the FMU (fmi2Discard, cause logged): not judged"
    if status == "failed":
        return "FAIL (no run succeeded)"
    if problem.unjudged:
        return "not judged: " + problem.unjudged
    if problem.contact and adaptive and not fixed:
        return "not judged: a body in contact moves by solver.step's sub-steps, not by the tolerance"
    anyway = "*" in problem.not_asymptotic or (name in problem.not_asymptotic and not
                                               (adaptive and not fixed))
    if status == "no convergence":
        return "not in its asymptotic range" if anyway else "FAIL (no convergence)"
    if status != "ok":
        return "not in its asymptotic range"
    # steeper than expected is allowed by a further 0.5 (a small leading error
    # coefficient steepens the slope before the asymptotic range); flatter is not
    if expected - tol <= slope <= expected + tol + 0.5:
        return "pass"
    if anyway:
        return "not in its asymptotic range"
    return "FAIL"


# ----------------------------------------------------------------------------------
# outputs: plots and markdown

def fmt_x(c, x):
    return f"tol {x:.0e}" if c["kind"] == "tolerance" else f"h {x:.4g}"


def peer_points(problem, peers):
    """The peers' measurements (scripts/reports/accuracy_peers.py, JSON) on this problem."""
    return [p for p in peers if problem.key == "intermediate_axis"
            and p.get("problem", "").startswith("torque-free, intermediate axis")]


def plot(problem, curves, path, peers=()):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.3))
    for k, p in enumerate(peer_points(problem, peers)):
        marker = "^sDvo<>p"[k % 8]
        ax1.loglog([p["s_per_simulated_s"] * 1e3], [max(p["error"], 1e-17)], marker, ms=7,
                   color="k", mfc="none", label=f"{p['engine']} {p['method']} dt {p['dt']:g}")
        ax2.loglog([p["dt"]], [max(p["error"], 1e-17)], marker, ms=7, color="k", mfc="none")
    if peer_points(problem, peers):
        ax1.legend(fontsize=7)
    for c in curves:
        ok = [r for r in c["rows"] if r["error"] is not None and r["error"] > 0]
        if not ok:
            continue
        floor = [max(r["error"], 1e-17) for r in ok]
        walls = [r["wall"] for r in ok]
        style = "--" if c["kind"] == "tolerance" else "-"
        if all(w is not None for w in walls):
            ax1.loglog(np.array(walls) * 1e3, floor, style, marker="o", ms=4, label=c["label"])
        # error vs mean internal step (T / internal steps)
        hs = [problem.T / r["internal"] if r["internal"] else r["x"] for r in ok]
        ax2.loglog(hs, floor, style, marker="o", ms=4, label=c["label"])
    ax1.set_xlabel("wall time per simulated second (ms)")
    ax2.set_xlabel("mean internal step (s)")
    for ax in (ax1, ax2):
        ax.set_ylabel(f"error at T = {problem.T:g} s ({problem.unit})")
        ax.grid(True, which="both", alpha=0.3)
    ax1.set_title("work-precision")
    ax2.set_title("convergence")
    ax2.legend(fontsize=8)
    fig.suptitle(problem.title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_grid(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    n = len(results)
    cols = 3 if n > 4 else 2
    rows = math.ceil(n / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(5 * cols, 3.8 * rows), squeeze=False)
    for ax, (problem, curves) in zip(axes.flat, results):
        for c in curves:
            ok = [r for r in c["rows"] if r["error"] is not None and r["error"] > 0
                  and r["wall"] is not None]
            if ok:
                ax.loglog([r["wall"] * 1e3 for r in ok], [max(r["error"], 1e-17) for r in ok],
                          "--" if c["kind"] == "tolerance" else "-", marker="o", ms=3,
                          label=c["label"])
        ax.set_title(problem.title, fontsize=9)
        ax.set_xlabel("ms per simulated s", fontsize=8)
        ax.set_ylabel(f"error ({problem.unit})", fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    axes.flat[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def order_text(c):
    if c["slope"] is None:
        return "–"
    return f"{c['slope']:.2f}"


def findings(results):
    """One line per failed order, then the problems' notes."""
    lines = []
    for p, curves in results:
        for c in curves:
            if not c["verdict"].startswith("FAIL"):
                continue
            errs = [r["error"] for r in c["rows"] if r["error"] is not None]
            extra = (f" The error does not fall with the step: {min(errs):.3g} to "
                     f"{max(errs):.3g} {p.unit} over the sweep, so the FMU's result itself "
                     "is off the reference." if c["status"] == "no convergence" and errs else "")
            lines.append(f"- **{c['label']}** on *{p.title}*: {c['verdict']}, measured order "
                         f"{order_text(c)}, expected {c['expected']:g} ± {c['tol']:g}.{extra}")
    if not lines:
        lines.append("- Every judged order is within its tolerance.")
    lines += [f"- *{p.title}*: {p.note}" for p, _ in results if p.note]
    return "\n".join(lines)


def order_cell(c):
    v = c["verdict"]
    if v == "pass":
        return order_text(c)
    if v == "exact to rounding":
        return "exact" + (f" ({order_text(c)})" if c["slope"] is not None else "")
    if v.startswith("not in"):
        return f"{order_text(c)} (not asymptotic)" if c["slope"] is not None else "not asymptotic"
    if v.startswith(("not judged", "unknown")):
        return f"{order_text(c)} (not judged)"
    return f"**{order_text(c)} {v}**"


def cost_cell(problem, c):
    hit = [r for r in c["rows"] if r["error"] is not None and r["wall"] is not None
           and r["error"] <= 1e-6 * problem.scale]
    if not hit:
        return "not reached"
    r = min(hit, key=lambda r: r["wall"])
    return f"{r['wall'] * 1e3:.3g} ms ({fmt_x(c, r['x'])})"


def problem_table(results, labels, cell_of):
    """A row per problem, a column per method label: cell_of(problem, curve)."""
    lines = ["| problem | " + " | ".join(labels) + " |", "|---|" + "---:|" * len(labels)]
    for problem, curves in results:
        by = {c["label"]: c for c in curves}
        cells = [cell_of(problem, by[lab]) if lab in by else "" for lab in labels]
        lines.append(f"| {problem.title} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def problem_section(problem, curves):
    L = [f"## {problem.title}", "", f"**What it tests.** {problem.tests}", "",
         f"**Reference.** {problem.reference} Scale for the order fit: {problem.scale:g} {problem.unit}.", ""]
    if problem.note:
        L += [f"**Finding.** {problem.note}", ""]
    L += [f"![{problem.title}](accuracy/{problem.key}.png)", "",
          f"| method | step h / tolerance | error at T ({problem.unit}) | internal steps | ms per simulated s |",
          "|---|---:|---:|---:|---:|"]
    for c in curves:
        for i, r in enumerate(c["rows"]):
            err = ("failed: " + (r["failure"] or "")[:60]) if r["error"] is None \
                else f"{r['error']:.3e}" + ("" if i in c["used"] else " ·")
            wall = "–" if r["wall"] is None else f"{r['wall'] * 1e3:.4g}"
            internal = "–" if r["internal"] is None else str(r["internal"])
            L.append(f"| {c['label'] if i == 0 else ''} | {fmt_x(c, r['x'])} | {err} | {internal} | {wall} |")
        exp = "–" if c["expected"] is None else f"{c['expected']:g}"
        L.append(f"| | **order** | **{order_text(c)}** (expected {exp}: {c['verdict']}) | | |")
    L += ["", "(· = point left out of the order fit: saturated or at the rounding floor.)", ""]
    return "\n".join(L)


def write_markdown(path, results, model_methods, meta):
    """docs/reports/accuracy.md: templates/accuracy.md filled with the sweeps' figures."""
    labels = []
    for _, curves in results:
        labels += [c["label"] for c in curves if c["label"] not in labels]
    text = template.fill("accuracy", {
        "args": meta["args"], "date": meta["date"], "cpu": meta["cpu"], "source": meta["source"],
        "methods": ", ".join(f"`{n}` = {v}" for n, v, _ in model_methods),
        "comm": f"{COMM:g}", "runs": meta["runs"],
        "expected": ", ".join(f"{k} {v:g} (± {ORDER_TOLERANCE[k]:g})" for k, v in EXPECTED_ORDER.items()),
        "adaptive_order": f"{ADAPTIVE_ORDER:g}", "adaptive_tolerance": f"{ADAPTIVE_TOLERANCE:g}",
        "findings": findings(results),
        "orders_table": problem_table(results, labels, lambda p, c: order_cell(c)),
        "cost_table": problem_table(results, labels, cost_cell),
        "problems": "\n".join(problem_section(p, curves) for p, curves in results),
    })
    path.write_text(text)


# ----------------------------------------------------------------------------------
# modes

def report(args, builder, folder):
    probs = problems()
    if args.quick:
        probs = [p for p in probs if p.smooth]
    if args.problems:
        keys = args.problems.split(",")
        probs = [p for p in probs if p.key in keys]
    runs = 1 if args.quick else args.runs
    out = pathlib.Path(args.out)
    (out / "accuracy").mkdir(parents=True, exist_ok=True)
    peers_file = pathlib.Path(args.peers)
    peers = json.loads(peers_file.read_text()) if peers_file.is_file() else []
    results, methods_seen = [], None
    t_start = time.perf_counter()
    for p in probs:
        model = Model(builder(p.scene), folder)
        methods_seen = model.methods
        print(f"{p.key}: {p.title} (T = {p.T:g} s; methods "
              f"{', '.join(n for n, _, _ in model.methods)})", flush=True)
        curves = sweep(model, p, args.quick, runs, log=(print if args.verbose else lambda s: None))
        results.append((p, curves))
        plot(p, curves, out / "accuracy" / f"{p.key}.png", peers)
        for c in curves:
            print(f"  {c['label']:34s} order {order_text(c):>6s}  "
                  f"(expected {c['expected'] if c['expected'] is not None else '–'}): "
                  f"{c['verdict']}", flush=True)
    plot_grid(results, out / "accuracy" / "work_precision.png")
    meta = {"args": (" --quick" if args.quick else ""), "runs": runs,
            "date": time.strftime("%Y-%m-%d"), "cpu": cpu_name(), "source": source_state()}
    write_markdown(out / "accuracy.md", results, methods_seen or [], meta)
    fails = [(p.key, c["label"]) for p, curves in results for c in curves
             if c["verdict"].startswith("FAIL")]
    print(f"wrote {out / 'accuracy.md'} and {out / 'accuracy'}/*.png "
          f"({time.perf_counter() - t_start:.1f} s)")
    if fails:
        print("orders off their expected values: " +
              ", ".join(f"{k}/{m}" for k, m in fails))
        return 1
    print("orders: all as expected (or not judged)")
    return 0


def cpu_name():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip() + f", {os.cpu_count()} CPUs"
    except OSError:
        pass
    return "unknown CPU"


def scene_state(model, outputs):
    """Positions (m) and orientations (quaternions) of every body, from the outputs."""
    pos, ori = {}, {}
    for name in outputs:
        if name.endswith(".position[1]"):
            b = name[:-len(".position[1]")]
            pos[b] = vec(outputs, f"{b}.position")
        elif name.endswith(".orientation[1]"):
            b = name[:-len(".orientation[1]")]
            ori[b] = vec(outputs, f"{b}.orientation", 4)
    return pos, ori


def state_error(a, b):
    """max over bodies of |position difference| components (m) and rotation angles (rad)."""
    pa, oa = a
    pb, ob = b
    errs = [float(np.max(np.abs(pa[k] - pb[k]))) for k in pa]
    errs += [rotation_angle(oa[k], ob[k]) for k in oa]
    return max(errs) if errs else float("nan")


def scene_mode(args, builder, folder):
    scene_dict = json.loads(pathlib.Path(args.scene).read_text())
    T = args.stop_time
    base = float(scene_dict.get("solver", {}).get("step", 1e-3))
    model = Model(builder(scene_dict), folder)
    if not any(n.endswith((".position[1]", ".orientation[1]")) for n in model.vars):
        raise ReportError("report accuracy: the scene exposes no position or orientation output")
    comm = min(COMM, T)
    names = {n: v for n, v, _ in model.methods}
    # reference: the adaptive method at a tight tolerance, else rk4 (or the method of
    # highest expected order) at the scene's step / 64
    adaptive = [(n, v) for n, v, d in model.methods if model.is_adaptive(n, d)]
    if adaptive:
        ref_label = f"{adaptive[0][0]} at tolerance 1e-12 (solver.step {base / 4:g} s)"
        out, _, _, fail = model.run(adaptive[0][1], T, step=base / 4, tolerance=1e-12, comm=comm)
    else:
        ref_name = "rk4" if "rk4" in names else max(
            names, key=lambda n: EXPECTED_ORDER.get(n, 0))
        ref_label = f"{ref_name} at h = {base / 64:.3g} s (scene step / 64)"
        out, _, _, fail = model.run(names[ref_name], T, step=base / 64, comm=comm)
    if out is None:
        raise ReportError(f"report accuracy: the reference run failed: {fail}")
    ref = scene_state(model, out)
    print(f"scene {scene_dict.get('name', 'scene')} to T = {T:g} s; reference: {ref_label}")
    print("error: max over bodies of |position component| (m) and orientation angle (rad) at T")
    rows = []
    factors = [8, 4, 2, 1, 0.5, 0.25] if not args.quick else [4, 1, 0.25]
    for n, v, d in model.methods:
        if model.is_adaptive(n, d):
            configs = [("tolerance", tol, dict(step=comm, tolerance=tol))
                       for tol in ([1e-3, 1e-5, 1e-7, 1e-9] if not args.quick else [1e-4, 1e-7])]
        else:
            hs = sorted({base * f for f in factors if base * f <= comm}, reverse=True)
            configs = [("step", h, dict(step=h, tolerance=0.0 if model.has_tolerance and
                                         model.is_adaptive(n, d) else None)) for h in hs]
        for kind, x, kw in configs:
            o, wall, internal, fail = model.run(v, T, runs=args.runs if not args.quick else 1,
                                                comm=comm, **kw)
            err = state_error(scene_state(model, o), ref) if o is not None else None
            rows.append({"method": n, "kind": kind, "x": x, "error": err, "wall": wall,
                         "internal": internal, "failure": fail})
    print(f"{'method':16s} {'step/tol':>12s} {'error':>11s} {'ms per sim s':>13s} {'steps':>9s}")
    for r in rows:
        x = f"tol {r['x']:.0e}" if r["kind"] == "tolerance" else f"h {r['x']:.4g}"
        err = "failed" if r["error"] is None else f"{r['error']:.3e}"
        wall = "–" if r["wall"] is None else f"{r['wall'] * 1e3:.4g}"
        steps = "–" if r["internal"] is None else str(r["internal"])
        ok = "  <= TOL" if r["error"] is not None and r["error"] <= args.tolerance else ""
        print(f"{r['method']:16s} {x:>12s} {err:>11s} {wall:>13s} {steps:>9s}{ok}")
    good = [r for r in rows if r["error"] is not None and r["wall"] is not None
            and r["error"] <= args.tolerance]
    if not good:
        best = min((r for r in rows if r["error"] is not None), key=lambda r: r["error"],
                   default=None)
        print(f"recommendation: none of the tried methods and steps reaches TOL = "
              f"{args.tolerance:g}" + ("" if best is None else
                                       f" (smallest error {best['error']:.3e} with "
                                       f"{best['method']}); lower solver.step below the tried range"))
        return 2
    r = min(good, key=lambda r: r["wall"])
    setting = (f"solver.tolerance = {r['x']:g} (solver.step = {comm:g} s)"
               if r["kind"] == "tolerance" else f"solver.step = {r['x']:.6g} s")
    print(f"recommendation: solver.method = {r['method']}, {setting}: error {r['error']:.2e} "
          f"<= {args.tolerance:g}, {r['wall'] * 1e3:.4g} ms per simulated second")
    return 0


def main(argv=None, prog=None):
    p = argparse.ArgumentParser(prog=prog, description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true",
                   help="a few steps per method, 1 run each, smooth problems; exit 1 on a wrong order")
    p.add_argument("--out", default=str(ROOT / "docs" / "reports"), help="output directory (default docs/reports/)")
    p.add_argument("--runs", type=int, default=5, help="timed runs per configuration (median)")
    p.add_argument("--problems", help="comma-separated problem keys (default: all)")
    p.add_argument("--scene", help="a scene file: recommend a method and step for it")
    p.add_argument("--tolerance", type=float, help="with --scene: the error to stay below")
    p.add_argument("--stop-time", type=float, default=2.0, help="with --scene: T (default 2 s)")
    p.add_argument("--build", default=os.environ.get("RIGIDFMU_BUILD", str(ROOT / "build")))
    p.add_argument("--no-build", action="store_true", help="do not (re)build the core")
    p.add_argument("--verbose", "-v", action="store_true", help="print every run")
    p.add_argument("--peers", default=str(ROOT / "docs" / "reports" / "peers.json"),
                   help="the peers' measurements (scripts/peers.sh) to draw beside ours, if the file exists")
    args = p.parse_args(argv)
    if args.scene and args.tolerance is None:
        p.error("--scene needs --tolerance")
    build = pathlib.Path(args.build).resolve()
    ensure_core(build, args.no_build, "report accuracy")
    folder = tempfile.mkdtemp(prefix="rigidfmu-accuracy-")
    try:
        builder = functools.partial(package, build, folder)  # scene dict -> FMU path
        return scene_mode(args, builder, folder) if args.scene else report(args, builder, folder)
    finally:
        shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main(prog="scripts/report_accuracy.sh"))
