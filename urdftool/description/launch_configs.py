"""What runs with a robot, as its repository's launch files tell: decided once, used by every rule.

Every launch file of the robot's repository (:func:`launch_index`: files named ``*.launch``,
``*.launch.xml|py|yaml``, or ``.py``/``.xml``/``.yaml`` in a ``launch/`` folder; bounded in
number and size, links leading outside not followed) is read
(:mod:`urdftool.description.launch`), and each one no other includes (what a user runs) is
expanded as a configuration: its includes followed
(``$(find pkg)``, ``FindPackageShare``: only packages inside the repository; an installed
``share/`` path is mapped back to the package's source folder), its arguments at their defaults.
A package a launch argument names (``$(find $(arg pkg))``, ``FindPackageShare(
LaunchConfiguration("pkg"))``) is the one its value names; from a default, what it builds and
includes holds for that value only (:attr:`Described.by_default`, and a condition in its
:class:`When`).
A configuration *describes* the robot when one of its robot descriptions is the robot's file;
then what it starts is what runs with the robot:

- the parameter files it loads (controller YAML, with or without ``subst_value`` /
  ``allow_substs``);
- the controllers its spawners start (active, or ``--stopped``/``--inactive``/``load``);
- its other nodes (joint_state_publisher, move_group);
- the xacro arguments it gives the robot, compared with those the robot was checked with.

Each thing it does is *certain* (no ``if``/``unless`` and no launch argument it depends on), or
*conditional*, with the condition in words ("when gui is true", "robot_controller:=X, its
default"); an argument given at launch is free, its default what is used. Nothing is run,
imported or evaluated; what cannot be told (``$(eval ...)``, a value computed in Python, a file
outside the repository) is unknown, never guessed.
"""

from __future__ import annotations

import ast
import os
import re
import sys
from pathlib import Path

from urdftool.description.documents import read_text
from urdftool.description.files import MANIFESTS, inside, kind_of, listing, real_path, tree, \
    tree_made, walk
from urdftool.description.launch import (LAUNCH_TEST_ENTRY, MAX_LAUNCH_SIZE, MAX_TEXT, Arg,
                                         Condition, Description, Include, LaunchFile, ParamFile,
                                         Start, Value, is_launch_file, is_launch_name,
                                         is_launch_test, may_be_launch_test, read_launch_text,
                                         was_read)
from urdftool.description.launch_python import Modules, Room, read_python_launch
from urdftool.description.crashes import guarded
from urdftool.description.packages import SKIP_DIRS, containment_root, installed, \
    packages_below
from urdftool.description.run_memo import per_run
from urdftool.diagnostics import display_path
from urdftool.records import Frozen, NEW, Record

MAX_LAUNCH_FILES = 1500  # per repository
MAX_WALK_DEPTH = 10
MAX_INCLUDE_DEPTH = 12
MAX_EVENTS = 20_000  # per configuration
MAX_PACKAGE_FILES = 5000
TRUE, FALSE = ("true", "1"), ("false", "0")
DESCRIPTION_SUFFIXES = (".urdf", ".xacro", ".urdf.xml")


# --- resolved values ----------------------------------------------------------------------------

class Resolved(Frozen):
    """A value in a configuration: ``text`` (None when not known) and the launch arguments it
    depends on that may be given at launch (their defaults were used)."""

    text: str | None
    free: frozenset
    pattern: str | None  # the text with WILD where a value given at launch goes; None: text

    __slots__ = ("text", "free", "pattern")

    def __init__(self, text: str | None, free: frozenset = frozenset(),
                 pattern: str | None = None) -> None:
        set_field = object.__setattr__
        set_field(self, "text", text)
        set_field(self, "free", free)
        set_field(self, "pattern", pattern)


WILD = "\1"  # in a pattern: any value a launch argument may be given


class Scope(Record):
    """What resolving a launch file's values needs: its arguments so far, the repository's
    packages, the file itself."""

    args: dict
    packages: dict
    launch: LaunchFile
    root: Path
    ros1: bool
    # reached through an include from a package launch arguments name: that condition in words
    # (:attr:`Described.by_default`), and those arguments
    by_default: str
    default_free: frozenset

    __slots__ = ("args", "packages", "launch", "root", "ros1", "by_default", "default_free")

    def __init__(self, args: dict, packages: dict, launch: LaunchFile, root: Path, ros1: bool,
                 by_default: str = "", default_free: frozenset = frozenset()) -> None:
        self.args = args
        self.packages = packages
        self.launch = launch
        self.root = root
        self.ros1 = ros1
        self.by_default = by_default
        self.default_free = default_free


