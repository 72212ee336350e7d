"""Which files ``urdftool check DIR`` checks: top-level robots, not the macro libraries they
include.

Classifying a file reads it only when it is a regular file under the size limit and, links
followed, inside its repository (see :func:`~urdftool.description.packages.containment_root`); any
other file is kept as a target, unread, so that checking it reports why (U017, U008, U001).
Only what classification needs is kept per file, never its bytes.
"""

from __future__ import annotations

import os
import re
from fnmatch import fnmatchcase as fnmatch
from pathlib import Path

from urdftool.diagnostics import display_path
from urdftool.description.crashes import guarded
from urdftool.description.companions import COMPANION_SUFFIXES, may_use, users_below
from urdftool.description.launch import LAUNCH_SUFFIXES
from urdftool.description.files import DEFAULT_MAX_FILE_SIZE, kind_of, listable, unreachable, \
    walk
from urdftool.description.packages import SKIP_DIRS, PackageResolver, containment_root
from urdftool.description.urdf import ROBOT_GLOB, is_robot_name, is_urdf_name
from urdftool.description.xacro_text import (CHUNK as _CHUNK, DEFINITIONS as _DEFINITIONS,
                                             FIND as _FIND, INCLUDE as _INCLUDE,
                                             MACRO_START as _MACRO,
                                             XACRO_DIRECTIVES as _XACRO_DIRECTIVES,
                                             _Answered, arg_defaults as _arg_defaults,
                                             head as _head, included_files as _included_files,
                                             is_xacro as _is_xacro, local_name as _local_name,
                                             without_macro_bodies as _without_macro_bodies,
                                             reached, resolved_path, resolved_spec as _resolved_spec,
                                             stays_inside as _stays_inside, stream as _stream,
                                             uncommented as _uncommented)
from urdftool.lint.parts import EXTENSIONS as _EXTENSIONS, PART, rootless
from urdftool.records import NEW, Record


# A robot file named in an attribute value (a macro parameter or property that a macro hands to
# <xacro:include filename="${layout}"/>: osrf/vrx's thruster layouts)
_NAMED_FILE = re.compile(rb"=\s*[\"']([^\"'<>]+\.(?:xacro|urdf))[\"']")
# Elements only MoveIt's semantic description (SRDF) has below its <robot> root
_SRDF_TAGS = {"group", "group_state", "end_effector", "virtual_joint", "passive_joint",
              "disable_collisions", "disable_default_collisions", "enable_collisions",
              "link_sphere_approximation"}
SRDF_SOURCE = "an SRDF source (MoveIt's semantic description), not a robot"
SDF_SOURCE = "an SDF document (a Gazebo model or world, built by xacro), not a URDF robot"
OTHER_DOCUMENT = ("an XML document of another kind built by xacro (its root is no <robot>, and it "
                  "calls macros or writes content), not a URDF robot")
FRAGMENT = ("a fragment of a robot defined elsewhere (only <gazebo>, <transmission>, "
            "<ros2_control> or <webots> blocks besides definitions)")


def robot_files(folder: Path, unlisted: list[Path] | None = None) -> list[Path]:
    """Every .urdf and .xacro file below ``folder``, sorted, skipping tool folders. Symbolic
    links (to files or folders) leading outside the repository are listed too, not followed, so
    that checking them reports it; a ``folder`` that is itself such a link is listed alone.
    Folders that could not be listed (no permission, a path past the system's limit) are
    added to ``unlisted``: their files are not checked, which a run must say."""
    if not _stays_inside(folder):
        return [folder]
    found = []
    for current, entries in walk(Path(folder), f"*/|{ROBOT_GLOB}", _ANY_DEPTH, SKIP_DIRS):
        current = Path(current)
        if not entries and unlisted is not None and not listable(current):
            unlisted.append(current)
        for name, kind in entries:
            if kind == "folder":
                continue  # (walked, unless hidden or a tool's)
            path = current / name
            if kind == "link" and kind_of(path) == "folder":
                if name not in SKIP_DIRS and not name.startswith(".") and not _stays_inside(path):
                    found.append(path)
            elif is_robot_name(name):
                found.append(path)
    return sorted(found)


_ANY_DEPTH = 1 << 30  # (folders below folders: walked to the bottom)
_HELD = (("*.srdf", "SRDF"), ("*.launch|*.launch.*", "launch file"), ("*.sdf", "SDF document"))


def _what_it_holds(folder) -> str:
    """For the error of a folder without robot files: the robot descriptions' companions it
    holds (a MoveIt configuration's SRDF, launch files, SDF documents), said so that the reader
    knows they are checked only beside the robot they describe. Walked as robot_files walks."""
    counts = dict.fromkeys([name for _, name in _HELD], 0)
    pattern = "*/|" + "|".join(glob for glob, _ in _HELD)
    # an error message: bounded, never the run's cost
    for _, entries in walk(Path(folder), pattern, _ANY_DEPTH, SKIP_DIRS, most=2000):
        for name, kind in entries:
            if kind == "file":
                counts[next(what for glob, what in _HELD
                            if any(fnmatch(name, g) for g in glob.split("|")))] += 1
    held = [f"{n} {what}{'s' if n > 1 else ''}" for what, n in counts.items() if n]
    if not held:
        return ""
    one = len(held) == 1 and held[0].startswith("1 ")  # "1 launch file, which is ..."
    checked = "which is checked with the robot it describes" if one else \
        "which are checked with the robot they describe"
    return (f"; it holds {', '.join(held)}, {checked}: check a folder holding that robot's "
            ".urdf or .xacro too")


_UNREAD = object()  # (a file's bytes not yet asked of _head)


