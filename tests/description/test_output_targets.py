"""Outputs the system refuses to look up or that would wait forever (docs/attacks.md,
session 8): every writer (``-o``, ``--write``, ``--plot``, ``--render``, ``--write-srdf``)
goes through ``files.check_output`` before the work and ``files.write_file`` after it, so a
name the system cannot stat (longer than NAME_MAX or PATH_MAX) and a named pipe nobody reads
(an unpacked archive can hold one where a workflow writes its report) are usage errors: one
line, exit 2, never a traceback or a run that waits for a reader forever."""

from __future__ import annotations

import os
import threading
from pathlib import Path

import pytest

from tests.lint.test_untrusted_files import ROBOT, SUFFIX, WRITERS, _commands
from urdftool.description import files
from urdftool.errors import UsageError


@pytest.mark.parametrize("writer", WRITERS)
@pytest.mark.parametrize("length", ["name", "path"])
def test_an_output_name_the_system_cannot_look_up_is_a_usage_error(run_cli, tmp_path, writer,
                                                                    length):
    robot = tmp_path / "robot.urdf"
    robot.write_text(ROBOT)
    suffix = SUFFIX.get(writer, ".txt")
    name = "x" * 300 + suffix if length == "name" else "/".join(["y" * 200] * 25) + suffix
    result = run_cli(*_commands(robot, tmp_path / name)[writer])
    assert result.exit_code == 2, result.output
    assert isinstance(result.exception, SystemExit), result.exception
    assert len(result.stderr.strip().splitlines()) == 1, result.stderr
    assert "cannot write" in result.stderr or "must end in" in result.stderr


def test_a_named_pipe_nobody_reads_is_refused_not_waited_for(tmp_path, monkeypatch):
    monkeypatch.setattr(files, "PIPE_READER_WAIT", 0.5)  # (10 s as shipped)
    pipe = tmp_path / "report.sarif"
    os.mkfifo(pipe)
    done: list[BaseException | None] = []

    def write():
        try:
            files.write_file(pipe, "{}")
            done.append(None)
        except BaseException as error:  # noqa: BLE001 - handed to the test's thread
            done.append(error)

    worker = threading.Thread(target=write, daemon=True)
    worker.start()
    worker.join(5)
    if worker.is_alive():  # unblock the writer so the test process can end
        with open(pipe, "rb") as reader:
            reader.read()
        pytest.fail("write_file waited for a reader of a named pipe")
    assert isinstance(done[0], UsageError) and "no process reads" in str(done[0])
    assert pipe.is_fifo()  # never replaced by a file


def test_a_named_pipe_with_a_reader_gets_the_whole_report(tmp_path):
    pipe = tmp_path / "report.txt"
    os.mkfifo(pipe)
    got: list[bytes] = []
    reader = threading.Thread(target=lambda: got.append(Path(pipe).read_bytes()), daemon=True)
    data = "line\n" * 100_000  # more than a pipe holds: the writer waits for the reader
    threading.Timer(0.3, reader.start).start()  # a reader that opens its end a moment later
    files.write_file(pipe, data)
    reader.join(10)
    assert got == [data.encode()]


MEANT_IN_PLACE = ("inertia --write", "collisions --write-srdf")  # a file rewritten on purpose


@pytest.mark.parametrize("writer", [w for w in WRITERS if w not in MEANT_IN_PLACE])
def test_an_output_that_is_an_input_is_refused_before_it_replaces_it(run_cli, tmp_path, writer):
    """``check robot.urdf -o robot.urdf`` wrote its report over the robot (attack8, session 8):
    every writer refuses an output that is a file the command was given, before the work."""
    robot = tmp_path / "robot.urdf"
    robot.write_text(ROBOT)
    result = run_cli(*_commands(robot, robot)[writer])
    assert result.exit_code == 2, result.output
    assert robot.read_text() == ROBOT
    assert "cannot write" in result.stderr or "must end in" in result.stderr


def test_a_robot_below_a_folder_checked_is_no_output(run_cli, tmp_path):
    robot = tmp_path / "robot.urdf"
    robot.write_text(ROBOT)
    result = run_cli("check", tmp_path, "-o", robot, "--jobs", "1")
    assert result.exit_code == 2 and robot.read_text() == ROBOT
    assert "which the output would replace" in result.stderr
    # a report file of its own there, and a link named as the output (replaced, not
    # followed), are no input
    report = run_cli("check", robot, "-o", tmp_path / "report.txt", "--jobs", "1")
    assert report.exit_code == 0 and (tmp_path / "report.txt").is_file()
    (tmp_path / "link.txt").symlink_to(robot)
    linked = run_cli("check", robot, "-o", tmp_path / "link.txt", "--jobs", "1")
    assert linked.exit_code == 0 and robot.read_text() == ROBOT
