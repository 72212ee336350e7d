"""Which files ``check`` checks: folders, and files named explicitly (as pre-commit passes)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

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



def test_a_folder_without_robots_says_which_companions_it_holds(tmp_path):
    """A MoveIt configuration alone (its SRDF and launch files, no robot): the error says what
    the folder holds and that it is checked beside its robot; a tool folder's files are not
    counted, and a folder holding nothing of the kind gets the plain error."""
    from urdftool.errors import TargetError
    from urdftool.lint.settings import CheckRequest
    from urdftool.lint.targets import expand

    (tmp_path / "config").mkdir()
    (tmp_path / "config" / "arm.srdf").write_text("<robot name='arm'/>")
    (tmp_path / "launch").mkdir()
    for name in ("demo.launch.py", "move_group.launch", "rviz.launch.xml"):
        (tmp_path / "launch" / name).write_text("")
    (tmp_path / "build").mkdir()
    (tmp_path / "build" / "copy.srdf").write_text("")
    with pytest.raises(TargetError) as raised:
        expand([str(tmp_path)], CheckRequest())
    assert str(raised.value).endswith("; it holds 1 SRDF, 3 launch files, which are checked with "
                                      "the robot they describe: check a folder holding that "
                                      "robot's .urdf or .xacro too")
    empty = tmp_path / "build" / "empty"
    empty.mkdir()
    with pytest.raises(TargetError) as raised:
        expand([str(empty)], CheckRequest())
    assert str(raised.value).endswith("files found in '" + str(empty) + "'")
    # one file is said as one (husky_robot's quadruped neighbour: '1 launch file, which are')
    (empty / "view.launch").write_text("")
    with pytest.raises(TargetError) as raised:
        expand([str(empty)], CheckRequest())
    assert str(raised.value).endswith("; it holds 1 launch file, which is checked with the robot "
                                      "it describes: check a folder holding that robot's .urdf "
                                      "or .xacro too")

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


def test_a_condition_choosing_a_property_leaves_a_macro_library_a_library(tmp_path):
    """MiR's imu.gazebo.urdf.xacro chooses its frame's name in a top-level ``xacro:if`` /
    ``xacro:unless`` and defines a macro: a macro library (its copy nobody includes, in
    match_mobile_robotics_jazzy, was checked as a robot: U106 'robot has no <link> elements').
    A condition holding a link, or a macro call, is a robot's."""
    from urdftool.lint.settings import CheckRequest
    from urdftool.lint.targets import expand

    (tmp_path / ".git").mkdir()
    (tmp_path / "imu.urdf.xacro").write_text(
        f'<robot {XACRO_NS}><xacro:arg name="p" default=""/>'
        '<xacro:if value="${p == \'\'}"><xacro:property name="f" value="imu"/></xacro:if>'
        '<xacro:unless value="${p == \'\'}"><xacro:property name="f" value="$(arg p)/imu"/>'
        '</xacro:unless><xacro:macro name="imu"><gazebo reference="${f}"/></xacro:macro></robot>')
    for name, body in {"linked.urdf.xacro": '<link name="a"/>', "called.urdf.xacro": "<xacro:m/>"}.items():
        (tmp_path / name).write_text(
            f'<robot name="r" {XACRO_NS}><xacro:macro name="m"><link name="b"/></xacro:macro>'
            f'<xacro:if value="true">{body}</xacro:if></robot>')
    targets = expand([str(tmp_path)], CheckRequest())
    assert targets.files == [str(tmp_path / "called.urdf.xacro"), str(tmp_path / "linked.urdf.xacro")]
    assert targets.skipped[str(tmp_path / "imu.urdf.xacro")].startswith("defines only macros")


def test_a_robot_named_whose_includes_cannot_be_followed_is_checked(run_cli, tmp_path):
    robot = _robot_built_by_includes(tmp_path, include="$(find nowhere_pkg)/core.xacro")
    result = run_cli("check", robot)  # (a package not installed: not checked, exit 2)
    assert result.exit_code == 2 and "U006" in result.stdout


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
    result = run_cli("check", root / "pkg/config/b_controllers.yaml", "-v", "--strict")
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
    # (a warning: no launch file says whether the controller is started; --strict fails on it)
    result = run_cli("check", tmp_path / "ctl" / "config" / "controllers.yaml", "--strict")
    assert result.exit_code == 1 and "U602" in result.stdout
    assert "a companion of" in result.stderr and "robot.urdf" in result.stderr


def test_a_yaml_no_robot_uses_checks_nothing_quietly(run_cli, tmp_path):
    # issue 30 class 9: pre-commit passes every staged YAML (launch, navigation, CI settings)
    root = _two_robots(tmp_path)
    result = run_cli("check", root / ".github/ci.yml", "--format", "json")
    assert result.exit_code == 0 and '"files": 0' in result.stdout
    assert result.stderr == ""
    verbose = run_cli("check", root / ".github/ci.yml", "--format", "json", "-v")
    assert "nothing to check" in verbose.stderr


def test_a_launch_file_named_checks_the_robots_it_builds(run_cli, tmp_path):
    """A launch file is no robot (it was checked as one: U001 'malformed XML' for a .launch.py,
    U004 for a <launch>): naming it checks the robots it builds, through the launch files that
    include it too, and one that builds none checks nothing."""
    root = tmp_path / "repo"
    (root / ".git").mkdir(parents=True)
    (root / "pkg" / "urdf").mkdir(parents=True)
    (root / "pkg" / "launch").mkdir()
    (root / "pkg" / "package.xml").write_text("<package><name>pkg</name></package>")
    (root / "pkg" / "urdf" / "bot.urdf.xacro").write_text(
        '<robot name="bot" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="base"/>'
        '<joint name="j" type="revolute"><parent link="base"/><child link="arm"/>'
        '<limit lower="1" upper="-1" effort="1" velocity="1"/></joint><link name="arm"/></robot>')
    (root / "pkg" / "launch" / "load.launch").write_text(
        '<launch><param name="robot_description" '
        'command="$(find xacro)/xacro $(find pkg)/urdf/bot.urdf.xacro"/></launch>')
    (root / "pkg" / "launch" / "run.launch").write_text(
        '<launch><include file="$(find pkg)/launch/load.launch"/></launch>')
    (root / "pkg" / "launch" / "nothing.launch.py").write_text(
        "from launch import LaunchDescription\n\n\ndef generate_launch_description():\n"
        "    return LaunchDescription([])\n")
    for launch in ("load.launch", "run.launch"):
        result = run_cli("check", root / "pkg" / "launch" / launch, "--format", "concise")
        assert result.exit_code == 1 and "bot.urdf.xacro" in result.stdout, result.stdout
        assert "U001" not in result.stdout and "U004" not in result.stdout
        assert "a launch file building" in result.stderr
    nothing = run_cli("check", root / "pkg" / "launch" / "nothing.launch.py", "--format", "json")
    assert nothing.exit_code == 0 and '"files": 0' in nothing.stdout and "U001" not in nothing.stdout
    # "0 files checked" says why without -v when a launch file named gave nothing to check
    assert nothing.stderr.startswith(f"skipped {root / 'pkg' / 'launch' / 'nothing.launch.py'}: "
                                     "a launch file that builds no robot file urdftool can tell")



