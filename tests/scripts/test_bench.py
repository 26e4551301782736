"""scripts/bench.sh --quick: the performance report runs and is complete (every method
and body count, the pile phases, the piles falling and at rest, the chain of hinged
links, the FMU costs, MuJoCo's ratios when its venv is there, the convex meshes'
narrowphase beside the cube's, the plots). Times are figures: none is asserted, only
that each is measured (finite and positive)."""
import json
import math
import os
import pathlib
import subprocess

import pytest

pytestmark = pytest.mark.slow  # a whole script or browser run (pyproject.toml)

ROOT = pathlib.Path(__file__).resolve().parents[2]
METHODS = ("euler", "rk4", "symplecticEuler", "splitting", "lieRk4", "dopri5", "rosenbrock")
FREE_N = (1, 10, 100, 1000)  # quick mode: no 10000
PILE_N = (10, 100)           # quick mode: no pile of 1000
PHASES = ("broadphase", "narrowphase", "response", "integration")
STEP_STAGES = ("plan", "wake", "collide", "integrate", "solve", "impacts", "commit", "sleep")  # world.h
WINDOWS = ("fall", "rest")   # BM_PileWindows: 0-1 s and 2-3 s
HAVE_PEERS = (ROOT / ".venv-peers" / "bin" / "python").exists()


def measured(x):
    return isinstance(x, (int, float)) and math.isfinite(x) and x > 0


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    out = tmp_path_factory.mktemp("bench")
    env = dict(os.environ, RIGIDFMU_SKIP_SETUP="1")
    env.pop("LD_PRELOAD", None)  # a sanitizer runtime is not for the build tools
    proc = subprocess.run([str(ROOT / "scripts" / "bench.sh"), "--quick", "--out", str(out)],
                          capture_output=True, text=True, env=env, cwd=ROOT, timeout=300)
    assert proc.returncode == 0, proc.stdout[-4000:] + proc.stderr[-4000:]
    report = json.loads((out / "performance" / "bench.json").read_text())
    return proc, out, report


def test_core_free_bodies_every_method_and_count(quick):
    _, _, r = quick
    for m in METHODS:
        for n in FREE_N:
            assert measured(r["free"][m][str(n)]), (m, n)


def test_core_piles_split_into_phases(quick):
    _, _, r = quick
    for n in PILE_N:
        p = r["piles"][str(n)]
        for key in PHASES + ("total_us", "s_per_simulated_s"):
            assert measured(p[key]), (n, key)
        assert math.isfinite(p["other"])
        assert math.isclose(sum(p[k] for k in PHASES) + p["other"], p["total_us"], rel_tol=1e-9)
        assert p["steps_ok"] == p["steps"], f"pile {n}: a step failed"
        assert math.isfinite(p["max_penetration_m"]) and p["max_penetration_m"] >= 0
        assert math.isfinite(p["max_overlap_state_m"]) and p["max_overlap_state_m"] >= 0


def test_piles_falling_and_at_rest(quick):
    _, _, r = quick
    for n in PILE_N:
        m = r["windows"][str(n)]
        assert m["steps_ok"] == m["steps"], f"pile {n} over 3 s: a step failed"
        for w in WINDOWS:
            x = m[w]
            assert measured(x["s_per_simulated_s"]) and measured(x["us_per_step"]), (n, w)
            # a pile's cubes touch in both windows, so the solver ran, unless at rest every
            # island sleeps (a sleeping island is not solved)
            assert x["solves_per_step"] > 0 or (w == "rest" and m["asleep_3s"] == n), (n, w)
            # the contact points a solve answered (its work); at rest the islands may all
            # be asleep, with no points
            assert measured(x["points_per_solve"]) or (w == "rest" and x["points_per_solve"] == 0), (n, w)
            shares = x["shares"]
            for k in PHASES:
                assert math.isfinite(shares[k]) and shares[k] >= 0, (n, w, k)
            assert math.isclose(sum(shares[k] for k in PHASES) + shares["other"], 1.0, rel_tol=1e-9)
            # the step's stages: each timed, the ones every step runs with a share
            stages = x["stage_shares"]
            for k in STEP_STAGES:
                assert math.isfinite(stages[k]) and stages[k] >= 0, (n, w, k)
            for k in ("plan", "collide", "integrate", "commit"):
                assert stages[k] > 0, (n, w, k)
            assert stages["other"] >= 0 and math.isclose(sum(stages.values()), 1.0, rel_tol=1e-9), (n, w)
        for key in ("max_overlap_state_m", "max_overlap_rest_m", "max_speed_1s_mps", "max_speed_3s_mps"):
            assert math.isfinite(m[key]) and m[key] >= 0, (n, key)
        assert m["max_overlap_rest_m"] <= m["max_overlap_state_m"]
    # the same piles with sleep off (the solver alone): every body awake to the end
    for n in PILE_N:
        a = r["windows_awake"][str(n)]
        assert a["steps_ok"] == a["steps"] and a["asleep_3s"] == 0, n
        assert measured(a["rest"]["s_per_simulated_s"]) and a["rest"]["solves_per_step"] > 0, n
        assert measured(a["rest"]["points_per_solve"]), n
    # the falling piles again under other tilt patterns: the same solves, other falls
    assert len(r["windows_tilts"]) == 3
    for tilt, piles in r["windows_tilts"].items():
        for n in PILE_N:
            f = piles[str(n)]["fall"]
            assert measured(f["s_per_simulated_s"]) and measured(f["points_per_solve"]), (tilt, n)
    labels = [row[0] for row in r["windows_targets"]]
    assert any(x.startswith("pile of 1000 at rest (2–3 s)") and "MuJoCo" in x for x in labels)
    assert any(x.startswith(f"pile of {PILE_N[-1]} over 3 s: penetration ≤ 1 mm") for x in labels)
    assert any(x.startswith("piles at rest: growth") for x in labels)
    # growth is a target only at equal outcome: the cube-root piles' falling growth and
    # the sleep-off figures are checks beside the targets
    assert not any("falling" in x and not x.startswith("equal height") for x in labels)
    checks = [row[0] for row in r["windows_checks"]]
    assert any(x.startswith("falling, cube-root piles: growth 10 → 100") for x in checks)
    assert any(x.startswith("sleep off, at rest: growth") for x in checks)


