"""Companion discovery: which controller YAML, SRDF and spec files a robot is checked against."""

from __future__ import annotations

import math
import os
import textwrap

import pytest

from conftest import ROBOTS
from urdftool.description.companions import (companions, is_fake_controller_list, is_spec,
                                              looks_like_controllers)
from urdftool.description.documents import read_yaml
from urdftool.description.robot import CompanionPaths
from urdftool.lint.engine import CheckOptions, load_and_check
from urdftool.description.load import load

ROBOT = """<robot name="r">
  <link name="base_link"/><link name="head"/>
  <joint name="head_joint" type="revolute">
    <parent link="base_link"/><child link="head"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="5" velocity="1"/>
  </joint>
</robot>
"""
CONTROLLERS = "head_controller:\n  type: position_controllers/JointPositionController\n  joint: head_joint\n"
SPEC = "unit: rad\njoints:\n  head_joint: {servo_id: 1, lower: -1, upper: 1}\n"


def write(folder, files: dict):
    for name, text in files.items():
        path = folder / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text))
    return folder


@pytest.fixture(scope="module")
def example_robots():
    return {name: load_and_check(str(ROBOTS / name / f"{name}.urdf.xacro"), CheckOptions())
            for name in ("diffbot", "r2d2", "humanoid")}


@pytest.mark.parametrize("name", ["diffbot", "r2d2", "humanoid"])
def test_example_robots_check_clean_with_their_companions(example_robots, name):
    result = example_robots[name]
    assert result.findings == []


def test_example_robots_companions_are_found(example_robots):
    humanoid = companions(example_robots["humanoid"].robot)
    assert [f.path.name for f in humanoid.controllers] == ["controllers.yaml"]
    assert humanoid.srdf.path.name == "humanoid.srdf" and humanoid.spec.path.name == "joint_limits.yaml"
    r2d2 = companions(example_robots["r2d2"].robot)
    assert [f.path.name for f in r2d2.controllers] == ["head_controller.yaml"]
    assert r2d2.srdf is None and r2d2.spec is None
    assert companions(example_robots["diffbot"].robot).controllers == []


def test_companions_are_parsed_once_per_robot(tmp_path):
    write(tmp_path, {"r.urdf": ROBOT, "config/c.yaml": CONTROLLERS})
    robot = load(str(tmp_path / "r.urdf"))
    assert companions(robot) is companions(robot)


def test_a_controllers_file_named_again_is_read_and_checked_once(tmp_path):
    """One file named 3,000 times (``--controllers``, or ``controllers`` in a repository's
    settings), by several paths: each copy was checked against the others (U015 at 60 s);
    it is one file, in the order first named."""
    write(tmp_path, {"r.urdf": ROBOT, "config/c.yaml": CONTROLLERS, "other.yaml": CONTROLLERS})
    c, other = tmp_path / "config" / "c.yaml", tmp_path / "other.yaml"
    named = [c, other, tmp_path / "config" / ".." / "config" / "c.yaml"] * 1000
    os.symlink(c, tmp_path / "link.yaml")
    robot = load(str(tmp_path / "r.urdf"))
    robot.companion_paths = CompanionPaths([*named, tmp_path / "link.yaml"])
    assert [f.path for f in companions(robot).controllers] == [c, other]
    result = load_and_check(str(tmp_path / "r.urdf"), CheckOptions(
        companions=CompanionPaths(named)))
    assert not [f for f in result.findings if f.code == "U015"]


def test_yaml_keeps_the_line_of_every_key_and_item(tmp_path):
    path = write(tmp_path, {"c.yaml": """\
        # comment
        a:
          joints:
            - j1
            - j2
          flow: [x,
                 y]
        """}) / "c.yaml"
    data = read_yaml(path).data
    assert data.lines["a"] == 2 and data["a"].lines["joints"] == 3
    assert data["a"]["joints"].lines == [4, 5] and data["a"]["flow"].lines == [6, 7]