@pytest.mark.parametrize("name, text, why", [
    ("broken.launch", "<launch>\n<oops></launch>\n", "could not be read (not well-formed XML: "),
    ("empty.launch", "", "could not be read (empty)"),
    ("broken.launch.py", "def generate_launch_description(:\n",
     "could not be read (not valid Python: "),
    ("large.launch", "<launch><!--" + "x" * (600 * 1024) + "--></launch>",
     "could not be read (larger than "),
    ("nothing.launch", "<launch/>", "builds no robot file urdftool can tell"),
])
def test_a_launch_file_named_that_builds_nothing_says_why(tmp_path, name, text, why):
    """session 9: every launch file named that gave no robot said "builds no robot file
    urdftool can tell", a launch file not well-formed, over the size limit or in no
    repository too; the skip now says why (``runtime.why_builds_nothing``)."""
    from urdftool.lint.settings import CheckRequest
    from urdftool.lint.targets import expand

    (tmp_path / ".git").mkdir()
    (tmp_path / "launch").mkdir()
    (tmp_path / "launch" / name).write_text(text)
    targets = expand([str(tmp_path / "launch" / name)], CheckRequest())
    assert targets.files == []
    [reason] = targets.skipped.values()
    assert reason.startswith(f"a launch file that {why}"), reason
    assert "('syntax'" not in reason


def test_a_launch_file_named_that_builds_nothing_is_recorded_as_such_once(tmp_path):
    """session 11: the command found these among the skipped by the start of their reason (a
    YAML's or a macro's reason worded alike would have been said too); ``Targets.unbuilt``
    records them, each once however often named."""
    from urdftool.lint.settings import CheckRequest
    from urdftool.lint.targets import expand

    (tmp_path / ".git").mkdir()
    (tmp_path / "empty.launch").write_text("<launch/>")
    (tmp_path / "robot.yaml").write_text("a: 1\n")
    named = [str(tmp_path / "empty.launch"), str(tmp_path / "robot.yaml"),
             str(tmp_path / "empty.launch")]
    targets = expand(named, CheckRequest())
    assert targets.unbuilt == [named[0]]
    assert set(targets.skipped) == {named[0], named[1]}


def test_a_launch_file_named_in_no_repository_says_so(tmp_path):
    (tmp_path / "show.launch").write_text('<launch><param name="robot_description" '
                                          'textfile="robot.urdf"/></launch>')
    from urdftool.lint.settings import CheckRequest
    from urdftool.lint.targets import expand

    [reason] = expand([str(tmp_path / "show.launch")], CheckRequest()).skipped.values()
    assert "is in no repository or package" in reason, reason


GAZEBO_FRAGMENT = """<?xml version="1.0"?>
<robot name="bot_sim" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="laser_visual" default="false"/>
  <gazebo reference="base_link"><material>Gazebo/DarkGrey</material></gazebo>
  <gazebo reference="wheel_link"><mu1>0.1</mu1></gazebo>
  <gazebo>
    <plugin name="bot_controller" filename="libgazebo_ros_diff_drive.so">
      <leftJoint>wheel_joint</leftJoint><rightJoint>wheel_joint</rightJoint>
      <robotBaseFrame>base_link</robotBaseFrame>
    </plugin>
  </gazebo>
  <transmission name="wheel_transmission">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="wheel_joint"><hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface></joint>
    <actuator name="wheel_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
ROBOT_WITH_FRAGMENT = """<?xml version="1.0"?>
<robot name="bot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find bot_description)/urdf/bot.gazebo.xacro"/>
  <link name="base_link"/>
  <link name="wheel_link"/>
  <joint name="wheel_joint" type="continuous">
    <parent link="base_link"/><child link="wheel_link"/><axis xyz="0 1 0"/>
  </joint>
