"""One record of what a check read: made by the loader and discovery as they work, read by
the result cache (is a kept result stale?) and the language server (which robots does a
changed file concern?).

Nobody writes to a record by hand. Every question the description layer and the linter ask of
the file system goes through :mod:`urdftool.description.files` (a test fails on any other
open, stat, listing or glob under ``urdftool/description`` and ``urdftool/lint``), and each
of those functions notes its question and its answer in the record of the block running
(:func:`recording`). What a record holds, each entry (kind, key) -> what was found (the
first answer, when the same question is asked twice):

- ``read``: a file's bytes, by absolute path as named -> :class:`Read` (where its links led,
  its stamp and size, a digest of the bytes read; or that it could not be read), and
  ``labels[path]``: what it was read as (robot, include, yaml, companion, mesh, manifest,
  settings, ...);
- ``search``: a folder listed, (folder, pattern) -> where the folder led and the entries
  matching (name, kind), or None when there was no folder: a file appearing there later, or
  the folder itself, changes the answer;
- ``probe``: what is at a path, (path, links followed) -> 'file', 'folder', 'link', 'other'
  or '' (nothing);
- ``real``: where a path's symbolic links lead (every containment decision asks it);
- ``env``: an environment variable -> its value, or None when unset;
- ``resolved``: what the loader made of the answers, for people and the language server: a
  package -> its folder, a mesh URI -> its file, or why not. Never compared: the entries it
  was made from are.

Answers remembered between robots (``per_run``, the mesh cache of a process, the settings
cache) keep what their first computation recorded and replay it into the record of every
later caller (:func:`remembered`), so a record is complete however much of it was computed
once for another robot.
"""

from __future__ import annotations

import fnmatch
import os
from _thread import _local  # (threading.local: threading itself not imported for it)
from contextlib import contextmanager

from urdftool.records import Frozen, NEW, Record

READ, SEARCH, PROBE, REAL, ENV, RESOLVED = "read", "search", "probe", "real", "env", "resolved"


class Read(Frozen):
    """A file read. real: where the path led, links followed; stamp: device, inode, size,
    modification and change times as git's index keeps them (None when the file had changed
    too recently to trust them, '' when nothing was there); size [bytes] (None when nothing
    was there); digest: of the bytes read (None when none were: ``failure`` says why; or when
    it was read where no record is compared with the disk by content: :func:`digesting`)."""

    real: str
    stamp: str | None
    size: int | None
    digest: str | None
    failure: str | None

    __slots__ = ("real", "stamp", "size", "digest", "failure")

    def __init__(self, real: str, stamp: str | None, size: int | None, digest: str | None,
                 failure: str | None = None) -> None:
        set_field = object.__setattr__
        set_field(self, "real", real)
        set_field(self, "stamp", stamp)
        set_field(self, "size", size)
        set_field(self, "digest", digest)
        set_field(self, "failure", failure)


