#!/usr/bin/env python3
"""Mutation campaign over the public CAD files: every file in tests/data/public is truncated
(33 %, 66 %, one byte short), bit-flipped (1, 16 and 256 bits, several seeds) and
digit-mutated (digits changed, numbers blown up to 1e308 / 1e-308, signs flipped), and each
mutant is run through the vericad commands that read it: `info`, `convert` (to JSON, read
back, `eval` at the domain centre of every surface; and to the file's own format), `ssi`
and `repair` — with a timeout and an RSS cap per run.

A run fails when it
- panics (exit 101, "panicked" on stderr) or dies by a signal (abort, out of memory);
- does not return within the timeout (a hang) or exceeds the RSS cap;
- exits with an unexpected code (anything but 0, 2 = bad input, 3 = uncertified);
- loses data silently: a mutant read with exit 0 that holds fewer surfaces, curves or
  triangles than the pristine file without saying so in a warning the pristine file does
  not have; a file truncated at 33 % or 66 % read with exit 0 and no warning; a converted
  model that reads back with other counts than its source without `convert` naming what
  it did not write; non-finite numbers (`null`, NaN, inf) in a written model; a
  conversion that exits 0 without writing its output.

Usage:
  scripts/mutation_campaign.py [--bin target/release/vericad] [--timeout 60] [--rss-mb 2048]
                               [--seeds 3] [--only NAME] [--jobs 1] [--keep DIR]

Prints one line per failure and a summary table; exit 1 when anything failed.
"""

import argparse
import json
import os
import random
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PUBLIC = ROOT / "tests" / "data" / "public"
OK_CODES = {0, 2, 3}