def test_malformed_yaml_is_located_where_the_bracket_opened(tmp_path):
    path = write(tmp_path, {"c.yaml": "a: 1\nb: [1, 2\nc: 3\n"}) / "c.yaml"
    parsed = read_yaml(path)
    assert parsed.data is None and parsed.problem and parsed.line == 2


def test_unknown_yaml_tags_load_as_plain_values(tmp_path):
    # ur_description/config/*/joint_limits.yaml uses rosparam's !degrees tag: read as rosparam
    # (and ROS 2 MoveIt's launch_param_builder) reads it, in radians; a tag nobody knows is text
    path = write(tmp_path, {"c.yaml": "joint_limits:\n  a: {max_position: !degrees 360, "
                                      "min_position: !foo -360}\n"}) / "c.yaml"
    limits = read_yaml(path).data["joint_limits"]["a"]
    assert limits["max_position"] == pytest.approx(2 * math.pi) and limits["min_position"] == "-360"


def test_ros_joint_limits_yaml_is_not_a_spec_nor_controllers(corpus):
    ros = read_yaml(corpus / "ur_description/config/ur5e/joint_limits.yaml")
    assert ros.problem is None and not is_spec(ros.data) and not looks_like_controllers(ros.data)
    assert is_spec(read_yaml(ROBOTS / "humanoid/joint_limits.yaml").data)


def test_ros_joint_limits_yaml_beside_the_robot_is_ignored(tmp_path):
    write(tmp_path, {"r.urdf": ROBOT, "joint_limits.yaml": "joint_limits:\n  head_joint: {has_position_limits: true}\n"})
    result = load_and_check(str(tmp_path / "r.urdf"), CheckOptions())
    assert companions(result.robot).spec is None and result.findings == []


def test_given_ros_joint_limits_yaml_as_spec_is_malformed(tmp_path):
    write(tmp_path, {"r.urdf": ROBOT, "x/limits.yaml": "joint_limits:\n  head_joint: {max_velocity: 1}\n"})
    result = load_and_check(str(tmp_path / "r.urdf"), CheckOptions(
        companions=CompanionPaths(spec=tmp_path / "x/limits.yaml")))
    assert [(f.code, f.line) for f in result.findings] == [("U701", 1)]
    assert "ROS joint_limits.yaml" in result.findings[0].message


def test_yaml_beside_the_robot_counts_only_when_it_looks_like_controllers(tmp_path):
    write(tmp_path, {"r.urdf": ROBOT, "c.yaml": CONTROLLERS, "other.yaml": "a: [1, 2\n",
                     "params.yaml": "mass: 3\n"})
    robot = load(str(tmp_path / "r.urdf"))
    assert [f.path.name for f in companions(robot).controllers] == ["c.yaml"]


def test_srdf_matching_the_robot_name_is_preferred(tmp_path):
    write(tmp_path, {"r.urdf": ROBOT, "a.srdf": "<robot name='a'/>", "config/r.srdf": "<robot name='r'/>"})
    assert companions(load(str(tmp_path / "r.urdf"))).srdf.path.name == "r.srdf"
    (tmp_path / "config/r.srdf").unlink()
    write(tmp_path, {"b.srdf": "<robot name='b'/>"})
    assert companions(load(str(tmp_path / "r.urdf"))).srdf is None  # two, neither matches


@pytest.mark.skipif(not hasattr(os, "symlink"), reason="needs symbolic links")
def test_links_leading_outside_the_robot_folder_are_not_followed(tmp_path):
    outside = write(tmp_path / "outside", {"c.yaml": CONTROLLERS, "r.srdf": "<robot name='r'/>",
                                           "joint_limits.yaml": SPEC})
    robot_dir = write(tmp_path / "robot", {"r.urdf": ROBOT})
    (robot_dir / "config").symlink_to(outside, target_is_directory=True)
    for name in ("c.yaml", "r.srdf", "joint_limits.yaml"):
        (robot_dir / name).symlink_to(outside / name)
    found = companions(load(str(robot_dir / "r.urdf")))
    assert found.controllers == [] and found.srdf is None and found.spec is None


