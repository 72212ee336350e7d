"""Load a robot description (URDF, xacro, or stdin) into a :class:`Robot` with source locations.

Every failure is a :class:`~urdftool.errors.LoadError` whose findings carry a rule code and
the file and line where the problem is, so broken files go through the same reporters.
"""

from __future__ import annotations

import os
import stat
import sys
from pathlib import Path

from lxml import etree

from ..diagnostics import Finding, Location, Severity, display_path
from ..errors import LoadError
from .model import Robot
from .packages import PackageResolver
from .xmlparse import XmlProblem, parse, refuse_empty_or_binary

DEFAULT_MAX_FILE_SIZE = 16 * 1024 * 1024
XACRO_SUFFIXES = (".xacro",)

__all__ = ["Robot", "load", "first_xacro_use", "PackageResolver"]


def first_xacro_use(root):
    """The first element that needs xacro (a xacro: tag, or a ``${}``/``$()`` in an attribute or
    text), or None. Comments do not count: generated URDFs often keep commented-out xacro."""
    for element in root.iter(etree.Element):
        if _is_xacro_tag(element.tag):
            return element
        if any(_substitutes(value) for value in element.attrib.values()) or \
                _substitutes(element.text):
            return element
    return None


def _substitutes(text: str | None) -> bool:
    return bool(text) and ("${" in text or "$(" in text)


def load(path: str | os.PathLike, *, xacro_args: dict[str, str] | None = None,
         packages: dict[str, Path] | None = None, allow_env: bool = True,
         max_file_size: int = DEFAULT_MAX_FILE_SIZE, data: bytes | None = None) -> Robot:
    """Load a robot from ``path`` (``-`` reads stdin); raises LoadError with located findings."""
    path = os.fspath(path)
    shown = display_path(path) if path != "-" else "<stdin>"
    start = Path.cwd() if path == "-" else _folder_of(path)
    resolver = PackageResolver(packages, start=start)
    if data is None:
        data = _read(path, shown, max_file_size)
    extra_findings = []
    if path.endswith(XACRO_SUFFIXES):
        robot = _load_xacro(path, shown, data, xacro_args or {}, resolver, allow_env,
                            max_file_size)
    else:
        robot = _load_urdf(path, shown, data, resolver)
        first = first_xacro_use(robot.root)
        if first is not None and path == "-":
            robot = _load_xacro(path, shown, data, xacro_args or {}, resolver, allow_env,
                                max_file_size)
        elif first is not None:
            robot, finding = _load_disguised_xacro(robot, first, data, xacro_args or {},
                                                   allow_env, max_file_size)
            extra_findings.append(finding)
    robot.options["load_findings"] = extra_findings
    if robot.root.tag != "robot":
        raise LoadError([_finding("U004", robot.locate(robot.root),
                                  f"root element is <{robot.root.tag}>, expected <robot>")])
    return robot


def _folder_of(path) -> Path:
    """The real folder holding ``path``; its plain absolute folder when it cannot be resolved
    (a symbolic link loop: reading the file then reports it)."""
    try:
        return Path(path).resolve().parent
    except (OSError, RuntimeError, ValueError):
        return Path(os.path.abspath(path)).parent


def _read(path: str, shown: str, limit: int) -> bytes:
    if path == "-":
        data = sys.stdin.buffer.read(limit + 1)
    else:
        try:
            data = _read_regular(path, limit)
        except _TooLarge as error:
            raise LoadError([_finding("U008", Location(shown, None),
                                      f"{error.strerror} (raise it with --max-file-size)")]) from None
        except OSError as error:
            raise LoadError([_finding("U001", Location(shown, None),
                                      f"cannot read file: {error.strerror}")]) from None
    if len(data) > limit:
        raise LoadError([_finding("U008", Location(shown, None),
                                  f"input is over the limit of {limit} bytes "
                                  "(raise it with --max-file-size)")])
    return data


class _TooLarge(OSError):
    """A file over the size limit."""


def _read_regular(name, limit: int) -> bytes:
    """A regular file's bytes (at most ``limit + 1``); OSError for anything else, _TooLarge when
    its size is over ``limit``."""
    info = os.stat(name)
    if not stat.S_ISREG(info.st_mode):
        raise OSError(21, "not a regular file", name)
    if info.st_size > limit:
        raise _TooLarge(27, f"file is {info.st_size} bytes, over the limit of {limit}", name)
    with open(name, "rb") as handle:
        return handle.read(limit + 1)


