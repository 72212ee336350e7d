"""U5xx transmission and ros2_control rules: ROS 1 and ROS 2 forms, PR2 and franka patterns."""

from __future__ import annotations

import os

import pytest

from urdftool.diagnostics import Severity

from crossfile_helpers import HEAD_ROBOT, broken_copy, case_messages, check_folder


def tx(joint="head_joint", iface="hardware_interface/PositionJointInterface", name="t"):
    return (f'<transmission name="{name}"><type>transmission_interface/SimpleTransmission</type>'
            f'<joint name="{joint}"><hardwareInterface>{iface}</hardwareInterface></joint>'
            f'<actuator name="{name}_m"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>')


def codes(tmp_path, body):
    return [code for _, _, code in check_folder(tmp_path, {"robot.urdf": HEAD_ROBOT.format(body=body)})[0]]


def test_ros2_form_transmission_inside_ros2_control(tmp_path):
    body = """<ros2_control name="s" type="system"><hardware><plugin>p/P</plugin></hardware>
      <joint name="head_joint"><command_interface name="position"/><state_interface name="position"/></joint>
      <transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>
        <actuator name="a" role="a"/><joint name="head_joint" role="j"><mechanical_reduction>0</mechanical_reduction></joint>
      </transmission></ros2_control>"""
    assert codes(tmp_path, body) == ["U505"]


def test_a_ros2_control_transmission_without_actuator_is_its_hardware_plugins(tmp_path):
    # uwrt_mars_rover's drivetrain: ros2_control's parser accepts a transmission with no
    # <actuator>; only a hardware plugin configuring it fails (its own does not load it yet)
    body = """<ros2_control name="s" type="actuator"><hardware><plugin>rover/Drive</plugin></hardware>
      <joint name="head_joint"><command_interface name="position"/><state_interface name="position"/></joint>
      <transmission name="t"><plugin>transmission_interface/SimpleTransmission</plugin>
        <joint name="head_joint" role="j"><mechanical_reduction>2</mechanical_reduction></joint>
      </transmission></ros2_control>"""
    _, findings = check_folder(tmp_path, {"robot.urdf": HEAD_ROBOT.format(body=body)})
    [u504] = [f for f in findings if f.code == "U504"]
    assert u504.severity == Severity.WARNING
    assert u504.message.startswith("if hardware plugin 'rover/Drive' loads its transmissions")


def test_different_interfaces_in_separate_transmissions_are_allowed(tmp_path):
    # franka_gazebo declares Position, Velocity and Effort transmissions per joint
    body = tx(name="a") + tx(name="b", iface="hardware_interface/EffortJointInterface") + tx(
        name="c", iface="franka_hw/FrankaStateInterface")
    assert codes(tmp_path, body) == []
    assert codes(tmp_path / "2", body + tx(name="d", iface="EffortJointInterface")) == ["U506", "U508"]


def test_read_only_transmission_may_name_a_fixed_joint(tmp_path):
    assert codes(tmp_path, tx() + tx(joint="cam_joint", name="m", iface="franka_hw/FrankaModelInterface")) == []


def test_pr2_style_transmissions(tmp_path):
    body = """<transmission type="pr2_mechanism_model/SimpleTransmission" name="t">
      <actuator name="m"/><joint name="head_joint"/><mechanicalReduction>-1.0</mechanicalReduction></transmission>
      <transmission type="PR2GripperTransmission" name="g"><actuator name="gm"/>
      <gap_joint name="head_jnt" mechanical_reduction="1"/><use_simulated_gripper_joint/></transmission>"""
    assert codes(tmp_path, body) == ["U501"]


def test_unactuated_joint_with_ros2_control_but_not_mimic(tmp_path):
    body = """<link name="f"/><joint name="finger" type="revolute"><parent link="head"/><child link="f"/>
      <axis xyz="0 0 1"/><limit lower="0" upper="1" effort="1" velocity="1"/><mimic joint="head_joint"/></joint>
      <ros2_control name="s" type="system"><hardware><plugin>p/P</plugin></hardware>
      <joint name="head_joint"><command_interface name="position"/><state_interface name="position"/></joint></ros2_control>"""
    assert codes(tmp_path, body) == []


