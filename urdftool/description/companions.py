"""Files that describe a robot beside its URDF: controller YAML, SRDF, the joint spec table, and
MoveIt's kinematics.yaml and joint_limits.yaml.

Where they are looked for (:func:`search_folders`), only inside the robot's repository:

- the robot's folder and its ``config/``;
- the ROS package layout ``pkg/urdf/robot.urdf.xacro``: ``pkg/config/`` (the package is the
  folder above a ``urdf/``, ``xacro/``, ``robots/``, ``description/`` or ``models/`` folder, or
  the nearest folder above holding a package.xml);
- the sibling MoveIt package ``NAME_moveit_config/config/`` beside the package, for NAME the
  package name without ``_description`` or the robot file's stem.

Which files belong to the robot (an option always wins; a file named in the URDF too):

- controllers: every ``--controllers FILE``; else each YAML file the URDF's
  ``gazebo_ros2_control``/``gz_ros2_control`` ``<parameters>`` names (inside the repository),
  and each controller YAML the robot's launch files load (:mod:`urdftool.description.runtime`:
  the configurations that describe the robot's file); else, or when a launch file loads a file
  urdftool cannot resolve, the YAML files found that look like a controller configuration (a
  mapping with a ``type: package/Class`` entry, a ``controller_manager`` key, or MoveIt's
  ``controller_list``/``controller_names``; in a ``config/`` folder a file that is not valid
  YAML counts, so that it is reported). A file the URDF's ``<parameters>`` or a launch file
  names is the robot's controller file: a sibling demo's file in the same folder is not
  (MoveIt's controller lists found there still are), nor is a file found that the
  ``<parameters>`` of a file the robot does not read names (another robot's Gazebo plugin's:
  gz_ros2_examples' ``joint_controller.yaml``, which only ``moving_stick.xacro`` loads, was
  checked against its three neighbours). A controller YAML is read as its launch
  files load it: with ``subst_value``/``allow_substs``, its ``$(arg)``/``$(var)`` take the
  launch arguments' values.
- SRDF: ``--srdf FILE``; else the SRDF a launch file of the robot gives MoveIt
  (``robot_description_semantic``); else the ``*.srdf`` found whose file name matches the
  robot, else the one whose ``<robot name>`` is the robot's, else the only one.
- spec: ``--spec FILE``; else ``joint_limits.yaml`` or ``joint_spec.yaml``, when it is a
  urdftool spec (top-level ``unit:`` and ``joints:``; a ROS ``joint_limits.yaml`` has a top-level
  ``joint_limits:`` and is left alone) or is not valid YAML.
- MoveIt: ``kinematics.yaml``, and the ROS ``joint_limits.yaml`` (top-level ``joint_limits:``) in
  the MoveIt package (one beside the robot is often its xacro's input, not MoveIt's); when none
  is found there, those in the SRDF's own folder (a moveit_config package's
  ``config/``), with MoveIt's controller list (``moveit_controllers.yaml``,
  ``simple_moveit_controllers.yaml``, ``ros_controllers.yaml``, ``controllers.yaml`` holding a
  ``controller_list`` or ``moveit_simple_controller_manager``) when it is not already among the
  controllers.

A folder holding several robots (``.urdf``/``.urdf.xacro`` files) shares its files only by
name: a file whose name starts with a robot's file stem or name (``arm_controllers.yaml`` for
``arm.urdf``; the longest match wins) belongs to that robot, an SRDF also by its ``<robot
name>``; any other file found there belongs to none of them (``used`` says why). A robot alone in
its folder gets every file found; files of the same stem (``panda.urdf`` beside
``panda.urdf.xacro``) are one robot in two forms.

Files found automatically are never read through a symbolic link leading elsewhere: robot
files may come from untrusted pull requests. Each file is read (by
:mod:`urdftool.description.documents`) and parsed once per robot (kept in ``Robot.memo``).
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from urdftool.description.actuation import CONTROL_PLUGINS, gazebo_plugins
from urdftool.description import runtime as launched
from urdftool.description.documents import SrdfFile, YamlFile, read_srdf, read_yaml
from urdftool.description.files import MANIFESTS, inside, kind_of, listing, read_regular, \
    real_path, walk
from urdftool.description.launch import named as launch_named
from urdftool.description.moveit_config import fake_list
from urdftool.description.packages import SKIP_DIRS, containment_root
from urdftool.description.urdf import ROBOT_GLOB
from urdftool.description.run_memo import per_run
from urdftool.diagnostics import display_path
from urdftool.records import NEW, Record

SPEC_NAMES = ("joint_limits.yaml", "joint_spec.yaml")
MOVEIT_CONTROLLER_NAMES = ("moveit_controllers.yaml", "simple_moveit_controllers.yaml",
                           "ros_controllers.yaml", "controllers.yaml")
COMPANION_SUFFIXES = (".yaml", ".yml", ".srdf")
URDF_FOLDERS = ("urdf", "urdfs", "xacro", "robots", "robot", "description", "models", "model")
ROBOT_SUFFIXES = (".urdf", ".urdf.xacro")


# --- discovery --------------------------------------------------------------------------------

class Companions(Record):
    """The companion files of one robot, parsed.

    used: path -> why it is this robot's; unused: path found but not this robot's -> why;
    unread: path of the name of a companion found where no file could be read (a folder, a
    FIFO, a link to another folder), and each folder companions are looked for in that is a
    link -> why (``diff`` says so of the place, not "removed")
    """

    controllers: list[YamlFile]
    srdf: SrdfFile | None
    spec: YamlFile | None
    kinematics: YamlFile | None  # MoveIt's
    planning_limits: YamlFile | None  # MoveIt's joint_limits.yaml
    moveit_controllers: list[YamlFile]  # beside the SRDF
    moveit_given: list[Path]  # MoveIt settings launch files load
    used: dict[Path, str]
    unused: dict[Path, str]
    unread: dict[Path, str]

    def describe(self) -> list[str]:
        """One line per file found: what it is used as and why, or why it is not used."""
        kinds = [("controllers", f) for f in self.controllers] + [
            (kind, getattr(self, kind)) for kind in ("srdf", "spec", "kinematics",
                                                     "planning_limits")
            if getattr(self, kind) is not None] + [
            ("MoveIt controllers", f) for f in self.moveit_controllers]
        lines = [f"{kind}: {file.display} ({self.used.get(file.path, 'named')})" for kind, file in kinds]
        lines += [f"not used: {display_path(path)} ({why})" for path, why in self.unused.items()]
        lines += [f"not read: {display_path(path)} ({why})" for path, why in self.unread.items()]
        return lines + self.launch

    launch: list[str]  # what the robot's launch files told

    __slots__ = ("controllers", "srdf", "spec", "kinematics", "planning_limits",
                 "moveit_controllers", "moveit_given", "used", "unused", "unread", "launch")

    def __init__(self, controllers: list[YamlFile] = NEW, srdf: SrdfFile | None = None,
                 spec: YamlFile | None = None, kinematics: YamlFile | None = None,
                 planning_limits: YamlFile | None = None, moveit_controllers: list[YamlFile] = NEW,
                 moveit_given: list[Path] = NEW, used: dict[Path, str] = NEW,
                 unused: dict[Path, str] = NEW, unread: dict[Path, str] = NEW,
                 launch: list[str] = NEW) -> None:
        self.controllers = [] if controllers is NEW else controllers
        self.srdf = srdf
        self.spec = spec
        self.kinematics = kinematics
        self.planning_limits = planning_limits
        self.moveit_controllers = [] if moveit_controllers is NEW else moveit_controllers
        self.moveit_given = [] if moveit_given is NEW else moveit_given
        self.used = {} if used is NEW else used
        self.unused = {} if unused is NEW else unused
        self.unread = {} if unread is NEW else unread
        self.launch = [] if launch is NEW else launch


def companions(robot) -> Companions:
    """The robot's companion files, found and parsed on first use and then cached on it."""
    return robot.memo(companions, lambda: _discover(robot))


