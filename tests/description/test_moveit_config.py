"""MoveIt's configuration read from its YAML (urdftool/description/moveit_config.py): what a
file of another shape than MoveIt's is said as (the rules' own cases are in
tests/lint/rules/test_moveit.py)."""

from __future__ import annotations

import pytest

from crossfile_helpers import HEAD_ROBOT, check_folder

ROBOT = HEAD_ROBOT.format(body="")
SRDF = '<robot name="r">\n<group name="head">\n<chain base_link="base_link" tip_link="head"/>\n</group>\n</robot>\n'
ROS2_CONTROLLERS = ("controller_manager:\n  ros__parameters:\n    head_controller:\n"
                    "      type: joint_trajectory_controller/JointTrajectoryController\n"
                    "head_controller:\n  ros__parameters:\n    joints: [head_joint]\n")


@pytest.mark.parametrize("manager, line", [
    ("moveit_simple_controller_manager: [head_controller]\n", None),
    ("moveit_simple_controller_manager:\n  controller_names: [[head_controller]]\n", 2),
    ("moveit_simple_controller_manager:\n  controller_names:\n    - {head_controller: 1}\n", 3),
])
def test_a_moveit_controller_list_of_another_shape_is_said_at_its_line(tmp_path, manager, line):
    """attack30: a manager that is a list (its lines a list: ``.get`` of them) and a
    controller name that is a list or a mapping (looked up as a key, unhashable) crashed
    every rule reading MoveIt's controllers (U900). Each is said at its line."""
    files = {"robot.urdf": ROBOT, "config/robot.srdf": SRDF,  # (MoveIt's package: beside it)
             "config/ros2_controllers.yaml": ROS2_CONTROLLERS,
             "config/moveit_controllers.yaml": manager}
    found, findings = check_folder(tmp_path, files)
    assert not [f for f in findings if f.code == "U900"], [f.message for f in findings]
    assert line is None or ("moveit_controllers.yaml", line) in {(f, at) for f, at, _ in found}