</robot>
"""


def _fragment_package(root):
    """The X.urdf.xacro beside X.gazebo.xacro layout (turtlebot3's), in a repository."""
    (root / ".git").mkdir(parents=True)
    urdf = root / "bot_description" / "urdf"
    urdf.mkdir(parents=True)
    (root / "bot_description" / "package.xml").write_text(
        "<package format='2'><name>bot_description</name></package>")
    (urdf / "bot.urdf.xacro").write_text(ROBOT_WITH_FRAGMENT)
    (urdf / "bot.gazebo.xacro").write_text(GAZEBO_FRAGMENT)
    (urdf / "unused.gazebo.xacro").write_text(GAZEBO_FRAGMENT)
    return urdf


def test_a_gazebo_fragment_named_is_checked_through_the_robot_including_it(run_cli, tmp_path):
    # issue 30 class 9: pre-commit passes bot.gazebo.xacro by name; alone it has no links
    # (U106) and every reference misses (U611, U612): 89 false errors on turtlebot3
    urdf = _fragment_package(tmp_path)
    result = run_cli("check", urdf / "bot.gazebo.xacro", "--format", "json")
    assert '"files": 1' in result.stdout and "U106" not in result.stdout, result.stdout
    assert "U611" not in result.stdout and "included by" in result.stderr
    assert "bot.urdf.xacro" in result.stderr
    both = run_cli("check", urdf / "bot.gazebo.xacro", urdf / "bot.urdf.xacro", "--format", "json")
    assert '"files": 1' in both.stdout


def test_a_fragment_nobody_includes_is_skipped_named_or_walked(run_cli, tmp_path):
    from urdftool.lint.settings import CheckRequest
    from urdftool.lint.targets import FRAGMENT, expand

    urdf = _fragment_package(tmp_path)
    named = run_cli("check", urdf / "unused.gazebo.xacro", "--format", "json")
    assert named.exit_code == 0 and '"files": 0' in named.stdout
    assert FRAGMENT in named.stderr and "nothing to check" in named.stderr
    walked = expand([str(tmp_path)], CheckRequest())
    assert [p.rsplit("/", 1)[-1] for p in walked.files] == ["bot.urdf.xacro"]
    assert walked.skipped[str(urdf / "unused.gazebo.xacro")] == FRAGMENT


UNBOUND_PREFIX = """<?xml version="1.0"?>
<robot name="arm">
  <xacro:macro name="arm" params="prefix">
    <link name="${prefix}base"/>
  </xacro:macro>
</robot>
"""


def test_a_malformed_xacro_file_is_reported_walked_or_named(run_cli, tmp_path):
    # issue 30 class 10: the xacro: prefix without xmlns:xacro made a folder walk skip the file
    # as a macro library (lxml's recovering parser kept going), and nothing reported it
    (tmp_path / ".git").mkdir()
    (tmp_path / "arm_macro.xacro").write_text(UNBOUND_PREFIX)
    (tmp_path / "lib.xacro").write_text(UNBOUND_PREFIX.replace(
        '<robot name="arm">', '<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">'))
    for target in (tmp_path, tmp_path / "arm_macro.xacro"):
        result = run_cli("check", target, "--format", "json")
        assert result.exit_code == 1 and '"files": 1' in result.stdout, result.stdout
        assert "U001" in result.stdout and "arm_macro.xacro" in result.stdout
    broken = tmp_path / "broken.xacro"
    broken.write_text('<robot name="b" xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="m">')
    result = run_cli("check", tmp_path, "--format", "json")
    assert '"files": 2' in result.stdout and "broken.xacro" in result.stdout


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


def test_a_robot_of_its_own_named_is_read_once_and_its_includes_not_resolved(monkeypatch):
    """Named on the command line, a robot of its own is decided from its bytes, read once:
    its includes (which a robot of its own does not need) are not resolved, and the rest of
    the classification is not done. A 10,000-link robot's text was read and scanned three
    times."""
    from urdftool.lint import targets
    from urdftool.lint.settings import CheckRequest

    reads, head = [], targets._head
    monkeypatch.setattr(targets, "_head", lambda path, *rest: reads.append(path) or head(path, *rest))

    def resolved(*_):
        raise AssertionError("its includes were resolved")

    monkeypatch.setattr(targets, "_included_files", resolved)
    monkeypatch.setattr(targets, "_summary", resolved)
    robot = str(ROBOTS / "r2d2" / "r2d2.urdf.xacro")
    assert targets.expand([robot], CheckRequest()).files == [robot]
    assert [str(path) for path in reads] == [robot]


def test_macro_definitions_are_removed_only_where_a_macro_is_written():
    import random
    import re

    from urdftool.lint.targets import _without_macro_bodies

    # the expression they were removed by: each opening tag looked for its closing one to the
    # end of the file (quadratic: xacro_text.without_macro_bodies says the same in linear time)
    macro_body = re.compile(rb"<(?:xacro:)?macro\s.*?</(?:xacro:)?macro\s*>", re.S)
    parts = [b"<xacro:macro name='m'>", b"</xacro:macro>", b"<macro ", b"</macro >", b"macro",
             b"<link name='a'/>", b"<xacro:include filename='x.xacro'/>", b"\n", b" ", b"mac"]
    chance = random.Random(34)
    for _ in range(2000):
        data = b"".join(chance.choice(parts) for _ in range(chance.randint(0, 8)))
        assert _without_macro_bodies(data) == macro_body.sub(b"", data), data


@pytest.mark.parametrize("name, words", [
    ("_ANY_INCLUDE", [b"include"]), ("_INCLUDE", [b"include"]), ("_MACRO", [b"macro"]),
    ("_LINK_MAKER", [b"<xacro:", b"include"]), ("_NAMED_FILE", [b".xacro", b".urdf"])])
def test_a_pattern_is_searched_only_where_a_word_it_needs_is(name, words):
    """The classification looks for a word with bytes' own search before a pattern tried at
    each "<" or "=" of a file: a text without any of the words must hold no match."""
    import random

    from urdftool.lint import targets

    pattern = getattr(targets, name)
    parts = [b"<xacro:include filename='a.xacro'/>", b"<include ", b"<xacro:macro name='m'>",
             b"<macro ", b"<xacro:m/>", b"<xacro:property name='p'/>", b'value="x.urdf"',
             b"= 'y.xacro'", b"<link name='a'/>", b"incl", b"ude", b"mac", b"ro", b".xac",
             b"ro'", b".ur", b'df"', b"<xacro", b":", b"=", b"'", b'"', b" ", b"\n", b"<"]
    chance = random.Random(19)
    for _ in range(3000):
        data = b"".join(chance.choice(parts) for _ in range(chance.randint(0, 10)))
        assert any(word in data for word in words) or pattern.search(data) is None, data


def test_the_include_graph_is_what_the_summaries_include(tmp_path):
    """``includers_below`` reads only each file's includes, not its whole summary: the same
    graph as the summaries' includes (an include, a file named by a macro's parameter, one
    commented out, one through $(arg) and a file that includes nothing)."""
    from urdftool.lint import targets
    from urdftool.lint.settings import CheckRequest, for_file

    (tmp_path / ".git").mkdir()
    files = {
        "robot.urdf.xacro": '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                            '<xacro:arg name="part" default="part.xacro"/>'
                            '<xacro:include filename="arm.xacro"/>'
                            '<xacro:include filename="$(arg part)"/>'
                            '<!-- <xacro:include filename="old.xacro"/> -->'
                            '<xacro:arm layout="legs.xacro"/></robot>',
        "arm.xacro": '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro '
                     'name="arm" params="layout"><xacro:include filename="${layout}"/>'
                     '<link name="a"/></xacro:macro></robot>',
        "part.xacro": '<robot><link name="p"/></robot>', "legs.xacro": "<robot/>",
        "old.xacro": "<robot/>", "alone.urdf": '<robot name="x"><link name="x"/></robot>'}
    for name, text in files.items():
        (tmp_path / name).write_text(text)

    def resolver_for(path):
        return targets.PackageResolver(for_file(str(path), CheckRequest()).options.packages,
                                       start=path.parent)

    graph = {}
    for path in targets.robot_files(tmp_path):
        for target in targets._summary(path, resolver_for, 1 << 20).includes:
            graph.setdefault(target, []).append(path)
    assert targets.includers_below(tmp_path, resolver_for) == graph
    assert sorted(target.name for target in graph) == ["arm.xacro", "legs.xacro", "part.xacro"]


def test_a_part_that_only_calls_macros_named_is_checked_through_its_robot(run_cli, tmp_path):
    # niryo's niryo_ned.transmission.xacro: a named <robot> whose content is transmissions made
    # by macro calls; alone it has no link (U106) and no joint its transmissions name (U501)
    urdf = _fragment_package(tmp_path)
    part = urdf / "bot.transmission.xacro"
    part.write_text("""<robot name="bot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="trans" params="joint">
    <transmission name="${joint}_t"><type>transmission_interface/SimpleTransmission</type>
      <joint name="${joint}"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
      <actuator name="${joint}_m"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>
  </xacro:macro>
  <xacro:trans joint="wheel_joint"/>
</robot>""")
    robot = urdf / "bot.urdf.xacro"
    robot.write_text(robot.read_text().replace(
        "</robot>", '<xacro:include filename="$(find bot_description)/urdf/bot.transmission.xacro"/>\n</robot>'))
    result = run_cli("check", part, "--format", "json")
    assert '"files": 1' in result.stdout and "U106" not in result.stdout and "U501" not in result.stdout
    assert "included by" in result.stderr and "bot.urdf.xacro" in result.stderr


def test_a_part_hanging_on_its_robots_link_named_is_checked_through_its_robot(run_cli, tmp_path):
    # baxter's pedestal.xacro: a named <robot> with links and joints of its own, one joint on
    # the 'torso' of the robot that includes it; alone it is U105 (the walk skips it as included)
    urdf = _fragment_package(tmp_path)
    part = urdf / "bot_pedestal.xacro"
    part.write_text("""<robot name="pedestal" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="pedestal"/>
  <joint name="pedestal_fixed" type="fixed"><parent link="base_link"/><child link="pedestal"/></joint>
</robot>""")
    robot = urdf / "bot.urdf.xacro"
    robot.write_text(robot.read_text().replace(
        "</robot>", '<xacro:include filename="$(find bot_description)/urdf/bot_pedestal.xacro"/>\n</robot>'))
    result = run_cli("check", part, "--format", "json")
    assert '"files": 1' in result.stdout and "U105" not in result.stdout
    assert "included by" in result.stderr and "bot.urdf.xacro" in result.stderr


def test_a_part_calling_its_includers_macro_named_is_checked_through_its_robot(run_cli, tmp_path):
    # programmatoroSeduto/arm_urdf's arm.xacro: a named <robot> with its own links, which calls
    # the cylinder_inertia macro its includer took from macros.xacro before including it; alone
    # xacro fails on it (U005 'unknown macro name'), which the walk (main.xacro) never said
    (tmp_path / ".git").mkdir()
    (tmp_path / "macros.xacro").write_text("""<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="box_inertia" params="m"><inertia ixx="${m}" ixy="0" ixz="0" iyy="${m}" iyz="0" izz="${m}"/></xacro:macro>
</robot>""")
    part = tmp_path / "arm.xacro"
    part.write_text("""<robot name="robot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <!-- <xacro:include filename="macros.xacro"/> -->
  <link name="arm"><inertial><mass value="1"/><xacro:box_inertia m="0.1"/></inertial></link>
</robot>""")
    _checked_through_its_includer(run_cli, part, "macros.xacro", "arm", "U005")  # xacro fails alone


def test_a_part_naming_its_includers_materials_named_is_checked_through_its_robot(run_cli, tmp_path):
    # aip-primeca-occitanie/ros_yaskawa_hc10's cell.xacro: a named <robot> with its own links
    # whose <material name="silver"/> the includer defines (materials.xacro, included first);
    # alone urdfdom refuses it (U406), which the walk (hc10dt_with_env.xacro) never said
    (tmp_path / ".git").mkdir()
    (tmp_path / "materials.xacro").write_text(
        '<robot><material name="silver"><color rgba="0.7 0.7 0.7 1"/></material></robot>')
    part = tmp_path / "cell.xacro"
    part.write_text("""<robot name="env">
  <link name="cell"><visual><geometry><box size="1 1 1"/></geometry><material name="silver"/></visual></link>
  <link name="rail"><visual><geometry><box size="1 1 1"/></geometry>
    <material name="red"><color rgba="1 0 0 1"/></material></visual></link>
  <joint name="j" type="fixed"><parent link="cell"/><child link="rail"/></joint>
</robot>""")
    _checked_through_its_includer(run_cli, part, "materials.xacro", "cell", "U406")  # silver undefined alone


def _checked_through_its_includer(run_cli, part, library: str, link: str, code: str):
    """``part`` named: checked through main.xacro, which includes ``library`` and then it
    (no ``code``); once nobody includes it, checked as it is (``code``)."""
    main = part.parent / "main.xacro"
    main.write_text(f"""<robot name="robot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="{library}"/>
  <link name="base"/>
  <xacro:include filename="{part.name}"/>
  <joint name="j" type="fixed"><parent link="base"/><child link="{link}"/></joint>
</robot>""")
    result = run_cli("check", part, "--format", "json")
    assert '"files": 1' in result.stdout and code not in result.stdout, result.stdout
    assert "included by" in result.stderr and "main.xacro" in result.stderr
    main.unlink()
    result = run_cli("check", part, "--format", "json")
    assert '"files": 1' in result.stdout and code in result.stdout


def test_a_library_named_including_a_package_found_nowhere_is_checked(run_cli, tmp_path):
    # doosan-robot2's macro.*mobile.xacro: $(find dsr_description), ROS 1's name of the ROS 2
    # package dsr_description2; naming it says so (U006), as it did before libraries whose
    # includes cannot be followed were skipped; one inside a macro body is not (kortex's grippers)
    (tmp_path / ".git").mkdir()
    library = tmp_path / "mobile_macro.xacro"
    library.write_text("""<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find no_such_description)/xacro/base.xacro"/>
  <xacro:macro name="mobile" params="prefix"><link name="${prefix}base"/></xacro:macro>
</robot>""")
    named = run_cli("check", library, "--format", "json")
    assert '"files": 1' in named.stdout and "U006" in named.stdout
    library.write_text(library.read_text().replace(
        '<xacro:include filename="$(find no_such_description)/xacro/base.xacro"/>', "").replace(
        '<link name="${prefix}base"/>',
        '<xacro:include filename="$(find no_such_description)/xacro/base.xacro"/><link name="${prefix}base"/>'))
    named = run_cli("check", library, "--format", "json")
    assert '"files": 0' in named.stdout


def test_a_macro_library_named_whose_includes_cannot_be_followed_is_a_library(run_cli, tmp_path):
    # kortex's gen3_macro.xacro, named by pre-commit: a named <robot> defining a macro and
    # including files by ${...} paths; the walk skips it, and so does naming it
    (tmp_path / ".git").mkdir()
    library = tmp_path / "arm_macro.xacro"
    library.write_text("""<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="dof" value="6"/>
  <xacro:include filename="$(find arm)/${dof}dof/parts.xacro"/>
  <xacro:macro name="load_arm" params="prefix"><link name="${prefix}base"/></xacro:macro>
</robot>""")
    named = run_cli("check", library, "--format", "json")
    assert '"files": 0' in named.stdout and "defines only macros" in named.stderr


def test_a_urdf_holding_only_plugin_blocks_is_a_fragment_walked_or_named(run_cli, tmp_path):
    # webots_ros2's resource/*_webots.urdf: a <robot> of <webots> and <ros2_control> blocks that
    # the driver reads beside the real robot description; alone it has no link (U106, U511)
    (tmp_path / ".git").mkdir()
    (tmp_path / "robot.urdf").write_text(
        '<robot name="r"><link name="base"/><link name="wheel"/><joint name="j" type="continuous">'
        '<parent link="base"/><child link="wheel"/></joint></robot>')
    (tmp_path / "robot_webots.urdf").write_text(
        '<robot name="r"><webots><plugin type="webots_ros2_control::Ros2Control"/></webots>'
        '<ros2_control name="w" type="system"><hardware><plugin>webots_ros2_control::Ros2ControlSystem'
        '</plugin></hardware><joint name="j"><command_interface name="velocity"/></joint>'
        '</ros2_control></robot>')
    walked = run_cli("check", tmp_path, "--format", "json")
    assert '"files": 1' in walked.stdout and "U106" not in walked.stdout
    named = run_cli("check", tmp_path / "robot_webots.urdf", "--format", "json")
    assert '"files": 0' in named.stdout and "fragment" in named.stderr


def test_a_part_included_only_by_a_library_nobody_includes_is_skipped_named_or_walked(
        run_cli, tmp_path):
    """clearpath's a200.urdf.xacro: a nameless <robot> of arguments, includes and the macro
    a robot generated at run time calls. Named with its wheel macro (pre-commit names every
    staged file) the wheel was checked through it, the library checked as a robot: U011 and
    U106, as the library named alone or walked is skipped."""
    (tmp_path / ".git").mkdir()
    lib = tmp_path / "a200.urdf.xacro"
    lib.write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
                   '<xacro:include filename="wheel.urdf.xacro"/>'
                   '<xacro:macro name="a200"><link name="base"/><xacro:wheel/></xacro:macro>'
                   '</robot>')
    (tmp_path / "wheel.urdf.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:macro name="wheel">'
        '<link name="wheel"/></xacro:macro></robot>')
    for named in ([tmp_path / "wheel.urdf.xacro"], [lib, tmp_path / "wheel.urdf.xacro"]):
        result = run_cli("check", *named, "--format", "json")
        assert result.exit_code == 0 and '"files": 0' in result.stdout, result.output
        assert "nothing to check" in result.stderr
    walked = run_cli("check", tmp_path, "--format", "json")  # a folder: a robot was asked for
    assert walked.exit_code == 2 and "nothing checked" in walked.stderr and not walked.stdout
    # a robot including the library is checked instead, as before
    (tmp_path / "robot.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="a200.urdf.xacro"/><xacro:a200/></robot>')
    result = run_cli("check", tmp_path / "wheel.urdf.xacro", "--format", "json")
    assert '"files": 1' in result.stdout and "robot.urdf.xacro" in result.stderr


def _repository(folder: Path, files: dict[str, str]) -> Path:
    """``folder`` made a repository (a ``.git`` folder) holding ``files`` (name -> text)."""
    (folder / ".git").mkdir(exist_ok=True)
    for name, text in files.items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(text)
    return folder


def _walked_and_named(tmp_path, *named):
    """expand() of the folder walked and of ``named`` files (as pre-commit names them)."""
    from urdftool.lint.settings import CheckRequest
    from urdftool.lint.targets import expand

    return (expand([str(tmp_path)], CheckRequest()),
            expand([str(tmp_path / name) for name in named], CheckRequest()))


def test_an_empty_robot_is_a_placeholder_walked_or_named(tmp_path):
    # Clearpath's empty.urdf (husky, jackal, dingo, ridgeback, warthog, spot): the file an
    # $(optenv X_URDF_EXTRAS empty.urdf) include takes by default; alone U011 and U106
    _repository(tmp_path, {
        "empty.urdf": "<robot>\n  <!-- a placeholder -->\n</robot>\n",
        "nothing.urdf": '<robot name="empty"/>',
    })
    walked, named = _walked_and_named(tmp_path, "empty.urdf", "nothing.urdf")
    assert walked.files == [] and named.files == []
    assert "empty <robot>" in walked.skipped[str(tmp_path / "empty.urdf")]
    assert all("empty <robot>" in note for note in named.notes)


def test_an_accessory_with_no_root_of_its_own_is_a_part_walked_or_named(tmp_path):
    # jackal's custom_example.urdf, meant for $(optenv JACKAL_URDF_EXTRAS ...): joints on the
    # 'front_mount' of the jackal including it; alone U011, U106 and a U105 per joint end
    _repository(tmp_path, {
        "custom_example.urdf":
            '<robot><joint name="j" type="fixed"><parent link="front_mount"/><child link="cam"/>'
            '</joint><link name="cam"/></robot>',
        # a robot whose joint names a misspelt parent keeps its root: checked (U105 says it)
        "robot.urdf":
            '<robot name="r"><link name="base"/><link name="cam"/><joint name="j" type="fixed">'
            '<parent link="bsae"/><child link="cam"/></joint></robot>',
    })
    walked, named = _walked_and_named(tmp_path, "custom_example.urdf", "robot.urdf")
    assert walked.files == [str(tmp_path / "robot.urdf")]
    assert named.files == [str(tmp_path / "robot.urdf")]
    assert "no root link" in walked.skipped[str(tmp_path / "custom_example.urdf")]


def test_an_include_through_an_optenv_default_or_an_argument_default_is_an_include(tmp_path):
    # jackal.urdf.xacro: <xacro:include filename="$(optenv JACKAL_URDF_EXTRAS extras.urdf)"/>;
    # husky.urdf.xacro: the same default given to an argument, included as $(arg urdf_extras);
    # ros-naoqi's nao_robot_v4.urdf.xacro: pre-2019 <include> without the xacro: prefix;
    # a commented include is none (cob_common's ur10_arm.urdf.xacro named a missing package
    # only there, and was checked as a robot when named: U011, U106)
    (tmp_path / ".git").mkdir()
    part = ('<robot><link name="{n}"/><joint name="{n}_j" type="fixed"><parent link="base"/>'
            '<child link="{n}"/></joint></robot>')
    for name in ("extras", "more", "old"):
        (tmp_path / f"{name}.xacro").write_text(part.format(n=name))
    (tmp_path / "robot.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="base"/>'
        '<xacro:arg name="more" default="$(optenv MORE more.xacro)"/>'
        '<xacro:include filename="$(optenv EXTRAS extras.xacro)"/>'
        '<xacro:include filename="$(arg more)"/><include filename="old.xacro"/></robot>')
    (tmp_path / "library.urdf.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<!-- <xacro:include filename="$(find nowhere_description)/urdf/arm.xacro"/> -->'
        '<xacro:macro name="arm"><link name="a"/></xacro:macro></robot>')
    walked, named = _walked_and_named(tmp_path, "extras.xacro", "more.xacro", "old.xacro",
                                      "library.urdf.xacro")
    assert walked.files == named.files == [str(tmp_path / "robot.urdf.xacro")]
    assert "macro library" in walked.skipped[str(tmp_path / "library.urdf.xacro")]


def test_a_xacro_part_with_no_root_of_its_own_is_a_part_and_world_is_no_link(tmp_path):
    # articubot_one's depth_camera.xacro (its include commented out, so nobody includes it):
    # joints on the 'chassis' of a robot defined elsewhere; a robot fixed to Gazebo's 'world'
    # is a robot, and so is one whose root a macro call writes
    ns = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
    _repository(tmp_path, {
        "depth_camera.xacro":
            f'<robot {ns}><joint name="j" type="fixed"><parent link="chassis"/>'
            '<child link="camera_link"/></joint><link name="camera_link"/></robot>',
        "arm.urdf.xacro":
            f'<robot name="arm" {ns}><joint name="j" type="fixed"><parent link="world"/>'
            '<child link="base"/></joint><link name="base"/></robot>',
        "rover.urdf.xacro":
            f'<robot name="rover" {ns}><xacro:macro name="body"><link name="chassis"/>'
            '</xacro:macro><xacro:body/><joint name="j" type="fixed"><parent link="chassis"/>'
            '<child link="mast"/></joint><link name="mast"/></robot>',
    })
    walked, named = _walked_and_named(tmp_path, "depth_camera.xacro", "arm.urdf.xacro",
                                      "rover.urdf.xacro")
    robots = [str(tmp_path / "arm.urdf.xacro"), str(tmp_path / "rover.urdf.xacro")]
    assert walked.files == named.files == robots
    assert "no root link" in walked.skipped[str(tmp_path / "depth_camera.xacro")]


def test_a_macro_called_inside_a_link_writes_no_root(tmp_path):
    # HerGousis' camera3_dokari.xacro (its include commented out, so nobody includes it): a
    # camera on the 'dokari_link' of a robot defined elsewhere, whose <link> calls the
    # box_inertia macro its includer takes from common_properties.xacro; alone xacro failed
    # on it (U005). A macro called at the top level may still write the root.
    ns = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
    joint = ('<joint name="j" type="fixed"><parent link="dokari_link"/><child link="camera"/>'
             '</joint>')
    _repository(tmp_path, {
        "camera.xacro": f'<robot {ns}><link name="camera"><xacro:box_inertia m="0.1"/>'
                        f'</link>{joint}</robot>',
        "mast.xacro": f'<robot {ns}><xacro:dokari/><link name="camera"/>{joint}</robot>',
    })
    walked, named = _walked_and_named(tmp_path, "camera.xacro", "mast.xacro")
    assert walked.files == [str(tmp_path / "mast.xacro")]
    assert "no root link" in walked.skipped[str(tmp_path / "camera.xacro")]


def test_a_macro_library_with_a_top_level_plugin_is_a_library(tmp_path):
    # laloutsos/Custom_Clearpath_Robot's clearpath_common do100.urdf.xacro: arguments, the
    # do100 macro and, at the top level, a gz-sim JointStatePublisher <plugin>; checked alone
    # it was a robot with no name and no link (U011, U106)
    ns = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
    _repository(tmp_path, {
        "do100.urdf.xacro": f'<robot {ns}><xacro:arg name="is_sim" default="false"/>'
                            '<xacro:macro name="do100"><link name="base_link"/></xacro:macro>'
                            '<plugin filename="gz-sim-joint-state-publisher-system" '
                            'name="gz::sim::systems::JointStatePublisher"/></robot>',
    })
    walked, named = _walked_and_named(tmp_path, "do100.urdf.xacro")
    assert walked.files == named.files == []


def test_a_file_handed_to_an_include_through_a_macro_parameter_is_included(tmp_path):
    # osrf/vrx: wamv_gazebo.urdf.xacro calls <xacro:wamv_gazebo thruster_layout="$(find
    # wamv_gazebo)/urdf/thruster_layouts/wamv_aft_thrusters.xacro"/>, whose macro includes
    # "${thruster_layout}"; the layout (and the engine.xacro it includes) are parts of that
    # robot, not robots checked on their own (U005: 'namespace' is the robot's property)
    ns = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
    _repository(tmp_path, {
        "layout.xacro":
            f'<robot {ns}><link name="${{namespace}}/engine"/><joint name="e" type="fixed">'
            '<parent link="${namespace}/base"/><child link="${namespace}/engine"/></joint></robot>',
        "macros.xacro":
            f'<robot {ns}><xacro:macro name="boat" params="layout">'
            '<xacro:include filename="${layout}"/></xacro:macro></robot>',
        "boat.urdf.xacro":
            f'<robot name="boat" {ns}><xacro:property name="namespace" value="wamv"/>'
            '<link name="wamv/base"/><xacro:include filename="macros.xacro"/>'
            '<xacro:boat layout="layout.xacro"/></robot>',
    })
    walked, named = _walked_and_named(tmp_path, "layout.xacro")
    assert walked.files == named.files == [str(tmp_path / "boat.urdf.xacro")]
    assert "included by" in walked.skipped[str(tmp_path / "layout.xacro")]


def test_a_urdf_holding_a_xacro_include_keeps_its_root_to_the_include(tmp_path):
    # elephantrobotics' mycobot_with_vision_copy.urdf: a .urdf that includes (with xacro) the
    # arm writing 'joint1', a file since removed; it is a robot, checked (U007 and what is
    # missing), not a part of another robot
    (tmp_path / ".git").mkdir()
    (tmp_path / "copy.urdf").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="gone.urdf"/><link name="env"/>'
        '<joint name="j" type="fixed"><parent link="joint1"/><child link="env"/></joint></robot>')
    walked, named = _walked_and_named(tmp_path, "copy.urdf")
    assert walked.files == named.files == [str(tmp_path / "copy.urdf")]


