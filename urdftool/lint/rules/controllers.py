"""U60x: controller configuration YAML (ROS 1 ros_control and ROS 2 ros2_control layouts).

Which controllers run is the launch files' choice (:mod:`urdftool.description.runtime`): a
finding on a controller is an error when a launch file of the robot as checked starts it, active
and unconditionally; a warning naming when it holds when a launch file starts it only under a
condition or no launch file says (a controller file is often a menu from which a launch file
starts a few); nothing when the robot's launch files start it nowhere (docs/certainty.md).

One convention for every controller message (U6xx, U820): ``controller 'NAME' (CLASS)``, what
is wrong, then what to do; a defect that holds only if the controller runs says first why that
is not known, as a clause of its own ("no launch file of the robot says whether it is started;
if controller 'NAME' (CLASS) is started against this robot as checked, it names ..."), or last
for a controller that fails to configure ("...; if 'NAME' is started, it fails to configure;
WHY"). No parentheses inside another's: the condition's own (an argument value) stay one deep.
"""

from __future__ import annotations


from urdftool.description.actuation import (command_interfaces, control_plugin, interface_kind,
                                            ros2_command_interfaces, ros2_state_interfaces,
                                            transmission_joints, transmissions)
from urdftool.description.companions import companions, parameter_files
from urdftool.description.controller_classes import COUNTERPARTS, MOVEIT_TYPES, classes, known_package, lookup
from urdftool.description import controllers as described
from urdftool.description.packages import containment_root, exported_classes
from urdftool.description.controllers import (Controller, JointRef, controller_files, controllers,
                                              runs_of)
from urdftool.description.runtime import STATE_PUBLISHERS, Runs, runtime, together
from urdftool.description.documents import YamlList, YamlMap
from urdftool.description.moveit_config import moveit_controllers
from urdftool.errors import available, shown_word
from urdftool.lint.catalogue import Conditional, Severity, rule


def _substituted(name: str, controller: Controller | None = None) -> bool:
    """A launch substitution (``$(arg arm_id)_joint1``, ``$(var prefix)``) is replaced at
    launch: not checkable, unless every launch file of the robot loads the file without
    substitution (then the controller gets the text as written)."""
    return "$(" in name and (controller is None or controller.file.substituted is not False)


def label(controller: Controller) -> str:
    return f"controller '{controller.name}' ({controller.type or 'no type'})"


def hedged(robot, controller: Controller, message: str):
    """``message`` as a rule yields it for ``controller``: as it is when a launch file of the
    robot as checked starts it (the defect holds whenever the robot runs); None when the
    robot's launch files start it nowhere; else a :class:`Conditional` naming when it holds
    (a launch file starts it only under a condition, or no launch file says: a controller file
    is often a menu from which a launch file starts a few)."""
    answer = described.started(robot, controller)
    if answer is False:
        return None
    if answer:
        return message
    verdict = runs_of(robot, controller)
    return Conditional(f"{_if_started(controller, verdict)}, " + _after(controller, message))


def _if_started(controller: Controller, verdict: Runs) -> str:
    """Why the controller may not run, then the condition: "WHY; if controller 'x' (CLASS) is
    started against this robot as checked" (the message goes on with its defect)."""
    import re

    named = f"'{controller.name}'"  # the clause comes first: "it" would name nothing yet
    why = re.sub(r"\bit\b", lambda _: named, verdict.condition, count=1) if verdict.condition \
        else f"no launch file of the robot says whether {named} is started"
    return f"{why}; if {label(controller)} is started against this robot as checked"


def _after(controller: Controller, message: str) -> str:
    """``message`` without the controller's label it starts with (the condition names it)."""
    named = label(controller)
    return (message[len(named) + 2:] if message.startswith(named + ": ") else
            "it" + message[len(named):] if message.startswith(named) else message)


def if_started(robot, controller: Controller, consequence: str) -> tuple[Severity | None, str]:
    """How bad a defect is that matters only when ``controller`` runs (it fails to configure,
    it commands nothing), and how to say so, for a rule yielding ``(where, message, None,
    severity)``: an error stating ``consequence`` when a launch file of the robot as checked
    starts it, active and unconditionally; a warning stating it under the condition ("if 'x' is
    started, ...", with why it may not be) when a launch file starts it only under a condition
    or none says (a controller file is often a menu from which a launch file starts a few);
    None when the robot's launch files start it nowhere. :func:`hedged` says the same for a
    rule yielding a message; both ask :func:`~urdftool.description.controllers.runs_of`."""
    answer = described.started(robot, controller)
    if answer is False:
        return None, consequence
    if answer:
        return Severity.ERROR, consequence
    verdict = runs_of(robot, controller)
    why = f"; {verdict.condition}" if verdict.condition else ""
    return Severity.WARNING, f"if '{controller.name}' is started, {consequence}{why}"


def _urdf_joints(robot, controller: Controller) -> list[JointRef]:
    """The names a controller holds that are meant as URDF joints: all of them for a known
    class; for a class nothing is known about (a vendor's), only when some of them are URDF
    joints (its ``joint: tcp`` may be a hardware interface prefix, not a joint)."""
    refs = [ref for ref in controller.joints() if not _substituted(ref.name, controller)]
    if controller.known or any(ref.name in robot.joints for ref in refs):
        return refs
    return []


