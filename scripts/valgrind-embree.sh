#!/usr/bin/env bash
# Runs scratchwave-embree's tests under valgrind memcheck and fails on any memory error
# (invalid reads/writes, uses of uninitialised values, invalid frees).
#
#   scripts/valgrind-embree.sh
#
# Runs: every ABI canary, every ray-query path on small scenes, the segment radius query
# (10^3 segments x 10^4 queries, concurrency, edge cases). The 10^6-primitive tests are left
# out (hours under memcheck); they exercise the same code paths.
# Then a negative control: a test that hands Embree a 4.2-layout (too small) hit record
# must make memcheck report the 4-byte overflow, proving the check can fail.
#
# Known noise outside scratchwave is suppressed in scripts/valgrind-embree.supp.
# Note: valgrind does not emulate AVX-512, so Embree runs its AVX2 kernels here.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

command -v valgrind >/dev/null || { echo "valgrind-embree: valgrind not installed (apt-get install valgrind)" >&2; exit 2; }
export CARGO_BUILD_JOBS=${CARGO_BUILD_JOBS:-1}

# Build the test binaries and find them by target name.
mapfile -t BINARIES < <(cargo test -p scratchwave-embree --no-run --message-format=json 2>/dev/null |
    python3 -c '
import json, sys
for line in sys.stdin:
    m = json.loads(line)
    if m.get("reason") == "compiler-artifact" and m.get("executable") and m["target"]["kind"] == ["test"]:
        print(m["target"]["name"], m["executable"])
')
declare -A BIN
for entry in "${BINARIES[@]}"; do BIN[${entry%% *}]=${entry#* }; done
for name in abi rays segments; do
    [[ -n ${BIN[$name]:-} ]] || { echo "valgrind-embree: test binary '$name' not built" >&2; exit 2; }
done

MEMCHECK=(valgrind --tool=memcheck --error-exitcode=99 --suppressions="$ROOT/scripts/valgrind-embree.supp"
    --leak-check=no --num-callers=30)
LOG=$(mktemp -d)
trap 'rm -rf "$LOG"' EXIT
status=0

run() {
    local label=$1
    shift
    echo "== memcheck: $label"
    if "${MEMCHECK[@]}" --log-file="$LOG/$label.log" "$@" >"$LOG/$label.out" 2>&1; then
        echo "   ok: $(grep -h 'test result' "$LOG/$label.out") / $(grep -h 'ERROR SUMMARY' "$LOG/$label.log" | sed 's/^==[0-9]*== //')"
    else
        echo "   FAILED (exit $?):"
        tail -n 20 "$LOG/$label.out"
        grep -v '^==[0-9]*== *$' "$LOG/$label.log" | head -n 80
        status=1
    fi
}

run abi "${BIN[abi]}" --test-threads=2
run rays "${BIN[rays]}" --test-threads=2 small_scenes invalid_rays out_of_range scenes_are_queried
run segments "${BIN[segments]}" --test-threads=2 --exact thousand_segments \
    boundary_degenerate_and_invalid_queries queries_run_concurrently

echo "== memcheck negative control: a 4.2-layout hit record must be reported"
set +e
"${MEMCHECK[@]}" --log-file="$LOG/control.log" "${BIN[abi]}" --ignored --exact \
    memcheck_catches_a_4_2_layout_hit_record >"$LOG/control.out" 2>&1
control=$?
set -e
if [[ $control == 99 ]] && grep -q 'Invalid write of size 4' "$LOG/control.log"; then
    echo "   ok: memcheck reported $(grep -c 'Invalid write' "$LOG/control.log") invalid write(s) past the 80-byte record"
else
    echo "   FAILED: memcheck did not catch the overflow (exit $control)"
    head -n 40 "$LOG/control.log"
    status=1
fi

if [[ $status == 0 ]]; then
    echo "valgrind-embree: no invalid reads or writes"
else
    echo "valgrind-embree: memory errors found" >&2
fi
exit $status
