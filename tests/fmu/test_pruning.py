"""FMUs carry only what their scene needs: the smallest prebuilt binary that has the
scene's modules, and every shared library beyond the C/C++ runtime bundled beside it."""
import hashlib
import os
import pathlib
import shutil
import subprocess
import tempfile
import zipfile

import pytest
from fmpy import extract, read_model_description, simulate_fmu

import scenes
from harness import Slave

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("RIGIDFMU_BUILD", ROOT / "build"))
RUNTIME = ("linux-vdso", "libc.so", "libm.so", "libstdc++.so", "libgcc_s.so", "ld-linux")


def colliding_scene():
    a = scenes.body("a", position=[0, 0, 1])
    b = scenes.body("b", position=[0.5, 0, 1])
    return scenes.scene("Colliding", [a, b])


def gravity_only_scene():
    return scenes.scene("GravityOnly", [scenes.body("ball", collision=False)])


def jointed_scene():
    a, b = scenes.body("a", position=[0, 0, 1]), scenes.body("b", position=[1, 0, 1])
    s = scenes.scene("Jointed", [a, b])
    s["joints"] = [{"name": "hinge", "type": "revolute", "bodies": ["a", "b"], "anchor": [0.5, 0, 1],
                    "axis": [0, 1, 0]}]
    return s


def media_scene():
    s = scenes.scene("MediaOnly", [scenes.body("ball")])
    s["media"] = [{"name": "tank", "type": "water", "min": [-1, -1, -1], "max": [1, 1, 1]}]
    return s


SANITIZED = os.environ.get("RIGIDFMU_SANITIZED") == "1"
# In the sanitizer run (scripts/sanitize.sh) the binaries also need the sanitizer
# runtimes, which the host process provides (preloaded) and the packager leaves out.
SANITIZER_RUNTIME = ("libasan.so", "libubsan.so") if SANITIZED else ()
# The sanitizer build compiles only the combination with every module (RIGIDFMU_VARIANTS=top),
# whose code is a superset of the others': every scene gets that binary there.
ONLY_TOP = ("the sanitizer build compiles only the binary with every module (RIGIDFMU_VARIANTS=top, "
            "scripts/sanitize.sh): no smaller binary to choose or to refuse with; the plain run checks it")


def built_masks():
    return sorted(int(p.stem.rsplit("_", 1)[1]) for p in BUILD.glob("rigidfmu_fmi2_*.so"))


def expected_mask(mask):
    """The binary a scene of modules `mask` gets: its own in a full build; in the
    sanitizer's build of the top combination only, that one."""
    if not SANITIZED or mask in built_masks():
        return mask
    built = built_masks()
    assert len(built) == 1 and built[0] & mask == mask, built
    return built[0]


def runtime(name):
    """The C and C++ runtime and the loader, which an FMU may take from the system."""
    return os.path.basename(name).startswith(RUNTIME + SANITIZER_RUNTIME)


def ldd(library, folder):
    out = subprocess.run(["ldd", str(library)], capture_output=True, text=True, check=True,
                         env=dict(os.environ, LD_LIBRARY_PATH=""), cwd=folder).stdout
    rows = {}
    for line in out.splitlines():
        line = line.strip()
        name = line.split()[0]
        rows[name] = line.split("=>")[1].split("(")[0].strip() if "=>" in line else line
    return rows


def sha(path):
    return hashlib.sha256(pathlib.Path(path).read_bytes()).hexdigest()


def binary_of(fmu, unzip):
    md = read_model_description(str(fmu))
    return pathlib.Path(unzip, "binaries", "linux64", md.coSimulation.modelIdentifier + ".so")


def test_colliding_fmu_resolves_every_library_inside_its_folder(fmu_of):
    fmu = fmu_of(colliding_scene())
    unzip = pathlib.Path(extract(str(fmu), unzipdir=tempfile.mkdtemp(prefix="rigid-ldd-")))
    try:
        libs = ldd(binary_of(fmu, unzip), unzip)
        bundled = pathlib.Path(unzip, "binaries", "linux64").resolve()
        assert any("libfcl" in name for name in libs), libs
        for name, where in libs.items():
            if runtime(name):
                continue
            assert "not found" not in where, (name, where)
            assert pathlib.Path(where).resolve().parent == bundled, (name, where)
        # and each bundled library finds its own dependencies there too
        for lib in bundled.glob("lib*.so*"):
            for name, where in ldd(lib, unzip).items():
                if not runtime(name):
                    assert pathlib.Path(where).resolve().parent == bundled, (lib.name, name, where)
        # the unpacked FMU runs
        r = simulate_fmu(str(unzip), stop_time=0.1, output_interval=0.05)
        assert r["a.position[3]"][-1] < 1.0
    finally:
        shutil.rmtree(unzip, ignore_errors=True)


@pytest.mark.skipif(SANITIZED and 0 not in built_masks(), reason=ONLY_TOP)
def test_gravity_only_fmu_needs_no_collision_libraries(fmu_of):
    fmu = fmu_of(gravity_only_scene())
    with zipfile.ZipFile(fmu) as z:
        binaries = [n for n in z.namelist() if n.startswith("binaries/linux64/") and not n.endswith("/")]
    assert binaries == ["binaries/linux64/GravityOnly.so"]
    unzip = pathlib.Path(extract(str(fmu), unzipdir=tempfile.mkdtemp(prefix="rigid-ldd-")))
    try:
        libs = ldd(binary_of(fmu, unzip), unzip)
        for name in libs:
            assert not any(k in name for k in ("fcl", "ccd", "octo")), libs
            assert runtime(name), libs
        # it is the binary built without any optional module
        assert sha(binary_of(fmu, unzip)) == sha(BUILD / "rigidfmu_fmi2_0.so")
    finally:
        shutil.rmtree(unzip, ignore_errors=True)


