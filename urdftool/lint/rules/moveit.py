"""U812-U818: MoveIt's YAML beside the SRDF (kinematics.yaml, joint_limits.yaml, the controller
list) against the SRDF, the URDF and the ros_control controllers.

The files are found in the SRDF's folder (see :mod:`urdftool.description.companions`); MoveIt's
controller list is also read from the controller YAML the robot is checked with.
"""

from __future__ import annotations

from pathlib import Path

from urdftool.description import moveit_config as moveit
from urdftool.description.documents import read_srdf
from urdftool.description.files import listing
from urdftool.description.companions import companions
from urdftool.description.urdf import LIMITED, MOVING
from urdftool.description.values import limit_value
from urdftool.errors import available
from urdftool.description.runtime import moveit_action_remaps, moveit_execution
from urdftool.lint.catalogue import Conditional, Severity, rule
from urdftool.lint.rules.srdf import as_moveit_runs
from urdftool.numbers import decimal_slip

TOLERANCE = 1e-9  # relative, so that a value copied from the URDF with all its digits passes


def _kinematics(robot):
    """(kinematics.yaml, its entries, its problems), read once per robot."""
    file = companions(robot).kinematics
    return robot.memo(_kinematics, lambda: (file, *moveit.kinematics(file)) if file is not None
                      else (None, [], []))


def _limits(robot):
    """(MoveIt's joint_limits.yaml, its entries, its problems), read once per robot."""
    file = companions(robot).planning_limits
    return robot.memo(_limits, lambda: (file, *moveit.planning_limits(file)) if file is not None
                      else (None, [], []))


def _controller_files(robot):
    found = companions(robot)
    return [*found.controllers, *found.moveit_controllers]


def _moveit_controllers(robot):
    def read():
        entries, problems = [], []
        for file in _controller_files(robot):
            listed, bad = moveit.moveit_controllers(file)
            entries += listed
            problems += [(file, line, message) for line, message in bad]
        return entries, problems
    return robot.memo(_moveit_controllers, read)


def _srdf_groups(robot):
    srdf = companions(robot).srdf
    if srdf is None or srdf.root is None:
        return None
    from urdftool.kinematics.groups import groups, tree

    return srdf, tree(robot, srdf.root), groups(robot, srdf.root)


@rule("U812", "malformed-moveit-config", Severity.ERROR)
@as_moveit_runs
def malformed_moveit_config(robot):
    """MoveIt's kinematics.yaml, joint_limits.yaml or controller list is malformed.

    A YAML syntax error, a wrong layout, a misspelt key or a value of the wrong kind: MoveIt
    cannot read the file as meant.

    Reported at the line of the key (or where YAML failed). MoveIt ignores a key it does not
    know (``max_velocty``), and with ``has_velocity_limits: true`` and no ``max_velocity`` it
    plans without the limit the file meant to set.

    MoveIt's controller list is read wherever it is, beside the SRDF or in the controller YAML
    the robot is checked with, as moveit_simple_controller_manager reads it (see
    :func:`urdftool.description.moveit_config.moveit_controllers`): MoveIt skips a controller
    that lacks ``action_ns``, ``type`` or a ``joints:`` list of names (MoveIt 2: a non-empty
    one), or that ``controller_names`` lists without its mapping beside the list; it reads no
    list that is not a list. A note when the file names a ``moveit_controller_manager`` that
    reads no list (moveit_ros_control_interface's, which asks the controller manager). A
    ``type`` MoveIt does not know is U606's.

    Bad: ``kinematics_solver_timeout: fast``; ``max_velocty: 1.0``;
    ``controller_names: [arm_controller]`` without an ``arm_controller:`` block
    Good: ``kinematics_solver_timeout: 0.005``; ``max_velocity: 1.0``
    """
    read = []
    for file, _, problems in (_kinematics(robot), _limits(robot)):
        read.append(file)
        for line, message in problems:
            yield file.at(line), message
    for file, line, message in _moveit_controllers(robot)[1]:
        plugin = moveit.controller_manager(file)
        if plugin is not None and not moveit.reads_list(plugin[0]):
            message = Conditional(f"{file.display} names moveit_controller_manager {plugin[0]} "
                                  "(which asks the controller manager and reads no list); if "
                                  "MoveIt's simple controller manager is given it: " + message,
                                  Severity.INFO)
        yield file.at(line), message
    beside_srdf = companions(robot).moveit_controllers
    for file in beside_srdf:
        if file.problem:
            yield file.at(file.line), file.problem
    for file in (*read, *beside_srdf):
        if file is not None and file.problem is None and file.caution:  # (a ROS 2 parameter
            yield file.at(file.line), Conditional(file.caution)  # file PyYAML cannot read)