def resolve(value: Value | None, scope: Scope, depth: int = 0) -> Resolved:
    if value is None:
        return Resolved(None)
    text, free, pattern = [], set(), []
    for part in value.parts:
        if isinstance(part, str):
            text.append(part)
            pattern.append(part)
            continue
        kind = part[0]
        if kind == "arg":
            bound = scope.args.get(part[1])
            if bound is None and part[2] is not None and depth < 8:
                bound = resolve(part[2], scope, depth + 1)
            if bound is None:
                return Resolved(None, frozenset(free | {part[1]}))
            free |= bound.free
            if bound.text is None and WILD not in (bound.pattern or ""):
                return Resolved(None, frozenset(free))
            text.append(bound.text)  # None: a value only given at launch; the pattern goes on
            pattern.append(bound.text if bound.pattern is None else bound.pattern)
        elif kind == "find":
            name, named = part[1], None
            if isinstance(name, Value):  # $(find $(arg pkg)): the package the argument names
                named = resolve(name, scope, depth + 1) if depth < 8 else Resolved(None)
                free |= named.free
                name = named.text
            folder = scope.packages.get(name) if name else None
            if folder is None:  # not a package of the repository: nothing is built
                return Resolved(None, frozenset(free))
            text.append(f"\0{name}\0")  # the package's folder, placed by resolve_path
            # given at launch, the argument may name another package: WILD where its name goes
            pattern.append(text[-1] if named is None or named.pattern is None
                           else f"\0{named.pattern}\0")
        elif kind == "env":
            free.add(f"${part[1]}")
            default = resolve(part[2], scope, depth + 1) if part[2] is not None and depth < 8 \
                else Resolved(None)
            free |= default.free
            if default.text is None:  # only given at launch, as an argument without a default
                text.append(None)
                pattern.append(WILD)
                continue
            text.append(default.text)
        elif kind == "dirname":
            text.append(str(scope.launch.path.parent))
        else:  # command, unknown
            return Resolved(None, frozenset(free | value.names()))
        if kind in ("env", "dirname"):
            pattern.append(text[-1])
        if max(sum(len(t) for t in text if t is not None), sum(len(t) for t in pattern)) > MAX_TEXT:
            return Resolved(None, frozenset(free))
    patterned = "".join(pattern)
    if None in text:
        return Resolved(None, frozenset(free), patterned)
    joined = "".join(text)
    return Resolved(joined, frozenset(free), patterned if patterned != joined else None)


def shown(resolved: Resolved) -> str | None:
    """The text as a user reads it (a package's folder as ``$(find pkg)``)."""
    if resolved.text is None:
        return None
    parts = resolved.text.split("\0")
    return "".join(f"$(find {p})" if i % 2 else p for i, p in enumerate(parts))


def shell_word(resolved: Resolved) -> Resolved:
    """A command word as the shell split reads it: roslaunch's ``command=`` and ROS 2's
    ``$(command)`` substitute first and split with ``shlex`` after, so the quotes of a
    substituted value (Yaskawa's ``<let name="xacro_path" value="'$(find-pkg-share p)/x.xacro'"/>``)
    are the shell's, not the path's. Only a value wrapped whole in one pair is unwrapped."""
    def unwrapped(text):
        if text and len(text) >= 2 and text[0] == text[-1] and text[0] in "'\"" \
                and text[0] not in text[1:-1]:
            return text[1:-1]
        return None

    text = unwrapped(resolved.text)
    if text is None:
        return resolved
    return Resolved(text, resolved.free, unwrapped(resolved.pattern) or resolved.pattern)


def resolve_path(value: Value, scope: Scope, shell: bool = False) -> tuple[Path | None, Resolved]:
    """The file a path value names, inside the repository: ``$(find pkg)/rest`` is
    ``pkg/rest`` in the package's source folder, or where the package's install rules take
    ``share/pkg/rest`` from (:func:`~urdftool.description.packages.installed`), or the one
    file below the package whose path ends with ``rest`` (an installed ``share/pkg/config/x.yaml`` comes from ``pkg/.../config/
    x.yaml``); an absolute path only inside the repository; None otherwise."""
    resolved = resolve(value, scope)
    resolved = shell_word(resolved) if shell else resolved
    text = resolved.text
    if text is None or "\n" in text:
        return None, resolved
    if text.count("\0") >= 2:
        _, package, rest = text.split("\0", 2)
        if "\0" in rest:
            return None, resolved
        folder = scope.packages.get(package)
        return (_in_package(package, folder, rest.strip("/"), scope.root) if folder else None), \
            resolved
    path = Path(text)
    if not path.is_absolute():
        path = scope.launch.path.parent / path
    path = Path(os.path.normpath(path))
    return (path if _regular_inside(path, scope.root) else None), resolved


def _regular_inside(path: Path, root: Path) -> bool:
    return kind_of(path) == "file" and inside(path, root)


def _in_package(name: str, folder: Path, rest: str, root: Path) -> Path | None:
    if not rest or ".." in Path(rest).parts:
        return None
    direct = installed(name, folder, folder / rest).path
    if _regular_inside(direct, root):  # where the package's install rules put it
        return direct
    tail = "/" + rest
    matches = [p for p in _package_files(folder) if ("/" + p.relative_to(folder).as_posix()).endswith(tail)]
    if len(matches) == 1 and _regular_inside(matches[0], root):
        return matches[0]
    return None


@per_run
def _package_files(folder: Path) -> tuple[Path, ...]:
    found = []
    for current, files in _walk(folder, 8):
        found.extend(Path(current, f) for f in files)
        if len(found) > MAX_PACKAGE_FILES:
            break
    return tuple(found)


def _walk(root: Path, depth: int, pattern: str = "*"):
    """(folder, its file names matching ``pattern``) for ``root`` and the folders below it,
    ``depth`` levels at most, in sorted order, through the recorded walk
    (:func:`~urdftool.description.files.walk`): folders that are links, hidden or build
    output (SKIP_DIRS) are not entered. A folder is named as text (``root`` joined with the
    names below it): a repository's hundreds of folders, few of which hold a file wanted."""
    # hidden folders: not entered, not listed
    for current, entries in walk(root, pattern + "|[!.]*/", depth, SKIP_DIRS):
        yield current, [name for name, kind in entries if kind == "file"]


_SPACES = re.compile(r"\s+")  # (what str.isspace says is a space)


