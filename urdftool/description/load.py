"""Load a robot description (URDF, xacro, or stdin) into a :class:`Robot` with source locations.

Every failure is a :class:`~urdftool.errors.LoadError` saying what kind of failure it is and
the file and line where the problem is; what did not stop loading is a :class:`LoadNote` in
``Robot.notes``. The linter turns both into findings.
"""

from __future__ import annotations

import os
import re
import sys
from collections.abc import Mapping
from pathlib import Path

from lxml import etree

from urdftool.diagnostics import Location, Severity, display_path, line_at
from urdftool.errors import LoadError
from urdftool.description.files import DEFAULT_MAX_FILE_SIZE, TooLarge, env_allowed, kind_of, \
    read_regular
from urdftool.description.inputs import SettingValue, checked_file_size, held
from urdftool.description.robot import LoadNote, Robot
from urdftool.description.packages import PackageResolver, containment_root, link_out
from urdftool.description.run_memo import one_run
from urdftool.description.xml import XmlProblem, parse, refuse_empty_or_binary, tinyxml2_comments
from urdftool.description.urdf import is_xacro_element

XACRO_SUFFIXES = (".xacro",)

__all__ = ["Robot", "LoadNote", "load", "first_xacro_use", "PackageResolver"]


def first_xacro_use(root, substitutions: bool = True):
    """The first element that needs xacro (a xacro: tag, or a ``${}``/``$()`` in an attribute or
    text), or None. Comments do not count: generated URDFs often keep commented-out xacro.
    ``substitutions`` False: the document's bytes hold no ``${`` or ``$(`` that could reach
    an attribute or a text (:func:`_may_substitute`), so only a tag is looked at."""
    if not substitutions:  # (every xacro tag holds the word: a C test first) only an element
        # of a namespace ("{URI}name"), or whose name keeps a prefix (lxml's recovering parser
        # keeps an undeclared ``xacro:``), may be xacro's: a plain name is not asked more
        return next((e for e in root.iter(etree.Element)
                     if ("{" in e.tag or ":" in e.tag) and is_xacro_element(e)), None)
    return next((e for e in root.iter(etree.Element) if _needs_xacro(e)), None)


def _needs_xacro(element) -> bool:
    """A xacro tag, or a ``${}``/``$()`` in one of its attributes or its text."""
    return is_xacro_element(element) or _substitutes(element.text) or \
        any(_substitutes(value) for value in element.attrib.values())


def _may_use_xacro(data: bytes) -> bool:
    """False when the bytes alone show that no element needs xacro (no ``${``, ``$(`` or
    ``xacro`` in an ASCII-compatible file without character references), sparing a walk of every
    element of a large URDF."""
    # (one byte looked for first: memchr's pace, a tenth of a pair's search, and most robot
    # files hold no "&" and no "$")
    if b"\x00" in data[:4] or b"&" in data and b"&#" in data:
        return True  # UTF-16/32, or "$" written as a reference: only the parsed tree tells
    return b"$" in data and (b"${" in data or b"$(" in data) or b"xacro" in data


def _may_substitute(data: bytes) -> bool:
    """False when the bytes alone show that no attribute or text holds ``${`` or ``$(``: none
    is outside comments (generated URDFs keep commented-out xacro)."""
    if b"\x00" in data[:4] or b"&" in data and b"&#" in data:  # ("&" first: memchr's pace)
        return True  # UTF-16/32, or "$" written as a reference: only the parsed tree tells
    if b"$" not in data:
        return False
    if b"<![CDATA[" in data or b"<!DOCTYPE" in data or data.find(b"<?", 1) >= 0:
        return True  # "$<![CDATA[{", an entity, a processing instruction holding "<!--"
    for found in _SUBSTITUTION.finditer(data):
        opening = data.rfind(b"<!--", 0, found.start())
        # in a comment when the first "-->" after the last "<!--" before it is after it (a
        # comment holds no "--"; "<" stands for itself nowhere else in these documents)
        if opening < 0 or data.find(b"-->", opening + 4) < found.start():
            return True
    return False


_SUBSTITUTION = re.compile(rb"\$[{(]")


