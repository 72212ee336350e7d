"""What runs with a robot (description/runtime.py): how a robot file is built when a launch
argument names the package holding it, in each form a launch file writes that, and what the
build then tells the rules (docs/launch.md)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from urdftool.description.launch_configs import launch_index
from urdftool.description.load import load
from urdftool.description.runtime import AS_CHECKED, builds, built_otherwise, runtime
from urdftool.lint.engine import CheckOptions, load_and_check

PACKAGE = "<package format='2'><name>{}</name></package>"
ROBOT = """<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base"/><link name="tool"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="tool"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""
BY_DEFAULT = "when launched with description_package's default 'arm_description'"


def _repo(root: Path, files: dict[str, str]) -> Path:
    (root / ".git").mkdir(parents=True, exist_ok=True)
    files = {"arm_description/package.xml": PACKAGE.format("arm_description"),
             "arm_description/urdf/arm.urdf.xacro": ROBOT,
             "arm_bringup/package.xml": PACKAGE.format("arm_bringup"), **files}
    for name, text in files.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text)
    return root


# each form of "the package a launch argument names", building arm_description's arm
PYTHON_SUBSTITUTION = '''
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, FindExecutable, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare

def generate_launch_description():
    description_package = LaunchConfiguration("description_package")
    description = Command([FindExecutable(name="xacro"), " ",
                           PathJoinSubstitution([FindPackageShare(description_package), "urdf", "arm.urdf.xacro"]),
                           " prefix:=", LaunchConfiguration("prefix")])
    return LaunchDescription([
        DeclareLaunchArgument("description_package", default_value="arm_description"),
        DeclareLaunchArgument("prefix", default_value=""),
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": description}]),
        Node(package="controller_manager", executable="spawner", arguments=["arm_controller"]),
    ])
'''
PYTHON_OPAQUE = '''
import os
import xacro
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, OpaqueFunction
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

def launch_setup(context, *args, **kwargs):
    package = LaunchConfiguration("description_package").perform(context)
    path = os.path.join(get_package_share_directory(package), "urdf", "arm.urdf.xacro")
    description = xacro.process_file(path, mappings={"prefix": ""}).toxml()
    return [Node(package="robot_state_publisher", executable="robot_state_publisher",
                 parameters=[{"robot_description": description}])]

def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument("description_package", default_value="arm_description"),
        OpaqueFunction(function=launch_setup),
    ])
'''
ROS1 = """<launch>
  <arg name="description_package" default="arm_description"/>
  <param name="robot_description" command="$(find xacro)/xacro $(find $(arg description_package))/urdf/arm.urdf.xacro prefix:=''"/>
</launch>"""
ROS2_XML = """<launch>
  <arg name="description_package" default="arm_description"/>
  <node pkg="robot_state_publisher" exec="robot_state_publisher">
    <param name="robot_description" value="$(command 'xacro $(find-pkg-share $(var description_package))/urdf/arm.urdf.xacro prefix:=')"/>
  </node>
</launch>"""
FORMS = {"python_substitution": ("arm.launch.py", PYTHON_SUBSTITUTION),
         "python_opaque_function": ("arm.launch.py", PYTHON_OPAQUE),
         "ros1_xml": ("arm.launch", ROS1), "ros2_xml": ("arm.launch.xml", ROS2_XML)}


@pytest.mark.parametrize("form", FORMS)
def test_a_package_a_launch_argument_names_is_its_default_and_the_build_holds_for_it_only(
        tmp_path, form):
    name, text = FORMS[form]
    root = _repo(tmp_path, {f"arm_bringup/launch/{name}": text})
    robot_file = root / "arm_description/urdf/arm.urdf.xacro"
    [build] = builds(str(robot_file))
    assert build.xacro and build.args == {"prefix": ""}
    # built for the default only: never a certain build (U005 is then a warning)
    assert build.chosen and not build.certain and build.condition == BY_DEFAULT
    robot = load_and_check(str(robot_file), CheckOptions()).robot
    [(_, relation)] = [c for c in runtime(robot).configurations if c[1]]
    assert relation == f"{AS_CHECKED} {BY_DEFAULT}"


