"""The one door to the file system: reading a stranger's repository, recording what was read,
and writing.

Every question the description layer and the linter ask of the file system goes through
this module, and each function notes its question and answer in the record of the block
running (:mod:`.record`): what a check read, searched, probed and followed is known because
there is no other way to read. ``tests/description/test_files.py`` fails when a module under
``urdftool/description`` or ``urdftool/lint`` opens, stats, lists or globs files itself.

- :func:`read_regular`: a file's bytes, only a regular file, only when it is not over a size
  limit (a FIFO, ``/dev/zero`` or a sparse 100 GB file is refused before it is read), with
  what it was read as; inside :func:`unsaved`, the buffer an editor holds for a file instead
  of the disk's bytes (the language server's overlay, for one check);
- :func:`kind_of` and :func:`identity`: what is at a path;
- :func:`listing`: the entries of a folder (an include's pattern is expanded with it);
  :func:`walk`: those of a folder and of the folders below it;
- :func:`real_path` and :func:`inside`: where links lead, whether a path stays in a folder;
  :func:`repository_root` and :func:`enclosing_root` say which folder that is;
- :func:`environ`: an environment variable; :func:`env_allowed`: whether a robot may name
  them (and files outside its repository), the safe mode under CI (:func:`under_ci`).

:func:`holds` compares an entry of a record with the disk, by the same functions, unrecorded:
the result cache asks it, and reads nothing else of a robot's. urdftool's own files (the
cache's entries, its key, urdftool's source and data) are read by :func:`read_own`,
:func:`own_folder` and :func:`tree_stamp`, never recorded.

This module is the only writer (``tests/test_writer.py`` fails on any other module that opens a
file for writing, renames, makes or removes one): :func:`write_file` for every output a command
writes, :func:`make_folders` for the folders of the result cache, :func:`temporary_folder` and
:func:`write_new` for a tree urdftool builds itself (a git revision), :func:`scratch_file` for
what a C library prints. An output goes to a
temporary file beside the target, which then replaces it, so a symbolic link planted at the output
path is replaced, never followed; and no output, nor any folder made, is reached through a
symbolic link in a repository that leads outside it (:func:`real_folder`). Writing records
nothing.
"""

from __future__ import annotations

import collections
import errno
import fnmatch
import functools
import os
import re
import stat
import time
from _thread import _local  # (threading.local: threading itself not imported for it)
from collections.abc import Mapping
from contextlib import contextmanager
from pathlib import Path

from urdftool.description import record as records
from urdftool.description.record import ENV, PROBE, READ, REAL, RESOLVED, SEARCH, Read
from urdftool.description.run_memo import answering, per_run
from urdftool.errors import UsageError

DEFAULT_MAX_FILE_SIZE = 16 * 1024 * 1024  # [bytes]
RACY_NS = 2_000_000_000  # [ns] a file changed this recently may change again unseen


class TooLarge(OSError):
    """A file over the size limit (not read); ``size``: its size [bytes], as far as known."""

    def __init__(self, *args, size: int | None = None):
        super().__init__(*args)
        self.size = size


def read_regular(name, limit: int = DEFAULT_MAX_FILE_SIZE, as_: str = "file") -> bytes:
    """A regular file's bytes; OSError for anything else (strerror says why), TooLarge when its
    size is over ``limit`` [bytes]. Recorded as read as ``as_`` (robot, include, mesh, ...).
    Inside :func:`unsaved`, a file open in an editor is read from its buffer."""
    buffer = _buffer_of(name)
    if buffer is not None:
        return _read_buffer(name, buffer, limit, as_)
    return _read_disk(name, limit, as_)


def _read_disk(name, limit: int, as_: str) -> bytes:
    try:
        info = os.stat(name)
    except OSError as error:
        _note_read(name, as_, None, None, error.strerror or type(error).__name__)
        raise
    try:
        data, info = _read(name, info, limit, as_)
    except OSError as error:
        _note_read(name, as_, info, None, error.strerror or type(error).__name__)
        raise
    _note_read(name, as_, info, data, None)
    return data


def _not_regular(info: os.stat_result, name) -> OSError:
    """The error of a file that is not a regular file, saying what it is when a folder (a
    path built from an empty argument: motoman's load_yaml('') read the macro's folder)."""
    what = "a folder, not a regular file" if stat.S_ISDIR(info.st_mode) else "not a regular file"
    return OSError(21, what, str(name))


