"""The performance report (issue 9): what a step costs, in the core and through FMI, and
beside MuJoCo on the same scenes, at equal or better accuracy. Figures only: nothing
here is asserted; the targets are printed with PASS or MISS.

1. Core (bench/bench_core.cpp, Google Benchmark): ns per body-step of N free tumbling
   bodies with every method, and piles of N cubes falling on a floor with the time
   split into broadphase, narrowphase, response and integration.
2. FMU (fmpy's FMU2Slave): one fmi2DoStep of one internal step, reading every Real
   output, and the FMI layer's overhead over the core, for 1 and 100 bodies.
3. MuJoCo (scripts/reports/performance_peers.py in .venv-peers): the same piles and free bodies;
   the free body's orientation error at T against scipy's DOP853 (the accuracy
   report's reference), ours and theirs, so that ratios are quoted at equal accuracy;
   then the pile of 1000 (100 in quick mode) timed again, ours and theirs interleaved
   round by round, the ratio its target is judged on.
4. The same piles over 3 s (BM_PileWindows, answered by the constraint solver, the one
   contact solver), timed while they fall (first second) and at rest (third second),
   with the stages' shares, the contact points per solve, the overlap in the output
   state and the fastest body at 3 s, and again with sleep off (BM_PileAwake); the pile
   of 1000 (100 in quick mode) at rest timed round by round with MuJoCo's at rest
   (Euler), the ratio its target is judged on; the wide pile (BM_PileWide); the two
   largest piles again with the cubes tilted by other patterns (OTHER_TILTS), since a
   fall is chaotic and one fall's growth may be its own.
5. A chain of 100 links hinged end to end (issue 41) swinging down from horizontal for
   2 s (0.2 s in quick mode), h = 1 ms: ours (BM_Chain, rk4) and MuJoCo's (a chain of
   hinge joints, Euler and RK4) timed round by round, the ratio to MuJoCo's Euler its
   target is judged on; our joints' drift and both engines' energy error.
6. Convex meshes (issue 42, reports.performance_meshes): the narrowphase's time per pair
   for hulls of 100-1000 vertices on the floor and on one another, beside the cube's
   (BM_Narrow), as ratios to it; a pile of 100 pebbles falling into a mesh bin beside
   MuJoCo (BM_PileHulls). --meshes-only runs this part alone and renders the report
   again from OUT/performance/bench.json with its figures replaced (and its date noted).
7. Writes OUT/performance.md, OUT/performance/*.png and OUT/performance/bench.json.

Times are CPU times (the machine is shared), medians of repeats.

usage: scripts/bench.sh [--quick] [--out DIR] [--build BUILD_DIR] [--chain-only | --meshes-only]"""
import argparse
import json
import math
import os
import pathlib
import platform
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

from reports import performance_meshes, template
from reports import scenes as bench_scenes
from reports.accuracy import cpu_name
from reports.provenance import source_state
from rigidfmu import driver
from rigidfmu.errors import ReportError
from rigidfmu.native import SOURCE_ROOT
from rigidfmu.references.quaternion import rotation_angle
from rigidfmu.references.torque_free import torque_free_reference

ROOT = SOURCE_ROOT  # the source tree: its build, scripts and docs
PEERS_PYTHON = ROOT / ".venv-peers" / "bin" / "python"

# The targets
RK4_TARGET_NS = 100.0        # ns per body-step, free bodies, rk4, N = 1000
COLLIDING_RATIO_TARGET = 1.3  # bodies that can collide but touch nothing, over free ones (FMU)
PILE_RATIO_TARGET = 0.5      # our time per simulated second / MuJoCo's, pile of 1000
PENETRATION_TARGET = 1e-3    # m
CHAIN_RATIO_TARGET = 1.0     # our time per simulated second / MuJoCo's (Euler), chain of 100 (issue 41)
DRIFT_TARGET = 1e-3          # m, the chain's joints apart
# the stages of WorldData::profile, in the 3 s piles' section's order
STAGES = ("integration", "broadphase", "narrowphase", "response")
# the step's stages in the order it runs them (src/world.h, Stage): the benchmark's
# <window>_ns_stage_<name> and <window>_runs_stage_<name>
STEP_STAGES = ("plan", "wake", "collide", "integrate", "solve", "impacts", "commit", "islands", "sleep")


def log(msg):
    print(msg, flush=True)


# ----------------------------------------------------------------------------------
# 1. the core

def run_core(build, scenes, quick, pattern=None, reps=1):
    """{("free", method, n): entry} and {("pile", n): entry} from rigid-bench-core's JSON;
    with repetitions, the median aggregate (Google Benchmark takes the median of each
    counter too). With a pattern, only the piles it matches, `reps` times."""
    exe = build / "rigid-bench-core"
    free_n = "(1|10|100|1000)" if quick else "(1|10|100|1000|10000)"
    pile_n = "(10|100)" if quick else "(10|100|1000)"
    # free bodies: many short iterations, so min_time and repetitions; piles: one whole
    # simulated second per repetition
    runs = [(f"^BM_Free/[A-Za-z0-9]+/{free_n}$", "0.05" if quick else "0.2", 1 if quick else 5),
            (f"^BM_Pile/{pile_n}/", None, 1 if quick else 3)]
    if pattern:
        runs = [(pattern, None, reps)]
    results = {}
    context = None
    for pattern, min_time, reps in runs:
        with tempfile.NamedTemporaryFile(suffix=".json") as f:
            subprocess.run([str(exe), str(scenes), f"--benchmark_filter={pattern}",
                            *([f"--benchmark_min_time={min_time}"] if min_time else []),
                            f"--benchmark_repetitions={reps}",
                            "--benchmark_report_aggregates_only=true" if reps > 1 else
                            "--benchmark_report_aggregates_only=false",
                            "--benchmark_format=console", "--benchmark_out_format=json",
                            f"--benchmark_out={f.name}"], check=True, stdout=sys.stdout)
            data = json.load(open(f.name))
        context = data["context"]
        for b in data["benchmarks"]:
            if reps > 1 and b.get("aggregate_name") != "median":
                continue
            parts = b["run_name"].split("/")
            if parts[0] == "BM_Free":
                key = ("free", parts[1], int(parts[2]))
            elif parts[0] == "BM_PileWindows":
                key = ("windows", int(parts[1]))
            elif parts[0] == "BM_PileAwake":
                key = ("awake", int(parts[1]))
            elif parts[0] == "BM_PileWide":
                key = ("wide", int(parts[1]))
            elif parts[0] == "BM_Chain":
                key = ("chain", int(parts[1]), int(parts[2]))
            else:
                key = ("pile", int(parts[1]))
            results[key] = b
    return results, context


def free_table(core):
    """{method: {n: ns per body-step}}"""
    out = {}
    for key, b in core.items():
        if key[0] == "free":
            # a rate counter inverted: seconds per body-step in the JSON (the console
            # shows it with an SI prefix)
            out.setdefault(key[1], {})[key[2]] = b["ns_per_body_step"] * 1e9
    return out


def pile_table(core):
    """{n: {phase: us per step, total, per simulated second, penetration}}"""
    out = {}
    for key, b in core.items():
        if key[0] != "pile":
            continue
        scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
        cpu = b["cpu_time"] * scale  # s for one simulated second (iterations: 1)
        wall = b["real_time"] * scale
        steps = b["steps_ok"]
        # The profile reads the wall clock (steady_clock): each phase is taken as its
        # share of the wall time, applied to the CPU time, so that the phases and
        # "other" add up to the CPU total even while the machine is shared.
        share = cpu / wall
        phases = {p: b[f"us_{p}"] * share for p in ("broadphase", "narrowphase", "response", "integration")}
        total = cpu / steps * 1e6
        out[key[1]] = dict(phases, other=total - sum(phases.values()), total_us=total,
                           s_per_simulated_s=cpu / b["sim_seconds"] if steps else math.nan,
                           steps_ok=steps, steps=round(b["sim_seconds"] / bench_scenes.PILE_STEP),
                           max_penetration_m=b["max_penetration_m"],
                           max_overlap_state_m=b.get("max_overlap_state_m", math.nan),
                           max_speed_end_mps=b.get("max_speed_end_mps", math.nan))
    return dict(sorted(out.items()))


def window_figures(b):
    """The figures of one BM_PileWindows (or BM_PileAwake, BM_PileWide) entry: per window
    (fall: 0-1 s, rest: 2-3 s) the CPU time per simulated second and per step, the
    stages' shares of the steps' wall time (the profile's clock; "other" is the rest of
    the step), the solves per step and the contact points per solve (the solver's work:
    its sub-steps are fixed); and over the run the overlap in the output state, the
    fastest body's speed at 1 s and 3 s and the bodies asleep at 3 s."""
    out = {"steps_ok": b["steps_ok"], "steps": b["steps_planned"],
           "max_overlap_state_m": b["max_overlap_state_m"], "max_overlap_rest_m": b["max_overlap_rest_m"],
           "max_speed_1s_mps": b["max_speed_1s_mps"], "max_speed_3s_mps": b["max_speed_3s_mps"],
           "asleep_3s": b.get("asleep_3s", 0.0)}
    for w in ("fall", "rest"):
        out[w] = window_of(b, w, bench_scenes.PILE_STEP)
    return out