def test_r2d2_transmission_on_a_misspelt_joint(tmp_path):
    findings = broken_copy(tmp_path, "r2d2", "r2d2.urdf.xacro", 'simple_transmission joint="head_joint"',
                           'simple_transmission joint="head_jiont"')
    assert [f.code for f in findings] == ["U501"]  # head_joint stays actuated by ros2_control
    u501 = findings[0]
    assert u501.file.endswith("transmission.xacro") and u501.location.via[0].file.endswith("r2d2.urdf.xacro")
    # r2d2 runs under ROS 2 only (<ros2_control>, gazebo_ros2_control): nothing reads its ROS 1
    # transmissions, so a stale joint name in one is a note, not an error
    assert u501.severity == Severity.INFO and u501.message.startswith("nothing reads this ROS 1")


def test_humanoid_unknown_hardware_interface(tmp_path):
    findings = broken_copy(tmp_path, "humanoid", "transmission.xacro", "${interface}JointInterface",
                           "${interface}Interface")
    assert {f.code for f in findings} == {"U503"} and len(findings) == 20
    assert "did you mean 'PositionJointInterface'" in findings[0].message


@pytest.mark.parametrize("case, code, fix", [
    ("U502_transmission_fixed_joint.urdf", "U502",
     "remove the transmission, or make the joint revolute, continuous or prismatic"),
    ("U504_transmission_no_actuator.urdf", "U504", 'add <actuator name="...">'),
    ("U512_ros2_control_fixed_joint.urdf", "U512", "remove it from <ros2_control>, or make the joint"),
])
def test_message_says_what_would_be_right(case, code, fix):
    messages = case_messages(case, code)
    assert messages and all(fix in m for m in messages)


LEGACY = """
      <transmission name="t"><type>transmission_interface/SimpleTransmission</type>
        <joint name="head_joint"><hardwareInterface>{interface}</hardwareInterface></joint>
        <actuator name="m"/></transmission>
      <ros2_control name="s" type="system"><hardware><plugin>mock_components/GenericSystem</plugin></hardware>
        <joint name="head_joint"><command_interface name="position"/><state_interface name="position"/></joint></ros2_control>"""


@pytest.mark.parametrize("interface", ["hardware_interface/PositionInterface", "", "position",
                                       "EffortJointInterface"])
def test_a_ros2_robot_keeping_legacy_transmissions_is_not_judged_as_ros1(tmp_path, interface):
    # issue 30 class 3: ros2_control reads only the transmissions inside <ros2_control>
    robot = HEAD_ROBOT.format(body=LEGACY.format(interface=interface))
    _, findings = check_folder(tmp_path, {"robot.urdf": robot}, select=("U5",))
    assert findings == []


def test_an_ament_package_is_ros2_without_ros2_control(tmp_path):
    robot = HEAD_ROBOT.format(body=LEGACY.format(interface="EffortJointInterface").split("<ros2_control")[0])
    manifest = ("<package format='3'><name>p</name><buildtool_depend>ament_cmake</buildtool_depend>"
                "</package>")
    _, findings = check_folder(tmp_path, {"robot.urdf": robot}, select=("U508",))
    assert [f.code for f in findings] == ["U508"]  # no evidence: the element is ROS 1's
    _, findings = check_folder(tmp_path / "ament", {"robot.urdf": robot, "package.xml": manifest},
                               select=("U508",))
    assert findings == []


