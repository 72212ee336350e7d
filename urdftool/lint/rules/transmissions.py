"""U5xx: transmissions (ROS 1 and ROS 2 forms) and ``<ros2_control>`` blocks.

A top-level ``<transmission>`` is read by ROS 1 only (gazebo_ros_control, ros_control's
transmission loader): ros2_control reads the transmissions inside ``<ros2_control>`` and no
other. So the transmission rules judge a top-level transmission as ROS 1 reads it when the
robot is ROS 1 or nothing says (the element itself is ROS 1's); say nothing of it when the
robot is ROS 2 only (its package builds with ament, it has ``<ros2_control>``, its launch files
are ROS 2's: :func:`~urdftool.description.ros_version.ros_versions`), and make a warning naming
the condition when both may read it (docs/certainty.md).
"""

from __future__ import annotations

import functools
import re

from urdftool.description.ros_version import nothing_says_ros, ros_versions
from urdftool.description.runtime import (STATE_PUBLISHERS, built_as_checked, built_otherwise,
                                         runtime)
from urdftool.lint.catalogue import Conditional, Severity, rule
from urdftool.description.actuation import (HARDWARE_INTERFACES, control_plugin, diff_drive_wheels,
                                            exported_interface, hardware_plugin, interface_kind,
                                            interface_params, is_ros2_form, moving_joints,
                                            published_by_gazebo,
                                            read_bound, ros2_control_joints, transmission_joints,
                                            transmissions)
from urdftool.errors import available, close_names, renamed
from urdftool.description.values import parse_numbers
from urdftool.description.xacro_text import dropped_under
from urdftool.description.xml import attribute
from urdftool.numbers import decimal_slip

ROS2_INTERFACES = ("position", "velocity", "acceleration", "effort", "torque", "force",
                   "current", "temperature")


def _label(transmission) -> str:
    return f"transmission '{transmission.get('name') or '?'}'"


def _as_read(robot, transmission, message, unread_note: bool = False):
    """``message`` as the ROS versions reading ``transmission`` make it: None when none does
    (a ROS 1 transmission on a robot only ROS 2 runs; a note with ``unread_note``), a
    :class:`Conditional` when only one of the versions the robot runs under does, else as it
    is."""
    if is_ros2_form(transmission):
        return message
    versions = ros_versions(robot)
    if versions.ros2_only:
        return Conditional(f"nothing reads this ROS 1 transmission (ros2_control reads only those "
                           f"inside <ros2_control>; {versions.why(2)}), but " + message,
                           Severity.INFO) if unread_note else None
    if 2 in versions.versions and 1 in versions.versions:
        return Conditional(f"if ROS 1 reads this transmission ({versions.why(1)}; ros2_control "
                           f"ignores it: {versions.why(2)}): " + message)
    return message


def _as_ros_reads(unread_note: bool = False):
    """A transmission rule whose findings are made :func:`_as_read` (the transmission is the
    element found, or the one holding it)."""
    def decorate(check):
        @functools.wraps(check)
        def judged(robot):
            for where, message, *fix in check(robot):
                transmission = where
                while transmission is not None and getattr(transmission, "tag", None) != "transmission":
                    transmission = transmission.getparent()
                if transmission is not None:
                    message = _as_read(robot, transmission, message, unread_note)
                if message is not None:
                    yield (where, message, *fix)
        return judged
    return decorate


@rule("U501", "transmission-unknown-joint", Severity.ERROR)
@_as_ros_reads(unread_note=True)
def transmission_unknown_joint(robot):
    """A transmission names a joint that does not exist (or names none).

    The controller manager refuses to load: "Could not find resource 'X' in
    'hardware_interface::EffortJointInterface'".

    Bad: ``<transmission name="t"> <joint name="head_jnt"> ...``
    Good: ``<joint name="head_joint">``, a joint of the robot
    """
    for transmission in transmissions(robot):
        joints = transmission_joints(robot, transmission)
        if not joints:
            yield transmission, f"{_label(transmission)} has no <joint>"
        for joint in joints:
            if not joint.name:
                yield joint.element, f"{_label(transmission)}: <joint> has no name"
            elif joint.name not in robot.joints:
                yield joint.element, (f"{_label(transmission)} names joint '{joint.name}', which "
                                      "does not exist; " + available('joints', joint.name, robot.joints))


