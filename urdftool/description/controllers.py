"""The controllers a robot's controller YAML declares, read the way each controller manager does.

Layouts read (a file may hold several):

- **ROS 2** (``ros2``; a file with ``ros__parameters``, read as rcl_yaml_param_parser does:
  repeated keys merge, see :mod:`urdftool.description.documents`): node blocks
  ``[/namespace/]node: ros__parameters: {...}``, nested node-name keys (``/**: node:
  ros__parameters:``) and the wildcards ``/**`` and ``/*`` (their parameters apply to every
  node). A controller is declared by ``NAME: {type: pkg/Class}`` in a node's parameters (the
  controller_manager's), or by ``type:`` in its own block (the spawner's ``--param-file``
  form); it reads the parameters of the wildcard blocks and of its own ``NAME:
  ros__parameters:`` blocks (``/robot_1/NAME``, ``/**/NAME``: one controller name may be
  configured per namespace; its blocks are read together).
- **ROS 1** (``ros1``; rosparam): any mapping ``NAME: {type: pkg/Class, ...}`` at any depth
  (the keys above it are its namespace), or a file that is one controller (top-level
  ``type:``; named after the file).
- **MoveIt** (``moveit``): the controllers of MoveIt's lists (MoveIt 1's ``controller_list``,
  MoveIt 2's ``controller_names``), as :func:`urdftool.description.moveit_config.
  moveit_controllers` reads them: each with a name and a ``joints:`` list.

Reading only: whether a name is a URDF joint or a class exists is the rules' business.
"""

from __future__ import annotations


from urdftool.description.companions import companions
from urdftool.description.controller_classes import MOVEIT_TYPES, ControllerClass, lookup
from urdftool.description.documents import YamlFile, YamlList, YamlMap, merged
from urdftool.description.moveit_config import moveit_controllers
from urdftool.records import NEW, Record

WILDCARDS = ("*", "**")
# Keys that name joints in classes nothing is known about (vendor controllers).
GUESSED_JOINT_KEYS = ("joints", "joint", "joint_names")
_MAX_DEPTH = 12


class JointRef(Record):
    """A joint name a controller's parameters hold: ``key`` is the parameter it is under."""

    name: str
    line: int | None
    key: str

    __slots__ = ("name", "line", "key")

    def __init__(self, name: str, line: int | None, key: str) -> None:
        self.name = name
        self.line = line
        self.key = key


class Controller(Record):
    """One controller of a YAML file.

    layout: "ros1", "ros2" or "moveit"
    line: where its ``type`` is (or its entry, for MoveIt)
    params: the parameters it reads (ROS 2: the wildcard blocks' merged with its own block;
        ROS 1 and MoveIt: its mapping)
    block_line: ROS 2: the line of its own ``NAME: ros__parameters:`` block, None without one
    namespace: the keys above it ("/"-joined; ROS 2: its node's namespace)
    own: ROS 2: the parameters of its own block alone (``params`` without the wildcard
        blocks', which every node reads); ROS 1: ``params``
    """

    file: YamlFile
    name: str
    type: str
    line: int
    layout: str
    params: YamlMap | None
    block_line: int | None
    namespace: str
    own: YamlMap | None

    __slots__ = ("file", "name", "type", "line", "layout", "params", "block_line", "namespace",
                 "own")

    def __init__(self, file: YamlFile, name: str, type: str, line: int, layout: str,
                 params: YamlMap | None = None, block_line: int | None = None, namespace: str = "",
                 own: YamlMap | None = None) -> None:
        self.file = file
        self.name = name
        self.type = type
        self.line = line
        self.layout = layout
        self.params = params
        self.block_line = block_line
        self.namespace = namespace
        self.own = own

    @property
    def package(self) -> str:
        return self.type.split("/")[0]

    @property
    def ros(self) -> int:
        return 2 if self.file.ros2 else 1

    @property
    def cls(self) -> ControllerClass | None:
        """Its class in the table for its file's ROS version; None when unknown (or MoveIt)."""
        return None if self.layout == "moveit" else lookup(self.type, self.ros)

    @property
    def is_state(self) -> bool:
        known = self.cls
        if known is not None:
            return known.state
        return self.type.endswith(("StateController", "StateBroadcaster"))

    @property
    def known(self) -> bool:
        """Whether what its parameters mean is known (a class in the table, or a MoveIt
        FollowJointTrajectory/GripperCommand controller)."""
        return self.cls is not None or (self.layout == "moveit" and self.type in MOVEIT_TYPES)

    def joint_keys(self) -> dict[str, str]:
        """Parameter -> "list"/"name"/"any": the parameters naming URDF joints."""
        if self.cls is not None:
            return self.cls.joints
        if self.layout == "moveit":
            return {"joints": "list"}
        return {key: "any" for key in GUESSED_JOINT_KEYS}

    def joints(self) -> list[JointRef]:
        """The joint names under its joint parameters (for a class nothing is known about, under
        ``joints``/``joint``/``joint_names``, which may name something else)."""
        found = []
        for key in self.joint_keys():
            found.extend(JointRef(name, line, key) for name, line in names_at(self.params, key))
        return found

    def interfaces(self) -> list[str] | None:
        """The command interfaces it claims on each joint, or None when not known."""
        known = self.cls
        if known is None or known.commands is None:
            return None
        if not known.commands.startswith("@"):
            return [known.commands]
        value = (self.params or {}).get(known.commands[1:])
        if isinstance(value, str):
            return [value]
        if isinstance(value, list) and all(isinstance(v, str) for v in value):
            return list(value)
        return None

    def where(self, key: str) -> int:
        """The line of parameter ``key``, else of its block, else of its type."""
        if isinstance(self.params, YamlMap) and key in self.params.lines:
            return self.params.lines[key]
        return self.block_line or self.line


