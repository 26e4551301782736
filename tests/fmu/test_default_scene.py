"""The default scene of scripts/run.sh shows the seed's world: a block slides down the
ramp and into the pool where it floats, a rougher block stays put on the same ramp, a
puck slides to a stop on the floor, a light ball drops into the pool and floats."""
import json
import math
import pathlib

import numpy as np
import pytest
from fmpy import simulate_fmu

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENE = json.loads((ROOT / "scripts" / "scenes" / "default.json").read_text())


@pytest.fixture(scope="module")
def run(fmu_of):
    return simulate_fmu(str(fmu_of(SCENE)), stop_time=12.0, output_interval=0.01)


def pos(r, body):
    return np.column_stack([r[f"{body}.position[{i}]"] for i in (1, 2, 3)])


def test_rough_block_stays_on_the_ramp(run):
    # combined mu_s = sqrt(1.0 * 0.4) = 0.632 > tan 30 deg = 0.577
    p = pos(run, "sticker")
    assert np.max(np.linalg.norm(p - p[0], axis=1)) < 1e-6


def test_puck_slides_to_a_stop(run):
    # v0 = 4 m/s, combined mu_k = 0.3: stops after v0^2 / (2 mu_k g)
    x = run["puck.position[1]"]
    assert x[-1] - x[0] == pytest.approx(16.0 / (2 * 0.3 * 9.81), rel=5e-3)


def test_slider_goes_down_the_ramp_into_the_pool_and_floats(run):
    p = pos(run, "slider")
    pool_min, pool_max = np.array(SCENE["media"][0]["min"]), np.array(SCENE["media"][0]["max"])
    assert np.all((p[-1] > pool_min) & (p[-1] < pool_max + [0, 0, 0.2]))
    # density 9 kg / (0.3 * 0.3 * 0.2 m^3) = 500 kg/m^3: floats with draft m / (rho_w A)
    draft = 9.0 / (998.2 * 0.09)
    late = run["time"] > 9.0
    z_bottom = p[late, 2] - 0.1
    assert np.mean(z_bottom) == pytest.approx(-draft, abs=5e-3)


def test_ball_floats_in_the_pool(run):
    z = run["ball.position[3]"]
    late = run["time"] > 9.0
    # 4 kg sphere of radius 0.15 m: its cap of depth d under the water line displaces
    # pi d^2 (3r - d) / 3 = m / rho_w; solve for d by bisection
    r, need = 0.15, 4.0 / 998.2
    lo, hi = 0.0, 2 * r
    for _ in range(60):
        d = 0.5 * (lo + hi)
        lo, hi = (d, hi) if math.pi * d * d * (3 * r - d) / 3 < need else (lo, d)
    assert np.mean(z[late]) == pytest.approx(r - d, abs=5e-3)  # centre above the line


def test_every_output_stays_finite(run):
    for name in run.dtype.names:
        assert np.all(np.isfinite(run[name])), name