@rule("U813", "kinematics-unknown-group", Severity.ERROR)
@as_moveit_runs
def kinematics_unknown_group(robot):
    """kinematics.yaml configures a group that the SRDF does not define.

    MoveIt looks up a solver for each SRDF group by name and ignores other entries: the group
    meant (often a misspelt name) gets no IK solver and cannot be planned to a pose.

    A group that another SRDF beside the checked one defines is a note: one kinematics.yaml
    serves the package's SRDFs, which its launch files choose between (a cell's left and right
    robots), and MoveIt given this SRDF ignores the other's entry.

    Bad: ``left_am: {kinematics_solver: kdl_kinematics_plugin/KDLKinematicsPlugin}``
    Good: ``left_arm:``, the SRDF's ``<group name="left_arm">``
    """
    file, entries, _ = _kinematics(robot)
    found = _srdf_groups(robot)
    if file is None or found is None:
        return
    names = {element.get("name") for element in found[0].root.iterfind("group")}
    for entry in entries:
        if entry.group not in names and str(entry.group).startswith("/"):  # a node pattern
            yield file.at(entry.line), (
                f"kinematics.yaml wraps its groups in '{entry.group}: ros__parameters:' without "
                "robot_description_kinematics: MoveItConfigsBuilder loads the file as it is (its "
                f"group is then '{entry.group}'), and a node given it reads no "
                "robot_description_kinematics.GROUP: the SRDF's groups "
                f"({', '.join(sorted(n for n in names if n))}) get no IK solver; write the groups at "
                "the top of the file")
        elif entry.group not in names and entry.group in (beside := _groups_beside(robot, found[0])):
            yield file.at(entry.line), Conditional(
                f"kinematics.yaml configures group '{entry.group}', which this SRDF does not "
                f"define but {beside[entry.group]} beside it does: one kinematics.yaml serves "
                "both, and MoveIt given this SRDF ignores the entry", Severity.INFO)
        elif entry.group not in names:
            yield file.at(entry.line), (f"kinematics.yaml configures group '{entry.group}', which "
                                        "the SRDF does not define; " + available('groups', entry.group, names))


def _groups_beside(robot, srdf) -> dict:
    """Group name -> the other SRDF (shown) in the checked SRDF's folder that defines it."""
    def read():
        found = {}
        folder = Path(srdf.path).parent
        for name, kind in listing(folder, "*.srdf"):
            path = folder / name
            other = read_srdf(path) if kind == "file" and path != Path(srdf.path) else None
            for group in other.root.iterfind("group") if other is not None and other.root is not None else ():
                found.setdefault(group.get("name"), other.display)
        return found
    return robot.memo(_groups_beside, read)


@rule("U814", "kinematics-group-not-chain", Severity.ERROR)
@as_moveit_runs
def kinematics_group_not_chain(robot):
    """A group solved by KDL (or LMA) is not one serial chain.

    MoveIt's KDL plugin (``kdl_kinematics_plugin/KDLKinematicsPlugin``, the Setup Assistant's
    default) solves only a group whose joints form one unbranched path down the tree, each with
    one variable; otherwise it refuses the group ("Group 'x' is not a chain") or solves the
    wrong chain. Reported, naming the links involved:

    - a chain written backwards (its base below its tip) or across two branches (the tip does
      not descend from the base): at the ``<chain>``;
    - a gap (a moving joint of the path left out of a joint or link list): at the ``<group>``;
    - a tree (the group branches, e.g. both arms), a floating or planar joint, or no moving
      joint: at the group's kinematics.yaml entry (pick another solver, or split the group).

    A link in a group stands for its parent joint, a chain for the joints from its tip up to
    its base, a subgroup for its joints (as MoveIt builds groups). A group with an unknown
    member is left to U803-U805; a group without ``kinematics_solver`` has no solver in MoveIt
    and is not checked.

    Bad: ``<chain base_link="tool0" tip_link="base_link"/>`` with KDL
    Good: ``<chain base_link="base_link" tip_link="tool0"/>``
    """
    file, entries, _ = _kinematics(robot)
    found = _srdf_groups(robot)
    if file is None or found is None:
        return
    from urdftool.kinematics.groups import serial_problems

    srdf, model, groups = found
    for entry in entries:
        group = groups.get(entry.group)
        if entry.solver not in moveit.CHAIN_SOLVERS or group is None or not group.complete:
            continue
        solver = entry.solver.split("/")[-1]
        for shape in serial_problems(model, group, robot.links):
            at_entry = shape.kind in ("tree", "multi-dof", "empty")
            where = file.at(entry.solver_line) if at_entry else srdf.at(shape.element.sourceline)
            said = "" if at_entry else f" (kinematics.yaml line {entry.solver_line})"
            yield where, (f"group '{group.name}' is solved by {solver}{said} but is not one "
                          f"serial chain: {shape.message}")


