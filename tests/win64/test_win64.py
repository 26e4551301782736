"""The win64 binary of every example FMU (issue 20), FMI 2.0 and FMI 3.0: what the DLL
exports and imports, and the same calls through our C importer (fmu_driver.c, compiled
for either version) on the linux64 .so natively and on the win64 .dll under Debian's
wine64, whose results must agree.

Skipped, with the reason, only where MinGW-w64 or wine64 is not installed;
scripts/setup.sh installs both, so the suite's own runs (./scripts/test.sh, CI) always
run these tests."""
import json
import math
import os
import pathlib
import re
import shutil
import subprocess
import urllib.parse
import zipfile

import pytest
from fmpy import extract

from rigidfmu.driver import Fmu

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENES = sorted((ROOT / "scripts" / "scenes").glob("*.json"))
DRIVER = pathlib.Path(__file__).with_name("fmu_driver.c")
MINGW = "x86_64-w64-mingw32-gcc-posix"
OBJDUMP = "x86_64-w64-mingw32-objdump"
WINE = shutil.which("wine64") or ("/usr/lib/wine/wine64" if os.access("/usr/lib/wine/wine64", os.X_OK) else None)
# Windows' own DLLs: the kernel and the C runtime. Everything else (libstdc++, libgcc,
# winpthread, FCL, libccd) is linked into the DLL.
SYSTEM_DLLS = {"kernel32.dll", "msvcrt.dll"}
# outputs are compared to this relative difference (the bound); see
# test_win64_runs_the_same_calls_as_linux64 for what is found
RELATIVE = 1e-12

pytestmark = [
    pytest.mark.skipif(not shutil.which(MINGW), reason=f"MinGW-w64 is not installed ({MINGW}: scripts/setup.sh)"),
    pytest.mark.skipif(WINE is None, reason="wine64 is not installed (Debian wine64: scripts/setup.sh)"),
]


def fmi_headers() -> pathlib.Path:
    import fmpy
    return pathlib.Path(fmpy.__file__).parent / "c-code"


# fmi2Functions.h's Model Exchange functions, which a Co-Simulation FMU does not have
MODEL_EXCHANGE_ONLY = {"fmi2EnterEventMode", "fmi2NewDiscreteStates", "fmi2EnterContinuousTimeMode",
                       "fmi2CompletedIntegratorStep", "fmi2SetTime", "fmi2SetContinuousStates",
                       "fmi2GetDerivatives", "fmi2GetEventIndicators", "fmi2GetContinuousStates",
                       "fmi2GetNominalsOfContinuousStates"}


def co_simulation_functions(fmi=2) -> set[str]:
    """The functions fmi2Functions.h declares (FMI2_Export fmi2xxxTYPE fmi2xxx;) for a
    Co-Simulation FMU: the common ones and the Co-Simulation ones. FMI 3.0: every
    function fmi3Functions.h declares (an FMU exports them all, those of the interfaces
    it does not provide refusing)."""
    text = (fmi_headers() / f"fmi{fmi}Functions.h").read_text()
    declared = set(re.findall(rf"FMI{fmi}_Export\s+fmi{fmi}\w+TYPE\s+(fmi{fmi}\w+);", text))
    return declared - MODEL_EXCHANGE_ONLY if fmi == 2 else declared


# the number of functions co_simulation_functions finds: a header read wrong finds fewer
DECLARED = {2: 34, 3: 75}


@pytest.fixture(scope="module")
def drivers(tmp_path_factory):
    """fmu_driver.c compiled for this machine and for win64, per FMI version:
    {fmi: (linux driver, windows driver)}."""
    d = tmp_path_factory.mktemp("drivers")
    env = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}  # not for the compilers
    out = {}
    for fmi, define in ((2, []), (3, ["-DFMI3"])):
        flags = ["-std=c99", "-O1", "-Wall", "-Wextra", "-Werror", *define, "-I", str(fmi_headers()), str(DRIVER)]
        subprocess.run(["gcc", *flags, "-o", str(d / f"fmu{fmi}_driver"), "-ldl", "-lm"], check=True, env=env)
        subprocess.run([MINGW, *flags, "-o", str(d / f"fmu{fmi}_driver.exe")], check=True, env=env)
        out[fmi] = d / f"fmu{fmi}_driver", d / f"fmu{fmi}_driver.exe"
    return out