@rule("U502", "transmission-fixed-joint", Severity.ERROR)
@_as_ros_reads(unread_note=True)
def transmission_fixed_joint(robot):
    """A transmission drives a fixed joint.

    A fixed joint cannot move; gazebo_ros_control and ros2_control skip or reject it.

    Bad: a transmission on ``camera_joint`` (type fixed)
    Good: transmissions only on revolute, continuous and prismatic joints
    """
    for transmission in transmissions(robot):
        for joint in transmission_joints(robot, transmission):
            target = robot.joints.get(joint.name)
            if joint.interfaces and not _commands(joint):
                continue  # read-only (franka_hw/FrankaModelInterface names the flange joint)
            if target is not None and target.get("type") == "fixed":
                yield joint.element, (f"{_label(transmission)} drives fixed joint '{joint.name}'; "
                                       "remove the transmission, or make the joint revolute, "
                                       "continuous or prismatic")


@rule("U503", "unknown-hardware-interface", Severity.ERROR)
@_as_ros_reads()
def unknown_hardware_interface(robot):
    """A ROS 1 transmission joint has no ``<hardwareInterface>`` or an unknown one.

    ``hardware_interface/`` may be omitted (old Gazebo form). Vendor interfaces written
    ``package/Name`` (franka_hw/FrankaStateInterface) are accepted. Transmissions inside
    ``<ros2_control>`` take their interfaces from the ros2_control joint instead. Only ROS 1
    reads a top-level transmission: on a robot ROS 2 alone runs (``<ros2_control>``, an ament
    package) nothing is said of it; on one both may run, a warning says so.

    A **warning**, not an error, for a joint whose interface is written only in its
    ``<actuator>`` (the form before ROS Indigo): gazebo_ros_control reads it there, with a
    deprecation warning at every start.

    A **warning** naming the condition on a robot nothing says ROS runs (no package.xml naming
    a ROS build tool, launch file, controller file or ros_control plugin): only ROS 1's ros_control reads the
    interface, and Drake reads a transmission without one (kinova_drake's Gen3 models, loaded
    by pydrake scripts beside them, were seven errors each).

    Bad: ``<hardwareInterface>hardware_interface/PositionInterface</hardwareInterface>``
    Good: ``<hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>``
    """
    unsaid = None if ros_versions(robot).versions else nothing_says_ros(robot)
    for transmission in transmissions(robot):
        kind = transmission.findtext("type") or transmission.get("type") or ""
        if is_ros2_form(transmission) or not kind.startswith("transmission_interface/"):
            continue
        for joint in transmission_joints(robot, transmission):
            if not joint.interfaces:
                yield joint.element, _if_ros(unsaid, (
                    f"{_label(transmission)}: joint '{joint.name}' has no <hardwareInterface>; "
                    "e.g. hardware_interface/PositionJointInterface"))
            elif joint.in_actuator:
                text = (joint.interfaces[0].text or "").strip()
                yield joint.element, Conditional(
                    f"{_label(transmission)}: joint '{joint.name}' has no <hardwareInterface>; "
                    f"its actuator's ('{text}') stands in for it in gazebo_ros_control, which "
                    "warns at every start that it 'should be nested inside the <joint> "
                    "element, not <actuator>': move it into <joint>")
            for interface in joint.interfaces:
                known, _ = interface_kind(interface.text)
                if not known:
                    text = (interface.text or "").strip()
                    bare = text.split("/")[-1].split("::")[-1]
                    yield interface, _if_ros(unsaid, (
                        f"{_label(transmission)}: unknown hardware interface '{text}'; "
                        + available('interfaces', bare, HARDWARE_INTERFACES)))


def _if_ros(unsaid: str | None, message: str):
    """U503's ``message``, as a warning naming the condition when nothing says ROS runs the
    robot (``unsaid``: :func:`~urdftool.description.ros_version.nothing_says_ros`; None when
    something says ROS runs it)."""
    return Conditional(f"if ROS 1's ros_control loads it ({unsaid}; Drake reads a transmission "
                       "without one): " + message) if unsaid is not None else message


