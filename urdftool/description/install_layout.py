"""Where a package's files are after its build: ``share/NAME`` read from the build description.

``$(find NAME)`` and ``package://NAME/...`` name the *installed* ``share/NAME`` folder (or, in a
ROS 1 devel space, the source folder). Many packages install files from source folders laid out
otherwise: CMake's ``install(DIRECTORY description/urdf DESTINATION share/${PROJECT_NAME})``,
ament_python's ``data_files=[('share/' + package_name + '/urdf', glob('urdf/*'))]``, a Python
package of the package's own name kept under ``src/`` (Pinocchio's package directories naming
site-packages find ``NAME/...`` there). :func:`layout` reads them without running anything:

- ``CMakeLists.txt`` (and the folders its ``add_subdirectory`` names): ``install(DIRECTORY``,
  ``FILES`` and ``PROGRAMS ... DESTINATION ...)`` with ``${PROJECT_NAME}``, ``project()``,
  ``set()`` variables set once, ``foreach`` over literal items, ``CATKIN_PACKAGE_SHARE_DESTINATION``,
  and ``ament_auto_package(INSTALL_TO_SHARE ...)``; ``dir/`` installs the folder's contents,
  ``dir`` the folder itself (``DESTINATION share`` installs a folder named NAME as share/NAME);
  a source in the build folder (``${CMAKE_CURRENT_BINARY_DIR}``) is what ``file(COPY ...
  DESTINATION ${CMAKE_CURRENT_BINARY_DIR}/...)`` put there, and ``file(GLOB VAR [RELATIVE d]
  d/*)`` lists one folder of the repository (both leave a doubt: the build may write or find
  more there);
- ``setup.py`` by ``ast`` only (never imported): ``setup(data_files=..., package_dir=...)`` of
  literals, module-level string constants, ``os.path.join``, ``+``, f-strings, ``glob(...)``
  (files land flat in their destination), and a list variable built by ``=``, ``+=``,
  ``append``/``extend`` at module level;
- ``setup.cfg``: ``[options.data_files]`` and ``[options] package_dir``.

A package.xml with none of these beside it is built by nothing that reads it: another build
(the repository's own CMake, a script) makes its share folder, and nothing is certain; the
nearest CMakeLists.txt above it is read for what it installs as share/NAME (icub-models: its
placeholder iCub_manual/package.xml, share/iCub made of iCub/, iCub_manual/ and
iCub_creo2urdf/), which is then found there.
What cannot be read with certainty (a variable set in a loop, a generator expression, a
``data_files`` built by walking folders) is kept as a reason in :attr:`Layout.unread`: a file
then missing from the source tree is not certainly missing after the build. Everything read is
bounded; a source or destination leading outside the repository is refused (not looked at), and
the resolver follows no link out (:meth:`Layout.sources` gives paths; the caller checks them).
"""

from __future__ import annotations

import ast
from ast import walk as ast_nodes  # (in memory: ast.walk reads no file)
import fnmatch
import os
import posixpath
import re
from pathlib import Path

from urdftool.diagnostics import lines_between
from urdftool.description.files import kind_of, listing, read_regular
from urdftool.description.run_memo import per_run
from urdftool.records import Frozen

MAX_BUILD_FILE = 512 * 1024  # [bytes] of a CMakeLists.txt, setup.py or setup.cfg read
MAX_COMMANDS = 20_000  # CMake commands evaluated per package
MAX_SUBDIRECTORIES = 32  # add_subdirectory folders followed per package
MAX_RULES = 2_000
_MAGIC = re.compile(r"[*?[]")


class InstallRule(Frozen):
    """One thing the build puts into ``share/NAME``.

    destination: the folder below ``share/NAME`` ('' for the share folder itself), POSIX;
    source: relative to the package folder, POSIX (may climb out of it, never out of the
    repository); kind: 'tree' (the source folder's contents land in ``destination``), 'file'
    (the source file lands as ``destination/as_name``), 'glob' (each file matching the source
    pattern lands in ``destination`` by its name); origin: where it was read, for people."""

    destination: str
    source: str
    kind: str
    origin: str
    as_name: str

    __slots__ = ("destination", "source", "kind", "origin", "as_name")

    def __init__(self, destination: str, source: str, kind: str, origin: str,
                 as_name: str = "") -> None:
        set_field = object.__setattr__
        set_field(self, "destination", destination)
        set_field(self, "source", source)
        set_field(self, "kind", kind)
        set_field(self, "origin", origin)
        set_field(self, "as_name", as_name)


