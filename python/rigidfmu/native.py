"""Where the C++ core's binaries are: the scene checker `rigidfmu-describe` and one FMU
library per combination of physics modules (rigidfmu_fmi2_<mask>.so, src/modules.h).

An installed package carries them in rigidfmu/_native (CMake's install rules put them
there when pip builds the wheel). In the source tree they are in the CMake build tree,
build/ or $RIGIDFMU_BUILD, which is configured and brought up to date first, as
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

    @property
    def describe(self) -> pathlib.Path:
        return self.directory / "rigidfmu-describe"

    def library(self, modules: str) -> pathlib.Path:
        """The FMU library for a module mask (the describe tool's `modules`)."""
        return self.directory / f"rigidfmu_fmi2_{modules}.so"


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


def find(build: bool = True) -> Native:
    """The binaries to package from: $RIGIDFMU_BUILD when set (a build tree: the
    sanitizer build, say), else the installed ones, else the source tree's build/.
    A build tree is brought up to date first unless `build` is false or it holds
    binaries but no CMake cache (a prebuilt copy)."""
    chosen = os.environ.get("RIGIDFMU_BUILD")
    if not chosen and (INSTALLED / "rigidfmu-describe").exists():
        return Native(INSTALLED)
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
    native = Native(tree)
    if not native.describe.exists():
        raise NativeError(f"no rigidfmu-describe in {tree}")
    return native