@rule("U504", "transmission-no-actuator", Severity.ERROR)
@_as_ros_reads()
def transmission_no_actuator(robot):
    """A transmission has no actuator.

    ROS 1's transmission_interface needs an actuator to map commands through; its loaders
    reject the transmission without one. A transmission inside ``<ros2_control>`` is read by
    the hardware plugin of its block alone, when it loads its transmissions (ros2_control's
    parser accepts one without an actuator, and its SimpleTransmissionLoader reads only the
    joint; configuring it with no actuator handle fails): a warning naming that plugin
    (uwrt_mars_rover's drivetrain, whose plugin does not load them yet).

    Bad: ``<transmission> <type>...</type> <joint .../> </transmission>``
    Good: add ``<actuator name="head_motor"><mechanicalReduction>1</mechanicalReduction></actuator>``
    """
    for transmission in transmissions(robot):
        if not any(child.tag.lower().endswith("actuator") for child in transmission
                   if isinstance(child.tag, str)):
            message = (f"{_label(transmission)} has no <actuator>; add <actuator name=\"...\"> "
                       "naming the motor that drives the joint")
            block = transmission.getparent()
            if block is not None and block.tag == "ros2_control":
                plugin = hardware_plugin(block) or "?"
                message = Conditional(
                    f"if hardware plugin '{plugin}' loads its transmissions (ros2_control's "
                    "parser accepts this one; configuring it with no actuator fails): " + message)
            yield transmission, message


@rule("U505", "zero-mechanical-reduction", Severity.ERROR)
@_as_ros_reads()
def zero_mechanical_reduction(robot):
    """A transmission's mechanical reduction is zero or not a number.

    The joint command is divided by the reduction: zero gives infinite actuator commands.

    Bad: ``<mechanicalReduction>0</mechanicalReduction>``
    Good: ``<mechanicalReduction>1</mechanicalReduction>`` (or the gear ratio)
    """
    for transmission in transmissions(robot):
        for tag in ("mechanicalReduction", "mechanical_reduction"):
            for element in transmission.iter(tag):
                values, problem = parse_numbers(element.text, 1)
                if problem:
                    yield element, f"{_label(transmission)}: <{tag}> {problem}"
                elif values[0] == 0:
                    yield element, (f"{_label(transmission)}: <{tag}> is 0; use the gear ratio "
                                    "(1 for direct drive)")


def _commands(joint) -> set:
    """Command interfaces a transmission joint offers (empty for read-only ones)."""
    return {kind for kind in (interface_kind(i.text)[1] for i in joint.interfaces) if kind}


@rule("U506", "duplicate-transmission", Severity.ERROR)
@_as_ros_reads()
def duplicate_transmission(robot):
    """A joint is driven by more than one transmission with the same interface.

    Two transmissions writing the same command to one joint fight; the controller manager
    reports a resource conflict. Separate transmissions offering different interfaces
    (franka_gazebo's Position, Velocity and Effort per joint) and read-only ones
    (JointStateInterface, vendor state interfaces) are allowed.

    Bad: two transmissions with ``<joint name="head_joint">`` and PositionJointInterface
    Good: one transmission per joint
    """
    first: dict[tuple, str] = {}
    for transmission in transmissions(robot):
        for joint in transmission_joints(robot, transmission):
            if not joint.name:
                continue
            kinds = _commands(joint) if joint.interfaces else {"(any)"}
            if is_ros2_form(transmission):
                kinds = {"(ros2_control)"}
            for kind in sorted(kinds):
                if (joint.name, kind) in first:
                    yield joint.element, (f"joint '{joint.name}' is already driven by transmission "
                                          f"'{first[joint.name, kind]}'"
                                          f"{'' if kind.startswith('(') else f' with {kind}'}; keep one")
                    break
                first[joint.name, kind] = transmission.get("name") or "?"


