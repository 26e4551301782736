"""The tests' names for the scene builders (rigidfmu.scenes): dicts in the scene format."""
from rigidfmu.scenes import body, conveyor, cube_on_floor, floor, free_spin, projectile, scene, two_bodies  # noqa: F401
