"""The convex mesh benchmark's scenes (issue 42), written beside reports.scenes' so that
our core benchmark (bench/bench_core.cpp, BM_Narrow) and, later, MuJoCo read the very
same meshes: hulls of N points spread evenly on a sphere of HULL_RADIUS (a Fibonacci
lattice: every point is a vertex of the hull, so the hull has exactly N vertices).

Each hull is written as a binary STL (hull_<N>.stl, as a CAD tool exports it) and as the
FILE.mesh.json `rigidfmu build` makes of it (rigidfmu.mesh_conversion, decision 0006), so
that the core reads it as it reads a user's mesh. The narrowphase scenes narrow_<shape>.json
hold two bodies of one shape (a hull of N vertices, or the cube the hulls are set beside)
and a floor; the benchmark poses them itself (bench_core.cpp, narrowPoses).

  hull_<N>.stl, hull_<N>.stl.mesh.json    N in HULL_VERTICES
  narrow_hull_<N>.json, narrow_cube.json  two bodies and a floor
"""
import json
import math
import pathlib

import numpy as np
import trimesh

from rigidfmu.mesh_conversion import convert
from rigidfmu.scenes import body, floor, scene

HULL_VERTICES = (100, 300, 1000)  # the range: 100-1000 hull vertices
HULL_RADIUS = 0.1                 # m
CUBE_EDGE = 2 * HULL_RADIUS       # m: the cube the hulls are set beside, as wide as they are
DENSITY = 1000.0                  # kg/m^3: the hull bodies' mass from their solid


def sphere_points(n, radius=HULL_RADIUS):
    """n points spread evenly on a sphere (a Fibonacci lattice), none at a pole: each is
    a vertex of their hull."""
    k = np.arange(n) + 0.5
    z = 1.0 - 2.0 * k / n
    r = np.sqrt(1.0 - z * z)
    phi = math.pi * (3.0 - math.sqrt(5.0)) * k
    return radius * np.column_stack((r * np.cos(phi), r * np.sin(phi), z))


def hull_mesh(n, radius=HULL_RADIUS):
    """The convex hull of sphere_points(n) as a closed triangle mesh, wound outwards."""
    return trimesh.convex.convex_hull(sphere_points(n, radius))


def write_hull(directory, n, radius=HULL_RADIUS, name=None):
    """DIR/<name>.stl and its FILE.mesh.json; the file name the scenes give."""
    file = f"{name or f'hull_{n}'}.stl"
    path = pathlib.Path(directory) / file
    hull_mesh(n, radius).export(str(path), file_type="stl")
    (path.parent / (file + ".mesh.json")).write_bytes(convert(path, file, "bench"))
    return file


def narrow_scene(name, shape, mass):
    """Two bodies of one shape and a floor (top face z = 0); poses are the benchmark's."""
    bodies = [body(f"{name}{k}", shape, mass, position=[0.0, 0.0, 1.0 + k], restitution=0.0,
                   staticFriction=0.6, kineticFriction=0.6, outputs=["position"], inputs=[]) for k in range(2)]
    return scene(f"Narrow_{name}", bodies, surfaces=[floor(0.6, 0.6, 0.0)])


def write(directory):
    d = pathlib.Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    for n in HULL_VERTICES:
        file = write_hull(d, n)
        mass = DENSITY * hull_mesh(n).volume
        (d / f"narrow_hull_{n}.json").write_text(json.dumps(narrow_scene(f"hull{n}", {"type": "mesh", "file": file},
                                                                         mass)))
    cube = {"type": "box", "size": [CUBE_EDGE] * 3}
    (d / "narrow_cube.json").write_text(json.dumps(narrow_scene("cube", cube, DENSITY * CUBE_EDGE ** 3)))