def _discover(robot) -> Companions:
    named = robot.companion_paths
    found = Companions()
    folders = search_folders(Path(robot.path)) if robot.path != "-" else []
    if robot.path != "-":
        for folder in _linked_folders(Path(os.path.abspath(robot.path))):
            found.unread[folder] = "a folder that is a symbolic link: not entered"
    owner = _Owner(robot, folders)
    if robot.path != "-":
        found.launch = launched.runtime(robot).describe()
    if named.controllers:  # each file once, however often and by whatever path it is named
        # (2,000 --controllers of one file, or as many in the settings, were each checked,
        # past the time budget)
        unique: dict = {}
        for path in map(Path, named.controllers):
            unique.setdefault(real_path(path), path)
        found.controllers = [controller_yaml(robot, path, "named controllers")
                             for path in unique.values()]
    else:
        found.controllers = _auto_controllers(robot, folders, owner, found)
    launched_srdf = launched.semantic_files(robot) if robot.path != "-" else []
    if named.srdf:
        found.srdf = read_srdf(Path(named.srdf), "named SRDF")
    elif launched_srdf:
        path, configuration, _ = launched_srdf[0]
        found.srdf = read_srdf(path)
        found.used[path] = f"given to MoveIt by {configuration.named}"
    else:
        path = _pick_srdf(robot, folders, owner, found)
        found.srdf = read_srdf(path) if path else None
    picked = found.srdf if not named.srdf and not launched_srdf else None
    if named.spec:
        found.spec = read_yaml(Path(named.spec), "named spec")
    else:
        found.spec = _auto_yaml(folders, SPEC_NAMES, owner, found, lambda p: is_spec(p.data) or p.problem,
                                "a urdftool joint spec")
    found.kinematics = _auto_yaml(folders, ("kinematics.yaml",), owner, found,
                                  lambda p: p.problem is not None or isinstance(p.data, dict),
                                  "MoveIt kinematics",
                                  picked)
    # a joint_limits.yaml beside the robot is often its xacro's input: MoveIt's is in its package
    moveit_folders = [f for f in folders if f.parent.name.endswith("_moveit_config")]
    found.planning_limits = _auto_yaml(moveit_folders, ("joint_limits.yaml",), owner, found,
                                       lambda p: p.problem is not None or isinstance(p.data, dict)
                                       and "joint_limits" in p.data, "MoveIt/ROS joint limits", picked)
    if found.srdf is not None and not _written_for_another_srdf(found.srdf.path, picked):
        _beside_srdf(found, found.srdf.path)
    return found