class Record(Record):
    """What one check (or one block of work) asked of the file system, and the answers."""

    entries: dict  # (kind, key) -> answer
    labels: dict  # path read -> what it was read as
    parent: "Record | None"
    _index: tuple | None

    __slots__ = ("entries", "labels", "parent", "_index")
    _compared = ("entries", "labels")
    _shown = ("entries", "labels")

    def __init__(self, entries: dict = NEW, labels: dict = NEW, parent: "Record | None" = None,
                 _index: tuple | None = None) -> None:
        self.entries = {} if entries is NEW else entries
        self.labels = {} if labels is NEW else labels
        self.parent = parent
        self._index = _index

    def note(self, kind: str, key, answer, label: str | None = None) -> None:
        """Keep ``answer`` to (``kind``, ``key``) unless an earlier one is kept, and pass it
        to the enclosing record."""
        record, question = self, (kind, key)
        while record is not None:
            record.entries.setdefault(question, answer)
            if label is not None:
                record.labels.setdefault(key, set()).add(label)
            record._index = None
            record = record.parent

    def merge(self, other: "Record") -> None:
        """Note every entry of ``other`` here (and in the enclosing records): as :meth:`note`
        of each entry, then of each label, a record at a time (a remembered answer is replayed
        into every robot's record)."""
        record = self
        while record is not None:
            entries, labels = record.entries, record.labels
            for question, answer in other.entries.items():
                if question not in entries:
                    entries[question] = answer
            for key, kept in other.labels.items():
                if not kept:
                    continue
                question = (READ, key)
                if question not in entries:
                    entries[question] = other.entries[question]
                labels.setdefault(key, set()).update(kept)
            record._index = None
            record = record.parent

    # -- what it holds

    def reads(self) -> dict[str, Read]:
        """Path -> :class:`Read`, for every file read (or tried)."""
        return {key: answer for (kind, key), answer in self.entries.items() if kind == READ}

    def searched(self) -> dict[tuple[str, str], tuple | None]:
        """(folder, pattern) -> the entries found ((name, kind) pairs), None: no folder."""
        return {key: answer[1] for (kind, key), answer in self.entries.items()
                if kind == SEARCH}

    def resolutions(self) -> dict[str, str]:
        return {key: answer for (kind, key), answer in self.entries.items() if kind == RESOLVED}

    def read_as(self, label: str) -> list[str]:
        """The paths read as ``label`` (a mesh, a companion, settings, ...)."""
        return [path for path, labels in self.labels.items() if label in labels]

    def concerns(self, path, file: bool = False) -> bool:
        """Whether a change at ``path`` (written, created, removed, made a link) may change
        what the check found: a file it read, a path it probed or followed, or a folder above
        one; an entry of a folder it listed that matches what it looked for (the path itself
        or a folder above it); a path below a place that held no folder when it looked.
        ``file``: ``path`` is now a regular file (a search for folders does not match it;
        else what it is, or was, is not known); a function saying so is asked only when a
        listing of its folder makes it matter (a stat per file an editor reports changed)."""
        paths, patterns, not_folders, _ = self._indexed()
        path = os.path.abspath(path)
        if path in paths:  # a path it knows, or a folder above one
            return True
        folder, name = os.path.dirname(path), os.path.basename(path)
        listed = patterns.get(folder)
        if listed:
            if callable(file):
                file = file()
            if any(_matches(name, pattern, not file) for pattern, _ in listed):
                return True
        if folder in not_folders:  # it was nothing, or a file: now it holds ``path``
            return True
        if folder == path or not name:
            return False
        return self._below(folder)

    def _below(self, folder: str) -> bool:
        """Whether a change below ``folder`` (a folder now, or made one) concerns the check:
        a listing above that matches a folder on the way and did not hold it, or a place on
        the way that held no folder. Answered once per folder while the record is unchanged:
        the files an editor reports changed at once share a few folders (300,000 of them cost
        the server's loop 5 s, a walk to the root each)."""
        _, patterns, not_folders, known = self._indexed()
        found = known.get(folder)
        if found is None:
            found = False
            child = folder
            while True:
                above, name = os.path.dirname(child), os.path.basename(child)
                # (a change below a folder the listing already held leaves that listing as it was)
                if any(_matches(name, pattern, True) and name not in held
                       for pattern, held in patterns.get(above, ())) or above in not_folders:
                    found = True
                    break
                if above == child or not name:
                    break
                child = above
            known[folder] = found
        return found

    def _indexed(self):
        if self._index is None:
            paths, patterns, not_folders = set(), {}, set()
            for (kind, key), answer in self.entries.items():
                if kind in (READ, REAL):
                    paths.add(key)
                elif kind == PROBE:
                    paths.add(key[0])
                    if answer != "folder":
                        not_folders.add(key[0])
                elif kind == SEARCH:
                    folder, pattern = key
                    held = frozenset(entry[0] for entry in (answer[1] or ()) if entry[1] == "folder")
                    patterns.setdefault(folder, []).append((pattern, held))
                    if answer[1] is None:
                        not_folders.add(folder)
            for known in list(paths):  # the folders above each: one lookup per question (an
                folder = os.path.dirname(known)  # editor reports 300,000 files changed at once)
                while folder not in paths and folder != known:
                    paths.add(folder)
                    known, folder = folder, os.path.dirname(folder)
            self._index = paths, patterns, not_folders, {}  # (the answers of _below)
        return self._index

    # -- as kept by the result cache

    def dump(self) -> list[list]:
        """The entries as JSON-ready lists, which :func:`urdftool.description.files.holds`
        compares with the disk."""
        return [_dumped(kind, key, answer, sorted(self.labels.get(key, ())) if kind == READ
                        else None)
                for (kind, key), answer in self.entries.items()]


def entry_key(entry: list) -> tuple:
    """The question a dumped entry answers (its kind and key), to merge records: an entry's
    key is its path, or (folder, pattern) for a search, (path, links followed) for a probe."""
    return tuple(entry[:3] if entry[0] in (SEARCH, PROBE) else entry[:2])