class _Summary(Record):
    """What classifying one file needs: the files it includes, and whether it is a robot."""

    includes: list[Path]
    defines_robot: bool
    named_robot: bool
    srdf: bool
    unfollowed: bool  # it includes files whose path is only known when expanding
    fragment: bool  # only <gazebo>, <transmission>, <ros2_control> and definitions
    macros: bool  # it defines xacro macros
    missing_package: bool  # an include's $(find PKG) names a package found nowhere
    empty: bool  # a <robot> with nothing in it (Clearpath's empty.urdf placeholders)
    root_elsewhere: str | None  # no root link of its own: why, as parts.rootless says
    sdf: bool  # a xacro file with an <sdf> root: a Gazebo model or world (nav2's
    # gz_waffle.sdf.xacro); a .urdf holding SDF is checked (U004: it says it is a URDF)
    blank: bool  # no text at all, or white space only
    document: bool  # a .xacro whose root is no <robot> (nor a misspelling of it), with
    # content besides definitions: another kind of XML xacro builds (Shadow's <test> harness)

    __slots__ = ("includes", "defines_robot", "named_robot", "srdf", "unfollowed", "fragment",
                 "macros", "missing_package", "empty", "root_elsewhere", "sdf", "blank",
                 "document")

    def __init__(self, includes: list[Path], defines_robot: bool, named_robot: bool,
                 srdf: bool = False, unfollowed: bool = False, fragment: bool = False,
                 macros: bool = False, missing_package: bool = False, empty: bool = False,
                 root_elsewhere: str | None = None, sdf: bool = False,
                 blank: bool = False, document: bool = False) -> None:
        self.includes = includes
        self.defines_robot = defines_robot
        self.named_robot = named_robot
        self.srdf = srdf
        self.unfollowed = unfollowed
        self.fragment = fragment
        self.macros = macros
        self.missing_package = missing_package
        self.empty = empty
        self.root_elsewhere = root_elsewhere
        self.sdf = sdf
        self.blank = blank
        self.document = document


def _checked_as(path: Path) -> Path:
    """What checking ``path`` checks, so that a file named twice (two names, links within the
    repository) is checked once: its real path; but a link leading outside its repository is
    itself the finding (U017: never followed), so each such link is said, however many lead
    to one file (two committed links to ``/dev/zero`` were one finding: the second appeared
    only once the first was removed)."""
    resolved = resolved_path(path)
    if resolved == Path(os.path.abspath(path)) or _stays_inside(path):
        return resolved
    return Path(os.path.abspath(path))


def split_top_level(files: list[Path], resolver_for, max_file_size: int = DEFAULT_MAX_FILE_SIZE
                    ) -> tuple[list[Path], dict[Path, str]]:
    """(top-level files, {skipped file: reason}) for a set of files found in a folder.

    max_file_size: files larger [bytes] are not read; they stay targets (U008 when checked)
    """
    included: dict[Path, Path] = {}
    summaries = {path: _guarded(path, lambda path=path: _summary(path, resolver_for,
                                                                 max_file_size))
                 for path in files}
    for path, summary in summaries.items():
        for target in summary.includes if summary is not None else ():
            included.setdefault(target, path)
    top, skipped = [], {}
    for path in files:
        key = resolved_path(path)
        if summaries[path] is None:
            skipped[path] = CRASHED
        elif key in included:
            skipped[path] = f"included by {included[key]}"
        elif (reason := _guarded(path, lambda path=path: _not_a_robot(
                path, summaries[path], resolver_for, max_file_size), CRASHED)):
            skipped[path] = reason
        else:
            top.append(path)
    return top, skipped


FINDING = "finding the robots to check"  # (the reader a crash while finding targets names)
CRASHED = "urdftool crashed reading it (U900): not checked"


def _guarded(path: Path, read, fallback=None):
    """``read()`` of one file while finding the robots, or ``fallback`` when it crashes: U900
    at that file (:func:`urdftool.description.crashes.guarded`), the walk going on with the
    folder's other files (a crash reading one lost them all)."""
    return guarded(FINDING, path, read, fallback)


def _summary(path: Path, resolver_for, limit: int, data=_UNREAD) -> _Summary:
    """Read ``path`` (when :func:`_head` may) and keep only what classification needs; the
    includes only given ``resolver_for``. ``data``: what :func:`_head` gave, when read."""
    if data is _UNREAD:
        data = _head(path, limit)
    if data is None or b"\0" in data:  # unread, or binary: a target, so checking says why
        return _Summary([], True, True)
    if not data.strip():  # nothing a consumer could read as a robot, unless one loads it
        return _Summary([], False, False, blank=True)
    written = _uncommented(data)
    includes = _included(path, written, resolver_for(path)) if resolver_for else []
    unfollowed = resolver_for is not None and _INCLUDE_WORD in written and \
        len(_INCLUDE.findall(written)) > len(includes)
    if resolver_for:
        includes += _named_files(path, written, resolver_for(path), includes)
    answer = _top_level_answer(data)
    if answer in ("definitions", "fragment", "empty") and path.name.endswith(".xacro") and \
            not _well_formed_for_xacro(data):
        answer = "robot"  # not a library: checking it reports why xacro cannot read it
    return _Summary(includes, answer not in ("definitions", "fragment", "empty"),
                    bool(_NAMED_ROBOT.search(data)),
                    answer == "srdf" or path.name.endswith(".srdf.xacro"),
                    unfollowed, answer == "fragment",
                    b"macro" in written and bool(_MACRO.search(written)),
                    resolver_for is not None and _misses_a_package(written, resolver_for(path)),
                    answer == "empty",
                    _root_elsewhere(written, expanded=not is_urdf_name(path.name)),
                    sdf=answer == "sdf" and not is_urdf_name(path.name),  # .urdf: U004
                    document=answer == "document" and not _urdf_named(path.name))