@rule("U507", "unactuated-joint", Severity.WARNING)
def unactuated_joint(robot):
    """A moving joint has no transmission or ros2_control entry although the robot loads ros_control.

    With gazebo_ros_control or ``<ros2_control>``, only actuated joints are simulated as
    actuated and published: the joint never appears in /joint_states and falls limp.
    Mimic joints are exempt, and so are the wheels a Gazebo diff-drive plugin drives (it
    turns them and publishes their states itself) and the joints something else publishes:
    a Gazebo joint state publisher plugin naming them, or a joint_state_publisher every launch
    file starting the robot's controllers starts (passive joints: casters, sprung wheel-drop
    joints). When only some of those launch files start one, this is a note naming the others.
    Checked for ``<ros2_control>`` and the control plugins whose behaviour is known
    (gazebo_ros_control, gazebo_ros2_control, gz_ros2_control, ign_ros2_control); a vendor's
    (``libhsrb_gazebo_ros_control.so``) may publish every joint.

    Fix (unsafe: the interface is a guess): a ros2_control ``<joint>`` with the interfaces of
    the block's first joint, or a ROS 1 SimpleTransmission with the interface most of the
    robot's transmissions use (effort when none), added at the end of the block or robot.

    Bad: ``<ros2_control>`` lists head_joint but not the wheel joints
    Good: a transmission or a ros2_control ``<joint>`` for every revolute, continuous and
    prismatic joint
    """
    plugin = control_plugin(robot)
    if plugin is None or plugin.tag != "ros2_control" and not _known_loader(plugin):
        return  # a vendor's control plugin (libhsrb_gazebo_ros_control.so) may publish them all
    actuated = {joint.name for t in transmissions(robot) for joint in transmission_joints(robot, t)}
    actuated.update(joint.get("name") for _, joint in ros2_control_joints(robot))
    actuated.update(diff_drive_wheels(robot))
    actuated.update(published_by_gazebo(robot))
    publishing, silent = _state_publishers(robot)
    if publishing and not silent:
        return  # every launch file starting the robot's controllers starts joint_state_publisher
    loader = "<ros2_control>" if plugin.tag == "ros2_control" else f"plugin '{plugin.get('filename')}'"
    moving = moving_joints(robot)
    misspelt = _misspelt_entries(robot, [name for name in moving if name not in actuated])
    for name, joint in moving.items():
        if name not in actuated:
            message = (f"{joint.get('type')} joint '{name}' has no transmission or ros2_control joint "
                       f"although the robot loads {loader}; it will not be in /joint_states")
            if name in misspelt:  # U501's or U511's unknown name: the entry is there, misspelt
                label, element = misspelt[name]
                where = robot.locate(element)
                at = f" at {where.file}:{where.line}" if where is not None and where.line else ""
                message += f"; {label}{at} names no joint and may be meant for it"
            if publishing:
                message = Conditional(
                    f"if the robot is started by {', '.join(silent[:2])} (which start"
                    f"{'s' if len(silent) == 1 else ''} no joint_state_publisher; "
                    f"{publishing[0]} does): " + message, Severity.INFO)
            from urdftool.lint.fixes import offer  # (only for a finding)
            yield offer(joint, message, f"actuate joint '{name}'", _actuation(robot, plugin, name),
                        safe=False)


def _misspelt_entries(robot, unactuated: list) -> dict:
    """Unactuated robot joint -> (label, element) of the ``<ros2_control>`` ``<joint>`` or
    transmission ``<joint>`` naming no joint whose closest name it is (Bolt's 'FLHAA' for
    FL_HAA, U511; victor.urdf's transmissions' 'iiwa_joint_1' for victor_left_arm_joint_1 and
    then victor_right_arm_joint_1, U501): said where the joint falls limp. Each joint is
    claimed by one entry, the first written."""
    entries = [("the <ros2_control> joint", element, element.get("name") or "")
               for _, element in ros2_control_joints(robot)]
    entries += [(f"{_label(transmission)}'s joint", joint.element, joint.name or "")
                for transmission in transmissions(robot)
                for joint in transmission_joints(robot, transmission)]
    found: dict = {}
    for label, element, written in entries:
        if written and written not in robot.joints:
            free = [name for name in unactuated if name not in found]
            close = close_names(written, free, n=1) or renamed(written, free)[:1]
            if close:
                found[close[0]] = (f"{label} '{written}'", element)
    return found


