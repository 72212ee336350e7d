"""Run work in forked worker processes, each piece within a time and memory budget.

Each worker is a forked process that does one piece of work at a time and sends the result back
over a pipe. Its address space is capped (``--max-memory``), so an allocation over the budget
raises MemoryError in the worker instead of taking the machine's memory. A worker that overruns
the time budget is killed with every process it started (a hung xacro expression cannot be
interrupted from inside) and replaced. Either way the piece ends with a :class:`Stop` that says
where the work was (see :mod:`urdftool.budget`), and the run goes on. Results come back in the
order given, whatever order the workers finish in. What a worker prints goes to this process's
standard streams: directly when they are files, passed on over the pipe when they are not (under
a test runner). Workers are forked, so they inherit what this process imported before: callers
import what their work needs first (the runner imports the rules).

The pool knows no rule and no file format: ``run_budgeted`` is the general form every budgeted
command, the checks (:mod:`urdftool.lint.runner`), crosscheck's loaders and the language server
use; what a :class:`Stop` is reported as is the engine's (``engine.stop_finding``).
"""

from __future__ import annotations

import errno
import io
import os
import signal
import sys
import time

from urdftool import budget as budgets, guardian
from urdftool.budget import Budget
from urdftool.guardian import end_after
from urdftool.description.run_memo import one_run
from urdftool.errors import described
from urdftool.diagnostics import Location
from urdftool.records import Frozen


def default_jobs() -> int:
    """The number of cores this process may run on."""
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1


FILES_PER_WORKER = 4  # a worker pays for its own lazy imports (numpy) and mesh reads


def auto_jobs(files: int) -> int:
    """How many workers check ``files`` files when ``--jobs`` is not given: one per core that
    is idle now (the cores less what keeps them busy: :func:`urdftool.budget.busy_cores`), and
    at most one per FILES_PER_WORKER files. Two workers cost more CPU than one (each imports and
    reads again what the other did), so they finish sooner only on a core nobody else uses: on
    a busy machine, one."""
    most = files // FILES_PER_WORKER
    if most <= 1:
        return 1  # (the machine's load is not read: nothing to decide)
    cores = default_jobs()
    # (busy enough to leave at most one core idle: one worker, however many more are found)
    idle = max(1, round(cores - budgets.busy_cores(enough=cores - 1.5)))
    return max(1, min(idle, most))


class Stop(Frozen):
    """Why a piece of work ended without a result.

    kind: 'time' (over the time budget), 'memory' (MemoryError, over the memory budget or out of
        memory), 'died' (the worker process ended; ``detail`` says how), 'crash' (an
        exception; ``detail`` is its traceback) or 'cancelled' (the caller no longer wanted it)
    where: the location the work had reached, when known
    """

    kind: str
    budget: Budget
    detail: str
    where: Location | None

    __slots__ = ("kind", "budget", "detail", "where")

    def __init__(self, kind: str, budget: Budget, detail: str = "",
                 where: Location | None = None) -> None:
        set_field = object.__setattr__
        set_field(self, "kind", kind)
        set_field(self, "budget", budget)
        set_field(self, "detail", detail)
        set_field(self, "where", where)


def run_budgeted(count: int, work, budget: Budget, stopped, jobs: int = 1,
                 finished=None, cancel=None) -> list:
    """``[work(i) for i in range(count)]``, each call within ``budget`` in one of up to ``jobs``
    forked workers; a call that ends without a result gives ``stopped(i, Stop)`` instead.

    Without a budget, with one job or one call (or where processes cannot fork) the work is
    done in this process, and only a MemoryError becomes a Stop.
    finished: called in this process with how many calls have ended, as each ends (progress)
    cancel: a ``threading.Event`` another thread sets when it no longer wants the results (a
        language server's document changed again): the workers are killed within
        :data:`CANCEL_POLL` and every call not done gives ``stopped(i, Stop('cancelled'))``.
        With it, the work is always done in a worker (only a worker can be stopped).
    """
    finished = finished or (lambda done: None)
    if count == 1 and cancel is None and not budget.unlimited:
        guardian.STATE["pieces"] += 1  # (the same count in the guardian's run again: a verdict's)
        verdict = guardian.STATE["verdict"]
        if verdict is not None and verdict[0] == guardian.STATE["pieces"]:
            guardian.STATE["verdict"] = None  # (given once)
            result = [stopped(0, Stop(verdict[1], budget, verdict[2],
                                      budgets.read_slot(verdict[3])))]
        elif guardian.STATE["guardian"] is not None:
            result = [_guarded_piece(work, budget, stopped)]
        else:
            result = None
        if result is not None:
            finished(1)
            return result
    if count == 0 or not hasattr(os, "fork") or \
            cancel is None and budget.unlimited and min(jobs, count) == 1:
        results = []
        for index in range(count):
            results.append(_here(index, work, budget, stopped))
            finished(index + 1)
        return results
    results: list = [None] * count
    _run_pool(work, list(range(count)), min(jobs, count), budget, stopped, results, finished,
              cancel)
    return results