def _urdf_named(name: str) -> bool:
    """Whether a file's name says it is URDF, as it is or built by xacro (``.urdf``,
    ``.urdf.xacro``, any case): whatever its root, it is checked (U004 names the root)."""
    return name.lower().endswith((".urdf", ".urdf.xacro"))


def _not_urdf(summary: _Summary) -> str:
    """Why a file of another kind than a URDF robot is not checked (SRDF, SDF, other XML)."""
    return SRDF_SOURCE if summary.srdf else SDF_SOURCE if summary.sdf else OTHER_DOCUMENT


def _well_formed_for_xacro(data: bytes) -> bool:
    """Whether xacro can parse ``data``: well-formed XML with its namespaces declared (xacro's
    parser refuses a ``xacro:`` prefix used without ``xmlns:xacro``; lxml's recovering parser,
    which classifies files, would not say)."""
    from xml.parsers import expat

    parser = expat.ParserCreate(namespace_separator=" ")
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    try:
        parser.Parse(data, True)
    except Exception:  # noqa: BLE001 - malformed (the check says how), or an unknown encoding
        return False
    return True


def _includes_yield_links(summary: _Summary, resolver_for, limit: int) -> bool | None:
    """Whether the files ``summary``'s file includes, followed through their own includes,
    produce links (see :func:`_yields_links`): a robot built by its includes is a robot. None
    when they do not as far as they could be followed, but some could not (a missing file, an
    include whose path needs an argument or a package not found)."""
    unknown = summary.unfollowed
    for data, complete in reached(summary.includes, resolver_for, limit, also=_named_files):
        if data is None:  # missing or refused: checking the includer says why
            unknown = True
        elif _yields_links(data):
            return True
        else:
            unknown = unknown or not complete
    return None if unknown else False


def _defines_robot(data: bytes) -> bool:
    """Whether a xacro file produces a robot itself: anything under <robot> besides xacro
    definitions (properties, args, includes, macros) and extension blocks (a fragment).
    Unparsable files count, so that the parse error is reported."""
    return _top_level_answer(data) not in ("definitions", "fragment", "empty")


def _top_level_answer(data: bytes) -> str:
    """'robot' (content of its own, or not a xacro library at all), 'srdf' (a semantic
    description), 'fragment' (<gazebo>, <transmission>, <ros2_control> blocks and definitions:
    part of a robot defined elsewhere) or 'definitions' (only properties, args, includes,
    macros)."""
    return _stream(data, _TopLevelTags())


def _has_own_links(path: Path, limit: int, data=_UNREAD) -> bool:
    """Whether the file at ``path`` writes ``<link>`` or ``<joint>`` elements of its own under
    ``<robot>`` (inside ``xacro:if``/``unless`` too): a robot, not a part that only calls
    macros (``niryo_ned.transmission.xacro``: transmissions through macro calls). A file that
    is not read counts (checking it says why). ``data``: what :func:`_head` gave, when read."""
    if data is _UNREAD:
        data = _head(path, limit)
    return data is None or b"\0" in data or _stream(data, _OwnLinks()) == "own"


_LINK_NAME = re.compile(rb"<link\s[^<>]*?name\s*=\s*[\"']([^\"'<>]*)[\"']", re.S)
_JOINT_END = re.compile(rb"<(?:parent|child)\s[^<>]*?link\s*=\s*[\"']([^\"'<>]*)[\"']", re.S)


def _self_contained(path: Path, limit: int, data=_UNREAD) -> bool:
    """Whether every link the file's joints name as parent or child is a link the file
    writes (names compared as written): a robot of its own. A file whose joints hang on links
    it does not write (baxter's pedestal.xacro on the 'torso' of the robot including it) is a
    part, checked through what includes it. A file that is not read counts (checking it says
    why). ``data``: what :func:`_head` gave, when read."""
    if data is _UNREAD:
        data = _head(path, limit)
    if data is None or b"\0" in data:
        return True
    return set(_JOINT_END.findall(data)) <= set(_LINK_NAME.findall(data))


_CHILD = re.compile(rb"<child\s[^<>]*?link\s*=\s*[\"']([^\"'<>]*)[\"']", re.S)
_PARENT = re.compile(rb"<parent\s[^<>]*?link\s*=\s*[\"']([^\"'<>]*)[\"']", re.S)


def _root_elsewhere(data: bytes, expanded: bool = True) -> str | None:
    """Why the robot ``data`` writes has no root of its own, as its text shows, or None when
    it has one (:func:`urdftool.lint.parts.rootless` decides, from the links and joints read
    here): it has joints, every link it writes is a joint's child, and some joint names a
    link it does not write. A robot has one root link; such a file is a part of a robot
    defined elsewhere, whatever its root element says (jackal's custom_example.urdf, meant
    for $(optenv JACKAL_URDF_EXTRAS): joints on the 'front_mount' of the jackal that
    includes it). A misspelt parent in a robot leaves its real root a root; Gazebo's 'world'
    is no link to write. Only when nothing outside macro definitions and link bodies may
    write links the text does not show (macro calls, includes), unless the file is not
    ``expanded`` (a ``.urdf`` is read as written) and does not declare xacro's namespace (a
    ``.urdf`` that does is expanded, with U007: elephantrobotics' stale
    mycobot_with_vision_copy.urdf includes a file that is gone; jackal's custom_example.urdf
    calls a macro without declaring it, which xacro cannot parse)."""
    data = _without_macro_bodies(data)
    if (expanded or b"xmlns:xacro" in data) and _makes_links_outside_link_bodies(data):
        return None  # a macro call or an include may write the root
    found = rootless(*([name.decode("utf-8", "replace") for name in pattern.findall(data)]
                       for pattern in (_LINK_NAME, _PARENT, _CHILD)))
    return found.condition if found is not None else None


