"""U60x controller YAML rules: layouts, joints, interfaces, and broken example robots."""

from __future__ import annotations

import pytest

from conftest import ROBOTS
from urdftool.diagnostics import Severity
from urdftool.lint.engine import CheckOptions, load_and_check
from crossfile_helpers import HEAD_ROBOT, broken_copy, case_messages, check_folder, line_of

TX = """<transmission name="t"><type>transmission_interface/SimpleTransmission</type>
    <joint name="head_joint"><hardwareInterface>{iface}</hardwareInterface></joint>
    <actuator name="m"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>"""
ROS2 = """<ros2_control name="s" type="system"><hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="head_joint"><command_interface name="{iface}"/><state_interface name="position"/></joint>
  </ros2_control>"""
ROS2_YAML = """\
    controller_manager:
      ros__parameters:
        joint_state_broadcaster:
          type: joint_state_broadcaster/JointStateBroadcaster
        head_controller:
          type: {type}
    head_controller:
      ros__parameters:
        joints:
          - head_joint
        command_interfaces: [{claim}]
        interface_name: {claim}
        state_interfaces: [position]
    """
# ROS2_YAML sets both command_interfaces and interface_name for whichever class it holds: the
# one the class does not read is U632's business, not these tests'.
ONLY_U60 = ("U5", "U60", "U61", "U7", "U8")


def test_ros2_layout_trajectory_controller_command_interfaces(tmp_path):
    robot = HEAD_ROBOT.format(body=ROS2.format(iface="velocity"))
    yaml = ROS2_YAML.format(type="joint_trajectory_controller/JointTrajectoryController", claim="position")
    found, findings = check_folder(tmp_path, {"robot.urdf": robot, "config/c.yaml": yaml}, select=ONLY_U60)
    assert found == [("c.yaml", 10, "U604")]
    assert "offers velocity; set command_interfaces to [velocity]" in findings[0].message


def test_a_ros2_controller_is_offered_nothing_by_ros1_transmissions(tmp_path):
    """naranjelio's stale naranjelio.urdf: ROS 1 transmissions (EffortJointInterface), no
    <ros2_control>, and the package's ROS 2 JointTrajectoryController commanding position.
    ros2_control reads no transmission outside <ros2_control>: the joint offers the ROS 2
    controller nothing, so it was wrong to say it "offers effort" (U604); what is missing is
    its <ros2_control> joint (U603), in a robot that has <ros2_control> for other joints; a
    robot with none at all (naranjelio's stale URDF beside the xacro its launch file builds)
    is no robot a ROS 2 controller runs on, and nothing is said."""
    tx = TX.format(iface="hardware_interface/EffortJointInterface")
    yaml = ROS2_YAML.format(type="joint_trajectory_controller/JointTrajectoryController", claim="position")
    found, _ = check_folder(tmp_path, {"robot.urdf": HEAD_ROBOT.format(body=tx),
                                       "config/c.yaml": yaml}, select=ONLY_U60)
    assert found == [], found
    other = ROS2.format(iface="position").replace("head_joint", "cam_joint")
    found, findings = check_folder(tmp_path / "2", {"robot.urdf": HEAD_ROBOT.format(body=tx + other),
                                                    "config/c.yaml": yaml}, select=ONLY_U60)
    assert [code for *_, code in found if code.startswith("U60")] == ["U603"], found
    assert "has no <ros2_control> joint, only a transmission" in findings[0].message


def test_ros2_forward_command_controller_uses_interface_name(tmp_path):
    robot = HEAD_ROBOT.format(body=ROS2.format(iface="effort"))
    yaml = ROS2_YAML.format(type="forward_command_controller/ForwardCommandController", claim="effort")
    assert check_folder(tmp_path, {"robot.urdf": robot, "config/c.yaml": yaml}, select=ONLY_U60)[0] == []


def test_ros1_namespaced_layout_and_prefixless_interface(tmp_path):
    robot = HEAD_ROBOT.format(body=TX.format(iface="EffortJointInterface"))
    yaml = """\
        robot:
          joint_state_controller: {type: joint_state_controller/JointStateController, publish_rate: 50}
          head_controller:
            type: effort_controllers/JointPositionController
            joint: head_joint
            pid: {p: 10.0}
          cam_controller:
            type: effort_controllers/JointPositionController
            joint: cam_joint
            pid: {p: 10.0}
        """
    found, _ = check_folder(tmp_path, {"robot.urdf": robot, "config/c.yaml": yaml})
    # the bare name still offers effort (U508 only asks for the prefix)
    assert found == [("c.yaml", 9, "U603"), ("robot.urdf", 9, "U508")]