def test_unknown_interface_when_ros1_may_read_it_too_is_a_warning_naming_it(tmp_path):
    body = LEGACY.format(interface="hardware_interface/PositionInterface") + \
        '<gazebo><plugin name="c" filename="libgazebo_ros_control.so"/></gazebo>'
    _, findings = check_folder(tmp_path, {"robot.urdf": HEAD_ROBOT.format(body=body)}, select=("U503",))
    assert [(f.code, f.severity) for f in findings] == [("U503", Severity.WARNING)]
    assert findings[0].message.startswith("if ROS 1 reads this transmission (the URDF loads "
                                          "libgazebo_ros_control.so; ros2_control ignores it: the URDF "
                                          "has <ros2_control>)")


@pytest.mark.parametrize("plugin, reported", [
    ('<plugin name="c" filename="libgazebo_ros_control.so"/>', True),
    # a vendor's control plugin (HSR's) may publish every joint: not known, not judged
    ('<plugin name="c" filename="libhsrb_gazebo_ros_control.so"/>', False),
    # Gazebo Sim's joint state publisher publishes every joint unless it names some
    ('<plugin name="c" filename="libgazebo_ros_control.so"/>'
     '<plugin filename="gz-sim-joint-state-publisher-system" name="gz::sim::systems::JointStatePublisher"/>', False),
])
def test_a_passive_joint_is_judged_only_with_a_known_control_plugin(tmp_path, plugin, reported):
    robot = HEAD_ROBOT.format(body=f"<gazebo>{plugin}</gazebo>")
    marks, _ = check_folder(tmp_path, {"robot.urdf": robot}, select=("U507",))
    assert bool(marks) is reported


def test_a_joint_whose_ros2_control_entry_is_misspelt_names_that_entry(tmp_path):
    # PaulRouanet/ros2_control_bolt: <joint name="FLHAA"> for FL_HAA (U511 at the entry); the
    # joint falling limp says which entry was meant for it
    robot = HEAD_ROBOT.format(body='<ros2_control name="s" type="system"><hardware><plugin>'
                                   'mock_components/GenericSystem</plugin></hardware>\n'
                                   '<joint name="headjoint"><command_interface name="position"/>'
                                   '</joint></ros2_control>')
    marks, findings = check_folder(tmp_path, {"robot.urdf": robot}, select=("U507", "U511"))
    assert marks == [("robot.urdf", 3, "U507"), ("robot.urdf", 9, "U511")]
    said = findings[0].message.partition("; the <ros2_control> joint 'headjoint' at ")[2]
    assert said.endswith("robot.urdf:9 names no joint and may be meant for it"), findings[0].message


def test_a_joint_whose_transmission_is_misspelt_names_that_transmission(tmp_path):
    # UM-ARM-Lab/kuka_iiwa_interface's stale victor.urdf: transmissions name iiwa_joint_N (U501
    # at the transmission) for victor_left_arm_joint_N; the joint said to have no transmission
    # names the one meant for it rather than asking for a new one
    robot = HEAD_ROBOT.format(body='<gazebo><plugin name="c" filename="libgazebo_ros_control.so"/>'
                                   '</gazebo>\n<transmission name="t"><type>transmission_interface/'
                                   'SimpleTransmission</type><joint name="head_jiont"><hardwareInterface>'
                                   'hardware_interface/PositionJointInterface</hardwareInterface></joint>'
                                   '<actuator name="m"/></transmission>')
    marks, findings = check_folder(tmp_path, {"robot.urdf": robot}, select=("U507",))
    assert marks == [("robot.urdf", 3, "U507")]
    said = findings[0].message.partition("; transmission 't''s joint 'head_jiont' at ")[2]
    assert said.endswith("robot.urdf:9 names no joint and may be meant for it"), findings[0].message


