# Sourced by scripts/python.sh and scripts/reference-smoke.sh: the Python test environment
# they share ($SCRATCHWAVE_VENV, default ~/.cache/scratchwave/venv, outside the clone).
#   venv_with REQUIREMENTS STAMP   creates the venv if missing and installs the pinned file
#                                  into it unless $VENV/STAMP holds that same file
VENV="${SCRATCHWAVE_VENV:-$HOME/.cache/scratchwave/venv}"

venv_with() {
  local req="$1" stamp="$VENV/$2"
  if [ ! -x "$VENV/bin/python" ]; then
    log "creating $VENV"
    mkdir -p "$(dirname "$VENV")"
    python3 -m venv "$VENV"
  fi
  if ! cmp -s "$req" "$stamp" 2>/dev/null; then
    log "pip install -r $req"
    "$VENV/bin/python" -m pip install -q --upgrade pip
    "$VENV/bin/python" -m pip install -q -r "$req"
    cp "$req" "$stamp"
  fi
}
