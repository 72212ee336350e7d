"""The guardian's child dies with it (:func:`urdftool.guardian.watched_by`)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest

from conftest import guardian_and_child, parsed

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="the guardian forks")

# the child says its pid, whether ctypes was imported and how many processes the guardian
# has below it (its child, and a watcher if one was forked), then hangs (as a C call can)
_HANGS = ("import os, sys, time\nfrom urdftool import guardian\n"
          "if guardian.guarded() is None:\n"
          "    time.sleep(0.2)\n"
          "    print(os.getpid(), 'ctypes' in sys.modules, len(_below(os.getppid())), flush=True)\n"
          "    time.sleep(120)\n")
_BELOW = ("def _below(pid):\n"
          "    found = [int(p) for p in os.listdir('/proc') if p.isdigit() and\n"
          "             _parent(p) == pid]\n"
          "    return found + [q for p in found for q in _below(p)]\n"
          "def _parent(pid):\n"
          "    try:\n"
          "        with open(f'/proc/{pid}/stat') as stat:\n"
          "            return int(stat.read().rsplit(')', 1)[1].split()[1])\n"
          "    except (OSError, IndexError, ValueError):\n"
          "        return None\n")
# the system's signal is not to be had (F_SETSIG is Linux's): a watcher is forked instead
_NO_SETSIG = "import fcntl\ndel fcntl.F_SETSIG\n"


def _state(pid: int) -> str:
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0]
    except FileNotFoundError:
        return "gone"


@pytest.mark.skipif(not os.path.isdir("/proc/self"), reason="reads /proc")
@pytest.mark.parametrize("setup, processes", [
    pytest.param("", "1", marks=pytest.mark.skipif(not sys.platform.startswith("linux"),
                                                   reason="F_SETSIG is Linux's"),
                 id="the system's signal"),
    pytest.param(_NO_SETSIG, "2", id="a watcher")])
def test_a_child_dies_when_its_guardian_is_killed_without_ctypes(setup, processes):
    """A guardian killed (SIGKILL: a CI runner's timeout) leaves no child to run on unwatched,
    the child hung where it cannot notice; and the guarantee costs the child no ``ctypes``
    (its import cost a plain check more than the watcher's fork). On Linux the system kills
    the child, no watcher forked; elsewhere a watcher does."""
    guardian = subprocess.Popen([sys.executable, "-c", setup + _BELOW + _HANGS],
                                stdout=subprocess.PIPE, text=True)
    try:
        pid, ctypes, below = guardian.stdout.readline().split()
        child = int(pid)
        assert ctypes == "False"
        assert below == processes
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


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="F_SETSIG is Linux's")
def test_a_child_whose_guardian_ended_before_it_was_watched_ends():
    """The pipe's writer closed before the system was told to signal its end (a guardian gone
    already): no signal comes later, so the child ends at once."""
    program = ("import os\nfrom urdftool import guardian\nlife, alive = os.pipe()\n"
               "os.close(alive)\nguardian._killed_by_the_end_of(life)\nprint('ran on')\n")
    done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True,
                          timeout=60)
    assert (done.returncode, done.stdout) == (-signal.SIGKILL, "")


def test_a_child_whose_watcher_cannot_be_forked_still_does_the_work():
    """No process to spare for the watcher (EAGAIN): the child goes on unwatched, as it did
    where ``PR_SET_PDEATHSIG`` was missing, rather than failing the command."""
    setup = (_NO_SETSIG + "real, forks = os.fork, []\n"
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


@pytest.mark.parametrize("code, said", [
    (0, "exit code 0"), (127, "exit code 127"), (-signal.SIGSEGV, "killed by SIGSEGV "
                                                                   "(segmentation fault)"),
    (-signal.SIGKILL, "killed by SIGKILL (killed)"), (-200, "killed by signal 200")])
def test_a_process_end_is_said_by_its_exit_code_or_the_signals_name(code, said):
    from urdftool.guardian import ended

    assert ended(code) == said


def test_every_report_of_a_process_end_says_it_through_one_function():
    """No message formats an exit code or a return code itself (``-11`` for a segfault):
    :func:`urdftool.guardian.ended` says each."""
    import ast
    from pathlib import Path

    import urdftool

    found = []
    for path in Path(urdftool.__file__).parent.rglob("*.py"):
        tree = parsed(path.read_text(encoding="utf-8"))
        owner = [node for node in ast.walk(tree)
                 if isinstance(node, ast.FunctionDef) and node.name == "ended"
                 and path.name == "guardian.py"]
        skipped = {id(n) for o in owner for n in ast.walk(o)}
        for node in ast.walk(tree):
            if id(node) in skipped or not isinstance(node, ast.JoinedStr):
                continue
            said = [v.value for v in node.values if isinstance(v, ast.Constant)]
            formatted = {v.value.attr for v in node.values  # (not through ended)
                         if isinstance(v, ast.FormattedValue) and isinstance(v.value, ast.Attribute)}
            if formatted & {"returncode", "exitcode"} or any("exit code" in s for s in said):
                found.append(f"{path.name}:{node.lineno}")
    assert not found, found