def test_moveit_controller_list_joints_are_checked(tmp_path):
    robot = HEAD_ROBOT.format(body=TX.format(iface="hardware_interface/PositionJointInterface"))
    yaml = """\
        controller_list:
          - name: arm
            type: FollowJointTrajectory
            joints: [head_joint, neck_joint]
            action_ns: follow_joint_trajectory
        """
    found, findings = check_folder(tmp_path, {"robot.urdf": robot, "other/c.yaml": yaml},
                                   controllers=[str(tmp_path / "other/c.yaml")])
    assert found == [("c.yaml", 4, "U602")]  # no U605: MoveIt does not publish joint states


def test_roslaunch_substitutions_in_joint_names_are_not_checked(tmp_path):
    robot = HEAD_ROBOT.format(body=TX.format(iface="hardware_interface/PositionJointInterface"))
    yaml = ("jsc: {type: joint_state_controller/JointStateController, publish_rate: 50}\n"
            "c: {type: position_controllers/JointGroupPositionController, joints: [$(arg prefix)head_joint]}\n")
    assert check_folder(tmp_path, {"robot.urdf": robot, "config/c.yaml": yaml})[0] == []


def test_controller_yaml_in_config_without_controllers_is_ignored(tmp_path):
    robot = HEAD_ROBOT.format(body="")
    assert check_folder(tmp_path, {"robot.urdf": robot, "config/params.yaml": "rate: 5\n"})[0] == []


def test_given_yaml_without_controllers_is_reported(tmp_path):
    robot = HEAD_ROBOT.format(body="")
    found, _ = check_folder(tmp_path, {"robot.urdf": robot, "x/p.yaml": "rate: 5\n"},
                            controllers=[str(tmp_path / "x/p.yaml")])
    assert found == [("p.yaml", 1, "U601")]


def test_yaml_alias_bomb_is_a_located_error(tmp_path):
    """Nine aliases a line for eight lines (43 million controllers): was walked once by the
    walkers that remembered what they had seen, while others ran to the time or memory budget
    (a bomb of joint names); now refused when read, at the first line over the limit, as
    xacro's load_yaml refuses it (yaml_limits)."""
    bomb = "a: &a {type: x/Y, joints: [head_joint]}\n" + "".join(
        f"l{i}: &l{i} [{', '.join([f'*{p}' for p in ['a' if i == 0 else f'l{i - 1}'] * 9])}]\n"
        for i in range(8))
    robot = HEAD_ROBOT.format(body="")
    found, _ = check_folder(tmp_path, {"robot.urdf": robot, "config/c.yaml": bomb})
    assert found == [("c.yaml", 6, "U601")]


@pytest.mark.parametrize("layout, severity", [
    ("humanoid:\n  c:\n    type: a/B\n    joints: [head_joint]\n    rate: VALUE\n", Severity.ERROR),
    ("controller_manager:\n  ros__parameters:\n    c: {type: a/B}\nc:\n  ros__parameters:\n"
     "    joints: [head_joint]\n    rate: VALUE\n", Severity.WARNING),
])
@pytest.mark.parametrize("value", ["2001-02-30", "!!float junk", "!!bool maybe", "1" * 400])
def test_a_value_pyyaml_cannot_construct_is_u601_an_error_where_every_reader_fails(tmp_path, layout, severity, value):
    """ROS 1 (rosparam) reads a controllers file with PyYAML, which cannot construct these: an
    error of the file at the value's line. ROS 2's parameter parser reads each as written (no
    dates, no tags): a warning naming the readers that fail (a launch file loading it with
    PyYAML). Each was 61 crashed rules (U900) before."""
    robot = HEAD_ROBOT.format(body="")
    found, findings = check_folder(tmp_path, {"robot.urdf": robot,
                                              "config/c.yaml": layout.replace("VALUE", value)})
    line = layout.count("\n")
    assert [(f.code, f.line, f.severity) for f in findings if f.code in ("U601", "U900")] == [
        ("U601", line, severity)]


def test_a_rosparam_angle_that_is_no_number_is_u601_at_its_line(tmp_path):
    """``!degrees abc`` in a ROS 1 controllers file: rosparam's constructor raises and roslaunch
    refuses the file (no controller gets its parameters); it was read as the text 'abc', and
    nothing said. One it reads is a number in radians (``!radians pi/2``), no finding."""
    robot = HEAD_ROBOT.format(body="")
    layout = "humanoid:\n  c:\n    type: a/B\n    joints: [head_joint]\n    angle: VALUE\n"
    for value, expected in (("!degrees abc", [("U601", 5, Severity.ERROR)]), ("!radians pi/2", [])):
        _, findings = check_folder(tmp_path / value[1:4], {"robot.urdf": robot,
                                                           "config/c.yaml": layout.replace("VALUE", value)})
        assert [(f.code, f.line, f.severity) for f in findings if f.code in ("U601", "U900")] == \
            expected, value


