#!/usr/bin/env bash
# scripts/build_fmu.sh SCENE.json OUT.fmu [--fmi 2|3] [--no-win64]
# Builds the FMU of one scene: `rigidfmu build SCENE -o OUT [options]` from the source
# tree (FMI 2.0 unless --fmi 3). The core is compiled once in build/ (set RIGIDFMU_BUILD
# to use another build tree); a further scene only runs the packaging.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ $# -lt 2 ]; then
  echo "usage: $0 SCENE.json OUT.fmu [--fmi 2|3] [--no-win64]" >&2
  exit 2
fi
[ -f "$1" ] || { echo "build_fmu: no scene file $1" >&2; exit 2; }
[ -n "${RIGIDFMU_SKIP_SETUP:-}" ] || "$root/scripts/setup.sh"
scene="$1" out="$2"
shift 2
exec "$root/.venv/bin/python" -m rigidfmu build "$scene" -o "$out" "$@"
