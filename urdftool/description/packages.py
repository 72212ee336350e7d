"""Find ROS packages without ROS, for ``$(find pkg)`` and ``package://pkg/...``.

Search order: ``--package NAME=PATH``, ROS_PACKAGE_PATH, AMENT_PREFIX_PATH (``share/NAME``),
package.xml files walking up from the input to the repository root (a folder that is the
package, or has it as a child), then package.xml files below the repository root (the nearest
folder holding ``.git``). A folder or package.xml in the repository that is a symbolic link
leading outside it is not a package: it is not read, and the not-found message says so. Without
a ``.git`` above the input there is no repository to keep to, and the walk goes up to ``/``.
A folder holding a manifest.xml and no package.xml is a rosbuild package (ROS 1's), as rospack
takes it: named by its folder (:data:`~urdftool.description.files.MANIFESTS`).

A path below a package found (``$(find NAME)/urdf/x.xacro``, ``package://NAME/meshes/x.stl``)
names the package's installed ``share/NAME``: when the source folder has no such file, the
package's build description says where it comes from (:mod:`.install_layout`), and
:meth:`PackageResolver.locate` is the one place that answers, for xacro's includes and YAML,
meshes, launch files' ``FindPackageShare`` and the cache's record alike.
"""

from __future__ import annotations

import os
import re
from collections import deque
from pathlib import Path

from urdftool.diagnostics import line_start, lines_between
from urdftool.errors import PackageNotFound, close_names
from urdftool.description.files import MANIFESTS, MANIFESTS_SAID, enclosing_root, environ, \
    inside, kind_of, listing, read_regular, real_path, repository_root, resolved, tree_made, walk
from urdftool.description.install_layout import layout
from urdftool.description.run_memo import per_run
from urdftool.records import Frozen

_NAME = re.compile(rb"<name>\s*([^<\s]+)\s*</name>")
SKIP_DIRS = frozenset({  # tool and build folders no walk enters
    ".git", ".venv", "venv", "node_modules", "__pycache__", "build", "install", "log"})
_MAX_SCAN_DEPTH = 6
_MAX_SCAN_DIRS = 20000
_MAX_MANIFEST = 1024 * 1024  # [bytes]


def package_name(folder: Path, root: Path | None = None) -> str | None:
    """The ``<name>`` a folder's package.xml declares (the folder's name for a rosbuild
    manifest.xml), or None when it has no manifest (or, given ``root``, when its manifest
    leads outside ``root``: then it is not opened)."""
    found = _manifest_of(folder, root)
    if found is None:
        return None
    match = _NAME.search(found[1]) if found[0] == "package.xml" else None
    return match.group(1).decode("utf-8", "replace") if match else folder.name


def _manifest_of(folder: Path, root: Path | None = None) -> tuple[str, bytes] | None:
    """(file name, text, comments removed) of the manifest of ``folder``: its package.xml,
    else its manifest.xml (:data:`MANIFESTS`); None when neither can be read, or, given
    ``root``, when the first present leads outside ``root`` (not opened)."""
    for name in MANIFESTS:
        path = os.path.join(folder, name)  # (a str: 600 questions on the corpus, no Path each)
        if root is not None and not inside(path, root):
            return None
        data = _manifest(path)
        if data is not None:
            return name, data
    return None


@per_run
def _manifest(path: str) -> bytes | None:
    """The bytes of the manifest (package.xml, manifest.xml) at ``path``, comments removed,
    None when it cannot be read: read once per run, whoever asks (every robot's resolver walks
    up and scans below the same repository, and two rules read its manifest: a check of the
    corpus read 83 package.xml files 351 times), its comments too."""
    try:
        return _COMMENT.sub(b"", read_regular(path, _MAX_MANIFEST, as_="package manifest"))
    except OSError:
        return None


@per_run
def containment_root(folder: Path) -> Path:
    """The folder files read for a robot in ``folder`` must stay in: its repository (nearest
    ``.git`` above); without one, the nearest folder above holding a package.xml; else
    ``folder`` itself. ``folder`` is taken as named, symbolic links not followed.

    The one "where may files be" rule: the loader's allowed roots, mesh paths and the include
    graph of ``urdftool check`` use it. (Companion discovery is stricter on purpose: only a few
    folders beside the robot, see :mod:`urdftool.description.companions`.)"""
    folder = Path(os.path.abspath(folder))
    return enclosing_root(folder) or folder