# The control plugins whose behaviour is known: they publish only the joints they actuate
KNOWN_LOADERS = ("libgazebo_ros_control.so", "libgazebo_ros2_control.so", "gz_ros2_control-system",
                 "libgz_ros2_control-system.so", "ign_ros2_control-system",
                 "libign_ros2_control-system.so")


def _known_loader(plugin) -> bool:
    return (plugin.get("filename") or "").strip() in KNOWN_LOADERS


def _state_publishers(robot) -> tuple[list[str], list[str]]:
    """(the robot's launch files that start its controllers and a joint_state_publisher, those
    that start its controllers and none)."""
    facts = runtime(robot)
    publishing, silent = [], []
    for configuration in facts.described:
        if not any(spawn.configuration is configuration for spawn in facts.spawns):
            continue
        starts = any(start.package in STATE_PUBLISHERS for start in configuration.started)
        (publishing if starts else silent).append(configuration.named)
    return publishing, silent


def _actuation(robot, plugin, name: str):
    """Edits adding joint ``name`` to the robot's ros2_control block (with the interfaces of
    the block's first joint), or a ROS 1 transmission (with the interface most transmissions
    use) at the end of the robot."""
    from urdftool.lint.fixes import Unfixable, append_child

    if plugin.tag == "ros2_control":
        location = robot.locations.get(plugin)
        if location is not None and location.via:
            return Unfixable(f"the <ros2_control> block is written in a macro (called at "
                             f"{location.via[0]}); add the joint there")
        model = plugin.find("joint")
        kinds = [(child.tag, child.get("name")) for child in (model if model is not None else ())
                 if child.tag in ("command_interface", "state_interface") and child.get("name")]
        kinds = kinds or [("command_interface", "position"), ("state_interface", "position"),
                          ("state_interface", "velocity")]
        lines = [f'<joint name="{attribute(name)}">',
                 *(f'  <{tag} name="{attribute(kind)}"/>' for tag, kind in kinds), "</joint>"]
        return append_child(robot, plugin, "\n".join(lines))
    used = [(interface.text or "").strip() for t in transmissions(robot)
            for joint in transmission_joints(robot, t) for interface in joint.interfaces]
    # the most used; of those used as often, the first written (a set's order of strings
    # changes with the hash seed: the fix changed from run to run)
    interface = max(dict.fromkeys(used), key=used.count) if used else \
        "hardware_interface/EffortJointInterface"
    name = attribute(name)
    lines = [f'<transmission name="{name}_transmission">',
             "  <type>transmission_interface/SimpleTransmission</type>",
             f'  <joint name="{name}"><hardwareInterface>{attribute(interface)}'
             "</hardwareInterface></joint>",
             f'  <actuator name="{name}_motor"><mechanicalReduction>1</mechanicalReduction>'
             "</actuator>", "</transmission>"]
    return append_child(robot, robot.root, "\n".join(lines))


# The bare names gazebo_ros_control (DefaultRobotHWSim) warns about: "Deprecated syntax, please
# prepend 'hardware_interface/' to 'EffortJointInterface' within the <hardwareInterface> tag".
_DEPRECATED_BARE = ("EffortJointInterface", "PositionJointInterface", "VelocityJointInterface")


@rule("U508", "hardware-interface-prefix", Severity.WARNING)
@_as_ros_reads()
def hardware_interface_prefix(robot):
    """A ROS 1 transmission joint names its interface without ``hardware_interface/``.

    gazebo_ros_control still accepts the old form but warns on every start ("Deprecated syntax,
    please prepend 'hardware_interface/' ..."), and ros_control's transmission loader expects
    the full name.

    Fix (safe): ``hardware_interface/`` written before the name.

    Bad: ``<hardwareInterface>EffortJointInterface</hardwareInterface>``
    Good: ``<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>``
    """
    for transmission in transmissions(robot):
        if is_ros2_form(transmission):
            continue
        for joint in transmission_joints(robot, transmission):
            for interface in [] if joint.in_actuator else joint.interfaces:  # U503 says move it
                text = (interface.text or "").strip()
                if text in _DEPRECATED_BARE:
                    from urdftool.lint.fixes import offer, prefix_text  # (only for a finding)
                    yield offer(interface, (
                        f"{_label(transmission)}: joint '{joint.name}' names '{text}' without "
                        "hardware_interface/, the old form gazebo_ros_control warns about on "
                        f"every start ('Deprecated syntax'); write hardware_interface/{text}"),
                        "prepend hardware_interface/", prefix_text(robot, interface,
                                                                    "hardware_interface/"))


