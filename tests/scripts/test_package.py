"""The `rigidfmu` package and command: every command's help, a refused scene's message
and exit status, and the package installed into a fresh venv that builds and
simulates an FMU from a folder outside this source tree, the same FMU as
scripts/build_fmu.sh makes."""
import ast
import json
import os
import pathlib
import re
import subprocess
import sys
import tomllib
import zipfile

import numpy as np
import pytest
from fmpy import simulate_fmu

from rigidfmu import cli

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("RIGIDFMU_BUILD", ROOT / "build")).resolve()
ENV = dict(os.environ, RIGIDFMU_SKIP_SETUP="1")
COMMANDS = ("build", "check", "simulate", "replay", "study")
# scripts/report.sh KIND: the reports, made from the source tree (not in the package)
REPORTS = {"accuracy": "scripts/report_accuracy.sh", "stability": "scripts/stress.sh",
           "performance": "scripts/bench.sh", "pruning": "scripts/report.sh pruning",
           "fmus": "scripts/report.sh fmus"}


def rigidfmu(*args, python=sys.executable, env=ENV, cwd=ROOT):
    return subprocess.run([str(python), "-m", "rigidfmu", *map(str, args)], capture_output=True, text=True,
                          env=env, cwd=cwd)


def test_help_of_the_command_and_of_every_subcommand():
    top = rigidfmu("--help")
    assert top.returncode == 0
    for command in COMMANDS:
        assert command in top.stdout
        sub = rigidfmu(command, "--help")
        assert sub.returncode == 0, sub.stderr
        assert sub.stdout.startswith(f"usage: rigidfmu {command}")
    gone = rigidfmu("report", "--help")  # the reports are the source tree's: scripts/report.sh
    assert gone.returncode == 2 and "invalid choice: 'report'" in gone.stderr, gone.stderr


def report(*args):
    return subprocess.run([str(ROOT / "scripts" / "report.sh"), *map(str, args)], capture_output=True, text=True,
                          env=ENV, cwd=ROOT)


def test_help_of_every_report():
    for kind, prog in REPORTS.items():
        sub = report(kind, "--help")
        assert sub.returncode == 0, sub.stderr
        assert sub.stdout.startswith(f"usage: {prog}"), sub.stdout
        assert "--quick" in sub.stdout


def test_report_and_study_usage_errors_and_failures():
    wrong = report("nonsense")
    assert wrong.returncode == 2 and "usage: scripts/report.sh" in wrong.stderr
    assert rigidfmu("study").returncode == 2
    assert report("pruning", "--no-such-option").returncode == 2
    missing = rigidfmu("study", "no-such-study.json")
    assert missing.returncode == 1, missing.stderr
    assert missing.stderr.startswith("rigidfmu: study: no-such-study.json:"), missing.stderr
    assert "Traceback" not in missing.stderr