def written_from_above(anchor, written: str, above: bool = False,
                       skip: str | None = None) -> str | None:
    """The nearest folder, from ``anchor``'s folder (``above``: from the folder above it) up to
    its containment root, from which the relative path ``written`` names a file; ``skip``: a
    folder not to count (the one it was not found from); None when none does. The one answer
    to "written for a tool run from another folder": xacro's ``$(cwd)`` in a mesh's filename
    or an include's (the folder xacro runs from), an include written from the repository's
    root. Folders as named, links not followed (as :func:`containment_root`)."""
    anchor = os.path.abspath(anchor)
    root = os.fspath(containment_root(Path(anchor)))
    folder = os.path.dirname(anchor) if above else anchor
    while folder == root or folder.startswith(root.rstrip(os.sep) + os.sep):
        if folder != skip and kind_of(os.path.join(folder, written)) == "file":
            return folder
        if folder == root:
            break
        folder = os.path.dirname(folder)
    return None


def link_out(path) -> tuple[str, Path] | None:
    """(where it leads, the repository) when ``path`` is, or lies in a folder that is, a
    symbolic link leading outside the repository that holds it as named; None otherwise. A
    file named in a repository is read only when it stays there: a link planted in a pull
    request cannot make urdftool read, and print parts of, a file elsewhere."""
    root = containment_root(Path(os.path.abspath(path)).parent)
    return None if inside(path, root) else (real_path(path), root)


class Located(Frozen):
    """Where a path below a package is in the source tree.

    path: the file (or folder) found, or, when none is, the path as named; within: the folder
    it must stay in, links followed (its package's, or the source folder an install rule
    copies; None for a path below no package found); doubt: when nothing was found and the
    package's install rules for that path could not be read, why the file may still exist
    after a build (a missing file is then not certain)."""

    path: Path
    within: Path | None
    doubt: str | None

    __slots__ = ("path", "within", "doubt")

    def __init__(self, path: Path, within: Path | None = None, doubt: str | None = None) -> None:
        set_field = object.__setattr__
        set_field(self, "path", path)
        set_field(self, "within", within)
        set_field(self, "doubt", doubt)


def installed(name: str, folder: Path, path) -> Located:
    """Where ``path``, below the source folder ``folder`` of package ``name``, is: itself when
    it exists; else the source an install rule of the package's build puts at that place of
    ``share/NAME`` (inside the repository, no link leading out); else not found, with the
    doubt when the rules for that place could not be read."""
    named = path if isinstance(path, Path) else Path(path)
    if kind_of(named):
        return Located(named, folder)
    tail = Path(os.path.relpath(os.path.abspath(named), folder)).as_posix()
    if tail == ".." or tail.startswith("../"):
        return Located(named, folder)
    root = containment_root(folder)
    found = layout(folder, name, root)
    for source, rule in found.sources(tail):
        candidate = Path(os.path.normpath(folder / source))
        within = Path(os.path.normpath(folder / rule.source))
        if rule.kind != "tree":
            within = candidate.parent
        if kind_of(candidate) and inside(candidate, root) and inside(candidate, within):
            resolved(f"installed share/{name}/{tail}", f"{candidate} ({rule.origin})")
            return Located(candidate, within)
    return Located(named, folder, found.doubt(tail))


