#!/usr/bin/env bash
# scripts/test.sh: every test. Installs what is missing, builds the core once (build/),
# runs the C++ unit tests (ctest) and the FMU tests (pytest + fmpy), then both again
# against the ASan/UBSan build (scripts/sanitize.sh, build-asan/). Arguments go to the
# first pytest run; RIGIDFMU_NO_SANITIZE=1 leaves the sanitizer run out.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
build="${RIGIDFMU_BUILD:-$root/build}"
/usr/bin/cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DRIGIDFMU_TESTS=ON >/dev/null
/usr/bin/cmake --build "$build" -j"$(nproc)"
(cd "$build" && /usr/bin/ctest --output-on-failure -j"$(nproc)")
# the win64 DLLs every FMU carries (MinGW-w64; FCL and libccd cross-built once per
# machine, which prints its time)
start=$SECONDS
"$root/scripts/build_win64.sh"
echo "test.sh: win64 binaries up to date in $((SECONDS - start)) s"
cd "$root"
RIGIDFMU_SKIP_SETUP=1 RIGIDFMU_BUILD="$build" "$root/.venv/bin/python" -m pytest tests -q "$@"
if [ -z "${RIGIDFMU_NO_SANITIZE:-}" ]; then
  RIGIDFMU_SKIP_SETUP=1 RIGIDFMU_SANITIZE_BUILD="$build-asan" "$root/scripts/sanitize.sh"
fi