def words(value: Value | None) -> list[Value]:
    """A command line or argument list value split into words at the spaces of its literal
    text outside quotes (quotes removed); a substitution belongs to the word it is written in."""
    if value is None:
        return []
    found, current, piece, quote, quoted = [], [], "", None, False
    for part in value.parts:
        if not isinstance(part, str):
            if piece:
                current.append(piece)
                piece = ""
            current.append(part)
            continue
        if quote is None and "'" not in part and '"' not in part:  # (as below, a run at a time)
            at = 0
            for space in _SPACES.finditer(part):
                piece += part[at:space.start()]
                if piece:
                    current.append(piece)
                if current or quoted:
                    found.append(current or [""])
                piece, current, quoted, at = "", [], False, space.end()
            piece += part[at:]
            continue
        for char in part:
            if quote:
                if char == quote:
                    quote = None
                else:
                    piece += char
            elif char in "'\"":
                quote, quoted = char, True
            elif char.isspace():
                if piece:
                    current.append(piece)
                if current or quoted:
                    found.append(current or [""])
                piece, current, quoted = "", [], False
            else:
                piece += char
    if piece:
        current.append(piece)
    if current or quoted:
        found.append(current or [""])
    return [Value(tuple(p for p in parts if p != ""),
                  "".join(p if isinstance(p, str) else "$(...)" for p in parts)) for parts in found]


# --- conditions ---------------------------------------------------------------------------------

class When(Frozen):
    """Whether an action runs in a configuration: ``truth`` True/False/None (not known), the
    arguments it depends on, and the condition in words (empty when certain)."""

    truth: bool | None
    free: frozenset
    words: tuple
    # what the condition requires of launch arguments given at launch, as far as read:
    # (argument, value, True: it equals the value / False: it differs); value TRUTHY for an
    # if/unless on the argument itself (roslaunch's true/1)
    requires: frozenset

    __slots__ = ("truth", "free", "words", "requires")

    def __init__(self, truth: bool | None = True, free: frozenset = frozenset(), words: tuple = (),
                 requires: frozenset = frozenset()) -> None:
        set_field = object.__setattr__
        set_field(self, "truth", truth)
        set_field(self, "free", free)
        set_field(self, "words", words)
        set_field(self, "requires", requires)

    @property
    def certain(self) -> bool:
        return self.truth is True and not self.free

    def also(self, other: When) -> When:
        if self.truth is False or other.truth is False:
            truth = False
        elif self.truth is None or other.truth is None:
            truth = None
        else:
            truth = True
        return When(truth, self.free | other.free, self.words + other.words,
                    self.requires | other.requires)

    def excludes(self, other: When) -> bool:
        """Whether the two can never hold in one run: one requires a launch argument to be a
        value the other forbids (``mobile == 'husky'`` and ``mobile == 'none'``; ``if gui`` and
        ``unless gui``). What was not read (an expression, a Python test) excludes nothing."""
        return any(_contradict(a, b) for a in self.requires for b in other.requires
                   if a[0] == b[0])

    def text(self) -> str:
        return " and ".join(dict.fromkeys(self.words))


TRUTHY = "\0true"  # in When.requires: the argument is roslaunch's true (true or 1)


def _contradict(a: tuple, b: tuple) -> bool:
    """Whether two requirements on one launch argument (:attr:`When.requires`) exclude each
    other."""
    (_, first, equal), (_, second, same) = a, b
    if equal and same:
        if TRUTHY in (first, second):
            other = second if first == TRUTHY else first
            return other != TRUTHY and other not in TRUE
        return first != second
    if equal != same:
        wanted, refused = (first, second) if equal else (second, first)
        return wanted == refused or (refused == TRUTHY and wanted in TRUE)
    return False


def _argument(value: Resolved) -> str | None:
    """The launch argument (or environment variable, ``$NAME``) a resolved value is, whole:
    its value is what is given at launch, nothing added."""
    return next(iter(value.free)) if value.pattern == WILD and len(value.free) == 1 else None


def _requires(value: Resolved, other: Resolved | None, equal: bool) -> frozenset:
    """:attr:`When.requires` of a comparison of ``value`` with ``other`` (None: a truth test)."""
    if other is None:
        name = _argument(value)
        return frozenset({(name, TRUTHY, equal)}) if name is not None else frozenset()
    for one, two in ((value, other), (other, value)):
        name = _argument(one)
        if name is not None and not two.free and two.text is not None:
            return frozenset({(name, two.text.strip().lower(), equal)})
    return frozenset()


def evaluate(condition: Condition, scope: Scope) -> When:
    value = resolve(condition.value, scope)
    text = (value.text or "").strip().lower()
    arguments = ", ".join(sorted(n for n in condition.value.names())) or condition.text
    if condition.kind in ("if", "unless"):
        truth = True if text in TRUE else False if text in FALSE else None
        if truth is not None and condition.kind == "unless":
            truth = not truth
        if value.free or truth is None:
            return When(None if truth is None else truth, value.free, (f"when {condition.text}",),
                        _requires(value, None, condition.kind == "if"))
        return When(truth)
    if condition.kind in ("equals", "differs"):
        other = resolve(condition.other, scope)
        free = value.free | other.free
        requires = _requires(value, other, condition.kind == "equals")
        if value.text is None or other.text is None:
            return When(None, free, (f"when {condition.text}",), requires)
        same = value.text.strip().lower() == other.text.strip().lower()
        truth = same if condition.kind == "equals" else not same
        return When(truth, free, (f"when {condition.text}",) if free else (), requires)
    return When(None, value.free, (f"when {condition.text}" + (f" (reads {arguments})" if arguments != condition.text else ""),))


def _when_of(conditions, scope: Scope) -> When:
    found = When()
    for condition in conditions:
        found = found.also(evaluate(condition, scope))
    return found


# --- configurations -----------------------------------------------------------------------------