class PackageResolver:
    """Maps package names to folders; one instance serves xacro and mesh look-ups."""

    def __init__(self, explicit: dict[str, Path] | None = None, start: Path | None = None,
                 environ: dict[str, str] | None = None):
        # A relative folder is relative to the working directory (where the user typed it),
        # never to the file that includes $(find NAME): made absolute here, once.
        self.explicit = {name: Path(path).absolute() for name, path in (explicit or {}).items()}
        self.start = Path(real_path(start)) if start else None
        self.environ = environ  # None: this process's, each variable read recorded
        self._cache: dict[str, Path] = {}
        self._scanned: dict[str, Path] | None = None
        self._links_out: list[Path] = []  # package folders leading outside the repository

    def find(self, name: str) -> Path:
        """The folder of package ``name``; raises PackageNotFound listing where it looked."""
        if name in self._cache:
            return self._cache[name]
        searched: list[str] = []
        for candidate, where in self._candidates(name):
            searched.append(where)
            if candidate is not None:
                self._cache[name] = candidate
                resolved(f"package {name}", candidate)
                return candidate
        resolved(f"package {name}", "not found")
        raise PackageNotFound(name, searched,  # (a misspelt name: one of those found, nearly)
                              close=close_names(name, sorted(self._scanned or ()), cutoff=0.9))

    def _candidates(self, name: str):
        if name in self.explicit:
            path = self.explicit[name]
            yield (path if kind_of(path) == "folder" else None), f"--package {name}={path}"
        for entry in _split_path(environ("ROS_PACKAGE_PATH", self.environ) or ""):
            yield _find_below(Path(entry), name, depth=3), f"ROS_PACKAGE_PATH entry {entry}"
        for prefix in _split_path(environ("AMENT_PREFIX_PATH", self.environ) or ""):
            share = Path(prefix) / "share" / name
            yield (share if kind_of(share) == "folder" else None), f"AMENT_PREFIX_PATH {share}"
        if self.start is None:
            return
        root = repository_root(self.start)
        above = f"{MANIFESTS_SAID} above {self.start}" + (f" up to {root}" if root else "")
        yield self._walk_up(name, root), above
        if root is not None:
            yield self._scan(root).get(name), f"{MANIFESTS_SAID} below {root}"
        for link in dict.fromkeys(self._links_out):
            yield None, f"{link} (a symbolic link leading outside {root}; not followed)"

    def _walk_up(self, name: str, root: Path | None) -> Path | None:
        chain = [self.start, *self.start.parents]
        if root is not None:
            chain = chain[:chain.index(root) + 1]
        for folder in chain:
            for candidate in (folder, folder / name):
                if root is not None and not inside(os.path.join(candidate, "package.xml"),
                                                   root):
                    if any(kind_of(candidate / manifest) for manifest in MANIFESTS):
                        self._links_out.append(candidate)
                    continue
                if package_name(candidate, root) == name:
                    return candidate
        return None

    def _scan(self, root: Path) -> dict[str, Path]:
        if self._scanned is None:
            self._scanned = {}
            links: list[Path] = []
            for folder in _walk_dirs(root, links=links):
                name = package_name(folder, root)
                if name is not None:
                    self._scanned.setdefault(name, folder)
            self._links_out += [link for link in links if not inside(link, root)
                                and any(kind_of(link / manifest) for manifest in MANIFESTS)]
        return self._scanned

    def resolve_uri(self, uri: str, base_dir: Path) -> Path:
        """A mesh or include URI as a path: package://, file:// or relative to ``base_dir``,
        where :meth:`locate` finds it."""
        return self.locate_uri(uri, base_dir).path

    def locate_uri(self, uri: str, base_dir: Path) -> Located:
        """:meth:`locate` of a package://, file:// or relative (to ``base_dir``) URI."""
        if uri.startswith("package://"):
            name, tail = package_uri_parts(uri)
            return installed(name, self.find(name), self.find(name) / tail)
        if uri.startswith("file://"):
            return self.locate(Path(uri[len("file://"):]))
        return self.locate(base_dir / uri)

    def locate(self, path) -> Located:
        """Where ``path`` is when it lies below a package this resolver found (``$(find
        NAME)/...``): see :func:`installed`. Any other path is as named."""
        below = self.package_at(path)
        return installed(*below, path) if below else Located(Path(path))

    def package_at(self, path) -> tuple[str, Path] | None:
        """The name and folder of the package this resolver found (by ``$(find NAME)`` or
        ``package://NAME``) whose folder holds ``path`` (the innermost); None for none."""
        named = os.path.abspath(path)
        for name, folder in sorted(self._cache.items(), key=lambda item: -len(str(item[1]))):
            if named == str(folder) or named.startswith(str(folder).rstrip(os.sep) + os.sep):
                return name, folder
        return None


# ---- a package's manifest: which package a file is in, what that package declares -------------

