"""MoveIt's YAML beside the SRDF, read into entries with their lines: ``kinematics.yaml`` (the
IK solver per group), ``joint_limits.yaml`` (the limits MoveIt plans with) and the controller
list (which ros_control controllers MoveIt sends trajectories to), plus a small reader of the
ros_control controllers those names refer to.

Layouts read (each also under ``/**: ros__parameters:`` or ``<node>: ros__parameters:`` as ROS 2
parameter files are written):

- kinematics: ``GROUP: {kinematics_solver: pkg/Class, kinematics_solver_timeout: ...}``, also
  under ``robot_description_kinematics:`` (MoveIt 2);
- joint limits: ``joint_limits: {JOINT: {has_velocity_limits: true, max_velocity: ...}}``, also
  under ``robot_description_planning:`` (MoveIt 2);
- controllers: MoveIt 1 ``controller_list: [{name, action_ns, type, joints}]``; MoveIt 2
  ``moveit_simple_controller_manager: {controller_names: [...], NAME: {type, joints}}``.

Reading only: each reader returns entries and the file's problems as (line, message); what is
wrong against the URDF or the SRDF is the rules' business.
"""

from __future__ import annotations


from urdftool.description.documents import YamlFile, YamlList, YamlMap
from urdftool.errors import available
from urdftool.records import NEW, Record

# Solvers that need the group to be one serial chain (moveit_kinematics: they build a KDL chain
# and refuse a group for which JointModelGroup::isChain() is false; the cached one wraps KDL's).
CHAIN_SOLVERS = ("kdl_kinematics_plugin/KDLKinematicsPlugin",
                 "lma_kinematics_plugin/LMAKinematicsPlugin",
                 "cached_ik_kinematics_plugin/CachedKDLKinematicsPlugin")
# The kinematics plugins whose names are known, with where each is exported: moveit_kinematics'
# plugin XML files (moveit/moveit2 main: kdl_, lma_, srv_ and cached_ik_kinematics_plugin
# _description.xml; the same names in MoveIt 1), trac_ik (traclabs/trac_ik,
# trac_ik_kinematics_plugin), bio_ik (TAMS-Group/bio_ik) and pick_ik (PickNikRobotics/pick_ik,
# its USAGE.md). An IKFast plugin is generated per robot: any PACKAGE/IKFastKinematicsPlugin.
SOLVERS = ("kdl_kinematics_plugin/KDLKinematicsPlugin", "lma_kinematics_plugin/LMAKinematicsPlugin",
           "srv_kinematics_plugin/SrvKinematicsPlugin",
           "cached_ik_kinematics_plugin/CachedKDLKinematicsPlugin",
           "cached_ik_kinematics_plugin/CachedSrvKinematicsPlugin",
           "cached_ik_kinematics_plugin/CachedTRACKinematicsPlugin",
           "cached_ik_kinematics_plugin/CachedUR3KinematicsPlugin",
           "cached_ik_kinematics_plugin/CachedUR5KinematicsPlugin",
           "cached_ik_kinematics_plugin/CachedUR10KinematicsPlugin",
           "trac_ik_kinematics_plugin/TRAC_IKKinematicsPlugin", "bio_ik/BioIKKinematicsPlugin",
           "pick_ik/PickIkPlugin")
IKFAST = "IKFastKinematicsPlugin"
SOLVER_NUMBERS = ("kinematics_solver_timeout", "kinematics_solver_search_resolution")
# joint_limits_interface (ROS 1) and joint_limits (ROS 2) keys
LIMIT_FLAGS = {"has_position_limits": ("min_position", "max_position"),
               "has_velocity_limits": ("max_velocity",),
               "has_acceleration_limits": ("max_acceleration",),
               "has_deceleration_limits": ("max_deceleration",),
               "has_jerk_limits": ("max_jerk",), "has_effort_limits": ("max_effort",)}
LIMIT_KEYS = (*LIMIT_FLAGS, *(k for keys in LIMIT_FLAGS.values() for k in keys), "angle_wraparound",
              "has_soft_limits", "k_position", "k_velocity", "soft_lower_limit", "soft_upper_limit")