def _substitutes(text: str | None) -> bool:
    return bool(text) and ("${" in text or "$(" in text)


def load(path: str | os.PathLike, *, xacro_args: dict[str, str] | None = None,
         packages: dict[str, Path] | None = None, allow_env: bool | None = None,
         max_file_size: int = DEFAULT_MAX_FILE_SIZE, data: bytes | None = None,
         as_written: bool = False) -> Robot:
    """Load a robot from ``path`` (``-`` reads stdin); raises a located LoadError.

    as_written: read a file not named .xacro as plain URDF even when it holds xacro, as
    urdfdom (check_urdf) reads it; by default such a file is expanded, with a note.
    allow_env: ``$(env)`` and files outside the repository allowed; None, as ``check`` and
    every command: the safe mode when ``CI`` is set (:func:`~urdftool.description.files.
    env_allowed`; this was True, and a script's ``load`` under CI read the job's secrets a
    robot named).

    One load is one view of the file system (:func:`~urdftool.description.run_memo.one_run`,
    the check's when it loads within one): a library caller's load asks each repository root,
    real path and package of its includes once, as a check does."""
    if not isinstance(data, (bytes, type(None))):
        raise TypeError(f"data must be the file's bytes, not {type(data).__name__}")
    # the one guard of a caller's options, as check_paths' (packages="x" was an
    # AttributeError from inside, allow_env="no" true)
    xacro_args = held("xacro_args", xacro_args, "names", none=True)
    packages = held("packages", packages, "paths", none=True)
    allow_env = env_allowed(held("allow_env", allow_env, "flag", none=True))
    held("as_written", as_written, "flag")
    checked_file_size(max_file_size, "max_file_size")
    with one_run():  # (a path in bytes as os reads them: os.fspath kept bytes, and each reader
        # failed on it in its own way)
        return _load(os.fsdecode(path), xacro_args, packages, allow_env, max_file_size, data,
                     as_written)


def _load(path: str, xacro_args, packages, allow_env: bool, max_file_size: int,
          data: bytes | None, as_written: bool) -> Robot:
    shown = display_path(path) if path != "-" else "<stdin>"
    start = Path.cwd() if path == "-" else _folder_of(path)
    if data is None and path != "-":
        _refuse_link_out(path, shown)
    resolver = PackageResolver(packages, start=start)
    if data is None:
        data = _read(path, shown, max_file_size)
    if path.endswith(XACRO_SUFFIXES):
        robot = _load_xacro(path, shown, data, xacro_args or {}, resolver, allow_env,
                            max_file_size)
    else:
        robot = _load_urdf(path, shown, data, resolver)
        first = None if as_written or not _may_use_xacro(data) else \
            first_xacro_use(robot.root, _may_substitute(data))
        if first is not None and path == "-":
            robot = _load_xacro(path, shown, data, xacro_args or {}, resolver, allow_env,
                                max_file_size)
        elif first is not None:
            robot, note = _load_disguised_xacro(robot, first, data, xacro_args or {},
                                                allow_env, max_file_size)
            robot.notes.insert(0, note)
    if robot.root.tag != "robot":
        note = _in_default_namespace(robot)
        if note is None:
            raise LoadError("root", f"root element is <{robot.root.tag}>, expected <robot>",
                            robot.locate(robot.root))
        robot.notes.append(note)
    return robot


def _in_default_namespace(robot: Robot) -> LoadNote | None:
    """A ``<robot xmlns="...">`` (the namespace of urdf.xsd, written to validate the file
    against it: JLSchol/omni_marco_gazebo's omni.urdf) read as urdfdom reads it, with a warning;
    None when the root is anything else. TinyXML2 knows no namespaces: urdfdom (check_urdf,
    robot_state_publisher, Gazebo, MoveIt) and xacro read each element by its name as written,
    so every element of that namespace written without a prefix is given its bare name (one
    written with a prefix, ``<urdf:link>``, is a name urdfdom does not read, and stays so)."""
    root = robot.root
    if not isinstance(root.tag, str) or root.prefix is not None or not root.tag.startswith("{"):
        return None
    name = etree.QName(root)
    if name.localname != "robot":
        return None
    for element in list(root.iter(f"{{{name.namespace}}}*")):
        if element.prefix is None:
            element.tag = etree.QName(element).localname
    return LoadNote("root-namespace", robot.locate(root), (
        f"<robot> is in the XML namespace '{name.namespace}' (xmlns=\"...\"): urdfdom "
        "(check_urdf, robot_state_publisher, Gazebo, MoveIt) and xacro read elements by their "
        "names as written and load the robot, but parsers that read namespaces find no <link> "
        "or <joint> in it (urdf_parser_py, yourdfpy, ElementTree's find('link')); remove the "
        "xmlns"), severity=Severity.WARNING)


