"""How a robot's joints are actuated: transmissions (ROS 1 and ROS 2 forms) and ros2_control."""

from __future__ import annotations


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
            (block.findtext("hardware/plugin") or "").strip(), {})
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
