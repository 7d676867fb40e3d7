import numpy as np
import pytest

import vericad
from conftest import MALFORMED, PUBLIC, SPHERE, YANG, cli_json, plain


def test_read_native_json_gives_control_nets_as_arrays():
    m = vericad.read_model(YANG)
    assert isinstance(m, vericad.Model)
    assert len(m.surfaces) == 1 and len(m.curves) == 1
    s = m.surfaces[0]
    assert (s.degree_u, s.degree_v) == (2, 2)
    assert s.control_points.shape == (3, 3, 3)
    assert s.control_points.dtype == np.float64
    assert s.weights.shape == (3, 3) and np.all(s.weights == 1.0)
    np.testing.assert_array_equal(s.knots_u, [0, 0, 0, 1, 1, 1])
    c = m.curves[0]
    assert c.dimension == 2 and c.degree == 2
    assert c.control_points.shape == (3, 2)


def test_read_iges_rational_sphere():
    m = vericad.read_model(SPHERE)
    s = m.surfaces[0]
    assert s.control_points.shape == (9, 5, 3)
    assert s.weights.shape == (9, 5) and not np.all(s.weights == 1.0)
    # The net of a unit sphere: weighted control points lie on or outside the unit sphere.
    assert np.all(np.linalg.norm(s.control_points, axis=2) >= 1.0 - 1e-12)
    assert m.unit == "mm"


def test_read_stl_gives_a_triangulation():
    m = vericad.read_model(PUBLIC / "gmsh-surface1.stl")
    t = m.triangulations[0]
    assert t.vertices.shape[1] == 3 and t.triangles.shape[1] == 3
    assert t.triangles.max() < t.vertices.shape[0]


def test_read_step_with_topology():
    m = vericad.read_model(PUBLIC / "abc-0000.step")
    assert len(m.surfaces) == 25 and m.brep_faces == 25 and m.brep_edges > 0


def test_info_equals_the_cli(cli):
    for f in [YANG, SPHERE, PUBLIC / "abc-0000.step", PUBLIC / "gmsh-surface1.stl"]:
        assert plain(vericad.info(f)) == cli_json(cli, "info", f)


def test_skip_invalid_reads_a_part_without_its_invalid_face(tmp_path):
    text = (PUBLIC / "gmsh-t20_data.step").read_text()
    knots = "(2.09439510241284,3.14159264302763)"
    assert text.count(knots) == 1
    bad = tmp_path / "t20-bad.step"
    bad.write_text(text.replace(knots, "(3.14159264302763,2.09439510241284)"))
    with pytest.raises(vericad.BadInputError, match="knot"):
        vericad.read_model(bad)
    vericad.set_skip_invalid(True)
    try:
        m = vericad.read_model(bad)
        intact = vericad.read_model(PUBLIC / "gmsh-t20_data.step")
    finally:
        vericad.set_skip_invalid(False)
    assert len(m.surfaces) + 1 == len(intact.surfaces) == 21
    assert any(w.startswith("invalid face #") for w in m.warnings)
    with pytest.raises(vericad.BadInputError):
        vericad.read_model(bad)


def test_missing_file_is_bad_input():
    with pytest.raises(vericad.BadInputError, match="No such file"):
        vericad.read_model("no/such/model.step")
    with pytest.raises(vericad.BadInputError):
        vericad.info("no/such/model.json")


@pytest.mark.parametrize(
    "name", sorted(p.name for p in MALFORMED.glob("*.json") if p.name != "EXPECTED.json")
)
def test_malformed_files_are_bad_input_naming_the_fault(name):
    import json

    expected = json.loads((MALFORMED / "EXPECTED.json").read_text())[name]
    with pytest.raises(vericad.BadInputError) as e:
        vericad.read_model(MALFORMED / name)
    assert expected["path"] in str(e.value)
    assert expected["reason_contains"] in str(e.value)


def test_exception_hierarchy():
    for cls in (vericad.BadInputError, vericad.ComputationError, vericad.OutputError):
        assert issubclass(cls, vericad.VericadError)
    assert issubclass(vericad.VericadError, Exception)
    assert vericad.BadInputError.__module__ == "vericad"


def test_result_is_a_dict_with_attributes_and_json():
    m = vericad.read_model(YANG)
    assert isinstance(m, dict) and m["surfaces"] is m.surfaces
    with pytest.raises(AttributeError):
        m.no_such_key
    import json

    back = json.loads(m.to_json())
    assert back["surfaces"][0]["control_points"] == m.surfaces[0].control_points.tolist()


def test_results_pickle_for_sending_between_processes():
    import pickle

    import numpy as np

    m = vericad.read_model(YANG)
    back = pickle.loads(pickle.dumps(m))
    assert type(back) is vericad.Model
    np.testing.assert_array_equal(back.surfaces[0].control_points, m.surfaces[0].control_points)
