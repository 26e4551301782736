#!/usr/bin/env bash
# scripts/build_fmu.sh SCENE.json OUT.fmu
# Builds the FMU of one scene. The core is compiled once in build/ (set RIGIDFMU_BUILD
# to use another build tree); a further scene only runs the packaging.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ $# -ne 2 ]; then
  echo "usage: $0 SCENE.json OUT.fmu" >&2
  exit 2
fi
scene="$(realpath "$1")"
out="$(realpath -m "$2")"
[ -f "$scene" ] || { echo "build_fmu: no scene file $1" >&2; exit 2; }

[ -n "${RIGIDFMU_SKIP_SETUP:-}" ] || "$root/scripts/setup.sh"
build="${RIGIDFMU_BUILD:-$root/build}"
. "$root/scripts/ensure_build.sh"
"$cmake_bin" -DSCENE="$scene" -DOUT="$out" \
  -DDESCRIBE="$build/rigidfmu-describe" -DLIBRARY_DIR="$build" \
  -P "$root/cmake/package_fmu.cmake"
