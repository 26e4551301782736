"""Bodies shaped by mesh files, through the FMU (issue 42): a cube read from an STL tips,
stacks and slides as the primitive cube does and as the closed forms say; a
tetrahedron dropped on its vertex falls onto a face; the mass comes from the mesh;
broken meshes and paths are refused naming the file and the fault."""
import io
import json
import math
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest
import trimesh

import scenes
from rigidfmu.references.quaternion import quat_axis_angle, quat_mul, rotation_matrix

G = 9.81
EDGE = 0.2  # m, the cubes' edge
H = 0.05  # s, communication step
ROOT = pathlib.Path(__file__).resolve().parents[2]


def stl(mesh: trimesh.Trimesh) -> bytes:
    """The mesh as a binary STL file, as a CAD tool exports it (float32 coordinates)."""
    out = io.BytesIO()
    mesh.export(out, file_type="stl")
    return out.getvalue()


CUBE_FILES = {"parts/cube.stl": stl(trimesh.creation.box(extents=(EDGE, EDGE, EDGE)))}
MESH_CUBE = {"type": "mesh", "file": "parts/cube.stl"}
BOX = {"type": "box", "size": [EDGE] * 3}


def quat_about_y(angle):
    return list(quat_axis_angle([0.0, 1.0, 0.0], angle))


def run(slave, scene, files, seconds, names):
    s = slave(scene, files=files)
    for k in range(round(seconds / H)):
        s.slave.doStep(k * H, H)
    return {n: s.get(n) for n in names}


def position(values, body):
    return np.array([values[f"{body}.position[{i}]"] for i in (1, 2, 3)])


def names_of(*bodies):
    return [f"{b}.{q}[{i}]" for b in bodies for q in ("position", "velocity") for i in (1, 2, 3)] + \
        [f"{b}.orientation[{i}]" for b in bodies for i in (1, 2, 3, 4)]


def on_edge(angle, x):
    """A cube turned by `angle` about y, standing on its lowest edge on the floor z = 0,
    its centre at x: the start position, and the edge's x."""
    R = np.array([[math.cos(angle), 0, math.sin(angle)], [0, 1, 0], [-math.sin(angle), 0, math.cos(angle)]])
    corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * EDGE / 2 @ R.T
    lowest = corners[np.argmin(corners[:, 2])]
    return [x, 0.0, -lowest[2] + 1e-4], x + lowest[0]


@pytest.mark.parametrize("degrees", [40.0, 50.0])
def test_a_mesh_cube_tips_as_the_closed_form_and_the_primitive_cube(slave, degrees):
    """Set on an edge, a cube falls to the side of the edge where its centre of mass is:
    turned 40 deg it falls back to 0 deg, turned 50 deg on to 90 deg (within 1 deg); it
    ends face down, its centre EDGE/2 from the edge on that side within 2 cm (it may
    slip), and the mesh cube where the primitive one ends within 1 mm."""
    angle = math.radians(degrees)
    start_mesh, edge_mesh = on_edge(angle, 0.0)
    start_box, edge_box = on_edge(angle, 2.0)
    bodies = [scenes.body("mesh", shape=MESH_CUBE, position=start_mesh, orientation=quat_about_y(angle),
                          restitution=0.0),
              scenes.body("box", shape=BOX, position=start_box, orientation=quat_about_y(angle), restitution=0.0)]
    scene = scenes.scene(f"Tip{round(degrees)}", bodies, surfaces=[scenes.floor(mus=0.8, muk=0.8)])
    v = run(slave, scene, CUBE_FILES, 3.0, names_of("mesh", "box"))
    for body, edge, x0 in (("mesh", edge_mesh, 0.0), ("box", edge_box, 2.0)):
        p = position(v, body)
        assert p[2] == pytest.approx(EDGE / 2, abs=1e-3)
        assert p[0] - edge == pytest.approx(math.copysign(EDGE / 2, x0 - edge), abs=0.02)
        turned = 2.0 * math.atan2(v[f"{body}.orientation[3]"], v[f"{body}.orientation[1]"])
        assert math.degrees(turned) == pytest.approx(0.0 if degrees < 45.0 else 90.0, abs=1.0)
    assert position(v, "mesh") - [0, 0, 0] == pytest.approx(position(v, "box") - [2.0, 0, 0], abs=1e-3)