def test_what_it_starts_is_conditional_on_that_default(tmp_path):
    root = _repo(tmp_path, {"arm_bringup/launch/arm.launch.py": PYTHON_SUBSTITUTION})
    robot = load_and_check(str(root / "arm_description/urdf/arm.urdf.xacro"), CheckOptions()).robot
    [spawn] = runtime(robot).spawns
    assert spawn.name == "arm_controller" and not spawn.certain
    assert spawn.condition == f"against the robot {AS_CHECKED} {BY_DEFAULT}"


def test_a_package_an_including_launch_file_names_is_certain(tmp_path):
    # the including file gives the value: no launch argument is left to choose the package
    root = _repo(tmp_path, {
        "arm_bringup/launch/arm.launch": ROS1.replace('default="arm_description"', ""),
        "arm_bringup/launch/bringup.launch": """<launch>
  <include file="$(find arm_bringup)/launch/arm.launch">
    <arg name="description_package" value="arm_description"/>
  </include>
</launch>"""})
    [build] = builds(str(root / "arm_description/urdf/arm.urdf.xacro"))
    assert build.launch.endswith("bringup.launch") and build.certain


def test_an_including_launch_files_own_argument_is_the_condition(tmp_path):
    root = _repo(tmp_path, {
        "arm_bringup/launch/arm.launch": ROS1.replace('default="arm_description"', ""),
        "arm_bringup/launch/bringup.launch": """<launch>
  <arg name="robot_package" default="arm_description"/>
  <include file="$(find arm_bringup)/launch/arm.launch">
    <arg name="description_package" value="$(arg robot_package)"/>
  </include>
</launch>"""})
    [build] = builds(str(root / "arm_description/urdf/arm.urdf.xacro"))
    assert build.condition == "when launched with robot_package's default 'arm_description'"


def test_what_an_include_from_a_package_so_named_builds_holds_for_the_default_too(tmp_path):
    # Kassow: <include file="$(find-pkg-share $(var configuration_package))/launch/...">
    root = _repo(tmp_path, {
        "arm_bringup/launch/arm.launch": ROS1.replace("$(arg description_package)", "arm_description"),
        "arm_bringup/launch/bringup.launch": """<launch>
  <arg name="bringup_package" default="arm_bringup"/>
  <include file="$(find $(arg bringup_package))/launch/arm.launch"/>
</launch>"""})
    robot_file = root / "arm_description/urdf/arm.urdf.xacro"
    by_default = "when launched with bringup_package's default 'arm_bringup'"
    [build] = builds(str(robot_file))
    assert build.launch.endswith("bringup.launch") and not build.certain
    assert build.condition == by_default
    robot = load_and_check(str(robot_file), CheckOptions()).robot
    assert [r for _, r in runtime(robot).configurations if r] == [f"{AS_CHECKED} {by_default}"]


def test_both_conditions_are_said_once_when_the_include_and_the_file_are_so_named(tmp_path):
    # Kassow's dual-arm bringup includes $(find-pkg-share $(var configuration_package))/launch/
    # ...description.launch.xml, which builds $(find-pkg-share $(var description_package))/urdf/...
    root = _repo(tmp_path, {
        "arm_bringup/launch/arm.launch.xml": ROS2_XML,
        "arm_bringup/launch/bringup.launch.xml": """<launch>
  <arg name="bringup_package" default="arm_bringup"/>
  <include file="$(find-pkg-share $(var bringup_package))/launch/arm.launch.xml"/>
</launch>"""})
    [build] = builds(str(root / "arm_description/urdf/arm.urdf.xacro"))
    assert build.condition == ("when launched with bringup_package's default 'arm_bringup' and "
                               "description_package's default 'arm_description'")