@pytest.mark.parametrize("layout, expected", [
    ("humanoid:\n  c:\n    type: a/B\n    joints: [head_joint]\n    VALUE\n", Severity.ERROR),
    ("moveit_simple_controller_manager:\n  controller_names: [c]\n  c:\n    action_ns: x\n"
     "    VALUE\n", Severity.WARNING),
    ("controller_manager:\n  ros__parameters:\n    c: {type: a/B}\nc:\n  ros__parameters:\n"
     "    joints: [head_joint]\n    VALUE\n", None),
])
@pytest.mark.parametrize("value", ["count: 2147483648", "counts: [1, -2147483649]"])
def test_an_integer_past_int32_in_a_ros1_parameter_file_is_u601_at_its_line(tmp_path, layout,
                                                                             expected, value):
    """The ROS 1 parameter server speaks XML-RPC, whose integers are 32-bit (<i4>): roslaunch's
    client refuses to send 2147483648 ("int exceeds XML-RPC limits") and stops before any node
    starts. An error in a file of ROS 1 controllers; a warning saying the condition in a file
    only of MoveIt's lists (ROS 2's MoveIt reads it too, into 64-bit parameters); nothing in a
    ROS 2 parameter file (ROS 2's own bound, int64, is U630's). Nothing said it before."""
    robot = HEAD_ROBOT.format(body="")
    _, findings = check_folder(tmp_path, {"robot.urdf": robot,
                                          "config/c.yaml": layout.replace("VALUE", value)})
    found = [(f.line, f.severity) for f in findings if f.code == "U601" and "32-bit" in f.message]
    assert found == ([] if expected is None else [(layout.count("\n"), expected)])
    if expected is not None:
        assert "int exceeds XML-RPC limits" in next(f.message for f in findings if "32-bit" in f.message)


# --- the example robots, broken in a temporary copy ------------------------------------------

@pytest.mark.parametrize("file, old, new, code, message", [
    ("config/controllers.yaml", "joints: [head_pan, head_tilt]", "joints: [head_pan, head_tlit]",
     "U602", "did you mean 'head_tilt'"),
    ("parts.xacro", 'interface="Position"', """interface="${'Velocity' if name == 'head_pan' else 'Position'}\"""",
     "U604", "commands position on joint 'head_pan', which offers velocity; use "
             "velocity_controllers/JointTrajectoryController, or make the joint offer position"),
], ids=["joint-renamed-in-yaml", "transmission-swapped-to-velocity"])
def test_humanoid_broken_is_located_in_the_controller_yaml(tmp_path, file, old, new, code, message):
    findings = broken_copy(tmp_path, "humanoid", file, old, new)
    yaml = ROBOTS / "humanoid/config/controllers.yaml"
    # (renaming a joint in joints: also leaves its constraints naming the old one: U609)
    assert [(f.code, f.file.endswith("controllers.yaml"), f.line) for f in findings if f.code != "U609"] == [
        (code, True, line_of(yaml, "joints: [head_pan, head_tilt]"))]
    assert message in findings[0].message


def test_r2d2_joint_renamed_in_controller_yaml(tmp_path):
    findings = broken_copy(tmp_path, "r2d2", "config/head_controller.yaml",
                           "      - head_joint", "      - dome_joint")
    yaml = ROBOTS / "r2d2/config/head_controller.yaml"
    assert [(f.code, f.line) for f in findings] == [("U602", line_of(yaml, "- head_joint"))]


def test_r2d2_ros2_control_and_transmission_swapped_to_velocity(tmp_path):
    # the ROS 1 transmission still offers position, but ros2_control reads only <ros2_control>
    findings = broken_copy(tmp_path, "r2d2", "r2d2.urdf.xacro",
                           '<command_interface name="position"/>', '<command_interface name="velocity"/>')
    assert [(f.code, f.line) for f in findings] == [
        ("U604", line_of(ROBOTS / "r2d2/config/head_controller.yaml", "- head_joint"))]
    assert findings[0].message.endswith(
        "offers velocity; use velocity_controllers/JointGroupVelocityController, or make the joint "
        "offer position (a position command interface in its <ros2_control> joint)")
    findings = broken_copy(tmp_path / "2", "r2d2", "r2d2.urdf.xacro",
                           'actuator="head_motor" interface="Position"', 'actuator="head_motor" interface="Velocity"')
    assert findings == []  # ros2_control still offers position