def window_of(b, w, h):
    """One timed window `w` of a benchmark entry whose steps are h long (BM_PileWindows'
    fall and rest, BM_Chain's swing): the CPU time per simulated second and per step,
    the stages' shares of the steps' wall time, the solves per step and the contact
    points per solve."""
    steps, cpu, wall = b[f"{w}_steps"], b[f"{w}_cpu_s"], b[f"{w}_wall_ns"]
    shares = {s: b[f"{w}_ns_{s}"] / wall if wall > 0 else math.nan for s in STAGES}
    shares["other"] = 1.0 - sum(shares.values())
    stage_shares = {s: b[f"{w}_ns_stage_{s}"] / wall if wall > 0 else math.nan for s in STEP_STAGES}
    stage_shares["other"] = 1.0 - sum(stage_shares.values())
    solves = b[f"{w}_solves"]
    return {"steps": steps,
            # a window cut short by a failed step: the time of the steps it has
            "s_per_simulated_s": cpu / (steps * h) if steps else math.nan,
            "us_per_step": cpu / steps * 1e6 if steps else math.nan,
            "shares": shares, "stage_shares": stage_shares,
            "solves_per_step": solves / steps if steps else math.nan,
            # the contact points a solve answered, each through the same fixed
            # sub-steps and relax pass; none when no solve ran (every island asleep)
            "points_per_solve": b[f"{w}_points_per_solve"] if solves else 0.0}


def median_entry(entries):
    """Each numeric field's median over several runs of one benchmark, as Google
    Benchmark's median aggregate takes it of every counter."""
    return {k: statistics.median(e[k] for e in entries) for k, v in entries[0].items()
            if isinstance(v, (int, float))}


def run_windows(build, scenes, folder, quick):
    """BM_PileWindows over the pile counts. The largest pile (1000; 100 in quick mode)
    is timed round by round with MuJoCo's at rest, ours once then theirs once, each in
    its own process (as interleaved_pile_ratio does for the first second): its figures
    are the medians over the rounds, so that the rounds are also its repetitions and the
    slow pile is not run twice. Without MuJoCo, its repetitions alone. Then every pile
    once with sleep off (BM_PileAwake: the solver alone). Returns ({n: figures},
    {n, rounds, ratio} or None, {n: figures with sleep off})."""
    counts = bench_scenes.PILE_COUNTS[:2] if quick else bench_scenes.PILE_COUNTS
    big, rounds = counts[-1], 1 if quick else 3
    entries = {}
    if len(counts) > 1:
        small, _ = run_core(build, scenes, quick, pattern=f"^BM_PileWindows/({'|'.join(map(str, counts[:-1]))})/",
                            reps=1 if quick else 3)
        entries.update({k[1]: b for k, b in small.items()})
    interleaved = None
    if PEERS_PYTHON.exists():
        runs, rows = [], []
        for _ in range(rounds):
            ours, _ = run_core(build, scenes, quick, pattern=f"^BM_PileWindows/{big}/", reps=1)
            runs.append(ours[("windows", big)])
            mine = window_figures(runs[-1])["rest"]["s_per_simulated_s"]
            out = pathlib.Path(folder) / "pile_rest_timing.json"
            subprocess.run([str(PEERS_PYTHON), "-m", "reports.performance_peers", str(scenes), str(out),
                            "--pile-timing", str(big), "--at-rest"], check=True)
            theirs = json.loads(out.read_text())["s_per_simulated_s"]
            rows.append({"ours": mine, "mujoco": theirs, "ratio": mine / theirs})
            log(f"pile {big} at rest, round {len(rows)}: ours {mine:.3g} s, MuJoCo {theirs:.3g} s "
                f"per simulated s, ratio {mine / theirs:.2f}")
        entries[big] = median_entry(runs)
        interleaved = {"n": big, "rounds": rows, "ratio": statistics.median(r["ratio"] for r in rows)}
    else:
        ours, _ = run_core(build, scenes, quick, pattern=f"^BM_PileWindows/{big}/", reps=rounds)
        entries[big] = ours[("windows", big)]
    awake, _ = run_core(build, scenes, quick, pattern=f"^BM_PileAwake/({'|'.join(map(str, counts))})/", reps=1)
    return ({n: window_figures(entries[n]) for n in sorted(entries)}, interleaved,
            {k[1]: window_figures(b) for k, b in sorted(awake.items())})


# Other tilt patterns (reports.scenes --tilt) than the benchmark's: a falling pile
# is chaotic, so the falling piles are run again under these to show whether a growth
# read from one fall holds for others.
OTHER_TILTS = ((1.3, 2.9), (0.7, 1.9), (2.1, 3.1))


def run_tilts(build, folder, quick):
    """BM_PileWindows's two largest piles (10 and 100 in quick mode) once under each of
    OTHER_TILTS, their scenes written to `folder`: {"A,B": {n: figures}}."""
    counts = bench_scenes.PILE_COUNTS[:2] if quick else bench_scenes.PILE_COUNTS[-2:]
    out = {}
    for tilt in OTHER_TILTS:
        scenes = pathlib.Path(folder) / f"tilt_{tilt[0]}_{tilt[1]}"
        scenes.mkdir(parents=True, exist_ok=True)
        for n in counts:  # only the scenes this run reads
            (scenes / f"pile_{n}.json").write_text(json.dumps(bench_scenes.pile_scene(n, tilt=tilt)))
        core, _ = run_core(build, scenes, quick, pattern=f"^BM_PileWindows/({'|'.join(map(str, counts))})/")
        out[f"{tilt[0]},{tilt[1]}"] = {k[1]: window_figures(b) for k, b in sorted(core.items())}
    return out


def run_wide(build, scenes, quick):
    """BM_PileWide: the wide pile (bench_scenes.WIDE_PILE cubes in columns of the pile of
    100's height), the medians of 3 runs; {} in quick mode (it is as dear as the pile of
    1000)."""
    if quick:
        return {}
    wide, _ = run_core(build, scenes, quick, pattern=f"^BM_PileWide/{bench_scenes.WIDE_PILE}/", reps=3)
    return {k[1]: window_figures(b) for k, b in sorted(wide.items())}


def chain_energy_scale(n=bench_scenes.CHAIN_LINKS):
    """M g L (J) of the chain: its mass, gravity and its length; the energy errors are
    given as fractions of it."""
    return (n * bench_scenes.CHAIN_LINK_MASS) * bench_scenes.G * (n * bench_scenes.CHAIN_LINK[0])


def chain_figures(b):
    """Our figures of one BM_Chain entry: the swing's timing and stages (window_of), the
    joints' drift, the energy error as a fraction of chain_energy_scale, the tip at the
    end."""
    scale = chain_energy_scale(round(b["joints"]))
    return {"steps_ok": b["steps_ok"], "steps": b["steps_planned"], "step_s": b["step_s"],
            "sim_seconds": b["sim_seconds"], **window_of(b, "swing", b["step_s"]),
            "max_drift_m": b["max_drift_m"], "max_axis_drift_rad": b["max_axis_drift_rad"],
            "max_energy_error": b["max_energy_error_j"] / scale, "energy_error_end": b["energy_error_end_j"] / scale,
            "max_speed_mps": b["max_speed_mps"], "tip_m": [b["tip_x_m"], b["tip_z_m"]]}


def run_chain(build, scenes, folder, quick):
    """The chain of bench_scenes.CHAIN_LINKS links over 2 s (0.2 s in quick mode): ours
    (BM_Chain) once, then MuJoCo's (Euler and RK4, performance_peers --chain) once, each
    in its own process, round by round (5 rounds, 1 in quick mode); without MuJoCo, ours
    alone. Our figures are the medians over the rounds (drift and energy are the same in
    every round: a run is deterministic), MuJoCo's timings too, its energy figures those
    of the last round's untimed runs. Ratios: each round's ours over its MuJoCo's; the
    median."""
    n, ms, rounds = bench_scenes.CHAIN_LINKS, 200 if quick else 2000, 1 if quick else 5
    T = ms * 1e-3
    runs, rows, theirs = [], [], None
    for _ in range(rounds):
        ours, _ = run_core(build, scenes, quick, pattern=f"^BM_Chain/{n}/{ms}/", reps=1)
        runs.append(ours[("chain", n, ms)])
        mine = chain_figures(runs[-1])["s_per_simulated_s"]
        if not PEERS_PYTHON.exists():
            continue
        out = pathlib.Path(folder) / "chain.json"
        subprocess.run([str(PEERS_PYTHON), "-m", "reports.performance_peers", str(scenes), str(out),
                        "--chain", str(n), "--T", f"{T:g}"], check=True)
        theirs = json.loads(out.read_text())
        euler, rk4 = theirs["Euler"]["s_per_simulated_s"], theirs["RK4"]["s_per_simulated_s"]
        rows.append({"ours": mine, "mujoco": euler, "ratio": mine / euler, "mujoco_rk4": rk4, "ratio_rk4": mine / rk4})
        log(f"chain {n} over {T:g} s, round {len(rows)}: ours {fmt_s(mine)}, MuJoCo Euler {fmt_s(euler)}, "
            f"RK4 {fmt_s(rk4)} per simulated s; ratio to Euler {mine / euler:.2f}, to RK4 {mine / rk4:.2f}")
    mujoco = None
    if theirs:
        scale = chain_energy_scale(n)
        mujoco = {"engine": theirs["engine"]}
        for integrator in ("Euler", "RK4"):
            m = theirs[integrator]
            mujoco[integrator] = {
                "step_s": m["dt"], "warnings": m["warnings"], "tip_m": [m["tip_x_m"], m["tip_z_m"]],
                "s_per_simulated_s": statistics.median(r["mujoco" if integrator == "Euler" else "mujoco_rk4"]
                                                       for r in rows),
                "max_energy_error": m["max_energy_error_j"] / scale,
                "energy_error_end": m["energy_error_end_j"] / scale}
            mujoco[integrator]["us_per_step"] = mujoco[integrator]["s_per_simulated_s"] * m["dt"] * 1e6
    ours = chain_figures(runs[0])
    for key in ("s_per_simulated_s", "us_per_step"):  # the timings: medians over the rounds
        ours[key] = statistics.median(chain_figures(b)[key] for b in runs)
    return {"n": n, "T": T, "step_s": ours["step_s"], "energy_scale_j": chain_energy_scale(n),
            "ours": ours, "mujoco": mujoco, "rounds": rows,
            "ratio": statistics.median(r["ratio"] for r in rows) if rows else None,
            "ratio_rk4": statistics.median(r["ratio_rk4"] for r in rows) if rows else None}


