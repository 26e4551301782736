"""Scenes the tests build FMUs from (dicts in the scene format of INTERFACE.md)."""


def body(name="ball", shape=None, mass=1.0, **fields):
    b = {"name": name, "shape": shape or {"type": "sphere", "radius": 0.1}, "mass": mass}
    b.update(fields)
    return b


def scene(name, bodies, gravity=(0.0, 0.0, -9.81), method="rk4", step=1e-3):
    return {"name": name, "gravity": list(gravity),
            "solver": {"method": method, "step": step}, "bodies": bodies}


def projectile():
    return scene("Projectile", [body("ball", position=[1.0, 2.0, 10.0], velocity=[3.0, -2.0, 4.0])])


def free_spin(inertia=(1.0, 2.0, 3.0), omega=(0.01, 5.0, 0.01), method="rk4", step=1e-3,
              name="Spin"):
    """A torque-free body with principal inertia diag(inertia), identity orientation
    (so world and body frames coincide at t = 0), gravity off."""
    I = [[inertia[0], 0, 0], [0, inertia[1], 0], [0, 0, inertia[2]]]
    return scene(name, [body("spinner", shape={"type": "box", "size": [0.3, 0.2, 0.1]}, mass=1.0,
                             inertia=I, angularVelocity=list(omega))],
                 gravity=(0, 0, 0), method=method, step=step)


def two_bodies():
    """Two bodies with distinct start values in every field, to tell variables apart."""
    return scene("TwoBodies", [
        body("a", shape={"type": "box", "size": [0.4, 0.2, 0.1]}, mass=2.5,
             position=[1.5, -2.5, 3.5], orientation=[0.5, 0.5, 0.5, 0.5],
             velocity=[0.25, -0.75, 1.25], angularVelocity=[0.3, -0.6, 0.9], restitution=0.7),
        body("b", shape={"type": "capsule", "radius": 0.05, "length": 0.3}, mass=0.75,
             position=[-4.0, 5.0, -6.0], velocity=[7.0, -8.0, 9.0],
             angularVelocity=[-1.5, 2.5, -3.5], restitution=0.1),
    ], gravity=(0.5, -0.25, -9.5), method="euler", step=2e-3)


def floor(mus=0.5, muk=0.5, xi=0.0, half=5.0):
    """A floor whose top face is z = 0."""
    return {"name": "floor", "min": [-half, -half, -1], "max": [half, half, 0],
            "staticFriction": mus, "kineticFriction": muk, "restitution": xi}


def cube_on_floor(name, edge, floor_friction=0.5, **fields):
    """A cube "box" set down on a floor, its face on the floor's top (step 1 ms)."""
    box = body("box", shape={"type": "box", "size": [edge] * 3}, position=[0, 0, edge / 2],
               restitution=0.0, **fields)
    s = scene(name, [box], step=1e-3)
    s["surfaces"] = [floor(floor_friction, floor_friction)]
    return s