# Outside macro definitions, what may write links the text does not show: a macro call (any
# xacro: element but the directives that write none) or an include.
_LINK_MAKER = re.compile(rb"<xacro:(?!(?:property|arg|macro|if|unless|load_yaml)[\s/>])[\w.]|"
                         rb"<(?:xacro:)?include\s")
# A <link>'s start and end tags, and what may write links: read in one pass, in order
_LINK_TOKENS = re.compile(rb"<link\b[^<>]*>|</link\s*>|" + _LINK_MAKER.pattern)


def _makes_links_outside_link_bodies(data: bytes) -> bool:
    """Whether a macro call or an include stands outside every <link> body: one inside a
    link writes the link's content (an inertial, a visual), never a link urdfdom reads
    (HerGousis' camera3_dokari.xacro calls box_inertia inside its link). One linear pass,
    after one search when there is none at all (a URDF's 10,000 links are not walked)."""
    if (b"<xacro:" not in data and _INCLUDE_WORD not in data) or _LINK_MAKER.search(data) is None:
        return False
    inside = False
    for token in _LINK_TOKENS.finditer(data):
        text = token.group(0)
        if text.startswith(b"</link"):
            inside = False
        elif text.startswith(b"<link"):
            inside = not text.endswith(b"/>")
        elif not inside:
            return True
    return False


def _yields_links(data: bytes) -> bool:
    """Whether a file, included, produces links: a <link> or <joint>, or a macro call, outside
    its macro definitions (inside <xacro:if> too)."""
    return _stream(data, _LinksOutsideMacros()) == "links"


def _misspelt_robot(root: str) -> bool:
    """Whether a root element's name may be ``robot`` misspelt (``robt``, ``Robot``, an old
    macro file's ``root``): such a file is checked, and U004 names its root."""
    from urdftool.errors import similarity

    return similarity(root.lower(), "robot") >= 0.6


class _TopLevelTags:
    """lxml parser target: answers 'robot' at a child of the root that is neither a definition
    nor an extension block (<gazebo>, ...), 'srdf' at a child only an SRDF has, 'sdf' at an
    ``<sdf>`` root (a Gazebo model or world that xacro builds, never a URDF), 'document' at
    such a child of a root that is no ``<robot>`` misspelt (xacro builds any XML: Shadow's
    ``<test>`` harness, which calls macros that print); at the end,
    'fragment' when it saw extension blocks, else 'definitions' ('empty' for a <robot> with no
    child). A root other than <robot> holding only definitions is a macro library too: xacro's
    includes ignore the root element, and pre-Groovy macro files were written ``<root
    xmlns:xacro=...>`` (mas-group/youbot_description's sensors); with anything else, or
    nothing, it is checked (and its root reported). The children of a ``xacro:if``/``unless``
    child of the root are judged as the root's own: a condition choosing a property (MiR's
    ``imu.gazebo.urdf.xacro``) leaves a macro library one; a condition holding a link makes a
    robot."""

    def __init__(self):
        self.depth, self.seen_robot, self.other_root, self.root = 0, False, False, ""
        self.extensions = self.children = False
        self.conditions: list[int] = []  # depths of the top-level xacro:if/unless open

    def start(self, tag, attributes):
        self.depth += 1
        level = self.depth - len(self.conditions)  # their children count as the root's
        if level > 2:
            return
        name = _local_name(tag)
        if level == 2 and name in ("if", "unless") and _is_xacro(tag):
            # a condition choosing among definitions (MiR's imu frame property)
            self.conditions.append(self.depth)
            self.seen_robot = self.children = True
            return
        if self.depth == 1 and name == "sdf" and not _is_xacro(tag):
            raise _Answered("sdf")
        if self.depth == 1 and name != "robot":
            self.other_root, self.root = True, name
            return
        self.seen_robot = True
        if level == 2 and name in _SRDF_TAGS and not _is_xacro(tag):
            raise _Answered("srdf")
        self.children = self.children or level == 2
        if level == 2 and name in _EXTENSIONS and not _is_xacro(tag):
            self.extensions = True
        # Pre-2019 xacro wrote the same tags without the xacro: prefix.
        elif level == 2 and name not in _DEFINITIONS:
            raise _Answered("document" if self.other_root and not _misspelt_robot(self.root)
                            else "robot")

    def end(self, tag):
        if self.conditions and self.conditions[-1] == self.depth:
            self.conditions.pop()
        self.depth -= 1

    def close(self):
        return None

    def default(self) -> str:
        if not self.seen_robot:
            return "robot"
        return "fragment" if self.extensions else "definitions" if self.children else "empty"


class _OwnLinks:
    """lxml parser target: answers 'own' at a <link> or <joint> child of <robot>, or of a
    ``xacro:if``/``unless`` there."""

    def __init__(self):
        self.path: list[str] = []

    def start(self, tag, attributes):
        name = _local_name(tag)
        if name in ("link", "joint") and not _is_xacro(tag) and len(self.path) >= 1 and \
                all(part in ("if", "unless") for part in self.path[1:]):
            raise _Answered("own")
        self.path.append(name if _is_xacro(tag) or not self.path else "?")

    def end(self, tag):
        if self.path:
            self.path.pop()

    def close(self):
        return None

    def default(self) -> str:
        return "none"