def test_a_package_named_in_part_by_an_argument(tmp_path):
    # Rokae: f"rokae_xMate{robot_type}_moveit_config"; KUKA: f"kuka_{robot_family}_support"
    text = PYTHON_OPAQUE.replace('LaunchConfiguration("description_package").perform(context)',
                                 'f"arm_{LaunchConfiguration(\'kind\').perform(context)}"').replace(
        'DeclareLaunchArgument("description_package", default_value="arm_description")',
        'DeclareLaunchArgument("kind", default_value="description")')
    root = _repo(tmp_path, {"arm_bringup/launch/arm.launch.py": text})
    [build] = builds(str(root / "arm_description/urdf/arm.urdf.xacro"))
    assert build.condition == "when launched with the default of kind (package 'arm_description')"


def test_a_default_naming_no_package_of_the_repository_builds_nothing(tmp_path):
    root = _repo(tmp_path, {"arm_bringup/launch/arm.launch": ROS1.replace(
        'default="arm_description"', 'default="ur_description"')})
    assert builds(str(root / "arm_description/urdf/arm.urdf.xacro")) == []
    [configuration] = launch_index(root).configurations
    [described] = configuration.described
    assert described.path is None and described.by_default == ""


def test_a_package_given_at_launch_only_builds_nothing(tmp_path):
    # no default: the package is known only at launch
    root = _repo(tmp_path, {"arm_bringup/launch/arm.launch": ROS1.replace(
        ' default="arm_description"', "")})
    assert builds(str(root / "arm_description/urdf/arm.urdf.xacro")) == []


def test_a_build_from_a_package_so_named_comes_after_those_naming_theirs(tmp_path):
    # ros2_kortex: kortex_bringup's launch files name the package by an argument, and
    # kortex_description's view_robot.launch.py names it: a robot needing a xacro argument is
    # checked as the latter builds it, whatever the order the launch files are read in
    root = _repo(tmp_path, {
        "arm_bringup/launch/a_by_default.launch": ROS1,
        "arm_bringup/launch/z_named.launch": ROS1.replace("$(arg description_package)",
                                                          "arm_description")})
    assert [Path(b.launch).name for b in builds(str(root / "arm_description/urdf/arm.urdf.xacro"))] \
        == ["z_named.launch", "a_by_default.launch"]


def test_an_srdf_from_a_package_so_named_is_moveits_for_the_default_only(tmp_path):
    from urdftool.description.runtime import moveit_with

    root = _repo(tmp_path, {
        "arm_moveit_config/package.xml": PACKAGE.format("arm_moveit_config"),
        "arm_moveit_config/config/arm.srdf": "<robot name='arm'/>",
        "arm_bringup/launch/moveit.launch": """<launch>
  <arg name="moveit_config_package" default="arm_moveit_config"/>
  <param name="robot_description" command="$(find xacro)/xacro $(find arm_description)/urdf/arm.urdf.xacro"/>
  <param name="robot_description_semantic" textfile="$(find $(arg moveit_config_package))/config/arm.srdf"/>
</launch>"""})
    robot = load_and_check(str(root / "arm_description/urdf/arm.urdf.xacro"), CheckOptions()).robot
    state, why = moveit_with(robot, root / "arm_moveit_config/config/arm.srdf")
    assert state == "by default"
    assert why.endswith("gives MoveIt this SRDF with the robot as checked when launched with "
                        "moveit_config_package's default 'arm_moveit_config'")


