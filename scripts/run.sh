#!/usr/bin/env bash
# scripts/run.sh [SCENE.json] [STOP_TIME]
# The main job: builds the scene's FMU (default: scripts/scenes/default.json),
# simulates it with fmpy and writes out/<name>.fmu, out/<name>.csv, PNG plots and
# out/<name>.html, the run's 3D replay (`rigidfmu simulate SCENE --plot --replay`).
# The first result comes from the linux64 binary alone; the win64 binaries (cross-built
# with MinGW-w64, minutes the first time on a machine) are added to out/<name>.fmu after
# it. RIGIDFMU_NO_WIN64=1 leaves them out.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
scene="${1:-$root/scripts/scenes/default.json}"
stop_time="${2:-5}"
[ -n "${RIGIDFMU_SKIP_SETUP:-}" ] || "$root/scripts/setup.sh"
out="${RIGIDFMU_OUT:-$root/out}"
"$root/.venv/bin/python" -m rigidfmu simulate "$scene" --stop-time "$stop_time" --out "$out" --plot --replay \
  --no-win64
[ "${RIGIDFMU_NO_WIN64:-0}" = 1 ] && exit 0
fmu="$out/$(basename "${scene%.json}").fmu"
echo "run.sh: the result is above; now adding the win64 binaries to $fmu (RIGIDFMU_NO_WIN64=1 skips this)" >&2
exec "$root/.venv/bin/python" -m rigidfmu build "$scene" -o "$fmu"
