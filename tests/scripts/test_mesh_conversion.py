"""Mesh files read when an FMU is built (python/rigidfmu/meshes.py and
mesh_conversion.py, decision 0006): the FILE.mesh.json of meshes made with trimesh
itself in every format, against closed forms (counts, volumes, outward faces); the path
rule's refusals, each naming the field; the resources staged for a scene, and the FMU
that carries them (with a stand-in core: the core's mesh reading is the core's tests)."""
import json
import pathlib
import zipfile

import numpy as np
import pytest
import trimesh

from rigidfmu import fmu_package, mesh_conversion, meshes, native
from rigidfmu.errors import SceneError

FIELD = "bodies[0].shape.file"
EXTENTS = (0.5, 1.5, 2.0)  # exact in float32 (binary STL) and in OBJ's 8 decimals
FORMATS = {"binary.stl": "stl", "ascii.stl": "stl_ascii", "box.obj": "obj"}
TETRAHEDRON = ([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
               [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])  # counter-clockwise seen from outside


def export(mesh: trimesh.Trimesh, path: pathlib.Path, file_type: str) -> pathlib.Path:
    mesh.export(str(path), file_type=file_type)
    return path


def converted(path: pathlib.Path, source: str = "part") -> dict:
    return json.loads(mesh_conversion.convert(path, source, FIELD))


def signed_volume(vertices, triangles) -> float:
    """Divergence theorem: the sum of the tetrahedra from the origin to each triangle,
    positive when the triangles are wound counter-clockwise seen from outside."""
    v = np.asarray(vertices)[np.asarray(triangles)]
    return float(np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6.0)


def newell_normal(points) -> np.ndarray:
    p = np.asarray(points)
    q = np.roll(p, -1, axis=0)
    return np.array([((p[:, 1] - q[:, 1]) * (p[:, 2] + q[:, 2])).sum(),
                     ((p[:, 2] - q[:, 2]) * (p[:, 0] + q[:, 0])).sum(),
                     ((p[:, 0] - q[:, 0]) * (p[:, 1] + q[:, 1])).sum()])


def outward_normals(hull: dict) -> list[np.ndarray]:
    """Each hull face's Newell normal, checked to point away from the hull's centroid
    (the face counter-clockwise seen from outside)."""
    points = np.array(hull["vertices"])
    centroid = points.mean(axis=0)
    normals = [newell_normal(points[face]) for face in hull["faces"]]
    for face, normal in zip(hull["faces"], normals):
        assert normal @ (points[face].mean(axis=0) - centroid) > 0, face
    return normals


def box(tmp_path, name="binary.stl") -> pathlib.Path:
    return export(trimesh.creation.box(extents=EXTENTS), tmp_path / name, FORMATS[name])


@pytest.mark.parametrize("name", FORMATS)
def test_a_box_gives_its_8_vertices_12_triangles_and_a_hull_of_6_quads(tmp_path, name):
    mesh = converted(box(tmp_path, name))
    assert (mesh["format"], mesh["version"], mesh["source"]) == ("rigidfmu-mesh", 1, "part")
    half = np.array(EXTENTS) / 2
    corners = {tuple(s * half) for s in np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1])).T.reshape(-1, 3)}
    assert len(mesh["vertices"]) == 8 and {tuple(v) for v in mesh["vertices"]} == corners
    assert len(mesh["triangles"]) == 12
    assert signed_volume(mesh["vertices"], mesh["triangles"]) == pytest.approx(np.prod(EXTENTS), rel=1e-12)
    hull = np.array(mesh["hull"]["vertices"])
    assert {tuple(v) for v in hull} == corners
    faces = mesh["hull"]["faces"]
    assert len(faces) == 6 and all(len(f) == 4 and len(set(f)) == 4 for f in faces)
    outward = {tuple(np.round(n / np.linalg.norm(n), 12) + 0.0) for n in outward_normals(mesh["hull"])}
    assert outward == {tuple(s * e) for e in np.eye(3) for s in (1.0, -1.0)}


def test_the_three_formats_of_one_box_give_the_same_bytes(tmp_path):
    files = {mesh_conversion.convert(box(tmp_path, name), "part", FIELD) for name in FORMATS}
    assert len(files) == 1