# Every dependency tag of package.xml formats 1 to 3: a package named in any of them is declared
# (a build-only one too: whether it reaches a binary install is the build's business).
_DEPEND = re.compile(rb"<(?:depend|build_depend|build_export_depend|exec_depend|run_depend|"
                     rb"test_depend|doc_depend|buildtool_depend|buildtool_export_depend)"
                     rb"(?:\s[^<>]*)?>\s*([^<\s]+)\s*</")
# rosbuild's manifest.xml: <depend package="NAME"/> (a <depend stack=...> names a stack, no package)
_ROSBUILD_DEPEND = re.compile(rb"<depend\s[^<>]*?\bpackage\s*=\s*[\"']\s*([^\"'\s]+)\s*[\"']")
_COMMENT = re.compile(rb"<!--.*?(?:-->|\Z)", re.S)
# A package named literally in robot files: $(find NAME), package://NAME/ (not ${...} names);
# and the tags of xacro's conditional blocks (unprefixed as ROS 1's xacro took them too).
_FIND = re.compile(rb"\$\(find\s+([A-Za-z0-9_][A-Za-z0-9_.-]*)\s*\)")
_PACKAGE_URI = re.compile(rb"package://([A-Za-z0-9_][A-Za-z0-9_.-]*)/")
_REFERENCE = re.compile(_FIND.pattern + b"|" + _PACKAGE_URI.pattern + b"|" +
                        rb"<(/?)(?:xacro:)?(if|unless)\b[^<>]*?(/?)>")
# What every conditional tag _REFERENCE finds holds ("<if", "</xacro:unless", ...)
_CONDITIONAL = (b"<if", b"/if", b":if", b"<unless", b"/unless", b":unless")


def package_of(path) -> Path | None:
    """The folder of the ROS package holding the file ``path``: the nearest folder at or above
    the file's own folder holding a package.xml or a manifest.xml (:data:`MANIFESTS`), without
    leaving its containment root; None when there is none. Links are not followed (the package
    is where the file is named). (launch_configs.launch_file_packages answers it for every
    launch file of a repository from the launch walk's listings: this function asked of each
    cost 18 M instructions of r2d2's 560 M, session 20.)"""
    return _package_at_or_above(os.path.dirname(os.path.abspath(path)))


@per_run
def _package_at_or_above(where: str) -> Path | None:
    """:func:`package_of` of the files in the folder ``where``, once per run: three steps of a
    check ask it of each robot file (the package rule, the build tools, the launch files that
    may run it), and the robots of a corpus share folders (its 46 URDFs lie in 22: 140
    questions)."""
    start = Path(where)
    root = containment_root(start)
    for folder in [start, *start.parents]:
        if any(kind_of(manifest) == "file" and inside(manifest, root)
               for manifest in [os.path.join(folder, name) for name in MANIFESTS]):
            return folder
        if folder == root:
            return None
    return None


def manifest_file(folder: Path) -> str | None:
    """The file name of the manifest of ``folder`` (``package.xml``, else rosbuild's
    ``manifest.xml``), None when it has no readable one."""
    found = _manifest_of(folder)
    return None if found is None else found[0]


def manifest_text(folder: Path) -> bytes | None:
    """The manifest (package.xml, else rosbuild's manifest.xml) of ``folder``, comments
    removed; None when it cannot be read."""
    found = _manifest_of(folder)
    return None if found is None else found[1]


def declared_dependencies(folder: Path) -> frozenset[str] | None:
    """Every package the package.xml of ``folder`` names in a dependency tag (``<depend>``,
    ``<exec_depend>``, ``<run_depend>``, ``<build_depend>``, ...), whatever its ``condition``
    (of a rosbuild manifest.xml, each ``<depend package="NAME"/>``); None when there is no
    readable manifest."""
    found = _manifest_of(folder)
    if found is None:
        return None
    pattern = _DEPEND if found[0] == "package.xml" else _ROSBUILD_DEPEND
    return frozenset(name.decode("utf-8", "replace") for name in pattern.findall(found[1]))


_CATKIN = re.compile(rb"<buildtool_depend[^<>]*>\s*(catkin)\s*<")
_AMENT = re.compile(rb"<buildtool_depend[^<>]*>\s*(ament_(?:cmake|python))|<build_type>\s*(ament_\w+)")
_CONDITIONED = re.compile(rb"<buildtool_depend[^<>]*condition=")