@rule("U815", "moveit-limits-unknown-joint", Severity.WARNING)
@as_moveit_runs
def moveit_limits_unknown_joint(robot):
    """MoveIt's joint_limits.yaml sets limits for a joint the URDF does not have.

    MoveIt reads limits only for the robot's joints: the entry (often a misspelt or renamed
    joint) is ignored and the joint meant keeps the URDF's limits.

    Bad: ``joint_limits: {elbw: {has_velocity_limits: true, max_velocity: 1.0}}``
    Good: ``elbow:``
    """
    file, entries, _ = _limits(robot)
    for entry in entries:
        if entry.joint not in robot.joints:
            yield file.at(entry.line), (f"joint_limits.yaml sets limits for joint '{entry.joint}', "
                                        "which is not in the URDF; " + available('joints', entry.joint, robot.joints))


@rule("U816", "moveit-limits-exceed-urdf", Severity.ERROR)
@as_moveit_runs
def moveit_limits_exceed_urdf(robot):
    """MoveIt's joint_limits.yaml allows more than the URDF's ``<limit>``.

    A higher ``max_velocity`` or ``max_effort``, or a position range beyond ``lower``/``upper``.

    MoveIt plans with the YAML's limits, so it produces trajectories the controllers and the
    hardware reject (or that drive the joint into its stop). The YAML may only tighten the
    URDF's limits. Only limits switched on (``has_velocity_limits: true``, ...) count.

    A value that is the URDF's rounded to the decimals it is written with (2.53073 for
    2.5307274) is the same limit. A URDF velocity or effort of 0 or less is no limit to keep
    under (a CAD exporter's placeholder, which U212 reports; the YAML is where such robots
    give the real one: AuboRobot's aubo_i5L.urdf).

    Bad: ``max_velocity: 3.0`` for a joint with ``<limit velocity="2.0" .../>``
    Good: ``max_velocity: 2.0`` or less
    """
    file, entries, _ = _limits(robot)
    for entry in entries:
        joint = robot.joints.get(entry.joint)
        if joint is None or joint.get("type") not in MOVING:
            continue
        checks = [("max_velocity", "velocity", 1), ("max_effort", "effort", 1)]
        if joint.get("type") in LIMITED:
            checks += [("max_position", "upper", 1), ("min_position", "lower", -1)]
        for key, attribute, sign in checks:
            mine, urdf = entry.values.get(key), limit_value(joint, attribute)
            if mine is None or urdf is None or attribute in ("velocity", "effort") and urdf <= 0:
                continue
            if sign * (mine - urdf) > TOLERANCE * max(1.0, abs(urdf)) and not _rounded(mine, urdf):
                what, bound = ("above", "at most") if sign > 0 else ("below", "at least")
                yield file.at(entry.lines[key]), (
                    f"joint '{entry.joint}': MoveIt's {key} {mine:g} is {what} the URDF's "
                    f"<limit {attribute}=\"{urdf:g}\">, so MoveIt would plan beyond what the "
                    f"joint allows; use {bound} {urdf:g}" + decimal_slip(sign * mine, sign * urdf))


def _rounded(written: float, urdf: float) -> bool:
    """Whether ``written`` is ``urdf`` rounded to the decimals it is written with: MoveIt's
    Setup Assistant writes 2.53073 for a URDF's ${radians(145)} (2.5307274...)."""
    text = repr(written)
    if "e" in text or "." not in text:
        return False
    return round(urdf, len(text.split(".")[1])) == written


def _ros_control(robot, ros: int) -> dict[str, set[str]]:
    """The ros_control controllers a MoveIt of ROS ``ros`` meets (MoveIt 2's list is served by
    ros2_control's controllers, MoveIt 1's by ros_control's), by name, with their joints."""
    return robot.memo_for(_ros_control, ros, lambda: moveit.ros_control_controllers(
        _controller_files(robot), ros))


def _remaps(robot, entry) -> list:
    """The launch files' remaps of the action MoveIt sends ``entry``'s trajectories to
    (:func:`~urdftool.description.runtime.moveit_action_remaps`)."""
    action = f"{entry.name.strip('/')}/{entry.action_ns or ''}".strip("/")
    return moveit_action_remaps(robot, entry.file.path, f"/{action}" if not entry.name.strip("/")
                                else action)


