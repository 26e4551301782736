#!/usr/bin/env bash
# scripts/study.sh STUDY [options]: a parameter study of an FMU on Dask (`rigidfmu study`;
# --help for the study file's format). Installs what is missing first, like run.sh.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
[ -n "${RIGIDFMU_SKIP_SETUP:-}" ] || "$root/scripts/setup.sh"
# the scene variants are built by build_fmu.sh, which need not set up again
RIGIDFMU_SKIP_SETUP=1 exec "$root/.venv/bin/python" -m rigidfmu study "$@"