def _setup_assistant_srdf(folder: Path) -> Path | None:
    """The SRDF that the ``.setup_assistant`` of the ROS 2 MoveIt package above ``folder``
    (its ``config/``) names (``srdf: relative_path:``), when it is a regular file of the
    package. MoveItConfigsBuilder loads that SRDF whatever robot name it is given, and the
    Setup Assistant wrote the package's kinematics.yaml, joint_limits.yaml and controller lists
    for it. ROS 1's MoveIt never reads the file: its launch files choose the SRDF
    (turtlebot_arm's planning_context.launch loads ``$(arg arm_type)_arm.srdf`` with the one
    joint_limits.yaml of the package), so a ROS 1 package gives nothing here."""
    package = folder.parent
    settings = launched.setup_assistant(package) if folder.name == "config" else None
    srdf = (settings.get("srdf") or settings.get("SRDF")) if settings is not None else None
    relative = srdf.get("relative_path") if isinstance(srdf, dict) else None
    if not isinstance(relative, str) or not relative:
        return None
    path = package / relative
    return path if kind_of(path) == "file" and inside(path, package) else None


def _written_for_another_srdf(path: Path, picked: SrdfFile | None) -> Path | None:
    """The SRDF the Setup Assistant wrote MoveIt's file ``path`` (kinematics.yaml,
    joint_limits.yaml, or the SRDF itself, for the files beside it) for, when it is another
    SRDF of the same folder than ``picked``, the robot's SRDF found by name (one a launch file
    or --srdf gives is what MoveIt pairs the files with). A package holding the SRDFs of two
    Setup Assistant runs (Fairino's fairino5_v6_robot.srdf and fairino_with_ag95.srdf) has
    its YAML written for the one its .setup_assistant names: checked against the other, each
    group was 'not in the SRDF'."""
    if picked is None or not kind_of(picked.path):
        return None
    named = _setup_assistant_srdf(Path(path).parent)
    if named is None or real_path(named) == real_path(picked.path) or \
            Path(real_path(named)).parent != Path(real_path(picked.path)).parent:
        return None
    return named


def _beside_srdf(found: Companions, srdf: Path) -> None:
    """MoveIt's YAML files in the SRDF's folder, for the kinds not found yet (regular files
    there, no link leading out)."""
    if not kind_of(srdf):
        return
    folder = Path(real_path(srdf)).parent

    def here(name: str) -> Path | None:
        path = folder / name
        real = Path(real_path(path))
        return path if kind_of(real) == "file" and real.parent == folder else None

    if found.kinematics is None and (path := here("kinematics.yaml")):
        found.kinematics = read_yaml(path)
        found.used[path] = "beside the SRDF"
    if found.planning_limits is None and (path := here("joint_limits.yaml")) and not (
            found.spec is not None and real_path(found.spec.path) == real_path(path)):
        limits = read_yaml(path)  # (a spec that does not read is said as the spec's)
        if not is_spec(limits.data):
            found.planning_limits = limits
            found.used[path] = "beside the SRDF"
    known = {real_path(f.path) for f in found.controllers if kind_of(f.path)}
    for name in MOVEIT_CONTROLLER_NAMES:
        path = here(name)
        if path is None or real_path(path) in known or path in found.unused:
            continue  # (a list the launch files do not give MoveIt is not used: _auto_controllers)
        parsed = read_yaml(path)
        if found.moveit_given and not parsed.problem and \
                real_path(path) not in {real_path(p) for p in found.moveit_given}:
            found.unused[path] = ("no launch file of the robot gives it to MoveIt (they give "
                                  f"{', '.join(display_path(p) for p in found.moveit_given[:2])})")
            continue
        if parsed.problem or is_moveit_controllers(parsed.data):
            found.moveit_controllers.append(parsed)
            found.used[path] = "beside the SRDF"


