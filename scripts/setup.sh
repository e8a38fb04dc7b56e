#!/usr/bin/env bash
# Installs everything scratchwave needs on a Debian 12 machine, idempotently:
#   * apt packages: Vulkan loader + lavapipe, libclang (bindgen), SPIRV-Tools, python3 with
#     venv (the Python package's test environment, scripts/python.sh), g++ (libFuzzer, built
#     by the fuzz targets of scripts/fuzz.sh; also the C ABI example);
#   * Rust toolchains: the pinned stable (rust-toolchain.toml) and the rust-gpu nightly;
#   * Embree 4.4 into .deps/embree (scripts/fetch-embree.sh), unless EMBREE_DIR is set.
# Safe to run repeatedly; each step checks before it installs.
set -euo pipefail
cd "$(dirname "$0")/.."

STABLE=1.95.0
NIGHTLY=nightly-2026-08-15
APT_PACKAGES=(mesa-vulkan-drivers libvulkan1 libclang-dev spirv-tools python3 python3-pip python3-venv g++)

SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO=sudo; fi

log() { printf '[setup] %s\n' "$*" >&2; }

missing=()
for p in "${APT_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  log "apt-get install ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
else
  log "apt packages present"
fi

if ! command -v rustup >/dev/null 2>&1; then
  if [ -x "$HOME/.cargo/bin/rustup" ]; then
    export PATH="$HOME/.cargo/bin:$PATH"
  else
    log "rustup is required (https://rustup.rs); it is not packaged for Debian 12"
    exit 1
  fi
fi
if ! rustup toolchain list | grep -q "^$STABLE"; then
  log "installing Rust $STABLE"
  rustup toolchain install "$STABLE" --profile minimal -c rustfmt -c clippy
fi
rustup component list --toolchain "$STABLE" --installed | grep -q '^clippy' || rustup component add --toolchain "$STABLE" clippy rustfmt
if ! rustup toolchain list | grep -q "^$NIGHTLY"; then
  log "installing $NIGHTLY (rust-gpu)"
  rustup toolchain install "$NIGHTLY" --profile minimal -c rust-src -c rustc-dev -c llvm-tools
else
  have=$(rustup component list --toolchain "$NIGHTLY" --installed)
  for c in rust-src rustc-dev llvm-tools; do
    echo "$have" | grep -q "^$c" || rustup component add --toolchain "$NIGHTLY" "$c"
  done
fi

if [ -x scripts/fetch-embree.sh ]; then
  scripts/fetch-embree.sh
fi
log "ready"