def test_transmissions_written_before_the_arms_took_their_prefixes_name_each_arm_in_turn(tmp_path):
    # victor.urdf: both arms' transmissions name iiwa_joint_7 (written before the prefixes),
    # the joints are victor_left_arm_joint_7 and victor_right_arm_joint_7 (difflib's ratio
    # 0.57, not close): the first transmission written is meant for the first arm
    arm = '<joint name="victor_{side}_arm_joint_7" type="revolute"><parent link="base_link"/>' \
          '<child link="{side}"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="5" ' \
          'velocity="1"/></joint><link name="{side}"/>\n'
    transmission = '<transmission name="t_{n}"><type>transmission_interface/SimpleTransmission' \
                   '</type><joint name="iiwa_joint_7"><hardwareInterface>hardware_interface/' \
                   'PositionJointInterface</hardwareInterface></joint><actuator name="m"/>' \
                   '</transmission>\n'
    robot = HEAD_ROBOT.format(body=arm.format(side="left") + arm.format(side="right") +
                              '<gazebo><plugin name="c" filename="libgazebo_ros_control.so"/>'
                              '</gazebo>\n' + transmission.format(n=1) + transmission.format(n=2))
    _, findings = check_folder(tmp_path, {"robot.urdf": robot}, select=("U507",))
    said = {f.message.split("'")[1]: f.message.partition("/joint_states; ")[2] for f in findings}
    assert said["victor_left_arm_joint_7"].startswith("transmission 't_1''s joint 'iiwa_joint_7'")
    assert said["victor_right_arm_joint_7"].startswith("transmission 't_2''s joint 'iiwa_joint_7'")


def test_the_added_transmissions_interface_is_the_same_whatever_the_hash_seed(tmp_path):
    """U507's fix gives a new transmission the interface most transmissions use; of interfaces
    used equally often, the first written (it was the first of a set of strings: which one
    changed with PYTHONHASHSEED, from run to run)."""
    import json
    import subprocess
    import sys

    joints = "".join(
        f'<link name="l{i}"/><joint name="j{i}" type="revolute"><parent link="base_link"/>'
        f'<child link="l{i}"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="5" '
        'velocity="1"/></joint>' for i in range(3))
    body = joints + tx(joint="j0", name="a", iface="hardware_interface/VelocityJointInterface") \
        + tx(joint="j1", name="b", iface="hardware_interface/PositionJointInterface") \
        + '<gazebo><plugin name="c" filename="libgazebo_ros_control.so"/></gazebo>'
    robot = tmp_path / "robot.urdf"
    robot.write_text(HEAD_ROBOT.format(body=body))
    (tmp_path / ".git").mkdir()
    chosen = set()
    for seed in range(6):
        done = subprocess.run(
            [sys.executable, "-m", "urdftool", "check", str(robot), "--format", "json",
             "--no-cache", "--select", "U507"], capture_output=True, text=True,
            env={**os.environ, "PYTHONHASHSEED": str(seed)})
        text = json.dumps([d for d in json.loads(done.stdout)["diagnostics"]
                           if "'j2'" in d["message"]])
        chosen.add("Velocity" if "VelocityJointInterface</hardwareInterface>" in text
                   else "Position" if "PositionJointInterface</hardwareInterface>" in text
                   else text)
    assert chosen == {"Velocity"}


def test_a_plugin_s_own_interface_is_claimed_under_the_name_it_exports(tmp_path):
    """gazebo_ros2_control's GazeboSystem reads <command_interface name="position_pid"> and
    exports it as position (gazebo_system.cpp): a position controller claims it, and the name
    is not a misspelt interface (gazebo_ros2_control_demos' vertical cart examples). Another
    plugin exports no such name: there it stays non-standard."""
    from urdftool.description.load import load

    def body(plugin):
        return (f'<ros2_control name="s" type="system"><hardware><plugin>{plugin}</plugin>'
                '</hardware><joint name="head_joint"><command_interface name="position_pid"/>'
                '<state_interface name="position"/></joint></ros2_control>')

    assert "U513" not in codes(tmp_path, body("gazebo_ros2_control/GazeboSystem"))
    assert "U513" in codes(tmp_path, body("mock_components/GenericSystem"))
    from urdftool.description.actuation import ros2_command_interfaces

    robot = HEAD_ROBOT.format(body=body("gazebo_ros2_control/GazeboSystem"))
    (tmp_path / "robot.urdf").write_text(robot)
    assert ros2_command_interfaces(load(str(tmp_path / "robot.urdf"))) == {"head_joint": {"position"}}