def test_the_launch_file_said_to_give_moveit_its_files_is_one_running_the_robot(tmp_path):
    """hans-robot's elfin5_l: run_benchmark_ompl.launch (MoveIt Setup Assistant's, starting
    moveit_ros_benchmarks) was named as how MoveIt runs with the robot. A launch file that
    starts the robot or move_group is named first; when only a tool's gives MoveIt both, the
    message says what it starts."""
    from urdftool.description.runtime import moveit_with

    context = """<launch>
  <param name="robot_description" command="$(find xacro)/xacro $(find arm_description)/urdf/arm.urdf.xacro"/>
  <param name="robot_description_semantic" textfile="$(find arm_moveit_config)/config/arm.srdf"/>
</launch>"""
    benchmark = """<launch>
  <include file="$(find arm_moveit_config)/launch/planning_context.launch"/>
  <node name="b" pkg="moveit_ros_benchmarks" type="moveit_run_benchmark"/>
</launch>"""
    demo = """<launch>
  <include file="$(find arm_moveit_config)/launch/planning_context.launch"/>
  <node name="robot_state_publisher" pkg="robot_state_publisher" type="robot_state_publisher"/>
  <node name="move_group" pkg="moveit_ros_move_group" type="move_group"/>
</launch>"""
    files = {"arm_moveit_config/package.xml": PACKAGE.format("arm_moveit_config"),
             "arm_moveit_config/config/arm.srdf": "<robot name='arm'/>",
             "arm_moveit_config/launch/planning_context.launch": context,
             "arm_moveit_config/launch/a_benchmark.launch": benchmark}
    root = _repo(tmp_path / "tool", files)
    robot = load_and_check(str(root / "arm_description/urdf/arm.urdf.xacro"), CheckOptions()).robot
    state, why = moveit_with(robot, root / "arm_moveit_config/config/arm.srdf")
    assert state == "certain"
    assert why.startswith("launch file ") and why.endswith(
        "arm_moveit_config/launch/a_benchmark.launch (which starts moveit_ros_benchmarks, not "
        "the robot nor move_group) gives MoveIt this SRDF with the robot as checked"), why
    root = _repo(tmp_path / "demo", {**files, "arm_moveit_config/launch/demo.launch": demo})
    robot = load_and_check(str(root / "arm_description/urdf/arm.urdf.xacro"), CheckOptions()).robot
    state, why = moveit_with(robot, root / "arm_moveit_config/config/arm.srdf")
    assert state == "certain" and why.endswith(
        "arm_moveit_config/launch/demo.launch gives MoveIt this SRDF with the robot as checked"), why


AMENT = ("<package format='3'><name>{}</name><buildtool_depend>ament_cmake</buildtool_depend>"
          "</package>")
GRIPPER_ROBOT = """<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="gripper" default=""/><link name="base"/>
</robot>"""


@pytest.mark.parametrize("robot_file, given, expected", [
    # the URDF the .setup_assistant names, built with the arguments it gives: as before
    ("arm_description/urdf/arm.urdf.xacro", {"gripper": "two_finger"}, ("unknown", "")),
    # built with the gripper's default: MoveItConfigsBuilder builds it with the gripper
    ("arm_description/urdf/arm.urdf.xacro", {}, (
        "conditional", "arm_moveit_config/.setup_assistant writes this SRDF for the robot built "
        "with gripper:=two_finger, as MoveItConfigsBuilder builds it")),
    # the Setup Assistant's config/arm.urdf.xacro, which MoveItConfigsBuilder prefers: likewise
    ("arm_moveit_config/config/arm.urdf.xacro", {}, (
        "conditional", "arm_moveit_config/.setup_assistant writes this SRDF for the robot built "
        "with gripper:=two_finger, as MoveItConfigsBuilder builds it")),
    # another robot file of the package, named like the robot: not MoveIt's
    ("arm_description/assets/arm.links.xacro", {}, (
        "conditional", "arm_moveit_config/.setup_assistant writes this SRDF for "
        "arm_description/urdf/arm.urdf.xacro, another robot file, which MoveItConfigsBuilder "
        "loads")),
])
def test_the_setup_assistant_says_which_robot_moveit_runs_an_srdf_with(
        tmp_path, monkeypatch, robot_file, given, expected):
    """A ROS 2 MoveIt package no launch file read gives MoveIt: its .setup_assistant says what
    MoveItConfigsBuilder builds (Kinova's link6_moveit_config: link6.urdf.xacro with
    gripper:=robotiq_2f_85; 23 U803 errors on the gripper's default and on assets/)."""
    from urdftool.description.runtime import moveit_with

    root = _repo(tmp_path, {
        "arm_description/package.xml": AMENT.format("arm_description"),
        "arm_description/urdf/arm.urdf.xacro": GRIPPER_ROBOT,
        "arm_description/assets/arm.links.xacro": GRIPPER_ROBOT,
        "arm_moveit_config/package.xml": AMENT.format("arm_moveit_config"),
        "arm_moveit_config/.setup_assistant": """moveit_setup_assistant_config:
  urdf:
    package: arm_description
    relative_path: urdf/arm.urdf.xacro
    xacro_args: gripper:=two_finger
  srdf:
    relative_path: config/arm.srdf
""",
        "arm_moveit_config/config/arm.srdf": "<robot name='arm'/>",
        "arm_moveit_config/config/arm.urdf.xacro": """<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find arm_description)/urdf/arm.urdf.xacro"/></robot>"""})
    monkeypatch.chdir(root)
    robot = load_and_check(str(root / robot_file), CheckOptions(xacro_args=given)).robot
    assert moveit_with(robot, root / "arm_moveit_config/config/arm.srdf") == expected


