#!/usr/bin/env bash
# Correctness first (every backend equals num-rational exactly), then the timings, then the
# Markdown tables. Extra arguments go to criterion, e.g. `bash run.sh --measurement-time 3`.
# CARGO_TARGET_DIR is honoured (default: ./target).
set -euo pipefail
cd "$(dirname "$0")"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$PWD/target}"
rustc --version
cargo test --release
cargo run --release --example crosscheck
cargo bench --bench exact -- "$@"
python3 report.py
