"""The budgeted pool: a time and memory budget per piece of work, the processes a worker started
stopped with it, workers that end with their parent, what workers print reaches this process,
cancelling from another thread, how many workers by default."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest

from conftest import guardian_and_child

from urdftool import budget
from urdftool.budget import Budget, address_space
from urdftool.lint import pool
from urdftool.lint.pool import run_budgeted


def test_a_stopped_worker_takes_the_processes_it_started_along(tmp_path):
    pid_file = tmp_path / "pid"

    def work(_):
        child = subprocess.Popen(["sleep", "60"])
        pid_file.write_text(str(child.pid))
        time.sleep(60)

    [stop] = run_budgeted(1, work, Budget(1.0, None), lambda _, stop: stop)
    assert stop.kind == "time"
    pid = int(pid_file.read_text())
    deadline = time.monotonic() + 5
    while _running(pid) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not _running(pid)


def _running(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


def test_a_worker_ends_with_its_parent(tmp_path):
    """Workers have a process group of their own, so a signal to the command's group misses
    them; they die with the command instead of running on."""
    (tmp_path / "fact.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <link name="${factorial(10**7)}"/>\n</robot>\n')
    command = subprocess.Popen([sys.executable, "-c", "from urdftool.cli import main; main()",
                                "tree", "--timeout", "100", "fact.urdf.xacro"], cwd=tmp_path,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    children = f"/proc/{command.pid}/task/{command.pid}/children"
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline and not open(children).read().split():
        time.sleep(0.05)
    [worker] = map(int, open(children).read().split())
    command.send_signal(signal.SIGTERM)
    command.wait(10)
    deadline = time.monotonic() + 5
    while _running(worker) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not _running(worker)


def test_what_a_worker_prints_reaches_this_process(capsys):
    def talk(index):
        print(f"out {index}")
        print(f"err {index}", file=sys.stderr)
        return index

    assert run_budgeted(2, talk, Budget(30.0, None), None, jobs=2) == [0, 1]
    captured = capsys.readouterr()  # streams without a file: passed on over the pipe
    assert sorted(captured.out.split("\n")) == ["", "out 0", "out 1"]
    assert sorted(captured.err.split("\n")) == ["", "err 0", "err 1"]


def test_a_worker_that_prints_without_end_is_stopped_on_time(capsys, monkeypatch):
    """Its channel is always ready to be read (here: a slow reader of what it prints): its
    time budget is looked at all the same."""
    real = pool._pass_on
    monkeypatch.setattr(pool, "_pass_on", lambda *a: (time.sleep(0.005), real(*a)))

    def shout(_):
        while True:
            print("x" * 1000)

    started = time.monotonic()
    assert run_budgeted(1, shout, Budget(0.3, None), lambda _, stop: stop.kind) == ["time"]
    assert time.monotonic() - started < 5


def test_a_worker_that_closes_its_channel_costs_no_one_else_time(tmp_path):
    """A worker whose end of the channel closes while it lives on is stopped at once; no
    other worker's piece waits for it (it had once to end on its own within 5 s)."""

    def work(index):
        if index == 0:
            os.closerange(3, 1024)  # its channel among them
            time.sleep(60)
        time.sleep(0.5)
        return index

    started = time.monotonic()
    results = run_budgeted(2, work, Budget(2.0, None), lambda _, stop: stop.kind, jobs=2)
    assert results == ["died", 1]
    assert time.monotonic() - started < 2


def test_one_call_without_a_budget_runs_in_this_process():
    import os

    unlimited = Budget(None, None)
    assert run_budgeted(1, lambda _: os.getpid(), unlimited, None, jobs=2) == [os.getpid()]
    # two calls on two jobs are spread over workers
    assert os.getpid() not in run_budgeted(2, lambda _: os.getpid(), unlimited, None, jobs=2)


