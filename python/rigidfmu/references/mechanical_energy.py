"""The mechanical energy of a run's bodies over time, J, from the FMU's outputs and its
scene: kinetic, gravity's potential and buoyancy's potential. What the total loses
from its start value is what friction, impacts and drag have dissipated.

Buoyancy's potential: a medium pushes a body up with rho |g| V_sub (src/medium.cpp),
the weight of the fluid it displaces. Displacing that fluid lifts it to the medium's
top, so the potential is U_b = rho |g| * integral over the submerged part of the depth
below the medium's top dV; its gradient is the buoyant force and its turn gradient
the torque of that force at the centre of buoyancy. (This holds for a body entering a
medium through its top, as in the example scenes; one pushed in through a side wall
would change U_b without the force doing work, and the dissipation would show it.)
The integral is taken over a fixed grid of points inside the body (midpoint rule,
GRID per axis of its bounding box), each standing for an equal share of the exact
volume: exact for a body wholly inside, within a cell's thickness at the waterline.
"""
import numpy as np

from rigidfmu.driven import is_driven

FLUID_DENSITY = {"water": 998.2, "air": 1.204}  # kg/m3, the FMU's defaults (README, Scenes)
GRID = 16


def vector(result, body, field):
    return np.column_stack([result[f"{body}.{field}[{i}]"] for i in (1, 2, 3)])


def volume(shape):
    """m3, of the solid shape (sizes as in the scene format: box full edges)."""
    r = shape.get("radius", 0.0)
    if shape["type"] == "sphere":
        return 4 / 3 * np.pi * r**3
    if shape["type"] == "box":
        return float(np.prod(shape["size"]))
    cylinder = np.pi * r**2 * shape["length"]
    return cylinder + (4 / 3 * np.pi * r**3 if shape["type"] == "capsule" else 0.0)


def inside_points(shape, n=GRID):
    """Body-frame cell centres of an n^3 grid over the shape's bounding box that lie
    inside the shape (cylinder and capsule axes along body z, src/shape.h)."""
    r = shape.get("radius", 0.0)
    half = {"sphere": [r, r, r], "box": np.asarray(shape.get("size", [0, 0, 0])) / 2,
            "cylinder": [r, r, shape.get("length", 0) / 2],
            "capsule": [r, r, shape.get("length", 0) / 2 + r]}[shape["type"]]
    u = (np.arange(n) + 0.5) / n * 2 - 1
    p = np.stack(np.meshgrid(u, u, u, indexing="ij"), axis=-1).reshape(-1, 3) * np.asarray(half)
    if shape["type"] == "sphere":
        keep = np.sum(p * p, axis=1) <= r * r
    elif shape["type"] == "box":
        keep = np.ones(len(p), dtype=bool)
    elif shape["type"] == "cylinder":
        keep = p[:, 0] ** 2 + p[:, 1] ** 2 <= r * r
    else:  # capsule: within r of its axis segment
        z = np.clip(p[:, 2], -shape["length"] / 2, shape["length"] / 2)
        keep = p[:, 0] ** 2 + p[:, 1] ** 2 + (p[:, 2] - z) ** 2 <= r * r
    return p[keep]


def rotations(q):
    """R_WB of each unit quaternion (w, x, y, z) of an (T, 4) array, (T, 3, 3)."""
    q = q / np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], axis=-1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], axis=-1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=-1),
    ], axis=1)


def medium_density(medium):
    return medium["density"] if medium.get("type") == "custom" else FLUID_DENSITY[medium.get("type", "water")]


def buoyancy_potential(position, orientation, shape, media, g):
    """U_b of one body over time (module docstring), J; position (T, 3), orientation (T, 4)."""
    g_norm = np.linalg.norm(g)
    energy = np.zeros(len(position))
    if g_norm == 0 or not media:
        return energy
    up = -np.asarray(g) / g_norm
    points = inside_points(shape)
    dV = volume(shape) / len(points)
    reach = np.max(np.linalg.norm(points, axis=1))
    for medium in media:
        rho = medium_density(medium)
        lo, hi = np.asarray(medium["min"]), np.asarray(medium["max"])
        near = np.all((position > lo - reach) & (position < hi + reach), axis=1)
        if rho == 0 or not near.any():
            continue
        top = np.sum(np.maximum(lo * up, hi * up))  # the medium's highest corner along up
        # only the frames where the body is near the medium: (T_near, k, 3) points
        world = np.einsum("tij,kj->tki", rotations(orientation[near]), points) + position[near, None, :]
        inside = np.all((world >= lo) & (world <= hi), axis=2)
        depth = top - world @ up
        energy[near] += rho * g_norm * dV * np.sum(inside * depth, axis=1)
    return energy


NEEDED = ("position", "orientation", "velocity", "angularVelocity", "angularMomentum")


def energies(result, scene, masses, g):
    """(kinetic, gravity potential, buoyancy potential, left_out): the first three summed
    over the bodies, J, each (T,): kinetic 1/2 (m v.v + omega.L), gravity's -m g.x,
    buoyancy's U_b. left_out names the bodies that do not output all of NEEDED (scene
    "outputs"): they are in none of the sums, and the plot says so. Driven bodies
    (no mass, their motion given) are in none of the sums either, nor in left_out."""
    t = len(result["time"])
    kinetic, gravity, buoyancy = np.zeros(t), np.zeros(t), np.zeros(t)
    names = set(result.dtype.names if hasattr(result, "dtype") else result)
    media = scene.get("media", [])
    left_out = []
    for body in scene["bodies"]:
        if is_driven(body):
            continue
        b, m = body["name"], masses[body["name"]]
        if any(f"{b}.{f}[1]" not in names for f in NEEDED):
            left_out.append(b)
            continue
        x, v, w, L = (vector(result, b, f) for f in ("position", "velocity", "angularVelocity",
                                                     "angularMomentum"))
        q = np.column_stack([result[f"{b}.orientation[{i}]"] for i in (1, 2, 3, 4)])
        kinetic += 0.5 * (m * np.sum(v * v, axis=1) + np.sum(w * L, axis=1))
        gravity += -m * x @ g
        buoyancy += buoyancy_potential(x, q, body["shape"], media, g)
    return kinetic, gravity, buoyancy, left_out
