"""The convex mesh benchmark's scenes (issue 42), written beside reports.scenes' so that
our core benchmark (bench/bench_core.cpp, BM_Narrow) and, later, MuJoCo read the very
same meshes: hulls of N points spread evenly on a sphere of HULL_RADIUS (a Fibonacci
lattice: every point is a vertex of the hull, so the hull has exactly N vertices).

Each hull is written as a binary STL (hull_<N>.stl, as a CAD tool exports it) and as the
FILE.mesh.json `rigidfmu build` makes of it (rigidfmu.mesh_conversion, decision 0006), so
that the core reads it as it reads a user's mesh. The narrowphase scenes narrow_<shape>.json
hold two bodies of one shape (a hull of N vertices, or the cube the hulls are set beside)
and a floor; the benchmark poses them itself (bench_core.cpp, narrowPoses). The pile
pile_hulls_<N>.json is reports.scenes' pile of N cubes with each cube replaced by a hull
of PILE_HULL_VERTICES points on an ellipsoid of semi-axes PILE_HULL_AXES (a pebble, which
fits in the cube's place and settles where a sphere would roll), turned by more than the
cubes are; MuJoCo runs it from the same STL (reports.performance_peers --mesh-pile).

  hull_<N>.stl, hull_<N>.stl.mesh.json    N in HULL_VERTICES
  narrow_hull_<N>.json, narrow_cube.json  two bodies and a floor
  pebble.stl, pebble.stl.mesh.json, pile_hulls_<N>.json   N in PILE_COUNTS
  bin.stl, bin.stl.mesh.json   the pile's bin
"""
import json
import math
import pathlib

import numpy as np
import trimesh

from reports import scenes
from rigidfmu.mesh_conversion import convert
from rigidfmu.scenes import body, floor, scene

HULL_VERTICES = (100, 300, 1000)  # the range: 100-1000 hull vertices
HULL_RADIUS = 0.1                 # m
CUBE_EDGE = 2 * HULL_RADIUS       # m: the cube the hulls are set beside, as wide as they are
DENSITY = 1000.0                  # kg/m^3: the hull bodies' mass from their solid
PILE_COUNTS = (100,)
PILE_HULL_VERTICES = 100
PILE_HULL_AXES = (0.05, 0.04, 0.03)  # m: at most as wide as the pile's cubes (0.1 m)
PILE_TURN = 1.2                   # rad: the pebbles' turns about x and y, times the cubes' tilt pattern
BIN_SIZE = (1.0, 1.0, 0.5)        # m: the bin's inside, x by y, and its walls' height
BIN_CELLS = 3                     # each face a grid of 3 x 3 squares, two triangles each
BIN_THICKNESS = 0.1               # m: the prisms behind the bin's triangles (its walls' and floor's thickness)


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


def pebble_mesh():
    """The pile's pebble: the hull of PILE_HULL_VERTICES points on an ellipsoid."""
    return trimesh.convex.convex_hull(sphere_points(PILE_HULL_VERTICES, 1.0) * np.array(PILE_HULL_AXES))


def grid_triangles(origin, u, v, cells=BIN_CELLS):
    """A rectangle from `origin` along the edges u and v as cells x cells squares, two
    triangles each, wound counter-clockwise about u x v (its front)."""
    origin, u, v = (np.asarray(x, dtype=float) for x in (origin, u, v))
    t = np.linspace(0.0, 1.0, cells + 1)
    out = []
    for i in range(cells):
        for j in range(cells):
            a, b = origin + t[i] * u + t[j] * v, origin + t[i + 1] * u + t[j] * v
            c, d = origin + t[i + 1] * u + t[j + 1] * v, origin + t[i] * u + t[j + 1] * v
            out += [(a, b, c), (a, c, d)]
    return out