@pytest.mark.parametrize("absent, message", [
    ("pandas", "needs pandas, not installed"),
    ("dask", "needs dask, not installed"),  # imported only once the runs start: looked for first
    ("pyarrow.parquet", "cannot import pyarrow.parquet"),  # a package there, but incomplete
])
def test_study_without_its_dependencies_names_the_extra(absent, message):
    """A None in sys.modules makes a module unimportable, as if it were not installed."""
    code = (f"import sys; sys.modules[{absent!r}] = None\n"
            "from rigidfmu.cli import main\n"
            "sys.exit(main(['study', 'no-such-study.json']))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=ENV, cwd=ROOT)
    assert done.returncode == 1, done.stderr
    assert done.stderr == f"rigidfmu: study: {message}: pip install 'rigidfmu[study]'\n", done.stderr
    assert done.stdout == ""


def requirement(line):
    """(normalised name, version) of a `name==version` pin (PEP 503 names)."""
    name, sep, version = line.split("#")[0].strip().partition("==")
    assert sep and version, f"not pinned: {line!r}"
    return re.sub(r"[-_.]+", "-", name).lower(), version


def test_pyproject_pins_agree_with_requirements():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    pinned = dict(requirement(line) for line in (ROOT / "requirements.txt").read_text().splitlines()
                  if line.strip() and not line.startswith("#"))
    declared = project["dependencies"] + [d for group in project["optional-dependencies"].values() for d in group]
    assert project["optional-dependencies"]["study"]
    for dependency in declared:
        name, version = requirement(dependency)
        assert pinned.get(name) == version, f"pyproject.toml {dependency}, requirements.txt {pinned.get(name)}"


def test_the_study_extra_holds_what_the_study_imports():
    """Every module from outside the standard library and this package that
    python/rigidfmu/study imports is a dependency of the package or of its study extra,
    the extra holds nothing else, and the command looks for exactly those."""
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    imported = set()
    for source in (ROOT / "python" / "rigidfmu" / "study").glob("*.py"):
        for node in ast.walk(ast.parse(source.read_text())):
            if isinstance(node, ast.Import):
                imported |= {a.name.split(".")[0] for a in node.names}
            elif isinstance(node, ast.ImportFrom) and node.level == 0:
                imported.add(node.module.split(".")[0])
    third_party = imported - set(sys.stdlib_module_names) - {"rigidfmu"}
    base = {requirement(d)[0] for d in project["dependencies"]}
    extra = {requirement(d)[0] for d in project["optional-dependencies"]["study"]}
    assert third_party - base == extra
    assert set(cli.STUDY_MODULES) == extra


def test_help_imports_neither_matplotlib_nor_dask():
    code = ("import sys; from rigidfmu import cli\n"
            "try:\n    cli.main(['--help'])\nexcept SystemExit:\n    pass\n"
            "print(sorted(m for m in ('matplotlib', 'dask', 'distributed', 'numpy', 'fmpy') if m in sys.modules))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=ENV, cwd=ROOT)
    assert done.stdout.strip().splitlines()[-1] == "[]", done.stdout + done.stderr


@pytest.mark.parametrize("body, field, message", [
    ({"name": "a", "mass": 1.0}, "bodies[0].shape", "is required"),
    ({"name": "a", "shape": {"type": "sphere", "radius": 0.1}, "mass": -1}, "bodies[0].mass", "must be > 0, got -1"),
])
def test_a_malformed_scene_fails_with_the_fields_message(tmp_path, body, field, message):
    scene = tmp_path / "bad.json"
    scene.write_text(json.dumps({"name": "Bad", "bodies": [body]}))
    for command in ("check", "build"):
        run = rigidfmu(command, scene, cwd=tmp_path)
        assert run.returncode == 1
        assert f"{field}: {message}" in run.stderr
        assert "Traceback" not in run.stderr
    assert not (tmp_path / "bad.fmu").exists()


def test_a_wrong_command_line_is_a_usage_error(tmp_path):
    run = rigidfmu("build", tmp_path / "missing.json")
    assert run.returncode == 2 and "no such file" in run.stderr


def test_check_accepts_every_example_scene():
    for scene in sorted((ROOT / "scripts" / "scenes").glob("*.json")):
        run = rigidfmu("check", scene)
        assert run.returncode == 0, run.stderr
        assert "the scene is valid" in run.stdout


def test_the_source_trees_command_is_where_the_readme_says():
    # README: "in the source tree `.venv/bin/rigidfmu`" (scripts/setup.sh writes it)
    command = ROOT / ".venv" / "bin" / "rigidfmu"
    assert command.is_file(), f"{command} is missing: scripts/setup.sh writes it"
    run = subprocess.run([str(command), "check", ROOT / "scripts" / "scenes" / "default.json"], capture_output=True,
                         text=True, env=ENV, cwd=ROOT)
    assert run.returncode == 0 and "the scene is valid" in run.stdout, run.stderr


def members(fmu):
    with zipfile.ZipFile(fmu) as z:
        return {name: z.read(name) for name in z.namelist()}


@pytest.fixture(scope="module")
def installed(tmp_path_factory, fmu_of):
    """A fresh venv with the package installed from this tree, taking the binaries of
    the tests' build trees as they are (RIGIDFMU_PREBUILT and RIGIDFMU_PREBUILT_WIN64:
    nothing compiled again)."""
    fmu_of(json.loads((ROOT / "scripts" / "scenes" / "default.json").read_text()))  # both trees built
    win64 = pathlib.Path(os.environ.get("RIGIDFMU_BUILD_WIN64") or ROOT / "build-win64")
    venv = tmp_path_factory.mktemp("venv")
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    pip = [str(venv / "bin" / "python"), "-m", "pip", "install", "-q", "--disable-pip-version-check"]
    backend = tomllib.loads((ROOT / "pyproject.toml").read_text())["build-system"]["requires"][0]
    subprocess.run([*pip, backend], check=True)
    subprocess.run([*pip, "--no-build-isolation", f"--config-settings=cmake.define.RIGIDFMU_PREBUILT={BUILD}",
                    f"--config-settings=cmake.define.RIGIDFMU_PREBUILT_WIN64={win64}", str(ROOT)],
                   check=True, cwd=ROOT)
    env = {k: v for k, v in os.environ.items() if k not in ("RIGIDFMU_BUILD", "PYTHONPATH", "LD_PRELOAD")}
    return venv, env


@pytest.mark.slow
def test_the_installed_command_builds_the_same_fmu_outside_the_tree(installed, tmp_path, fmu_of):
    venv, env = installed
    work = tmp_path / "elsewhere"
    work.mkdir()
    scene = json.loads((ROOT / "scripts" / "scenes" / "default.json").read_text())
    (work / "scene.json").write_text(json.dumps(scene))

    where = subprocess.run([str(venv / "bin" / "python"), "-c", "import rigidfmu, rigidfmu.native as n; "
                            "print(rigidfmu.__file__); print(n.find(build=False).directory)"],
                           capture_output=True, text=True, env=env, cwd=work, check=True).stdout.split()
    assert all(pathlib.Path(p).is_relative_to(venv) for p in where), where

    run = subprocess.run([str(venv / "bin" / "rigidfmu"), "build", "scene.json", "-o", "x.fmu"],
                         capture_output=True, text=True, env=env, cwd=work)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == str(work / "x.fmu")
    ours = members(work / "x.fmu")
    theirs = members(fmu_of(scene))  # scripts/build_fmu.sh in this tree
    assert sorted(ours) == sorted(theirs)
    for name in ours:
        if name != "resources/scene.json":  # the same scene, written by another json.dumps
            assert ours[name] == theirs[name], name
    assert json.loads(ours["resources/scene.json"]) == scene

    # simulated with fmpy: the same run, bitwise, as the tree's FMU
    a = simulate_fmu(str(work / "x.fmu"), stop_time=0.5, output_interval=0.01)
    b = simulate_fmu(str(fmu_of(scene)), stop_time=0.5, output_interval=0.01)
    assert a.dtype.names == b.dtype.names and len(a) == 51
    for name in a.dtype.names:
        assert np.array_equal(a[name], b[name]), name

    # and by the installed command, with its own fmpy (the package's dependencies)
    run = subprocess.run([str(venv / "bin" / "rigidfmu"), "simulate", "x.fmu", "--stop-time", "0.2",
                          "--out", "results"], capture_output=True, text=True, env=env, cwd=work)
    assert run.returncode == 0, run.stderr
    assert (work / "results" / "x.csv").is_file()


@pytest.mark.slow
def test_the_installed_package_is_the_users_alone(installed, tmp_path):
    """The wheel carries the command, its builders and references, not the lab: no
    reports, benchmark scenes or peer engines' modules; and every subcommand answers
    --help from outside the source tree (study names its extra, not installed here)."""
    venv, env = installed
    site = subprocess.run([str(venv / "bin" / "python"), "-c", "import rigidfmu, pathlib; "
                           "print(pathlib.Path(rigidfmu.__file__).parent)"],
                          capture_output=True, text=True, env=env, cwd=tmp_path, check=True).stdout.strip()
    package = pathlib.Path(site)
    modules = {p.relative_to(package).as_posix() for p in package.rglob("*.py")}
    lab = [m for m in modules if m.startswith(("reports/", "scenes/bench")) or "peers" in m or "mujoco" in m]
    assert not lab, f"the wheel carries the lab: {lab}"
    for command in COMMANDS:
        run = subprocess.run([str(venv / "bin" / "rigidfmu"), command, "--help"], capture_output=True, text=True,
                             env=env, cwd=tmp_path)
        if command == "study" and run.returncode == 1:
            assert "pip install 'rigidfmu[study]'" in run.stderr, run.stderr
            continue
        assert run.returncode == 0 and run.stdout.startswith(f"usage: rigidfmu {command}"), run.stderr