@rule("U511", "ros2-control-unknown-joint", Severity.ERROR)
def ros2_control_unknown_joint(robot):
    """A ``<ros2_control>`` joint does not exist in the URDF (or has no name).

    The resource manager fails on start: the hardware's joint is not in the description.

    Bad: ``<ros2_control ...> <joint name="head_jnt">``
    Good: ``<joint name="head_joint">``
    """
    for _, joint in ros2_control_joints(robot):
        name = joint.get("name")
        if not name:
            yield joint, "<ros2_control> <joint> has no name"
        elif name not in robot.joints:
            yield joint, (f"ros2_control joint '{name}' does not exist; "
                          + available('joints', name, robot.joints))


@rule("U512", "ros2-control-fixed-joint", Severity.ERROR)
def ros2_control_fixed_joint(robot):
    """A ``<ros2_control>`` joint is a fixed joint.

    Bad: ``<joint name="camera_joint">`` (fixed) in ``<ros2_control>``
    Good: only moving joints in ``<ros2_control>``
    """
    for _, joint in ros2_control_joints(robot):
        target = robot.joints.get(joint.get("name"))
        if target is not None and target.get("type") == "fixed":
            yield joint, (f"ros2_control joint '{joint.get('name')}' is a fixed joint; remove it "
                          "from <ros2_control>, or make the joint revolute, continuous or prismatic")


_MISSPELT = 0.8  # difflib's ratio from which an interface name is a standard one misspelt


@rule("U513", "ros2-control-interface-name", Severity.WARNING)
def ros2_control_interface_name(robot):
    """A ros2_control command or state interface has no name or not a standard one.

    Controllers claim interfaces by name (``head_joint/position``); a misspelt interface is
    never claimed. Custom names are legal for custom hardware (a legged robot's ``kp`` and
    ``kd`` gains, a Dynamixel's ``load``, KUKA's ``stiffness``): a name close to a standard one
    is a warning (a misspelling, most likely), any other a **note** (the standard controllers
    cannot claim it; the robot's own hardware plugin and controllers must know it).

    A name the hardware plugin reads and exports as a standard one is not reported
    (gazebo_ros2_control's ``position_pid``, exported as ``position``).

    Bad: ``<command_interface name="positon"/>``
    Good: ``<command_interface name="position"/>`` (velocity, effort, acceleration, ...)
    """
    for block, joint in ros2_control_joints(robot):
        for interface in [*joint.findall("command_interface"), *joint.findall("state_interface")]:
            name = interface.get("name")
            if not name:
                yield interface, f"ros2_control joint '{joint.get('name')}': <{interface.tag}> has no name"
            elif name not in ROS2_INTERFACES and (interface.tag == "state_interface" or
                                                  exported_interface(robot, block, name) == name):
                said = (f"ros2_control joint '{joint.get('name')}': <{interface.tag}> '{name}' "
                        "is not a standard interface")
                if close_names(name, ROS2_INTERFACES, n=1, cutoff=_MISSPELT):
                    yield interface, f"{said}; " + available('interfaces', name, ROS2_INTERFACES)
                else:  # a custom interface: legal, for the robot's own plugin and controllers
                    yield interface, Conditional(
                        f"{said}: the standard controllers (ros2_controllers) cannot claim it, "
                        "only controllers that know the hardware plugin's own names; "
                        + available('standard interfaces', name, ROS2_INTERFACES),
                        Severity.INFO)


