"""Which files ``check`` checks: folders, and files named explicitly (as pre-commit passes)."""

from __future__ import annotations

import shutil

from conftest import CASES, ROBOTS


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


def test_a_macro_library_with_another_root_is_skipped_and_other_roots_are_reported(run_cli,
                                                                                   tmp_path):
    """Pre-Groovy macro files are ``<root xmlns:xacro=...>`` (mas-group/youbot_description's
    sensors): a macro library all the same. A non-robot root with content stays U004."""
    (tmp_path / ".git").mkdir()
    (tmp_path / "sensor.urdf.xacro").write_text(
        '<root xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:property name="w" value="1"/>'
        '<xacro:macro name="m" params="parent"><link name="a"/></xacro:macro></root>')
    (tmp_path / "world.urdf").write_text('<sdf version="1.6"><model name="m"/></sdf>')
    result = run_cli("check", tmp_path, "--format", "json")
    assert '"code": "U004"' in result.stdout and "world.urdf" in result.stdout
    assert "sensor.urdf.xacro" not in result.stdout and '"files": 1' in result.stdout


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


XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def _srdf_sources(folder):
    """A MoveIt 2 config: an .srdf.xacro calling a macro, a plain-named one holding <group>."""
    (folder / ".git").mkdir()
    config = folder / "config"
    config.mkdir()
    (config / "arm.srdf.xacro").write_text(
        f'<robot name="arm" {XACRO_NS}><xacro:arg name="prefix" default=""/>'
        '<xacro:include filename="arm_macro.xacro"/><xacro:arm_srdf prefix="$(arg prefix)"/>'
        '</robot>')
    (config / "arm_macro.xacro").write_text(
        f'<robot {XACRO_NS}><xacro:macro name="arm_srdf" params="prefix">'
        '<group name="${prefix}arm"/></xacro:macro></robot>')
    (config / "semantic.xacro").write_text(
        f'<robot name="arm" {XACRO_NS}><xacro:arg name="n" default=""/>'
        '<group name="arm"><chain base_link="base" tip_link="tool0"/></group></robot>')
    (folder / "arm.urdf").write_text('<robot name="arm"><link name="base"/></robot>')
    return config


def test_srdf_sources_are_not_robots_in_a_folder_walk(tmp_path):
    from urdftool.lint.settings import CheckRequest
    from urdftool.lint.targets import SRDF_SOURCE, expand

    config = _srdf_sources(tmp_path)
    targets = expand([str(tmp_path)], CheckRequest())
    assert targets.files == [str(tmp_path / "arm.urdf")]
    assert targets.skipped == {str(config / "arm.srdf.xacro"): SRDF_SOURCE,
                               str(config / "semantic.xacro"): SRDF_SOURCE,
                               str(config / "arm_macro.xacro"):
                                   f"included by {config / 'arm.srdf.xacro'}"}


def test_an_srdf_source_named_is_not_checked_as_a_robot(run_cli, tmp_path):
    config = _srdf_sources(tmp_path)
    result = run_cli("check", config / "arm.srdf.xacro", "--format", "json")
    assert result.exit_code == 0 and '"files": 0' in result.stdout
    assert "SRDF source" in result.stderr and "U106" not in result.stdout


def _robot_built_by_includes(folder, include="core.xacro"):
    (folder / ".git").mkdir()
    (folder / "robot.urdf.xacro").write_text(
        f'<robot name="r" {XACRO_NS}>\n<xacro:include filename="{include}"/>\n</robot>')
    (folder / "parts.xacro").write_text(
        f'<robot {XACRO_NS}><xacro:include filename="core.xacro"/></robot>')
    (folder / "core.xacro").write_text(
        f'<robot {XACRO_NS}>\n<link name="base"/>\n<joint name="j" type="hinge">'
        '<parent link="base"/><child link="arm"/></joint>\n<link name="arm"/>\n</robot>')
    return folder / "robot.urdf.xacro"


def test_a_robot_named_whose_body_is_only_includes_is_checked(run_cli, tmp_path):
    robot = _robot_built_by_includes(tmp_path, include="parts.xacro")
    result = run_cli("check", robot)
    assert result.exit_code == 1 and "core.xacro:3" in result.stdout and "U201" in result.stdout