def bin_mesh():
    """The pile's bin: an open box of BIN_SIZE, its floor's top at z = 0 centred on the
    z axis, the floor and four walls each a grid_triangles facing inwards (seams between
    the triangles, edges shared with the next face). One-sided: a surface's triangles
    collide on their counter-clockwise side."""
    (x, y, z), ex, ey, ez = BIN_SIZE, np.array([1.0, 0, 0]), np.array([0, 1.0, 0]), np.array([0, 0, 1.0])
    x0, y0 = -x / 2, -y / 2
    faces = [((x0, y0, 0), x * ex, y * ey),            # the floor, facing up
             ((x0, y0, 0), y * ey, z * ez),            # x = x0, facing +x
             ((-x0, y0, 0), z * ez, y * ey),           # x = -x0, facing -x
             ((x0, y0, 0), z * ez, x * ex),            # y = y0, facing +y
             ((x0, -y0, 0), x * ex, z * ez)]           # y = -y0, facing -y
    triangles = [t for f in faces for t in grid_triangles(*f)]
    return trimesh.Trimesh(vertices=np.array(triangles).reshape(-1, 3),
                           faces=np.arange(3 * len(triangles)).reshape(-1, 3), process=True)


def bin_surface(file):
    """The bin as a static mesh surface, the file's frame the world's; the floor's friction."""
    return {"name": "bin", "mesh": {"file": file, "scale": 1, "thickness": BIN_THICKNESS},
            "position": [0.0, 0.0, 0.0], "orientation": [1.0, 0.0, 0.0, 0.0],
            "staticFriction": 0.6, "kineticFriction": 0.6, "restitution": 0.0}


def write_mesh(directory, mesh, name):
    """DIR/<name>.stl and its FILE.mesh.json; the file name the scenes give."""
    file = f"{name}.stl"
    path = pathlib.Path(directory) / file
    mesh.export(str(path), file_type="stl")
    (path.parent / (file + ".mesh.json")).write_bytes(convert(path, file, "bench"))
    return file


def pile_hulls_scene(n, file, mass, bin_file="bin.stl"):
    """reports.scenes' pile of n cubes, each cube a pebble (the mesh `file`) in its place,
    turned by PILE_TURN times the cube's tilt about x and about y, the floor replaced by
    the bin (the mesh `bin_file`, bin_surface)."""
    pile = scenes.pile_scene(n)
    pile["name"] = f"PileHulls{n}"
    pile["surfaces"] = [bin_surface(bin_file)]
    # the energy audit off, as for the free bodies' timing: rk4 at the pile's 2 ms sums a
    # rotational energy gain of 1e-3 on a pebble spinning in flight after 0.64 s (a
    # pebble's principal moments differ, a cube's do not), and would refuse the step
    pile["solver"]["energyGainLimit"] = 0.0
    for k, ((x, y, z), (ax, ay)) in enumerate(scenes.pile_layout(n)):
        b = pile["bodies"][k]
        b.update(name=f"p{k}", shape={"type": "mesh", "file": file}, mass=mass,
                 orientation=scenes.quat_xy(PILE_TURN / 0.05 * ax, PILE_TURN / 0.05 * ay))
    return pile


def narrow_scene(name, shape, mass):
    """Two bodies of one shape and a floor (top face z = 0); poses are the benchmark's."""
    bodies = [body(f"{name}{k}", shape, mass, position=[0.0, 0.0, 1.0 + k], restitution=0.0,
                   staticFriction=0.6, kineticFriction=0.6, outputs=["position"], inputs=[]) for k in range(2)]
    return scene(f"Narrow_{name}", bodies, surfaces=[floor(0.6, 0.6, 0.0)])


def write(directory):
    d = pathlib.Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    for n in HULL_VERTICES:
        file = write_mesh(d, hull_mesh(n), f"hull_{n}")
        mass = DENSITY * hull_mesh(n).volume
        (d / f"narrow_hull_{n}.json").write_text(json.dumps(narrow_scene(f"hull{n}", {"type": "mesh", "file": file},
                                                                         mass)))
    cube = {"type": "box", "size": [CUBE_EDGE] * 3}
    (d / "narrow_cube.json").write_text(json.dumps(narrow_scene("cube", cube, DENSITY * CUBE_EDGE ** 3)))
    pebble = pebble_mesh()
    file = write_mesh(d, pebble, "pebble")
    bin_file = write_mesh(d, bin_mesh(), "bin")
    for n in PILE_COUNTS:
        scene = pile_hulls_scene(n, file, DENSITY * pebble.volume, bin_file)
        (d / f"pile_hulls_{n}.json").write_text(json.dumps(scene))