def _target(remap) -> str:
    """The remap's target as a message names it, and its condition."""
    if remap.target is None:
        target = "a name urdftool cannot read"
    else:
        target = f"'{remap.target}'" + (", named by launch arguments" if remap.controller is None
                                       else "")
    return target + (f"; {remap.condition}" if remap.condition else "")


@rule("U817", "moveit-controller-unknown", Severity.ERROR)
def moveit_controller_unknown(robot):
    """MoveIt's controller list names a controller that ros_control does not declare.

    MoveIt sends each trajectory to ``<name>/<action_ns>``; with no such controller running,
    execution fails ("Action client not connected"). Checked only when ros_control controllers
    are declared in the YAML the robot is checked with (a namespace before the name is ignored),
    of MoveIt's ROS: MoveIt 2's ``controller_names`` against ROS 2 parameter files, MoveIt 1's
    ``controller_list`` against the others.

    A MoveIt configuration is often written for the real robot, whose driver serves the
    trajectory action itself (ur_robot_driver's scaled_pos_joint_traj_controller, kortex_driver's
    own action server), while the ros_control YAML beside it is the simulation's. So this is an
    error only when a launch file of the robot starts MoveIt with this list and ros_control with
    those controllers, and nothing else that could serve the action (a node of another package
    than ROS's own); nothing when every launch file starting MoveIt with this list starts such a
    node beside it (aubo_driver's trajectory action); a warning naming the condition otherwise.
    An entry with an empty name is a driver's by construction (MoveIt then sends to
    ``/<action_ns>``, motoman_driver's ``joint_trajectory_action``, where a ros_control
    controller never serves: its action is ``<controller>/follow_joint_trajectory``): nothing.
    A launch file starting MoveIt may remap the action to a ros_control controller's (xArm's
    Gazebo launch: ``<remap from="/follow_joint_trajectory" to="/xarm/xarm7_traj_controller/
    follow_joint_trajectory"/>`` before move_group; ROS 2's ``remappings``): nothing when it
    does so on every run; a warning naming the condition when only with some launch arguments
    (an ``if=``, a target read from an argument), or to a name not known without running it.

    Bad: ``controller_list: [{name: arm_controller, ...}]`` when ros_control declares
    ``arm_trajectory_controller``
    Good: the same name in both
    """
    for entry in _moveit_controllers(robot)[0]:
        declared = _ros_control(robot, entry.ros)
        name = entry.name.strip("/").split("/")[-1]
        if not name or not declared:  # MoveIt sends to ``/<action_ns>`` itself: a driver's
            continue
        if name not in declared:
            message = (f"MoveIt controller '{entry.name}' is not a ros_control controller of this "
                       "robot; " + available('controllers', name, declared))
            remaps = _remaps(robot, entry)
            if any(r.certain and r.controller in declared for r in remaps):
                continue  # a launch file remaps MoveIt's action to a served controller's
            who, where = moveit_execution(robot, entry.file.path)
            if who == "other":
                continue  # a launch file starts MoveIt with it beside the driver serving it
            remap = next((r for r in remaps if r.controller in declared or r.controller is None),
                         None)
            if remap is not None:  # served by a remap with some launch arguments only
                message = Conditional(
                    f"unless {remap.written} remaps MoveIt's action to a ros_control "
                    f"controller's ({_target(remap)}): " + message)
            elif who == "unknown":
                message = Conditional(
                    f"if MoveIt executes through the ros_control controllers the robot is checked "
                    f"with (a driver may serve '{entry.name}' with its own action server; no "
                    f"launch file of the robot starts MoveIt with them alone): " + message)
            else:
                message = f"{where} starts MoveIt with this list and ros_control: " + message
            yield entry.file.at(entry.line), message


