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


@pytest.mark.parametrize("where", [".git/HEAD", ".git/hooks/pre-commit", "sub/.git",
                                   ".hg/store/x", "bare/HEAD", "bare/refs/heads/main",
                                   "link/config"])
def test_an_output_in_a_version_control_folder_is_refused(tmp_path, monkeypatch, where):
    # session 9: -o .git/HEAD replaced the branch with a report (nothing the check read)
    for folder in (".git/hooks", ".git/objects", ".git/refs", ".hg/store", "bare/objects",
                   "bare/refs/heads", "sub"):
        (tmp_path / folder).mkdir(parents=True, exist_ok=True)
    for name in (".git/HEAD", "bare/HEAD", ".git/hooks/pre-commit", "bare/refs/heads/main",
                 ".hg/store/x"):
        (tmp_path / name).write_text("ref: refs/heads/main\n")
    (tmp_path / "sub/.git").write_text("gitdir: ../.git\n")  # a worktree's .git file
    (tmp_path / "link").symlink_to(".git")
    monkeypatch.chdir(tmp_path)
    before = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    with pytest.raises(UsageError, match="version control system's own folder"):
        files.write_file(where, "a report\n")
    assert {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()} == before
    files.write_file("report.txt", "a report\n")  # beside them: written
    files.write_file("bare.txt", "a report\n")


def test_a_hard_link_of_a_file_read_is_replaced_and_the_file_read_keeps_its_bytes(tmp_path):
    # session 9: the rename puts the output at the link's name only; the name read is refused
    read, link = tmp_path / "robot.urdf", tmp_path / "copy.urdf"
    read.write_text(ROBOT)
    os.link(read, link)
    files.read_regular(read)
    with pytest.raises(UsageError, match="a file the command read"):
        files.write_file(tmp_path / "." / "robot.urdf", "a report\n")
    files.write_file(link, "a report\n")
    assert read.read_text() == ROBOT and link.read_text() == "a report\n"


def test_a_rewrite_meant_for_one_kind_of_file_refuses_a_file_read_as_another(tmp_path):
    # session 13: collisions --write-srdf over an include the robot was built from rewrote the
    # macro file as an SRDF (the grant was "any file but the robot"); it is meant for an SRDF
    include, srdf = tmp_path / "arm.xacro", tmp_path / "robot.srdf"
    include.write_text(ROBOT)
    srdf.write_text('<robot name="r"/>\n')
    srdf_only = frozenset({"companion SRDF"})
    files.read_regular(include, as_="include")
    files.read_regular(include, as_="companion SRDF")  # the writer's own reading of it
    with pytest.raises(UsageError, match=r"a file the command read \(as companion SRDF, "
                                         r"include\)"):
        files.write_file(include, "<robot/>\n", rewrites=srdf_only)
    assert include.read_text() == ROBOT
    files.read_regular(srdf, as_="companion SRDF")
    files.write_file(srdf, "<robot/>\n", rewrites=srdf_only)
    assert srdf.read_text() == "<robot/>\n"
    files.write_file(include, "<robot/>\n", rewrites=True)  # the fixes: any file they read
    assert include.read_text() == "<robot/>\n"


def test_a_rewrite_through_a_link_writes_the_file_read_and_keeps_the_link(tmp_path):
    # session 13: check --fix, inertia --write of a robot file that is a committed link
    # replaced the link with a fixed copy and left the file it leads to unfixed
    real, link, planted = tmp_path / "real.urdf", tmp_path / "link.urdf", tmp_path / "p.urdf"
    real.write_text(ROBOT)
    link.symlink_to("real.urdf")
    planted.symlink_to("real.urdf")  # a link not read: replaced, as any output's
    files.read_regular(link)
    files.write_file(link, "fixed\n", rewrites=True)
    assert link.is_symlink() and real.read_text() == "fixed\n"
    files.write_file(planted, "a report\n", rewrites=True)
    assert not planted.is_symlink() and real.read_text() == "fixed\n"


