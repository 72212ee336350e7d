"""The reach envelope: sampled positions and manipulability against a planar arm's closed forms,
the humanoid's arm with a hand point, and ``urdftool workspace``."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from conftest import ROBOTS
from urdftool.description.load import load
from urdftool.kinematics.chain import build_chain
from urdftool.kinematics.workspace import manipulability, sample

HUMANOID = ROBOTS / "humanoid" / "humanoid.urdf.xacro"
A, B = 0.3, 0.2  # [m] the two links

# two joints about z, straight links along x: the textbook planar arm
ARM = f"""<robot name="arm">
  <link name="base"/><link name="one"/><link name="two"/><link name="tip"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="one"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="one"/><child link="two"/>
    <origin xyz="{A} 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-2.5" upper="2.5" effort="1" velocity="1"/></joint>
  <joint name="tool" type="fixed"><parent link="two"/><child link="tip"/>
    <origin xyz="{B} 0 0"/></joint>
</robot>"""


@pytest.fixture
def arm(tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    return build_chain(load(path), "base", "tip")


def test_planar_arm_positions_and_manipulability_match_the_closed_forms(arm):
    space = sample(arm, 300, seed=4)
    q1, q2 = space.values[:, 0], space.values[:, 1]
    # tip = A e(q1) + B e(q1 + q2), 0.1 up; Yoshikawa's measure of the 2R arm is A B |sin q2|
    expected = np.stack([A * np.cos(q1) + B * np.cos(q1 + q2),
                         A * np.sin(q1) + B * np.sin(q1 + q2), np.full(len(q1), 0.1)], -1)
    assert np.allclose(space.points, expected, atol=1e-12)
    assert np.allclose(space.manipulability, A * B * np.abs(np.sin(q2)), atol=1e-12)
    assert np.allclose(space.centre, [0, 0, 0.1])
    assert space.reach <= A + B + 1e-12 and space.reach > 0.99 * (A + B)
    assert space.upper[2] - space.lower[2] == pytest.approx(0.0, abs=1e-12)
    assert space.values[0].tolist() == [0.0, 0.0]  # the default configuration first


def test_manipulability_is_zero_at_a_singularity(arm):
    _, jacobian = arm.pose_and_jacobian(np.array([0.3, 0.0]), local=False)
    assert manipulability(jacobian) == pytest.approx(0.0, abs=1e-15)


def test_a_hand_point_on_the_forearm_gives_the_arm_its_reach():
    humanoid = load(HUMANOID)
    elbow = sample(build_chain(humanoid, "body_link", "l_forearm_link"), 200)
    hand = sample(build_chain(humanoid, "body_link", "l_forearm_link", point=(0, 0, -0.07)), 200)
    # the forearm link's origin is the elbow: the elbow joint cannot move it
    assert np.allclose(elbow.manipulability, 0.0, atol=1e-10)
    assert hand.reach == pytest.approx(elbow.reach + 0.07, abs=0.01)
    assert hand.manipulability.max() > 1e-4


def test_cli_text_json_and_pictures(run_cli, tmp_path):
    result = run_cli("workspace", HUMANOID, "--base", "body_link", "--tip", "l_forearm_link",
                     "--point", "0", "0", "-0.07", "--samples", "100", "--plot",
                     tmp_path / "w.svg")
    assert result.exit_code == 0, result.output
    assert "max reach 0.15" in result.output
    svg = (tmp_path / "w.svg").read_text()
    assert svg.count("<circle") == 2 * 100 and "side view" in svg
    result = run_cli("workspace", HUMANOID, "--tip", "r_foot_link", "--samples", "50", "-f",
                     "json", "--plot", tmp_path / "w.png")
    assert result.exit_code == 0, result.output
    document = json.loads(result.output)
    assert document["samples"] == 50 and len(document["joints"]) == 6
    assert (tmp_path / "w.png").read_bytes()[:4] == b"\x89PNG"


@pytest.mark.parametrize("args,message", [(["--samples", "0"], "--samples must be"),
                                          (["--plot", "x.pdf"], ".svg or .png")])
def test_cli_usage(run_cli, args, message):
    result = run_cli("workspace", HUMANOID, "--tip", "l_foot_link", *args)
    assert result.exit_code == 2 and message in result.output


def test_cli_unknown_tip(run_cli):
    result = run_cli("workspace", HUMANOID, "--tip", "l_fot_link")  # a name given: exit 2
    assert result.exit_code == 2 and "did you mean 'l_foot_link'" in result.output


@pytest.mark.parametrize("size", [1e60, 1e100])
def test_manipulability_of_large_rows_is_the_measure_not_inf(size):
    """attack25: ``sqrt(det(J J^T))`` of rows of 1e60 squared and cubed past the float range
    ("mean inf, max inf"), though the measure (1e180) is a float; and of fewer than three
    joints too. Infinite only when the measure is."""
    rows = np.array([[2.0, 0.0, 0.0, 1.0], [0.0, 3.0, 0.0, 0.0], [0.0, 0.0, 5.0, 0.0]])
    jacobian = np.vstack([rows * size, np.zeros((3, 4))])
    assert manipulability(jacobian) == pytest.approx(math.sqrt(1125) * size ** 3, rel=1e-12)
    assert manipulability(jacobian[:, :2]) == pytest.approx(6 * size ** 2, rel=1e-12)
    assert manipulability(np.vstack([rows * 1e150, np.zeros((3, 4))])) == math.inf
    assert manipulability(np.vstack([rows, np.zeros((3, 4))])) == pytest.approx(math.sqrt(1125))


def test_a_point_whose_manipulability_is_past_the_float_range_is_a_usage_error(run_cli):
    """attack25: ``--point 1e150 0 0`` (within what ik squares) printed "manipulability: min 0,
    mean inf, max inf" and numpy's overflow warning; 1e100 gives the measure, 1e150 is refused
    as --point's."""
    result = run_cli("workspace", HUMANOID, "--tip", "l_foot_link", "--point", "1e100", "0", "0",
                     "--samples", "50")
    assert result.exit_code == 0, result.output
    assert "inf" not in result.output and "Warning" not in result.output
    result = run_cli("workspace", HUMANOID, "--tip", "l_foot_link", "--point", "1e150", "0", "0",
                     "--samples", "50", "-f", "json")
    assert result.exit_code == 2, result.output
    assert "--point: the manipulability of the point is past what a float holds" in result.output