def test_bodies_that_can_collide_cost_beside_free_ones(quick):
    _, _, r = quick
    c = r["colliding"]
    assert c["n"] == 100  # quick mode
    assert measured(c["free_ns"]) and measured(c["colliding_ns"]) and measured(c["ratio"])
    labels = [row[0] for row in r["targets"]]
    assert any(x.startswith("100 bodies that can collide but touch nothing") for x in labels)


def test_fmu_costs_and_overhead(quick):
    _, _, r = quick
    for n in ("1", "100"):
        f = r["fmu"][n]
        for key in ("do_step_s", "get_all_s", "get_one_s", "amortised_step_s", "core_step_s"):
            assert measured(f[key]), (n, key)
        assert math.isfinite(f["overhead_s"])
        assert f["outputs"] == 7 * int(n) + 1  # position, orientation per body; solver.errorEstimate


def test_free_body_accuracy_ours(quick):
    _, _, r = quick
    ours = r["accuracy"]["ours"]
    assert [o["dt"] for o in ours] == [1e-2, 1e-3]
    for o in ours:
        assert math.isfinite(o["error_rad"]) and measured(o["s_per_simulated_s"])
    # rk4 is fourth order: ten times finer is far more accurate (a check that the
    # reference and our runs describe the same body, not a timing)
    assert ours[1]["error_rad"] < 1e-2 * ours[0]["error_rad"]


@pytest.mark.skipif(not HAVE_PEERS, reason="no .venv-peers: the full ./scripts/bench.sh creates it "
                                           "(slow to install, so quick runs do not)")
def test_mujoco_side_by_side(quick):
    _, _, r = quick
    peers = r["peers"]
    assert peers and peers["engine"].startswith("MuJoCo")
    for n in PILE_N:
        rows = [p for p in peers["piles"] if p["n"] == n]
        assert {p["integrator"] for p in rows} >= {"Euler"}
        for p in rows:
            assert measured(p["s_per_simulated_s"]) and math.isfinite(p["max_penetration_m"])
            assert measured(r["piles"][str(n)]["s_per_simulated_s"] / p["s_per_simulated_s"])
    for m in r["accuracy"]["mujoco"]:
        assert math.isfinite(m["error_rad"]) and measured(m["s_per_simulated_s"])
    # the interleaved rounds (quick: one round of the pile of 100)
    il = r["interleaved"]
    assert il and il["n"] == 100 and len(il["rounds"]) == 1
    for row in il["rounds"]:
        assert measured(row["ours"]) and measured(row["mujoco"])
        assert math.isclose(row["ratio"], row["ours"] / row["mujoco"], rel_tol=1e-12)
    # the piles over 3 s beside MuJoCo's: its third second and fastest body at 3 s, and
    # the interleaved rounds at rest (quick: one round of the pile of 100)
    for n in PILE_N:
        (p,) = [p for p in peers["piles"] if p["n"] == n and p["integrator"] == "Euler"]
        assert measured(p["rest_s_per_simulated_s"])
        assert math.isfinite(p["max_speed_3s"]) and p["max_speed_3s"] >= 0
    mil = r["windows_interleaved"]
    assert mil and mil["n"] == 100 and len(mil["rounds"]) == 1
    for row in mil["rounds"]:
        assert measured(row["ours"]) and measured(row["mujoco"])
        assert math.isclose(row["ratio"], row["ours"] / row["mujoco"], rel_tol=1e-12)
    eq = r["accuracy"]["equal_accuracy"]
    assert eq and any(e["ratio"] is not None for e in eq)
    for e in eq:
        assert e["ratio"] is None or measured(e["ratio"])


