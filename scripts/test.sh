#!/usr/bin/env bash
# The whole test suite: setup, formatting, lints, docs, every crate's tests (including the
# SPIR-V build and the lavapipe conformance cases), the conformance run (tables on every
# backend, scenes rendered on cpu, embree and spirv), a fuzz smoke
# (scripts/fuzz.sh 20: every cargo-fuzz target for 20 s), the Python package's pytest
# suite (scripts/python.sh), and a smoke of the reference generators
# (scripts/reference-smoke.sh). Formatting and lints cover the fuzz and Python crates too (each
# its own workspace).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
export CARGO_TERM_COLOR=never
# The property tests (proptest) draw the same cases on every run of this script, so that a
# red run can be rerun and a green one means the same thing twice; set PROPTEST_RNG_SEED to
# draw others (`cargo test` alone draws fresh ones each time).
export PROPTEST_RNG_SEED="${PROPTEST_RNG_SEED:-20170721}"
step() { printf '\n== %s\n' "$*" >&2; }
step "cargo fmt --check"
cargo fmt --all -- --check
# fuzz/ is its own workspace, which `--all`/`--workspace` skip: check it by its manifest.
cargo fmt --manifest-path fuzz/Cargo.toml -- --check
cargo fmt --manifest-path python/Cargo.toml -- --check
step "cargo clippy -D warnings"
cargo clippy --workspace --all-targets -- -D warnings
# The benches' SPIR-V example sits behind their `spirv` feature.
cargo clippy -p scratchwave-benches --all-targets --features spirv -- -D warnings
# The fuzz crate with the same stable clippy (no sanitizer flags: lints only), in the fuzz
# build directory so its dependencies are checked once per cache.
CARGO_TARGET_DIR=${FUZZ_TARGET_DIR:-$PWD/fuzz/target} \
  cargo clippy --manifest-path fuzz/Cargo.toml --all-targets --locked -- -D warnings
# The Python extension crate, in the Python build directory (PyO3 finds python3 on PATH).
CARGO_TARGET_DIR=${PYTHON_TARGET_DIR:-$HOME/.cache/scratchwave/python-target} \
  cargo clippy --manifest-path python/Cargo.toml --all-targets -- -D warnings
step "cargo doc"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --quiet
step "cargo test"
cargo test --workspace
step "scratchwave run (conformance)"
cargo run --release --quiet -p scratchwave-conformance --bin scratchwave -- run
step "scripts/python.sh (Python package: build, install, pytest)"
scripts/python.sh
step "scripts/reference-smoke.sh (the sweep generators regenerate their committed subsets)"
scripts/reference-smoke.sh
step "scripts/fuzz.sh 20 (fuzz smoke: 20 s per target)"
scripts/fuzz.sh 20
