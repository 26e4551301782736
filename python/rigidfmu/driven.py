"""Driven bodies as the scripts see a scene (docs/guide/driven-bodies.md): a body or a
surface with "motion": "driven" is moved by its inputs, not by the world. A driven
surface is a driven body with the surface's box as its shape, centred between min and
max and turned by its orientation (src/scene.cpp, readMovingSurface); the FMU lists
it after the scene's bodies. A driven body has no mass, and its pose is an input."""

IDENTITY = [1.0, 0.0, 0.0, 0.0]
POSE = (("position", 3), ("orientation", 4))


def is_driven(item: dict) -> bool:
    return item.get("motion") == "driven"


def surface_body(surface: dict) -> dict:
    """The driven body a driven surface is, in the scene format's body fields (to 1e-12 m:
    max - min in floating point is 0.6000000000000001 where 0.6 is meant)."""
    lo, hi = surface["min"], surface["max"]
    return {"name": surface["name"], "motion": "driven",
            "shape": {"type": "box", "size": [round(b - a, 12) for a, b in zip(lo, hi)]},
            "position": [round(0.5 * (a + b), 12) for a, b in zip(lo, hi)],
            "orientation": surface.get("orientation", IDENTITY)}


def all_bodies(scene: dict) -> list:
    """The FMU's bodies in its order: the scene's bodies, then its driven surfaces."""
    surfaces = [surface_body(s) for s in scene.get("surfaces", []) if is_driven(s)]
    return [*scene["bodies"], *surfaces]


def static_surfaces(scene: dict) -> list:
    return [s for s in scene.get("surfaces", []) if not is_driven(s)]


def driven_names(scene: dict) -> list:
    return [b["name"] for b in all_bodies(scene) if is_driven(b)]


def pose_inputs(scene: dict) -> list:
    """The inputs that hold the driven bodies' poses: b.position[1..3], b.orientation[1..4]."""
    return [f"{name}.{field}[{i}]" for name in driven_names(scene)
            for field, n in POSE for i in range(1, n + 1)]