SCALING_KEYS = ("default_velocity_scaling_factor", "default_acceleration_scaling_factor")
MOVEIT_KEYS = ("controller_list", "moveit_simple_controller_manager")


def _number(value) -> bool:
    """Whether a value read from MoveIt's YAML is a number: not a boolean, not NaN (``.nan``
    passed every comparison: a max_velocity of NaN was no finding, and MoveIt plans with it)."""
    return isinstance(value, (int, float)) and not isinstance(value, bool) and value == value


def _tagged_number(value) -> bool:
    """A number written with a tag its reader does not construct (``!degrees 360`` in a ROS 2
    parameter file; rosparam's tags are read as it reads them, :func:`~urdftool.description.
    documents.rosparam_angle`) is read as its text: its unit is unknown."""
    try:
        float(value)
    except (TypeError, ValueError):
        return False
    return isinstance(value, str)


def section(data, key: str, depth: int = 3):
    """The mapping that holds ``key``: ``data`` itself, or one found under ``ros__parameters`` or
    another node name, at most ``depth`` levels down; None without one."""
    if not isinstance(data, YamlMap) or depth < 0:
        return None
    if key in data:
        return data
    for value in data.values():
        found = section(value, key, depth - 1)
        if found is not None:
            return found
    return None


# --- kinematics.yaml -------------------------------------------------------------------------

class SolverEntry(Record):
    """A planning group of kinematics.yaml and its solver, with their lines."""

    group: str
    line: int
    solver: str | None
    solver_line: int

    __slots__ = ("group", "line", "solver", "solver_line")

    def __init__(self, group: str, line: int, solver: str | None, solver_line: int) -> None:
        self.group = group
        self.line = line
        self.solver = solver
        self.solver_line = solver_line


def kinematics(file: YamlFile) -> tuple[list[SolverEntry], list[tuple[int, str]]]:
    """The groups of ``kinematics.yaml`` with their solvers, and the file's problems."""
    if file.problem:
        return [], [(file.line or 1, file.problem)]
    holder = section(file.data, "robot_description_kinematics")
    data = holder["robot_description_kinematics"] if holder is not None else file.data
    if not isinstance(data, YamlMap):
        return [], [(getattr(data, "line", 1) or 1, "kinematics.yaml must map each planning group "
                     "to {kinematics_solver: ..., kinematics_solver_timeout: ...}")]
    entries, problems = [], []
    for group, entry in data.items():
        line = data.lines[group]
        if group == "ros__parameters" or (isinstance(entry, YamlMap) and "robot_description_kinematics" in entry):
            continue
        if not isinstance(entry, YamlMap):
            problems.append((line, f"group '{group}' must map to {{kinematics_solver: ..., "
                             f"kinematics_solver_timeout: ...}}, not {entry!r}"))
            continue
        solver = entry.get("kinematics_solver")
        if solver is not None and (not isinstance(solver, str) or "/" not in solver):
            problems.append((entry.lines["kinematics_solver"], f"group '{group}': "
                             f"kinematics_solver '{solver}' is not a plugin name (package/Class)"))
            solver = None
        for key in SOLVER_NUMBERS:
            value = entry.get(key)
            if key in entry and not (_number(value) and value > 0):
                problems.append((entry.lines[key], f"group '{group}': {key} '{value}' must be a "
                                 "number > 0"))
        entries.append(SolverEntry(str(group), line, solver,
                                   entry.lines.get("kinematics_solver", line)))
    return entries, problems


# --- joint_limits.yaml -----------------------------------------------------------------------

class LimitEntry(Record):
    """One joint's MoveIt limits: ``values`` {key: number} that apply (their flag is true)."""

    joint: str
    line: int
    values: dict
    lines: dict

    __slots__ = ("joint", "line", "values", "lines")

    def __init__(self, joint: str, line: int, values: dict = NEW, lines: dict = NEW) -> None:
        self.joint = joint
        self.line = line
        self.values = {} if values is NEW else values
        self.lines = {} if lines is NEW else lines


