import json
import threading
import time

import numpy as np
import pytest

import vericad
from conftest import FAULTY, PLANE, PUBLIC, SPHERE, YANG, cli_json, plain, without

NAN = float("nan")
BILINEAR = FAULTY / "ok-bilinear.step"


# ---------------------------------------------------------------- ssi


def test_ssi_sphere_and_plane_is_one_closed_loop_at_the_radius():
    r = vericad.ssi(SPHERE, PLANE)
    assert isinstance(r, vericad.SsiResult)
    assert r.certified and r.summary.branches == 1
    (b,) = r.branches
    assert b.closed
    assert b.points.shape == (r.summary.points, 3) and b.points.shape[0] > 100
    assert b.uv_a.shape == (b.points.shape[0], 2) and b.uv_b.shape == b.uv_a.shape
    # The unit sphere cut by z = 0: the unit circle.
    radius = np.hypot(b.points[:, 0], b.points[:, 1])
    assert np.max(np.abs(radius - 1.0)) < 1e-6
    assert np.max(np.abs(b.points[:, 2])) < 1e-6
    # Every point's proven distance to the curve is within tol.
    assert r.summary.dist_curve_max <= 1e-6


def test_ssi_equals_the_cli(cli, tmp_path):
    r = vericad.ssi(SPHERE, PLANE, out=tmp_path / "r.json", threads=1)
    c = cli_json(cli, "ssi", SPHERE, PLANE)
    strip = {"seconds"}
    assert without(plain(r), strip) == without(c, strip)
    # The written result is the returned one.
    assert without(json.loads((tmp_path / "r.json").read_text()), strip) == without(c, strip)


def test_ssi_without_certificates_equals_the_cli(cli):
    r = vericad.ssi(SPHERE, PLANE, certify=False, threads=1)
    c = cli_json(cli, "ssi", SPHERE, PLANE, "--no-certify")
    strip = {"seconds"}
    assert without(plain(r), strip) == without(c, strip)
    assert not r.certified and not r.summary.no_missed_branches
    assert r.summary.dist_curve_max is None and r.summary.branches == 1


def test_ssi_cubic_pieces_equal_the_cli(cli):
    r = vericad.ssi(SPHERE, PLANE, pieces="cubic", threads=1)
    c = cli_json(cli, "ssi", SPHERE, PLANE, "--pieces", "cubic")
    strip = {"seconds"}
    assert without(plain(r), strip) == without(c, strip)
    assert r.certified and r.summary.branches == 1
    (b,) = r.branches
    chords = vericad.ssi(SPHERE, PLANE, threads=1).branches[0]
    assert 10 * b.points.shape[0] < chords.points.shape[0]
    # Every point has its tangent jet: a unit tangent of the unit circle z = 0 (horizontal,
    # perpendicular to the radius).
    assert len(b.tangents) == b.points.shape[0]
    for p, j in zip(b.points, b.tangents):
        t = np.asarray(j["t"])
        assert abs(np.linalg.norm(t) - 1.0) < 1e-12 and abs(t[2]) < 1e-9
        assert abs(t[0] * p[0] + t[1] * p[1]) < 1e-9
    with pytest.raises(vericad.BadInputError, match="pieces"):
        vericad.ssi(SPHERE, PLANE, pieces="splines")


def test_ssi_outputs_and_fits(tmp_path):
    r = vericad.ssi(SPHERE, PLANE, vtk=tmp_path / "r.vtp", iges=tmp_path / "r.igs", fits=True)
    assert (tmp_path / "r.vtp").stat().st_size > 0
    m = vericad.read_model(tmp_path / "r.igs")
    assert len(m.curves) == 1
    fit = r.branches[0].fit
    assert fit.control_points.shape[1] == 3 and fit.knots.ndim == 1


