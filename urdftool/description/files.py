"""Reading and writing files that a stranger's repository may have planted.

Every file urdftool reads goes through :func:`read_regular`: only a regular file, only when it is
not over a size limit (a FIFO, ``/dev/zero`` or a sparse 100 GB file is refused before it is
read). :func:`inside` tells whether a path, links followed, stays in a folder;
:func:`repository_root` and :func:`enclosing_root` say which folder that is.

This module is the only writer (``tests/test_writer.py`` fails on any other module that opens a
file for writing, renames, makes or removes one): :func:`write_file` for every output a command
writes, :func:`make_folders` for the folders of the result cache, :func:`temporary_folder` and
:func:`write_new` for a tree urdftool builds itself (a git revision), :func:`scratch_file` for
what a C library prints. An output goes to a
temporary file beside the target, which then replaces it, so a symbolic link planted at the output
path is replaced, never followed; and no output, nor any folder made, is reached through a
symbolic link in a repository that leads outside it (:func:`real_folder`).
"""

from __future__ import annotations

import os
import stat
from contextlib import contextmanager
from contextvars import ContextVar
from pathlib import Path

from urdftool.description.run_memo import per_run
from urdftool.errors import UsageError

DEFAULT_MAX_FILE_SIZE = 16 * 1024 * 1024  # [bytes]


class TooLarge(OSError):
    """A file over the size limit (not read)."""


# (digest function, {absolute path: digest of the bytes last read}) while noting_reads runs
_NOTES: ContextVar[tuple | None] = ContextVar("urdftool_read_notes", default=None)


@contextmanager
def noting_reads(digest):
    """Note ``digest(data)`` of every file :func:`read_regular` reads while the block runs, by
    absolute path (the last read of each), in the dict it yields; a nested block shares the
    outer one's notes. The result cache compares them with the files when it keeps a result:
    a file that changed after it was read is not kept."""
    if (outer := _NOTES.get()) is not None:
        yield outer[1]
        return
    notes: dict[str, str] = {}
    token = _NOTES.set((digest, notes))
    try:
        yield notes
    finally:
        _NOTES.reset(token)


def noted_reads() -> dict[str, str]:
    """The notes of the :func:`noting_reads` block running, or an empty dict."""
    found = _NOTES.get()
    return found[1] if found is not None else {}


