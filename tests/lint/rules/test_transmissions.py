"""U5xx transmission and ros2_control rules: ROS 1 and ROS 2 forms, PR2 and franka patterns."""

from __future__ import annotations

import pytest

from crossfile_helpers import HEAD_ROBOT, broken_copy, case_messages, check_folder


def tx(joint="head_joint", iface="hardware_interface/PositionJointInterface", name="t"):
    return (f'<transmission name="{name}"><type>transmission_interface/SimpleTransmission</type>'
            f'<joint name="{joint}"><hardwareInterface>{iface}</hardwareInterface></joint>'
            f'<actuator name="{name}_m"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>')


def codes(tmp_path, body):
    return [code for _, _, code in check_folder(tmp_path, {"robot.urdf": HEAD_ROBOT.format(body=body)})[0]]


def test_ros2_form_transmission_inside_ros2_control(tmp_path):
    body = """<ros2_control name="s" type="system"><hardware><plugin>p/P</plugin></hardware>
      <joint name="head_joint"><command_interface name="position"/><state_interface name="position"/></joint>
      <transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>
        <actuator name="a" role="a"/><joint name="head_joint" role="j"><mechanical_reduction>0</mechanical_reduction></joint>
      </transmission></ros2_control>"""
    assert codes(tmp_path, body) == ["U505"]


def test_different_interfaces_in_separate_transmissions_are_allowed(tmp_path):
    # franka_gazebo declares Position, Velocity and Effort transmissions per joint
    body = tx(name="a") + tx(name="b", iface="hardware_interface/EffortJointInterface") + tx(
        name="c", iface="franka_hw/FrankaStateInterface")
    assert codes(tmp_path, body) == []
    assert codes(tmp_path / "2", body + tx(name="d", iface="EffortJointInterface")) == ["U506", "U508"]


def test_read_only_transmission_may_name_a_fixed_joint(tmp_path):
    assert codes(tmp_path, tx() + tx(joint="cam_joint", name="m", iface="franka_hw/FrankaModelInterface")) == []


def test_pr2_style_transmissions(tmp_path):
    body = """<transmission type="pr2_mechanism_model/SimpleTransmission" name="t">
      <actuator name="m"/><joint name="head_joint"/><mechanicalReduction>-1.0</mechanicalReduction></transmission>
      <transmission type="PR2GripperTransmission" name="g"><actuator name="gm"/>
      <gap_joint name="head_jnt" mechanical_reduction="1"/><use_simulated_gripper_joint/></transmission>"""
    assert codes(tmp_path, body) == ["U501"]


def test_unactuated_joint_with_ros2_control_but_not_mimic(tmp_path):
    body = """<link name="f"/><joint name="finger" type="revolute"><parent link="head"/><child link="f"/>
      <axis xyz="0 0 1"/><limit lower="0" upper="1" effort="1" velocity="1"/><mimic joint="head_joint"/></joint>
      <ros2_control name="s" type="system"><hardware><plugin>p/P</plugin></hardware>
      <joint name="head_joint"><command_interface name="position"/><state_interface name="position"/></joint></ros2_control>"""
    assert codes(tmp_path, body) == []


def test_r2d2_transmission_on_a_misspelt_joint(tmp_path):
    findings = broken_copy(tmp_path, "r2d2", "r2d2.urdf.xacro", 'simple_transmission joint="head_joint"',
                           'simple_transmission joint="head_jiont"')
    assert [f.code for f in findings] == ["U501"]  # head_joint stays actuated by ros2_control
    u501 = findings[0]
    assert u501.file.endswith("transmission.xacro") and u501.location.via[0].file.endswith("r2d2.urdf.xacro")


def test_humanoid_unknown_hardware_interface(tmp_path):
    findings = broken_copy(tmp_path, "humanoid", "transmission.xacro", "${interface}JointInterface",
                           "${interface}Interface")
    assert {f.code for f in findings} == {"U503"} and len(findings) == 20
    assert "did you mean 'PositionJointInterface'" in findings[0].message


@pytest.mark.parametrize("case, code, fix", [
    ("U502_transmission_fixed_joint.urdf", "U502",
     "remove the transmission, or make the joint revolute, continuous or prismatic"),
    ("U504_transmission_no_actuator.urdf", "U504", 'add <actuator name="...">'),
    ("U512_ros2_control_fixed_joint.urdf", "U512", "remove it from <ros2_control>, or make the joint"),
])
def test_message_says_what_would_be_right(case, code, fix):
    messages = case_messages(case, code)
    assert messages and all(fix in m for m in messages)


def test_unknown_interface_on_a_ros2_robot_says_ros2_control_does_not_read_it(tmp_path):
    robot = HEAD_ROBOT.format(body="""
      <transmission name="t"><type>transmission_interface/SimpleTransmission</type>
        <joint name="head_joint"><hardwareInterface>hardware_interface/PositionInterface</hardwareInterface></joint>
        <actuator name="m"/></transmission>
      <ros2_control name="s" type="system"><hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="head_joint"><command_interface name="position"/><state_interface name="position"/></joint></ros2_control>""")
    _, findings = check_folder(tmp_path, {"robot.urdf": robot}, select=("U503",))
    assert [f.code for f in findings] == ["U503"]
    assert "ros2_control does not read this ROS 1 transmission" in findings[0].message
