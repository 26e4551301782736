"""MuJoCo on the benchmark scenes of reports.scenes, run by reports.performance in
the peers' own venv (.venv-peers, made by scripts/peers_venv.sh) and read back as JSON.

- Piles: each pile_<N>.json converted to MJCF (free-joint boxes of the same size, mass,
  friction and start poses, a floor plane at the surface's top face, the scene's step
  2 ms), stepped 1 simulated second with MuJoCo's default Euler integrator (and RK4 where
  cheap): CPU time per step (median of the repeats, mj_step with nstep so that no Python
  runs between steps), and, in a separate untimed run of 3 s, the deepest penetration
  (max over the first second's steps and contacts of -contact.dist; over all 3 s too)
  and the fastest body's speed at 1 s and at 3 s. With Euler, also the CPU time of the
  third second (from the state at 2 s, at rest), beside our pile at rest
  (bench_core.cpp's BM_PileWindows times the same window).
- Free bodies: the free_<N>.json bodies (inertia diag(1, 2, 3), no gravity) with RK4 at
  the scene's step, CPU time per step for N = 1 .. 1000; and the first body alone with
  RK4 (and Euler) at the given steps for T seconds, its final orientation returned so
  that reports.performance measures its error against the same reference as ours.

- With --pile-timing N: only the CPU time of one simulated second of pile_<N> (Euler,
  one repeat), for the performance report's interleaved ratio (ours and MuJoCo's, round by round);
  with --at-rest too, of the third second (after 2 s untimed).
- With --chain N: chain_<N>.json (links hinged end to end, issue 41) as nested bodies,
  each on a hinge joint at its shared end with the one before (the same axis, mass and
  inertia, no geoms so nothing collides), swinging down from horizontal for --T seconds
  at the scene's step, with Euler and with RK4: the CPU time of one run each (mj_step
  with nstep), and, in separate untimed runs, the energy (kinetic + potential,
  mj_energyPos and mj_energyVel, J) at the start and its largest departure, and the
  tip's position at the end. Generalized coordinates: the joints cannot drift.
- With --mesh-pile N: pile_hulls_<N>.json (reports.mesh_scenes: the pile with each cube
  a convex mesh, a pebble read from the same STL as ours, falling into a bin) with Euler:
  the CPU time of its first second (falling, from the start) and of its third (at rest,
  from the state at 2 s), one run each, and from an untimed run of 3 s the deepest
  penetration, the most contacts, the fastest body and the bodies inside the bin at 3 s.
  The bin is five box geoms, the solids our mesh surface's prisms make: MuJoCo collides
  a mesh geom as its convex hull, which for an open box is a solid block.

usage: python -m reports.performance_peers SCENES_DIR OUT.json [--quick] [--T 10] [--dts 1e-2,1e-3]
                      [--pile-timing N [--at-rest]] [--chain N --T 2] [--mesh-pile N]"""
import argparse
import copy
import json
import pathlib
import statistics
import time

import mujoco
import numpy as np

# Our cubes do not bounce (restitution 0); MuJoCo's default contact (solref 0.02,
# dampratio 1) is critically damped, which is its own way of saying the same.
PILE_MJCF = """<mujoco model="{name}">
  <option timestep="{dt}" gravity="{g}" integrator="{integrator}"/>
  <size memory="{memory}"/>
  <worldbody>
    <geom name="floor" type="plane" size="{half} {half} 0.1" pos="{floor}" friction="{mu} 0.005 0.0001"/>
{bodies}
  </worldbody>
</mujoco>"""

BODY = ('    <body pos="{p}" quat="{q}"><freejoint/>'
        '<geom type="box" size="{s}" mass="{m}" friction="{mu} 0.005 0.0001"/></body>')

