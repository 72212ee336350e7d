"""Dynamics against a hand-computed two-link arm, and the humanoid's gravity margins."""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest

from conftest import ROBOTS
from urdftool.physics.dynamics import build, gravity_loads, gravity_variables, state
from urdftool.description.load import load

G0 = 9.81
M1, M2, L1, L2 = 2.0, 1.0, 0.5, 0.4  # point-like masses at the link ends, arm in the x-z plane

ARM = f"""<robot name="arm">
  <link name="base"><inertial><mass value="3"/>
    <inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial></link>
  <link name="fixed_tool"/>
  <joint name="tool" type="fixed"><parent link="base"/><child link="fixed_tool"/></joint>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="20" velocity="1"/></joint>
  <link name="upper"><inertial><origin xyz="{L1} 0 0"/><mass value="{M1}"/>
    <inertia ixx="1e-9" ixy="0" ixz="0" iyy="1e-9" iyz="0" izz="1e-9"/></inertial></link>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/>
    <origin xyz="{L1} 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <link name="fore"><inertial><origin xyz="{L2} 0 0"/><mass value="{M2}"/>
    <inertia ixx="1e-9" ixy="0" ixz="0" iyy="1e-9" iyz="0" izz="1e-9"/></inertial></link>
</robot>"""


@pytest.fixture(scope="module")
def arm(tmp_path_factory):
    path = tmp_path_factory.mktemp("arm") / "arm.urdf"
    path.write_text(ARM)
    return build(load(path))


def _hand_gravity(q1, q2):
    # Rotation about +y pitches a link along x downwards: heights z1 = -L1 sin q1 and
    # z2 = -L1 sin q1 - L2 sin(q1 + q2). G = dV/dq with V = g (M1 z1 + M2 z2): the torque the
    # joint must apply to hold the pose (tau = M a + C v + G).
    g2 = -M2 * G0 * L2 * math.cos(q1 + q2)
    g1 = -(M1 + M2) * G0 * L1 * math.cos(q1) + g2
    return np.array([g1, g2])


@pytest.mark.parametrize("q1,q2", [(0.0, 0.0), (0.3, -0.7), (1.2, 0.4)])
def test_gravity_matches_hand_computation(arm, q1, q2):
    result = state(arm, {"shoulder": q1, "elbow": q2})
    assert np.allclose(result.G, _hand_gravity(q1, q2), atol=1e-9)


def test_total_mass_counts_root_and_fixed_links(arm):
    assert math.isclose(state(arm, {}).mass, 3 + M1 + M2)


def test_whole_body_com(arm):
    result = state(arm, {})
    assert np.allclose(result.com, [(M1 * L1 + M2 * (L1 + L2)) / (3 + M1 + M2), 0, 0])


def test_tau_matches_rnea(arm):
    result = state(arm, {"shoulder": 0.2}, {"shoulder": 1.0, "elbow": -2.0}, {"elbow": 3.0})
    assert result.rnea_residual < 1e-9
    assert result.C.shape == (2, 2) and np.allclose(result.M, result.M.T)


def test_gravity_loads_flag_a_weak_joint(arm):
    loads = {load.joint: load for load in gravity_loads(arm, 50)}
    assert math.isclose(loads["elbow"].zero_pose, M2 * G0 * L2)
    assert not loads["elbow"].holds  # 3.9 N m against a 1 N m limit
    assert loads["shoulder"].holds


def test_humanoid_holds_itself_with_mx28(run_cli):
    result = run_cli("dynamics", ROBOTS / "humanoid" / "humanoid.urdf.xacro", "--samples", "100",
                     "--format", "json")
    assert result.exit_code == 0, result.output
    loads = json.loads(result.output)["gravity_loads"]
    assert {load["effort"] for load in loads} == {2.5}
    assert all(load["holds"] for load in loads)
    hips = [l for l in loads if "hip_pitch" in l["joint"]]
    assert all(0.3 < l["worst"] < 2.5 for l in hips)


def test_dynamics_unknown_joint_is_usage_error(run_cli):
    result = run_cli("dynamics", ROBOTS / "humanoid" / "humanoid.urdf.xacro", "--q", "l_kne=1")
    assert result.exit_code == 2 and "l_knee" in result.output
    assert result.stderr.startswith("urdftool: error: --q: unknown joint 'l_kne'")
    result = run_cli("dynamics", ROBOTS / "humanoid" / "humanoid.urdf.xacro", "--v", "l_el=x")
    assert result.stderr == ("urdftool: error: --v: value 'x' for joint 'l_el' is not a "
                             "number\n")


def test_joint_values_say_which_input_is_wrong(tmp_path):
    from urdftool.kinematics.configuration import ConfigError, joint_values

    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    robot = load(path)
    values = joint_values(robot, {"shoulder": "90"}, None, {"elbow": "1"}, degrees=True)
    assert values.q == {"shoulder": pytest.approx(math.pi / 2)} and values.v is None
    assert values.a == {"elbow": pytest.approx(math.radians(1))}
    with pytest.raises(ConfigError, match="^unknown joint 'elbw'") as caught:
        joint_values(robot, {}, {"elbw": "1"})
    assert caught.value.argument == "v"


def test_a_robot_without_mass_gets_a_warning(tmp_path):
    from urdftool.physics.dynamics import build, state

    path = tmp_path / "massless.urdf"
    path.write_text('<robot name="r"><link name="a"/><link name="b"/><joint name="j" '
                    'type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>'
                    '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>')
    result = state(build(load(str(path))), {})
    assert result.warnings and result.warnings[0].startswith("no link has a mass")


