#!/usr/bin/env bash
# scripts/test.sh: every test. Installs what is missing, builds the core once (build/),
# runs the C++ unit tests (ctest) and the FMU tests (pytest + fmpy).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
build="${RIGIDFMU_BUILD:-$root/build}"
/usr/bin/cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DRIGIDFMU_TESTS=ON >/dev/null
/usr/bin/cmake --build "$build" -j"$(nproc)"
(cd "$build" && /usr/bin/ctest --output-on-failure -j"$(nproc)")
cd "$root"
RIGIDFMU_SKIP_SETUP=1 RIGIDFMU_BUILD="$build" "$root/.venv/bin/python" -m pytest tests -q "$@"