def test_a_cancelled_run_kills_its_workers_at_once():
    """A language server's check of a version that has changed since: the caller sets the
    switch, the worker is killed within CANCEL_POLL, every piece not done is 'cancelled'."""
    import threading

    cancel = threading.Event()
    started = time.monotonic()
    threading.Timer(0.3, cancel.set).start()
    results = run_budgeted(3, lambda _: time.sleep(60), Budget(None, None),
                           lambda index, stop: stop.kind, cancel=cancel)
    assert results == ["cancelled"] * 3
    assert time.monotonic() - started < 5  # not the 60 s the work takes
    # with a switch, even one call without a budget runs in a worker (only it can be stopped)
    assert run_budgeted(1, lambda _: os.getpid(), Budget(None, None), None,
                        cancel=threading.Event()) != [os.getpid()]


@pytest.mark.parametrize("cores, load, files, jobs", [
    (2, 0.3, 46, 2),  # an idle second core: two workers
    (2, 12.0, 46, 1),  # a busy machine: two workers would cost more CPU for nothing
    (8, 5.2, 46, 3),  # the idle cores only
    (2, 0.0, 5, 1),  # too few files to pay a second worker's imports and reads
    (2, 0.0, 1, 1),
])
def test_the_default_jobs_follow_idle_cores_and_the_work(monkeypatch, tmp_path, cores, load,
                                                         files, jobs):
    monkeypatch.setattr(pool, "default_jobs", lambda: cores)
    monkeypatch.setattr(os, "getloadavg", lambda: (load, load, load))
    running = 1 + round(load)  # (this process, and the threads of the load)
    (tmp_path / "loadavg").write_text(f"{load:.2f} {load:.2f} {load:.2f} {running}/300 4242\n")
    monkeypatch.setattr(budget, "LOADAVG", str(tmp_path / "loadavg"))
    assert pool.auto_jobs(files) == jobs


@pytest.mark.parametrize("running, jobs", [(1, 2), (2, 1), (3, 1)])
def test_the_default_jobs_count_what_runs_now_not_only_the_last_minute(monkeypatch, tmp_path,
                                                                       running, jobs):
    """A job that started seconds ago (the 1-minute load average still near 0) keeps a core
    busy: a second worker would share it with it (slower than one, issue 34). ``running``
    counts this process too."""
    monkeypatch.setattr(pool, "default_jobs", lambda: 2)
    monkeypatch.setattr(os, "getloadavg", lambda: (0.05, 0.1, 0.1))
    (tmp_path / "loadavg").write_text(f"0.05 0.10 0.10 {running}/300 4242\n")
    monkeypatch.setattr(budget, "LOADAVG", str(tmp_path / "loadavg"))
    assert pool.auto_jobs(46) == jobs



@pytest.mark.parametrize("runs, jobs", [([1] * 6, 2), ([1, 1, 2, 1, 1, 1], 1), ([2], 1)])
def test_the_default_jobs_do_not_count_a_run_that_has_ended(monkeypatch, tmp_path, runs, jobs):
    """The user's previous check (a benchmark's previous round) left the 1-minute average at
    1.3 on 2 idle cores: one worker did the work of two (issue 34's 1.03x). The average makes
    it look a few times; work seen in any look counts (work in bursts), none: both cores."""
    monkeypatch.setattr(pool, "default_jobs", lambda: 2)
    monkeypatch.setattr(os, "getloadavg", lambda: (1.3, 1.1, 0.6))
    monkeypatch.setattr(budget.time, "sleep", lambda seconds: None)
    looks = iter(runs)
    monkeypatch.setattr(budget, "_running_now", lambda: next(looks) - 1)
    assert pool.auto_jobs(46) == jobs


def test_the_default_jobs_stop_looking_once_one_worker_is_the_answer(monkeypatch):
    """With one of 2 cores busy at the first look, more looks can only find more busy: one
    worker whatever they find. The default ``--jobs`` waited 5 looks (20 ms) for nothing, a
    core busy (make bench: 1.03x ``--jobs 1``). Not yet one, it looks again."""
    monkeypatch.setattr(pool, "default_jobs", lambda: 2)
    monkeypatch.setattr(os, "getloadavg", lambda: (2.5, 2.0, 1.0))
    slept = []
    monkeypatch.setattr(budget.time, "sleep", slept.append)
    for first, looks in ((2, 1), (1, 6)):
        slept.clear()
        monkeypatch.setattr(budget, "_running_now", lambda: first - 1)
        assert pool.auto_jobs(46) == first % 2 + 1
        assert len(slept) == looks - 1


