#!/usr/bin/env bash
# The Python package: a virtual environment (outside the clone, reused), the pinned test
# requirements, the package built by maturin and installed, then its pytest suite.
#   scripts/python.sh          build, install and test
#   scripts/python.sh install  build and install only (then: "$SCRATCHWAVE_VENV/bin/python")
# The venv lives in $SCRATCHWAVE_VENV (default ~/.cache/scratchwave/venv); the extension's
# cargo build in $PYTHON_TARGET_DIR (default ~/.cache/scratchwave/python-target).
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TARGET_DIR_MAIN="${CARGO_TARGET_DIR:-$PWD/target}"
log() { printf '[python] %s\n' "$*" >&2; }
. scripts/venv.sh
venv_with python/requirements-test.txt .scratchwave-requirements
export PATH="$VENV/bin:$PATH"
log "building and installing the package (maturin)"
CARGO_TARGET_DIR="${PYTHON_TARGET_DIR:-$HOME/.cache/scratchwave/python-target}" \
  python -m pip install -q --no-build-isolation --force-reinstall --no-deps ./python
if [ "${1:-test}" = install ]; then
  exit 0
fi
log "pytest python/tests"
# The tests build the release CLI and the C static library in the main target directory.
CARGO_TARGET_DIR="$CARGO_TARGET_DIR_MAIN" python -m pytest -q python/tests