@rule("U514", "ros2-control-no-plugin", Severity.ERROR)
def ros2_control_no_plugin(robot):
    """A ``<ros2_control>`` block names no hardware plugin.

    The controller manager cannot load hardware without ``<hardware><plugin>``.

    Bad: ``<ros2_control name="sys" type="system"> <hardware/> ...``
    Good: ``<hardware><plugin>gazebo_ros2_control/GazeboSystem</plugin></hardware>``

    A warning when the launch files run the robot's file through xacro only with other
    arguments than it was checked with (its ``<xacro:arg>`` defaults, or ``--arg``), as when
    an ``xacro:if`` on a ``mode`` argument picks the plugin and no launch file builds the
    default: the builds that run are not checked, and the message names them. A warning too
    when the ``<hardware>`` as written holds its ``<plugin>`` under an ``xacro:if`` or
    ``xacro:unless`` that is false as checked (a plugin for the simulation only, the real
    robot driven by a node of its own) and no launch file is known to build it as checked:
    whether a controller manager reads the robot built so is the launch's choice, and the
    message names the condition.
    """
    otherwise = None
    for block in robot.children("ros2_control"):
        hardware = block.find("hardware")
        plugin = hardware.findtext("plugin", "").strip() if hardware is not None else ""
        if not plugin:
            named = f"<ros2_control name='{block.get('name')}'> names no <hardware><plugin>"
            example = "e.g. gazebo_ros2_control/GazeboSystem or mock_components/GenericSystem"
            otherwise = built_otherwise(robot) if otherwise is None else otherwise
            # a launch file building it as checked runs a build without the plugin: an error
            dropped = None if otherwise or built_as_checked(robot) else \
                _plugin_condition(robot, hardware)
            if otherwise:
                build, other = otherwise[0]
                other = _deciding_first(other, _plugin_condition(robot, hardware))
                more = f" (and {len(otherwise) - 1} more)" if len(otherwise) > 1 else ""
                message = Conditional(
                    f"{named} with the xacro arguments the robot is checked with; "
                    f"{build.named_at()} builds it with {', '.join(other[:4])}{more}, and no "
                    "launch file as checked: whether their builds name one is not checked "
                    f"(--arg NAME=VALUE checks one); {example}")
            elif dropped:
                message = Conditional(f"{named} with the xacro arguments the robot is checked "
                                      f"with: {dropped}; a controller manager given the robot "
                                      "built so cannot load its hardware (--arg NAME=VALUE "
                                      "checks another build)")
            else:
                message = f"{named}; {example}"
            yield (hardware if hardware is not None else block), message


def _deciding_first(given: list[str], condition: str | None) -> list[str]:
    """The arguments a build gives (``name:=value``), those the condition on the ``<plugin>``
    names first (mycobot_ros2's use_gazebo, after add_world, base_link, ... alphabetically)."""
    words = set(re.findall(r"\w+", condition or ""))
    return sorted(given, key=lambda text: text.partition(":=")[0] not in words)


def _plugin_condition(robot, hardware) -> str | None:
    """How the source of ``hardware`` gives its ``<plugin>`` only under conditions false as
    the robot was expanded (``its <plugin> is under <xacro:if value="$(arg sim_mode)"> (line
    15) of ros2_control.xacro``), or None."""
    return dropped_under(robot, hardware, "plugin") if hardware is not None else None


_LIMIT_ATTRIBUTE = {"velocity": "velocity", "effort": "effort"}
_LIMIT_SLACK = 1e-6  # [rad, m, rad/s, N, ...] rounding in values a xacro computed


