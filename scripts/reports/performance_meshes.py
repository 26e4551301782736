"""The convex mesh part of the performance report (issue 42), on reports.mesh_scenes'
scenes. Figures only: the issue sets no number for either.

- The narrowphase's cost per pair for hulls of 100-1000 vertices beside the cube's, from
  rigid-bench-core's BM_Narrow/<shape>/<pair> (bench/bench_core.cpp): each hull's ratio
  to the cube's pair of the same kind (on the floor, on a body of its shape), measured
  in one run with the benchmarks' repetitions interleaved in random order, so that the
  machine's load falls on all of them alike.
- A pile of 100 pebbles (convex meshes of 100 hull vertices) falling into a bin (a
  static mesh surface, an open box), the time per simulated second of its first second
  (falling) and third (at rest) beside MuJoCo's on the same STL (reports.performance_peers
  --mesh-pile; its bin five box geoms), ours then theirs round by round, each in its own
  process; the median ratio. A correctness figure beside it: the pebbles inside the bin
  at 3 s, and how far a pebble's vertex got beyond a wall or below the floor."""
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile

from reports import mesh_scenes
from reports import scenes as bench_scenes

PAIRS = ("surface", "body")  # BM_Narrow's: on the floor, on a body of its shape
CUBE = "cube"


def shapes():
    """BM_Narrow's shapes: the cube, then the hulls by vertex count."""
    return (CUBE, *(f"hull_{n}" for n in mesh_scenes.HULL_VERTICES))


def run_narrow(build, scenes, quick):
    """{shape: {pair: figures}} of BM_Narrow: the median over the repetitions of the time
    per pair (ns, CPU) and of the contact points it gave, the hull's vertices and faces
    (a cube's: 8 and 6), and the ratio of the time to the cube's for the same pair."""
    reps, min_time = (3, "0.02") if quick else (9, "0.1")
    with tempfile.NamedTemporaryFile(suffix=".json") as f:
        subprocess.run([str(build / "rigid-bench-core"), str(scenes), "--benchmark_filter=^BM_Narrow/",
                        f"--benchmark_min_time={min_time}", f"--benchmark_repetitions={reps}",
                        "--benchmark_enable_random_interleaving=true", "--benchmark_report_aggregates_only=true",
                        "--benchmark_format=console", "--benchmark_out_format=json", f"--benchmark_out={f.name}"],
                       check=True, stdout=sys.stdout)
        data = json.load(open(f.name))
    out = {}
    for b in data["benchmarks"]:
        if b.get("aggregate_name") != "median":
            continue
        _, shape, pair = b["run_name"].split("/")
        # a rate counter inverted: seconds per pair in the JSON
        out.setdefault(shape, {})[pair] = {"ns_per_pair": b["ns_per_pair"] * 1e9,
                                           "contacts_per_pair": b["contacts_per_pair"],
                                           "hull_vertices": round(b["hull_vertices"]),
                                           "hull_faces": round(b["hull_faces"])}
    for shape in out.values():
        for pair, x in shape.items():
            x["ratio_to_cube"] = x["ns_per_pair"] / out[CUBE][pair]["ns_per_pair"]
    return {"repetitions": reps, "radius_m": mesh_scenes.HULL_RADIUS, "cube_edge_m": mesh_scenes.CUBE_EDGE,
            "shapes": {s: out[s] for s in shapes() if s in out}}


def core_json(build, scenes, pattern):
    """rigid-bench-core's JSON entries of one run of the benchmarks `pattern` matches."""
    with tempfile.NamedTemporaryFile(suffix=".json") as f:
        subprocess.run([str(build / "rigid-bench-core"), str(scenes), f"--benchmark_filter={pattern}",
                        "--benchmark_format=console", "--benchmark_out_format=json", f"--benchmark_out={f.name}"],
                       check=True, stdout=sys.stdout)
        return json.load(open(f.name))["benchmarks"]


def our_mesh_pile(b):
    """BM_PileHulls' figures: CPU time per simulated second falling (0-1 s) and at rest
    (2-3 s), the narrowphase's share of each window's wall time, the overlap in the
    output state, the fastest body, the bodies asleep and inside the bin at 3 s, and the
    farthest a vertex got beyond the bin's walls and below its floor (0-3 s)."""
    h = bench_scenes.PILE_STEP
    out = {"steps_ok": b["steps_ok"], "steps": b["steps_planned"], "max_overlap_state_m": b["max_overlap_state_m"],
           "max_speed_3s_mps": b["max_speed_3s_mps"], "asleep_3s": b["asleep_3s"], "inside_3s": b["inside_3s"],
           "max_beyond_wall_m": b["max_beyond_wall_m"], "max_below_floor_m": b["max_below_floor_m"]}
    for w in ("fall", "rest"):
        steps = b[f"{w}_steps"]
        out[f"{w}_s_per_simulated_s"] = b[f"{w}_cpu_s"] / (steps * h) if steps else float("nan")
        out[f"{w}_narrowphase_share"] = b[f"{w}_ns_narrowphase"] / b[f"{w}_wall_ns"] if b[f"{w}_wall_ns"] else 0.0
    return out


