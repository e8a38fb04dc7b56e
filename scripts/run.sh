#!/usr/bin/env bash
# The main job: the cross-backend conformance run over the committed cases, with an
# agreement/accuracy report (also written to target/conformance/report.{md,json}).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cargo run --release --quiet -p scratchwave-conformance --bin scratchwave -- run "$@"