def test_an_interface_written_only_in_the_actuator_is_a_warning_to_move_it(tmp_path):
    # the form before ROS Indigo (mastering_ros's diff_wheeled_robot): gazebo_ros_control reads
    # the actuator's interface with a deprecation warning; U503 said the joint had none, an error
    body = ('<transmission name="t"><type>transmission_interface/SimpleTransmission</type>'
            '<joint name="head_joint"/><actuator name="m"><hardwareInterface>EffortJointInterface'
            '</hardwareInterface><mechanicalReduction>1</mechanicalReduction></actuator>'
            '</transmission><gazebo><plugin name="c" filename="libgazebo_ros_control.so"/></gazebo>')
    _, findings = check_folder(tmp_path, {"robot.urdf": HEAD_ROBOT.format(body=body)},
                               select=("U503", "U507", "U508"))
    assert [(f.code, f.severity) for f in findings] == [("U503", Severity.WARNING)]
    assert "its actuator's ('EffortJointInterface')" in findings[0].message
    assert "move it into <joint>" in findings[0].message


def _u515(tmp_path, low: str, high: str, limits: str = 'lower="-1" upper="1"') -> list[str]:
    """U515's messages (min's, then max's) for head_joint's position bounds ``low``, ``high``
    (its URDF ``limits``)."""
    body = f"""<ros2_control name="s" type="system"><hardware><plugin>p/P</plugin></hardware>
      <joint name="head_joint"><command_interface name="position"><param name="min">{low}</param>
      <param name="max">{high}</param></command_interface><state_interface name="position"/></joint>
      </ros2_control>"""
    robot = HEAD_ROBOT.format(body=body).replace('lower="-1" upper="1"', limits)
    _, findings = check_folder(tmp_path, {"robot.urdf": robot}, select=("U515",))
    return sorted((f.message for f in findings), key=lambda m: "max" in m)


def _no_interface_findings(tmp_path, package: str | None) -> list:
    """U503's findings on a head joint's transmission without a <hardwareInterface>, in a
    repository with the ``package`` manifest (None: none)."""
    body = ('<transmission name="t"><type>transmission_interface/SimpleTransmission</type>'
            '<joint name="head_joint"/><actuator name="m"/></transmission>')
    files = {"robot.urdf": HEAD_ROBOT.format(body=body)}
    if package:
        files["package.xml"] = package
    (tmp_path / ".git").mkdir()
    return check_folder(tmp_path, files, select=("U503",))[1]


@pytest.mark.parametrize("package, severity", [
    (None, Severity.WARNING),  # nothing says ROS runs it: Drake reads it without an interface
    ("<package format='2'><name>arm</name><buildtool_depend>catkin</buildtool_depend></package>",
     Severity.ERROR),  # ROS 1's: its ros_control refuses the joint
])
def test_a_transmission_without_an_interface_is_an_error_where_ros_1_runs_it(
        tmp_path, package, severity):
    # kinova_drake's Gen3 models (copied into a pydrake project, no package.xml): seven U503
    # errors each for an interface only ROS 1's ros_control reads
    findings = _no_interface_findings(tmp_path, package)
    assert [(f.code, f.severity) for f in findings] == [("U503", severity)]
    assert findings[0].message.endswith("joint 'head_joint' has no <hardwareInterface>; e.g. "
                                        "hardware_interface/PositionJointInterface")


@pytest.mark.parametrize("package, said", [
    (None, "nothing says ROS runs this robot: no package.xml or manifest.xml; no launch file"),
    # Drake's model collection: a package.xml naming no ROS build tool (sweep: RobotLocomotion/
    # models' allegro hands read "no package.xml" beside drake_models' package.xml)
    ("<package format='2'><name>drake_models</name><version>0.0.0</version></package>",
     "nothing says ROS runs this robot: a package.xml ('drake_models') naming no ROS build "
     "tool (catkin, ament); no launch file"),
    ("<?xml version='1.0'?><project><name>site</name></project>",  # another tool's file
     "nothing says ROS runs this robot: a package.xml that is not a ROS package manifest (no "
     "<package> element); no launch file"),
])
def test_nothing_saying_ros_runs_the_robot_says_what_package_xml_there_is(tmp_path, package, said):
    findings = _no_interface_findings(tmp_path, package)
    assert [(f.code, f.severity) for f in findings] == [("U503", Severity.WARNING)]
    assert said in findings[0].message