class _LinksOutsideMacros:
    """lxml parser target: answers 'links' at a <link>, <joint> or macro call that is not
    inside a <xacro:macro>, nor inside an extension block (<transmission>, <ros2_control>,
    <gazebo>, ...: their <joint name> names a joint of the robot, it writes none; fusion2urdf's
    NAME.trans, included by the NAME_macro.urdf.xacro nobody calls, made that library a robot)."""

    def __init__(self):
        self.in_macro = self.in_block = 0

    def start(self, tag, attributes):
        name = _local_name(tag)
        if name == "macro":  # pre-2019 xacro wrote it without the xacro: prefix
            self.in_macro += 1
        elif name in _EXTENSIONS and not _is_xacro(tag):
            self.in_block += 1
        elif not self.in_macro and not self.in_block and (
                name in ("link", "joint") and not _is_xacro(tag)
                or _is_xacro(tag) and name not in _XACRO_DIRECTIVES):
            raise _Answered("links")

    def end(self, tag):
        name = _local_name(tag)
        if name == "macro":
            self.in_macro -= 1
        elif name in _EXTENSIONS and not _is_xacro(tag):
            self.in_block -= 1

    def close(self):
        return None

    def default(self) -> str:
        return "none"


def _named_files(path: Path, data: bytes, resolver: PackageResolver, includes) -> list[Path]:
    """Robot files (existing, other than ``includes``) named by attribute values of ``data``:
    a macro parameter or property holding a path that a macro includes
    (``<xacro:wamv_gazebo thruster_layout="$(find wamv_gazebo)/urdf/.../wamv_aft_thrusters.xacro"/>``
    handed to ``<xacro:include filename="${thruster_layout}"/>``), which the include graph
    counts as included by ``path``."""
    if b".xacro" not in data and b".urdf" not in data:  # (what every name it finds ends with)
        return []
    named, defaults = [], _arg_defaults(data)
    for match in _NAMED_FILE.finditer(data):
        found = _resolved_spec(path, match.group(1).decode("utf-8", "replace"), defaults,
                               resolver)
        if found is not None and found not in includes and found not in named and \
                kind_of(found) == "file":
            named.append(found)
    return named


def _misses_a_package(data: bytes, resolver: PackageResolver) -> bool:
    """Whether an include names, through ``$(find PKG)``, a package that cannot be found (a
    defect expanding the file reports, U006), rather than a path only known when expanding.
    Includes inside a macro definition are left out: they are expanded only where it is called."""
    for match in _INCLUDE.finditer(_without_macro_bodies(data)):
        spec = match.group(1).decode("utf-8", "replace")
        find = _FIND.search(spec)
        if find and "$" not in spec.replace(find.group(0), ""):  # the rest is written out
            try:
                resolver.find(find.group(1))
            except Exception:  # noqa: BLE001 - not found, whatever the resolver says
                return True
    return False


_NAMED_ROBOT = re.compile(rb"<robot\b[^<>]*?\sname\s*=", re.S)


def companion_users(companion: Path, robots: list[Path], limit: int = DEFAULT_MAX_FILE_SIZE
                    ) -> list[Path]:
    """The robots (top-level robot files) that may be checked with ``companion`` (a controller
    YAML, an SRDF, a spec): see :func:`~urdftool.description.companions.may_use`."""
    return [robot for robot in robots
            if may_use(robot, companion, _head(robot, limit) or b"")]


def _own_robot(path: Path, limit: int, data) -> bool:
    """Whether a file named, read as ``data`` (its :func:`_head`), is a robot of its own: not
    an SRDF source, a named ``<robot>`` writing links or joints of its own that hang on no
    link it does not write, or a file not read (checking it says why). Asked before its
    :func:`_summary`, whose includes only a file that is not one needs."""
    if data is None or b"\0" in data:
        return True
    if path.name.endswith(".srdf.xacro") or not _NAMED_ROBOT.search(data) or \
            _top_level_answer(data) == "srdf" or not _has_own_links(path, limit, data) or \
            not _self_contained(path, limit, data):
        return False
    written = _uncommented(data)  # (once for the three questions left)
    return not _borrows_macros(data, written) and not _borrows_materials(data, written) and \
        not _urdf_for_xacro(path, written)


def _uses_xacro(written: bytes) -> bool:
    """Whether a text without comments uses xacro (``${``, ``$(``, ``<xacro:``), each looked
    for by bytes' own search (a regular expression of the three alternatives scanned a
    10,000-link robot's 3 MB at 100 instructions a byte, +4 %); the two-byte needles only in
    a text holding a "$" (one byte is memchr's pace, two bytes several times slower)."""
    return b"$" in written and (b"${" in written or b"$(" in written) or b"<xacro:" in written


def _urdf_for_xacro(path: Path, written: bytes) -> bool:
    """Whether a ``.urdf`` holds xacro (``$(find)``, ``${}``, ``<xacro:``): named, it is
    checked through the robots that include it, as the folder walk checks it (RealMan's
    rm_65_gazebo.urdf, whose meshes are ``$(find rm_description)/...``, included by
    gazebo_65_description.urdf.xacro: named alone, a U007 error the walk never gave); nobody
    including it, or a launch file loading it as it is (nextage's NextageOpen.urdf, given
    MoveIt with ``textfile=``), it is checked as it is (U007 says what reads it). ``written``:
    its text without comments."""
    if not is_urdf_name(path.name) or not _uses_xacro(written):
        return False
    from urdftool.description.runtime import builds

    return not any(not build.xacro for build in builds(str(path)))


