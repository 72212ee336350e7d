"""Run work in forked worker processes, each piece within a time and memory budget.

Each worker is a forked process that does one piece of work at a time and sends the result back
over a pipe. Its address space is capped (``--max-memory``), so an allocation over the budget
raises MemoryError in the worker instead of taking the machine's memory. A worker that overruns
the time budget is killed with every process it started (a hung xacro expression cannot be
interrupted from inside) and replaced. Either way the piece ends with a :class:`Stop` that says
where the work was (see :mod:`urdftool.budget`), and the run goes on. Results come back in the
order given, whatever order the workers finish in. What a worker prints goes to this process's
standard streams: directly when they are files, passed on over the pipe when they are not (under
a test runner). The rules are imported before the workers that check files are forked, so that
each inherits them rather than importing them again.

``run_budgeted`` is the general form every command uses; ``check_files`` checks many robot files;
``check_paths`` is ``urdftool check`` (settings, targets, budgets, exit code) and ``check_file``
one file in this process, as an editor has it (both are the public API: ``urdftool.check_paths``).
"""

from __future__ import annotations

import io
import os
import signal
import sys
import time
from collections.abc import Mapping
from dataclasses import dataclass, field

from urdftool import budget as budgets
from urdftool.budget import DEFAULT_TIMEOUT, Budget
from urdftool.description.run_memo import one_run
from urdftool.diagnostics import Finding, Location, Severity, display_path
from urdftool.errors import SettingsError
from urdftool.lint.options import CheckOptions, FileResult
from urdftool.lint.settings import CheckRequest, Companions, check_companions, for_file


def default_jobs() -> int:
    """The number of cores this process may run on."""
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1


FILES_PER_WORKER = 4  # a worker pays for its own lazy imports (numpy) and mesh reads