def _folder_of(path) -> Path:
    """The folder holding ``path`` as named, links not followed: a robot file that is a link
    elsewhere in the repository resolves its includes, packages and companions from where the
    link is, as xacro does, and never from where a link leads."""
    return Path(os.path.abspath(path)).parent


def _refuse_link_out(path: str, shown: str) -> None:
    """A LoadError of kind 'link' when ``path`` is (or lies in a folder that is) a symbolic link
    leading outside the repository holding it; the file is not opened."""
    leads = link_out(path)
    if leads:
        raise LoadError("link", (  # where it leads is not said: that is outside
            f"is a symbolic link leading outside the repository ({display_path(leads[1])}); "
            "not followed"), Location(shown, None))


def _read(path: str, shown: str, limit: int) -> bytes:
    if path == "-":
        data = sys.stdin.buffer.read(limit + 1)
    else:
        try:
            data = read_regular(path, limit, as_="robot")
        except TooLarge as error:
            raise LoadError("too-large", error.strerror, Location(shown, None)) from None
        except OSError as error:
            raise LoadError("read", f"cannot read file: {error.strerror}",
                            Location(shown, None)) from None
    if len(data) > limit:
        raise LoadError("too-large", f"input is over the limit of {limit} bytes",
                        Location(shown, None))
    return data


def _load_disguised_xacro(plain: Robot, first, data, args, allow_env, limit):
    """A ``.urdf`` holding xacro: a xacro robot when every launch file and launch test that
    loads it runs xacro on it (:func:`~urdftool.description.runtime.builds`: what its
    consumers read, and a xacro error is theirs), with a note (a warning when one that names it
    could not be read: :func:`~urdftool.description.runtime.unread_naming`); else expanded when
    xacro can, read as plain URDF when not, with the loader's error note."""
    from urdftool.description.runtime import builds, unread_naming

    where = plain.locate(first)
    named = f"named {Path(plain.path).suffix or 'without .xacro'}"
    loads = builds(plain.path)
    through = list(dict.fromkeys(b.named for b in loads if b.xacro))
    as_is = list(dict.fromkeys(b.named for b in loads if not b.xacro and not b.replaced))
    filling = [b for b in loads if not b.xacro and b.replaced]
    if filling and not through and not as_is:  # a template its launch files fill
        return _filled(plain, first, data, args, allow_env, limit, filling, named)
    # what a launch file or test that could not be read does with it is unknown
    unread = unread_naming(plain.path) if through and not as_is else []
    if through and not as_is:
        robot = _load_xacro(plain.path, plain.display, data, args, plain.resolver, allow_env, limit)
        every = f"every launch file and launch test {'read ' if unread else ''}that loads it"
        tail = (f"; {_listed(unread)} may read it as it is: rename it .urdf.xacro" if unread
                else "; a tool given the file itself (check_urdf, Gazebo, MuJoCo) reads it "
                     "unexpanded: a name ending .xacro says which it is")
        return robot, LoadNote("xacro-in-urdf", where, (
            f"file is {named} but needs xacro ({_shown_use(first)} at this line); {every} "
            f"runs xacro on it ({_listed(through)}), so it is checked as xacro{tail}"),
            severity=Severity.WARNING if unread else Severity.INFO)
    read_by = f"; {_listed(as_is)} may read it as it is" if as_is else ""
    try:
        robot = _load_xacro(plain.path, plain.display, data, args, plain.resolver, allow_env,
                            limit)
    except LoadError as error:
        # (a plain str: a note is printed as it is; its cause carries the repeated parts)
        return plain, LoadNote("xacro-in-urdf", where, str(
            f"file is {named} but contains xacro ({_shown_use(first)}), which xacro cannot "
            "expand (" + error.message + f") and URDF parsers ignore{read_by}; remove it or "
            "rename the file .urdf.xacro"), cause=error)
    if _only_in_gazebo(first.getroottree().getroot()):  # what URDF parsers skip
        return robot, LoadNote("xacro-in-urdf", where, (
            f"file is {named} but needs xacro ({_shown_use(first)} at this line), only inside "
            f"<gazebo>, which URDF parsers skip{read_by}: if Gazebo is given the file itself, it "
            "reads it unexpanded; rename it .urdf.xacro"), severity=Severity.WARNING)
    return robot, LoadNote("xacro-in-urdf", where, (
        f"file is {named} but needs xacro ({_shown_use(first)} at this line); urdftool "
        f"expanded it, but URDF parsers will not{read_by}: rename it .urdf.xacro"))


