#!/usr/bin/env bash
# GPU check for a machine with a real GPU: the whole conformance run (BRDF tables on cpu,
# simd and spirv; every conformance scene on cpu, embree and spirv) on the GPU adapter, the
# table and light throughput of every backend, and the frame time of the Velinov Table 2
# scene on every backend, printed as one report.
#
#   scripts/gpu-check.sh                      # builds here (setup, release build), then checks
#   scripts/gpu-check.sh --bundle FILE.tar.xz # runs the binaries scripts/gpu-bundle.sh packed
#
# SCRATCHWAVE_ADAPTER defaults to gpu. Needs a Vulkan loader (libvulkan1) and the GPU's
# Vulkan driver; without them the spirv checks fail with the reason. Exit status 1 if any
# check failed or a step did not finish. Output files go to target/gpu-check.
set -euo pipefail
cd "$(dirname "$0")/.."
export SCRATCHWAVE_ADAPTER="${SCRATCHWAVE_ADAPTER:-gpu}"
export CARGO_TERM_COLOR=never
out=target/gpu-check
mkdir -p "$out"
start=$(date +%s)
if [ "${1:-}" = "--bundle" ]; then
  [ -f "${2:-}" ] || { echo "error: --bundle needs the archive scripts/gpu-bundle.sh wrote" >&2; exit 2; }
  bin=$out/bundle
  rm -rf "$bin"
  mkdir -p "$bin"
  tar -C "$bin" -xJf "$2"
  export SCRATCHWAVE_EMBREE_LIBRARY="$PWD/$bin/embree/libembree4.so.4"
  if [ "$(cat "$bin/commit")" != "$(git rev-parse HEAD 2>/dev/null || echo unknown)" ]; then
    echo "note: the bundle is of commit $(cat "$bin/commit"), the checkout is not" >&2
  fi
  examples=$bin
else
  scripts/setup.sh
  cargo build --release --quiet -p scratchwave-conformance --bin scratchwave --example scene_timing
  cargo build --release --quiet -p scratchwave-benches --features spirv --example throughput
  bin=${CARGO_TARGET_DIR:-target}/release
  examples=$bin/examples
fi
built=$(date +%s)
status=0
"$bin/scratchwave" run --cases conformance/cases --cases reference/golden/tables \
  --scenes conformance/scenes --spirv-scenes yes --out "$out" >"$out/run.txt" 2>&1 || status=$?
"$examples/throughput" 1000000 >"$out/throughput.txt" 2>&1 || status=$?
"$examples/scene_timing" benches/scenes/velinov_table2.json 3 >"$out/timing.txt" 2>&1 || status=$?
end=$(date +%s)
echo "# scratchwave GPU check (adapter: $SCRATCHWAVE_ADAPTER)"
grep -E '^backends:|^note:|^conformance:' "$out/run.txt" || true
echo
sed -n '/^## Scenes/,$p' "$out/report.md" 2>/dev/null || tail -20 "$out/run.txt"
echo
cat "$out/throughput.txt"
echo
cat "$out/timing.txt"
echo
echo "build $((built - start)) s, checks $((end - built)) s; exit status $status"
[ "$status" -eq 0 ] || exit 1
