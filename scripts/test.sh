#!/usr/bin/env bash
# scripts/test.sh: every test. Installs what is missing, builds the core once (build/),
# runs the C++ unit tests (ctest) and the FMU tests (pytest + fmpy), then both again
# against the ASan/UBSan build (scripts/sanitize.sh, build-asan/). Arguments go to the
# first pytest run; RIGIDFMU_NO_SANITIZE=1 leaves the sanitizer run out,
# RIGIDFMU_SKIP_SETUP=1 the set-up (as in the other scripts). Each phase
# prints its wall time ("time: PHASE N s"), so that CI's log shows where the time goes.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
. "$root/scripts/phase.sh"
start=$SECONDS
[ -n "${RIGIDFMU_SKIP_SETUP:-}" ] || phase setup "$root/scripts/setup.sh"
build="${RIGIDFMU_BUILD:-$root/build}"
build_core() {
  /usr/bin/cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DRIGIDFMU_TESTS=ON >/dev/null
  /usr/bin/cmake --build "$build" -j"$(nproc)"
}
phase build build_core
phase ctest bash -c 'cd "$1" && /usr/bin/ctest --output-on-failure -j"$(nproc)"' - "$build"
# the win64 DLLs every FMU carries (MinGW-w64; FCL and libccd cross-built once per
# machine, which prints its time)
phase win64 "$root/scripts/build_win64.sh"
cd "$root"
phase pytest env RIGIDFMU_SKIP_SETUP=1 RIGIDFMU_BUILD="$build" "$root/.venv/bin/python" -m pytest tests -q -n "$(nproc)" --dist loadfile "$@"
if [ -z "${RIGIDFMU_NO_SANITIZE:-}" ]; then
  RIGIDFMU_SKIP_SETUP=1 RIGIDFMU_SANITIZE_BUILD="$build-asan" "$root/scripts/sanitize.sh"
fi
echo "time: test.sh $((SECONDS - start)) s"
