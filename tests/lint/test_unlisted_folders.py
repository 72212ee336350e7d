"""A folder walk that cannot list a folder says so (docs/attacks.md, session 8): a folder
without read permission, or one whose path is past the system's PATH_MAX (an unpacked
archive holds such trees; git does not refuse them), was skipped in silence, its robots and
its links leading out never reported, and the run said "no problems found". Now
``lint.targets.robot_files`` collects what it could not list and ``expand`` makes each a note
(standard error, every format)."""

from __future__ import annotations

import os

import pytest


ROBOT = """<robot name="deep"><link name="a"/><link name="b"/>
<joint name="j" type="fixed"><parent link="a"/><child link="nowhere"/></joint></robot>
"""


def _deep(top) -> None:
    """A robot 20 folders of 250 characters below ``top`` (past PATH_MAX: made through
    descriptors, as tar does)."""
    descriptor = os.open(top, os.O_RDONLY)
    try:
        for _ in range(20):
            os.mkdir("d" * 250, dir_fd=descriptor)
            inner = os.open("d" * 250, os.O_RDONLY, dir_fd=descriptor)
            os.close(descriptor)
            descriptor = inner
        out = os.open("robot.urdf", os.O_WRONLY | os.O_CREAT, 0o644, dir_fd=descriptor)
        os.write(out, ROBOT.encode())
        os.close(out)
    finally:
        os.close(descriptor)


@pytest.mark.parametrize("format", ["text", "json", "sarif"])
def test_a_folder_too_deep_to_list_is_said_not_passed_in_silence(run_cli, tmp_path, format):
    (tmp_path / ".git").mkdir()
    (tmp_path / "good.urdf").write_text('<robot name="g"><link name="a"/></robot>\n')
    _deep(tmp_path)
    result = run_cli("check", tmp_path, "--no-cache", "-f", format)
    assert "cannot be read: its files are not checked" in result.stderr, result.stderr
    assert "Traceback" not in result.output


@pytest.mark.skipif(os.geteuid() == 0, reason="root reads any folder")
def test_a_folder_without_permission_is_said(run_cli, tmp_path):
    (tmp_path / ".git").mkdir()
    (tmp_path / "good.urdf").write_text('<robot name="g"><link name="a"/></robot>\n')
    closed = tmp_path / "closed"
    closed.mkdir()
    (closed / "robot.urdf").write_text(ROBOT)
    closed.chmod(0)
    try:
        result = run_cli("check", tmp_path, "--no-cache")
    finally:
        closed.chmod(0o755)
    assert "folder 'closed' cannot be read" in result.stderr or "closed' cannot be read" in \
        result.stderr, result.stderr