MIMIC_ARM = ARM.replace('<limit lower="-3" upper="3" effort="1" velocity="1"/></joint>',
                        '<limit lower="-3" upper="3" effort="1" velocity="1"/>'
                        '<mimic joint="shoulder" multiplier="-1" offset="0.2"/></joint>')


@pytest.fixture(scope="module")
def mimic_arm(tmp_path_factory):
    path = tmp_path_factory.mktemp("mimic") / "arm.urdf"
    path.write_text(MIMIC_ARM)
    return build(load(path))


@pytest.mark.parametrize("q1", [0.0, 0.7, -1.1])
def test_mimic_joint_follows_its_variable(mimic_arm, q1):
    # elbow = -shoulder + 0.2: the forearm keeps a fixed pitch of 0.2 rad
    result = state(mimic_arm, {"shoulder": q1}, {"shoulder": 1.5}, {})
    assert np.allclose(result.G, _hand_gravity(q1, -q1 + 0.2), atol=1e-9)
    assert result.rnea_residual < 1e-9
    assert np.allclose(mimic_arm.velocity({"shoulder": 1.5}), [1.5, -1.5])


def test_gravity_loads_draw_mimic_joints_from_their_variable(mimic_arm):
    loads = {load.joint: load for load in gravity_loads(mimic_arm, 30, seed=3)}
    for load in loads.values():
        assert set(load.worst_pose) == {"shoulder"}  # the mimic joint is not drawn
    # the forearm's pitch never changes, so neither does the elbow's torque
    expected = M2 * G0 * L2 * math.cos(0.2)
    assert math.isclose(loads["elbow"].worst, expected, rel_tol=1e-9)
    worst = max(abs(_hand_gravity(q, -q + 0.2)[0]) for q in
                [0.0] + [p["shoulder"] for p in [loads["shoulder"].worst_pose]])
    assert math.isclose(loads["shoulder"].worst, worst, rel_tol=1e-9)


def test_samples_text_reports_margins_without_the_zero_pose_matrices(run_cli, tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    result = run_cli("dynamics", path, "--samples", "20")
    assert result.exit_code == 1, result.output
    assert "M(q)" not in result.output and "G(q)" not in result.output
    assert "1 joint cannot hold itself: elbow" in result.output
    with_q = run_cli("dynamics", path, "--samples", "20", "--q", "shoulder=0.5")
    assert "M(q): joint-space mass matrix" in with_q.output


def test_a_vertical_axis_carries_no_gravity_load(run_cli):
    result = run_cli("dynamics", ROBOTS / "humanoid" / "humanoid.urdf.xacro", "--samples", "20",
                     "--format", "json")
    loads = {load["joint"]: load for load in json.loads(result.output)["gravity_loads"]}
    assert loads["l_hip_yaw"]["worst"] == 0.0 and loads["r_hip_yaw"]["worst"] == 0.0


def test_a_massless_robot_is_warned_about(run_cli, tmp_path):
    path = tmp_path / "massless.urdf"
    path.write_text(re.sub(r"<inertial>.*?</inertial>", "", ARM, flags=re.S))
    result = run_cli("dynamics", path, "--samples", "5")
    assert result.exit_code == 0
    assert "warning: no link has a mass" in result.stderr
    path.write_text(ARM)
    assert "warning" not in run_cli("dynamics", path, "--samples", "5").stderr


def test_gravity_variables_are_the_branch_of_the_joint(mimic_arm):
    humanoid = build(load(ROBOTS / "humanoid" / "humanoid.urdf.xacro"))
    assert gravity_variables(humanoid, "r_knee") == {
        "r_hip_yaw", "r_hip_roll", "r_hip_pitch", "r_knee", "r_ank_pitch", "r_ank_roll"}
    assert gravity_variables(humanoid, "head_pan") == {"head_pan", "head_tilt"}
    assert gravity_variables(mimic_arm, "elbow") == {"shoulder"}  # through the mimic


@pytest.mark.parametrize("q2,v1,v2", [(0.4, 1.0, -2.0), (-1.1, 0.5, 0.3)])
def test_coriolis_matrix_matches_the_two_link_closed_form(arm, q2, v1, v2):
    # point masses: h = -M2 L1 L2 sin q2, C = [[h v2, h (v1 + v2)], [-h v1, 0]] (Christoffel)
    result = state(arm, {"shoulder": 0.3, "elbow": q2}, {"shoulder": v1, "elbow": v2}, {})
    h = -M2 * L1 * L2 * math.sin(q2)
    np.testing.assert_allclose(result.C, [[h * v2, h * (v1 + v2)], [-h * v1, 0.0]], atol=1e-6)
    np.testing.assert_allclose(result.tau - result.G, result.C @ [v1, v2], atol=1e-12)


def test_a_robot_whose_pinocchio_data_cannot_fit_is_refused_before_allocating(tmp_path,
                                                                              monkeypatch):
    # Pinocchio's Data holds nv^3 tensors: 300 joints ~1.7 GB; with 1 GiB allowed it is refused
    import resource

    from conftest import synthetic_robot
    from urdftool.errors import DynamicsError

    robot = load(str(synthetic_robot(tmp_path, 301)))
    monkeypatch.setattr(resource, "getrlimit", lambda _: (1024 ** 3, resource.RLIM_INFINITY))
    with pytest.raises(DynamicsError, match="300 joint variables.*cube of the joints"):
        build(robot)
