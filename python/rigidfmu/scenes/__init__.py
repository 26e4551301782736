"""Scene builders: dicts in the scene format (docs/scene-format.md) for the tests, the
reports and the benchmarks. `bench` holds the benchmark scenes; the example scenes are
files, scripts/scenes/*.json."""

G = 9.81  # m/s^2, the scenes' default gravity


def body(name="ball", shape=None, mass=1.0, **fields):
    """A body (default: a 1 kg sphere of radius 0.1 m named ball); fields as in the format."""
    b = {"name": name, "shape": shape or {"type": "sphere", "radius": 0.1}, "mass": mass}
    b.update(fields)
    return b


def scene(name, bodies, gravity=(0.0, 0.0, -G), method="rk4", step=1e-3, **extra):
    """A scene of bodies (extra: surfaces, media, ... as in the format)."""
    s = {"name": name, "gravity": list(gravity), "solver": {"method": method, "step": step},
         "bodies": bodies}
    s.update(extra)
    return s


def diag(inertia):
    """The inertia tensor diag(inertia)."""
    return [[inertia[0], 0, 0], [0, inertia[1], 0], [0, 0, inertia[2]]]


def free_spin(inertia=(1.0, 2.0, 3.0), omega=(0.01, 5.0, 0.01), method="rk4", step=1e-3,
              name="Spin", body_name="spinner", **fields):
    """A torque-free 0.3 x 0.2 x 0.1 m box of 1 kg with principal inertia diag(inertia),
    identity orientation (so world and body frames coincide at t = 0), gravity off;
    fields go to the body."""
    return scene(name, [body(body_name, shape={"type": "box", "size": [0.3, 0.2, 0.1]}, mass=1.0,
                             inertia=diag(inertia), angularVelocity=list(omega), **fields)],
                 gravity=(0, 0, 0), method=method, step=step)


def projectile():
    return scene("Projectile", [body("ball", position=[1.0, 2.0, 10.0], velocity=[3.0, -2.0, 4.0])])


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


def floor(mus=0.5, muk=0.5, xi=0.0, half=5.0, name="floor"):
    """A floor (a fixed surface) whose top face is z = 0."""
    return {"name": name, "min": [-half, -half, -1.0], "max": [half, half, 0.0],
            "staticFriction": mus, "kineticFriction": muk, "restitution": xi}


def cube_on_floor(name, edge, floor_friction=0.5, **fields):
    """A cube "box" set down on a floor, its face on the floor's top (step 1 ms)."""
    box = body("box", shape={"type": "box", "size": [edge] * 3}, position=[0, 0, edge / 2],
               restitution=0.0, **fields)
    return scene(name, [box], step=1e-3, surfaces=[floor(floor_friction, floor_friction)])


def conveyor(name, belt, edge=0.2, mus=0.6, muk=0.4, **fields):
    """A cube "box" of 1 kg set down at rest on a conveyor: a floor (top face z = 0)
    whose belt moves at `belt` (m/s, world frame); mu_s and mu_k on both sides, so the
    pair's too (step 1 ms)."""
    box = body("box", shape={"type": "box", "size": [edge] * 3}, position=[0, 0, edge / 2],
               restitution=0.0, staticFriction=mus, kineticFriction=muk, **fields)
    belt_floor = dict(floor(mus, muk, half=50.0, name="belt"), beltVelocity=list(belt))
    return scene(name, [box], step=1e-3, surfaces=[belt_floor])