def test_a_min_beyond_the_lower_limit_says_commands_go_down_to_it(tmp_path):
    # igus ReBeL's joint2: 'position min is -2.0944, beyond the URDF <limit> (-1.91986);
    # commands up to -2.0944 pass ros2_control' read as if -2.0944 were a ceiling
    low, high = _u515(tmp_path, "-1.2", "1.2")
    assert "position min is -1.2, beyond the URDF <limit> (-1); commands down to -1.2 pass" in low
    assert "position max is 1.2, beyond the URDF <limit> (1); commands up to 1.2 pass" in high


def test_a_ros2_control_bound_of_the_limits_digits_a_power_of_ten_off_is_a_slipped_decimal(tmp_path):
    said = _u515(tmp_path, "-12.5", "1.5", 'lower="-1.25" upper="1.25"')
    assert said[0].endswith("really moves that far: the same digits 10 times apart, a decimal "
                            "point slipped")
    assert said[1].endswith("really moves that far")
def test_a_ros2_control_block_of_3000_joints_looks_for_its_plugin_once(tmp_path, monkeypatch):
    """session 9: each command interface looked for its block's hardware plugin among the
    block's children; 20,000 joints in one <ros2_control> went past the 60 s budget (U015)."""
    from urdftool.description import actuation
    from urdftool.description.actuation import ros2_command_interfaces
    from urdftool.description.load import load

    asked = []

    class Counting(dict):
        def get(self, *args):
            asked.append(args[0])
            return super().get(*args)

    monkeypatch.setattr(actuation, "PLUGIN_INTERFACES", Counting(actuation.PLUGIN_INTERFACES))
    joints = "".join(f'<joint name="j"><command_interface name="position_pid"/></joint>'
                     for _ in range(3000))
    (tmp_path / "robot.urdf").write_text(
        '<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="continuous">'
        '<parent link="a"/><child link="b"/></joint><ros2_control name="s" type="system">'
        '<hardware><plugin>gazebo_ros2_control/GazeboSystem</plugin></hardware>'
        f'{joints}</ros2_control></robot>')
    assert ros2_command_interfaces(load(str(tmp_path / "robot.urdf"))) == {"j": {"position"}}
    assert len(asked) == 1, len(asked)


def test_each_transmissions_joints_are_read_once_per_robot(tmp_path, monkeypatch):
    """Eight rules and loaders ask for the joints of each transmission (1,878 reads of the
    corpus's 248, lxml's findall three times each): read once per robot, the same findings."""
    from urdftool.description import actuation

    read = []
    reading = actuation._transmission_joints
    monkeypatch.setattr(actuation, "_transmission_joints",
                        lambda transmission: read.append(transmission.get("name")) or
                        reading(transmission))
    body = tx() + tx(joint="head_jnt", name="u") + tx(joint="cam_joint", name="v")
    assert codes(tmp_path, body) == ["U501", "U502"]
    assert sorted(read) == ["t", "u", "v"]


