"""The run's outputs for people: `rigidfmu simulate --plot`'s figures, and the 3D
replay page that replay.sh writes, self-contained, and that headless chromium opens with no error,
shows every body in its palette colour and moves the bodies with the time slider. A run
of scripts/scenes/pusher.json keeps its driven pusher and driven surface lift: their
poses in the CSV, out of the energy, in the replay as bodies of their own colour. Mesh
bodies (STL files made with trimesh) reach the page as their triangles in the body
frame, moved by the solid's centroid (closed forms of a box and a tetrahedron), and a
compound's parts are moved by the compound's."""
import colorsys
import csv
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest
import trimesh
from PIL import Image

from rigidfmu.errors import ReplayError
from rigidfmu.plots import energy_note
from rigidfmu.replay import DRIVEN_COLOUR, colour_of, read_result, write_replay
from rigidfmu.scenes import body, scene

pytestmark = pytest.mark.slow  # a whole script or browser run (pyproject.toml)

ROOT = pathlib.Path(__file__).resolve().parents[2]
ENV = dict(os.environ, RIGIDFMU_SKIP_SETUP="1")
CHROMIUM = os.environ.get("CHROMIUM", "/usr/bin/chromium")
STOP_TIME = 1.0
PUSHER = ROOT / "scripts" / "scenes" / "pusher.json"
PUSHER_STOP_TIME = 0.2


def colours_scene():
    """Three bodies of three shapes that all move in the first second (a ball dropped on
    the floor, a brick tossed with spin, a capsule thrown up), a floor, and a pool
    beside it that nothing enters, so that it is drawn without tinting a body."""
    s = scene("ReplayColours", [
        body("ball", {"type": "sphere", "radius": 0.25}, position=[-1.5, 0, 1.5]),
        body("brick", {"type": "box", "size": [0.6, 0.3, 0.3]}, position=[0, -0.5, 0.5],
             velocity=[1.5, 0, 3], angularVelocity=[0, 4, 0]),
        body("rod", {"type": "capsule", "radius": 0.1, "length": 0.5}, position=[1.5, 0.8, 0.6],
             velocity=[-0.5, 0, 2.5], angularVelocity=[3, 0, 0]),
    ])
    s["surfaces"] = [{"name": "floor", "min": [-3, -2, -0.2], "max": [3, 2, 0]}]
    s["media"] = [{"name": "pool", "type": "water", "min": [-3, 2.5, -1], "max": [3, 4, 0]}]
    return s


@pytest.fixture(scope="module")
def run(fmu_of, tmp_path_factory):
    """A simulated run (CSV and plots by `rigidfmu simulate`) and its replay by replay.sh."""
    out = tmp_path_factory.mktemp("replay")
    s = colours_scene()
    scene_file = out / "scene.json"
    scene_file.write_text(json.dumps(s))
    fmu = fmu_of(s)
    printed = subprocess.run([sys.executable, "-m", "rigidfmu", "simulate", str(fmu), "--plot",
                              "--stop-time", str(STOP_TIME), "--output-interval", "0.02",
                              "--out", str(out)],
                             check=True, capture_output=True, text=True, env=ENV).stdout
    csv = out / f"{fmu.stem}.csv"
    # no OUT.html: the page goes beside the CSV
    subprocess.run([str(ROOT / "scripts" / "replay.sh"), str(csv), str(scene_file)],
                   check=True, capture_output=True, env=ENV)
    return {"dir": out, "scene": s, "csv": csv, "html": csv.with_suffix(".html"), "printed": printed}


def test_simulate_writes_the_four_plots(run):
    for kind in ("position", "velocity", "energy", "contacts"):
        png = run["csv"].with_name(f"{run['csv'].stem}_{kind}.png")
        assert str(png) in run["printed"].splitlines()
        with Image.open(png) as image:
            assert image.width >= 600 and image.height >= 150


