"""The guardian of a command's process: forked at once, small, before the command imports
what it works with, it waits while its child does the command, and stops the child at the end
of a piece's time budget (see :func:`guarded`); the pool (:mod:`urdftool.lint.pool`) runs a
budgeted piece of one file in that child rather than in a worker forked from it.

Imports stay light (no dataclasses: the door forks before the kept compiled code is given,
:func:`urdftool.__main__.kept_code`)."""

from __future__ import annotations

import os
import signal
import sys
import time

SLOT_SIZE = 8192  # [bytes] of shared memory for the location being worked on (urdftool.budget)

# guardian: (channel to the guardian, slot) in a process :func:`guarded` forked, else None;
# pieces: the budgeted single pieces this process has run; verdict: in the guardian's run
# again, (piece, kind, detail, the slot's bytes: where) of the piece it stopped
STATE: dict = {"guardian": None, "pieces": 0, "verdict": None}


def ended(code: int) -> str:
    """How a process ended, from its exit code as ``subprocess``, ``multiprocessing`` and
    ``os.waitstatus_to_exitcode`` give it (negative: the signal that ended it): ``exit code
    1``, ``killed by SIGSEGV (segmentation fault)``. Every report of a process's death (a
    worker, the guardian's child, a loader, git, Graphviz) says it in these words."""
    if code >= 0:
        return f"exit code {code}"
    try:
        name = signal.Signals(-code).name
    except ValueError:
        return f"killed by signal {-code}"
    what = signal.strsignal(-code)
    return f"killed by {name} ({what[0].lower() + what[1:]})" if what else f"killed by {name}"


def guarded():
    """Fork this process, early and small, into a guardian (the parent) and the process that
    does the work (the child, which returns None): a budgeted run of one piece
    (:func:`urdftool.lint.pool.run_budgeted`) is then done in the child itself, not in a worker forked from it
    (which would copy, page by page, the imports and the memory of a checked robot), its
    memory capped as a worker's, its time watched by the guardian, which kills it at the end
    of the budget. The guardian takes no part in the work and waits for the child; it returns
    ``(status, None)`` when the child ended (its exit status), or ``(None, verdict)`` when a
    piece was stopped (over its time, or the child died in it): the caller then does the same
    work again in the guardian with :func:`stopped_as` ``verdict``, and that piece gives the
    Stop without being done. A child killed by a signal outside a piece gives the guardian
    the same end. None, with nothing forked, where processes cannot fork."""
    if not hasattr(os, "fork"):
        return None
    import mmap
    import select  # noqa: F401  (the guardian's wait: loaded after the fork, the loader's and the
    # import system's writes copied some 140 pages the guardian shares with its child)

    slot = mmap.mmap(-1, SLOT_SIZE)  # (budget.share_slot's, made before budget is imported)
    read, write = os.pipe()
    life, alive = os.pipe()  # never written: it ends when the guardian does (watched_by)
    for stream in (sys.stdout, sys.stderr):
        stream.flush()
    parent = os.getpid()
    STATE["pieces"] = 0  # (the child's pieces, as the guardian counts them when it runs again)
    import gc

    frozen = gc.get_freeze_count()
    gc.freeze()  # the child's collector does not write into the pages it shares (copying them)
    pid = os.fork()
    if pid:
        if not frozen:  # (a caller's own frozen objects stay frozen)
            gc.unfreeze()
    else:
        os.close(read)
        os.close(alive)
        watched_by(life)  # a guardian killed (SIGKILL) leaves no child to run unwatched
        STATE["guardian"] = (write, slot)
        return None
    os.close(write)
    os.close(life)
    try:
        return _guard(pid, read, slot)
    finally:
        os.close(read)
        os.close(alive)  # (the child ended: its watcher ends)
        slot.close()


def guarding() -> bool:
    """Whether this process runs under a guardian (:func:`guarded`'s child)."""
    return STATE["guardian"] is not None


def stopped_as(verdict) -> None:
    """In this process from now on, the piece ``verdict`` names (counted from now) gives its
    Stop, once, without being done; None: no piece."""
    STATE.update(verdict=verdict, pieces=0)


def _guard(pid: int, read: int, slot):
    """The guardian's wait: (status, None) or (None, verdict); see :func:`guarded`."""
    import select

    interrupt = signal.signal(signal.SIGINT, signal.SIG_IGN)  # the child's to answer (the
    try:  # terminal's Ctrl-C reaches both)
        piece, deadline, pending, stopped = None, None, b"", None
        poller = select.poll()
        poller.register(read, select.POLLIN)
        while True:
            wait = None if deadline is None else max(0, int((deadline - time.monotonic()) * 1000
                                                             + 0.999))
            try:
                ready = poller.poll(wait)
            except InterruptedError:
                continue
            if not ready:
                if deadline is not None and time.monotonic() >= deadline:
                    stopped = (piece, "time", "", _where(slot))
                    os.kill(pid, signal.SIGKILL)
                    break
                continue
            data = os.read(read, 4096)
            if not data:  # the child ended (or closed its end: it ends)
                break
            pending += data
            while b"\n" in pending:
                line, pending = pending.split(b"\n", 1)
                kind, number, seconds = line.decode().split()
                piece = int(number) if kind == "start" else None
                deadline = time.monotonic() + float(seconds) if kind == "start" and \
                    float(seconds) else None
        while True:
            try:
                _, status = os.waitpid(pid, 0)
                break
            except InterruptedError:
                continue
        code = os.waitstatus_to_exitcode(status)
        if stopped is None and piece is not None:  # it died in the piece
            stopped = (piece, "died", f"worker process died: {ended(code)}",
                       _where(slot))
        if stopped is not None:
            return None, stopped
        if code < 0:  # a signal ended it: the status a shell gives (never this process
            code = 128 - code  # killed: a caller running the door in its own process goes on)
        return code, None
    finally:
        signal.signal(signal.SIGINT, interrupt)


