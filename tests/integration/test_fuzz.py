"""Fuzzing: every kept failing input stays fixed, and short seeded slices of new cases run.

``make fuzz`` runs 10,000 cases of each mode (tests/fuzz/run.py) and the seeded slices marked
``slow`` here (a hundred in-process cases from small seeds, a few whole hostile repositories
through every command); ``make test`` replays every kept input and tests the harness.
Regression inputs that fail on today's code are listed in XFAIL with the issue-12 class they
belong to (strict: once the fix is merged the replay passes, and the entry must go).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from conftest import ROBOTS, corpus_or_skip
from slow_robots import slow_xacro
from tests.fuzz.harness import REGRESSIONS, load_regression, replay

REGRESSION_FILES = sorted(REGRESSIONS.glob("*.bin"))
CI_CASES = 100
CI_COMMAND_CASES = 4
REPLAY_SECONDS = 5  # per command; a fixed command ends well within it
XFAIL: dict[str, str] = {}  # kept input -> why it fails today (issue class, what happens)


def _param(path: Path):
    reason = XFAIL.get(path.stem)
    marks = [pytest.mark.xfail(strict=True, reason=reason)] if reason else []
    return pytest.param(path, id=path.stem, marks=marks)


@pytest.fixture(scope="module")
def preloaded():
    from tests.fuzz.child import preload

    preload()


@pytest.mark.parametrize("path", [_param(p) for p in REGRESSION_FILES])
def test_regression_input_behaves(path: Path, preloaded):
    seed, _ = load_regression(path)
    if not seed.path.exists():
        corpus_or_skip()
        pytest.skip(f"seed {seed.path} is missing")
    assert replay(path, time_limit=REPLAY_SECONDS) == []


def test_every_xfail_names_a_kept_input():
    assert sorted(set(XFAIL) - {p.stem for p in REGRESSION_FILES}) == []


@pytest.mark.slow  # generated breadth: make fuzz runs the mode at length
def test_seeded_fuzz_slice():
    corpus_or_skip()
    from tests.fuzz.run import run

    stats = run(CI_CASES, seed=20240601, max_seed_bytes=50_000)
    assert stats["cases"] == CI_CASES
    assert stats["failures"] == 0, "see the FAIL lines above; inputs kept in tests/fuzz/regressions"


# ------------------------------------------------------------------ the harness itself


@pytest.fixture
def scratch_case(tmp_path):
    from tests.fuzz.child import Allow

    repo, scratch = tmp_path / "repo", tmp_path / "scratch"
    (repo / ".git").mkdir(parents=True)
    scratch.mkdir()
    (repo / "r.urdf").write_bytes(b'<robot name="r"><link name="a"/></robot>\n')
    return repo, scratch, Allow.for_case(repo, scratch)


def test_child_reports_exit_status_output_and_peak_memory(scratch_case, preloaded):
    from tests.fuzz.child import run

    repo, scratch, allow = scratch_case
    good = run(["check", "r.urdf"], cwd=repo, allow=allow, scratch=scratch)
    usage = run(["check", "no-such.urdf"], cwd=repo, allow=allow, scratch=scratch)
    assert (good.status, usage.status) == (0, 2)
    assert "no problems found" in good.output and "does not exist" in usage.output
    assert good.peak_kib > 10_000 and good.events == []


def test_child_audit_sees_reads_outside_and_links_leading_out(scratch_case, preloaded):
    """urdftool reads what the command line names, outside or not: a file outside and an
    explicit --package whose folder is a link leading out are reads the audit must see."""
    from tests.fuzz.child import run

    repo, scratch, allow = scratch_case
    (repo.parent / "elsewhere").mkdir()
    (repo.parent / "elsewhere" / "part.xacro").write_bytes(
        b'<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="b"/></robot>\n')
    (repo.parent / "pkg").symlink_to(repo.parent / "elsewhere")
    (repo / "r.urdf.xacro").write_bytes(
        b'<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="a"/>'
        b'<xacro:include filename="$(find pkg)/part.xacro"/></robot>\n')
    outcome = run(["check", "--allow-env", "-p", f"pkg={repo.parent / 'pkg'}", "/etc/hostname", "r.urdf.xacro"],
                  cwd=repo, allow=allow, scratch=scratch)
    assert "outside: open read /etc/hostname" in outcome.events
    assert any(e.endswith("part.xacro -> " + str(repo.parent / "elsewhere" / "part.xacro"))
               for e in outcome.events), outcome.events


def test_child_refuses_writes_outside_and_kills_on_time_limit(scratch_case, preloaded,
                                                             monkeypatch):
    from tests.fuzz.child import run

    repo, scratch, allow = scratch_case
    victim = repo.parent / "victim.txt"
    victim.write_text("VICTIM\n")
    (repo / "report.json").symlink_to(victim)

    def naive_write(path, data, rewrites=False, **_):  # the writer before it wrote beside and replaced
        with open(path, "w" if isinstance(data, str) else "wb") as handle:
            handle.write(data)

    monkeypatch.setattr("urdftool.description.files.write_file", naive_write)  # the child inherits it
    written = run(["check", "r.urdf", "-f", "json", "-o", "report.json"], cwd=repo, allow=allow,
                  scratch=scratch)
    assert victim.read_text() == "VICTIM\n"
    assert any(e.startswith("outside: open write") for e in written.events)
    # a robot that expands for hours under every cap of the sandbox (tests/slow_robots.py):
    # killed at the time limit however fast the machine (a tiny robot under 10 ms was not always)
    (repo / "slow.urdf.xacro").write_text(slow_xacro())
    slow = run(["check", "--timeout", "0", "slow.urdf.xacro"], cwd=repo, allow=allow,
               scratch=scratch, time_limit=1.0)
    assert slow.hung


def test_case_report_judges_the_issue_exploit(preloaded):
    """The issue's $(eval) exploit, judged by the harness (fails today: class 1)."""
    from tests.fuzz.cases import Case
    from tests.fuzz.harness import case_report
    from tests.fuzz.mutate import Seed

    data = (b'<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
            b'  <xacro:property name="r" value=")"/>\n'
            b'  <link name="$(eval exec(\'open(&quot;PWNED.txt&quot;,&quot;w&quot;${r}.write('
            b'&quot;x&quot;${r}\'${r})"/>\n</robot>\n')
    seed = Seed(ROBOTS / "diffbot" / "diffbot.urdf.xacro")
    report = case_report(Case(seed, data, "eval", commands=("check",)), time_limit=20)
    assert not any(f.startswith("code ran") for f in report.failures), report.failures


