"""What runs with one robot: its launch configurations, the controllers they start, the ROS
versions that read it. Decided once per robot (kept in ``Robot.memo``) and used by every rule.

A launch configuration is the robot's when it describes the robot's file
(:mod:`urdftool.description.launch_configs`): *as checked* when every xacro argument it gives
has the value the robot was checked with (``--arg``, else the ``<xacro:arg>`` default), else
*with other arguments*. A controller then runs (:func:`runs`):

- ``certain``: a configuration of the robot as checked starts it, active, unconditionally, and
  loads its file (or the URDF's ``<parameters>`` names the file);
- ``conditional``: a configuration starts it only under a launch argument or condition, with
  other xacro arguments, or one that describes no robot urdftool can tell; ``condition`` says
  which, in words;
- ``never``: the robot's configurations load its file, read every spawner, and start it in none;
- ``unknown``: no launch file of the robot says (the rules then judge what is certain without
  them: see docs/certainty.md).

The ROS versions that read the robot are :mod:`urdftool.description.ros_version`'s (its launch
files are part of the evidence).
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from urdftool.description.documents import read_yaml
from urdftool.description.files import DEFAULT_MAX_FILE_SIZE, enclosing_root, kind_of, listing, \
    read_regular, real_path
from urdftool.description.launch import MAX_LAUNCH_SIZE, is_launch_file, is_launch_test, named
from urdftool.description.launch_configs import (BY_DEFAULT, WILD, Configuration, Described,
                                                 Loaded, Resolved, Started, launch_file_packages,
                                                 launch_files, launch_index, launch_tests,
                                                 read_launch,
                                                 shown)
from urdftool.description.packages import (build_tools, containment_root, declared_dependencies,
                                           package_name, package_of, packages_below)
from urdftool.description.run_memo import per_run
from urdftool.description.xacro_text import ARG_DEFAULT
from urdftool.diagnostics import display_path
from urdftool.records import Frozen, NEW, Record, replace

AS_CHECKED = "as checked"  # a configuration's relation to the robot: built as it was checked
SPAWNERS = ("spawner", "spawner.py", "controller_manager")
STATE_PUBLISHERS = ("joint_state_publisher", "joint_state_publisher_gui")
_INACTIVE = ("--stopped", "--inactive", "--load-only")
_VALUED = {"-c", "--controller-manager", "-p", "--param-file", "-n", "--namespace", "-t",
           "--controller-type", "--controller-manager-timeout", "--switch-timeout",
           "--service-call-timeout", "--timeout", "--shutdown-timeout", "--controller-ros-args",
           "--fallback_controllers", "--fallback-controllers"}


class Spawn(Frozen):
    """A controller a configuration of the robot starts (or loads inactive)."""

    name: str
    active: bool
    configuration: Configuration
    start: Started
    certain: bool  # unconditional, name not from an argument, robot as checked
    condition: str  # when, in words ("when gui is true"), when not certain

    __slots__ = ("name", "active", "configuration", "start", "certain", "condition")

    def __init__(self, name: str, active: bool, configuration: Configuration, start: Started,
                 certain: bool, condition: str) -> None:
        set_field = object.__setattr__
        set_field(self, "name", name)
        set_field(self, "active", active)
        set_field(self, "configuration", configuration)
        set_field(self, "start", start)
        set_field(self, "certain", certain)
        set_field(self, "condition", condition)

    def told(self) -> str:
        """Which launch file starts it, and when."""
        return f"{self.configuration.named} starts it" + (f" {self.condition}" if self.condition else "")


class Runtime(Record):
    """The robot's launch configurations and what they start.

    configurations: (configuration, how it describes the robot: "as checked", "with other
        xacro arguments (a:=b)", or "" when it describes no robot urdftool can tell)
    """

    configurations: list
    spawns: list
    unread_spawners: list  # (configuration, start) with names not read
    read: list  # every launch file read to tell it (the index's)

    __slots__ = ("configurations", "spawns", "unread_spawners", "read")

    def __init__(self, configurations: list = NEW, spawns: list = NEW, unread_spawners: list = NEW,
                 read: list = NEW) -> None:
        self.configurations = [] if configurations is NEW else configurations
        self.spawns = [] if spawns is NEW else spawns
        self.unread_spawners = [] if unread_spawners is NEW else unread_spawners
        self.read = [] if read is NEW else read

    @property
    def described(self) -> list[Configuration]:
        return [c for c, relation in self.configurations if relation]

    def loads(self, path: Path) -> list[Loaded]:
        """Every load of the parameter file ``path`` by the robot's configurations."""
        key = real_path(path)
        return [loaded for c, relation in self.configurations if relation for loaded in c.loaded
                if loaded.path is not None and real_path(loaded.path) == key]

    def loaded_files(self) -> list[Path]:
        """The parameter files the robot's configurations load (resolved, once each)."""
        found: dict[str, Path] = {}
        for configuration, relation in self.configurations:
            if relation:
                for loaded in configuration.loaded:
                    if loaded.path is not None:
                        found.setdefault(real_path(loaded.path), loaded.path)
        return list(found.values())

    def outside(self) -> list[tuple[str, int | None, str]]:
        """(launch file as shown, line, the path as written) of each parameter file or launch
        file the robot's configurations name that leads outside the repository (not read),
        once each."""
        return list(dict.fromkeys(entry for c, relation in self.configurations if relation
                                  for entry in c.outside))

    def unresolved_loads(self) -> list[Loaded]:
        return [loaded for c, relation in self.configurations if relation for loaded in c.loaded
                if loaded.path is None]

    def starts(self, package: str, executables=()) -> list[tuple[Configuration, Started]]:
        return [(c, s) for c, relation in self.configurations if relation for s in c.started
                if s.package == package and (not executables or s.executable in executables)]

    def describe(self) -> list[str]:
        """One line per configuration of the robot, for ``check -v``."""
        lines = []
        for configuration, relation in [(c, r) for c, r in self.configurations if r][:12]:
            spawned = [s for s in self.spawns if s.configuration is configuration]
            parts = [f"describes the robot {relation}"]
            files = list(dict.fromkeys(loaded.written for loaded in configuration.loaded
                                       if loaded.path is not None and loaded.path.suffix in (".yaml", ".yml")))
            if files:
                parts.append("loads " + ", ".join(files[:6]) + (" ..." if len(files) > 6 else ""))
            if spawned:
                parts.append("starts controllers " + ", ".join(
                    dict.fromkeys(s.name + ("" if s.active else " (inactive)")
                                  + (f" ({s.condition})" if s.condition else "") for s in spawned)))
            lines.append(f"{configuration.named}: " + "; ".join(parts))
        return lines


def runtime(robot) -> Runtime:
    """What the robot's launch files start (read once per robot)."""
    return robot.memo(runtime, lambda: _runtime(robot))


def launch_files_read(robot) -> list[Path]:
    """The launch files the robot's findings were told by: none when no rule asked."""
    return runtime(robot).read if robot.memoized(runtime) else []


def _launch_root(folder: Path) -> Path | None:
    """The repository (or, without one, the package) whose launch files may run the robot in
    ``folder``; None for a robot in neither: a launch file finds a robot through its package
    (``$(find pkg)``, ``FindPackageShare``), and the files around a lone robot file (a
    download folder, the user's cache folder) are not its launch files."""
    return enclosing_root(Path(os.path.abspath(folder)))


def _robot_root(robot) -> tuple[Path, Path] | None:
    """(the robot file's absolute path, the root whose launch files may run it), or None."""
    if robot.path == "-":
        return None
    path = Path(os.path.abspath(robot.path))
    root = _launch_root(path.parent)
    return None if root is None else (path, root)


def _runtime(robot) -> Runtime:
    found = Runtime()
    placed = _robot_root(robot)
    if placed is None:
        return found
    path, root = placed
    index = launch_index(root, may_run(root, path))
    found.read = [launch.path for launch in index.files.values()]
    real = real_path(path)
    mine = None
    environment = _environment_names(robot)
    for configuration in index.configurations:
        described = [d for d in configuration.described if d.path is not None]
        relation = ""
        for description in described:
            if real_path(description.path) == real:
                mine = mine if mine is not None else _robot_args(robot)
                relation = _relation(description, mine, relation, packages_below(root))
        if relation == AS_CHECKED and environment:
            # the robot as checked is one build: what the environment says at launch decides it
            relation = f"as the environment builds it ({', '.join(environment[:4])})"
        if relation or not described:
            found.configurations.append((_narrowed(configuration, real, path, root) if relation
                                         else configuration, relation))
    for configuration, relation in found.configurations:
        _spawns(configuration, relation, found)
    return found


@per_run
def may_run(root: Path, path: Path) -> frozenset | None:
    """The launch files of the repository ``root`` (named as
    :func:`~urdftool.description.launch_configs.launch_files` names them) that may run the
    robot file ``path``, told from their bytes, never parsed; None when every one may. The one
    owner of whose a launch configuration is before it is read: a launch file finds a robot
    through its package or its file, so it may run the robot when

    - it is in the robot's package (or, the robot in no package, in none either), or its
      package's package.xml depends on the robot's package;
    - its text names the robot's package, or its file (the name before its first ``.``:
      ``r2d2`` of ``r2d2.urdf.xacro``, as ``f"{robot}.urdf.xacro"`` builds it), as a word
      (``robot`` is not named by ``robot_description``, nor ``arm`` by ``my_arm.urdf``);
    - its text names a launch file that may run it (its file name), or the package holding
      one: an include of it.

    Any other is another robot's, or no robot's: what it loads and starts, even describing no
    robot, is not this robot's (a launch file that cannot be read may run it: it is read, and
    its problem is told). What it includes is read as it includes it."""
    paths = launch_files(root)[0]
    holders = launch_file_packages(root)
    folder = package_of(path)
    own = None if folder is None else os.fspath(folder)
    name = None if folder is None else package_name(folder)
    names = [os.fsencode(word) for word in (name, path.name.split(".")[0] or path.name) if word]
    may, texts, depending = [], {}, {own: True}
    for launch in paths:
        key = os.fspath(launch)
        holder = holders.get(key)
        if holder not in depending:
            depending[holder] = name is not None and holder is not None and \
                name in (declared_dependencies(Path(holder)) or ())
        if depending[holder]:
            may.append(key)
            continue
        try:
            texts[key] = read_regular(launch, MAX_LAUNCH_SIZE, as_="launch")
        except OSError:
            may.append(key)
    if not texts:
        return None
    told, grown = 0, True
    while grown and texts:  # each launch file that may run it names more: its includers may
        for key in may[told:]:
            holder = holders.get(key)
            names.append(os.fsencode(os.path.basename(key)))
            if holder is not None and holder != own:
                names.append(os.fsencode(package_name(Path(holder)) or ""))
        told, names = len(may), [word for word in dict.fromkeys(names) if word]
        # a name as a word: not arm of my_arm.urdf, nor robot of robot_description
        naming = re.compile(rb"(?<!\w)(?:" + b"|".join(map(re.escape, names)) + rb")(?!\w)")
        for key, data in list(texts.items()):
            if naming.search(data):
                may.append(key)
                del texts[key]
        grown = len(may) > told
    return frozenset(may) if texts else None


def _narrowed(configuration: Configuration, real: str, path: Path, root: Path) -> Configuration:
    """``configuration`` as the robot (real path ``real``) has it:

    - what a launch file that describes other robots only loads and starts is theirs.
      ai_worker's ffw_bg2_ai.launch.py includes the follower's launch file and the leader's,
      each describing its robot and starting its own controller manager with its own
      controllers file: the follower's file is not the leader's companion. A launch file
      describing no robot (or this one too) stays shared;
    - what it loads or starts only under a condition that excludes every build of the robot
      is another robot's: Doosan's dsr_base.launch builds ``$(arg model).urdf.xacro`` when
      ``mobile == 'none'`` and ``$(arg model)mobile.urdf.xacro`` when ``mobile == 'husky'``,
      and spawns the wheels' controller when ``mobile == 'husky'``: never with the arm alone
      (:meth:`~urdftool.description.launch_configs.When.excludes`). The builds an action
      goes with are those of the nearest launch file including it that builds any robot (its
      own, else its includer's, ...): dsr_base.launch's, not the arm MoveIt's launch file
      builds for planning beside it, whatever ``mobile`` is. A build whose file is not known
      (a path not resolved), or that a launch argument may choose (:func:`_template_matches`),
      may be this robot's: its condition counts too."""
    described = [d for d in configuration.described if d.path is not None]
    mine = {d.launch for d in described if real_path(d.path) == real}
    others = {d.launch for d in described if real_path(d.path) != real} - mine
    builds = [d for d in configuration.described
              if d.path is None or real_path(d.path) == real
              or _template_matches(d.template, path, packages_below(root))]

    def its(action) -> bool:
        if action.launch in others:
            return False
        near = builds
        for end in range(len(action.chain), 0, -1):
            if any(d.chain[:end] == action.chain[:end] for d in configuration.described):
                near = [d for d in builds if d.chain[:end] == action.chain[:end]] or builds
                break
        # a description reaches the controller manager only where it is published to it
        return any(not action.when.excludes(d.published or d.when) for d in near)

    loaded = [load for load in configuration.loaded if its(load)]
    started = [start for start in configuration.started if its(start)]
    if len(loaded) == len(configuration.loaded) and len(started) == len(configuration.started):
        return configuration
    return replace(configuration, loaded=loaded, started=started)


_ENVIRONMENT = re.compile(rb"\$\((?:opt)?env\s+([A-Za-z_][A-Za-z0-9_]*)")


def _environment_names(robot) -> list[str]:
    """The environment variables the robot's files read (``$(optenv MOVO_HAS_ARM false)``)."""
    found = []
    for data in robot.sources.values():
        found.extend(name.decode() for name in _ENVIRONMENT.findall(data))
    return list(dict.fromkeys(found))


def _relation(description: Described, mine: dict, before: str, packages: dict) -> str:
    """How ``description`` gives the robot: "as checked", "as checked when launched with
    description_package's default 'x'" (:attr:`~urdftool.description.launch_configs.Described.
    by_default`: it is this robot only so, and nothing it runs is certain), or "with other xacro
    arguments (...)"; the better of it and ``before``."""
    if before == AS_CHECKED:
        return before
    other = []
    for name, value in description.args.items():
        if name not in mine:
            continue
        given = _as_given(value, packages)
        if given is None:
            other.append(f"{name} unknown")
        elif _normal(given) != _normal(mine[name]):
            other.append(f"{name}:={shown_text(value)}")
    if other:
        return before or f"with other xacro arguments ({', '.join(other[:4])})"
    if description.when.truth is True and description.by_default:
        # the package holding the file is named by launch arguments: it is this robot for
        # their defaults only
        return before if before.startswith(AS_CHECKED) else f"{AS_CHECKED} {description.by_default}"
    if description.when.truth is True:
        return AS_CHECKED
    return before or f"only {description.when.text() or 'under a condition'}"


def _normal(text: str) -> str:
    text = text.strip()
    if len(text) >= 2 and text[0] == text[-1] and text[0] in "'\"":
        text = text[1:-1]
    return text.lower() if text.lower() in ("true", "false") else text


def _robot_args(robot) -> dict:
    """Xacro argument -> the value the robot was checked with (given, else its literal
    default)."""
    found: dict = {}
    for data in robot.sources.values():
        for name, default in ARG_DEFAULT.findall(data):
            if b"$(" not in default:
                found.setdefault(name.decode("utf-8", "replace"), default.decode("utf-8", "replace"))
    found.update({str(k): str(v) for k, v in getattr(robot, "xacro_args", {}).items()})
    return found


def _spawns(configuration: Configuration, relation: str, found: Runtime) -> None:
    for start in configuration.started:
        names = _spawned(start)
        if names is None:
            continue
        active, listed = names
        if any(word is None for word in listed):
            found.unread_spawners.append((configuration, start))
        for word in listed:
            if word is None:
                continue
            text, free = word
            when = start.when
            certain = when.certain and not free and relation == AS_CHECKED
            words = [w for w in when.words]
            if free:
                words.append("by default (" + ", ".join(
                    f"the launch argument {name}" if not name.startswith("$")
                    else f"the environment variable {name[1:]}" for name in sorted(free)) + " names it)")
            if relation != AS_CHECKED:
                words.append(f"against the robot {relation}" if relation else
                             "against a robot description urdftool cannot tell")
            found.spawns.append(Spawn(text, active, configuration, start, certain, " and ".join(words)))


def _spawned(start: Started):
    """(active, [(name, free arguments) or None for a name not read]) when ``start`` starts
    controllers; None when it is not a spawner."""
    words = [w.text for w in start.arguments]
    frees = [w.free for w in start.arguments]
    executable = start.executable or ""
    if start.package == "controller_manager" and executable in ("spawner", "spawner.py"):
        pass
    elif start.package == "controller_manager" and executable == "controller_manager" and words:
        verb = words[0]
        if verb not in ("spawn", "load"):
            return None
        active = verb == "spawn"
        return active, [(w, f) if w is not None else None for w, f in zip(words[1:], frees[1:])
                        if w is None or not w.startswith("-")]
    elif not start.package and executable.split()[:3] == ["ros2", "control", "load_controller"]:
        parts = executable.split()[3:]
        active = "active" in parts
        return active, [(w, frozenset()) for w in parts if not w.startswith("-")
                        and w not in ("active", "inactive", "configured")]
    else:
        return None
    active = not any(w in _INACTIVE for w in words if w is not None)
    listed, skip = [], False
    for word, free in zip(words, frees):
        if skip:
            skip = False
            continue
        if word is None:
            listed.append(None)
            continue
        if word.startswith("-"):
            skip = word in _VALUED
            continue
        listed.append((word, free))
    return active, listed


def _as_given(value: Resolved, packages: dict) -> str | None:
    """A launch argument's value as xacro gets it: a package's place as its folder."""
    if value.text is None:
        return None
    parts = value.text.split("\0")
    if len(parts) % 2 == 0:
        return None
    text = "".join(str(packages[p]) if i % 2 else p for i, p in enumerate(parts))
    # the command line is split as a shell splits it: prefix:='""' gives an empty prefix
    return text[1:-1] if len(text) >= 2 and text[0] == text[-1] and text[0] in "'\"" else text


def shown_text(value: Resolved) -> str | None:
    """A launch argument's value as substituted into a file (a package folder as the path)."""
    if value.text is None:
        return None
    return shown(value) if "\0" in value.text else value.text


class Build(Frozen):
    """A launch file making a robot description from a file (:func:`builds`).

    launch: the launch file a user runs (its includes followed); ``written``: the one holding
        the description, and ``line`` there
    xacro: the file is run through xacro (else read as it is: ``textfile=``, ``cat``, ``open``)
    args: xacro argument -> its value as xacro gets it (None: not known without running it)
    complete: every argument given is in ``args`` (no word or mapping left unread)
    chosen: a launch argument chooses the file (``talos_$(arg robot).urdf.xacro``) or the package
        holding it (``$(find $(arg description_package))``): built so for its default only, or
        its default names another file
    condition: when the description is made, in words; "" when unconditionally
    test: ``launch`` is a launch test (it builds the file for the test alone)
    replaced: read as it is, with these texts replaced in it first (None: one not known
        without running the launch file): a template the launch file fills
    """

    launch: str
    written: str
    line: int | None
    xacro: bool
    args: dict
    free: frozenset
    complete: bool
    chosen: bool
    condition: str
    test: bool
    replaced: tuple

    __slots__ = ("launch", "written", "line", "xacro", "args", "free", "complete", "chosen",
                 "condition", "test", "replaced")

    def __init__(self, launch: str, written: str, line: int | None, xacro: bool, args: dict,
                 free: frozenset, complete: bool, chosen: bool, condition: str, test: bool = False,
                 replaced: tuple = ()) -> None:
        set_field = object.__setattr__
        set_field(self, "launch", launch)
        set_field(self, "written", written)
        set_field(self, "line", line)
        set_field(self, "xacro", xacro)
        set_field(self, "args", args)
        set_field(self, "free", free)
        set_field(self, "complete", complete)
        set_field(self, "chosen", chosen)
        set_field(self, "condition", condition)
        set_field(self, "test", test)
        set_field(self, "replaced", replaced)

    @property
    def named(self) -> str:
        """The launch file or test run, as a finding names it."""
        return named(self.launch, self.test)

    def named_at(self) -> str:
        """Where it builds the robot, as a finding names it: the file and line, and the launch
        file run when an include of it holds the description."""
        at = f"{self.written}:{self.line or '?'}"
        return named(at, self.test) if self.written == self.launch else \
            f"{named(at)} (run by {self.named})"

    @property
    def certain(self) -> bool:
        """Made, from this very file, whenever the launch file runs."""
        return not self.chosen and not self.condition

    def shown_args(self, limit: int = 6) -> str:
        texts = [f"{k}:={display_path(v) if v and os.path.isabs(v) else v}"
                 for k, v in sorted(self.args.items()) if v is not None][:limit]
        return ", ".join(texts) + (" ..." if len(self.args) > limit else "")


def builds(path: str) -> list[Build]:
    """How the launch files of the repository holding ``path`` make a robot description from
    it: one :class:`Build` per launch file a user runs and description action, in the index's
    order, those from a package a launch argument names (built for its default only) after the
    others, so that a robot needing an argument is checked as a launch file naming its package
    builds it when one does. The one owner of "this file is loaded through xacro by launch files
    X" and of "launch file X gives it these xacro arguments": loading a ``.urdf`` that holds
    xacro, and the rules on xacro errors and on xacro in a ``.urdf``, ask here. Empty for stdin,
    or a file in no repository or package."""
    absolute, root = _file_root(path)
    if root is None:
        return []
    index, packages = launch_index(root), packages_below(root)
    real, found, by_default = real_path(absolute), [], []
    # launch tests too: a test shows how the file is built, not what a deployment starts
    for configuration in index.configurations + launch_tests(root):
        for described in configuration.described:
            exact = described.path is not None and real_path(described.path) == real
            if described.when.truth is False or not (
                    exact or _template_matches(described.template, absolute, packages)):
                continue
            chosen = not exact or described.template is not None
            # an argument from the launch argument choosing the file follows the choice
            texts = {name: None if chosen and value.free & described.chosen_by
                     else _as_given(value, packages) for name, value in described.args.items()}
            free = frozenset().union(*(value.free for value in described.args.values()))
            words = list(described.when.words) if not described.when.certain else []
            if described.by_default:  # its includes' and its own, said once
                words = [described.by_default] + [w for w in words if not w.startswith(BY_DEFAULT)]
            if described.when.truth is None and not words:
                words = ["under a condition urdftool cannot tell"]
            (by_default if described.by_default else found).append(Build(
                configuration.display, described.launch, described.line, described.xacro, texts,
                free, described.complete, chosen, " and ".join(dict.fromkeys(words)),
                configuration.top.test, described.replaced))
    return found + by_default


def built_by(launch_path: str) -> list[Path]:
    """The robot files the launch file ``launch_path`` makes a description from, as a user runs
    it, or as the launch files running it (its includers) do, in the index's order; not the
    ones it makes only under a condition known false. Empty for a file the index did not read
    (no launch file, or one in no repository or package)."""
    absolute, root = _file_root(launch_path)
    if root is None:
        return []
    real, found = real_path(absolute), {}
    for configuration in launch_index(root).configurations:
        if real_path(configuration.top.path) == real or real in configuration.included:
            for described in configuration.described:
                if described.path is not None and described.when.truth is not False:
                    found.setdefault(real_path(described.path), Path(described.path))
    return list(found.values())


def why_builds_nothing(launch_path: str) -> str:
    """Why the launch file ``launch_path`` gives :func:`built_by` no robot file, in words
    completing "a launch file that ...": it is in no repository or package (whose launch files
    are read), it could not be read (its problem: not well-formed, over the size limit or the
    reading budget, ...; the one reading, :func:`~urdftool.description.launch_configs.
    read_launch`, asked again), it is not among the launch files read below its root (past
    their bound, or leading outside), or it was read and builds none urdftool can tell."""
    absolute, root = _file_root(launch_path)
    if root is None:
        return "is in no repository or package, whose launch files urdftool reads"
    if real_path(absolute) in launch_index(root).files:
        return "builds no robot file urdftool can tell"
    if real_path(absolute) not in {real_path(p) for p in launch_files(root)[0]}:
        return f"is not among the launch files urdftool reads below {display_path(root)}"
    return f"could not be read ({_problem(absolute, root)[0]})"


@per_run
def _problem(launch: Path, root: Path) -> tuple[str, int | None]:
    """Why the launch file ``launch`` of the repository ``root`` could not be read, and the
    line it is at when the parser said, as its one reading
    (:func:`~urdftool.description.launch_configs.read_launch`, asked again, once a run: a file
    ``ast`` cannot parse costs its parse again) found."""
    read = read_launch(launch, root)
    return (getattr(read, "problem", None) or "what it does is not known",
            getattr(read, "problem_line", None))


def _file_root(path: str) -> tuple[Path | None, Path | None]:
    """A robot file's absolute path and the root whose launch files may build it (None, None
    for stdin)."""
    if path == "-":
        return None, None
    absolute = Path(os.path.abspath(path))
    return absolute, _launch_root(absolute.parent)


def unread_naming(path: str, words: tuple[str, ...] = (), tests: bool = True) -> list[str]:
    """The launch files (and, with ``tests``, launch tests) of the repository holding ``path``
    that could not be read (not well-formed, not valid Python, a merge conflict left in, over
    the reading budget: :func:`~urdftool.description.launch.was_read`) and whose text names its
    file (or any of ``words``), as findings name them: what they do with it is not known. The
    one answer to "could not read" for every question the launch files answer: a rule that
    finds no build of a kind (:func:`builds`, tests included), or a controller started nowhere
    (:func:`runs`, launch files only), asks here before it says there is none. A Python file
    placed or named as a test counts when its text defines the launch test's entry point."""
    return [named(display_path(launch), test, read=False)
            for launch, test in _unread_naming(path, words, tests)]


def _unread_naming(path: str, words: tuple[str, ...], tests: bool,
                   running: bool = False) -> list[tuple[Path, bool]]:
    """(path, whether a launch test) of each launch file not read that :func:`unread_naming`
    names; with ``running``, only those that may run the robot file ``path``
    (:func:`may_run`): the question is what runs with it."""
    absolute, root = _file_root(path)
    if root is None:
        return []
    names = [os.fsencode(word) for word in words] or [os.fsencode(absolute.name)]  # (a name
    # may hold bytes that are not UTF-8: a file name's as the file system gives them)
    only = may_run(root, absolute) if running else None
    return [(launch, test) for launch, data, test in _not_read(root, tests, only)
            if any(name in data for name in names)]


def unread_describing(path: str) -> list[tuple[str, str, int | None]]:
    """(the launch file as shown, why it could not be read, the line) for each launch file of the
    repository holding the robot file ``path`` that names it and could not be read
    (:func:`unread_naming`, launch tests left out): what it loads, starts and builds the
    robot with is not known, and is not checked."""
    root = _file_root(path)[1]
    return [(display_path(launch), *_problem(launch, root))
            for launch, _ in _unread_naming(path, (), tests=False, running=True)]


@per_run
def _not_read(root: Path, tests: bool,
              only: frozenset | None = None) -> tuple[tuple[Path, bytes, bool], ...]:
    """(path, text, whether it is a launch test) of each launch file (and, with ``tests``,
    each launch test) of the repository ``root`` that was not read (:func:`unread_naming`);
    with ``only``, of those launch files (:func:`may_run`)."""
    read = set(launch_index(root, only).files) | (
        {real_path(c.top.path) for c in launch_tests(root)} if tests else set())
    found = []
    for launch in launch_files(root, tests=tests)[0]:
        if only is not None and os.fspath(launch) not in only or real_path(launch) in read:
            continue
        try:  # (up to any file's limit: one over a launch file's is not read, and is said so
            # when it names the file, not left out in silence)
            data = read_regular(launch, DEFAULT_MAX_FILE_SIZE, as_="launch")
        except OSError:
            continue
        test = is_launch_test(data.decode("utf-8", "replace"))
        if (test and tests) or (not test and is_launch_file(launch, root)):
            found.append((launch, data, test))
    return tuple(found)


def _template_matches(template: str | None, path: Path, packages: dict) -> bool:
    """Whether the file ``path`` is one a launch argument may choose: ``template`` (a
    description's path with WILD for the argument's value, ``\\0pkg\\0`` for a package's
    folder) matches it, each WILD standing for part of one path segment. The template is
    read as the file system reads it, its ``..`` and ``.`` folded (roslaunch's
    ``$(dirname)/../urdf/$(arg device)_gripper.urdf``, aist_robotiq)."""
    if template is None:
        return False
    parts = template.split("\0")
    if len(parts) % 2 == 0 or any(WILD in p for p in parts[1::2]):
        return False
    texts = []
    for index, part in enumerate(parts):
        if index % 2:
            folder = packages.get(part)
            if folder is None:
                return False
            texts.append(str(folder))
        else:
            texts.append(part)
    written = "".join(texts).replace("//", "/")
    if not written.startswith("/"):
        return False
    pattern = "[^/]+".join(re.escape(piece) for piece in os.path.normpath(written).split(WILD))
    return re.fullmatch(pattern, os.path.normpath(str(path))) is not None


def launch_xacro_args(path: str, argument: str) -> list[tuple[Build, dict]]:
    """(build, the xacro arguments it gives whose values are known) for each launch file that
    runs ``path`` through xacro giving ``argument`` a known value; the same arguments once.
    What to build a robot with when it needs an argument that has no default: the arguments
    only given at launch are left to the robot's defaults."""
    found, seen = [], set()
    for build in builds(path):
        if not build.xacro or build.args.get(argument) is None:
            continue
        known = {name: text for name, text in build.args.items() if text is not None}
        key = tuple(sorted(known.items()))
        if key not in seen:
            seen.add(key)
            found.append((build, known))
    return found


def built_otherwise(robot) -> list[tuple[Build, list[str]]]:
    """(build, the robot's xacro arguments it gives another value, as ``name:=value``) for each
    launch file (or launch test) that runs the robot's file through xacro, when every one of
    them gives one of the robot's ``<xacro:arg>`` another value than it was checked with (its
    default, or ``--arg``): what xacro made as checked is then no build they run, and a finding
    of it may not hold in theirs (lbr-stack's ``mode`` defaults to ``true``, which no
    ``xacro:if`` of its hardware macro takes; every launch file gives ``mode:=mock|gazebo|
    hardware``). Empty when one builds it as checked, or none builds it (the finding is then
    on a build that runs, or on the file as written). A value known only at launch is
    another value; an argument a build may give without its being read counts as given as
    checked."""
    if robot.path == "-":
        return []
    mine, found = None, []
    for build in builds(robot.path):
        if not build.xacro:
            continue
        mine = mine if mine is not None else _robot_args(robot)
        other = [f"{name}:={'(known only at launch)' if value is None else value}"
                 for name, value in sorted(build.args.items())
                 if name in mine and (value is None or _normal(value) != _normal(mine[name]))]
        if not other:
            return []
        found.append((build, other))
    return found


def built_as_checked(robot) -> bool:
    """Whether a launch file (or launch test) runs the robot's file through xacro with the
    arguments it was checked with: what xacro made as checked is then a build that runs."""
    return robot.path != "-" and any(build.xacro for build in builds(robot.path)) and \
        not built_otherwise(robot)


class Placeholders(Frozen):
    """Names that clash in the robot as checked only because xacro arguments kept an empty
    default (:func:`placeholder_clashes`): ``args`` those arguments, in the order declared;
    ``links`` and ``joints`` the clashing names that differ once each is given a value of its
    own."""

    args: tuple
    links: frozenset
    joints: frozenset

    __slots__ = ("args", "links", "joints")

    def __init__(self, args: tuple, links: frozenset, joints: frozenset) -> None:
        set_field = object.__setattr__
        set_field(self, "args", args)
        set_field(self, "links", links)
        set_field(self, "joints", joints)


def placeholder_clashes(robot) -> Placeholders | None:
    """What of the robot's clashing link and joint names comes from placeholder arguments: a
    dual arm whose arms take their names from ``prefix_1`` and ``prefix_2``, both declared
    ``default=""``, names both arms alike when xacro runs without arguments, and urdfdom
    refuses it; the launch file building it gives each a value (abb_ros2_control reads them
    from a YAML file at launch). The robot is built once more with each argument declared with
    an empty default and not given a value of its own (``robot.rebuild``); a name clashing as
    checked clashes only with the defaults when, in that build, its elements have names of
    their own, each named from another of those arguments. A clash of ``${prefix}base_link``
    with a ``base_link`` written as it is (HEBI's rosie: an arm kit inside a base) stays: the
    robot's own default build, the one a single robot is meant to have, holds it. None when
    no name clashes so, when a launch file builds the robot as checked (the clash then
    runs), or when that build fails (nothing is known of it)."""
    return robot.memo(placeholder_clashes, lambda: _placeholder_clashes(robot))


def _placeholder_clashes(robot) -> Placeholders | None:
    if robot.rebuild is None or not robot.from_xacro:
        return None
    clashing = {tag: _clashing(robot, tag) for tag in ("link", "joint")}
    if not any(clashing.values()):
        return None
    given = getattr(robot, "xacro_args", {})
    empty = [name for name, value in _robot_args(robot).items() if value == "" and name not in given]
    if not empty or built_as_checked(robot):
        return None
    from urdftool.errors import LoadError

    values = {name: f"urdftool{index}z" for index, name in enumerate(empty)}
    try:
        other = robot.rebuild(values)
    except LoadError:
        return None

    def args_in(text) -> frozenset:
        return frozenset(name for name in empty if text and values[name] in text)

    found, used = {}, set()
    for tag, names in clashing.items():
        mine = [robot.names()[element] for element in robot.children(tag)]
        theirs = [other.names()[element] for element in other.children(tag)]
        still = _clashing(other, tag)
        if len(mine) != len(theirs):  # the arguments chose other elements: the whole, or nothing
            named = set().union(*(args_in(text) for text in theirs))
            found[tag] = frozenset() if still or len(named) < 2 else frozenset(names)
            used.update(named if found[tag] else ())
            continue
        found[tag] = frozenset()
        for name in names:
            each = [args_in(theirs[index]) for index, mine_name in enumerate(mine)
                    if mine_name == name]
            if all(each) and len(set(each)) == len(each) and not any(
                    theirs[index] in still for index, mine_name in enumerate(mine)
                    if mine_name == name):
                found[tag] |= {name}
                used.update(*each)
    if not (found["link"] or found["joint"]):
        return None
    return Placeholders(tuple(name for name in empty if name in used), found["link"],
                        found["joint"])


def _clashing(robot, tag: str) -> set:
    """The names two or more of the robot's ``tag`` elements have."""
    named, seen, twice = robot.names(), set(), set()
    for element in robot.children(tag):
        name = named[element]
        if name is not None:
            (twice if name in seen else seen).add(name)
    return twice


# --- the questions rules ask --------------------------------------------------------------------

class Runs(Frozen):
    """Whether a controller runs with the robot: ``state`` certain, conditional, never or
    unknown; ``condition`` says when (conditional) or why not (never)."""

    state: str
    condition: str
    spawns: tuple

    __slots__ = ("state", "condition", "spawns")

    def __init__(self, state: str, condition: str = "", spawns: tuple = ()) -> None:
        set_field = object.__setattr__
        set_field(self, "state", state)
        set_field(self, "condition", condition)
        set_field(self, "spawns", spawns)


def runs(robot, controller, parameter_files=()) -> Runs:
    """Whether ``controller`` (of :mod:`urdftool.description.controllers`) runs with the robot,
    as its launch files tell; ``parameter_files``: the files the URDF's ``<parameters>`` names
    (loaded wherever the robot runs in Gazebo)."""
    facts = runtime(robot)
    file = real_path(controller.file.path)
    named = {real_path(p) for p in parameter_files}
    short = controller.name.strip("/").split("/")[-1]
    relevant, loading = [], []
    for configuration, relation in facts.configurations:
        # a configuration describing no robot urdftool can tell counts when it loads the file
        loads = any(loaded.path is not None and real_path(loaded.path) == file
                    for loaded in configuration.loaded) or (bool(relation) and file in named)
        if relation and loads:
            loading.append(configuration)
        spawned = [s for s in facts.spawns if s.configuration is configuration
                   and s.name.strip("/").split("/")[-1] == short]
        if spawned and loads:
            relevant.extend(spawned)
    if not relevant:
        if not loading:
            return Runs("unknown")
        unread = [c for c, _ in facts.unread_spawners if c in loading]
        if unread:
            return Runs("conditional", f"{unread[0].named} starts controllers named by values "
                                       "urdftool cannot read", ())
        if (unknown := _unread_starting(robot, short)):
            return unknown
        return Runs("never", f"no launch file of the robot starts it ({loading[0].named} loads "
                             f"{display_path(controller.file.path)})")
    active = [s for s in relevant if s.active]
    if any(s.certain for s in active):
        return Runs("certain", "", tuple(relevant))
    if not active:
        return _unread_starting(robot, short) or Runs(
            "never", f"{relevant[0].configuration.named} loads it inactive", tuple(relevant))
    return Runs("conditional", active[0].told(), tuple(relevant))


def building_args(robot, configuration: Configuration) -> dict | None:
    """The xacro arguments ``configuration`` builds the robot's file with, as xacro gets them
    (name -> text), when it builds it with other arguments than the robot was checked with and
    every value given is known; else None (built as checked, not built, or a value known only
    at launch)."""
    placed = _robot_root(robot)
    if placed is None:
        return None
    path, root = placed
    real, mine, packages = real_path(path), _robot_args(robot), packages_below(root)
    for description in configuration.described:
        if description.path is None or real_path(description.path) != real or not description.xacro:
            continue
        given = {name: _as_given(value, packages) for name, value in description.args.items()}
        if not description.complete or any(text is None for text in given.values()):
            return None
        if all(_normal(text) == _normal(mine.get(name, text)) for name, text in given.items()):
            return None  # as checked
        return given
    return None


def _unread_starting(robot, short: str) -> Runs | None:
    """A launch file of the robot that could not be read and names controller ``short`` may
    start it: "never" is then not known (:func:`unread_naming`)."""
    unread = [named(display_path(launch), False, read=False) for launch, _ in _unread_naming(
        robot.path, (short,), tests=False, running=True)] if robot.path != "-" else []
    return Runs("conditional", f"{unread[0]} may start it", ()) if unread else None


def together(robot, first, second, parameter_files=()) -> tuple[str, str]:
    """Whether two controllers run at once: ("certain", where) when a configuration of the robot
    as checked starts both active unconditionally; ("conditional", when) when one starts both
    active under a condition; ("apart", "") when the launch files tell both and never start
    them active together (conditions that exclude each other, ``if`` and ``unless`` of one
    argument, never hold in one run); ("unknown", "") otherwise."""
    one, two = runs(robot, first, parameter_files), runs(robot, second, parameter_files)
    if "unknown" in (one.state, two.state):
        return "unknown", ""
    if "never" in (one.state, two.state):
        return "apart", ""
    best = None
    for a in one.spawns:
        for b in two.spawns:
            if (a.configuration is not b.configuration or not (a.active and b.active)
                    or a.start.when.excludes(b.start.when)):
                continue
            if a.certain and b.certain:
                return "certain", a.configuration.named
            if best is None:
                words = [c for c in (a.condition, b.condition) if c]
                best = ("conditional", f"{a.configuration.named} starts both "
                        + " and ".join(dict.fromkeys(words)))
    if best is not None:
        return best
    if not (one.spawns and two.spawns):  # started by a spawner whose names were not read
        return "unknown", ""
    return "apart", ""


# Packages of ROS itself whose nodes serve no trajectory action of a robot's controllers
_ROS_OWN = ("controller_manager", "robot_state_publisher", "joint_state_publisher",
            "joint_state_publisher_gui", "rviz", "rviz2", "moveit_ros_move_group",
            "moveit_ros_visualization", "moveit_ros_warehouse", "gazebo_ros", "ros_gz_sim",
            "ros_gz_bridge", "ros_ign_gazebo", "ros_ign_bridge", "tf", "tf2_ros", "xacro",
            "rqt_gui", "rqt_joint_trajectory_controller", "topic_tools", "warehouse_ros_mongo",
            "moveit_servo", "rosbag", "rosbag2", "joy", "teleop_twist_joy", "teleop_twist_keyboard",
            "nodelet", "image_proc", "depth_image_proc", "twist_mux", "robot_localization")


def moveit_execution(robot, moveit_file: Path) -> tuple[str, str]:
    """Who serves the trajectories MoveIt sends through the controller list ``moveit_file``, as
    the robot's launch files that start MoveIt with it tell: ("ros_control", launch file) when
    one starts MoveIt with it, spawns ros_control controllers, and starts no node that could
    serve a trajectory action itself (a node of a package other than ROS's own), all
    unconditionally, with the robot as checked; ("other", launch file) when every one starting
    MoveIt with it also starts such a node (a driver: aubo_driver, kortex_driver); ("unknown",
    "") otherwise. Once per robot and file (each entry of the list, in two rules, asks)."""
    return robot.memo_for(moveit_execution, moveit_file,
                          lambda: _moveit_execution(robot, moveit_file))


def _moveit_execution(robot, moveit_file: Path) -> tuple[str, str]:
    key = real_path(moveit_file)
    facts = runtime(robot)
    starting, served = [], []
    for configuration, relation in facts.configurations:
        if not relation:
            continue
        lists = [loaded for loaded in configuration.loaded
                 if loaded.path is not None and real_path(loaded.path) == key]
        group = [s for s in configuration.started if s.package == "moveit_ros_move_group"]
        if not (lists and group):
            continue
        starting.append(configuration)
        others = [s for s in configuration.started if s.package not in _ROS_OWN]
        spawns = [s for s in facts.spawns if s.configuration is configuration and s.certain]
        certain = relation == AS_CHECKED and all(x.when.certain for x in [*lists, *group])
        if certain and spawns and not others:
            return "ros_control", configuration.named
        if others:
            served.append((configuration, others[0]))
    if starting and len(served) == len(starting):
        configuration, node = served[0]
        return "other", f"{configuration.named} starts {node.package}/{node.executable} with it"
    return "unknown", ""


class ActionRemap(Frozen):
    """A remap of the action MoveIt sends to, in a launch file that starts MoveIt with the
    controller list (:func:`moveit_action_remaps`): the controller the action reaches (the
    name before the action's in the target; None when the target is not known without running
    the launch file or is chosen by launch arguments given at launch), whether it holds on
    every run of that launch file (the remap, move_group and the list unconditional), the
    condition in words otherwise, where it is written."""

    controller: str | None
    target: str | None
    certain: bool
    condition: str
    launch: str
    written: str

    __slots__ = ("controller", "target", "certain", "condition", "launch", "written")

    def __init__(self, controller: str | None, target: str | None, certain: bool, condition: str,
                 launch: str, written: str) -> None:
        set_field = object.__setattr__
        set_field(self, "controller", controller)
        set_field(self, "target", target)
        set_field(self, "certain", certain)
        set_field(self, "condition", condition)
        set_field(self, "launch", launch)
        set_field(self, "written", written)


def moveit_action_remaps(robot, moveit_file: Path, action: str) -> list[ActionRemap]:
    """The remaps that send MoveIt's ``action`` (``NAME/ACTION_NS`` of an entry of the
    controller list ``moveit_file``; ``/ACTION_NS`` for an empty name) elsewhere, one per launch
    file that starts MoveIt (move_group) with that list and the robot and remaps it: the last of
    move_group's remaps from that name (roslaunch's ``<remap>`` before the node or inside it,
    ROS 2's ``remappings``). Names are compared without their leading ``/`` (a namespace
    before them is not followed). xArm's Gazebo launch remaps ``/follow_joint_trajectory`` to
    its ros_control controller's ``follow_joint_trajectory``. Once per robot, file and action
    (each entry of the list, in two rules, asks)."""
    return robot.memo_for(moveit_action_remaps, (moveit_file, action),
                          lambda: _moveit_action_remaps(robot, moveit_file, action))


def _moveit_action_remaps(robot, moveit_file: Path, action: str) -> list[ActionRemap]:
    key, wanted = real_path(moveit_file), action.strip("/")
    found = []
    for configuration, relation in runtime(robot).configurations:
        if not relation:
            continue
        lists = [loaded for loaded in configuration.loaded
                 if loaded.path is not None and real_path(loaded.path) == key]
        if not lists:
            continue
        for group in configuration.started:
            if group.package != "moveit_ros_move_group":
                continue
            remap = next((r for r in reversed(group.remaps)
                          if r.source is not None and r.source.strip("/") == wanted), None)
            if remap is None:
                continue
            when = remap.when.also(group.when)
            certain = relation == AS_CHECKED and when.certain and all(x.when.certain for x in lists)
            condition = when.text() or ("when the launch arguments keep their defaults"
                                        if when.free else "") or \
                ("" if relation == AS_CHECKED else f"with the robot {relation}")
            parts = [p for p in (remap.target or "").split("/") if p]
            controller = parts[-2] if remap.target is not None and len(parts) >= 2 \
                and not remap.chosen else None
            found.append(ActionRemap(controller, remap.target, certain, condition,
                                     configuration.named, remap.written))
            break
    return found


def semantic_files(robot) -> list[tuple[Path, Configuration, str]]:
    """(SRDF, configuration, how it describes the robot) for each SRDF the robot's
    configurations give MoveIt (``robot_description_semantic``), the robot as checked first."""
    found = []
    for configuration, relation in runtime(robot).configurations:
        if not relation:
            continue
        for described in configuration.described:
            if described.path is not None and described.path.name.endswith(".srdf"):
                # an SRDF from a package launch arguments name is MoveIt's for their defaults
                found.append((described.path, configuration,
                              f"{AS_CHECKED} {described.by_default}"
                              if described.by_default and relation == AS_CHECKED else relation))
    return sorted(found, key=lambda item: item[2] != AS_CHECKED)


def moveit_with(robot, srdf: Path) -> tuple[str, str]:
    """Whether MoveIt runs with the SRDF ``srdf`` and the robot as checked: ("certain", which
    launch file) when a launch file gives MoveIt both; ("by default", which and when) when one
    does only with the defaults of the launch arguments naming the package of the robot or of
    the SRDF; ("conditional", why) when launch files give it that SRDF only with the robot built
    with other xacro arguments, or only with another robot file (a ``.urdf`` generated beside
    the ``.xacro`` that the launch files build); ("unknown", "") when none gives it. Once per
    robot and SRDF (each of the rules on MoveIt's files asks: lint.rules.srdf.as_moveit_runs)."""
    return robot.memo_for(moveit_with, srdf, lambda: _moveit_with(robot, srdf))


# Packages whose nodes start the robot itself: its state, its controllers (a launch file
# starting none of them, nor MoveIt's move_group, only hands MoveIt's files to a tool)
_ROBOT_STARTERS = ("robot_state_publisher", "controller_manager", "gazebo_ros", "ros_gz_sim",
                   "ros_ign_gazebo")


def _runs_robot(configuration) -> int:
    """How surely ``configuration`` runs the robot, as a message naming one launch file of
    several prefers it: 0 when it starts the robot (its state publisher, controllers or a
    simulator), 1 MoveIt's move_group alone, 2 neither (MoveIt Setup Assistant's
    run_benchmark_ompl.launch loads the URDF and SRDF for a benchmark: hans-robot's elfin5_l
    was said to be run by it, beside its demo.launch)."""
    packages = {start.package for start in configuration.started}
    return 0 if packages.intersection(_ROBOT_STARTERS) else \
        1 if "moveit_ros_move_group" in packages else 2


def _moveit_with(robot, srdf: Path) -> tuple[str, str]:
    key = real_path(srdf)
    loads = sorted(((c, r) for path, c, r in semantic_files(robot) if real_path(path) == key),
                   key=lambda load: _runs_robot(load[0]))  # (stable: the order kept otherwise)
    if not loads:
        other = _other_robot_with(robot, key) or _setup_assistant_robot(robot, Path(srdf))
        return ("conditional", other) if other else ("unknown", "")
    certain = [c for c, relation in loads if relation == AS_CHECKED]
    if certain:
        return "certain", f"{_giving(certain[0])} gives MoveIt this SRDF with the robot as checked"
    for configuration, relation in loads:
        if relation.startswith(f"{AS_CHECKED} {BY_DEFAULT}"):
            return "by default", (f"{_giving(configuration)} gives MoveIt this SRDF with the "
                                  f"robot {relation}")
    configuration, relation = loads[0]
    return "conditional", (f"{_giving(configuration)} gives MoveIt this SRDF with the robot "
                           f"{relation}")


def _giving(configuration) -> str:
    """The launch file of ``configuration`` as a message says it gives MoveIt its files: with
    what it starts when it starts nodes and neither the robot nor move_group
    (:func:`_runs_robot`), the only launch file that gives both being a tool's (elfin5_l's
    run_benchmark_ompl.launch, its demo.launch loading no robot_description); a fragment
    starting nothing (planning_context.launch) is named alone."""
    started = sorted({s.package for s in configuration.started if s.package})
    if _runs_robot(configuration) < 2 or not started:
        return configuration.named  # (a fragment starting nothing: the parameters of others)
    return f"{configuration.named} (which starts {', '.join(started)}, not the robot nor move_group)"


def setup_assistant(package: Path) -> dict | None:
    """The settings (``moveit_setup_assistant_config``) of the ``.setup_assistant`` file of the
    ROS 2 MoveIt package ``package``, which MoveItConfigsBuilder reads (the SRDF and URDF it
    names, the URDF's ``xacro_args``); None when there is none, it is not a regular file, the
    package is not ROS 2's only (ROS 1's MoveIt never reads it) or it holds no mapping."""
    marker = package / ".setup_assistant"
    if kind_of(marker, follow=False) != "file" or \
            [version for version, _, _ in build_tools(marker)] != [2]:
        return None
    data = read_yaml(marker, "MoveIt Setup Assistant settings", parameters=False).data
    settings = data.get("moveit_setup_assistant_config") if isinstance(data, dict) else None
    return settings if isinstance(settings, dict) else None


def _setup_assistant_robot(robot, srdf: Path) -> str:
    """Why MoveIt does not run the SRDF ``srdf`` with the robot as checked, from the
    ``.setup_assistant`` of the ROS 2 MoveIt package holding it (``config/``), when no launch
    file read gives MoveIt that SRDF: MoveItConfigsBuilder, given no robot_description, loads
    the package's ``config/ROBOT.urdf.xacro`` or else the URDF the file names, built with its
    ``xacro_args``, which the Setup Assistant wrote the SRDF for. "" when the file names no
    URDF of this repository, or the robot as checked is that URDF (or a ``config/*.urdf.xacro``
    of the package) built with those arguments. Kinova's link6_moveit_config names
    ``link6.urdf.xacro`` with ``gripper:=robotiq_2f_85``: checked with the gripper's default
    ``''``, or as ``assets/link6.links.xacro`` (a drawing aid named like the robot), its SRDF
    named 23 joints of a gripper that build has not, each an error."""
    package = srdf.parent.parent
    settings = None if robot.path == "-" or srdf.parent.name != "config" else \
        setup_assistant(package)
    if settings is None:
        return ""
    marker = package / ".setup_assistant"
    urdf, written = settings.get("urdf") or settings.get("URDF"), settings.get("srdf") or \
        settings.get("SRDF")
    if not isinstance(urdf, dict) or not isinstance(written, dict) or \
            real_path(package / str(written.get("relative_path") or "")) != real_path(srdf):
        return ""
    folder = packages_below(containment_root(package)).get(str(urdf.get("package")))
    relative = urdf.get("relative_path")
    if folder is None or not isinstance(relative, str) or kind_of(folder / relative) != "file":
        return ""  # another repository's URDF: what it is built with is not known here
    named = folder / relative
    mine = real_path(os.path.abspath(robot.path))
    wrappers = [package / "config" / name for name, kind in
                listing(package / "config", "*.urdf.xacro") if kind == "file"]
    where = display_path(marker)
    if mine not in {real_path(p) for p in [named, *wrappers]}:
        return (f"{where} writes this SRDF for {display_path(named)}, another robot file, "
                f"which MoveItConfigsBuilder loads")
    checked = _robot_args(robot)
    wanted = dict(word.split(":=", 1) for word in str(urdf.get("xacro_args") or "").split()
                  if ":=" in word)
    other = [f"{name}:={value}" for name, value in wanted.items()
             if name in checked and _normal(value) != _normal(checked[name])]
    if other:
        return (f"{where} writes this SRDF for the robot built with {', '.join(other[:4])}, "
                f"as MoveItConfigsBuilder builds it")
    return ""


def _other_robot_with(robot, srdf_key) -> str:
    """Why MoveIt never runs the SRDF ``srdf_key`` with this robot: the first launch file of
    its repository that gives MoveIt that SRDF with another robot file; "" when none does, or
    when one gives it with this robot file too."""
    if robot.path == "-":
        return ""
    path = Path(os.path.abspath(robot.path))
    root = _launch_root(path.parent)
    if root is None:
        return ""
    mine, found = real_path(path), ""
    for configuration in launch_index(root).configurations:
        paths = [d.path for d in configuration.described if d.path is not None]
        if not any(real_path(p) == srdf_key for p in paths):
            continue
        robots = [p for p in paths if not p.name.endswith((".srdf", ".srdf.xacro"))]
        if any(real_path(p) == mine for p in robots):
            return ""
        if robots and not found:
            found = (f"{configuration.named} gives MoveIt this SRDF with "
                     f"{display_path(robots[0])}, another robot file")
    return found


# the executables that put a robot description into a simulator: (package, executables)
SIMULATOR_SPAWNERS = (("gazebo_ros", ("spawn_model", "spawn_entity.py")),
                      ("ros_gz_sim", ("create",)), ("ros_ign_gazebo", ("create",)))


def simulators(robot) -> list[str]:
    """What simulates the robot, in words, from what is read of it already: the Gazebo plugins
    of its own ``<gazebo>`` blocks (the one loading its control first: it clamps commands), its launch files' spawners (gazebo_ros' spawn_model and
    spawn_entity.py, ros_gz_sim's create) and the simulators it is checked for
    (``--target``); [] when nothing here says a simulator loads it (once per robot)."""
    def build():
        from urdftool.description.actuation import gazebo_plugins

        from urdftool.description.actuation import CONTROL_PLUGINS

        found = []
        named = [p for p in gazebo_plugins(robot) if p.get("filename")]
        # the plugin that loads the robot's control (it clamps the commands), else the first
        control = [p for p in named if any(name in p.get("filename") for name in CONTROL_PLUGINS)]
        plugin = next((p.get("filename") for p in control or named), None)
        if plugin:
            found.append(f"Gazebo ({plugin})")
        for package, executables in SIMULATOR_SPAWNERS:
            for _, start in runtime(robot).starts(package, executables):
                found.append(f"{Path(start.launch).name} spawns it into Gazebo")
                break
        found.extend(sorted(robot.targets))
        return list(dict.fromkeys(found))

    return robot.memo(simulators, build)


def state_publishers(robot) -> list[tuple[Configuration, Started]]:
    """The joint_state_publisher nodes the robot's configurations start."""
    facts = runtime(robot)
    return [found for package in STATE_PUBLISHERS for found in facts.starts(package)]



# the nodes that publish a fixed transform: (package, executable) -> the words its command line
# takes after the two frames (ROS 1 tf's takes a period in milliseconds, tf2_ros' none)
STATIC_PUBLISHERS = {("tf2_ros", "static_transform_publisher"): 0,
                     ("tf", "static_transform_publisher"): 1}


class Published(Frozen):
    """A frame a launch configuration of the robot publishes with a static_transform_publisher:
    its parent frame, where (the launch file and line, and the one run), and when, in words
    (empty when every run of that launch file publishes it)."""

    frame: str
    parent: str
    where: str
    condition: str

    __slots__ = ("frame", "parent", "where", "condition")

    def __init__(self, frame: str, parent: str, where: str, condition: str) -> None:
        set_field = object.__setattr__
        set_field(self, "frame", frame)
        set_field(self, "parent", parent)
        set_field(self, "where", where)
        set_field(self, "condition", condition)


def static_frames(robot) -> dict[str, Published]:
    """The frames the robot's launch configurations publish with tf2_ros' or ROS 1 tf's
    static_transform_publisher, by name (the first configuration's; once per robot): frames
    that TF knows while the robot runs with that launch file though no link is named so
    (COEX Clover's ``main_camera_optical``)."""
    def build():
        found: dict[str, Published] = {}
        for (package, executable), trailing in STATIC_PUBLISHERS.items():
            for configuration, start in runtime(robot).starts(package, (executable,)):
                frames = _published_frames(start, trailing)
                if frames is None or frames[1] in found:
                    continue
                at = f"{start.launch}:{start.line or '?'}"
                where = named(at) if start.launch == configuration.display else \
                    f"{named(at)} (run by {configuration.named})"
                found[frames[1]] = Published(frames[1], frames[0], where,
                                             " and ".join(start.when.words))
        return found

    return robot.memo(static_frames, build)


def _published_frames(start: Started, trailing: int) -> tuple[str, str] | None:
    """(parent, child) a static_transform_publisher's words name: ROS 2's ``--frame-id P
    --child-frame-id C``, else the last two positional words before ``trailing`` ones
    (``x y z yaw pitch roll P C`` or ``x y z qx qy qz qw P C``); None when not read."""
    if any(argument.text is None for argument in start.arguments):
        return None
    words = [word for argument in start.arguments for word in argument.text.split()]
    flags, positional, index = {}, [], 0
    while index < len(words):
        word = words[index]
        if word == "--ros-args":
            break
        if word.startswith("--"):
            flags[word] = words[index + 1] if index + 1 < len(words) else ""
            index += 2
            continue
        if ":=" not in word:  # ROS 1's __name:=... remappings
            positional.append(word)
        index += 1
    if "--child-frame-id" in flags:
        return flags.get("--frame-id", "").strip("/"), flags["--child-frame-id"].strip("/")
    positional = positional[:len(positional) - trailing]
    if len(positional) not in (8, 9):
        return None
    return positional[-2].strip("/"), positional[-1].strip("/")
