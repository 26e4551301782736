"""One mesh file into the `FILE.mesh.json` the core reads (decision 0006):

    {"format": "rigidfmu-mesh", "version": 1, "source": "part.stl",
     "vertices": [[x, y, z], ...], "triangles": [[i, j, k], ...],
     "hull": {"vertices": [[x, y, z], ...], "faces": [[i, j, k, l], ...]}}

The file is read with trimesh (STL binary or ASCII, OBJ, whatever trimesh 5.2.0 reads);
a file that holds several meshes (an OBJ with several objects) is concatenated into
one. Exactly equal vertices are merged (an STL repeats each vertex in every triangle),
and nothing else is changed: an open, inconsistently wound or degenerate mesh reaches the
core as the user made it, and the core refuses it naming the fault; a repair here would
hide the fault and change the solid. The scene's `scale` is the core's to apply.

The hull is qhull's (scipy) of the merged vertices, its coplanar triangles merged into
convex polygons, counter-clockwise seen from outside; absent when the vertices span no
volume (a flat sheet, as a floor). The output's bytes depend only on the file's
geometry: vertices in sorted order, so that the same solid from STL and from OBJ gives
the same file; floats as Python's repr, which reads back to the same double.
"""
import json
import pathlib

import numpy as np
import trimesh
from scipy.spatial import ConvexHull, QhullError

from rigidfmu.errors import SceneError

# Two hull triangles lie in one face when their unit normals differ by at most this, and
# their offsets by at most this times the mesh's size (its bounding box's diagonal).
PLANE_TOLERANCE = 1e-9


def load_mesh(path: pathlib.Path, source: str, field: str) -> trimesh.Trimesh:
    """The file as trimesh reads it, unprocessed; SceneError with trimesh's reason."""
    try:
        loaded = trimesh.load(str(path), process=False, force="mesh")
    except ModuleNotFoundError as e:  # trimesh guesses a text file's encoding with an optional package
        reason = f"not a binary mesh and not UTF-8 text (guessing its encoding needs {e.name})"
    except Exception as e:  # any failure of the reader is the file's
        reason = f"{type(e).__name__}: {e}"
    else:
        if isinstance(loaded, trimesh.Trimesh) and len(loaded.faces):
            return loaded
        reason = "it holds no triangles"
    raise SceneError(f'{field}: trimesh cannot read "{source}": {reason}')


def merged(vertices: np.ndarray, triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Exactly equal vertices as one (-0.0 and 0.0 are equal), sorted; the triangles
    reindexed to them, as they were wound."""
    points = np.asarray(vertices, dtype=np.float64) + 0.0  # -0.0 + 0.0 is 0.0
    unique, inverse = np.unique(points, axis=0, return_inverse=True)
    return unique, inverse.reshape(-1)[np.asarray(triangles, dtype=np.int64)]


def coplanar_neighbours(hull: ConvexHull, size: float) -> np.ndarray:
    """The pairs (i, j) of neighbouring hull triangles that lie in one plane."""
    i = np.repeat(np.arange(len(hull.simplices)), hull.neighbors.shape[1])
    j = hull.neighbors.reshape(-1)
    normals, offsets = hull.equations[:, :3], hull.equations[:, 3]
    same = ((np.abs(normals[i] - normals[j]).max(axis=1) <= PLANE_TOLERANCE)
            & (np.abs(offsets[i] - offsets[j]) <= PLANE_TOLERANCE * size))
    return np.column_stack((i[same], j[same]))


def coplanar_groups(hull: ConvexHull, size: float) -> list[list[int]]:
    """The hull's triangles grouped by plane. The triangles of one face of a convex
    polyhedron are joined through their edges, so neighbours in one plane are joined
    (union-find over qhull's neighbour lists), in qhull's order."""
    parent = list(range(len(hull.simplices)))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for i, j in coplanar_neighbours(hull, size).tolist():
        a, b = root(i), root(j)
        parent[max(a, b)] = min(a, b)
    groups = {}
    for i in range(len(parent)):
        groups.setdefault(root(i), []).append(i)
    return list(groups.values())


def outward_triangle(points: np.ndarray, normal: np.ndarray, corners) -> list[int] | None:
    """A hull triangle alone in its plane, counter-clockwise seen from outside (qhull's
    simplices are not wound alike); None when it has no area."""
    a, b, c = (int(k) for k in corners)
    turn = np.cross(points[b] - points[a], points[c] - points[a]) @ normal
    if turn == 0.0:
        return None
    return [a, b, c] if turn > 0.0 else [a, c, b]


def face_polygon(points: np.ndarray, normal: np.ndarray, corners: np.ndarray) -> list[int] | None:
    """The convex polygon of the points `corners` (indexes into `points`) in a plane of
    outward unit `normal`, counter-clockwise seen from outside; None when they span no
    area. Their 2-D hull in a basis (u, v) with u x v = normal is counter-clockwise
    (qhull's order in 2-D), and leaves out any vertex inside the face or inside one of
    its edges."""
    axis = np.zeros(3)
    axis[np.argmin(np.abs(normal))] = 1.0
    u = np.cross(normal, axis)
    u /= np.linalg.norm(u)
    v = np.cross(normal, u)
    flat = np.column_stack((points[corners] @ u, points[corners] @ v))
    try:
        order = ConvexHull(flat).vertices
    except QhullError:
        return None
    return [int(corners[k]) for k in order]


def convex_hull(vertices: np.ndarray) -> dict | None:
    """The hull as convex polygons indexing its own vertices (in the order of the
    mesh's), or None when the vertices span no volume."""
    try:
        hull = ConvexHull(vertices)
    except QhullError:
        return None
    size = float(np.linalg.norm(vertices.max(axis=0) - vertices.min(axis=0)))
    polygons = []
    for group in coplanar_groups(hull, size):
        normal = hull.equations[group[0], :3]
        if len(group) == 1:
            polygon = outward_triangle(vertices, normal, hull.simplices[group[0]])
        else:
            polygon = face_polygon(vertices, normal, np.unique(hull.simplices[group]))
        if polygon is not None:
            first = polygon.index(min(polygon))
            polygons.append(polygon[first:] + polygon[:first])
    used = sorted({i for polygon in polygons for i in polygon})
    index = {old: new for new, old in enumerate(used)}
    faces = sorted([index[i] for i in polygon] for polygon in polygons)
    return {"vertices": vertices[used].tolist(), "faces": faces}


def convert(path: pathlib.Path, source: str, field: str) -> bytes:
    """The FILE.mesh.json of the mesh file `path`, which the scene names `source` at
    `field`; SceneError naming both when trimesh cannot read it or a vertex is not a
    finite number (JSON has no NaN)."""
    mesh = load_mesh(path, source, field)
    vertices, triangles = merged(mesh.vertices, mesh.faces)
    if not np.isfinite(vertices).all():
        bad = vertices[~np.isfinite(vertices).all(axis=1)][0].tolist()
        raise SceneError(f'{field}: "{source}" has a vertex that is not finite: {bad}')
    document = {"format": "rigidfmu-mesh", "version": 1, "source": source,
                "vertices": vertices.tolist(), "triangles": triangles.tolist()}
    hull = convex_hull(vertices)
    if hull is not None:
        document["hull"] = hull
    return (json.dumps(document, allow_nan=False, separators=(",", ":")) + "\n").encode()