MODE_ROBOT = """<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="mode" default="true"/><xacro:arg name="prefix" default=""/>
  <link name="base"/>
  <ros2_control name="arm" type="system"><hardware>
    <xacro:if value="${'$(arg mode)' == 'mock'}"><plugin>mock_components/GenericSystem</plugin></xacro:if>
  </hardware></ros2_control>
</robot>"""
MODE_LAUNCH = '''
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare
from launch.substitutions import Command, PathJoinSubstitution

def generate_launch_description():
    return [Node(package="robot_state_publisher", executable="robot_state_publisher",
                 parameters=[{"robot_description": Command(["xacro ",
                     PathJoinSubstitution([FindPackageShare("arm_description"), "urdf", "arm.urdf.xacro"]),
                     " mode:={mode} prefix:="])}])]
'''


@pytest.mark.parametrize("modes, otherwise", [
    (["mock"], [["mode:=mock"]]),  # every launch file builds it otherwise
    (["mock", "true"], []),  # one builds it as checked
    ([], []),  # none builds it
])
def test_builds_all_giving_other_xacro_arguments_are_the_robot_built_otherwise(
        tmp_path, modes, otherwise):
    files = {"arm_description/urdf/arm.urdf.xacro": MODE_ROBOT}
    for index, mode in enumerate(modes):
        files[f"arm_bringup/launch/l{index}.launch.py"] = MODE_LAUNCH.replace("{mode}", mode)
    root = _repo(tmp_path, files)
    found = built_otherwise(load(str(root / "arm_description/urdf/arm.urdf.xacro")))
    assert [other for _, other in found] == otherwise


DUAL = """<robot name="dual" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="prefix_1" default=""/><xacro:arg name="prefix_2" default=""/>
  <xacro:arg name="side" default=""/>
  <link name="base"/>
  <link name="$(arg prefix_1)_tool"/><link name="$(arg prefix_2)_tool"/>
  <xacro:if value="${'$(arg side)' != ''}"><link name="extra"/></xacro:if>
</robot>"""


def test_placeholder_clashes_names_the_arguments_that_name_the_clashing_elements_apart(tmp_path):
    from urdftool.description.runtime import placeholder_clashes

    path = tmp_path / "dual.urdf.xacro"
    path.write_text(DUAL)
    robot = load_and_check(str(path), CheckOptions()).robot
    clash = placeholder_clashes(robot)
    # `side` changed the elements (an `xacro:if`), so the two builds are compared as wholes,
    # and it names nothing that clashed: only the two prefixes are said
    assert clash is not None and clash.args == ("prefix_1", "prefix_2")
    assert clash.links == {"_tool"} and not clash.joints


def test_placeholder_clashes_knows_nothing_of_a_build_that_fails_or_was_not_made_by_the_engine(tmp_path):
    from urdftool.description.runtime import placeholder_clashes
    from urdftool.errors import LoadError

    path = tmp_path / "dual.urdf.xacro"
    path.write_text(DUAL)
    robot = load(path)
    assert robot.rebuild is None and placeholder_clashes(robot) is None
    robot = load(path)

    def fails(args):
        raise LoadError("xacro", "fails", None)

    robot.rebuild = fails
    assert placeholder_clashes(robot) is None


