"""U517-U519: ``<ros2_control>`` interfaces and the simulator plugin that loads the hardware."""

from __future__ import annotations

from urdftool.description import gazebo_plugins as vocabulary
from urdftool.description.actuation import gazebo_plugins, ros2_control_joints
from urdftool.lint.catalogue import Severity, rule


@rule("U517", "ros2-control-no-state-interface", Severity.WARNING)
def ros2_control_no_state_interface(robot):
    """A ``<ros2_control>`` joint has command interfaces and no state interface.

    joint_state_broadcaster publishes the state interfaces of the joints: a joint with none
    is missing from /joint_states, so robot_state_publisher cannot place the links below it
    (RViz shows them at the origin, TF has no transform), and a controller that reads its
    position (joint_trajectory_controller) cannot be configured on it. A warning: hardware may
    report the joint some other way.

    A state interface of the joint in another ``<ros2_control>`` block counts: a sensor
    component reporting an actuator's position (ros2_control_demos example 14) is the joint's
    state as joint_state_broadcaster reads it. A joint the URDF makes a ``<mimic>`` of a joint
    with a state interface is not reported: robot_state_publisher places it from that joint's
    state (a gripper's second finger, driven by gazebo_ros2_control's ``mimic`` parameter).

    Bad: ``<joint name="head_joint"><command_interface name="position"/></joint>``
    Good: ``<command_interface name="position"/><state_interface name="position"/>``
    """
    joints = ros2_control_joints(robot)
    reported = {joint.get("name") for _, joint in joints if joint.find("state_interface") is not None}
    for block, joint in joints:
        if joint.find("command_interface") is not None and joint.get("name") not in reported \
                and _mimicked(robot, joint.get("name")) not in reported:
            commands = ", ".join(c.get("name", "?") for c in joint.findall("command_interface"))
            yield joint, (f"ros2_control joint '{joint.get('name')}' in '{block.get('name')}' has command "
                          f"interface(s) {commands} and no state interface: joint_state_broadcaster "
                          "publishes nothing for it, so TF cannot place the links below it; add "
                          "<state_interface name=\"position\"/>")


def _mimicked(robot, name) -> str | None:
    """The joint the URDF joint ``name`` mimics (its ``<mimic joint>``), or None."""
    joint = robot.joints.get(name)
    mimic = joint.find("mimic") if joint is not None else None
    return mimic.get("joint") if mimic is not None else None


def _hardware(robot) -> list:
    """(<plugin> element of <ros2_control><hardware>, its class) of every <ros2_control>."""
    return [(element, (element.text or "").strip()) for block in robot.children("ros2_control")
            for element in block.iterfind("hardware/plugin")]


def _simulated(robot) -> list:
    """The hardware plugins of the robot that a Gazebo plugin loads (GazeboSystem, ...)."""
    simulators = {h for loaded in vocabulary.control_plugins().values() for h in loaded}
    return [(element, name) for element, name in _hardware(robot) if name in simulators]


def _loaders(robot) -> list:
    """(<plugin> element, Plugin) of the Gazebo plugins that load ros2_control hardware."""
    found = []
    for element in gazebo_plugins(robot):
        plugin = vocabulary.plugin(element)
        if plugin is not None and plugin.hardware:
            found.append((element, plugin))
    return found


@rule("U518", "ros2-control-simulator-mismatch", Severity.ERROR)
def ros2_control_simulator_mismatch(robot):
    """The ``<ros2_control>`` hardware is another simulator's than the Gazebo plugin that loads it.

    Gazebo Classic's gazebo_ros2_control (``libgazebo_ros2_control.so``) loads
    ``gazebo_ros2_control/GazeboSystem``; the new Gazebo's gz_ros2_control
    (``gz_ros2_control-system``) loads ``gz_ros2_control/GazeboSimSystem`` (and, from Jazzy,
    ``ign_ros2_control/IgnitionSystem``); Humble's ign_ros2_control
    (``ign_ros2_control-system``) loads ``ign_ros2_control/IgnitionSystem``. Any other pair
    fails to load the hardware ("According to the loaded plugin descriptions the class ... does
    not exist") and no controller starts. What each plugin loads is read from its plugin XML.

    Bad: ``<plugin>gazebo_ros2_control/GazeboSystem</plugin>`` with
    ``<plugin filename="libgz_ros2_control-system.so">``
    Good: ``<plugin>gz_ros2_control/GazeboSimSystem</plugin>`` with it
    """
    loaders = _loaders(robot)
    if not loaders:
        return
    for element, name in _simulated(robot):
        if any(name in plugin.hardware for _, plugin in loaders):
            continue
        shown = ", ".join(f"{e.get('filename')} (loads {' or '.join(p.hardware)})" for e, p in loaders)
        yield element, (f"hardware plugin '{name}' is not one the robot's Gazebo control plugin loads: "
                        f"{shown}; use the hardware of the simulator the robot runs in")


@rule("U519", "ros2-control-no-simulator-plugin", Severity.WARNING)
def ros2_control_no_simulator_plugin(robot):
    """A ``<ros2_control>`` block's hardware is a simulator's, and no Gazebo plugin loads it.

    ``gazebo_ros2_control/GazeboSystem``, ``gz_ros2_control/GazeboSimSystem`` and
    ``ign_ros2_control/IgnitionSystem`` run only inside Gazebo, started by the Gazebo plugin
    (``libgazebo_ros2_control.so``, ``gz_ros2_control-system``) with the controllers'
    parameter file: without the plugin neither the hardware nor the controllers are ever
    loaded. A warning: the plugin may be added by a file that includes this one.

    Bad: ``<ros2_control>`` with ``gazebo_ros2_control/GazeboSystem`` and no ``<gazebo>`` plugin
    Good: ``<gazebo><plugin filename="libgazebo_ros2_control.so" name="gazebo_ros2_control">
    <parameters>$(find my_robot)/config/controllers.yaml</parameters></plugin></gazebo>``
    """
    if _loaders(robot) or any((e.get("filename") or "").strip().endswith("libgazebo_ros_control.so")
                              for e in gazebo_plugins(robot)):
        return  # ROS 1's gazebo_ros_control in a ROS 2 robot: U618 names the plugin to use
    loaded_by: dict[str, list] = {}
    for key, loaded in vocabulary.control_plugins().items():
        for hardware in loaded:
            loaded_by.setdefault(hardware, []).append(key)
    for element, name in _simulated(robot):
        yield element, (f"hardware plugin '{name}' runs inside Gazebo, loaded by the "
                        f"{' or '.join(loaded_by[name])} plugin, and the robot has no such "
                        "<gazebo><plugin>: its hardware and "
                        "controllers are never loaded in simulation")