def test_r2d2_without_joint_state_broadcaster(tmp_path):
    findings = broken_copy(tmp_path, "r2d2", "config/head_controller.yaml",
                           "type: joint_state_broadcaster/JointStateBroadcaster", "type: x_controllers/Other")
    assert [f.code for f in findings] == ["U605"]


def test_unactuated_controller_joint_says_what_would_be_right():
    messages = case_messages("U603_controller_joint_not_actuated", "U603")
    assert messages and all("add one for it, or remove it from the controller" in m for m in messages)


def test_diff_drive_controller_on_position_wheels_says_what_ros2_needs(tmp_path):
    robot = HEAD_ROBOT.format(body=ROS2.format(iface="position")).replace(
        'type="revolute"', 'type="continuous"')
    yaml = """\
        controller_manager:
          ros__parameters:
            jsb: {type: joint_state_broadcaster/JointStateBroadcaster}
            base: {type: diff_drive_controller/DiffDriveController}
        base:
          ros__parameters:
            left_wheel_names: [head_joint]
            right_wheel_names: [head_joint]
            wheel_separation: 0.1
            wheel_radius: 0.05
        """
    found, findings = check_folder(tmp_path, {"robot.urdf": robot, "config/c.yaml": yaml}, select=("U604",))
    assert found == [("c.yaml", 7, "U604"), ("c.yaml", 8, "U604")]
    assert findings[0].message.endswith(
        "which offers position; diff_drive_controller turns its wheels by velocity: make the joint "
        "offer velocity (a velocity command interface in its <ros2_control> joint)")


def test_a_ros1_class_in_a_ros2_file_names_the_ros2_class():
    messages = case_messages("U606_controller_unknown_class", "U606")
    # no launch file says whether it is started: the message says so first (a warning)
    assert any(m.endswith("position_controllers/JointPositionController is a class of ROS 1 "
                          "(ros_control), and the file has ros__parameters, so it is a ROS 2 parameter "
                          "file; ROS 2 (ros2_control) has "
                          "position_controllers/JointGroupPositionController") for m in messages)


# --- which controllers run: the launch files' say (issue 30 classes 1, 5; issue 32 class 9) ------

ROS2_HEAD = HEAD_ROBOT.format(body="""
  <ros2_control name="s" type="system"><hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="head_joint"><command_interface name="position"/><state_interface name="position"/></joint>
  </ros2_control>""")
ROS2_CONTROLLERS = """
controller_manager:
  ros__parameters:
    jsb: {type: joint_state_broadcaster/JointStateBroadcaster}
    head_controller: {type: forward_command_controller/ForwardCommandController}
head_controller:
  ros__parameters:
    joints: [$(var prefix)joint]
    interface_name: position
"""
ROS2_LAUNCH = """
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterFile
from launch_ros.substitutions import FindPackageShare

def generate_launch_description():
    robot = Command(["xacro ", PathJoinSubstitution([FindPackageShare("head"), "robot.urdf"])])
    params = ParameterFile(PathJoinSubstitution([FindPackageShare("head"), "config", "c.yaml"]),
                           allow_substs={allow})
    return LaunchDescription([
        DeclareLaunchArgument("prefix", default_value="{prefix}"),
        Node(package="controller_manager", executable="ros2_control_node",
             parameters=[{{"robot_description": robot}}]),
        Node(package="controller_manager", executable="spawner", parameters=[params],
             arguments=["jsb", "head_controller"]),
    ])
"""


def _ros2_head(tmp_path, prefix: str, allow: bool):
    files = {"robot.urdf": ROS2_HEAD, "config/c.yaml": ROS2_CONTROLLERS,
             "package.xml": "<package format='3'><name>head</name>"
                            "<buildtool_depend>ament_cmake</buildtool_depend></package>",
             "launch/head.launch.py": ROS2_LAUNCH.format(prefix=prefix, allow=allow)}
    (tmp_path / ".git").mkdir(parents=True, exist_ok=True)
    return check_folder(tmp_path, files, select=("U602",))


def test_var_substitutions_take_the_launch_arguments_values(tmp_path):
    # ros2_control_demos example 1: joints [$(var joint_prefix)1, ...] loaded with allow_substs
    assert _ros2_head(tmp_path / "fits", "head_", True)[0] == []
    marks, findings = _ros2_head(tmp_path / "typo", "hed_", True)
    assert marks == [("c.yaml", 8, "U602")] and "'hed_joint'" in findings[0].message
    assert findings[0].severity == Severity.ERROR


