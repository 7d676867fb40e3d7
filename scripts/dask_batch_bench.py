"""Time the batch on Dask against `vericad batch` (BENCHMARKS.md, "Batch on Dask").

Usage (from the repository root, with the vericad wheel and dask[distributed] installed):

    python scripts/dask_batch_bench.py target/release/vericad

Two measurements, each the median of `--repeat` runs:
* overhead per task: the `info` job (milliseconds per model) over every model file under
  tests/data, repeated `--copies` times through a @LIST file of distinct paths (symlinks in a
  temporary directory), so the time is mostly scheduling: (Dask wall - CLI wall) / models;
* 1 vs 2 workers: the `ssi` job over the mid-sized public models (seconds each), with
  `vericad batch --threads 1/2` beside it.
Cluster start-up is timed separately and not included in the runs. Beside wall time, the
CPU time of all processes involved (the CLI; the driver with the scheduler, the workers and
their nannies) is measured, which depends less on other load on the machine.
"""

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import vericad
from distributed import Client, LocalCluster
from vericad.dask import run_batch

SSI_MODELS = [
    "tests/data/public/gmsh-periodic_u_cst.step",
    "tests/data/public/gmsh-t20_data.step",
    "tests/data/public/occt-bug28366_fuselage.stp",
    "tests/data/public/gmsh-cube1000.igs",
    "tests/data/public/gmsh-sphere_Rhino3D_default.igs",
    "tests/data/public/occt-bad_header.igs",
]


CPU = {}


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def cli_run(cli, inputs, job, threads, out, name):
    out.unlink(missing_ok=True)
    c = children_cpu()
    t = time.perf_counter()
    subprocess.run(
        [cli, "batch", *inputs, "--job", job, "--out", str(out), "--quiet", "--threads", str(threads)],
        check=False,
        capture_output=True,
    )
    CPU.setdefault(name, []).append(children_cpu() - c)
    return time.perf_counter() - t


def cluster_cpu(procs):
    total = time.process_time()
    for p in procs:
        ct = p.cpu_times()
        total += ct.user + ct.system
    return total


def dask_run(client, inputs, job, out, procs, name):
    out.unlink(missing_ok=True)
    c = cluster_cpu(procs)
    t = time.perf_counter()
    run_batch(inputs, job, out=out, client=client)
    w = time.perf_counter() - t
    CPU.setdefault(name, []).append(cluster_cpu(procs) - c)
    return w


def median(f, repeat):
    return statistics.median(f() for _ in range(repeat))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cli")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--copies", type=int, default=10)
    a = ap.parse_args()
    tmp = Path(tempfile.mkdtemp())
    # Distinct paths for the same files: `batch` removes repeated paths, not repeated files.
    files = vericad.discover(["tests/data"])
    lines = []
    for c in range(a.copies):
        d = tmp / f"copy{c}"
        d.mkdir()
        for k, f in enumerate(files):
            link = d / f"{k}-{Path(f).name}"
            link.symlink_to(Path(f).resolve())
            lines.append(str(link))
    (tmp / "list.txt").write_text("\n".join(lines) + "\n")
    info_inputs = ["@" + str(tmp / "list.txt")]
    n_info = len(lines)
    out = tmp / "out.jsonl"
    print(f"load average before: {os.getloadavg()}", file=sys.stderr)

    res = {}
    for threads in (1, 2):
        res[f"cli info t{threads}"] = median(
            lambda: cli_run(a.cli, info_inputs, "info", threads, out, f"cli info t{threads}"),
            a.repeat,
        )
        res[f"cli ssi t{threads}"] = median(
            lambda: cli_run(a.cli, SSI_MODELS, "ssi", threads, out, f"cli ssi t{threads}"),
            a.repeat,
        )
    t = time.perf_counter()
    for k, line in enumerate(lines):
        vericad.batch_record_line(line, "info", threads=1)
    res["python in-process info"] = time.perf_counter() - t
    for workers in (1, 2):
        t = time.perf_counter()
        cluster = LocalCluster(
            n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None
        )
        client = Client(cluster)
        client.run(lambda: __import__("vericad"))
        res[f"dask start w{workers}"] = time.perf_counter() - t
        import psutil

        procs = []
        for pid in client.run(os.getpid).values():
            p = psutil.Process(pid)
            procs.append(p)
            procs.append(p.parent())  # the nanny
        res[f"dask info w{workers}"] = median(
            lambda: dask_run(client, info_inputs, "info", out, procs, f"dask info w{workers}"),
            a.repeat,
        )
        res[f"dask ssi w{workers}"] = median(
            lambda: dask_run(client, SSI_MODELS, "ssi", out, procs, f"dask ssi w{workers}"),
            a.repeat,
        )
        client.close()
        cluster.close()
    print(f"load average after: {os.getloadavg()}", file=sys.stderr)
    for k, v in res.items():
        cpu = f"  cpu {statistics.median(CPU[k]):8.3f} s" if k in CPU else ""
        print(f"{k:28s} {v:9.3f} s{cpu}")
    print(f"models (info): {n_info}")
    for w in (1, 2):
        per = (res[f"dask info w{w}"] - res[f"cli info t{w}"]) / n_info
        print(f"overhead per task, {w} worker(s) vs CLI --threads {w}: {per * 1e3:.2f} ms")
    for w in (1, 2):
        per = (statistics.median(CPU[f"dask info w{w}"]) - statistics.median(CPU[f"cli info t{w}"])) / n_info
        print(f"CPU overhead per task, {w} worker(s): {per * 1e3:.2f} ms")
    print(f"in-process per model (python, info): {res['python in-process info'] / n_info * 1e3:.3f} ms")
    print(f"cli per model (info, t1): {res['cli info t1'] / n_info * 1e3:.3f} ms")
    print(f"ssi: dask 1 worker / 2 workers: {res['dask ssi w1'] / res['dask ssi w2']:.2f}")
    print(f"ssi: cli t1 / t2: {res['cli ssi t1'] / res['cli ssi t2']:.2f}")
    print(f"ssi: dask w1 / cli t1: {res['dask ssi w1'] / res['cli ssi t1']:.2f}")
    print(f"ssi: dask w2 / cli t2: {res['dask ssi w2'] / res['cli ssi t2']:.2f}")


if __name__ == "__main__":
    main()