def test_a_part_a_launch_file_runs_as_the_robot_is_checked_walked_or_named(tmp_path):
    """Whatever its text shows (a fragment, no root of its own, an empty placeholder), a file
    a launch file of its repository gives robot_state_publisher unconditionally is a robot:
    checked, and what it lacks is an error where it runs (a misspelt root, no link)."""
    (tmp_path / ".git").mkdir()
    (tmp_path / "package.xml").write_text("<package format='3'><name>p</name></package>")
    root_typo = ('<robot name="r"><link name="base"/><link name="arm"/>'
                 '<joint name="j0" type="fixed"><parent link="bsae"/><child link="base"/></joint>'
                 '<joint name="j1" type="fixed"><parent link="base"/><child link="arm"/></joint>'
                 '</robot>')
    files = {"typo.urdf": root_typo, "typo_unrun.urdf": root_typo,
             "gazebo.urdf": '<robot><gazebo><plugin name="x" filename="libx.so"/></gazebo></robot>',
             "empty.urdf": "<robot>\n</robot>\n"}
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    run = "".join(
        f"        Node(package='robot_state_publisher', executable='robot_state_publisher',"
        f" parameters=[{{'robot_description': Command(['xacro ', PathJoinSubstitution("
        f"[FindPackageShare('p'), '{name}'])])}}]),\n"
        for name in ("typo.urdf", "gazebo.urdf", "empty.urdf"))
    (tmp_path / "launch").mkdir()
    (tmp_path / "launch/robot.launch.py").write_text(
        "def generate_launch_description():\n    return LaunchDescription([\n" + run + "    ])\n")
    walked, named = _walked_and_named(tmp_path, *files)
    ran = sorted(str(tmp_path / name) for name in ("empty.urdf", "gazebo.urdf", "typo.urdf"))
    assert sorted(walked.files) == ran and sorted(named.files) == ran
    assert "no root link" in walked.skipped[str(tmp_path / "typo_unrun.urdf")]