# The pile of pebbles: one mesh asset, MuJoCo's own convex hull of it (the mesh is convex),
# each body's frame the file's as ours is (MuJoCo moves the geom to keep the mesh where
# the file has it; our body frame is the file's moved to the centre of mass, which the
# pebble's symmetric points put at the file's origin). The bin is five box geoms
# (bin_geoms), not a mesh geom of bin.stl: MuJoCo collides a mesh geom as its convex
# hull, which would fill the open box.
MESH_PILE_MJCF = """<mujoco model="{name}">
  <compiler meshdir="{meshdir}"/>
  <option timestep="{dt}" gravity="{g}" integrator="Euler"/>
  <size memory="{memory}"/>
  <asset><mesh name="hull" file="{file}"/></asset>
  <worldbody>
{bin}
{bodies}
  </worldbody>
</mujoco>"""

BIN_GEOM = '    <geom name="{name}" type="box" size="{s}" pos="{p}" friction="{mu} 0.005 0.0001"/>'

MESH_BODY = ('    <body pos="{p}" quat="{q}"><freejoint/>'
             '<geom type="mesh" mesh="hull" mass="{m}" friction="{mu} 0.005 0.0001"/></body>')

FREE_MJCF = """<mujoco>
  <option gravity="0 0 0" timestep="{dt}" integrator="{integrator}"/>
  <size memory="{memory}"/>
  <worldbody>
{bodies}
  </worldbody>
</mujoco>"""

FREE_BODY = ('    <body pos="{p}"><freejoint/>'
             '<inertial pos="0 0 0" mass="{m}" diaginertia="{I}"/></body>')


CHAIN_MJCF = """<mujoco model="{name}">
  <option timestep="{dt}" gravity="{g}" integrator="{integrator}"/>
  <worldbody>
{bodies}
  </worldbody>
</mujoco>"""


def fmt(v):
    return " ".join(f"{x:.17g}" for x in v)


def memory_for(n):
    """MuJoCo's arena: its default (about 1 MB here) overflows at hundreds of boxes in
    contact; a few hundred kB per body is plenty for a pile."""
    return f"{max(16, n // 2)}M"


def pile_xml(scene, integrator):
    surface = scene["surfaces"][0]
    lo, hi = np.array(surface["min"]), np.array(surface["max"])
    mu = surface.get("staticFriction", 0.6)
    bodies = []
    for b in scene["bodies"]:
        assert b["shape"]["type"] == "box"
        bodies.append(BODY.format(p=fmt(b["position"]), q=fmt(b.get("orientation", [1, 0, 0, 0])),
                                  s=fmt(0.5 * np.array(b["shape"]["size"])), m=b["mass"],
                                  # MuJoCo takes the larger friction of the pair, we the geometric
                                  # mean: equal values give the same coefficient in both
                                  mu=b.get("staticFriction", 0.6)))
    centre = 0.5 * (lo + hi)
    return PILE_MJCF.format(name=scene["name"], dt=scene["solver"]["step"], g=fmt(scene["gravity"]),
                            integrator=integrator, memory=memory_for(len(bodies)),
                            half=0.5 * float(max(hi[0] - lo[0], hi[1] - lo[1])),
                            floor=fmt([centre[0], centre[1], hi[2]]), mu=mu, bodies="\n".join(bodies))


def box_inertia(mass, size):
    """The principal moments (kg m^2) of a solid box of edges `size` about its centre:
    what our scene reader gives a box without an inertia."""
    a, b, c = size
    return [mass * (b * b + c * c) / 12, mass * (a * a + c * c) / 12, mass * (a * a + b * b) / 12]


