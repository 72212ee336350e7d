"""Find ROS packages without ROS, for ``$(find pkg)`` and ``package://pkg/...``.

Search order: ``--package NAME=PATH``, ROS_PACKAGE_PATH, AMENT_PREFIX_PATH (``share/NAME``),
package.xml files walking up from the input to the repository root (a folder that is the
package, or has it as a child), then package.xml files below the repository root (the nearest
folder holding ``.git``). A folder or package.xml in the repository that is a symbolic link
leading outside it is not a package: it is not read, and the not-found message says so. Without
a ``.git`` above the input there is no repository to keep to, and the walk goes up to ``/``.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from urdftool.errors import PackageNotFound
from urdftool.description.files import enclosing_root, inside, read_regular, repository_root
from urdftool.description.run_memo import per_run

_NAME = re.compile(rb"<name>\s*([^<\s]+)\s*</name>")
SKIP_DIRS = {  # tool and build folders no walk enters
    ".git", ".venv", "venv", "node_modules", "__pycache__", "build", "install", "log"}
_MAX_SCAN_DEPTH = 6
_MAX_SCAN_DIRS = 20000
_MAX_MANIFEST = 1024 * 1024  # [bytes]


def package_name(folder: Path, root: Path | None = None) -> str | None:
    """The ``<name>`` a folder's package.xml declares, or None when it has none (or, given
    ``root``, when the package.xml leads outside ``root``: then it is not opened)."""
    manifest = folder / "package.xml"
    if root is not None and not inside(manifest, root):
        return None
    try:
        head = read_regular(manifest, _MAX_MANIFEST)
    except OSError:
        return None
    match = _NAME.search(head)
    return match.group(1).decode("utf-8", "replace") if match else folder.name


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


def link_out(path) -> tuple[str, Path] | None:
    """(where it leads, the repository) when ``path`` is, or lies in a folder that is, a
    symbolic link leading outside the repository that holds it as named; None otherwise. A
    file named in a repository is read only when it stays there: a link planted in a pull
    request cannot make urdftool read, and print parts of, a file elsewhere."""
    root = containment_root(Path(os.path.abspath(path)).parent)
    return None if inside(path, root) else (os.path.realpath(path), root)


class PackageResolver:
    """Maps package names to folders; one instance serves xacro and mesh look-ups."""

    def __init__(self, explicit: dict[str, Path] | None = None, start: Path | None = None,
                 environ: dict[str, str] | None = None):
        # A relative folder is relative to the working directory (where the user typed it),
        # never to the file that includes $(find NAME): made absolute here, once.
        self.explicit = {name: Path(path).absolute() for name, path in (explicit or {}).items()}
        self.start = start.resolve() if start else None
        self.environ = os.environ if environ is None else environ
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
                return candidate
        raise PackageNotFound(name, searched)

    def _candidates(self, name: str):
        if name in self.explicit:
            path = self.explicit[name]
            yield (path if path.is_dir() else None), f"--package {name}={path}"
        for entry in _split_path(self.environ.get("ROS_PACKAGE_PATH", "")):
            yield _find_below(Path(entry), name, depth=3), f"ROS_PACKAGE_PATH entry {entry}"
        for prefix in _split_path(self.environ.get("AMENT_PREFIX_PATH", "")):
            share = Path(prefix) / "share" / name
            yield (share if share.is_dir() else None), f"AMENT_PREFIX_PATH {share}"
        if self.start is None:
            return
        root = repository_root(self.start)
        above = f"package.xml above {self.start}" + (f" up to {root}" if root else "")
        yield self._walk_up(name, root), above
        if root is not None:
            yield self._scan(root).get(name), f"package.xml below {root}"
        for link in dict.fromkeys(self._links_out):
            yield None, f"{link} (a symbolic link leading outside {root}; not followed)"

    def _walk_up(self, name: str, root: Path | None) -> Path | None:
        chain = [self.start, *self.start.parents]
        if root is not None:
            chain = chain[:chain.index(root) + 1]
        for folder in chain:
            for candidate in (folder, folder / name):
                if root is not None and not inside(candidate / "package.xml", root):
                    if (candidate / "package.xml").exists():
                        self._links_out.append(candidate)
                    continue
                if package_name(candidate) == name:
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
                                and (link / "package.xml").exists()]
        return self._scanned

    def resolve_uri(self, uri: str, base_dir: Path) -> Path:
        """A mesh or include URI as a path: package://, file:// or relative to ``base_dir``."""
        if uri.startswith("package://"):
            name, tail = package_uri_parts(uri)
            return self.find(name) / tail
        if uri.startswith("file://"):
            return Path(uri[len("file://"):])
        return base_dir / uri


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


def _split_path(value: str) -> list[str]:
    return [entry for entry in value.split(os.pathsep) if entry]


def _find_below(folder: Path, name: str, depth: int) -> Path | None:
    if package_name(folder) == name:
        return folder
    for candidate in _walk_dirs(folder, max_depth=depth):
        if package_name(candidate) == name:
            return candidate
    return None


def _walk_dirs(root: Path, max_depth: int = _MAX_SCAN_DEPTH, links: list | None = None):
    """Folders below root, breadth first, bounded in depth and count, never following links
    (appended to ``links`` when given)."""
    frontier = [root]
    seen = 0
    for _ in range(max_depth + 1):
        next_frontier = []
        for folder in frontier:
            yield folder
            seen += 1
            if seen > _MAX_SCAN_DIRS:
                return
            try:
                entries = sorted(os.scandir(folder), key=lambda e: e.name)
            except OSError:
                continue
            next_frontier.extend(
                Path(entry.path) for entry in entries
                if entry.is_dir(follow_symlinks=False) and entry.name not in SKIP_DIRS
            )
            if links is not None:
                links.extend(Path(entry.path) for entry in entries if entry.is_symlink())
        frontier = next_frontier
