"""What a reader of the user's files did when it crashed outside a rule: the one record of a
reader's internal error (a bug in urdftool, never the file's defect), kept until the linter
says it (an internal error, at the file being read, naming the reader). A reader run while
finding targets (launch files read to know which robots they build) or inside a rule then
answers as if the file said nothing, and the run goes on with the other files; nothing is
swallowed: each crash is said once, by whoever drains the record (:func:`drained`)."""

from __future__ import annotations

from urdftool.records import Frozen

_CRASHED: list = []  # (this process's; a worker forked inherits a copy and drains its own)


class Crash(Frozen):
    """``reader`` (in words: "the Python launch reader") crashed with ``error`` reading
    ``path``."""

    reader: str
    path: str
    error: BaseException

    __slots__ = ("reader", "path", "error")

    def __init__(self, reader: str, path: str, error: BaseException) -> None:
        set_field = object.__setattr__
        set_field(self, "reader", reader)
        set_field(self, "path", path)
        set_field(self, "error", error)


def guarded(reader: str, path, read, fallback=None):
    """``read()``, or ``fallback`` when it raises, the crash kept for :func:`drained`. A
    MemoryError is raised again (the memory budget's to stop), and so is an UrdftoolError (one
    raised on purpose)."""
    from urdftool.errors import UrdftoolError

    try:
        return read()
    except (MemoryError, UrdftoolError):  # (an error raised on purpose is no crash)
        raise
    except Exception as error:  # noqa: BLE001 - said as urdftool's internal error
        _CRASHED.append(Crash(reader, str(path), error))
        return fallback


def any_kept() -> bool:
    """Whether a crash was kept since the last :func:`drained` (asked before importing what
    reports it: a run served whole from the result cache imports no rule)."""
    return bool(_CRASHED)


def drained() -> list[Crash]:
    """The crashes kept since the last call, in order; the record is emptied."""
    found = list(_CRASHED)
    _CRASHED.clear()
    return found