def _dumped(kind: str, key, answer, labels) -> list:
    if kind == READ:
        return [READ, key, answer.real, answer.stamp, answer.size, answer.digest, labels]
    if kind == SEARCH:
        real, found = answer
        return [SEARCH, key[0], key[1], real,
                None if found is None else [list(entry) for entry in found]]
    if kind == PROBE:
        return [PROBE, key[0], key[1], answer]
    return [kind, key, answer]


def _matches(name: str, pattern: str, folder: bool) -> bool:
    """Whether a changed path called ``name`` matches some alternative of a listing's
    ``pattern``; ``folder`` false: it is a file (a folder-only alternative does not match)."""
    return any(fnmatch.fnmatchcase(name, alternative.rstrip("/"))
               for alternative in pattern.split("|") if folder or not alternative.endswith("/"))


def matches(name: str, kind: str, pattern: str) -> bool:
    """Whether a folder entry ``name`` of ``kind`` (as ``lstat`` says: 'file', 'folder',
    'link', 'other') matches a listing's ``pattern``: alternatives separated by ``|``, each an
    fnmatch pattern (case-sensitive); one ending in ``/`` matches only folders and links."""
    for alternative in pattern.split("|"):
        if alternative.endswith("/"):
            if kind in ("folder", "link") and fnmatch.fnmatchcase(name, alternative[:-1]):
                return True
        elif fnmatch.fnmatchcase(name, alternative):
            return True
    return False


# ---- the record being made ------------------------------------------------------------------

class _Active(_local):
    """The record of the block running in this thread (a check runs in one thread: the
    language server's worker, a worker process's main thread)."""

    record: Record | None = None
    digests: bool = True  # see digesting()


_ACTIVE = _Active()


def digests_kept() -> bool:
    """Whether a file read now is noted with the digest of its bytes (:func:`digesting`)."""
    return _ACTIVE.digests


@contextmanager
def digesting(wanted: bool):
    """Whether the files the block reads are noted with the digest of their bytes. The digest
    is read only where a record is compared with the disk by content (a stamp that changed, a
    buffer's bytes: :func:`urdftool.description.files.holds`), i.e. by the result cache; a run
    that keeps no cache says so here (:func:`urdftool.lint.runner.check_paths`, the one
    owner), and spares hashing every mesh it reads. A Read without a digest (replayed later
    from an answer remembered in the process) never holds by content: a stale-looking entry
    is checked again, never taken for the disk's."""
    outer, _ACTIVE.digests = _ACTIVE.digests, wanted
    try:
        yield
    finally:
        _ACTIVE.digests = outer


def active() -> Record | None:
    """The record of the block running, or None (nothing is recorded)."""
    return _ACTIVE.record


def note(kind: str, key, answer, label: str | None = None) -> None:
    """Note an answer in the record of the block running, if any."""
    record = _ACTIVE.record
    if record is not None:
        record.note(kind, key, answer, label)


@contextmanager
def recording(record: Record | None = None):
    """Note what the block asks of the file system in ``record`` (a new one by default),
    which it yields; what is noted reaches the records of enclosing blocks too."""
    record = Record() if record is None else record
    record.parent = outer = _ACTIVE.record
    _ACTIVE.record = record
    try:
        yield record
    finally:
        _ACTIVE.record = outer
        record.parent = None


@contextmanager
def unrecorded():
    """Nothing the block asks is recorded: urdftool's own files, and the comparison of a
    record with the disk (:func:`urdftool.description.files.holds`)."""
    outer, _ACTIVE.record = _ACTIVE.record, None
    try:
        yield
    finally:
        _ACTIVE.record = outer


def captured(compute):
    """(``compute()``, what it recorded, or None for nothing), the entries noted in the
    enclosing record as well. An exception passes through, its entries noted."""
    record = Record()  # (recording()'s work, without a generator: every per-run answer's)
    record.parent = outer = _ACTIVE.record
    _ACTIVE.record = record
    try:
        value = compute()
    finally:
        _ACTIVE.record = outer
        record.parent = None
    return value, (record if record.entries else None)


def replay(events: Record | None) -> None:
    """Note in the record of the block running what a remembered computation recorded."""
    if events is not None and (record := _ACTIVE.record) is not None:
        record.merge(events)


def remembered(memo: dict, key, compute):
    """``compute()`` once per ``key`` in ``memo``; a later call gets the same answer and its
    recorded entries replayed (see the module doc)."""
    try:
        value, events = memo[key]
    except KeyError:
        memo[key] = (value, events) = captured(compute)
        return value
    replay(events)
    return value
