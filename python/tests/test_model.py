"""load_model and the model's census, names and default pose, against `sinew info` and the model file;
the error path: bad input raises sinew.Error carrying the file and line."""
import re

import numpy as np
import pytest

import sinew
from conftest import ARM26_YAML, WHOLE_BODY_YAML, run_cli

CENSUS_ROWS = {"links": "links", "virtual links": "virtual_links", "DOF": "dof",
               "DOF with virtual links": "dof_with_virtual", "muscles": "muscles", "tendons": "tendons",
               "ligaments": "ligaments", "cartilage": "cartilage", "wires (total)": "wires",
               "wire points": "wire_points", "loops": "loops"}


def cli_census(path):
    """The model column of `sinew info`'s table."""
    values = {}
    for line in run_cli("info", path).splitlines():
        match = re.match(r"^  (.+?)\s+(\d+)\s+(\d+|-)$", line)
        if match and match.group(1) in CENSUS_ROWS:
            values[CENSUS_ROWS[match.group(1)]] = int(match.group(2))
    assert len(values) == len(CENSUS_ROWS), values
    return values


@pytest.mark.parametrize("path", [ARM26_YAML, WHOLE_BODY_YAML], ids=["arm26", "whole_body"])
def test_census_matches_sinew_info(path):
    census = sinew.load_model(str(path)).census()
    for field, value in cli_census(path).items():
        assert getattr(census, field) == value, field


def test_osim_census_matches_sinew_info(opensim_arm26):
    notes = []
    model = sinew.load_model(str(opensim_arm26 / "arm26.osim"), notes.append)
    census = model.census()
    for field, value in cli_census(opensim_arm26 / "arm26.osim").items():
        assert getattr(census, field) == value, field
    assert model.num_wires == 6 and all(isinstance(n, str) for n in notes)


def test_sizes_and_names_agree(whole_body, arm26):
    for model in (arm26, whole_body):
        assert model.default_q.shape == (model.nq,)
        assert len(model.coordinate_names) == model.nq and len(model.speed_names) == model.nu
        assert sum(j.nq for j in model.joints) == model.nq and sum(j.nu for j in model.joints) == model.nu
        assert [l.name for l in model.links] == model.link_names and len(model.links) == model.num_links
        assert model.find_link(model.link_names[-1]) == model.num_links - 1
        assert model.find_wire(model.wire_names[0]) == 0 and model.find_wire("no such wire") is None
    census = whole_body.census()
    assert census.links + census.virtual_links == whole_body.num_links
    assert census.wires == whole_body.num_wires and census.dof_with_virtual == whole_body.nu


def test_default_pose_is_the_model_files(arm26):
    # models/arm26.yaml: the elbow's initial_angle, and the shoulder's initial_rotation, a rotation vector,
    # as the quaternion [cos(|v|/2), sin(|v|/2) v/|v|]
    elbow = arm26.find_coordinate("r_elbow")
    assert arm26.default_q[elbow] == 1.0471975511965976
    v = np.array([-0.046258396513, 0.001806415767, 0.78403263496])
    angle = np.linalg.norm(v)
    shoulder = [arm26.find_coordinate(f"r_shoulder_{c}") for c in ("qw", "qx", "qy", "qz")]
    np.testing.assert_allclose(arm26.default_q[shoulder], np.r_[np.cos(angle / 2), np.sin(angle / 2) * v / angle],
                               rtol=0, atol=1e-12)
    assert not arm26.default_q.flags.writeable  # a view into the immutable model
    assert arm26.gravity[1] == -9.8066
    assert arm26.joints[arm26.coordinates[elbow].joint].type == sinew.JointType.Pin


def test_bad_model_names_file_and_line(tmp_path):
    text = ARM26_YAML.read_text().splitlines()
    line = next(i for i, l in enumerate(text) if "name: r_humerus" in l and "mass:" in l)
    text[line] = text[line].replace("mass: 1.864572", "mass: -1.0")
    bad = tmp_path / "bad_arm.yaml"
    bad.write_text("\n".join(text) + "\n")
    with pytest.raises(sinew.Error) as error:
        sinew.load_model(str(bad))
    assert f"bad_arm.yaml:{line + 1}" in str(error.value), str(error.value)
    assert isinstance(error.value, sinew.ModelError) and isinstance(error.value, RuntimeError)


def test_missing_file_and_bad_sizes_raise_sinew_error(tmp_path, arm26):
    with pytest.raises(sinew.Error, match="nowhere.yaml"):
        sinew.load_model(str(tmp_path / "nowhere.yaml"))
    with pytest.raises(sinew.Error, match=r"q has 3 entries; model 'arm26' expects 5"):
        sinew.calc_wire_lengths(arm26, np.zeros(3))
    with pytest.raises(sinew.Error, match="link_forces is 2 x 6"):
        sinew.calc_inverse_dynamics(arm26, arm26.default_q, np.zeros(arm26.nu), np.zeros(arm26.nu), np.zeros((2, 6)))