class Layout(Frozen):
    """What a package's build installs into ``share/NAME``. ``build``: the build files read
    ('' when the package has none: its source folder is its only layout); ``unread``: why part
    of it could not be read (then a file missing from the source tree may exist after the
    build)."""

    rules: tuple[InstallRule, ...]
    unread: tuple[tuple[str | None, str], ...]  # (the destination it concerns or None, why)
    build: str

    __slots__ = ("rules", "unread", "build")

    def __init__(self, rules: tuple[InstallRule, ...] = (),
                 unread: tuple[tuple[str | None, str], ...] = (), build: str = "") -> None:
        set_field = object.__setattr__
        set_field(self, "rules", rules)
        set_field(self, "unread", unread)
        set_field(self, "build", build)

    def sources(self, tail: str) -> list[tuple[str, InstallRule]]:
        """The source paths (relative to the package folder) that ``share/NAME/tail`` may come
        from, the last rule first (a later install overwrites an earlier one)."""
        tail = posixpath.normpath(tail) if tail else ""
        if tail in (".", ""):
            tail = ""
        if tail.startswith("../") or tail == ".." or tail.startswith("/"):
            return []
        found = []
        for rule in reversed(self.rules):
            rest = _below(tail, rule.destination)
            if rest is None:
                continue
            if rule.kind == "tree":
                found.append((_join(rule.source, rest), rule))
            elif rule.kind == "file" and rest == rule.as_name:
                found.append((rule.source, rule))
            elif rule.kind == "glob" and rest and "/" not in rest:
                folder, pattern = posixpath.split(rule.source)
                if fnmatch.fnmatchcase(rest, pattern) and not rest.startswith("."):
                    found.append((_join(folder, rest), rule))
        return found

    def doubt(self, tail: str) -> str | None:
        """Why ``share/NAME/tail``, missing from the source tree, may still be installed (an
        install rule not read whose destination is unknown or holds ``tail``), or None."""
        tail = posixpath.normpath(tail) if tail else ""
        reasons = [why for scope, why in self.unread
                   if scope is None or _below(tail, scope) is not None]
        if not reasons:
            return None
        return (f"the package's install rules could not be read ({reasons[0]}"
                + (f", and {len(reasons) - 1} more" if len(reasons) > 1 else "") + ")")


def _below(tail: str, destination: str) -> str | None:
    if not destination:
        return tail
    if tail == destination:
        return ""
    return tail[len(destination) + 1:] if tail.startswith(destination + "/") else None


def _join(folder: str, rest: str) -> str:
    return posixpath.normpath(posixpath.join(folder, rest)) if rest else folder


@per_run
def layout(folder: Path, name: str, root: Path) -> Layout:
    """The install layout of the package ``name`` whose package.xml is in ``folder``, inside
    the repository (or containment root) ``root``; once per run."""
    reader = _Reader(Path(folder), name, Path(root))
    if kind_of(Path(folder) / "CMakeLists.txt") == "file":
        reader.build.append("CMakeLists.txt")
        _CMake(reader).run_file(Path(folder), ())
    for setup in ("setup.py", "setup.cfg"):
        if kind_of(Path(folder) / setup) == "file":
            reader.build.append(setup)
            (_setup_py if setup == "setup.py" else _setup_cfg)(reader)
    if not reader.build:  # colcon and catkin build no such folder: another build lays out
        # share/NAME (icub-models' placeholder package.xml, its share folder made by the
        # repository's own CMake from three source folders)
        reader.doubt(None, "no CMakeLists.txt, setup.py or setup.cfg in the package's folder: "
                           "another build makes its share folder")
        # the repository's own CMake above it, which may install a folder as share/NAME
        # (icub-models: install(DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/iCub DESTINATION share)
        # of a build folder its file(COPY) fills): what it is read to install is found there;
        # the doubt stays (a missing file is not certain)
        above = _enclosing_build(Path(folder), Path(root))
        if above is not None:
            reader.build.append(Path(os.path.relpath(above / "CMakeLists.txt", folder)).as_posix())
            _CMake(reader).run_file(above, ())
    return Layout(tuple(reader.rules[:MAX_RULES]), tuple(dict.fromkeys(reader.unread)),
                  ", ".join(reader.build))


def _enclosing_build(folder: Path, root: Path) -> Path | None:
    """The nearest folder above ``folder``, up to ``root``, holding a CMakeLists.txt."""
    top = os.path.normpath(root)
    for above in folder.parents:
        here = os.path.normpath(above)
        if not (here == top or here.startswith(top.rstrip(os.sep) + os.sep)):
            return None
        if kind_of(above / "CMakeLists.txt") == "file":
            return above
        if here == top:
            return None
    return None


class _Reader:
    """The rules and doubts gathered from one package's build files."""

    def __init__(self, folder: Path, name: str, root: Path):
        self.folder = folder
        self.name = name
        self.root = root
        self.rules: list[InstallRule] = []
        self.unread: list[str] = []
        self.build: list[str] = []
        # what CMake's file(COPY) put into the build folder: (the place below it, the source
        # copied there, absolute; where it was read), in the build's order
        self.copies: list[tuple[str, str, str]] = []

    def read(self, path: Path) -> str | None:
        try:
            data = read_regular(path, MAX_BUILD_FILE, as_="build description")
        except OSError as error:
            self.doubt(None, f"{self._shown(path)}: {getattr(error, 'strerror', None) or error}")
            return None
        return data.decode("utf-8", "replace")

    def doubt(self, scope: str | None, why: str) -> None:
        """Keep why the install rules for ``share/NAME/scope`` (None: anywhere) were not read."""
        self.unread.append((scope, why))

    def _shown(self, path: Path) -> str:
        return os.path.relpath(path, self.folder)

    def destination(self, text: str) -> str | None:
        """``text`` (an install destination, relative to the install prefix) as a folder below
        ``share/NAME``, or None when it is not one."""
        text = posixpath.normpath(text.replace("\\", "/").lstrip("/")) if text else ""
        share = f"share/{self.name}"
        if text == share:
            return ""
        return text[len(share) + 1:] if text.startswith(share + "/") else None

    def add(self, destination: str, source: str, kind: str, origin: str, base: Path,
            as_name: str = "") -> None:
        """Keep one rule; a source leading outside the repository is refused (never looked at).
        A source in CMake's build folder is what file(COPY) put there (:meth:`from_build`)."""
        if source.startswith(_BUILD):
            self.from_build(destination, source[len(_BUILD):], kind, origin, as_name)
            return
        joined = os.path.normpath(os.path.join(base, source.replace("\\", "/")))
        root = os.path.normpath(self.root)
        if not (joined == root or joined.startswith(root.rstrip(os.sep) + os.sep)):
            self.doubt(destination, f"{origin}: source '{source}' leads outside the repository; "
                                    "refused")
            return
        relative = Path(os.path.relpath(joined, self.folder)).as_posix()
        if len(self.rules) < MAX_RULES:
            self.rules.append(InstallRule(destination, relative, kind, origin, as_name))


    def from_build(self, destination: str, place: str, kind: str, origin: str,
                   as_name: str) -> None:
        """The rules installing ``place`` of CMake's build folder: the sources file(COPY) put
        at or below it (tree), or at a folder holding it (file). Other commands may write
        there too (configure_file, file(WRITE), custom commands), which are not read: the
        place is doubted as well, so that a file missing is never certain."""
        place = posixpath.normpath(place.strip("/")) if place.strip("/") else ""
        place = "" if place == "." else place
        self.doubt(destination, f"{origin}: installs CMake's build folder, of which only what "
                                "file(COPY) puts there is read")
        for landing, copied, where in self.copies:
            told = f"{origin}, from {where}"
            if kind == "tree":
                rest = _below(landing, place)  # the copy lands inside the folder installed
                if rest is not None:
                    self.add(_join(destination, rest) if destination else rest, copied,
                             "tree", told, self.folder)
                    continue
                inner = _below(place, landing)  # the folder installed is inside the copy
                if inner is not None:
                    self.add(destination, _join(copied, inner), "tree", told, self.folder)
            elif kind == "file":
                inner = _below(place, landing)
                if inner is not None:
                    self.add(destination, _join(copied, inner), "file", told, self.folder,
                             as_name)