def planning_limits(file: YamlFile) -> tuple[list[LimitEntry], list[tuple[int, str]]]:
    """The joints of MoveIt's ``joint_limits.yaml`` with the limits that are on, and problems."""
    if file.problem:
        return [], [(file.line or 1, file.problem)]
    holder = section(file.data, "joint_limits")
    if holder is None:
        return [], [(getattr(file.data, "line", 1) or 1, "a MoveIt joint_limits.yaml needs a "
                     "'joint_limits:' map of joint name to limits")]
    problems = []
    for key in SCALING_KEYS:
        value = holder.get(key)
        if key in holder and not (_number(value) and 0 < value <= 1):
            problems.append((holder.lines[key], f"{key} '{value}' must be a number in (0, 1]"))
    table = holder["joint_limits"]
    if not isinstance(table, YamlMap):
        return [], [*problems, (holder.lines["joint_limits"], "joint_limits must be a map of "
                                "joint name to {has_velocity_limits, max_velocity, ...}")]
    entries = []
    for joint, limits in table.items():
        line = table.lines[joint]
        if not isinstance(limits, YamlMap):
            problems.append((line, f"joint '{joint}' must map to {{has_velocity_limits, "
                             "max_velocity, ...}"))
            continue
        entry = LimitEntry(str(joint), line, lines=limits.lines)
        problems.extend(_limit_problems(entry, limits))
        entries.append(entry)
    return entries, problems


def _limit_problems(entry: LimitEntry, limits: YamlMap) -> list[tuple[int, str]]:
    problems = []
    for key, value in limits.items():
        where = limits.lines[key]
        if key not in LIMIT_KEYS:
            problems.append((where, f"joint '{entry.joint}': unknown key '{key}', which MoveIt "
                             "ignores; " + available('keys', str(key), LIMIT_KEYS)))
        elif key in LIMIT_FLAGS or key == "angle_wraparound" or key == "has_soft_limits":
            if not isinstance(value, bool):
                problems.append((where, f"joint '{entry.joint}': {key} '{value}' must be true "
                                 "or false"))
        elif not (_number(value) or _tagged_number(value)):
            problems.append((where, f"joint '{entry.joint}': {key} '{value}' must be a number"))
    for flag, keys in LIMIT_FLAGS.items():
        if limits.get(flag) is not True:
            continue
        for key in keys:
            value = limits.get(key)
            if key not in limits:
                problems.append((limits.lines[flag], f"joint '{entry.joint}': {flag} is true "
                                 f"but {key} is missing"))
            elif _number(value):
                if key.startswith("max_") and key != "max_position" and value <= 0:
                    problems.append((limits.lines[key], f"joint '{entry.joint}': {key} {value} "
                                     "must be > 0"))
                else:
                    entry.values[key] = float(value)
    return problems


# --- MoveIt's controller list and the ros_control controllers --------------------------------

class ControllerEntry(Record):
    """A controller MoveIt sends to: its name, type and joints as written, where."""

    file: YamlFile
    name: str
    line: int
    type: str
    joints: list  # (name, line)
    joints_line: int
    action_ns: str | None  # None when not written
    action_line: int

    __slots__ = ("file", "name", "line", "type", "joints", "joints_line", "action_ns",
                 "action_line")

    def __init__(self, file: YamlFile, name: str, line: int, type: str, joints: list = NEW,
                 joints_line: int = 0, action_ns: str | None = None, action_line: int = 0) -> None:
        self.file = file
        self.name = name
        self.line = line
        self.type = type
        self.joints = [] if joints is NEW else joints
        self.joints_line = joints_line
        self.action_ns = action_ns
        self.action_line = action_line


def moveit_controllers(file: YamlFile) -> tuple[list[ControllerEntry], list[tuple[int, str]]]:
    """MoveIt's controllers in ``file`` (none when it has no controller list), and problems."""
    if file.problem:
        return [], []  # a broken controller file is reported with the controllers (U6xx)
    holder = section(file.data, "controller_list", 2)
    if holder is not None:
        return _moveit1(file, holder)
    holder = section(file.data, "moveit_simple_controller_manager", 2)
    if holder is not None:
        return _moveit2(file, holder)
    return [], []


