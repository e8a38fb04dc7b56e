#!/usr/bin/env bash
# Fuzz smoke (or long run): every cargo-fuzz target for SECONDS seconds (default 30).
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]
#
# Installs cargo-fuzz (pinned) and the pinned nightly if missing, builds the targets with
# debug assertions (overflow checks) and AddressSanitizer, then runs each target with
# libFuzzer on fuzz/corpus/TARGET (a working corpus, git-ignored) seeded from the committed
# fuzz/seeds/TARGET. Prints per target: executions, corpus size, crashes (files written to
# fuzz/artifacts/TARGET: crash-*, oom-*, timeout-*, leak-*). Exits 1 if any target crashed.
# FUZZ_TARGET_DIR overrides the build directory (default fuzz/target).
set -euo pipefail
cd "$(dirname "$0")/.."

SECONDS_PER_TARGET=${1:-30}
shift || true
NIGHTLY=nightly-2026-08-15
CARGO_FUZZ_VERSION=0.13.1
TARGETS=("$@")
if [ ${#TARGETS[@]} -eq 0 ]; then
  TARGETS=(table_spec footprint_spec scratch_sources kernel_raw scene_file obj_mesh light_spec)
fi

log() { printf '[fuzz] %s\n' "$*" >&2; }

if ! command -v c++ >/dev/null 2>&1; then
  log "libFuzzer needs a C++ compiler: run scripts/setup.sh (installs g++)"
  exit 1
fi
if ! rustup toolchain list | grep -q "^$NIGHTLY"; then
  log "installing $NIGHTLY"
  rustup toolchain install "$NIGHTLY" --profile minimal
fi
if [ "$(cargo fuzz --version 2>/dev/null || true)" != "cargo-fuzz $CARGO_FUZZ_VERSION" ]; then
  log "installing cargo-fuzz $CARGO_FUZZ_VERSION"
  cargo install cargo-fuzz --version "$CARGO_FUZZ_VERSION" --locked --force
fi

export CARGO_TARGET_DIR=${FUZZ_TARGET_DIR:-$PWD/fuzz/target}
log "building the fuzz targets (nightly, ASan, debug assertions)"
cargo "+$NIGHTLY" fuzz build --debug-assertions
# The targets run straight from the build directory, as `cargo fuzz run` would run them
# (same ASAN_OPTIONS) but without one cargo invocation (and fingerprint check) per target.
HOST=$(rustc "+$NIGHTLY" -vV | sed -n 's/^host: //p')
BIN_DIR=$CARGO_TARGET_DIR/$HOST/release
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_odr_violation=0"

failed=0
summary=()
for t in "${TARGETS[@]}"; do
  corpus=fuzz/corpus/$t
  artifacts=fuzz/artifacts/$t
  mkdir -p "$corpus" "$artifacts"
  before=$(find "$artifacts" -type f | wc -l)
  log "$t: ${SECONDS_PER_TARGET}s"
  logf=$(mktemp)
  set +e
  "$BIN_DIR/$t" "$corpus" "fuzz/seeds/$t" \
    -max_total_time="$SECONDS_PER_TARGET" -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$artifacts/" >"$logf" 2>&1
  rc=$?
  set -e
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$logf" | grep -o '[0-9]*$' | tail -n 1)
  if [ -z "$execs" ]; then
    execs=$(grep -o '^#[0-9]*' "$logf" | tail -n 1 | tr -d '#')
  fi
  size=$(find "$corpus" -type f | wc -l)
  crashes=$(($(find "$artifacts" -type f | wc -l) - before))
  if [ "$rc" != 0 ] || [ "$crashes" != 0 ]; then
    failed=1
    log "$t FAILED (exit $rc); the panic, then the last lines of the log:"
    grep -m 1 -A 3 'panicked at' "$logf" >&2 || true
    tail -n 25 "$logf" >&2
  fi
  rm -f "$logf"
  summary+=("$(printf '%-16s executions %10s  corpus %6s  crashes %s' "$t" "${execs:-?}" "$size" "$crashes")")
done
printf '\n'
printf '%s\n' "${summary[@]}"
exit "$failed"
