"""Reading controller YAML as each controller manager does: ROS 2 blocks, ROS 1, MoveIt."""

from __future__ import annotations

import textwrap

from urdftool.description.controller_classes import CLASSES, lookup
from urdftool.description.controllers import read_controllers
from urdftool.description.documents import read_yaml


def read(tmp_path, text):
    path = tmp_path / "c.yaml"
    path.write_text(textwrap.dedent(text))
    return read_controllers(read_yaml(path))


def test_repeated_node_blocks_merge_in_ros2_files_only(tmp_path):
    ros2 = read(tmp_path, """\
        /**:
          ros__parameters: {update_rate: 5}
        /**:
          controller_manager:
            ros__parameters:
              arm: {type: position_controllers/JointGroupPositionController}
        /**:
          arm:
            ros__parameters: {joints: [a]}
        """)
    [arm] = ros2.controllers
    assert (arm.layout, arm.line, arm.block_line) == ("ros2", 6, 8)
    assert [(j.name, j.line) for j in arm.joints()] == [("a", 9)]
    assert arm.params["update_rate"] == 5  # a /** block's parameters reach every node
    ros1 = read(tmp_path, "ns:\n  a: {type: x/Y, joints: [a]}\nns:\n  b: {type: x/Z}\n")
    assert [c.name for c in ros1.controllers] == ["b"]  # rosparam (PyYAML): the last wins


def test_ros2_type_in_the_controllers_own_block(tmp_path):
    [arm] = read(tmp_path, """\
        arm:
          ros__parameters:
            type: joint_trajectory_controller/JointTrajectoryController
            joints: [a, b]
        """).controllers
    assert arm.cls.name == "joint_trajectory_controller/JointTrajectoryController"
    assert [j.name for j in arm.joints()] == ["a", "b"]


def test_moveit_layouts_are_read_wherever_they_are(tmp_path):
    nested = read(tmp_path, """\
        move_group:
          ros__parameters:
            moveit_simple_controller_manager:
              controller_names: [arm, hand]
              arm: {type: FollowJointTrajectory, joints: [a, b]}
              hand: {type: GripperCommand, joints: [c]}
        """)
    assert [(c.layout, c.name, c.type, [j.name for j in c.joints()]) for c in nested.controllers] == [
        ("moveit", "arm", "FollowJointTrajectory", ["a", "b"]),
        ("moveit", "hand", "GripperCommand", ["c"])]
    top = read(tmp_path, "controller_names: [arm, missing]\narm: {type: FollowJointTrajectory, joints: [a]}\n")
    # (a name listed without its mapping is no controller: moveit_config's reader says so, U812)
    assert [(c.name, c.line) for c in top.controllers] == [("arm", 2)]


def test_unknown_classes_guess_joint_keys_known_ones_read_their_own(tmp_path):
    ros1 = read(tmp_path, """\
        c: {type: position_controllers/JointPositionController, joint: a, joints: [b]}
        v: {type: acme/Twist, joint: tcp}
        """)
    known, vendor = ros1.controllers
    assert known.known and [j.name for j in known.joints()] == ["a"]  # joints: is not read
    assert not vendor.known and [j.name for j in vendor.joints()] == ["tcp"]


def test_class_table_is_sorted_unique_and_sourced():
    keys = [(c.ros == 1, c.name) for c in CLASSES]
    assert keys == sorted(keys) and len(set(keys)) == len(keys)
    assert all(c.source.startswith("ros-controls/ros") and ".xml" in c.source for c in CLASSES)
    assert lookup("position_controllers/JointPositionController", 2) is None
    assert lookup("position_controllers/JointPositionController", 1).joints == {"joint": "name"}
    assert lookup("joint_trajectory_controller/JointTrajectoryController", 2).required == (
        "joints", "command_interfaces", "state_interfaces")


def test_dotted_parameter_names_are_the_nested_ones(tmp_path):
    [arm] = read(tmp_path, """\
        controller_manager:
          ros__parameters:
            arm.type: joint_trajectory_controller/JointTrajectoryController
        arm:
          ros__parameters:
            joints: [a]
            constraints.goal_time: 0.5
            constraints:
              a.goal: 0.1
        """).controllers
    assert (arm.name, arm.line) == ("arm", 3)
    assert arm.params["constraints"] == {"goal_time": 0.5, "a": {"goal": 0.1}}
    assert arm.params["constraints"].lines["goal_time"] == 7


def test_one_controller_name_declared_in_two_namespaces_is_two_controllers(tmp_path):
    """The managers of namespaces robot1 and robot2 both declare 'arm': each is a controller
    reading its own namespace's block (and those of namespaces declaring nothing), where one
    name used to be one controller with the blocks of both merged (robot2's joints read as
    robot1's)."""
    section = """\
        {r}:
          controller_manager:
            ros__parameters:
              arm: {{type: position_controllers/JointGroupPositionController}}
          arm:
            ros__parameters: {{joints: [{r}/a]}}
        """
    sections = "".join(section.rstrip(" ").format(r=r) for r in ("robot1", "robot2"))
    found = read(tmp_path, sections + """\
        /**/arm:
          ros__parameters: {interface_name: position}
        """)
    assert [(c.namespace, [j.name for j in c.joints()], c.params.get("interface_name"))
            for c in found.controllers] == [("robot1", ["robot1/a"], "position"),
                                            ("robot2", ["robot2/a"], "position")]