def test_the_winding_is_kept_as_the_file_gives_it(tmp_path):
    """An inside-out box is not turned back: its volume comes out negative."""
    inside_out = trimesh.creation.box(extents=EXTENTS)
    inside_out = trimesh.Trimesh(inside_out.vertices, inside_out.faces[:, ::-1], process=False)
    mesh = converted(export(inside_out, tmp_path / "inside_out.stl", "stl"))
    assert signed_volume(mesh["vertices"], mesh["triangles"]) == pytest.approx(-np.prod(EXTENTS), rel=1e-12)
    assert len(mesh["hull"]["faces"]) == 6  # the hull is the points', whatever the winding


def test_an_open_mesh_is_converted_as_it_is(tmp_path):
    whole = trimesh.creation.box(extents=EXTENTS)
    open_box = trimesh.Trimesh(whole.vertices, whole.faces[1:], process=False)
    mesh = converted(export(open_box, tmp_path / "open.stl", "stl"))
    assert len(mesh["vertices"]) == 8 and len(mesh["triangles"]) == 11
    given = {tuple(map(tuple, whole.vertices[t])) for t in whole.faces[1:]}
    got = {tuple(tuple(mesh["vertices"][i]) for i in t) for t in mesh["triangles"]}
    assert got == given  # each triangle with its vertices in the file's order


def test_a_flat_sheet_has_no_hull(tmp_path):
    sheet = trimesh.Trimesh([[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]], [[0, 1, 2], [0, 2, 3]], process=False)
    mesh = converted(export(sheet, tmp_path / "floor.stl", "stl"))
    assert len(mesh["vertices"]) == 4 and len(mesh["triangles"]) == 2
    assert "hull" not in mesh
    assert signed_volume(mesh["vertices"], mesh["triangles"]) == 0.0


# the icosahedron of trimesh.creation.icosphere(subdivisions=0): circumradius 1, edge
# a = 4 / sqrt(10 + 2 sqrt 5), volume 5 (3 + sqrt 5) a^3 / 12
ICOSAHEDRON_VOLUME = 5 * (3 + 5 ** 0.5) / 12 * (4 / (10 + 2 * 5 ** 0.5) ** 0.5) ** 3


@pytest.mark.parametrize("solid, count, volume", [
    (lambda: trimesh.Trimesh(*TETRAHEDRON, process=False), (4, 4), 1 / 6),
    (lambda: trimesh.creation.icosphere(subdivisions=0), (12, 20), ICOSAHEDRON_VOLUME),
], ids=["tetrahedron", "icosahedron"])
def test_a_solid_without_coplanar_faces_has_its_triangles_as_hull(tmp_path, solid, count, volume):
    vertices, faces = count
    mesh = converted(export(solid(), tmp_path / "solid.obj", "obj"))
    assert len(mesh["vertices"]) == vertices and len(mesh["triangles"]) == faces
    assert signed_volume(mesh["vertices"], mesh["triangles"]) == pytest.approx(volume, rel=1e-7)  # OBJ's 8 decimals
    assert len(mesh["hull"]["vertices"]) == vertices
    assert sorted(map(len, mesh["hull"]["faces"])) == [3] * faces
    assert len(outward_normals(mesh["hull"])) == faces


def test_two_conversions_give_the_same_bytes(tmp_path):
    path = export(trimesh.creation.icosphere(subdivisions=2), tmp_path / "ball.stl", "stl")
    assert mesh_conversion.convert(path, "ball.stl", FIELD) == mesh_conversion.convert(path, "ball.stl", FIELD)


def test_an_unreadable_file_is_refused_naming_the_field_and_the_file(tmp_path):
    (tmp_path / "bad.stl").write_bytes(bytes(range(256)) * 3)
    with pytest.raises(SceneError) as refused:
        mesh_conversion.convert(tmp_path / "bad.stl", "parts/bad.stl", FIELD)
    assert str(refused.value).startswith(f'{FIELD}: trimesh cannot read "parts/bad.stl": ')


def scene_with_body_mesh(tmp_path, file) -> pathlib.Path:
    scene = tmp_path / "scene.json"
    scene.write_text(json.dumps({"name": "M", "bodies": [
        {"name": "a", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1},
        {"name": "b", "shape": {"type": "mesh", "file": file}, "mass": 1}]}))
    return scene


