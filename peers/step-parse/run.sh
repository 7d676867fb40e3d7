#!/usr/bin/env bash
# STEP parsing throughput, vericad beside foxtrot's `step` crate and Open CASCADE, in one run.
# From the repository root of a clean clone:  bash peers/step-parse/run.sh
# Needs: cargo (crates.io reachable for criterion etc.), python3 with cadquery-ocp-novtk,
# /usr/bin/time (Debian package `time`) for peak memory. Results go to $OUT (default
# peers/step-parse/out/): criterion's report, occt.jsonl, peak_rss.tsv and table.md.
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HERE/target}"
OUT="${OUT:-$HERE/out}"
mkdir -p "$OUT"
cd "$ROOT"

FILES=()
for f in tests/data/public/*.step tests/data/public/*.stp tests/data/public/occt-written/*.step \
         tests/data/large/*.step tests/data/large/*.stp; do
  [ -f "$f" ] && FILES+=("$f")
done

python3 -c 'import OCP' 2>/dev/null || pip install cadquery-ocp-novtk

# 1. vericad and foxtrot: criterion (decimal MB/s), one group per file.
rm -rf "$CARGO_TARGET_DIR/criterion"
cargo bench --manifest-path "$HERE/Cargo.toml" --bench parse 2>&1 | tee "$OUT/criterion.txt"

# 2. Open CASCADE ReadFile, same files, right after.
python3 "$HERE/occt_readfile.py" "${FILES[@]}" | tee "$OUT/occt.jsonl"

# 3. Peak memory (max RSS) of one parse per process; `none` = read the file only (baseline).
cargo build --release --manifest-path "$HERE/Cargo.toml" --bin parse_once
RUNNER="$CARGO_TARGET_DIR/release/parse_once"
rss() { /usr/bin/time -f '%M' "$@" 2>&1 >/dev/null | tail -1; }
printf 'file\tnone\tvericad\tfoxtrot\tread_model\tpython_occt_import\tocct_readfile\n' > "$OUT/peak_rss.tsv"
occt_base=$(rss python3 "$HERE/occt_readfile.py" --once)
for f in "${FILES[@]}"; do
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$f" "$(rss "$RUNNER" none "$f")" "$(rss "$RUNNER" vericad "$f")" \
    "$(rss "$RUNNER" foxtrot "$f")" "$(rss "$RUNNER" read_model "$f")" "$occt_base" \
    "$(rss python3 "$HERE/occt_readfile.py" --once "$f")" >> "$OUT/peak_rss.tsv"
done
cat "$OUT/peak_rss.tsv"

# 4. Table.
python3 "$HERE/report.py" "$CARGO_TARGET_DIR/criterion" "$OUT/occt.jsonl" "$OUT/peak_rss.tsv" \
  | tee "$OUT/table.md"