def is_moveit_execution(data) -> bool:
    """MoveIt's execution settings: its controller list, or the file choosing its controller
    manager (``moveit_controller_manager``, ``trajectory_execution``)."""
    return is_moveit_controllers(data) or isinstance(data, dict) and any(
        key in data for key in ("moveit_controller_manager", "trajectory_execution"))


def is_moveit_controllers(data) -> bool:
    """MoveIt's controller list: ``controller_list`` (MoveIt 1) or
    ``moveit_simple_controller_manager`` (MoveIt 2), at the top or under ``ros__parameters``."""
    if not isinstance(data, dict):
        return False
    if "controller_list" in data or "moveit_simple_controller_manager" in data:
        return True
    return any(is_moveit_controllers(value.get("ros__parameters")) for value in data.values()
               if isinstance(value, dict))


def is_fake_controller_list(data) -> bool:
    """MoveIt's fake controller manager's list (``fake_controllers.yaml``): a
    ``controller_list`` whose entries name no ``action_ns`` and no simple controller manager
    type (``interpolate``, ``via points`` or none), beside nothing that configures a controller
    (its ``initial`` poses, moveit_sim_controllers' ``moveit_sim_hw_interface``); no controller
    runs it; a ``moveit_controller_manager`` beside it names the fake one."""
    if not isinstance(data, dict) or looks_like_controllers(
            {key: value for key, value in data.items() if key != "controller_list"}) or \
            "fake" not in str(data.get("moveit_controller_manager", "fake")).lower():
        return False
    return fake_list(data.get("controller_list"))


def users_below(companion: Path) -> Path:
    """The folder below which lie all the robots whose :func:`search_folders` may hold
    ``companion`` (the inverse of the search): the repository or package holding it (see
    :func:`~urdftool.description.packages.containment_root`); without either, the folder above
    a ``config/`` folder (a robot finds its own ``config/``), else the companion's folder."""
    folder = Path(os.path.abspath(companion)).parent
    root = containment_root(folder)
    return folder.parent if root == folder and folder.name == "config" else root


def search_folders(robot_path: Path) -> list[Path]:
    """The folders companions of the robot file ``robot_path`` are looked for in, as named
    (links not followed), each a folder inside the robot's repository: see the module doc."""
    return list(_search_folders(Path(os.path.abspath(robot_path))))


@per_run
def _search_folders(robot_path: Path) -> tuple[Path, ...]:
    root, named = _named_folders(robot_path)
    return tuple(folder for folder in named
                 if kind_of(folder, follow=False) == "folder" and inside(folder, root))


def _named_folders(robot_path: Path) -> tuple[Path, tuple[Path, ...]]:
    """(the robot's repository, the folders its companions are looked for in, each once, as
    the module doc names them, whatever is there)."""
    base = robot_path.parent
    root = containment_root(base)
    folders = [base, base / "config"]
    package = _package(base, root)
    if package is not None and package != base:
        folders.append(package / "config")
    home = package or base
    stems = {home.name.removesuffix("_description"), robot_path.name.split(".")[0]}
    for stem in sorted(stems):
        folders.append(home.parent / f"{stem}_moveit_config" / "config")
    return root, tuple(dict.fromkeys(folders))


@per_run
def _linked_folders(robot_path: Path) -> tuple[Path, ...]:
    """The folders companions are looked for in that are symbolic links: not entered, wherever
    they lead (:func:`_candidates` does not follow a link to another folder either)."""
    root, named = _named_folders(robot_path)
    return tuple(folder for folder in named
                 if kind_of(folder, follow=False) == "link" and inside(folder.parent, root))


def _package(base: Path, root: Path) -> Path | None:
    """The ROS package holding a robot in ``base``: the folder above a urdf/-like folder, else the
    nearest folder at or above ``base`` holding a package.xml or manifest.xml (inside ``root``)."""
    if base.name in URDF_FOLDERS and base != root and inside(base.parent, root):
        return base.parent
    for folder in [base, *base.parents]:
        if not inside(folder, root):
            return None
        if any(kind_of(os.path.join(folder, name)) == "file" for name in MANIFESTS):
            return folder
        if folder == root:
            return None
    return None