def chain_xml(scene, integrator):
    """chain_<N>.json as MJCF: body k nested in body k - 1 (the joints' second bodies,
    each hinged to the one before or to the world), frames at the links' centres and
    unrotated at the start as ours are, each with a hinge at its anchor about its axis;
    an explicit inertial (no geom: nothing to collide) and a site at the last link's
    free end (its hinge's anchor mirrored through its centre)."""
    bodies = {b["name"]: b for b in scene["bodies"]}
    opened, parent_pos, lines = [], np.zeros(3), []
    for k, j in enumerate(scene["joints"]):
        parent = "world" if k == 0 else scene["joints"][k - 1]["bodies"][1]
        assert j["type"] == "revolute" and j["bodies"][0] == parent
        b = bodies[j["bodies"][1]]
        assert b["shape"]["type"] == "box" and b.get("orientation", [1, 0, 0, 0]) == [1, 0, 0, 0]
        pos = np.array(b["position"], dtype=float)
        anchor = np.array(j["anchor"], dtype=float) - pos
        indent = "    " + "  " * k
        inertia = box_inertia(b["mass"], b["shape"]["size"])
        lines.append(f'{indent}<body name="{b["name"]}" pos="{fmt(pos - parent_pos)}">'
                     f'<joint name="{j["name"]}" type="hinge" pos="{fmt(anchor)}" axis="{fmt(j["axis"])}"/>'
                     f'<inertial pos="0 0 0" mass="{b["mass"]}" diaginertia="{fmt(inertia)}"/>')
        opened.append(indent)
        parent_pos = pos
    lines.append(f'{opened[-1]}  <site name="tip" pos="{fmt(-anchor)}"/>')
    lines += [f"{indent}</body>" for indent in reversed(opened)]
    return CHAIN_MJCF.format(name=scene["name"], dt=scene["solver"]["step"], g=fmt(scene["gravity"]),
                             integrator=integrator, bodies="\n".join(lines))


def energy(model, data):
    """Kinetic + potential energy (J) of the state in `data`, the potential zero at the
    origin as ours: mj_forward first, so that the positions' quantities are of this
    state (mj_step leaves those of the step's start)."""
    mujoco.mj_forward(model, data)
    mujoco.mj_energyPos(model, data)
    mujoco.mj_energyVel(model, data)
    return float(data.energy[0] + data.energy[1])


def chain(scene, T):
    """The chain with Euler (MuJoCo's default) and RK4: CPU seconds per simulated second
    of one timed run from rest, and from an untimed run the energy at the start, its
    largest departure over the steps and at T (J), and the tip's position at T."""
    out = {}
    for integrator in ("Euler", "RK4"):
        model = mujoco.MjModel.from_xml_string(chain_xml(scene, integrator))
        dt = model.opt.timestep
        steps = round(T / dt)
        per_step = cpu_per_step(model, lambda: mujoco.MjData(model), steps, 1)
        data = mujoco.MjData(model)
        e0 = energy(model, data)
        worst = 0.0
        for _ in range(steps):
            mujoco.mj_step(model, data)
            gain = energy(model, data) - e0
            worst = max(worst, abs(gain))
        tip = data.site("tip").xpos
        out[integrator] = {"dt": dt, "steps": steps, "us_per_step": per_step * 1e6,
                           "s_per_simulated_s": per_step / dt, "energy_start_j": e0,
                           "max_energy_error_j": worst, "energy_error_end_j": gain,
                           "tip_x_m": float(tip[0]), "tip_z_m": float(tip[2]),
                           "warnings": int(sum(w.number for w in data.warning))}
    return out


def free_xml(scene, integrator, dt, count=None):
    bodies = [FREE_BODY.format(p=fmt(b["position"]), m=b["mass"],
                               I=fmt(np.diag(np.array(b["inertia"]))))
              for b in scene["bodies"][:count]]
    return FREE_MJCF.format(dt=dt, integrator=integrator, memory=memory_for(len(bodies)),
                            bodies="\n".join(bodies))


def set_spins(model, data, scene, count=None):
    """Our angularVelocity is in the world frame; a free joint's is in the body frame,
    which is the world frame at t = 0 (every body starts unrotated)."""
    for i, b in enumerate(scene["bodies"][:count]):
        assert b.get("orientation", [1, 0, 0, 0]) == [1, 0, 0, 0]
        data.qvel[6 * i + 3:6 * i + 6] = b["angularVelocity"]


def cpu_per_step(model, start, steps, repeats):
    """Median over repeats of the CPU seconds per mj_step, each repeat from `start`."""
    times = []
    for _ in range(repeats):
        data = start()
        t0 = time.process_time()
        mujoco.mj_step(model, data, nstep=steps)
        times.append((time.process_time() - t0) / steps)
    return statistics.median(times)


def fastest(data):
    """The fastest body's speed (m/s): how settled the pile is. A free joint's first
    three velocities are the body's linear velocity in the world frame."""
    return float(np.max(np.linalg.norm(data.qvel.reshape(-1, 6)[:, :3], axis=1)))


