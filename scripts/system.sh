#!/usr/bin/env bash
# scripts/system.sh scripts/systems/NAME [--master libcosim|fmpy|both] [--out DIR]
# Builds the FMUs of one example system (its scenes with rigidfmu, its C controllers
# against fmpy's FMI headers), runs its system.ssd in libcosim (the Open Simulation
# Platform's engine; --master fmpy or both), prints the outcome and exits 0 only when
# it holds (docs/guide/systems.md). FMUs and recordings go to out/systems/NAME.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ $# -lt 1 ]; then
  echo "usage: $0 scripts/systems/NAME [--master libcosim|fmpy|both] [--out DIR]" >&2
  exit 2
fi
[ -n "${RIGIDFMU_SKIP_SETUP:-}" ] || "$root/scripts/setup.sh"
export PYTHONPATH="$root/scripts${PYTHONPATH:+:$PYTHONPATH}"
exec "$root/.venv/bin/python" -m systems "$@"