CANCEL_POLL = 0.1  # [s] how often a pool looks whether it was cancelled


def out_of_memory(error: BaseException) -> bool:
    """Whether ``error`` is the memory budget's doing though not a MemoryError: under a small
    address-space cap, importing a module fails to map its shared library (ImportError) and
    the system refuses allocations (ENOMEM); Python 3.11 that cannot map the next chunk of its
    frame stack for a call raises SystemError ("error return without exception set"), and the
    next call made there (a U900 finding built) ended the worker with a segmentation fault.
    Such a piece is stopped as over its memory (U018), as a MemoryError is, never reported as
    a crash with a traceback."""
    if isinstance(error, OSError) and error.errno == errno.ENOMEM:
        return True
    if isinstance(error, SystemError) and str(error) == "error return without exception set":
        import resource

        return resource.getrlimit(resource.RLIMIT_AS)[0] != resource.RLIM_INFINITY
    return isinstance(error, ImportError) and any(
        words in str(error) for words in ("failed to map segment", "Cannot allocate memory"))


# ---- one piece in this process, under the guardian (urdftool.guardian) ------------------

def _guarded_piece(work, budget: Budget, stopped):
    """``work(0)`` in this process under its guardian: its memory capped (a MemoryError gives
    a Stop, as in a worker), its start and end told, the guardian kills it over its time."""
    import resource

    channel, slot = guardian.STATE["guardian"]
    slot[:4] = bytes(4)
    budgets.report_into(slot)
    _tell_guardian(channel, f"start {guardian.STATE['pieces']} {budget.seconds or 0}\n")
    limits = resource.getrlimit(resource.RLIMIT_AS)
    budgets.limit_memory(budget.memory)
    try:
        return work(0)
    except MemoryError:
        return stopped(0, Stop("memory", budget, where=budgets.where()))
    except (Exception, SystemExit) as error:  # as a worker reports it
        if out_of_memory(error):
            return stopped(0, Stop("memory", budget, where=budgets.where()))
        import traceback

        return stopped(0, Stop("crash", budget, traceback.format_exc(), budgets.where()))
    finally:
        resource.setrlimit(resource.RLIMIT_AS, limits)
        _tell_guardian(channel, f"end {guardian.STATE['pieces']} 0\n")


def _tell_guardian(channel: int, line: str) -> None:
    """Tell the guardian a piece's start or end; a guardian that is gone (killed with its
    watcher first: nothing killed this process) leaves the work to go on unwatched, as where no
    guardian could be forked, its result printed, never a BrokenPipeError's traceback."""
    try:
        _write_all(channel, line.encode())
    except OSError:
        pass


def _here(index, work, budget, stopped):
    budgets.working_at(None)
    try:
        return work(index)
    except MemoryError:
        return stopped(index, Stop("memory", budget, where=budgets.where()))


# ---- in the worker -------------------------------------------------------------------------

class _Relay(io.RawIOBase):
    """A stream of the worker whose bytes go over the pipe to the parent's stream."""

    def __init__(self, connection, number: int):
        self.connection, self.number = connection, number

    def writable(self) -> bool:
        return True

    def write(self, data) -> int:
        self.connection.send(("write", self.number, bytes(data)))
        return len(data)