class ParameterBlock(Record):
    """A ROS 2 node's ``NAME: ros__parameters:`` block."""

    name: str
    namespace: str
    params: YamlMap
    line: int

    __slots__ = ("name", "namespace", "params", "line")

    def __init__(self, name: str, namespace: str, params: YamlMap, line: int) -> None:
        self.name = name
        self.namespace = namespace
        self.params = params
        self.line = line


class ControllerFile(Record):
    """What one YAML file declares."""

    file: YamlFile
    controllers: list[Controller]
    blocks: list[ParameterBlock]  # ROS 2 node blocks

    __slots__ = ("file", "controllers", "blocks")

    def __init__(self, file: YamlFile, controllers: list[Controller] = NEW,
                 blocks: list[ParameterBlock] = NEW) -> None:
        self.file = file
        self.controllers = [] if controllers is NEW else controllers
        self.blocks = [] if blocks is NEW else blocks


def runs_of(robot, controller: Controller):
    """Whether the robot's launch files start ``controller``
    (:func:`urdftool.description.runtime.runs`, the URDF's ``<parameters>`` files counted as
    loaded), once per controller."""
    from urdftool.description.companions import parameter_files
    from urdftool.description.runtime import runs

    return robot.memo_for(runs_of, id(controller),
                          lambda: runs(robot, controller, parameter_files(robot)))


def started(robot, controller: Controller) -> bool | None:
    """Whether the robot is run with ``controller`` started: True when a launch file of the robot
    as checked starts it, active and unconditionally; False when the robot's launch files load
    its file and start it nowhere (or only inactive); None when nothing read says, or it starts
    only under a condition (a controller file is often a menu from which a launch file starts a
    few). The one place that question is answered (:func:`runs_of` says the condition)."""
    state = runs_of(robot, controller).state
    return True if state == "certain" else False if state == "never" else None


def controllers(robot) -> list[Controller]:
    """Every controller in the robot's controller YAML files (read once per robot), but those
    of another instance of the robot: a file whose controller managers in several namespaces
    declare controllers, one of them the namespace the robot's simulated controller manager
    runs in (:func:`manager_namespaces`), holds the others' for the robot built there with
    another name (a file with a ``robot1:`` and a ``robot2:`` section, each robot's
    gz_ros2_control plugin in its own namespace)."""
    namespaces = manager_namespaces(robot)
    found = []
    for file in controller_files(robot):
        spaces = {c.namespace.strip("/") for c in file.controllers if c.layout == "ros2"}
        ours = namespaces & spaces
        found.extend(c for c in file.controllers
                     if not ours or c.layout != "ros2" or c.namespace.strip("/") in ours
                     or any(w in c.namespace.split("/") for w in WILDCARDS))
    return found