@pytest.fixture(scope="module")
def wine_env():
    """A wine prefix kept per machine (its first creation takes seconds), no debug output."""
    cache = pathlib.Path(os.environ.get("RIGIDFMU_CACHE") or
                         pathlib.Path(os.environ.get("XDG_CACHE_HOME", pathlib.Path.home() / ".cache")) / "rigidfmu")
    env = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}
    env.update(WINEPREFIX=str(cache / "wine64-prefix"), WINEDEBUG="-all")
    return env


# the binaries' folders (FMI 2.0's platform names, FMI 3.0's platform tuples)
PLATFORMS = {2: ("linux64", "win64"), 3: ("x86_64-linux", "x86_64-windows")}


class Unpacked:
    """One FMU unpacked: its model description and the paths the driver needs."""

    def __init__(self, fmu, folder, fmi=2):
        self.fmu, self.fmi = fmu, fmi
        unpacked = Fmu(fmu, unzip_dir=extract(str(fmu), unzipdir=str(folder)))
        self.md = unpacked.md
        assert self.md.fmiVersion.startswith(f"{fmi}."), self.md.fmiVersion
        self.dir = pathlib.Path(unpacked.dir).resolve()
        ident = self.md.coSimulation.modelIdentifier
        linux, windows = PLATFORMS[fmi]
        self.so = self.dir / "binaries" / linux / f"{ident}.so"
        self.dll = self.dir / "binaries" / windows / f"{ident}.dll"
        real = "Real" if fmi == 2 else "Float64"
        self.reals = [v for v in self.md.modelVariables if v.type == real]

    def resources(self, windows):
        """FMI 2.0: the resources' URI; FMI 3.0: their path, ending in a separator, with
        %XX escapes that the driver decodes. wine's drive Z: is the root of this machine's
        file system."""
        folder = self.dir / "resources"
        if self.fmi == 3:
            return escaped("Z:" + str(folder).replace("/", "\\") + "\\" if windows else str(folder) + "/")
        return "file:///Z:" + escaped(str(folder)) if windows else folder.as_uri()

    def linux_args(self):
        return [escaped(str(self.so)), self.md.guid, self.resources(windows=False)]

    def windows_args(self):
        return [escaped("Z:" + str(self.dll).replace("/", "\\")), self.md.guid, self.resources(windows=True)]


def escaped(path):
    """A path as the driver takes it: UTF-8, %XX-escaped outside ASCII letters, digits
    and separators (fmu_driver.c decodes it)."""
    return urllib.parse.quote(path, safe="/\\:-_.~")


@pytest.fixture(scope="module", params=[(s.name, fmi) for s in SCENES for fmi in (2, 3)],
                ids=lambda p: f"{p[0].removesuffix('.json')}-fmi{p[1]}")
def unpacked(request, fmu_of, tmp_path_factory):
    scene, fmi = request.param
    fmu = fmu_of(ROOT / "scripts" / "scenes" / scene, fmi=fmi)
    return Unpacked(fmu, tmp_path_factory.mktemp(f"{scene.removesuffix('.json')}-fmi{fmi}"), fmi)


def run(cmd, env=None):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=300, env=env)
    out = p.stdout.replace("\r\n", "\n")
    assert p.returncode == 0, f"{cmd[0]} exit {p.returncode}\n{out[-2000:]}\n{p.stderr[-2000:]}"
    return out


def test_the_fmu_carries_a_win64_dll_beside_the_linux64_library(unpacked):
    names = zipfile.ZipFile(unpacked.fmu).namelist()
    linux, windows = PLATFORMS[unpacked.fmi]
    assert f"binaries/{windows}/{unpacked.dll.name}" in names
    assert f"binaries/{linux}/{unpacked.so.name}" in names
    assert [n for n in names if n.startswith(f"binaries/{windows}/")] == [f"binaries/{windows}/{unpacked.dll.name}"], \
        "the DLL needs nothing beside it"