_CALLED = re.compile(rb"<xacro:([\w.-]+)")  # a macro call, or one of xacro's directives
_DIRECTIVE_NAMES = frozenset(name.encode() for name in _XACRO_DIRECTIVES)
_DEFINED_MACRO = re.compile(rb"<xacro:macro\s[^<>]*?name\s*=\s*[\"']([^\"'<>]*)[\"']", re.S)
_ANY_INCLUDE = re.compile(rb"<(?:xacro:)?include\s")
# A word every include's tag holds, looked for first (bytes' own search) before a pattern that
# is tried at each "<" of a file: most robot files include nothing (so for "macro", ".xacro").
_INCLUDE_WORD = b"include"


def _included(path: Path, written: bytes, resolver: PackageResolver) -> list[Path]:
    """The files ``written`` (``path``'s text without comments) includes, resolved
    (:func:`~urdftool.description.xacro_text.included_files`); none looked for in a text
    without the word."""
    return list(_included_files(path, written, resolver)) if _INCLUDE_WORD in written else []


def _borrows_macros(data: bytes, written: bytes) -> bool:
    """Whether a file calls a macro it neither defines nor includes (it includes nothing): xacro
    expands it only inside a file that defines the macro before including it, so it is a part
    of that robot, not a robot of its own (programmatoroSeduto/arm_urdf's arm.xacro calls the
    ``cylinder_inertia`` that main.xacro takes from macros.xacro before including it; named
    alone, as pre-commit names it, xacro failed on it, a U005 error the folder walk, which
    checks main.xacro, never gave). Nobody including it, it is checked as it is. ``written``:
    ``data`` without comments."""
    if b"<xacro:" not in data:
        return False
    data = written
    if _INCLUDE_WORD in data and _ANY_INCLUDE.search(data):
        return False
    calls = set(_CALLED.findall(data)) - _DIRECTIVE_NAMES
    return bool(calls - set(_DEFINED_MACRO.findall(data)))


_MATERIAL_NAMED = re.compile(rb"<material\s(?>[^<>]*?name\s*=\s*[\"']([^\"'<>$]+)[\"'])[^<>]*?(/?)>", re.S)


def _borrows_materials(data: bytes, written: bytes) -> bool:
    """Whether a file names materials (``<material name="silver"/>``) that it defines nowhere
    (no ``<material name="silver">`` with a colour or texture) and includes nothing: urdfdom
    refuses such a robot alone, so it is written to be included after the file defining them,
    a part of the robot including it (aip-primeca-occitanie/ros_yaskawa_hc10's cell.xacro and
    pince.xacro, whose colours hc10dt_with_env.xacro includes from materials.xacro first:
    named alone, as pre-commit names them, each was U406 warnings the folder walk never gave).
    Nobody including it, it is checked as it is. ``written``: ``data`` without comments."""
    if b"<material" not in data:
        return False
    data = written
    if _INCLUDE_WORD in data and _ANY_INCLUDE.search(data):
        return False
    named = _MATERIAL_NAMED.findall(data)
    return bool({name for name, closed in named if closed} - {name for name, closed in named if not closed})


def project_root(path: Path) -> Path:
    """The folder whose robots may include ``path``: its
    :func:`~urdftool.description.packages.containment_root` (repository, else package, else
    its own folder; as named, a link is not followed)."""
    return containment_root(Path(os.path.abspath(path)).parent)


def explicit_targets(path: Path, includers: dict, root: Path,
                     max_file_size: int = DEFAULT_MAX_FILE_SIZE, resolver_for=None
                     ) -> tuple[list[Path], str | None]:
    """What to check for a file named on the command line (as pre-commit does), and why.

    includers: :func:`includers_below` ``root``, or a function of the bytes already read
        (absolute path -> bytes) returning it, called only when the file is not a robot of its
        own (walking a repository costs more than checking a robot)
    A robot of its own (a named ``<robot>`` with links, joints or macro calls) is checked as it
    is, and so is a file that is not read (a link leading outside the repository, a file over
    the size limit, a FIFO): checking it reports why. A file that is not (a macro library, a
    fragment) but that robots below ``root`` include, directly or through other includes, is
    replaced by those top-level robots: a change to ``leg.xacro`` checks the robot built from
    it. One nobody includes is checked as it is when it
    has content or its includes produce links, and skipped when it only defines macros or
    properties, or is an SRDF source.
    resolver_for: path -> its PackageResolver, to follow ``$(find)`` includes
    """
    data = _head(path, max_file_size)  # read once for every question below
    if _own_robot(path, max_file_size, data):
        return [path], None  # a robot of its own: no need to look for robots including it
    summary = _summary(path, resolver_for, max_file_size, data)
    if summary.srdf or summary.sdf or summary.document:
        return [], f"{_not_urdf(summary)}: nothing to check"
    yields = None if summary.defines_robot else _includes_yield_links(summary, resolver_for,
                                                                       max_file_size)
    includers = includers({os.path.abspath(path): data}) if callable(includers) else includers
    target, seen, tops = resolved_path(path), set(), []
    pending = [target]
    while pending:
        current = pending.pop()
        for parent in includers.get(current, ()):
            resolved = resolved_path(parent)
            if resolved in seen:
                continue
            seen.add(resolved)
            pending.append(resolved)
            if resolved not in includers:
                tops.append(parent)
    if tops:  # as the folder walk takes it, a robot of its own too (baxter's pedestal.xacro)
        tops = sorted(tops)
        # each top as if it were named: a macro library or fragment nobody includes is skipped
        # (clearpath's a200.urdf.xacro defines the macro a robot generated at run time calls),
        # so a file included only by such libraries is not checked through them either
        robots = list(dict.fromkeys(
            robot for top in tops
            for robot in explicit_targets(top, includers, root, max_file_size, resolver_for)[0]))
        shown = ', '.join(display_path(p) for p in tops)
        if not robots:
            return [], (f"included by {shown}, which define only macros, properties or "
                        f"fragments, and no robot below {root} includes them: nothing to check")
        if robots != tops:
            return robots, (f"included by {shown}: checking "
                            f"{', '.join(display_path(p) for p in robots)} instead")
        return robots, f"included by {shown}: checking that instead"
    reason = _not_a_robot(path, summary, resolver_for, max_file_size, yields, data)
    if reason:
        return [], f"{reason}, and no robot below {root} includes it: nothing to check"
    return [path], None


