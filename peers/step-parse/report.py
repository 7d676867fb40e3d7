#!/usr/bin/env python3
"""Render run.sh's results as Markdown tables.

Usage: report.py CRITERION_DIR OCCT_JSONL PEAK_RSS_TSV
MB/s are decimal (10^6 bytes) over the median time per parse: criterion's median for vericad and
foxtrot, the median of the timed ReadFile calls for Open CASCADE.
"""
import csv
import glob
import json
import os
import sys


def criterion(dirname):
    out = {}  # (group, function) -> median ns
    for bj in glob.glob(os.path.join(dirname, "*", "*", "new", "benchmark.json")):
        b = json.load(open(bj))
        e = json.load(open(os.path.join(os.path.dirname(bj), "estimates.json")))
        out[(b["group_id"], b["function_id"])] = e["median"]["point_estimate"]
    return out


def main(crit_dir, occt_jsonl, rss_tsv):
    crit = criterion(crit_dir)
    occt = {}
    for line in open(occt_jsonl):
        line = line.strip()
        if line.startswith("{"):
            r = json.loads(line)
            occt[r["file"]] = r
    print("| file | size (bytes) | vericad parse MB/s | foxtrot step MB/s | OCCT ReadFile MB/s "
          "| vericad read_model MB/s | vericad / foxtrot | vericad / OCCT |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for f, r in occt.items():
        size = r["bytes"]
        group = f.split("tests/data/", 1)[-1].replace("/", "__")
        t = {k: crit.get((group, k)) for k in ("vericad_parse", "foxtrot_parse", "vericad_read_model")}
        mbs = {k: (size / (ns * 1e-9) / 1e6 if ns else None) for k, ns in t.items()}
        o = r["mb_per_s"]
        fmt = lambda x: f"{x:.1f}" if x is not None else "—"
        ratio = lambda a, b: f"{a / b:.2f}×" if a and b else "—"
        print(f"| {f.split('tests/data/', 1)[-1]} | {size:,} | {fmt(mbs['vericad_parse'])} "
              f"| {fmt(mbs['foxtrot_parse'])} | {fmt(o)} | {fmt(mbs['vericad_read_model'])} "
              f"| {ratio(mbs['vericad_parse'], mbs['foxtrot_parse'])} "
              f"| {ratio(mbs['vericad_parse'], o)} |")
    print()
    print("Median time per parse (µs): vericad parse / foxtrot / OCCT ReadFile / vericad read_model")
    print()
    for f, r in occt.items():
        group = f.split("tests/data/", 1)[-1].replace("/", "__")
        ts = [crit.get((group, k)) for k in ("vericad_parse", "foxtrot_parse")]
        tr = crit.get((group, "vericad_read_model"))
        fmt = lambda ns: f"{ns / 1e3:.0f}" if ns else "—"
        print(f"- {group.replace('__', '/')}: {fmt(ts[0])} / {fmt(ts[1])} / "
              f"{r['median_s'] * 1e6:.0f} ({r['runs']} runs) / {fmt(tr)}")
    print()
    print("| file | max RSS, KiB: read file only | vericad parse | foxtrot parse | vericad read_model "
          "| python + OCP import | OCCT ReadFile |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for row in csv.DictReader(open(rss_tsv), delimiter="\t"):
        print(f"| {row['file'].split('tests/data/', 1)[-1]} | {row['none']} | {row['vericad']} "
              f"| {row['foxtrot']} | {row['read_model']} | {row['python_occt_import']} "
              f"| {row['occt_readfile']} |")


if __name__ == "__main__":
    main(*sys.argv[1:])
