#!/usr/bin/env bash
# scripts/stress.sh [--quick] [--out DIR] [--only SUBSTRING] [--no-peers] [--jobs N]
# The stability stress suite (`scripts/stress.sh`): every case with every integration
# method of the FMU, judged by the criteria written in the suite; writes DIR/stability.md
# (default docs/reports/) and exits 1 when any run FAILS. Builds the core like build_fmu.sh (in
# build/, or $RIGIDFMU_BUILD), then runs the suite with the venv's python; every argument
# is passed through. In full mode MuJoCo is measured beside the fast-spin case with the
# peers' venv (.venv-peers, made by scripts/peers.sh) when it can be had.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
[ -n "${RIGIDFMU_SKIP_SETUP:-}" ] || "$root/scripts/setup.sh"
build="${RIGIDFMU_BUILD:-$root/build}"
. "$root/scripts/ensure_build.sh"
export PYTHONPATH="$root/scripts${PYTHONPATH:+:$PYTHONPATH}"  # the reports (scripts/reports), not in the package
exec "$root/.venv/bin/python" -m reports.stability --build "$build" --no-build "$@"
