"""The guardian's child dies with it (:func:`urdftool.guardian.watched_by`)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest

from conftest import guardian_and_child

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="the guardian forks")

# the child says its pid, whether ctypes was imported, then hangs (as a C call can)
_HANGS = ("import os, sys, time\nfrom urdftool import guardian\n"
          "if guardian.guarded() is None:\n"
          "    print(os.getpid(), 'ctypes' in sys.modules, flush=True)\n"
          "    time.sleep(120)\n")


def _state(pid: int) -> str:
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0]
    except FileNotFoundError:
        return "gone"


@pytest.mark.skipif(not os.path.isdir("/proc/self"), reason="reads /proc")
def test_a_child_dies_when_its_guardian_is_killed_without_ctypes():
    """A guardian killed (SIGKILL: a CI runner's timeout) leaves no child to run on unwatched,
    the child hung where it cannot notice; and the guarantee costs the child no ``ctypes``
    (its import cost a plain check more than the watcher's fork)."""
    guardian = subprocess.Popen([sys.executable, "-c", _HANGS], stdout=subprocess.PIPE,
                                text=True)
    try:
        pid, ctypes = guardian.stdout.readline().split()
        child = int(pid)
        assert ctypes == "False"
        assert _state(child) not in ("gone", "Z")
        os.kill(guardian.pid, signal.SIGKILL)
        guardian.wait(timeout=30)
        deadline = time.monotonic() + 30
        while _state(child) not in ("gone", "Z") and time.monotonic() < deadline:
            time.sleep(0.02)
        assert _state(child) in ("gone", "Z")
    finally:
        guardian.kill()
        guardian.wait()


def test_a_child_whose_watcher_cannot_be_forked_still_does_the_work():
    """No process to spare for the watcher (EAGAIN): the child goes on unwatched, as it did
    where ``PR_SET_PDEATHSIG`` was missing, rather than failing the command."""
    setup = ("real, forks = os.fork, []\n"
             "def fork():\n    forks.append(1)\n"
             "    if len(forks) == 2:\n        raise BlockingIOError(11, 'no process')\n"
             "    return real()\n"
             "os.fork = fork\n")
    assert guardian_and_child(setup) == ["[child]", "[guardian (0, None)]"]


def test_the_guardian_imports_nothing_once_it_has_forked():
    """What the guardian's wait needs is imported before the fork: a module loaded after it
    made the guardian copy pages it shares with its child (select's load: some 140 of the
    check's page faults)."""
    setup = ("import sys\nreal = os.fork\nforked = []\n"
             "def fork():\n    forked.append(set(sys.modules))\n    return real()\n"
             "os.fork = fork\n")
    said = " {sorted(set(sys.modules) - forked[0])}"
    assert guardian_and_child(setup, said) == ["[child]", "[guardian (0, None) []]"]
