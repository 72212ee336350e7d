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
from dataclasses import dataclass
from pathlib import Path

from urdftool.diagnostics import display_path
from urdftool.description.files import DEFAULT_MAX_FILE_SIZE, inside, read_regular
from urdftool.description.packages import SKIP_DIRS, PackageResolver, containment_root

SUFFIXES = (".urdf", ".xacro")
# [^<>]: a tag ends before the next "<", so no character is scanned from two starts (linear time
# on files made of "<xacro:include " repeated).
_INCLUDE = re.compile(rb"<xacro:include\s[^<>]*?filename\s*=\s*[\"']([^\"'<>]+)[\"']", re.S)
_CHUNK = 64 * 1024
_FIND = re.compile(r"\$\(find\s+([^)\s]+)\)")
_DEFINITIONS = {"property", "arg", "include", "macro", "material"}


def robot_files(folder: Path) -> list[Path]:
    """Every .urdf and .xacro file below ``folder``, sorted, skipping tool folders. Symbolic
    links (to files or folders) leading outside the repository are listed too, not followed, so
    that checking them reports it; a ``folder`` that is itself such a link is listed alone."""
    if not _stays_inside(folder):
        return [folder]
    found = []
    for current, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS and not d.startswith("."))
        found.extend(Path(current) / d for d in dirs
                     if os.path.islink(os.path.join(current, d))
                     and not _stays_inside(Path(current) / d))
        found.extend(Path(current) / f for f in files if f.endswith(SUFFIXES))
    return sorted(found)


@dataclass
class _Summary:
    """What classifying one file needs: the files it includes, and whether it is a robot."""

    includes: list[Path]
    defines_robot: bool
    named_robot: bool


def split_top_level(files: list[Path], resolver_for, max_file_size: int = DEFAULT_MAX_FILE_SIZE
                    ) -> tuple[list[Path], dict[Path, str]]:
    """(top-level files, {skipped file: reason}) for a set of files found in a folder.

    max_file_size: files larger [bytes] are not read; they stay targets (U008 when checked)
    """
    included: dict[Path, Path] = {}
    summaries = {path: _summary(path, resolver_for, max_file_size) for path in files}
    for path, summary in summaries.items():
        for target in summary.includes:
            included.setdefault(target, path)
    top, skipped = [], {}
    for path in files:
        key = resolved_path(path)
        if key in included:
            skipped[path] = f"included by {included[key]}"
        elif path.name.endswith(".xacro") and not summaries[path].defines_robot:
            skipped[path] = "defines only macros or properties (a macro library)"
        else:
            top.append(path)
    return top, skipped


def resolved_path(path: Path) -> Path:
    try:
        return path.resolve()
    except (OSError, ValueError, RuntimeError):  # NUL in a name, a symlink loop
        return path.absolute()


def _stays_inside(path: Path) -> bool:
    """Whether ``path``, links followed, stays in the repository holding it (as named)."""
    return inside(path, containment_root(Path(os.path.abspath(path)).parent))


def _summary(path: Path, resolver_for, limit: int) -> _Summary:
    """Read ``path`` (when :func:`_head` may) and keep only what classification needs; the
    includes only given ``resolver_for``."""
    data = _head(path, limit)
    if data is None or b"\0" in data:  # unread, or binary: a target, so checking says why
        return _Summary([], True, True)
    includes = list(_included_files(path, data, resolver_for(path))) if resolver_for else []
    return _Summary(includes, _defines_robot(data), bool(_NAMED_ROBOT.search(data)))


def _head(path: Path, limit: int = DEFAULT_MAX_FILE_SIZE) -> bytes | None:
    """A file's bytes; None, without opening it, for a link leading outside the repository, a
    file over ``limit`` [bytes] or anything else :func:`~urdftool.description.files.read_regular` refuses."""
    if not _stays_inside(path):
        return None
    try:
        return read_regular(path, limit)
    except (OSError, ValueError):
        return None


def _defines_robot(data: bytes) -> bool:
    """Whether a xacro file produces a robot itself: anything under <robot> besides xacro
    definitions (properties, args, includes, macros). Unparsable files count, so that the parse
    error is reported. Parsed as a stream of start and end tags, no tree kept, stopping at the
    first answer: memory stays small whatever the file holds."""
    from lxml import etree

    target = _TopLevelTags()
    parser = etree.XMLParser(target=target, resolve_entities=False, no_network=True,
                             load_dtd=False, recover=True)
    try:
        for offset in range(0, len(data) or 1, _CHUNK):
            parser.feed(data[offset:offset + _CHUNK])
        parser.close()
    except (_Answered, etree.LxmlError):
        return True
    return not target.seen_robot


class _Answered(Exception):
    """The file is a robot (or not a xacro library at all): stop reading."""