def _load_disguised_xacro(plain: Robot, first, data, args, allow_env, limit):
    """A ``.urdf`` holding xacro: expanded when xacro can, read as plain URDF when not."""
    where = plain.locate(first)
    named = f"named {Path(plain.path).suffix or 'without .xacro'}"
    try:
        robot = _load_xacro(plain.path, plain.display, data, args, plain.resolver, allow_env,
                            limit)
    except LoadError as error:
        reason = error.findings[0].message
        return plain, _finding("U007", where, (
            f"file is {named} but contains xacro (<{_shown_tag(first)}>), which xacro cannot "
            f"expand ({reason}) and URDF parsers ignore; remove it or rename the file .urdf.xacro"))
    return robot, _finding("U007", where, (
        f"file is {named} but needs xacro (<{_shown_tag(first)}> at this line); urdftool "
        "expanded it, but URDF parsers will not: rename it .urdf.xacro"))


def _shown_tag(element) -> str:
    local = etree.QName(element).localname
    return f"{element.prefix}:{local}" if element.prefix else local


def _is_xacro_tag(tag) -> bool:
    return isinstance(tag, str) and (tag.startswith("xacro:") or "ros.org/wiki/xacro}" in tag)


def _load_urdf(path: str, shown: str, data: bytes, resolver: PackageResolver) -> Robot:
    try:
        root, lines = parse(data)
    except XmlProblem as problem:
        raise LoadError([_problem_finding(problem, shown)]) from None
    locations = {element: Location(shown, line) for element, line in lines.items()}
    return Robot(path=path, display=shown, root=root, locations=locations, resolver=resolver,
                 files=[shown])


def _load_xacro(path, shown, data, args, resolver, allow_env, limit) -> Robot:
    from .xacro_expand import XacroFailure, expand

    try:
        refuse_empty_or_binary(data)
        source_path = Path(path) if path != "-" else Path.cwd() / "stdin.xacro"
        expansion = expand(source_path, data, args=args, resolver=resolver, allow_env=allow_env,
                           read_file=lambda name: _read_regular(name, limit),
                           roots=_allowed_roots(source_path, args))
    except XmlProblem as problem:
        raise LoadError([_problem_finding(problem, shown)]) from None
    except XacroFailure as failure:
        code = {"package": "U006", "syntax": "U001", "entity": "U009", "sandbox": "U016",
                "outside": "U014"}.get(failure.kind, "U005")
        location = failure.location
        if path == "-" and location.file.endswith("stdin.xacro"):
            location = Location(shown, location.line, location.via)
        raise LoadError([_finding(code, location, failure.message)]) from None
    robot = Robot(path=path, display=shown, root=expansion.root, locations=expansion.locations,
                  resolver=resolver, files=[display_path(f) for f in expansion.files],
                  from_xacro=True)
    robot.options["xacro_warnings"] = expansion.warnings
    robot.options["outside_files"] = expansion.outside
    return robot


def _allowed_roots(source: Path, args: dict[str, str]) -> list[Path]:
    """Where included and YAML files may be: the repository (nearest ``.git`` above the input;
    without one, the nearest package.xml folder, else the input's folder) and the files and
    folders named by xacro arguments. Folders of packages ``$(find)`` resolves are added later."""
    from .packages import repository_root

    folder = _folder_of(source)
    root = repository_root(folder) or next(
        (f for f in [folder, *folder.parents] if (f / "package.xml").is_file()), folder)
    roots = [root]
    for value in args.values():
        try:
            if value and os.path.exists(value):
                roots.append(Path(value))
        except (OSError, ValueError):
            continue
    return roots


_PROBLEM_CODES = {"empty": "U002", "binary": "U003", "syntax": "U001", "entity": "U009"}


def _problem_finding(problem: XmlProblem, shown: str) -> Finding:
    return _finding(_PROBLEM_CODES[problem.kind], Location(shown, problem.line), problem.message)


def _finding(code: str, location: Location, message: str) -> Finding:
    from ..rules import registered

    return registered(code).finding(message, location)
