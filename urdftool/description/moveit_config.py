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
  ``moveit_simple_controller_manager: {controller_names: [...], NAME: {action_ns, type,
  joints}}``; the one reader of MoveIt's lists (:func:`moveit_controllers`), wherever in a file
  they are (the controllers of :mod:`urdftool.description.controllers` are its entries).

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
    """A controller of MoveIt's controller list: its name, type and joints as written, where.

    type: "" when not written; joints: (name, line) of each name the ``joints:`` list holds;
    block: its mapping (the list's entry, or the ``NAME:`` mapping controller_names points to);
    ros: the MoveIt that reads its list (1: ``controller_list``; 2: ``controller_names``).
    """

    file: YamlFile
    name: str
    line: int
    type: str
    joints: list  # (name, line)
    joints_line: int
    action_ns: str | None  # None when not written
    action_line: int
    block: YamlMap | None
    ros: int

    __slots__ = ("file", "name", "line", "type", "joints", "joints_line", "action_ns",
                 "action_line", "block", "ros")

    def __init__(self, file: YamlFile, name: str, line: int, type: str, joints: list = NEW,
                 joints_line: int = 0, action_ns: str | None = None, action_line: int = 0,
                 block: YamlMap | None = None, ros: int = 1) -> None:
        self.file = file
        self.name = name
        self.line = line
        self.type = type
        self.joints = [] if joints is NEW else joints
        self.joints_line = joints_line
        self.action_ns = action_ns
        self.action_line = action_line
        self.block = block
        self.ros = ros


# How deep in a file a controller list is looked for: a launch file may load the file in any
# namespace (``<rosparam ns="move_group">``), so the keys above a list are its namespace.
_LIST_DEPTH = 12


def controller_manager(file: YamlFile) -> tuple[str, int] | None:
    """(plugin, line) of the ``moveit_controller_manager:`` ``file`` names (at the top, or under
    a node's ``ros__parameters``), None without one: the plugin that reads MoveIt's list."""
    holder = section(file.data, "moveit_controller_manager", 2)
    if holder is None or not isinstance(holder["moveit_controller_manager"], str):
        return None
    return holder["moveit_controller_manager"], holder.lines["moveit_controller_manager"]


def reads_list(plugin: str) -> bool:
    """Whether MoveIt's controller manager plugin ``plugin`` reads a controller list: the simple
    controller manager does (and MoveIt 1's fake one, its ``name`` and ``joints``);
    moveit_ros_control_interface's managers ask the controller manager instead."""
    return "ros_control_interface" not in plugin and "Ros2ControlManager" not in plugin


# The types of MoveIt 1's fake controller manager (moveit_fake_controllers: its execution
# types; none is interpolate), or one a launch argument sets (fake_execution_type).
FAKE_TYPES = ("", "interpolate", "last point", "via points")


def fake_list(listed) -> bool:
    """Whether a ``controller_list`` is MoveIt 1's fake controller manager's (the Setup
    Assistant's ``fake_controllers.yaml``): entries that name no ``action_ns`` and a fake
    execution type or none. That manager reads ``name`` and ``joints`` only."""
    return isinstance(listed, list) and all(
        isinstance(e, dict) and "action_ns" not in e
        and (str(e.get("type", "")) in FAKE_TYPES or "$(" in str(e.get("type", "")))
        for e in listed)


def moveit_controllers(file: YamlFile) -> tuple[list[ControllerEntry], list[tuple[int, str]]]:
    """MoveIt's controllers in ``file``, read as moveit_simple_controller_manager reads them, and
    the file's problems (what makes MoveIt skip a controller or the whole list), both located.

    Every list in the file is read (the keys above one are the namespace it is loaded in):

    - MoveIt 1, ``controller_list: [{name, action_ns, type, joints, default}]``: the list must be a
      list; an entry lacking any of ``name``, ``joints``, ``action_ns`` and ``type`` is skipped
      ("name, joints, action_ns, and type must be specifed for each controller"); each must be
      a string but ``joints``, a list of strings (MoveIt's XmlRpc casts throw otherwise); a
      ``default`` must be true or false. The fake controller manager's list (``fake`` in the
      file's ``moveit_controller_manager``, a ``fake_*.yaml`` file as the Setup Assistant writes
      it, or :func:`fake_list`) needs only ``name`` and ``joints``.
    - MoveIt 2, ``controller_names: [NAME, ...]`` beside one ``NAME: {action_ns, type, joints,
      default}`` mapping per name, where MoveIt reads it (``moveit_simple_controller_manager.
      controller_names``): under ``moveit_simple_controller_manager:`` (at any depth: a node's
      ``ros__parameters``), or at the top of a file a launch file loads into that namespace
      (another node's ``controller_names``, a joystick's or MoveIt Task Constructor's, is not
      MoveIt's list): the
      names must be strings; a name without its mapping, ``action_ns`` or ``type`` is skipped,
      and so is one whose ``joints`` is not a non-empty list of strings ("No joints specified").

    An entry is returned when it has a name and a ``joints:`` list, whatever else it lacks (its
    joints and name are still compared by the rules); what MoveIt refuses is a problem.
    """
    if file.problem or not isinstance(file.data, YamlMap):
        return [], []  # a broken file is said as the file itself (the rules read file.problem)
    plugin = controller_manager(file)
    fake = file.path.name.startswith("fake_") or plugin is not None and "fake" in plugin[0].lower()
    entries, problems, seen = [], [], set()

    def walk(node, depth, key=None):
        if not isinstance(node, YamlMap) or id(node) in seen or depth > _LIST_DEPTH:
            return
        seen.add(id(node))
        if "controller_list" in node:
            _moveit1(file, node, fake, entries, problems)
        if "controller_names" in node and (depth == 0 or key == "moveit_simple_controller_manager"):
            _moveit2(file, node, entries, problems)  # (another node's controller_names is its own)
        manager = node.get("moveit_simple_controller_manager")
        if "moveit_simple_controller_manager" in node and not (
                isinstance(manager, YamlMap) and "controller_names" in manager):
            problems.append((node.lines["moveit_simple_controller_manager"],
                             "moveit_simple_controller_manager needs a 'controller_names:' list"))
        for name, value in node.items():
            walk(value, depth + 1, name)

    walk(file.data, 0)
    problems.sort(key=lambda problem: problem[0])
    return entries, problems


