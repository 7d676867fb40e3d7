#!/usr/bin/env python3
"""Open CASCADE's STEP parse, timed: STEPControl_Reader().ReadFile(path) (file -> OCCT's entity
model; no TransferRoots, so no B-rep is built). Needs `pip install cadquery-ocp-novtk`.

Usage: occt_readfile.py [--runs N] [--once] FILE...
Prints one JSON object per file: bytes, median/min seconds over N runs, MB/s (decimal, bytes /
median), the number of entities OCCT read. --once reads each file once (for peak memory
under /usr/bin/time -v) and prints the entity count.
"""
import json
import os
import statistics
import sys
import time

import OCP.OCP as o


def quiet():
    # OCCT's messenger prints to stdout; drop its printers so printing is not timed.
    m = o.Message.Message.DefaultMessenger_s()
    for p in list(m.Printers()):
        m.RemovePrinter(p)


def read_once(path):
    r = o.STEPControl.STEPControl_Reader()
    t0 = time.perf_counter()
    st = r.ReadFile(path)
    t1 = time.perf_counter()
    if st != o.IFSelect.IFSelect_ReturnStatus.IFSelect_RetDone:
        raise SystemExit(f"{path}: ReadFile returned {st}")
    return t1 - t0, r.StepModel().NbEntities()


def main(argv):
    runs, once, files = 30, False, []
    it = iter(argv)
    for a in it:
        if a == "--runs":
            runs = int(next(it))
        elif a == "--once":
            once = True
        else:
            files.append(a)
    quiet()
    for f in files:
        if once:
            _, n = read_once(f)
            print(json.dumps({"file": f, "entities": n}))
            continue
        size = os.path.getsize(f)
        # Warm-up: first read loads OCCT's STEP protocol tables and the file into the page cache.
        for _ in range(3):
            read_once(f)
        # At least `runs` reads and at least ~2 s of reading.
        ts, n, t_start = [], 0, time.perf_counter()
        while len(ts) < runs or time.perf_counter() - t_start < 2.0:
            t, n = read_once(f)
            ts.append(t)
        med = statistics.median(ts)
        print(json.dumps({
            "file": f, "bytes": size, "runs": len(ts), "median_s": med, "min_s": min(ts),
            "mb_per_s": size / med / 1e6, "entities": n,
        }), flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