def test_a_stack_of_mesh_cubes_rests_at_the_closed_form_heights(slave):
    """Three mesh cubes set on each other rest at EDGE/2, 3 EDGE/2 and 5 EDGE/2 within
    1 mm, straight above each other within 1 mm, still (below 1 mm/s), after 2 s; as a
    stack of primitive cubes beside it, within 1 mm."""
    bodies = []
    for k in range(3):
        z = (k + 0.5) * EDGE + k * 1e-4
        bodies.append(scenes.body(f"m{k}", shape=MESH_CUBE, position=[0.0, 0.0, z], restitution=0.0))
        bodies.append(scenes.body(f"b{k}", shape=BOX, position=[1.0, 0.0, z], restitution=0.0))
    scene = scenes.scene("MeshStack", bodies, surfaces=[scenes.floor()])
    v = run(slave, scene, CUBE_FILES, 2.0, names_of(*(b["name"] for b in bodies)))
    for k in range(3):
        m, b = position(v, f"m{k}"), position(v, f"b{k}")
        assert m == pytest.approx([0.0, 0.0, (k + 0.5) * EDGE], abs=1e-3)
        assert m - [0.0, 0, 0] == pytest.approx(b - [1.0, 0, 0], abs=1e-3)
        assert np.linalg.norm([v[f"m{k}.velocity[{i}]"] for i in (1, 2, 3)]) < 1e-3


def sliding_acceleration(s, start, down, seconds, settled):
    """The cube's acceleration down the slope: twice the leading coefficient of a
    parabola fitted to its travel from `settled` s to `seconds` s."""
    t, travel = [], []
    for k in range(round(seconds / H)):
        s.slave.doStep(k * H, H)
        t.append((k + 1) * H)
        travel.append((np.array(s.get("cube.position[1]", "cube.position[2]", "cube.position[3]")) - start) @ down)
    t, travel = np.array(t), np.array(travel)
    late = t >= settled - 1e-9
    return 2 * np.polyfit(t[late], travel[late], 2)[0]


@pytest.mark.parametrize("shape", ["mesh", "box"])
def test_a_mesh_cube_slides_down_a_ramp_at_the_closed_form_acceleration(slave, shape):
    """On a 30 deg ramp, mu_s 0.5 < tan 30 deg, a cube slides at g (sin - mu_k cos),
    mu_k = 0.3, within 1 % (a fit of its travel from 0.5 s to 2 s): the mesh cube as the
    primitive one."""
    theta = math.radians(30.0)
    q = quat_about_y(theta)
    n = np.array([math.sin(theta), 0.0, math.cos(theta)])
    down = np.array([math.cos(theta), 0.0, -math.sin(theta)])
    centre = (0.5 + EDGE / 2) * n
    cube = scenes.body("cube", shape=MESH_CUBE if shape == "mesh" else BOX, mass=2.0, position=list(centre),
                       orientation=q, staticFriction=0.5, kineticFriction=0.3, restitution=0.0)
    ramp = {"name": "ramp", "min": [-5, -1, -0.5], "max": [5, 1, 0.5], "orientation": q,
            "staticFriction": 0.5, "kineticFriction": 0.3, "restitution": 0.0}
    s = slave(scenes.scene(f"Ramp_{shape}", [cube], surfaces=[ramp]), files=CUBE_FILES)
    a = G * (math.sin(theta) - 0.3 * math.cos(theta))
    assert sliding_acceleration(s, centre, down, 2.0, 0.5) == pytest.approx(a, rel=1e-2)


