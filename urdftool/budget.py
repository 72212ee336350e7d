"""Time and memory budgets: how much a piece of work may take, and where it was when stopped.

A budgeted piece of work runs in a forked process (see :mod:`urdftool.lint.pool`) whose address
space is capped with ``RLIMIT_AS``: an allocation over the cap raises MemoryError instead of
taking the machine's memory. A process stopped for overrunning its time cannot say where it was,
so the work tells as it goes: the xacro expander calls :func:`working_at` with the location of
each element it reaches, and the process that stops a worker reads the last one from memory the
two share. Imports stay light: every command imports this module, and the loader calls it for
every element.
"""

from __future__ import annotations

import os
import sys
import time

from urdftool.errors import UsageError
from urdftool.guardian import SLOT_SIZE as _SLOT_SIZE  # (the slot of the guardian's child too)
from urdftool.records import Frozen

# ``Location`` below is urdftool.diagnostics.Location, in annotations only (never evaluated):
# importing typing for TYPE_CHECKING would slow every command's start-up

DEFAULT_TIMEOUT = 60.0  # [s] per file
DEFAULT_MEMORY = 2 * 1024 ** 3  # [bytes] of address space per worker process
SMALL_BUDGET = 512 * 1024 ** 2  # [bytes] below which numpy is imported before the cap is set
# numpy's OpenBLAS starts a thread per core and reserves address space for each (some 80 MiB):
# on a 64-core CI runner that alone is over 5 GiB. The matrices here are 4x4.
_ONE_THREAD = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
_UNITS = {"": 1, "K": 1024, "M": 1024 ** 2, "G": 1024 ** 3, "T": 1024 ** 4}


class Budget(Frozen):
    """What one piece of work may use.

    seconds: wall-clock time in [s], None for no limit
    memory: address space of the process doing it in [bytes], None for no limit
    """

    seconds: float | None
    memory: int | None

    __slots__ = ("seconds", "memory")

    def __init__(self, seconds: float | None = DEFAULT_TIMEOUT,
                 memory: int | None = DEFAULT_MEMORY) -> None:
        set_field = object.__setattr__
        set_field(self, "seconds", seconds)
        set_field(self, "memory", memory)

    @classmethod
    def of(cls, timeout: float, max_memory: str | None) -> "Budget":
        """A budget from option values: ``--timeout`` in [s], ``--max-memory`` as
        :func:`parse_memory` reads it (None: the default); 0 for no limit. UsageError when one
        is malformed or negative."""
        if not timeout >= 0 or timeout == float("inf"):  # NaN compares false: refused too
            raise UsageError(f"--timeout must be a number of seconds, 0 or more (0: no limit), "
                             f"got {timeout:g}")
        memory = DEFAULT_MEMORY if max_memory is None else parse_memory(max_memory)
        return cls(timeout or None, memory)

    @property
    def unlimited(self) -> bool:
        return self.seconds is None and self.memory is None


def parse_memory(text: str) -> int | None:
    """Bytes from ``2G``, ``512M``, ``1.5GiB``, ``800000`` (powers of 1024); None for ``0``."""
    import re

    match = re.fullmatch(r"\s*(\d+(?:\.\d+)?)\s*([KMGT]?)(?:I?B)?\s*", text.upper())
    if not match:
        raise UsageError(f"--max-memory must be a size such as 2G, 512M or 0 (no limit), "
                         f"not '{text}'")
    size = float(match[1]) * _UNITS[match[2]]
    if size == float("inf"):  # 400 digits: a float, but no integer
        raise UsageError(f"--max-memory must be a size such as 2G, 512M or 0 (no limit), "
                         f"not '{text}'")
    return int(size) or None


def format_memory(size: int) -> str:
    """``2 GiB``, ``512 MiB``, ``1000 bytes``."""
    for unit in ("T", "G", "M", "K"):
        if size >= _UNITS[unit]:
            from urdftool.numbers import number

            return f"{number(size / _UNITS[unit])} {unit}iB"
    return f"{size} bytes"


def limit_memory(size: int | None) -> None:
    """Cap this process's address space at ``size`` bytes (soft ``RLIMIT_AS``; never above a
    hard limit already set), with one BLAS thread so that numpy fits in it. Call it in a worker,
    before numpy is imported."""
    one_blas_thread()
    if size is None:
        return
    if size < SMALL_BUDGET or "numpy" in sys.modules:
        map_blas_buffers()
    import resource

    _, hard = resource.getrlimit(resource.RLIMIT_AS)
    if hard != resource.RLIM_INFINITY:
        size = min(size, hard)
    resource.setrlimit(resource.RLIMIT_AS, (size, hard))


def map_blas_buffers() -> None:
    """Have OpenBLAS map its buffers now: at numpy's import (~70 MiB of address space) and at
    its first product of 128 x 128 or more (32 MiB). Refused under a memory cap, OpenBLAS ends
    the process (exit code 1, "Memory allocation still failed"), a worker's death no piece can
    be told apart by (an "internal error"). :func:`limit_memory` calls it before it sets the
    cap where numpy is imported already (the product only: 0.3 ms) or the budget is small
    (numpy imported first): what does not fit then is Python's MemoryError, reported as out
    of memory with its budget. A process forked after it keeps the buffers."""
    import numpy

    numpy.ones((128, 128)) @ numpy.ones((128, 128))