def test_ssi_picture(cli, tmp_path):
    r = vericad.ssi(SPHERE, PLANE, svg=tmp_path / "r.svg", view="0,90")
    text = (tmp_path / "r.svg").read_text()
    assert text.startswith("<svg") and text.rstrip().endswith("</svg>")
    assert f"points proven within tol of the curve ({r.summary.points})" in text
    # The same picture as the command line's.
    cli("ssi", SPHERE, PLANE, "--svg", tmp_path / "c.svg", "--view", "0,90")
    assert (tmp_path / "c.svg").read_text() == text
    with pytest.raises(vericad.BadInputError, match="view"):
        vericad.ssi(SPHERE, PLANE, svg=tmp_path / "x.svg", view="0,95")


@pytest.mark.parametrize("tol", [NAN, -1e-6, 0.0, float("inf")])
def test_ssi_bad_tolerance(tol):
    with pytest.raises(vericad.BadInputError, match="tol"):
        vericad.ssi(SPHERE, PLANE, tol=tol)


def test_ssi_bad_threads_and_files(tmp_path):
    with pytest.raises(vericad.BadInputError, match="threads"):
        vericad.ssi(SPHERE, PLANE, threads=0)
    with pytest.raises(vericad.BadInputError):
        vericad.ssi(tmp_path / "missing.step")
    bad = tmp_path / "bad.json"
    bad.write_text("{ not json")
    with pytest.raises(vericad.BadInputError):
        vericad.ssi(bad)


def test_ssi_unwritable_output_is_an_output_error(tmp_path):
    with pytest.raises(vericad.OutputError):
        vericad.ssi(SPHERE, PLANE, out=tmp_path / "no" / "such" / "dir" / "r.json")


def test_ssi_releases_the_gil():
    # While another thread is inside ssi, this thread keeps running Python code: the largest
    # pause between its ticks is far shorter than one call (with the GIL held through a
    # call, one pause would last the whole call).
    calls = []
    done = threading.Event()

    def work():
        for _ in range(3):
            t = time.perf_counter()
            vericad.ssi(PUBLIC / "gmsh-cube1000.igs", threads=1)
            calls.append(time.perf_counter() - t)
        done.set()

    ticks = [time.perf_counter()]
    t = threading.Thread(target=work)
    t.start()
    while not done.is_set():
        time.sleep(0.0005)
        ticks.append(time.perf_counter())
    t.join()
    gap = max(b - a for a, b in zip(ticks, ticks[1:]))
    assert gap < 0.5 * min(calls), (gap, calls)


# ---------------------------------------------------------------- certify-ssi


def test_certify_ssi_accepts_vericads_own_curves(tmp_path):
    vericad.ssi(SPHERE, PLANE, out=tmp_path / "r.json")
    c = vericad.certify_ssi(SPHERE, PLANE, curves=tmp_path / "r.json")
    assert isinstance(c, vericad.CertifyReport) and isinstance(c, dict)
    assert c.certified is True
    assert len(c.curves) == 1


def test_certify_ssi_refuses_curves_off_the_intersection(tmp_path):
    # A circle of radius 1.01 in z = 0: 0.01 off the true intersection.
    t = np.linspace(0, 2 * np.pi, 200)
    poly = [[1.01 * np.cos(a), 1.01 * np.sin(a), 0.0] for a in t]
    (tmp_path / "c.json").write_text(json.dumps([poly]))
    c = vericad.certify_ssi(SPHERE, PLANE, curves=tmp_path / "c.json")
    assert c.certified is False


def test_certify_ssi_equals_the_cli(cli, tmp_path):
    vericad.ssi(SPHERE, PLANE, out=tmp_path / "r.json")
    c = vericad.certify_ssi(SPHERE, PLANE, curves=tmp_path / "r.json")
    ref = cli_json(cli, "certify-ssi", SPHERE, PLANE, "--curves", tmp_path / "r.json")
    strip = {"seconds"}
    assert without(plain(c), strip) == without(ref, strip)


def test_certify_ssi_bad_input(tmp_path):
    with pytest.raises(vericad.BadInputError):
        vericad.certify_ssi(SPHERE, PLANE, curves=tmp_path / "missing.json")
    (tmp_path / "r.json").write_text("[]")
    with pytest.raises(vericad.BadInputError):
        vericad.certify_ssi(SPHERE, PLANE, curves=tmp_path / "r.json", tol=NAN)


# ---------------------------------------------------------------- curve-on-surface


