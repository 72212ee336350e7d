"""Which ROS a robot is written for, from what its files say (or None when they do not agree).

Evidence, each with the reason it is shown with:

- ``<ros2_control>`` in the URDF: ROS 2 (ros2_control reads it; ROS 1's ros_control does not);
- its controller YAML: ROS 2 with ``ros__parameters``, ROS 1 without (MoveIt's lists aside);
- Gazebo's ros_control plugin: ``libgazebo_ros_control.so`` is ROS 1's,
  ``libgazebo_ros2_control.so`` and the gz_ros2_control systems ROS 2's;
- the package.xml of the robot's package: ``catkin`` (ROS 1) or ``ament_cmake``/``ament_python``
  (ROS 2) as its build tool.

A robot whose evidence disagrees, or that has none, has no version: what depends on it is not
certain.
"""

from __future__ import annotations

import re
from pathlib import Path

from urdftool.description.actuation import gazebo_plugins
from urdftool.description.packages import manifest_text, package_of

_BUILD_TOOL = re.compile(rb"<buildtool_depend>\s*(catkin|ament_cmake|ament_python)\s*</buildtool_depend>")
_CONTROL = {"libgazebo_ros_control.so": 1, "libgazebo_ros2_control.so": 2,
            "gz_ros2_control-system": 2, "ign_ros2_control-system": 2}


def ros_version(robot) -> tuple[int | None, str]:
    """(1, 2 or None, the evidence in words), read once per robot."""
    return robot.memo(ros_version, lambda: _decide(robot))


def _decide(robot) -> tuple[int | None, str]:
    from urdftool.description.controllers import controller_files  # companions: not at import

    found: dict[int, list[str]] = {1: [], 2: []}
    if robot.children("ros2_control"):
        found[2].append("it has <ros2_control>")
    for read in controller_files(robot):
        if any(c.layout != "moveit" for c in read.controllers):
            found[2 if read.file.ros2 else 1].append(
                f"{read.file.display} is a {'ROS 2' if read.file.ros2 else 'ROS 1'} parameter file")
    for plugin in gazebo_plugins(robot):
        name = (plugin.get("filename") or "").strip().rsplit("/", 1)[-1]
        version = _CONTROL.get(name) or _CONTROL.get(re.sub(r"^lib|\.so$", "", name))
        if version:
            found[version].append(f"it loads {name}")
    package = _package_build_tool(robot)
    if package:
        found[package[0]].append(package[1])
    if found[1] and not found[2]:
        return 1, "; ".join(found[1])
    if found[2] and not found[1]:
        return 2, "; ".join(found[2])
    return None, ""


def _package_build_tool(robot) -> tuple[int, str] | None:
    """(version, why) from the build tool of the package.xml above the robot's file."""
    return None if robot.path == "-" else package_build_tool(robot.path)


def package_build_tool(path: str) -> tuple[int, str] | None:
    """(version, why) from the build tool of the package.xml above ``path``, or None."""
    folder = package_of(path)
    text = manifest_text(folder) if folder is not None else None
    match = _BUILD_TOOL.search(text) if text else None
    if match is None:
        return None
    tool = match.group(1).decode()
    return (1 if tool == "catkin" else 2), f"its package builds with {tool}"