class Loaded(Frozen):
    """A parameter file a configuration loads."""

    path: Path | None
    written: str
    substitute: bool
    args: dict  # the launch arguments it is loaded with, for its $(arg)/$(var)
    when: When
    launch: str
    line: int | None
    chain: tuple  # the launch files from the one run to ``launch`` (its includers)

    __slots__ = ("path", "written", "substitute", "args", "when", "launch", "line", "chain")

    def __init__(self, path: Path | None, written: str, substitute: bool, args: dict, when: When,
                 launch: str, line: int | None, chain: tuple = ()) -> None:
        set_field = object.__setattr__
        set_field(self, "path", path)
        set_field(self, "written", written)
        set_field(self, "substitute", substitute)
        set_field(self, "args", args)
        set_field(self, "when", when)
        set_field(self, "launch", launch)
        set_field(self, "line", line)
        set_field(self, "chain", chain)


class Remapped(Frozen):
    """A name a started node has remapped (:class:`~urdftool.description.launch.Remap`):
    ``source`` and ``target`` as resolved (None: not known without running the launch file),
    ``when`` the remap's own conditions (and the launch arguments it reads); ``chosen``: the
    target reads launch arguments that may be given at launch; where written."""

    source: str | None
    target: str | None
    when: When
    launch: str
    line: int | None
    chosen: bool

    __slots__ = ("source", "target", "when", "launch", "line", "chosen")

    def __init__(self, source: str | None, target: str | None, when: When, launch: str,
                 line: int | None, chosen: bool = False) -> None:
        set_field = object.__setattr__
        set_field(self, "source", source)
        set_field(self, "target", target)
        set_field(self, "when", when)
        set_field(self, "launch", launch)
        set_field(self, "line", line)
        set_field(self, "chosen", chosen)

    @property
    def written(self) -> str:
        """Where it is written, as a finding names it."""
        return f"{self.launch}:{self.line}" if self.line else self.launch


class Started(Frozen):
    """A node or process a configuration starts; ``remaps``: the names remapped for it
    (:class:`Remapped`, in the order roslaunch applies them: the scope's, then its own)."""

    package: str | None
    executable: str | None
    arguments: tuple  # Resolved words
    files: tuple  # Loaded
    when: When
    launch: str
    line: int | None
    chain: tuple  # the launch files from the one run to ``launch`` (its includers)
    remaps: tuple  # Remapped

    __slots__ = ("package", "executable", "arguments", "files", "when", "launch", "line", "chain",
                 "remaps")

    def __init__(self, package: str | None, executable: str | None, arguments: tuple, files: tuple,
                 when: When, launch: str, line: int | None, chain: tuple = (),
                 remaps: tuple = ()) -> None:
        set_field = object.__setattr__
        set_field(self, "package", package)
        set_field(self, "executable", executable)
        set_field(self, "arguments", arguments)
        set_field(self, "files", files)
        set_field(self, "when", when)
        set_field(self, "launch", launch)
        set_field(self, "line", line)
        set_field(self, "chain", chain)
        set_field(self, "remaps", remaps)


class Described(Frozen):
    """A robot description a configuration makes: the file, and the xacro arguments given."""

    path: Path | None
    written: str
    args: dict  # name -> Resolved
    when: When
    launch: str
    line: int | None
    xacro: bool  # run through xacro (else read as it is: textfile=, cat, open)
    complete: bool  # every argument given is in args
    template: str | None  # the path, WILD where a launch argument chooses it
    chosen_by: frozenset  # the launch arguments the path depends on
    chain: tuple  # the launch files from the one run to ``launch`` (its includers)
    # when launch arguments given at launch name the package holding the file, the build holds
    # for their defaults only: that condition in words (also in ``when``), else ""
    by_default: str
    replaced: tuple  # read as it is, with these texts replaced first (Description's)
    # when it reaches a controller manager: under more than ``when`` (Description's published)
    published: When | None

    __slots__ = ("path", "written", "args", "when", "launch", "line", "xacro", "complete",
                 "template", "chosen_by", "chain", "by_default", "replaced", "published")

    def __init__(self, path: Path | None, written: str, args: dict, when: When, launch: str,
                 line: int | None, xacro: bool = True, complete: bool = True,
                 template: str | None = None, chosen_by: frozenset = frozenset(),
                 chain: tuple = (), by_default: str = "", replaced: tuple = (),
                 published: When | None = None) -> None:
        set_field = object.__setattr__
        set_field(self, "path", path)
        set_field(self, "written", written)
        set_field(self, "args", args)
        set_field(self, "when", when)
        set_field(self, "launch", launch)
        set_field(self, "line", line)
        set_field(self, "xacro", xacro)
        set_field(self, "complete", complete)
        set_field(self, "template", template)
        set_field(self, "chosen_by", chosen_by)
        set_field(self, "chain", chain)
        set_field(self, "by_default", by_default)
        set_field(self, "replaced", replaced)
        set_field(self, "published", published)


class Configuration(Record):
    """One launch file run as it is, its includes followed."""

    top: LaunchFile
    loaded: list
    started: list
    described: list
    files: list  # display names of the launch files it read
    included: set  # the real paths of the files it includes
    incomplete: bool  # an include could not be followed, or a bound was reached
    # (launch file as shown, line, the path as written) of each parameter file or launch file
    # it names that leads outside the repository: not read (:func:`_leads_outside`)
    outside: list

    __slots__ = ("top", "loaded", "started", "described", "files", "included", "incomplete",
                 "outside")

    def __init__(self, top: LaunchFile, loaded: list = NEW, started: list = NEW,
                 described: list = NEW, files: list = NEW, included: set = NEW,
                 incomplete: bool = False, outside: list = NEW) -> None:
        self.top = top
        self.loaded = [] if loaded is NEW else loaded
        self.started = [] if started is NEW else started
        self.described = [] if described is NEW else described
        self.files = [] if files is NEW else files
        self.included = set() if included is NEW else included
        self.incomplete = incomplete
        self.outside = [] if outside is NEW else outside

    @property
    def display(self) -> str:
        return self.top.display

    @property
    def named(self) -> str:
        """The launch file run, as a finding names it (:func:`~urdftool.description.launch.named`)."""
        return self.top.named


