#!/usr/bin/env bash
# scripts/run.sh [SCENE.json] [STOP_TIME]
# The main job: builds the scene's FMU (default: scripts/scenes/default.json),
# simulates it with fmpy and writes out/<name>.fmu, out/<name>.csv, PNG plots and
# out/<name>.html, the run's 3D replay.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
scene="${1:-$root/scripts/scenes/default.json}"
stop_time="${2:-5}"
"$root/scripts/setup.sh"
out="${RIGIDFMU_OUT:-$root/out}"
mkdir -p "$out"
name="$(basename "$scene" .json)"
RIGIDFMU_SKIP_SETUP=1 "$root/scripts/build_fmu.sh" "$scene" "$out/$name.fmu"
"$root/.venv/bin/python" "$root/scripts/simulate.py" "$out/$name.fmu" --stop-time "$stop_time" --out "$out"
RIGIDFMU_SKIP_SETUP=1 "$root/scripts/replay.sh" "$out/$name.csv" "$scene" "$out/$name.html"
