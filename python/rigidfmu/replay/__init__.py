"""Writes the 3D replay of a run: one self-contained HTML file (three.js inlined, no
network) from a result CSV (as rigidfmu.simulate writes it) and the scene JSON.

    rigidfmu replay RESULT.csv SCENE.json [-o OUT.html]

The run is embedded in the page as JSON:
    {"title": str, "up": [x, y, z] (unit, against gravity; z without gravity),
     "time": [s, ...],
     "bodies": [{"name", "shape" (as in the scene, meshes' triangles added: shapes.py),
                 "motion": "free" or "driven",
                 "colour": "#rrggbb",
                 "position": [x, y, z, ...] m, "orientation": [w, x, y, z, ...],
                 "contacts": [int, ...] or null}],
     "surfaces": [{"name", "min", "max", "orientation": [w, x, y, z]}],
     "media": [{"name", "type", "min", "max"}]}
"bodies" are the FMU's bodies in its order: the scene's bodies, then its driven
surfaces, each as the driven body it is (rigidfmu.driven: a box of size max - min,
its position the box's centre); "surfaces" are the static surfaces only. A body's
position or orientation that the CSV does not hold (an output left out, or an older
CSV without a driven body's pose inputs) is its start value from the scene (one
frame); its contacts are null when the CSV does not hold b.contacts. A mesh body's
vertices are in its body frame (moved to its centre of mass), a compound's parts at
their positions in it (replay/shapes.py), read from the scene's folder.

Body k (scene order) is drawn in PALETTE[k % len(PALETTE)], a driven body or surface
in DRIVEN_COLOUR: colours are the replay's choice, not part of the scene format, and
the browser test finds the bodies by them.
"""
import csv
import json
import pathlib
import subprocess
import tempfile
import zipfile

import numpy as np

from rigidfmu import driven
from rigidfmu.errors import ReplayError
from rigidfmu.replay.shapes import replay_shape

PAGE = pathlib.Path(__file__).resolve().parent / "page"  # its sources, npm packages and build
TEMPLATE = PAGE / "dist" / "replay.html"
DATA_MARKER = "<!-- replay-data -->"

# Saturated colours with hues at least 20 degrees apart, none of them the grey of the
# surfaces or the pale blue of water.
PALETTE = ["#e53935", "#43a047", "#fb8c00", "#1e88e5", "#8e24aa", "#fdd835", "#00acc1", "#d81b60"]


# Driven bodies are the world's machinery, moved by their inputs: slate, darker and
# bluer than the still grey surfaces and far less saturated than any body's colour.
DRIVEN_COLOUR = "#546e7a"


def colour_of(index: int) -> str:
    return PALETTE[index % len(PALETTE)]


def body_colour(body: dict, index: int) -> str:
    """The colour of the body at `index` of rigidfmu.driven.all_bodies(scene)."""
    return DRIVEN_COLOUR if driven.is_driven(body) else colour_of(index)


def ensure_template() -> pathlib.Path:
    """dist/replay.html, rebuilt by esbuild when a source of the page is newer. An
    installed package carries the template built, without the sources."""
    if not (PAGE / "src").is_dir():
        if not TEMPLATE.exists():
            raise ReplayError(f"{TEMPLATE} is missing from the installed package")
        return TEMPLATE
    sources = [*(PAGE / "src").iterdir(), PAGE / "build.mjs", PAGE / "package-lock.json"]
    if TEMPLATE.exists() and TEMPLATE.stat().st_mtime >= max(s.stat().st_mtime for s in sources):
        return TEMPLATE
    if not (PAGE / "node_modules" / "three").is_dir():
        raise ReplayError(f"{PAGE}/node_modules is missing; scripts/setup.sh installs it (npm ci)")
    subprocess.run(["node", str(PAGE / "build.mjs")], check=True, stdout=subprocess.DEVNULL)
    return TEMPLATE