def auto_jobs(files: int) -> int:
    """How many workers check ``files`` files when ``--jobs`` is not given: one per core that
    is idle now (the cores less the load average), and at most one per FILES_PER_WORKER files.
    Two workers cost more CPU than one (each imports and reads again what the other did), so
    they finish sooner only on a core nobody else uses: on a busy machine, one."""
    try:
        busy = os.getloadavg()[0]
    except (AttributeError, OSError):
        busy = 0.0
    idle = max(1, round(default_jobs() - busy))
    return max(1, min(idle, files // FILES_PER_WORKER))


@dataclass(frozen=True)
class Stop:
    """Why a piece of work ended without a result.

    kind: 'time' (over the time budget), 'memory' (MemoryError, over the memory budget or out of
        memory), 'died' (the worker process ended; ``detail`` says how), 'crash' (an
        exception; ``detail`` is its traceback) or 'cancelled' (the caller no longer wanted it)
    where: the location the work had reached, when known
    """

    kind: str
    budget: Budget
    detail: str = ""
    where: Location | None = None


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


def _here(index, work, budget, stopped):
    budgets.working_at(None)
    try:
        return work(index)
    except MemoryError:
        return stopped(index, Stop("memory", budget, where=budgets.where()))


def check_files(files: list[str], options_for, jobs: int | None = None,
                timeout: float | None = DEFAULT_TIMEOUT,
                memory: int | None = None, stdin_as: str | None = None,
                cache=None, finished=None) -> list[FileResult]:
    """Check ``files`` (``options_for(path) -> CheckOptions``) and return results in order.

    jobs: worker processes [default: :func:`auto_jobs`]; timeout: budget per file in [s],
    memory: address space per worker in [bytes]; None or 0 for no limit. Without a budget and
    with one job, files are checked in this process. Standard input ('-') is read here.
    stdin_as: the path standard input is checked as (its includes and packages are found from
        there, its findings name it), as an editor sends an unsaved buffer
    cache: a :class:`~urdftool.lint.cache.Cache`: files whose result it holds are not checked
        again (looked up here, before any worker starts), the others' results are kept in it;
        standard input is never cached
    finished: called with how many of ``files`` are done (found in the cache or checked), as
        each is (progress)
    """
    with one_run():  # one view of the file system for the files (the workers inherit it)
        return _check_files(files, options_for, jobs, timeout, memory, stdin_as, cache,
                            finished or (lambda done: None))


def _check_files(files, options_for, jobs, timeout, memory, stdin_as, cache,
                 finished) -> list[FileResult]:
    budget = Budget(timeout or None, memory or None)
    stdin = {}
    if "-" in files:
        stdin["-"] = sys.stdin.buffer.read(options_for("-").max_file_size + 1)
    named = [stdin_as if path == "-" and stdin_as else path for path in files]
    kept = [cache.get(path, options_for(path)) if cache and path != "-" else None
            for path in files]
    todo = [index for index, found in enumerate(kept) if found is None]
    finished(len(files) - len(todo))
    jobs = max(1, jobs or auto_jobs(len(todo)))

    if todo:
        from urdftool.lint import engine  # noqa: F401  (before the workers fork: they inherit it)
    work = _Checking([files[i] for i in todo], [named[i] for i in todo],
                     [options_for(files[i]) for i in todo], stdin, cache)

    def stopped(index: int, stop: Stop) -> tuple[list[Finding], list[str]]:
        return [stop_finding(named[todo[index]], stop, "checking")], []

    lines: list[list[str]] = [[] for _ in files]
    checked = run_budgeted(len(todo), work, budget, stopped, jobs,
                           lambda done: finished(len(files) - len(todo) + done))
    for index, (found, companions) in zip(todo, checked):
        kept[index], lines[index] = found, companions
    return [FileResult(path, found, companions=companions)
            for path, found, companions in zip(named, kept, lines)]


@dataclass
class _Checking:
    """Checking ``paths[i]`` as ``named[i]`` with ``options[i]``, a worker's piece ``i``.
    stdin: the bytes read for '-'; cache: where results are kept, or None."""

    paths: list[str]
    named: list[str]
    options: list[CheckOptions]
    stdin: dict[str, bytes]
    cache: object = None

    def __call__(self, index: int) -> tuple[list[Finding], list[str]]:
        path, options = self.paths[index], self.options[index]
        from urdftool.lint import engine  # every rule: imported only when a file is checked

        result = engine.check_file(self.named[index], options, data=self.stdin.get(path))
        if self.cache and path != "-":
            self.cache.put(path, options, result)  # with the record of what its check read
        return result.findings, result.companions


@dataclass
class Run:
    """What checking some paths found.

    results: one per file checked, in order
    skipped: files found in folders and not checked -> why
    notes: "PATH: what happened" for files named that were checked through others or not at all
    strict: per result, whether a warning in it fails the run (its settings or the request)
    depends: for a run the result cache keeps whole, the stamps of what it was built from
        (see :mod:`urdftool.lint.cache`); None for any other
    errors: why files were not checked: the settings file that applies to them is broken
        (each message names it); the other files were checked
    """

    results: list[FileResult]
    skipped: dict[str, str] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    strict: list[bool] = field(default_factory=list)
    depends: list | None = field(default=None, repr=False)
    errors: list[str] = field(default_factory=list)

    def __post_init__(self):
        for result, strict in zip(self.results, self.strict):
            result.strict = strict
        self.strict = [result.strict for result in self.results]

    @property
    def exit_code(self) -> int:
        """0 clean, 1 when a file has an error, or a warning and is checked strictly; 2 when
        files were not checked for their broken settings (:attr:`errors`)."""
        if self.errors:
            return 2
        return 1 if any(result.failures for result in self.results) else 0


def check_paths(paths, request: CheckRequest | None = None, /, *, progress=None,
                **options) -> Run:
    """Check files and folders as ``urdftool check PATH...`` does: the settings file above each
    target applies to it, folders are walked for top-level robots, a macro library named is
    replaced by the robots including it, and files are checked in worker processes within the
    time and memory budgets.

    paths: files, folders or ``-`` (standard input); one path alone works too
    request: a :class:`~urdftool.lint.settings.CheckRequest`, or its fields as keywords
        (``select``, ``ignore``, ``strict``, ``xacro_args``, ``packages``, ``companions``,
        ``allow_env``, ``max_file_size``, ``max_triangles``, ``max_memory``, ``timeout`` [s],
        ``jobs``, ``use_settings``, ``cache_dir``); defaults as the command line's, except
        that results are kept between runs only with ``cache_dir``
    progress: called with (files done, files to check) as the files are checked
    Raises TargetError (an UrdftoolError) before anything is checked, and SettingsError when
    the settings of every file to check are broken; broken settings that apply to some files
    only are the run's ``errors``, and the other files are checked.
    """
    if request is None:
        request = _request(options)
    elif options:
        raise TypeError("check_paths takes a CheckRequest or keyword options, not both")
    check_companions(request.companions)
    if isinstance(paths, (str, os.PathLike)):
        paths = [paths]  # one path, not its characters
    with one_run():  # one view of the file system: roots and settings looked up once
        return _check_paths(list(paths), request, progress or (lambda done, planned: None))


def _check_paths(paths: list, request: CheckRequest, progress) -> Run:
    cache = None
    if request.cache_dir is not None:
        from urdftool.lint.cache import Cache

        cache = Cache(request.cache_dir)
        kept = cache.get_run(paths, request)
        if kept is not None:
            return Run(kept[0], strict=kept[1], depends=kept[2])
    from urdftool.description.record import recording
    from urdftool.lint.targets import expand  # not on a re-run served whole from the cache

    with recording() as surroundings:  # what finding targets and settings read: a run kept
        targets = expand(paths, request)  # whole depends on it
        by_path, errors = {}, []
        for path in targets.files:  # broken settings stop the files they apply to, no others
            try:
                by_path[path] = for_file(request.stdin_filename if path == "-" and
                                         request.stdin_filename else path, request)
            except SettingsError as error:
                errors.append(str(error))
    errors = list(dict.fromkeys(errors))
    if errors and not by_path:
        raise SettingsError(errors[0])
    files = [path for path in targets.files if path in by_path]
    plans = [by_path[path] for path in files]
    results: list[FileResult | None] = [None] * len(files)
    before = 0  # files of the pools already run
    for memory, timeout in dict.fromkeys((plan.memory, plan.timeout) for plan in plans):
        indexes = [i for i, plan in enumerate(plans)  # one pool per budget
                   if (plan.memory, plan.timeout) == (memory, timeout)]
        found = check_files([files[i] for i in indexes], lambda p: by_path[p].options,
                            jobs=request.jobs, timeout=timeout, memory=memory,
                            stdin_as=request.stdin_filename, cache=cache,
                            finished=lambda done: progress(before + done, len(files)))
        before += len(indexes)
        for index, result in zip(indexes, found):
            results[index] = result
    run = Run(results, targets.skipped, targets.notes, [plan.strict for plan in plans],
              errors=errors)
    if cache is not None and not errors:
        run.depends = cache.put_run(paths, request, run, lambda path: by_path[path].options,
                                    surroundings)
    return run


def check_file(path, *, data: bytes | str | None = None, **options) -> FileResult:
    """Check one file in this process, with no time budget, as an editor has it.

    data: the file's content when it is not to be read from ``path`` (an unsaved buffer);
        suppression comments are read from it too. It is read as any unsaved buffer
        (:func:`urdftool.description.files.unsaved`, which also gives the check the buffers
        of other files: included macro files, companions): recorded by its digest, and
        refused where the file would be (a link leading out of the repository)
    options: as :func:`check_paths` (the settings file above ``path`` applies, per-file ignores
        too, unless ``use_settings=False``); the result keeps the loaded ``robot`` and the
        ``record`` of what the check read, searched and followed, the settings looked for
        included (:mod:`urdftool.description.record`)
    """
    path = os.fspath(path)
    request = _request(options)
    buffers = {}
    if data is not None and path != "-":
        buffers[path], data = data, None
    if isinstance(data, str):
        data = data.encode("utf-8")
    from urdftool.description.files import unsaved
    from urdftool.description.record import recording
    from urdftool.lint import engine

    with recording() as record, unsaved(buffers):  # the settings found, and the check's own
        check_companions(request.companions)  # record
        result = engine.check_file(path, for_file(path, request).options, data=data)
    result.record = record
    return result


def _request(options: dict) -> CheckRequest:
    companions = options.get("companions")
    if isinstance(companions, Mapping):
        options = {**options, "companions": Companions(**companions)}
    return CheckRequest(**options)


def stop_finding(path: str, stop: Stop, doing: str) -> Finding:
    """The finding for work on ``path`` that ``stop`` ended; ``doing``: what it was, e.g.
    'checking'. Located where the work was, when known."""
    shown = display_path(path) if path != "-" else "<stdin>"
    where = stop.where or Location(shown)
    if path == "-" and where.file.endswith("stdin.xacro"):
        where = Location(shown, where.line, where.via)
    if stop.kind == "time":
        return _finding("U015", where, f"{doing} took longer than {stop.budget.seconds:g} s and "
                                       "was stopped (raise the budget with --timeout)")
    if stop.kind == "memory":
        limit = stop.budget.memory
        needed = (f"needed more than {budgets.format_memory(limit)} of memory"
                  if limit else "ran out of memory")
        return _finding("U018", where, f"{doing} {needed} and was stopped"
                                       + (" (raise the budget with --max-memory)" if limit else ""))
    detail = stop.detail.strip().splitlines()[-1] if stop.detail.strip() else stop.kind
    if stop.kind == "died" and stop.budget.memory:  # C libraries may exit when malloc fails
        detail += (f"; it may have run out of its {budgets.format_memory(stop.budget.memory)} "
                   "of memory (--max-memory)")
    return _finding("U900", where, f"internal error: {detail}")


def _finding(code: str, where: Location, message: str) -> Finding:
    from urdftool.lint.rules import CATALOGUE

    return CATALOGUE.get(code).finding(message, where)


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
    _die_with(parent)
    budgets.report_into(slot)
    budgets.limit_memory(memory)
    for number in relay:
        setattr(sys, ("stdout", "stderr")[number - 1], io.TextIOWrapper(
            io.BufferedWriter(_Relay(connection, number)), encoding="utf-8",
            errors="backslashreplace", line_buffering=True))
    with one_run():  # one view of the file system for its pieces (a forked worker's: the block
        # it was forked in, when there was one)
        _serve_pieces(connection, work)


def _serve_pieces(connection, work) -> None:
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
        except BaseException:  # report, never die silently
            import traceback

            message = ("stop", index, "crash", traceback.format_exc())
        for stream in (sys.stdout, sys.stderr):
            stream.flush()
        try:
            connection.send(message)
        except Exception as error:  # a result that does not pickle, or memory to pickle it
            connection.send(("stop", index, "crash", f"{type(error).__name__}: {error}"))


def _die_with(parent: int) -> None:
    """Be killed when the parent process ends (Linux): in a process group of its own, a worker
    no longer hears the terminal's or the CI runner's signals, and a hung one would run on."""
    try:
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        return
    if os.getppid() != parent:  # it ended before the request
        os._exit(1)


# ---- in the parent -------------------------------------------------------------------------

class _Worker:
    def __init__(self, context, work, memory):
        self.connection, child = context.Pipe()
        self.slot = budgets.share_slot()
        self.relay = _relayed()
        # not a daemon: a worker may start processes of its own (collisions --matrix)
        self.process = context.Process(target=_serve, args=(child, self.slot, work, memory,
                                                            self.relay, os.getpid()))
        self.process.start()
        try:
            os.setpgid(self.process.pid, self.process.pid)
        except OSError:
            pass  # already done by the worker, or it has ended
        child.close()
        self.index: int | None = None
        self.started = 0.0

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
    import multiprocessing
    from multiprocessing.connection import wait

    context = multiprocessing.get_context("fork")
    timeout = budget.seconds
    pending = list(reversed(queue))
    ended = 0
    workers = [_Worker(context, work, budget.memory) for _ in range(jobs)]
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
            ready = wait([w.connection for w in busy], wait_for)
            for position, worker in enumerate(workers):
                if worker.index is None:
                    continue
                stop = None  # why the worker's piece has no result
                if worker.connection in ready:
                    message = _receive(worker)
                    if message == ():
                        continue
                    if message is None:
                        worker.process.join(5)
                        stop = Stop("died", budget, "worker process died (exit code "
                                                    f"{worker.process.exitcode})")
                    elif message[0] == "stop":
                        stop = Stop(message[2], budget, message[3])
                    else:
                        results[message[1]] = message[2]
                elif timeout and time.monotonic() - worker.started >= timeout:
                    stop = Stop("time", budget)
                else:
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
                        workers[position] = worker = _Worker(context, work, budget.memory)
                worker.index = None
                ended += 1
                finished(ended)
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


__all__ = ["Budget", "CheckOptions", "CheckRequest", "DEFAULT_TIMEOUT", "FileResult", "Run", "Stop",
           "auto_jobs", "check_file", "check_files", "check_paths", "default_jobs", "run_budgeted",
           "stop_finding"]
