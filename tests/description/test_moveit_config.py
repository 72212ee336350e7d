"""MoveIt's configuration read from its YAML (urdftool/description/moveit_config.py): what a
file of another shape than MoveIt's is said as (the rules' own cases are in
tests/lint/rules/test_moveit.py)."""

from __future__ import annotations

import textwrap

import pytest

from crossfile_helpers import HEAD_ROBOT, check_folder
from urdftool.description.documents import read_yaml
from urdftool.description.moveit_config import controller_manager, moveit_controllers, reads_list

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


# --- the one reader of MoveIt's controller lists (moveit_config.moveit_controllers) -----------

def _read_list(tmp_path, text):
    path = tmp_path / "moveit_controllers.yaml"
    path.write_text(textwrap.dedent(text))
    entries, problems = moveit_controllers(read_yaml(path))
    return [(e.name, e.line, e.type, [j for j, _ in e.joints], e.action_ns) for e in entries], problems


@pytest.mark.parametrize("text", [
    # MoveIt 1: every key moveit_simple_controller_manager's isStruct asks for
    """\
    controller_list:
      - name: arm
        action_ns: follow_joint_trajectory
        type: FollowJointTrajectory
        default: true
        joints: [a, b]
    """,
    # MoveIt 2: the names, one mapping each beside them
    """\
    moveit_controller_manager: moveit_simple_controller_manager/MoveItSimpleControllerManager
    moveit_simple_controller_manager:
      controller_names: [arm]
      arm: {action_ns: follow_joint_trajectory, type: FollowJointTrajectory, joints: [a, b]}
    """,
    # MoveIt 2, the file a launch file loads into moveit_simple_controller_manager's namespace
    """\
    controller_names: [arm]
    arm: {action_ns: follow_joint_trajectory, type: FollowJointTrajectory, joints: [a, b]}
    """,
    # a node's parameters, any depth (the keys above a list are the namespace it is loaded in)
    """\
    move_group:
      ros__parameters:
        moveit_simple_controller_manager:
          controller_names: [arm]
          arm: {action_ns: follow_joint_trajectory, type: FollowJointTrajectory, joints: [a, b]}
    """,
])
def test_each_layout_moveit_reads_is_read_without_a_problem(tmp_path, text):
    entries, problems = _read_list(tmp_path, text)
    assert problems == [] and [(name, kind, joints, action) for name, _, kind, joints, action in entries] == [
        ("arm", "FollowJointTrajectory", ["a", "b"], "follow_joint_trajectory")]


@pytest.mark.parametrize("text, expected", [
    ("controller_list: {name: arm}\n", [(1, "controller_list must be a list")]),
    ("controller_list:\n  - arm\n  - {action_ns: x, type: FollowJointTrajectory, joints: [a]}\n",
     [(2, "needs a 'name:'"), (3, "needs a 'name:'")]),
    ("controller_list:\n  - name: arm\n    type: FollowJointTrajectory\n    joints: [a]\n",
     [(2, "'arm' has no action_ns: MoveIt's simple controller manager skips it")]),
    ("controller_list:\n  - {name: arm, action_ns: x, joints: [a]}\n", [(2, "has no type")]),
    ("controller_list:\n  - {name: arm, action_ns: x, type: FollowJointTrajectory}\n",
     [(2, "has no joints")]),
    ("controller_list:\n  - {name: arm, action_ns: x, type: FollowJointTrajectory, joints: a}\n",
     [(2, "needs a 'joints:' list")]),
    ("controller_list:\n  - name: arm\n    action_ns: x\n    type: FollowJointTrajectory\n"
     "    joints: [a, [b]]\n", [(5, "joint '['b']' must be a joint's name")]),
    ("controller_list:\n  - name: arm\n    action_ns: x\n    type: FollowJointTrajectory\n"
     "    default: yes please\n    joints: [a]\n", [(5, "default 'yes please' must be true or false")]),
    ("controller_names: arm\n", [(1, "controller_names must be a list")]),
    ("controller_names: [arm, [hand]]\narm: {action_ns: x, type: FollowJointTrajectory, joints: [a]}\n",
     [(1, "each entry of controller_names must be a controller's name")]),
    ("moveit_simple_controller_manager:\n  controller_names: [arm]\n"
     "arm: {action_ns: x, type: FollowJointTrajectory, joints: [a]}\n",
     [(2, "its mapping is at the top of the file, outside the mapping that holds controller_names")]),
    ("controller_names: [arm]\narm: {type: FollowJointTrajectory, joints: [a]}\n",
     [(2, "'arm' has no action_ns")]),
    ("controller_names: [arm]\narm: {action_ns: x, type: FollowJointTrajectory, joints: []}\n",
     [(2, "empty joints list")]),
    ("moveit_simple_controller_manager: [arm]\n", [(1, "needs a 'controller_names:' list")]),
    ("moveit_simple_controller_manager:\n  arm: {action_ns: x}\n", [(1, "needs a 'controller_names:' list")]),
])
def test_each_shape_moveit_refuses_is_a_problem_at_its_line(tmp_path, text, expected):
    _, problems = _read_list(tmp_path, text)
    assert [line for line, _ in problems] == [line for line, _ in expected], problems
    for (_, message), (_, words) in zip(problems, expected):
        assert words in message, message


