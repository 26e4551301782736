#!/usr/bin/env bash
# scripts/bench.sh [--quick] [--out DIR] [--chain-only | --meshes-only]
# The performance report (`scripts/bench.sh`): builds the core and its Google Benchmark
# (rigid-bench-core) like build_fmu.sh (in build/, or $RIGIDFMU_BUILD), makes sure the
# peers' venv (.venv-peers, MuJoCo) is there, then runs the core, FMU and MuJoCo
# benchmarks in one run. Default: writes docs/reports/performance.md and docs/reports/performance/.
# --quick: short runs for the test suite (no 10000 free bodies, no pile of 1000, and
# MuJoCo only if .venv-peers already exists, since installing it is slow).
# --chain-only: only the chain of hinged links beside MuJoCo (2 s, 5 interleaved rounds;
# with --quick 0.2 s, one), its figures printed and no report written.
# --meshes-only: only the convex meshes (the narrowphase per pair, the pile of pebbles in
# its bin beside MuJoCo), rendered into the report from OUT/performance/bench.json.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
[ -n "${RIGIDFMU_SKIP_SETUP:-}" ] || "$root/scripts/setup.sh"
build="${RIGIDFMU_BUILD:-$root/build}"
. "$root/scripts/ensure_build.sh"
# ensure_build.sh builds the FMU binaries; the benchmark target exists only when CMake
# found Google Benchmark (libbenchmark-dev, installed by setup.sh), so a build tree
# configured before it was installed is configured again once
if ! "$cmake_bin" --build "$build" -j"$(nproc)" --target rigid-bench-core >/dev/null 2>&1; then
  "$cmake_bin" -S "$root" -B "$build" >/dev/null
  "$cmake_bin" --build "$build" -j"$(nproc)" --target rigid-bench-core >/dev/null || {
    echo "bench: cannot build rigid-bench-core (is libbenchmark-dev installed? scripts/setup.sh)" >&2
    exit 1; }
fi
case " $* " in
  *" --quick "*|*" --help "*|*" -h "*) ;;
  *) . "$root/scripts/peers_venv.sh" ;;
esac
export PYTHONPATH="$root/scripts${PYTHONPATH:+:$PYTHONPATH}"  # the reports (scripts/reports), not in the package
exec "$root/.venv/bin/python" -m reports.performance --build "$build" "$@"