def build_tools(path) -> tuple[tuple[int, str, Path], ...]:
    """(ROS version, build tool, its manifest) for each build tool the package.xml above
    ``path`` names (comments removed): none when a build tool is conditioned (a package built
    by both ROS versions); ROS 1's rosbuild for a manifest.xml (ROS 2 has no rosbuild)."""
    folder = package_of(path)
    found = _manifest_of(folder) if folder is not None else None
    if found is not None and found[0] == "manifest.xml":
        return ((1, "rosbuild", Path(folder) / "manifest.xml"),)
    data = found[1] if found is not None else None
    if data is None or _CONDITIONED.search(data):
        return ()
    found = ((version, pattern.search(data)) for version, pattern in ((1, _CATKIN), (2, _AMENT)))
    return tuple((version, next(g for g in match.groups() if g).decode(),
                  Path(folder) / "package.xml") for version, match in found if match)


_PACKAGE_ELEMENT = re.compile(rb"<package[\s>]")  # a ROS package manifest's root (REP 127, 140, 149)


def _foreign(found: tuple[str, bytes]) -> bool:
    """Whether a folder's manifest (:func:`_manifest_of`'s (file name, bytes)) is a package.xml
    that is no ROS package manifest (no ``<package>`` element: another tool's file)."""
    return found[0] == "package.xml" and not _PACKAGE_ELEMENT.search(found[1])


def manifest_said(folder, name: str | None = None) -> str:
    """What the folder ``folder`` (None: no package) holds as a ROS package manifest, in the
    words a message says when that manifest does not settle its question: "no package.xml or
    manifest.xml"; a package.xml that is not a ROS package manifest (no ``<package>``
    element: another tool's file of that name); given ``name``, a manifest naming another
    package; without it, a package.xml naming no ROS build tool (Drake's model collection:
    ``drake_models``, no catkin or ament) or naming its build tools only under conditions.
    Empty when the manifest answers (the package ``name``; a build tool of one ROS). The one
    wording of "is there a package here", so that a message never says "no package.xml" of a
    folder that has one."""
    found = _manifest_of(Path(folder)) if folder is not None else None
    if found is None:
        return f"no {MANIFESTS_SAID}"
    file, data = found
    if _foreign(found):
        return "a package.xml that is not a ROS package manifest (no <package> element)"
    declared = package_name(Path(folder))
    if name is not None:
        return "" if declared == name else f"its {file} naming package '{declared}'"
    if file != "package.xml":
        return ""  # rosbuild: ROS 1's
    if _CONDITIONED.search(data):
        return f"a package.xml ('{declared}') naming its build tools under conditions"
    return "" if _CATKIN.search(data) or _AMENT.search(data) else \
        f"a package.xml ('{declared}') naming no ROS build tool (catkin, ament)"


def declaring_package(path, package: str) -> tuple[str | None, bool, str]:
    """(the name of the package holding the file ``path``, whether its package.xml declares
    ``package`` as a dependency, the manifest's file name: ``package.xml``, or rosbuild's
    ``manifest.xml``); (None, False, "package.xml") outside a package, or in a folder whose
    package.xml is not a ROS package manifest (:func:`manifest_said`). A package not found that
    it declares is one not installed here, the environment's; one it does not declare is a
    misspelt name or a dependency rosdep would not install (xacro's ``$(find)``, a mesh's
    ``package://``)."""
    folder = package_of(path) if path else None
    found = _manifest_of(folder) if folder is not None else None
    if found is None or _foreign(found):
        return None, False, "package.xml"  # (another tool's package.xml: rosdep reads none)
    return package_name(folder), package in (declared_dependencies(folder) or ()), found[0]


def package_references(data: bytes) -> list[tuple[int, int, str]]:
    """(line, column, package name) of each package a robot file names literally, by
    ``$(find NAME)`` or ``package://NAME/``, outside XML comments and outside xacro's
    ``<xacro:if>``/``<xacro:unless>`` blocks (used in some configurations only: an optional
    dependency, often one that would be circular); a name built by xacro (``$(find ${pkg})``)
    is not one."""
    found, line, counted = [], 1, 0
    for at, name in _named(_COMMENT.sub(_blanked, data)):
        line += lines_between(data, counted, at)  # the lines since the last one
        counted = at
        column = len(data[line_start(data, at):at].decode("utf-8", "replace")) + 1
        found.append((line, column, name.decode()))
    return found


