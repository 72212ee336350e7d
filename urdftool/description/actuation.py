"""How a robot's joints are actuated: transmissions (ROS 1 and ROS 2 forms) and ros2_control."""

from __future__ import annotations


from urdftool.description import values
from urdftool.description.urdf import MOVING
from urdftool.description.xml import children_named, first_child
from urdftool.records import NEW, Record

# ROS 1 hardware interfaces (without the hardware_interface/ prefix) -> command interface, or
# None for the read-only ones.
HARDWARE_INTERFACES = {
    "PositionJointInterface": "position",
    "VelocityJointInterface": "velocity",
    "EffortJointInterface": "effort",
    "PosVelJointInterface": "position",
    "PosVelAccJointInterface": "position",
    "JointStateInterface": None,
    "PositionActuatorInterface": "position",
    "VelocityActuatorInterface": "velocity",
    "EffortActuatorInterface": "effort",
    "ActuatorStateInterface": None,
}
PREFIXES = ("hardware_interface/", "hardware_interface::")
CONTROL_PLUGINS = ("gazebo_ros_control", "gazebo_ros2_control", "gz_ros2_control",
                   "ign_ros2_control")


def interface_kind(text: str | None):
    """(known, command interface or None) for a ``<hardwareInterface>`` text.

    Vendor interfaces written ``package/Name`` outside hardware_interface (franka_hw/...) are
    accepted as known and read-only.
    """
    if not text:
        return False, None
    name = text.strip()
    for prefix in PREFIXES:
        if name.startswith(prefix):
            name = name[len(prefix):]
            return name in HARDWARE_INTERFACES, HARDWARE_INTERFACES.get(name)
    if name in HARDWARE_INTERFACES:
        return True, HARDWARE_INTERFACES[name]
    if "/" in name and not name.startswith("/"):
        return True, None
    return False, None


class TransmissionJoint(Record):
    """A joint a transmission names, with the hardware interfaces it gives it."""

    element: object          # the <joint> inside the transmission
    name: str | None
    interfaces: list   # <hardwareInterface> elements
    in_actuator: bool  # the interfaces are the first actuator's: the joint names none

    __slots__ = ("element", "name", "interfaces", "in_actuator")

    def __init__(self, element: object, name: str | None, interfaces: list = NEW,
                 in_actuator: bool = False) -> None:
        self.element = element
        self.name = name
        self.interfaces = [] if interfaces is NEW else interfaces
        self.in_actuator = in_actuator


def transmissions(robot) -> list:
    """Every ``<transmission>``: top-level (ROS 1) or inside ``<ros2_control>`` (ROS 2)."""
    found = list(robot.children("transmission"))
    for block in robot.children("ros2_control"):
        found.extend(block.findall("transmission"))
    return found


def transmission_joints(robot, transmission) -> tuple[TransmissionJoint, ...]:
    """The joints of a transmission of ``robot``; an old-style ``<hardwareInterface>`` beside
    the joint too. A joint that names none takes its transmission's first actuator's, as
    gazebo_ros_control and gazebo_ros2_control read them (with a deprecation warning: "should
    be nested inside the <joint> element, not <actuator>"; ``in_actuator`` says so).

    PR2 transmissions name joints as ``<flexJoint>``, ``<rollJoint>``, ``<gap_joint>`` too.
    Read once per robot and transmission, for the callers to read, not change (eight rules
    and loaders ask of each: 1,878 reads of the corpus's 248 transmissions).
    """
    return robot.memo_for(transmission_joints, transmission,
                          lambda: tuple(_transmission_joints(transmission)))


def _transmission_joints(transmission) -> list[TransmissionJoint]:
    shared = children_named(transmission, "hardwareInterface")
    actuator = next((child for child in transmission if child.tag == "actuator"), None)
    held = children_named(actuator, "hardwareInterface") if actuator is not None else []
    found = []
    for joint in transmission:
        if _is_joint(joint):
            own = children_named(joint, "hardwareInterface") or shared
            found.append(TransmissionJoint(joint, joint.get("name"), own or held,
                                           not own and bool(held)))
    return found


def _is_joint(element) -> bool:
    tag = element.tag
    return isinstance(tag, str) and (tag == "joint" or (
        tag.endswith(("Joint", "_joint")) and element.get("name") is not None))


def is_ros2_form(transmission) -> bool:
    return transmission.getparent() is not None and transmission.getparent().tag == "ros2_control"


def ros2_control_joints(robot) -> list:
    """(block, joint element) for every ``<joint>`` of every ``<ros2_control>``."""
    return [(block, joint) for block in robot.children("ros2_control")
            for joint in block.findall("joint")]