def test_the_dll_exports_the_fmi_functions_and_imports_only_system_dlls(unpacked):
    dump = run([OBJDUMP, "-p", str(unpacked.dll)])
    imports = {m.lower() for m in re.findall(r"DLL Name: (\S+)", dump)}
    assert imports and imports <= SYSTEM_DLLS, f"imports beyond {sorted(SYSTEM_DLLS)}: {sorted(imports - SYSTEM_DLLS)}"
    table = dump[dump.index("[Ordinal/Name Pointer] Table"):].split("\n\n")[0]
    exported = set(re.findall(r"^\s*\[\s*\d+\]\s+(\w+)\s*$", table, re.M))
    wanted = co_simulation_functions(unpacked.fmi)
    assert len(wanted) == DECLARED[unpacked.fmi], f"the header's functions were not found: {sorted(wanted)}"
    assert exported == wanted, (f"missing {sorted(wanted - exported)}, "
                                f"beyond the FMI functions {sorted(exported - wanted)}")
    # the same set as the linux64 library's
    symbols = run(["nm", "-D", "--defined-only", str(unpacked.so)])
    assert set(re.findall(rf" T (fmi{unpacked.fmi}\w+)$", symbols, re.M)) == exported


def settings(unpacked):
    """A parameter changed before initialisation (a fixed one, 10 % up) and every input
    driven by a sine of amplitude 0.5 (force, torque, a driven body's position and
    velocities, ...); a driven body's orientation keeps its start (a wave in each
    component would be no quaternion, which the step refuses)."""
    out = []
    fixed = [v for v in unpacked.reals if v.causality == "parameter" and v.variability == "fixed"
             and v.start not in (None, "0", "0.0") and not v.name.startswith("solver.")]
    for v in fixed[:1]:
        out.append(f"{v.valueReference}={float(v.start) * 1.1!r}")
    for v in unpacked.reals:
        if v.causality == "input" and ".orientation[" not in v.name:
            out.append(f"{v.valueReference}~0.5")
    return out


def parse(text):
    rows = {}
    for line in text.splitlines():
        fields = line.split()
        if fields and fields[0] in ("step", "again", "reset"):
            rows[(fields[0], int(fields[1]))] = [float(x) for x in fields[2:]]
    return rows


def test_win64_runs_the_same_calls_as_linux64(unpacked, drivers, wine_env):
    """1000 steps with a parameter set and the inputs driven, the state taken and
    serialised halfway and set again at the end, a reset: the outputs of the .dll under
    wine and of the .so agree to 1e-12 relative (to the largest output of the same unit),
    and each platform continues bitwise from
    its own state. Measured: the two are bitwise equal on every example scene. Both
    binaries are the same sources compiled by GCC 12 for x86-64 (SSE2 arithmetic, no
    -ffast-math, no FMA), so +, *, / and sqrt round alike; what could differ is the C
    runtime's transcendental functions (glibc's libm against msvcrt's): the driver's
    inputs were first sin() waves and differed in the last bit, so they are triangle waves
    now. The bound allows a last-bit difference of the core's own libm calls."""
    linux, windows = drivers[unpacked.fmi]
    outputs = ",".join(str(v.valueReference) for v in unpacked.reals)
    call = ["run", "1000", "0.005", outputs, *settings(unpacked)]
    ours = parse(run([str(linux), *unpacked.linux_args(), *call]))
    theirs = parse(run([WINE, str(windows), *unpacked.windows_args(), *call], env=wine_env))
    assert len(ours) == 10 + 1 + 5 + 1 and ours.keys() == theirs.keys()
    for key, values in ours.items():
        assert all(math.isfinite(x) for x in values), key
        # each output against the largest of its unit at that point: a component that
        # is rounding noise about zero (a gate's vertical velocity of 1e-8 m/s, its
        # contact force of 1e-12 N beside a cable's 49 N in crane.json) carries the
        # last-bit differences of the quantities it was computed from
        scale = {}
        for v, a, b in zip(unpacked.reals, values, theirs[key]):
            scale[v.unit] = max(scale.get(v.unit, 0.0), abs(a), abs(b))
        for v, a, b in zip(unpacked.reals, values, theirs[key]):
            assert abs(a - b) <= RELATIVE * scale[v.unit], f"{key} {v.name}: linux64 {a!r}, win64 {b!r}"
    # each platform continues bitwise from its own serialised state, and resets to a fresh run
    for platform in (ours, theirs):
        for n in range(600, 1001, 100):
            assert platform[("again", n)] == platform[("step", n)]
        assert platform[("reset", 10)] == platform[("step", 10)]