def test_replay_sh_writes_one_self_contained_page(run):
    html = run["html"].read_text()
    assert 100_000 < len(html) < 3_000_000
    # nothing fetched: no script, stylesheet, image or module from anywhere
    assert not re.search(r"<(script|link|img|iframe)\b[^>]*\b(src|href)\s*=", html, re.I)
    assert not re.search(r"""(src|href)\s*=\s*["']?https?://""", html, re.I)
    assert not re.search(r"\bimport\s*\(|\bfrom\s*['\"]https?:", html)
    data = replay_data(html)
    assert [b["name"] for b in data["bodies"]] == ["ball", "brick", "rod"]
    assert [b["colour"] for b in data["bodies"]] == [colour_of(k) for k in range(3)]
    frames = len(data["time"])
    assert frames == round(STOP_TIME / 0.02) + 1
    assert all(len(b["position"]) == 3 * frames and len(b["orientation"]) == 4 * frames
               and len(b["contacts"]) == frames for b in data["bodies"])
    assert data["up"] == [0.0, 0.0, 1.0]
    assert [s["name"] for s in data["surfaces"]] == ["floor"]
    assert [m["name"] for m in data["media"]] == ["pool"]


def replay_data(html):
    """The run embedded in a replay page (rigidfmu.replay's JSON)."""
    return json.loads(re.search(r'<script id="replay-data" type="application/json">(.*?)</script>',
                                html, re.S).group(1))


def body_pixels(png, colour, saturation=0.45):
    """(count, centroid x, centroid y) of the pixels whose hue is the colour's, within
    12 degrees, and that are saturated and bright enough to be the body and not the
    grey floor or the pale water: shading changes a lit body's brightness, not its hue.
    The driven bodies' slate is less saturated than the palette: a lower `saturation`."""
    hsv = np.asarray(Image.open(png).convert("RGB").convert("HSV"), dtype=float)
    r, g, b = (int(colour[i:i + 2], 16) / 255 for i in (1, 3, 5))
    hue = colorsys.rgb_to_hsv(r, g, b)[0] * 255
    dh = np.abs(hsv[..., 0] - hue)
    match = ((np.minimum(dh, 255 - dh) <= 12 / 360 * 255)
             & (hsv[..., 1] >= saturation * 255) & (hsv[..., 2] >= 0.2 * 255))
    ys, xs = np.nonzero(match)
    return len(xs), (xs.mean() if len(xs) else np.nan), (ys.mean() if len(ys) else np.nan)


def snapshots(html, shots):
    """The page's screenshots at the first and the last frame (snapshot.mjs's report)."""
    snapshot = ROOT / "python" / "rigidfmu" / "replay" / "page" / "snapshot.mjs"
    printed = subprocess.run(["node", str(snapshot), str(html), str(shots), "0", "last"],
                             check=True, capture_output=True, text=True, timeout=120).stdout
    return json.loads(printed.strip().splitlines()[-1])


BROWSER = pytest.mark.skipif(not (os.access(CHROMIUM, os.X_OK) and shutil.which("node")),
                             reason=f"no {CHROMIUM} or node (scripts/setup.sh installs Debian's chromium)")


@BROWSER
def test_page_shows_the_bodies_and_the_slider_moves_them(run):
    report = snapshots(run["html"], run["dir"] / "shots")
    assert report["errors"] == []
    first, last = (pathlib.Path(p) for p in report["screenshots"])
    assert report["frames"] == [0, round(STOP_TIME / 0.02)]
    for k, b in enumerate(run["scene"]["bodies"]):
        n0, x0, y0 = body_pixels(first, colour_of(k))
        n1, x1, y1 = body_pixels(last, colour_of(k))
        assert n0 >= 40 and n1 >= 40, f"{b['name']} ({colour_of(k)}): {n0} and {n1} pixels"
        moved = np.hypot(x1 - x0, y1 - y0)
        assert moved > 5, f"{b['name']} moved {moved:.1f} px on the screen"


# ---- driven bodies: scripts/scenes/pusher.json ------------------------------------------

DRIVEN = ("pusher", "lift")  # a driven body and a driven surface


