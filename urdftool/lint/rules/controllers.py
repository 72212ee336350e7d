"""U60x: controller configuration YAML (ROS 1 ros_control and ROS 2 ros2_control layouts)."""

from __future__ import annotations

from dataclasses import dataclass, field

from urdftool.description.companions import companions
from urdftool.description.documents import YamlFile, YamlList, YamlMap
from urdftool.lint.catalogue import Severity, rule
from urdftool.description.actuation import command_interfaces, interface_kind, transmission_joints, transmissions
from urdftool.errors import available

STATE_PACKAGES = ("joint_state_controller", "joint_state_broadcaster")
STATE_CLASSES = ("StateController", "StateBroadcaster")
JOINT_KEYS = ("joints", "joint", "joint_names", "left_wheel", "right_wheel", "left_wheel_names",
              "right_wheel_names")
SINGLE_INTERFACE = {
    "position_controllers": "position", "velocity_controllers": "velocity",
    "effort_controllers": "effort", "pos_vel_controllers": "position",
    "pos_vel_acc_controllers": "position", "diff_drive_controller": "velocity",
}


@dataclass
class Controller:
    """One controller of a YAML file: where its ``type`` is, its joints and their lines."""

    file: YamlFile
    name: str
    type: str
    line: int
    joints: list = field(default_factory=list)  # (name, line)
    settings: dict = field(default_factory=dict)

    @property
    def package(self) -> str:
        return self.type.split("/")[0]

    @property
    def is_state(self) -> bool:
        return self.package in STATE_PACKAGES or self.type.endswith(STATE_CLASSES)

    def interfaces(self) -> list[str] | None:
        """Command interfaces it claims on each joint, or None when the type is not known."""
        if self.package in SINGLE_INTERFACE:
            return [SINGLE_INTERFACE[self.package]]
        if self.package == "joint_trajectory_controller":
            claimed = self.settings.get("command_interfaces")
            return [str(c) for c in claimed] if isinstance(claimed, list) else None
        if self.package == "forward_command_controller":
            claimed = self.settings.get("interface_name")
            return [claimed] if isinstance(claimed, str) else None
        return None


def controllers(robot) -> list[Controller]:
    """Every controller in the robot's controller YAML files (parsed once per robot)."""
    return robot.memo(controllers, lambda: [c for f in companions(robot).controllers
                                            if f.problem is None for c in _file_controllers(f)])


def _file_controllers(file: YamlFile) -> list[Controller]:
    declared, parameters = [], {}
    seen: set[int] = set()

    def walk(node):
        if not isinstance(node, dict) or id(node) in seen:
            return
        seen.add(id(node))
        for key, value in node.items():
            if not isinstance(value, dict):
                continue
            kind = value.get("type")
            if isinstance(kind, str) and "/" in kind:
                declared.append((str(key), value, node.lines.get(key, node.line)))
            if isinstance(value.get("ros__parameters"), dict):
                parameters[str(key).split("/")[-1]] = value["ros__parameters"]
            walk(value)

    if isinstance(file.data, dict) and isinstance(file.data.get("type"), str) and "/" in file.data["type"]:
        declared.append((file.path.name.split(".")[0], file.data, file.data.lines["type"]))
    walk(file.data)
    found = _moveit_controllers(file)
    for name, declaration, line in declared:
        settings = {**declaration, **parameters.get(name, {})}
        source = parameters.get(name, declaration)
        controller = Controller(file, name, declaration["type"], line, settings=settings)
        for key in JOINT_KEYS:
            holder = source if key in source else declaration
            controller.joints.extend(_names_at(holder, key))
        found.append(controller)
    return found


def _moveit_controllers(file: YamlFile) -> list[Controller]:
    """MoveIt's ``controller_list`` (moveit_config/config/ros_controllers.yaml): names and joints."""
    listed = file.data.get("controller_list") if isinstance(file.data, dict) else None
    if not isinstance(listed, YamlList):
        return []
    found = []
    for entry, line in zip(listed, listed.lines):
        if isinstance(entry, YamlMap) and "joints" in entry:
            controller = Controller(file, str(entry.get("name", "?")),
                                    f"moveit/{entry.get('type', '?')}", line)
            controller.joints = _names_at(entry, "joints")
            found.append(controller)
    return found


def _names_at(mapping, key) -> list[tuple[str, int]]:
    value = mapping.get(key) if isinstance(mapping, dict) else None
    line = mapping.lines.get(key, mapping.line) if isinstance(mapping, YamlMap) else None
    if isinstance(value, str):
        return [(value, line)]
    if isinstance(value, YamlList):
        return [(str(item), at) for item, at in zip(value, value.lines) if isinstance(item, str)]
    return []


def _substituted(name: str) -> bool:
    """A roslaunch substitution (``$(arg arm_id)_joint1``) is resolved at launch: not checkable."""
    return "$(" in name


def _label(controller: Controller) -> str:
    return f"controller '{controller.name}' ({controller.type})"


