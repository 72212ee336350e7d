"""benchmarks/timing.py: a timed command that never returns is stopped, with what it started."""

from __future__ import annotations

import os
import subprocess
import time

import pytest

from benchmarks.timing import Hung, alternating, run_once


def test_a_command_past_its_timeout_is_stopped_with_the_processes_it_started(tmp_path):
    """A shell loop running a command that never returns (check_urdf on a kinematic cycle
    below the root): the timeout stops the loop and the command, not the shell alone."""
    pid_file = tmp_path / "pid"
    start = time.perf_counter()
    with pytest.raises(Hung, match="did not finish in 0.5 s"):
        run_once(f"sleep 60 & echo $! > {pid_file}; wait", timeout=0.5)
    assert time.perf_counter() - start < 10
    child = int(pid_file.read_text())
    for _ in range(50):  # (killed; reaped by init a moment later)
        try:
            os.kill(child, 0)
        except ProcessLookupError:
            break
        with open(f"/proc/{child}/stat") as stat:
            if stat.read().split(") ")[1].startswith("Z"):
                break
        time.sleep(0.1)
    else:
        pytest.fail(f"the shell's child {child} still runs")


def test_a_timeout_that_does_not_fire_changes_nothing():
    cpu, wall = run_once(["true"], timeout=30)
    assert 0 <= cpu and 0 < wall < 30


def test_alternating_takes_a_timeout_with_a_command_and_check_says_a_failure():
    with pytest.raises(Hung):
        alternating({"stuck": (["sleep", "60"], None, 0.3)}, repeat=1)
    assert len(alternating({"quick": (["true"], None, 30)}, repeat=2)["quick"].cpu) == 2
    with pytest.raises(subprocess.CalledProcessError):
        run_once(["false"], check=True)