@pytest.fixture(scope="module")
def pusher_run(tmp_path_factory):
    """`rigidfmu simulate scripts/scenes/pusher.json --plot --replay`, with no master:
    the driven inputs keep their start values."""
    out = tmp_path_factory.mktemp("pusher")
    printed = subprocess.run([sys.executable, "-m", "rigidfmu", "simulate", str(PUSHER), "--plot", "--replay",
                              "--no-win64", "--stop-time", str(PUSHER_STOP_TIME), "--out", str(out)],
                             check=True, capture_output=True, text=True, env=ENV).stdout
    return {"dir": out, "csv": out / "pusher.csv", "html": out / "pusher.html", "printed": printed}


def pose_columns(name):
    return [f"{name}.{field}[{i}]" for field, n in (("position", 3), ("orientation", 4)) for i in range(1, n + 1)]


def test_the_csv_holds_the_driven_poses_at_their_start_values(pusher_run):
    result = read_result(pusher_run["csv"])
    assert all(c in result for name in DRIVEN for c in pose_columns(name))
    # the pusher where the scene puts it; the lift centred between its min and max
    for name, start in (("pusher", [-0.3, 0, 0.1, 1, 0, 0, 0]), ("lift", [1.5, 0, 0.45, 1, 0, 0, 0])):
        track = np.column_stack([result[c] for c in pose_columns(name)])
        assert np.allclose(track, start, rtol=0, atol=1e-12), name
    assert "crate.position[1]" in result and "pusher.contacts" in result  # the outputs as before


def test_the_plots_are_written_and_the_energy_leaves_the_driven_out(pusher_run):
    for kind in ("position", "velocity", "energy", "contacts"):
        png = pusher_run["dir"] / f"pusher_{kind}.png"
        assert str(png) in pusher_run["printed"].splitlines()
        with Image.open(png) as image:
            assert image.width >= 600 and image.height >= 150
    assert "driven, not counted (no mass, motion given): pusher, lift" in energy_note([], list(DRIVEN))


def test_the_replay_draws_the_driven_bodies_with_their_tracks(pusher_run):
    data = replay_data(pusher_run["html"].read_text())
    frames = len(data["time"])
    assert frames == round(PUSHER_STOP_TIME / 0.01) + 1
    bodies = {b["name"]: b for b in data["bodies"]}
    assert list(bodies) == ["crate", "ball", *DRIVEN]
    assert [s["name"] for s in data["surfaces"]] == ["floor"]  # the lift is a body now
    assert [bodies[n]["colour"] for n in ("crate", "ball")] == [colour_of(0), colour_of(1)]
    for name in DRIVEN:
        b = bodies[name]
        assert b["motion"] == "driven" and b["colour"] == DRIVEN_COLOUR, name
        assert len(b["position"]) == 3 * frames and len(b["orientation"]) == 4 * frames, name
        assert len(b["contacts"]) == frames, name
    assert bodies["lift"]["shape"] == {"type": "box", "size": [0.6, 0.6, 0.1]}
    assert bodies["lift"]["position"][-3:] == [1.5, 0.0, 0.45]
    assert bodies["ball"]["contacts"][-1] == 1  # resting on the lift


@BROWSER
def test_page_moves_the_driven_bodies_with_their_recorded_pose(pusher_run, tmp_path):
    """The run's CSV with both driven bodies carried 2 m along y over the run, as a
    master would move them: the page draws them in DRIVEN_COLOUR, and where they are."""
    with open(pusher_run["csv"], newline="") as f:
        rows = list(csv.reader(f))
    columns = [rows[0].index(f"{name}.position[2]") for name in DRIVEN]
    for row in rows[1:]:
        for c in columns:
            row[c] = str(2.0 * float(row[0]) / PUSHER_STOP_TIME)
    moved = tmp_path / "moved.csv"
    with open(moved, "w", newline="") as f:
        csv.writer(f).writerows(rows)
    report = snapshots(write_replay(moved, json.loads(PUSHER.read_text()), tmp_path / "moved.html"),
                       tmp_path / "shots")
    assert report["errors"] == []
    (n0, x0, y0), (n1, x1, y1) = (body_pixels(p, DRIVEN_COLOUR, saturation=0.15) for p in report["screenshots"])
    assert n0 >= 40 and n1 >= 40, f"driven bodies: {n0} and {n1} pixels"
    assert np.hypot(x1 - x0, y1 - y0) > 5