def _read(name, info, limit: int, as_: str = "file") -> tuple[bytes, os.stat_result]:
    if not stat.S_ISREG(info.st_mode):
        raise _not_regular(info, name)
    if info.st_size > limit:
        raise TooLarge(27, f"file is {info.st_size} bytes, over the limit of {limit}", str(name),
                       size=info.st_size)
    # O_NONBLOCK: should the file be swapped for a FIFO after the stat, opening does not hang.
    descriptor = os.open(name, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    try:  # (read from the descriptor: a file object asked the system twice more, fstat and isatty)
        info = os.fstat(descriptor)  # the file read, whatever the name leads to now
        if not stat.S_ISREG(info.st_mode):
            raise _not_regular(info, name)
        # the size it has (a read of limit + 1 bytes allocates that much first), then any more
        data = _read_up_to(descriptor, info.st_size + 1)
        if len(data) > info.st_size:  # grew since the stat
            data += _read_up_to(descriptor, limit + 1 - len(data))
    finally:
        os.close(descriptor)
    if len(data) > limit:
        raise TooLarge(27, f"file is over the limit of {limit} bytes", str(name), size=len(data))
    _READ_HERE.setdefault(_which_file(info), {}).setdefault(os.path.abspath(name), set()).add(as_)
    return data, info


def _read_up_to(descriptor: int, size: int) -> bytes:
    """``size`` bytes read from ``descriptor``, fewer at the end of the file."""
    data = os.read(descriptor, size)
    if len(data) < size and data:  # (a read may give less than asked before the end)
        parts = [data]
        while size > (got := sum(map(len, parts))) and (more := os.read(descriptor, size - got)):
            parts.append(more)
        data = b"".join(parts)
    return data


# every regular file this process read (:func:`_which_file`) -> each name it was read by -> what
# it was read as there (robot, include, companion SRDF, ...; a worker's: "read by a worker"):
# what an output must not replace (:func:`_reads_replaced`)
_READ_HERE: dict[tuple, dict[str, set[str]]] = {}
BY_A_WORKER = "read by a worker"


def _which_file(info: os.stat_result) -> tuple:
    """Which file ``info`` is, by any name: device, inode and change time (an inode freed and
    given to a new file in a long-lived process is not the file read)."""
    return info.st_dev, info.st_ino, info.st_ctime_ns


def read_elsewhere(paths) -> None:
    """Note the files at ``paths`` as read by this process's command (a worker read them for
    it: the paths of its results' records), for :func:`write_file`'s refusal."""
    for path in paths:
        try:
            info = os.stat(path)
        except (OSError, ValueError):
            continue
        if stat.S_ISREG(info.st_mode):
            _READ_HERE.setdefault(_which_file(info), {}).setdefault(
                os.path.abspath(path), set()).add(BY_A_WORKER)


def _note_read(name, as_: str, info, data: bytes | None, failure: str | None) -> None:
    if records.active() is None:
        return
    stamp = "" if info is None else _stamp(info)
    _note(name, as_, stamp, None if info is None else (
        info.st_size if data is None else len(data)), data, failure)


def _note(name, as_: str, stamp: str | None, size: int | None, data: bytes | None,
          failure: str | None) -> None:
    path = os.path.abspath(name)
    records.note(READ, path, Read(_real_path(path), stamp, size, None if data is None or
                                  not records.digests_kept() else digest(data), failure), as_)


# ---- unsaved buffers: what an editor holds, read in place of the disk --------------------

class _Unsaved(_local):
    """The buffers of the blocks running in this thread (:func:`unsaved`): real path -> (the
    path the buffer was given as, its bytes, the set its block yields)."""

    buffers: dict | None = None


_UNSAVED = _Unsaved()


@contextmanager
def unsaved(buffers: Mapping[str, bytes | str]):
    """For the block, :func:`read_regular` reads the file at each path of ``buffers`` (path ->
    its content, unsaved in an editor) from the buffer instead of the disk; yields the set of
    those paths read so far.

    A buffer stands for the file it names, links followed: a read of any name leading to that
    file reads it. It is read only where the check reads the file from disk (whoever reads
    decides first whether the path may be read: inside the repository, no link out), under the
    same size limit; nothing else about the file system changes (a buffer of a file not on
    disk is found by no listing or probe). The record notes a buffer read by the digest of its
    bytes and no stamp, so a record made from buffers holds only while the disk has the same
    bytes (:func:`holds`): a result from buffers is never taken for the disk's. Blocks nest:
    an inner block's buffers are added to the outer's (its own win)."""
    served: set[str] = set()
    table = dict(_UNSAVED.buffers or {})
    for path, content in buffers.items():
        data = content.encode("utf-8", "replace") if isinstance(content, str) else bytes(content)
        table[os.path.realpath(os.path.abspath(path))] = (path, data, served)
    outer, _UNSAVED.buffers = _UNSAVED.buffers, table
    try:
        yield served
    finally:
        _UNSAVED.buffers = outer


def _buffer_of(name) -> tuple | None:
    if not _UNSAVED.buffers:
        return None
    return _UNSAVED.buffers.get(_real_path(os.path.abspath(name)))


def _read_buffer(name, buffer: tuple, limit: int, as_: str) -> bytes:
    given, data, served = buffer
    if len(data) > limit:
        message = f"file is {len(data)} bytes, over the limit of {limit}"
        if records.active() is not None:
            _note(name, as_, None, len(data), None, message)
        raise TooLarge(27, message, str(name), size=len(data))
    served.add(given)
    if records.active() is not None:
        _note(name, as_, None, len(data), data, None)
    return data


def digest(data: bytes) -> str:
    """The digest records keep of the bytes read (only the result cache asks for them: hashlib,
    which loads OpenSSL, is imported then)."""
    import hashlib

    return hashlib.blake2b(data, digest_size=20).hexdigest()


def _stamp(info: os.stat_result) -> str | None:
    """A file's identity and change times, as git's index keeps them: while they are the same
    the content is taken to be (the change time cannot be set back by a user). None when it
    changed in the last :data:`RACY_NS` (file times tick coarsely, by milliseconds to
    seconds, so a file written again within the same tick keeps its times: git calls it
    racily clean); its content must be compared instead."""
    if time.time_ns() - max(info.st_mtime_ns, info.st_ctime_ns) < RACY_NS:
        return None
    return f"{info.st_dev}:{info.st_ino}:{info.st_size}:{info.st_mtime_ns}:{info.st_ctime_ns}"


def _stamp_at(path: str) -> str | None:
    """:func:`_stamp` of what is at ``path`` now; '' when nothing is."""
    try:
        return _stamp(os.stat(path))
    except (OSError, ValueError):
        return ""


def kind_of(path, follow: bool = True) -> str:
    """What is at ``path``: 'file' (a regular file), 'folder', 'other', or '' for nothing
    (or nothing reachable); with ``follow`` false a symbolic link is 'link', not where it
    leads."""
    found = _kind(os.fspath(path), follow)
    records.note(PROBE, (os.path.abspath(path), follow), found)
    return found


def unreachable(path) -> str:
    """Why nothing is at ``path`` for :func:`kind_of`, in words: 'does not exist', or what
    the system said when it could not look (a folder on the way it may not search, a name
    too long) — not 'does not exist' for a file that may well be there."""
    try:
        os.stat(path)
    except FileNotFoundError:  # a link to nothing too
        return "does not exist"
    except NotADirectoryError:
        return "does not exist (a part of it is a file)"
    except OSError as error:
        return f"cannot be reached: {(error.strerror or str(error)).lower()}"
    except ValueError:
        return "does not exist (a name with a NUL character)"
    return "does not exist"


def _kind(path: str, follow: bool) -> str:
    try:
        mode = (os.stat if follow else os.lstat)(path).st_mode
    except (OSError, ValueError):
        return ""
    return _kind_of_mode(mode)


def _kind_of_mode(mode: int) -> str:
    if stat.S_ISREG(mode):
        return "file"
    if stat.S_ISDIR(mode):
        return "folder"
    return "link" if stat.S_ISLNK(mode) else "other"


def identity(path) -> tuple | None:
    """(device, inode, size, modification time [ns]) of the regular file at ``path``, links
    followed, for keys of what is remembered of it; None when there is none. Recorded as
    :func:`kind_of` (its content is recorded by whoever reads it)."""
    found = identity_or_why(path)
    return found if isinstance(found, tuple) else None


def owner(path) -> int | None:
    """The user id owning the file at ``path`` (links followed), or None when it cannot be
    looked at: whose file it is, for a file urdftool reads only when it is the user's
    (:func:`urdftool.lint.settings.foreign`)."""
    try:
        return os.stat(path).st_uid
    except (OSError, ValueError):
        return None


def identity_or_why(path) -> tuple | str:
    """:func:`identity` of the regular file at ``path``; else why there is none, in words: ''
    for nothing there (no entry, or a link to nothing), else what is there instead ('a
    folder', 'a named pipe', 'a device', 'a socket') or why it cannot be reached (a link loop,
    a folder on the way it may not search). Recorded as :func:`identity`, by the same one
    look."""
    why = ""
    try:
        info = os.stat(path)
    except FileNotFoundError:
        info = None
    except (OSError, ValueError) as error:
        info = None
        why = f"cannot be reached: {(getattr(error, 'strerror', None) or str(error)).lower()}"
    kind = "" if info is None else _kind_of_mode(info.st_mode)
    records.note(PROBE, (os.path.abspath(path), True), kind)
    if kind == "file":
        return info.st_dev, info.st_ino, info.st_size, info.st_mtime_ns
    if info is None:
        return why
    mode = info.st_mode
    return "a folder" if kind == "folder" else "a named pipe" if stat.S_ISFIFO(mode) else \
        "a socket" if stat.S_ISSOCK(mode) else "a device"


def no_file_there(path) -> str:
    """Why no regular file is at ``path``, as words following its name in a message: 'does not
    exist', 'is a folder' ('a named pipe', 'a device', 'a socket'), or 'cannot be reached:
    why' (:func:`identity_or_why`'s one look): a path where something else is was said "not
    found" (a mesh that is a named pipe, a plugin's parameters file that is a folder)."""
    why = identity_or_why(path)
    if isinstance(why, tuple):  # (a regular file now: it appeared since the first look)
        return "was not a file when looked at"
    return "does not exist" if not why else why if why.startswith("cannot") else f"is {why}"


def listing(folder, pattern: str = "*") -> list[tuple[str, str]]:
    """(name, kind) of the entries of ``folder`` whose name matches ``pattern``, sorted by
    name: alternatives separated by ``|``, each an fnmatch pattern (case-sensitive), one ending
    in ``/`` matching only folders and links. kind as ``lstat`` says ('file', 'folder',
    'link', 'other'): links are not followed. Empty when ``folder`` is no readable folder;
    recorded as such (a file appearing there later changes the answer)."""
    folder = os.path.abspath(folder)
    found = _listing(folder, pattern)
    records.note(SEARCH, (folder, pattern), (_real_path(folder), found))
    return list(found or ())


def walk(root, pattern: str, depth: int, skip=frozenset(), breadth_first: bool = False,
         most: int = 0):
    """(folder, its :func:`listing` for ``pattern``) for ``root`` and the folders below it,
    ``depth`` levels at most, each listing recorded as :func:`listing` records it; a folder is
    entered when ``pattern`` lists it (as a folder, never a link), is not hidden and its name
    is not in ``skip``. Depth first in sorted order, or ``breadth_first``: level by level,
    the folders of a level in the order of their parents, each parent's in sorted order; at
    most ``most`` folders when given. A folder is named as text, ``root`` joined with the
    names below it; where each leads is its parent's and its name (it is no link), not asked
    again of the system: one repository's hundreds of folders, each listed once."""
    selected = _selected(pattern)
    top = os.fspath(root)
    absolute = os.path.abspath(top)
    named = (lambda folder: folder) if absolute == top else (  # (as the caller named it)
        lambda folder: top if folder == absolute else os.path.join(top, os.path.relpath(
            folder, absolute)))
    pending = collections.deque([(absolute, _real_path(absolute), 0)])
    take, note, listed = pending.popleft if breadth_first else pending.pop, records.note, 0
    real_path_of, entries_of = answering(_real_path), answering(_entries)
    while pending:
        folder, real, level = take()
        if level:
            real = real_path_of(folder, _same, real)
        entries = entries_of(folder, _entries.__wrapped__, folder)
        found = None if entries is None else selected(entries)
        note(SEARCH, (folder, pattern), (real, found))
        yield named(folder), list(found or ())
        listed += 1
        if listed == most:
            return
        if found and level + 1 < depth:
            # (a name listed holds no separator: joined as os.path.join joins it)
            base = folder if folder.endswith(os.sep) else folder + os.sep
            under = real if real.endswith(os.sep) else real + os.sep
            level += 1
            below = [(base + name, under + name, level) for name, kind in found
                     if kind == "folder" and name not in skip and name[:1] != "."]
            pending.extend(below if breadth_first else reversed(below))


@per_run
def tree(root, pattern: str, depth: int, skip: frozenset = frozenset()) -> tuple:
    """Every (folder, its listing) :func:`walk` gives (depth first, ``root`` named as
    given), each listing a tuple: the whole walk, once per run, its record replayed to each
    later asker. A later walk of fewer names of the same folders takes these listings
    (:func:`tree_made`) rather than listing every folder again."""
    found = tuple((folder, tuple(entries)) for folder, entries in walk(root, pattern, depth, skip))
    _trees_made(os.path.abspath(root)).append((root, pattern, depth, skip))
    return found


@per_run
def _trees_made(root: str) -> list:
    """(root as named, pattern, depth, skip) of each :func:`tree` of the folder ``root``
    (absolute) walked in this run: one list a run, grown by :func:`tree` (none outside a run)."""
    return []


def tree_made(root, pattern: str, depth: int, skip: frozenset = frozenset()) -> dict | None:
    """Folder -> its listing, from a :func:`tree` of ``root`` (named alike) walked in this run
    to ``depth`` levels or more with the same ``skip``, whose pattern lists every entry
    ``pattern`` lists: its record replayed, so the asker's record holds every folder and
    listing it takes; None when no such tree was walked. A listing holds the tree's entries:
    more than ``pattern`` may list, never fewer."""
    wanted = _unions(pattern)
    for made_root, made, made_depth, made_skip in _trees_made(os.path.abspath(root)):
        if made_root == root and made_depth >= depth and made_skip == skip and all(
                _covers(has, asked) for has, asked in zip(_unions(made), wanted)):
            return dict(tree(made_root, made, made_depth, made_skip))
    return None


def _covers(has: tuple, asked: tuple) -> bool:
    """Whether every name the alternatives ``asked`` (:func:`_union`'s) match, ``has``
    matches (told by names, endings and ``[!.]*`` alone: False when unsure)."""
    names, ends, visible, other = asked
    has_names, has_ends, has_visible, _ = has
    return other is None and all(
        name in has_names or name.endswith(has_ends) or has_visible and name[:1] not in ("", ".")
        for name in names) and all(end.endswith(has_ends) for end in ends) and \
        (not visible or has_visible or "" in has_ends)


def _same(value):
    return value


_LISTED = ("folder", "link")  # the kinds of entries a pattern's "NAME/" alternatives match


def listable(folder) -> bool:
    """Whether ``folder`` could be listed: :func:`listing` gives nothing for a folder it may
    not read or whose path is past the system's limit, as for an empty one. Asks the disk
    nothing :func:`listing` did not (the answer is recorded there)."""
    return _entries(os.path.abspath(folder)) is not None


def _listing(folder: str, pattern: str) -> tuple | None:
    entries = _entries(folder)
    if entries is None:
        return None
    return _selected(pattern)(entries)


@per_run
def _entries(folder: str) -> tuple | None:
    """(name, kind) of every entry of ``folder``, sorted, once per run whatever the patterns
    asked of it (a launch file walk and a package walk list the same folders)."""
    try:
        with os.scandir(folder) as entries:
            found = [(entry.name, "file" if entry.is_file(follow_symlinks=False) else
                      "folder" if entry.is_dir(follow_symlinks=False) else
                      "link" if entry.is_symlink() else "other") for entry in entries]
    except (OSError, ValueError):
        return None
    return tuple(sorted(found))


@functools.lru_cache(maxsize=64)
def _selected(pattern: str):
    """The entries of a listing ``pattern`` matches, as :func:`urdftool.description.record.
    matches` decides (:func:`_unions`; each name tested in one comprehension: a call per
    name cost a walk more than its test)."""
    (names, ends, visible, other), (anys, any_ends, any_visible, any_other) = _unions(pattern)

    def selected(entries: tuple) -> tuple:
        return tuple([entry for entry in entries for name in (entry[0],) if (
            name in anys or name.endswith(any_ends) or any_visible and name[:1] not in ("", ".")
            or any_other is not None and any_other(name) is not None
            if entry[1] in _LISTED else
            name in names or name.endswith(ends) or visible and name[:1] not in ("", ".")
            or other is not None and other(name) is not None)])

    return selected


def _unions(pattern: str) -> tuple[tuple, tuple]:
    """(for a file's name, for a folder's or link's) the alternatives of ``pattern`` as
    (names, endings, whether ``[!.]*``, one expression of the others or None): a name
    without wildcards is compared, ``*`` and a name is an ending, ``[!.]*`` a first
    character, as fnmatch decides (its ``*.launch`` expressions backtracked over every
    character of every name a walk lists)."""
    alternatives = pattern.split("|")
    return (_union([a for a in alternatives if not a.endswith("/")]),
            _union([a[:-1] if a.endswith("/") else a for a in alternatives]))


def _union(chosen: list[str]) -> tuple:
    names, ends, visible, rest = set(), [], False, []
    for alternative in chosen:
        if not _WILDCARDS.intersection(alternative):
            names.add(alternative)
        elif alternative[:1] == "*" and not _WILDCARDS.intersection(alternative[1:]):
            ends.append(alternative[1:])  # ("*" alone: "", every name's ending)
        elif alternative == "[!.]*":
            visible = True
        else:
            rest.append(alternative)
    other = re.compile("|".join(fnmatch.translate(a) for a in rest)).match if rest else None
    return frozenset(names), tuple(ends), visible, other


_WILDCARDS = frozenset("*?[")  # (fnmatch's: any other character of a pattern is itself)


def environ(name: str, variables=None) -> str | None:
    """The environment variable ``name``, or None when unset; recorded when read from this
    process's environment (``variables`` None), not from a mapping given."""
    value = (os.environ if variables is None else variables).get(name)
    if variables is None:
        records.note(ENV, name, value)
    return value


def under_ci(variables=None) -> bool:
    """Whether this run is a CI job's: ``CI`` set (GitHub Actions, GitLab CI and most services
    set ``CI=true``) to anything but ``0``, ``false`` or ``no``. The one answer of the safe
    mode's default (:func:`env_allowed`) and of the cache's
    (:func:`urdftool.lint.cache.default_folder`): ``CI=false`` turned the cache off but left
    the full mode on, and ``CI=" "`` the same."""
    value = (os.environ if variables is None else variables).get("CI", "")
    return value.strip().lower() not in ("", "0", "false", "no")


def env_allowed(flag: bool | None) -> bool:
    """``allow_env`` as given; unset, the safe mode when ``CI`` is set: the one decision of
    every reader of robots (``load``, ``check``, every command, ``crosscheck``).

    A CI job on a pull request checks files a stranger wrote, and its environment holds
    tokens and secrets: ``$(env)`` or an include of a file outside the checkout would print
    them in the job's public log. GitHub Actions, GitLab CI and most other services set
    ``CI=true``; on a developer's machine the files are their own.
    """
    return flag if flag is not None else not under_ci()


def resolved(what: str, outcome) -> None:
    """Record what the loader made of what it read: ``what`` ('package NAME', 'mesh URI')
    resolved to ``outcome`` (a path, or why not)."""
    records.note(RESOLVED, what, os.fspath(outcome) if isinstance(outcome, Path) else outcome)


def inside(path, folder) -> bool:
    """Whether ``path``, every symbolic link followed, is ``folder`` or below it (itself with
    links followed)."""
    try:
        real = real_path(os.fspath(path))
        base = real_path(os.fspath(folder))
    except (OSError, ValueError):
        return False
    return real_inside(real, base)


def real_inside(real: str, base: str) -> bool:
    """:func:`inside` of paths whose links were followed already (:func:`real_path`'s
    answers): whether ``real`` is ``base`` or below it."""
    return real == base or real.startswith(base.rstrip(os.sep) + os.sep)


def real_path(path) -> str:
    """``os.path.realpath(path)``, recorded (a link made or changed later changes what every
    containment decision said)."""
    path = os.fspath(path)
    found = _real_path(path)
    records.note(REAL, os.path.abspath(path), found)
    return found


# folders below which a real path is realpath's, not the folder's answered once and a name: a
# folder 200 deep, committed, ran the recursion past Python's limit (a traceback)
MAX_REAL_DEPTH = 48


@per_run
def _real_path(path: str) -> str:
    """``os.path.realpath(path)``, answered once per run (see :mod:`.run_memo`). A file that
    is not a link is its folder's real path (itself answered once per run) and its name: the
    meshes of a package share a few folders, and realpath would walk every component of each
    (``lstat`` calls in a check of the corpus's 46 URDFs: 4,240 before, 2,034 so)."""
    folder, name = os.path.split(path)
    if not folder or name in ("", ".", "..") or path.count(os.sep) > MAX_REAL_DEPTH:
        return os.path.realpath(path)  # (deep: each level asked of the folder above is frames)
    try:
        if stat.S_ISLNK(os.lstat(path).st_mode):
            return os.path.realpath(path)
    except OSError:  # missing, or not reachable: realpath's own answer
        return os.path.realpath(path)
    return os.path.join(_real_path(folder), name)


@per_run
def repository_root(start: Path) -> Path | None:
    """The nearest ancestor of ``start`` (itself included) holding a ``.git`` entry: the
    repository, by urdftool's own rule (git's discovery is never asked). Each ``.git`` looked
    for is recorded (one made later changes the answer)."""
    start = Path(start)
    for folder in [start, *start.parents]:
        if kind_of(os.path.join(folder, ".git")):  # (a str: no Path made for each look)
            return folder
    return None


@per_run
def enclosing_root(folder: Path) -> Path | None:
    """The folder whose files a stranger may have written, holding ``folder``: its repository
    (:func:`repository_root`); without one, the nearest folder above holding a package's
    manifest (:data:`MANIFESTS`); None when there is neither (the user's own folders)."""
    folder = Path(os.path.abspath(folder))
    return repository_root(folder) or next(
        (f for f in [folder, *folder.parents]
         if any(kind_of(os.path.join(f, name)) == "file" for name in MANIFESTS)), None)


# The files that make a folder a ROS package, as rospack reads them: package.xml (catkin's,
# ament's), else manifest.xml (a rosbuild package, ROS 1's only: rospack, roslaunch's $(find)
# and resource_retriever's package:// find it by its folder's name). The one list of them.
MANIFESTS = ("package.xml", "manifest.xml")
MANIFESTS_SAID = " or ".join(MANIFESTS)  # as a message names them: what makes a package


# ---- a record compared with the disk ----------------------------------------------------

def holds(entry: list, quick: bool = False) -> bool:
    """Whether an entry of a record (:meth:`.record.Record.dump`) is still the answer: the same
    question asked again, unrecorded, by the functions above. A file read is compared by where
    its links lead (a path that now leads elsewhere is not read), then its stamp, then (unless
    ``quick``) its content, read only when its size is the same. ValueError for an entry of
    no known kind."""
    kind = entry[0]
    with records.unrecorded():
        if kind == READ:
            return _read_holds(*entry[1:6], quick)
        if kind == SEARCH:
            folder, pattern, real, found = entry[1:5]
            if _real_path(folder) != real:
                return False
            now = _listing(folder, pattern)
            return (None if now is None else [list(e) for e in now]) == found
        if kind == PROBE:
            return _kind(entry[1], entry[2]) == entry[3]
        if kind == REAL:
            return _real_path(entry[1]) == entry[2]
        if kind == ENV:
            return os.environ.get(entry[1]) == entry[2]
        if kind == RESOLVED:
            return True  # made from the other entries
    raise ValueError(f"no entry of kind {kind!r}")


def _read_holds(path: str, real: str, stamp: str | None, size: int | None,
                digested: str | None, quick: bool) -> bool:
    now = _real_path(path)
    if now != real:
        return False  # a link made or changed: what it leads to now is not read
    if stamp is not None and _stamp_at(now) == stamp:
        return True
    if quick or digested is None or size is None:
        return False
    try:
        data, _ = _read(now, os.stat(now), size)
    except OSError:
        return False
    return digest(data) == digested


def unchanged(entries: list, quick: bool = False) -> bool:
    """Whether every entry still :func:`holds`: the places first (where links lead, what is
    at a path, folders), then the files, so that no file is read once a link on its way
    changed. False for a malformed entry."""
    from urdftool.description.run_memo import one_run

    try:
        with one_run():
            return all(holds(entry, quick) for entry in entries if entry[0] != READ) and \
                all(holds(entry, quick) for entry in entries if entry[0] == READ)
    except (ValueError, TypeError, IndexError, KeyError):
        return False


# ---- urdftool's own files: never a robot's, never recorded ------------------------------

def read_own(path, limit: int) -> bytes | None:
    """One of urdftool's own files (a result cache entry, its signing key): its bytes when it
    is a regular file, not a symbolic link, of at most ``limit`` bytes; else None."""
    with records.unrecorded():
        try:
            if stat.S_ISLNK(os.lstat(path).st_mode):
                return None
            return _read_disk(path, limit, "own")
        except (OSError, ValueError):
            return None


def own_folder(folder, create: bool = False) -> str:
    """'there' when ``folder`` is a real folder (never a link), 'made' when ``create`` made it
    (mode 0o700, parents too), '' otherwise."""
    try:
        mode = os.lstat(folder).st_mode
    except FileNotFoundError:
        if not create:
            return ""
        try:
            make_folders(folder, 0o700)  # never through a link leading out of a repository
            mode = os.lstat(folder).st_mode
        except (OSError, UsageError):
            return ""
        return "made" if stat.S_ISDIR(mode) else ""
    except OSError:
        return ""
    return "there" if stat.S_ISDIR(mode) else ""


def tree_stamp(root) -> str:
    """The count and newest modification of the ``.py`` and ``.json`` files below ``root``
    (urdftool's own source and data), the folder's real path first."""
    root = os.path.realpath(root)
    newest, count = 0, 0
    for folder, _, names in os.walk(root):
        for name in names:
            if name.endswith((".py", ".json")):
                count += 1
                newest = max(newest, os.stat(os.path.join(folder, name)).st_mtime_ns)
    return f"{root}:{count}:{newest}"


# ---- writing: never recorded ----------------------------------------------------------

def real_folder(folder) -> str:
    """The folder ``folder`` names, its symbolic links resolved one by one as the system
    resolves them (a ``..`` after a link goes up from where the link leads). UsageError when
    one of them lies in a repository (or package, see :func:`enclosing_root`) and leads
    outside it: a link committed in a pull request (``reports -> /home/runner``) cannot make
    urdftool write, or make folders, elsewhere. Links outside any repository are the user's
    own and followed. The message names the link, never where it leads. Nothing is recorded
    (where urdftool writes is no part of what a check read)."""
    with records.unrecorded():
        return _real_folder(folder)


def _real_folder(folder) -> str:
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
    symbolic link, or it is a folder; or it is in a version control system's own folder
    (:func:`_version_control_folder`). Commands call it before their work, so that a typo or a
    planted link costs no time. ``-`` is no file name: it names standard input to every
    reader, so a file of that name would be read as standard input by the next check given
    it (a hook passing the repository's files); an output to standard output is no ``-o``."""
    if os.fspath(path) == "-":
        raise UsageError("cannot write '-': it names standard input and output, not a file; "
                         "leave the output option out to write to standard output")
    path = Path(path)
    folder = path.parent
    try:  # a name the system cannot look up (too long, a loop) is refused as one missing
        if not folder.is_dir():
            raise UsageError(f"cannot write '{path}': {_no_folder_there(folder)}")
        real = real_folder(folder)
        if path.is_dir() and not path.is_symlink():
            raise UsageError(f"cannot write '{path}': it is a folder; give a file name")
        owner = _version_control_folder(os.path.join(real, path.name))
    except OSError as error:
        raise UsageError(f"cannot write '{path}': {error.strerror}") from None
    if owner is not None:
        raise UsageError(f"cannot write '{path}': it is in '{owner}', the version control "
                         "system's own folder, which the output would break; give another "
                         "file name")
    return real


def _no_folder_there(folder: Path) -> str:
    """Why an output's folder is none, as itself: missing, or something else in its place
    (a file, a named pipe: ``-o report.urdf/x.json`` was "folder 'report.urdf' does not
    exist" of a file that exists)."""
    with records.unrecorded():  # (where urdftool writes is no part of what a check read)
        why = identity_or_why(folder)
    if isinstance(why, tuple):
        return f"'{folder}' is a file, not a folder"
    if why.startswith("a "):
        return f"'{folder}' is {why}, not a folder"
    return f"folder '{folder}' {unreachable(folder)}"


# the folders a version control system keeps its own data in, by name (a worktree's ``.git``
# file too): ``-o .git/HEAD`` replaced the branch with a report and the repository was gone
VERSION_CONTROL_NAMES = frozenset({".git", ".hg", ".svn", ".bzr"})


def _version_control_folder(target: str) -> str | None:
    """The folder of a version control system's own that the output file ``target`` (its
    folder's real path and its name) is, or is in: one named as :data:`VERSION_CONTROL_NAMES`
    are, or a git directory by git's own test (``HEAD``, ``objects`` and ``refs``: a bare
    repository, ``git --git-dir``'s, a submodule's below ``.git/modules``); None when none."""
    parts = target.split(os.sep)
    for index, part in enumerate(parts):
        if part in VERSION_CONTROL_NAMES:
            return os.sep.join(parts[:index + 1]) or os.sep
    folder = os.path.dirname(target)
    while True:
        if (os.path.isfile(os.path.join(folder, "HEAD")) and
                os.path.isdir(os.path.join(folder, "objects")) and
                os.path.isdir(os.path.join(folder, "refs"))):
            return folder
        above = os.path.dirname(folder)
        if above == folder:
            return None
        folder = above


def write_file(path, data: str | bytes, rewrites: bool | frozenset = False,
               private: bool = False) -> None:
    """Write ``data`` (text as UTF-8) to ``path`` through a temporary file beside it that then
    replaces it: a symbolic link at ``path`` is replaced by the file, its target left alone.
    A regular file keeps its permissions, and one no one may write (mode 0444: a generated or
    installed file) is refused, as ``>`` refuses it. UsageError when the folder is missing or
    reached through a link leading outside its repository, ``path`` is a folder, or the system
    refuses; and when the file at ``path`` is one this process read (or was told a worker
    read: :func:`read_elsewhere`), by any spelling, bind or link of its folder: a robot, an
    include, a mesh or a companion the command's output would replace (a hard link of one is
    not: :func:`_reads_replaced`), unless its caller rewrites that file on purpose:
    ``rewrites`` True (the fixes, ``inertia --write`` over its robot, urdftool's own files), or
    the kinds of reading a rewrite is meant for (``collisions --write-srdf`` updates a file
    read as an SRDF, never an include named in its place). A rewrite writes the file it read:
    a link at ``path`` by which this process read a file is followed to it, and the link is
    kept (a fix of a robot file that is a committed link replaced the link with a copy and
    left the robot unfixed). ``private``: readable and writable by its owner only, whatever
    was there and whatever the umask (a secret: the cache's signing key). A regular file
    replaced keeps its owner and group where this process may give them
    (:func:`_keep_owner`)."""
    folder, target, existing = _written(path, rewrites)
    path = Path(path)
    if isinstance(data, str):
        data = data.encode("utf-8")
    if existing is not None and stat.S_ISLNK(existing.st_mode):
        stream = _own_stream(target)
        if stream is not None:  # -o /dev/stdout: the stream itself, the link left as it is
            _write_descriptor(stream, data)
            return
    if existing is not None and stat.S_ISBLK(existing.st_mode):
        raise UsageError(f"cannot write '{path}': it is a block device")
    if existing is not None and (stat.S_ISCHR(existing.st_mode) or
                                 stat.S_ISFIFO(existing.st_mode)):
        _write_in_place(path, target, data)  # /dev/null, /dev/full, a named pipe: never replaced
        return
    if existing is not None and stat.S_ISREG(existing.st_mode) and \
            not existing.st_mode & 0o222 and not private:  # (replacing it by a rename would
        raise UsageError(f"cannot write '{path}': it is read-only (mode "  # pass over that,
                         f"{stat.S_IMODE(existing.st_mode):04o})")  # as root or not)
    if private:
        mode = 0o600
    elif existing is not None and stat.S_ISREG(existing.st_mode):
        mode = stat.S_IMODE(existing.st_mode)
    else:
        umask = os.umask(0)
        os.umask(umask)
        mode = 0o666 & ~umask
    import tempfile  # only where a file is written (a re-run from the cache reads)

    try:
        descriptor, temporary = tempfile.mkstemp(prefix=_temporary_prefix(path.name, folder),
                                                 suffix=".tmp", dir=folder)
    except OSError as error:
        raise UsageError(f"cannot write '{path}': {error.strerror}") from None
    try:
        if existing is not None and stat.S_ISREG(existing.st_mode) and not private:
            _keep_owner(descriptor, existing)
        with open(descriptor, "wb") as handle:
            handle.write(data)
        os.chmod(temporary, mode)
        os.replace(temporary, target)
    except OSError as error:
        os.unlink(temporary)
        raise UsageError(f"cannot write '{path}': {error.strerror}") from None


def _temporary_prefix(name: str, folder: str) -> str:
    """The start of the temporary file's name beside ``name``: ``.NAME.``, the name's bytes cut
    so that with mkstemp's 8 characters and ``.tmp`` it fits the folder's longest name (a robot
    named with 250 bytes was "File name too long" to ``--fix``: that name is the file
    system's to allow, the temporary file's is ours)."""
    try:
        longest = os.pathconf(folder, "PC_NAME_MAX")
    except (OSError, ValueError):
        longest = 255
    room = max(longest - len("..") - 8 - len(".tmp"), 1)
    return f".{os.fsdecode(os.fsencode(name)[:room])}."


def _keep_owner(descriptor: int, existing: os.stat_result) -> None:
    """Give the temporary file that replaces ``existing`` its owner and group, as far as this
    process may (root: both; another user: a group of theirs; else they stay the writer's, as
    ``sed -i`` leaves them): ``sudo urdftool check --fix`` made a user's robot root's."""
    for owner, group in ((existing.st_uid, existing.st_gid), (-1, existing.st_gid)):
        try:
            os.fchown(descriptor, owner, group)
            return
        except PermissionError:
            continue


def check_write(path, rewrites: bool | frozenset = False) -> None:
    """Raise the UsageError :func:`write_file` would raise for a file read that the output
    would replace, before the work: a command that reads the file it rewrites (``collisions
    --write-srdf``, once the SRDF is read) says so at once, not after minutes of work."""
    _written(path, rewrites)


def _written(path, rewrites: bool | frozenset) -> tuple[str, str, os.stat_result | None]:
    """Where :func:`write_file` writes ``path``: the real folder, the target in it (a link
    by which this process read a file followed, for a rewrite) and what is there now; the
    UsageError of a file read the output would replace unless a rewrite meant."""
    folder = check_output(path)
    target = os.path.join(folder, Path(path).name)
    if rewrites:
        linked = _read_through_link(target)
        if linked is not None:
            folder, target = check_output(linked), linked
    try:
        existing = os.lstat(target)
    except OSError:
        existing = None
    kinds = _reads_replaced(existing, target) if existing is not None else None
    if kinds and not (rewrites is True or (rewrites and kinds <= rewrites)):
        raise UsageError(f"cannot write '{path}': it is a file the command read (as "
                         f"{', '.join(sorted(kinds))}), which the output would replace; give "
                         "another file name")
    return folder, target, existing


def _reads_replaced(existing: os.stat_result, target: str) -> set[str] | None:
    """What this process read the regular file ``existing`` at ``target`` (its folder's real
    path and its name) as, when replacing it by a rename replaces a file it read (None when
    not): the same file (device, inode, change time) at the same entry (the folder, by device
    and inode: any spelling, link or bind mount of it, and the name). A hard link of a file
    read is another entry: the rename puts the output at that name only, and the file read
    keeps its bytes under its own (the writer never writes through a name into the file it
    leads to), so it is not refused."""
    names = _READ_HERE.get(_which_file(existing)) if stat.S_ISREG(existing.st_mode) else None
    if not names:
        return None
    kinds = set().union(*names.values())
    if existing.st_nlink <= 1:
        return kinds  # one name: the entry read
    here = _entry(target)
    return kinds if here is None or any(_entry(name) in (here, None) for name in names) \
        else None


def _read_through_link(target: str) -> str | None:
    """The real path of the regular file the symbolic link ``target`` leads to when this
    process read that file by the link's name (a rewrite writes the file it read); else
    None."""
    try:
        if not stat.S_ISLNK(os.lstat(target).st_mode):
            return None
        info = os.stat(target)
    except (OSError, ValueError):
        return None
    names = _READ_HERE.get(_which_file(info)) if stat.S_ISREG(info.st_mode) else None
    if not names:
        return None
    name_of_link = os.path.join(os.path.realpath(os.path.dirname(target)),
                                os.path.basename(target))
    if not any(os.path.join(os.path.realpath(os.path.dirname(name)), os.path.basename(name))
               == name_of_link for name in names):
        return None
    return os.path.realpath(target)


def _entry(path: str) -> tuple | None:
    """The folder entry holding the file ``path`` leads to: (the real folder's device and
    inode, the name), links followed; None when it cannot be looked up."""
    try:
        real = os.path.realpath(path)
        folder = os.stat(os.path.dirname(real))
    except (OSError, ValueError):
        return None
    return folder.st_dev, folder.st_ino, os.path.basename(real)


def _own_stream(target: str) -> int | None:
    """1 or 2 when the link ``target`` leads to this process's standard output or error (the
    very open file: ``/dev/stdout``, ``/proc/self/fd/2``), else None. Only these links are
    followed: replacing ``/dev/stdout`` with a file (run as root) broke the machine's, and a
    link a repository commits may lead anywhere else (it is replaced, its target untouched)."""
    try:
        reached = os.stat(target)
    except OSError:
        return None
    for descriptor in (1, 2):
        try:
            stream = os.fstat(descriptor)
        except OSError:
            continue
        if (stream.st_dev, stream.st_ino) == (reached.st_dev, reached.st_ino):
            return descriptor
    return None


def _write_descriptor(descriptor: int, data: bytes) -> None:
    """Write ``data`` on the standard stream ``descriptor`` as printing there does (after what
    is buffered for it, through the stream :mod:`urdftool.streams` watches when it runs: a
    reader that left or a full disk end the run as for any output)."""
    import sys

    stream = sys.stdout if descriptor == 1 else sys.stderr
    stream.flush()
    binary = getattr(stream, "buffer", None)
    if binary is None:
        stream.write(data.decode("utf-8", "replace"))
    else:
        binary.write(data)
    stream.flush()


PIPE_READER_WAIT = 10.0  # [s] how long an output that is a named pipe may wait for a reader


def _write_in_place(path, target: str, data: bytes) -> None:
    """Write ``data`` into the character device or named pipe at ``target`` (a temporary file
    renamed over it would replace the device itself: ``-o /dev/null`` run as root); UsageError
    when the system refuses (``/dev/full``: no space left) or a named pipe has no reader
    within :data:`PIPE_READER_WAIT` seconds (an archive can hold a pipe where a workflow writes
    its report: opening it waited for a reader forever; a reader started just before urdftool
    may open its end a moment later)."""
    deadline = time.monotonic() + PIPE_READER_WAIT
    try:
        while True:
            try:
                descriptor = os.open(target, os.O_WRONLY | os.O_NOFOLLOW | os.O_NOCTTY |
                                     os.O_NONBLOCK)
                break
            except OSError as error:
                if error.errno != errno.ENXIO or time.monotonic() > deadline:
                    raise
                time.sleep(0.05)
        os.set_blocking(descriptor, True)  # a reader that is slow is waited for
        with open(descriptor, "wb") as handle:
            handle.write(data)
    except OSError as error:
        why = "a named pipe no process reads" if error.errno == errno.ENXIO else error.strerror
        raise UsageError(f"cannot write '{path}': {why}") from None


def append_stream(path):
    """A binary stream appending to ``path`` (a log), made if missing: refused as any output
    file is (:func:`check_output`: a missing folder, a folder, a version control system's own
    folder), and a named pipe with no reader within :data:`PIPE_READER_WAIT` seconds refused,
    not waited for (the language server's ``--log-file`` of a pipe nobody read hung before it
    read a message; of ``.git/HEAD`` it wrote its log into the branch). UsageError."""
    check_output(path)
    deadline = time.monotonic() + PIPE_READER_WAIT
    try:
        while True:
            try:
                descriptor = os.open(path, os.O_WRONLY | os.O_APPEND | os.O_CREAT | os.O_NOCTTY |
                                     os.O_NONBLOCK, 0o666)
                break
            except OSError as error:
                if error.errno != errno.ENXIO or time.monotonic() > deadline:
                    raise
                time.sleep(0.05)
        os.set_blocking(descriptor, True)
    except OSError as error:
        why = "a named pipe no process reads" if error.errno == errno.ENXIO else error.strerror
        raise UsageError(f"cannot write '{path}': {why}") from None
    return open(descriptor, "ab", buffering=0)


def remove_file(path) -> None:
    """Remove the regular file ``path`` (a link is removed, never its target) in the folder
    :func:`check_output` allows; UsageError when that folder is refused or the system
    refuses."""
    folder = check_output(path)
    try:
        os.unlink(os.path.join(folder, Path(path).name))
    except OSError as error:
        raise UsageError(f"cannot remove '{path}': {error.strerror}") from None


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


def link_folder_new(root: Path, name: str, folder: str) -> bool:
    """Create the symbolic link ``name`` (one plain name) in ``root``, a folder made by
    :func:`temporary_folder`, to the existing folder ``folder`` (made absolute and real):
    for a loader that finds a package's files only beside the file it reads (PyBullet), as
    they are beside a robot in its own repository. It leads out of ``root`` on purpose:
    urdftool does not follow it, the loader does, to a folder urdftool already resolved.
    False, and nothing made, when ``name`` is not plain, exists, or ``folder`` is no folder."""
    if "/" in name or os.sep in name or kind_of(folder) != "folder":
        return False
    try:
        target = _new_path(root, name)
        os.symlink(real_path(folder), target, target_is_directory=True)
    except (ValueError, OSError):
        return False
    return True


def link_file_new(root: Path, relative: str, file: str) -> bool:
    """Create the symbolic link ``relative`` (``/``-separated plain names) below ``root``, a
    folder made by :func:`temporary_folder`, to the existing file ``file`` (made real): for a
    loader that finds a package's files only beside the file it reads, where the package's
    install puts a file elsewhere than its source folder holds it. It leads out of ``root`` on
    purpose, as :func:`link_folder_new`'s. False, and nothing made, when ``relative`` is not
    plain or exists, or ``file`` is no file."""
    if kind_of(file) != "file":
        return False
    try:
        target = _new_path(root, relative)
        os.symlink(real_path(file), target)
    except (ValueError, OSError):
        return False
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
