"""Check many files in worker processes, each file within a time budget.

Each worker is a forked process that checks one file at a time and sends the findings back over
a pipe. A worker that overruns the budget is killed (a hung xacro expression cannot be
interrupted from inside) and replaced; its file gets a U015 finding and the run goes on.
Results come back in the order the files were given, whatever order the workers finish in.
"""

from __future__ import annotations

import multiprocessing
import os
import time
from multiprocessing.connection import wait

from .diagnostics import Finding, Location, display_path
from .engine import CheckOptions, FileResult, check_file

DEFAULT_TIMEOUT = 60.0  # [s] per file


def default_jobs() -> int:
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1


def check_files(files: list[str], options_for, jobs: int | None = None,
                timeout: float | None = DEFAULT_TIMEOUT) -> list[FileResult]:
    """Check ``files`` (``options_for(path) -> CheckOptions``) and return results in order.

    jobs: worker processes [default: the number of cores]; timeout: budget per file in [s],
    None or 0 for none. Without a budget and with one job, files are checked in this process.
    """
    jobs = max(1, jobs or default_jobs())
    all_here = not timeout and jobs == 1 or "fork" not in multiprocessing.get_all_start_methods()
    results: list[FileResult | None] = [None] * len(files)
    queue = []
    for index, path in enumerate(files):
        if all_here or path == "-":  # stdin is only readable in this process
            results[index] = _without_robot(check_file(path, options_for(path)))
        else:
            queue.append(index)
    if queue:
        _run_pool(files, queue, options_for, min(jobs, len(queue)), timeout or None, results)
    return results


def _without_robot(result: FileResult) -> FileResult:
    return FileResult(result.path, result.findings)


def _worker(connection, files, options_for):
    while True:
        index = connection.recv()
        if index is None:
            return
        try:
            result = check_file(files[index], options_for(files[index]))
            connection.send((index, result.findings))
        except BaseException as error:  # report, never die silently
            connection.send((index, [_internal(files[index], f"{type(error).__name__}: {error}")]))


class _Worker:
    def __init__(self, context, files, options_for):
        self.connection, child = context.Pipe()
        self.process = context.Process(target=_worker, args=(child, files, options_for),
                                       daemon=True)
        self.process.start()
        child.close()
        self.index: int | None = None
        self.started = 0.0

    def give(self, index: int) -> None:
        self.index, self.started = index, time.monotonic()
        self.connection.send(index)

    def stop(self, kill: bool = False) -> None:
        if kill:
            self.process.kill()
        else:
            try:
                self.connection.send(None)
            except OSError:
                self.process.kill()
        self.process.join(5)
        if self.process.is_alive():
            self.process.kill()
            self.process.join()
        self.connection.close()


def _run_pool(files, queue, options_for, jobs, timeout, results) -> None:
    context = multiprocessing.get_context("fork")
    pending = list(reversed(queue))
    workers = [_Worker(context, files, options_for) for _ in range(jobs)]
    try:
        for worker in workers:
            if pending:
                worker.give(pending.pop())
        while any(worker.index is not None for worker in workers):
            busy = [w for w in workers if w.index is not None]
            wait_for = None
            if timeout:
                wait_for = max(0.0, min(w.started + timeout for w in busy) - time.monotonic())
            ready = wait([w.connection for w in busy], wait_for)
            for position, worker in enumerate(workers):
                if worker.index is None:
                    continue
                failure = None  # the finding of a file whose worker is lost
                if worker.connection in ready:
                    try:
                        index, findings = worker.connection.recv()
                    except (EOFError, OSError):
                        worker.process.join(5)
                        failure = _internal(files[worker.index], "worker process died "
                                            f"(exit code {worker.process.exitcode})")
                    else:
                        results[index] = FileResult(files[index], findings)
                elif timeout and time.monotonic() - worker.started >= timeout:
                    failure = _timeout(files[worker.index], timeout)
                else:
                    continue
                if failure is not None:
                    results[worker.index] = FileResult(files[worker.index], [failure])
                    worker.stop(kill=True)
                    workers[position] = worker = _Worker(context, files, options_for)
                worker.index = None
                if pending:
                    worker.give(pending.pop())
    finally:
        for worker in workers:
            worker.stop(kill=worker.index is not None)


def _timeout(path: str, seconds: float) -> Finding:
    return _finding("U015", path, f"checking took longer than {seconds:g} s and was stopped "
                                  "(raise the budget with --timeout)")


def _internal(path: str, message: str) -> Finding:
    return _finding("U900", path, f"internal error: {message}")


def _finding(code: str, path: str, message: str) -> Finding:
    from .rules import registered

    return registered(code).finding(message, Location(display_path(path)))


__all__ = ["check_files", "default_jobs", "DEFAULT_TIMEOUT", "CheckOptions"]