@rule("U601", "malformed-controllers-yaml", Severity.ERROR)
def malformed_controllers_yaml(robot):
    """A controller configuration file is not valid YAML, or names no controller.

    The controller manager cannot load its parameters, so no controller starts. Files given
    with ``--controllers`` must hold at least one controller (a mapping with
    ``type: package/Class``), a ``controller_manager`` section, or MoveIt's
    ``controller_list``/``controller_names`` (whose shape is U812's).

    A value PyYAML cannot construct (``2001-02-30``, a date to YAML 1.1 and no date; ``!!float
    junk``; ``<<: 5``) fails every loader of a ROS 1 file (rosparam reads with PyYAML); in a ROS
    2 parameter file it is a warning: ROS 2's parser reads it as written (no dates, no tag but
    ``!!str``), while a launch file or tool loading the file with PyYAML fails. An alias
    (``*defaults``, ``<<: *defaults``) in a ROS 2 parameter file is a warning too: ROS 2's parser
    refuses every alias, PyYAML reads it. rosparam's ``!degrees`` and ``!radians`` are read as
    it reads them (``!radians 2*pi``); one it makes no number of (``!degrees abc``,
    ``!radians 1/0``) is an error at its line: roslaunch refuses the file, and ROS 2's MoveIt,
    which reads the tags as ``float(text)``, fails too. An integer past 32 bits in a ROS 1
    parameter file (``encoder_ticks: 4294967296``) is an error too: the ROS 1 parameter server
    speaks XML-RPC (``<i4>``), and roslaunch cannot send it ("int exceeds XML-RPC limits");
    a warning in a file of MoveIt's lists alone, which ROS 2's MoveIt reads as well.

    Bad: ``joints: [head_pan, head_tilt`` (unclosed list)
    Good: ``joints: [head_pan, head_tilt]``
    """
    explicit = bool(robot.companion_paths.controllers)
    for file in companions(robot).controllers:
        if file.problem:
            yield file.at(file.line), file.problem
        elif file.caution:  # read as ROS 2's parser reads it; PyYAML cannot
            yield file.at(file.line), Conditional(file.caution)
    for read in controller_files(robot):
        file = read.file
        if explicit and not read.controllers and not _has_manager(read) and \
                not moveit_controllers(file)[1]:  # (a MoveIt list it cannot read: U812)
            yield file.at(1), (f"{file.display} names no controller (a mapping with "
                               "'type: package/Class', e.g. joint_state_broadcaster/JointStateBroadcaster)")
        yield from _past_int32(robot, read)


def _past_int32(robot, read):
    """The first integer past int32 in a ROS 1 parameter file: the ROS 1 parameter server
    speaks XML-RPC, whose integers are ``<i4>``; roslaunch's client (Python's xmlrpc.client)
    refuses to send one past them and stops before any node starts. Certain in a file of ROS 1
    controllers, or of a robot only ROS 1 reads; for one of MoveIt's lists alone, a warning
    (ROS 2's MoveIt reads it too, into int64 parameters); never in a ROS 2 parameter file."""
    from urdftool.description.ros_version import ros_version
    from urdftool.numbers import INT32, in_int32

    if read.file.ros2:
        return
    version = 1 if any(c.layout == "ros1" for c in read.controllers) else ros_version(robot)[0]
    if version == 2:
        return
    for name, past, line in _integers(read.file.data, "", read.file.line, set()):
        if in_int32(past):
            continue
        said = (f"{name}: {shown_word(str(past))} is past the 32-bit integers of the ROS 1 "
                f"parameter server (XML-RPC's <i4>, {INT32[0]} to {INT32[1]}): roslaunch cannot "
                "send it (\"int exceeds XML-RPC limits\") and stops before any node starts; "
                "write it as a double or a string")
        yield read.file.at(line), said if version == 1 else Conditional(
            f"if ROS 1 loads {read.file.display}: {said}")
        return