def test_no_plugin_as_checked_when_every_launch_file_builds_it_otherwise_is_a_warning(tmp_path):
    # lbr-stack: mode defaults to 'true', which no xacro:if of the hardware macro takes, and
    # every launch file gives mode:=mock|gazebo|hardware (through a mixin of another package)
    from urdftool.lint.engine import CheckOptions, load_and_check

    (tmp_path / ".git").mkdir()
    robot = tmp_path / "arm_description/urdf/arm.urdf.xacro"
    robot.parent.mkdir(parents=True)
    (tmp_path / "arm_description/package.xml").write_text(
        "<package format='2'><name>arm_description</name></package>")
    robot.write_text("""<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="mode" default="true"/>
  <link name="base"/>
  <ros2_control name="arm" type="system"><hardware>
    <xacro:if value="${'$(arg mode)' == 'mock'}"><plugin>mock_components/GenericSystem</plugin></xacro:if>
  </hardware></ros2_control>
</robot>""")
    launch = tmp_path / "arm_description/launch/mock.launch.py"
    launch.parent.mkdir()
    launch.write_text('''
from launch.substitutions import Command
from launch_ros.substitutions import FindPackageShare

def generate_launch_description():
    return [Node(package="robot_state_publisher", executable="robot_state_publisher",
                 parameters=[{"robot_description": Command(["xacro ", FindPackageShare("arm_description"),
                                                            "/urdf/arm.urdf.xacro mode:=mock"])}])]
''')
    findings = [f for f in load_and_check(str(robot), CheckOptions()).findings if f.code == "U514"]
    assert [f.severity for f in findings] == [Severity.WARNING]
    assert "mock.launch.py:7 builds it with mode:=mock, and no launch file as checked" in \
        findings[0].message
    launch.write_text(launch.read_text().replace("mode:=mock", "mode:=true"))
    findings = [f for f in load_and_check(str(robot), CheckOptions()).findings if f.code == "U514"]
    assert [f.severity for f in findings] == [Severity.ERROR]  # built as checked: it holds there


def test_a_custom_interface_is_a_note_a_misspelt_one_a_warning(tmp_path):
    """Legged robots' hardware plugins export ``kp`` and ``kd`` gains, Dynamixel's ``load``
    (22 sweep rows, none a defect): legal names the standard controllers cannot claim, a
    note. ``positon`` is ``position`` misspelt: a warning."""
    def severities(name):
        body = ('<ros2_control name="s" type="system"><hardware><plugin>my/Hardware</plugin>'
                f'</hardware><joint name="head_joint"><command_interface name="{name}"/>'
                '<state_interface name="position"/></joint></ros2_control>')
        _, findings = check_folder(tmp_path, {"robot.urdf": HEAD_ROBOT.format(body=body)})
        return [f.severity for f in findings if f.code == "U513"]

    for name in ("kp", "kd", "load", "stiffness", "external_effort"):
        assert severities(name) == [Severity.INFO], name
    for name in ("positon", "velocty", "efort"):
        assert severities(name) == [Severity.WARNING], name


def test_no_plugin_as_checked_whose_source_gives_one_under_an_argument_is_a_warning(tmp_path):
    # slgrobotics' articubot_one turtle: <plugin> only under xacro:if sim_mode (the real robot
    # is driven by create_driver, no controller manager); its launch file's path is built from
    # a launch argument, so no build of it is known
    from urdftool.lint.engine import CheckOptions, load_and_check

    (tmp_path / ".git").mkdir()
    robot = tmp_path / "robot.urdf.xacro"
    hardware = """<hardware>
    <xacro:unless value="$(arg sim_mode)"><!-- a driver of its own --></xacro:unless>
    <xacro:if value="$(arg sim_mode)"><plugin>gz_ros2_control/GazeboSimSystem</plugin></xacro:if>
  </hardware>"""
    robot.write_text(f"""<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="sim_mode" default="false"/>
  <link name="base"/>
  <ros2_control name="r" type="system">{hardware}</ros2_control>
</robot>""")
    findings = [f for f in load_and_check(str(robot), CheckOptions()).findings if f.code == "U514"]
    assert [(f.line, f.severity) for f in findings] == [(4, Severity.WARNING)]
    assert '<plugin> is under <xacro:if value="$(arg sim_mode)"> (line 6) of ' in \
        findings[0].message and "robot.urdf.xacro, false then" in findings[0].message
    # a condition on no argument or property holds in no build: an error still
    robot.write_text(robot.read_text().replace('value="$(arg sim_mode)"><plugin>',
                                               'value="false"><plugin>'))
    findings = [f for f in load_and_check(str(robot), CheckOptions()).findings if f.code == "U514"]
    assert [f.severity for f in findings] == [Severity.ERROR]