def mutants(data: bytes, seeds: int):
    """(name, bytes) of every mutation of `data`."""
    n = len(data)
    yield "trunc33", data[: n * 33 // 100]
    yield "trunc66", data[: n * 66 // 100]
    yield "trunc-1", data[: n - 1]
    for flips in (1, 16, 256):
        for s in range(seeds):
            r = random.Random(f"flip{flips}-{s}")
            b = bytearray(data)
            for _ in range(flips):
                i = r.randrange(n)
                b[i] ^= 1 << r.randrange(8)
            yield f"flip{flips}-s{s}", bytes(b)
    digits = [m.start() for m in re.finditer(rb"[0-9]", data)]
    numbers = [m.span() for m in re.finditer(rb"[-+]?[0-9]+\.?[0-9]*([eE][-+]?[0-9]+)?", data)]
    for count in (1, 16, 256):
        for s in range(seeds):
            r = random.Random(f"digit{count}-{s}")
            b = bytearray(data)
            for _ in range(min(count, len(digits))):
                b[r.choice(digits)] = ord(str(r.randrange(10)))
            yield f"digit{count}-s{s}", bytes(b)
    # Numbers replaced wholesale: huge, tiny, negated, zero.
    for kind, repl in (
        ("huge", b"1.E308"),
        ("tiny", b"4.9E-324"),
        ("neg", None),
        ("zero", b"0."),
    ):
        for s in range(seeds):
            r = random.Random(f"num{kind}-{s}")
            picks = sorted(r.sample(numbers, min(8, len(numbers))), reverse=True)
            b = bytearray(data)
            for lo, hi in picks:
                new = repl if repl is not None else b"-" + bytes(b[lo:hi]).lstrip(b"+-")
                b[lo:hi] = new
            yield f"num-{kind}-s{s}", bytes(b)


class Runner:
    def __init__(self, exe, timeout, rss_mb):
        self.exe = exe
        self.timeout = timeout
        self.rss_mb = rss_mb
        self.runs = 0
        self.max_rss_mb = 0.0
        self.slowest = (0.0, "")
        self.lock = threading.Lock()

    def run(self, args, label):
        """(code or None on timeout, stdout, stderr, peak RSS MB, seconds)."""
        cap = self.rss_mb * 2 * 1024 * 1024

        def limits():
            # A hard address-space cap well above the RSS cap keeps a runaway allocation from
            # taking the machine down; the RSS cap itself is checked from the child's rusage.
            resource.setrlimit(resource.RLIMIT_AS, (cap * 2, cap * 2))
            resource.setrlimit(resource.RLIMIT_CORE, (0, 0))

        t0 = time.monotonic()
        with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
            p = subprocess.Popen(
                [self.exe, *args], stdout=out, stderr=err, preexec_fn=limits
            )
            timed_out = False
            status, rss_kb = None, 0
            while True:
                pid, st, ru = os.wait4(p.pid, os.WNOHANG)
                if pid:
                    status, rss_kb = st, ru.ru_maxrss
                    break
                if time.monotonic() - t0 > self.timeout:
                    p.kill()
                    _, st, ru = os.wait4(p.pid, 0)
                    timed_out, rss_kb = True, ru.ru_maxrss
                    break
                time.sleep(0.01)
            p.returncode = 0  # reaped by wait4
            secs = time.monotonic() - t0
            out.seek(0)
            err.seek(0)
            so = out.read().decode("utf-8", "replace")
            se = err.read().decode("utf-8", "replace")
        if timed_out:
            code = None
        elif os.WIFSIGNALED(status):
            code = -os.WTERMSIG(status)
        else:
            code = os.WEXITSTATUS(status)
        rss = rss_kb / 1024
        with self.lock:
            self.runs += 1
            self.max_rss_mb = max(self.max_rss_mb, rss)
            if secs > self.slowest[0]:
                self.slowest = (secs, label)
        return code, so, se, rss, secs


def finite_numbers(x):
    """False when a parsed JSON value holds null or a non-finite number."""
    if x is None:
        return False
    if isinstance(x, float):
        return x == x and abs(x) != float("inf")
    if isinstance(x, list):
        return all(finite_numbers(v) for v in x)
    if isinstance(x, dict):
        return all(finite_numbers(v) for k, v in x.items() if k not in ("source", "unit"))
    return True


def counts(info):
    return (
        len(info.get("surfaces", [])),
        len(info.get("curves", [])),
        sum(t[2] for t in info.get("triangulations", [])),
    )


def check_mutant(r, path, name, pristine, work):
    """Failures of one mutant, as strings."""
    fails = []
    label = f"{path.name}/{name}"

    def run(args, what):
        code, so, se, rss, secs = r.run(args, f"{label} {what}")
        if code is None:
            fails.append(f"{label}: {what}: no result within {r.timeout} s (hang)")
        elif code < 0:
            fails.append(f"{label}: {what}: killed by signal {-code} (rss {rss:.0f} MB): {se[-300:]}")
        elif code == 101 or "panicked" in se:
            fails.append(f"{label}: {what}: panic: {se.strip()[-400:]}")
        elif code not in OK_CODES:
            fails.append(f"{label}: {what}: exit {code}: {se.strip()[-300:]}")
        if rss > r.rss_mb:
            fails.append(f"{label}: {what}: peak RSS {rss:.0f} MB above {r.rss_mb} MB")
        return code, so, se

    code, so, se = run(["info", "--json", str(path)], "info")
    if code != 0:
        return fails
    try:
        info = json.loads(so)
    except ValueError:
        fails.append(f"{label}: info: exit 0 but no JSON report")
        return fails
    new_warnings = [w for w in info.get("warnings", []) if w not in pristine["warnings"]]
    c = counts(info)
    if any(x < y for x, y in zip(c, pristine["counts"])) and not new_warnings:
        fails.append(
            f"{label}: silent loss: {c} (surfaces, curves, triangles) vs {pristine['counts']} in the pristine file, no new warning"
        )
    if name in ("trunc33", "trunc66") and not info.get("warnings"):
        fails.append(f"{label}: silent loss: a truncated file read with exit 0 and no warning ({c})")

    out = work / f"{name}.json"
    code, so, se = run(["convert", str(path), str(out)], "convert json")
    if code == 0:
        if not out.exists():
            fails.append(f"{label}: convert: exit 0 and no output")
        else:
            try:
                model = json.loads(out.read_text())
                if not finite_numbers(model):
                    fails.append(f"{label}: convert: non-finite number or null in the JSON model")
            except ValueError as e:
                fails.append(f"{label}: convert: unreadable JSON output: {e}")
            code2, so2, _ = run(["info", "--json", str(out)], "info of converted")
            if code2 == 0:
                back = json.loads(so2)
                # What the output does not hold must be said on stderr (the JSON model holds
                # surfaces and curves; triangulations are reported as not written).
                lost = [k for k, x, y in zip(("surface", "curve", "triangulation"), counts(back), c) if x != y]
                if any(k not in se for k in lost):
                    fails.append(f"{label}: convert: read back {counts(back)}, source {c}, unreported: {se.strip()[-200:]}")
                for s in back.get("surfaces", [])[:4]:
                    u0, u1, v0, v1 = s["domain"]
                    uv = f"{(u0 + u1) / 2!r},{(v0 + v1) / 2!r}"
                    run(["eval", str(out), "--surface", str(s["index"]), "--uv", uv], "eval")
            elif code2 is not None:
                fails.append(f"{label}: convert: its own output refused (exit {code2})")
    same = work / f"{name}{path.suffix}"
    if path.suffix.lower() != ".stl":
        run(["convert", str(path), str(same)], f"convert {path.suffix}")
        run(
            ["ssi", str(path), "--threads", "1", "--time-limit", "20", "--out", str(work / "ssi.json")],
            "ssi",
        )
        run(["repair", str(path), "--out", str(work / "rep.json")], "repair")
    else:
        run(["convert", "--format", "stl-binary", str(path), str(same)], "convert stl-binary")
    return fails


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", default=None)
    ap.add_argument("--timeout", type=float, default=60.0)
    ap.add_argument("--rss-mb", type=int, default=2048)
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--only", default=None, help="only public files whose name contains this")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--keep", default=None, help="keep the failing mutants in this directory")
    a = ap.parse_args()
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    exe = a.bin or str(target / "release" / "vericad")
    if not Path(exe).exists():
        sys.exit(f"{exe} not found: build with cargo build --release first")
    r = Runner(exe, a.timeout, a.rss_mb)
    files = sorted(p for p in PUBLIC.iterdir() if p.suffix != ".md")
    if a.only:
        files = [p for p in files if a.only in p.name]
    tmp = Path(tempfile.mkdtemp(prefix="vericad-mutants-"))
    keep = Path(a.keep) if a.keep else None
    if keep:
        keep.mkdir(parents=True, exist_ok=True)
    tasks = []
    pristine = {}
    for f in files:
        code, so, se, _, _ = r.run(["info", "--json", str(f)], f"{f.name} pristine")
        if code != 0:
            sys.exit(f"{f.name}: the pristine file does not read: {se}")
        info = json.loads(so)
        pristine[f.name] = {"counts": counts(info), "warnings": set(info.get("warnings", []))}
        for name, data in mutants(f.read_bytes(), a.seeds):
            tasks.append((f, name, data))
    print(f"{len(tasks)} mutants of {len(files)} files", flush=True)
    stats = {}
    t0 = time.monotonic()

    def one(task):
        f, name, data = task
        d = tmp / f"{f.stem}-{name}"
        d.mkdir()
        p = d / f.name
        p.write_bytes(data)
        fails = check_mutant(r, p, name, pristine[f.name], d)
        for x in fails:
            print("FAIL", x, flush=True)
        if fails and keep:
            shutil.copy(p, keep / f"{f.stem}-{name}{f.suffix}")
        shutil.rmtree(d, ignore_errors=True)
        return f.name, name, fails

    with ThreadPoolExecutor(a.jobs) as ex:
        for fname, name, fails in ex.map(one, tasks):
            s = stats.setdefault(fname, [0, 0])
            s[0] += 1
            s[1] += bool(fails)
    shutil.rmtree(tmp, ignore_errors=True)
    print()
    print("| file | mutants | failing |")
    print("|---|---|---|")
    for fname, (n, bad) in sorted(stats.items()):
        print(f"| {fname} | {n} | {bad} |")
    total_bad = sum(b for _, b in stats.values())
    print(
        f"\n{len(tasks)} mutants, {r.runs} runs, {total_bad} failing; peak RSS {r.max_rss_mb:.0f} MB; "
        f"slowest run {r.slowest[0]:.1f} s ({r.slowest[1]}); {time.monotonic() - t0:.0f} s in all"
    )
    sys.exit(1 if total_bad else 0)


if __name__ == "__main__":
    main()