def test_nothing_is_discovered_for_stdin(tmp_path, monkeypatch):
    write(tmp_path, {"config/c.yaml": CONTROLLERS, "joint_limits.yaml": SPEC})
    monkeypatch.chdir(tmp_path)
    from urdftool.description.robot import Robot
    from urdftool.description.packages import PackageResolver
    from lxml import etree

    robot = Robot("-", "-", etree.fromstring(ROBOT), {}, PackageResolver({}))
    found = companions(robot)
    assert found.controllers == [] and found.spec is None


def test_cli_options_pass_companions_and_locate_findings(run_cli, tmp_path):
    write(tmp_path, {"r.urdf": ROBOT, "elsewhere/c.yaml": CONTROLLERS.replace("head_joint", "head_jnt"),
                     "elsewhere/s.yaml": SPEC, "elsewhere/r.srdf": "<robot name='r'><group name='g'>"
                     "<joint name='head_joint'/></group></robot>"})
    other = tmp_path / "elsewhere"
    result = run_cli("check", tmp_path / "r.urdf", "--controllers", other / "c.yaml",
                     "--spec", other / "s.yaml", "--srdf", other / "r.srdf", "--format", "json",
                     "--strict")  # no launch file says the controller starts: a warning
    assert result.exit_code == 1, result.output
    assert '"U602"' in result.output and '"U605"' in result.output and "c.yaml" in result.output


def test_cli_missing_companion_is_a_usage_error(run_cli, tmp_path):
    write(tmp_path, {"r.urdf": ROBOT})
    result = run_cli("check", tmp_path / "r.urdf", "--srdf", tmp_path / "nope.srdf")
    assert result.exit_code == 2 and "nope.srdf" in result.output



def test_collisions_reads_the_srdf_as_check_does(tmp_path):
    """One SRDF reader (description.documents.read_srdf): the same lines, the same refusals."""
    from urdftool.collision import srdf
    from urdftool.description.documents import read_srdf

    path = tmp_path / "r.srdf"
    path.write_text('<robot name="r">\n<disable_collisions\n  link1="a" link2="b" reason="Never"/>\n'
                    "</robot>\n")
    entries, root = srdf.read(path)
    document = read_srdf(path)
    assert [(e.link1, e.location.line) for e in entries] == [("a", 2)] == \
        [(e.get("link1"), e.sourceline) for e in document.root.iter("disable_collisions")]
    assert root.line == 1
    path.write_text('<robot name="r">\n<group name="g">\n</robot>\n')
    with pytest.raises(srdf.SrdfError, match="r.srdf:3: not well-formed XML: Opening and ending tag "
                                             "mismatch: group line 2 and robot"):
        srdf.read(path)
    path.write_text('<robt name="r"/>\n')
    with pytest.raises(srdf.SrdfError, match=r"r.srdf:1: root element is <robt>, not <robot>"):
        srdf.read(path)


# --- where companions are found: ROS package layouts, shared folders, the URDF's own pointers ----

HEAD_YAML = ("controller_manager:\n  ros__parameters:\n    jsb: {type: joint_state_broadcaster/JointStateBroadcaster}\n"
             "    head: {type: position_controllers/JointGroupPositionController}\n"
             "head:\n  ros__parameters: {joints: [head_joint]}\n")


