#!/usr/bin/env bash
# scripts/peers.sh [--quick] [--out FILE]
# Measures the peer engines (MuJoCo from PyPI) on the reference problems that
# the accuracy report (reports.accuracy) puts them beside: error against the same independent reference
# and time per simulated second. Their own venv (.venv-peers), so that the project's
# packages never depend on them.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
[ -n "${RIGIDFMU_SKIP_SETUP:-}" ] || "$root/scripts/setup.sh"
. "$root/scripts/peers_venv.sh"
export PYTHONPATH="$root/scripts${PYTHONPATH:+:$PYTHONPATH}"  # the reports (scripts/reports)
exec "$peers_venv/bin/python" -m reports.accuracy_peers "$@"