EMPTY = "an empty <robot> (a placeholder an include takes when nothing is added)"
BLANK = "a blank file (a placeholder: no launch file here loads it)"
_UNKNOWN = object()


def _not_a_robot(path: Path, summary: _Summary, resolver_for, limit: int,
                 yields=_UNKNOWN, data=_UNREAD) -> str | None:
    """Why a file that no robot found includes is not checked as a robot, or None to check
    it: the one decision for a file walked and a file named (pre-commit).

    yields: :func:`_includes_yield_links` when already known
    Skipped: an SRDF source; an SDF document (its root is ``<sdf>``); a ``.xacro`` (not
    ``.urdf.xacro``) of another XML whose root is no ``<robot>`` misspelt; an empty ``<robot>``; a
    blank file (a placeholder; xacro fails on it, U002, where something loads it); a ``.urdf`` that is a fragment (only
    ``<gazebo>``, transmission, ros2_control or webots blocks) or a part with no root of its
    own (:func:`_root_elsewhere`, ``.xacro`` too: stretch's stretch_dry_erase_marker.xacro); a
    ``.xacro`` that defines only macros and properties, or is a
    fragment, whose includes produce no links. A named ``<robot>`` with links of its own is a
    robot, hanging on links nobody here writes or not; so is one whose includes could not all
    be followed (expanding it says), unless it defines macros of its own: then it is a macro
    library including others (kortex's gen3_macro.xacro); one whose include names a package
    found nowhere is checked (expanding it says so, U006). Any of them a launch file of its
    repository runs as the robot description, unconditionally, is a robot: checked
    (:mod:`urdftool.lint.parts` then judges what it lacks).
    data: the file's :func:`_head`, when the caller read it (a file named: read once)."""
    if summary.srdf or summary.sdf or summary.document:
        return _not_urdf(summary)
    reason = _not_a_robot_by_text(path, summary, resolver_for, limit, yields, data)
    return None if reason is not None and _run_as_robot(path) else reason


def _run_as_robot(path: Path) -> bool:
    """Whether a launch file of ``path``'s repository gives it, unconditionally, as the robot
    description (:func:`urdftool.description.runtime.builds`). A launch test's build is not a
    deployment (it builds the file for the test alone): as for the check
    (:func:`urdftool.lint.parts._unless_run_as_checked`, launch configurations only), it makes
    no part a robot."""
    from urdftool.description.runtime import builds

    return any(not build.condition and not build.chosen and not build.test
               for build in builds(str(path)))


def _not_a_robot_by_text(path: Path, summary: _Summary, resolver_for, limit: int,
                         yields, data=_UNREAD) -> str | None:
    if summary.empty:
        return EMPTY
    if summary.blank:
        return BLANK
    if is_urdf_name(path.name):
        return FRAGMENT if summary.fragment else summary.root_elsewhere
    if summary.root_elsewhere:
        return summary.root_elsewhere
    if summary.defines_robot or summary.named_robot and _has_own_links(path, limit, data):
        return None
    if yields is _UNKNOWN:
        yields = _includes_yield_links(summary, resolver_for, limit)
    if yields or yields is None and (summary.named_robot and not summary.macros
                                     or summary.missing_package):
        return None
    return FRAGMENT if summary.fragment else "defines only macros or properties (a macro library)"


def includers_below(root: Path, resolver_for, max_file_size: int = DEFAULT_MAX_FILE_SIZE,
                    read: dict | None = None) -> dict[Path, list[Path]]:
    """Included file (resolved) -> the files below ``root`` that include it. ``read``:
    absolute path -> the bytes :func:`_head` gave of files already read (not read again)."""
    includers: dict[Path, list[Path]] = {}
    read = read or {}
    for path in robot_files(root):
        data = read.get(os.path.abspath(path), _UNREAD)
        for target in _guarded(path, lambda path=path, data=data: _includes(
                path, resolver_for, max_file_size, data), ()):
            includers.setdefault(target, []).append(path)
    return includers


def _includes(path: Path, resolver_for, limit: int, data=_UNREAD) -> list[Path]:
    """The files ``path`` includes, as its :func:`_summary` lists them, without the rest of the
    summary (whether it is a robot, its root, its macros: an include graph needs none of it,
    and its questions searched each robot file of a repository once more)."""
    if data is _UNREAD:
        data = _head(path, limit)
    if data is None or b"\0" in data or not data.strip():
        return []
    written = _uncommented(data)
    includes = _included(path, written, resolver_for(path))
    return includes + _named_files(path, written, resolver_for(path), includes)