KEPT = []  # what a worker's earlier pieces kept (a run's memo of meshes, say)
MB = 1 << 20


@pytest.fixture(autouse=True)
def _blas_mapped():
    """The budgets below are this process's address space and more: OpenBLAS's buffers,
    which a worker maps before its cap (budget.map_blas_buffers), are mapped here first, so
    that a worker starts at the size measured."""
    budget.map_blas_buffers()


def _keep(size: int) -> int:
    KEPT.append(bytearray(size))
    return os.getpid()


@pytest.mark.skipif(not os.path.exists("/proc/self/statm"), reason="Linux's /proc")
def test_a_worker_grown_past_half_its_budget_hands_the_next_piece_to_a_fresh_one():
    """mycobot_ros walked: one worker checked 86 robots in turn, what it kept grew to its 2 GiB
    and the 87th died (exit code 127). A worker past half its budget after a piece now ends,
    and the next piece starts in a fresh one."""
    half = address_space() + 300 * MB
    pids = run_budgeted(3, lambda _: _keep(200 * MB), Budget(60.0, 2 * half),
                        lambda _, stop: stop, jobs=1)
    assert all(isinstance(pid, int) for pid in pids), pids
    assert pids[0] == pids[1] != pids[2]  # 400 MB kept after the second: past half


@pytest.mark.skipif(not os.path.exists("/proc/self/statm"), reason="Linux's /proc")
def test_a_worker_born_past_half_its_budget_is_not_replaced_until_its_pieces_keep_more():
    """Forked from a process already past half the budget (a program calling the API, the
    test session that replays fuzz case 59cee68e5577: 90 files, 1.4 GB), a worker retired
    after every piece, a fresh one as large forked for the next: 90 forks, 16 s of CPU. It
    is replaced once its pieces have kept KEPT_AT_LEAST, as one born small is past half."""
    half = address_space() - 100 * MB  # already past it
    pids = run_budgeted(3, lambda _: os.getpid(), Budget(60.0, 2 * half),
                        lambda _, stop: stop, jobs=1)
    assert len(set(pids)) == 1 and all(isinstance(pid, int) for pid in pids), pids
    pids = run_budgeted(3, lambda _: _keep(budget.KEPT_AT_LEAST), Budget(60.0, 2 * half),
                        lambda _, stop: stop, jobs=1)
    assert pids[0] != pids[1] != pids[2], pids


@pytest.mark.skipif(not os.path.exists("/proc/self/statm"), reason="Linux's /proc")
def test_a_piece_that_runs_out_in_a_worker_others_filled_runs_again_afresh(monkeypatch):
    """A piece stopped for memory or death in a worker that did earlier pieces is given once
    more to a fresh worker: only there is the verdict (U900, U018) its own."""
    monkeypatch.setattr(pool.budgets, "grown", lambda size, born: False)  # the worker never retires
    start = address_space()
    # the worker starts at the size of this process: a fresh one leaves 250 MB, the one the
    # first piece filled 150 MB (a second piece the size of this process, as before, had the
    # test write 1-3 GB of zeros: 3.4 s of CPU)
    budget = Budget(60.0, start + 250 * MB)

    def work(index):  # the second fits alone, not after the first
        return _keep(100 * MB if index == 0 else 200 * MB)

    pids = run_budgeted(2, work, budget, lambda _, stop: stop, jobs=1)
    assert all(isinstance(pid, int) for pid in pids), pids
    assert pids[0] != pids[1]
    [stop] = run_budgeted(1, lambda _: _keep(budget.memory), budget, lambda _, stop: stop, jobs=1)
    assert stop.kind == "memory"  # alone, it does not fit: reported, not tried again