def test_ros_package_layout_and_sibling_moveit_package(tmp_path):
    (tmp_path / ".git").mkdir()
    write(tmp_path, {"r_description/package.xml": "<package/>", "r_description/urdf/r.urdf": ROBOT,
                     "r_description/config/c.yaml": HEAD_YAML,
                     "r_moveit_config/config/r.srdf": "<robot name='r'/>",
                     "r_moveit_config/config/kinematics.yaml": "head: {kinematics_solver: kdl}\n",
                     "r_moveit_config/config/joint_limits.yaml": "joint_limits:\n  head_joint: {max_velocity: 1}\n",
                     "r_moveit_config/config/moveit_controllers.yaml":
                         "controller_names: [head]\nhead: {type: FollowJointTrajectory, joints: [head_joint]}\n"})
    found = companions(load(str(tmp_path / "r_description/urdf/r.urdf")))
    assert sorted(f.path.name for f in found.controllers) == ["c.yaml", "moveit_controllers.yaml"]
    assert found.srdf.path.parent.parent.name == "r_moveit_config"
    assert found.kinematics.path.name == "kinematics.yaml"
    assert found.planning_limits.path.name == "joint_limits.yaml" and found.spec is None


def test_sibling_packages_outside_the_repository_are_not_searched(tmp_path):
    (tmp_path / "r_description/.git").mkdir(parents=True)
    write(tmp_path, {"r_description/urdf/r.urdf": ROBOT, "r_moveit_config/config/r.srdf": "<robot name='r'/>"})
    assert companions(load(str(tmp_path / "r_description/urdf/r.urdf"))).srdf is None


def test_a_folder_holding_two_robots_gives_each_only_its_own(tmp_path):
    other = ROBOT.replace('name="r"', 'name="b"').replace("head_joint", "neck_joint")
    write(tmp_path, {"r.urdf": ROBOT, "b.urdf": other,
                     "config/r_controllers.yaml": HEAD_YAML,
                     "config/b_controllers.yaml": HEAD_YAML.replace("head_joint", "neck_joint"),
                     "config/controllers.yaml": HEAD_YAML, "joint_limits.yaml": SPEC,
                     "one.srdf": "<robot name='r'/>", "two.srdf": "<robot name='b'/>"})
    mine = companions(load(str(tmp_path / "r.urdf")))
    assert [f.path.name for f in mine.controllers] == ["r_controllers.yaml"]
    assert mine.srdf.path.name == "one.srdf" and mine.spec is None
    theirs = companions(load(str(tmp_path / "b.urdf")))
    assert [f.path.name for f in theirs.controllers] == ["b_controllers.yaml"]
    assert theirs.srdf.path.name == "two.srdf"
    lines = mine.describe()
    assert "controllers: config/r_controllers.yaml (named after the robot)" in [
        line.replace(str(tmp_path) + "/", "") for line in lines]
    assert any(line.startswith("not used:") and "controllers.yaml (2 robots share its folder"
               in line for line in lines)
    # no finding from the neighbour's files
    assert load_and_check(str(tmp_path / "r.urdf"), CheckOptions()).findings == []


def test_gazebo_ros2_control_parameters_are_followed_inside_the_repository(tmp_path):
    (tmp_path / ".git").mkdir()
    plugin = ('<gazebo><plugin filename="libgazebo_ros2_control.so" name="gazebo_ros2_control">'
              "<parameters>{}</parameters></plugin></gazebo>\n</robot>")
    write(tmp_path, {"pkg/urdf/r.urdf": ROBOT.replace("</robot>", plugin.format("params/head.yaml")),
                     "pkg/package.xml": "<package/>", "pkg/params/head.yaml": HEAD_YAML})
    found = companions(load(str(tmp_path / "pkg/urdf/r.urdf")))
    assert [f.path.name for f in found.controllers] == ["head.yaml"]
    assert found.used[found.controllers[0].path] == "named by the URDF's <parameters>"
    outside = tmp_path.parent / f"{tmp_path.name}_outside.yaml"
    outside.write_text(HEAD_YAML)
    write(tmp_path, {"pkg/urdf/r.urdf": ROBOT.replace("</robot>", plugin.format(outside))})
    assert companions(load(str(tmp_path / "pkg/urdf/r.urdf"))).controllers == []
    outside.unlink()