def test_no_plugin_built_otherwise_names_first_the_arguments_its_plugin_depends_on(tmp_path):
    """Automatic Addison's mycobot_ros2: the <plugin> is under xacro:if use_gazebo, and the
    launch file gives add_world, base_link, base_type, flange_link and use_gazebo values known
    only at launch; the message named the first four (alphabetically) and left out use_gazebo,
    the one that decides."""
    from urdftool.lint.engine import CheckOptions, load_and_check

    (tmp_path / ".git").mkdir()
    robot = tmp_path / "arm_description/urdf/arm.urdf.xacro"
    robot.parent.mkdir(parents=True)
    (tmp_path / "arm_description/package.xml").write_text(
        "<package format='2'><name>arm_description</name></package>")
    names = ("add_world", "base_link", "base_type", "flange_link", "use_gazebo")
    robot.write_text('<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                     + "".join(f'<xacro:arg name="{n}" default="false"/>' for n in names) + """
  <link name="base"/>
  <ros2_control name="arm" type="system"><hardware>
    <xacro:if value="$(arg use_gazebo)"><plugin>gz_ros2_control/GazeboSimSystem</plugin></xacro:if>
  </hardware></ros2_control>
</robot>""")
    launch = tmp_path / "arm_description/launch/rsp.launch.py"
    launch.parent.mkdir()
    given = ", ".join(f'" {n}:=", LaunchConfiguration("{n}")' for n in names)
    launch.write_text(f'''
from launch.substitutions import Command, LaunchConfiguration
from launch_ros.substitutions import FindPackageShare

def generate_launch_description():
    return [Node(package="robot_state_publisher", executable="robot_state_publisher",
                 parameters=[{{"robot_description": Command(["xacro ", FindPackageShare("arm_description"),
                                                            "/urdf/arm.urdf.xacro", {given}])}}])]
''')
    findings = [f for f in load_and_check(str(robot), CheckOptions()).findings if f.code == "U514"]
    assert [f.severity for f in findings] == [Severity.WARNING]
    assert "builds it with use_gazebo:=(known only at launch), add_world:=" in \
        findings[0].message, findings[0].message


def test_the_control_plugin_is_looked_for_once_per_robot(tmp_path, monkeypatch):
    """U507 and U603 ask for the plugin that reads the transmissions; each looked in every
    <gazebo> block's plugins (lxml's findall of each): looked for once, the same element."""
    from urdftool.description import actuation
    from urdftool.description.load import load

    looked = []
    looking = actuation._control_plugin
    monkeypatch.setattr(actuation, "_control_plugin", lambda robot: looked.append(1) or
                        looking(robot))
    plugin = '<gazebo><plugin name="c" filename="libgazebo_ros_control.so"/></gazebo>'
    (tmp_path / "robot.urdf").write_text(HEAD_ROBOT.format(body="<gazebo/>" + plugin + tx()))
    robot = load(str(tmp_path / "robot.urdf"))
    first = actuation.control_plugin(robot)
    assert first.get("filename") == "libgazebo_ros_control.so"
    assert actuation.control_plugin(robot) is first
    assert len(looked) == 1
    assert codes(tmp_path, plugin) == ["U507"]


def test_a_bare_interface_name_says_who_warns_about_it():
    """Shadow's hands: 120 U508 lines said "names 'EffortJointInterface' without
    hardware_interface/; write ..." and not why it matters: gazebo_ros_control takes the old
    form with a warning on every start."""
    [message] = case_messages("U508_hardware_interface_prefix.urdf", "U508")
    assert "without hardware_interface/, the old form gazebo_ros_control warns about on every " \
        "start ('Deprecated syntax'); write hardware_interface/EffortJointInterface" in message