def _integers(value, name: str, line, seen: set, depth: int = 0):
    """(dotted name, integer, line) of each integer in a YAML value, in mappings and lists
    alike (XML-RPC sends them all), each collection once (an alias shares one)."""
    if isinstance(value, int) and not isinstance(value, bool):
        yield name, value, line
    if not isinstance(value, (YamlMap, YamlList)) or id(value) in seen or depth > 64:
        return
    seen.add(id(value))
    if isinstance(value, YamlMap):
        for key, item in value.items():
            yield from _integers(item, f"{name}.{key}" if name else str(key),
                                 value.lines.get(key, line), seen, depth + 1)
    else:
        for index, item in enumerate(value):
            yield from _integers(item, f"{name}[{index}]", value.lines[index], seen, depth + 1)


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

    A file whose controllers name two or more joints, none of them in the robot (no launch file
    of the robot starting any of them for certain), is another build's (a prefix, other xacro
    arguments, a sibling robot's file): one note says so, at its first controller. One name
    alone that is missing may be a slip, and is judged as any other.

    A controller that every launch file starting it starts against the robot built with other
    xacro arguments (all known) is checked against that build (aist_robotiq's gazebo.launch,
    ``prefix:=a_bot_gripper_``): nothing when each has the joint, else a warning naming it.

    A name ``CONTROLLER/NAME`` where CONTROLLER is another controller of the robot is a chained
    controller's reference interface (diff_drive_controller driving two pid_controllers,
    ros2_control_demos example 16), not a joint.

    Bad: ``joints: [head_jont]``
    Good: ``joints: [head_joint]``
    """
    foreign = _foreign_files(robot)
    for read in controller_files(robot):
        if read.file.path in foreign:
            first, names = foreign[read.file.path]
            yield first.file.at(first.line), Conditional(
                f"none of the {len(names)} joints {read.file.display}'s controllers name is in the "
                f"robot as checked ({', '.join(names[:4])}{', ...' if len(names) > 4 else ''}): "
                "the file is for another build of the robot (a prefix, other xacro arguments) "
                "or another robot; check the robot as that build with --arg", Severity.INFO)
    # a chained controller claims another's reference interfaces, CONTROLLER/NAME, not joints
    chainable = {controller.name for controller in controllers(robot)}
    for controller in controllers(robot):
        if controller.file.path in foreign:
            continue
        for ref in _urdf_joints(robot, controller):
            if ref.name not in robot.joints and ref.name.partition("/")[0] not in chainable:
                builds = _starting_builds(robot, controller) if controller.known else None
                lacking = [(spawn, built) for spawn, built in builds or ()
                           if ref.name not in built.joints]
                if builds and not lacking:
                    continue  # in every robot the controller is started with
                if lacking:  # checked against the robot it is started with, which lacks it too
                    spawn, built = lacking[0]
                    yield controller.file.at(ref.line), Conditional(
                        f"if {spawn.told()}: {label(controller)} names joint '{ref.name}', "
                        "which is not in that build of the robot either; "
                        + available('joints', ref.name, built.joints))
                    continue
                literal = (" (every launch file of the robot loads the file without substitution, "
                           "so it is not replaced)" if "$(" in ref.name else "")
                message = hedged(robot, controller, (
                    f"{label(controller)} names joint '{ref.name}', which is not in the URDF"
                    f"{literal}; " + available('joints', ref.name, robot.joints)))
                if message is not None:
                    yield controller.file.at(ref.line), message


def _starting_builds(robot, controller: Controller) -> list | None:
    """(spawn, the robot as built there) for each launch configuration starting ``controller``
    active, when every one builds the robot with other xacro arguments, all known, and xacro
    succeeds so; else None. The controller runs with those robots, not the one checked
    (aist_robotiq's gazebo.launch builds the gripper with prefix:=a_bot_gripper_, the joints
    its YAML names)."""
    from urdftool.description.runtime import building_args

    active = [spawn for spawn in runs_of(robot, controller).spawns if spawn.active]
    if not active or getattr(robot, "rebuild", None) is None:
        return None
    found = []
    for spawn in active:
        args = building_args(robot, spawn.configuration)
        built = False if args is None else robot.memo_for(
            _starting_builds, tuple(sorted(args.items())), lambda: _rebuilt(robot, args))
        if built is False:
            return None
        found.append((spawn, built))
    return found


def _rebuilt(robot, args: dict):
    """The robot built again with xacro arguments ``args``, or False when xacro fails so."""
    from urdftool.errors import LoadError

    try:
        return robot.rebuild(args)
    except LoadError:
        return False


def _foreign_files(robot) -> dict:
    """Controller file -> (its first controller, the joints named) for each file whose
    controllers name two or more joints and none of the robot's, none started for certain."""
    found = {}
    for read in controller_files(robot):
        mine = [c for c in read.controllers if c.layout != "moveit"]
        names = list(dict.fromkeys(ref.name for c in mine for ref in _urdf_joints(robot, c)))
        if len(names) > 1 and not any(name in robot.joints for name in names) and \
                not any(runs_of(robot, c).state == "certain" for c in mine):
            found[read.file.path] = (mine[0], names)
    return found