def _candidates(folders: list[Path], pattern: str, found: Companions | None = None) -> list[Path]:
    """Regular files matching ``pattern`` in ``folders`` whose real location is that folder
    (no link leading elsewhere); what else matches is ``found.unread`` (when given), with
    why."""
    paths = []
    for folder in folders:
        for path, why in _candidates_in(folder, pattern):
            if why is None:
                paths.append(path)
            elif found is not None:
                found.unread[path] = why
    return paths


@per_run
def _candidates_in(folder: Path, pattern: str) -> tuple[tuple[Path, str | None], ...]:
    """(path, None) of each regular file matching ``pattern`` in ``folder``, (path, why it
    is not read) of anything else so named."""
    real_folder = Path(real_path(folder))
    paths = []
    for name, kind in listing(folder, pattern):
        path = folder / name
        if kind == "link" and Path(real_path(path)).parent != real_folder:
            why = "a symbolic link to another folder: not followed"
        elif kind == "link":  # where a link leads is looked at only inside its folder
            kind = kind_of(path) or "link"
            why = None if kind == "file" else "a symbolic link to nothing" if kind == "link" \
                else "a link to a folder" if kind == "folder" else \
                "a link to a named pipe or device"
        else:
            why = None if kind == "file" else "a folder" if kind == "folder" else \
                "a named pipe or device, not a regular file"
        paths.append((path, why))
    return tuple(paths)


class _Owner:
    """Which robot of a shared folder a file found there belongs to."""

    def __init__(self, robot, folders: list[Path]):
        self.robot = robot
        self.path = Path(os.path.abspath(robot.path)) if robot.path != "-" else None
        self.keys = {k for k in (robot.name, self.path.name.split(".")[0] if self.path else "") if k}
        self.neighbours = _robots_beside(self.path) if self.path else []

    @property
    def alone(self) -> bool:
        return not self.neighbours

    def matches(self, path: Path) -> bool:
        """``path``'s name starts with this robot's key (at a separator), and with no
        neighbour's longer key."""
        return _match_length(path, self.keys) > max(
            (_match_length(path, {n.name.split(".")[0]}) for n in self.neighbours), default=0)

    def named_after_neighbour(self, path: Path) -> bool:
        """``path``'s name starts with another robot file's stem of the folder."""
        return any(_match_length(path, {n.name.split(".")[0]}) for n in self.neighbours)

    def claims(self, path: Path) -> tuple[bool, str]:
        """(whether ``path``, found automatically, is this robot's, why / why not)."""
        if self.matches(path):
            return True, "named after the robot"
        others = _moveit_package_of_another(path, self.robot)
        if others:
            return False, (f"in the MoveIt package of {display_path(others[0])}, the robot "
                           "its SRDF names")
        if self.alone:
            return True, "found beside the robot"
        return False, (f"{len(self.neighbours) + 1} robots share its folder and it is not named "
                       "after this one (ROBOT_...); --controllers/--srdf/--spec name it")


def _match_length(path: Path, keys) -> int:
    stem = path.name.split(".")[0].lower()
    best = 0
    for key in keys:
        key = key.lower()
        if stem == key or (stem.startswith(key) and stem[len(key)] in "_-."):
            best = max(best, len(key))
    return best


def _robots_beside(path: Path) -> list[Path]:
    """Other robots' files (``.urdf``, ``.urdf.xacro``) in the folder of ``path``: a file of
    the same stem is the same robot in another form (``panda.urdf``, xacro's output committed
    beside ``panda.urdf.xacro``), not a robot that files named after it could belong to."""
    stem = path.name.split(".")[0].lower()
    return [p for p in _robot_files(path.parent)
            if p.name != path.name and p.name.split(".")[0].lower() != stem]


@per_run
def _robot_files(folder: Path) -> tuple[Path, ...]:
    return tuple(folder / name for name, kind in listing(
        folder, "|".join(f"*{suffix}" for suffix in ROBOT_SUFFIXES))
                 if kind == "file" or kind == "link" and kind_of(folder / name) == "file")