def test_a_file_a_launch_argument_chooses_through_a_parent_folder_is_built_by_it(tmp_path):
    # aist_robotiq's gazebo.launch: xacro '$(dirname)/../urdf/$(arg device)_gripper.urdf'; the
    # file another value chooses (robotiq_140_gripper.urdf) is built by it as the default's is
    root = _repo(tmp_path, {
        "arm_description/urdf/a_gripper.urdf.xacro": ROBOT,
        "arm_description/urdf/b_gripper.urdf.xacro": ROBOT,
        "arm_description/launch/show.launch": """<launch>
  <arg name="device" default="a"/>
  <param name="robot_description"
         command="$(find xacro)/xacro '$(dirname)/../urdf/$(arg device)_gripper.urdf.xacro'"/>
</launch>"""})
    for name in ("a", "b"):
        [build] = builds(str(root / f"arm_description/urdf/{name}_gripper.urdf.xacro"))
        assert build.xacro and build.launch.endswith("show.launch") and build.chosen


def test_moveits_facts_about_a_file_are_found_once_per_robot(monkeypatch):
    """moveit_action_remaps, moveit_execution and moveit_with are asked by several rules for
    the same file (U817 and U818 for each entry of the controller list; moveit_with by each
    of 19 rules on MoveIt's files): each is computed once per robot and file, the same value
    given again (before, each question walked the launch files' configurations again)."""
    from urdftool.description import runtime as module
    from urdftool.description.companions import companions

    case = Path(__file__).parent.parent / "cases" / "U818_moveit_action_remapped_in_launch"
    robot = load(case / "arm.urdf")
    listing = case / "config" / "moveit_controllers.yaml"
    remaps = module.moveit_action_remaps(robot, listing, "/follow_joint_trajectory")
    assert [r.controller for r in remaps] == ["arm_traj_controller"]
    assert module.moveit_action_remaps(robot, listing, "/follow_joint_trajectory") is remaps
    assert module.moveit_execution(robot, listing) is module.moveit_execution(robot, listing)
    srdf = companions(robot).srdf
    if srdf is not None:
        assert module.moveit_with(robot, srdf.path) is module.moveit_with(robot, srdf.path)
    computed = []
    real = module._moveit_action_remaps
    monkeypatch.setattr(module, "_moveit_action_remaps",
                        lambda *args: computed.append(args[1:]) or real(*args))
    result = load_and_check(str(case / "arm.urdf"), CheckOptions())
    assert sorted(f.code for f in result.findings if f.code in ("U817", "U818")) == \
        ["U817", "U818"]
    assert len(computed) == len(set(computed)) == 2  # (both entries, each once)


def test_a_robot_file_named_with_bytes_that_are_not_utf8_is_looked_for_by_its_bytes(tmp_path):
    # a file system name is bytes: os.fsdecode gives U+DCFF for 0xff, which the strict codec
    # cannot write back (every check of such a robot was U900 from U620 before)
    from urdftool.description.runtime import unread_naming

    (tmp_path / ".git").mkdir()
    robot = Path(os.fsdecode(bytes(tmp_path / "r") + b"\xff.urdf"))
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    (tmp_path / "launch").mkdir()
    (tmp_path / "launch" / "bad.launch").write_bytes(b'<launch><param name="r" textfile="r\xff.urdf"')
    assert [Path(p).name for p in unread_naming(str(robot))] == ["bad.launch (not read)"]
    result = load_and_check(str(robot), CheckOptions())
    assert not [f for f in result.findings if f.code == "U900"]


# --- whose a launch file is: may_run ---------------------------------------------------------

SPAWNING = """<launch>
  <node name="spawner" pkg="controller_manager" type="spawner" args="{}"/>
</launch>"""


def _may_run(root: Path) -> set[str] | None:
    from urdftool.description.run_memo import one_run
    from urdftool.description.runtime import may_run

    with one_run():
        found = may_run(root, root / "arm_description/urdf/arm.urdf.xacro")
    return None if found is None else {str(Path(p).relative_to(root)) for p in found}


