"""The FMUs of a system, built into one folder beside a copy of its system.ssd (whose
sources name them relative to itself), so that a master can load the SSD from there.

A component whose source is X.fmu is built from the system folder's
- X.json, a scene: `scripts/build_fmu.sh X.json X.fmu --no-win64` (rigidfmu build), or
- X/, a C FMU: its modelDescription.xml and its *.c (the model of a sampled controller),
  compiled with the C compiler together with sampled_fmu/ (the FMI functions that every
  controller shares) against the FMI 2.0 headers of the installed fmpy package (as
  CMakeLists.txt finds them, never a copy), the XML's GUID passed as MODEL_GUID; the
  FMU carries its sources."""
import os
import pathlib
import shutil
import subprocess
import tempfile
import xml.etree.ElementTree as ET
import zipfile

from systems import ssd

ROOT = pathlib.Path(__file__).resolve().parents[2]
SAMPLED_FMU = pathlib.Path(__file__).resolve().parent / "sampled_fmu"  # the controllers' FMI functions


class BuildError(RuntimeError):
    pass


def fmi_headers() -> pathlib.Path:
    import fmpy

    headers = pathlib.Path(fmpy.__file__).parent / "c-code"
    if not (headers / "fmi2Functions.h").is_file():
        raise BuildError(f"no fmi2Functions.h in {headers}: is fmpy installed (scripts/setup.sh)?")
    return headers


def build_scene(scene: pathlib.Path, out: pathlib.Path) -> None:
    """The scene's FMU (FMI 2.0, linux64 only: the masters run here)."""
    env = dict(os.environ, RIGIDFMU_SKIP_SETUP="1")
    run = subprocess.run([str(ROOT / "scripts" / "build_fmu.sh"), str(scene), str(out), "--no-win64"],
                         capture_output=True, text=True, env=env)
    if run.returncode != 0:
        raise BuildError(f"building {scene.name}: {run.stderr.strip()}")


def build_c(folder: pathlib.Path, out: pathlib.Path) -> None:
    """A C FMU from `folder`: modelDescription.xml and the *.c beside it, with the
    FMI functions of sampled_fmu/."""
    description = folder / "modelDescription.xml"
    own = sorted(folder.glob("*.c"))
    sources = own + sorted(SAMPLED_FMU.glob("*.c"))
    if not description.is_file() or not own:
        raise BuildError(f"{folder}: needs modelDescription.xml and at least one .c file")
    root = ET.parse(description).getroot()
    guid, cs = root.get("guid"), root.find("CoSimulation")
    if not guid or cs is None or not cs.get("modelIdentifier"):
        raise BuildError(f"{description}: needs a guid and <CoSimulation modelIdentifier=...>")
    identifier = cs.get("modelIdentifier")
    with tempfile.TemporaryDirectory(prefix="rigidfmu-system-") as stage:
        library = pathlib.Path(stage) / f"{identifier}.so"
        compile_ = ["cc", "-std=c99", "-O2", "-fPIC", "-shared", "-Wall", "-Wextra", "-Werror",
                    f"-I{fmi_headers()}", f"-I{SAMPLED_FMU}", f'-DMODEL_GUID="{guid}"', *map(str, sources),
                    "-o", str(library), "-lm"]
        run = subprocess.run(compile_, capture_output=True, text=True)
        if run.returncode != 0:
            raise BuildError(f"compiling {folder.name}: {run.stderr.strip()}")
        partial = out.with_name(out.name + ".partial")
        with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as z:
            z.write(description, "modelDescription.xml")
            z.write(library, f"binaries/linux64/{identifier}.so")
            for source in sources + sorted(SAMPLED_FMU.glob("*.h")):
                z.write(source, f"sources/{source.name}")
        partial.replace(out)


def check_names(system: ssd.System, folder: pathlib.Path) -> None:
    """Every connected variable and bound parameter exists in its FMU, as a Real of the
    right causality: libcosim would only warn about a misspelt parameter and run on."""
    from fmpy import read_model_description

    wanted = [(c.source, c.output, ("output",)) for c in system.connections]
    wanted += [(c.target, c.input, ("input",)) for c in system.connections]
    wanted += [(c, name, ("parameter", "input")) for c, values in system.parameters.items() for name in values]
    variables = {}
    for component, variable, causalities in wanted:
        if component not in variables:
            md = read_model_description(str(folder / system.components[component]))
            variables[component] = {v.name: v for v in md.modelVariables}
        v = variables[component].get(variable)
        if v is None or v.type != "Real" or v.causality not in causalities:
            found = "none" if v is None else f"a {v.causality} {v.type}"
            raise BuildError(f"{system.path}: {component}.{variable} must be a Real {' or '.join(causalities)} "
                             f"of {system.components[component]}, found {found}")


def build(folder, out, build_scene=build_scene, build_c=build_c) -> pathlib.Path:
    """Builds every FMU of the system in `folder` into `out` and copies its system.ssd
    there; returns the copy's path. The builders can be replaced (a test reuses FMUs)."""
    folder, out = pathlib.Path(folder).resolve(), pathlib.Path(out).resolve()
    system = ssd.read(folder)
    out.mkdir(parents=True, exist_ok=True)
    for component, source in sorted(system.components.items()):
        stem = pathlib.PurePosixPath(source).stem
        if not source.endswith(".fmu") or "/" in source:
            raise BuildError(f"{system.path}: component {component}: source {source} is not a file name X.fmu")
        if (folder / f"{stem}.json").is_file():
            build_scene(folder / f"{stem}.json", out / source)
        elif (folder / stem).is_dir():
            build_c(folder / stem, out / source)
        else:
            raise BuildError(f"{folder}: component {component} needs {stem}.json (a scene) or {stem}/ (a C FMU)")
    check_names(system, out)
    shutil.copyfile(system.path, out / "system.ssd")
    return out / "system.ssd"