def command_interfaces(robot) -> dict[str, set]:
    """Joint name -> command interfaces it offers (position, velocity, effort, ...).

    A joint present here with an empty set is actuated read-only (a state interface only).
    """
    offered: dict[str, set] = {}
    for transmission in transmissions(robot):
        for joint in transmission_joints(robot, transmission):
            if joint.name is None:
                continue
            kinds = offered.setdefault(joint.name, set())
            for interface in joint.interfaces:
                _, kind = interface_kind(interface.text)
                if kind:
                    kinds.add(kind)
    for name, kinds in ros2_command_interfaces(robot).items():
        offered.setdefault(name, set()).update(kinds)
    return offered


# Command interfaces a hardware plugin reads under a name of its own and exports under a standard
# one: gazebo_ros2_control's GazeboSystem drives position_pid and velocity_pid through a PID and
# exports them as position and velocity (gazebo_system.cpp), which controllers claim.
PLUGIN_INTERFACES = {"gazebo_ros2_control/GazeboSystem": {"position_pid": "position",
                                                         "velocity_pid": "velocity"}}


def exported_interface(robot, block, name: str) -> str:
    """The name under which the hardware plugin of ``<ros2_control>`` ``block`` exports the
    command interface ``name`` (:data:`PLUGIN_INTERFACES`; else ``name``). Each block's plugin
    is looked up once per robot: a block of 20,000 joints looked for it among its children for
    each interface (quadratic: over the 60 s budget)."""
    exports = robot.memo(exported_interface, dict)  # block -> its plugin's renames
    renamed = exports.get(block)
    if renamed is None:
        renamed = exports[block] = PLUGIN_INTERFACES.get(
            hardware_plugin(block), {})
    return renamed.get(name, name)


def ros2_command_interfaces(robot) -> dict[str, set]:
    """Joint name -> command interfaces its ``<ros2_control>`` entries offer, as their hardware
    plugins export them: all a ROS 2 controller can claim (ros2_control reads no transmission
    outside ``<ros2_control>``)."""
    offered: dict[str, set] = {}
    for block, joint in ros2_control_joints(robot):
        offered.setdefault(joint.get("name"), set()).update(
            exported_interface(robot, block, c.get("name"))
            for c in joint.findall("command_interface") if c.get("name"))
    return offered


def ros2_state_interfaces(robot) -> dict[str, set]:
    """Joint name -> state interfaces its ``<ros2_control>`` entries offer."""
    offered: dict[str, set] = {}
    for _, joint in ros2_control_joints(robot):
        offered.setdefault(joint.get("name"), set()).update(
            c.get("name") for c in joint.findall("state_interface") if c.get("name"))
    return offered


# --- the numbers of a ros2_control interface's <param>s, as their consumers read them ---------
# (ros2_control's hardware_interface/src/component_parser.cpp, handle.hpp, the mock and Gazebo
# hardware; as each distribution's current release reads them.) A configuration: ros2_control
# of Humble (2.x), which reads a param's text as written, or of Jazzy and later (4.x and on),
# which strips its white space (4.43.0, 5.12.0, 6.4.0) and is built as C++17 or as C++20
# (values.stream_double or values.from_chars_double).
HUMBLE, LATER_CXX17, LATER_CXX20 = "Humble", "Jazzy and later, C++17 build", "Jazzy and later, C++20 build"
CONFIGURATIONS = (HUMBLE, LATER_CXX17, LATER_CXX20)
LATER = (LATER_CXX17, LATER_CXX20)
# The ros-controls hardware that runs in some configurations only (Gazebo Classic and the
# fake_components alias end with Humble; gz_ros2_control's GazeboSimSystem starts with Jazzy;
# Jazzy's gz_ros2_control loads ign_ros2_control/IgnitionSystem too). Any other runs in all.
HARDWARE_CONFIGURATIONS = {"fake_components/GenericSystem": (HUMBLE,),
                           "gazebo_ros2_control/GazeboSystem": (HUMBLE,),
                           "gz_ros2_control/GazeboSimSystem": LATER}
MOCK = ("mock_components/GenericSystem", "fake_components/GenericSystem")
GAZEBO = ("gazebo_ros2_control/GazeboSystem", "gz_ros2_control/GazeboSimSystem",
          "ign_ros2_control/IgnitionSystem")
# The command interfaces whose min and max ros2_control (from 4.10.0) reads as joint limits
# (component_parser.cpp update_interface_limits; position, velocity and effort only while their
# limits are enabled, acceleration and jerk always).
LIMITED = ("position", "velocity", "effort", "acceleration", "jerk")
GAZEBO_STATES = ("position", "velocity", "effort")  # the state interfaces the Gazebo hardware
# reads an initial_value of


