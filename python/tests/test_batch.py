import json

import pytest

import vericad
from conftest import FAULTY, MALFORMED, PUBLIC, REPO

# Every model of the public data, one malformed file, one missing path.
INPUTS = [
    str(PUBLIC.relative_to(REPO)),
    str((MALFORMED / "truncated.json").relative_to(REPO)),
    "tests/data/no-such-model.step",
]
# Small models for the ssi job (the large ones take minutes).
SSI_INPUTS = [
    str((PUBLIC / n).relative_to(REPO))
    for n in ["gmsh-cube1000.igs", "gmsh-sphere_Rhino3D_default.igs", "occt-bad_header.igs"]
] + [str((MALFORMED / "negative-weight.json").relative_to(REPO))]


def strip_times(rec):
    rec = dict(rec)
    rec.pop("seconds", None)
    if "ssi" in rec:
        rec["ssi"] = {k: v for k, v in rec["ssi"].items() if k != "seconds"}
    return rec


def by_path(records):
    return {r["path"]: strip_times(r) for r in records}


def read_lines(p):
    return [json.loads(line) for line in p.read_text().splitlines() if line.strip()]


def cli_batch(cli, tmp_path, inputs, job):
    out = tmp_path / f"cli-{job}.jsonl"
    cli("batch", *inputs, "--job", job, "--out", out, "--quiet", "--threads", "2")
    return read_lines(out)


def test_discover_matches_the_cli(cli, tmp_path, monkeypatch):
    monkeypatch.chdir(REPO)
    found = vericad.discover(INPUTS)
    recs = cli_batch(cli, tmp_path, INPUTS, "info")
    assert found == sorted(r["path"] for r in recs)
    # Every model file under the directory (recursively; the READMEs are not models), plus the
    # two other inputs.
    models = [
        p
        for p in PUBLIC.rglob("*")
        if p.is_file() and p.suffix.lower() in {".step", ".stp", ".igs", ".iges", ".json", ".stl"}
    ]
    assert len(found) == len(models) + 2


@pytest.mark.parametrize("job,inputs", [("info", INPUTS), ("repair", INPUTS), ("ssi", SSI_INPUTS)])
def test_batch_record_equals_the_cli_record(cli, tmp_path, monkeypatch, job, inputs):
    monkeypatch.chdir(REPO)
    ref = by_path(cli_batch(cli, tmp_path, inputs, job))
    mine = {}
    for p in vericad.discover(inputs):
        line = vericad.batch_record_line(p, job)
        assert "\n" not in line
        mine[p] = strip_times(json.loads(line))
    assert mine == ref
    bad = "tests/data/no-such-model.step" if job != "ssi" else SSI_INPUTS[-1]
    assert ref[bad]["status"] == "bad_input" and ref[bad]["error"]["kind"] == "read"


def test_batch_in_process_equals_the_cli_and_resumes(cli, tmp_path, monkeypatch):
    monkeypatch.chdir(REPO)
    out = tmp_path / "py.jsonl"
    s = vericad.batch(INPUTS, "info", out=out, threads=2)
    assert s["models"] == len(vericad.discover(INPUTS)) and s["resumed"] == 0
    assert s["counts"]["bad_input"] == 2  # the truncated file and the missing path
    assert s["counts"]["ok"] == s["models"] - 2
    recs = read_lines(out)
    assert by_path(recs) == by_path(cli_batch(cli, tmp_path, INPUTS, "info"))
    # A second run finds every record and runs nothing.
    s2 = vericad.batch(INPUTS, "info", out=out)
    assert s2["resumed"] == s["models"] and len(read_lines(out)) == len(recs)
    assert vericad.read_records(out) == recs


def test_batch_record_is_a_dict():
    r = vericad.batch_record(FAULTY / "two-patches-1.json", "repair")
    assert r["status"] == "ok" and r["repair"]["patches_in"] == 2


@pytest.mark.parametrize(
    "kw",
    [{"job": "mesh"}, {"tol": float("nan")}, {"tol": -1.0}, {"time_limit": 0.0},
     {"time_limit": float("nan")}],
)
def test_batch_bad_options(kw, tmp_path):
    job = kw.pop("job", "ssi")
    with pytest.raises(vericad.BadInputError):
        vericad.batch_record_line(PUBLIC / "gmsh-cube1000.igs", job, **kw)
    with pytest.raises(vericad.BadInputError):
        vericad.batch([str(PUBLIC)], job, out=tmp_path / "o.jsonl", **kw)


def test_batch_record_in_its_own_pool_is_the_same():
    p = PUBLIC / "gmsh-cube1000.igs"
    a = strip_times(vericad.batch_record(p, "ssi"))
    assert strip_times(vericad.batch_record(p, "ssi", threads=1)) == a
    assert strip_times(vericad.batch_record(p, "ssi", threads=2)) == a
    with pytest.raises(vericad.BadInputError, match="threads"):
        vericad.batch_record(p, "ssi", threads=0)


def test_batch_bad_arguments(tmp_path):
    with pytest.raises(vericad.BadInputError):
        vericad.batch([str(PUBLIC)], "info", out=tmp_path / "o.jsonl", shard="2/2")
    with pytest.raises(vericad.BadInputError):
        vericad.batch([str(PUBLIC)], "info", out=tmp_path / "o.jsonl", threads=0)
    with pytest.raises(vericad.BadInputError):
        vericad.discover(["@" + str(tmp_path / "missing-list.txt")])
    bad = tmp_path / "bad.jsonl"
    bad.write_text("not a record\n")
    with pytest.raises(vericad.BadInputError):
        vericad.read_records(bad)