def test_curve_on_surface_equals_the_cli(cli, tmp_path):
    r = vericad.curve_on_surface(YANG, YANG, out=tmp_path / "c.json")
    assert isinstance(r, vericad.CurveOnSurfaceResult)
    ref = cli_json(cli, "curve-on-surface", "--surface", YANG, "--curve", YANG)
    strip = {"elapsed_ms"}
    assert without(plain(r), strip) == without(ref, strip)
    assert r.bspline.control_points.shape == (r.num_control_points, 3)
    assert r.domain_polyline.shape[1] == 2
    for s in r.segments:
        assert s.control_points.shape[1] == 3
    written = json.loads((tmp_path / "c.json").read_text())
    assert without(written, strip) == without(ref, strip)


def test_curve_on_surface_evidence_only_when_asked(cli):
    plain_run = vericad.curve_on_surface(YANG, YANG)
    assert plain_run.evidence.measured is False and plain_run.evidence.samples == 0
    r = vericad.curve_on_surface(YANG, YANG, evidence=8)
    ref = cli_json(cli, "curve-on-surface", "--surface", YANG, "--curve", YANG, "--evidence", "8")
    assert without(plain(r), {"elapsed_ms"}) == without(ref, {"elapsed_ms"})
    assert r.evidence.measured is True
    assert r.evidence.samples >= 9 * r.num_segments
    assert 0 < r.evidence.max_distance_sampled <= r.certificate.hausdorff_bound


def test_curve_on_surface_picture_equals_the_cli(cli, tmp_path):
    r = vericad.curve_on_surface(YANG, YANG, svg_3d=tmp_path / "p.svg", view="10,40")
    text = (tmp_path / "p.svg").read_text()
    assert f"segments with proven bound within ε_d ({r.num_segments})" in text
    cli("curve-on-surface", "--surface", YANG, "--curve", YANG,
        "--svg-3d", tmp_path / "c.svg", "--view", "10,40")
    assert (tmp_path / "c.svg").read_text() == text


def test_curve_on_surface_options(cli):
    r = vericad.curve_on_surface(f"{YANG}:0", f"{YANG}:0", tol=1e-4, angle=5.0, bound="paper")
    ref = cli_json(
        cli, "curve-on-surface", "--surface", f"{YANG}:0", "--curve", f"{YANG}:0",
        "--tol", "1e-4", "--angle", "5", "--bound", "paper",
    )
    strip = {"elapsed_ms"}
    assert without(plain(r), strip) == without(ref, strip)


@pytest.mark.parametrize("kw", [{"tol": NAN}, {"tol": -1e-3}, {"angle": NAN}, {"bound": "x"}])
def test_curve_on_surface_bad_options(kw):
    with pytest.raises(vericad.BadInputError):
        vericad.curve_on_surface(YANG, YANG, **kw)


def test_curve_on_surface_bad_files(tmp_path):
    with pytest.raises(vericad.BadInputError):
        vericad.curve_on_surface(tmp_path / "x.json", YANG)
    with pytest.raises(vericad.BadInputError):
        vericad.curve_on_surface(f"{YANG}:7", YANG)
    # A domain curve outside the surface's domain.
    with pytest.raises(vericad.BadInputError):
        vericad.curve_on_surface(FAULTY / "yang.json", FAULTY / "cos-hang.json")


# ---------------------------------------------------------------- repair

TWO = FAULTY / "two-patches-1.json"


def test_repair_equals_the_cli_and_returns_the_patches(cli, tmp_path):
    r = vericad.repair(TWO, out=tmp_path / "out.json", report=tmp_path / "rep.json")
    assert isinstance(r, vericad.RepairResult)
    ref = cli_json(cli, "repair", TWO)
    assert without(plain(r.report), {"seconds"}) == without(ref, {"seconds"})
    assert r.report.patches_in == 2 and len(r.patches) == r.report.patches_out
    back = vericad.read_model(tmp_path / "out.json")
    for p, q in zip(r.patches, back.surfaces):
        np.testing.assert_array_equal(p.control_points, q.control_points)
        np.testing.assert_array_equal(p.weights, q.weights)
    assert json.loads((tmp_path / "rep.json").read_text())["patches_in"] == 2