def _where(slot) -> bytes:
    """What the child last wrote into ``slot`` (read as a location by the pool:
    :func:`urdftool.budget.read_slot`, which is above this module)."""
    return bytes(slot)


def watched_by(life: int) -> None:
    """Be killed (SIGKILL) when the guardian ends, as a hung C call cannot notice it: a
    watcher forked now, small, waits on ``life`` (the read end of a pipe whose only write end
    the guardian holds and never writes to: it reads its end when the guardian ends, however it
    ends) and then kills this process, if it still runs. ``life`` is closed here; the watcher
    closes every other descriptor it inherited (the guardian hears this process end when its
    channel to it ends, a reader of its output when its streams do). Without ``ctypes``
    (``PR_SET_PDEATHSIG``: its import cost a plain check more than this fork).

    Where the system can (Linux: :func:`_killed_by_the_end_of`), no watcher is forked: the
    system itself sends SIGKILL to this process when the pipe's last writer closes (the
    watcher's fork and its pages cost 1-2 ms of a plain check's CPU)."""
    if _killed_by_the_end_of(life):
        return
    watched = os.getpid()
    try:
        this = os.pidfd_open(watched)  # (the very process: its pid may be reused after it)
    except (AttributeError, OSError):
        this = None
    try:
        watcher = os.fork()
    except OSError:  # (no process to spare: watched by nothing, the work goes on)
        watcher = -1
    if watcher:
        os.close(life)
        if this is not None:
            os.close(this)
        return
    try:  # the watcher: nothing of the command's, no output
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # (the terminal's Ctrl-C is the child's)
        kept = sorted({life} | ({this} if this is not None else set()))
        os.closerange(0, kept[0])
        if len(kept) > 1:
            os.closerange(kept[0] + 1, kept[1])
        os.closerange(kept[-1] + 1, 1 << 20)
        while True:
            try:
                if not os.read(life, 1):
                    break
            except InterruptedError:
                continue
        if this is not None:
            signal.pidfd_send_signal(this, signal.SIGKILL)
        elif os.getppid() == watched:  # (still its parent: it runs)
            os.kill(watched, signal.SIGKILL)
    except BaseException:
        pass
    finally:
        os._exit(0)


def _killed_by_the_end_of(life: int) -> bool:
    """Whether the system now kills this process (SIGKILL) when ``life``'s writers are gone:
    ``life`` (the read end of the pipe, kept open) signals its owner, this process, when its
    last writer closes (``O_ASYNC``; ``F_SETSIG`` makes the signal SIGKILL, which a hung C
    call cannot hold back, and the owner is this very process, not a number a later one may
    reuse). Checked once set: a guardian already gone sent nothing, and this process ends
    now. False, with nothing set, where the system has no such signal (``F_SETSIG`` is
    Linux's): the caller forks a watcher instead."""
    try:
        import fcntl

        fcntl.fcntl(life, fcntl.F_SETOWN, os.getpid())
        fcntl.fcntl(life, fcntl.F_SETSIG, signal.SIGKILL)
        fcntl.fcntl(life, fcntl.F_SETFL, fcntl.fcntl(life, fcntl.F_GETFL) | os.O_ASYNC)
    except (ImportError, AttributeError, OSError):
        return False
    import select

    ended = select.poll()  # (poll, not select: any descriptor number)
    ended.register(life, select.POLLIN)
    if ended.poll(0):  # (its end already read, or hung up: the guardian is gone)
        os.kill(os.getpid(), signal.SIGKILL)
    return True


def die_with(parent: int) -> None:
    """Be killed when the parent process ends (Linux): in a process group of its own, a worker
    no longer hears the terminal's or the CI runner's signals, and a hung one would run on."""
    try:
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        return
    if os.getppid() != parent:  # it ended before the request
        os._exit(1)


def end_after(target) -> None:
    """Run ``target()``, then end this (forked) process: 0, the status of a SystemExit, or 1
    after an exception it prints; its standard streams flushed. A forked process never returns
    into the callers of the process it was forked from."""
    code = 1
    try:
        target()
        code = 0
    except SystemExit as ended:
        code = 0 if ended.code is None else ended.code if isinstance(ended.code, int) else 1
    except BaseException:
        import traceback

        traceback.print_exc()
    finally:
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (AttributeError, OSError, ValueError):
                pass
        os._exit(code)