def test_a_part_only_a_launch_test_builds_stays_a_part_walked_as_checked(tmp_path):
    """A launch test builds a file for the test alone, never as a deployment: the walk skips a
    part only a launch test builds, as the check judges it a part (launch configurations
    only). Before, the walk checked it and the check then made every finding a note."""
    _repository(tmp_path, {
        "package.xml": "<package format='3'><name>p</name></package>",
        "tested.urdf":
            '<robot name="r"><link name="base"/><link name="arm"/>'
            '<joint name="j0" type="fixed"><parent link="bsae"/><child link="base"/></joint>'
            '<joint name="j1" type="fixed"><parent link="base"/><child link="arm"/></joint>'
            '</robot>',
    })
    (tmp_path / "test").mkdir()
    (tmp_path / "test/test_robot.py").write_text(
        "def generate_test_description():\n    return LaunchDescription([\n"
        "        Node(package='robot_state_publisher', executable='robot_state_publisher',"
        " parameters=[{'robot_description': Command(['xacro ', PathJoinSubstitution("
        "[FindPackageShare('p'), 'tested.urdf'])])}]),\n"
        "        ReadyToTest(),\n    ])\n")
    walked, _ = _walked_and_named(tmp_path, "tested.urdf")
    assert walked.files == [] and "no root link" in walked.skipped[str(tmp_path / "tested.urdf")]


