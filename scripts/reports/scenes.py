"""The benchmark scenes, written once as scene files so that our core benchmark
(bench/bench_core.cpp), the FMU benchmark and MuJoCo (reports.performance_peers)
run the very same bodies: free tumbling bodies, and piles of cubes falling on a floor.
One pile file per count serves the benchmarks that time it over 1 s (BM_Pile) and over
3 s with its falling and resting windows (BM_PileWindows, BM_PileAwake), and MuJoCo. A
wide pile (BM_PileWide) has as many cubes as the largest but in columns as short as the
pile of 100's, so that the growth from 100 cubes can be read at equal height as well as
at the growing height of the cube-root piles. Tumbling bodies are the free bodies with
collisions on: they can collide but, 3 m apart, touch nothing. No scene names a contact
solver: there is one (the constraint solver). A chain of links hinged end to end
(issue 41) starts horizontal and swings down under gravity: its joints are rows of the
same solver, and MuJoCo runs it as a chain of hinges (reports.performance_peers). The
convex mesh scenes (hulls of 100-1000 vertices, issue 42) are reports.mesh_scenes'.

  python -m reports.scenes DIR    writes DIR/free_<N>.json, DIR/pile_<N>.json,
                                         DIR/pile_wide_<N>.json, DIR/tumbling_<N>.json
                                         DIR/chain_<N>.json, and the mesh scenes
                                         (reports.mesh_scenes)
  python -m reports.scenes DIR --tilt A,B
                                         the same with the piles' cubes tilted by another
                                         pattern (TILT's frequencies replaced by A and B):
                                         a pile is chaotic, and a figure read from one
                                         pattern's fall can be checked on others
"""
import json
import math
import pathlib
import sys

from rigidfmu.scenes import G, body, diag, floor, scene

FREE_COUNTS = (1, 10, 100, 1000, 10000)
PILE_COUNTS = (10, 100, 1000)
TUMBLING_COUNTS = (100, 1000)
WIDE_PILE = 1024   # 16 x 16 columns of 4: the pile of 100's height (5 x 5 columns of 4)
WIDE_LAYERS = 4
PILE_STEP = 2e-3   # s: MuJoCo's default timestep, the issue's figures' dt
EDGE = 0.1         # m, cube edge
GAP = 0.02         # m, between neighbouring cubes at the start
FREE_INERTIA = (1.0, 2.0, 3.0)  # kg m^2: asymmetric, so the bodies really tumble
TILT = (1.7, 2.3)  # cube k tilted 0.05 sin(1.7 k) rad about x and 0.05 cos(2.3 k) about y
CHAIN_LINKS = 100
CHAIN_LINK = (0.1, 0.02, 0.02)  # m: a box along x, hinged at both ends of that edge
CHAIN_LINK_MASS = 0.1           # kg
CHAIN_STEP = 1e-3               # s, ours (rk4) and MuJoCo's (Euler and RK4)