@rule("U818", "moveit-controller-joints", Severity.ERROR)
@as_moveit_runs
def moveit_controller_joints(robot):
    """A MoveIt controller lists other joints than the ros_control controller of that name.

    MoveIt splits a trajectory by the joints it believes each controller has; the controller
    rejects a goal naming joints it does not control, and joints it controls but MoveIt does not
    list are never commanded. For a ``GripperCommand`` controller (gripper_action_controller
    takes one ``joint:``) the ros_control joint need only be among MoveIt's.

    An error when a launch file of the robot starts MoveIt with this list and ros_control
    with that controller (and nothing else that could serve the action, as for U817); a
    warning naming the condition otherwise. When a launch file starting MoveIt remaps the
    entry's action to another ros_control controller's (U817), that controller's joints are
    compared, with the remap's condition when it has one.

    Bad: MoveIt ``joints: [j1, j2, j3]`` for a controller with ``joints: [j1, j2]``
    Good: the same joints (in any order)
    """
    for entry in _moveit_controllers(robot)[0]:
        declared = _ros_control(robot, entry.ros)
        name = entry.name.strip("/").split("/")[-1]
        remap = next((r for r in _remaps(robot, entry) if r.controller in declared), None) \
            if declared else None
        if remap is not None and remap.controller != name:
            name = remap.controller  # MoveIt's action reaches that controller
        else:
            remap = None
        theirs = declared.get(name)
        if not theirs:
            continue
        mine = {joint for joint, _ in entry.joints}
        gripper = entry.type == "GripperCommand"
        if (theirs <= mine) if gripper else (theirs == mine):
            continue
        missing, extra = sorted(theirs - mine), sorted(mine - theirs)
        parts = ([f"lacks {', '.join(missing)}"] if missing else []) + \
                ([f"adds {', '.join(extra)}"] if extra and not gripper else [])
        whose = f"ros_control controller '{name}' it is remapped to" if remap \
            else "ros_control controller"
        message = (f"MoveIt controller '{entry.name}' {' and '.join(parts)} compared with the "
                   f"joints of the {whose} ({', '.join(sorted(theirs))})")
        who, _ = moveit_execution(robot, entry.file.path)
        if who == "other":
            continue
        if remap is not None and not remap.certain:
            message = Conditional(f"when {remap.written} remaps MoveIt's action to "
                                  f"{_target(remap)}: " + message)
        elif remap is not None:
            message = f"{remap.written} remaps MoveIt's action to '{remap.target}': " + message
        elif who == "unknown":
            message = Conditional(f"if MoveIt executes through the ros_control controller of that "
                                  f"name the robot is checked with (a driver may serve "
                                  f"'{entry.name}' itself): " + message)
        yield entry.file.at(entry.joints_line), message


@rule("U819", "kinematics-solver-unknown", Severity.ERROR)
def kinematics_solver_unknown(robot):
    """kinematics.yaml names a solver plugin that is a near miss of a known one.

    MoveIt loads the solver by its plugin name; a misspelt one fails ("According to the loaded
    plugin descriptions the class ... does not exist") and the group gets no IK solver. Known
    names: moveit_kinematics' (``kdl_kinematics_plugin/KDLKinematicsPlugin``,
    ``lma_kinematics_plugin/LMAKinematicsPlugin``, ``srv_kinematics_plugin/SrvKinematicsPlugin``,
    the ``cached_ik_kinematics_plugin`` ones), ``trac_ik_kinematics_plugin/TRAC_IKKinematicsPlugin``,
    ``bio_ik/BioIKKinematicsPlugin``, ``pick_ik/PickIkPlugin``, and any
    ``PACKAGE/IKFastKinematicsPlugin`` (generated per robot). A name of a known package with
    another class, or close to a known name, is reported; another vendor's plugin is not.

    Bad: ``kinematics_solver: kdl_kinematics_plugin/KDLKinematicPlugin``
    Good: ``kinematics_solver: kdl_kinematics_plugin/KDLKinematicsPlugin``
    """
    from urdftool.errors import close_names

    file, entries, _ = _kinematics(robot)
    packages = {name.split("/")[0] for name in moveit.SOLVERS}
    for entry in entries:
        solver = entry.solver
        if solver is None or solver in moveit.SOLVERS or solver.endswith(f"/{moveit.IKFAST}"):
            continue
        close = close_names(solver, moveit.SOLVERS, n=1, cutoff=0.8)
        if close or solver.split("/")[0] in packages:
            hint = (f"did you mean '{close[0]}'?" if close else
                    available("solvers", solver, moveit.SOLVERS))
            yield file.at(entry.solver_line), (
                f"group '{entry.group}': kinematics solver '{solver}' is no plugin MoveIt can load, so "
                "the group has no IK solver; " + hint)


def _ros_control_by_name(robot) -> dict:
    """The ros_control controllers (the controller model's), by name."""
    from urdftool.description.controllers import controllers

    found: dict = {}
    for controller in controllers(robot):
        if controller.layout != "moveit":
            found.setdefault(controller.name, []).append(controller)
    return found


def _entry_namespace(entry) -> tuple[str, str]:
    """(namespace, name) of a MoveIt controller entry's name (``/robot1/arm_controller``)."""
    parts = [p for p in entry.name.split("/") if p]
    return "/".join(parts[:-1]), parts[-1] if parts else entry.name