def test_a_robot_named_is_read_once_and_its_settings_looked_up_once(tmp_path, monkeypatch):
    """What a file named on the command line is (a robot of its own, a part, a library) is
    decided from one read of it, under the settings looked up once for it; a robot of its own
    without following its includes (its summary is for what is not one)."""
    from urdftool.lint import settings, targets
    from urdftool.lint.settings import CheckRequest

    (tmp_path / ".git").mkdir()
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/><link name="b"/><joint name="j" '
                     'type="fixed"><parent link="a"/><child link="b"/></joint></robot>')
    reads, lookups = [], []
    from urdftool.description import xacro_text

    real_read, real_for_file = xacro_text.read_regular, settings.for_file
    monkeypatch.setattr(xacro_text, "read_regular",
                        lambda path, *a, **k: reads.append(path) or real_read(path, *a, **k))
    monkeypatch.setattr(settings, "for_file",
                        lambda path, *a: lookups.append(path) or real_for_file(path, *a))
    summaries = []
    real_summary = targets._summary
    monkeypatch.setattr(targets, "_summary", lambda *a: summaries.append(a) or real_summary(*a))
    assert targets.expand([str(robot)], CheckRequest()).files == [str(robot)]
    assert [str(p) for p in reads] == [str(robot)] and lookups == [str(robot)]
    assert not summaries