def test_a_yaml_another_robots_gazebo_plugin_names_is_not_this_robots(tmp_path):
    """RB2023ROS/gz_ros2_examples' basic_stick/urdf holds four robots written as plain .xacro
    (each alone in its folder to the walk); config/joint_controller.yaml is the <parameters> of
    the gazebo_ros2_control plugin that ros2_control.gazebo.xacro gives, which only
    moving_stick.xacro includes: its three neighbours were checked against it (a false U602 on
    each). A robot that reads the part naming it keeps it."""
    (tmp_path / ".git").mkdir()
    plugin = ('<robot><gazebo><plugin filename="libgazebo_ros2_control.so" name="g">'
              "<parameters>$(find pkg)/config/joint_controller.yaml</parameters></plugin>"
              "</gazebo></robot>")
    include = '<xacro:include filename="control.gazebo.xacro"/>\n</robot>'
    write(tmp_path, {"pkg/package.xml": "<package/>", "pkg/urdf/stick.xacro": ROBOT,
                     "pkg/urdf/control.gazebo.xacro": plugin,
                     "pkg/config/joint_controller.yaml": HEAD_YAML})
    found = companions(load(str(tmp_path / "pkg/urdf/stick.xacro")))
    assert found.controllers == []
    assert "control.gazebo.xacro" in found.unused[tmp_path / "pkg/config/joint_controller.yaml"]
    write(tmp_path, {"pkg/urdf/stick.xacro": ROBOT.replace(
        '<robot name="r">', '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">')
        .replace("</robot>", include)})
    mine = companions(load(str(tmp_path / "pkg/urdf/stick.xacro")))
    assert [f.path.name for f in mine.controllers] == ["joint_controller.yaml"]


def test_an_srdf_named_after_a_neighbour_is_not_claimed_by_robot_name(tmp_path):
    """Dexmate ships vega_1.urdf, vega_1.srdf and vega_1_collision_spheres.collision.urdf, all
    with <robot name="vega_1">: the SRDF is vega_1.urdf's, not the spheres model's (whose
    spheres overlap where the meshes do not: false U810 on the sweep)."""
    write(tmp_path, {"vega_1.urdf": ROBOT, "vega_1_spheres.urdf": ROBOT,
                     "vega_1.srdf": "<robot name='r'/>"})
    assert companions(load(str(tmp_path / "vega_1.urdf"))).srdf.path.name == "vega_1.srdf"
    assert companions(load(str(tmp_path / "vega_1_spheres.urdf"))).srdf is None


def test_a_robot_and_its_committed_xacro_output_are_one_robot(tmp_path):
    """moveit_resources' panda_description/urdf holds panda.urdf.xacro and xacro's output
    panda.urdf: the same robot in two forms, not two robots sharing a folder. panda.urdf lost
    panda_moveit_config's panda.srdf ('collisions' then called the SRDF's allowed pairs
    colliding) and its controllers; a robot of another stem still keeps its own."""
    (tmp_path / ".git").mkdir()
    write(tmp_path, {"panda_description/package.xml": "<package/>",
                     "panda_description/urdf/panda.urdf": ROBOT,
                     "panda_description/urdf/panda.urdf.xacro": ROBOT,
                     "panda_moveit_config/config/panda.srdf": "<robot name='r'/>",
                     "panda_description/config/controllers.yaml": HEAD_YAML})
    for name in ("panda.urdf", "panda.urdf.xacro"):
        found = companions(load(str(tmp_path / "panda_description/urdf" / name)))
        assert found.srdf is not None and found.srdf.path.name == "panda.srdf", name
        assert [f.path.name for f in found.controllers] == ["controllers.yaml"], name
    write(tmp_path, {"panda_description/urdf/fr3.urdf": ROBOT})
    found = companions(load(str(tmp_path / "panda_description/urdf/panda.urdf")))
    assert found.srdf.path.name == "panda.srdf" and found.controllers == []