def _auto_controllers(robot, folders, owner: _Owner, found: Companions) -> list[YamlFile]:
    files, seen = [], set()
    named = parameter_files(robot)
    for path in named:
        seen.add(real_path(path))
        files.append(controller_yaml(robot, path, "controllers named by the URDF"))
        found.used[files[-1].path] = "named by the URDF's <parameters>"
    facts = launched.runtime(robot) if robot.path != "-" else None
    loaded = facts.loaded_files() if facts is not None else []
    moveit_given = found.moveit_given  # MoveIt settings a launch file loads: it picks MoveIt's list
    for path in loaded:
        if real_path(path) in seen or path.name in SPEC_NAMES or path.name == "kinematics.yaml":
            continue
        parsed = controller_yaml(robot, path)
        if is_moveit_execution(parsed.data):
            moveit_given.append(path)
        if not looks_like_controllers(parsed.data) and not parsed.problem or is_fake_controller_list(parsed.data):
            continue
        seen.add(real_path(path))
        files.append(parsed)
        launches = sorted({launch_named(load.launch) for load in facts.loads(path)})
        found.used[path] = f"loaded by {', '.join(launches[:3])}"
    chosen = named or ([f for f in files if f.path not in named] if loaded else [])
    # A launch file loading a file urdftool cannot resolve may load any of those found
    decided = bool(named) or (bool(chosen) and not facts.unresolved_loads())
    for path in _candidates(folders, "*.yaml", found):
        if path.name in SPEC_NAMES or path.name == "kinematics.yaml" or real_path(path) in seen:
            continue
        parsed = controller_yaml(robot, path)
        in_config = path.parent.name == "config"
        if not (looks_like_controllers(parsed.data) or (in_config and parsed.problem)) or \
                is_fake_controller_list(parsed.data):
            continue
        if decided and not is_moveit_controllers(parsed.data):
            found.unused[path] = (
                f"the URDF's <parameters> names the robot's controller file ({display_path(named[0])})"
                if named else "no launch file of the robot loads it (they load "
                f"{', '.join(display_path(f.path) for f in chosen[:3])})")
            continue
        if moveit_given and is_moveit_controllers(parsed.data) and not facts.unresolved_loads():
            found.unused[path] = ("no launch file of the robot gives it to MoveIt (they give "
                                  f"{', '.join(display_path(p) for p in moveit_given[:2])})")
            continue
        if namer := _named_by_another(robot, path):
            found.unused[path] = (f"the <parameters> of {display_path(namer)}, which this robot "
                                  "does not include, names it: another robot's controllers")
            continue
        mine, why = owner.claims(path)
        if mine:
            files.append(parsed)
            found.used[path] = why
        else:
            found.unused[path] = why
    return files


_PARAMETERS = re.compile(rb"<parameters>([^<]*)</parameters>")  # (the value stripped where read)


def _named_by_another(robot, path: Path) -> Path | None:
    """A robot or part file of ``path``'s ROS package that names ``path`` (its folder and file
    name) in a ``<parameters>`` element, as a Gazebo ros2_control plugin gives its controller
    file, and that the robot does not read; None when none does, or one the robot reads does
    (or ``path`` is in no package: a file of another folder naming config/x.yaml may mean its
    own)."""
    if robot.path == "-":
        return None
    root = containment_root(path.parent)
    package = _package(path.parent, root)
    if package is None:
        return None
    tail = f"{path.parent.name}/{path.name}"
    namers = [f for f, value in _parameters_named(root).get(path.name, ())
              if value.endswith(tail) and _package(f.parent, root) == package]
    read = {real_path(os.path.abspath(f)) for f in robot.files}
    return namers[0] if namers and not any(real_path(f) in read for f in namers) else None


@per_run
def _parameters_named(root: Path) -> dict[str, list[tuple[Path, str]]]:
    """The ``<parameters>`` values written in the robot and part files below ``root``, by the
    file name each ends with: (the file writing it, the value). Bounded as :func:`_robot_names`
    is."""
    named: dict[str, list[tuple[Path, str]]] = {}
    for path, data in _robot_file_texts(root, "<parameters>"):
        for value in _PARAMETERS.findall(data) if b"<parameters>" in data else ():
            text = value.decode("utf-8", "replace").strip()
            named.setdefault(text.rsplit("/", 1)[-1], []).append((path, text))
    return named


def controller_yaml(robot, path: Path, as_: str = "companion YAML") -> YamlFile:
    """A controller YAML read as the robot's launch files load it (with or without
    substitution of its ``$(arg)``/``$(var)``; see ``CompanionFile.substituted``); as_: what
    it is read as, for the record."""
    if robot.path == "-":
        return read_yaml(path, as_)
    loads = launched.runtime(robot).loads(path)
    if not loads:
        return read_yaml(path, as_)
    if not any(load.substitute for load in loads):
        return read_yaml(path, as_, substituted=False)
    if not all(load.substitute for load in loads):
        return read_yaml(path, as_)
    values: dict[str, str | None] = {}
    for load in loads:
        for name, value in load.args.items():
            text = launched.shown_text(value)
            if values.setdefault(name, text) != text:
                values[name] = None  # loaded with different values: not known
    return read_yaml(path, as_, substituted=True,
                     substitutions={k: v for k, v in values.items() if v is not None})


