#!/usr/bin/env bash
# Packs what scripts/gpu-check.sh runs into one archive, for a GPU machine that has no Rust
# toolchain or no network: the `scratchwave` CLI and the `scene_timing` and `throughput`
# examples (release, stripped; the SPIR-V module is inside them) and the Embree library
# they load. The machine needs x86-64 Linux with a glibc at least this one's, a Vulkan
# loader and its GPU's Vulkan driver.
#
#   scripts/gpu-bundle.sh [OUT.tar.xz]      # default target/gpu-bundle.tar.xz
#   # on the GPU machine, in a checkout of the same commit:
#   scripts/gpu-check.sh --bundle OUT.tar.xz
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
out=$(realpath -m "${1:-target/gpu-bundle.tar.xz}")
export CARGO_TERM_COLOR=never
cargo build --release --quiet -p scratchwave-conformance --bin scratchwave --example scene_timing
cargo build --release --quiet -p scratchwave-benches --features spirv --example throughput
bin=${CARGO_TARGET_DIR:-target}/release
embree=${EMBREE_DIR:-.deps/embree}
lib=""
for dir in "$embree/lib" "$embree/lib64" "$embree"; do
  if [ -f "$dir/libembree4.so.4" ]; then lib=$dir; break; fi
done
[ -n "$lib" ] || { echo "error: no libembree4.so.4 under $embree" >&2; exit 1; }
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir "$stage/embree"
cp "$bin/scratchwave" "$bin/examples/scene_timing" "$bin/examples/throughput" "$stage/"
strip "$stage/scratchwave" "$stage/scene_timing" "$stage/throughput"
# The library and the libraries beside it that it needs (TBB), links kept as links.
cp -a "$lib"/libembree4.so* "$lib"/libtbb.so* "$stage/embree/"
git rev-parse HEAD >"$stage/commit"
mkdir -p "$(dirname "$out")"
tar -C "$stage" -cJf "$out" .
echo "wrote $out ($(du -h "$out" | cut -f1), commit $(cat "$stage/commit"))"