def chain_targets(chain):
    """Issue 41's: the chain's time per simulated second against MuJoCo's Euler at the
    same step (judged on the interleaved rounds), and its joints' drift."""
    n, T = chain["n"], chain["T"]
    ours = chain["ours"]
    label = (f"chain of {n} swinging from horizontal (0–{T:g} s, h = {chain['step_s'] * 1e3:g} ms): time per "
             f"simulated second ≤ {CHAIN_RATIO_TARGET:g}x MuJoCo's (Euler)")
    if chain["ratio"] is not None:
        rounds = ", ".join(f"{r['ratio']:.2f}" for r in chain["rounds"])
        rows = [(label, f"ratio {chain['ratio']:.2f}, the median of {len(chain['rounds'])} interleaved rounds "
                        f"({rounds}): {fmt_s(ours['s_per_simulated_s'])} vs "
                        f"{fmt_s(chain['mujoco']['Euler']['s_per_simulated_s'])}",
                 "PASS" if chain["ratio"] <= CHAIN_RATIO_TARGET else "MISS")]
    else:
        rows = [(label, f"not measured (no MuJoCo); ours {fmt_s(ours['s_per_simulated_s'])}", "–")]
    complete = ours["steps_ok"] == ours["steps"]
    rows.append((f"chain of {n}: joint drift < {DRIFT_TARGET * 1e3:g} mm",
                 f"{ours['max_drift_m'] * 1e3:.3f} mm, the largest over joints and steps (hinge axes apart: "
                 f"{ours['max_axis_drift_rad']:.2g} rad at most)"
                 + ("" if complete else f" (a step failed: {ours['steps_ok']:.0f} of {ours['steps']:.0f} steps)"),
                 "PASS" if complete and ours["max_drift_m"] < DRIFT_TARGET else "MISS"))
    return rows


# ----------------------------------------------------------------------------------
# 2. the FMU

def build_fmus(build, scenes, names, folder):
    env = dict(os.environ, RIGIDFMU_SKIP_SETUP="1", RIGIDFMU_BUILD=str(build))
    out = {}
    for name in names:
        fmu = folder / f"{name}.fmu"
        subprocess.run([str(ROOT / "scripts" / "build_fmu.sh"), str(scenes / f"{name}.json"), str(fmu)],
                       check=True, env=env, stdout=subprocess.DEVNULL)
        out[name] = fmu
    return out


class Slave(driver.Slave):
    """One instance of an FMU (rigidfmu.driver), initialised with the given Real parameters."""

    def __init__(self, fmu, folder, params=None):
        super().__init__(fmu, "bench", folder=folder, prefix="bench-", recorder=False)
        self.initialize(params)
        self.t = 0.0
        self.real_outputs = [v.valueReference for v in self.model.real_outputs()]

    def steps(self, h, n):
        """n calls of fmi2DoStep(h); the CPU seconds they took. Time is t0 + k h, never
        summed (the FMU checks the communication point)."""
        t_begin = self.t
        t0 = time.process_time()
        for k in range(n):
            self.slave.doStep(t_begin + k * h, h)
        dt = time.process_time() - t0
        self.t = t_begin + n * h
        return dt

    def close(self):
        self.slave.terminate()
        self.free()


def median_per_call(fn, calls, repeats):
    """Median over repeats of the CPU seconds per call of fn(calls) (fn returns CPU s)."""
    return statistics.median(fn(calls) / calls for _ in range(repeats))


def fmu_bench(fmus, folder, quick):
    """Per body count: doStep of one internal step (1 ms), getReal of every Real output,
    a one-variable getReal (the floor of a call from Python through ctypes), and doStep
    of 1 s (1000 internal steps) for the amortised cost; seconds, medians."""
    calls, repeats = (500, 3) if quick else (3000, 7)
    out = {}
    for n, fmu in fmus.items():
        s = Slave(fmu, folder)
        s.steps(1e-3, 50)  # warm-up: first-touch of the instance's memory
        do_step = median_per_call(lambda c: s.steps(1e-3, c), calls, repeats)
        vrs = s.real_outputs

        def reads(c, vrs=vrs):
            t0 = time.process_time()
            for _ in range(c):
                s.slave.getReal(vrs)
            return time.process_time() - t0
        get_all = median_per_call(reads, calls, repeats)
        get_one = median_per_call(lambda c: reads(c, vrs[:1]), calls, repeats)
        long_calls = 2 if quick else 5
        amortised = statistics.median(s.steps(1.0, long_calls) / (long_calls * 1000) for _ in range(repeats))
        s.close()
        out[n] = {"do_step_s": do_step, "get_all_s": get_all, "outputs": len(vrs),
                  "get_one_s": get_one, "amortised_step_s": amortised}
        log(f"FMU free_{n}: doStep {do_step * 1e6:.2f} us, getReal({len(vrs)}) {get_all * 1e6:.2f} us, "
            f"getReal(1) {get_one * 1e6:.2f} us, amortised {amortised * 1e6:.2f} us/step")
    return out


def colliding_cost(build, scenes, folder, quick):
    """Free bodies that can collide but touch nothing (tumbling_<N>: 3 m apart) against
    the same bodies out of collisions (free_<N>), and the same bodies driven
    (driven_<N>), through the FMU: CPU per body-step, amortised over communication
    steps of 1 s, the three timed in turn round by round; medians."""
    n = 100 if quick else 1000
    kinds = (("free", f"free_{n}"), ("colliding", f"tumbling_{n}"), ("driven", f"driven_{n}"))
    fmus = build_fmus(build, scenes, [name for _, name in kinds], folder)
    per = {key: [] for key, _ in kinds}
    for _ in range(1 if quick else 3):
        for key, name in kinds:
            s = Slave(fmus[name], folder)
            s.steps(1e-3, 10)  # warm-up
            per[key].append(s.steps(1.0, 1) / (1000 * n))
            s.close()
    free, colliding, driven = (statistics.median(per[key]) for key, _ in kinds)
    log(f"FMU tumbling_{n} (can collide) {colliding * 1e9:.0f} ns vs free_{n} {free * 1e9:.0f} ns vs "
        f"driven_{n} {driven * 1e9:.0f} ns per body-step")
    return {"n": n, "free_ns": free * 1e9, "colliding_ns": colliding * 1e9, "ratio": colliding / free,
            "driven_ns": driven * 1e9, "driven_ratio": driven / colliding}


# ----------------------------------------------------------------------------------
# 3. accuracy of the free tumbling body, ours and MuJoCo's

def free_body(scenes):
    """Principal inertia (kg m^2) and omega0 (rad/s) of free_1's body, which starts unrotated."""
    b = json.loads((scenes / "free_1.json").read_text())["bodies"][0]
    return np.diag(np.array(b["inertia"])), np.array(b["angularVelocity"])


def our_free_accuracy(fmu, folder, T, dts, repeats):
    """Our rk4 through the FMU at each step: orientation error at T (rad) against the
    reference and CPU seconds per simulated second (communication steps of 1 s, so the
    FMI call is amortised as a master with coarse communication steps would have it)."""
    rows = []
    for dt in dts:
        times, q = [], None
        for r in range(repeats):
            s = Slave(fmu, folder, {"solver.step": dt, "solver.energyGainLimit": 0.0})
            times.append(s.steps(1.0, round(T)) / T)
            q = s.slave.getReal([s.vars[f"b0.orientation[{i}]"].valueReference for i in range(1, 5)])
            s.close()
        rows.append({"dt": dt, "q_end": list(q), "s_per_simulated_s": statistics.median(times)})
    return rows


def add_errors(rows, q_ref):
    for r in rows:
        r["error_rad"] = float(rotation_angle(r["q_end"], q_ref))


def equal_accuracy(ours, theirs):
    """For each of MuJoCo's runs: our cheapest run whose error is at most theirs, and
    the ratio of the times per simulated second (ours / theirs)."""
    out = []
    for m in theirs:
        ok = [o for o in ours if o["error_rad"] <= m["error_rad"]]
        best = min(ok, key=lambda o: o["s_per_simulated_s"]) if ok else None
        out.append({"mujoco": m, "ours": best,
                    "ratio": best["s_per_simulated_s"] / m["s_per_simulated_s"] if best else None})
    return out


def interleaved_pile_ratio(build, scenes, folder, n, rounds):
    """Our time per simulated second of pile_<n> over MuJoCo's, measured round by round
    (ours once, then theirs once, each in its own process): the two stand seconds apart
    instead of a minute, so a change of the shared machine's load moves both. Returns the
    rounds' {ours, mujoco, ratio} and the median ratio, or None without MuJoCo."""
    if not PEERS_PYTHON.exists():
        return None
    rows = []
    for _ in range(rounds):
        ours, _ = run_core(build, scenes, quick=True, pattern=f"^BM_Pile/{n}/", reps=1)
        mine = pile_table(ours)[n]["s_per_simulated_s"]
        out = pathlib.Path(folder) / "pile_timing.json"
        subprocess.run([str(PEERS_PYTHON), "-m", "reports.performance_peers", str(scenes), str(out),
                        "--pile-timing", str(n)], check=True)
        theirs = json.loads(out.read_text())["s_per_simulated_s"]
        rows.append({"ours": mine, "mujoco": theirs, "ratio": mine / theirs})
        log(f"pile {n} round {len(rows)}: ours {mine:.3g} s, MuJoCo {theirs:.3g} s per simulated s, "
            f"ratio {mine / theirs:.2f}")
    return {"n": n, "rounds": rows, "ratio": statistics.median(r["ratio"] for r in rows)}


