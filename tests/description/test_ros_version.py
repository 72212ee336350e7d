"""ros_version: the one owner of which ROS reads a robot (the plugin, transmission and gazebo
rules and xacro's ROS 1 dialect all ask it)."""

from __future__ import annotations

from pathlib import Path

from urdftool.description.load import load
from urdftool.description.ros_version import package_build_tool, ros_version, ros_versions

ROBOT = '<robot name="r"><link name="base"/>{body}</robot>'
MANIFEST = """<package format="3"><name>bot</name><version>0.0.0</version>
  <description>d</description><maintainer email="a@b.c">a</maintainer><license>MIT</license>
  {tools}</package>"""
ROS1_LAUNCH = """<launch>
  <param name="robot_description" command="$(find xacro)/xacro $(find bot)/urdf/robot.urdf.xacro"/>
  <node name="rsp" pkg="robot_state_publisher" type="robot_state_publisher"/>
</launch>"""


def _package(tmp_path: Path, tools: str, body: str = "", extra: dict | None = None) -> Path:
    (tmp_path / "urdf").mkdir()
    (tmp_path / "package.xml").write_text(MANIFEST.format(tools=tools))
    robot = tmp_path / "urdf" / "robot.urdf.xacro"
    robot.write_text(ROBOT.format(body=body))
    for name, text in (extra or {}).items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    return robot


def test_a_build_tool_under_a_condition_names_no_version(tmp_path):
    """A package built by both ROS versions (conditioned build tools) says nothing: the first
    build tool written is not the one that reads it."""
    robot = _package(tmp_path, '<buildtool_depend condition="$ROS_VERSION == 1">catkin'
                               '</buildtool_depend><buildtool_depend condition="$ROS_VERSION == 2">'
                               'ament_cmake</buildtool_depend>')
    assert package_build_tool(str(robot)) is None
    assert ros_version(load(robot)) == (None, "")


def test_a_commented_out_build_tool_is_not_read(tmp_path):
    robot = _package(tmp_path, "<!-- <buildtool_depend>catkin</buildtool_depend> -->"
                               "<buildtool_depend>ament_cmake</buildtool_depend>")
    assert package_build_tool(str(robot))[0] == 2
    version, why = ros_version(load(robot))
    assert version == 2 and why.startswith("its package builds with ament_cmake")


def test_the_one_version_is_the_one_every_piece_of_evidence_names(tmp_path):
    """An ament package whose ROS 1 launch file builds the robot has no one version: the plugin
    rules (ros_version) and the transmission rules (ros_versions) see the same evidence."""
    robot = _package(tmp_path, "<buildtool_depend>ament_cmake</buildtool_depend>",
                     extra={"launch/view.launch": ROS1_LAUNCH})
    found = ros_versions(load(robot))
    assert found.versions == {1, 2}
    assert [e.kind for e in found.evidence] == ["package", "launch"]
    assert ros_version(load(robot)) == (None, "")


def test_controller_files_count_for_both_views(tmp_path):
    """A ROS 2 parameter file is evidence for the transmission rules too (ros_versions), as it
    was for the plugin rules."""
    robot = _package(tmp_path, "", extra={
        "config/controllers.yaml": "controller_manager:\n  ros__parameters:\n    update_rate: 10\n"
                                   "    jtc:\n      type: joint_trajectory_controller/"
                                   "JointTrajectoryController\n"})
    found = ros_versions(load(robot))
    assert found.ros2_only and [e.kind for e in found.evidence] == ["controllers"]
    assert ros_version(load(robot))[0] == 2


def test_many_launch_files_are_named_two_and_counted(tmp_path):
    """PPI-PUT's A1 named its seven launch files on each of six U640 lines: the first two are
    named, the rest counted."""
    launches = {f"launch/v{index}.launch": ROS1_LAUNCH for index in range(5)}
    robot = _package(tmp_path, "<buildtool_depend>catkin</buildtool_depend>", extra=launches)
    why = ros_versions(load(robot)).why(1)
    assert why.count("launches it") == 2 and why.endswith("; 3 more launch files launch it")
    assert why.startswith("its package builds with catkin")
