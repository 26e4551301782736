#!/usr/bin/env bash
# scripts/report.sh KIND [OPTIONS]: one of the generated reports, made from this source
# tree (they need its build, the benchmarks and, for some, MuJoCo in .venv-peers, so they
# are not part of the rigidfmu package: scripts/reports). KIND: accuracy
# (report_accuracy.sh), stability (stress.sh), performance (bench.sh), fmus
# (docs/reports/fmus.md: the example FMUs), pruning (what leaving out unused physics
# modules saves per step). Each has --help.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
kind="${1:-}"
[ $# -gt 0 ] && shift
case "$kind" in
  accuracy) exec "$root/scripts/report_accuracy.sh" "$@" ;;
  stability) exec "$root/scripts/stress.sh" "$@" ;;
  performance) exec "$root/scripts/bench.sh" "$@" ;;
  fmus) module=fmu_table ;;
  pruning) module=pruning ;;
  *) echo "usage: scripts/report.sh accuracy|stability|performance|fmus|pruning [OPTIONS]" >&2; exit 2 ;;
esac
[ -n "${RIGIDFMU_SKIP_SETUP:-}" ] || "$root/scripts/setup.sh"
export PYTHONPATH="$root/scripts${PYTHONPATH:+:$PYTHONPATH}"
exec "$root/.venv/bin/python" -m "reports.$module" "$@"