def run_peers(scenes, folder, quick, T, dts):
    if not PEERS_PYTHON.exists():
        return None
    out = pathlib.Path(folder) / "peers.json"
    cmd = [str(PEERS_PYTHON), "-m", "reports.performance_peers", str(scenes), str(out),
           "--T", str(T), "--dts", ",".join(f"{d:g}" for d in dts)] + (["--quick"] if quick else [])
    subprocess.run(cmd, check=True)
    return json.loads(out.read_text())


# ----------------------------------------------------------------------------------
# 4. targets and checks, the plots

def slope(n1, t1, n2, t2):
    return math.log(t2 / t1) / math.log(n2 / n1)


def nlogn_slope(n1, n2):
    """The log-log slope of N log N between n1 and n2: growth 'no faster than N log N'
    means a measured slope at most this (1.18 from 100 to 1000, 1.12 from 1000 to 1e4)."""
    return slope(n1, n1 * math.log(n1), n2, n2 * math.log(n2))


def growth(points):
    """[(n1, n2, slope, N log N's slope)] between consecutive counts of {n: time per step}."""
    ns = sorted(points)
    return [(a, b, slope(a, points[a], b, points[b]), nlogn_slope(a, b)) for a, b in zip(ns, ns[1:])]


def targets(free, piles, peers, interleaved=None, colliding=None):
    rows = []
    rk4 = free.get("rk4", {})
    if 1000 in rk4:
        v = rk4[1000]
        rows.append(("free-body rk4 at 1000 bodies ≤ 100 ns per body-step", f"{v:.1f} ns",
                     "PASS" if v <= RK4_TARGET_NS else "MISS"))
    else:
        rows.append(("free-body rk4 at 1000 bodies ≤ 100 ns per body-step", "not measured", "–"))
    mj = {p["n"]: p for p in (peers or {}).get("piles", []) if p["integrator"] == "Euler"}
    if interleaved and interleaved["n"] == 1000:
        # judged on the rounds that time ours and theirs seconds apart
        rounds = ", ".join(f"{r['ratio']:.2f}" for r in interleaved["rounds"])
        separate = ""
        if 1000 in piles and 1000 in mj:
            separate = (f"; timed a minute apart in the full runs above, {piles[1000]['s_per_simulated_s']:.3g} s "
                        f"vs {mj[1000]['s_per_simulated_s']:.3g} s: "
                        f"{piles[1000]['s_per_simulated_s'] / mj[1000]['s_per_simulated_s']:.2f}")
        rows.append(("pile of 1000: time per simulated second ≤ ½ MuJoCo's",
                     f"ratio {interleaved['ratio']:.2f}, the median of {len(interleaved['rounds'])} interleaved "
                     f"rounds ({rounds}){separate}",
                     "PASS" if interleaved["ratio"] <= PILE_RATIO_TARGET else "MISS"))
    elif 1000 in piles and 1000 in mj:
        ratio = piles[1000]["s_per_simulated_s"] / mj[1000]["s_per_simulated_s"]
        rows.append(("pile of 1000: time per simulated second ≤ ½ MuJoCo's",
                     f"{piles[1000]['s_per_simulated_s']:.3g} s vs MuJoCo {mj[1000]['s_per_simulated_s']:.3g} s: "
                     f"ratio {ratio:.2f}", "PASS" if ratio <= PILE_RATIO_TARGET else "MISS"))
    else:
        rows.append(("pile of 1000: time per simulated second ≤ ½ MuJoCo's",
                     "not measured (quick run or no MuJoCo)", "–"))
    big = max(piles) if piles else None
    if big is not None:
        # judged on the state a step hands back (what the FMU outputs and what MuJoCo's
        # figure is of); the step's own last detection, before its response moved the
        # bodies, is an intermediate state, shown beside it
        pen = piles[big]["max_penetration_m"]
        state = piles[big]["max_overlap_state_m"]
        rows.append((f"pile of {big}: penetration ≤ 1 mm",
                     f"{state * 1e3:.2f} mm in the output state ({pen * 1e3:.2f} mm before the response)",
                     "PASS" if state <= PENETRATION_TARGET else "MISS"))
    if colliding:
        c = colliding
        rows.append((f"{c['n']} bodies that can collide but touch nothing: ≤ {COLLIDING_RATIO_TARGET}x the same "
                     "bodies out of collisions, through the FMU",
                     f"{c['colliding_ns']:.0f} ns vs {c['free_ns']:.0f} ns per body-step: ratio {c['ratio']:.2f}",
                     "PASS" if c["ratio"] <= COLLIDING_RATIO_TARGET else "MISS"))
        if "driven_ns" in c:
            rows.append((f"{c['n']} driven bodies: ≤ 1x the same bodies free (both can collide, touch nothing), "
                         "through the FMU",
                         f"{c['driven_ns']:.0f} ns vs {c['colliding_ns']:.0f} ns per body-step: ratio "
                         f"{c['driven_ratio']:.2f}", "PASS" if c["driven_ratio"] <= 1.0 else "MISS"))
    # time per step; free bodies from 100 up (below, the fixed cost of a step dominates)
    for label, pts in (("free rk4", {n: v * n for n, v in rk4.items() if n >= 100}),
                       ("piles", {n: p["total_us"] for n, p in piles.items()})):
        for a, b, s, limit in growth(pts):
            rows.append((f"{label}: growth {a} → {b} no faster than N log N (slope ≤ {limit:.2f})",
                         f"slope {s:.2f}", "PASS" if s <= limit else "MISS"))
    return rows


def equal_height_targets(windows, wide):
    """Growth from the pile of 100 (5 x 5 columns of 4) to the wide pile (16 x 16 columns
    of 4): N grows, the columns' height does not."""
    rows = []
    if 100 not in windows:
        return rows
    for n, m in wide.items():
        limit = nlogn_slope(100, n)
        for w, name in (("fall", "falling"), ("rest", "at rest")):
            a, b = windows[100][w]["us_per_step"], m[w]["us_per_step"]
            if not (math.isfinite(a) and math.isfinite(b)):
                continue
            s = slope(100, a, n, b)
            rows.append((f"equal height (columns of {bench_scenes.WIDE_LAYERS}) {name}: growth 100 → {n} "
                         f"no faster than N log N (slope ≤ {limit:.2f})", f"slope {s:.2f}",
                         "PASS" if s <= limit else "MISS"))
    return rows


def windows_targets(windows, peers, interleaved):
    """The targets of the piles over 3 s: the pile of 1000 at rest against MuJoCo's
    default at rest (judged on the interleaved rounds), the overlap in the output state
    over the 3 s, and the growth of a step's time at rest. Growth is judged where the
    piles of 100 and 1000 are at the same outcome: at rest here, and falling in columns of
    one height in equal_height_targets. (The cube-root piles' falling seconds are
    different events, columns of 4 and of 10: windows_checks.)"""
    rows = []
    label = "pile of 1000 at rest (2–3 s): time per simulated second ≤ 0.5x MuJoCo's (Euler, at rest)"
    if interleaved and interleaved["n"] == 1000:
        rounds = ", ".join(f"{r['ratio']:.2f}" for r in interleaved["rounds"])
        rows.append((label, f"ratio {interleaved['ratio']:.2f}, the median of {len(interleaved['rounds'])} "
                            f"interleaved rounds ({rounds})",
                     "PASS" if interleaved["ratio"] <= PILE_RATIO_TARGET else "MISS"))
    else:
        rows.append((label, "not measured (quick run: no pile of 1000)" if peers else "not measured (no MuJoCo)", "–"))
    if windows:
        big = max(windows)
        m = windows[big]
        rows.append((f"pile of {big} over 3 s: penetration ≤ 1 mm",
                     f"{m['max_overlap_state_m'] * 1e3:.2f} mm in the output state over 0–3 s "
                     f"({m['max_overlap_rest_m'] * 1e3:.2f} mm at rest, 2–3 s)",
                     "PASS" if m["max_overlap_state_m"] <= PENETRATION_TARGET else "MISS"))
    rows += growth_rows(windows, "rest", "piles at rest")
    return rows


def growth_rows(piles, window, label):
    """One row per pair of consecutive pile sizes: the growth of a step's time in the
    window ("fall" or "rest") against N log N's."""
    pts = {n: m[window]["us_per_step"] for n, m in piles.items() if math.isfinite(m[window]["us_per_step"])}
    return [(f"{label}: growth {a} → {b} no faster than N log N (slope ≤ {limit:.2f})", f"slope {s:.2f}",
             "PASS" if s <= limit else "MISS") for a, b, s, limit in growth(pts)]


def windows_checks(windows, interleaved, awake=None):
    """Figures held to the targets' bounds that are not targets: the cube-root piles'
    falling growth (from columns of 4 to columns of 10, whose tops land at 1.7 and 2.7
    m/s: different falls, not more of one), and the piles with sleep off (the solver
    alone) against the interleaved rounds' MuJoCo figure."""
    rows = growth_rows(windows, "fall", "falling, cube-root piles")
    if awake and interleaved and interleaved["n"] in awake:
        n = interleaved["n"]
        theirs = statistics.median(r["mujoco"] for r in interleaved["rounds"])
        ratio = awake[n]["rest"]["s_per_simulated_s"] / theirs
        rows.append((f"sleep off (the solver alone), pile of {n} at rest: ≤ 0.5x MuJoCo's",
                     f"ratio {ratio:.2f} ({fmt_s(awake[n]['rest']['s_per_simulated_s'])} against the rounds' "
                     f"median {fmt_s(theirs)}; one run)", "PASS" if ratio <= PILE_RATIO_TARGET else "MISS"))
    if awake:
        rows += growth_rows(awake, "rest", "sleep off, at rest")
    return rows