RULE = 'bodies[1].shape.file: must be a path inside the scene\'s folder (relative, no "..", "/" separators), got "{}"'


@pytest.mark.parametrize("file", ["../x.stl", "parts/../../x.stl", "/x.stl", "parts\\x.stl", "C:/x.stl", "c:x.stl",
                                  ""])
def test_a_path_outside_the_rule_is_refused_naming_the_field(tmp_path, file):
    folder = tmp_path / "scene"
    (folder / "parts").mkdir(parents=True)
    box(folder / "parts")  # parts/binary.stl: the rule refuses before the file is looked for
    box(tmp_path)  # ../x.stl and /x.stl would find a file
    (tmp_path / "binary.stl").rename(tmp_path / "x.stl")
    with pytest.raises(SceneError) as refused:
        meshes.stage_resources(scene_with_body_mesh(folder, file), tmp_path / "resources")
    assert str(refused.value) == RULE.format(file)


def test_an_absolute_path_to_an_existing_file_is_refused(tmp_path):
    path = box(tmp_path)
    with pytest.raises(SceneError) as refused:
        meshes.stage_resources(scene_with_body_mesh(tmp_path, str(path)), tmp_path / "resources")
    assert str(refused.value) == RULE.format(path)


def test_a_missing_file_is_refused_naming_the_field(tmp_path):
    with pytest.raises(SceneError) as refused:
        meshes.stage_resources(scene_with_body_mesh(tmp_path, "parts/x.stl"), tmp_path / "resources")
    assert str(refused.value) == 'bodies[1].shape.file: no file "parts/x.stl" beside the scene'


def test_an_unreadable_file_in_a_scene_is_refused_naming_the_field(tmp_path):
    (tmp_path / "bad.stl").write_bytes(b"\xff\xfe not a mesh \x00\x01")
    with pytest.raises(SceneError) as refused:
        meshes.stage_resources(scene_with_body_mesh(tmp_path, "bad.stl"), tmp_path / "resources")
    assert str(refused.value).startswith('bodies[1].shape.file: trimesh cannot read "bad.stl": ')


def test_the_resources_hold_the_scene_as_given_and_each_mesh_once_with_its_json(tmp_path, monkeypatch):
    folder = tmp_path / "scene"
    (folder / "parts").mkdir(parents=True)
    box(folder / "parts")
    export(trimesh.Trimesh(*TETRAHEDRON, process=False), folder / "parts" / "tet.obj", "obj")
    sheet = trimesh.Trimesh([[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]], [[0, 1, 2], [0, 2, 3]], process=False)
    export(sheet, folder / "floor.stl", "stl")
    tet = {"type": "mesh", "file": "parts/tet.obj", "scale": 0.5}
    scene = {"name": "M", "bodies": [
        {"name": "a", "shape": {"type": "mesh", "file": "parts/binary.stl", "scale": [1, 2, 3]}, "mass": 1},
        {"name": "b", "shape": {"type": "compound", "parts": [
            {"shape": {"type": "sphere", "radius": 0.1}, "position": [0, 0, 0]},
            {"shape": tet, "position": [1, 0, 0]}, {"shape": tet, "position": [-1, 0, 0]}]}, "mass": 1}],
        "surfaces": [{"name": "bin", "mesh": {"file": "floor.stl", "scale": 1}, "position": [0, 0, 0]}]}
    text = json.dumps(scene, indent=3) + "\n\n"  # a rewritten scene would lose the spacing
    (folder / "my scene.json").write_text(text)
    assert [(r.field, r.file) for r in meshes.mesh_references(scene)] == [
        ("bodies[0].shape.file", "parts/binary.stl"), ("bodies[1].shape.parts[1].shape.file", "parts/tet.obj"),
        ("bodies[1].shape.parts[2].shape.file", "parts/tet.obj"), ("surfaces[0].mesh.file", "floor.stl")]

    calls = []
    convert = mesh_conversion.convert
    monkeypatch.setattr(mesh_conversion, "convert", lambda *args: calls.append(args[1]) or convert(*args))
    resources = tmp_path / "resources"
    written = meshes.stage_resources(folder / "my scene.json", resources)
    names = ["floor.stl", "floor.stl.mesh.json", "parts/binary.stl", "parts/binary.stl.mesh.json", "parts/tet.obj",
             "parts/tet.obj.mesh.json", "scene.json"]
    assert written == names
    assert sorted(p.relative_to(resources).as_posix() for p in resources.rglob("*") if p.is_file()) == names
    assert sorted(calls) == ["floor.stl", "parts/binary.stl", "parts/tet.obj"]
    assert (resources / "scene.json").read_text() == text
    for name in ("floor.stl", "parts/binary.stl", "parts/tet.obj"):
        assert (resources / name).read_bytes() == (folder / name).read_bytes()
        assert (resources / f"{name}.mesh.json").read_bytes() == convert(folder / name, name, "x")
    assert "hull" not in json.loads((resources / "floor.stl.mesh.json").read_text())

    again = tmp_path / "again"
    assert meshes.stage_resources(folder / "my scene.json", again) == names
    for name in names:
        assert (again / name).read_bytes() == (resources / name).read_bytes(), name


