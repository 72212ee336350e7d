"""U517-U520: ``<ros2_control>`` interfaces, their numbers, and the simulator plugin that loads the
hardware."""

from __future__ import annotations

from urdftool.description import gazebo_plugins as vocabulary
from urdftool.description.actuation import (CONFIGURATIONS, LATER, gazebo_plugins,
                                            hardware_plugin, interface_params, param_readers, ros2_control_double,
                                            ros2_control_joints)
from urdftool.description.values import SPACE, strtod_double
from urdftool.errors import BARE_EXPRESSION, bare_substitution, shown_word
from urdftool.lint.catalogue import Conditional, Severity, rule


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


READ_PARAMS = ("min", "max", "initial_value")


@rule("U520", "ros2-control-param-not-a-number", Severity.ERROR)
def ros2_control_param_not_a_number(robot):
    """A ros2_control interface's ``min``, ``max`` or ``initial_value`` is not a number its readers parse.

    ros2_control parses these with its own hardware_interface::stod: one finite decimal number
    and nothing else (no ``inf``, ``nan``, hexadecimal, unit or comment). Jazzy and later strip
    white space around the text first; Humble reads it as written, white space after the number
    refused. A ``min`` or ``max`` of a position,
    velocity, effort, acceleration or jerk command interface it cannot parse makes ros2_control
    (4.10.0 and later: Jazzy, Kilted, Rolling) print "Error parsing the limits ... Skipping
    it" and drop both bounds of the interface, the URDF's ``<limit>`` holding alone; an
    ``initial_value`` throws as the hardware starts: mock_components' GenericSystem (a state
    interface's; a command interface's too from Jazzy) and the Gazebo hardware (a position,
    velocity or effort state interface's: Gazebo then starts no controllers; Humble's Gazebo
    Classic and Ignition plugins read it with std::stod, which takes ``1.5rad`` as 1.5), and
    from Jazzy any hardware that exports its interfaces ros2_control's default way.

    An error when every configuration the hardware runs in refuses the value (the hardware
    plugin's: fake_components and Gazebo Classic end with Humble, gz_ros2_control's
    GazeboSimSystem starts with Jazzy); a warning naming the configurations when only some
    read it (Humble reads no ``min``/``max``; a vendor's hardware may not read
    ``initial_value``); a note when none reads it. Interfaces of another ``data_type`` than
    double are not judged; of ``<param>``s of one name, the last is, as ros2_control keeps it.

    Bad: ``<param name="min">{-2*pi}</param>`` (xacro leaves ``{...}`` without ``$`` as written)
    Good: ``<param name="min">${-2*pi}</param>``
    """
    for block, joint in ros2_control_joints(robot):
        for interface in (*joint.findall("command_interface"), *joint.findall("state_interface")):
            params = interface_params(interface)
            for name in READ_PARAMS:
                param = params.get(name)
                text = param.text if param is not None else None
                if text and text.strip(SPACE):  # (an empty one is unset, to ros2_control too)
                    message = _refused(block, joint, interface, name, text)
                    if message is not None:
                        yield param, message


def _refused(block, joint, interface, name: str, text: str):
    """U520's message for ``<param name=NAME>TEXT`` of ``interface``, or None when every
    configuration that reads it reads a number."""
    readers = param_readers(block, joint, interface, name)
    if not readers:  # (another data type than double: not judged)
        return None
    refusing: dict = {}  # (who, consequence, certain) -> configurations where it refuses
    read_as: dict = {}  # configuration -> the value its readers read
    for configuration, ones in readers.items():
        for reader in ones:
            value = reader.parse(configuration, text)
            if value is None:
                refusing.setdefault((reader.who, reader.consequence, reader.certain), []).append(configuration)
            else:
                read_as.setdefault(configuration, value)
    junk = all(ros2_control_double(c, text) is None for c in CONFIGURATIONS) and strtod_double(text) is None
    said = (f"ros2_control joint '{joint.get('name')}' {interface.tag} '{interface.get('name')}': "
            f"{name} '{shown_word(ascii(text)[1:-1] if not text.isprintable() else text)}' is not a number")
    hint = bare_substitution(text, BARE_EXPRESSION)
    hint = f"; {hint}" if hint else ""
    if not refusing:
        if not junk or read_as:
            return None
        plugin = hardware_plugin(block)
        return Conditional(f"{said}, though nothing reads it where hardware '{plugin}' runs "
                           f"({_where(readers)}); a driver or a later ROS reading it would refuse it{hint}",
                           Severity.INFO)
    whom = "; ".join(f"{who}{'' if set(where) == _reading(readers, who) else f' ({_where(where)})'} "
                     f"{'' if certain else 'if the hardware exports its interfaces from the URDF (the default), '}"
                     f"{consequence}" for (who, consequence, certain), where in refusing.items())
    certain = all(any(c in where for (_, _, sure), where in refusing.items() if sure) for c in readers)
    if certain:
        return f"{said}: {whom}{hint}"
    rest = [f"{_where(c for c, v in read_as.items() if v == value)} read it as {value:g}"
            for value in sorted(set(read_as.values()))]
    unread = [c for c, ones in readers.items() if not ones]
    if unread:
        rest.append(f"nothing reads it in {_where(unread)}")
    tail = f" ({'; '.join(rest)})" if rest else ""
    return Conditional(f"{said}: {whom}{tail}{hint}")


def _reading(readers: dict, who: str) -> set:
    """The configurations in which the reader ``who`` reads the param."""
    return {c for c, ones in readers.items() if any(r.who == who for r in ones)}


def _where(configurations) -> str:
    """Configurations as a message names them: 'Jazzy and later' for both its builds."""
    chosen = list(configurations)
    if set(LATER) <= set(chosen):
        chosen = [c for c in chosen if c not in LATER] + ["Jazzy and later"]
    return " and ".join(chosen) or "none"