def test_a_launch_file_that_cannot_name_the_robot_may_not_run_it(tmp_path):
    root = _repo(tmp_path, {
        "arm_description/launch/view.launch": SPAWNING.format("view_controller"),  # its package
        "arm_bringup/launch/states.launch": SPAWNING.format("joint_state_controller"),
        "other_robot/package.xml": PACKAGE.format("other_robot"),
        "other_robot/launch/other.launch": SPAWNING.format("other_controller"),
        # names are words: another file, another package
        "other_robot/launch/words.launch": '<launch><param name="robot_description" textfile='
                                           '"$(find arm_description_extra)/my_arm.urdf"/></launch>'})
    assert _may_run(root) == {"arm_description/launch/view.launch"}


def test_a_launch_file_may_run_the_robot_that_its_package_depends_on(tmp_path):
    root = _repo(tmp_path, {
        "arm_bringup/package.xml": "<package format='2'><name>arm_bringup</name>"
                                   "<exec_depend>arm_description</exec_depend></package>",
        "arm_bringup/launch/states.launch": SPAWNING.format("joint_state_controller"),
        "other_robot/package.xml": PACKAGE.format("other_robot"),
        "other_robot/launch/other.launch": SPAWNING.format("other_controller")})
    assert _may_run(root) == {"arm_bringup/launch/states.launch"}


def test_a_launch_file_naming_the_package_or_the_file_or_including_one_that_does_may_run_it(
        tmp_path):
    root = _repo(tmp_path, {
        "arm_bringup/launch/package.launch": '<launch><param name="robot_description" '
                                             'textfile="$(find arm_description)/urdf/x.urdf"/></launch>',
        "arm_bringup/launch/file.launch.py": 'robot = "arm" + ".urdf.xacro"',
        # includes one that may: by its file's name, and by its package's
        "sim/package.xml": PACKAGE.format("sim"),
        "sim/launch/sim.launch": '<launch><include file="$(dirname)/../../arm_bringup/launch/'
                                 'package.launch"/></launch>',
        "world/package.xml": PACKAGE.format("world"),
        "world/launch/world.launch": '<launch><include file="$(find sim)/launch/x.launch"/></launch>',
        "other_robot/package.xml": PACKAGE.format("other_robot"),
        "other_robot/launch/other.launch": SPAWNING.format("joint_state_controller")})
    assert _may_run(root) == {"arm_bringup/launch/package.launch",
                              "arm_bringup/launch/file.launch.py", "sim/launch/sim.launch",
                              "world/launch/world.launch"}


def test_every_launch_file_may_run_the_robot_is_none(tmp_path):
    root = _repo(tmp_path, {"arm_description/launch/view.launch": SPAWNING.format("c")})
    assert _may_run(root) is None


def test_what_a_launch_file_that_cannot_name_the_robot_starts_is_not_the_robots(tmp_path):
    # before: a configuration describing no robot was every robot's, its spawns too
    root = _repo(tmp_path, {
        "arm_bringup/launch/states.launch": SPAWNING.format("joint_state_controller"),
        "arm_description/launch/view.launch": SPAWNING.format("view_controller")})
    robot = load_and_check(str(root / "arm_description/urdf/arm.urdf.xacro"), CheckOptions()).robot
    facts = runtime(robot)
    assert [Path(c.top.path).name for c, _ in facts.configurations] == ["view.launch"]
    assert [s.name for s in facts.spawns] == ["view_controller"]


def test_an_index_of_some_launch_files_reads_what_they_include(tmp_path):
    from urdftool.description.run_memo import one_run

    root = _repo(tmp_path, {
        "arm_description/launch/view.launch": '<launch><include file="$(find arm_bringup)/'
                                              'launch/control.launch"/></launch>',
        "arm_bringup/launch/control.launch": SPAWNING.format("arm_controller"),
        "arm_bringup/launch/other.launch": SPAWNING.format("other_controller")})
    with one_run():
        index = launch_index(root, frozenset({str(root / "arm_description/launch/view.launch")}))
        [configuration] = index.configurations
        assert [s.arguments[0].text for s in configuration.started] == ["arm_controller"]
        assert sorted(Path(p).name for p in index.files) == ["control.launch", "view.launch"]