def hardware_plugin(block) -> str:
    """The class name of a ``<ros2_control>`` block's ``<hardware><plugin>`` as
    ros2_control's component parser keeps it (its first, its text stripped); '' when it has
    none."""
    return (block.findtext("hardware/plugin") or "").strip()


def ros2_control_double(configuration: str, text: str) -> float | None:
    """``text`` as hardware_interface::stod reads it in ``configuration``, or None."""
    if configuration == HUMBLE:
        return values.stream_double(text)
    stripped = text.strip(values.SPACE)
    return (values.stream_double if configuration == LATER_CXX17 else values.from_chars_double)(stripped)


def humble_gazebo_double(configuration: str, text: str) -> float | None:
    """``text`` as Humble's gazebo_ros2_control and ign_ros2_control read an initial_value
    (std::stod), and as Jazzy's gz_ros2_control does (hardware_interface::stod)."""
    return values.strtod_double(text) if configuration == HUMBLE else ros2_control_double(configuration, text)


def read_bound(text: str | None) -> float | None:
    """The number ros2_control reads as a ``min`` or ``max`` (4.10.0 and later, either build),
    or None when it reads none (then it skips both bounds of the interface)."""
    found = {ros2_control_double(configuration, text or "") for configuration in LATER}
    return None if len(found) != 1 else found.pop()


class ParamReader(Record):
    """Who reads a ``<param>``'s number in one configuration, how, and what a text it cannot
    read does there. ``certain``: it reads it whenever the hardware runs (False: only if the
    hardware exports its interfaces ros2_control's default way)."""

    who: str
    parse: object  # (configuration, text) -> float or None
    consequence: str
    certain: bool

    __slots__ = ("who", "parse", "consequence", "certain")

    def __init__(self, who: str, parse: object, consequence: str, certain: bool = True) -> None:
        self.who = who
        self.parse = parse
        self.consequence = consequence
        self.certain = certain


def interface_params(interface) -> dict:
    """Name -> the ``<param>`` of a ``<command_interface>`` or ``<state_interface>`` that
    ros2_control's component parser keeps: its name stripped, the last of a name (they are
    assigned in document order into a map)."""
    return {name.strip(): param for param in interface.findall("param")
            if (name := param.get("name")) is not None}


def param_readers(block, joint, interface, name: str) -> dict[str, list[ParamReader]]:
    """Configuration -> the readers of ``<param name=NAME>`` (min, max, initial_value) of
    ``interface`` of ``joint`` of ``<ros2_control>`` ``block`` there, for each configuration
    its hardware runs in (:data:`HARDWARE_CONFIGURATIONS`). Empty for an interface of
    another data type than double: its initial_value has a parser of its own, not modelled."""
    if (interface.get("data_type") or "double").strip() != "double":
        return {}
    plugin = hardware_plugin(block)
    kind, tag = interface.get("name"), interface.tag
    found = {configuration: [] for configuration in HARDWARE_CONFIGURATIONS.get(plugin, CONFIGURATIONS)}
    for configuration, readers in found.items():
        later = configuration != HUMBLE
        if name in ("min", "max"):
            if later and tag == "command_interface" and kind in LIMITED and (
                    kind in ("acceleration", "jerk") or _limits_enabled(joint, interface)):
                readers.append(ParamReader(
                    "ros2_control (4.10.0 and later: Jazzy, Kilted, Rolling)", ros2_control_double,
                    f"prints 'Error parsing the limits for the interface: {kind}' and skips its "
                    "min and max (the URDF's <limit> still holds)"))
        elif name == "initial_value":
            if plugin in MOCK and (later or tag == "state_interface"):
                readers.append(ParamReader(
                    f"{plugin}", ros2_control_double,
                    "throws 'Invalid initial value' and imports none of the hardware's interfaces"
                    if later else "throws 'Failed converting string to real number' as the "
                    "hardware initializes: the controller manager stops"))
            elif plugin in GAZEBO:
                if tag == "state_interface" and kind in GAZEBO_STATES:
                    readers.append(ParamReader(
                        plugin, humble_gazebo_double, "throws 'Failed converting initial_value "
                        "string': Gazebo starts no controllers"))
            elif later:
                readers.append(ParamReader(
                    "ros2_control (4.31.0 and later: Jazzy, Kilted, Rolling)", ros2_control_double,
                    "throws 'Invalid initial value' and imports none of the hardware's interfaces",
                    certain=False))
    return found


