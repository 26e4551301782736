"""scripts/report_accuracy.sh: the quick report runs, writes its figures and table, and
the measured orders of convergence hold; the --scene mode recommends a method. No time
is asserted (timings are figures only)."""
import os
import pathlib
import re
import subprocess
import sys

import pytest

pytestmark = pytest.mark.slow  # a whole script or browser run (pyproject.toml)

ROOT = pathlib.Path(__file__).resolve().parents[2]
LAB = os.pathsep.join(filter(None, [str(ROOT / "scripts"), os.environ.get("PYTHONPATH")]))  # scripts/reports
# the reports are the source tree's (scripts/reports), as scripts/report_accuracy.sh runs them
ENV = dict(os.environ, RIGIDFMU_SKIP_SETUP="1", PYTHONPATH=LAB)


def run(*args):
    return subprocess.run([sys.executable, "-m", "reports.accuracy", *args], capture_output=True,
                          text=True, env=ENV, cwd=ROOT, timeout=600)


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    out = tmp_path_factory.mktemp("accuracy")
    return run("--quick", "--out", str(out)), out


def order_cells(markdown, problem):
    """The 'Measured orders' table: {method label: cell} of one problem's row."""
    lines = markdown.split("## Measured orders", 1)[1].strip().splitlines()
    header = [c.strip() for c in lines[0].strip("|").split("|")]
    for line in lines[2:]:
        cells = [c.strip() for c in line.strip("|").split("|")]
        if cells[0] == problem:
            return dict(zip(header[1:], cells[1:]))
    raise AssertionError(f"no row for {problem!r} in the orders table")


def test_quick_report_passes_its_order_checks(quick):
    proc, _ = quick
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "orders: all as expected" in proc.stdout


def test_quick_report_writes_figures_and_table(quick):
    proc, out = quick
    md = out / "accuracy.md"
    assert md.exists(), proc.stdout + proc.stderr
    text = md.read_text()
    assert len(text) > 2000
    assert re.search(r"(commit [0-9a-f]{7,}|unknown source state)", text.split("\n", 3)[2])  # the code it measured
    for title in ("torque-free body near the intermediate axis", "torque-free body near the major axis",
                  "projectile with linear drag"):
        assert f"## {title}" in text
    pngs = sorted((out / "accuracy").glob("*.png"))
    assert len(pngs) >= 4
    for png in pngs:
        data = png.read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10000, png
        assert f"accuracy/{png.name}" in text or png.name == "work_precision.png"


@pytest.mark.parametrize("method,order,tol", [("euler", 1.0, 0.25), ("rk4", 4.0, 0.5)])
@pytest.mark.parametrize("problem", ["torque-free body near the major axis",
                                     "projectile with linear drag"])
def test_table_shows_the_expected_orders_on_smooth_problems(quick, problem, method, order, tol):
    _, out = quick
    cell = order_cells((out / "accuracy.md").read_text(), problem)[method]
    value = float(re.match(r"[0-9.]+", cell).group(0))
    assert abs(value - order) <= tol, (problem, method, cell)


def test_symplectic_euler_is_first_order_with_forces(quick):
    """Without torque its drift is the splitting's free rotation (second order, see
    tests/fmu/test_torque_free.py); with drag the kick makes it first order."""
    _, out = quick
    cell = order_cells((out / "accuracy.md").read_text(), "projectile with linear drag")["symplecticEuler"]
    assert abs(float(re.match(r"[0-9.]+", cell).group(0)) - 1.0) <= 0.25, cell


def test_euler_near_the_intermediate_axis_is_marked_not_asymptotic(quick):
    _, out = quick
    cell = order_cells((out / "accuracy.md").read_text(),
                       "torque-free body near the intermediate axis")["euler"]
    assert "not asymptotic" in cell


def test_scene_mode_prints_a_table_and_a_recommendation():
    proc = run("--scene", str(ROOT / "scripts" / "scenes" / "spinner.json"), "--tolerance", "1e-4",
               "--stop-time", "1.0", "--quick")
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert re.search(r"^rk4\s+h 0\.001\s+[0-9.e+-]+", proc.stdout, re.M), proc.stdout
    rec = [l for l in proc.stdout.splitlines() if l.startswith("recommendation: ")]
    assert len(rec) == 1, proc.stdout
    m = re.match(r"recommendation: solver\.method = (\w+), .*error ([0-9.e+-]+) <= 0\.0001", rec[0])
    assert m, rec[0]
    assert float(m.group(2)) <= 1e-4