def test_chain_of_hinges_beside_mujoco(quick):
    """The chain of 100 hinged links (issue 41), 0.2 s in quick mode: our time, drift and
    energy error measured, every step taken; MuJoCo's Euler and RK4 beside it, round by
    round, when its venv is there, on the same chain (its tip where ours is)."""
    _, _, r = quick
    c = r["chain"]
    assert c["n"] == 100 and c["T"] == 0.2 and c["step_s"] == 1e-3
    ours = c["ours"]
    assert ours["steps_ok"] == ours["steps"] == 200, "the chain: a step failed"
    for key in ("s_per_simulated_s", "us_per_step", "max_drift_m", "max_energy_error", "max_speed_mps"):
        assert measured(ours[key]), key
    assert math.isfinite(ours["energy_error_end"]) and abs(ours["energy_error_end"]) <= ours["max_energy_error"]
    assert math.isfinite(ours["max_axis_drift_rad"]) and ours["max_axis_drift_rad"] >= 0
    assert ours["solves_per_step"] >= 1  # the joints are solved in every step
    stages = ours["stage_shares"]
    assert stages["solve"] > 0 and math.isclose(sum(stages.values()), 1.0, rel_tol=1e-9)
    labels = [row[0] for row in r["chain_targets"]]
    assert any("chain of 100 swinging from horizontal" in x and "MuJoCo's (Euler)" in x for x in labels)
    assert any(x.startswith("chain of 100: joint drift < 1 mm") for x in labels)
    if not HAVE_PEERS:
        assert c["mujoco"] is None and c["ratio"] is None
        return
    assert c["mujoco"]["engine"].startswith("MuJoCo") and len(c["rounds"]) == 1
    for integrator in ("Euler", "RK4"):
        m = c["mujoco"][integrator]
        assert m["step_s"] == c["step_s"] and measured(m["s_per_simulated_s"]) and measured(m["us_per_step"])
        assert measured(m["max_energy_error"]) and m["warnings"] == 0, integrator
        # the same chain: after 0.2 s its tip (still near free fall) is where ours is
        assert math.dist(m["tip_m"], ours["tip_m"]) < 1e-2, (integrator, m["tip_m"], ours["tip_m"])
    for row in c["rounds"]:
        assert measured(row["ours"]) and measured(row["mujoco"]) and measured(row["mujoco_rk4"])
        assert math.isclose(row["ratio"], row["ours"] / row["mujoco"], rel_tol=1e-12)
    assert measured(c["ratio"]) and measured(c["ratio_rk4"])


def test_convex_mesh_narrowphase_beside_the_cube(quick):
    """BM_Narrow (issue 42): every hull of the issue's 100-1000 vertices and the cube, on
    the floor and on a body of its shape: a time per pair, the contact points it gave,
    and the ratio to the cube's pair of the same kind."""
    _, _, r = quick
    narrow = r["meshes"]["narrow"]
    assert list(narrow["shapes"]) == ["cube", "hull_100", "hull_300", "hull_1000"]
    for shape, pairs in narrow["shapes"].items():
        assert set(pairs) == {"surface", "body"}, shape
        for pair, x in pairs.items():
            assert measured(x["ns_per_pair"]) and x["contacts_per_pair"] >= 1, (shape, pair)
            assert math.isclose(x["ratio_to_cube"], x["ns_per_pair"] / narrow["shapes"]["cube"][pair]["ns_per_pair"])
            assert x["hull_vertices"] == (8 if shape == "cube" else int(shape.split("_")[1])), (shape, pair)