def parameter_files(robot) -> list[Path]:
    """The YAML files a ``gazebo_ros2_control``/``gz_ros2_control`` plugin's ``<parameters>``
    names, resolved (absolute, ``package://``, ``$(find)`` already expanded, or relative to the
    robot's folder or its package), that are regular files inside the robot's repository."""
    if robot.path == "-":
        return []
    base = robot.base_dir
    root = containment_root(base)
    package = _package(base, root)
    found = []
    for plugin in gazebo_plugins(robot):
        text = f"{plugin.get('filename', '')} {plugin.get('name', '')}"
        if not any(name in text for name in CONTROL_PLUGINS):
            continue
        for element in plugin.iter("parameters"):
            value = (element.text or "").strip()
            path = _parameter_path(robot, value, base, package)
            if path is not None and inside(path, root) and kind_of(path) == "file" and \
                    path not in found:
                found.append(path)
    return found


def _parameter_path(robot, value: str, base: Path, package: Path | None) -> Path | None:
    if not value or "\0" in value or "$(" in value:
        return None
    if value.startswith(("package://", "file://")):
        try:
            return robot.resolver.resolve_uri(value, base)
        except Exception:  # an unknown package: nothing to follow
            return None
    path = Path(value)
    if path.is_absolute():
        return path
    for folder in (base, package):
        if folder is not None and kind_of(folder / path) == "file":
            return folder / path
    return None


def _pick_srdf(robot, folders, owner: _Owner, found: Companions) -> Path | None:
    paths = _candidates(folders, "*.srdf", found)
    named = [p for p in paths if owner.matches(p)]
    if named:
        chosen, why = named[0], "named after the robot"
    else:
        # by <robot name>, unless the file is named after another robot of the folder: it is
        # that robot's (a collision-spheres variant shares the robot name, not its SRDF)
        by_name = [p for p in paths if _srdf_robot_name(p) == robot.name and robot.name
                   and not owner.named_after_neighbour(p)]
        if by_name:
            chosen, why = by_name[0], f"its <robot name> is '{robot.name}'"
        elif len(paths) == 1 and owner.alone and not _anothers(paths[0], robot):
            chosen, why = paths[0], "the only SRDF found"
        else:
            chosen, why = None, ""
    for path in paths:
        others = [] if path == chosen or chosen else _anothers(path, robot)
        if path == chosen:
            found.used[path] = why
        elif others:
            found.unused[path] = (f"its <robot name> is '{_srdf_robot_name(path)}', the name of "
                                  f"{display_path(others[0])}")
        else:
            found.unused[path] = ("another SRDF was chosen" if chosen else
                                  "neither its name nor its <robot name> matches the robot, and "
                                  "it is not the only SRDF of a robot alone in its folder")
    return chosen


def _moveit_package_of_another(path: Path, robot) -> list[Path]:
    """The other robots whose MoveIt package holds ``path`` (a ``*_moveit_config/config``
    file): every SRDF there is theirs (:func:`_anothers`), so its controllers, kinematics and
    limits are too (deepwithin's YAM: the other arm got its MoveIt controllers' gripper
    joint). The package's SRDF is ``config/*.srdf``, or an ``.srdf.xacro`` there or in
    ``config/srdf/`` (PAL's packages: the TIAGo Pro's force-torque sensor, alone in its folder,
    got pal_sea_arm_moveit_config's joint limits). Empty for any other file."""
    folder = path.parent
    if folder.name != "config" or not folder.parent.name.endswith("_moveit_config"):
        return []
    srdfs = _candidates([folder, folder / "srdf"], _PACKAGE_SRDF)
    owners = [_anothers(srdf, robot) for srdf in srdfs]
    return owners[0] if srdfs and all(owners) else []


def _anothers(path: Path, robot) -> list[Path]:
    """The other robot files of the repository whose ``<robot name>`` is the SRDF ``path``'s
    when it is not ``robot``'s, and which look for companions where it is: the SRDF is theirs
    (deepwithin/yam_ros2_control's only SRDF, i2rt_arm's, was checked against the other arm of
    the repository, 'output': 33 errors). A robot of that name that would not find it (Rokae's
    generic xMate_robot, whose name every model's SRDF takes) claims nothing."""
    name = _srdf_robot_name(path)
    if not name or name == robot.name or robot.path == "-":
        return []
    mine, folder = real_path(os.path.abspath(robot.path)), Path(os.path.abspath(path.parent))
    return [other for other in _robot_names(containment_root(path.parent)).get(name, ())
            if real_path(other) != mine and folder in search_folders(other)]


_PACKAGE_SRDF = "*.srdf|*.srdf.xacro"  # a MoveIt package's SRDF, as written or as xacro
_ROBOT_NAME = re.compile(rb"<robot\b[^<>]*?\sname\s*=\s*[\"']([^\"'$<>]*)[\"']")
_HEAD = 64 * 1024  # [bytes] of a robot file where its <robot name> is looked for
_NAMED_MOST = 1024 * 1024  # [bytes] a robot file read for its name may have (larger: no name)
_NAMED_FILES = 2000  # robot files of a repository read for their names, at most