def _has_file(stream) -> bool:
    try:
        return stream.fileno() >= 0
    except (AttributeError, OSError, ValueError):
        return False


def _serve(connection, slot, work, memory: int | None, relay: tuple[int, ...],
           parent: int) -> None:
    """The worker: do the piece of work it is sent, until told to stop. ``parent``: the pid of
    the process that started it, taken before the fork (read here, it could already be the
    reaper's when the parent died first)."""
    try:
        os.setpgid(0, 0)  # its own process group: a kill reaches what it starts (dot, pools)
    except OSError:
        pass
    guardian.die_with(parent)
    budgets.report_into(slot)
    budgets.limit_memory(memory)
    for number in relay:
        setattr(sys, ("stdout", "stderr")[number - 1], io.TextIOWrapper(
            io.BufferedWriter(_Relay(connection, number)), encoding="utf-8",
            errors="backslashreplace", line_buffering=True))
    with one_run():  # one view of the file system for its pieces (a forked worker's: the block
        # it was forked in, when there was one)
        _serve_pieces(connection, work, memory)


def _serve_pieces(connection, work, memory: int | None = None) -> None:
    """Do each piece sent, until told to stop, or until the worker has grown past half its
    memory budget (:func:`urdftool.budget.grown`): it then says so with the piece's result
    (``("done", index, result, True)``) and ends, and the parent starts a fresh one."""
    born = budgets.address_space() or 0
    while True:
        try:
            index = connection.recv()
        except (EOFError, OSError):
            return
        if index is None:
            return
        budgets.working_at(None)
        try:
            message = ("done", index, work(index))
        except MemoryError:
            message = ("stop", index, "memory", "")
        except BaseException as error:  # report, never die silently
            import traceback

            message = ("stop", index, "memory", "") if out_of_memory(error) else \
                ("stop", index, "crash", traceback.format_exc())
        for stream in (sys.stdout, sys.stderr):
            stream.flush()
        retiring = message[0] == "done" and budgets.grown(memory, born)
        try:
            connection.send((*message, True) if retiring else message)
        except Exception as error:  # a result that does not pickle, or memory to pickle it
            connection.send(("stop", index, "crash", described(error)))
        if retiring:
            return


# ---- in the parent -------------------------------------------------------------------------

class _Worker:
    def __init__(self, work, memory):
        self.slot = budgets.share_slot()
        self.relay = _relayed()
        self.connection, child = _channels()
        parent = os.getpid()
        # not a daemon: a worker may start processes of its own (collisions --matrix)
        self.process = _Forked(lambda: _serve(child, self.slot, work, memory, self.relay,
                                              parent), (self.connection,))
        try:
            os.setpgid(self.process.pid, self.process.pid)
        except OSError:
            pass  # already done by the worker, or it has ended
        child.close()
        self.index: int | None = None
        self.started = 0.0
        self.served = 0  # pieces it has done

    def give(self, index: int) -> None:
        self.index, self.started = index, time.monotonic()
        self.slot[:4] = bytes(4)
        self.connection.send(index)

    def kill(self) -> None:
        try:
            os.killpg(self.process.pid, signal.SIGKILL)
        except OSError:
            pass
        self.process.kill()

    def stop(self, kill: bool = False) -> None:
        if kill:
            self.kill()
        else:
            try:
                self.connection.send(None)
            except OSError:
                self.kill()
        self.process.join(5)
        if self.process.is_alive():
            self.kill()
            self.process.join()
        self.connection.close()
        self.slot.close()


# ---- processes and pipes without multiprocessing (whose import costs a one-file check more
# than its worker needs): a forked process, and two pipes carrying pickled messages

class _Channel:
    """One end of a two-way channel: pickled messages, each after its length (8 bytes)."""

    def __init__(self, read: int, write: int):
        self.read, self.write = read, write

    def fileno(self) -> int:
        return self.read

    def send(self, message) -> None:
        import pickle

        data = pickle.dumps(message, pickle.HIGHEST_PROTOCOL)
        _write_all(self.write, len(data).to_bytes(8, "big"))
        _write_all(self.write, data)

    def recv(self):
        """The next message; EOFError when the other end is closed."""
        import pickle

        return pickle.loads(_read_exactly(self.read, int.from_bytes(_read_exactly(self.read, 8),
                                                                     "big")))

    def poll(self) -> bool:
        """Whether a message (or the end) is ready to be read."""
        return bool(_ready([self], 0))

    def close(self) -> None:
        for fd in (self.read, self.write):
            try:
                os.close(fd)
            except OSError:
                pass
        self.read = self.write = -1