class LaunchIndex(Record):
    """Every launch file of a repository, read; and each run as a configuration (a launch
    test among them is in ``files``, not in ``configurations``: :func:`launch_tests`). An
    index of some of them (:func:`launch_index`'s ``only``) reads the others only as those
    include them (:meth:`included`)."""

    root: Path
    files: dict  # real path -> LaunchFile
    configurations: list
    truncated: bool
    rest: list | dict | None  # the launch files not read yet (None: every one read); by real
    # path once an include asks

    __slots__ = ("root", "files", "configurations", "truncated", "rest")

    def __init__(self, root: Path, files: dict, configurations: list,
                 truncated: bool = False, rest: list | dict | None = None) -> None:
        self.root = root
        self.files = files
        self.configurations = configurations
        self.truncated = truncated
        self.rest = rest

    def included(self, key: str) -> LaunchFile | None:
        """The launch file of real path ``key`` as an include finds it: read when first
        included, in an index of some launch files."""
        found = self.files.get(key)
        if found is None and isinstance(self.rest, list):
            self.rest = {_key(path): path for path in self.rest}
        if found is None and self.rest is not None and key in self.rest:
            launch = read_launch(self.rest.pop(key), self.root)
            if was_read(launch):
                self.files[key] = found = launch
        return found


_LAUNCH_NAMES = "*.launch|*.py|*.xml|*.yaml|*.yml"  # what is_launch_file may take


def launch_files(root: Path, tests: bool = False) -> tuple[list[Path], bool]:
    """The launch files below ``root`` (sorted, bounded; folders that are links not entered,
    files leading outside ``root`` left out), and whether the bound was reached; with
    ``tests``, the Python files that may be launch tests too
    (:func:`~urdftool.description.launch.may_be_launch_test`: :func:`read_launch` tells).
    Walked once per run (the launch index and the files it could not read ask alike); the
    list is shared: not to be changed."""
    return _launch_files(root, bool(tests))


@per_run
def _launch_files(root: Path, tests: bool) -> tuple[list[Path], bool]:
    found, top = [], os.fspath(root)
    # (the whole walk, once per run: the package walk takes its listings, packages.packages_below)
    for current, entries in tree(root, f"{_LAUNCH_NAMES}|[!.]*/", MAX_WALK_DEPTH + 1, SKIP_DIRS):
        in_launch = os.path.basename(current) == "launch" and current != top
        # a regular file listed (not a link) in a folder walked (no link either) is inside
        # ``root``: the listing's record says so, no real path is asked
        for name, kind in entries:
            if kind == "file" and (is_launch_name(name, in_launch) or tests and name.endswith(
                    ".py") and may_be_launch_test(Path(current, name), root)):
                found.append(Path(current, name))
                if len(found) >= MAX_LAUNCH_FILES:
                    return found, True
    return found, False


@per_run
def launch_file_packages(root: Path) -> dict[str, str | None]:
    """Each launch file of ``root`` (named as :func:`launch_files` names it) -> the folder of
    the package holding it (the nearest folder at or above its own, up to ``root``, whose
    listing names a package.xml or manifest.xml), None in no package; from the launch-file
    walk's listings."""
    paths = launch_files(root)[0]
    listings = tree_made(root, "package.xml|manifest.xml|[!.]*/", MAX_WALK_DEPTH + 1,
                         SKIP_DIRS) or {}
    top, holders, found = os.fspath(root), {}, {}

    def holder(folder: str) -> str | None:
        if folder not in holders:
            entries = listings[folder] if folder in listings else listing(
                folder, "package.xml|manifest.xml")
            if any(name in MANIFESTS for name, _ in entries):
                holders[folder] = folder
            else:
                parent = os.path.dirname(folder)
                holders[folder] = None if folder == top or parent == folder else holder(parent)
        return holders[folder]

    for path in paths:
        found[os.fspath(path)] = holder(os.path.dirname(os.fspath(path)))
    return found


def read_launch(path: Path, root: Path | None = None, only_test: bool = False) -> LaunchFile | None:
    """One launch file read, never run, once a run: XML and YAML by
    :mod:`urdftool.description.launch`, Python by :mod:`urdftool.description.launch_python` (a
    launch test from its entry point) at the cost of the repository ``root``'s room
    (:func:`reading_room`; a room of its own without ``root``), the modules it imports found
    as :func:`repository_modules` finds them. ``only_test``: a Python file that may be a launch
    test, None (not parsed) when it is not one.

    Asked again (why a file was not read, for a finding), the answer is the first reading's:
    a second reading drew on the room again, which the repository's other files had spent by
    then, and a file refused as not valid Python was said to be "too large to read all" (its
    line lost)."""
    return _read_launch(path, root, only_test)


@per_run
def _read_launch(path: Path, root: Path | None, only_test: bool) -> LaunchFile | None:
    # a crash of the reader is urdftool's (an internal error at the launch file), not the file's: the file
    # is then as if not read, and whatever asked (finding targets, a rule) goes on
    reader = "the Python launch reader" if path.name.endswith(".py") else "the launch reader"
    return guarded(reader, path, lambda: _read_launch_file(path, root, only_test))


def _read_launch_file(path: Path, root: Path | None, only_test: bool) -> LaunchFile | None:
    room = reading_room(root) if root is not None else None
    modules = repository_modules(root) if root is not None else None
    read = read_launch_text(path)
    if isinstance(read, str):
        if is_launch_test(read):
            return read_python_launch(path, display_path(path), read, LAUNCH_TEST_ENTRY, room,
                                      modules)
        return None if only_test else read_python_launch(path, display_path(path), read,
                                                         room=room, modules=modules)
    return None if only_test else read


