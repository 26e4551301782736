"""Building FMUs from the reports' scripts (reports.accuracy, reports.stability), as
build_fmu.sh does: the core once, then one packaging per scene content (cached by a
hash of the scene in `folder`)."""
import hashlib
import json
import pathlib

from rigidfmu import fmu_package
from rigidfmu.errors import ReportError
from rigidfmu.native import Native, build_core


def ensure_core(build, no_build, who):
    """Configures and builds the core in `build`; a directory with the binaries but no
    CMakeCache.txt is taken as prebuilt. `who` names the caller in its exit message."""
    build = pathlib.Path(build)
    prebuilt = (build / "rigidfmu-describe").exists() and not (build / "CMakeCache.txt").exists()
    if no_build or prebuilt:
        if not (build / "rigidfmu-describe").exists():
            raise ReportError(f"{who}: no rigidfmu-describe in {build} (build it, or drop --no-build)")
        return
    build_core(build.resolve())


def package(build, folder, scene_dict):
    """The FMU of a scene (a dict in the scene format), packaged once per content."""
    text = json.dumps(scene_dict, indent=1, sort_keys=True)
    key = hashlib.sha256(text.encode()).hexdigest()[:12]
    name = scene_dict.get("name", "scene")
    out = pathlib.Path(folder) / f"{name}-{key}.fmu"
    if not out.exists():
        path = pathlib.Path(folder) / f"{name}-{key}.json"
        path.write_text(text)
        fmu_package.package(path, out, Native(pathlib.Path(build).resolve()))
    return out
