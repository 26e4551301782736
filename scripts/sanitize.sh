#!/usr/bin/env bash
# scripts/sanitize.sh: the C++ unit tests and the FMU tests again, against a second
# build of the core with AddressSanitizer and UndefinedBehaviorSanitizer
# (RIGIDFMU_SANITIZE=ON, in build-asan/). The FMU binaries are loaded into Python, so the
# sanitizer runtimes are preloaded into the test process; leak checking is off there
# (CPython keeps its allocations to the end) and on for the C driver of the abuse tests,
# which runs 1000 instantiate/step/free cycles under LeakSanitizer. Any sanitizer report
# fails the run (halt_on_error). Extra arguments go to pytest.
#
# Only the FMU binary with every module is built here (RIGIDFMU_VARIANTS=top): the
# smaller ones differ from it only by `if constexpr` branches compiled out
# (src/module_switches.h), so its code is a superset of theirs; every scene's FMU gets
# it, and the plain run checks the choice of the smallest binary.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
. "$root/scripts/phase.sh"
[ -n "${RIGIDFMU_SKIP_SETUP:-}" ] || "$root/scripts/setup.sh"
build="${RIGIDFMU_SANITIZE_BUILD:-$root/build-asan}"
build_core() {
  /usr/bin/cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DRIGIDFMU_SANITIZE=ON \
    -DRIGIDFMU_TESTS=ON -DRIGIDFMU_VARIANTS=top >/dev/null
  /usr/bin/cmake --build "$build" -j"$(nproc)" --target rigid_unit_tests rigidfmu-describe rigidfmu_fmus
}
phase "sanitizer build" build_core
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_leaks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
phase "sanitizer ctest" bash -c 'cd "$1" && /usr/bin/ctest --output-on-failure -j"$(nproc)"' - "$build"
cd "$root"
# tests/fmu only: tests/scripts (the reports, replay, studies, benchmarks and the package)
# drive whole scripts, browsers and worker processes rather than the FMU's memory and run
# in the plain suite; valgrind is left out too, it cannot run beside ASan.
phase "sanitizer pytest" env LD_PRELOAD="$(gcc -print-file-name=libasan.so) $(gcc -print-file-name=libubsan.so)" \
  ASAN_OPTIONS="halt_on_error=1:detect_leaks=0" RIGIDFMU_SANITIZED=1 RIGIDFMU_SKIP_SETUP=1 \
  RIGIDFMU_BUILD="$build" "$root/.venv/bin/python" -m pytest tests/fmu -q -n "$(nproc)" --dist loadfile "$@"
