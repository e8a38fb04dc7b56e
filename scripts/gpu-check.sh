#!/usr/bin/env bash
# GPU check for a machine with a real GPU: builds, renders every conformance scene on
# cpu, embree and spirv (the GPU adapter) and compares them, then times the Velinov
# Table 2 scene on the CPU and the GPU, and prints one table. Meant to fit in 8 minutes
# from a fresh clone (most of it the first build; see README "GPU check").
#
#   scripts/gpu-check.sh            # SCRATCHWAVE_ADAPTER defaults to gpu here
#
# Needs a Vulkan loader (libvulkan1) and the GPU's Vulkan driver; without them the spirv
# comparisons fail with the reason and the script exits 1.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
export SCRATCHWAVE_ADAPTER="${SCRATCHWAVE_ADAPTER:-gpu}"
export CARGO_TERM_COLOR=never
start=$(date +%s)
cargo build --release --quiet -p scratchwave-conformance --bin scratchwave --example scene_timing
bin=${CARGO_TARGET_DIR:-target}/release
built=$(date +%s)
out=target/gpu-check
mkdir -p "$out"
status=0
"$bin/scratchwave" run --scenes conformance/scenes --spirv-scenes yes --out "$out" >"$out/run.txt" || status=$?
"$bin/examples/scene_timing" benches/scenes/velinov_table2.json 3 >"$out/timing.txt" || status=$?
end=$(date +%s)
echo "# scratchwave GPU check (adapter: $SCRATCHWAVE_ADAPTER)"
grep -E '^backends:|^note:' "$out/report.md" || true
echo
sed -n '/^## Scenes/,$p' "$out/report.md"
echo
cat "$out/timing.txt"
echo
echo "build $((built - start)) s, checks $((end - built)) s; exit status $status"
exit "$status"