@pytest.mark.parametrize("command", [["check", "--fix"], ["inertia", "--all", "--write"]])
def test_a_fix_of_a_robot_file_that_is_a_link_fixes_the_file_it_leads_to(run_cli, tmp_path,
                                                                          monkeypatch, command):
    (tmp_path / ".git").mkdir()
    real, link = tmp_path / "real.urdf", tmp_path / "link.urdf"
    real.write_text('<robot name="r"><link name="a"><inertial><mass value="1"/><inertia ixx="1"'
                    ' iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial><collision><geometry>'
                    '<box size="0.1 0.1 0.1"/></geometry></collision></link><link name="b"/>'
                    '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
                    '<axis xyz="0 0 1"/><limit lower="1" upper="-1" effort="1" velocity="1"/>'
                    '</joint></robot>\n')
    link.symlink_to("real.urdf")
    monkeypatch.chdir(tmp_path)
    words = [command[0], "link.urdf", *command[1:]] + (["link.urdf"] if "--write" in command
                                                       else [])
    run_cli(*words, "--timeout", "0", "--max-memory", "0")
    assert link.is_symlink()
    fixed = real.read_text()
    assert ('lower="-1" upper="1"' in fixed) if command[0] == "check" else 'ixx="1"' not in fixed


@pytest.mark.parametrize("writer", WRITERS)
def test_an_output_named_dash_is_refused_not_a_file_named_dash(run_cli, tmp_path, monkeypatch,
                                                               writer):
    """``check -o -`` wrote a file named ``-`` where the user meant standard output; the next
    ``urdftool check -`` of the repository's files (a hook passing them) reads standard input
    in its place. ``-`` names standard input to every reader: no writer takes it."""
    robot = tmp_path / "robot.urdf"
    robot.write_text(ROBOT)
    monkeypatch.chdir(tmp_path)
    result = run_cli(*_commands(robot, Path("-"))[writer])
    assert result.exit_code == 2, result.output
    assert len(result.stderr.strip().splitlines()) == 1, result.stderr
    assert not (tmp_path / "-").exists()


@pytest.mark.parametrize("words", [
    ["diff", "{robot}", "{robot}", "--render", "{out}.svg", "-o", "{out}.svg"],
    ["diff", "{robot}", "{robot}", "--render", "{out}.svg", "-o", "{here}/sub/../{name}.svg"],
    ["collisions", "{robot}", "--matrix", "--write-srdf", "{out}.svg", "--plot", "{out}.svg"],
])
def test_two_outputs_of_one_command_naming_one_file_are_refused_before_the_work(
        run_cli, tmp_path, words):
    """``diff --render x.svg -o x.svg`` wrote the report, then the picture over it (the
    report lost, exit as if both were written); refuse_bad_outputs, the check of every
    command's outputs before the work, refuses two outputs naming one file (its name in its
    folder's real place)."""
    robot = tmp_path / "robot.urdf"
    robot.write_text(ROBOT)
    (tmp_path / "sub").mkdir()
    result = run_cli(*[word.format(robot=robot, out=tmp_path / "x", here=tmp_path, name="x")
                       for word in words])
    assert result.exit_code == 2, result.output
    assert "name one file" in result.stderr and not (tmp_path / "x.svg").exists()


@pytest.mark.parametrize("place, said", [
    ("report.urdf/x.json", "'{tmp}/report.urdf' is a file, not a folder"),
    ("pipe/x.json", "'{tmp}/pipe' is a named pipe, not a folder"),
    ("report.urdf/a/x.json", "folder '{tmp}/report.urdf/a' does not exist (a part of it is a "
                             "file)"),
    ("missing/x.json", "folder '{tmp}/missing' does not exist"),
])
def test_an_output_whose_folder_is_something_else_says_what_is_there(tmp_path, place, said):
    """``-o report.urdf/x.json`` of a file report.urdf said "folder 'report.urdf' does not
    exist" (and so of a named pipe): the refusal names what is there instead."""
    (tmp_path / "report.urdf").write_text("x")
    os.mkfifo(tmp_path / "pipe")
    with pytest.raises(UsageError) as refused:
        files.check_output(tmp_path / place)
    assert str(refused.value) == f"cannot write '{tmp_path / place}': " + said.format(tmp=tmp_path)