def read_result(path: pathlib.Path) -> dict:
    """The CSV's columns by name, as float arrays."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, values = rows[0], np.array(rows[1:], dtype=float)
    return {name: values[:, i] for i, name in enumerate(header)}


def flat(result: dict, columns: list, decimals: int):
    """Frames of several columns interleaved, rounded: a smaller page, and still far
    finer than a pixel."""
    return np.round(np.column_stack([result[c] for c in columns]), decimals).ravel().tolist()


def body_track(result: dict, body: dict, index: int, folder: pathlib.Path | None = None) -> dict:
    """The page's data of the body at `index`; `folder`: the scene's, for mesh files."""
    name = body["name"]
    shape, _, _ = replay_shape(body["shape"], folder, f"bodies[{index}].shape")
    track = {"name": name, "shape": shape, "motion": body.get("motion", "free"),
             "colour": body_colour(body, index)}
    for field, n, start in (("position", 3, [0.0, 0.0, 0.0]), ("orientation", 4, [1.0, 0.0, 0.0, 0.0])):
        columns = [f"{name}.{field}[{i}]" for i in range(1, n + 1)]
        if all(c in result for c in columns):
            track[field] = flat(result, columns, 6)
        else:
            track[field] = [float(v) for v in body.get(field, start)]
    contacts = result.get(f"{name}.contacts")
    track["contacts"] = None if contacts is None else contacts.astype(int).tolist()
    return track


def up_of(scene: dict) -> list:
    g = np.array(scene.get("gravity", [0.0, 0.0, -9.81]), dtype=float)
    norm = np.linalg.norm(g)
    return [0.0, 0.0, 1.0] if norm == 0 else (-g / norm).tolist()


def run_data(result: dict, scene: dict, title: str, folder: pathlib.Path | None = None) -> dict:
    """The page's data (the module's docstring); `folder`: the scene's, where its mesh
    files are (None for a scene without meshes)."""
    return {
        "title": title,
        "up": up_of(scene),
        "time": np.round(result["time"], 9).tolist(),
        "bodies": [body_track(result, b, k, folder) for k, b in enumerate(driven.all_bodies(scene))],
        "surfaces": [{"name": s["name"], "min": s["min"], "max": s["max"],
                      "orientation": s.get("orientation", driven.IDENTITY)}
                     for s in driven.static_surfaces(scene)],
        "media": [{"name": m["name"], "type": m.get("type", "water"), "min": m["min"], "max": m["max"]}
                  for m in scene.get("media", [])],
    }


def write_replay(csv_path, scene, out_path, folder=None) -> pathlib.Path:
    """The replay page of a result CSV; `scene` is the scene file or its dict. The mesh
    files a scene names are read in `folder`, by default the scene file's."""
    csv_path, out_path = pathlib.Path(csv_path), pathlib.Path(out_path)
    if not isinstance(scene, dict):
        folder = pathlib.Path(scene).parent if folder is None else folder
        scene = json.loads(pathlib.Path(scene).read_text())
    title = f"{scene.get('name', 'scene')} ({csv_path.name})"
    data = json.dumps(run_data(read_result(csv_path), scene, title, folder), separators=(",", ":"))
    # "</" inside the JSON would end its script element early; "<\/" reads the same
    data = data.replace("</", "<\\/")
    page = ensure_template().read_text()
    block = f'<script id="replay-data" type="application/json">{data}</script>'
    out_path.parent.mkdir(parents=True, exist_ok=True)
    out_path.write_text(page.replace(DATA_MARKER, block, 1))
    return out_path


def write_fmu_replay(csv_path, fmu, out_path) -> pathlib.Path:
    """The replay page of a run of `fmu`, from the scene and mesh files it carries: its
    resources are the scene's folder as `rigidfmu build` staged it (meshes.py), so the
    page draws what the FMU simulated even when the user's files have changed since."""
    with tempfile.TemporaryDirectory(prefix="rigidfmu-replay-") as folder:
        with zipfile.ZipFile(fmu) as z:
            # extract() drops absolute parts and ".." from member names: nothing lands outside
            for member in z.namelist():
                if member.startswith("resources/") and not member.endswith("/"):
                    z.extract(member, folder)
        return write_replay(csv_path, pathlib.Path(folder) / "resources" / "scene.json", out_path)
