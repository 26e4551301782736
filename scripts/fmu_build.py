"""Building FMUs from the reports' scripts (report_accuracy.py, stress.py), as
build_fmu.sh does: the core once, then one packaging per scene content (cached by a
hash of the scene in `folder`)."""
import hashlib
import json
import os
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
CMAKE = "/usr/bin/cmake"


def ensure_core(build, no_build, who):
    """Configures and builds the core in `build`; a directory with the binaries but no
    CMakeCache.txt is taken as prebuilt. `who` names the caller in its exit message."""
    build = pathlib.Path(build)
    prebuilt = (build / "rigidfmu-describe").exists() and not (build / "CMakeCache.txt").exists()
    if no_build or prebuilt:
        if not (build / "rigidfmu-describe").exists():
            sys.exit(f"{who}: no rigidfmu-describe in {build} (build it, or drop --no-build)")
        return
    if not (build / "CMakeCache.txt").exists():
        subprocess.run([CMAKE, "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release"],
                       check=True, stdout=subprocess.DEVNULL)
    subprocess.run([CMAKE, "--build", str(build), f"-j{os.cpu_count() or 1}", "--target",
                    "rigidfmu-describe", "rigidfmu_fmus"], check=True, stdout=subprocess.DEVNULL)


def package(build, folder, scene_dict):
    """The FMU of a scene (a dict in the scene format), packaged once per content."""
    text = json.dumps(scene_dict, indent=1, sort_keys=True)
    key = hashlib.sha256(text.encode()).hexdigest()[:12]
    name = scene_dict.get("name", "scene")
    out = pathlib.Path(folder) / f"{name}-{key}.fmu"
    if not out.exists():
        path = pathlib.Path(folder) / f"{name}-{key}.json"
        path.write_text(text)
        subprocess.run([CMAKE, f"-DSCENE={path}", f"-DOUT={out}",
                        f"-DDESCRIBE={pathlib.Path(build) / 'rigidfmu-describe'}",
                        f"-DLIBRARY_DIR={build}", "-P", str(ROOT / "cmake" / "package_fmu.cmake")],
                       check=True, stdout=subprocess.DEVNULL)
    return out
