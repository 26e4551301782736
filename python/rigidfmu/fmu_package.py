"""One scene into one FMU (a zip):

    modelDescription.xml
    binaries/linux64/<modelIdentifier>.so   the prebuilt library (of the FMI 2.0 or 3.0
                                            entry points) with just the modules
                                            the scene needs (src/modules.h), plus the
                                            shared libraries it needs beyond the C and
                                            C++ runtime, found through RUNPATH $ORIGIN
    binaries/win64/<modelIdentifier>.dll    the same sources cross-compiled with
                                            MinGW-w64, everything linked in statically:
                                            it needs only Windows' own DLLs
    resources/scene.json                    the user's scene file, byte for byte
    resources/<file>, <file>.mesh.json      each mesh file the scene names, at the path
                                            it gives, and the triangles and hull read
                                            from it (meshes.py, decision 0006)

An FMI 3.0 FMU (fmi=3) has the same layout with FMI 3's platform folders,
binaries/x86_64-linux and binaries/x86_64-windows.

The describe tool checks the staged scene first, reading the staged FILE.mesh.json files
as the FMU will; its message names the field and the limit.
"""
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import zipfile
from dataclasses import dataclass

from rigidfmu import meshes
from rigidfmu import native as native_module
from rigidfmu.errors import NativeError, PackagingError, SceneError

# Libraries every Linux machine has (the C and C++ runtime), never carried; nor the
# sanitizer runtimes, which a sanitizer build's host process preloads.
SYSTEM_LIBRARIES = re.compile(
    r"^(ld-linux.*|libc|libm|libstdc\+\+|libgcc_s|libpthread|libdl|librt|libasan|libubsan)\.so(\.|$)")


@dataclass(frozen=True)
class Description:
    model_description: bytes
    model_identifier: str
    modules: str
    warnings: tuple[str, ...] = ()  # notes that break no rule (a mesh's hull much larger than its solid)
    frames: tuple[str, ...] = ()  # where each mesh or compound body's file or compound frame lies


def describe(scene: pathlib.Path, native: native_module.Native, fmi: int = 2) -> Description:
    """The scene checked and described by the core (modelDescription.xml for FMI 2.0 or
    3.0); SceneError with the core's message. Its mesh files are staged first, as for
    the FMU, so that the core checks what the FMU will read (`rigidfmu check`)."""
    with tempfile.TemporaryDirectory(prefix="rigidfmu-resources-") as stage:
        resources = pathlib.Path(stage) / "resources"
        meshes.stage_resources(scene, resources)
        return describe_staged(scene, resources, native, fmi)


def describe_staged(scene: pathlib.Path, resources: pathlib.Path, native: native_module.Native,
                    fmi: int) -> Description:
    """describe() of the scene staged in `resources`; the core's message names the
    user's files, not the staged copies."""
    staged = resources / "scene.json"
    with tempfile.TemporaryDirectory(prefix="rigidfmu-describe-") as out:
        run = subprocess.run([str(native.describe), str(staged), out, "--fmi", str(fmi)], capture_output=True,
                             text=True)
        if run.returncode != 0:
            message = run.stderr.strip().replace(str(staged), str(scene))
            message = message.replace(str(resources) + "/", str(scene.parent) + "/")
            raise SceneError(message or f"{scene}: refused (exit status {run.returncode})")
        folder = pathlib.Path(out)
        notes = folder / "warnings"  # (a describe tool of before issue 42 writes none)
        warnings = tuple(notes.read_text().splitlines()) if notes.exists() else ()
        for warning in warnings:
            print(f"rigidfmu: warning: {warning}", file=sys.stderr)
        frames = folder / "frames"
        return Description((folder / "modelDescription.xml").read_bytes(),
                           (folder / "model_identifier").read_text().strip(),
                           (folder / "modules").read_text().strip(), warnings,
                           tuple(frames.read_text().splitlines()) if frames.exists() else ())


def runtime_dependencies(library: pathlib.Path) -> list[pathlib.Path]:
    """The shared libraries `library` loads, transitively, beyond the system's (ldd)."""
    run = subprocess.run(["ldd", str(library)], capture_output=True, text=True)
    if run.returncode != 0:
        raise PackagingError(f"ldd {library}: {run.stderr.strip()}")
    found = []
    for line in run.stdout.splitlines():
        parts = line.split()
        if "=>" not in parts:
            continue  # the vdso, or the loader by its absolute path
        name, target = parts[0], parts[parts.index("=>") + 1]
        if SYSTEM_LIBRARIES.match(name):
            continue
        if target == "not":
            raise PackagingError(f"{library} needs {name}, which is not installed")
        found.append(pathlib.Path(target))
    return found


def bundle(dependency: pathlib.Path, folder: pathlib.Path) -> None:
    """A dependency beside the binary, with RUNPATH $ORIGIN so that each finds the
    others there."""
    patchelf = shutil.which("patchelf")
    if not patchelf:
        raise PackagingError(f"patchelf is needed to bundle {dependency.name} (scripts/setup.sh installs it)")
    copy = folder / dependency.name
    shutil.copyfile(dependency, copy)
    subprocess.run([patchelf, "--set-rpath", "$ORIGIN", str(copy)], check=True)


def package(scene: pathlib.Path, out: pathlib.Path, native: native_module.Native, fmi: int = 2) -> list[str]:
    """Writes the FMI `fmi` (2 or 3) FMU of `scene` to `out`, with a win64 binary when
    `native` has them; returns the names of the bundled libraries."""
    if fmi not in (2, 3):
        raise PackagingError(f"FMI version {fmi}: 2 or 3")
    with tempfile.TemporaryDirectory(prefix="rigidfmu-fmu-") as stage:
        resources = pathlib.Path(stage) / "resources"
        staged = meshes.stage_resources(scene, resources)
        described = describe_staged(scene, resources, native, fmi)
        try:
            variant = native.variant(described.modules, fmi)
        except NativeError as e:
            raise PackagingError(str(e)) from e
        library = native.library(variant, fmi)
        dll = native.win64_library(variant, fmi)
        if dll is not None and not dll.exists():
            raise PackagingError(f"no win64 binary for modules {described.modules}: {dll}")
        linux, windows = ("linux64", "win64") if fmi == 2 else ("x86_64-linux", "x86_64-windows")
        binaries = pathlib.Path(stage) / "binaries" / linux
        binaries.mkdir(parents=True)
        shutil.copyfile(library, binaries / f"{described.model_identifier}.so")
        dependencies = runtime_dependencies(library)
        for dependency in dependencies:
            bundle(dependency, binaries)
        out.parent.mkdir(parents=True, exist_ok=True)
        partial = out.with_name(out.name + ".partial")
        with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as z:
            z.writestr("modelDescription.xml", described.model_description)
            for f in sorted(binaries.iterdir()):
                z.write(f, f"binaries/{linux}/{f.name}")
            if dll is not None:
                z.write(dll, f"binaries/{windows}/{described.model_identifier}.dll")
            for name in staged:  # sorted; a scene without meshes: resources/scene.json alone, as before
                z.write(resources / name, f"resources/{name}")
        partial.replace(out)  # a reader never sees half an FMU
    return [d.name for d in dependencies]