@rule("U601", "malformed-controllers-yaml", Severity.ERROR)
def malformed_controllers_yaml(robot):
    """A controller configuration file is not valid YAML, or names no controller.

    The controller manager cannot load its parameters, so no controller starts. Files given
    with ``--controllers`` must hold at least one controller (a mapping with
    ``type: package/Class``) or a ``controller_manager`` section.

    Bad: ``joints: [head_pan, head_tilt`` (unclosed list)
    Good: ``joints: [head_pan, head_tilt]``
    """
    explicit = bool(robot.companion_paths.controllers)
    for file in companions(robot).controllers:
        if file.problem:
            yield file.at(file.line), file.problem
        elif explicit and not _file_controllers(file) and not (
                isinstance(file.data, dict) and "controller_manager" in file.data):
            yield file.at(1), (f"{file.display} names no controller (a mapping with "
                               "'type: package/Class', e.g. joint_state_broadcaster/JointStateBroadcaster)")


@rule("U602", "controller-unknown-joint", Severity.ERROR)
def controller_unknown_joint(robot):
    """A controller names a joint that is not in the URDF.

    The controller fails to configure ("Could not find resource 'X'").

    Bad: ``joints: [head_jont]``
    Good: ``joints: [head_joint]``
    """
    for controller in controllers(robot):
        for name, line in controller.joints:
            if name not in robot.joints and not _substituted(name):
                yield controller.file.at(line), (
                    f"{_label(controller)} names joint '{name}', which is not in the URDF; "
                    f"{available('joints', name, robot.joints)}")


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
        for name, line in controller.joints:
            joint = robot.joints.get(name)
            if joint is None or name in offered:
                continue
            what = ("is a fixed joint; remove it from the controller" if joint.get("type") == "fixed"
                    else "has no transmission or ros2_control joint; add one for it, or remove "
                         "it from the controller")
            yield controller.file.at(line), f"{_label(controller)}: joint '{name}' {what}"


@rule("U604", "controller-interface-mismatch", Severity.ERROR)
def controller_interface_mismatch(robot):
    """A controller commands an interface the joint's transmission or ros2_control does not offer.

    position_controllers/* need a PositionJointInterface (or a ``position`` command interface),
    velocity_controllers/* a velocity one, effort_controllers/* an effort one;
    joint_trajectory_controller uses its ``command_interfaces``.

    Bad: ``position_controllers/JointTrajectoryController`` on a joint with
    ``hardware_interface/VelocityJointInterface``
    Good: ``velocity_controllers/JointTrajectoryController`` on that joint, or
    ``hardware_interface/PositionJointInterface`` in its transmission
    """
    offered = command_interfaces(robot)
    unknown = {joint.name for t in transmissions(robot) for joint in transmission_joints(t)
               if any(not interface_kind(i.text)[0] for i in joint.interfaces)}  # U503
    for controller in controllers(robot):
        claimed = controller.interfaces()
        if not claimed or controller.is_state:
            continue
        for name, line in controller.joints:
            if name not in offered or name not in robot.joints or name in unknown:
                continue
            missing = [c for c in claimed if c not in offered[name]]
            if missing:
                has = ", ".join(sorted(offered[name])) or "no command interface (read-only)"
                yield controller.file.at(line), (
                    f"{_label(controller)} commands {'/'.join(missing)} on joint '{name}', which "
                    f"offers {has}; {_interface_fix(controller, offered[name], missing)}")


# Controller classes that position_, velocity_ and effort_controllers all provide (ROS 1).
_IN_EVERY_PACKAGE = ("JointPositionController", "JointTrajectoryController")


def _interface_fix(controller: Controller, offered: set, missing: list[str]) -> str:
    """What would be right: a controller for what the joint offers, or the joint offering more."""
    kinds = sorted(offered & {"position", "velocity", "effort"})
    if controller.package == "joint_trajectory_controller" and kinds:
        use = f"set command_interfaces to [{', '.join(kinds)}]"
    elif controller.package == "forward_command_controller" and kinds:
        use = f"set interface_name to {kinds[0]}"
    elif controller.package in SINGLE_INTERFACE and kinds:
        kind_class = controller.type.split("/")[-1]
        shown = kind_class if kind_class in _IN_EVERY_PACKAGE else "..."
        use = "use " + " or ".join(f"{kind}_controllers/{shown}" for kind in kinds)
    else:
        use = "change the controller"
    wanted = missing[0]
    return (f"{use}, or make the joint offer {wanted} ({wanted.capitalize()}JointInterface in its "
            f"transmission, or a {wanted} command interface in <ros2_control>)")


@rule("U605", "no-joint-state-controller", Severity.WARNING)
def no_joint_state_controller(robot):
    """The controller configuration has no joint state broadcaster or controller.

    Without joint_state_broadcaster (ROS 2) or joint_state_controller (ROS 1) nothing publishes
    /joint_states, so robot_state_publisher and RViz show the robot frozen.

    Bad: only ``head_controller`` in the YAML
    Good: add ``joint_state_broadcaster: {type: joint_state_broadcaster/JointStateBroadcaster}``
    """
    found = [c for c in controllers(robot) if c.package != "moveit"]
    if found and not any(c.is_state for c in found):
        first = found[0]
        yield first.file.at(first.line), (
            f"no joint state broadcaster/controller among {len(found)} controllers in "
            f"{', '.join(sorted({c.file.display for c in found}))}; add joint_state_broadcaster/"
            "JointStateBroadcaster (ROS 2) or joint_state_controller/JointStateController (ROS 1)")
