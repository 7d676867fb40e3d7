#!/usr/bin/env python3
"""Markdown table of the criterion medians: per operation (the iteration median divided by
the number of cases one iteration runs), per backend, with ratios to rug and to
num-rational. Reads $CARGO_TARGET_DIR/criterion (default ./target/criterion).

    python3 report.py [--cpu] [CRITERION_DIR]

--cpu reads the groups of a run with EXACT_BENCH_CLOCK=cpu (thread CPU time, `<kernel>-cpu`).
"""
import json
import os
import sys

KERNELS = [
    # group, label, cases per iteration
    ("orient3d", "orient3d (one 3×3 determinant + sign)", 48),
    ("half_split", "bicubic half-split (4 quarter nets)", 4),
    ("compose6", "bicubic ∘ chord, degree 6", 4),
    ("compose8", "bi-(3,5) ∘ chord, degree 8", 4),
]
BACKENDS = ["num-rational", "num-rational+bigint0.5", "rug", "dashu", "malachite"]
PURE_RUST = ["num-rational", "num-rational+bigint0.5", "dashu", "malachite"]


def fmt(ns):
    return f"{ns / 1000:.2f} µs" if ns >= 1000 else f"{ns:.0f} ns"


def main():
    args = sys.argv[1:]
    suffix = "-cpu" if "--cpu" in args else ""
    args = [a for a in args if a != "--cpu"]
    root = args[0] if args else os.path.join(
        os.environ.get("CARGO_TARGET_DIR", os.path.join(os.path.dirname(os.path.abspath(__file__)), "target")), "criterion")
    med = {}
    for group, _, n in KERNELS:
        for b in BACKENDS:
            path = os.path.join(root, group + suffix, b, "new", "estimates.json")
            if os.path.exists(path):
                with open(path) as f:
                    e = json.load(f)
                med[group, b] = (e["median"]["point_estimate"] / n,
                                 e["median"]["confidence_interval"]["lower_bound"] / n,
                                 e["median"]["confidence_interval"]["upper_bound"] / n)
    clock = "thread CPU time" if suffix else "wall time"
    print(f"Median {clock} per operation (95% CI of the median in brackets):\n")
    print("| operation | " + " | ".join(BACKENDS) + " |")
    print("|---|" + "---:|" * len(BACKENDS))
    for group, label, _ in KERNELS:
        cells = []
        for b in BACKENDS:
            m = med.get((group, b))
            cells.append(f"{fmt(m[0])} [{fmt(m[1])}–{fmt(m[2])}]" if m else "–")
        print(f"| {label} | " + " | ".join(cells) + " |")
    for ref in ["rug", "num-rational"]:
        print(f"\nRatio to {ref} (time ÷ {ref}'s time; < 1 is faster):\n")
        print("| operation | " + " | ".join(BACKENDS) + " |")
        print("|---|" + "---:|" * len(BACKENDS))
        for group, label, _ in KERNELS:
            r = med.get((group, ref))
            cells = [f"{med[group, b][0] / r[0]:.2f}×" if r and (group, b) in med else "–"
                     for b in BACKENDS]
            print(f"| {label} | " + " | ".join(cells) + " |")
    print("\nFastest pure-Rust backend per operation, against the 1.5× rule:\n")
    print("| operation | fastest pure Rust | ÷ rug | within 1.5× of rug |")
    print("|---|---|---:|---|")
    for group, label, _ in KERNELS:
        have = [b for b in PURE_RUST if (group, b) in med]
        if not have or (group, "rug") not in med:
            continue
        best = min(have, key=lambda b: med[group, b][0])
        ratio = med[group, best][0] / med[group, "rug"][0]
        print(f"| {label} | {best} | {ratio:.2f}× | {'yes' if ratio <= 1.5 else 'no'} |")


if __name__ == "__main__":
    main()