def free_scene(n):
    """n torque-free tumbling bodies (no gravity, no collisions), each with its own spin."""
    bodies = []
    for i in range(n):
        a = 2 * math.pi * i / max(n, 1)
        bodies.append(body(
            f"b{i}", {"type": "box", "size": [0.3, 0.2, 0.1]}, 1.0, inertia=diag(FREE_INERTIA),
            position=[3.0 * (i % 100), 3.0 * (i // 100), 0.0],
            angularVelocity=[0.4 + 0.1 * math.cos(a), 0.3, 3.0 + 0.1 * math.sin(a)],
            collision=False, outputs=["position", "orientation"], inputs=[]))
    return scene(f"Free{n}", bodies, gravity=(0, 0, 0))


def tumbling_scene(n):
    """free_scene(n) with collisions on: the same bodies, 3 m apart, which can collide
    but never touch; what the collision module costs bodies that meet nothing."""
    scene = free_scene(n)
    scene["name"] = f"Tumbling{n}"
    for b in scene["bodies"]:
        b["collision"] = True
    return scene


def driven_scene(n):
    """tumbling_scene(n) with every body driven (motion in, force out): the same boxes
    at the same places, their spins and a drift of 0.1 m/s as inputs; what a driven
    body costs beside a free one of the same shape."""
    scene = tumbling_scene(n)
    scene["name"] = f"Driven{n}"
    for b in scene["bodies"]:
        for key in ("mass", "inertia", "inputs"):
            b.pop(key, None)
        b.update(motion="driven", velocity=[0.1, 0.0, 0.0], outputs=[])
    return scene


def pile_layout(n, layers=None, tilt=TILT):
    """Columns on a square grid, layers upwards: (x, y, z) of each cube's centre and a
    small tilt (rad, about x and y; frequencies `tilt`) so that cubes land on edges and
    tumble. The grid is n^(1/3) a side (10 cubes: 2 x 2 columns, 100: 5 x 5 of 4, 1000:
    10 x 10 of 10), or sqrt(n / layers) with columns of `layers` cubes."""
    side = max(1, round(n ** (1 / 3) if layers is None else math.sqrt(n / layers)))
    per_layer = side * side
    pitch = EDGE + GAP
    out = []
    for k in range(n):
        layer, cell = divmod(k, per_layer)
        ix, iy = divmod(cell, side)
        x = (ix - (side - 1) / 2) * pitch
        y = (iy - (side - 1) / 2) * pitch
        z = 0.5 * EDGE + GAP + layer * (pitch + GAP)
        out.append(((x, y, z), (0.05 * math.sin(tilt[0] * k), 0.05 * math.cos(tilt[1] * k))))
    return out


def quat_xy(ax, ay):
    """Quaternion (w, x, y, z) of a turn ax about x followed by ay about y."""
    cx, sx, cy, sy = math.cos(ax / 2), math.sin(ax / 2), math.cos(ay / 2), math.sin(ay / 2)
    return [cy * cx, cy * sx, sy * cx, -sy * sx]


def pile_scene(n, layers=None, tilt=TILT):
    bodies = []
    for k, ((x, y, z), (ax, ay)) in enumerate(pile_layout(n, layers, tilt)):
        bodies.append(body(f"c{k}", {"type": "box", "size": [EDGE] * 3}, 1.0,
                           position=[x, y, z], orientation=quat_xy(ax, ay),
                           restitution=0.0, staticFriction=0.6, kineticFriction=0.6,
                           outputs=["position"], inputs=[]))
    return scene(f"Pile{n}", bodies, step=PILE_STEP, surfaces=[floor(0.6, 0.6, 0.0, half=5.0)])


def pile_wide_scene(n, tilt=TILT):
    """pile_scene(n) laid out in columns of WIDE_LAYERS cubes (the pile of 100's
    height): the same cubes, floor, step and solver, only the layout differs."""
    scene = pile_scene(n, layers=WIDE_LAYERS, tilt=tilt)
    scene["name"] = f"PileWide{n}"
    return scene


def chain_scene(n=CHAIN_LINKS):
    """n boxes (CHAIN_LINK, CHAIN_LINK_MASS) laid end to end along +x from the origin,
    at rest: link k from x = k a to (k + 1) a, hinged about y to the world at the origin
    (link 0) or to link k - 1 at their shared end. Planar: it swings in the x-z plane.
    No collisions (a hinge's two leaves touch), so the joints alone cost."""
    a = CHAIN_LINK[0]
    links = [body(f"link{k}", {"type": "box", "size": list(CHAIN_LINK)}, CHAIN_LINK_MASS,
                  position=[(k + 0.5) * a, 0.0, 0.0], collision=False,
                  outputs=["position", "orientation"], inputs=[]) for k in range(n)]
    joints = [{"name": f"hinge{k}", "type": "revolute", "bodies": ["world" if k == 0 else f"link{k - 1}", f"link{k}"],
               "anchor": [k * a, 0.0, 0.0], "axis": [0.0, 1.0, 0.0]} for k in range(n)]
    return scene(f"Chain{n}", links, gravity=(0.0, 0.0, -G), step=CHAIN_STEP, joints=joints)


def write(directory, tilt=TILT):
    d = pathlib.Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    for n in FREE_COUNTS:
        (d / f"free_{n}.json").write_text(json.dumps(free_scene(n)))
    for n in PILE_COUNTS:
        (d / f"pile_{n}.json").write_text(json.dumps(pile_scene(n, tilt=tilt)))
    (d / f"pile_wide_{WIDE_PILE}.json").write_text(json.dumps(pile_wide_scene(WIDE_PILE, tilt)))
    for n in TUMBLING_COUNTS:
        (d / f"tumbling_{n}.json").write_text(json.dumps(tumbling_scene(n)))
        (d / f"driven_{n}.json").write_text(json.dumps(driven_scene(n)))
    (d / f"chain_{CHAIN_LINKS}.json").write_text(json.dumps(chain_scene()))
    from reports import mesh_scenes  # here: it builds on this module's piles
    mesh_scenes.write(d)


def main(argv):
    """DIR [--tilt A,B] (module docstring)."""
    args = list(argv)
    tilt = TILT
    if "--tilt" in args:
        at = args.index("--tilt")
        try:
            tilt = tuple(float(f) for f in args[at + 1].split(","))
        except (IndexError, ValueError):
            tilt = ()
        if len(tilt) != 2 or not all(math.isfinite(f) for f in tilt):
            sys.exit("--tilt takes two finite frequencies A,B (rad per cube), e.g. --tilt 1.3,2.9")
        del args[at:at + 2]
    write(args[0] if args else "build/bench-scenes", tilt)


if __name__ == "__main__":
    main(sys.argv[1:])