@pytest.mark.slow  # generated breadth: make fuzz runs the mode at length
def test_seeded_command_slice(preloaded):
    """A few whole hostile repositories through every command (tests/fuzz/cases.py)."""
    from tests.fuzz.run import run_commands

    stats = run_commands(CI_COMMAND_CASES, seed=20261124, max_seed_bytes=50_000, time_limit=10,
                         keep=False)
    assert stats["cases"] == CI_COMMAND_CASES
    assert stats["outside"] == 0 and stats["failures"] == 0, json.dumps(stats["failed"])


def test_git_trace_judges_what_git_opens_and_starts(tmp_path):
    """strace's log of the traced git (cases.GIT_WRAPPER): a program other than git started, a
    file opened outside the repository, its scratch folder and git's installation, and a
    marker a planted configuration wrote are failures; git's own reads are not."""
    from types import SimpleNamespace

    from tests.fuzz.harness import _git_traced

    repo, scratch = tmp_path / "repo", tmp_path / "scratch"
    (repo / ".git").mkdir(parents=True)
    (scratch / "markers").mkdir(parents=True)
    (scratch / "strace.1").write_text(
        f'1 execve("/usr/bin/git", ["git"], 0x0 /* 3 vars */) = 0\n'
        f'1 openat(AT_FDCWD, "/etc/ld.so.cache", O_RDONLY|O_CLOEXEC) = 3\n'
        f'1 openat(AT_FDCWD, "{repo}/.git/config", O_RDONLY) = 3\n'
        f'1 openat(AT_FDCWD, "/root/.gitconfig", O_RDONLY) = -1 ENOENT (No such file)\n'
        f'2 execve("/bin/sh", ["sh", "-c", "touch x"], 0x0 /* 3 vars */) = 0\n'
        f'2 openat(AT_FDCWD, "/etc/passwd", O_RDONLY) = 4\n')
    layout = SimpleNamespace(repo=repo, scratch=scratch)
    assert _git_traced(layout) == ["code ran: git started /bin/sh",
                                   "outside: git openat /etc/passwd"]
    (scratch / "markers" / "filter.smudge").write_text("")
    assert _git_traced(layout)[0] == "code ran: git ran what a planted config names " \
                                     "(filter.smudge)"


def _spin(group_seconds: float, busy: bool) -> int:
    """A child in a process group of its own that spins (or sleeps) ``group_seconds``."""
    import os
    import time

    pid = os.fork()
    if pid == 0:
        os.setpgid(0, 0)
        end = time.monotonic() + group_seconds
        while time.monotonic() < end:
            if not busy:
                time.sleep(0.01)
        os._exit(0)
    return pid


def test_a_hang_is_judged_by_cpu_time_or_a_wall_ceiling(tmp_path):
    """A child spinning past its limit of CPU is hung whatever the load; one sleeping past its
    wall deadline is waited for until the wall ceiling (a loaded machine makes commands late,
    not hung); tree_cpu_seconds counts the CPU of the child and its descendants."""
    import time

    from tests.fuzz import child

    out, log = tmp_path / "out", tmp_path / "log"
    busy = child.Running(["spin"], _spin(30, busy=True), out, log, time_limit=0.3)
    while not busy.poll():
        time.sleep(0.01)
    assert busy.status is None and busy.seconds < 10  # killed: hung on CPU, not on the ceiling
    sleeper = child.Running(["sleep"], _spin(0.8, busy=False), out, log, time_limit=0.2)
    while not sleeper.poll():
        time.sleep(0.01)
    assert sleeper.status == 0  # past its 0.2 s deadline, under its CPU and the 1.2 s ceiling
    asleep = child.Running(["sleep"], _spin(30, busy=False), out, log, time_limit=0.2)
    while not asleep.poll():
        time.sleep(0.01)
    assert asleep.status is None and asleep.seconds < 5  # the ceiling (6 x 0.2 s) holds


def test_the_cpu_of_a_descendant_in_a_session_of_its_own_counts():
    """The pool's workers leave the command's process group: their CPU counts for a hang
    all the same (counting the group only, a hung worker was judged by the wall ceiling)."""
    import os
    import signal
    import time

    from tests.fuzz.child import tree_cpu_seconds

    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(read)
        worker = os.fork()
        if worker == 0:
            os.setsid()
            while True:
                pass
        os.write(write, str(worker).encode())
        os.waitpid(worker, 0)  # reaped here: no zombie left for a PID 1 that does not reap
        os._exit(0)
    os.close(write)
    worker = int(os.read(read, 32))
    try:
        deadline = time.monotonic() + 20
        while tree_cpu_seconds(pid) < 0.2 and time.monotonic() < deadline:
            time.sleep(0.02)
        assert tree_cpu_seconds(pid) >= 0.2
    finally:
        os.kill(worker, signal.SIGKILL)
        os.waitpid(pid, 0)
