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


def test_expand_returns_files_skipped_and_notes_without_printing(capsys):
    from urdftool.lint.settings import CheckRequest
    from urdftool.lint.targets import expand

    targets = expand([str(ROBOTS / "humanoid" / "leg.xacro"), str(ROBOTS / "diffbot")],
                     CheckRequest())
    assert [p.rsplit("/", 1)[-1] for p in targets.files] == ["humanoid.urdf.xacro",
                                                             "diffbot.urdf.xacro"]
    assert [p.rsplit("/", 1)[-1] for p in targets.skipped] == ["inertial.xacro", "wheel.xacro"]
    assert len(targets.notes) == 1 and targets.notes[0].startswith(
        f"{ROBOTS / 'humanoid' / 'leg.xacro'}: included by ")
    assert capsys.readouterr() == ("", "")


def test_expand_refuses_a_missing_path_and_a_folder_without_robots(tmp_path):
    import pytest

    from urdftool.errors import TargetError
    from urdftool.lint.settings import CheckRequest
    from urdftool.lint.targets import expand

    with pytest.raises(TargetError, match="path '.*nowhere' does not exist"):
        expand([str(tmp_path / "nowhere")], CheckRequest())
    with pytest.raises(TargetError, match="no .urdf or .xacro files found in"):
        expand([str(tmp_path)], CheckRequest())


def test_packages_of_the_settings_file_resolve_includes_when_walking(tmp_path):
    """A macro library included through $(find pkg) of a package the settings name is skipped
    as included, not checked as a robot of its own."""
    from urdftool.lint.settings import CheckRequest
    from urdftool.lint.targets import expand

    (tmp_path / ".git").mkdir()
    (tmp_path / "pkg").mkdir()
    (tmp_path / "pkg" / "arm.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="arm"/></robot>')
    (tmp_path / "robot.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="$(find pkg)/arm.xacro"/><link name="base"/></robot>')
    (tmp_path / "urdftool.toml").write_text('[packages]\npkg = "pkg"\n')
    targets = expand([str(tmp_path)], CheckRequest())
    assert targets.files == [str(tmp_path / "robot.urdf.xacro")]
    assert list(targets.skipped) == [str(tmp_path / "pkg" / "arm.xacro")]


def test_a_robot_named_on_the_command_line_does_not_walk_its_repository(monkeypatch):
    # the include graph is for macro libraries named; walking this repository for r2d2 cost
    # more than checking it (0.5 s of a 1.2 s `urdftool check r2d2`)
    from urdftool.lint import targets
    from urdftool.lint.settings import CheckRequest

    def walk(*_):
        raise AssertionError("the repository was walked")

    monkeypatch.setattr(targets, "includers_below", walk)
    found = targets.expand([str(ROBOTS / "r2d2" / "r2d2.urdf.xacro")], CheckRequest())
    assert found.files == [str(ROBOTS / "r2d2" / "r2d2.urdf.xacro")]