def settled(model, seconds):
    """The pile's state after `seconds` of simulated time from the start (untimed)."""
    data = mujoco.MjData(model)
    mujoco.mj_step(model, data, nstep=round(seconds / model.opt.timestep))
    return data


def from_state(model, state):
    """A fresh MjData holding a copy of `state` (its warm start too), for repeats that
    all start where the pile was at that instant, as our benchmark's third second does."""
    data = mujoco.MjData(model)
    mujoco.mj_copyData(data, model, state)
    return data


def pile(scene, integrator, repeats):
    model = mujoco.MjModel.from_xml_string(pile_xml(scene, integrator))
    dt = model.opt.timestep
    steps = round(1.0 / dt)
    # untimed: penetration after every step (what our benchmark records too), for 3 s
    # so that the pile's speed at rest compares with our manifold solver's at 3 s
    data = mujoco.MjData(model)
    deepest, deepest3, contacts, warnings = 0.0, 0.0, 0, 0
    speed_1s, at_2s = None, None
    for k in range(3 * steps):
        mujoco.mj_step(model, data)
        if data.ncon:
            depth = float(-np.min(data.contact.dist[:data.ncon]))
            deepest3 = max(deepest3, depth)
            if k < steps:
                deepest = max(deepest, depth)
            contacts = max(contacts, int(data.ncon))
        if k + 1 == steps:
            speed_1s = fastest(data)
        if k + 1 == 2 * steps:
            at_2s = copy.copy(data)
    warnings = int(sum(w.number for w in data.warning))
    per_step = cpu_per_step(model, lambda: mujoco.MjData(model), steps, repeats)
    out = {"n": len(scene["bodies"]), "integrator": integrator, "dt": dt, "steps": steps,
           "us_per_step": per_step * 1e6, "s_per_simulated_s": per_step / dt,
           "max_penetration_m": deepest, "max_penetration_3s_m": deepest3,
           "max_contacts": contacts, "warnings": warnings,
           # how settled the pile is at 1 s and at 3 s: the fastest body's speed (m/s)
           "max_speed_end": speed_1s, "max_speed_3s": fastest(data)}
    if integrator == "Euler":
        # their default at rest: the third second, every repeat from the state at 2 s
        rest = cpu_per_step(model, lambda: from_state(model, at_2s), steps, repeats)
        out.update(rest_us_per_step=rest * 1e6, rest_s_per_simulated_s=rest / dt)
    return out


def bin_bounds(surface, meshdir):
    """The inside of the scene's bin (reports.mesh_scenes.bin_surface, not turned): the
    box its triangles bound, (lo, hi), from its FILE.mesh.json, in the world frame."""
    assert surface["orientation"] == [1.0, 0.0, 0.0, 0.0] and surface["mesh"]["scale"] == 1, surface
    file = pathlib.Path(meshdir) / (surface["mesh"]["file"] + ".mesh.json")
    v = np.array(json.loads(file.read_text())["vertices"]) + np.array(surface["position"])
    return v.min(axis=0), v.max(axis=0)


def bin_geoms(surface, meshdir):
    """The bin as five boxes: its floor and four walls, each the solid behind the face
    that our mesh surface's prisms fill (thickness deep, the face's own extent)."""
    (lo, hi), t = bin_bounds(surface, meshdir), surface["mesh"]["thickness"]
    c, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
    z = lo[2] + half[2]
    boxes = {"floor": ([c[0], c[1], lo[2] - t / 2], [half[0], half[1], t / 2]),
             "wall_x0": ([lo[0] - t / 2, c[1], z], [t / 2, half[1], half[2]]),
             "wall_x1": ([hi[0] + t / 2, c[1], z], [t / 2, half[1], half[2]]),
             "wall_y0": ([c[0], lo[1] - t / 2, z], [half[0], t / 2, half[2]]),
             "wall_y1": ([c[0], hi[1] + t / 2, z], [half[0], t / 2, half[2]])}
    return "\n".join(BIN_GEOM.format(name=k, p=fmt(p), s=fmt(s), mu=surface.get("staticFriction", 0.6))
                     for k, (p, s) in boxes.items())