def _limits_enabled(joint, interface) -> bool:
    """Whether neither ``<limits enable="false"/>`` of the joint nor of the interface turns
    ros2_control's limits of the interface off (component_parser.cpp)."""
    return all((element.get("enable") or "").strip().lower() != "false"
               for element in (joint.find("limits"), interface.find("limits")) if element is not None)


def control_plugin(robot):
    """The element that makes a simulator or ros2_control read the transmissions, or None;
    looked for once per robot (two rules ask, the transmissions' and the controllers': each
    looked in every ``<gazebo>`` block's plugins, 1,434 lxml findall of the corpus's blocks)."""
    return robot.memo(control_plugin, lambda: _control_plugin(robot))


def _control_plugin(robot):
    blocks = robot.children("ros2_control")
    if blocks:
        return blocks[0]
    for gazebo in robot.children("gazebo"):
        for plugin in children_named(gazebo, "plugin"):
            text = f"{plugin.get('filename', '')} {plugin.get('name', '')}"
            if any(name in text for name in CONTROL_PLUGINS):
                return plugin
    return None


DIFF_DRIVE = ("diff_drive", "diff-drive", "DiffDrive")
WHEEL_JOINT_TAGS = ("leftJoint", "rightJoint", "left_joint", "right_joint")


def gazebo_plugins(robot) -> tuple:
    """Every ``<plugin>`` inside a ``<gazebo>`` block, in document order; once per robot (a
    dozen rules and loaders ask, and each search walked every block to its leaves)."""
    return robot.memo(gazebo_plugins, lambda: tuple(
        element for _, element in gazebo_elements(robot) if element.tag == "plugin"))


def gazebo_sensors(robot) -> tuple:
    """(``<gazebo>`` block, ``<sensor>``) for every sensor inside a block, in document order;
    once per robot (the camera conventions walked the blocks to their leaves three times: 1,395
    walks of the corpus's 806 blocks)."""
    return robot.memo(gazebo_sensors, lambda: tuple(
        (gazebo, element) for gazebo, element in gazebo_elements(robot) if element.tag == "sensor"))


GAZEBO_WALKED = ("plugin", "sensor", "frame_name", "frameName", "bodyName", "body_name")


def gazebo_elements(robot) -> tuple:
    """(``<gazebo>`` block, element) for every element of :data:`GAZEBO_WALKED` inside a block
    (its plugins, its sensors, the frames they name), in document order; one walk of each block
    once per robot (the plugins, the sensors and the sensor-frame rule's frames walked the
    corpus's 806 blocks to their leaves once each)."""
    return robot.memo(gazebo_elements, lambda: tuple(
        (gazebo, element) for gazebo in robot.children("gazebo")
        for element in gazebo.iter(*GAZEBO_WALKED)))


def diff_drive_plugins(robot):
    """The Gazebo diff-drive plugins (gazebo_ros_diff_drive, gz-sim-diff-drive-system, ...)."""
    for plugin in gazebo_plugins(robot):
        text = f"{plugin.get('filename', '')} {plugin.get('name', '')}"
        if any(word in text for word in DIFF_DRIVE):
            yield plugin


def diff_drive_wheels(robot) -> set:
    """Names of the joints a Gazebo diff-drive plugin drives (its left and right joints)."""
    return {(element.text or "").strip() for plugin in diff_drive_plugins(robot)
            for tag in WHEEL_JOINT_TAGS for element in plugin.findall(tag)}


STATE_PLUGIN = "joint_state_publisher"  # libgazebo_ros_joint_state_publisher.so, ROS 1 and 2


def published_by_gazebo(robot) -> set:
    """Names of the joints a Gazebo joint state publisher plugin publishes: ROS 1's
    ``<jointName>a, b</jointName>``, ROS 2's ``<joint_name>`` (one per element); Gazebo Sim's
    ``gz-sim-joint-state-publisher-system`` every joint unless it names some."""
    found = set()
    for plugin in gazebo_plugins(robot):
        filename = plugin.get("filename") or ""
        if STATE_PLUGIN not in filename and "joint-state-publisher" not in filename:
            continue
        named = [*plugin.iter("jointName"), *plugin.iter("joint_name")]
        if not named and "joint-state-publisher" in filename:  # Gazebo Sim's: every joint
            found.update(robot.joints)
        for element in named:
            found.update(name.strip() for name in (element.text or "").split(",") if name.strip())
    return found


def moving_joints(robot) -> dict:
    """Non-fixed joints that need a driver: revolute, continuous and prismatic, not mimic."""
    return {name: joint for name, joint in robot.joints.items()
            if joint.get("type") in MOVING and first_child(joint, "mimic") is None}