def test_a_substitution_loaded_as_written_is_the_name_the_controller_gets(tmp_path):
    marks, findings = _ros2_head(tmp_path, "head_", False)
    assert marks == [("c.yaml", 8, "U602")]
    assert "'$(var prefix)joint'" in findings[0].message and "without substitution" in findings[0].message


# A robot whose controller file holds 'spare' (on a joint it lacks) beside jsc, which its one
# launch file starts alone
_SPARE = {"robot.urdf": HEAD_ROBOT.format(body=""),
          "package.xml": "<package format='2'><name>head</name></package>",
          "config/c.yaml": "jsc: {type: joint_state_controller/JointStateController}\n"
                           "spare: {type: position_controllers/JointPositionController, joint: nek}\n",
          "launch/head.launch": """<launch>
            <param name="robot_description" textfile="$(find head)/robot.urdf"/>
            <rosparam file="$(find head)/config/c.yaml" command="load"/>
            <node name="s" pkg="controller_manager" type="spawner" args="jsc"/>
          </launch>"""}


def test_a_controller_no_launch_file_starts_is_not_judged(tmp_path):
    (tmp_path / ".git").mkdir()
    files = dict(_SPARE)
    assert check_folder(tmp_path, files, select=("U602",))[0] == []
    (tmp_path / "launch/head.launch").write_text((tmp_path / "launch/head.launch").read_text().replace(
        'args="jsc"', 'args="jsc spare"'))
    marks, findings = check_folder(tmp_path, {}, select=("U602",))
    assert marks == [("c.yaml", 2, "U602")] and findings[0].severity == Severity.ERROR