def test_a_scene_without_meshes_stages_its_file_alone(tmp_path):
    scene = tmp_path / "plain.json"
    scene.write_text('{"name": "P", "bodies": [{"name": "a", "shape": {"type": "sphere", "radius": 0.1}}]}')
    assert meshes.stage_resources(scene, tmp_path / "resources") == ["scene.json"]
    assert (tmp_path / "resources" / "scene.json").read_bytes() == scene.read_bytes()
    assert [p.name for p in (tmp_path / "resources").iterdir()] == ["scene.json"]


FAKE_DESCRIBE = """#!/bin/sh
# rigidfmu-describe SCENE OUT --fmi N, as a core that reads the staged mesh files: the
# scene named "Refused" is refused naming its staged mesh file, any other is described.
folder=$(dirname "$1")
test -f "$folder/parts/binary.stl.mesh.json" || { echo "$1: no staged mesh" >&2; exit 1; }
if grep -q Refused "$1"; then echo "$1: bodies[0].shape.file: $folder/parts/binary.stl.mesh.json: open" >&2; exit 1; fi
echo '<fmiModelDescription/>' > "$2/modelDescription.xml"; echo M > "$2/model_identifier"; echo 0 > "$2/modules"
"""


@pytest.fixture
def fake_core(tmp_path):
    """A stand-in for the core's binaries (the core's mesh reading is tested with the core)."""
    core = tmp_path / "core"
    core.mkdir()
    (core / "rigidfmu-describe").write_text(FAKE_DESCRIBE)
    (core / "rigidfmu-describe").chmod(0o755)
    (core / "rigidfmu_fmi2_0.so").write_bytes(b"library")
    return native.Native(core)


def mesh_scene(folder: pathlib.Path, name: str) -> pathlib.Path:
    (folder / "parts").mkdir(parents=True)
    box(folder / "parts")
    scene = folder / "m.json"
    scene.write_text(json.dumps({"name": name, "bodies": [{"name": "a", "shape": {"type": "mesh",
                                                                                "file": "parts/binary.stl"}}]}))
    return scene


def test_the_core_checks_the_staged_scene_and_its_message_names_the_users_files(tmp_path, fake_core):
    scene = mesh_scene(tmp_path / "user", "Refused")
    with pytest.raises(SceneError) as refused:
        fmu_package.describe(scene, fake_core)
    assert str(refused.value) == f"{scene}: bodies[0].shape.file: {scene.parent}/parts/binary.stl.mesh.json: open"


def test_the_fmu_carries_the_staged_resources(tmp_path, fake_core, monkeypatch):
    monkeypatch.setattr(fmu_package, "runtime_dependencies", lambda library: [])  # not a real library
    scene = mesh_scene(tmp_path / "user", "M")
    fmu_package.package(scene, tmp_path / "m.fmu", fake_core)
    with zipfile.ZipFile(tmp_path / "m.fmu") as z:
        assert z.namelist() == ["modelDescription.xml", "binaries/linux64/M.so", "resources/parts/binary.stl",
                                "resources/parts/binary.stl.mesh.json", "resources/scene.json"]
        assert z.read("resources/scene.json") == scene.read_bytes()
        assert z.read("resources/parts/binary.stl.mesh.json") == mesh_conversion.convert(
            scene.parent / "parts/binary.stl", "parts/binary.stl", FIELD)