def mesh_pile_xml(scene, meshdir):
    """pile_hulls_<N>.json as MJCF: the bin as box geoms (bin_geoms), the bodies' one
    mesh file."""
    (file,) = {b["shape"]["file"] for b in scene["bodies"]}
    bodies = [MESH_BODY.format(p=fmt(b["position"]), q=fmt(b.get("orientation", [1, 0, 0, 0])), m=b["mass"],
                               mu=b.get("staticFriction", 0.6)) for b in scene["bodies"]]
    return MESH_PILE_MJCF.format(name=scene["name"], meshdir=meshdir, file=file, dt=scene["solver"]["step"],
                                 g=fmt(scene["gravity"]), memory=memory_for(len(bodies)),
                                 bin=bin_geoms(scene["surfaces"][0], meshdir), bodies="\n".join(bodies))


def inside_bin(data, lo, hi):
    """The bodies whose centre is inside the bin (in x and y, above its floor)."""
    x = data.xpos[1:]
    within = (x[:, 0] > lo[0]) & (x[:, 0] < hi[0]) & (x[:, 1] > lo[1]) & (x[:, 1] < hi[1]) & (x[:, 2] > lo[2])
    return int(np.sum(within))


def mesh_pile(scene, meshdir):
    """The pebbles' pile with Euler: CPU time per simulated second of the first second
    and of the third (one run each), and from an untimed run of 3 s the deepest
    penetration (-contact.dist), the most contacts, the fastest body and the bodies
    inside the bin at 3 s."""
    model = mujoco.MjModel.from_xml_string(mesh_pile_xml(scene, meshdir))
    dt = model.opt.timestep
    steps = round(1.0 / dt)
    data = mujoco.MjData(model)
    deepest, contacts, at_2s = 0.0, 0, None
    for k in range(3 * steps):
        mujoco.mj_step(model, data)
        if data.ncon:
            deepest = max(deepest, float(-np.min(data.contact.dist[:data.ncon])))
            contacts = max(contacts, int(data.ncon))
        if k + 1 == 2 * steps:
            at_2s = copy.copy(data)
    fall = cpu_per_step(model, lambda: mujoco.MjData(model), steps, 1)
    rest = cpu_per_step(model, lambda: from_state(model, at_2s), steps, 1)
    return {"engine": f"MuJoCo {mujoco.__version__}", "n": len(scene["bodies"]), "integrator": "Euler", "dt": dt,
            "fall_s_per_simulated_s": fall / dt, "rest_s_per_simulated_s": rest / dt,
            "max_penetration_3s_m": deepest, "max_contacts": contacts, "max_speed_3s": fastest(data),
            "inside_3s": inside_bin(data, *bin_bounds(scene["surfaces"][0], meshdir)),
            "warnings": int(sum(w.number for w in data.warning))}


def free_many(scene, dt, repeats):
    model = mujoco.MjModel.from_xml_string(free_xml(scene, "RK4", dt))

    def start():
        data = mujoco.MjData(model)
        set_spins(model, data, scene)
        return data
    steps = max(20, min(2000, round(2e5 / len(scene["bodies"]))))
    per_step = cpu_per_step(model, start, steps, repeats)
    n = len(scene["bodies"])
    return {"n": n, "integrator": "RK4", "dt": dt, "us_per_step": per_step * 1e6,
            "ns_per_body_step": per_step * 1e9 / n}


def free_one(scene, integrator, dt, T, repeats):
    model = mujoco.MjModel.from_xml_string(free_xml(scene, integrator, dt, count=1))

    def start():
        data = mujoco.MjData(model)
        set_spins(model, data, scene, count=1)
        return data
    steps = round(T / dt)
    data = start()
    mujoco.mj_step(model, data, nstep=steps)
    per_step = cpu_per_step(model, start, steps, repeats)
    return {"integrator": integrator, "dt": dt, "T": T, "q_end": [float(x) for x in data.qpos[3:7]],
            "us_per_step": per_step * 1e6, "s_per_simulated_s": per_step / dt}