def _channels() -> tuple[_Channel, _Channel]:
    """The two ends of a new channel (made before a worker forks: pickle, which both ends
    use, is imported here once, and the worker inherits it)."""
    import pickle  # noqa: F401
    down_read, down_write = os.pipe()
    up_read, up_write = os.pipe()
    return _Channel(up_read, down_write), _Channel(down_read, up_write)


def _write_all(fd: int, data: bytes) -> None:
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view):]


def _read_exactly(fd: int, size: int) -> bytes:
    chunks, left = [], size
    while left:
        chunk = os.read(fd, min(left, 1 << 20))
        if not chunk:
            raise EOFError("the other end of the channel is closed")
        chunks.append(chunk)
        left -= len(chunk)
    return b"".join(chunks)


MAX_WAIT = 24 * 3600.0  # [s] the longest one wait for a worker's message (poll's limit is 24 days)


def _ready(channels: list, timeout: float | None) -> list:
    """The channels of ``channels`` with a message or their end to read, waiting up to
    ``timeout`` [s] (None: until one has)."""
    import select

    poller = select.poll()
    by_fd = {channel.fileno(): channel for channel in channels}
    for fd in by_fd:
        poller.register(fd, select.POLLIN)
    # poll takes at most 2**31 - 1 ms (24 days): a longer budget (--timeout 1e7) waits a day at
    # a time, and the caller, finding nothing ready, looks at the time and waits again
    wait = None if timeout is None else max(0, int(min(timeout, MAX_WAIT) * 1000 + 0.999))
    while True:
        try:
            events = poller.poll(wait)
            break
        except InterruptedError:
            continue
    return [by_fd[fd] for fd, _ in events]


class _Forked:
    """``target()`` run in a forked process, which then exits (0, or 1 after an exception
    it prints); ``closed``: the parent's channels the process closes first."""

    def __init__(self, target, closed=()):
        self.exitcode: int | None = None
        self.lost = False  # (its status taken by another wait)
        self.pid = os.fork()
        if self.pid:
            return

        def child():
            for channel in closed:
                channel.close()
            try:
                sys.stdin.close()  # (standard input is the parent's to read)
            except (AttributeError, OSError, ValueError):
                pass
            target()

        end_after(child)

    def end(self) -> str:
        """How the process ended (:func:`urdftool.guardian.ended`), once joined."""
        return "its status lost" if self.lost else guardian.ended(self.exitcode)

    def kill(self) -> None:
        if self.exitcode is None:
            try:
                os.kill(self.pid, signal.SIGKILL)
            except OSError:
                pass

    def join(self, timeout: float | None = None) -> None:
        """Wait until the process ends, at most ``timeout`` [s]."""
        deadline = None if timeout is None else time.monotonic() + timeout
        pause = 0.0005
        while self.exitcode is None:
            try:
                pid, status = os.waitpid(self.pid, 0 if deadline is None else os.WNOHANG)
            except ChildProcessError:  # reaped by another: its status is lost
                self.exitcode, self.lost = -1, True
                return
            if pid:
                self.exitcode = os.waitstatus_to_exitcode(status)
                return
            if time.monotonic() >= deadline:
                return
            time.sleep(pause)
            pause = min(pause * 2, 0.05)

    def is_alive(self) -> bool:
        self.join(0)
        return self.exitcode is None


def _relayed() -> tuple[int, ...]:
    """The standard streams (1, 2) a worker sends over its pipe: those that are not files."""
    return tuple(n for n, s in ((1, sys.stdout), (2, sys.stderr)) if not _has_file(s))


def _pass_on(number: int, data: bytes) -> None:
    """Write what a worker printed to this process's stdout (1) or stderr (2)."""
    stream = sys.stdout if number == 1 else sys.stderr
    stream.flush()
    if hasattr(stream, "buffer"):
        stream.buffer.write(data)
        stream.buffer.flush()
    else:
        stream.write(data.decode("utf-8", errors="replace"))
        stream.flush()


