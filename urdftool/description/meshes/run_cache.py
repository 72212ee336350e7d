"""Meshes kept between the robots of one process, within a byte bound.

A run of robots of one package reads each mesh once, not once per robot. Entries are keyed by
resolved path, file identity and modification (a changed file is read again) and the limits;
what computing an entry recorded (the mesh read, :mod:`urdftool.description.record`) is
replayed into the record of each later caller.
"""

from __future__ import annotations

from pathlib import Path

from urdftool.description.files import identity
from urdftool.description.record import captured, replay
from urdftool.errors import MeshProblem

RUN_CACHE_BYTES = 128 * 1024 * 1024

# Meshes read in this process, shared by every robot checked in it (a run of robots of one
# package reads each mesh once, not once per robot): key -> (bytes held, outcome, what
# computing it recorded), least recently used first. Outcomes: a trimesh (counted as its file's
# size), a mesh's arrays and their measures (counted as the arrays' bytes), or a MeshProblem.
# A worker process per file has its own; it dies with its file.
class _RunCache(dict):
    """key -> (bytes held, outcome, record), with ``held``: the bytes of all entries (kept as
    entries come and go, not summed again at each insertion)."""

    held = 0

    def __setitem__(self, key, entry) -> None:
        self.held += entry[0] - (self[key][0] if key in self else 0)
        super().__setitem__(key, entry)

    def pop(self, key, *default):
        if key in self:
            self.held -= self[key][0]
        return super().pop(key, *default)

    def clear(self) -> None:
        self.held = 0
        super().clear()


_RUN_CACHE = _RunCache()


def stamp_of(path: Path):
    """A file's identity and modification (device, inode, size, mtime in ns), or None."""
    return identity(path)


def once(key: tuple, uri: str, compute):
    """``compute()`` -> (outcome, bytes held) once per run for ``key`` (which starts with the
    path and its :func:`stamp_of`: a changed file is read again); a MeshProblem is kept under the
    URI its message names too. What computing it recorded (the mesh read, :mod:`.record`) is
    replayed into the record of each later caller. Returns the outcome or the MeshProblem."""
    for known in (key, (*key, uri)):
        if known in _RUN_CACHE:
            _RUN_CACHE[known] = entry = _RUN_CACHE.pop(known)  # most recently used last
            replay(entry[2])
            return entry[1]

    def outcome_of():
        try:
            return compute()
        except MeshProblem as problem:
            return problem, 0

    (outcome, size), events = captured(outcome_of)
    if key[1] is not None:
        _RUN_CACHE[(*key, uri) if isinstance(outcome, MeshProblem) else key] = (size, outcome,
                                                                               events)
        while _RUN_CACHE.held > RUN_CACHE_BYTES:
            _RUN_CACHE.pop(next(iter(_RUN_CACHE)))  # the least recently used
    return outcome