@per_run
def _robot_names(root: Path) -> dict[str, list[Path]]:
    """The robot files below the repository ``root`` by the ``<robot name>`` each declares
    (a literal one, in its first 64 kB; a name xacro substitutes is no name here). Regular
    files only (a link is not followed), of at most 1 MiB, 2,000 at most: a hostile repository
    costs what a repository of ordinary robots does."""
    names: dict[str, list[Path]] = {}
    for path, data in _robot_file_texts(root, "robot name"):
        found = _ROBOT_NAME.search(data[:_HEAD])
        if found:
            names.setdefault(found.group(1).decode("utf-8", "replace"), []).append(path)
    return names


def _robot_file_texts(root: Path, as_: str):
    """(path, bytes) of the robot and part files below ``root``: regular files only (a link is
    not followed), of at most 1 MiB, 2,000 at most; as_: what they are read for."""
    read = 0
    for folder, entries in walk(root, f"*/|{ROBOT_GLOB}", 1 << 30, SKIP_DIRS):
        for entry, kind in entries:
            if kind != "file" or read >= _NAMED_FILES:
                continue
            path, read = Path(folder) / entry, read + 1
            try:
                yield path, read_regular(path, _NAMED_MOST, as_=as_)
            except OSError:  # (over the size, or not a regular file any more)
                continue


def find_srdf(robot) -> Path | None:
    """The robot's SRDF when none is given (see the module doc); None for stdin. ``check`` and
    ``collisions`` both find it here."""
    if robot.path == "-":
        return None
    folders = search_folders(Path(robot.path))
    return _pick_srdf(robot, folders, _Owner(robot, folders), Companions())


def _srdf_robot_name(path: Path) -> str | None:
    parsed = read_srdf(path)
    return parsed.data.get("name") if parsed.data is not None else None


def _auto_yaml(folders, names, owner: _Owner, found: Companions, wanted, what: str,
               picked: SrdfFile | None = None):
    for name in names:
        for path in _candidates(folders, name, found):
            parsed = read_yaml(path)
            if not wanted(parsed):
                continue
            if other := _written_for_another_srdf(path, picked):
                found.unused[path] = (f"its package's .setup_assistant writes it for "
                                      f"{display_path(other)}, not for this robot's SRDF")
                continue
            mine, why = owner.claims(path)
            if mine or path.parent.name == "config" and path.parent.parent.name.endswith(
                    "_moveit_config") and not _moveit_package_of_another(path, owner.robot):
                found.used[path] = why if mine else "in the robot's MoveIt package"
                return parsed
            found.unused[path] = why
    return None


def is_spec(data) -> bool:
    """A urdftool joint spec: a mapping with top-level ``unit`` and ``joints`` keys."""
    return isinstance(data, dict) and "unit" in data and "joints" in data


_CONTROLLER_KEYS = ("controller_manager", "controller_list", "controller_names",
                    "moveit_simple_controller_manager")


def looks_like_controllers(data, depth: int = 0) -> bool:
    """A controller configuration: ``type: pkg/Class`` in some mapping, a ``controller_manager``,
    or MoveIt's ``controller_list``/``controller_names``/``moveit_simple_controller_manager``."""
    if not isinstance(data, dict) or depth > 6:
        return False
    if any(key in data for key in _CONTROLLER_KEYS):
        return True
    kind = data.get("type")
    if isinstance(kind, str) and "/" in kind:
        return True
    return any(looks_like_controllers(value, depth + 1) for value in data.values())




def may_use(robot_path: Path, companion: Path, text: bytes = b"") -> bool:
    """Whether the robot in file ``robot_path`` (not loaded; ``text``: its bytes) may be checked
    with ``companion`` when discovery runs: the file is in one of its search folders and the
    robot is alone there or the file is named after it (an SRDF may also match by its
    ``<robot name>``, known only once the robot is loaded), or the robot's file names it (a
    ``<parameters>`` path). Errs on the side of yes: the check itself decides exactly."""
    if os.fsencode(companion.name) in text:  # (a name's bytes as the file system gives them)
        return True
    real = Path(real_path(companion))
    if not any(real.parent == Path(real_path(folder)) for folder in search_folders(robot_path)):
        return False
    stem = robot_path.name.split(".")[0]
    beside = _robots_beside(Path(os.path.abspath(robot_path)))
    return (not beside or companion.suffix == ".srdf"
            or _match_length(companion, {stem}) > max(
                (_match_length(companion, {p.name.split(".")[0]}) for p in beside), default=0))