def _entry(file, name, block: YamlMap, line) -> tuple[ControllerEntry | None, list]:
    joints = block.get("joints")
    if not isinstance(joints, YamlList):
        return None, [(block.lines.get("joints", line), f"MoveIt controller '{name}' needs a "
                       "'joints:' list")]
    action = block.get("action_ns")
    entry = ControllerEntry(file, str(name), line, str(block.get("type", "")),
                            [(str(j), at) for j, at in zip(joints, joints.lines)],
                            block.lines["joints"], None if action is None else str(action),
                            block.lines.get("action_ns", line))
    return entry, []


def _moveit1(file, holder) -> tuple[list[ControllerEntry], list]:
    listed = holder["controller_list"]
    if not isinstance(listed, YamlList):
        return [], [(holder.lines["controller_list"], "controller_list must be a list of "
                     "{name, action_ns, type, joints}")]
    entries, problems = [], []
    for block, line in zip(listed, listed.lines):
        if not isinstance(block, YamlMap) or not isinstance(block.get("name"), str):
            problems.append((line, "each controller_list entry needs a 'name:'"))
            continue
        entry, bad = _entry(file, block["name"], block, line)
        problems.extend(bad)
        entries += [entry] if entry else []
    return entries, problems


def _moveit2(file, holder) -> tuple[list[ControllerEntry], list]:
    manager = holder["moveit_simple_controller_manager"]
    where = holder.lines["moveit_simple_controller_manager"]
    names = manager.get("controller_names") if isinstance(manager, YamlMap) else None
    if not isinstance(names, YamlList):  # (a list's lines are a list: its .get was a crash)
        return [], [(manager.lines.get("controller_names", where) if isinstance(manager, YamlMap)
                     else where, "moveit_simple_controller_manager needs a 'controller_names:' "
                     "list")]
    entries, problems = [], []
    for name, line in zip(names, names.lines):
        if isinstance(name, bool) or not isinstance(name, (str, int)):  # (a list or a map
            problems.append((line, "each entry of controller_names must be a controller's "
                             "name"))  # was looked up as a key, unhashable)
            continue
        block = manager.get(name)
        if not isinstance(block, YamlMap):
            problems.append((line, f"controller '{name}' is listed in controller_names but has "
                             f"no '{name}:' block with its type and joints"))
            continue
        entry, bad = _entry(file, name, block, manager.lines[name])
        problems.extend(bad)
        entries += [entry] if entry else []
    return entries, problems


def ros_control_controllers(files) -> dict[str, set[str]]:
    """The ros_control controllers declared in ``files`` (a mapping with ``type: pkg/Class``,
    ROS 1; or its ``NAME: ros__parameters:`` block, ROS 2), by name, with their joints
    (``joints:`` or ``joint:``). MoveIt's own lists are skipped."""
    declared: dict[str, set[str]] = {}
    parameters: dict[str, set[str]] = {}

    def joints_of(block) -> set[str]:
        value = block.get("joints", block.get("joint"))
        return {str(j) for j in value} if isinstance(value, list) else \
            ({value} if isinstance(value, str) else set())

    def walk(node, depth: int) -> None:
        if not isinstance(node, dict) or depth > 6:
            return
        for key, value in node.items():
            if key in MOVEIT_KEYS or not isinstance(value, dict):
                continue
            name = str(key).split("/")[-1]
            kind = value.get("type")
            if isinstance(kind, str) and "/" in kind:
                declared.setdefault(name, set()).update(joints_of(value))
            if isinstance(value.get("ros__parameters"), dict):
                parameters.setdefault(name, set()).update(joints_of(value["ros__parameters"]))
            walk(value, depth + 1)

    for file in files:
        if file.problem is None:
            walk(file.data, 0)
    return {name: joints | parameters.get(name, set()) for name, joints in declared.items()}
