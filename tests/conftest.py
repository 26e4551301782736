"""Shared fixtures: FMUs are built once per scene content and shared between tests."""
import hashlib
import json
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
BUILD = pathlib.Path(os.environ.get("RIGIDFMU_BUILD", ROOT / "build"))
# Under pytest-xdist (`pytest -n 2`, scripts/test.sh) each worker process builds into a
# folder of its own: a worker never sees another's half-written FMU.
WORKER = os.environ.get("PYTEST_XDIST_WORKER")
FMU_DIR = BUILD / "test-fmus" / (WORKER or "session")
# FMUs are shared between the tests of one session, never across sessions: the code
# they were built from may have changed since.
shutil.rmtree(FMU_DIR, ignore_errors=True)
# The session's first FMU brings the build trees up to date (build_fmu.sh runs CMake on
# the core's tree and the win64 one, over a second even when nothing changed); the
# others package from them as they are (--no-build): a session does not change the code.
# Workers never build the trees (two CMake runs on one tree would race): the
# controlling process has (pytest_sessionstart).
built = [] if WORKER is None else [None]


def bring_trees_up_to_date():
    env = dict(os.environ, RIGIDFMU_SKIP_SETUP="1")
    env.pop("LD_PRELOAD", None)  # not for the build tools (see build_fmu)
    subprocess.run([sys.executable, "-c", "from rigidfmu import native; native.find(build=True, win64=True)"],
                   check=True, env=env, stdout=subprocess.DEVNULL)


def pytest_sessionstart(session):
    """With workers (pytest -n N) the controlling process brings the build trees up to
    date once, before any worker builds an FMU."""
    if WORKER is None and session.config.getoption("numprocesses", default=None):
        bring_trees_up_to_date()


def scene_and_files(path: pathlib.Path) -> tuple[dict, dict]:
    """A scene file (an example's) and the mesh files it names, {path: bytes}."""
    from rigidfmu import meshes
    scene = json.loads(path.read_text())
    return scene, {r.file: (path.parent / r.file).read_bytes() for r in meshes.mesh_references(scene)}


def build_fmu(scene: dict | pathlib.Path, fmi: int = 2, files: dict | None = None) -> pathlib.Path:
    """The FMU of a scene (a dict in the scene format, or a scene file with the mesh files
    beside it), built once per content and FMI version (2 or 3). `files`: {relative path:
    bytes} written beside a dict's scene (the mesh files it names)."""
    if isinstance(scene, pathlib.Path):
        scene, files = scene_and_files(scene)
    text = json.dumps(scene, indent=1, sort_keys=True)
    digest = hashlib.sha256(text.encode())
    for name, data in sorted((files or {}).items()):
        digest.update(name.encode() + b"\0" + data)
    key = digest.hexdigest()[:16]
    fmu = FMU_DIR / f"{scene.get('name', 'scene')}-{key}{'' if fmi == 2 else '-fmi3'}.fmu"
    if not fmu.exists():
        FMU_DIR.mkdir(parents=True, exist_ok=True)
        folder = FMU_DIR / f"{scene.get('name', 'scene')}-{key}" if files else FMU_DIR
        scene_file = folder / f"{scene.get('name', 'scene')}-{key}.json"
        for name, data in (files or {}).items():
            (folder / name).parent.mkdir(parents=True, exist_ok=True)
            (folder / name).write_bytes(data)
        scene_file.write_text(text)
        env = dict(os.environ, RIGIDFMU_SKIP_SETUP="1")
        # a sanitizer runtime preloaded into the tests (ASan/UBSan build) is not for the
        # build tools: cmake's children hang under it
        env.pop("LD_PRELOAD", None)
        subprocess.run([str(ROOT / "scripts" / "build_fmu.sh"), str(scene_file), str(fmu), "--fmi", str(fmi)] +
                       (["--no-build"] if built else []), check=True, env=env, stdout=subprocess.DEVNULL)
        built.append(fmu)
    return fmu


@pytest.fixture(scope="session")
def fmu_of():
    return build_fmu


@pytest.fixture
def slave(fmu_of):
    """Opens initialised instances of scenes' FMUs (FMI version `fmi`, the start values
    `start` set before initialisation), closed after the test."""
    from rigidfmu.driver import Slave
    opened = []

    def open_(scene, fmi=2, start=None, files=None):
        s = Slave(fmu_of(scene, fmi=fmi, files=files))
        opened.append(s)
        s.initialize(start)
        return s
    yield open_
    for s in opened:
        s.close()


# Under the sanitizers (scripts/sanitize.sh) a physics sweep runs its first case only.
# `@pytest.mark.sweep("name", ...)` names the parameters of a parametrized test that only
# change numbers (a step, a mass ratio, an angle), not the code a case runs; a parameter
# that picks a method, a shape or a branch (restitution zero or not) is not named, and all
# of its values run. The plain run runs every case.
SANITIZED = os.environ.get("RIGIDFMU_SANITIZED") == "1"
SWEEP_SKIP = ("sweep: under the sanitizers the first value of {} only (the same code with other "
              "numbers; the plain run runs them all)")


def first_value(item, name):
    """The first value that the test's parametrize gives the parameter `name`."""
    for marker in item.iter_markers("parametrize"):
        names = marker.args[0].split(",") if isinstance(marker.args[0], str) else list(marker.args[0])
        names = [n.strip() for n in names]
        if name in names:
            first = marker.args[1][0]
            if hasattr(first, "marks"):  # a pytest.param(...)
                first = first.values if len(names) > 1 else first.values[0]
            return first[names.index(name)] if len(names) > 1 else first
    raise pytest.UsageError(f"{item.nodeid}: sweep({name!r}) names no parameter of the test")


def pytest_collection_modifyitems(config, items):
    for item in items:
        marker = item.get_closest_marker("sweep")
        if marker is None:
            continue
        params = getattr(getattr(item, "callspec", None), "params", {})
        if not marker.args or any(name not in params for name in marker.args):
            raise pytest.UsageError(f"{item.nodeid}: sweep{marker.args} must name parameters of the test")
        if SANITIZED and any(params[name] != first_value(item, name) for name in marker.args):
            item.add_marker(pytest.mark.skip(reason=SWEEP_SKIP.format(", ".join(marker.args))))


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_setup(item):
    """Every test, and every fixture it sets up, starts in the project's root. fmpy
    changes into an FMU's binaries folder to load its library and stays there when the
    load fails; once that folder (a temporary extraction) is removed, every later
    os.getcwd() raises and the rest of the session fails with it (seen twice in CI
    simulations, from test_fmu_state on)."""
    os.chdir(ROOT)