def test_repair_of_trimmed_faces_equals_the_cli(cli, tmp_path):
    t20 = FAULTY.parent / "public" / "gmsh-t20_data.step"
    r = vericad.repair(t20, out=tmp_path / "out.step")
    ref = cli_json(cli, "repair", t20)
    assert without(plain(r.report), {"seconds"}) == without(ref, {"seconds"})
    assert r.report.mode == "faces" and r.report.faces == 21 and r.patches == []
    assert vericad.read_model(tmp_path / "out.step").brep_faces == 21
    p = vericad.repair(t20, mode="patches")
    ref = cli_json(cli, "repair", t20, "--patches")
    assert without(plain(p.report), {"seconds"}) == without(ref, {"seconds"})
    assert any("trims ignored: 15 of 21 faces" in n for n in p.report.not_done)
    with pytest.raises(vericad.BadInputError, match="mode"):
        vericad.repair(t20, mode="trimmed")


def test_repair_options_reach_the_library(cli):
    r = vericad.repair(TWO, u1=1e-2, u2=1e-2, feature_angle=60.0)
    ref = cli_json(cli, "repair", TWO, "--u1", "1e-2", "--u2", "1e-2", "--feature-angle", "60")
    assert without(plain(r.report), {"seconds"}) == without(ref, {"seconds"})


def test_repair_picture_equals_the_cli(cli, tmp_path):
    r = vericad.repair(TWO, svg=tmp_path / "r.svg", view="20,30")
    text = (tmp_path / "r.svg").read_text()
    assert f"output patches ({r.report.patches_out})" in text
    cli("repair", TWO, "--svg", tmp_path / "c.svg", "--view", "20,30")
    assert (tmp_path / "c.svg").read_text() == text
    with pytest.raises(vericad.BadInputError, match="view"):
        vericad.repair(TWO, svg=tmp_path / "x.svg", view="north")


@pytest.mark.parametrize("kw", [{"u1": NAN}, {"u1": -1.0}, {"u2": 0.0}])
def test_repair_bad_options(kw):
    with pytest.raises(vericad.BadInputError):
        vericad.repair(TWO, **kw)


def test_repair_bad_features_file(tmp_path):
    (tmp_path / "f.json").write_text('{"add": "x"}')
    with pytest.raises(vericad.BadInputError):
        vericad.repair(TWO, features=tmp_path / "f.json")


# ---------------------------------------------------------------- reparam


def test_reparam_equals_the_cli(cli):
    r = vericad.reparam(YANG)
    assert isinstance(r, vericad.ReparamResult)
    ref = cli_json(cli, "reparam", YANG)
    assert without(plain(r), {"seconds"}) == without(ref, {"seconds"})
    assert r.within_tol is True


def test_reparam_without_the_bound_equals_the_cli(cli):
    r = vericad.reparam(YANG, bound=False)
    ref = cli_json(cli, "reparam", YANG, "--no-bound")
    assert without(plain(r), {"seconds"}) == without(ref, {"seconds"})
    assert r.faces[0].result.bound is None
    assert r.faces[0].result.decided_by == "evidence"


def test_reparam_one_face_with_outputs(tmp_path):
    r = vericad.reparam(f"{YANG}:0", tol=1e-3, out=tmp_path / "r.json", svg=tmp_path / "r.svg")
    assert len(r.faces) == 1 and r.faces[0].index == 0
    assert len(vericad.read_model(tmp_path / "r.json").surfaces) == 1
    assert (tmp_path / "r.svg").read_text().lstrip().startswith("<")
    with pytest.raises(vericad.BadInputError):
        vericad.reparam(f"{YANG}:3")


@pytest.mark.parametrize("kw", [{"tol": NAN}, {"tol": -1.0}, {"max_lines": -1}])
def test_reparam_bad_options(kw):
    with pytest.raises(vericad.BadInputError):
        vericad.reparam(YANG, **kw)


# ---------------------------------------------------------------- coons / approximate


