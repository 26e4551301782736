#!/usr/bin/env bash
# scripts/report_accuracy.sh [--quick] [--out DIR] [--scene SCENE.json --tolerance TOL ...]
# The accuracy report of the integration methods (`scripts/report_accuracy.sh`): builds the
# core like build_fmu.sh (in build/, or $RIGIDFMU_BUILD), then runs the report with the
# venv's python; every argument is passed through. Default: writes docs/reports/accuracy.md
# and docs/reports/accuracy/*.png.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
[ -n "${RIGIDFMU_SKIP_SETUP:-}" ] || "$root/scripts/setup.sh"
build="${RIGIDFMU_BUILD:-$root/build}"
. "$root/scripts/ensure_build.sh"
# The full report measures the peers (MuJoCo, its own venv) first, in the same run, so
# that their points sit on our diagrams; quick and --scene modes leave them out.
case " $* " in
  *" --quick "*|*" --scene "*|*" --help "*|*" -h "*) ;;
  *) RIGIDFMU_SKIP_SETUP=1 "$root/scripts/peers.sh" --out "$root/docs/reports/peers.json" || echo "peers: not measured" >&2 ;;
esac
export PYTHONPATH="$root/scripts${PYTHONPATH:+:$PYTHONPATH}"  # the reports (scripts/reports), not in the package
exec "$root/.venv/bin/python" -m reports.accuracy --build "$build" --no-build "$@"