def test_a_moveit_package_whose_srdf_is_another_robots_lends_this_one_nothing(tmp_path):
    """deepwithin/yam_ros2_control: the MoveIt package of the arm named 'i2rt_arm' gave the
    repository's other arm, alone in its folder, its controllers and kinematics ("found beside
    the robot"), and their gripper joint was reported missing there. Its SRDF names its robot;
    the package's files are that robot's."""
    (tmp_path / ".git").mkdir()
    arm = '<robot name="{}"><link name="base_link"/><link name="l1"/><joint name="j1" ' \
          'type="revolute"><parent link="base_link"/><child link="l1"/><axis xyz="0 0 1"/>' \
          '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>\n'
    files = {"arm_description/urdf/arm.urdf": arm.format("arm"),
             "arm_description/other/output.urdf": arm.format("output"),
             "arm_moveit_config/config/arm.srdf": '<robot name="arm"><group name="g">'
                                                   '<joint name="j1"/></group></robot>\n',
             "arm_moveit_config/config/kinematics.yaml": "g:\n  kinematics_solver: kdl\n",
             "arm_moveit_config/config/moveit_controllers.yaml":
                 "moveit_simple_controller_manager:\n  controller_names: [c]\n  c:\n"
                 "    type: FollowJointTrajectory\n    joints: [j1, gripper_joint]\n"}
    for name, text in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    (tmp_path / "arm_description" / "package.xml").write_text(
        "<package format='2'><name>arm_description</name></package>")
    mine = companions(load(tmp_path / "arm_description/urdf/arm.urdf"))
    assert mine.srdf is not None and mine.kinematics is not None
    other = companions(load(tmp_path / "arm_description/other/output.urdf"))
    assert other.srdf is None and other.kinematics is None and not other.controllers
    assert any("the robot its SRDF names" in why for why in other.unused.values()), other.unused


def test_a_moveit_package_keeping_its_srdf_xacro_in_srdf_lends_another_robot_nothing(tmp_path):
    """PAL's TIAGo Pro (MAK-RPTU/Tiago_pro): pal_sea_arm_moveit_config keeps its SRDF as
    config/srdf/pal_sea_arm.srdf.xacro, and the force-torque sensor's tiago_ft.urdf in
    pal_sea_arm_description (alone in its folder) took the package's joint_limits.yaml and had
    the seven arm joints reported missing from it. The package's SRDF, .srdf or .srdf.xacro,
    in config/ or config/srdf/, names the robot its files are for."""
    (tmp_path / ".git").mkdir()
    robot = '<robot name="{}"><link name="base_link"/><link name="l1"/><joint name="{}" ' \
            'type="revolute"><parent link="base_link"/><child link="l1"/><axis xyz="0 0 1"/>' \
            '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>\n'
    files = {"arm_description/robots/arm.urdf": robot.format("arm", "arm_1_joint"),
             "arm_description/urdf/sensors/ft.urdf": robot.format("ft", "ft_joint"),
             "arm_description/package.xml": "<package format='2'><name>arm_description</name>"
                                            "</package>",
             "arm_moveit_config/config/srdf/arm.srdf.xacro":
                 '<robot name="arm" xmlns:xacro="http://ros.org/wiki/xacro"><group name="g">'
                 '<joint name="arm_1_joint"/></group></robot>\n',
             "arm_moveit_config/config/joint_limits.yaml":
                 "joint_limits:\n  arm_1_joint:\n    has_velocity_limits: true\n"
                 "    max_velocity: 1.0\n"}
    write(tmp_path, files)
    mine = companions(load(tmp_path / "arm_description/robots/arm.urdf"))
    assert mine.planning_limits is not None
    other = companions(load(tmp_path / "arm_description/urdf/sensors/ft.urdf"))
    assert other.planning_limits is None and other.kinematics is None
    assert any("the robot its SRDF names" in why for why in other.unused.values()), other.unused


