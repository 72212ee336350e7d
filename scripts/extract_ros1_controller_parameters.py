#!/usr/bin/env python3
"""Record what ROS 1's ros_controllers read, with the source line of each fact.

ROS 1 controllers read their parameters in C++ (``controller_nh.getParam("publish_rate",
publish_rate_)``), with nothing declared beside them. The facts urdftool checks are listed in
:data:`FACTS` below, each with the file and a pattern of the line that reads it (and, for a
parameter the controller cannot start without, the line that gives up); this script finds each
pattern in ros-controls/ros_controllers at its noetic-devel branch, refuses to write anything
when one is not there, and writes ``urdftool/data/ros_controllers.json`` with the class names
the plugin XML files export and each fact's path and line. ros_controllers is BSD-3-Clause.

    python scripts/extract_ros1_controller_parameters.py \\
        --ros-controllers /path/to/ros_controllers.git -o urdftool/data/ros_controllers.json

(``--tree DIR`` reads a checked-out folder instead, as tests/scripts does with a fixture.)
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from extract_controller_parameters import DirTree, GitTree, dump  # noqa: E402

REPOSITORY, REF = "ros-controls/ros_controllers", "noetic-devel"
LICENCE = {"spdx": "BSD-3-Clause",
           "notice": ("Facts (class names, parameter names and types, which parameters a "
                      "controller cannot start without) read from ros-controls/ros_controllers, "
                      "Copyright its authors, BSD 3-Clause licence; each with the file and line.")}

JSC = "joint_state_controller/src/joint_state_controller.cpp"
DDC = "diff_drive_controller/src/diff_drive_controller.cpp"
JTC = "joint_trajectory_controller/include/joint_trajectory_controller/joint_trajectory_controller_impl.h"
JTC_ADAPTER = "joint_trajectory_controller/include/joint_trajectory_controller/hardware_interface_adapter.h"
GRIPPER = "gripper_action_controller/include/gripper_action_controller/gripper_action_controller_impl.h"
GRIPPER_ADAPTER = "gripper_action_controller/include/gripper_action_controller/hardware_interface_adapter.h"
FORWARD = "forward_command_controller/include/forward_command_controller/forward_command_controller.h"
FORWARD_GROUP = ("forward_command_controller/include/forward_command_controller/"
                 "forward_joint_group_command_controller.h")

# (type, required, path, pattern of the line reading it). A required parameter's reading line
# must be followed, within a few lines, by ``return false`` (checked). control_toolbox's
# Pid::init(NodeHandle) refuses a namespace without ``p`` ("No p gain specified for pid"): the
# controllers that init a Pid from a namespace need its p.
_RATE = ("double", True, None, r'getParam\("publish_rate", publish_rate_\)')
_TRAJECTORY = {
    "joints": ("string_array", True, JTC, r'getStrings\(controller_nh_, "joints"\)'),
    "state_publish_rate": ("double", False, JTC, r'getParam\("state_publish_rate"'),
    "action_monitor_rate": ("double", False, JTC, r'getParam\("action_monitor_rate"'),
    "stop_trajectory_duration": ("double", False, JTC, r'getParam\("stop_trajectory_duration"'),
    "allow_partial_joints_goal": ("bool", False, JTC, r'param<bool>\("allow_partial_joints_goal"'),
}
_CLOSED_LOOP = {"gains.__map_joints.p": ("double", True, JTC_ADAPTER, r'pids_\[i\]->init\(joint_nh\)')}
_ONE_JOINT = {"joint": ("string", True, FORWARD, r'getParam\("joint", joint_name\)')}
_JOINT_GROUP = {"joints": ("string_array", True, FORWARD_GROUP, r'getParam\(param_name, joint_names_\)')}


def _own(path: str, **facts) -> dict:
    return {name: (kind, required, path, pattern) for name, (kind, required, pattern) in facts.items()}


def _pid_loop(path: str) -> dict:
    """A single-joint controller closing its loop with a control_toolbox Pid read from ``pid``."""
    return _own(path, joint=("string", True, r'getParam\("joint", joint_name\)'),
                **{"pid.p": ("double", True, r'pid_controller_\.init\(ros::NodeHandle\(n, "pid"\)\)')})


FACTS = {
    "joint_state_controller/JointStateController": {
        "publish_rate": (*_RATE[:2], JSC, _RATE[3]),
        "joints": ("string_array", False, JSC, r'getParam\("joints", joint_names\)'),
    },
    "imu_sensor_controller/ImuSensorController": {
        "publish_rate": (*_RATE[:2], "imu_sensor_controller/src/imu_sensor_controller.cpp", _RATE[3]),
    },
    "force_torque_sensor_controller/ForceTorqueSensorController": {
        "publish_rate": (*_RATE[:2], "force_torque_sensor_controller/src/force_torque_sensor_controller.cpp",
                         _RATE[3]),
    },
    "diff_drive_controller/DiffDriveController": {
        "left_wheel": ("string_or_array", True, DDC, r'getWheelNames\(controller_nh, "left_wheel"'),
        "right_wheel": ("string_or_array", True, DDC, r'getWheelNames\(controller_nh, "right_wheel"'),
        **_own(DDC, publish_rate=("double", False, r'param\("publish_rate", publish_rate'),
               wheel_separation=("double", False, r'getParam\("wheel_separation", wheel_separation_\)'),
               wheel_radius=("double", False, r'getParam\("wheel_radius", wheel_radius_\)'),
               cmd_vel_timeout=("double", False, r'param\("cmd_vel_timeout"'),
               base_frame_id=("string", False, r'param\("base_frame_id"'),
               odom_frame_id=("string", False, r'param\("odom_frame_id"'),
               enable_odom_tf=("bool", False, r'param\("enable_odom_tf"'),
               open_loop=("bool", False, r'param\("open_loop"')),
    },
    "position_controllers/JointTrajectoryController": _TRAJECTORY,
    "pos_vel_controllers/JointTrajectoryController": _TRAJECTORY,
    "pos_vel_acc_controllers/JointTrajectoryController": _TRAJECTORY,
    "velocity_controllers/JointTrajectoryController": {**_TRAJECTORY, **_CLOSED_LOOP},
    "effort_controllers/JointTrajectoryController": {**_TRAJECTORY, **_CLOSED_LOOP},
    "position_controllers/JointPositionController": _ONE_JOINT,
    "velocity_controllers/JointVelocityController": _ONE_JOINT,
    "effort_controllers/JointEffortController": _ONE_JOINT,
    "position_controllers/JointGroupPositionController": _JOINT_GROUP,
    "velocity_controllers/JointGroupVelocityController": _JOINT_GROUP,
    "effort_controllers/JointGroupEffortController": _JOINT_GROUP,
    "effort_controllers/JointPositionController": _pid_loop("effort_controllers/src/joint_position_controller.cpp"),
    "effort_controllers/JointVelocityController": _pid_loop("effort_controllers/src/joint_velocity_controller.cpp"),
    "velocity_controllers/JointPositionController": _pid_loop("velocity_controllers/src/joint_position_controller.cpp"),
    "effort_controllers/JointGroupPositionController": _own(
        "effort_controllers/src/joint_group_position_controller.cpp",
        joints=("string_array", True, r'getParam\(param_name, joint_names_\)'),
        **{"__map_joints.pid.p": ("double", True, r'init\(ros::NodeHandle\(n, joint_name \+ "/pid"\)\)')}),
    "position_controllers/GripperActionController": _own(
        GRIPPER, joint=("string", True, r'getParam\("joint", joint_name_\)')),
    "effort_controllers/GripperActionController": {
        **_own(GRIPPER, joint=("string", True, r'getParam\("joint", joint_name_\)')),
        "gains.__map_joint.p": ("double", True, GRIPPER_ADAPTER, r'pid_->init\(joint_nh\)'),
    },
}
# A parameter read without giving up when it is missing; its reading line is all the evidence.
_GIVES_UP = re.compile(r"return false")
_CLASS = re.compile(r'<class\s+name="([^"]+)"')


def _line_of(tree, path: str, pattern: str, required: bool) -> int:
    lines = tree.read(path).splitlines()
    for number, line in enumerate(lines, 1):
        if re.search(pattern, line):
            if required and not any(_GIVES_UP.search(after) or "getStrings" in line
                                    for after in lines[number - 1:number + 8]):
                raise SystemExit(f"{path}:{number}: reads {pattern} but gives up on no "
                                 "'return false' after it: is it still required?")
            return number
    raise SystemExit(f"{tree.ref}: no line matching {pattern} in {path}: update FACTS")


def extract(tree, facts: dict | None = None) -> dict:
    """The data file's content from a tree of ros_controllers, for ``facts`` (all of FACTS)."""
    facts = FACTS if facts is None else facts
    classes = {}
    for path in tree.files():
        if path.endswith(".xml") and path.count("/") == 1 and "plugin" in path:
            classes.update({name: {} for name in _CLASS.findall(tree.read(path)) if "/" in name})
    for name, read in facts.items():
        if name not in classes:
            raise SystemExit(f"{name} is in FACTS but no plugin XML exports it")
        entry = {}
        for parameter, (kind, required, path, pattern) in read.items():
            entry[parameter] = {"type": kind, "path": path, "line": _line_of(tree, path, pattern, required)}
            if not required:
                entry[parameter]["default"] = None  # it has one (given in the source), not kept
        classes[name] = entry
    return {
        "about": ("What ROS 1's ros_controllers read, generated by "
                  "scripts/extract_ros1_controller_parameters.py: do not edit. A parameter "
                  "without 'default' is one the controller does not start without."),
        "licence": LICENCE,
        "source": {"repository": REPOSITORY, "ref": tree.ref, "commit": tree.commit},
        "classes": dict(sorted(classes.items())),
    }


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ros-controllers", type=Path, help="bare git dir of ros_controllers")
    parser.add_argument("--tree", type=Path, help="a checked-out folder instead")
    parser.add_argument("-o", "--output", type=Path, required=True)
    args = parser.parse_args(argv)
    tree = DirTree(args.tree, REF) if args.tree else GitTree(args.ros_controllers, REF)
    args.output.write_text(dump(extract(tree), expand=("classes",)), encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