def _square_sides():
    s = np.linspace(0.0, 1.0, 11)
    return {
        "s": [[x, 0.0, 0.0] for x in s],
        "e": [[1.0, y, 0.0] for y in s],
        "n": [[x, 1.0, 0.0] for x in s[::-1]],
        "w": [[0.0, y, 0.0] for y in s[::-1]],
    }


def test_coons_on_a_plane(cli, tmp_path):
    sides = _square_sides()
    b = tmp_path / "boundary.json"
    b.write_text(json.dumps({"curves": [{"polyline": sides[k]} for k in "senw"]}))
    r = vericad.coons(BILINEAR, boundary=b, out=tmp_path / "a.json")
    assert isinstance(r, vericad.CoonsResult)
    assert r.report.approximant.within_tol
    s = r.surface
    assert (s.degree_u, s.degree_v) == (3, 3)
    assert np.max(np.abs(s.control_points[:, :, 2])) < 1e-9
    corners = {tuple(np.round(s.control_points[i, j], 9)) for i in (0, -1) for j in (0, -1)}
    assert corners == {(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)}
    back = vericad.read_model(tmp_path / "a.json")
    np.testing.assert_array_equal(back.surfaces[0].control_points, s.control_points)
    ref = cli_json(cli, "coons", BILINEAR, "--boundary", b)
    strip = {"seconds"}
    assert without(plain(r.report), strip) == without(ref, strip)


def test_approximate_one_approximant_layout(cli, tmp_path):
    sides = _square_sides()
    lay = tmp_path / "layout.json"
    lay.write_text(
        json.dumps(
            {
                "curves": {k: {"polyline": v} for k, v in sides.items()},
                "approximants": [
                    {"name": "square", "sides": [{"curve": k} for k in "senw"]}
                ],
            }
        )
    )
    r = vericad.approximate(BILINEAR, layout=lay, out=tmp_path / "a.json")
    assert isinstance(r, vericad.ApproximateResult)
    assert r.report.within_tol and len(r.surfaces) == 1
    assert r.surfaces[0].control_points.shape[2] == 3
    back = vericad.read_model(tmp_path / "a.json")
    np.testing.assert_array_equal(back.surfaces[0].control_points, r.surfaces[0].control_points)
    ref = cli_json(cli, "approximate", BILINEAR, "--layout", lay)
    assert without(plain(r.report), {"seconds"}) == without(ref, {"seconds"})


@pytest.mark.parametrize("kw", [{"tol": NAN}, {"m": -1}, {"k": -2}, {"tol": -1.0}])
def test_coons_bad_options(tmp_path, kw):
    sides = _square_sides()
    b = tmp_path / "boundary.json"
    b.write_text(json.dumps({"curves": [{"polyline": sides[k]} for k in "senw"]}))
    with pytest.raises(vericad.BadInputError):
        vericad.coons(BILINEAR, boundary=b, **kw)
    with pytest.raises(vericad.BadInputError):
        vericad.approximate(BILINEAR, layout=tmp_path / "missing.json")
    (tmp_path / "bad.json").write_text('{"curves": []}')
    with pytest.raises(vericad.BadInputError):
        vericad.coons(BILINEAR, boundary=tmp_path / "bad.json")


def test_curve_on_faces_equals_the_cli(cli, tmp_path):
    step = PUBLIC / "gmsh-t20_data.step"
    r = vericad.curve_on_faces(step, "#113,#99", tol=5e-3, out=tmp_path / "f.json")
    assert isinstance(r, vericad.FacesCurvesResult)
    assert r.all_certified and r.edges == 12
    ref = cli_json(cli, "curve-on-surface", "--surface", step, "--face", "#113,#99", "--tol", "5e-3")
    strip = {"elapsed_ms"}
    assert without(plain(r), strip) == without(ref, strip)
    rational = [f for f in r.faces if f.rational]
    assert rational and all(
        s.weights.shape == (s.control_points.shape[0],)
        for f in rational for l in f.loops for e in l.edges for c in e.curves for s in c.segments
    )
    with pytest.raises(vericad.BadInputError):
        vericad.curve_on_faces(step, "#999999")
