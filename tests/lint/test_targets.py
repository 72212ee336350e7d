"""Which files ``check`` checks: folders, and files named explicitly (as pre-commit passes)."""

from __future__ import annotations

import shutil

from conftest import ROBOTS


def test_macro_file_checks_the_robot_that_includes_it(run_cli):
    result = run_cli("check", ROBOTS / "humanoid" / "leg.xacro", "--format", "json")
    assert result.exit_code == 0
    assert "included by" in result.stderr and "humanoid.urdf.xacro" in result.stderr
    assert '"files": 1' in result.stdout


def test_robot_and_its_macro_are_checked_once(run_cli):
    result = run_cli("check", ROBOTS / "diffbot" / "wheel.xacro",
                     ROBOTS / "diffbot" / "diffbot.urdf.xacro", "--format", "json")
    assert result.exit_code == 0 and '"files": 1' in result.stdout


def test_unused_macro_library_is_skipped(run_cli, tmp_path):
    (tmp_path / ".git").mkdir()
    lib = tmp_path / "lib.xacro"
    lib.write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
                   '<xacro:macro name="m"><link name="a"/></xacro:macro></robot>')
    result = run_cli("check", lib, "--format", "json")
    assert result.exit_code == 0 and '"files": 0' in result.stdout
    assert "nothing to check" in result.stderr


def test_finding_in_macro_is_reported_through_its_robot(run_cli, tmp_path):
    (tmp_path / ".git").mkdir()
    shutil.copytree(ROBOTS / "diffbot", tmp_path / "diffbot")
    wheel = tmp_path / "diffbot" / "wheel.xacro"
    wheel.write_text(wheel.read_text().replace('type="continuous"', 'type="contnuous"', 1))
    result = run_cli("check", wheel)
    assert result.exit_code == 1 and "U201" in result.stdout and "wheel.xacro:" in result.stdout