def plots(out_dir, free, piles, peers, windows=None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    out_dir.mkdir(parents=True, exist_ok=True)
    files = []

    fig, ax = plt.subplots(figsize=(7, 4.8))
    for method, pts in sorted(free.items()):
        ns = sorted(pts)
        bold = method == "rk4"
        ax.loglog(ns, [pts[n] * n * 1e-3 for n in ns], "o-" if bold else ".-", lw=2.4 if bold else 1,
                  alpha=1 if bold else 0.6, label=f"rigidfmu {method}")
    if peers and peers.get("free"):
        ns = [r["n"] for r in peers["free"]]
        ax.loglog(ns, [r["us_per_step"] for r in peers["free"]], "s--k", lw=2, label=f"{peers['engine']} RK4")
    ax.set_xlabel("free bodies N")
    ax.set_ylabel("CPU time per step (µs)")
    ax.set_title("Free tumbling bodies, h = 1 ms")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    files.append(out_dir / "free_bodies.png")
    fig.savefig(files[-1], dpi=110)
    plt.close(fig)

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.6))
    ns = sorted(piles)
    ax.loglog(ns, [piles[n]["total_us"] for n in ns], "o-", lw=2.4, label="rigidfmu (rk4, BM_Pile: 0–1 s)")
    if windows:
        ms = sorted(windows)
        for w, style, name in (("fall", "D-", "falling, 0–1 s"), ("rest", "D--", "at rest, 2–3 s")):
            ax.loglog(ms, [windows[n][w]["us_per_step"] for n in ms], style, lw=1.4,
                      label=f"rigidfmu (BM_PileWindows), {name}")
    for integ, style in (("Euler", "s--k"), ("RK4", "^:k")):
        rows = [r for r in (peers or {}).get("piles", []) if r["integrator"] == integ]
        if rows:
            ax.loglog([r["n"] for r in rows], [r["us_per_step"] for r in rows], style,
                      label=f"{peers['engine']} {integ}")
    if ns:
        # through our largest pile, so that the slope at the top of the range compares
        ref, top = piles[ns[-1]]["total_us"], ns[-1]
        ax.loglog(ns, [ref * n * math.log(n) / (top * math.log(top)) for n in ns], color="grey",
                  lw=0.8, label="∝ N log N")
    ax.set_xlabel("cubes N")
    ax.set_ylabel("CPU time per step (µs)")
    ax.set_title("Piles of cubes falling on a floor, h = 2 ms")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    # shares of the step (a stacked bar on a log axis would misdraw the parts), with
    # the total above each bar
    bottom = np.zeros(len(ns))
    for phase in ("broadphase", "narrowphase", "response", "integration", "other"):
        vals = np.array([100 * max(0.0, piles[n][phase]) / piles[n]["total_us"] for n in ns])
        bx.bar([str(n) for n in ns], vals, bottom=bottom, label=phase)
        bottom += vals
    for i, n in enumerate(ns):
        bx.text(i, bottom[i] + 1, f"{piles[n]['total_us']:.0f} µs", ha="center", fontsize=8)
    bx.set_ylim(0, 112)
    bx.set_xlabel("cubes N")
    bx.set_ylabel("share of the step's CPU time (%)")
    bx.set_title("rigidfmu: where a pile's first second goes")
    bx.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    fig.tight_layout()
    files.append(out_dir / "piles.png")
    fig.savefig(files[-1], dpi=110)
    plt.close(fig)
    return files


def fmt_s(seconds):
    """A duration with a readable unit."""
    for unit, scale in (("s", 1.0), ("ms", 1e-3), ("µs", 1e-6), ("ns", 1e-9)):
        if seconds >= scale:
            return f"{seconds / scale:.3g} {unit}"
    return f"{seconds / 1e-9:.3g} ns"


# ----------------------------------------------------------------------------------
# 5. the report: templates/performance.md filled with the figures

def pct(x):
    return f"{100 * x:.1f} %" if math.isfinite(x) else "–"


def mm(metres):
    return f"{metres * 1e3:.2f} mm"


def table(head, align, rows):
    """A Markdown table: its column titles, each column's alignment ("l" or "r") and its
    rows of cells (strings); every table of the report is written by this one."""
    def line(cells):
        return "|" + "|".join(f" {c} " if c else " " for c in cells) + "|"
    rule = "|" + "".join("---:|" if a == "r" else "---|" for a in align)
    return "\n".join([line(head), rule, *(line(row) for row in rows)])


def verdicts(rows, head="target"):
    """The targets (or checks) as a table: label, measured value, PASS, MISS or –."""
    return table([head, "measured", ""], "lll", [[label, value, f"**{status}**"] for label, value, status in rows])


def part(name, **values):
    """A part of templates/performance.md, filled."""
    return template.fill("performance", values, part=name)


def block(name, **values):
    """A part that stands or not before the next paragraph: itself and a blank line."""
    return part(name, **values) + "\n\n"


def mujoco_euler(peers):
    """{n: MuJoCo's pile of n with its default integrator (Euler)}."""
    return {p["n"]: p for p in (peers or {}).get("piles", []) if p["integrator"] == "Euler"}


def fall_work(piles):
    """{n: contact points per solve while the pile falls} of the piles that solved any.
    Every point goes through the solver's same fixed sub-steps and relax pass, so they
    count its work exactly, without the machine's noise: the same solves each run (a
    step is deterministic)."""
    return {int(n): m["fall"]["points_per_solve"] for n, m in piles.items()
            if m["fall"]["points_per_solve"] > 0}


def render(r):
    """The report's Markdown from its figures (the dict main writes to bench.json): a
    pure function of them, so that a saved bench.json renders again (load_report)."""
    return template.fill("performance", {**header_values(r), **core_values(r), "mujoco": mujoco_section(r),
                                         **windows_values(r), **chain_values(r), **meshes_values(r)})


def meshes_values(r):
    """The convex meshes' section (reports.performance_meshes); a bench.json saved
    before it was measured renders it as not measured."""
    narrow = (r.get("meshes") or {}).get("narrow")
    pile = (r.get("meshes") or {}).get("pile")
    again = r["meta"].get("meshes_date")
    note = (f"*Measured again on {again}, on its own (`scripts/bench.sh --meshes-only`), on a shared machine.* "
            if again else "")
    if not narrow:
        return {"narrow_repetitions": "–", "hull_radius": "–", "cube_edge": "–", "meshes_note": note,
                "narrow_table": "Not measured in this run.", "mesh_pile": ""}
    pairs = ("on the floor", "on a body")
    head = ["shape", "hull vertices", "hull faces",
            *(f"{p}: {k}" for p in pairs for k in ("ns per pair", "contact points", "× cube"))]
    return {"narrow_repetitions": narrow["repetitions"], "hull_radius": f"{narrow['radius_m']:g} m",
            "cube_edge": f"{narrow['cube_edge_m']:g} m", "meshes_note": note,
            "narrow_table": table(head, "lrrrrrrrr", performance_meshes.narrow_rows(narrow)),
            # a bench.json saved before the pile fell into the bin renders no pile
            "mesh_pile": mesh_pile_part(pile) if pile and "bin" in pile else ""}


def mesh_pile_part(pile):
    """The pebbles' pile (performance_meshes.run_mesh_pile)."""
    head = ["engine", "per simulated second, falling (0–1 s)", "at rest (2–3 s)", "deepest overlap (0–3 s)",
            "fastest body at 3 s", "asleep at 3 s", "inside the bin at 3 s"]
    o, box = pile["ours"], pile["bin"]
    return block("mesh_pile", n=pile["n"], vertices=pile["vertices"],
                 axes=" × ".join(f"{2e3 * a:g}" for a in pile["axes_m"]), rounds=len(pile["rounds"]),
                 narrowphase=f"{o['fall_narrowphase_share']:.0%}",
                 narrowphase_rest=f"{o['rest_narrowphase_share']:.0%}",
                 bin_size=" × ".join(f"{a:g}" for a in box["size_m"]), bin_cells=box["cells"],
                 bin_thickness=f"{box['thickness_m']:g}", beyond_wall=f"{o['max_beyond_wall_m'] * 1e3:.2f} mm",
                 below_floor=f"{o['max_below_floor_m'] * 1e3:.2f} mm",
                 mesh_pile_table=table(head, "lrrrrrr", performance_meshes.mesh_pile_rows(pile, fmt_s)))


def write_markdown(path, r):
    """OUT/performance.md."""
    path.write_text(render(r))


def header_values(r):
    meta, peers = r["meta"], r["peers"]
    return {"quick_flag": " --quick" if meta["quick"] else "", "date": meta["date"],
            "seconds": f"{meta['seconds']:.0f}", "source": meta["source"], "cpu": meta["cpu"],
            "python": meta["python"], "benchmark_library": meta["benchmark_library"],
            "peer_engine": ", " + peers["engine"] if peers else "", "repeats": meta["repeats"],
            "targets_table": verdicts(r["targets"])}