def tetrahedron(a):
    """A regular tetrahedron of edge a, its base on z = 0 and its apex up, faces
    counter-clockwise seen from outside; and its height."""
    h = a * math.sqrt(2.0 / 3.0)
    vertices = [[0, 0, 0], [a, 0, 0], [a / 2, a * math.sqrt(3) / 2, 0], [a / 2, a * math.sqrt(3) / 6, h]]
    faces = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]]
    return trimesh.Trimesh(vertices, faces, process=False), h


def test_a_tetrahedron_dropped_on_its_vertex_falls_onto_a_face(slave):
    """A regular tetrahedron (edge 0.3 m) dropped apex down, tilted 0.1 rad, comes to rest
    on a face: its centre of mass h/4 above the floor within 1 mm, a face's normal (the
    body's own axes turned) pointing down within 1 deg."""
    mesh, h = tetrahedron(0.3)
    files = {"tetra.stl": stl(mesh)}
    flip = [0.0, 1.0, 0.0, 0.0]  # (w, x, y, z): half a turn about x, apex down
    q = list(quat_mul(quat_about_y(0.1), flip))
    body = scenes.body("tetra", shape={"type": "mesh", "file": "tetra.stl"}, density=2700.0,
                       position=[0.0, 0.0, 0.75 * h + 0.02], orientation=q, restitution=0.0)
    del body["mass"]
    v = run(slave, scenes.scene("Tetra", [body], surfaces=[scenes.floor()]), files, 3.0, names_of("tetra"))
    assert v["tetra.position[3]"] == pytest.approx(h / 4, abs=1e-3)
    R = rotation_matrix([v[f"tetra.orientation[{i}]"] for i in (1, 2, 3, 4)])
    normals = [np.cross(mesh.vertices[f[1]] - mesh.vertices[f[0]], mesh.vertices[f[2]] - mesh.vertices[f[0]])
               for f in mesh.faces]
    lowest = min((R @ (n / np.linalg.norm(n)))[2] for n in normals)
    assert lowest < -math.cos(math.radians(1.0))


def test_the_mass_of_a_mesh_body_comes_from_its_volume_and_density(fmu_of):
    """density 1000 kg/m^3 x (0.2 m)^3 = 8 kg, to the float32 rounding of the STL's
    coordinates (0.2 is 0.200000003 there: 4.5e-8 relative)."""
    from fmpy import read_model_description
    body = scenes.body("cube", shape=MESH_CUBE, density=1000.0)
    del body["mass"]
    md = read_model_description(str(fmu_of(scenes.scene("MeshMass", [body]), files=CUBE_FILES)))
    mass = next(v for v in md.modelVariables if v.name == "cube.mass")
    assert float(mass.start) == pytest.approx(8.0, rel=1e-7)


def build(tmp_path, scene, files):
    for name, data in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_bytes(data)
    (tmp_path / "scene.json").write_text(json.dumps(scene))
    env = dict(os.environ, RIGIDFMU_SKIP_SETUP="1", PYTHONPATH=str(ROOT / "python"))
    env.pop("LD_PRELOAD", None)
    return subprocess.run([sys.executable, "-m", "rigidfmu", "build", str(tmp_path / "scene.json"), "-o",
                           str(tmp_path / "out.fmu"), "--no-win64", "--no-build"], capture_output=True, text=True,
                          env=env)


def test_an_open_mesh_is_refused_naming_the_file_and_the_edge(tmp_path):
    box = trimesh.creation.box(extents=(EDGE, EDGE, EDGE))
    open_box = trimesh.Trimesh(box.vertices, box.faces[1:], process=False)
    run_ = build(tmp_path, scenes.scene("Open", [scenes.body("part", shape={"type": "mesh", "file": "open.stl"})]),
                 {"open.stl": stl(open_box)})
    assert run_.returncode == 1
    assert "bodies[0].shape.file: open.stl: the edge from vertex" in run_.stderr
    assert "borders no other triangle: the mesh is open" in run_.stderr