class Targets(Record):
    """What checking some paths means.

    files: the files to check, in a stable order, each once
    skipped: files found in folders and not checked -> why (included by a robot, a macro library),
        and companion files named that no robot is checked with (said only with -v)
    notes: "PATH: what happened" for files named that are checked through others or not at all
    unchecked: "PATH: why" for each path named that asked for a robot to be checked and gave
        none: a folder whose robot files are all skipped, a file with links of its own that is
        a part (its root link deleted looks the same) nobody here includes. When the run checks
        no file at all these make it a usage error (:func:`urdftool.lint.runner.check_paths`),
        as a folder without robot files is; a companion, a macro library, a fragment or an
        SRDF source named (pre-commit names every staged file) is none by what it is.
    unbuilt: the launch files named that build no robot (each in ``skipped`` with why): a run
        that checks nothing says why without -v, where "0 files checked" would not
    """

    files: list[str]
    skipped: dict[str, str]
    notes: list[str]
    unchecked: list[str]
    unbuilt: list[str]

    __slots__ = ("files", "skipped", "notes", "unchecked", "unbuilt")

    def __init__(self, files: list[str], skipped: dict[str, str], notes: list[str],
                 unchecked: list[str] = NEW, unbuilt: list[str] = NEW) -> None:
        self.files = files
        self.skipped = skipped
        self.notes = notes
        self.unchecked = [] if unchecked is NEW else unchecked
        self.unbuilt = [] if unbuilt is NEW else unbuilt


def expand(paths: list[str], request) -> Targets:
    """The files ``urdftool check PATH...`` checks: folders walked for top-level robots, a macro
    library named replaced by the robots that include it. Packages and the size limit come
    from the settings above each path (:func:`~urdftool.lint.settings.for_file`) under
    ``request``. Raises TargetError for a path that does not exist or a folder without robot
    files."""
    from urdftool.errors import SettingsError, TargetError
    from urdftool.lint.settings import for_file
    from urdftool.records import replace

    known = {}  # path -> its options: asked for each file up to four times (its size limit,
    # the resolver of each question its classification asks)

    def options_for(path):
        """The options ``path`` is checked with; when the settings that apply to it are broken,
        the request's alone: a settings file in another folder never stops this walk (checking
        a file it applies to says what is wrong with it)."""
        path = str(path)
        if path not in known:
            try:
                known[path] = for_file(path, request).options
            except SettingsError:
                known[path] = for_file(path, replace(request, use_settings=False)
                                       ).options
        return known[path]

    def resolver_for(path: Path) -> PackageResolver:
        return PackageResolver(options_for(path).packages, start=path.parent)

    includers = {}  # (project root, size limit) -> its include graph, built once
    robots = {}  # (project root, size limit) -> its top-level robots, found once
    files, skipped, notes, unchecked, unbuilt = [], {}, [], [], []
    def one(path: str) -> None:
        if path != "-" and not kind_of(path, follow=False):
            raise TargetError(f"path '{path}' {unreachable(path)}")
        kind = kind_of(path) if path != "-" else ""
        if kind not in ("file", "folder"):
            files.append(path)
            return
        limit = options_for(path).max_file_size
        if kind == "file" and path.endswith(COMPANION_SUFFIXES):
            root = users_below(Path(path))
            if (root, limit) not in robots:
                robots[root, limit] = split_top_level(robot_files(root), resolver_for, limit)[0]
            users = companion_users(Path(path), robots[root, limit], limit)
            files.extend(display_path(p) for p in users)
            if users:
                notes.append(f"{path}: a companion of {', '.join(display_path(p) for p in users)}: "
                             f"checking {'that' if len(users) == 1 else 'those'}")
            else:  # any YAML a hook passes (launch, navigation, CI settings): said with -v only
                skipped[path] = f"no robot below {root} is checked with it: nothing to check"
            return
        if kind == "file" and path.endswith(LAUNCH_SUFFIXES):
            # a launch file is no robot: the robots it builds are checked, with it
            from urdftool.description.runtime import built_by, why_builds_nothing

            users = [robot for robot in built_by(path) if is_robot_name(robot.name)]
            files.extend(display_path(p) for p in users)
            if users:
                notes.append(f"{path}: a launch file building "
                             f"{', '.join(display_path(p) for p in users)}: checking "
                             f"{'that' if len(users) == 1 else 'those'}")
            else:
                skipped[path] = f"a launch file that {why_builds_nothing(path)}: nothing to check"
                unbuilt.append(path)
            return
        if kind == "file":
            root = project_root(Path(path))

            def graph(read, root=root, limit=limit):
                if (root, limit) not in includers:
                    includers[root, limit] = includers_below(root, resolver_for, limit, read)
                return includers[root, limit]

            targets, reason = explicit_targets(Path(path), graph, root, limit, resolver_for)
            files.extend(display_path(p) if p != Path(path) else path for p in targets)
            if reason:
                notes.append(f"{path}: {reason}")
                if not targets and reason.startswith(PART):
                    unchecked.append(f"{path}: {reason}")
            return
        unlisted: list[Path] = []
        found = robot_files(Path(path), unlisted)
        notes.extend(f"folder '{folder}' cannot be read: its files are not checked"
                     for folder in unlisted)
        top, skipped_here = split_top_level(found, resolver_for, limit)
        files.extend(str(p) for p in top)
        skipped.update({str(p): reason for p, reason in skipped_here.items()})
        if not found:
            raise TargetError(f"no .urdf or .xacro files found in '{path}'{_what_it_holds(path)}")
        if not top:
            first, why = next(iter(skipped_here.items()))
            more = f" (and {len(found) - 1} more)" if len(found) > 1 else ""
            unchecked.append(f"{path}: no robot of its own in it: {first}: {why}{more}")
    for path in map(os.fspath, paths):  # a reader's crash here is urdftool's: U900 at the path
        guarded(FINDING, path, lambda: one(path))  # (the others go on)
    unique = {}  # the same file named twice, or a robot and a macro it includes: check it once
    for file in files:
        unique.setdefault(file if file == "-" else _checked_as(Path(file)), file)
    return Targets(list(unique.values()), skipped, notes, unchecked,
                   list(dict.fromkeys(unbuilt)))  # (a launch file named twice: said once)
