#!/usr/bin/env bash
# The reference generators still regenerate their committed subsets: reference/smoke.py runs
# each sweep script for its first queries and compares what it writes with the committed
# CSVs. Uses the Python test environment (scripts/venv.sh, shared with scripts/python.sh)
# with reference/requirements.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
log() { printf '[reference] %s\n' "$*" >&2; }
. scripts/venv.sh
venv_with reference/requirements.txt .scratchwave-reference-requirements
log "reference/smoke.py"
"$VENV/bin/python" reference/smoke.py