@rule("U603", "controller-joint-not-actuated", Severity.ERROR)
def controller_joint_not_actuated(robot):
    """A controller commands a joint that has no transmission or ros2_control entry.

    The hardware offers no interface for the joint, so the controller cannot claim it.
    Checked when the URDF describes its actuation (has a transmission or ``<ros2_control>``).
    A joint without a transmission is a **warning** naming the condition when nothing in the
    URDF reads its ROS 1 transmissions (no gazebo_ros_control): a robot's own RobotHW
    registers the joints it is written for (ros_control_boilerplate's, from its ``joints``
    parameter), whatever transmissions say.

    A ROS 2 controller's joint needs a ``<ros2_control>`` entry: a ROS 1 ``<transmission>``
    outside ``<ros2_control>`` offers it nothing. Checked in a robot that has ``<ros2_control>``
    at all: one without is no robot a ROS 2 controller runs on (a stale generated URDF beside
    the xacro the launch files build, whose controller file is the xacro's: naranjelio's, the
    A1's ``urdf/robot.urdf``), and nothing is said of it.

    A MoveIt ``GripperCommand`` controller's joint that is a ``<mimic>`` of another of its
    joints is not commanded (MoveIt sends the action one joint's position).

    Bad: ``joints: [camera_joint]`` (fixed), or a joint without a transmission
    Good: a transmission or ros2_control ``<joint>`` for every commanded joint
    """
    if not transmissions(robot) and not robot.children("ros2_control"):
        return
    own_hardware = control_plugin(robot) is None  # ROS 1 transmissions nothing here reads
    ros2_control = bool(robot.children("ros2_control"))
    for controller in controllers(robot):
        if controller.is_state or controller.ros == 2 and not ros2_control:
            continue  # (a URDF with no <ros2_control> is no robot a ROS 2 controller runs on)
        offered = _offered(robot, controller)
        following = _gripper_followers(robot, controller)
        for ref in _urdf_joints(robot, controller):
            joint = robot.joints.get(ref.name)
            if joint is None or ref.name in offered or ref.name in following:
                continue
            if joint.get("type") == "fixed":
                what = "is a fixed joint; remove it from the controller"
            elif controller.ros == 2 and ref.name in command_interfaces(robot):
                what = ("has no <ros2_control> joint, only a transmission, which ros2_control "
                        "reads only inside <ros2_control>; add a <ros2_control> joint for it, "
                        "or remove it from the controller")
            else:
                what = ("has no transmission or ros2_control joint; add one for it, or remove "
                        "it from the controller")
            message = hedged(robot, controller, f"{label(controller)}: joint '{ref.name}' {what}")
            if message is not None and own_hardware and joint.get("type") != "fixed":
                message = Conditional(
                    f"if the robot's hardware interface offers only the joints of its "
                    f"transmissions (gazebo_ros_control does, and the URDF loads none: a RobotHW "
                    f"of its own registers the joints it is written for): " + message,
                    getattr(message, "severity", Severity.WARNING))
            if message is not None:
                yield controller.file.at(ref.line), message


def _gripper_followers(robot, controller: Controller) -> set[str]:
    """The joints of a MoveIt ``GripperCommand`` controller that are ``<mimic>``s of another of
    its joints: MoveIt sends the action one joint's position (its ``command_joint``, else the
    first), and a mimic follows its joint (robot_state_publisher places it), needing no
    interface of its own (the Setup Assistant lists every joint of the gripper group)."""
    if controller.layout != "moveit" or controller.type not in ("GripperCommand", "ParallelGripperCommand"):
        return set()
    names = {ref.name for ref in controller.joints()}
    return {name for name in names if robot.joints.get(name) is not None
            and robot.joints[name].find("mimic") is not None
            and robot.joints[name].find("mimic").get("joint") in names}


@rule("U604", "controller-interface-mismatch", Severity.ERROR)
def controller_interface_mismatch(robot):
    """A controller commands an interface the joint's transmission or ros2_control does not offer.

    position_controllers/* need a PositionJointInterface (or a ``position`` command interface),
    velocity_controllers/* a velocity one, effort_controllers/* an effort one;
    joint_trajectory_controller uses its ``command_interfaces``, forward_command_controller its
    ``interface_name``, diff_drive_controller velocity on its wheels. A ROS 2 controller gets
    only what the joint's ``<ros2_control>`` entry offers (ros2_control does not read
    transmissions outside ``<ros2_control>``).

    A controller file is often a menu: effort, position and velocity variants for the same joints,
    of which a launch argument starts one (and the robot's xacro arguments choose the interfaces
    its transmissions offer). So this is an error only for a controller that runs with the robot
    as checked (a launch file starts it, active, unconditionally); a warning naming the
    condition when a launch file starts it only under an argument or no launch file says; and
    when no launch file says and the file offers alternatives for its joints, nothing when one
    of them fits the robot as checked (it is the one for this configuration), one warning per
    controller when none does. Nothing for a controller no launch file of the robot starts.

    Bad: ``position_controllers/JointTrajectoryController`` on a joint with
    ``hardware_interface/VelocityJointInterface``
    Good: ``velocity_controllers/JointTrajectoryController`` on that joint, or
    ``hardware_interface/PositionJointInterface`` in its transmission
    """
    for controller in controllers(robot):
        mismatches = _mismatches(robot, controller)
        if not mismatches:
            continue
        verdict = runs_of(robot, controller)
        if verdict.state == "never":
            continue
        rivals = _rivals(robot, controller)
        if verdict.state == "certain" or verdict.state == "unknown" and not rivals:
            for ref, missing, has_set in mismatches:  # each joint where it was written
                has = ", ".join(sorted(has_set)) or "no command interface (read-only)"
                yield controller.file.at(ref.line), hedged(robot, controller, (
                    f"{label(controller)} commands {'/'.join(missing)} on joint '{ref.name}', "
                    f"which offers {has}; {_interface_fix(controller, has_set, missing)}"))
            continue
        if verdict.state == "unknown" and any(not _mismatches(robot, rival) for rival in rivals):
            continue  # one of the file's alternatives fits the robot as checked: it is the one
        if verdict.state == "unknown" and rivals:
            verdict = Runs("unknown", f"'{controller.name}' is one of {len(rivals) + 1} "
                                      f"controllers for these joints ({', '.join(sorted({r.name for r in rivals})[:3])}, ...), and no "
                                      "launch file of the robot says which starts; none fits the "
                                      "robot as checked")
        joints = ", ".join(dict.fromkeys(ref.name for ref, _, _ in mismatches))
        ref, missing, has_set = mismatches[0]
        has = ", ".join(sorted(has_set)) or "no command interface (read-only)"
        yield controller.file.at(controller.line), Conditional(
            f"{_if_started(controller, verdict)}, it commands {'/'.join(missing)} on {joints}, "
            f"where {ref.name} offers {has}; {_interface_fix(controller, has_set, missing)}")