@rule("U820", "moveit-controller-action", Severity.ERROR)
def moveit_controller_action(robot):
    """A MoveIt controller's ``action_ns`` or ``type`` is not the action its ros_control controller serves.

    MoveIt sends goals to ``NAME/ACTION_NS``: joint_trajectory_controller serves
    ``NAME/follow_joint_trajectory`` (type ``FollowJointTrajectory``), the gripper action
    controllers ``NAME/gripper_cmd`` (``GripperCommand``; ROS 2's parallel gripper controller
    ``ParallelGripperCommand``), in ROS 1 and ROS 2 alike. Another ``action_ns`` connects to
    nothing ("Action client not connected"); another type sends the wrong action. Checked
    for the controllers of ros_controllers/ros2_controllers MoveIt's list names. An error when
    the controller is started; a warning saying "if it is started" while that is not known.

    Bad: ``action_ns: joint_trajectory_action`` for a joint_trajectory_controller
    Good: ``action_ns: follow_joint_trajectory``
    """
    from urdftool.description.controller_classes import action_served
    from urdftool.lint.rules.controllers import if_started

    declared = _ros_control_by_name(robot)
    for entry in _moveit_controllers(robot)[0]:
        namespace, name = _entry_namespace(entry)
        for controller in declared.get(name, [])[:1]:
            served = action_served(controller.type)
            if served is None:
                continue
            kind, action = served
            wrong = []
            if entry.action_ns is not None and entry.action_ns.strip("/") != action:
                wrong.append((entry.action_line, f"action_ns '{entry.action_ns}'", f"action_ns: {action}"))
            if entry.type and entry.type != kind:
                wrong.append((entry.line, f"type '{entry.type}'", f"type: {kind}"))
            if not wrong:
                continue
            severity, condition = if_started(robot, controller, "MoveIt cannot execute through it")
            if severity is None:
                continue
            for line, what, right in wrong:
                yield entry.file.at(line), (
                    f"MoveIt controller '{entry.name}': {what}, but {controller.type} serves "
                    f"{name}/{action} ({kind}); write {right}; {condition}"), None, severity


@rule("U821", "moveit-controller-namespace", Severity.WARNING)
def moveit_controller_namespace(robot):
    """A MoveIt controller's name is in another namespace than the ros_control controller of that name.

    MoveIt resolves ``NAME/ACTION_NS`` in move_group's namespace. A ROS 1 controller YAML that
    nests its controllers under a namespace (``robot1: arm_controller: ...``) loads them
    there, and MoveIt's ``arm_controller`` reaches ``/robot1/arm_controller`` only when
    move_group runs in ``/robot1`` too; ``/robot1/arm_controller`` in MoveIt's list and a
    controller loaded at the top disagree the other way. Which namespaces the nodes run in is
    up to the launch files: a warning that states the condition.

    Bad: MoveIt ``name: arm_controller`` for ``robot1: arm_controller: {type: ...}``, move_group
    outside ``/robot1``
    Good: ``name: robot1/arm_controller``, or move_group in ``/robot1``
    """
    declared = _ros_control_by_name(robot)
    for entry in _moveit_controllers(robot)[0]:
        namespace, name = _entry_namespace(entry)
        found = declared.get(name, [])
        spaces = {c.namespace.strip("/") for c in found if c.layout == "ros1"}
        if not spaces or namespace in spaces:
            continue
        theirs = sorted(spaces)[0]
        mine = f"{namespace}/{name}" if namespace else name
        condition = (f"unless move_group runs in /{theirs}" if not namespace else
                     f"unless the two namespaces meet where the nodes run")
        yield entry.file.at(entry.line), (
            f"MoveIt controller '{entry.name}' is looked for as {mine} in move_group's namespace, and "
            f"the controller YAML puts '{name}' under '{theirs or '/'}': MoveIt does not reach it "
            f"{condition}; name it '{f'{theirs}/{name}' if theirs else name}' in MoveIt's list if "
            "move_group runs at the top")


def _with_geometry(robot) -> set:
    """The links with collision geometry: the ones MoveIt's collision matrix pairs."""
    return {name for name, link in robot.links.items() if link.find("collision/geometry") is not None}


