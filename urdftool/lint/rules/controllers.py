"""U60x: controller configuration YAML (ROS 1 ros_control and ROS 2 ros2_control layouts)."""

from __future__ import annotations


from urdftool.description.actuation import (command_interfaces, interface_kind, ros2_command_interfaces,
                                            transmission_joints, transmissions)
from urdftool.description.companions import companions
from urdftool.description.controller_classes import classes, lookup
from urdftool.description.controllers import Controller, JointRef, controller_files, controllers
from urdftool.errors import available
from urdftool.lint.catalogue import Severity, rule


def _substituted(name: str) -> bool:
    """A roslaunch substitution (``$(arg arm_id)_joint1``) is resolved at launch: not checkable."""
    return "$(" in name


def _label(controller: Controller) -> str:
    return f"controller '{controller.name}' ({controller.type or 'no type'})"


def _urdf_joints(robot, controller: Controller) -> list[JointRef]:
    """The names a controller holds that are meant as URDF joints: all of them for a known
    class; for a class nothing is known about (a vendor's), only when some of them are URDF
    joints (its ``joint: tcp`` may be a hardware interface prefix, not a joint)."""
    refs = [ref for ref in controller.joints() if not _substituted(ref.name)]
    if controller.known or any(ref.name in robot.joints for ref in refs):
        return refs
    return []


@rule("U601", "malformed-controllers-yaml", Severity.ERROR)
def malformed_controllers_yaml(robot):
    """A controller configuration file is not valid YAML, or names no controller.

    The controller manager cannot load its parameters, so no controller starts. Files given
    with ``--controllers`` must hold at least one controller (a mapping with
    ``type: package/Class``), a ``controller_manager`` section, or MoveIt's
    ``controller_list``/``controller_names``; a name MoveIt's ``controller_names`` lists needs
    its own mapping (``type``, ``action_ns``, ``joints``) beside the list.

    Bad: ``joints: [head_pan, head_tilt`` (unclosed list)
    Good: ``joints: [head_pan, head_tilt]``
    """
    explicit = bool(robot.companion_paths.controllers)
    for file in companions(robot).controllers:
        if file.problem:
            yield file.at(file.line), file.problem
    for read in controller_files(robot):
        file = read.file
        for controller in read.controllers:
            if controller.layout == "moveit" and controller.params is None:
                yield file.at(controller.line), (
                    f"MoveIt's controller_names lists '{controller.name}', but there is no "
                    f"'{controller.name}:' mapping beside the list (with type, action_ns and joints)")
        if explicit and not read.controllers and not _has_manager(read):
            yield file.at(1), (f"{file.display} names no controller (a mapping with "
                               "'type: package/Class', e.g. joint_state_broadcaster/JointStateBroadcaster)")


def _has_manager(read) -> bool:
    return (isinstance(read.file.data, dict) and "controller_manager" in read.file.data) or any(
        block.name == "controller_manager" for block in read.blocks)


@rule("U602", "controller-unknown-joint", Severity.ERROR)
def controller_unknown_joint(robot):
    """A controller names a joint that is not in the URDF.

    The controller fails to configure ("Could not find resource 'X'"). Joints are read from the
    parameters the controller's class reads (``joints``, ``joint``, ``left_wheel_names``, ...; see
    the class table). A class nothing is known about (a vendor's) is checked only when some of
    its ``joint``/``joints``/``joint_names`` are URDF joints: its ``joint: tcp`` may name a
    hardware interface prefix, not a joint.

    Bad: ``joints: [head_jont]``
    Good: ``joints: [head_joint]``
    """
    for controller in controllers(robot):
        for ref in _urdf_joints(robot, controller):
            if ref.name not in robot.joints:
                yield controller.file.at(ref.line), (
                    f"{_label(controller)} names joint '{ref.name}', which is not in the URDF; "
                    f"{available('joints', ref.name, robot.joints)}")


@rule("U603", "controller-joint-not-actuated", Severity.ERROR)
def controller_joint_not_actuated(robot):
    """A controller commands a joint that has no transmission or ros2_control entry.

    The hardware offers no interface for the joint, so the controller cannot claim it.
    Checked when the URDF describes its actuation (has a transmission or ``<ros2_control>``).

    Bad: ``joints: [camera_joint]`` (fixed), or a joint without a transmission
    Good: a transmission or ros2_control ``<joint>`` for every commanded joint
    """
    if not transmissions(robot) and not robot.children("ros2_control"):
        return
    offered = command_interfaces(robot)
    for controller in controllers(robot):
        if controller.is_state:
            continue
        for ref in _urdf_joints(robot, controller):
            joint = robot.joints.get(ref.name)
            if joint is None or ref.name in offered:
                continue
            what = ("is a fixed joint; remove it from the controller" if joint.get("type") == "fixed"
                    else "has no transmission or ros2_control joint; add one for it, or remove "
                         "it from the controller")
            yield controller.file.at(ref.line), f"{_label(controller)}: joint '{ref.name}' {what}"