# a ``$(...)`` or ``${...}`` as written in a file, whole
_SUBSTITUTED = re.compile(r"\$\([^()]*\)|\$\{[^{}]*\}")


def _filled(plain: Robot, first, data, args, allow_env, limit, filling, named: str) -> tuple:
    """(robot, note) for a ``.urdf`` holding ``$(...)``/``${...}`` that every launch file
    loading it reads as text and rewrites before loading it (``text.replace('$(x)', path)``,
    my-zzy/am_description): a template they fill. A note when each replaces every such text
    in the file by name; a warning when what they replace is not known without running them, or
    the file holds xacro elements: it may be filled. Checked as xacro expands it where it can,
    else as it is."""
    where = plain.locate(first)
    used = set(_SUBSTITUTED.findall(data.decode("utf-8", "replace")))
    root = first.getroottree().getroot()
    certain = not any(is_xacro_element(e) for e in root.iter(etree.Element)) and all(
        None not in b.replaced and all(any(text in old for old in b.replaced) for text in used)
        for b in filling)
    names = list(dict.fromkeys(b.named for b in filling))
    replaced = list(dict.fromkeys(old for b in filling for old in b.replaced if old))
    try:
        robot = _load_xacro(plain.path, plain.display, data, args, plain.resolver, allow_env,
                            limit)
    except LoadError:
        robot = plain
    if certain:
        return robot, LoadNote("xacro-in-urdf", where, (
            f"file is {named} and holds {_shown_use(first)} at this line, which "
            f"{_listed(names)} {'replaces' if len(names) == 1 else 'replace'} in its text "
            f"before loading it ({_listed([repr(t) for t in replaced])}): a template its launch "
            "files fill; a tool given the file itself (check_urdf, Gazebo) reads it unfilled"),
            severity=Severity.INFO)
    what = f" (replacing {_listed([repr(t) for t in replaced])} and more)" if replaced else ""
    return robot, LoadNote("xacro-in-urdf", where, (
        f"file is {named} but holds {_shown_use(first)} at this line; {_listed(names)} "
        f"{'rewrites' if len(names) == 1 else 'rewrite'} its text before loading it{what}, "
        "which may fill it: if not, URDF parsers read it unexpanded; rename it .urdf.xacro if "
        "it is xacro"), severity=Severity.WARNING)


def _only_in_gazebo(root) -> bool:
    """Whether every element that needs xacro is a ``<gazebo>`` extension or inside one
    (JAKA's ``<parameters>$(find ...)/ros2_controllers.yaml</parameters>``): URDF parsers skip
    them, so only Gazebo, given the file itself, reads the unexpanded text."""
    uses = [e for e in root.iter(etree.Element) if _needs_xacro(e)]
    return bool(uses) and all(
        any(a.tag == "gazebo" for a in e.iterancestors(etree.Element)) or e.tag == "gazebo"
        for e in uses)


def _listed(launches: list[str], limit: int = 3) -> str:
    return ", ".join(launches[:limit]) + (f" and {len(launches) - limit} more" if len(launches) > limit else "")