# ---- CMake ------------------------------------------------------------------------------------

_COMMAND = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)[ \t]*\(")
_BRACKET_OPEN = re.compile(r"\[(=*)\[")
_VARIABLE = re.compile(r"\$\{([A-Za-z0-9_./+-]+)\}")
_UNKNOWN = object()


class _Arg(Frozen):
    """An argument of a CMake command, and whether it was quoted."""

    text: str
    quoted: bool

    __slots__ = ("text", "quoted")

    def __init__(self, text: str, quoted: bool) -> None:
        set_field = object.__setattr__
        set_field(self, "text", text)
        set_field(self, "quoted", quoted)


def cmake_commands(text: str) -> list[tuple[str, list[_Arg], int]]:
    """(lower-case name, arguments, line) of each command of a CMake file: comments, quoted and
    bracket arguments as CMake's grammar has them; at most MAX_COMMANDS."""
    commands, i, n, line, counted = [], 0, len(text), 1, 0
    while i < n and len(commands) < MAX_COMMANDS:
        char = text[i]
        if char == "#":
            i = _skip_comment(text, i)
            continue
        match = _COMMAND.match(text, i)
        if match is None:
            i += 1
            continue
        line, counted = line + lines_between(text, counted, i), i
        args, i = _arguments(text, match.end())
        commands.append((match.group(1).lower(), args, line))
    return commands


def _skip_comment(text: str, i: int) -> int:
    bracket = _BRACKET_OPEN.match(text, i + 1)
    if bracket:
        end = text.find("]" + bracket.group(1) + "]", bracket.end())
        return len(text) if end < 0 else end + len(bracket.group(1)) + 2
    end = text.find("\n", i)
    return len(text) if end < 0 else end + 1


def _arguments(text: str, i: int) -> tuple[list[_Arg], int]:
    args, depth, n, word = [], 0, len(text), None
    while i < n:
        char = text[i]
        if char in " \t\r\n":
            if word is not None:
                args.append(_Arg(word, False))
                word = None
            i += 1
        elif char == "#":
            i = _skip_comment(text, i)
        elif char == '"' and word is None:
            end, parts = i + 1, []
            while end < n and text[end] != '"':
                if text[end] == "\\" and end + 1 < n:
                    parts.append(text[end:end + 2] if text[end + 1] == "$" else text[end + 1])
                    end += 2
                    continue
                parts.append(text[end])
                end += 1
            args.append(_Arg("".join(parts), True))
            i = end + 1
        elif char == "[" and word is None and _BRACKET_OPEN.match(text, i):
            bracket = _BRACKET_OPEN.match(text, i)
            end = text.find("]" + bracket.group(1) + "]", bracket.end())
            end = n if end < 0 else end
            args.append(_Arg(text[bracket.end():end], True))
            i = end + len(bracket.group(1)) + 2
        elif char == "(":
            depth += 1
            word = (word or "") + char
            i += 1
        elif char == ")":
            if depth == 0:
                if word is not None:
                    args.append(_Arg(word, False))
                return args, i + 1
            depth -= 1
            word = (word or "") + char
            i += 1
        else:
            word = (word or "") + char
            i += 1
    if word is not None:
        args.append(_Arg(word, False))
    return args, n


_INSTALL_KEYWORDS = {"DESTINATION", "FILES_MATCHING", "PATTERN", "REGEX", "EXCLUDE",
                     "USE_SOURCE_PERMISSIONS", "OPTIONAL", "COMPONENT", "PERMISSIONS",
                     "FILE_PERMISSIONS", "DIRECTORY_PERMISSIONS", "CONFIGURATIONS",
                     "MESSAGE_NEVER", "RENAME", "EXCLUDE_FROM_ALL", "TYPE"}
_SETTERS = {"list", "string", "file", "get_filename_component", "math", "cmake_path",
            "find_file", "find_path", "option", "unset", "set_property", "get_property",
            "separate_arguments", "configure_file", "include"}
_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
_PREFIX_VARIABLES = ("CMAKE_INSTALL_PREFIX",)
# install folders catkin and GNUInstallDirs name ({} is the project's name)
_INSTALL_DIRS = {
    "CATKIN_PACKAGE_SHARE_DESTINATION": "share/{}", "CATKIN_GLOBAL_SHARE_DESTINATION": "share",
    "CMAKE_INSTALL_DATADIR": "share", "CMAKE_INSTALL_DATAROOTDIR": "share",
    "CATKIN_PACKAGE_BIN_DESTINATION": "lib/{}", "CATKIN_PACKAGE_LIB_DESTINATION": "lib",
    "CATKIN_PACKAGE_INCLUDE_DESTINATION": "include/{}",
    "CATKIN_PACKAGE_PYTHON_DESTINATION": "lib/python3/dist-packages/{}",
    "CATKIN_PACKAGE_ETC_DESTINATION": "etc/{}", "CATKIN_GLOBAL_BIN_DESTINATION": "bin",
    "CATKIN_GLOBAL_LIB_DESTINATION": "lib", "CATKIN_GLOBAL_LIBEXEC_DESTINATION": "lib",
    "CATKIN_GLOBAL_INCLUDE_DESTINATION": "include", "CATKIN_GLOBAL_ETC_DESTINATION": "etc",
    "CATKIN_GLOBAL_PYTHON_DESTINATION": "lib/python3/dist-packages",
    "CMAKE_INSTALL_BINDIR": "bin", "CMAKE_INSTALL_LIBDIR": "lib",
    "CMAKE_INSTALL_INCLUDEDIR": "include", "CMAKE_INSTALL_LIBEXECDIR": "libexec",
    "CMAKE_INSTALL_SYSCONFDIR": "etc", "CMAKE_INSTALL_DOCDIR": "share/doc/{}"}
_SOURCE_VARIABLES = ("CMAKE_CURRENT_SOURCE_DIR", "CMAKE_CURRENT_LIST_DIR", "PROJECT_SOURCE_DIR",
                     "CMAKE_SOURCE_DIR")
# CMake's build folder (CMAKE_CURRENT_BINARY_DIR...), a place no path of the source tree names:
# what is installed from it is what file(COPY) put there (_Reader.from_build)
_BUILD = "\x00build"
_COPY_FILTERS = {"FILES_MATCHING", "PATTERN", "REGEX", "EXCLUDE"}
_FALSE = {"FALSE", "OFF", "0", "NO", "N", "IGNORE", ""}


class _CMake:
    """Evaluates the install commands of a package's CMake files (never runs CMake)."""

    def __init__(self, reader: _Reader):
        self.reader = reader
        self.followed = 0
        self.top: Path | None = None
        self.globbed: set[str] = set()  # variables holding a file(GLOB) of the source tree

    def run_file(self, folder: Path, inherited: tuple) -> None:
        path = folder / "CMakeLists.txt"
        text = self.reader.read(path)
        if text is None:
            return
        commands = cmake_commands(text)
        shown = Path(os.path.relpath(path, self.reader.folder)).as_posix()
        if self.top is None:
            self.top = folder
        below = Path(os.path.relpath(folder, self.top)).as_posix()
        binary = [_Arg(_BUILD if below == "." else f"{_BUILD}/{below}", True)]
        seeded = {**dict(inherited), "CMAKE_CURRENT_BINARY_DIR": binary,
                  "CMAKE_BINARY_DIR": [_Arg(_BUILD, True)]}
        if "PROJECT_BINARY_DIR" not in seeded or any(c[0] == "project" for c in commands):
            seeded["PROJECT_BINARY_DIR"] = binary
        variables = self._variables(commands, seeded, folder)
        self._run(commands, variables, folder, shown)

    def _variables(self, commands, variables: dict, folder: Path) -> dict:
        """Variables set once (``set``, ``project``, ``file(GLOB)`` of one folder's entries);
        set twice or by anything else: unknown."""
        counts: dict[str, int] = {}
        for name, args, _ in commands:
            if name == "set" and args:
                counts[args[0].text] = counts.get(args[0].text, 0) + 1
            elif name == "file" and len(args) > 1 and args[0].text == "GLOB":
                counts[args[1].text] = counts.get(args[1].text, 0) + 1
            elif name == "project" and args:
                counts["PROJECT_NAME"] = counts.get("PROJECT_NAME", 0) + 1
            elif name in _SETTERS:  # may set any variable named among its arguments
                for arg in args:
                    if not arg.quoted and _IDENTIFIER.match(arg.text):
                        counts[arg.text] = counts.get(arg.text, 0) + 2
        projects = {args[0].text for name, args, _ in commands if name == "project" and args}
        if self.reader.name in projects:  # a superbuild's project() beside the package's own
            counts["PROJECT_NAME"] = 1
            projects = {self.reader.name}
        for name, args, _ in commands:
            if name == "project" and args and counts.get("PROJECT_NAME") == 1 and \
                    args[0].text in projects:
                variables["PROJECT_NAME"] = [_Arg(args[0].text, True)]
            elif name == "set" and args and counts.get(args[0].text) == 1:
                values = [a for a in args[1:] if a.text not in ("CACHE", "PARENT_SCOPE")]
                if any(a.text in ("CACHE", "PARENT_SCOPE") for a in args[1:]):
                    values = args[1:2]
                variables[args[0].text] = values
            elif name == "file" and len(args) > 1 and args[0].text == "GLOB" and \
                    counts.get(args[1].text) == 1:
                variables[args[1].text] = self._glob(args[2:], variables, folder)
                self.globbed.add(args[1].text)
        for name, count in counts.items():
            if count > 1:
                variables[name] = _UNKNOWN
        variables.setdefault("PROJECT_NAME", [_Arg(self.reader.name, True)])
        return variables

    def _run(self, commands, variables: dict, folder: Path, shown: str) -> None:
        i = 0
        while i < len(commands):
            name, args, line = commands[i]
            origin = f"{shown}:{line}"
            if name == "foreach":
                end = _block_end(commands, i, "foreach", "endforeach")
                self._foreach(args, commands[i + 1:end], variables, folder, shown, origin)
                i = end + 1
                continue
            if name in ("function", "macro"):  # bodies run when called, with their arguments
                end = _block_end(commands, i, name, "end" + name)
                if any(c[0] in ("install", "ament_auto_package") for c in commands[i + 1:end]):
                    self.reader.doubt(None, f"{origin}: install() inside {name}() "
                                              f"'{args[0].text if args else ''}'")
                i = end + 1
                continue
            if name == "install":
                self._install(args, variables, folder, origin)
            elif name == "file" and args and args[0].text == "COPY":
                self._copy(args, variables, folder, origin)
            elif name == "ament_auto_package":
                self._auto_package(args, variables, folder, origin)
            elif name == "add_subdirectory" and args:
                self._subdirectory(args[0], variables, folder, origin)
            i += 1

    def _of_glob(self, args) -> bool:
        """Whether an argument names a variable holding a file(GLOB)."""
        return any(match.group(1) in self.globbed
                   for a in args for match in _VARIABLE.finditer(a.text))

    def _glob(self, args, variables, folder: Path):
        """``file(GLOB VAR [LIST_DIRECTORIES b] [RELATIVE dir] patterns)``'s values: the
        entries of one folder of the repository matching a pattern (none in the folder's
        path), sorted as CMake sorts them; unknown for anything else."""
        relative, folders, patterns, i = None, True, [], 0
        while i < len(args):
            word = args[i].text
            if word in ("RELATIVE", "LIST_DIRECTORIES") and i + 1 < len(args):
                value = _expand(args[i + 1], variables, folder)
                if value is None or len(value) != 1:
                    return _UNKNOWN
                if word == "RELATIVE":
                    relative = value[0]
                else:
                    folders = value[0].upper() not in _FALSE
                i += 2
                continue
            if word in ("FOLLOW_SYMLINKS", "CONFIGURE_DEPENDS"):
                i += 1
                continue
            values = _expand(args[i], variables, folder)
            if values is None:
                return _UNKNOWN
            patterns += values
            i += 1
        top = os.path.normpath(self.reader.root)
        found = []
        for pattern in patterns:
            if _BUILD in pattern:  # the build folder's entries: written by the build
                return _UNKNOWN
            parent, leaf = os.path.split(os.path.normpath(os.path.join(folder, pattern)))
            if _MAGIC.search(parent) or "|" in leaf or not leaf or not (
                    parent == top or parent.startswith(top.rstrip(os.sep) + os.sep)):
                return _UNKNOWN
            for entry, kind in listing(parent, leaf):
                if kind == "folder" and not folders:
                    continue
                full = os.path.join(parent, entry)
                found.append(os.path.relpath(full, os.path.join(folder, relative))
                             if relative is not None else full)
        return [_Arg(Path(value).as_posix(), True) for value in sorted(set(found))][:256]

    def _copy(self, args, variables, folder: Path, origin: str) -> None:
        """``file(COPY sources DESTINATION dir)`` into the build folder: kept (unfiltered
        copies only) as the sources of what is installed from there."""
        words = [a.text for a in args]
        if "DESTINATION" not in words or _COPY_FILTERS & set(words):
            return
        at = words.index("DESTINATION")
        where = _expand(args[at + 1], variables, folder) if at + 1 < len(args) else None
        if where is None or len(where) != 1 or not where[0].startswith(_BUILD):
            return
        landing = posixpath.normpath(where[0][len(_BUILD):].strip("/") or ".")
        landing = "" if landing == "." else landing
        for arg in args[1:at]:
            for value in _expand(arg, variables, folder) or ():
                if not value or value.startswith(_BUILD):
                    continue
                source = os.path.normpath(os.path.join(folder, value))
                into = landing if value.endswith("/") else \
                    _join(landing, posixpath.basename(value.rstrip("/")))
                self.reader.copies.append((into, source, origin))

    def _foreach(self, args, body, variables, folder, shown, origin) -> None:
        if not args:
            return
        items = args[1:]
        if items and items[0].text == "IN":
            if len(items) > 1 and items[1].text == "ITEMS":
                items = items[2:]
            elif len(items) > 1 and items[1].text == "LISTS":
                items = [value for list_name in items[2:]
                         for value in (variables.get(list_name.text) or [])] \
                    if all(variables.get(a.text, _UNKNOWN) is not _UNKNOWN for a in items[2:]) \
                    else None
            else:
                items = None
        elif items and items[0].text == "RANGE":
            items = []  # numbers: no install source
        if items is None or any(_expand(a, variables) is None for a in items):
            if any(c[0] in ("install", "ament_auto_package") for c in body):
                self.reader.doubt(None, f"{origin}: install() in a foreach() over values "
                                          "not read")
            return
        if self._of_glob(items) and any(c[0] in ("install", "ament_auto_package", "file")
                                        for c in body):
            self.reader.doubt(None, f"{origin}: install() or file(COPY) in a foreach() over "
                                      "a file(GLOB) of the source tree, which may hold more in "
                                      "a build (generated folders, submodules)")
        for item in [value for a in items for value in _expand(a, variables)][:256]:
            self._run(body, {**variables, args[0].text: [_Arg(item, True)]}, folder, shown)

    def _subdirectory(self, arg: _Arg, variables, folder: Path, origin: str) -> None:
        values = _expand(arg, variables)
        if not values or len(values) != 1:
            return
        sub = Path(os.path.normpath(folder / values[0]))
        root = os.path.normpath(self.reader.root)
        if not str(sub).startswith(root.rstrip(os.sep) + os.sep) or self.followed >= \
                MAX_SUBDIRECTORIES:
            return
        self.followed += 1
        if kind_of(sub / "CMakeLists.txt") == "file":
            inherited = {k: v for k, v in variables.items() if k == "PROJECT_NAME"}
            self.run_file(sub, tuple(inherited.items()))

    def _install(self, args, variables, folder: Path, origin: str) -> None:
        if not args or args[0].text not in ("DIRECTORY", "FILES", "PROGRAMS"):
            return
        kind = args[0].text
        sources, destination, rename, i = [], None, None, 1
        while i < len(args) and args[i].text not in _INSTALL_KEYWORDS:
            sources.append(args[i])
            i += 1
        while i < len(args):
            word = args[i].text
            if word == "DESTINATION" and i + 1 < len(args):
                destination = args[i + 1]
                i += 2
                continue
            if word == "RENAME" and i + 1 < len(args):
                rename = args[i + 1]
                i += 2
                continue
            i += 1
        if destination is None:
            return
        where = _expand(destination, variables, folder)
        if where is None or len(where) != 1:
            self.reader.doubt(None, f"{origin}: install(... DESTINATION "
                                      f"{destination.text}) not read")
            return
        target = self.reader.destination(where[0])
        if target is None and kind != "DIRECTORY":
            return
        paths = [_expand(a, variables, folder) for a in sources]
        if self._of_glob(sources):
            self.reader.doubt(target, f"{origin}: install({kind} ...) of a file(GLOB) of the "
                                      "source tree, which may hold more in a build")
        new_name = _expand(rename, variables, folder) if rename is not None else None
        if any(p is None for p in paths) or (rename is not None and not new_name):
            if target is not None:
                self.reader.doubt(target, f"{origin}: install({kind} ...) sources not read")
            return
        for source in [value for values in paths for value in values]:
            if not source:
                continue
            if target is None:  # a folder installed into share itself: share/NAME when so named
                into = None if source.endswith("/") else self.reader.destination(
                    posixpath.join(where[0], posixpath.basename(source.rstrip("/"))))
                if into is not None:
                    self.reader.add(into, source.rstrip("/"), "tree", origin, folder)
                continue
            if kind == "DIRECTORY":
                trimmed = source.rstrip("/")
                if source.endswith("/"):
                    self.reader.add(target, trimmed or ".", "tree", origin, folder)
                else:
                    self.reader.add(_join(target, posixpath.basename(trimmed)) if target
                                    else posixpath.basename(trimmed), trimmed, "tree", origin,
                                    folder)
            elif _MAGIC.search(source):
                self.reader.doubt(target, f"{origin}: install({kind} {source}) pattern")
            else:
                as_name = new_name[0] if new_name else posixpath.basename(source)
                self.reader.add(target, source, "file", origin, folder, as_name)

    def _auto_package(self, args, variables, folder: Path, origin: str) -> None:
        words = [a.text for a in args]
        if "INSTALL_TO_SHARE" not in words:
            return
        for arg in args[words.index("INSTALL_TO_SHARE") + 1:]:
            if arg.text.isupper() and not arg.quoted:
                break  # the next keyword
            values = _expand(arg, variables, folder)
            if values is None:
                self.reader.doubt(None, f"{origin}: ament_auto_package(INSTALL_TO_SHARE "
                                          f"{arg.text}) not read")
                continue
            for value in values:
                trimmed = value.rstrip("/")
                self.reader.add(posixpath.basename(trimmed), trimmed, "tree", origin, folder)


def _block_end(commands, start: int, opener: str, closer: str) -> int:
    depth = 0
    for index in range(start, len(commands)):
        if commands[index][0] == opener:
            depth += 1
        elif commands[index][0] == closer:
            depth -= 1
            if depth == 0:
                return index
    return len(commands)


def _expand(arg: _Arg, variables: dict, folder: Path | None = None,
            depth: int = 0) -> list[str] | None:
    """An argument's values with ``${VAR}`` replaced (an unquoted one split at ``;``); None
    when a variable is unknown, or for a generator expression ``$<...>``."""
    text = arg.text
    if "$<" in text or "$ENV{" in text or depth > 8:
        return None
    unknown = False

    def replace(match: re.Match) -> str:
        nonlocal unknown
        name = match.group(1)
        if name in _PREFIX_VARIABLES:
            return "/"
        if name in _INSTALL_DIRS:
            if "{}" not in _INSTALL_DIRS[name]:
                return _INSTALL_DIRS[name]
            project = variables.get("PROJECT_NAME")
            values = None if project in (None, _UNKNOWN) else \
                _joined(project, variables, depth, folder)
            if values is None:
                unknown = True
                return ""
            return _INSTALL_DIRS[name].format(values)
        if folder is not None and (name in _SOURCE_VARIABLES or name.endswith("_SOURCE_DIR")):
            return str(folder)
        value = variables.get(name, _UNKNOWN)
        if value is _UNKNOWN:
            unknown = True
            return ""
        joined = _joined(value, variables, depth, folder)
        if joined is None:
            unknown = True
            return ""
        return joined

    for _ in range(8):  # nested ${${x}}: inner first
        replaced = _VARIABLE.sub(replace, text)
        if replaced == text:
            break
        text = replaced
    if unknown or "${" in text:
        return None
    return [text] if arg.quoted else [part for part in text.split(";") if part]


def _joined(values, variables, depth, folder) -> str | None:
    parts = []
    for value in values:
        expanded = _expand(value, variables, folder, depth + 1)
        if expanded is None:
            return None
        parts.extend(expanded)
    return ";".join(parts)


# ---- setup.py and setup.cfg -------------------------------------------------------------------

class _NotLiteral(Exception):
    """A value of setup.py that is not read without running it."""


class _Glob(Frozen):
    """A ``glob(...)`` of setup.py: its pattern."""

    pattern: str

    __slots__ = ("pattern",)

    def __init__(self, pattern: str) -> None:
        set_field = object.__setattr__
        set_field(self, "pattern", pattern)


def _setup_py(reader: _Reader) -> None:
    text = reader.read(reader.folder / "setup.py")
    if text is None:
        return
    try:
        module = ast.parse(text)
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        reader.doubt(None, "setup.py: not parsed")
        return
    calls = [node for node in ast_nodes(module) if isinstance(node, ast.Call)
             and _called(node.func) in ("setup", "setuptools.setup")]
    if len(calls) != 1:
        if calls:
            reader.doubt(None, "setup.py: several setup() calls")
        return
    call, values = calls[0], _Values(module)
    keywords = [k for k in call.keywords if k.arg is not None]
    for spread in (k.value for k in call.keywords if k.arg is None):
        # setup(**generate_distutils_setup(...)) or setup(**d), d = a call with keywords only
        made = values.bindings.get(spread.id) if isinstance(spread, ast.Name) else None
        made = made[0][0] if made and len(made) == 1 and spread.id not in values.touched \
            else spread
        if not (isinstance(made, ast.Call) and not made.args and
                all(k.arg is not None for k in made.keywords)):
            reader.doubt(None, f"setup.py:{call.lineno}: setup(**...) not read")
            return
        keywords += made.keywords
    for keyword in keywords:
        origin = f"setup.py:{keyword.value.lineno}"
        try:
            if keyword.arg == "data_files":
                _data_files(reader, values.value(keyword.value), origin)
            elif keyword.arg == "package_dir":
                _package_dir(reader, values.value(keyword.value), origin)
        except _NotLiteral as why:
            reader.doubt(None, f"{origin}: {keyword.arg} {why}")


def _called(func: ast.AST) -> str:
    if isinstance(func, ast.Name):
        return func.id
    if isinstance(func, ast.Attribute):
        return f"{_called(func.value)}.{func.attr}"
    return ""


class _Values:
    """Module-level values of a setup.py, read as literals (nothing is run)."""

    def __init__(self, module: ast.Module):
        self.module = module
        self.bindings: dict[str, list[ast.AST]] = {}
        self.touched: set[str] = set()  # names changed anywhere but a top-level statement
        for statement in module.body:
            simple = isinstance(statement, (ast.Assign, ast.AnnAssign, ast.AugAssign, ast.Expr))
            if simple:
                for target, value, how in _top_binding(statement):
                    self.bindings.setdefault(target, []).append((value, how))
            else:
                self.touched.update(_changed_names(statement))
        self.depth = 0

    def value(self, node: ast.AST):
        self.depth += 1
        try:
            if self.depth > 50:
                raise _NotLiteral("nested too deeply")
            return self._value(node)
        finally:
            self.depth -= 1

    def _value(self, node: ast.AST):
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            return node.value
        if isinstance(node, (ast.List, ast.Tuple)):
            return [self.value(item) for item in node.elts]
        if isinstance(node, ast.Dict) and None not in node.keys:
            return {self.value(k): self.value(v) for k, v in zip(node.keys, node.values)}
        if isinstance(node, ast.Name):
            return self.name(node.id)
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
            left, right = self.value(node.left), self.value(node.right)
            if type(left) is not type(right) or isinstance(left, (dict, _Glob)):
                raise _NotLiteral("is not a literal")
            return left + right
        if isinstance(node, ast.JoinedStr):
            parts = []
            for part in node.values:
                if isinstance(part, ast.FormattedValue):
                    if part.format_spec is not None or part.conversion != -1:
                        raise _NotLiteral("is not a literal")
                    part = part.value
                value = self.value(part)
                if not isinstance(value, str):
                    raise _NotLiteral("is not a literal")
                parts.append(value)
            return "".join(parts)
        if isinstance(node, ast.Call) and (not node.keywords or _recursive_only(node)):
            called = _called(node.func)
            args = [self.value(arg) for arg in node.args]
            if called in ("os.path.join", "path.join", "join", "osp.join") and \
                    all(isinstance(a, str) for a in args) and args:
                return posixpath.join(*args)
            if called in ("glob", "glob.glob") and len(args) == 1 and isinstance(args[0], str):
                return _Glob(args[0])
            if called in ("list", "sorted") and len(args) == 1 and isinstance(args[0], _Glob):
                return args[0]
        raise _NotLiteral(f"is not a literal (line {getattr(node, 'lineno', '?')})")

    def name(self, name: str):
        bound = self.bindings.get(name)
        if not bound or name in self.touched:
            raise _NotLiteral(f"uses '{name}', not set once at module level")
        value = None
        for node, how in bound:
            if how == "=":
                value = self.value(node)
            elif value is None:
                raise _NotLiteral(f"uses '{name}' before it is set")
            elif how in ("+=", "extend"):
                more = self.value(node)
                if not isinstance(value, list) or not isinstance(more, list):
                    raise _NotLiteral(f"uses '{name}', not a literal list")
                value = value + more
            elif how == "append" and isinstance(value, list):
                value = value + [self.value(node)]
            else:
                raise _NotLiteral(f"uses '{name}', changed in a way not read")
        return value


def _recursive_only(node: ast.Call) -> bool:
    """``glob(pattern, recursive=True)``: a call whose only keyword is ``recursive``."""
    return _called(node.func) in ("glob", "glob.glob") and \
        [k.arg for k in node.keywords] == ["recursive"]


def _top_binding(statement: ast.stmt):
    """(name, value node, how) for ``name = v``, ``name += v``, ``name.append(v)``,
    ``name.extend(v)`` as a module-level statement."""
    if isinstance(statement, ast.Assign):
        for target in statement.targets:
            if isinstance(target, ast.Name):
                yield target.id, statement.value, "="
            else:
                for name in _changed_names(target):
                    yield name, ast.Constant(None), "?"
    elif isinstance(statement, ast.AnnAssign) and isinstance(statement.target, ast.Name) \
            and statement.value is not None:
        yield statement.target.id, statement.value, "="
    elif isinstance(statement, ast.AugAssign) and isinstance(statement.target, ast.Name):
        yield statement.target.id, statement.value, ("+=" if isinstance(statement.op, ast.Add)
                                                     else "?")
    elif isinstance(statement, ast.Expr) and isinstance(statement.value, ast.Call) and \
            isinstance(statement.value.func, ast.Attribute) and \
            isinstance(statement.value.func.value, ast.Name) and \
            statement.value.func.attr in ("append", "extend") and \
            len(statement.value.args) == 1:
        yield statement.value.func.value.id, statement.value.args[0], statement.value.func.attr
    else:
        for name in _changed_names(statement):
            yield name, ast.Constant(None), "?"


_MUTATORS = {"append", "extend", "insert", "update", "setdefault", "pop", "remove", "clear",
             "__setitem__", "__iadd__"}


def _changed_names(node: ast.AST):
    """Names a statement may bind or change: stored, deleted, declared global, or a mutating
    method called on them (``name.append(...)``)."""
    for child in ast_nodes(node):
        if isinstance(child, ast.Name) and isinstance(child.ctx, (ast.Store, ast.Del)):
            yield child.id
        elif isinstance(child, ast.Call) and isinstance(child.func, ast.Attribute) and \
                isinstance(child.func.value, ast.Name) and child.func.attr in _MUTATORS:
            yield child.func.value.id
        elif isinstance(child, ast.Subscript) and isinstance(child.value, ast.Name) and \
                isinstance(child.ctx, ast.Store):
            yield child.value.id
        elif isinstance(child, (ast.Global, ast.Nonlocal)):
            yield from child.names


def _data_files(reader: _Reader, value, origin: str) -> None:
    if not isinstance(value, list):
        raise _NotLiteral("is not a list")
    for entry in value:
        if not (isinstance(entry, list) and len(entry) == 2 and isinstance(entry[0], str)
                and isinstance(entry[1], (list, _Glob))):
            raise _NotLiteral("has an entry that is not (folder, [files])")
        _data_entry(reader, entry[0], entry[1] if isinstance(entry[1], list) else [entry[1]],
                    origin)


def _data_entry(reader: _Reader, destination: str, sources: list, origin: str) -> None:
    target = reader.destination(destination)
    if target is None:
        return
    for source in sources:
        if isinstance(source, _Glob):
            source = source.pattern
            folder, pattern = posixpath.split(source)
            if _MAGIC.search(folder) or "**" in pattern:
                reader.doubt(target, f"{origin}: data_files pattern '{source}'")
                continue
            reader.add(target, source, "glob", origin, reader.folder)
        elif isinstance(source, str) and source:
            if _MAGIC.search(source):  # setup.cfg's data_files take patterns too
                reader.add(target, source, "glob", origin, reader.folder)
            else:
                reader.add(target, source, "file", origin, reader.folder,
                           posixpath.basename(source.rstrip("/")))
        else:
            raise _NotLiteral("has a source that is not a string")


def _package_dir(reader: _Reader, value, origin: str) -> None:
    """A Python package of the ROS package's own name: where Pinocchio's package directories
    (site-packages) find ``NAME/...``."""
    if not isinstance(value, dict):
        raise _NotLiteral("is not a dict")
    if reader.name in value and isinstance(value[reader.name], str):
        reader.add("", value[reader.name], "tree", origin, reader.folder)
    elif "" in value and isinstance(value[""], str) and \
            kind_of(reader.folder / value[""] / reader.name / "__init__.py") == "file":
        reader.add("", posixpath.join(value[""], reader.name), "tree", origin, reader.folder)


def _setup_cfg(reader: _Reader) -> None:
    text = reader.read(reader.folder / "setup.cfg")
    if text is None:
        return
    import configparser  # (a package with a setup.cfg: most have none)

    parser = configparser.ConfigParser(interpolation=None, strict=False)
    parser.optionxform = str  # destinations keep their case
    try:
        parser.read_string(text)
    except configparser.Error:
        reader.doubt(None, "setup.cfg: not parsed")
        return
    if parser.has_section("options.data_files"):
        for destination, listed in parser.items("options.data_files"):
            sources = [s.strip() for s in re.split(r"[,\n]", listed) if s.strip()]
            _data_entry(reader, destination, sources, "setup.cfg [options.data_files]")
    if parser.has_option("options", "package_dir"):
        mapping = {}
        for line in parser.get("options", "package_dir").splitlines():
            key, sep, folder = line.partition("=")
            if sep:
                mapping[key.strip()] = folder.strip()
        _package_dir(reader, mapping, "setup.cfg [options] package_dir")
