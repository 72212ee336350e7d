"""Which files ``urdftool check DIR`` checks: top-level robots, not the macro libraries they
include."""

from __future__ import annotations

import os
import re
import stat
from pathlib import Path

from .diagnostics import display_path
from .loader.packages import PackageResolver, repository_root

SUFFIXES = (".urdf", ".xacro")
_CLASSIFY_BYTES = 16 * 1024 * 1024  # read no more of a file to decide whether it is a robot
_SKIP_DIRS = {".git", ".venv", "venv", "node_modules", "__pycache__", "build", "install", "log"}
_INCLUDE = re.compile(rb"<xacro:include\s[^>]*?filename\s*=\s*[\"']([^\"']+)[\"']", re.S)
_FIND = re.compile(r"\$\(find\s+([^)\s]+)\)")
_DEFINITIONS = {"property", "arg", "include", "macro", "material"}


def robot_files(folder: Path) -> list[Path]:
    """Every .urdf and .xacro file below ``folder``, sorted, skipping tool folders."""
    found = []
    for current, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if d not in _SKIP_DIRS and not d.startswith("."))
        found.extend(Path(current) / f for f in files if f.endswith(SUFFIXES))
    return sorted(found)


def split_top_level(files: list[Path], resolver_for) -> tuple[list[Path], dict[Path, str]]:
    """(top-level files, {skipped file: reason}) for a set of files found in a folder."""
    included: dict[Path, Path] = {}
    contents = {}
    for path in files:
        contents[path] = _head(path)
    for path, data in contents.items():
        for target in _included_files(path, data, resolver_for(path)):
            included.setdefault(target, path)
    top, skipped = [], {}
    for path in files:
        key = resolved_path(path)
        if key in included:
            skipped[path] = f"included by {included[key]}"
        elif path.name.endswith(".xacro") and not _defines_robot(contents[path]):
            skipped[path] = "defines only macros or properties (a macro library)"
        else:
            top.append(path)
    return top, skipped


def resolved_path(path: Path) -> Path:
    try:
        return path.resolve()
    except (OSError, ValueError, RuntimeError):  # NUL in a name, a symlink loop
        return path.absolute()


def _head(path: Path) -> bytes:
    """The start of a regular file (enough to classify it); nothing for FIFOs and devices."""
    try:
        if not stat.S_ISREG(path.stat().st_mode):
            return b""
        with open(path, "rb") as handle:
            return handle.read(_CLASSIFY_BYTES)
    except (OSError, ValueError):
        return b""


def _defines_robot(data: bytes) -> bool:
    """Whether a xacro file produces a robot itself: anything under <robot> besides xacro
    definitions (properties, args, includes, macros). Unparsable files count, so that the parse
    error is reported."""
    from lxml import etree

    try:
        root = etree.fromstring(data, etree.XMLParser(resolve_entities=False, no_network=True,
                                                      load_dtd=False, recover=True))
    except etree.LxmlError:
        return True
    if root is None or etree.QName(root).localname != "robot":
        return True
    for child in root.iterchildren(etree.Element):
        # Pre-2019 xacro wrote the same tags without the xacro: prefix.
        if etree.QName(child).localname not in _DEFINITIONS:
            return True
    return False


def _included_files(path: Path, data: bytes, resolver: PackageResolver):
    for match in _INCLUDE.finditer(data):
        spec = match.group(1).decode("utf-8", "replace")
        find = _FIND.search(spec)
        if find:
            try:
                spec = spec.replace(find.group(0), str(resolver.find(find.group(1))))
            except Exception:
                continue
        if "$" in spec or "\0" in spec:
            continue
        yield resolved_path(path.parent / spec)


_NAMED_ROBOT = re.compile(rb"<robot\b[^>]*?\sname\s*=", re.S)


def project_root(path: Path) -> Path:
    """The repository holding ``path`` (nearest folder with ``.git``), or its own folder."""
    folder = resolved_path(path).parent
    return repository_root(folder) or folder


def explicit_targets(path: Path, includers: dict, root: Path) -> tuple[list[Path], str | None]:
    """What to check for a file named on the command line (as pre-commit does), and why.

    includers: :func:`includers_below` ``root``
    A robot of its own (a named ``<robot>`` with links, joints or macro calls) is checked as it
    is. A file that is not (a macro library, a fragment) but that robots below ``root`` include,
    directly or through other includes, is replaced by those top-level robots: a change to
    ``leg.xacro`` checks the robot built from it. One nobody includes is checked as it is when it
    has content, and skipped when it only defines macros or properties.
    """
    data = _head(path)
    if _NAMED_ROBOT.search(data) and _defines_robot(data):
        return [path], None
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
    if tops:
        tops = sorted(tops)
        return tops, f"included by {', '.join(display_path(p) for p in tops)}: checking that instead"
    if not _defines_robot(data) and path.name.endswith(".xacro"):
        return [], "defines only macros or properties, and no robot below " \
                   f"{root} includes it: nothing to check"
    return [path], None


def includers_below(root: Path, resolver_for) -> dict[Path, list[Path]]:
    """Included file (resolved) -> the files below ``root`` that include it."""
    includers: dict[Path, list[Path]] = {}
    for path in robot_files(root):
        for target in _included_files(path, _head(path), resolver_for(path)):
            includers.setdefault(target, []).append(path)
    return includers
