"""The budgeted pool (urdftool/lint/pool.py) against pebble's ProcessPool, on what the pool is for.

    pip install pebble && python benchmarks/pool_vs_pebble.py

Not a ``bench_*`` module (``make bench`` does not run it): pebble is not a dependency; this is
the measurement behind docs/architecture.md's paragraph on why the pool is not pebble's. Each
case, with both pools forked (fork after imports), two workers:
- many: 400 small pieces (the overhead per piece), median of 3 runs, alternating;
- stuck: one piece in a single C call (``sum(range(...))``) over a 0.5 s budget: how long
  until the caller has its Stop;
- children: a piece over its budget that started a process: is that process still running;
- printed: what a worker prints while this process's stdout is not a file (a test runner, the
  language server's stream): does it reach this process's ``sys.stdout``.
"""

from __future__ import annotations

import io
import multiprocessing
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from urdftool.budget import Budget  # noqa: E402
from urdftool.lint.pool import run_budgeted  # noqa: E402

PIECES = 400
JOBS = 2


def small(index: int) -> int:
    return sum(range(20_000)) + index


def stuck(index: int) -> int:
    return sum(range(10 ** 11))  # one C call: no Python signal handler runs until it returns


def with_child(index: int) -> int:
    child = subprocess.Popen(["sleep", "60"])
    Path(f"/tmp/pool_vs_pebble.{os.getppid()}.pid").write_text(str(child.pid))
    time.sleep(60)
    return index


def printing(index: int) -> int:
    print(f"printed {index}")
    sys.stdout.flush()
    return index


def ours(work, count: int, seconds: float) -> list:
    return run_budgeted(count, work, Budget(seconds, None), lambda i, stop: stop.kind, JOBS)


def pebbles(work, count: int, seconds: float) -> list:
    import pebble
    from concurrent.futures import TimeoutError as Timeout

    with pebble.ProcessPool(max_workers=JOBS, context=multiprocessing.get_context("fork")) as pool:
        futures = [pool.schedule(work, (i,), timeout=seconds) for i in range(count)]
        found = []
        for future in futures:
            try:
                found.append(future.result())
            except Timeout:
                found.append("time")
        return found


def timed(pool, work, count: int, seconds: float) -> tuple[float, list]:
    started = time.perf_counter()
    found = pool(work, count, seconds)
    return time.perf_counter() - started, found


def _running(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


def main() -> None:
    pools = {"urdftool pool": ours, "pebble": pebbles}
    many = {name: [] for name in pools}
    for _ in range(3):
        for name, pool in pools.items():
            seconds, found = timed(pool, small, PIECES, 30.0)
            assert found == [small(i) for i in range(PIECES)]
            many[name].append(seconds)
    for name in pools:
        print(f"many   {name:14} {PIECES} pieces: {statistics.median(many[name]) * 1000:7.1f} ms "
              f"(runs {', '.join(f'{s * 1000:.0f}' for s in many[name])})")
    for name, pool in pools.items():
        seconds, found = timed(pool, stuck, 1, 0.5)
        print(f"stuck  {name:14} 0.5 s budget, stopped after {seconds:.2f} s: {found}")
    for name, pool in pools.items():
        pid_file = Path(f"/tmp/pool_vs_pebble.{os.getpid()}.pid")
        timed(pool, with_child, 1, 0.5)
        time.sleep(0.5)
        pid = int(pid_file.read_text()) if pid_file.exists() else None
        left = pid is not None and _running(pid)
        print(f"child  {name:14} the process it started: {'still running' if left else 'ended'}")
        if left:
            os.kill(pid, 9)
        pid_file.unlink(missing_ok=True)
    for name, pool in pools.items():
        saved, sys.stdout = sys.stdout, io.StringIO()
        try:
            pool(printing, 2, 30.0)
            seen = sys.stdout.getvalue()
        finally:
            sys.stdout = saved
        print(f"print  {name:14} reached sys.stdout: {sorted(seen.split())!r}")


if __name__ == "__main__":
    main()
