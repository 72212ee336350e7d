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

# [bytes] of meshes kept between robots (a worker has 2 GiB of address space in all)
RUN_CACHE_BYTES = 128 * 1024 * 1024


def new_cache(limit: int = RUN_CACHE_BYTES):
    """An empty cache of at most ``limit`` bytes: key -> (bytes held, outcome, what computing it
    recorded), the least recently used dropped first. Outcomes: a trimesh (counted as its
    file's size), a mesh's arrays and their measures (counted as the arrays' bytes), or a
    MeshProblem (counted as nothing)."""
    from cachetools import LRUCache  # only robots with meshes pay for its import

    return LRUCache(maxsize=limit, getsizeof=lambda entry: entry[0])


# Meshes read in this process, shared by every robot checked in it; made when the first is
# kept. A worker process per file has its own; it dies with its file.
_RUN_CACHE = None


def clear() -> None:
    """Forget every mesh kept in this process."""
    if _RUN_CACHE is not None:
        _RUN_CACHE.clear()


def stamp_of(path: Path):
    """A file's identity and modification (device, inode, size, mtime in ns), or None."""
    return identity(path)


def limits_key(limits) -> tuple[int, int]:
    """A :class:`~urdftool.description.inputs.MeshLimits` as a part of a key: its numbers,
    which are hashed in C, where the record's own hash is a call of Python, made again each
    time the key is hashed (the cache hashes a key several times a look-up: 13,000 calls on
    the corpus)."""
    return limits.max_triangles, limits.max_bytes


def once(key: tuple, uri: str, compute):
    """``compute()`` -> (outcome, bytes held) once per run for ``key`` (which starts with the
    path and its :func:`stamp_of`: a changed file is read again); a MeshProblem is kept under the
    URI its message names too. What computing it recorded (the mesh read, :mod:`.record`) is
    replayed into the record of each later caller. Returns the outcome or the MeshProblem."""
    global _RUN_CACHE
    if _RUN_CACHE is None:
        _RUN_CACHE = new_cache()
    for known in (key, (*key, uri)):
        entry = _RUN_CACHE.get(known)  # a hit becomes the most recently used
        if entry is not None:
            replay(entry[2])
            return entry[1]

    def outcome_of():
        try:
            return compute()
        except MeshProblem as problem:
            return problem, 0

    (outcome, size), events = captured(outcome_of)
    if key[1] is not None and size <= _RUN_CACHE.maxsize:  # a larger one is not kept
        _RUN_CACHE[(*key, uri) if isinstance(outcome, MeshProblem) else key] = (size, outcome,
                                                                               events)
    return outcome