class _TopLevelTags:
    """lxml parser target: raises _Answered at a root other than <robot> or at a child of
    <robot> that is not a definition."""

    def __init__(self):
        self.depth, self.seen_robot = 0, False

    def start(self, tag, attributes):
        from lxml import etree

        self.depth += 1
        if self.depth > 2:
            return
        name = etree.QName(tag).localname
        if self.depth == 1 and name != "robot":
            raise _Answered
        self.seen_robot = True
        # Pre-2019 xacro wrote the same tags without the xacro: prefix.
        if self.depth == 2 and name not in _DEFINITIONS:
            raise _Answered

    def end(self, tag):
        self.depth -= 1

    def close(self):
        return None


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


_NAMED_ROBOT = re.compile(rb"<robot\b[^<>]*?\sname\s*=", re.S)


def project_root(path: Path) -> Path:
    """The folder whose robots may include ``path``: its
    :func:`~urdftool.description.packages.containment_root` (repository, else package, else
    its own folder; as named, a link is not followed)."""
    return containment_root(Path(os.path.abspath(path)).parent)


def explicit_targets(path: Path, includers: dict, root: Path,
                     max_file_size: int = DEFAULT_MAX_FILE_SIZE) -> tuple[list[Path], str | None]:
    """What to check for a file named on the command line (as pre-commit does), and why.

    includers: :func:`includers_below` ``root``, or a function returning it, called only when
        the file is not a robot of its own (walking a repository costs more than checking a robot)
    A robot of its own (a named ``<robot>`` with links, joints or macro calls) is checked as it
    is, and so is a file that is not read (a link leading outside the repository, a file over
    the size limit, a FIFO): checking it reports why. A file that is not (a macro library, a
    fragment) but that robots below ``root`` include, directly or through other includes, is
    replaced by those top-level robots: a change to ``leg.xacro`` checks the robot built from
    it. One nobody includes is checked as it is when it
    has content, and skipped when it only defines macros or properties.
    """
    summary = _summary(path, None, max_file_size)
    if summary.named_robot and summary.defines_robot:
        return [path], None
    includers = includers() if callable(includers) else includers
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
    if not summary.defines_robot and path.name.endswith(".xacro"):
        return [], "defines only macros or properties, and no robot below " \
                   f"{root} includes it: nothing to check"
    return [path], None


def includers_below(root: Path, resolver_for, max_file_size: int = DEFAULT_MAX_FILE_SIZE
                    ) -> dict[Path, list[Path]]:
    """Included file (resolved) -> the files below ``root`` that include it."""
    includers: dict[Path, list[Path]] = {}
    for path in robot_files(root):
        for target in _summary(path, resolver_for, max_file_size).includes:
            includers.setdefault(target, []).append(path)
    return includers


@dataclass
class Targets:
    """What checking some paths means.

    files: the files to check, in a stable order, each once
    skipped: files found in folders and not checked -> why (included by a robot, a macro library)
    notes: "PATH: what happened" for files named that are checked through others or not at all
    """

    files: list[str]
    skipped: dict[str, str]
    notes: list[str]


def expand(paths: list[str], request) -> Targets:
    """The files ``urdftool check PATH...`` checks: folders walked for top-level robots, a macro
    library named replaced by the robots that include it. Packages and the size limit come
    from the settings above each path (:func:`~urdftool.lint.settings.for_file`) under
    ``request``. Raises TargetError for a path that does not exist or a folder without robot
    files."""
    from urdftool.errors import TargetError
    from urdftool.lint.settings import for_file

    def resolver_for(path: Path) -> PackageResolver:
        return PackageResolver(for_file(str(path), request).options.packages, start=path.parent)

    includers = {}  # (project root, size limit) -> its include graph, built once
    files, skipped, notes = [], {}, []
    for path in map(os.fspath, paths):
        if path != "-" and not os.path.lexists(path):
            raise TargetError(f"path '{path}' does not exist")
        if path == "-" or not Path(path).is_file() and not Path(path).is_dir():
            files.append(path)
            continue
        limit = for_file(path, request).options.max_file_size
        if Path(path).is_file():
            root = project_root(Path(path))

            def graph(root=root, limit=limit):
                if (root, limit) not in includers:
                    includers[root, limit] = includers_below(root, resolver_for, limit)
                return includers[root, limit]

            targets, reason = explicit_targets(Path(path), graph, root, limit)
            files.extend(display_path(p) if p != Path(path) else path for p in targets)
            if reason:
                notes.append(f"{path}: {reason}")
            continue
        found = robot_files(Path(path))
        top, skipped_here = split_top_level(found, resolver_for, limit)
        files.extend(str(p) for p in top)
        skipped.update({str(p): reason for p, reason in skipped_here.items()})
        if not found:
            raise TargetError(f"no .urdf or .xacro files found in '{path}'")
    unique = {}  # the same file named twice, or a robot and a macro it includes: check it once
    for file in files:
        unique.setdefault(file if file == "-" else resolved_path(Path(file)), file)
    return Targets(list(unique.values()), skipped, notes)
