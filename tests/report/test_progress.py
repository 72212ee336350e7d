"""Progress of long runs: a bar on standard error only where a person watches it, moved by
the runs that take long (check over many files, workspace, dynamics --samples)."""

from __future__ import annotations

import io

import pytest

from conftest import ROBOTS
from urdftool.report.progress import progress, shown


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_a_bar_is_drawn_only_on_a_terminal_and_never_for_a_machine_format(monkeypatch):
    monkeypatch.setenv("TERM", "xterm")
    assert shown(Terminal())
    assert not shown(io.StringIO())  # a pipe, a file, a CI log
    assert not shown(Terminal(), machine=True)
    monkeypatch.setenv("TERM", "dumb")
    assert not shown(Terminal())


def test_the_bar_counts_and_is_erased_at_the_end(monkeypatch):
    monkeypatch.setenv("TERM", "xterm")
    terminal = Terminal()
    with progress("checking", "files", 4, stream=terminal, delay=0.0) as moved:
        for done in range(1, 5):
            moved(done, 4)
    written = terminal.getvalue()
    assert "checking" in written and "files" in written
    assert "\x1b[2K" in written  # transient: the line is cleared when the run ends
    pipe = io.StringIO()
    with progress("checking", "files", 4, stream=pipe, delay=0.0) as moved:
        moved(1, 4)
    assert pipe.getvalue() == ""


def test_a_quick_run_shows_nothing(monkeypatch):
    monkeypatch.setenv("TERM", "xterm")
    terminal = Terminal()
    with progress("checking", "files", 2, stream=terminal) as moved:  # 0.5 s delay
        moved(1, 2)
        moved(2, 2)
    assert terminal.getvalue() == ""


def test_check_paths_reports_each_file_checked(tmp_path):
    from urdftool.lint.runner import check_paths

    (tmp_path / ".git").mkdir()
    for name in ("a", "b", "c"):
        (tmp_path / f"{name}.urdf").write_text(f'<robot name="{name}"><link name="l"/></robot>')
    seen = []
    run = check_paths([str(tmp_path)], jobs=1, timeout=0, progress=lambda *d: seen.append(d))
    assert len(run.results) == 3
    assert seen[-1] == (3, 3) and [done for done, _ in seen] == sorted(done for done, _ in seen)


def test_sampling_runs_report_their_configurations():
    from urdftool.description.load import load
    from urdftool.kinematics.chain import build_chain
    from urdftool.kinematics.fk import KinematicModel
    from urdftool.kinematics.workspace import sample

    robot = load(ROBOTS / "humanoid" / "humanoid.urdf.xacro")
    kinematics = KinematicModel(robot)
    chain = build_chain(robot, None, "l_forearm_link", None, kinematics)
    seen = []
    sample(chain, 50, 0, lambda *d: seen.append(d))
    assert seen[-1] == (50, 50) and len(seen) == 50

    pytest.importorskip("pinocchio")
    from urdftool.physics.dynamics import build, gravity_loads

    seen.clear()
    gravity_loads(build(robot), 20, 0, progress=lambda *d: seen.append(d))
    assert seen[-1] == (21, 21)  # the zero pose and the 20 drawn