def read_regular(name, limit: int = DEFAULT_MAX_FILE_SIZE) -> bytes:
    """A regular file's bytes; OSError for anything else (strerror says why), TooLarge when its
    size is over ``limit`` [bytes]."""
    info = os.stat(name)
    if not stat.S_ISREG(info.st_mode):
        raise OSError(21, "not a regular file", str(name))
    if info.st_size > limit:
        raise TooLarge(27, f"file is {info.st_size} bytes, over the limit of {limit}", str(name))
    # O_NONBLOCK: should the file be swapped for a FIFO after the stat, opening does not hang.
    descriptor = os.open(name, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    with open(descriptor, "rb") as handle:
        if not stat.S_ISREG(os.fstat(descriptor).st_mode):
            raise OSError(21, "not a regular file", str(name))
        # the size it has (a read of limit + 1 bytes allocates that much first), then any more
        data = handle.read(info.st_size + 1)
        if len(data) > info.st_size:  # grew since the stat
            data += handle.read(limit + 1 - len(data))
    if len(data) > limit:
        raise TooLarge(27, f"file is over the limit of {limit} bytes", str(name))
    if (noting := _NOTES.get()) is not None:
        noting[1][os.path.abspath(name)] = noting[0](data)
    return data


def inside(path, folder) -> bool:
    """Whether ``path``, every symbolic link followed, is ``folder`` or below it (itself with
    links followed)."""
    try:
        real = real_path(os.fspath(path))
        base = real_path(os.fspath(folder))
    except (OSError, ValueError):
        return False
    return real == base or real.startswith(base.rstrip(os.sep) + os.sep)


@per_run
def repository_root(start: Path) -> Path | None:
    """The nearest ancestor of ``start`` (itself included) holding a ``.git`` entry: the
    repository, by urdftool's own rule (git's discovery is never asked)."""
    start = Path(start)
    for folder in [start, *start.parents]:
        if (folder / ".git").exists():
            return folder
    return None


@per_run
def enclosing_root(folder: Path) -> Path | None:
    """The folder whose files a stranger may have written, holding ``folder``: its repository
    (:func:`repository_root`); without one, the nearest folder above holding a package.xml;
    None when there is neither (the user's own folders)."""
    folder = Path(os.path.abspath(folder))
    return repository_root(folder) or next(
        (f for f in [folder, *folder.parents] if (f / "package.xml").is_file()), None)


@per_run
def real_path(path: str) -> str:
    """``os.path.realpath(path)``, answered once per run (see :mod:`.run_memo`). A file that
    is not a link is its folder's real path (itself answered once per run) and its name: the
    meshes of a package share a few folders, and realpath would walk every component of each
    (``lstat`` calls in a check of the corpus's 46 URDFs: 4,240 before, 2,034 so)."""
    folder, name = os.path.split(path)
    if not folder or name in ("", ".", ".."):
        return os.path.realpath(path)
    try:
        if stat.S_ISLNK(os.lstat(path).st_mode):
            return os.path.realpath(path)
    except OSError:  # missing, or not reachable: realpath's own answer
        return os.path.realpath(path)
    return os.path.join(real_path(folder), name)


def real_folder(folder) -> str:
    """The folder ``folder`` names, its symbolic links resolved one by one as the system
    resolves them (a ``..`` after a link goes up from where the link leads). UsageError when
    one of them lies in a repository (or package, see :func:`enclosing_root`) and leads
    outside it: a link committed in a pull request (``reports -> /home/runner``) cannot make
    urdftool write, or make folders, elsewhere. Links outside any repository are the user's
    own and followed. The message names the link, never where it leads."""
    named = os.fspath(folder)
    current = os.path.abspath(os.sep)
    for part in os.path.join(os.getcwd(), named).split(os.sep):
        if part in ("", "."):
            continue
        if part == "..":
            current = os.path.dirname(current)
            continue
        candidate = os.path.join(current, part)
        if not os.path.islink(candidate):
            current = candidate
            continue
        target = os.path.realpath(candidate)
        root = enclosing_root(Path(current))
        if root is not None and not inside(target, root):
            raise UsageError(f"cannot write in '{named}': '{candidate}' is a symbolic link "
                             f"leading outside the repository ({root}); not followed")
        current = target
    return current


def check_output(path) -> str:
    """The real folder an output file ``path`` goes to (:func:`real_folder`); UsageError when
    it cannot be an output file: its folder is missing, leads outside its repository through a
    symbolic link, or it is a folder. Commands call it before their work, so that a typo or a
    planted link costs no time."""
    path = Path(path)
    folder = path.parent
    if not folder.is_dir():
        raise UsageError(f"cannot write '{path}': folder '{folder}' does not exist")
    real = real_folder(folder)
    if path.is_dir() and not path.is_symlink():
        raise UsageError(f"cannot write '{path}': it is a folder; give a file name")
    return real


def write_file(path, data: str | bytes) -> None:
    """Write ``data`` (text as UTF-8) to ``path`` through a temporary file beside it that then
    replaces it: a symbolic link at ``path`` is replaced by the file, its target left alone.
    A regular file keeps its permissions. UsageError when the folder is missing or reached
    through a link leading outside its repository, ``path`` is a folder, or the system
    refuses."""
    folder = check_output(path)
    path = Path(path)
    target = os.path.join(folder, path.name)
    if isinstance(data, str):
        data = data.encode("utf-8")
    try:
        existing = os.lstat(target)
    except OSError:
        existing = None
    if existing is not None and stat.S_ISREG(existing.st_mode):
        mode = stat.S_IMODE(existing.st_mode)
    else:
        umask = os.umask(0)
        os.umask(umask)
        mode = 0o666 & ~umask
    import tempfile  # only where a file is written (a re-run from the cache reads)

    try:
        descriptor, temporary = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp",
                                                 dir=folder)
    except OSError as error:
        raise UsageError(f"cannot write '{path}': {error.strerror}") from None
    try:
        with open(descriptor, "wb") as handle:
            handle.write(data)
        os.chmod(temporary, mode)
        os.replace(temporary, target)
    except OSError as error:
        os.unlink(temporary)
        raise UsageError(f"cannot write '{path}': {error.strerror}") from None