def test_an_entry_moveit_skips_is_still_read_for_its_name_and_joints(tmp_path):
    """What else is wrong with a controller (its joints not URDF joints) is still said."""
    entries, problems = _read_list(tmp_path, "controller_list:\n  - {name: arm, type: FollowJointTrajectory, "
                                             "joints: [a]}\n")
    assert [(name, joints) for name, _, _, joints, _ in entries] == [("arm", ["a"])]
    assert [line for line, _ in problems] == [2]


@pytest.mark.parametrize("text", [
    "moveit_controller_manager: moveit_fake_controller_manager/MoveItFakeControllerManager\n"
    "controller_list:\n  - {name: fake_arm, type: FollowJointTrajectory, joints: [a]}\n",
    "controller_list:\n  - {name: fake_arm, type: interpolate, joints: [a]}\n  - {name: b, joints: [c]}\n",
])
def test_the_fake_controller_managers_list_needs_only_names_and_joints(tmp_path, text):
    assert _read_list(tmp_path, text)[1] == []


def test_every_list_of_a_file_is_read(tmp_path):
    """A file may hold a list per namespace it is loaded in (robot1's, robot2's)."""
    entries, problems = _read_list(tmp_path, """\
        robot1:
          controller_list:
            - {name: arm, action_ns: x, type: FollowJointTrajectory, joints: [a]}
        robot2:
          move_group:
            controller_list:
              - {name: arm, type: FollowJointTrajectory, joints: [b]}
        """)
    assert [(name, line, joints) for name, line, _, joints, _ in entries] == [
        ("arm", 3, ["a"]), ("arm", 7, ["b"])]
    assert [line for line, _ in problems] == [7]


def test_controller_manager_names_the_plugin_and_whether_it_reads_a_list(tmp_path):
    path = tmp_path / "moveit_controllers.yaml"
    path.write_text("moveit_controller_manager: moveit_ros_control_interface/Ros2ControlManager\n")
    plugin = controller_manager(read_yaml(path))
    assert plugin == ("moveit_ros_control_interface/Ros2ControlManager", 1)
    assert not reads_list(plugin[0])
    assert reads_list("moveit_simple_controller_manager/MoveItSimpleControllerManager")


def test_another_nodes_controller_names_is_not_moveits(tmp_path):
    """MoveIt reads moveit_simple_controller_manager.controller_names: a joystick node's list
    of the controllers it switches between, or MoveIt Task Constructor's, is theirs."""
    assert _read_list(tmp_path, """\
        joy_util_node:
          ros__parameters:
            controller_names: [neural_controller, forward_position_controller]
        """) == ([], [])
