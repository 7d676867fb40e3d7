"""The batch on a Dask LocalCluster (2 worker processes) gives the records of `vericad batch`."""

import json

import pytest

import vericad

distributed = pytest.importorskip("distributed")
from vericad.dask import _worker_failure, run_batch  # noqa: E402

from conftest import MALFORMED, PUBLIC  # noqa: E402
from test_batch import by_path, read_lines  # noqa: E402

INPUTS = [str(PUBLIC), str(MALFORMED / "truncated.json"), str(PUBLIC / "no-such-model.step")]
SSI_INPUTS = [
    str(PUBLIC / n)
    for n in ["gmsh-cube1000.igs", "gmsh-sphere_Rhino3D_default.igs", "occt-bad_header.igs"]
] + [str(MALFORMED / "negative-weight.json")]


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    )
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


@pytest.mark.parametrize("job,inputs", [("info", INPUTS), ("repair", INPUTS), ("ssi", SSI_INPUTS)])
def test_dask_batch_gives_the_records_of_vericad_batch(client, cli, tmp_path, job, inputs):
    out = tmp_path / "dask.jsonl"
    s = run_batch(inputs, job, out=out, client=client)
    recs = read_lines(out)
    assert s["models"] == len(recs) == len(vericad.discover(inputs)) and s["resumed"] == 0
    ref_out = tmp_path / "cli.jsonl"
    cli("batch", *inputs, "--job", job, "--out", ref_out, "--quiet")
    assert by_path(recs) == by_path(read_lines(ref_out))
    # The faulty models are isolated: their own records say why, the others finished.
    unreadable = [r for r in recs if r.get("error", {}).get("kind") == "read"]
    assert len(unreadable) == (2 if job != "ssi" else 1)
    assert all(r["status"] == "bad_input" for r in unreadable)
    assert sum(s["counts"].values()) == len(recs)
    for status in ("ok", "uncertified", "bad_input", "failed", "panic"):
        assert s["counts"].get(status, 0) == sum(r["status"] == status for r in recs)
    assert s["counts"].get("ok", 0) > 0


def test_dask_batch_resumes(client, tmp_path):
    out = tmp_path / "dask.jsonl"
    first = run_batch(INPUTS, "info", out=out, client=client)
    text = out.read_text()
    # Cut the last line short, as a killed run leaves it: only that model runs again.
    lines = text.splitlines(keepends=True)
    out.write_text("".join(lines[:-1]) + lines[-1][:10])
    again = run_batch(INPUTS, "info", out=out, client=client)
    assert again["resumed"] == first["models"] - 1 and again["models"] == first["models"]
    assert by_path(read_lines(out)) == by_path([json.loads(x) for x in lines])
    third = run_batch(INPUTS, "info", out=out, client=client)
    assert third["resumed"] == first["models"]


def test_a_failed_task_gets_a_record_vericad_batch_reads(tmp_path):
    line = _worker_failure("m.step", RuntimeError("worker lost"))
    out = tmp_path / "o.jsonl"
    out.write_text(line + "\n")
    (r,) = vericad.read_records(out)
    assert r["status"] == "failed" and r["error"]["kind"] == "worker"
    assert "worker lost" in r["error"]["message"]


def test_dask_batch_bad_options(client, tmp_path):
    with pytest.raises(vericad.BadInputError):
        run_batch(INPUTS, "mesh", out=tmp_path / "o.jsonl", client=client)
    with pytest.raises(vericad.BadInputError):
        run_batch(INPUTS, "ssi", out=tmp_path / "o.jsonl", client=client, tol=float("nan"))
    with pytest.raises(vericad.BadInputError):
        run_batch(INPUTS, "info", out=tmp_path / "o.jsonl", client=client, threads_per_task=0)
    assert not (tmp_path / "o.jsonl").exists()


def test_parquet_has_the_records(client, tmp_path):
    pq = pytest.importorskip("pyarrow.parquet")
    out = tmp_path / "dask.jsonl"
    run_batch(INPUTS, "info", out=out, client=client, parquet=tmp_path / "r.parquet")
    recs = read_lines(out)
    t = pq.read_table(tmp_path / "r.parquet").to_pylist()
    assert len(t) == len(recs)
    for row, rec in zip(t, recs):
        assert row["path"] == rec["path"] and row["status"] == rec["status"]
        if "info" in rec:
            assert row["info.faces"] == rec["info"]["faces"]
        else:
            assert row["info.faces"] is None and row["error.kind"] == rec["error"]["kind"]


def failing_on_cube(path, job, tol, time_limit, threads):
    """A task that fails outside the library for one model (run on the workers)."""
    if path.endswith("gmsh-cube1000.igs"):
        raise RuntimeError("worker-side failure")
    from vericad.dask import record_task

    return record_task(path, job, tol, time_limit, threads)


def test_a_task_failing_outside_the_library_is_isolated(client, cli, tmp_path):
    out = tmp_path / "dask.jsonl"
    s = run_batch(INPUTS, "info", out=out, client=client, task=failing_on_cube)
    recs = by_path(read_lines(out))
    cube = str(PUBLIC / "gmsh-cube1000.igs")
    assert recs[cube]["status"] == "failed" and recs[cube]["error"]["kind"] == "worker"
    assert "worker-side failure" in recs[cube]["error"]["message"]
    assert s["counts"]["failed"] == 1
    # Every other model has the record vericad batch gives it.
    ref_out = tmp_path / "cli.jsonl"
    cli("batch", *INPUTS, "--job", "info", "--out", ref_out, "--quiet")
    ref = by_path(read_lines(ref_out))
    del recs[cube], ref[cube]
    assert recs == ref