def _shown_use(element) -> str:
    """What in ``element`` needs xacro, as a reader finds it: a xacro tag, or the attribute or
    text holding ``${...}``/``$(...)`` (not the bare tag: ``<color>`` alone says nothing of the
    ``rgba="${255/255} ..."`` in it)."""
    tag = _shown_tag(element)
    if is_xacro_element(element):
        return f"<{tag}>"
    for name, value in element.attrib.items():
        if _substitutes(value):
            return f"{name}=\"{_clipped(value)}\" in <{tag}>"
    return f"\"{_clipped((element.text or '').strip())}\" in <{tag}>"


def _clipped(text: str, limit: int = 40) -> str:
    return text if len(text) <= limit else text[:limit - 3] + "..."


def _shown_tag(element) -> str:
    if not element.tag.startswith("{"):  # lxml in recover mode keeps an undeclared prefix
        return element.tag
    local = etree.QName(element).localname
    return f"{element.prefix}:{local}" if element.prefix else local



def _load_urdf(path: str, shown: str, data: bytes, resolver: PackageResolver) -> Robot:
    notes = []
    try:
        root, lines = parse(data)
    except XmlProblem as problem:
        read, notes = _as_urdfdom_reads(data, shown)
        if not notes:
            raise _problem_error(problem, shown) from None
        try:
            root, lines = parse(read)
        except XmlProblem:
            raise _problem_error(problem, shown) from None
    robot = Robot(path=path, display=shown, root=root, locations=_StartTags(shown, lines),
                  resolver=resolver, files=[shown], sources={shown: data})
    robot.notes.extend(notes)
    return robot


def _as_urdfdom_reads(data: bytes, shown: str) -> tuple[bytes, list[LoadNote]]:
    """``data`` as urdfdom's TinyXML2 reads what parsers that follow the XML standard refuse
    (white space before the XML declaration, ``--`` inside a comment), with a warning for each
    such thing, which names who refuses it; no note when there is none."""
    notes = []
    late = _late_declaration(data)
    if late is not None:
        data = late[0]
        notes.append(LoadNote("late-declaration", Location(shown, late[1], column=1), (
            "text before the XML declaration (white space): urdfdom reads the file "
            "(check_urdf, robot_state_publisher, Gazebo, PyBullet), but parsers that follow "
            "the XML standard refuse it (xacro, urdf_parser_py, yourdfpy: 'XML or text "
            "declaration not at start of entity'); remove what comes before '<?xml'"),
            severity=Severity.WARNING))
    comments = tinyxml2_comments(data)
    if comments is not None:
        data = comments[0]
        notes.append(LoadNote("double-hyphen", Location(shown, comments[1]), (
            "'--' inside a comment: urdfdom reads the file (check_urdf, robot_state_publisher, "
            "Gazebo, PyBullet: TinyXML2 ends a comment at the first '-->'), but parsers that "
            "follow the XML standard refuse it (xacro, urdf_parser_py, yourdfpy: 'not "
            "well-formed (invalid token)'); write the comment without '--'"),
            severity=Severity.WARNING))
    return data, notes


_LATE_DECLARATION = re.compile(rb"\A[ \t\r\n]+(<\?xml\s[^<>]*?\?>)")
_DECLARED_ENCODING = re.compile(rb"encoding\s*=\s*[\"']([^\"']*)[\"']")


def _late_declaration(data: bytes) -> tuple[bytes, int] | None:
    """(``data`` with its XML declaration blanked, the declaration's line) when only white
    space comes before the declaration, as urdfdom's TinyXML2 reads it (it skips the white
    space and takes the declaration as a node); None otherwise, or when the declaration names
    an encoding other than UTF-8 (blanking it would change how the bytes read)."""
    found = _LATE_DECLARATION.match(data)
    if found is None:
        return None
    declaration = found.group(1)
    encoding = _DECLARED_ENCODING.search(declaration)
    if encoding and encoding.group(1).lower().replace(b"-", b"") not in (b"utf8", b"ascii",
                                                                           b"usascii"):
        return None
    blanked = re.sub(rb"[^\r\n]", b" ", declaration)  # lines and columns stay where they were
    return data[:found.start(1)] + blanked + data[found.end(1):], line_at(data, found.start(1))