ROOTLESS = """<robot name="r"><link name="a"/>
<joint name="j" type="fixed"><parent link="base"/><child link="a"/></joint></robot>"""


@pytest.mark.parametrize("form", ["text", "json", "sarif", "github", "junit"])
def test_a_check_that_checks_nothing_is_a_usage_error_not_a_pass(run_cli, tmp_path, form):
    """A robot whose root link was deleted is a part nobody includes: named or walked, the run
    checked nothing and said 'no problems found' with exit 0 (attacks.md A172). A macro library
    or a YAML named alone (pre-commit names every staged file) is nothing to check by what it
    is: exit 0, and the text says so."""
    (tmp_path / ".git").mkdir()
    (tmp_path / "robots").mkdir()
    part = tmp_path / "robots" / "part.urdf"
    part.write_text(ROOTLESS)
    for path in (part, tmp_path / "robots"):
        result = run_cli("check", path, "--format", form)
        assert result.exit_code == 2 and not result.stdout, result.output
        assert "nothing checked" in result.stderr and "part.urdf" in result.stderr
    lib = tmp_path / "lib.xacro"
    lib.write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
                   '<xacro:macro name="m"><link name="a"/></xacro:macro></robot>')
    (tmp_path / "other.yaml").write_text("a: 1\n")
    quiet = run_cli("check", lib, tmp_path / "other.yaml", "--format", form)
    assert quiet.exit_code == 0 and "no problems found" not in quiet.stdout
    if form == "text":
        assert "0 files checked: nothing to check" in quiet.stdout
    both = run_cli("check", part, tmp_path / "robots" / ".." / "lib.xacro", "--format", form)
    assert both.exit_code == 2  # a part among what was named: still nothing checked


def test_a_solidworks_export_named_in_capitals_is_walked(tmp_path):
    """The SolidWorks exporter writes NAME.URDF (poppy-project/poppy-humanoid): a folder walk
    found no robot there and `check .` ended with a usage error; the language server and the
    pytest plugin ask the same question (description.urdf.is_robot_name)."""
    from urdftool.lint.settings import CheckRequest
    from urdftool.lint.targets import expand

    (tmp_path / ".git").mkdir()
    (tmp_path / "robots").mkdir()
    (tmp_path / "robots" / "Poppy.URDF").write_text('<robot name="p"><link name="a"/></robot>')
    walked = expand([str(tmp_path)], CheckRequest())
    assert [p.rsplit("/", 1)[-1] for p in walked.files] == ["Poppy.URDF"]
    from urdftool.description.urdf import is_robot_name

    assert is_robot_name("arm.Xacro") and not is_robot_name("arm.urdf.bak")