def make_folders(folder, mode: int = 0o777) -> None:
    """``os.makedirs(folder, mode, exist_ok=True)`` in the folder :func:`real_folder` finds;
    UsageError when a link on the way leads outside its repository; OSError when the system
    refuses."""
    os.makedirs(real_folder(folder), mode=mode, exist_ok=True)


@contextmanager
def temporary_folder(prefix: str):
    """A new private folder in the system's temporary folder, removed with everything in it
    when the block ends."""
    import shutil
    import tempfile

    folder = tempfile.mkdtemp(prefix=prefix)
    try:
        yield Path(folder)
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def scratch_file():
    """A new file without a name (removed as soon as it is made), open for reading and
    writing: where a C library's messages to file descriptor 2 are caught."""
    import tempfile

    return tempfile.TemporaryFile()


def _new_path(root: Path, relative: str) -> str:
    """``root/relative`` for a relative path of plain names (no ``..``, ``.``, empty or
    absolute part, no NUL): ValueError otherwise. Its folders are made below ``root``."""
    parts = relative.split("/")
    if not relative or "\0" in relative or any(p in ("", ".", "..") for p in parts):
        raise ValueError(f"not a plain relative path: {relative!r}")
    folder = os.path.join(root, *parts[:-1])
    os.makedirs(folder, mode=0o700, exist_ok=True)
    if os.path.realpath(folder) != os.path.join(os.path.realpath(root), *parts[:-1]):
        raise ValueError(f"a folder of {relative!r} is a link")
    return os.path.join(folder, parts[-1])


def write_new(root: Path, relative: str, data: bytes) -> None:
    """Create the file ``relative`` (``/``-separated plain names) below ``root``, a folder
    made by :func:`temporary_folder`, with ``data``; never through a link, never over an
    existing file. ValueError for a name that is not plain; OSError when the system refuses."""
    target = _new_path(root, relative)
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0)
    with open(os.open(target, flags, 0o600), "wb") as handle:
        handle.write(data)


def link_new(root: Path, relative: str, points_to: str) -> bool:
    """Create the symbolic link ``relative`` below ``root`` (as :func:`write_new`) pointing to
    ``points_to`` when that, read as written, stays below ``root``; False, and nothing made,
    otherwise. Links made together can still combine to lead out (``s -> .`` and
    ``t -> s/s/..``): :func:`remove_links_out` once they are all made."""
    target = _new_path(root, relative)
    if os.path.isabs(points_to) or "\0" in points_to:
        return False
    leads = os.path.normpath(os.path.join(os.path.dirname(target), points_to))
    if not (leads + os.sep).startswith(os.path.normpath(root) + os.sep):
        return False
    os.symlink(points_to, target)
    return True


def remove_links_out(root: Path, relatives: list[str]) -> list[str]:
    """Remove those of the links ``relatives`` below ``root`` that, every link followed, lead
    outside it (until none does: a removal can change where others lead); the ones left."""
    base = os.path.realpath(root) + os.sep
    left = list(relatives)
    while True:  # realpath itself, not the per-run memo of inside(): the links change here
        out = [r for r in left
               if not os.path.realpath(os.path.join(root, *r.split("/"))).startswith(base)]
        if not out:
            return left
        for relative in out:
            os.unlink(os.path.join(root, *relative.split("/")))
        left = [r for r in left if r not in out]