@pytest.mark.parametrize("make,mask", [(gravity_only_scene, 0), (media_scene, 2), (colliding_scene, 5),
                                       (jointed_scene, 13)])
def test_each_scene_gets_the_binary_of_its_modules(fmu_of, make, mask):
    fmu = fmu_of(make())
    unzip = extract(str(fmu), unzipdir=tempfile.mkdtemp(prefix="rigid-mask-"))
    try:
        assert sha(binary_of(fmu, unzip)) == sha(BUILD / f"rigidfmu_fmi2_{expected_mask(mask)}.so")
    finally:
        shutil.rmtree(unzip, ignore_errors=True)


def test_a_mesh_or_compound_scene_gets_the_binary_with_the_meshes_module(fmu_of):
    """Meshes come in one combination, with every module (CMakeLists.txt): 31."""
    compound = {"type": "compound", "parts": [{"shape": {"type": "sphere", "radius": 0.1}},
                                               {"shape": {"type": "sphere", "radius": 0.1}, "position": [0.3, 0, 0]}]}
    fmu = fmu_of(scenes.scene("CompoundOnly", [scenes.body("pair", shape=compound)]))
    unzip = extract(str(fmu), unzipdir=tempfile.mkdtemp(prefix="rigid-mask-"))
    try:
        assert sha(binary_of(fmu, unzip)) == sha(BUILD / f"rigidfmu_fmi2_{expected_mask(31)}.so")
    finally:
        shutil.rmtree(unzip, ignore_errors=True)


def test_only_the_binaries_with_meshes_carry_the_mesh_reader_and_solid_mass():
    """The mesh files' reading and the solids' mass properties (src/mesh_file.cpp,
    src/solid_mass.cpp, src/compound.cpp) are in the binaries of mask bit 16 only; the
    others link the refusal of meshes and compounds (src/mesh_file_absent.cpp)."""
    for mask in built_masks():
        symbols = subprocess.run(["nm", "-C", str(BUILD / f"rigidfmu_fmi2_{mask}.so")], capture_output=True,
                                 text=True, check=True).stdout
        assert ("rigid::meshSolidMass(" in symbols) == bool(mask & 16), mask


def test_only_the_binaries_with_joints_carry_the_joint_solver():
    """The joints' rows (src/joint_rows.cpp) are in the binaries of mask bit 8 only; the
    others read a joint scene only to refuse it."""
    for mask in built_masks():
        symbols = subprocess.run(["nm", "-C", str(BUILD / f"rigidfmu_fmi2_{mask}.so")], capture_output=True,
                                 text=True, check=True).stdout
        assert ("JointRows::solve" in symbols) == bool(mask & 8), mask


@pytest.mark.skipif(SANITIZED and 0 not in built_masks(), reason=ONLY_TOP)
def test_binary_without_a_needed_module_refuses_the_scene(fmu_of):
    """A scene edited to need media, under a binary built without them: refused."""
    s = Slave(fmu_of(gravity_only_scene()), instantiate=False)
    try:
        scene = pathlib.Path(s.dir, "resources", "scene.json")
        scene.write_text(scene.read_text().rstrip().rstrip("}") +
                         ', "media": [{"name": "tank", "type": "water", "min": [-1, -1, -1], "max": [1, 1, 1]}]}')
        c = s.slave.fmi2Instantiate(b"x", 1, s.md.guid.encode(),
                                    pathlib.Path(s.dir, "resources").as_uri().encode(),
                                    s.log.callbacks, 0, 0)
        assert not c
        assert "needs the media module" in s.log.messages[-1][2]
    finally:
        shutil.rmtree(s.dir, ignore_errors=True)


def test_variables_by_need(fmu_of):
    """A body may expose only some outputs and no inputs: the XML holds only those,
    fmpy's validation finds nothing, and the run gives the same motion."""
    from fmpy.validation import validate_fmu
    full = scenes.projectile()
    lean = scenes.projectile()
    lean["name"] = "LeanProjectile"
    lean["bodies"][0]["outputs"] = ["position", "orientation"]
    lean["bodies"][0]["inputs"] = []
    fmu = fmu_of(lean)
    assert validate_fmu(str(fmu)) == []
    names = {v.name for v in read_model_description(str(fmu)).modelVariables}
    body = {n for n in names if n.startswith("ball.")}
    assert body == {f"ball.position[{i}]" for i in (1, 2, 3)} | \
        {f"ball.orientation[{i}]" for i in (1, 2, 3, 4)} | {"ball.mass", "ball.restitution"}
    a = simulate_fmu(str(fmu), stop_time=1.0, output_interval=0.1)
    b = simulate_fmu(str(fmu_of(full)), stop_time=1.0, output_interval=0.1)
    for i in (1, 2, 3):
        assert list(a[f"ball.position[{i}]"]) == list(b[f"ball.position[{i}]"])
