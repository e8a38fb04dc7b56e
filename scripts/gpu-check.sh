#!/usr/bin/env bash
# GPU check for a machine with a real GPU: the whole conformance run (BRDF tables on cpu,
# simd and spirv; every conformance scene on cpu, embree and spirv) on the GPU adapter, the
# table and light throughput of every backend, and the frame time of the Velinov Table 2
# scene on every backend, printed as one report.
#
#   scripts/gpu-check.sh                      # builds and packs here (scripts/gpu-bundle.sh), then checks
#   scripts/gpu-check.sh --bundle FILE.tar.xz # runs the binaries scripts/gpu-bundle.sh packed
#
# SCRATCHWAVE_ADAPTER defaults to gpu. Needs a Vulkan loader (libvulkan1) and the GPU's
# Vulkan driver; without them the spirv checks fail with the reason. Exit status 1 if any
# check failed or a step did not finish. Output files go to target/gpu-check.
set -euo pipefail
# The archive as the caller named it, before changing to the repository root.
archive=""
if [ "${1:-}" = "--bundle" ] && [ -n "${2:-}" ]; then archive=$(realpath -m "$2"); fi
cd "$(dirname "$0")/.."
export SCRATCHWAVE_ADAPTER="${SCRATCHWAVE_ADAPTER:-gpu}"
export CARGO_TERM_COLOR=never
out=target/gpu-check
mkdir -p "$out"
start=$(date +%s)
if [ "${1:-}" = "--bundle" ]; then
  [ -f "$archive" ] || { echo "error: --bundle needs the archive scripts/gpu-bundle.sh wrote" >&2; exit 2; }
  bundle=$archive
else
  # One list of binaries: build them here through the packing script, then run its archive.
  bundle=$out/gpu-bundle.tar.xz
  scripts/gpu-bundle.sh "$bundle"
fi
bin=$out/bundle
rm -rf "$bin"
mkdir -p "$bin"
tar -C "$bin" -xJf "$bundle"
export SCRATCHWAVE_EMBREE_LIBRARY="$PWD/$bin/embree/libembree4.so.4"
if [ ! -f "$bin/commit" ] || [ "$(cat "$bin/commit")" != "$(git rev-parse HEAD 2>/dev/null || echo unknown)" ]; then
  echo "note: the bundle is of commit $(cat "$bin/commit" 2>/dev/null || echo unknown), the checkout is not" >&2
fi
built=$(date +%s)
status=0
"$bin/scratchwave" run --cases conformance/cases --cases reference/golden/tables \
  --scenes conformance/scenes --spirv-scenes yes --out "$out" >"$out/run.txt" 2>&1 || status=$?
"$bin/throughput" 1000000 >"$out/throughput.txt" 2>&1 || status=$?
"$bin/scene_timing" benches/scenes/velinov_table2.json 3 >"$out/timing.txt" 2>&1 || status=$?
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