KEPT_AT_LEAST = 64 << 20  # [bytes] what earlier pieces must have kept for a fresh worker to help


def grown(size: int | None, born: int = 0) -> bool:
    """Whether this process's address space has grown past half of ``size`` bytes, its memory
    budget, by at least :data:`KEPT_AT_LEAST` over ``born``, its size when it started (False
    without a budget, or where it cannot be read): a worker that kept that much from its
    earlier pieces (what a run remembers, the allocator's free pages) would give the next piece
    less than half of its budget. One forked from a process already past half (a program
    calling the API, a test session) starts that large: a fresh one would be no smaller, and
    a worker forked for every piece cost 0.2 s of CPU each from a 1.4 GB process."""
    if not size:
        return False
    used = address_space()
    return used is not None and used > size // 2 and used - born >= KEPT_AT_LEAST


def address_space() -> int | None:
    """This process's address space [bytes] (Linux's /proc), or None."""
    try:
        with open("/proc/self/statm", "rb") as handle:
            return int(handle.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return None


LOADAVG = "/proc/loadavg"  # (Linux) the load averages, then running/total scheduling entities


def busy_cores(looks: int = 6, gap: float = 0.004, enough: float = float("inf")) -> float:
    """How many cores other work keeps busy now: the threads of other processes ready to run
    (Linux's ``/proc/loadavg``, this process's own running one not counted), the most of a few
    looks. The 1-minute load average trails both ways: a build started seconds ago leaves it
    low while it takes a core (counted now, it is seen), and a run that ended seconds ago (the
    user's previous check, a benchmark's previous round) leaves it high while the cores are
    idle (one worker then did the work of two, issue 34). So the average only decides how hard
    to look: when it says more than the first look finds, ``looks`` looks ``gap`` seconds apart
    (about 20 ms) catch work that runs in bursts; where nothing can be read, the average.
    Once ``enough`` cores are found busy, more looks could not change what the caller decides
    (they only find more): it stops looking (the default ``--jobs`` with a core busy waited
    20 ms for nothing)."""
    running = _running_now()
    try:
        average = os.getloadavg()[0]
    except (AttributeError, OSError):
        average = 0.0
    if running is None:
        return average
    for _ in range(looks - 1):
        if average - running < 0.5 or running >= enough:  # (the two round to the same
            break                                               # number of idle cores)
        time.sleep(gap)
        running = max(running, _running_now() or 0)
    return float(running)


def _running_now() -> int | None:
    """The threads ready to run at this moment, less this process's running one."""
    try:
        with open(LOADAVG, "rb") as handle:
            return int(handle.read().split()[3].split(b"/")[0]) - 1
    except (OSError, ValueError, IndexError):
        return None


def one_blas_thread() -> None:
    """One BLAS thread for numpy when it is imported later in this process (unless the
    environment says otherwise): the products here are small, and after each large enough one
    OpenBLAS's idle threads spin, burning CPU."""
    for name in _ONE_THREAD:
        os.environ.setdefault(name, "1")


# Where the work of this process is. The slot, when there is one, is memory shared with the
# process that may stop this one; it holds the location after a 4-byte length.
_here: Location | None = None
_slot = None  # an mmap.mmap


def share_slot():
    """A new slot of shared memory (an anonymous shared ``mmap``); a process forked after this
    reports into it (see :func:`report_into`)."""
    import mmap

    return mmap.mmap(-1, _SLOT_SIZE)


def report_into(slot) -> None:
    """From now on, :func:`working_at` also writes into ``slot`` (None: only remember)."""
    global _slot
    _slot = slot
    working_at(None)


def working_at(location: Location | None) -> None:
    """The work has reached ``location`` (None: somewhere not in a file)."""
    global _here
    _here = location
    if _slot is None:
        return
    # LINE:FILE for the place and each macro call site, NUL-separated (no path holds a NUL)
    data = b"" if location is None else "\0".join(
        f"{place.line}:{place.file}" for place in (location, *location.via)).encode(
        "utf-8", "surrogateescape")
    if len(data) + 4 <= _SLOT_SIZE:
        _slot[4:4 + len(data)] = data
        _slot[:4] = len(data).to_bytes(4, "little")


def where() -> Location | None:
    """The location this process last reached."""
    return _here


def read_slot(slot) -> Location | None:
    """The location a (stopped) worker last wrote into ``slot``; None when it wrote none or the
    slot does not hold one whole location."""
    from urdftool.diagnostics import Location

    size = int.from_bytes(slot[:4], "little")
    if not 0 < size <= _SLOT_SIZE - 4:
        return None
    places = []
    for entry in slot[4:4 + size].decode("utf-8", "surrogateescape").split("\0"):
        line, _, file = entry.partition(":")
        places.append(Location(file, int(line) if line.isdigit() else None))
    return Location(places[0].file, places[0].line, tuple(places[1:]))


__all__ = ["Budget", "DEFAULT_MEMORY", "DEFAULT_TIMEOUT", "format_memory", "limit_memory",
           "one_blas_thread", "parse_memory", "read_slot", "report_into", "share_slot", "where",
           "working_at"]