def _named(text: bytes) -> list[tuple[int, bytes]]:
    """(offset, name) of each package ``text`` names literally outside xacro's conditional
    blocks, in order. Without a conditional tag (most robot files), the ``$(find`` and
    ``package://`` references are found apart, each by a pattern that starts with its words
    (quick to look for; one pattern whose third branch starts at every "<" cost the corpus's
    URDFs 24 ms): neither holds the other, so the same matches."""
    if not any(word in text for word in _CONDITIONAL):
        found = [(match.start(), match.group(1)) for pattern in (_FIND, _PACKAGE_URI)
                 for match in pattern.finditer(text)]
        found.sort()
        return found
    found, depth = [], 0
    for match in _REFERENCE.finditer(text):
        if match.group(4):  # a conditional block opens or closes
            if not match.group(5):
                depth += -1 if match.group(3) else 1
        elif depth <= 0:
            found.append((match.start(), match.group(1) or match.group(2)))
    return found


def _blanked(comment: re.Match) -> bytes:
    """A comment as as many spaces, its line breaks kept: lines and columns stay where they
    were."""
    return comment.group(0).translate(_BLANKS)


_BLANKS = bytes(0x0A if c == 0x0A else 0x20 for c in range(256))  # a byte's blank


def package_uri_parts(uri: str) -> tuple[str, str]:
    """(package name, path inside it) of a ``package://NAME/PATH`` URI.

    ``package:///NAME/PATH`` (an empty package name, as Pinocchio users write) is read the way
    Pinocchio's ``retrieveResourcePath`` reads it: the path after ``package://`` is looked up
    below each package directory, so its first folder is the package (ROS's resource_retriever
    cannot resolve it; the linter warns)."""
    name, _, tail = uri[len("package://"):].partition("/")
    if not name:
        name, _, tail = tail.lstrip("/").partition("/")
    return name, tail


def find_form(uri: str) -> str:
    """A ``package://NAME/PATH`` URI as xacro and launch files name the file: ``$(find
    NAME)/PATH``, what to write where only a path is read (a xacro:include, a Gazebo plugin's
    <parameters>)."""
    name, tail = package_uri_parts(uri)
    return f"$(find {name})/{tail}"


@per_run
def packages_below(root: Path) -> dict[str, Path]:
    """Package name -> folder of each package.xml (or manifest.xml) below ``root`` (its folders walked as
    :class:`PackageResolver` scans them: bounded, links not followed; the first of a name
    wins). Launch files' ``$(find pkg)`` resolve only to these: never outside the repository."""
    found: dict[str, Path] = {}
    for folder, regular in _package_folders(root):
        folder = Path(folder)
        # (a name: its manifest was read, as a regular file: the record holds that read);
        # one listed as a regular file (no link) of a folder walked is inside ``root``
        name = package_name(folder, None if regular else root)
        if name is not None:
            found.setdefault(name, folder)
    return found


_PACKAGE_WALK = "package.xml|manifest.xml|[!.]*/"


def _package_folders(root: Path) -> list[tuple[str, bool]]:
    """(folder, whether its manifests are listed as regular files) for the folders below
    ``root`` whose listing names a package.xml or manifest.xml, breadth first, as
    :func:`walk` lists them for package.xml (as _walk_dirs walks, each folder listed once for
    its subfolders and its package.xml): from the listings of the repository's launch-file
    walk when this run made it (:func:`~urdftool.description.files.tree_made`: the same
    folders, listed for more names; its record replayed), else walked."""
    depth, most = _MAX_SCAN_DEPTH + 1, _MAX_SCAN_DIRS + 1
    listings = tree_made(root, _PACKAGE_WALK, depth, SKIP_DIRS)
    if listings is None:
        return [(folder, regular) for folder, entries in walk(
            root, _PACKAGE_WALK, depth, SKIP_DIRS, breadth_first=True, most=most)
                for regular in [_manifests_regular(entries)] if regular is not None]
    found, sep = [], os.sep
    pending, listed = deque([(os.fspath(root), 0)]), 0
    while pending:
        folder, level = pending.popleft()
        entries = listings[folder]
        listed += 1
        regular = _manifests_regular(entries)
        if regular is not None:
            found.append((folder, regular))
        if listed == most:
            break
        if entries and level + 1 < depth:
            # (a folder below named as walk names it: its parent's name, a separator, its own)
            base, level = (folder if folder.endswith(sep) else folder + sep), level + 1
            pending.extend([(base + name, level) for name, kind in entries
                            if kind == "folder" and name not in SKIP_DIRS and name[:1] != "."])
    return found


