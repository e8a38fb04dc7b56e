#!/usr/bin/env bash
# The reference generators still regenerate their committed subsets: reference/smoke.py runs
# each sweep script for its first queries and compares what it writes with the committed
# CSVs. Uses the Python test environment ($SCRATCHWAVE_VENV, default
# ~/.cache/scratchwave/venv; scripts/python.sh creates it) with reference/requirements.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
VENV="${SCRATCHWAVE_VENV:-$HOME/.cache/scratchwave/venv}"
log() { printf '[reference] %s\n' "$*" >&2; }
if [ ! -x "$VENV/bin/python" ]; then
  log "creating $VENV"
  mkdir -p "$(dirname "$VENV")"
  python3 -m venv "$VENV"
fi
req=reference/requirements.txt
stamp="$VENV/.scratchwave-reference-requirements"
if ! cmp -s "$req" "$stamp" 2>/dev/null; then
  log "pip install -r $req"
  "$VENV/bin/python" -m pip install -q -r "$req"
  cp "$req" "$stamp"
fi
log "reference/smoke.py"
"$VENV/bin/python" reference/smoke.py
