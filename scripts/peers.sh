#!/usr/bin/env bash
# scripts/peers.sh [--quick] [--out FILE]
# Measures the peer engines (MuJoCo from PyPI) on the reference problems that
# report_accuracy.py puts them beside: error against the same independent reference
# and time per simulated second. Their own venv (.venv-peers), so that the project's
# packages never depend on them.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
[ -n "${RIGIDFMU_SKIP_SETUP:-}" ] || "$root/scripts/setup.sh"
venv="$root/.venv-peers"
stamp="$venv/.requirements.sha256"
want="$(sha256sum "$root/scripts/peers-requirements.txt" | cut -d' ' -f1)"
if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$want" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q --disable-pip-version-check -r "$root/scripts/peers-requirements.txt"
  echo "$want" > "$stamp"
fi
exec "$venv/bin/python" "$root/scripts/peers.py" "$@"
