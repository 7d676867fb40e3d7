"""``vericad batch`` on a Dask cluster: one task per model, records gathered into one JSON-lines file.

Each task calls :func:`vericad.batch_record_line`, the library's record of one model (the
same code ``vericad batch`` runs per model), so every line has the format and the figures
of ``vericad batch`` (only ``seconds`` differs run to run). Faults of a model (unreadable
file, failed job, panic) are in its record. A task that fails outside the library (its
worker died, the package is missing on the worker, ...) gets a ``failed`` record with
``error.kind`` ``"worker"``; the other tasks go on. The driver appends each line as its task
finishes and, like ``vericad batch``, skips models the output already has records for.

Requires ``dask[distributed]``.
"""

from __future__ import annotations

import json
import os
import time
import uuid
from typing import Any, Callable, Dict, Iterable, List, Optional

from . import BadInputError, _vericad, discover, read_records

__all__ = ["record_task", "records_to_parquet", "run_batch"]


def record_task(
    path: str, job: str, tol: float, time_limit: Optional[float], threads: Optional[int]
) -> str:
    """The task run on a worker: one model's record line."""
    return _vericad.batch_record_line(
        path, job, tol=tol, time_limit=time_limit, threads=threads
    )


def _worker_failure(path: str, exc: BaseException) -> str:
    rec = {
        "path": path,
        "status": "failed",
        "seconds": 0.0,
        "error": {"message": f"{type(exc).__name__}: {exc}", "kind": "worker"},
    }
    return json.dumps(rec, separators=(",", ":"))


def run_batch(
    inputs: Iterable["os.PathLike[str] | str"],
    job: str = "info",
    *,
    out: "os.PathLike[str] | str",
    client: Any = None,
    tol: float = 1e-6,
    time_limit: Optional[float] = None,
    threads_per_task: Optional[int] = 1,
    parquet: "os.PathLike[str] | str | None" = None,
    task: Callable[[str, str, float, Optional[float], Optional[int]], str] = record_task,
) -> Dict[str, Any]:
    """Run ``job`` (``info``, ``ssi`` or ``repair``) on every model of ``inputs`` (as
    ``vericad batch`` finds them) on the Dask ``client`` (default: the current one), one
    task per model, appending each record to ``out`` as it arrives. Each task runs its
    model in a pool of ``threads_per_task`` threads (``None``: one per core of the worker's
    machine); with one thread per Dask worker, the workers' count is the number of models
    run at once, as ``vericad batch --threads N`` runs N. With ``parquet``, every record of
    ``out`` is also written there as a table (see :func:`records_to_parquet`). ``task`` is
    the function run per model, ``task(path, job, tol, time_limit, threads) -> record line``
    (default :func:`record_task`; it must be importable on the workers).

    Returns ``models`` (of this run, resumed included), ``resumed``, ``counts`` (by status)
    and ``seconds`` (wall time of this run).
    """
    from distributed import as_completed, get_client

    _vericad.batch_check(job, tol=tol, time_limit=time_limit)
    if threads_per_task is not None and not 1 <= threads_per_task <= 1024:
        raise BadInputError(f"threads_per_task must be in 1..=1024, not {threads_per_task}")
    if client is None:
        client = get_client()
    t0 = time.perf_counter()
    models = discover(inputs)
    out = os.fspath(out)
    wanted = set(models)
    done: List[Dict[str, Any]] = []
    seen = set()
    for r in read_records(out):
        if r["path"] in wanted and r["path"] not in seen:
            seen.add(r["path"])
            done.append(r)
    todo = [m for m in models if m not in seen]
    counts: Dict[str, int] = {}
    for r in done:
        counts[r["status"]] = counts.get(r["status"], 0) + 1
    run = uuid.uuid4().hex[:8]
    futures = client.map(
        task,
        todo,
        job=job,
        tol=tol,
        time_limit=time_limit,
        threads=threads_per_task,
        key=[f"vericad-{job}-{run}-{k}" for k in range(len(todo))],
        pure=False,
    )
    path_of = {f.key: p for f, p in zip(futures, todo)}
    with open(out, "a", encoding="utf-8") as f:
        for fut in as_completed(futures):  # type: ignore[no-untyped-call]
            path = path_of[fut.key]
            try:
                line = fut.result()
            except Exception as exc:  # the task failed outside the library
                line = _worker_failure(path, exc)
            status = json.loads(line)["status"]
            counts[status] = counts.get(status, 0) + 1
            f.write(line + "\n")
            f.flush()
            fut.release()
    if parquet is not None:
        records_to_parquet(out, parquet)
    return {
        "models": len(done) + len(todo),
        "resumed": len(done),
        "counts": counts,
        "seconds": time.perf_counter() - t0,
    }


def _flatten(d: Dict[str, Any], prefix: str = "") -> Dict[str, Any]:
    flat: Dict[str, Any] = {}
    for k, v in d.items():
        if isinstance(v, dict):
            flat.update(_flatten(v, f"{prefix}{k}."))
        else:
            flat[f"{prefix}{k}"] = v
    return flat


def records_to_parquet(
    jsonl: "os.PathLike[str] | str", parquet: "os.PathLike[str] | str"
) -> int:
    """Write the records of a batch output (JSON lines) as a Parquet table: one row per
    record, nested fields as dotted columns (``ssi.certified``, ``error.message``), null where
    a record has no such field. Requires ``pyarrow``. Returns the number of rows."""
    import pyarrow as pa  # type: ignore[import-not-found, import-untyped, unused-ignore]
    import pyarrow.parquet as pq  # type: ignore[import-not-found, import-untyped, unused-ignore]

    rows = [_flatten(r) for r in read_records(jsonl)]
    columns: Dict[str, None] = {}
    for r in rows:
        for k in r:
            columns.setdefault(k, None)
    table = pa.table({k: [r.get(k) for r in rows] for k in columns})
    pq.write_table(table, os.fspath(parquet))
    return len(rows)