def _entry(file, name: str, block: YamlMap, line: int, required: tuple, ros: int,
           problems: list) -> ControllerEntry | None:
    """The entry of controller ``name`` (None without a ``joints:`` list), its problems added."""
    where = f"MoveIt controller '{name}'"
    missing = [key for key in required if key not in block]
    if missing:
        problems.append((line, f"{where} has no {' and no '.join(missing)}: MoveIt's simple "
                         "controller manager skips it" + (
                             " (it needs name, joints, action_ns and type)" if ros == 1 else "")))
    for key in ("action_ns", "type"):
        if key in block and not isinstance(block[key], str):
            problems.append((block.lines[key], f"{where}: {key} '{block[key]}' must be a string"))
    if "default" in block and not isinstance(block["default"], bool):
        problems.append((block.lines["default"], f"{where}: default '{block['default']}' must be "
                         "true or false"))
    joints = block.get("joints")
    if not isinstance(joints, YamlList):
        if "joints" in block:
            problems.append((block.lines["joints"], f"MoveIt controller '{name}' needs a "
                             "'joints:' list"))
        return None
    if ros == 2 and not joints:
        problems.append((block.lines["joints"], f"{where} has an empty joints list: MoveIt's "
                         "simple controller manager skips it (\"No joints specified\")"))
    for joint, at in zip(joints, joints.lines):
        if not isinstance(joint, str):
            problems.append((at, f"{where}: joint '{joint}' must be a joint's name"))
    action = block.get("action_ns")
    return ControllerEntry(file, name, line, str(block.get("type", "")),
                           [(j, at) for j, at in zip(joints, joints.lines) if isinstance(j, str)],
                           block.lines["joints"], None if action is None else str(action),
                           block.lines.get("action_ns", line), block, ros)


def _moveit1(file, holder: YamlMap, fake: bool, entries: list, problems: list) -> None:
    listed = holder["controller_list"]
    if not isinstance(listed, YamlList):
        problems.append((holder.lines["controller_list"], "controller_list must be a list of "
                         "{name, action_ns, type, joints}"))
        return
    required = ("joints",) if fake or fake_list(listed) else ("joints", "action_ns", "type")
    for block, line in zip(listed, listed.lines):
        if not isinstance(block, YamlMap) or not isinstance(block.get("name"), str):
            problems.append((line, "each controller_list entry needs a 'name:'"))
            continue
        entry = _entry(file, block["name"], block, line, required, 1, problems)
        entries += [entry] if entry else []


def _moveit2(file, manager: YamlMap, entries: list, problems: list) -> None:
    names = manager["controller_names"]
    if not isinstance(names, YamlList):
        problems.append((manager.lines["controller_names"], "controller_names must be a list of "
                         "the controllers' names"))
        return
    for name, line in zip(names, names.lines):
        if not isinstance(name, str):
            problems.append((line, "each entry of controller_names must be a controller's "
                             "name"))
            continue
        block = manager.get(name)
        if not isinstance(block, YamlMap):
            problems.append((line, f"controller '{name}' is listed in controller_names but has "
                             f"no '{name}:' block with its type and joints" + _elsewhere(
                                 file.data, name, manager)))
            continue
        entry = _entry(file, name, block, manager.lines[name], ("action_ns", "type", "joints"),
                       2, problems)
        entries += [entry] if entry else []


def _elsewhere(data: YamlMap, name: str, manager: YamlMap) -> str:
    """Where else in the file a ``name:`` mapping is (beside the list is the only place MoveIt
    reads it: ``moveit_simple_controller_manager.NAME.type``), said for the message."""
    for key, node in (("", data), *((k, v) for k, v in data.items() if isinstance(v, YamlMap))):
        if node is not manager and isinstance(node.get(name), YamlMap):
            return (f"; its mapping is {f'under {key!r}' if key else 'at the top of the file'}, "
                    "outside the mapping that holds controller_names, where MoveIt does not read it")
    return ""


def ros_control_controllers(files, ros: int | None = None) -> dict[str, set[str]]:
    """The ros_control controllers declared in ``files`` (a mapping with ``type: pkg/Class``,
    ROS 1; or its ``NAME: ros__parameters:`` block, ROS 2), by name, with their joints
    (``joints:`` or ``joint:``). MoveIt's own lists are skipped. ``ros``: only those of ROS 2
    parameter files (2) or of the others (1), the controllers a MoveIt of that ROS meets."""
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
        if file.problem is None and (ros is None or file.ros2 == (ros == 2)):
            walk(file.data, 0)
    return {name: joints | parameters.get(name, set()) for name, joints in declared.items()}