def core_values(r):
    """The core's free bodies and piles, and the FMU's costs."""
    free, piles, peers = r["free"], r["piles"], r["peers"]
    ns = sorted({n for pts in free.values() for n in pts})
    rows = [[f"`{method}`", *(f"{free[method][n]:.1f}" if n in free[method] else "–" for n in ns)]
            for method in sorted(free, key=lambda m: (m != "rk4", m))]
    if peers and peers.get("free"):
        mj = {x["n"]: x for x in peers["free"]}
        rows.append([f"{peers['engine']} RK4", *(f"{mj[n]['ns_per_body_step']:.1f}" if n in mj else "–" for n in ns)])
    pile_rows = [[str(n), *(f"{p[k]:.1f}" for k in ("broadphase", "narrowphase", "response", "integration", "other")),
                  f"**{p['total_us']:.1f}**", fmt_s(p["s_per_simulated_s"]), mm(p["max_penetration_m"]),
                  mm(p["max_overlap_state_m"]), f"{p['max_speed_end_mps']:.3g} m/s"] for n, p in piles.items()]
    incomplete = [n for n, p in piles.items() if p["steps_ok"] < p["steps"]]
    fmu_rows = [[str(n), f"{f['do_step_s'] * 1e6:.2f} µs", f"{f['core_step_s'] * 1e6:.2f} µs",
                 f"{f['overhead_s'] * 1e6:.2f} µs", f"{f['get_all_s'] * 1e6:.2f} µs ({f['outputs']} Reals)",
                 f"{f['get_one_s'] * 1e6:.2f} µs", f"{f['amortised_step_s'] * 1e6:.2f} µs"]
                for n, f in r["fmu"].items()]
    return {
        "free_table": table(["method", *(f"N = {n}" for n in ns)], "l" + "r" * len(ns), rows),
        "piles_table": table(["N", "broadphase", "narrowphase", "response", "integration", "other",
                              "total per step", "per simulated second", "max penetration before the response",
                              "in the output state", "fastest body at 1 s"], "r" * 11, pile_rows),
        "piles_incomplete": block("piles_incomplete", piles=incomplete) if incomplete else "",
        "fmu_table": table(["bodies", "fmi2DoStep (1 step)", "core step", "FMI overhead",
                            "fmi2GetReal, all outputs", "fmi2GetReal, 1 variable", "amortised per internal step"],
                           "r" * 7, fmu_rows)}


def interleaved(name, il, head):
    """The rounds of a pile timed ours then MuJoCo's, as the part `name`."""
    rows = [[str(k), fmt_s(row["ours"]), fmt_s(row["mujoco"]), f"{row['ratio']:.2f}"]
            for k, row in enumerate(il["rounds"], 1)]
    return block(name, n=il["n"], ratio=f"{il['ratio']:.2f}",
                 judged=part("judged_here" if il["n"] == 1000 else "judged_elsewhere"),
                 rounds_table=table(["round", *head, "ratio"], "rrrr", rows))


def mujoco_section(r):
    """Beside MuJoCo: the piles' first second, the interleaved pile, a free body at equal accuracy."""
    peers, piles, acc = r["peers"], r["piles"], r["accuracy"]
    if not peers:
        return part("mujoco_absent")
    engine = peers["engine"]
    pile_rows = [[str(m["n"]), m["integrator"], f"{m['us_per_step']:.1f} µs", fmt_s(m["s_per_simulated_s"]),
                  mm(m["max_penetration_m"]), f"{m['max_speed_end']:.3g} m/s", fmt_s(o["s_per_simulated_s"]),
                  mm(o["max_overlap_state_m"]), f"{o['max_speed_end_mps']:.3g} m/s",
                  f"**{o['s_per_simulated_s'] / m['s_per_simulated_s']:.2f}**"]
                 for m in peers["piles"] if (o := piles.get(m["n"])) is not None]
    runs = [["rigidfmu rk4 (FMU)", f"{o['dt']:g}", f"{o['error_rad']:.2g} rad", fmt_s(o["s_per_simulated_s"])]
            for o in acc["ours"]]
    runs += [[f"{engine} {m['integrator']}", f"{m['dt']:g}", f"{m['error_rad']:.2g} rad",
              fmt_s(m["s_per_simulated_s"])] for m in acc["mujoco"]]
    equal = []
    for e in acc["equal_accuracy"]:
        m, o = e["mujoco"], e["ours"]
        equal.append([f"{m['integrator']}, dt {m['dt']:g}", f"{m['error_rad']:.2g} rad",
                      *([f"rk4, h {o['dt']:g}", f"{o['error_rad']:.2g} rad", f"**{e['ratio']:.3f}**"] if o else
                        ["none of our steps reaches it", "–", "–"])])
    il = r.get("interleaved")
    return part("mujoco", engine=engine,
                mujoco_piles_table=table(["N", "MuJoCo integrator", "MuJoCo per step", "MuJoCo per simulated second",
                                          "MuJoCo max penetration", "MuJoCo fastest body at 1 s",
                                          "ours per simulated second", "our max penetration",
                                          "our fastest body at 1 s", "ratio ours/theirs"], "rl" + "r" * 8, pile_rows),
                interleaved=interleaved("interleaved", il, ["ours per simulated second",
                                                            "MuJoCo per simulated second"]) if il else "",
                omega0=acc["omega0"], T=f"{acc['T']:g}",
                accuracy_table=table(["engine, method", "step", "error at T", "CPU per simulated second"], "lrrr",
                                     runs),
                equal_accuracy_table=table(["MuJoCo run", "its error", "our run", "our error", "ratio ours/theirs"],
                                           "lrlrr", equal))


def windows_values(r):
    """The piles over 3 s: their targets and checks, figures, shares and MuJoCo beside."""
    windows, piles = r.get("windows") or {}, r["piles"]
    checks, awake, wide = r.get("windows_checks") or [], r.get("windows_awake") or {}, r.get("windows_wide") or {}
    incomplete = [n for n, m in windows.items() if m["steps_ok"] < m["steps"]]
    rows = []
    for n, m in windows.items():
        f, s, old = m["fall"], m["rest"], piles.get(n)
        rows.append([str(n), f"{f['us_per_step']:.1f} µs", fmt_s(f["s_per_simulated_s"]), f"{s['us_per_step']:.1f} µs",
                     f"**{fmt_s(s['s_per_simulated_s'])}**", fmt_s(old["s_per_simulated_s"]) if old else "–",
                     f"{f['points_per_solve']:.0f}", f"{s['points_per_solve']:.0f}", mm(m["max_overlap_state_m"]),
                     mm(m["max_overlap_rest_m"]), f"{m['max_speed_1s_mps']:.3g} m/s",
                     f"{m['max_speed_3s_mps']:.3g} m/s", f"{m['asleep_3s']:.0f} of {n}"])
    return {
        "windows_targets_table": verdicts(r["windows_targets"]),
        "checks": block("checks", wide_layers=bench_scenes.WIDE_LAYERS,
                        checks_table=verdicts(checks, "check (not a target)")) if checks else "",
        "windows_table": table(["N", "falling: per step", "falling: per simulated second", "at rest: per step",
                                "at rest: per simulated second", "BM_Pile per simulated second, falling",
                                "points per solve, falling", "points per solve, at rest",
                                "max overlap in the output state, 0–3 s", "at rest, 2–3 s", "fastest body at 1 s",
                                "fastest body at 3 s", "asleep at 3 s"], "r" * 13, rows),
        **growth_values(windows, r.get("windows_tilts") or {}),
        "windows_incomplete": block("windows_incomplete", piles=incomplete) if incomplete else "",
        "sleep_off": block("sleep_off", awake_table=awake_table(awake)) if awake else "",
        "equal_height": block("equal_height", wide_layers=bench_scenes.WIDE_LAYERS,
                              wide_table=wide_table(windows, wide)) if wide and 100 in windows else "",
        "shares_table": share_table(windows, "shares", STAGES),
        "stages_table": share_table(windows, "stage_shares", STEP_STAGES),
        **mujoco_at_rest_values(r)}


def growth_values(windows, tilts):
    """The growth of the points per solve while the piles fall, under the benchmark's tilt
    and the others."""
    work = fall_work(windows)
    steps = [f"{a} → {b} cubes {work[b] / work[a]:.1f}x, slope {measured:.2f} (N log N: {limit:.2f})"
             for a, b, measured, limit in growth(work)]
    growths = []
    for tilt, tilted in tilts.items():
        solved = fall_work(tilted)
        growths += [f"({tilt.replace(',', ', ')}) {solved[b] / solved[a]:.1f}x from {a} to {b} cubes"
                    for a, b, _, _ in growth(solved)]
    return {"fall_growth": block("fall_growth", steps="; ".join(steps)) if steps else "",
            "tilts": block("tilts", tilt=f"{bench_scenes.TILT[0]}, {bench_scenes.TILT[1]}",
                           growths="; ".join(growths)) if growths else ""}


def awake_table(awake):
    rows = [[str(n), fmt_s(a["fall"]["s_per_simulated_s"]), f"{a['rest']['us_per_step']:.1f} µs",
             f"**{fmt_s(a['rest']['s_per_simulated_s'])}**", f"{a['rest']['points_per_solve']:.0f}",
             mm(a["max_overlap_state_m"]), f"{a['max_speed_3s_mps']:.3g} m/s"] for n, a in awake.items()]
    return table(["N", "falling: per simulated second", "at rest: per step", "at rest: per simulated second",
                  "points per solve, at rest", "max overlap, 0–3 s", "fastest body at 3 s"], "r" * 7, rows)


def wide_table(windows, wide):
    """The pile of 100 beside the wide piles: columns of one height, N growing."""
    layers = bench_scenes.WIDE_LAYERS
    side = {n: round(math.sqrt(n / layers)) for n in (100, *wide)}
    rows = []
    for n, m, name in [(100, windows[100], "pile_100"), *((k, v, f"pile_wide_{k}") for k, v in wide.items())]:
        f, s = m["fall"], m["rest"]
        rows.append([f"{n} (`{name}`)", f"{side[n]} x {side[n]} of {layers}", f"{f['us_per_step']:.1f} µs",
                     fmt_s(f["s_per_simulated_s"]), f"{s['us_per_step']:.1f} µs",
                     f"**{fmt_s(s['s_per_simulated_s'])}**", f"{f['points_per_solve']:.0f}",
                     f"{s['points_per_solve']:.0f}", mm(m["max_overlap_state_m"]),
                     f"{m['max_speed_3s_mps']:.3g} m/s", f"{m['asleep_3s']:.0f} of {n}"])
    return table(["N", "columns", "falling: per step", "falling: per simulated second", "at rest: per step",
                  "at rest: per simulated second", "points per solve, falling", "points per solve, at rest",
                  "max overlap, 0–3 s", "fastest body at 3 s", "asleep at 3 s"], "rl" + "r" * 9, rows)


