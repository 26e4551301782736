#!/usr/bin/env bash
# scripts/replay.sh RESULT.csv SCENE.json [OUT.html]
# Writes the 3D replay of an earlier run: one self-contained HTML file (default: beside
# the CSV, with .html for .csv) that opens offline in any browser.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ $# -lt 2 ] || [ $# -gt 3 ]; then
  echo "usage: $0 RESULT.csv SCENE.json [OUT.html]" >&2
  exit 2
fi
csv="$1"
scene="$2"
out="${3:-${csv%.csv}.html}"
[ -f "$csv" ] || { echo "replay: no result file $csv" >&2; exit 2; }
[ -f "$scene" ] || { echo "replay: no scene file $scene" >&2; exit 2; }
[ -n "${RIGIDFMU_SKIP_SETUP:-}" ] || "$root/scripts/setup.sh"
"$root/.venv/bin/python" "$root/scripts/replay.py" "$csv" "$scene" "$out"