# modules a launch file imports that are never a repository's: Python's own, and ROS's launch
# libraries (no file is looked for)
_NOT_THE_REPOSITORY = frozenset(sys.stdlib_module_names) | {
    "launch", "launch_ros", "launch_xml", "launch_yaml", "launch_testing", "launch_testing_ros",
    "ament_index_python", "moveit_configs_utils", "xacro", "yaml", "rclpy", "numpy"}


class RepositoryModules(Modules):
    """The Python modules of the repository ``root`` a launch file may import, found as ROS 2
    finds them once installed, and only there: ``import pkg.mod`` in the package ``pkg``
    (``pkg/pkg/mod.py``, ament_python's layout, or ``pkg/src/pkg/mod.py``), a module beside
    the launch file (``import rs_launch``, on the path when the launch file puts its folder
    there), a relative import in its own package, and ``load_python_launch_file_as_module(
    path)``'s file (an installed ``share/`` path mapped back to the package's source). Read
    through the one door, never imported or run."""

    def __init__(self, root: Path, packages: dict):
        self.root, self.packages = root, packages

    def named(self, name: str, level: int, importer: Path) -> Path | None:
        parts = [p for p in name.split(".") if p]
        if not parts and not level or any(not p.isidentifier() for p in parts):
            return None
        if level:
            base = importer.parent
            for _ in range(level - 1):
                base = base.parent
            return self._file(base.joinpath(*parts))
        if parts[0] in _NOT_THE_REPOSITORY:
            return None
        package = self.packages.get(parts[0])
        for folder in ([package, package / "src"] if package is not None else []) + \
                [importer.parent]:
            found = self._file(folder.joinpath(*parts))
            if found is not None:
                return found
        return None

    def at(self, path: Value, importer: Path) -> Path | None:
        scope = Scope({}, self.packages, LaunchFile(importer, display_path(importer), "ros2-python"),
                      self.root, False)
        found, _ = resolve_path(path, scope)
        return found if found is not None and found.suffix == ".py" else None

    def tree(self, path: Path) -> tuple[ast.Module, int] | None:
        return _module_tree(path)

    def _file(self, stem: Path) -> Path | None:
        for candidate in (stem.with_name(stem.name + ".py"), stem / "__init__.py"):
            if _regular_inside(candidate, self.root):
                return candidate
        return None


@per_run
def repository_modules(root: Path) -> RepositoryModules:
    """The modules the Python launch files of the repository ``root`` may import."""
    return RepositoryModules(root, packages_below(root))


@per_run
def _module_tree(path: Path) -> tuple[ast.Module, int] | None:
    """A module's syntax tree (read through the door, parsed, never run) and its length."""
    text = read_text(path, MAX_LAUNCH_SIZE, "Python module").text
    if text is None:
        return None
    try:
        return ast.parse(text, filename=display_path(path)), len(text)
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return None


@per_run
def reading_room(root: Path) -> Room:
    """What reading the Python launch files of the repository ``root`` (its launch tests
    too) may still cost in this run."""
    return Room()


@per_run
def launch_index(root: Path, only: frozenset | None = None) -> LaunchIndex:
    """The launch files of the repository ``root`` read and expanded (once per run); with
    ``only`` (paths as :func:`launch_files` names them), those launch files, and the others
    as they include them: what a user runs is one of ``only`` that none of them includes."""
    paths, truncated = launch_files(root)
    chosen = paths if only is None else [p for p in paths if os.fspath(p) in only]
    files = {}
    if not chosen:
        return LaunchIndex(root, files, [], truncated)
    for path in chosen:
        launch = read_launch(path, root)
        if was_read(launch):
            files[_key(path)] = launch
    packages = packages_below(root)
    index = LaunchIndex(root, files, [], truncated, None if only is None else [
        p for p in paths if os.fspath(p) not in only])
    expanded = [_expand_top(index, launch, packages) for launch in list(files.values())
                if not launch.test]
    # what a user runs is a launch file no other includes: an included one (a controllers-only
    # launch file, planning_context.launch) runs as part of those including it
    included = {key for configuration in expanded for key in configuration.included}
    index.configurations = [c for c in expanded if _key(c.top.path) not in included]
    return index


@per_run
def launch_tests(root: Path) -> list[Configuration]:
    """The launch tests of the repository ``root`` (:func:`~urdftool.description.launch.
    is_launch_test`), each run as a configuration: how they build a robot file counts
    (``runtime.builds``), what they start does not (a test is not a deployment), so they are
    not among the index's ``configurations``. Read only when asked (only how a robot file is
    built asks), apart from the launch files: Python files named or placed as tests do not
    count against the launch files' bound."""
    index, packages = launch_index(root), packages_below(root)
    tests = [launch for launch in index.files.values() if launch.test]
    for path in launch_files(root, tests=True)[0]:
        if _key(path) in index.files or is_launch_file(path, root):
            continue
        launch = read_launch(path, root, only_test=True)
        if was_read(launch):  # one not read: runtime.unread_naming
            tests.append(launch)
    return [_expand_top(index, launch, packages) for launch in tests]


def _key(path: Path) -> str:
    return real_path(path)


def _expand_top(index: LaunchIndex, launch: LaunchFile, packages: dict) -> Configuration:
    configuration = Configuration(launch)
    _expand(index, launch, {}, True, When(), configuration, packages, (), 0)
    return configuration