@rule("U604", "controller-interface-mismatch", Severity.ERROR)
def controller_interface_mismatch(robot):
    """A controller commands an interface the joint's transmission or ros2_control does not offer.

    position_controllers/* need a PositionJointInterface (or a ``position`` command interface),
    velocity_controllers/* a velocity one, effort_controllers/* an effort one;
    joint_trajectory_controller uses its ``command_interfaces``, forward_command_controller its
    ``interface_name``, diff_drive_controller velocity on its wheels. A ROS 2 controller gets
    only what the joint's ``<ros2_control>`` entry offers (ros2_control does not read
    transmissions outside ``<ros2_control>``).

    Bad: ``position_controllers/JointTrajectoryController`` on a joint with
    ``hardware_interface/VelocityJointInterface``
    Good: ``velocity_controllers/JointTrajectoryController`` on that joint, or
    ``hardware_interface/PositionJointInterface`` in its transmission
    """
    offered = command_interfaces(robot)
    ros2 = ros2_command_interfaces(robot)
    unknown = {joint.name for t in transmissions(robot) for joint in transmission_joints(t)
               if any(not interface_kind(i.text)[0] for i in joint.interfaces)}  # U503
    for controller in controllers(robot):
        claimed = controller.interfaces()
        if not claimed or controller.is_state:
            continue
        for ref in _urdf_joints(robot, controller):
            name = ref.name
            if controller.ros == 2 and name in ros2:
                has_set = ros2[name]
            elif name in offered and name not in unknown:
                has_set = offered[name]
            else:
                continue
            if name not in robot.joints:
                continue
            missing = [c for c in claimed if c not in has_set]
            if missing:
                has = ", ".join(sorted(has_set)) or "no command interface (read-only)"
                yield controller.file.at(ref.line), (
                    f"{_label(controller)} commands {'/'.join(missing)} on joint '{name}', which "
                    f"offers {has}; {_interface_fix(controller, has_set, missing)}")


def _interface_fix(controller: Controller, offered: set, missing: list[str]) -> str:
    """What would be right: a controller for what the joint offers, or the joint offering more."""
    kinds = sorted(offered & {"position", "velocity", "effort"})
    known = controller.cls
    wanted = missing[0]
    param = known.commands[1:] if known and known.commands and known.commands.startswith("@") else None
    if param and kinds:
        use = (f"set {param} to [{', '.join(kinds)}]" if param.endswith("s")
               else f"set {param} to {kinds[0]}")
    elif known and kinds and _alternatives(controller, kinds):
        use = "use " + " or ".join(_alternatives(controller, kinds))
    elif known and known.package == "diff_drive_controller":
        use = "drive the wheels through velocity"
    else:
        use = "change the controller"
    if controller.ros == 2:
        offer = f"a {wanted} command interface in its <ros2_control> joint"
    else:
        offer = (f"{wanted.capitalize()}JointInterface in its transmission, or a {wanted} command "
                 "interface in <ros2_control>")
    return f"{use}, or make the joint offer {wanted} ({offer})"


def _alternatives(controller: Controller, kinds: list[str]) -> list[str]:
    """Classes of the controller's ROS version doing the same job through ``kinds``:
    ``velocity_controllers/JointTrajectoryController`` for ROS 1's position one,
    ``velocity_controllers/JointGroupVelocityController`` for ROS 2's JointGroupPositionController."""
    table = classes(controller.ros)
    claimed = controller.cls.commands or ""
    shown = controller.type.split("/")[-1]
    found = []
    for kind in kinds:
        for name in (f"{kind}_controllers/{shown}",
                     f"{kind}_controllers/{shown.replace(claimed.capitalize(), kind.capitalize())}"):
            if name in table and table[name].commands == kind and name not in found:
                found.append(name)
                break
    return found


@rule("U605", "no-joint-state-controller", Severity.WARNING)
def no_joint_state_controller(robot):
    """The controller configuration has no joint state broadcaster or controller.

    Without joint_state_broadcaster (ROS 2) or joint_state_controller (ROS 1) nothing publishes
    /joint_states, so robot_state_publisher and RViz show the robot frozen. MoveIt's controller
    lists are not counted: MoveIt does not publish joint states.

    Bad: only ``head_controller`` in the YAML
    Good: add ``joint_state_broadcaster: {type: joint_state_broadcaster/JointStateBroadcaster}``
    """
    found = [c for c in controllers(robot) if c.layout != "moveit"]
    if found and not any(c.is_state for c in found):
        first = found[0]
        yield first.file.at(first.line), (
            f"no joint state broadcaster/controller among {len(found)} controllers in "
            f"{', '.join(sorted({c.file.display for c in found}))}; add joint_state_broadcaster/"
            "JointStateBroadcaster (ROS 2) or joint_state_controller/JointStateController (ROS 1)")