@rule("U822", "srdf-adjacent-not-adjacent", Severity.WARNING)
@as_moveit_runs
def srdf_adjacent_not_adjacent(robot):
    """The SRDF disables a pair as ``Adjacent``, and the two links are not adjacent in the tree.

    The Setup Assistant writes ``reason="Adjacent"`` for links joined by a joint (or by a chain
    of joints through links without collision geometry), whose contact is expected. A pair
    that is not (the URDF changed since the SRDF was written, or the entry was copied from
    another robot) stays disabled under a false reason: MoveIt never checks it, and a real
    collision between the two is planned through. Said so when they also collide at the
    default pose or a group state (checked with FCL as U810 does).

    Bad: ``<disable_collisions link1="l_hand" link2="torso" reason="Adjacent"/>`` for a hand
    two joints away from the torso
    Good: no entry, or the reason the Setup Assistant gives on a fresh matrix
    """
    from urdftool.lint.rules.srdf import _overlaps, _srdf, _where

    srdf = _srdf(robot)
    entries = [e for e in srdf.root.iter("disable_collisions")
               if e.get("reason") == "Adjacent"] if srdf is not None else []
    if not entries:
        return
    from urdftool.kinematics.tree import adjacent_pairs, pair_key

    geometry = _with_geometry(robot)
    adjacent = adjacent_pairs(robot, geometry)
    found = None
    for element in entries:
        names = (element.get("link1", ""), element.get("link2", ""))
        pair = pair_key(*names)
        if any(name not in robot.links for name in names) or pair in adjacent:
            continue  # an unknown link: U804
        if not all(name in geometry for name in names):
            continue  # a link without collision geometry is in no pair MoveIt checks
        if found is None:
            found = _overlaps(robot, srdf) or {}
        overlap = found.get(pair)
        yield srdf.at(element.sourceline), (
            f"{pair[0]} and {pair[1]} are disabled as Adjacent but no joint joins them "
            f"({_path(robot, *pair)})" + (f", and they {_where(overlap)}" if overlap else "")
            + ": MoveIt never checks the pair; remove the entry, or give the reason a fresh "
            "collision matrix gives")


def _parents(robot) -> dict:
    """Child link -> (its joint, its parent link)."""
    from urdftool.kinematics.tree import children_by_link

    return {child: (joint, up) for up, children in children_by_link(robot).items()
            for joint, child in children}


def _path(robot, one: str, two: str) -> str:
    """The joints between two links, as words."""
    parent = robot.memo(_path, lambda: _parents(robot))  # once per robot, not per entry: an
    # SRDF of 100,000 false Adjacent entries built the tree 100,000 times (past the 60 s budget)

    def chain(link):
        found = [link]
        while found[-1] in parent and len(found) <= len(parent):
            found.append(parent[found[-1]][1])
        return found

    above_one, above_two = chain(one), chain(two)
    common = next((link for link in above_one if link in above_two), None)
    if common is None:
        return "they are in different trees"
    joints = above_one.index(common) + above_two.index(common)
    return f"{joints} joints apart" + ("" if common in (one, two) else f", through {common}")


@rule("U823", "srdf-adjacent-collision-not-disabled", Severity.WARNING)
@as_moveit_runs
def srdf_adjacent_collision_not_disabled(robot):
    """Two adjacent links overlap at the default pose or a group state, and the SRDF does not disable them.

    MoveIt checks every pair the SRDF does not disable, adjacent ones included: the Setup
    Assistant disables them as ``Adjacent``. Without the entry, links whose meshes overlap at
    the joint between them put the robot in collision there ("Start state appears to be in
    collision") and planning from it fails. Checked only when the robot has an SRDF, with FCL
    at the default configuration and each group state (as U811 for the other pairs).

    Fix (unsafe): add the entry MoveIt's Setup Assistant writes, ``reason="Adjacent"``, before
    ``</robot>``.

    Bad: ``upper_arm`` and ``forearm`` (joined by ``elbow``) overlapping at the elbow with no
    entry
    Good: ``<disable_collisions link1="forearm" link2="upper_arm" reason="Adjacent"/>``
    """
    from urdftool.lint.rules.srdf import _add_entry, _overlaps, _srdf, _where

    srdf = _srdf(robot)
    if srdf is None:
        return
    from urdftool.kinematics.tree import pair_key
    from urdftool.lint.fixes import offer

    listed = {pair_key(e.get("link1", ""), e.get("link2", "")) for e in srdf.root.iter("disable_collisions")}
    for pair, overlap in sorted((_overlaps(robot, srdf) or {}).items()):
        if not overlap.adjacent or pair in listed:
            continue
        element = overlap.poses[0][1]
        yield offer(srdf.at(element.sourceline if element is not None else srdf.root.sourceline), (
            f"{pair[0]} and {pair[1]} are adjacent and {_where(overlap)}, and the SRDF does not "
            "disable the pair: MoveIt reports the robot in collision there; add <disable_collisions "
            f"link1=\"{pair[0]}\" link2=\"{pair[1]}\" reason=\"Adjacent\"/>"),
            f"disable {pair[0]} and {pair[1]} as Adjacent", _add_entry(srdf, pair, "Adjacent"), safe=False)


_HOLDERS_NAMED = 5  # groups holding a cycle named in its message, at most


