"""The bodies' shapes as the replay page draws them: the scene's shape, with each mesh's
triangles put in and every part placed in the body frame the core simulates.

A mesh shape gains
    "vertices": [x, y, z, ...] m, in the body frame (rounded to 1 µm, as the positions),
    "triangles": [i, j, k, ...] indexes into the vertices, counter-clockwise seen from outside.
The body frame of a mesh is the file's frame, scaled, moved to the solid's centre of
mass (src/mesh_file.cpp): file point x lies at scale * x - c, c the volume centroid of
the scaled solid. The file is read as `rigidfmu build` reads it (mesh_conversion: trimesh,
exactly equal vertices merged), so that the page draws the triangles the core was given.

A compound's parts (a primitive placed by its centre, a mesh by its file's origin, at
"position" and turned by "orientation" in the compound's frame) keep their shapes, drawn
about their own centres of mass; their positions become those centres in the body
frame, the compound's frame moved to the centre of mass of the parts at one density
(their volumes' weighted mean), as the core places them (src/compound.cpp).
"""
import math
import pathlib

import numpy as np

from rigidfmu.errors import ReplayError
from rigidfmu.references.quaternion import rotation_matrix

PRIMITIVE_VOLUMES = {
    "sphere": lambda s: 4.0 / 3.0 * math.pi * s["radius"] ** 3,
    "box": lambda s: float(np.prod(s["size"])),
    "cylinder": lambda s: math.pi * s["radius"] ** 2 * s["length"],
    # a cylinder of `length` capped by two half spheres
    "capsule": lambda s: math.pi * s["radius"] ** 2 * s["length"] + 4.0 / 3.0 * math.pi * s["radius"] ** 3,
}


def solid_centroid(vertices: np.ndarray, triangles: np.ndarray) -> tuple[np.ndarray, float]:
    """(centre of mass, volume) of the solid the closed triangles bound, by the divergence
    theorem: the signed tetrahedra from a reference point to each triangle, their volumes
    det(a, b, c) / 6 and centroids (a + b + c) / 4 summed. Numpy rather than trimesh's
    mass properties: the same integrals as the core's (src/solid_mass.cpp), about the same
    reference point, the vertices' mean, so that a part far from the file's origin loses
    no digits and the page's centre is the simulated one; trimesh would build and cache a
    mesh object of its own for a few lines of sums."""
    origin = vertices.mean(axis=0)
    a, b, c = (vertices[triangles[:, k]] - origin for k in range(3))
    six_volumes = np.einsum("ij,ij->i", a, np.cross(b, c))
    total = six_volumes.sum()
    if not total > 0.0:  # the core refuses such a mesh; a page of it would mislead
        return origin, 0.0
    return origin + (six_volumes[:, None] * (a + b + c)).sum(axis=0) / (4.0 * total), total / 6.0


def scale_of(shape: dict, field: str) -> np.ndarray:
    """The mesh's scale per file axis: one factor, three, or 1 when absent."""
    scale = np.asarray(shape.get("scale", 1.0), dtype=float)
    if scale.shape not in ((), (3,)) or not (scale > 0.0).all():
        raise ReplayError(f"{field}.scale: must be > 0 (one factor or one per axis), got {shape.get('scale')}")
    return np.broadcast_to(scale, (3,))


def mesh_shape(shape: dict, folder: pathlib.Path | None, field: str) -> tuple[dict, float, np.ndarray]:
    """The mesh shape with its vertices in the body frame and its triangles, its volume
    (m^3), and its centre of mass in the scaled file's frame. The path is checked by the
    rule `rigidfmu build` checks."""
    from rigidfmu import mesh_conversion, meshes  # numpy, scipy and trimesh: only for a scene with meshes

    if folder is None:
        raise ReplayError(f"{field}: a mesh needs the scene's folder: give the scene as its file")
    reference = meshes.MeshReference(f"{field}.file", shape.get("file"))
    path = meshes.checked_path(reference, pathlib.Path(folder))
    mesh = mesh_conversion.load_mesh(path, reference.file, reference.field)
    vertices, triangles = mesh_conversion.merged(mesh.vertices, mesh.faces)
    vertices = vertices * scale_of(shape, field)
    centre, volume = solid_centroid(vertices, triangles)
    if not volume > 0.0:
        raise ReplayError(f'{reference.field}: "{reference.file}" bounds no solid wound outward '
                          "(the FMU refuses it too)")
    drawn = {**shape, "vertices": np.round(vertices - centre, 6).ravel().tolist(),
             "triangles": triangles.ravel().tolist()}
    return drawn, volume, centre


def compound_shape(shape: dict, folder: pathlib.Path | None, field: str) -> tuple[dict, float]:
    """The compound with its parts' shapes drawn and their positions in the body frame,
    and its volume (m^3)."""
    placed = []
    for k, part in enumerate(shape.get("parts", [])):
        drawn, volume, centre = replay_shape(part["shape"], folder, f"{field}.parts[{k}].shape")
        if volume is None:
            raise ReplayError(f"{field}.parts[{k}].shape: no volume for a {part['shape'].get('type')} shape")
        turn = rotation_matrix(part.get("orientation", [1.0, 0.0, 0.0, 0.0]))
        at = np.asarray(part.get("position", [0.0, 0.0, 0.0]), dtype=float) + turn @ centre
        placed.append((part, drawn, volume, at))
    total = sum(volume for _, _, volume, _ in placed)
    if not placed or not total > 0.0:
        raise ReplayError(f"{field}.parts: a compound needs parts of some volume")
    centre = sum(volume * position for _, _, volume, position in placed) / total
    parts = [{**part, "shape": drawn, "position": (position - centre).tolist()}
             for part, drawn, _, position in placed]
    return {**shape, "parts": parts}, total, np.zeros(3)


def replay_shape(shape: dict, folder: pathlib.Path | None, field: str) -> tuple[dict, float | None, np.ndarray]:
    """The shape as the page draws it (about its centre of mass), its volume (m^3; None
    for a type the replay does not know, which the page names), and its centre of mass
    from the point the scene places it by (a mesh's file origin; else none).
    `folder`: the scene's, where its mesh files are."""
    kind = shape.get("type")
    if kind == "mesh":
        return mesh_shape(shape, folder, field)
    if kind == "compound":
        return compound_shape(shape, folder, field)
    return shape, primitive_volume(shape), np.zeros(3)


def primitive_volume(shape: dict) -> float | None:
    """m^3; None for a type the replay does not know or a malformed shape (the core
    refuses that, and a body alone needs no volume: only a compound's part does)."""
    try:
        return PRIMITIVE_VOLUMES[shape["type"]](shape)
    except (KeyError, TypeError, ValueError):
        return None