def manager_namespaces(robot) -> set[str]:
    """The namespaces the robot's simulated controller manager runs in, as its URDF says: the
    ``<ros><namespace>`` of its gazebo_ros2_control/gz_ros2_control plugin, written without
    substitution (once per robot)."""
    from urdftool.description.actuation import CONTROL_PLUGINS, gazebo_plugins

    def read() -> set[str]:
        found = set()
        for plugin in gazebo_plugins(robot):
            text = f"{plugin.get('filename', '')} {plugin.get('name', '')}"
            if any(name in text for name in CONTROL_PLUGINS):
                for element in plugin.iterfind("ros/namespace"):
                    value = (element.text or "").strip().strip("/")
                    if value and "$(" not in value:
                        found.add(value)
        return found

    return robot.memo(manager_namespaces, read)


def controller_files(robot) -> list[ControllerFile]:
    """Each valid controller YAML file of the robot, read (once per robot)."""
    return robot.memo(controller_files, lambda: [read_controllers(f) for f in companions(robot).controllers
                                                 if f.problem is None])


def read_controllers(file: YamlFile) -> ControllerFile:
    """The controllers ``file`` declares, in all the layouts it holds."""
    found = ControllerFile(file)
    if not isinstance(file.data, dict):
        return found
    moveit_maps: set[int] = set()
    found.controllers.extend(_moveit(file, moveit_maps))
    if file.ros2:
        _ros2(file, found)
    else:
        found.controllers.extend(_ros1(file, moveit_maps))
    return found


# --- ROS 2 --------------------------------------------------------------------------------

def parameter_blocks(data) -> list[ParameterBlock]:
    """Every ``ros__parameters`` block: the node path above it split into namespace and name."""
    blocks, seen = [], set()

    def walk(node, path, line, depth):
        if not isinstance(node, YamlMap) or id(node) in seen or depth > _MAX_DEPTH:
            return
        seen.add(id(node))
        for key, value in node.items():
            if key == "ros__parameters":
                if isinstance(value, YamlMap):
                    parts = [p for part in path for p in str(part).split("/") if p]
                    blocks.append(ParameterBlock(parts[-1] if parts else "",
                                                 "/".join(parts[:-1]), nested(value), line or value.line))
            else:
                walk(value, (*path, key), node.lines.get(key), depth + 1)

    walk(data, (), None, 0)
    return blocks


def nested(params: YamlMap, depth: int = 0) -> YamlMap:
    """``params`` with dotted names unfolded (``constraints.goal_time: 1`` as ``constraints:
    {goal_time: 1}``): ROS 2 names a parameter by the path of keys to it, written either way."""
    if depth > _MAX_DEPTH or not any(isinstance(k, str) and "." in k or isinstance(v, YamlMap)
                                     for k, v in params.items()):
        return params
    result = YamlMap()
    result.line, result.lines = params.line, {}
    for key, value in params.items():
        line = params.lines.get(key, params.line)
        if isinstance(value, YamlMap):
            value = nested(value, depth + 1)
        if isinstance(key, str) and "." in key.strip("."):
            head, _, rest = key.partition(".")
            inner = YamlMap({rest: value})
            inner.line, inner.lines = line, {rest: line}
            value, key = nested(inner, depth + 1), head
        if key in result:
            value = merged(result[key], value)
        else:
            result.lines[key] = line
        result[key] = value
    return result