def test_a_mesh_turned_inside_out_is_refused(tmp_path):
    box = trimesh.creation.box(extents=(EDGE, EDGE, EDGE))
    inside_out = trimesh.Trimesh(box.vertices, box.faces[:, ::-1], process=False)
    run_ = build(tmp_path, scenes.scene("Inside", [scenes.body("part", shape={"type": "mesh", "file": "in.stl"})]),
                 {"in.stl": stl(inside_out)})
    assert run_.returncode == 1
    assert "bodies[0].shape.file: in.stl: the mesh is inside out" in run_.stderr


def prism(outline, depth):
    """The prism of a polygon in the xz plane (star-shaped from its first vertex),
    `depth` along y, wound outward."""
    n = len(outline)
    vertices = [(x, 0.0, z) for x, z in outline] + [(x, depth, z) for x, z in outline]
    faces = [(0, i, i + 1) for i in range(1, n - 1)] + [(n, n + i + 1, n + i) for i in range(1, n - 1)]
    for i in range(n):
        j = (i + 1) % n
        faces += [(i, n + j, j), (i, n + i, n + j)]
    mesh = trimesh.Trimesh(vertices, faces, process=False)
    return mesh if mesh.volume > 0 else trimesh.Trimesh(vertices, np.array(faces)[:, ::-1], process=False)


def test_a_concave_mesh_builds_with_a_warning_that_its_hull_collides(tmp_path):
    """An L prism (section 0.03 m^2, its hull's 0.035 m^2): the build says that the hull,
    which collides, holds 7/6 of the solid, and goes on."""
    ell = prism([(0, 0), (0.2, 0), (0.2, 0.1), (0.1, 0.1), (0.1, 0.2), (0, 0.2)], 0.1)
    run_ = build(tmp_path, scenes.scene("Ell", [scenes.body("ell", shape={"type": "mesh", "file": "ell.stl"})]),
                 {"ell.stl": stl(ell)})
    assert run_.returncode == 0, run_.stderr
    assert "bodies[0].shape.file: ell.stl: its convex hull, which collides, holds 1.16667 times" in run_.stderr


def gamma(bar):
    """A post 0.1 x 0.1 x 0.3 m standing on the floor with a bar of `bar` x 0.1 x 0.1 m on
    its top, reaching out along +x from the post's far side: the bar a mesh file (its
    corner at the file's origin, placed there), the post a primitive box. Its centre of
    mass by the parts' volumes, in the compound's frame (the post's foot's centre)."""
    post, beam = 0.1 * 0.1 * 0.3, bar * 0.1 * 0.1
    com = (post * np.array([0.0, 0.0, 0.15]) + beam * np.array([bar / 2 - 0.05, 0.0, 0.35])) / (post + beam)
    shape = {"type": "compound", "parts": [
        {"shape": {"type": "box", "size": [0.1, 0.1, 0.3]}, "position": [0.0, 0.0, 0.15]},
        {"shape": {"type": "mesh", "file": "bar.stl", "scale": [bar, 0.1, 0.1]}, "position": [-0.05, -0.05, 0.3]}]}
    corner = trimesh.creation.box(extents=(1.0, 1.0, 1.0))
    corner.apply_translation((0.5, 0.5, 0.5))
    return shape, com, {"bar.stl": stl(corner)}


@pytest.mark.parametrize("bar", [0.25, 0.35])
def test_a_compound_rests_on_the_side_its_centre_of_mass_allows(slave, bar):
    """The post's foot holds the compound while its centre of mass is above it: a bar of
    0.25 m puts it 0.0341 m out, inside the foot's 0.05 m, and it stands (within 1 mm,
    1 deg); a bar of 0.35 m puts it 0.0673 m out, and it falls over towards +x (turned
    beyond 45 deg about -y, its centre of mass moved on along +x)."""
    shape, com, files = gamma(bar)
    body = scenes.body("gamma", shape=shape, position=list(com), restitution=0.0)
    v = run(slave, scenes.scene(f"Gamma{round(bar * 100)}", [body], surfaces=[scenes.floor()]), files, 3.0,
            names_of("gamma"))
    p = position(v, "gamma")
    turned = 2.0 * math.atan2(v["gamma.orientation[3]"], v["gamma.orientation[1]"])
    if com[0] < 0.05:
        assert p == pytest.approx(com, abs=1e-3)
        assert abs(math.degrees(turned)) < 1.0
    else:
        assert math.degrees(turned) > 45.0
        assert p[0] > com[0] + 0.05