def _expand(index, launch: LaunchFile, given: dict, top: bool, outer: When,
            configuration: Configuration, packages: dict, via: tuple, depth: int,
            by_default: tuple = ("", frozenset()), remaps: tuple = ()) -> None:
    """``remaps``: the :class:`Remapped` of the includer's scope, for every node started."""
    configuration.files.append(launch.display)
    scope = Scope(dict(given) if launch.ros == 2 else {}, packages, launch, index.root, launch.ros == 1,
                  *by_default)
    for action in launch.actions:
        if len(configuration.loaded) + len(configuration.started) > MAX_EVENTS:
            configuration.incomplete = True
            return
        when = outer.also(_when_of(action.when, scope))
        if when.truth is False and not when.free:
            continue
        if isinstance(action, Arg):
            _bind(action, scope, given, top or launch.ros == 2, when)
        elif isinstance(action, Include):
            _include(index, action, scope, when, configuration, packages, via + (launch.display,),
                     depth, remaps)
        elif isinstance(action, ParamFile):
            configuration.loaded.append(_loaded(action, scope, when, launch, via, configuration))
        elif isinstance(action, Start):
            files = tuple(_loaded(f, scope, when.also(_when_of(f.when, scope)), launch, via,
                                  configuration)
                          for f in action.files)
            arguments = tuple(resolve(word, scope) for value in action.arguments for word in words(value))
            if launch.ros == 1:  # roslaunch splits args= after substituting: $(arg controllers)
                arguments = tuple(Resolved(text, word.free) if word.text is not None else word
                                  for word in arguments
                                  for text in (word.text.split() if word.text is not None else [None]))
            package, executable = resolve(action.package, scope), resolve(action.executable, scope)
            if package.free or executable.free:
                when = when.also(When(True, package.free | executable.free, ()))
            configuration.started.append(Started(package.text, executable.text, arguments, files, when,
                                                 launch.display, action.line,
                                                 via + (launch.display,),
                                                 remaps + _remapped(action.remaps, scope, launch)))
            configuration.loaded.extend(files)
        elif isinstance(action, Description) and _describes(action.parameter):
            published = outer.also(_when_of(action.published, scope)) \
                if action.published is not None else None
            configuration.described.append(_described(action, scope, when, launch, via, published))


def _bind(action: Arg, scope: Scope, given: dict, free: bool, when: When) -> None:
    if not action.fixed and action.name in given:
        scope.args[action.name] = given[action.name]
        return
    value = resolve(action.default, scope) if action.default is not None else Resolved(None)
    if not action.fixed and free:
        value = Resolved(value.text, value.free | {action.name}, WILD)
    if not when.certain:
        if when.truth is None:
            value = Resolved(None, value.free | when.free)
        elif action.name in scope.args and not action.fixed:
            return
        else:
            value = Resolved(value.text, value.free | when.free, value.pattern)
    scope.args[action.name] = value


def _include(index, action: Include, scope: Scope, when: When, configuration: Configuration,
             packages: dict, via: tuple, depth: int, remaps: tuple = ()) -> None:
    path, resolved = resolve_path(action.path, scope)
    _leads_outside(path, resolved, scope, action, configuration)
    target = index.included(_key(path)) if path is not None else None
    # a launch test cannot be included (ros2 launch asks it for generate_launch_description):
    # what it starts is never a deployment's
    if target is None or target.test or depth >= MAX_INCLUDE_DEPTH or target.display in via:
        configuration.incomplete = True
        return
    configuration.included.add(_key(path))
    given = dict(scope.args) if (action.every or target.ros == 2) else {}
    for name, value in action.args:
        given[name] = resolve(value, scope)
    # included from a package launch arguments name: what it does holds for their defaults only
    by_default, free = _packages_by_default(action.path, scope)
    if by_default:
        when = when.also(When(True, free, (by_default,)))
    _expand(index, target, given, False, when, configuration, packages, via, depth + 1,
            (_joined_words(scope.by_default, by_default), scope.default_free | free),
            remaps + _remapped(action.remaps, scope, scope.launch))


def _remapped(remaps: tuple, scope: Scope, launch: LaunchFile) -> tuple:
    """Each :class:`~urdftool.description.launch.Remap` resolved in ``scope``: a value read
    from launch arguments holds for what they are given (their names join its condition)."""
    found = []
    for remap in remaps:
        source, target = resolve(remap.source, scope), resolve(remap.target, scope)
        when = _when_of(remap.when, scope)
        if source.free or target.free:
            names = sorted(source.free | target.free)
            words = (f"as launch arguments {', '.join(names)} are given" if len(names) > 1
                     else f"as launch argument {names[0]} is given")
            when = when.also(When(True, source.free | target.free, (words,)))
        found.append(Remapped(source.text, target.text, when, launch.display, remap.line,
                              bool(target.free)))
    return tuple(found)


def _leads_outside(path: Path | None, resolved: Resolved, scope: Scope, action,
                   configuration: Configuration) -> None:
    """Record in ``configuration.outside`` a file ``action`` (an include, a parameter file)
    names by a path leading outside the repository, itself or through a link (not a
    package's: ``$(find pkg)`` of a package not in the repository is not known, not outside):
    it is not read, and was left out without a word (a controller YAML at
    ``../../outside/c.yaml``, an include of ``/etc/hostname``). Said as written."""
    text = resolved.text
    if path is not None or text is None or "\n" in text:
        return
    if text.count("\0") == 2:  # a file of a package of the repository, through a link
        _, package, rest = text.split("\0")
        folder = scope.packages.get(package)
        named = folder / rest.strip("/") if folder is not None and rest.strip("/") else None
        if named is None or not kind_of(named, follow=False):
            return
    elif "\0" in text:
        return
    else:
        named = Path(text) if Path(text).is_absolute() else scope.launch.path.parent / text
    if not inside(os.path.normpath(named), scope.root):
        configuration.outside.append((scope.launch.display, action.line,
                                      action.path.text or shown(resolved) or text))


