"""The mesh files a scene names (issue 42, decision 0006): found, checked against the
path rule, and staged with the scene as the FMU's resources.

`rigidfmu build` reads each mesh file once, here, with trimesh (mesh_conversion.py) and
puts `FILE.mesh.json` beside the file, so that the FMU needs no mesh library at run time.
The core checks the same path rule again, so that an FMU never opens a file outside its
resources; it also owns every other rule of the scene format: a malformed scene (no
`file`, a number for a file) is passed through here untouched and refused by the core,
with one message for one fault.

This module imports nothing beyond the standard library: a scene without meshes is
packaged without loading numpy, scipy or trimesh.
"""
import json
import os
import pathlib
import re
import shutil
from dataclasses import dataclass

from rigidfmu.errors import SceneError

WINDOWS_DRIVE = re.compile(r"^[A-Za-z]:")
MESH_JSON_SUFFIX = ".mesh.json"


@dataclass(frozen=True)
class MeshReference:
    field: str  # where the scene names it, in the core's style: bodies[1].shape.file
    file: str  # as the scene gives it: a path relative to the scene's folder


def shape_references(shape, path: str) -> list[MeshReference]:
    """The mesh files of one body shape at field `path`, a compound's parts' included
    (a part's shape is searched as a shape, so nesting needs no second rule)."""
    if not isinstance(shape, dict):
        return []
    if shape.get("type") == "mesh" and isinstance(shape.get("file"), str):
        return [MeshReference(f"{path}.file", shape["file"])]
    found = []
    if shape.get("type") == "compound" and isinstance(shape.get("parts"), list):
        for k, part in enumerate(shape["parts"]):
            if isinstance(part, dict):
                found += shape_references(part.get("shape"), f"{path}.parts[{k}].shape")
    return found


def mesh_references(scene) -> list[MeshReference]:
    """Every mesh file the parsed scene names, in the scene's order: bodies' shapes
    (compound parts too), then surfaces' meshes."""
    if not isinstance(scene, dict):
        return []
    found = []
    bodies = scene.get("bodies")
    for i, body in enumerate(bodies if isinstance(bodies, list) else []):
        if isinstance(body, dict):
            found += shape_references(body.get("shape"), f"bodies[{i}].shape")
    surfaces = scene.get("surfaces")
    for i, surface in enumerate(surfaces if isinstance(surfaces, list) else []):
        mesh = surface.get("mesh") if isinstance(surface, dict) else None
        if isinstance(mesh, dict) and isinstance(mesh.get("file"), str):
            found.append(MeshReference(f"surfaces[{i}].mesh.file", mesh["file"]))
    return found


def follows_path_rule(file: str) -> bool:
    """Relative, '/' separators, no '..': the same file on Linux and Windows, and never
    outside the folder the FMU unpacks its resources into."""
    return (file != "" and "\\" not in file and not file.startswith("/") and not WINDOWS_DRIVE.match(file)
            and ".." not in file.split("/"))


def checked_path(reference: MeshReference, folder: pathlib.Path) -> pathlib.Path:
    """The file `reference` names in the scene's `folder`; SceneError naming the field
    when the path breaks the rule or names no file."""
    if not follows_path_rule(reference.file):
        raise SceneError(f"{reference.field}: must be a path inside the scene's folder "
                         f'(relative, no "..", "/" separators), got "{reference.file}"')
    path = folder / reference.file
    if not path.is_file():
        raise SceneError(f'{reference.field}: no file "{reference.file}" beside the scene')
    return path


def stage_mesh(reference: MeshReference, source: pathlib.Path, resources_dir: pathlib.Path) -> list[str]:
    """The user's file and its FILE.mesh.json at the same relative path in
    `resources_dir`. Both keep the file's time stamp (and the copy its mode), so that
    the same inputs zip to the same bytes."""
    from rigidfmu import mesh_conversion  # numpy, scipy and trimesh: only for a scene with meshes

    target = resources_dir / reference.file
    target.parent.mkdir(parents=True, exist_ok=True)
    converted = target.with_name(target.name + MESH_JSON_SUFFIX)
    converted.write_bytes(mesh_conversion.convert(source, reference.file, reference.field))
    shutil.copy2(source, target)
    stamp = source.stat()
    os.utime(converted, ns=(stamp.st_atime_ns, stamp.st_mtime_ns))
    return [p.relative_to(resources_dir).as_posix() for p in (target, converted)]


def stage_resources(scene_path: pathlib.Path, resources_dir: pathlib.Path) -> list[str]:
    """Writes the FMU's resources into `resources_dir`: the user's scene file, byte for
    byte, as scene.json, and each mesh file it names with its FILE.mesh.json, at the
    path the scene gives (a file named twice is converted once). Returns the names
    written, relative to `resources_dir`, sorted. Every path is checked before any file
    is converted. A scene that is not JSON is staged alone: the core names its fault."""
    scene_path, resources_dir = pathlib.Path(scene_path), pathlib.Path(resources_dir)
    resources_dir.mkdir(parents=True, exist_ok=True)
    shutil.copy2(scene_path, resources_dir / "scene.json")  # its time stamp too: the zip's bytes as before meshes
    written = {"scene.json"}
    try:
        scene = json.loads(scene_path.read_bytes())
    except (ValueError, RecursionError):
        return sorted(written)
    first = {}
    for reference in mesh_references(scene):
        first.setdefault(reference.file, reference)
    checked = [(reference, checked_path(reference, scene_path.parent)) for reference in first.values()]
    for reference, source in checked:
        written.update(stage_mesh(reference, source, resources_dir))
    return sorted(written)