def test_the_mass_of_a_compound_is_its_parts_volumes_times_the_density(fmu_of):
    """The post (0.003 m^3) and the 0.25 m bar (0.0025 m^3) at 1000 kg/m^3: 5.5 kg."""
    shape, _, files = gamma(0.25)
    body = scenes.body("gamma", shape=shape, density=1000.0)
    del body["mass"]
    from fmpy import read_model_description
    md = read_model_description(str(fmu_of(scenes.scene("GammaMass", [body]), files=files)))
    assert float(next(v for v in md.modelVariables if v.name == "gamma.mass").start) == pytest.approx(5.5, rel=1e-7)


# ---- static mesh surfaces ---------------------------------------------------------------

def strip(length, width, along, across):
    """A flat strip in the file's xy plane, x in [-length/2, length/2], its front +z, cut
    into along x across cells of two triangles each (their seams cross a body's path)."""
    xs, ys = np.linspace(-length / 2, length / 2, along + 1), np.linspace(-width / 2, width / 2, across + 1)
    vertices = [(x, y, 0.0) for x in xs for y in ys]
    faces = []
    for i in range(along):
        for j in range(across):
            a, b, c, d = i * (across + 1) + j, (i + 1) * (across + 1) + j, (i + 1) * (across + 1) + j + 1, \
                i * (across + 1) + j + 1
            faces += [(a, b, c), (a, c, d)]
    return trimesh.Trimesh(vertices, faces, process=False)


def mesh_ramp(theta, **fields):
    """The strip of 3 x 1 m in 24 triangles, turned by theta about y: it descends
    towards +x."""
    return {"name": "ramp", "mesh": {"file": "ramp.stl"}, "orientation": quat_about_y(theta), **fields}


RAMP_FILES = {"ramp.stl": stl(strip(3.0, 1.0, 6, 2)), **CUBE_FILES}


def test_a_box_slides_down_a_mesh_ramp_at_the_closed_form_acceleration(slave):
    """The cube on the 30 deg mesh ramp (mu_s 0.5 < tan 30 deg, mu_k 0.3) slides at
    g (sin - mu_k cos) within 1 %, over the ramp's seams."""
    theta = math.radians(30.0)
    n = np.array([math.sin(theta), 0.0, math.cos(theta)])
    down = np.array([math.cos(theta), 0.0, -math.sin(theta)])
    start = -1.0 * down + (EDGE / 2) * n
    cube = scenes.body("cube", shape=BOX, mass=2.0, position=list(start), orientation=quat_about_y(theta),
                       staticFriction=0.5, kineticFriction=0.3, restitution=0.0)
    ramp = mesh_ramp(theta, staticFriction=0.5, kineticFriction=0.3, restitution=0.0)
    s = slave(scenes.scene("MeshRamp", [cube], surfaces=[ramp]), files=RAMP_FILES)
    a = G * (math.sin(theta) - 0.3 * math.cos(theta))
    assert sliding_acceleration(s, start, down, 1.0, 0.3) == pytest.approx(a, rel=1e-2)


