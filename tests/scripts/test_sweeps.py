"""The rule of tests/conftest.py for physics sweeps (`@pytest.mark.sweep("name")`): under
the sanitizers (RIGIDFMU_SANITIZED=1) only the first value of each named parameter runs,
every value of the others does; the plain run runs every case; a sweep that names no
parameter of its test is an error. Checked on a sample test with the suite's conftest."""
import os
import pathlib
import shutil
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
SAMPLE = '''
import pytest


@pytest.mark.sweep("ratio")
@pytest.mark.parametrize("ratio", [1.0, 1e3, 1e6])
@pytest.mark.parametrize("xi", [0.0, 0.5])
def test_impact(xi, ratio):
    pass


@pytest.mark.parametrize("h", [1e-3, 1e-2])
def test_not_a_sweep(h):
    pass
'''


def run(tmp_path, sample, sanitized):
    shutil.copyfile(ROOT / "tests" / "conftest.py", tmp_path / "conftest.py")
    (tmp_path / "pytest.ini").write_text("[pytest]\nmarkers =\n    sweep: numbers only\n")
    (tmp_path / "test_sample.py").write_text(sample)
    env = dict(os.environ, RIGIDFMU_BUILD=str(tmp_path / "build"), RIGIDFMU_SANITIZED="1" if sanitized else "0")
    return subprocess.run([sys.executable, "-m", "pytest", "-v", "-rs", "-p", "no:cacheprovider", str(tmp_path)],
                          cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)


def outcomes(out):
    return {line.split("::")[1].split()[0]: line.split()[1] for line in out.splitlines()
            if "::" in line and line.split()[1:2] in (["PASSED"], ["SKIPPED"])}


def test_the_plain_run_runs_every_case(tmp_path):
    p = run(tmp_path, SAMPLE, sanitized=False)
    assert p.returncode == 0, p.stdout + p.stderr
    assert set(outcomes(p.stdout).values()) == {"PASSED"} and len(outcomes(p.stdout)) == 8, p.stdout


def test_under_the_sanitizers_the_first_value_of_a_swept_parameter_only(tmp_path):
    p = run(tmp_path, SAMPLE, sanitized=True)
    assert p.returncode == 0, p.stdout + p.stderr
    ran = sorted(name for name, outcome in outcomes(p.stdout).items() if outcome == "PASSED")
    assert ran == ["test_impact[0.0-1.0]", "test_impact[0.5-1.0]", "test_not_a_sweep[0.001]",
                   "test_not_a_sweep[0.01]"], p.stdout
    assert len(outcomes(p.stdout)) == 8, p.stdout
    assert "first value of ratio only" in p.stdout


def test_a_sweep_that_names_no_parameter_is_an_error(tmp_path):
    p = run(tmp_path, SAMPLE.replace('sweep("ratio")', 'sweep("mass")'), sanitized=False)
    assert p.returncode != 0
    assert "must name parameters of the test" in p.stdout + p.stderr