def _offered(robot, controller: Controller) -> dict[str, set]:
    """Joint name -> the command interfaces it offers to ``controller``: the one owner of that
    fact for U603 and U604. A ROS 2 controller gets what the joints' ``<ros2_control>`` entries
    offer and nothing else (ros2_control reads no transmission outside ``<ros2_control>``: a
    stale URDF's ROS 1 transmissions offered naranjelio's JointTrajectoryController 'effort');
    a ROS 1 one (or one of no known version) the transmissions' and ``<ros2_control>``'s."""
    return ros2_command_interfaces(robot) if controller.ros == 2 else command_interfaces(robot)


def _offers(robot, controller: Controller, name: str) -> set | None:
    """The command interfaces joint ``name`` offers to ``controller`` (:func:`_offered`), None
    when not known (not a joint, not offered at all: U603's, or a transmission interface
    urdftool cannot read)."""
    unknown = robot.memo(_offers, lambda: {
        joint.name for t in transmissions(robot) for joint in transmission_joints(robot, t)
        if any(not interface_kind(i.text)[0] for i in joint.interfaces)})  # U503
    if name not in robot.joints:
        return None
    offered = _offered(robot, controller)
    if name in offered and (controller.ros == 2 or name not in unknown):
        return offered[name]
    return None


def _mismatches(robot, controller: Controller) -> list:
    """(joint reference, interfaces claimed and not offered, interfaces offered) for each joint
    ``controller`` claims an interface of that it does not offer."""
    claimed = controller.interfaces()
    if not claimed or controller.is_state:
        return []
    found = []
    for ref in _urdf_joints(robot, controller):
        has_set = _offers(robot, controller, ref.name)
        if has_set is None:
            continue
        missing = [c for c in claimed if c not in has_set]
        if missing:
            found.append((ref, missing, has_set))
    return found


def _commanding(controller: Controller) -> bool:
    return controller.layout != "moveit" and not controller.is_state and bool(controller.interfaces())