def main(argv=None, prog=None):
    p = argparse.ArgumentParser(prog=prog, description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scenes")
    p.add_argument("out")
    p.add_argument("--quick", action="store_true")
    p.add_argument("--T", type=float, default=10.0)
    p.add_argument("--dts", default="1e-2,1e-3")
    p.add_argument("--pile-timing", type=int, help="time pile_<N> once and write only that")
    p.add_argument("--at-rest", action="store_true", help="with --pile-timing: time the third second")
    p.add_argument("--chain", type=int, help="run chain_<N> for --T seconds and write only that")
    p.add_argument("--mesh-pile", type=int, help="run pile_hulls_<N> (falling, at rest) and write only that")
    args = p.parse_args(argv)
    d = pathlib.Path(args.scenes)
    load = lambda name: json.loads((d / name).read_text())  # noqa: E731
    if args.chain:
        out = {"engine": f"MuJoCo {mujoco.__version__}", "n": args.chain, "T": args.T,
               **chain(load(f"chain_{args.chain}.json"), args.T)}
        pathlib.Path(args.out).write_text(json.dumps(out, indent=1))
        return
    if args.mesh_pile:
        out = mesh_pile(load(f"pile_hulls_{args.mesh_pile}.json"), str(d.resolve()))
        pathlib.Path(args.out).write_text(json.dumps(out, indent=1))
        return
    if args.pile_timing:
        model = mujoco.MjModel.from_xml_string(pile_xml(load(f"pile_{args.pile_timing}.json"), "Euler"))
        start = lambda: mujoco.MjData(model)  # noqa: E731
        if args.at_rest:
            at_2s = settled(model, 2.0)
            start = lambda: from_state(model, at_2s)  # noqa: E731
        per_step = cpu_per_step(model, start, round(1.0 / model.opt.timestep), 1)
        pathlib.Path(args.out).write_text(json.dumps({"n": args.pile_timing, "at_rest": args.at_rest,
                                                      "s_per_simulated_s": per_step / model.opt.timestep}))
        return
    repeats = 3 if args.quick else 5
    pile_counts = (10, 100) if args.quick else (10, 100, 1000)
    free_counts = (1, 10, 100) if args.quick else (1, 10, 100, 1000)
    out = {"engine": f"MuJoCo {mujoco.__version__}", "piles": [], "free": [], "free_one": []}
    for n in pile_counts:
        scene = load(f"pile_{n}.json")
        # RK4 at 1000 cubes would take minutes per repeat; their default (Euler) is what
        # the figures use
        for integrator in ("Euler", "RK4") if n <= 100 else ("Euler",):
            # the pile of 1000 too takes the median of several repeats, as ours does
            # (BM_Pile's 3 repetitions): one repeat moved by 20 % from run to run
            r = pile(scene, integrator, min(repeats, 3) if n >= 1000 else repeats)
            out["piles"].append(r)
            print(f"MuJoCo pile {n:5d} {integrator:5s}: {r['us_per_step']:9.1f} us/step, "
                  f"penetration {r['max_penetration_m'] * 1e3:.2f} mm, fastest body at 3 s "
                  f"{r['max_speed_3s']:.3g} m/s" +
                  (f", at rest {r['rest_us_per_step']:.1f} us/step" if "rest_us_per_step" in r else ""),
                  flush=True)
    for n in free_counts:
        scene = load(f"free_{n}.json")
        r = free_many(scene, scene["solver"]["step"], repeats)
        out["free"].append(r)
        print(f"MuJoCo free {n:5d} RK4: {r['ns_per_body_step']:9.1f} ns/body-step", flush=True)
    scene = load("free_1.json")
    for dt in (float(x) for x in args.dts.split(",")):
        for integrator in ("RK4", "Euler"):
            r = free_one(scene, integrator, dt, args.T, repeats)
            out["free_one"].append(r)
            print(f"MuJoCo free body {integrator:5s} dt={dt:g}: {r['us_per_step']:.2f} us/step", flush=True)
    pathlib.Path(args.out).write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