def _loaded(action: ParamFile, scope: Scope, when: When, launch: LaunchFile, via: tuple,
            configuration: Configuration) -> Loaded:
    path, resolved = resolve_path(action.path, scope)
    _leads_outside(path, resolved, scope, action, configuration)
    if resolved.free:
        when = when.also(When(True, resolved.free, ()))
    return Loaded(path, shown(resolved) or action.path.text, action.substitute,
                  dict(scope.args) if action.substitute else {}, when, launch.display, action.line,
                  via + (launch.display,))


_DESCRIPTION_PARAMETER = re.compile(r"robot_description\)?(_semantic)?$")


def _describes(parameter: str) -> bool:
    """Whether a description loaded into ``parameter`` is what the robot's consumers read:
    ``robot_description`` (or ``..._semantic``, or a name that says nothing of it), not
    ``robot_description_tf2`` or another copy beside it."""
    return "robot_description" not in parameter or bool(_DESCRIPTION_PARAMETER.search(parameter.strip()))


def _described(action: Description, scope: Scope, when: When, launch: LaunchFile,
               via: tuple, published: When | None = None) -> Described:
    args: dict = {}
    path, written, template, through, complete = None, "", None, action.xacro, action.complete
    chosen_by: frozenset = frozenset()
    source = action.file  # the value naming the file
    if action.command is not None:
        command = action.command
        if len(command.parts) == 1 and isinstance(command.parts[0], tuple) and command.parts[0][0] == "command":
            command = command.parts[0][1]
        through, program = False, True
        for word in words(command):
            text = word.literal
            head = word.parts[0] if word.parts and isinstance(word.parts[0], str) else ""
            if ":=" in head:
                name, _, rest = head.partition(":=")
                tail = Value(((rest,) if rest else ()) + word.parts[1:], word.text)
                args[name] = shell_word(resolve(tail, scope))
                continue
            if text is not None and text.startswith("-"):
                continue
            candidate, resolved = resolve_path(word, scope, shell=True)
            if path is None and _program(resolved.text or word.text) in ("xacro", "xacro.py"):
                through = True
                continue
            shown_text = shown(resolved) or word.text
            if path is None and (shown_text.endswith(DESCRIPTION_SUFFIXES)
                                 or (resolved.pattern or "").endswith(DESCRIPTION_SUFFIXES)):
                path, written, template = candidate, shown_text, _template(resolved)
                chosen_by, program, source = resolved.free, False, word
            elif resolved.text is not None and ":=" in resolved.text:
                # roslaunch substitutes, then splits: $(arg xacro_args) may be "a:=1 b:=2"
                for piece in resolved.text.split():
                    name, given, value = piece.partition(":=")
                    if given:
                        args[name] = Resolved(value, resolved.free)
                    else:
                        complete = False
            elif not program:
                complete = False  # a word not read may give arguments
    elif action.file is not None:
        path, resolved = resolve_path(action.file, scope)
        written = shown(resolved) or action.file.text
        template, chosen_by = _template(resolved), resolved.free
        for name, value in action.args:
            args[name] = resolve(value, scope)
    by_default, free = _packages_by_default(source, scope) if path is not None else ("", frozenset())
    if by_default:
        when = when.also(When(True, free, (by_default,)))
    return Described(path, written, args, when, launch.display, action.line, through, complete,
                     template, chosen_by, via + (launch.display,),
                     _joined_words(scope.by_default, by_default) if path is not None else "",
                     action.replaced if action.command is None else (),
                     published.also(When(True, free, (by_default,))) if published is not None
                     and by_default else published)


BY_DEFAULT = "when launched with "  # how a condition on package arguments' defaults begins


def _joined_words(first: str, second: str) -> str:
    """Two conditions "when launched with ..." said as one."""
    if not (first and second) or second == first:
        return first or second
    return f"{first} and {second.removeprefix(BY_DEFAULT)}"


def _packages_by_default(value: Value | None, scope: Scope) -> tuple[str, frozenset]:
    """When launch arguments that may be given at launch name the packages in ``value``
    (``$(find $(arg description_package))``, ``FindPackageShare(LaunchConfiguration(...))``),
    the condition under which it names those it does, in words ("when launched with
    description_package's default 'ur_description'"), and those arguments; ("", empty) when
    the file names its packages itself, or an including launch file gives their names."""
    said, free = [], set()
    for part in value.parts if value is not None else ():
        if not (isinstance(part, tuple) and part[0] == "find" and isinstance(part[1], Value)):
            continue
        named = resolve(part[1], scope)
        # (arguments an including launch file's condition already names are said there)
        own = named.free - scope.default_free
        if not own or named.text is None:
            continue
        free |= own
        names = [f"the environment variable {n[1:]}" if n.startswith("$") else n
                 for n in sorted(own)]
        whole = named.pattern == WILD and len(names) == 1  # the argument's value, whole
        said.append(f"{names[0]}'s default '{named.text}'" if whole else
                    f"the default{'s' if len(names) > 1 else ''} of {', '.join(names)} "
                    f"(package '{named.text}')")
    return (BY_DEFAULT + " and ".join(said) if said else ""), frozenset(free)


def _program(text: str | None) -> str:
    """The name of the program a command line's word runs (``$(find xacro)/xacro``: xacro)."""
    return (text or "").strip("'\"").rstrip("/").rsplit("/", 1)[-1].rsplit("\0", 1)[-1]


def _template(resolved: Resolved) -> str | None:
    """The path a description is made from, with :data:`WILD` where a launch argument's value
    goes, when a launch argument chooses it (``talos_$(arg robot).urdf.xacro``); else None."""
    return resolved.pattern if resolved.pattern is not None and WILD in resolved.pattern else None


__all__ = ["BY_DEFAULT", "TRUTHY", "WILD", "Configuration", "Described", "LaunchIndex", "Loaded",
           "Remapped", "Resolved", "Started", "When",
           "launch_index", "resolve", "shown", "words"]
