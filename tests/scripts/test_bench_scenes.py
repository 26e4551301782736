"""The benchmark's wide pile differs from the cube-root piles in its layout only, so that
the growth it measures from the pile of 100 is that of N at equal height (bench.py's
"Equal height" rows)."""
import json

import numpy as np
import pytest
from reports import mesh_scenes
from reports import scenes as bench


def _without(body, *keys):
    return {k: v for k, v in body.items() if k not in keys}


def test_wide_pile_is_the_pile_of_100_on_a_wider_grid():
    wide, small = bench.pile_wide_scene(bench.WIDE_PILE), bench.pile_scene(100)
    assert len(wide["bodies"]) == bench.WIDE_PILE
    # the same cubes (shape, mass, friction, restitution), floor, step and solver
    assert {str(_without(b, "name", "position", "orientation")) for b in wide["bodies"]} == \
        {str(_without(small["bodies"][0], "name", "position", "orientation"))}
    assert wide["surfaces"] == small["surfaces"] and wide["solver"] == small["solver"]
    # columns as tall as the pile of 100's: 4 layers, 16 x 16 columns (5 x 5 for 100)
    for scene, layers, side in ((wide, bench.WIDE_LAYERS, 16), (small, 4, 5)):
        z = {round(b["position"][2], 9) for b in scene["bodies"]}
        xy = {(round(b["position"][0], 9), round(b["position"][1], 9)) for b in scene["bodies"]}
        assert len(z) == layers and len(xy) == side * side


def test_columns_of_four_lay_out_the_pile_of_100_as_before():
    assert bench.pile_layout(100, layers=4) == bench.pile_layout(100)
    assert len({round(p[2], 9) for p, _ in bench.pile_layout(1000)}) == 10  # the tall pile: columns of 10


def test_another_tilt_pattern_moves_no_cube_and_turns_them_otherwise():
    base, other = bench.pile_layout(1000), bench.pile_layout(1000, tilt=(1.3, 2.9))
    assert [p for p, _ in other] == [p for p, _ in base]
    assert sum(t != u for (_, t), (_, u) in zip(base, other)) > 990  # cube 0's tilt is the same
    assert max(max(abs(a) for a in t) for _, t in other) <= 0.05  # as small as the default's


def test_tilt_option_writes_the_piles_with_that_pattern(tmp_path):
    bench.main([str(tmp_path), "--tilt", "1.3,2.9"])
    written = json.loads((tmp_path / "pile_100.json").read_text())
    assert written == bench.pile_scene(100, tilt=(1.3, 2.9))
    assert written["bodies"] != bench.pile_scene(100)["bodies"]


@pytest.mark.parametrize("tilt", ["1.3", "a,b", "nan,1", "1,2,3"])
def test_malformed_tilt_is_refused_with_what_it_takes(tmp_path, tilt):
    with pytest.raises(SystemExit) as refused:
        bench.main([str(tmp_path), "--tilt", tilt])
    assert "two finite frequencies" in str(refused.value)
    assert not list(tmp_path.iterdir())


def test_tumbling_bodies_are_the_free_ones_with_collisions_on():
    free, tumbling = bench.free_scene(100), bench.tumbling_scene(100)
    assert [_without(b, "collision") for b in tumbling["bodies"]] == [_without(b, "collision") for b in free["bodies"]]
    assert all(b["collision"] for b in tumbling["bodies"]) and not any(b["collision"] for b in free["bodies"])
    # 3 m apart: the nearest two centres farther than twice a body's half diagonal
    xy = [b["position"] for b in tumbling["bodies"]]
    nearest = min(((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2) ** 0.5 for i, a in enumerate(xy) for b in xy[i + 1:])
    assert nearest >= 3.0 > 2 * (0.15 ** 2 + 0.1 ** 2 + 0.05 ** 2) ** 0.5


def test_mesh_scenes_hulls_have_the_issues_vertex_counts(tmp_path):
    """Every point of a hull scene's lattice is a vertex of its hull, so a hull of N points
    has N vertices as the core reads it (FILE.mesh.json); the pebble's too."""
    mesh_scenes.write(tmp_path)
    for n in mesh_scenes.HULL_VERTICES:
        written = json.loads((tmp_path / f"hull_{n}.stl.mesh.json").read_text())
        assert len(written["hull"]["vertices"]) == n
        scene = json.loads((tmp_path / f"narrow_hull_{n}.json").read_text())
        assert [b["shape"] for b in scene["bodies"]] == [{"type": "mesh", "file": f"hull_{n}.stl"}] * 2
    pebble = json.loads((tmp_path / "pebble.stl.mesh.json").read_text())
    assert len(pebble["hull"]["vertices"]) == mesh_scenes.PILE_HULL_VERTICES


def test_pile_of_pebbles_is_the_pile_of_cubes_with_meshes_in_their_places(tmp_path):
    pebbles = mesh_scenes.pile_hulls_scene(100, "pebble.stl", 0.25)
    cubes = bench.pile_scene(100)
    assert [b["position"] for b in pebbles["bodies"]] == [b["position"] for b in cubes["bodies"]]
    assert {str(_without(b, "name", "position", "orientation", "shape", "mass")) for b in pebbles["bodies"]} == \
        {str(_without(cubes["bodies"][0], "name", "position", "orientation", "shape", "mass"))}
    assert pebbles["solver"]["step"] == cubes["solver"]["step"]
    assert all(b["shape"] == {"type": "mesh", "file": "pebble.stl"} for b in pebbles["bodies"])
    # the floor replaced by the bin, with the floor's friction and restitution
    (floor,), (box,) = cubes["surfaces"], pebbles["surfaces"]
    assert box["mesh"] == {"file": "bin.stl", "scale": 1, "thickness": mesh_scenes.BIN_THICKNESS}
    assert all(box[k] == floor[k] for k in ("staticFriction", "kineticFriction", "restitution"))


def test_the_bin_is_an_open_box_facing_inwards_with_seams(tmp_path):
    """bin.stl: the floor (its top at the floor's, z = 0) and four walls of BIN_SIZE, every
    triangle's front (counter-clockwise side) towards the inside, each face a grid of
    BIN_CELLS x BIN_CELLS squares; the pile starts inside it."""
    mesh_scenes.write(tmp_path)
    written = json.loads((tmp_path / "bin.stl.mesh.json").read_text())
    v, t = np.array(written["vertices"]), np.array(written["triangles"])
    x, y, z = mesh_scenes.BIN_SIZE
    assert np.allclose(v.min(axis=0), [-x / 2, -y / 2, 0]) and np.allclose(v.max(axis=0), [x / 2, y / 2, z])
    assert len(t) == 5 * 2 * mesh_scenes.BIN_CELLS ** 2
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    fronts = np.cross(b - a, c - a)
    centres = (a + b + c) / 3
    assert (np.einsum("ij,ij->i", fronts, np.array([0, 0, z / 2]) - centres) > 0).all()
    # no triangle on top: the bin is open
    assert not (np.isclose(v[t], z).all(axis=(1, 2))).any()
    scene = json.loads((tmp_path / "pile_hulls_100.json").read_text())
    for b in scene["bodies"]:
        px, py, pz = b["position"]
        assert abs(px) + max(mesh_scenes.PILE_HULL_AXES) < x / 2 and abs(py) + max(mesh_scenes.PILE_HULL_AXES) < y / 2
        assert pz - max(mesh_scenes.PILE_HULL_AXES) > 0