def _gripper_launch(tmp_path, body: str = ""):
    """A robot whose launch file builds it with gripper:=true and starts controller 'grip'
    (joint 'finger') with it; its findings."""
    (tmp_path / ".git").mkdir()
    robot = HEAD_ROBOT.format(body=body).replace('<robot name="r">', '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                                                 '<xacro:arg name="gripper" default="false"/>')
    files = {"robot.urdf": "", "robot.urdf.xacro": robot,
             "package.xml": "<package format='2'><name>head</name></package>",
             "config/c.yaml": "jsc: {type: joint_state_controller/JointStateController}\n"
                              "grip: {type: position_controllers/JointPositionController, joint: finger}\n",
             "launch/head.launch": """<launch>
               <param name="robot_description" command="xacro $(find head)/robot.urdf.xacro gripper:=true"/>
               <rosparam file="$(find head)/config/c.yaml" command="load"/>
               <node name="s" pkg="controller_manager" type="spawner" args="jsc grip"/>
             </launch>"""}
    for name, text in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    return load_and_check(str(tmp_path / "robot.urdf.xacro"), CheckOptions()).findings


def test_a_controller_started_against_other_xacro_arguments_is_a_warning(tmp_path):
    # the build the launch file starts it with (gripper:=true) lacks the joint too
    [finding] = [f for f in _gripper_launch(tmp_path) if f.code == "U602"]
    assert finding.severity == Severity.WARNING
    assert "against the robot with other xacro arguments (gripper:=true)" in finding.message
    assert "which is not in that build of the robot either" in finding.message


def test_a_controller_is_checked_against_the_robot_its_launch_file_builds(tmp_path):
    # Automation-Research-Team/aist_robotiq: gazebo.launch builds the gripper with
    # prefix:=a_bot_gripper_ and starts the controller naming a_bot_gripper_finger_joint; the
    # robot as checked (prefix '') lacks it, the build that starts the controller has it
    grip = ('<xacro:if value="$(arg gripper)"><link name="finger_link"/><joint name="finger" '
            'type="prismatic"><parent link="head"/><child link="finger_link"/><axis xyz="1 0 0"/>'
            '<limit lower="0" upper="0.01" effort="5" velocity="1"/></joint></xacro:if>')
    assert [f.message for f in _gripper_launch(tmp_path, grip) if f.code == "U602"] == []


def test_a_file_naming_only_another_builds_joints_is_one_note(tmp_path):
    # a sibling build's file (every joint prefixed, as a dual-arm robot's left_ arm): not one
    # warning per joint, one note at its first controller; a file naming one missing joint alone
    # may hold a slip and is judged as before
    other = ("arm: {type: position_controllers/JointGroupPositionController,\n"
             "      joints: [left_head_joint, left_neck_joint]}\n"
             "grip: {type: position_controllers/JointPositionController, joint: left_finger}\n")
    marks, findings = check_folder(tmp_path / "other", {"robot.urdf": HEAD_ROBOT.format(body=""),
                                                       "config/c.yaml": other}, select=("U602",))
    assert marks == [("c.yaml", 1, "U602")] and findings[0].severity == Severity.INFO
    assert "none of the 3 joints" in findings[0].message and "another build" in findings[0].message
    slip = "grip: {type: position_controllers/JointPositionController, joint: hed_joint}\n"
    marks, findings = check_folder(tmp_path / "slip", {"robot.urdf": HEAD_ROBOT.format(body=""),
                                                      "config/c.yaml": slip}, select=("U602",))
    assert marks == [("c.yaml", 1, "U602")] and findings[0].severity == Severity.WARNING


def test_moveit2_parallel_gripper_command_is_a_moveit_type(tmp_path):
    # moveit_simple_controller_manager (moveit2 main) knows ParallelGripperCommand
    robot = HEAD_ROBOT.format(body=TX.format(iface="hardware_interface/PositionJointInterface"))
    yaml = """\
        moveit_simple_controller_manager:
          controller_names: [gripper]
          gripper:
            type: ParallelGripperCommand
            action_ns: gripper_cmd
            joints: [head_joint]
        """
    found, _ = check_folder(tmp_path, {"robot.urdf": robot, "other/c.yaml": yaml},
                            controllers=[str(tmp_path / "other/c.yaml")], select=("U606",))
    assert found == []


def test_a_moveit_gripper_commands_its_first_joint_and_its_mimics_follow(tmp_path):
    """ABC-iRobotics/tm5-900_rg6_moveit_config: the Setup Assistant's rg6_controller
    (GripperCommand) lists finger_joint and its five <mimic> joints, which have no
    ros2_control joint: MoveIt sends the action finger_joint's position alone. A joint that
    mimics nothing the controller lists stays U603's."""
    mimic = ('<link name="finger"/><joint name="finger_joint" type="revolute"><parent link="head"/>'
             '<child link="finger"/><limit lower="0" upper="1" effort="1" velocity="1"/>'
             '<mimic joint="head_joint"/></joint>')
    robot = HEAD_ROBOT.format(body=ROS2.format(iface="position") + mimic)
    yaml = """\
        moveit_simple_controller_manager:
          controller_names: [gripper, other]
          gripper:
            type: GripperCommand
            action_ns: gripper_cmd
            joints: [head_joint, finger_joint]
          other:
            type: FollowJointTrajectory
            action_ns: follow_joint_trajectory
            joints: [finger_joint]
        """
    found, _ = check_folder(tmp_path, {"robot.urdf": robot, "config/moveit_controllers.yaml": yaml},
                            controllers=[str(tmp_path / "config/moveit_controllers.yaml")],
                            select=("U603",))
    assert found == [("moveit_controllers.yaml", 10, "U603")]  # the trajectory controller's


def test_a_chained_controller_names_another_controllers_reference_interfaces(tmp_path):
    """ros2_control_demos example 16: diff_drive_controller's wheels are the reference
    interfaces of two pid_controllers (pid_left/head_joint), not joints of the URDF."""
    chained = """
controller_manager:
  ros__parameters:
    pid_left: {type: pid_controller/PidController}
    base: {type: diff_drive_controller/DiffDriveController}
    head_controller: {type: forward_command_controller/ForwardCommandController}
head_controller:
  ros__parameters:
    joints: [head_joint]
    interface_name: position
pid_left:
  ros__parameters:
    dof_names: [head_joint]
base:
  ros__parameters:
    left_wheel_names: ["pid_left/head_joint"]
    right_wheel_names: ["pid_rigth/head_joint"]
"""
    files = {"robot.urdf": ROS2_HEAD, "config/c.yaml": chained}
    marks, findings = check_folder(tmp_path, files, select=("U602",))
    assert [m[1] for m in marks] == [line_of(tmp_path / "config/c.yaml", "pid_rigth")]  # no such controller


def test_a_controller_a_launch_file_not_read_names_is_not_started_nowhere(tmp_path):
    """A launch file that cannot be read (not well-formed) and names the controller may start
    it: 'started nowhere' is not known (runtime.unread_naming, as for a robot file's builds),
    so the controller is judged, conditionally, naming the file."""
    (tmp_path / ".git").mkdir()
    not_closed = '<launch><node pkg="controller_manager" type="spawner" args="spare"></launch>'
    files = {**_SPARE, "launch/spare.launch": not_closed}
    marks, findings = check_folder(tmp_path, files, select=("U602",))
    assert marks == [("c.yaml", 2, "U602")] and findings[0].severity == Severity.WARNING
    assert f"launch file {tmp_path}/launch/spare.launch (not read) may start 'spare'" in \
        findings[0].message, findings[0].message


def test_a_class_a_package_of_the_repository_exports_is_loadable(tmp_path):
    """Pilz (pilz_robots): pilz_control exports position_controllers/PilzJointTrajectoryController
    in ros_controllers' namespace, through its package.xml's <export> and plugin XML."""
    robot = HEAD_ROBOT.format(body=TX.format(iface="hardware_interface/PositionJointInterface"))
    yaml = "arm: {type: position_controllers/PilzJointTrajectoryController, joints: [head_joint]}\n"
    files = {"robot.urdf": robot, "config/c.yaml": yaml, ".git/HEAD": "ref: refs/heads/main\n"}
    found, _ = check_folder(tmp_path / "alone", files, select=("U606",))
    assert found == [("c.yaml", 1, "U606")]  # no package exports it: a slip
    files.update({
        "pilz_control/package.xml": """<package format="2"><name>pilz_control</name>
            <export><controller_interface plugin="${prefix}/plugins.xml"/></export></package>""",
        "pilz_control/plugins.xml": """<library path="lib/libpilz_control">
            <!-- <class name="position_controllers/Commented"/> -->
            <class name="position_controllers/PilzJointTrajectoryController"
                   type="position_controllers::PilzJointTrajectoryController"
                   base_class_type="controller_interface::ControllerBase"/></library>"""})
    found, _ = check_folder(tmp_path / "exported", files, select=("U606",))
    assert found == []



def test_trajectory_constraints_naming_no_joint_of_the_controller_are_a_warning(tmp_path):
    """JLSchol/omni_marco_gazebo's torso_controller: constraints for torso_1_joint and
    torso_2_joint (copied from a two-joint torso) beside joints: [torso_lift_joint]. The
    controller reads constraints for its own joints only and ignores the entry, as a plugin
    ignores a parameter it does not read (U641, a warning): it was an error. A contradiction
    it refuses to configure on stays one."""
    (tmp_path / ".git").mkdir()
    files = dict(_SPARE)
    files["config/c.yaml"] = (
        "jsc: {type: joint_state_controller/JointStateController}\n"
        "arm:\n  type: position_controllers/JointTrajectoryController\n  joints: [head_joint]\n"
        "  state_publish_rate: 0\n  constraints:\n    head_jiont: {goal: 0.1}\n")
    files["launch/head.launch"] = files["launch/head.launch"].replace('args="jsc"', 'args="jsc arm"')
    marks, findings = check_folder(tmp_path, files, select=("U609",))
    assert [(m[1], f.severity) for m, f in zip(marks, findings)] == [
        (5, Severity.ERROR), (7, Severity.WARNING)]
    assert "so the controller ignores them; did you mean 'head_joint'?" in findings[1].message


def test_a_joint_state_broadcaster_declared_and_never_started_is_named(tmp_path):
    """giacomotambe/traquad_gazebo: joint_state_broadcaster_1 is declared beside the two
    controllers the launch files spawn, and never spawned; 'add one' sent the reader to a file
    that has it."""
    (tmp_path / ".git").mkdir()
    files = dict(_SPARE)
    files["config/c.yaml"] = files["config/c.yaml"].replace("joint: nek", "joint: head_joint")
    files["launch/head.launch"] = files["launch/head.launch"].replace('args="jsc"', 'args="spare"')
    marks, findings = check_folder(tmp_path, files, select=("U605",))
    assert marks == [("c.yaml", 2, "U605")]
    assert findings[0].message.endswith("controller 'jsc' (joint_state_controller/"
                                        "JointStateController) is declared, but no launch file "
                                        "of the robot starts it: spawn it")


def test_a_fake_controller_list_beside_moveit_sim_controllers_settings_is_not_checked(tmp_path):
    # abb_dual_arm's fake_controllers.yaml: moveit_sim_controllers' settings beside the list the
    # fake controller manager reads, whose 'interpolate' the simple controller manager never sees
    robot = HEAD_ROBOT.format(body=TX.format(iface="hardware_interface/PositionJointInterface"))
    yaml = """\
        moveit_sim_hw_interface:
          joint_model_group: head
          joint_model_group_pose: initial
        controller_list:
          - name: head
            type: interpolate
            joints: [head_joint]
        """
    assert check_folder(tmp_path, {"robot.urdf": robot, "config/fake_controllers.yaml": yaml})[0] == []


def test_a_ros1_trajectory_controller_of_3000_joints_is_searched_once(tmp_path, monkeypatch):
    """U609 looked for each joint among those before it: 40,000 joints took 13 s of a check.
    The joints listed twice are still each said, at their lines."""
    from urdftool.description import controllers

    from conftest import counting_str

    compared = []
    Name = counting_str(compared)

    real = controllers.Controller.joints
    monkeypatch.setattr(controllers.Controller, "joints", lambda self: [
        controllers.JointRef(Name(ref.name), ref.line, ref.key) for ref in real(self)])
    names = [f"j{i}" for i in range(3000)] + ["head_joint", "j7"]
    yaml_text = ("head_controller:\n  type: position_controllers/JointTrajectoryController\n"
                 "  joints:\n" + "".join(f"    - {name}\n" for name in names))
    found, messages = check_folder(tmp_path, {"robot.urdf": HEAD_ROBOT.format(body=""),
                                              "config/c.yaml": yaml_text})
    twice = [where for where in found if where[2] == "U609"]
    assert twice == [("c.yaml", 3 + len(names), "U609")], twice
    assert len(compared) < 100_000, len(compared)


@pytest.mark.parametrize("plugin, severity", [
    # a real robot's own RobotHW (Open_Mobile_Manipulator's ros_control_boilerplate registers
    # camera_dummy_joint from its 'joints' parameter): the transmissions do not say
    ("", Severity.WARNING),
    # gazebo_ros_control offers only the joints of the URDF's transmissions
    ('<gazebo><plugin name="c" filename="libgazebo_ros_control.so"/></gazebo>', Severity.ERROR),
])
def test_a_joint_without_a_transmission_is_an_error_where_transmissions_are_read(
        tmp_path, plugin, severity):
    (tmp_path / ".git").mkdir()
    files = dict(_SPARE)
    files["robot.urdf"] = HEAD_ROBOT.format(body=TX.format(
        iface="hardware_interface/PositionJointInterface").replace("head_joint", "other") + plugin)
    files["config/c.yaml"] = files["config/c.yaml"].replace("joint: nek", "joint: head_joint")
    files["launch/head.launch"] = files["launch/head.launch"].replace('args="jsc"', 'args="jsc spare"')
    marks, findings = check_folder(tmp_path, files, select=("U603",))
    assert marks == [("c.yaml", 2, "U603")] and findings[0].severity == severity
    assert findings[0].message.endswith("joint 'head_joint' has no transmission or ros2_control "
                                        "joint; add one for it, or remove it from the controller")


def test_a_file_with_a_section_per_robot_instance_is_read_for_this_instance_s_namespace(tmp_path):
    """One YAML with a ``robot1:`` and a ``robot2:`` section, each a controller manager
    declaring the same controllers for its own instance of the robot (robot2/head_joint:
    the same xacro built with robot_name:=robot2): the robot whose gz_ros2_control plugin
    runs in namespace robot1 has robot1's controllers, not robot2's (false U602 errors on
    robot2's joints, and robot1's controller read with robot2's joints). Without the
    plugin's namespace nothing says which section is the robot's: both are checked."""
    body = """<gazebo><plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin">
        <parameters>config/c.yaml</parameters>{ns}</plugin></gazebo>
      <ros2_control name="s" type="system"><hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
        <joint name="robot1/head_joint"><command_interface name="position"/><state_interface name="position"/></joint>
      </ros2_control>"""
    robot = HEAD_ROBOT.replace('"head_joint"', '"robot1/head_joint"')
    section = """\
        {r}:
          controller_manager:
            ros__parameters:
              head_controller:
                type: forward_command_controller/ForwardCommandController
          head_controller:
            ros__parameters:
              joints: [{r}/head_joint]
              interface_name: position
        """
    yaml = section.rstrip(" ").format(r="robot1") + section.rstrip(" ").format(r="robot2")
    found, _ = check_folder(tmp_path / "a", {
        "robot.urdf": robot.format(body=body.format(ns="<ros><namespace>robot1</namespace></ros>")),
        "config/c.yaml": yaml}, select=("U602",))
    assert found == []
    found, _ = check_folder(tmp_path / "b", {
        "robot.urdf": robot.format(body=body.format(ns="")), "config/c.yaml": yaml},
        select=("U602",))
    assert [line for _, line, _ in found] == [17]  # robot2's joint, robot1's read as robot1's