def _rivals(robot, controller: Controller) -> list[Controller]:
    """The other controllers of the robot's files that command one of ``controller``'s joints:
    alternatives, of which one runs at a time."""
    mine = {ref.name for ref in _urdf_joints(robot, controller)}
    return [other for other in controllers(robot) if other is not controller and _commanding(other)
            and mine & {ref.name for ref in _urdf_joints(robot, other)}]


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
    else:
        use = "change the controller"
    a = "an" if wanted[:1] in "aeiou" else "a"  # (an effort command interface)
    if controller.ros == 2:
        offer = f"{a} {wanted} command interface in its <ros2_control> joint"
    else:
        offer = (f"{wanted.capitalize()}JointInterface in its transmission, or {a} {wanted} "
                 "command interface in <ros2_control>")
    if known and known.package == "diff_drive_controller":
        return f"diff_drive_controller turns its wheels by {wanted}: make the joint offer {wanted} ({offer})"
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
    lists are not counted: MoveIt does not publish joint states. A launch file of the robot
    that starts one (from a file of another package), or that starts joint_state_publisher,
    counts; a controller no launch file of the robot starts is not counted.

    Bad: only ``head_controller`` in the YAML
    Good: add ``joint_state_broadcaster: {type: joint_state_broadcaster/JointStateBroadcaster}``
    """
    found = [c for c in controllers(robot) if c.layout != "moveit"
             and runs_of(robot, c).state != "never"]
    facts = runtime(robot)
    if any("joint_state" in spawn.name for spawn in facts.spawns):
        return  # a launch file starts one, from a file the robot is not checked with
    if any(start.package in STATE_PUBLISHERS for c in facts.described for start in c.started):
        return  # a launch file of the robot publishes the joint states itself
    if found and not any(c.is_state for c in found):
        first = found[0]
        # one declared that no launch file starts (giacomotambe/traquad_gazebo's
        # joint_state_broadcaster_1): starting it is the fix, not adding one
        idle = [c for c in controllers(robot) if c.layout != "moveit" and c.is_state]
        fix = (f"{label(idle[0])} is declared, but no launch file of the robot starts it: "
               "spawn it" if idle else "add joint_state_broadcaster/JointStateBroadcaster "
               "(ROS 2) or joint_state_controller/JointStateController (ROS 1)")
        yield first.file.at(first.line), (
            f"no joint state broadcaster/controller among {len(found)} controllers in "
            f"{', '.join(sorted({c.file.display for c in found}))}; {fix}")


_ROS = {1: "ROS 1 (ros_control)", 2: "ROS 2 (ros2_control)"}


def _version_reason(controller: Controller) -> str:
    return ("the file has ros__parameters, so it is a ROS 2 parameter file" if controller.ros == 2
            else "the file has no ros__parameters, so it is a ROS 1 (rosparam) file")


@rule("U606", "controller-unknown-class", Severity.ERROR)
def controller_unknown_class(robot):
    """A controller's ``type`` is not a class of its controller manager's ROS version.

    The controller manager cannot load it ("Loader for controller 'x' not found").
    A class only ROS 2 distributions past their end of life export
    (``joint_state_controller/JointStateController``, Foxy's name of the joint state broadcaster
    and ROS 1's class) is a warning: it loads on Foxy only. Which distribution exports which
    class is read from ros2_controllers' plugin files (``urdftool/data/ros2_controllers.json``).
    A file with ``ros__parameters`` is read by ROS 2's controller_manager, any other by ROS 1's
    ros_control; each has its own classes (ROS 1's
    ``position_controllers/JointPositionController`` is ROS 2's
    ``position_controllers/JointGroupPositionController``). Classes are checked for the packages
    of ros_controllers and ros2_controllers (see the class table,
    ``urdftool/description/controller_classes.py``, with the plugin XML of each); a vendor's
    package is not, and a class a package of the repository exports (its package.xml's
    ``<export>`` names a plugin description with that class, as Pilz's
    ``position_controllers/PilzJointTrajectoryController``) is one the manager loads. MoveIt's simple controller manager knows ``FollowJointTrajectory`` and
    ``GripperCommand``.

    Bad: ``type: position_controllers/JointPositionController`` under ``ros__parameters``
    Good: ``type: position_controllers/JointGroupPositionController``
    """
    for controller in controllers(robot):
        if _substituted(controller.type, controller):
            continue
        if controller.layout == "moveit":
            if "type" in controller.params and controller.type not in MOVEIT_TYPES:  # (none: U812)
                yield controller.file.at(controller.where("type")), (
                    f"MoveIt controller '{controller.name}' has type '{controller.type}'; MoveIt's "
                    f"simple controller manager knows {' and '.join(MOVEIT_TYPES)}")
            continue
        if controller.cls is not None:
            retired = _end_of_life(controller)
            if retired:
                yield controller.file.at(controller.line), retired, None, Severity.WARNING
            continue
        if not known_package(controller.type) or controller.type in exported_classes(
                containment_root(controller.file.path.parent)):
            continue
        other = 3 - controller.ros
        if lookup(controller.type, other) is not None:
            instead = COUNTERPARTS.get((other, controller.type))
            message = (
                f"{controller.type} is a class of {_ROS[other]}, and {_version_reason(controller)}; "
                + (f"{_ROS[controller.ros]} has {instead}" if instead
                   else available('classes', controller.type, classes(controller.ros))))
        else:
            message = (f"{_ROS[controller.ros]} has no controller class '{controller.type}'; "
                       + available('classes', controller.type, classes(controller.ros)))
        message = hedged(robot, controller, message)
        if message is not None:
            yield controller.file.at(controller.line), message


def _end_of_life(controller: Controller) -> str | None:
    """Why a ROS 2 class only distributions past their end of life export is a problem."""
    from urdftool.description import controller_parameters as schema

    if controller.ros != 2:
        return None
    found = schema.ros2_class_distributions(controller.type)
    if not found or any(d not in schema.END_OF_LIFE for d in found):
        return None
    instead = COUNTERPARTS.get((2, controller.type))
    also = (f"; ROS 1 has a class of that name, and it is not ROS 2's" if lookup(controller.type, 1)
            else "")
    return (f"{controller.type} is a class of ROS 2 {' and '.join(d.capitalize() for d in found)} only "
            f"(end of life){also}: the controller manager of later distributions cannot load it"
            + (f"; use {instead}" if instead else ""))


@rule("U607", "controller-missing-parameter", Severity.ERROR)
def controller_missing_parameter(robot):
    """A controller lacks a parameter its class needs, or writes it under the other ROS's key.

    What a class needs is read from the controllers' own definitions (see
    :mod:`urdftool.description.controller_parameters`): a ros2_controllers parameter without a
    default, or whose default its own validation refuses (``joints: []`` with ``size_gt``), in
    every ROS 2 distribution that has the class; what ROS 1's ros_controllers refuse to start
    without (``publish_rate`` of joint_state_controller, the ``pid`` or ``gains/JOINT`` of a
    controller closing a loop in software); and the checks the controllers' code makes beyond
    that (forward_command_controller's ``joints``). ROS 2 controllers read their parameters
    from their own ``NAME: ros__parameters:`` block (or a ``/**`` block); a controller declared
    in the controller_manager without one has none. ROS 2's classes read ``joints:`` (a list)
    where ROS 1's single-joint controllers read ``joint:``.

    An error when the controller is started; a warning saying "if it is started" while that
    is not known (a controller file is often a menu).

    Bad: ``joint_state_controller: {type: joint_state_controller/JointStateController}``
    (ROS 1, no ``publish_rate``); ``head_controller: {type:
    position_controllers/JointPositionController, joints: [head]}``
    Good: ``publish_rate: 50``; ``joint: head``
    """
    from urdftool.description import controller_parameters as schema

    blocks = {block.name for read in controller_files(robot) for block in read.blocks}
    flat = {name for read in controller_files(robot) for name in _flat_blocks(read)}
    for controller in controllers(robot):
        if controller.layout == "moveit":
            continue
        known = controller.cls
        needed = dict.fromkeys(known.required if known else ())
        needed.update(schema.required(controller.type, controller.ros, controller.own))
        if known is None and not needed:
            continue
        severity, condition = if_started(robot, controller, "it fails to configure")
        if severity is None:
            continue
        params = controller.params or {}
        if controller.layout == "ros2" and controller.block_line is None and controller.name not in blocks:
            if needed and controller.name not in flat:  # a block without ros__parameters: U633
                yield controller.file.at(controller.line), (
                    f"{label(controller)} is declared but has no '{controller.name}: "
                    f"ros__parameters:' block, and {controller.type.split('/')[-1]} needs "
                    f"{', '.join(n for n in needed if '__map_' not in n)}; add the block; {condition}"), \
                    None, severity
            continue
        misplaced = set()
        for key, shape in (known.joints.items() if known else ()):
            other = {"joints": "joint", "joint": "joints"}.get(key)
            if key not in params and other in params and other not in known.joints:
                misplaced.add(key)
                reads = ("joints: (a list)" if key == "joints" else "joint: (one name)")
                yield controller.file.at(controller.where(other)), (
                    f"{label(controller)}: {_ROS[controller.ros]}'s {known.name} reads {reads}; "
                    f"its {other}: is ignored; write {key}: instead; {condition}"), None, severity
        missing = [name for key in needed if key not in misplaced
                   for name in schema.expand(key, params) if schema.lookup(params, name) is None]
        if missing:
            yield controller.file.at(controller.block_line or controller.line), (
                f"{label(controller)} has no {', '.join(missing)}; {controller.type} does not "
                "configure without " + ("it" if len(missing) == 1 else "them") + f"; {condition}"), \
                None, severity


def _flat_blocks(read) -> list[str]:
    """Top-level keys of a ROS 2 file that hold parameters without ros__parameters (U633)."""
    data = read.file.data
    if not read.file.ros2 or not isinstance(data, dict):
        return []
    return [str(key) for key, value in data.items()
            if isinstance(value, dict) and "ros__parameters" not in value]


_CONTROLLER_PARAMETERS = ("joints", "joint", "interface_name", "command_interfaces",
                          "left_wheel_names", "right_wheel_names")


@rule("U608", "controller-parameters-not-declared", Severity.WARNING)
def controller_parameters_not_declared(robot):
    """A ROS 2 controller's parameter block names no controller the controller_manager declares.

    ``arm_controler: ros__parameters: {joints: ...}`` beside a controller_manager that declares
    ``arm_controller`` configures nothing: the controller starts without its joints. Checked
    when one of the robot's controller files declares controllers in a controller_manager.

    Bad: ``head_controler: ros__parameters:`` when the manager declares ``head_controller``
    Good: the same name in both places
    """
    declared = {c.name for c in controllers(robot) if c.layout == "ros2"}
    if not declared:
        return
    for read in controller_files(robot):
        for block in read.blocks:
            if block.name in declared or block.name in ("*", "**", "controller_manager"):
                continue
            if any(key in block.params for key in _CONTROLLER_PARAMETERS):
                yield read.file.at(block.line), (
                    f"'{block.name}: ros__parameters:' configures a controller no controller_manager "
                    "declares; " + available('controllers', block.name, declared))


_CONSTRAINT_SETTINGS = ("goal_time", "stopped_velocity_tolerance")
_RATES = ("state_publish_rate", "action_monitor_rate")


@rule("U609", "trajectory-controller-settings", Severity.ERROR)
def trajectory_controller_settings(robot):
    """A joint trajectory controller's settings contradict its joints or themselves.

    Checked for joint_trajectory_controller (ROS 2) and ``*_controllers/JointTrajectoryController``
    (ROS 1): a ROS 2 ``state_interfaces`` entry the joint's ``<ros2_control>`` entry does not
    offer; ``constraints`` naming a joint the controller does not command, a **warning**: the
    controller reads constraints for its own joints only and ignores the entry (a leftover of
    another configuration, or a misspelt joint, which then goes without its tolerance), as a
    plugin ignores a parameter it does not read (U641). ROS 1 (whose parameters are declared nowhere): a joint listed twice;
    ``constraints.goal_time`` below 0; ``state_publish_rate`` or ``action_monitor_rate`` not
    above 0 (the controller refuses to configure). ROS 2 declares these limits with the
    parameters: U631 checks them against ros2_controllers' own definitions.

    Bad: ``constraints: {elbw: {goal: 0.1}}`` for ``joints: [shoulder, elbow]``
    Good: ``constraints: {elbow: {goal: 0.1}}``
    """
    for controller in controllers(robot):
        if controller.cls is None or not controller.type.endswith("/JointTrajectoryController"):
            continue
        for where, message, severity in _trajectory_problems(robot, controller):
            message = hedged(robot, controller, message)
            if message is not None:
                yield where, message, None, severity


def _trajectory_problems(robot, controller: Controller):
    """(where, message, severity: None for the rule's own) for each contradiction in a
    trajectory controller's settings."""
    states = ros2_state_interfaces(robot)
    params, at = controller.params or {}, controller.file.at
    joints = [ref for ref in controller.joints() if ref.key == "joints"]
    names = dict.fromkeys(ref.name for ref in joints)  # (in order; a search of the names
    # before each joint was quadratic: 40,000 joints took 13 s of a check)
    declared = controller.ros == 2  # ROS 2 declares the limits below: U631
    seen: set = set()
    for ref in joints:
        if ref.name in seen and not declared:
            yield at(ref.line), f"{label(controller)} lists joint '{ref.name}' twice; keep one", None
        seen.add(ref.name)
    constraints = params.get("constraints")
    if isinstance(constraints, dict):
        for key, value in constraints.items():
            where = at(constraints.lines.get(key, controller.line))
            if key == "goal_time":
                if _number(value) is not None and _number(value) < 0 and not declared:
                    yield where, (f"{label(controller)}: constraints.goal_time is {value}; it "
                                  "must be 0 or more (0: no limit)"), None
            elif key not in _CONSTRAINT_SETTINGS and isinstance(value, dict) and key not in names \
                    and not _substituted(str(key)):
                yield where, (f"{label(controller)}: constraints name '{key}', which is not one "
                              "of its joints, so the controller ignores them; "
                              + available('joints', str(key), names)), Severity.WARNING
    for key in () if declared else _RATES:
        value = _number(params.get(key))
        if value is not None and value <= 0:
            yield at(controller.where(key)), (f"{label(controller)}: {key} is {params[key]}; "
                                               "it must be above 0 [Hz]"), None
    claimed = params.get("state_interfaces")
    if controller.ros == 2 and isinstance(claimed, list):
        for interface in dict.fromkeys(str(c) for c in claimed):
            lacking = [name for name in dict.fromkeys(names)
                       if name in states and interface not in states[name]]
            if lacking:
                yield at(controller.where("state_interfaces")), (
                    f"{label(controller)} reads state interface {interface} of "
                    f"{', '.join(lacking)}, which <ros2_control> does not offer there; add "
                    f"<state_interface name=\"{interface}\"/> to "
                    f"{'that joint' if len(lacking) == 1 else 'those joints'} or drop it "
                    "from state_interfaces"), None


def _number(value) -> float | None:
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        return None
    try:
        return float(value)
    except ValueError:
        return None


@rule("U610", "joint-commanded-twice", Severity.INFO)
def joint_commanded_twice(robot):
    """Two controllers command the same interface of one joint.

    The controller manager activates only one of them at a time (ROS 2: "resource conflict";
    ROS 1: a claimed resource): a configuration may offer both (a trajectory controller and a
    forward command controller on the arm) and start one. Which are started is up to the
    launch files, so this is a note when no launch file of the robot says: make sure the two
    are never spawned active together. When the launch files say, U619 reports the two they
    start together, and nothing is said of two they never start together.

    Bad: ``arm_controller`` and ``arm_position_controller`` both active on ``joints: [shoulder]``
    Good: spawn one active and the other ``--inactive``
    """
    for controller, other, line, joints in shared_commands(robot, by_interface=True):
        if together(robot, other, controller, parameter_files(robot))[0] != "unknown":
            continue
        yield controller.file.at(line), (
            f"{label(controller)} commands {', '.join(joints)} through the same interfaces as "
            f"{label(other)}; only one of them can be active at a time")


def _short(controller: Controller) -> str:
    return controller.name.strip("/").split("/")[-1]


def shared_commands(robot, by_interface: bool):
    """(controller, an earlier one, the line of the first joint shared, the joints shared) for
    each two controllers commanding one joint: through the same interface (``by_interface``),
    or at all (ROS 1's controller manager refuses two controllers claiming one joint whatever
    their interfaces)."""
    first: dict[tuple, Controller] = {}
    for controller in controllers(robot):
        claimed = controller.interfaces()
        if controller.layout == "moveit" or controller.is_state or not claimed:
            continue
        shared: dict[int, tuple] = {}  # the earlier controller -> (it, first line, joints shared)
        for ref in _urdf_joints(robot, controller):
            for interface in (claimed if by_interface else ["*"]):
                other = first.setdefault((ref.name, interface), controller)
                # one name is one controller: a second file's mapping of it is merged into
                # the same parameters (ROS 1), or is the same controller's (ROS 2)
                if other is not controller and _short(other) != _short(controller):
                    entry = shared.setdefault(id(other), (other, ref.line, []))
                    if ref.name not in entry[2]:
                        entry[2].append(ref.name)
        for other, line, joints in shared.values():
            yield controller, other, line, joints