@rule("U824", "srdf-group-cycle", Severity.ERROR)
@as_moveit_runs
def srdf_group_cycle(robot):
    """SRDF groups hold each other through their subgroups: a cycle.

    MoveIt's SRDF reader (srdfdom's ``Model::loadGroups``) keeps a group only once each of its
    subgroups is kept; a group of the cycle never is, so it is dropped ("Group 'arm' has
    unsatisfied subgroups"), with every group holding one of them, and the group states and
    end effectors naming those ("that group is not known").

    Bad: ``<group name="arm"><group name="hand"/></group> <group name="hand"><group name="arm"/></group>``
    Good: ``<group name="arm"><chain .../><group name="hand"/></group> <group name="hand"><joint .../></group>``
    """
    srdf = companions(robot).srdf
    if srdf is None or srdf.root is None:
        return
    # group name -> (subgroup name, element) of its first definition, names as srdfdom reads
    # them: trimmed, a group or subgroup without one left out ("Group name not specified")
    holds: dict[str, list[tuple[str, object]]] = {}
    for element in srdf.root.iterfind("group"):
        if element.get("name") is not None:
            holds.setdefault(element.get("name").strip(), [
                (sub.get("name").strip(), sub) for sub in element.iterfind("group")
                if sub.get("name") is not None])
    held_in: dict[str, list[str]] = {}  # group name -> the groups naming it as a subgroup
    for name, subs in holds.items():
        for sub in dict.fromkeys(sub for sub, _ in subs):
            held_in.setdefault(sub, []).append(name)
    for cycle in _group_cycles(holds, held_in):
        holders = _holders(holds, held_in, set(cycle))
        named = ", ".join(holders[:_HOLDERS_NAMED]) + (
            ", ..." if len(holders) > _HOLDERS_NAMED else "")
        closing = next(sub for name, sub in holds[cycle[0]] if name == cycle[1 % len(cycle)])
        yield srdf.at(closing.sourceline), (
            f"SRDF group '{cycle[0]}' holds itself through its subgroups "
            f"({' > '.join(repr(name) for name in cycle + [cycle[0]])}): MoveIt drops every "
            "group of the cycle "
            f"(\"Group '{cycle[0]}' has unsatisfied subgroups\")"
            + (f", and the group(s) holding one: {named}" if holders else "")
            + ", with the group states and end effectors naming them")


def _group_cycles(holds: dict[str, list[tuple[str, object]]], held_in: dict[str, list[str]]
                  ) -> list[list[str]]:
    """The cycles of subgroups, each once: its groups in the order they hold each other, from
    the one defined first. Walked with loops (a chain of groups is as deep as it is long):
    the groups srdfdom keeps are taken away (a group once its subgroups are all kept, as its
    ``loadGroups`` repeats), then those an undefined name alone keeps out (U805's); from each
    group left, a subgroup that is left leads on, to a cycle."""
    edges = {name: list(dict.fromkeys(sub for sub, _ in subs)) for name, subs in holds.items()}
    left = set(edges)
    waiting = {name: len(subs) for name, subs in edges.items()}  # subgroups not yet kept
    kept = [name for name, count in waiting.items() if not count]
    while kept:
        name = kept.pop()
        left.discard(name)
        for holder in held_in.get(name, ()):
            waiting[holder] -= 1
            if not waiting[holder]:
                kept.append(holder)
    onward = {name: sum(sub in left for sub in edges[name]) for name in left}
    ends = [name for name in left if not onward[name]]
    while ends:
        name = ends.pop()
        left.discard(name)
        for holder in held_in.get(name, ()):
            if holder in left:
                onward[holder] -= 1
                if not onward[holder]:
                    ends.append(holder)
    order = {name: index for index, name in enumerate(edges)}
    cycles, walked = [], set()
    for start in (name for name in edges if name in left):  # document order
        path, at = {}, start
        while at not in walked and at not in path:
            path[at] = len(path)
            at = next(sub for sub in edges[at] if sub in left)
        walked.update(path)
        if at in path:  # this walk closed a cycle
            ring = list(path)[path[at]:]
            first = ring.index(min(ring, key=order.__getitem__))
            cycles.append(ring[first:] + ring[:first])
    return cycles


def _holders(holds: dict[str, list[tuple[str, object]]], held_in: dict[str, list[str]],
             cycle: set) -> list[str]:
    """Groups outside ``cycle`` that hold one of its groups, directly or through others, in
    document order: all of them, or one more than a message names."""
    found, queue = set(), list(cycle)
    while queue and len(found) <= _HOLDERS_NAMED:
        for holder in held_in.get(queue.pop(), ()):
            if holder not in cycle and holder not in found:
                found.add(holder)
                queue.append(holder)
    return [name for name in holds if name in found]
