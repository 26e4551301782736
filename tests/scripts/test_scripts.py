"""The smaller reports run and print their figures (quick mode; no timing asserted), and
the README's main job, scripts/run.sh, writes what the guide says it writes."""
import os
import pathlib
import re
import subprocess

import pytest

pytestmark = pytest.mark.slow  # a whole script or browser run (pyproject.toml)

ROOT = pathlib.Path(__file__).resolve().parents[2]
ENV = dict(os.environ, RIGIDFMU_SKIP_SETUP="1")


def run(*args):
    return subprocess.run([str(ROOT / "scripts" / "report.sh"), *args], check=True, capture_output=True, text=True,
                          env=ENV, cwd=ROOT).stdout


def test_bench_pruning_prints_three_costs_and_ratios():
    out = run("pruning", "--quick")
    rows = re.findall(r"^(bare integrator \(C\+\+\)|gravity-only FMU|every feature, far away)\s+"
                      r"([0-9.]+)\s+([0-9.]+)$", out, re.M)
    assert [r[0] for r in rows] == ["bare integrator (C++)", "gravity-only FMU", "every feature, far away"]
    assert float(rows[0][2]) == 1.0 and all(float(r[1]) > 0 for r in rows)


def test_fmu_table_lists_every_example_scene():
    out = run("fmus", "--print", "--quick")
    scenes = sorted(p.name for p in (ROOT / "scripts" / "scenes").glob("*.json"))
    lines = [l for l in out.splitlines() if l.startswith("| `")]
    assert [re.match(r"\| `([^`]+)`", l).group(1) for l in lines] == scenes
    spinner = next(l for l in lines if "spinner.json" in l)
    assert "| none |" in spinner  # a lone body ships no extra library
    for line in lines:  # both platforms' binaries weighed
        linux64, win64 = line.split("|")[3:5]
        assert linux64.strip().endswith(" KiB") and win64.strip().endswith(" KiB"), line


def test_the_main_job_writes_the_run_and_its_replay(tmp_path):
    """README: `./scripts/run.sh` builds the scene's FMU, simulates it and writes the CSV,
    the plots and the replay (docs/guide/replay.md); win64 left out here (the win64
    tests build and run those binaries)."""
    env = dict(ENV, RIGIDFMU_OUT=str(tmp_path), RIGIDFMU_NO_WIN64="1")
    subprocess.run([str(ROOT / "scripts" / "run.sh"), str(ROOT / "scripts" / "scenes" / "default.json"), "0.2"],
                   check=True, capture_output=True, text=True, env=env, cwd=ROOT)
    written = sorted(p.name for p in tmp_path.iterdir())
    assert written == ["default.csv", "default.fmu", "default.html", "default_contacts.png", "default_energy.png",
                       "default_position.png", "default_velocity.png"], written
    rows = (tmp_path / "default.csv").read_text().splitlines()
    assert len(rows) == 1 + 21  # a header, then every 10 ms of 0.2 s