def test_pile_of_convex_meshes_beside_mujoco(quick):
    """BM_PileHulls (issue 42): the pile of 100 pebbles, convex meshes, falling and at rest,
    every step taken; MuJoCo's on the same STL beside it, round by round, when its venv
    is there (quick: one round)."""
    _, _, r = quick
    pile = r["meshes"]["pile"]
    assert pile["n"] == 100 and pile["vertices"] == 100 and len(pile["rounds"]) == 1
    ours = pile["ours"]
    assert ours["steps_ok"] == ours["steps"], "the pile of pebbles: a step failed"
    for key in ("fall_s_per_simulated_s", "rest_s_per_simulated_s", "fall_narrowphase_share"):
        assert measured(ours[key]), key
    assert math.isfinite(ours["max_overlap_state_m"]) and 0 <= ours["asleep_3s"] <= 100
    # the bin: the pebbles inside it at 3 s, the farthest a vertex got beyond it (figures)
    assert 0 <= ours["inside_3s"] <= 100 and pile["bin"]["size_m"] == [1.0, 1.0, 0.5]
    assert math.isfinite(ours["max_beyond_wall_m"]) and math.isfinite(ours["max_below_floor_m"])
    if not HAVE_PEERS:
        assert pile["mujoco"] is None and pile["ratio_fall"] is None
        return
    m = pile["mujoco"]
    assert m["engine"].startswith("MuJoCo") and m["warnings"] == 0 and 0 <= m["inside_3s"] <= 100
    assert measured(m["fall_s_per_simulated_s"]) and measured(m["rest_s_per_simulated_s"])
    assert measured(pile["ratio_fall"]) and measured(pile["ratio_rest"])


def test_markdown_and_plots(quick):
    proc, out, r = quick
    text = (out / "performance.md").read_text()
    for section in ("## Targets", "## Core: free bodies", "## Core: piles of cubes",
                    "## Through FMI", "## Beside MuJoCo", "## Piles over 3 s: falling and at rest",
                    "## A chain of hinged links", "## Convex meshes", "## How it is measured"):
        assert section in text
    chain = text[text.index("## A chain of hinged links"):text.index("## How it is measured")]
    for label, _, _ in r["chain_targets"]:
        assert f"| {label} |" in chain
    meshes = text[text.index("## Convex meshes"):text.index("## How it is measured")]
    for shape, pairs in r["meshes"]["narrow"]["shapes"].items():
        assert f"{pairs['body']['ratio_to_cube']:.2f} |" in meshes, shape
    assert "| hull of 1000 points | 1000 | 1996 |" in meshes
    assert "**A pile of 100 convex meshes** falling into a mesh bin" in meshes and "| rigidfmu (rk4) |" in meshes
    inside = r["meshes"]["pile"]["ours"]["inside_3s"]
    assert "| inside the bin at 3 s |" in meshes and f"{inside:.0f} of 100 |" in meshes
    assert ("| ratio ours/theirs (median of the rounds) |" in meshes) == HAVE_PEERS
    assert "| rigidfmu rk4 | 1 ms |" in chain and "| ours, 0–0.2 s |" in chain
    assert ("**Interleaved.**" in chain) == HAVE_PEERS and ("not measured" in chain) != HAVE_PEERS
    # the piles' section: its targets, a row per pile, the stages falling and at rest,
    # and its MuJoCo table (with "not measured" where MuJoCo was not)
    windows = text[text.index("## Piles over 3 s: falling and at rest"):text.index("## How it is measured")]
    for heading in ("points per solve, falling", "points per solve, at rest", "fastest body at 3 s",
                    "| N | window |", "### Beside MuJoCo", "MuJoCo fastest body at 3 s",
                    "ratio at rest, ours/theirs", "asleep at 3 s", "**Sleep off**",
                    "Growth of the points per solve while the piles fall", "other patterns",
                    "The same steps by the step's stages", "| N | window | plan | wake | collide |"):
        assert heading in windows, heading
    for n in PILE_N:
        assert f"| {n} | falling, 0–1 s |" in windows and f"| {n} | at rest, 2–3 s |" in windows
    for label, _, _ in r["windows_targets"] + r["windows_checks"]:
        assert f"| {label} |" in windows
    assert "| check (not a target) | measured | |" in windows
    if HAVE_PEERS:
        assert "**Interleaved, pile of 100 at rest.**" in windows
    else:
        assert "not measured" in windows
    assert "== piles over 3 s (BM_PileWindows" in proc.stdout
    for m in METHODS:
        assert f"| `{m}` |" in text
    assert "targets (figures, never asserted)" in proc.stdout
    statuses = [row[2] for row in r["targets"] + r["windows_targets"] + r["windows_checks"] + r["chain_targets"]]
    assert statuses and set(statuses) <= {"PASS", "MISS", "–"}
    if HAVE_PEERS:
        assert "ratio ours/theirs" in text
        assert "**Interleaved, pile of 100.**" in text
    for name in ("free_bodies.png", "piles.png"):
        png = out / "performance" / name
        data = png.read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10000, png
        assert f"performance/{name}" in text