def _ros2(file: YamlFile, found: ControllerFile) -> None:
    found.blocks = parameter_blocks(file.data)
    wildcard = YamlMap()
    wildcard.line, wildcard.lines = 0, {}
    for block in found.blocks:
        if block.name in WILDCARDS:
            wildcard = merged(wildcard, block.params)
    own: dict[str, ParameterBlock] = {}  # a node's blocks in every namespace, merged
    for block in found.blocks:
        if block.name in WILDCARDS:
            continue
        if block.name in own:
            first = own[block.name]
            own[block.name] = ParameterBlock(first.name, first.namespace,
                                             merged(first.params, block.params), first.line)
        else:
            own[block.name] = block
    declared: dict[tuple[str, str], Controller] = {}  # (namespace, name)
    for block in found.blocks:
        for key, value in block.params.items():
            kind = value.get("type") if isinstance(value, dict) else None
            if isinstance(kind, str) and "/" in kind and (block.namespace, str(key)) not in declared:
                declared[(block.namespace, str(key))] = Controller(
                    file, str(key), kind, value.lines.get("type", value.line), "ros2",
                    namespace=block.namespace)
    names = {name for _, name in declared}
    for block in own.values():
        kind = block.params.get("type")
        if isinstance(kind, str) and "/" in kind and block.name not in names:
            declared[(block.namespace, block.name)] = Controller(
                file, block.name, kind, block.params.lines["type"], "ros2", namespace=block.namespace)
    spaces: dict[str, set[str]] = {}  # a name -> the namespaces whose managers declare it
    for namespace, name in declared:
        spaces.setdefault(name, set()).add(namespace)
    for (namespace, name), controller in declared.items():
        block = own.get(name)
        if block is not None and len(spaces[name]) > 1:
            # one name declared by the managers of several namespaces (robot1 and robot2 of
            # one file, each instance its section): each reads its own namespace's blocks,
            # and those of namespaces declaring nothing (/**/NAME)
            block = _blocks_of(found.blocks, name, namespace, spaces[name])
        controller.params = merged(wildcard, block.params) if block else wildcard
        controller.own = block.params if block else None
        controller.block_line = block.line if block else None
    found.controllers.extend(declared.values())


def _blocks_of(blocks: list[ParameterBlock], name: str, namespace: str,
               declaring: set[str]) -> ParameterBlock | None:
    """The blocks of node ``name`` a controller of the manager in ``namespace`` reads, merged:
    those of its namespace and of namespaces whose managers declare no ``name``."""
    found = None
    for block in blocks:
        if block.name == name and (block.namespace == namespace or block.namespace not in declaring):
            found = block if found is None else ParameterBlock(
                found.name, found.namespace, merged(found.params, block.params), found.line)
    return found


# --- ROS 1 --------------------------------------------------------------------------------

def _ros1(file: YamlFile, skip: set[int]) -> list[Controller]:
    data, found, seen = file.data, [], set(skip)
    kind = data.get("type")
    if isinstance(kind, str) and "/" in kind:
        found.append(Controller(file, file.path.name.split(".")[0], kind, data.lines["type"], "ros1",
                                params=data, own=data))

    def walk(node, path, depth):
        if not isinstance(node, YamlMap) or id(node) in seen or depth > _MAX_DEPTH:
            return
        seen.add(id(node))
        for key, value in node.items():
            if not isinstance(value, YamlMap) or id(value) in skip:
                continue
            kind = value.get("type")
            if isinstance(kind, str) and "/" in kind:
                found.append(Controller(file, str(key), kind, node.lines.get(key, node.line), "ros1",
                                        params=value, namespace="/".join(path), own=value))
            walk(value, (*path, str(key)), depth + 1)

    walk(data, (), 0)
    return found


# --- MoveIt -------------------------------------------------------------------------------

def _moveit(file: YamlFile, entries: set[int]) -> list[Controller]:
    """MoveIt's controllers, as :func:`urdftool.description.moveit_config.moveit_controllers`
    reads them (the one reader of MoveIt's lists; their problems are its); the id of each
    entry's mapping is added to ``entries``."""
    found = []
    for entry in moveit_controllers(file)[0]:
        entries.add(id(entry.block))
        found.append(Controller(file, entry.name, entry.type, entry.line, "moveit",
                                params=entry.block))
    return found


def names_at(mapping, key) -> list[tuple[str, int | None]]:
    """(name, line) of each name ``mapping[key]`` holds (one string, or a list of them)."""
    value = mapping.get(key) if isinstance(mapping, dict) else None
    line = mapping.lines.get(key, mapping.line) if isinstance(mapping, YamlMap) else None
    if isinstance(value, str):
        return [(value, line)]
    if isinstance(value, YamlList):
        return [(str(item), at) for item, at in zip(value, value.lines) if isinstance(item, str)]
    return []