@rule("U515", "ros2-control-limits", Severity.WARNING)
def ros2_control_limits(robot):
    """A ros2_control command interface's ``min``/``max`` goes beyond the joint's ``<limit>``.

    ros2_control (and the hardware driver reading these parameters) lets commands through up
    to ``min``/``max``, while the URDF, MoveIt and the joint limiters stop at ``<limit>``: a
    position command the planner never produces is accepted, or a real arm is driven past
    the range its description promises. Position is compared with ``lower``/``upper``
    (not for continuous joints), velocity and effort with ``velocity``/``effort`` (a range
    of ``-limit`` to ``limit``); ``min`` above ``max`` is reported too.

    Bad: ``<param name="max">2.41</param>`` on a position interface of a joint with
    ``upper="2.24"``
    Good: ``<param name="max">2.24</param>``, or the same xacro property in both places
    """
    for _, joint in ros2_control_joints(robot):
        target = robot.joints.get(joint.get("name"))
        if target is None:
            continue
        limit = target.find("limit")
        for interface in joint.findall("command_interface"):
            kind = interface.get("name")
            params = interface_params(interface)  # (a bound ros2_control cannot read: U520)
            bounds = {name: params[name] for name in ("min", "max") if name in params}
            values = {name: value for name, element in bounds.items()
                      if (value := read_bound(element.text)) is not None}
            if "min" in values and "max" in values and values["min"] > values["max"]:
                yield bounds["min"], (f"ros2_control joint '{joint.get('name')}' {kind}: min "
                                      f"{values['min']:g} is above max {values['max']:g}; swap them")
                continue
            allowed = _allowed_range(target, limit, kind)
            if allowed is None:
                continue
            for name, value in values.items():
                low, high = allowed
                if (name == "min" and value < low - _LIMIT_SLACK) or (name == "max" and value > high + _LIMIT_SLACK):
                    edge = low if name == "min" else high
                    yield bounds[name], (
                        f"ros2_control joint '{joint.get('name')}' {kind} {name} is {value:g}, beyond "
                        f"the URDF <limit> ({edge:g}); commands {'down' if name == 'min' else 'up'} "
                        f"to {value:g} pass ros2_control "
                        f"but exceed the description: use {edge:g}, or widen <limit> if the joint "
                        "really moves that far" + decimal_slip(abs(value), abs(edge) if value * edge > 0 else 0.0))


def _allowed_range(joint, limit, kind) -> tuple[float, float] | None:
    """(low, high) the URDF allows for command interface ``kind``, or None when it says nothing."""
    if limit is None:
        return None
    if kind == "position":
        if joint.get("type") == "continuous":
            return None
        low, bad_low = parse_numbers(limit.get("lower", "0"), 1)
        high, bad_high = parse_numbers(limit.get("upper", "0"), 1)
        return None if bad_low or bad_high or low[0] >= high[0] else (low[0], high[0])
    if kind in _LIMIT_ATTRIBUTE and limit.get(_LIMIT_ATTRIBUTE[kind]) is not None:
        value, bad = parse_numbers(limit.get(_LIMIT_ATTRIBUTE[kind]), 1)
        return None if bad or value[0] <= 0 else (-abs(value[0]), abs(value[0]))
    return None


# Hardware plugins of the simulators and of ros2_control's mock components
# (ros-controls/gazebo_ros2_control, gz_ros2_control; ros2_control/hardware_interface).
KNOWN_HARDWARE = {
    "gazebo_ros2_control": ("gazebo_ros2_control/GazeboSystem",),
    "gz_ros2_control": ("gz_ros2_control/GazeboSimSystem",),
    "ign_ros2_control": ("ign_ros2_control/IgnitionSystem",),
    "mock_components": ("mock_components/GenericSystem",),
    "fake_components": ("fake_components/GenericSystem",),
}


@rule("U516", "ros2-control-hardware-plugin", Severity.ERROR)
def ros2_control_hardware_plugin(robot):
    """A ``<ros2_control>`` hardware plugin of a simulator or of mock_components is misspelt.

    The resource manager cannot load it ("According to the loaded plugin descriptions the class
    ... does not exist"). Checked for the packages whose classes are known:
    gazebo_ros2_control, gz_ros2_control, ign_ros2_control, mock_components and
    fake_components; a vendor's driver is not.

    Bad: ``<plugin>gazebo_ros2_control/GazeboSytem</plugin>``
    Good: ``<plugin>gazebo_ros2_control/GazeboSystem</plugin>``
    """
    for block in robot.children("ros2_control"):
        for element in block.iterfind("hardware/plugin"):
            name = (element.text or "").strip()
            known = KNOWN_HARDWARE.get(name.split("/")[0])
            if known and name not in known:
                yield element, (f"hardware plugin '{name}' does not exist; "
                                + available('plugins', name, [p for ps in KNOWN_HARDWARE.values() for p in ps]))
