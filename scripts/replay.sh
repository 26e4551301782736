#!/usr/bin/env bash
# scripts/replay.sh RESULT.csv SCENE.json [OUT.html]
# Writes the 3D replay of an earlier run: one self-contained HTML file (default: beside
# the CSV, with .html for .csv) that opens offline in any browser (`rigidfmu replay`).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ $# -lt 2 ] || [ $# -gt 3 ]; then
  echo "usage: $0 RESULT.csv SCENE.json [OUT.html]" >&2
  exit 2
fi
[ -f "$1" ] || { echo "replay: no result file $1" >&2; exit 2; }
[ -f "$2" ] || { echo "replay: no scene file $2" >&2; exit 2; }
[ -n "${RIGIDFMU_SKIP_SETUP:-}" ] || "$root/scripts/setup.sh"
exec "$root/.venv/bin/python" -m rigidfmu replay "$1" "$2" ${3:+-o "$3"}
