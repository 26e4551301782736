"""Where the C++ core's binaries are: the scene checker `rigidfmu-describe` and one FMU
library per combination of physics modules (rigidfmu_fmi2_<mask>.so, src/modules.h),
with its win64 twin (rigidfmu_fmi2_<mask>.dll, cross-compiled with MinGW-w64).

An installed package carries them in rigidfmu/_native and rigidfmu/_native/win64
(CMake's install rules put them there when pip builds the wheel). In the source tree
they are in the CMake build trees, build/ (or $RIGIDFMU_BUILD) and build-win64/ (or
$RIGIDFMU_BUILD_WIN64, scripts/build_win64.sh), which are brought up to date first, as
scripts/build_fmu.sh always did.
"""
import os
import pathlib
import subprocess
from dataclasses import dataclass

from rigidfmu.errors import NativeError

PACKAGE = pathlib.Path(__file__).resolve().parent
INSTALLED = PACKAGE / "_native"
# python/rigidfmu/native.py -> the source tree's root (when there is one)
SOURCE_ROOT = PACKAGE.parents[1]
CMAKE = "/usr/bin/cmake"  # Debian's, as the scripts use: not the venv's PyPI cmake


@dataclass(frozen=True)
class Native:
    directory: pathlib.Path
    win64: pathlib.Path | None = None  # the DLLs' folder, None: this installation has none

    @property
    def describe(self) -> pathlib.Path:
        return self.directory / "rigidfmu-describe"

    def built_variants(self, fmi: int = 2) -> list[int]:
        """The module masks this installation has a library of (FMI version `fmi`)."""
        prefix = f"rigidfmu_fmi{fmi}_"
        names = (p.name.removeprefix(prefix).removesuffix(".so") for p in self.directory.glob(prefix + "*.so"))
        return sorted(int(n) for n in names if n.isdigit())

    def variant(self, modules: str, fmi: int = 2) -> str:
        """The mask of the smallest built library that has the modules `modules` (the
        describe tool's mask): the scene's own combination where it is built (a full
        build has every one), else the superset with the fewest modules (a build of the
        top combination only, as the sanitizer's). NativeError when none has them."""
        needed = int(modules)
        covering = [mask for mask in self.built_variants(fmi) if mask & needed == needed]
        if not covering:
            raise NativeError(f"no FMU library in {self.directory} has the modules {modules} (FMI {fmi})")
        return str(min(covering, key=lambda mask: (bin(mask).count("1"), mask)))

    def library(self, modules: str, fmi: int = 2) -> pathlib.Path:
        """The FMU library for a module mask (the describe tool's `modules`, or a
        variant's) and FMI version (2 or 3)."""
        return self.directory / f"rigidfmu_fmi{fmi}_{modules}.so"

    def win64_library(self, modules: str, fmi: int = 2) -> pathlib.Path | None:
        return self.win64 / f"rigidfmu_fmi{fmi}_{modules}.dll" if self.win64 else None


def in_source_tree() -> bool:
    return (SOURCE_ROOT / "CMakeLists.txt").is_file() and (SOURCE_ROOT / "src").is_dir()


def build_core(build: pathlib.Path) -> None:
    """Configures `build` once (Release) and builds the describe tool and every FMU
    library; when they are up to date this only checks."""
    if not (build / "CMakeCache.txt").exists():
        subprocess.run([CMAKE, "-S", str(SOURCE_ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release"],
                       check=True, stdout=subprocess.DEVNULL)
    subprocess.run([CMAKE, "--build", str(build), f"-j{os.cpu_count() or 1}", "--target",
                    "rigidfmu-describe", "rigidfmu_fmus"], check=True, stdout=subprocess.DEVNULL)


def build_win64(build: pathlib.Path) -> None:
    """Cross-compiles the DLLs into `build` (scripts/build_win64.sh: MinGW-w64, FCL and
    libccd from Debian's sources, cached per machine)."""
    env = dict(os.environ, RIGIDFMU_BUILD_WIN64=str(build))
    subprocess.run([str(SOURCE_ROOT / "scripts" / "build_win64.sh")], check=True, env=env,
                   stdout=subprocess.DEVNULL)


def find_win64(build: bool = True) -> pathlib.Path | None:
    """The source tree's win64 build tree, brought up to date unless `build` is false;
    None when it is not to be built and has no DLLs."""
    tree = pathlib.Path(os.environ.get("RIGIDFMU_BUILD_WIN64") or SOURCE_ROOT / "build-win64").resolve()
    built = any(tree.glob("rigidfmu_fmi2_*.dll"))
    if not build and not built:
        return None
    prebuilt = built and not (tree / "CMakeCache.txt").exists()
    if build and not prebuilt:
        if not in_source_tree():
            raise NativeError(f"RIGIDFMU_BUILD_WIN64={tree} needs the source tree to build in")
        try:
            build_win64(tree)
        except subprocess.CalledProcessError as e:
            raise NativeError(f"cross-compiling the win64 binaries in {tree} failed ({e}); "
                              "--no-win64 leaves them out") from e
    return tree


def find(build: bool = True, win64: bool = True) -> Native:
    """The binaries to package from: $RIGIDFMU_BUILD when set (a build tree: the
    sanitizer build, say), else the installed ones, else the source tree's build/.
    A build tree is brought up to date first unless `build` is false or it holds
    binaries but no CMake cache (a prebuilt copy). With `win64`, the win64 DLLs as
    well: an installation's own (none when it was built without them), or the source
    tree's cross build."""
    chosen = os.environ.get("RIGIDFMU_BUILD")
    if not chosen and (INSTALLED / "rigidfmu-describe").exists():
        dlls = INSTALLED / "win64"
        return Native(INSTALLED, dlls if win64 and any(dlls.glob("*.dll")) else None)
    if not chosen:
        if not in_source_tree():
            raise NativeError(f"no core binaries: {INSTALLED} is missing (reinstall the package)")
        chosen = str(SOURCE_ROOT / "build")
    tree = pathlib.Path(chosen).resolve()
    prebuilt = (tree / "rigidfmu-describe").exists() and not (tree / "CMakeCache.txt").exists()
    if build and not prebuilt:
        if not in_source_tree():
            raise NativeError(f"RIGIDFMU_BUILD={tree} needs the source tree to build in")
        try:
            build_core(tree)
        except subprocess.CalledProcessError as e:
            raise NativeError(f"building the core in {tree} failed ({e})") from e
    native = Native(tree, find_win64(build) if win64 else None)
    if not native.describe.exists():
        raise NativeError(f"no rigidfmu-describe in {tree}")
    return native
