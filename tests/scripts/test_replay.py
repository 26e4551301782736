"""The run's outputs for people: `rigidfmu simulate --plot`'s figures, and the 3D
replay page that replay.sh writes, self-contained, and that headless chromium opens with no error,
shows every body in its palette colour and moves the bodies with the time slider."""
import colorsys
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from rigidfmu.replay import colour_of
from rigidfmu.scenes import body, scene

pytestmark = pytest.mark.slow  # a whole script or browser run (pyproject.toml)

ROOT = pathlib.Path(__file__).resolve().parents[2]
ENV = dict(os.environ, RIGIDFMU_SKIP_SETUP="1")
CHROMIUM = os.environ.get("CHROMIUM", "/usr/bin/chromium")
STOP_TIME = 1.0


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
    data = json.loads(re.search(r'<script id="replay-data" type="application/json">(.*?)</script>',
                                html, re.S).group(1))
    assert [b["name"] for b in data["bodies"]] == ["ball", "brick", "rod"]
    assert [b["colour"] for b in data["bodies"]] == [colour_of(k) for k in range(3)]
    frames = len(data["time"])
    assert frames == round(STOP_TIME / 0.02) + 1
    assert all(len(b["position"]) == 3 * frames and len(b["orientation"]) == 4 * frames
               and len(b["contacts"]) == frames for b in data["bodies"])
    assert data["up"] == [0.0, 0.0, 1.0]
    assert [s["name"] for s in data["surfaces"]] == ["floor"]
    assert [m["name"] for m in data["media"]] == ["pool"]


def body_pixels(png, colour):
    """(count, centroid x, centroid y) of the pixels whose hue is the colour's, within
    12 degrees, and that are saturated and bright enough to be the body and not the
    grey floor or the pale water: shading changes a lit body's brightness, not its hue."""
    hsv = np.asarray(Image.open(png).convert("RGB").convert("HSV"), dtype=float)
    r, g, b = (int(colour[i:i + 2], 16) / 255 for i in (1, 3, 5))
    hue = colorsys.rgb_to_hsv(r, g, b)[0] * 255
    dh = np.abs(hsv[..., 0] - hue)
    match = ((np.minimum(dh, 255 - dh) <= 12 / 360 * 255)
             & (hsv[..., 1] >= 0.45 * 255) & (hsv[..., 2] >= 0.2 * 255))
    ys, xs = np.nonzero(match)
    return len(xs), (xs.mean() if len(xs) else np.nan), (ys.mean() if len(ys) else np.nan)


@pytest.mark.skipif(not (os.access(CHROMIUM, os.X_OK) and shutil.which("node")),
                    reason=f"no {CHROMIUM} or node (scripts/setup.sh installs Debian's chromium)")
def test_page_shows_the_bodies_and_the_slider_moves_them(run):
    shots = run["dir"] / "shots"
    snapshot = ROOT / "python" / "rigidfmu" / "replay" / "page" / "snapshot.mjs"
    printed = subprocess.run(["node", str(snapshot), str(run["html"]), str(shots), "0", "last"],
                             check=True, capture_output=True, text=True, timeout=120).stdout
    report = json.loads(printed.strip().splitlines()[-1])
    assert report["errors"] == []
    first, last = (pathlib.Path(p) for p in report["screenshots"])
    assert report["frames"] == [0, round(STOP_TIME / 0.02)]
    for k, b in enumerate(run["scene"]["bodies"]):
        n0, x0, y0 = body_pixels(first, colour_of(k))
        n1, x1, y1 = body_pixels(last, colour_of(k))
        assert n0 >= 40 and n1 >= 40, f"{b['name']} ({colour_of(k)}): {n0} and {n1} pixels"
        moved = np.hypot(x1 - x0, y1 - y0)
        assert moved > 5, f"{b['name']} moved {moved:.1f} px on the screen"
