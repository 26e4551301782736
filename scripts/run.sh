#!/usr/bin/env bash
# scripts/run.sh [SCENE.json] [STOP_TIME]
# The main job: builds the scene's FMU (default: scripts/scenes/default.json),
# simulates it with fmpy and writes out/<name>.fmu, out/<name>.csv, PNG plots and
# out/<name>.html, the run's 3D replay (`rigidfmu simulate SCENE --plot --replay`).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
scene="${1:-$root/scripts/scenes/default.json}"
stop_time="${2:-5}"
"$root/scripts/setup.sh"
out="${RIGIDFMU_OUT:-$root/out}"
exec "$root/.venv/bin/python" -m rigidfmu simulate "$scene" --stop-time "$stop_time" --out "$out" --plot --replay