def _manifests_regular(entries) -> bool | None:
    """Of a folder's listing: None when it names no manifest (:data:`MANIFESTS`), else whether
    every manifest it names is a regular file."""
    kinds = [kind for name, kind in entries if name in MANIFESTS]
    return all(kind == "file" for kind in kinds) if kinds else None


_EXPORT = re.compile(rb"<export\b[^<>]*>((?:[^<]|<(?!/?export\b))*+)</export>")
_PLUGIN = re.compile(rb"\splugin\s*=\s*[\"']\$\{prefix\}/([^\"']+)[\"']")
_CLASS = re.compile(rb"<class\b([^<>]*)>")
_CLASS_NAME = re.compile(rb"\s(name|type)\s*=\s*[\"']([^\"']+)[\"']")


@per_run
def exported_classes(root: Path) -> frozenset[str]:
    """The pluginlib class names the packages below ``root`` export: each package.xml's
    ``<export><TAG plugin="${prefix}/FILE.xml"/>`` names a plugin description file in the
    package, whose ``<class name="...">`` (or, with no name, its ``type``, as pluginlib looks
    it up) a controller manager, the resource manager or MoveIt can load. A vendor's package
    exports classes in another package's namespace (Pilz's
    ``position_controllers/PilzJointTrajectoryController``)."""
    found: set[str] = set()
    for folder in packages_below(root).values():
        manifest = manifest_text(folder)
        for export in _EXPORT.findall(manifest or b""):
            for relative in _PLUGIN.findall(export):
                description = folder / relative.decode("utf-8", "replace")
                if not inside(description, folder):
                    continue
                try:
                    text = _COMMENT.sub(b"", read_regular(description, _MAX_MANIFEST,
                                                          as_="plugin description"))
                except OSError:
                    continue
                for attributes in _CLASS.findall(text):
                    named = dict(_CLASS_NAME.findall(attributes))
                    name = named.get(b"name") or named.get(b"type")
                    if name:
                        found.add(name.decode("utf-8", "replace"))
    return frozenset(found)


def _split_path(value: str) -> list[str]:
    """The entries of a search path, each once (as written, ``.`` and ``//`` folded): a
    ``setup.bash`` sourced twice repeats them, and ``/usr`` given 5,000 times was walked 5,000
    times (stopped at the 60 s budget)."""
    return list(dict.fromkeys(os.path.normpath(entry) for entry in value.split(os.pathsep)
                              if entry))


def _find_below(folder: Path, name: str, depth: int) -> Path | None:
    if package_name(folder) == name:
        return folder
    for candidate in _walk_dirs(folder, max_depth=depth):
        if package_name(candidate) == name:
            return candidate
    return None


def _walk_dirs(root: Path, max_depth: int = _MAX_SCAN_DEPTH, links: list | None = None):
    """Folders below root, breadth first, bounded in depth and count, never following links
    (appended to ``links`` when given), never entering a hidden folder (as catkin's and
    colcon's package crawlers do; ``.urdftool_cache`` among them: the result cache appearing
    beside the packages is no change to where they are)."""
    frontier = [os.fspath(root)]
    seen = 0
    for _ in range(max_depth + 1):
        next_frontier = []
        for folder in frontier:
            yield Path(folder)  # (listed once yielded: a caller may stop there)
            seen += 1
            if seen > _MAX_SCAN_DIRS:
                return
            entries = listing(folder, "[!.]*/")  # subfolders and links, not hidden; sorted
            next_frontier.extend(os.path.join(folder, name) for name, kind in entries
                                 if kind == "folder" and name not in SKIP_DIRS)
            if links is not None:
                links.extend(Path(folder, name) for name, kind in entries if kind == "link")
        frontier = next_frontier