def median_round(rounds, engine):
    """The figures of `engine`'s round with the median falling time (None if not run)."""
    runs = sorted((r[engine] for r in rounds if r[engine]), key=lambda x: x["fall_s_per_simulated_s"])
    return runs[len(runs) // 2] if runs else None


def run_mesh_pile(build, scenes, folder, peers_python, quick):
    """The pebbles' pile (mesh_scenes.PILE_COUNTS[0]) ours and MuJoCo's, round by round (1
    round in quick mode, 3 else): {n, vertices, axes_m, bin: its size, cells and thickness,
    rounds: [{ours, mujoco}], ours, mujoco: each engine's median round by its falling
    time, ratio_fall, ratio_rest: medians}; without MuJoCo
    (no peers_python) its figures and ratios are None."""
    n = mesh_scenes.PILE_COUNTS[0]
    rounds = []
    for _ in range(1 if quick else 3):
        (b,) = core_json(build, scenes, f"^BM_PileHulls/{n}/")
        ours, theirs = our_mesh_pile(b), None
        if peers_python.exists():
            out = pathlib.Path(folder) / "mesh_pile.json"
            subprocess.run([str(peers_python), "-m", "reports.performance_peers", str(scenes), str(out),
                            "--mesh-pile", str(n)], check=True)
            theirs = json.loads(out.read_text())
        rounds.append({"ours": ours, "mujoco": theirs})
    result = {"n": n, "vertices": mesh_scenes.PILE_HULL_VERTICES, "axes_m": list(mesh_scenes.PILE_HULL_AXES),
              "bin": {"size_m": list(mesh_scenes.BIN_SIZE), "cells": mesh_scenes.BIN_CELLS,
                      "thickness_m": mesh_scenes.BIN_THICKNESS},
              "rounds": rounds, "ours": median_round(rounds, "ours"), "mujoco": median_round(rounds, "mujoco"),
              "ratio_fall": None, "ratio_rest": None}
    if result["mujoco"]:
        for w in ("fall", "rest"):
            result[f"ratio_{w}"] = statistics.median(r["ours"][f"{w}_s_per_simulated_s"] /
                                                     r["mujoco"][f"{w}_s_per_simulated_s"] for r in rounds)
    return result


def narrow_rows(narrow):
    """The report's table: a row per shape, its two pairs side by side."""
    rows = []
    for shape, pairs in narrow["shapes"].items():
        first = next(iter(pairs.values()))
        name = "cube" if shape == CUBE else f"hull of {first['hull_vertices']} points"
        cells = [name, str(first["hull_vertices"]), str(first["hull_faces"])]
        for pair in PAIRS:
            x = pairs[pair]
            cells += [f"{x['ns_per_pair']:.0f}", f"{x['contacts_per_pair']:.0f}", f"{x['ratio_to_cube']:.2f}"]
        rows.append(cells)
    return rows


def log_narrow(narrow):
    """The figures, for the console."""
    print("\n== convex meshes: narrowphase per pair (BM_Narrow; ratio to the cube's pair of the same kind)",
          flush=True)
    for shape, pairs in narrow["shapes"].items():
        print(f"  {shape}: " + "; ".join(
            f"{pair} {pairs[pair]['ns_per_pair']:.0f} ns ({pairs[pair]['contacts_per_pair']:.0f} contact points), "
            f"{pairs[pair]['ratio_to_cube']:.2f}x" for pair in PAIRS), flush=True)


def mesh_pile_rows(pile, fmt_s):
    """The report's table of the pebbles' pile: ours, and MuJoCo's when measured."""
    o, m = pile["ours"], pile["mujoco"]
    rows = [["rigidfmu (rk4)", fmt_s(o["fall_s_per_simulated_s"]), fmt_s(o["rest_s_per_simulated_s"]),
             f"{o['max_overlap_state_m'] * 1e3:.2f} mm", f"{o['max_speed_3s_mps']:.3g} m/s",
             f"{o['asleep_3s']:.0f} of {pile['n']}", f"{o['inside_3s']:.0f} of {pile['n']}"]]
    if m:
        rows.append([f"{m['engine']} (Euler)", fmt_s(m["fall_s_per_simulated_s"]), fmt_s(m["rest_s_per_simulated_s"]),
                     f"{m['max_penetration_3s_m'] * 1e3:.2f} mm", f"{m['max_speed_3s']:.3g} m/s", "–",
                     f"{m['inside_3s']} of {pile['n']}"])
        rows.append(["ratio ours/theirs (median of the rounds)", f"{pile['ratio_fall']:.2f}",
                     f"{pile['ratio_rest']:.2f}", "", "", "", ""])
    else:
        rows.append(["MuJoCo", "not measured", "not measured", "", "", "", ""])
    return rows


def log_mesh_pile(pile):
    """The pebbles' pile, for the console."""
    o, m = pile["ours"], pile["mujoco"]
    print(f"\n== pile of {pile['n']} pebbles (convex meshes of {pile['vertices']} hull vertices), per simulated "
          f"second: ours falling {o['fall_s_per_simulated_s']:.3g} s, at rest {o['rest_s_per_simulated_s']:.3g} s "
          f"(narrowphase {o['fall_narrowphase_share']:.0%}, {o['rest_narrowphase_share']:.0%} of the steps)",
          flush=True)
    theirs = f", MuJoCo {m['inside_3s']}" if m else ""
    print(f"  inside the bin at 3 s: ours {o['inside_3s']:.0f} of {pile['n']}{theirs}; farthest vertex beyond a "
          f"wall {o['max_beyond_wall_m'] * 1e3:.2f} mm, below the floor {o['max_below_floor_m'] * 1e3:.2f} mm "
          "(0-3 s)", flush=True)
    if m:
        print(f"  {m['engine']} Euler: falling {m['fall_s_per_simulated_s']:.3g} s, at rest "
              f"{m['rest_s_per_simulated_s']:.3g} s; ours/theirs {pile['ratio_fall']:.2f} falling, "
              f"{pile['ratio_rest']:.2f} at rest", flush=True)
    else:
        print("  MuJoCo: not measured (no .venv-peers)", flush=True)
