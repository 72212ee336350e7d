"""Alternating timings of commands in CPU time (the load-independent measure on a shared host:
the CPU time of the child processes, from ``resource.getrusage``), with wall time and the load
average beside each figure."""

from __future__ import annotations

import os
import resource
import signal
import statistics
import subprocess
import time


class Hung(RuntimeError):
    """A timed command did not finish within its timeout (urdfdom's check_urdf loops for ever
    on a kinematic cycle below the root)."""


def run_once(command, timeout: float | None = None, check: bool = False,
             **kwargs) -> tuple[float, float]:
    """(CPU time, wall time) in [s] of one run of ``command`` (a list, or a shell string).
    ``timeout`` [s]: past it the command and every process it started (a shell loop's current
    check_urdf too: they run in a session of their own) are killed and :class:`Hung` raised.
    ``check``: a command that fails raises ``subprocess.CalledProcessError``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               shell=isinstance(command, str), start_new_session=True, **kwargs)
    try:
        process.wait(timeout)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        process.wait()
        raise Hung(f"{command if isinstance(command, str) else ' '.join(map(str, command))} "
                   f"did not finish in {timeout:g} s") from None
    wall = time.perf_counter() - start
    if check and process.returncode:
        raise subprocess.CalledProcessError(process.returncode, command)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime, wall


class Series:
    """The samples of one command: CPU and wall times in [s]."""

    def __init__(self):
        self.cpu, self.wall = [], []

    @property
    def median(self) -> float:
        return statistics.median(self.cpu)

    def text(self) -> str:
        return (f"{self.median * 1e3:.0f} ms cpu [{min(self.cpu) * 1e3:.0f}-"
                f"{max(self.cpu) * 1e3:.0f}], {statistics.median(self.wall) * 1e3:.0f} ms wall")


def alternating(commands: dict, repeat: int = 7, env: dict | None = None) -> dict:
    """name -> Series of each command of ``commands`` (name -> command, (command,
    environment), or (command, environment, timeout [s]): see :func:`run_once`), run in turn
    ``repeat`` times (one warm-up round first, not counted), so that each meets the same
    load."""
    found = {name: Series() for name in commands}
    for round_ in range(repeat + 1):
        for name, command in commands.items():
            command, environment, *timeout = command if isinstance(command, tuple) \
                else (command, env)
            cpu, wall = run_once(command, *timeout, env=environment)
            if round_:
                found[name].cpu.append(cpu)
                found[name].wall.append(wall)
    return found


def best_of(function, repeats: int = 3, clock=time.perf_counter) -> float:
    """The shortest of ``repeats`` in-process runs of ``function`` in [s] of ``clock``."""
    best = float("inf")
    for _ in range(repeats):
        start = clock()
        function()
        best = min(best, clock() - start)
    return best


def load() -> str:
    return "load {:.1f}/{:.1f}/{:.1f}".format(*os.getloadavg())