def test_a_named_macro_library_nobody_includes_is_read_once(monkeypatch, tmp_path):
    """A library named on the command line (a ``<robot name>`` of macros that nobody
    includes) is classified from the bytes read once: whether it writes links of its own is
    asked of them, not of the file read again. Skipped either way, as before."""
    from urdftool.lint import targets
    from urdftool.lint.settings import CheckRequest

    (tmp_path / ".git").mkdir()
    lib = tmp_path / "lib.xacro"
    lib.write_text('<robot name="lib" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                   '<xacro:macro name="m"><link name="a"/></xacro:macro></robot>')
    reads, head = [], targets._head
    monkeypatch.setattr(targets, "_head", lambda path, *rest: reads.append(path) or head(path, *rest))
    found = targets.expand([str(lib)], CheckRequest())
    assert found.files == [] and "nothing to check" in found.notes[0]
    assert [str(path) for path in reads] == [str(lib)]


def _beside_a_robot(folder, **files):
    """A repository of one robot.urdf and ``files`` (name, with '.' written '_', -> text)."""
    (folder / ".git").mkdir()
    (folder / "robot.urdf").write_text('<robot name="r"><link name="base"/></robot>')
    for name, text in files.items():
        (folder / name.replace("_", ".")).write_text(text)


def _sdf_sources(folder):
    """A Gazebo (gz) model and world built by xacro beside a robot (nav2's gz_waffle.sdf.xacro,
    tb3_sandbox.sdf.xacro: U004 'root element is <sdf>, expected <robot>' on both)."""
    _beside_a_robot(folder, waffle_sdf_xacro=(
        f'<?xml version="1.0"?>\n<sdf version="1.6" {XACRO_NS}><xacro:arg name="ns" default=""/>'
        '<model name="waffle"><link name="base"/></model></sdf>'), world_xacro=(
        f'<sdf version="1.8" {XACRO_NS}><world name="w"><include><uri>model://sun</uri>'
        '</include></world></sdf>'))


def test_sdf_documents_built_by_xacro_are_not_robots_in_a_folder_walk(tmp_path):
    from urdftool.lint.settings import CheckRequest
    from urdftool.lint.targets import SDF_SOURCE, expand

    _sdf_sources(tmp_path)
    targets = expand([str(tmp_path)], CheckRequest())
    assert targets.files == [str(tmp_path / "robot.urdf")]
    assert targets.skipped == {str(tmp_path / "waffle.sdf.xacro"): SDF_SOURCE,
                               str(tmp_path / "world.xacro"): SDF_SOURCE}


def test_an_sdf_document_named_is_not_checked_as_a_robot(run_cli, tmp_path):
    _sdf_sources(tmp_path)
    result = run_cli("check", tmp_path / "waffle.sdf.xacro", tmp_path / "world.xacro",
                     "--format", "json")
    assert result.exit_code == 0 and '"files": 0' in result.stdout
    assert "SDF document" in result.stderr and "U004" not in result.stdout


def test_a_blank_file_nothing_loads_is_a_placeholder_not_a_robot(run_cli, tmp_path):
    """maikelborys' diffbot.materials.xacro (zero bytes; the robot includes another file of
    that name) and neobotix's meca_wheel.xacro: U002 erred on files no consumer reads. As an
    empty <robot>: walked, skipped saying why; named alone, nothing to check. Loaded by a
    launch file, it is the robot, and U002 says it is empty (tests/cases/U002_empty_file)."""
    from urdftool.lint.settings import CheckRequest
    from urdftool.lint.targets import BLANK, expand

    (tmp_path / ".git").mkdir()
    (tmp_path / "robot.urdf").write_text('<robot name="r"><link name="a"/></robot>')
    blank = tmp_path / "placeholder.xacro"
    blank.write_text("\n  \n")
    walked = expand([str(tmp_path)], CheckRequest())
    assert walked.files == [str(tmp_path / "robot.urdf")]
    assert walked.skipped[str(blank)] == BLANK
    named = run_cli("check", blank)
    assert named.exit_code == 0 and "U002" not in named.output, named.output


def _xacro_test_harness(folder):
    """Shadow's sr_description/test/test_process_fingers_parameter.xacro: a ``<test>`` root
    whose macro calls print what a parameter expands to (U004 'root element is <test>,
    expected <robot>': an error on a file no consumer reads as a robot). Beside it, a robot
    file whose root is ``<robt>`` (a misspelling) and a ``.urdf.xacro`` with a ``<test>`` root,
    both still checked."""
    _beside_a_robot(folder, harness_xacro=(
        f'<test {XACRO_NS}><xacro:macro name="test" params="msg"><xacro:message msg="${{msg}}"/>'
        '</xacro:macro><xacro:test msg="a"/></test>'), typo_xacro=(
        f'<robt name="t" {XACRO_NS}><xacro:macro name="m"><link name="a"/></xacro:macro>'
        '<xacro:m/></robt>'), claims_urdf_xacro=(
        f'<test {XACRO_NS}><xacro:macro name="m"><link name="a"/></xacro:macro><xacro:m/></test>'))


def test_an_xml_document_of_another_kind_built_by_xacro_is_not_a_robot(tmp_path):
    from urdftool.lint.settings import CheckRequest
    from urdftool.lint.targets import OTHER_DOCUMENT, expand

    _xacro_test_harness(tmp_path)
    targets = expand([str(tmp_path)], CheckRequest())
    assert sorted(targets.files) == [str(tmp_path / name) for name in
                                     ("claims.urdf.xacro", "robot.urdf", "typo.xacro")]
    assert targets.skipped == {str(tmp_path / "harness.xacro"): OTHER_DOCUMENT}


def test_an_xml_document_of_another_kind_named_is_not_checked_as_a_robot(run_cli, tmp_path):
    _xacro_test_harness(tmp_path)
    result = run_cli("check", tmp_path / "harness.xacro", tmp_path / "typo.xacro",
                     "--format", "json")
    assert '"files": 1' in result.stdout and "another kind" in result.stderr
    assert result.stdout.count("U004") == 1 and "typo.xacro" in result.stdout


def test_a_urdf_holding_xacro_named_is_checked_through_the_robot_including_it(run_cli, tmp_path):
    """RealMan's rm_65_gazebo.urdf (its meshes '$(find rm_description)/meshes/...') is
    included by gazebo_65_description.urdf.xacro: the folder walk checks it there, but named
    alone, as pre-commit names it, it was a U007 error (a .urdf holding xacro) on a file only
    xacro reads. Nobody including it, it is still checked as it is, U007 and all."""
    _beside_a_robot(tmp_path, part_urdf=(
        f'<robot name="part" {XACRO_NS}><xacro:property name="n" value="b"/>'
        '<link name="${n}"/></robot>'), top_urdf_xacro=(
        f'<robot name="top" {XACRO_NS}><xacro:include filename="part.urdf"/></robot>'))
    result = run_cli("check", tmp_path / "part.urdf", "--format", "json")
    assert "U007" not in result.stdout and "top.urdf.xacro" in result.stderr, result.stderr
    (tmp_path / "top.urdf.xacro").unlink()
    result = run_cli("check", tmp_path / "part.urdf", "--format", "json")
    assert "U007" in result.stdout and '"files": 1' in result.stdout


def test_each_link_leading_outside_is_said_however_many_lead_to_one_file(run_cli, tmp_path):
    """Files are checked once by their real path (two names of one robot, a link within the
    repository: one check), but a link leading outside is itself the finding (U017, never
    followed): two committed links to ``/dev/zero`` and two to one file outside were one
    finding each pair, the second said only once the first was removed."""
    import json

    outside, repo = tmp_path / "outside", tmp_path / "repo"
    outside.mkdir()
    (outside / "secret.urdf").write_text('<robot name="s"><link name="a"/></robot>\n')
    (repo / ".git").mkdir(parents=True)
    (repo / "robots" / "sub").mkdir(parents=True)
    shutil.copy(CASES / "U021_misspelt_attribute.urdf", repo / "robots" / "real.urdf")
    (repo / "robots" / "alias.urdf").symlink_to("real.urdf")
    for folder in (repo / "robots", repo / "robots" / "sub"):
        (folder / "zero.urdf").symlink_to("/dev/zero")
        (folder / "secret.urdf").symlink_to(outside / "secret.urdf")
    result = run_cli("check", str(repo / "robots"), "--jobs", "1", "--timeout", "0",
                     "--max-memory", "0", "--no-cache", "-f", "json")
    said = sorted((Path(d["file"]).relative_to(repo / "robots").as_posix(), d["code"])
                  for d in json.loads(result.stdout)["diagnostics"])
    assert said == [("alias.urdf", "U021"), ("secret.urdf", "U017"), ("sub/secret.urdf", "U017"),
                    ("sub/zero.urdf", "U017"), ("zero.urdf", "U017")], said


@pytest.mark.parametrize("text", [b"", b"<link name='${n}'/>", b"$(find p)/a.stl", b"<xacro:if",
                                  b"cost: $5 {x} (y)", b"$", b"{$", b"($", b"xacro:if", b"<a/>"])
def test_uses_xacro_as_the_three_searches(text):
    """The "$" looked for first changes no answer of the three needles' searches."""
    from urdftool.lint.targets import _uses_xacro

    assert _uses_xacro(text) == any(use in text for use in (b"${", b"$(", b"<xacro:"))


@pytest.mark.parametrize("block", ["transmission", "ros2_control"])
def test_a_macro_library_including_a_block_fragment_is_a_library(run_cli, tmp_path, block):
    # fusion2urdf-ros2's NAME_macro.urdf.xacro (le0o0o0/URDF_exploring): a macro including
    # NAME.trans, whose <transmission> blocks name joints (<joint name="..."> inside the block, a
    # reference, no joint of the robot); nobody calls the macro, and the library was checked as
    # a robot: 'robot has no <link> elements' (U106)
    (tmp_path / ".git").mkdir()
    (tmp_path / "package.xml").write_text("<package format='3'><name>arm</name></package>")
    (tmp_path / "urdf").mkdir()
    (tmp_path / "urdf" / "arm.trans").write_text(
        f'<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro"><{block} name="t">'
        '<joint name="${prefix}j1"><hardwareInterface>hardware_interface/EffortJointInterface'
        f'</hardwareInterface></joint></{block}></robot>')
    library = tmp_path / "urdf" / "arm_macro.urdf.xacro"
    library.write_text('<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                       '<xacro:macro name="arm" params="prefix">'
                       '<xacro:include filename="$(find arm)/urdf/arm.trans"/>'
                       '<link name="${prefix}base_link"/></xacro:macro></robot>')
    walked = run_cli("check", tmp_path, "--format", "json")
    assert walked.exit_code == 2 and "defines only macros" in walked.stderr, walked.stdout
    named = run_cli("check", library, "--format", "json")
    assert '"files": 0' in named.stdout and "defines only macros" in named.stderr