def share_table(windows, key, columns):
    """Each pile's window shares `key` over `columns`, and the rest as other."""
    rows = [[str(n), name, *(pct(m[wnd][key][k]) for k in columns + ("other",))]
            for n, m in windows.items()
            for wnd, name in (("fall", "falling, 0–1 s"), ("rest", "at rest, 2–3 s"))]
    return table(["N", "window", *columns, "other"], "rl" + "r" * (len(columns) + 1), rows)


def mujoco_at_rest_values(r):
    """The piles over 3 s beside MuJoCo's (Euler): separate runs, then the interleaved rounds."""
    windows, peers, il = r.get("windows") or {}, r["peers"], r.get("windows_interleaved")
    mj, nm = mujoco_euler(peers), "not measured"
    rows = []
    for n, m in windows.items():
        p = mj.get(n)
        rest = p.get("rest_s_per_simulated_s") if p else None
        rows.append([str(n), fmt_s(p["s_per_simulated_s"]) if p else nm, fmt_s(rest) if rest else nm,
                     fmt_s(m["fall"]["s_per_simulated_s"]), fmt_s(m["rest"]["s_per_simulated_s"]),
                     f"**{m['rest']['s_per_simulated_s'] / rest:.2f}**" if rest else nm,
                     f"{p['max_speed_3s']:.3g} m/s" if p and "max_speed_3s" in p else nm,
                     f"{m['max_speed_3s_mps']:.3g} m/s",
                     mm(p["max_penetration_3s_m"]) if p and "max_penetration_3s_m" in p else nm,
                     mm(m["max_overlap_state_m"])])
    return {"mujoco_at_rest": part("mujoco_at_rest", engine=peers["engine"]) if peers else
            part("mujoco_at_rest_absent"),
            "mujoco_at_rest_table": table(
                ["N", "MuJoCo per simulated second, falling", "MuJoCo at rest", "ours, falling", "ours at rest",
                 "ratio at rest, ours/theirs", "MuJoCo fastest body at 3 s", "our fastest body at 3 s",
                 "MuJoCo max penetration, 0–3 s", "our max overlap, 0–3 s"], "r" * 10, rows),
            "interleaved_at_rest": interleaved("interleaved_at_rest", il, ["ours at rest, per simulated second",
                                                                           "MuJoCo at rest, per simulated second"])
            if il else ""}


def chain_values(r):
    """The chain of hinged links: its targets, ours beside MuJoCo's Euler and RK4, the
    interleaved rounds and where our step goes."""
    chain = r["chain"]
    ours, mj, nm = chain["ours"], chain["mujoco"], "not measured"

    def energy(x):
        return [f"{x['max_energy_error']:.2g}", f"{x['energy_error_end']:+.2g}"]

    def tip(x):
        return f"({x['tip_m'][0]:.3f}, {x['tip_m'][1]:.3f}) m"
    rows = [["rigidfmu rk4", f"{ours['step_s'] * 1e3:g} ms", f"{ours['us_per_step']:.1f} µs",
             f"**{fmt_s(ours['s_per_simulated_s'])}**", "–", f"{ours['max_drift_m'] * 1e3:.3f} mm", *energy(ours),
             tip(ours)]]
    for integrator, ratio in (("Euler", chain["ratio"]), ("RK4", chain["ratio_rk4"])):
        m = (mj or {}).get(integrator)
        rows.append([f"{mj['engine'] if mj else 'MuJoCo'} {integrator}",
                     *([f"{m['step_s'] * 1e3:g} ms", f"{m['us_per_step']:.1f} µs", fmt_s(m["s_per_simulated_s"]),
                        f"**{ratio:.2f}**", "none (generalized coordinates)", *energy(m), tip(m)] if m else
                       [nm] * 8)])
    rounds = [[str(k), fmt_s(x["ours"]), fmt_s(x["mujoco"]), fmt_s(x["mujoco_rk4"]), f"{x['ratio']:.2f}",
               f"{x['ratio_rk4']:.2f}"] for k, x in enumerate(chain["rounds"], 1)]
    stages = [pct(ours["stage_shares"][k]) for k in STEP_STAGES + ("other",)]
    return {
        "n": chain["n"], "link": " x ".join(f"{x:g}" for x in bench_scenes.CHAIN_LINK),
        "link_mass": f"{bench_scenes.CHAIN_LINK_MASS:g}", "T": f"{chain['T']:g}",
        "step": f"{chain['step_s'] * 1e3:g} ms", "max_speed": f"{ours['max_speed_mps']:.3g} m/s",
        "energy_scale": f"{chain['energy_scale_j']:.4g} J",
        "chain_targets_table": verdicts(r["chain_targets"]),
        "chain_mujoco": block("chain_mujoco", engine=mj["engine"]) if mj else block("chain_mujoco_absent"),
        "chain_table": table(["engine, integrator", "step", "per step", "per simulated second", "ratio ours/theirs",
                              "joint drift, max", "energy error, max", "energy error at T", "tip at T (x, z)"],
                             "lrrrrrrrr", rows),
        "chain_rounds": block("chain_rounds", ratio=f"{chain['ratio']:.2f}", ratio_rk4=f"{chain['ratio_rk4']:.2f}",
                              rounds_table=table(["round", "ours per simulated second", "MuJoCo Euler", "MuJoCo RK4",
                                                  "ratio to Euler", "ratio to RK4"], "rrrrrr", rounds))
        if chain["rounds"] else "",
        "chain_stages_table": table(["run", *STEP_STAGES, "other"], "l" + "r" * (len(STEP_STAGES) + 1),
                                    [[f"ours, 0–{chain['T']:g} s", *stages]])}


def load_report(path):
    """The figures a run saved (bench.json) as main holds them, to render again: JSON
    keeps a count only as a string, and a target row only as a list."""
    r = json.loads(pathlib.Path(path).read_text())

    def counts(d):
        return {int(k): v for k, v in (d or {}).items()}
    r["free"] = {method: counts(pts) for method, pts in r["free"].items()}
    for key in ("piles", "fmu", "windows", "windows_awake", "windows_wide"):
        r[key] = counts(r.get(key))
    r["windows_tilts"] = {tilt: counts(piles) for tilt, piles in (r.get("windows_tilts") or {}).items()}
    for key in ("targets", "windows_targets", "windows_checks", "chain_targets"):
        r[key] = [tuple(row) for row in r.get(key) or []]
    return r


def log_chain(chain):
    """The chain's figures, for the console."""
    ours, mj, T = chain["ours"], chain["mujoco"], chain["T"]
    log(f"\n== chain of {chain['n']} hinged links from horizontal, 0-{T:g} s, h = {chain['step_s'] * 1e3:g} ms "
        f"(BM_Chain; energy errors as fractions of M g L = {chain['energy_scale_j']:.4g} J)")
    log(f"  ours (rk4): {fmt_s(ours['s_per_simulated_s'])} per simulated s ({ours['us_per_step']:.1f} us/step); "
        f"drift {ours['max_drift_m'] * 1e3:.3f} mm; energy error max {ours['max_energy_error']:.3g}, at "
        f"{T:g} s {ours['energy_error_end']:+.3g}; fastest body {ours['max_speed_mps']:.3g} m/s; tip at "
        f"({ours['tip_m'][0]:.4f}, {ours['tip_m'][1]:.4f}) m")
    log("    stages: " + ", ".join(f"{k} {pct(ours['stage_shares'][k])}" for k in STEP_STAGES + ("other",)))
    if mj is None:
        log("  MuJoCo: not measured (no .venv-peers)")
        return
    for integrator, ratio in (("Euler", chain["ratio"]), ("RK4", chain["ratio_rk4"])):
        m = mj[integrator]
        log(f"  {mj['engine']} {integrator}: {fmt_s(m['s_per_simulated_s'])} per simulated s "
            f"({m['us_per_step']:.1f} us/step), ours/theirs {ratio:.2f}; energy error max "
            f"{m['max_energy_error']:.3g}, at {T:g} s {m['energy_error_end']:+.3g}; tip at "
            f"({m['tip_m'][0]:.4f}, {m['tip_m'][1]:.4f}) m")


def run_meshes(build, scenes, quick):
    """The convex meshes' part (6.): the narrowphase per pair and the pile of pebbles."""
    log("== convex meshes: the narrowphase per pair, beside the cube's (BM_Narrow)")
    meshes = {"narrow": performance_meshes.run_narrow(build, scenes, quick)}
    log("== convex meshes: a pile of pebbles in a bin, ours and MuJoCo's round by round (BM_PileHulls)")
    with tempfile.TemporaryDirectory() as tmp:
        meshes["pile"] = performance_meshes.run_mesh_pile(build, scenes, tmp, PEERS_PYTHON, quick)
    return meshes


