#!/usr/bin/env bash
# Installs everything scratchwave needs on a Debian 12 machine, idempotently:
#   * apt packages: Vulkan loader + lavapipe, libclang (bindgen), SPIRV-Tools, python3 with
#     venv (the Python package's test environment, scripts/python.sh), g++ (libFuzzer, built
#     by the fuzz targets of scripts/fuzz.sh; also the C ABI example);
#   * lavapipe from Mesa 25 (bookworm-backports) on Debian 12: bookworm's own Mesa 22.3
#     lavapipe runs loops that neighbouring invocations leave at different trips wrongly
#     (ARCHITECTURE.md, *Divergence*), which the SPIR-V scene conformance would fail on;
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

# Mesa 25's lavapipe: add bookworm-backports (once) and take mesa-vulkan-drivers from it.
MESA_MIN_MAJOR=25
mesa_major() {
  local v
  v=$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true)
  v=${v#*:}
  echo "${v%%.*}"
}
codename=$(. /etc/os-release 2>/dev/null && echo "${VERSION_CODENAME:-}")
have=$(mesa_major)
if [ "${have:-0}" -ge "$MESA_MIN_MAJOR" ] 2>/dev/null; then
  log "lavapipe: Mesa $have"
elif [ "$codename" = bookworm ]; then
  if ! grep -rqs "bookworm-backports" /etc/apt/sources.list /etc/apt/sources.list.d/; then
    log "adding bookworm-backports (Mesa $MESA_MIN_MAJOR lavapipe)"
    printf '%s\n' "Types: deb" "URIs: http://deb.debian.org/debian" "Suites: bookworm-backports" \
      "Components: main" "Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg" |
      $SUDO tee /etc/apt/sources.list.d/scratchwave-bookworm-backports.sources >/dev/null
  fi
  log "apt-get install -t bookworm-backports mesa-vulkan-drivers"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq -t bookworm-backports \
    mesa-vulkan-drivers >/dev/null
  log "lavapipe: Mesa $(mesa_major)"
else
  log "lavapipe: Mesa ${have:-none} (below $MESA_MIN_MAJOR; not Debian 12, left as it is)"
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

# EMBREE_DIR names another Embree 4 install (backend-embree/build.rs); then fetch none.
if [ -z "${EMBREE_DIR:-}" ] && [ -x scripts/fetch-embree.sh ]; then
  scripts/fetch-embree.sh
fi
log "ready"