def test_a_moveit_package_s_yaml_is_the_srdf_its_setup_assistant_names(tmp_path):
    """Devonics' fairino5_v6_moveit2_config holds two Setup Assistant runs' robots and SRDFs
    (fairino5_v6_robot, fairino_with_ag95) and one kinematics.yaml, written for the SRDF its
    .setup_assistant names (MoveItConfigsBuilder loads that SRDF whatever robot it is given):
    checked against the other SRDF, both its groups were U813 errors."""
    (tmp_path / ".git").mkdir()
    srdf = "<robot name='{}'><group name='{}'><joint name='head_joint'/></group></robot>\n"
    config = tmp_path / "r_moveit_config" / "config"
    write(tmp_path, {"r_moveit_config/package.xml": "<package><buildtool_depend>ament_cmake"
                                                    "</buildtool_depend></package>",
                     "r_moveit_config/.setup_assistant":
                         "moveit_setup_assistant_config:\n  srdf:\n    relative_path: config/new.srdf\n",
                     "r_moveit_config/config/old.urdf": ROBOT.replace('name="r"', 'name="old"'),
                     "r_moveit_config/config/new.urdf": ROBOT.replace('name="r"', 'name="new"'),
                     "r_moveit_config/config/old.srdf": srdf.format("old", "old_group"),
                     "r_moveit_config/config/new.srdf": srdf.format("new", "arm"),
                     "r_moveit_config/config/kinematics.yaml":
                         "arm:\n  kinematics_solver: kdl_kinematics_plugin/KDLKinematicsPlugin\n"})
    new = companions(load(str(config / "new.urdf")))
    assert new.srdf.path.name == "new.srdf" and new.kinematics is not None
    old = companions(load(str(config / "old.urdf")))
    assert old.srdf.path.name == "old.srdf" and old.kinematics is None
    assert "its package's .setup_assistant writes it for" in old.unused[config / "kinematics.yaml"]
    assert [f.code for f in load_and_check(str(config / "old.urdf"), CheckOptions()).findings
            if f.code == "U813"] == []
    # an SRDF a launch file or --srdf gives MoveIt is what MoveIt pairs the YAML with
    named = load(str(config / "old.urdf"))
    named.companion_paths = CompanionPaths(srdf=str(config / "old.srdf"))
    assert companions(named).kinematics is not None
    # ROS 1's MoveIt never reads .setup_assistant: its launch files pair the SRDF and the YAML
    # (turtlebot_arm's pincher_arm.srdf with the package's one joint_limits.yaml)
    write(tmp_path, {"r_moveit_config/package.xml": "<package><buildtool_depend>catkin"
                                                    "</buildtool_depend></package>"})
    assert companions(load(str(config / "old.urdf"))).kinematics is not None


def test_a_fake_controller_list_is_known_by_its_entries_beside_settings_of_no_controller():
    fake = {"controller_list": [{"name": "arm", "type": "interpolate", "joints": ["j1"]}]}
    assert is_fake_controller_list(fake)
    assert is_fake_controller_list({**fake, "initial": [{"group": "arm", "pose": "home"}],
                                    "moveit_sim_hw_interface": {"joint_model_group": "arm"}})
    # a controller of ros_control beside it, or the simple controller manager named: not fake
    assert not is_fake_controller_list(
        {**fake, "jsc": {"type": "joint_state_controller/JointStateController"}})
    assert not is_fake_controller_list(
        {**fake, "moveit_controller_manager":
         "moveit_simple_controller_manager/MoveItSimpleControllerManager"})
    assert not is_fake_controller_list(
        {"controller_list": [{"name": "arm", "action_ns": "follow_joint_trajectory",
                              "type": "FollowJointTrajectory", "joints": ["j1"]}]})