# ---- mesh and compound bodies ----------------------------------------------------------

# A box from (0, 0, 0) to (a, b, c) in the file (exact in binary STL's float32), scaled
# per axis to a 0.2 m cube: its centroid s * (a, b, c) / 2, its corners then at ±0.1 m.
BOX = (0.5, 0.25, 1.0)
BOX_SCALE = [0.4, 0.8, 0.2]
HALF = 0.1
TETRAHEDRON = ([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
               [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])  # counter-clockwise seen from outside


def box_stl() -> bytes:
    mesh = trimesh.creation.box(extents=BOX)
    mesh.apply_translation(np.array(BOX) / 2)  # its corner at the file's origin
    return mesh.export(file_type="stl")


def tetrahedron_stl() -> bytes:
    return trimesh.Trimesh(*TETRAHEDRON, process=False).export(file_type="stl")


def corners(half) -> set:
    return {(x, y, z) for x in (-half[0], half[0]) for y in (-half[1], half[1]) for z in (-half[2], half[2])}


def signed_volume(shape) -> float:
    v = np.array(shape["vertices"]).reshape(-1, 3)[np.array(shape["triangles"]).reshape(-1, 3)]
    return float(np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6.0)


def still_replay(tmp_path, s, files) -> dict:
    """The page's data of scene `s` written with its mesh `files` in tmp_path, from a
    run of two frames whose CSV holds no pose (the bodies stay at their start)."""
    for name, data in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_bytes(data)
    (tmp_path / "scene.json").write_text(json.dumps(s))
    (tmp_path / "run.csv").write_text("time\n0\n0.01\n")
    html = write_replay(tmp_path / "run.csv", tmp_path / "scene.json", tmp_path / "run.html")
    return replay_data(html.read_text())


def test_a_mesh_box_reaches_the_page_scaled_and_moved_to_its_centroid(tmp_path):
    shape = {"type": "mesh", "file": "parts/box.stl", "scale": BOX_SCALE}
    data = still_replay(tmp_path, scene("MeshBox", [body("part", shape)]), {"parts/box.stl": box_stl()})
    drawn = data["bodies"][0]["shape"]
    assert (drawn["type"], drawn["file"], drawn["scale"]) == ("mesh", "parts/box.stl", BOX_SCALE)
    assert len(drawn["vertices"]) == 3 * 8 and len(drawn["triangles"]) == 3 * 12
    assert {tuple(np.round(v, 9) + 0.0) for v in np.reshape(drawn["vertices"], (-1, 3))} == corners([HALF] * 3)
    assert signed_volume(drawn) == pytest.approx((2 * HALF) ** 3, rel=1e-9)  # wound outward, as the file


def test_a_tetrahedron_is_moved_by_its_centroid_with_one_scale_factor(tmp_path):
    shape = {"type": "mesh", "file": "tetra.stl", "scale": 0.5}
    data = still_replay(tmp_path, scene("MeshTetra", [body("tetra", shape)]), {"tetra.stl": tetrahedron_stl()})
    drawn = data["bodies"][0]["shape"]
    assert len(drawn["vertices"]) == 3 * 4 and len(drawn["triangles"]) == 3 * 4
    # the corners' mean, (1, 1, 1) / 8 after the scale of 0.5
    expected = 0.5 * np.array(TETRAHEDRON[0]) - 0.125
    assert np.allclose(sorted(np.reshape(drawn["vertices"], (-1, 3)).tolist()), sorted(expected.tolist()),
                       rtol=0, atol=1e-6)


def test_a_compounds_parts_are_moved_by_the_compounds_centroid(tmp_path):
    """A 0.2 m primitive cube centred at (0, 1, 2) and a 0.2 m mesh cube whose file puts
    its corner at its origin, that origin placed at (1, 1, 2) and turned half a turn
    about z: the mesh's centre of mass at (1, 1, 2) + (-0.1, -0.1, 0.1); equal volumes,
    so the compound's centre half way, each part +-(0.45, -0.05, 0.05) from it."""
    shape = {"type": "compound", "parts": [
        {"shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "position": [0, 1, 2]},
        {"shape": {"type": "mesh", "file": "box.stl", "scale": BOX_SCALE}, "position": [1, 1, 2],
         "orientation": [0.0, 0.0, 0.0, 1.0]}]}
    data = still_replay(tmp_path, scene("Compound", [body("pair", shape)]), {"box.stl": box_stl()})
    drawn = data["bodies"][0]["shape"]
    assert np.allclose([p["position"] for p in drawn["parts"]], [[-0.45, 0.05, -0.05], [0.45, -0.05, 0.05]],
                       rtol=0, atol=1e-12)
    assert drawn["parts"][0]["shape"] == {"type": "box", "size": [0.2, 0.2, 0.2]}
    assert drawn["parts"][1]["orientation"] == [0.0, 0.0, 0.0, 1.0]
    mesh = drawn["parts"][1]["shape"]
    assert {tuple(np.round(v, 9) + 0.0) for v in np.reshape(mesh["vertices"], (-1, 3))} == corners([HALF] * 3)


def test_a_mesh_scene_given_as_a_dict_needs_its_folder(tmp_path):
    (tmp_path / "run.csv").write_text("time\n0\n")
    s = scene("MeshBox", [body("part", {"type": "mesh", "file": "box.stl"})])
    with pytest.raises(ReplayError, match=r"bodies\[0\]\.shape: a mesh needs the scene's folder"):
        write_replay(tmp_path / "run.csv", s, tmp_path / "run.html")


@pytest.fixture(scope="module")
def mesh_run(fmu_of, tmp_path_factory):
    """A mesh cube tossed with spin over a floor, simulated by `rigidfmu simulate FMU
    --replay`: the page's meshes come from the FMU's resources."""
    out = tmp_path_factory.mktemp("mesh")
    s = scene("ReplayMesh", [body("cube", {"type": "mesh", "file": "parts/box.stl", "scale": BOX_SCALE},
                                  position=[0, 0, 0.5], velocity=[2, 0, 2], angularVelocity=[0, 5, 0])])
    s["surfaces"] = [{"name": "floor", "min": [-2, -1, -0.2], "max": [3, 1, 0]}]
    fmu = fmu_of(s, files={"parts/box.stl": box_stl()})
    subprocess.run([sys.executable, "-m", "rigidfmu", "simulate", str(fmu), "--replay", "--stop-time", "0.5",
                    "--out", str(out)], check=True, capture_output=True, env=ENV)
    return {"dir": out, "html": out / f"{fmu.stem}.html"}


def test_a_simulated_mesh_body_replays_with_its_triangles(mesh_run):
    data = replay_data(mesh_run["html"].read_text())
    cube = data["bodies"][0]
    assert len(cube["shape"]["vertices"]) == 3 * 8 and len(cube["shape"]["triangles"]) == 3 * 12
    assert len(cube["position"]) == 3 * len(data["time"]) > 3


@BROWSER
def test_page_draws_the_mesh_body_and_moves_it(mesh_run):
    report = snapshots(mesh_run["html"], mesh_run["dir"] / "shots")
    assert report["errors"] == []
    (n0, x0, y0), (n1, x1, y1) = (body_pixels(p, colour_of(0)) for p in report["screenshots"])
    assert n0 >= 40 and n1 >= 40, f"the mesh cube: {n0} and {n1} pixels"
    assert np.hypot(x1 - x0, y1 - y0) > 5


@BROWSER
def test_page_draws_a_compound_without_error(tmp_path):
    shape = {"type": "compound", "parts": [
        {"shape": {"type": "sphere", "radius": 0.2}, "position": [0, 0, 0]},
        {"shape": {"type": "mesh", "file": "box.stl", "scale": BOX_SCALE}, "position": [0.6, 0, 0],
         "orientation": [0.9238795, 0.0, 0.0, 0.3826834]}]}
    still_replay(tmp_path, scene("Compound", [body("pair", shape, position=[0, 0, 0.3])]), {"box.stl": box_stl()})
    report = snapshots(tmp_path / "run.html", tmp_path / "shots")
    assert report["errors"] == []
    n, _, _ = body_pixels(report["screenshots"][0], colour_of(0))
    assert n >= 40, f"the compound: {n} pixels"