def test_a_folder_walk_classifies_a_file_by_what_its_includes_produce(tmp_path):
    from urdftool.lint.settings import CheckRequest
    from urdftool.lint.targets import expand

    _robot_built_by_includes(tmp_path, include="parts.xacro")
    (tmp_path / "macros.xacro").write_text(  # a macro library including a macro library
        f'<robot name="lib" {XACRO_NS}><xacro:include filename="more.xacro"/></robot>')
    (tmp_path / "more.xacro").write_text(
        f'<robot {XACRO_NS}><xacro:macro name="m"><link name="a"/></xacro:macro>'
        '<macro name="old"><link name="b"/></macro>'  # pre-2019 xacro: no prefix
        '<xacro:property name="p" value="1"/></robot>')
    targets = expand([str(tmp_path)], CheckRequest())
    assert targets.files == [str(tmp_path / "robot.urdf.xacro")]
    assert targets.skipped[str(tmp_path / "macros.xacro")].startswith("defines only macros")


def test_a_robot_named_whose_includes_cannot_be_followed_is_checked(run_cli, tmp_path):
    robot = _robot_built_by_includes(tmp_path, include="$(find nowhere_pkg)/core.xacro")
    result = run_cli("check", robot)
    assert result.exit_code == 1 and "U006" in result.stdout
def _two_robots(tmp_path):
    """A repository with robots a and b in urdf/, each with its controller YAML, and a CI file."""
    (tmp_path / ".git").mkdir()
    robot = ('<robot name="{n}"><link name="base"/><link name="l"/><joint name="{n}_j" type="continuous">'
             '<parent link="base"/><child link="l"/></joint></robot>')
    yaml = ("{n}_c:\n  type: position_controllers/JointGroupPositionController\n  joints: [{j}]\n"
            "jsc: {{type: joint_state_controller/JointStateController}}\n")
    for name, text in {"pkg/urdf/a.urdf": robot.format(n="a"), "pkg/urdf/b.urdf": robot.format(n="b"),
                       "pkg/config/a_controllers.yaml": yaml.format(n="a", j="a_j"),
                       "pkg/config/b_controllers.yaml": yaml.format(n="b", j="b_jnt"),
                       ".github/ci.yml": "on: push\n"}.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    return tmp_path


def test_a_companion_named_checks_the_robots_checked_with_it(run_cli, tmp_path):
    root = _two_robots(tmp_path)
    result = run_cli("check", root / "pkg/config/b_controllers.yaml", "-v")
    assert result.exit_code == 1 and "b_controllers.yaml:3" in result.stdout and "U602" in result.stdout
    assert "a companion of" in result.stderr and "b.urdf" in result.stderr and "a.urdf:" not in result.stdout
    assert "companion of " in result.stderr and "controllers: " in result.stderr
    clean = run_cli("check", root / "pkg/config/a_controllers.yaml", "--format", "json")
    assert clean.exit_code == 0 and '"files": 1' in clean.stdout


def test_a_companion_in_the_config_folder_of_a_robot_outside_any_repository(run_cli, tmp_path):
    # discovery finds config/ beside a robot wherever it is; naming the companion found nothing
    # to check when no repository or package held them (the robots were looked for below
    # config/ only)
    shutil.copytree(CASES / "U602_controller_unknown_joint", tmp_path / "ctl")
    result = run_cli("check", tmp_path / "ctl" / "config" / "controllers.yaml")
    assert result.exit_code == 1 and "U602" in result.stdout
    assert "a companion of" in result.stderr and "robot.urdf" in result.stderr


def test_a_yaml_no_robot_uses_checks_nothing(run_cli, tmp_path):
    root = _two_robots(tmp_path)
    result = run_cli("check", root / ".github/ci.yml", "--format", "json")
    assert result.exit_code == 0 and '"files": 0' in result.stdout
    assert "nothing to check" in result.stderr


def test_the_pre_commit_hook_passes_companion_files():
    import re

    from conftest import ROOT

    pattern = re.search(r"files: (\S+)", (ROOT / ".pre-commit-hooks.yaml").read_text()).group(1)
    assert all(re.search(pattern, name) for name in ("r.urdf", "r.xacro", "config/c.yaml", "c.yml", "r.srdf"))


def test_a_robot_named_on_the_command_line_does_not_walk_its_repository(monkeypatch):
    # the include graph is for macro libraries named; walking this repository for r2d2 costs
    # more than checking it
    from urdftool.lint import targets
    from urdftool.lint.settings import CheckRequest

    def walk(*_):
        raise AssertionError("the repository was walked")

    monkeypatch.setattr(targets, "includers_below", walk)
    found = targets.expand([str(ROBOTS / "r2d2" / "r2d2.urdf.xacro")], CheckRequest())
    assert found.files == [str(ROBOTS / "r2d2" / "r2d2.urdf.xacro")]