class _StartTags(Mapping):
    """Element -> the :class:`Location` of its start tag in one file, made when asked: a
    10,000-link URDF has 190,000 elements, and findings name a few of them."""

    def __init__(self, file: str, positions: dict):
        self._file, self._positions = file, positions  # element -> (line, column)

    def __getitem__(self, element) -> Location:
        line, column = self._positions[element]
        return Location(self._file, line, column=column)

    def get(self, element, default=None):
        found = self._positions.get(element)
        return default if found is None else Location(self._file, found[0], column=found[1])

    def get_all(self, elements: list) -> list:
        """:meth:`get` of each of ``elements`` (None for one not found): in one call where
        their places were found by scanning the file (the findings of one rule, located
        together), else one by one."""
        bulk = getattr(self._positions, "positions", None)
        found = bulk(elements) if bulk is not None else [self._positions.get(element)
                                                         for element in elements]
        file = self._file
        return [None if place is None else Location(file, place[0], column=place[1])
                for place in found]

    def start_offset(self, element, data: bytes) -> int | None:
        """The byte offset of ``element``'s start tag in ``data``, when its place was found by
        scanning that very buffer (a plain document, :func:`~urdftool.description.xml.parse`),
        else None."""
        offset = getattr(self._positions, "offset", None)
        return offset(element, data) if offset is not None else None

    def shapes(self, elements: list) -> list | None:
        """:meth:`~urdftool.description.xml._StartOffsets.shapes` of these siblings, where
        their places were found by scanning the file (else None)."""
        shapes = getattr(self._positions, "shapes", None)
        return shapes(elements) if shapes is not None else None

    def __iter__(self):
        return iter(self._positions)

    def __len__(self) -> int:
        return len(self._positions)


def _load_xacro(path, shown, data, args, resolver, allow_env, limit) -> Robot:
    from urdftool.description.xacro import XacroFailure, expand

    try:
        refuse_empty_or_binary(data)
        source_path = Path(path) if path != "-" else Path.cwd() / "stdin.xacro"
        sources = {display_path(source_path): data}

        def read_file(name, as_: str = "include") -> bytes:  # kept: suppressions are read
            sources[display_path(name)] = read_regular(name, limit, as_)  # from what was loaded
            return sources[display_path(name)]

        expansion = expand(source_path, data, args=args, resolver=resolver, allow_env=allow_env,
                           read_file=read_file, roots=_allowed_roots(source_path, args))
    except XmlProblem as problem:
        raise _problem_error(problem, shown) from None
    except XacroFailure as failure:
        location = failure.location
        if path == "-" and location.file.endswith("stdin.xacro"):
            location = Location(shown, location.line, location.via)
        raise LoadError(failure.kind, failure.message, location, failure.subject,
                        failure.certain, failure.close, failure.whatever_args,
                        failure.declared, failure.undefined, failure.repeated) from None
    robot = Robot(path=path, display=shown, root=expansion.root, locations=expansion.locations,
                  resolver=resolver, files=[display_path(f) for f in expansion.files],
                  from_xacro=True, sources=sources)
    robot.notes.extend(LoadNote("xacro-warning", where, message)
                       for where, message in expansion.warnings)
    robot.notes.extend(LoadNote("outside-file", where, message)
                       for where, message in expansion.outside)
    return robot


def _allowed_roots(source: Path, args: dict[str, str]) -> list[Path]:
    """Where included and YAML files may be: the repository (see
    :func:`~urdftool.description.packages.containment_root`) and the files and folders named by xacro
    arguments given by whoever runs the check, not by a settings file (a
    :class:`~urdftool.description.inputs.SettingValue`: the repository's own data). Folders of
    packages ``$(find)`` resolves are added later."""
    roots = [containment_root(_folder_of(source))]
    for value in args.values():
        if isinstance(value, SettingValue):
            continue
        try:
            if value and kind_of(value):
                roots.append(Path(value))
        except (OSError, ValueError):
            continue
    return roots


def _problem_error(problem: XmlProblem, shown: str) -> LoadError:
    return LoadError(problem.kind, problem.message, Location(shown, problem.line))
