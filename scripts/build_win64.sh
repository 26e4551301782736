#!/usr/bin/env bash
# Cross-compiles the FMU binaries for 64-bit Windows (rigidfmu_fmi2_<mask>.dll, one per
# module combination as on Linux) into build-win64/ (or $RIGIDFMU_BUILD_WIN64) with
# MinGW-w64, against the cross-built FCL and libccd (scripts/win64_deps.sh, cached per
# machine). Configured once, then brought up to date like the Linux build.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${RIGIDFMU_BUILD_WIN64:-$root/build-win64}"
cmake=/usr/bin/cmake
if ! command -v x86_64-w64-mingw32-g++-posix >/dev/null; then
  echo "build_win64: MinGW-w64 is not installed (g++-mingw-w64-x86-64-posix: scripts/setup.sh installs it)" >&2
  exit 1
fi
# A configured tree keeps its dependencies (as build/ keeps the host's): the cache key's
# look-up (apt-cache) is left out of every later FMU's build.
deps="$(sed -n 's/^RIGIDFMU_WIN64_DEPS:PATH=//p' "$build/CMakeCache.txt" 2>/dev/null || true)"
if [ -z "$deps" ] || [ ! -f "$deps/.complete" ]; then
  deps="$("$root/scripts/win64_deps.sh")"
  rm -rf "$build/CMakeCache.txt" "$build/CMakeFiles"  # no package found in another cache stays
  "$cmake" -S "$root" -B "$build" -DCMAKE_TOOLCHAIN_FILE="$root/cmake/mingw-w64-x86_64.cmake" \
    -DCMAKE_BUILD_TYPE=Release -DRIGIDFMU_TESTS=OFF -DRIGIDFMU_WIN64_DEPS:PATH="$deps" \
    -DCMAKE_PREFIX_PATH="$deps" -DEigen3_DIR=/usr/share/eigen3/cmake >/dev/null
fi
"$cmake" --build "$build" "-j$(nproc)" --target rigidfmu_fmus >/dev/null