def meshes_only(build, scenes, out, quick, t_start):
    """--meshes-only: the convex meshes run again, their figures put in place of those
    OUT/performance/bench.json holds, and the report rendered again from it (the other
    sections' figures, plots and date as they were; this section's date noted)."""
    saved = out / "performance" / "bench.json"
    if not saved.exists():
        raise ReportError(f"report performance --meshes-only: no {saved} (run scripts/bench.sh once without it)")
    r = load_report(saved)
    r["meshes"] = run_meshes(build, scenes, quick)
    r["meta"]["meshes_date"] = time.strftime("%Y-%m-%d %H:%M %Z")
    saved.write_text(json.dumps(r, indent=1, default=float))
    write_markdown(out / "performance.md", r)
    performance_meshes.log_narrow(r["meshes"]["narrow"])
    performance_meshes.log_mesh_pile(r["meshes"]["pile"])
    log(f"wrote {out / 'performance.md'}, {saved} ({time.perf_counter() - t_start:.0f} s)")
    return 0


def main(argv=None, prog=None):
    p = argparse.ArgumentParser(prog=prog, description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true", help="short runs (for the test suite)")
    p.add_argument("--out", default=str(ROOT / "docs" / "reports"),
                   help="writes OUT/performance.md and OUT/performance/")
    p.add_argument("--build", default=os.environ.get("RIGIDFMU_BUILD", str(ROOT / "build")))
    p.add_argument("--chain-only", action="store_true",
                   help="only the chain of hinged links (5.): its figures and targets printed, no report written")
    p.add_argument("--meshes-only", action="store_true",
                   help="only the convex meshes (6.), the report rendered again from OUT/performance/bench.json")
    args = p.parse_args(argv)
    t_start = time.perf_counter()
    build = pathlib.Path(args.build).resolve()
    out = pathlib.Path(args.out).resolve()
    if not (build / "rigid-bench-core").exists():
        raise ReportError(f"report performance: no {build / 'rigid-bench-core'} (install libbenchmark-dev and build; "
                 "scripts/bench.sh does both)")
    scenes = build / "bench-scenes"
    bench_scenes.write(scenes)
    if args.chain_only:
        with tempfile.TemporaryDirectory() as tmp:
            chain = run_chain(build, scenes, pathlib.Path(tmp), args.quick)
        log_chain(chain)
        for label, value, status in chain_targets(chain):
            log(f"  {status:5s} {label}: {value}")
        return 0
    if args.meshes_only:
        return meshes_only(build, scenes, out, args.quick, t_start)
    repeats = 3 if args.quick else 7
    T = 2.0 if args.quick else 10.0
    mj_dts = (1e-2, 1e-3)
    our_dts = (1e-2, 1e-3) if args.quick else (1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2.5e-4)

    log("== core (rigid-bench-core)")
    core, context = run_core(build, scenes, args.quick)
    free, piles = free_table(core), pile_table(core)

    with tempfile.TemporaryDirectory() as tmp:
        folder = pathlib.Path(tmp)
        log("== FMU (fmpy)")
        fmus = build_fmus(build, scenes, ["free_1", "free_100"], folder)
        fmu = fmu_bench({1: fmus["free_1"], 100: fmus["free_100"]}, folder, args.quick)
        for n, f in fmu.items():
            f["core_step_s"] = free["rk4"][n] * n * 1e-9
            f["overhead_s"] = f["do_step_s"] - f["core_step_s"]
        colliding = colliding_cost(build, scenes, folder, args.quick)
        log("== accuracy of a free tumbling body (ours)")
        inertia, omega0 = free_body(scenes)
        q_ref = torque_free_reference(inertia, omega0, T)
        ours = our_free_accuracy(fmus["free_1"], folder, T, our_dts, repeats)
        add_errors(ours, q_ref)
        for o in ours:
            log(f"rigidfmu rk4 h={o['dt']:g}: error {o['error_rad']:.3g} rad, "
                f"{o['s_per_simulated_s'] * 1e3:.3f} ms per simulated s")
        log("== MuJoCo (.venv-peers)")
        peers = run_peers(scenes, folder, args.quick, T, mj_dts)
        log("== a pile, ours and MuJoCo's interleaved")
        interleaved = interleaved_pile_ratio(build, scenes, folder, 100 if args.quick else 1000,
                                             1 if args.quick else 3)
        log("== the piles over 3 s, falling and at rest (rigid-bench-core BM_PileWindows, BM_PileAwake)")
        windows, windows_il, windows_awake = run_windows(build, scenes, folder, args.quick)
        log("== the wide pile, columns as short as the pile of 100's (BM_PileWide)")
        windows_wide = run_wide(build, scenes, args.quick)
        log("== the falling piles under other tilt patterns (BM_PileWindows)")
        windows_tilts = run_tilts(build, folder, args.quick)
        log("== a chain of hinged links swinging from horizontal (BM_Chain), ours and MuJoCo's interleaved")
        chain = run_chain(build, scenes, folder, args.quick)
    meshes = run_meshes(build, scenes, args.quick)
    if peers is None:
        log("MuJoCo: not measured (no .venv-peers; scripts/bench.sh without --quick creates it)")
    accuracy = {"T": T, "omega0": [float(x) for x in omega0], "ours": ours, "mujoco": [], "equal_accuracy": []}
    if peers:
        add_errors(peers["free_one"], q_ref)
        accuracy["mujoco"] = peers["free_one"]
        accuracy["equal_accuracy"] = equal_accuracy(ours, [m for m in peers["free_one"] if m["integrator"] == "RK4"])

    rows = targets(free, piles, peers, interleaved, colliding)
    wrows = windows_targets(windows, peers, windows_il) + equal_height_targets(windows, windows_wide)
    wchecks = windows_checks(windows, windows_il, windows_awake)
    crows = chain_targets(chain)
    meta = {"quick": args.quick, "date": time.strftime("%Y-%m-%d %H:%M %Z"), "cpu": cpu_name(),
            "python": f"Python {platform.python_version()}", "repeats": repeats,
            "benchmark_library": f"1.7 ({context.get('library_build_type', '?')} build, Debian)",
            "load_avg": context.get("load_avg"), "source": source_state(),
            "seconds": time.perf_counter() - t_start}
    report = {"free": free, "piles": piles, "fmu": fmu, "colliding": colliding, "peers": peers,
              "interleaved": interleaved,
              "windows": windows, "windows_interleaved": windows_il, "windows_targets": wrows,
              "windows_checks": wchecks,
              "windows_awake": windows_awake, "windows_wide": windows_wide, "windows_tilts": windows_tilts,
              "chain": chain, "chain_targets": crows, "meshes": meshes,
              "accuracy": accuracy, "targets": rows, "meta": meta}
    fig_dir = out / "performance"
    files = plots(fig_dir, free, piles, peers, windows)
    (fig_dir / "bench.json").write_text(json.dumps(report, indent=1, default=float))
    write_markdown(out / "performance.md", report)

    log("\n== targets (figures, never asserted)")
    for label, value, status in rows + wrows + crows:
        log(f"  {status:5s} {label}: {value}")
    log("== checks beside them (figures, not targets)")
    for label, value, status in wchecks:
        log(f"  {status:5s} {label}: {value}")
    if peers:
        mj = {m["n"]: m for m in peers["piles"] if m["integrator"] == "Euler"}
        for n in piles:
            if n in mj:
                log(f"  pile {n}: ours/MuJoCo Euler per simulated second = "
                    f"{piles[n]['s_per_simulated_s'] / mj[n]['s_per_simulated_s']:.2f}")
        for e in accuracy["equal_accuracy"]:
            m = e["mujoco"]
            log(f"  free body vs MuJoCo RK4 dt {m['dt']:g} ({m['error_rad']:.2g} rad): " +
                (f"ours rk4 h {e['ours']['dt']:g} ({e['ours']['error_rad']:.2g} rad), ratio {e['ratio']:.3f}"
                 if e["ours"] else "no run of ours as accurate"))
    log("\n== piles over 3 s (BM_PileWindows; falling 0-1 s, at rest 2-3 s)")
    mj_piles = {m["n"]: m for m in (peers or {}).get("piles", []) if m["integrator"] == "Euler"}
    for n, m in windows.items():
        f, s = m["fall"], m["rest"]
        p = mj_piles.get(n, {})
        log(f"  pile {n}: per simulated second falling {fmt_s(f['s_per_simulated_s'])}, at rest "
            f"{fmt_s(s['s_per_simulated_s'])} (MuJoCo Euler at rest: "
            f"{fmt_s(p['rest_s_per_simulated_s']) if 'rest_s_per_simulated_s' in p else 'not measured'}); "
            f"points per solve {f['points_per_solve']:.0f} falling, {s['points_per_solve']:.0f} "
            f"at rest; fastest body at 3 s {m['max_speed_3s_mps']:.3g} m/s (MuJoCo: "
            f"{'%.3g m/s' % p['max_speed_3s'] if 'max_speed_3s' in p else 'not measured'}); overlap "
            f"{m['max_overlap_state_m'] * 1e3:.2f} mm (0-3 s), {m['max_overlap_rest_m'] * 1e3:.2f} mm at rest")
        for wnd, name in (("fall", "falling"), ("rest", "at rest")):
            log(f"    shares {name}: " + ", ".join(f"{k} {pct(m[wnd]['shares'][k])}"
                                                    for k in STAGES + ("other",)))
            log(f"    stages {name}: " + ", ".join(f"{k} {pct(m[wnd]['stage_shares'][k])}"
                                                    for k in STEP_STAGES + ("other",)))
    if windows_il:
        log(f"  pile {windows_il['n']} at rest: ours/MuJoCo Euler at rest = {windows_il['ratio']:.2f} "
            f"(median of {len(windows_il['rounds'])} interleaved rounds)")
    if peers is None:
        log("  MuJoCo: not measured (no .venv-peers): its columns say \"not measured\"")
    log_chain(chain)
    performance_meshes.log_narrow(meshes["narrow"])
    performance_meshes.log_mesh_pile(meshes["pile"])
    log(f"wrote {out / 'performance.md'}, {', '.join(str(f) for f in files)} "
        f"({time.perf_counter() - t_start:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main(prog="scripts/bench.sh"))
