"""Reading and writing files that a stranger's repository may have planted.

Every file urdftool reads goes through :func:`read_regular`: only a regular file, only when it is
not over a size limit (a FIFO, ``/dev/zero`` or a sparse 100 GB file is refused before it is
read). :func:`inside` tells whether a path, links followed, stays in a folder. Every file
urdftool writes goes through :func:`write_file`: the data goes to a temporary file beside the
target, which then replaces it, so a symbolic link planted at the output path is replaced, never
followed.
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


def check_output(path) -> None:
    """UsageError when ``path`` cannot be an output file: its folder is missing, or it is a
    folder. Commands call it before their work, so that a typo costs no time."""
    path = Path(path)
    folder = path.parent
    if not folder.is_dir():
        raise UsageError(f"cannot write '{path}': folder '{folder}' does not exist")
    if path.is_dir() and not path.is_symlink():
        raise UsageError(f"cannot write '{path}': it is a folder; give a file name")


def write_file(path, data: str | bytes) -> None:
    """Write ``data`` (text as UTF-8) to ``path`` through a temporary file beside it that then
    replaces it: a symbolic link at ``path`` is replaced by the file, its target left alone.
    A regular file keeps its permissions. UsageError when the folder is missing, ``path`` is a
    folder, or the system refuses."""
    check_output(path)
    path = Path(path)
    if isinstance(data, str):
        data = data.encode("utf-8")
    try:
        existing = os.lstat(path)
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
                                                 dir=path.parent)
    except OSError as error:
        raise UsageError(f"cannot write '{path}': {error.strerror}") from None
    try:
        with open(descriptor, "wb") as handle:
            handle.write(data)
        os.chmod(temporary, mode)
        os.replace(temporary, path)
    except OSError as error:
        os.unlink(temporary)
        raise UsageError(f"cannot write '{path}': {error.strerror}") from None