@pytest.mark.parametrize("fmi", [2, 3])
@pytest.mark.parametrize("scene", ["default.json", "thruster.json"])
def test_win64_answers_bad_calls_as_linux64(scene, fmi, fmu_of, drivers, wine_env, tmp_path):
    """The abuse tests' sample through the driver: DoStep before initialisation, a NaN
    input, an unknown value reference (get and set): each refused with Error (3 in both
    versions) and the same message on both platforms, and the instance still steps."""
    scene_dict = json.loads((ROOT / "scripts" / "scenes" / scene).read_text())
    unpacked = Unpacked(fmu_of(scene_dict, fmi=fmi), tmp_path, fmi)
    inputs = [v for v in unpacked.reals if v.causality == "input"]
    assert inputs, f"{scene} has no Real input"
    call = ["abuse", str(inputs[0].valueReference)]
    ours = run([str(drivers[fmi][0]), *unpacked.linux_args(), *call])
    theirs = run([WINE, str(drivers[fmi][1]), *unpacked.windows_args(), *call], env=wine_env)
    assert ours == theirs
    lines = [line for line in ours.splitlines() if " status " in line]
    assert len(lines) == 4
    for line in lines:
        assert " status 3: " in line, line  # fmi2Error, fmi3Error
    assert "not allowed in state Instantiated" in lines[0]
    assert f"{inputs[0].name}: must be finite" in lines[1]
    assert "unknown value reference 4000000000" in lines[2] and "unknown value reference 4000000000" in lines[3]
    assert ours.rstrip().endswith("done 0")


def test_the_dll_carries_fcl_exactly_when_the_linux64_binary_bundles_it(unpacked):
    """The pruning holds on both platforms: a scene without collisions carries no FCL.
    On Linux FCL is a bundled library; in the DLL it is linked in, and its code brings
    its type names (RTTI, N3fcl...) and messages."""
    linux_fcl = any(p.name.startswith("libfcl") for p in unpacked.so.parent.iterdir())
    text = unpacked.dll.read_bytes()
    assert (b"N3fcl" in text) == linux_fcl
    assert (b"ccd" in text.lower()) == linux_fcl  # libccd, FCL's GJK/EPA


@pytest.mark.parametrize("fmi", [2, 3])
def test_an_fmu_unpacked_in_a_folder_with_accents_and_spaces_runs_on_windows(fmi, fmu_of, drivers, wine_env,
                                                                          tmp_path):
    """The FMU unpacked under a user's folder as Windows names them (C:\\Users\\José
    Müller\\...): the win64 binary opens its scene there (its resource URI or path is
    UTF-8, read by wide-character name) and runs the same steps as the linux64 one."""
    scene = json.loads((ROOT / "scripts" / "scenes" / "default.json").read_text())
    unpacked = Unpacked(fmu_of(scene, fmi=fmi), tmp_path / "Users" / "José Müller" / "mis modelos", fmi)
    outputs = ",".join(str(v.valueReference) for v in unpacked.reals)
    call = ["run", "100", "0.005", outputs]
    ours = parse(run([str(drivers[fmi][0]), *unpacked.linux_args(), *call]))
    theirs = parse(run([WINE, str(drivers[fmi][1]), *unpacked.windows_args(), *call], env=wine_env))
    assert ours.keys() == theirs.keys() and ("step", 100) in ours
    for key, values in ours.items():
        for v, a, b in zip(unpacked.reals, values, theirs[key]):
            assert abs(a - b) <= RELATIVE * max(abs(a), abs(b)), f"{key} {v.name}: linux64 {a!r}, win64 {b!r}"