def _receive(worker: _Worker):
    """The worker's next message, None at its end; output it sent is passed on, giving ()."""
    try:
        message = worker.connection.recv()
    except (EOFError, OSError):
        return None
    if message[0] == "write":
        _pass_on(*message[1:])
        return ()
    return message


def _drain(worker: _Worker) -> None:
    """Pass on what a worker that is being stopped printed before."""
    try:
        while worker.connection.poll():
            message = worker.connection.recv()
            if message[0] == "write":
                _pass_on(*message[1:])
    except (EOFError, OSError):
        pass


def _run_pool(work, queue, jobs, budget: Budget, stopped, results, finished,
              cancel=None) -> None:
    timeout = budget.seconds
    pending = list(reversed(queue))
    ended, retried = 0, set()
    workers = [_Worker(work, budget.memory) for _ in range(jobs)]
    try:
        for worker in workers:
            if pending:
                worker.give(pending.pop())
        while any(worker.index is not None for worker in workers):
            busy = [w for w in workers if w.index is not None]
            wait_for = None
            if timeout:
                wait_for = max(0.0, min(w.started + timeout for w in busy) - time.monotonic())
            if cancel is not None:
                if cancel.is_set():
                    _cancel(workers, pending, budget, stopped, results)
                    return
                wait_for = CANCEL_POLL if wait_for is None else min(wait_for, CANCEL_POLL)
            ready = _ready([w.connection for w in busy], wait_for)
            for position, worker in enumerate(workers):
                if worker.index is None:
                    continue
                stop = None  # why the worker's piece has no result
                # (its time looked at on every turn: a worker that prints without end is
                # always ready to be read)
                message = _receive(worker) if worker.connection in ready else ()
                if message == ():
                    if not (timeout and time.monotonic() - worker.started >= timeout):
                        continue
                    stop = Stop("time", budget)
                elif message is None:  # its end of the channel closed: it died, or will
                    worker.kill()  # (the others' budgets run on: no waiting for it to end)
                    worker.process.join()
                    stop = Stop("died", budget, f"worker process died: {worker.process.end()}")
                elif message[0] == "stop":
                    stop = Stop(message[2], budget, message[3])
                else:
                    results[message[1]] = message[2]
                    worker.served += 1
                if stop is not None and stop.kind in ("died", "memory") and worker.served and \
                        worker.index not in retried:
                    # what earlier pieces left in it may be what ran out: once more, afresh
                    retried.add(worker.index)
                    _drain(worker)
                    worker.stop(kill=True)
                    workers[position] = fresh = _Worker(work, budget.memory)
                    fresh.give(worker.index)
                    continue
                if stop is not None:
                    if stop.kind != "crash":  # a worker out of time or memory starts afresh
                        worker.kill()
                    _drain(worker)
                    where = budgets.read_slot(worker.slot)
                    results[worker.index] = stopped(worker.index, Stop(
                        stop.kind, budget, stop.detail, where))
                    if stop.kind != "crash":
                        worker.stop(kill=True)
                        workers[position] = worker = _Worker(work, budget.memory)
                worker.index = None
                ended += 1
                finished(ended)
                if stop is None and message[3:] == (True,):  # grown past half its memory
                    worker.stop()  # (it has ended)
                    workers[position] = worker = _Worker(work, budget.memory)
                if pending:
                    worker.give(pending.pop())
    finally:
        for worker in workers:
            worker.stop(kill=worker.index is not None)


def _cancel(workers, pending, budget, stopped, results) -> None:
    """Kill the busy workers at once; every piece not done gives a 'cancelled' Stop."""
    for worker in workers:
        if worker.index is not None:
            worker.kill()
            results[worker.index] = stopped(worker.index, Stop("cancelled", budget))
    for index in pending:
        results[index] = stopped(index, Stop("cancelled", budget))
    pending.clear()


__all__ = ["CANCEL_POLL", "FILES_PER_WORKER", "Stop", "auto_jobs", "default_jobs", "run_budgeted"]