def test_a_ball_rolls_down_a_mesh_chute_at_the_speed_energy_gives(slave):
    """A ball set at rest on the 20 deg mesh chute rolls without slipping (mu_s 0.6 >
    2/7 tan 20 deg) over its seams: having come s down the slope, v^2 = 10/7 g s sin 20 deg
    within 1 % in speed, to the chute's end, where it leaves it at that speed."""
    theta, r = math.radians(20.0), 0.05
    n = np.array([math.sin(theta), 0.0, math.cos(theta)])
    down = np.array([math.cos(theta), 0.0, -math.sin(theta)])
    start = -1.4 * down + r * n
    ball = scenes.body("ball", shape={"type": "sphere", "radius": r}, position=list(start), staticFriction=0.6,
                       kineticFriction=0.5, restitution=0.0)
    chute = mesh_ramp(theta, staticFriction=0.6, kineticFriction=0.5, restitution=0.0)
    s = slave(scenes.scene("MeshChute", [ball], surfaces=[chute]), files=RAMP_FILES)
    checked = 0
    for k in range(round(2.0 / 0.01)):
        s.slave.doStep(k * 0.01, 0.01)
        travel = (np.array(s.get("ball.position[1]", "ball.position[2]", "ball.position[3]")) - start) @ down
        if travel > 2.9:  # the chute's end (1.5 m down from its middle) is 2.9 m from the start
            break
        if travel > 0.1:
            v = np.linalg.norm(s.get("ball.velocity[1]", "ball.velocity[2]", "ball.velocity[3]"))
            assert v == pytest.approx(math.sqrt(10 / 7 * G * travel * math.sin(theta)), rel=1e-2)
            checked += 1
    assert checked > 50 and travel > 2.8


@pytest.mark.parametrize("shape, height", [
    ({"type": "sphere", "radius": 0.1}, 0.1),
    (BOX, EDGE / 2),
    ({"type": "cylinder", "radius": 0.1, "length": 0.3}, 0.15),
    ({"type": "capsule", "radius": 0.05, "length": 0.2}, 0.05),
    (MESH_CUBE, EDGE / 2),
])
def test_every_shape_rests_on_a_mesh_floor_at_its_height(slave, shape, height):
    """Set down a little above a flat mesh floor of 24 triangles, off its seams' lines,
    a body of each shape rests with its centre at its closed-form height within 1 mm:
    a sphere r, a cube half its edge, a cylinder on end half its length, a capsule on its
    side its radius."""
    lying = [math.cos(math.pi / 4), math.sin(math.pi / 4), 0.0, 0.0] if shape["type"] == "capsule" else [1, 0, 0, 0]
    body = scenes.body("body", shape=shape, position=[0.13, 0.07, height + 0.01], orientation=lying,
                       restitution=0.0)
    floor = {"name": "floor", "mesh": {"file": "ramp.stl"}, "restitution": 0.0}
    v = run(slave, scenes.scene(f"MeshFloor_{shape['type']}", [body], surfaces=[floor]), RAMP_FILES, 1.0,
            names_of("body"))
    assert position(v, "body") == pytest.approx([0.13, 0.07, height], abs=1e-3)


def test_check_says_where_a_mesh_files_origin_lies_in_the_body_frame(tmp_path):
    """A box file from (0, 0, 0) to (1, 1, 1), scaled by 0.2: its centre of mass at
    (0.1, 0.1, 0.1) in the scaled file's frame, so the file's origin at (-0.1, -0.1, -0.1)
    in the body frame."""
    corner = trimesh.creation.box(extents=(1.0, 1.0, 1.0))
    corner.apply_translation((0.5, 0.5, 0.5))
    (tmp_path / "corner.stl").write_bytes(stl(corner))
    body = scenes.body("part", shape={"type": "mesh", "file": "corner.stl", "scale": 0.2})
    (tmp_path / "scene.json").write_text(json.dumps(scenes.scene("Corner", [body])))
    env = dict(os.environ, RIGIDFMU_SKIP_SETUP="1", PYTHONPATH=str(ROOT / "python"))
    env.pop("LD_PRELOAD", None)
    run_ = subprocess.run([sys.executable, "-m", "rigidfmu", "check", str(tmp_path / "scene.json")],
                          capture_output=True, text=True, env=env)
    assert run_.returncode == 0, run_.stderr
    line = next(line for line in run_.stdout.splitlines() if "bodies[0] part" in line)
    origin = [float(x) for x in line.split("(")[1].split(")")[0].split(",")]
    assert origin == pytest.approx([-0.1, -0.1, -0.1], abs=1e-8)  # (float32 coordinates in the STL)
    assert "the file's origin lies at" in line