def test_a_worker_inherits_pickle_from_the_process_that_forked_it(tmp_path):
    """Both ends of a worker's channel pickle: the module is imported once, before the fork,
    not again in each worker (``-X importtime`` prints a line per import, in either process)."""
    import re

    robots = [tmp_path / "r.urdf", tmp_path / "s.urdf"]  # (one file: no worker, see
    for robot in robots:  # test_a_plain_check_of_one_file_forks_before_the_rules_are_imported)
        robot.write_text('<robot name="r"><link name="a"/></robot>\n')
    done = subprocess.run([sys.executable, "-X", "importtime", "-m", "urdftool", "check",
                           "--no-cache", "--jobs", "1", *map(str, robots)], capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert len(re.findall(r"\|\s+pickle$", done.stderr, re.M)) == 1, done.stderr


def test_a_guardian_gives_the_stop_to_the_piece_its_child_was_stopped_in():
    """``guarded``: the child's pieces are counted from the fork, as the guardian counts them
    when it does the work again, whatever pieces this process ran before; the verdict is given
    once, to that piece, and not left to a later run."""
    import time

    from urdftool import guardian

    budget = Budget(0.5, None)
    for _ in range(3):  # pieces of this process before
        assert run_budgeted(1, lambda index: "done", budget, lambda _, stop: stop) == ["done"]
    found = guardian.guarded()
    if found is None:  # the child: its one piece runs for a minute
        guardian.end_after(lambda: run_budgeted(1, lambda index: time.sleep(60), budget,
                                            lambda _, stop: stop))

    def never(index):
        raise AssertionError("the stopped piece is not done again")

    code, verdict = found
    assert code is None and verdict[1] == "time"
    guardian.stopped_as(verdict)
    try:
        [stop] = run_budgeted(1, never, budget, lambda _, stop: stop)
        assert stop.kind == "time" and stop.budget == budget
        assert run_budgeted(1, lambda index: "again", budget, lambda _, stop: stop) == ["again"]
    finally:
        guardian.stopped_as(None)


def test_a_guardian_forked_where_objects_were_frozen_is_still_the_parent():
    """``guarded`` in a process whose objects were frozen before (``gc.freeze()``: a check
    run earlier in it, the door's ``_collect_less``): the parent guards and the child works,
    one each. (The parent took the child's part when objects were frozen: it did the work and
    ended with ``os._exit``, in pytest-xdist a worker lost, 'node down', and the suite hung.)"""
    assert guardian_and_child("import gc\ngc.freeze()", " {gc.get_freeze_count() > 0}") == \
        ["[child]", "[guardian (0, None) True]"]


def test_a_piece_whose_guardian_is_gone_gives_its_result_not_a_broken_pipe(monkeypatch):
    """The guardian killed after its watcher (docs/attacks.md, session 9: the watcher and then
    the guardian killed; session 8 saw it once): the child's piece ran on and its end, told to
    a channel nobody reads, was a BrokenPipeError traceback in place of the check's result."""
    import mmap

    from urdftool import guardian

    read, write = os.pipe()
    os.close(read)  # the guardian is gone
    slot = mmap.mmap(-1, guardian.SLOT_SIZE)
    monkeypatch.setitem(guardian.STATE, "guardian", (write, slot))
    # the piece reports where it works into the slot: this process's later work must not
    monkeypatch.setattr(budget, "_slot", budget._slot)
    try:
        assert run_budgeted(1, lambda index: "done", Budget(5.0, None),
                            lambda _, stop: stop) == ["done"]
    finally:
        os.close(write)
        slot.close()


@pytest.mark.parametrize("how, said", [
    (lambda: os.kill(os.getpid(), signal.SIGSEGV), "killed by SIGSEGV (segmentation fault)"),
    (lambda: os._exit(3), "exit code 3")])
def test_a_worker_that_dies_is_said_to_by_the_signal_that_ended_it(how, said):
    """A segfault (a C library's) is said by the signal's name, not as "exit code -11"."""
    import faulthandler

    def work(index):
        faulthandler.disable()  # (the test runner's handler would print the worker's stack)
        how()

    [stop, _] = run_budgeted(2, work, Budget(20.0, None), lambda _, stop: stop, jobs=2)
    assert (stop.kind, stop.detail) == ("died", f"worker process died: {said}")
