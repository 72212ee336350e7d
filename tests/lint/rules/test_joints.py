"""U2xx joint rules added for issue 14: mimic joints driven outside their limits (U216) and
revolute ranges written in degrees (U217)."""

from __future__ import annotations

import pytest

from crossfile_helpers import check_folder

MIMIC = """<robot name="r">
  <link name="base_link"/><link name="a"/><link name="b"/>
  <joint name="driver" type="{driver_type}"><parent link="base_link"/><child link="a"/>
    <axis xyz="0 0 1"/><limit lower="0" upper="0.8" effort="1" velocity="1"/></joint>
  <joint name="follower" type="revolute"><parent link="base_link"/><child link="b"/>
    <axis xyz="0 0 1"/><limit lower="{lower}" upper="{upper}" effort="1" velocity="1"/>
    <mimic joint="driver" {mimic}/></joint>
</robot>
"""


@pytest.mark.parametrize("driver_type, lower, upper, mimic, reported", [
    ("revolute", 0, 0.88, 'multiplier="-1"', True),     # the shipped gripper: goes to -0.8
    ("revolute", -0.88, 0, 'multiplier="-1"', False),
    ("revolute", 0, 0.88, "", False),                     # multiplier 1, offset 0 by default
    ("revolute", 0, 0.88, 'multiplier="1" offset="0.1"', True),   # up to 0.9
    ("revolute", 0, 0.8, 'multiplier="1" offset="0.0005"', False),  # within 0.1 % of the span
    ("revolute", 0, 0.4, 'multiplier="0.5"', False),
    ("continuous", 0, 0.88, 'multiplier="-1"', False),  # no range to sweep: not judged
    ("revolute", 0, 0.88, 'multiplier="x"', False),       # U207 says it
])
def test_mimic_range_must_fit_the_mimic_joint_limits(tmp_path, driver_type, lower, upper,
                                                      mimic, reported):
    text = MIMIC.format(driver_type=driver_type, lower=lower, upper=upper, mimic=mimic)
    found, findings = check_folder(tmp_path, {"robot.urdf": text}, select=("U216",))
    assert bool(found) == reported, [f.message for f in findings]


REVOLUTE = """<robot name="r">
  <link name="base_link"/><link name="a"/>
  <joint name="j" type="{kind}"><parent link="base_link"/><child link="a"/><axis xyz="0 0 1"/>
    <limit lower="{lower}" upper="{upper}" effort="1" velocity="1"/></joint>
</robot>
"""


@pytest.mark.parametrize("kind, lower, upper, reported", [
    ("revolute", -250, 250, True),
    ("revolute", 0, 30, True),                   # 30 degrees
    ("revolute", -720, 720, True),
    ("revolute", -6.2832, 6.2832, False),        # +-2 pi: a wrist that turns
    ("revolute", -18.85, 18.85, False),          # +-6 pi: three turns each way
    ("revolute", -1e10, 1e10, False),            # a stand-in for unlimited, not degrees
    ("prismatic", 0, 250, False),                # metres: another matter
])
def test_revolute_range_in_degrees(tmp_path, kind, lower, upper, reported):
    text = REVOLUTE.format(kind=kind, lower=lower, upper=upper)
    found, findings = check_folder(tmp_path, {"robot.urdf": text}, select=("U217",))
    assert bool(found) == reported, [f.message for f in findings]
    if reported:
        assert "degrees written as radians" in findings[0].message


def test_the_mimic_joints_are_read_once_per_robot(tmp_path):
    from urdftool.description.load import load
    from urdftool.lint.rules.joints import _mimics

    path = tmp_path / "r.urdf"
    path.write_text(MIMIC.format(driver_type="revolute", lower=0, upper=1, mimic=""))
    robot = load(str(path))
    found = _mimics(robot)
    assert [(joint.get("name"), target) for joint, _, target in found] == [("follower", "driver")]
    assert _mimics(robot) is found  # the four mimic rules share one reading



def test_each_axis_text_is_measured_once_per_robot(tmp_path, monkeypatch):
    """Robots repeat their axes (a 10,000-joint star has two): each distinct text is parsed,
    measured (its scaled length: ~20,000 instructions a joint) and judged once, and the
    joints that write it share that."""
    from conftest import synthetic_robot
    from urdftool.description.load import load
    from urdftool.lint.rules import joints

    measured = []
    monkeypatch.setattr(joints, "length", lambda values: measured.append(values) or 1.0)
    found = joints._axes(load(synthetic_robot(tmp_path, 30, "star")))
    assert len(found) == 29 and sorted(measured) == [(0.0, 1.0, 0.0), (1.0, 0.0, 0.0)]

def _mimic_chain(count: int, loop: bool) -> str:
    """``count`` joints, each mimicking the one before; with ``loop`` the first mimics the
    last."""
    links = "".join(f'<link name="l{i}"/>' for i in range(count + 1))
    joints = "".join(
        f'<joint name="j{i}" type="revolute"><parent link="l0"/><child link="l{i + 1}"/>'
        f'<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
        + (f'<mimic joint="j{(i - 1) % count}"/>' if i or loop else "") + "</joint>"
        for i in range(count))
    return f'<robot name="r">{links}{joints}</robot>'


def test_a_chain_of_3000_mimic_joints_is_walked_once(tmp_path):
    """U211 walked the chain again from every joint, with a list of the joints seen: cubic,
    minutes for 3,000 mimics in a row (the check stopped at its time budget). 20 s is a
    hundred times what the walk takes now, a tenth of what it took."""
    import signal

    def stop(*_):
        raise TimeoutError("U211 took more than 20 s")

    signal.signal(signal.SIGALRM, stop)
    signal.alarm(20)
    try:
        found, _ = check_folder(tmp_path / "chain", {"robot.urdf": _mimic_chain(3000, False)},
                                select=("U211",))
        assert not found
        found, findings = check_folder(tmp_path / "loop",
                                       {"robot.urdf": _mimic_chain(3000, True)},
                                       select=("U211",))
        assert len(found) == 1 and findings[0].message.count(" -> ") == 3000
    finally:
        signal.alarm(0)


@pytest.mark.parametrize("attribute", ["effort", "velocity"])
def test_a_negative_limit_says_what_each_consumer_makes_of_it(tmp_path, attribute):
    """A negative effort or velocity is no 'joint that cannot move': Gazebo and
    gazebo_ros_control enforce no limit, the URDF specification reads its absolute value, and
    Pinocchio refuses the model, which this test checks with the Pinocchio installed. A warning
    (consumers disagree), saying so."""
    pin = pytest.importorskip("pinocchio")
    values = {"effort": "10", "velocity": "2", attribute: "-1"}
    robot = ('<robot name="r"><link name="base_link"/><link name="a"/>\n'
             '<joint name="j" type="revolute"><parent link="base_link"/><child link="a"/>'
             f'<limit lower="0" upper="1" effort="{values["effort"]}" '
             f'velocity="{values["velocity"]}"/></joint></robot>\n')
    with pytest.raises(ValueError, match=f"min_{attribute}"):
        pin.buildModelFromXML(robot)
    found, findings = check_folder(tmp_path, {"robot.urdf": robot}, select=("U212",))
    [finding] = findings
    assert finding.severity.name == "WARNING"
    assert "cannot move" not in finding.message and "enforce no limit" in finding.message
    assert f"Pinocchio refuses the model (min_{attribute} above max_{attribute})" in finding.message
def test_a_zero_velocity_moveit_plans_from_its_joint_limits_yaml_says_so(tmp_path):
    """The JAXA IVR's body joints: velocity="0" in the URDF, and the MoveIt package's
    joint_limits.yaml switching on max_velocity 3.27 for them, which MoveIt plans with: it was
    said that MoveIt's time parameterisation holds them still. What clamps commands to the
    URDF's limit still does (the warning stays)."""
    robot = ('<robot name="r"><link name="base_link"/><link name="head"/>\n'
             '<joint name="head_joint" type="revolute"><parent link="base_link"/>'
             '<child link="head"/><limit lower="0" upper="1" effort="1" velocity="0"/></joint>'
             '</robot>\n')
    srdf = ('<robot name="r">\n<group name="head">\n<chain base_link="base_link" '
            'tip_link="head"/>\n</group>\n</robot>\n')
    files = {"robot.urdf": robot, "r_moveit_config/config/r.srdf": srdf,
             "r_moveit_config/config/joint_limits.yaml":
                 "joint_limits:\n  head_joint:\n    has_velocity_limits: true\n"
                 "    max_velocity: 3.27\n"}
    found, findings = check_folder(tmp_path, files, select=("U212",),
                                   srdf=str(tmp_path / "r_moveit_config/config/r.srdf"))
    [finding] = findings
    assert "MoveIt's time parameterisation" not in finding.message, finding.message
    assert "MoveIt plans with the max_velocity 3.27 of its joint_limits.yaml" in finding.message
    assert "holds the joint still" in finding.message


ZERO_EFFORT = ('<robot name="r"><link name="base_link"/><link name="a"/>\n'
               '<joint name="j" type="revolute"><parent link="base_link"/><child link="a"/>'
               '<limit lower="0" upper="1" effort="0" velocity="2"/></joint>{body}</robot>\n')


@pytest.mark.parametrize("body, files, severity, said", [
    # ROS-Industrial's support packages (fanuc, abb, kuka_experimental, motoman): effort 0 is
    # the exporters' "unknown", and nothing here simulates the robot; MoveIt and
    # robot_state_publisher do not read it
    ("", {}, "INFO", "nothing here simulates the robot"),
    # a Gazebo plugin in the robot: Gazebo clamps the joint's force to 0
    ('<gazebo><plugin name="c" filename="libgazebo_ros_control.so"/></gazebo>', {}, "WARNING",
     "Gazebo (libgazebo_ros_control.so) simulates the robot"),
    # the plugin that clamps the command is named, not the first one written (MIRTE's master:
    # "Gazebo (libgazebo_ros_imu_sensor.so) simulates the robot", an IMU as the witness)
    ('<gazebo reference="a"><sensor name="imu" type="imu"><plugin name="i" '
     'filename="libgazebo_ros_imu_sensor.so"/></sensor></gazebo><gazebo><plugin name="c" '
     'filename="libgazebo_ros2_control.so"/></gazebo>', {}, "WARNING",
     "Gazebo (libgazebo_ros2_control.so) simulates the robot"),
    ('<gazebo reference="a"><sensor name="imu" type="imu"><plugin name="i" '
     'filename="libgazebo_ros_imu_sensor.so"/></sensor></gazebo><gazebo><plugin name="c" '
     'filename="libgazebo_ros_control.so"/></gazebo>', {}, "WARNING",
     "Gazebo (libgazebo_ros_control.so) simulates the robot"),
    # a launch file spawning the file into Gazebo (mathemonads' gazebo.launch)
    ("", {"launch/gazebo.launch": '<launch><param name="robot_description" '
          'textfile="$(find bot)/robot.urdf"/><node pkg="gazebo_ros" type="spawn_model" '
          'name="s" args="-urdf -param robot_description -model r"/></launch>',
          "package.xml": "<package format=\"2\"><name>bot</name><buildtool_depend>catkin"
                         "</buildtool_depend></package>", ".git/HEAD": ""},
     "WARNING", "gazebo.launch spawns it into Gazebo"),
    # both: each said as a sentence of its own (ESA's ExoMy read "Gazebo (...),
    # simulation.launch.py spawns it into Gazebo simulates the robot")
    ('<gazebo><plugin name="c" filename="libgazebo_ros_control.so"/></gazebo>',
     {"launch/gazebo.launch": '<launch><param name="robot_description" '
      'textfile="$(find bot)/robot.urdf"/><node pkg="gazebo_ros" type="spawn_model" '
      'name="s" args="-urdf -param robot_description -model r"/></launch>',
      "package.xml": "<package format=\"2\"><name>bot</name><buildtool_depend>catkin"
                     "</buildtool_depend></package>", ".git/HEAD": ""},
     "WARNING", "; Gazebo (libgazebo_ros_control.so) simulates the robot; gazebo.launch spawns it "
                "into Gazebo"),
    # real hardware (judge17): a <ros2_control> joint taking effort commands from a vendor's
    # hardware plugin; ros2_control's joint limits read <limit effort> from the URDF and clamp
    # the command to it, simulator or not (a note said it mattered only to a simulator)
    ('<ros2_control name="hw" type="system"><hardware><plugin>vendor_driver/ArmHardware'
     '</plugin></hardware><joint name="j"><command_interface name="effort"/>'
     '<state_interface name="position"/></joint></ros2_control>', {}, "WARNING",
     "its <ros2_control> joint takes effort commands (hardware vendor_driver/ArmHardware)"),
    # the same joint commanded by position: the hardware closes the loop, the effort limit
    # clamps no command (a note, as without ros2_control)
    ('<ros2_control name="hw" type="system"><hardware><plugin>vendor_driver/ArmHardware'
     '</plugin></hardware><joint name="j"><command_interface name="position"/>'
     '<state_interface name="position"/></joint></ros2_control>', {}, "INFO",
     "nothing here simulates the robot"),
])
def test_a_zero_effort_matters_only_where_something_simulates_the_robot(
        tmp_path, body, files, severity, said):
    found, findings = check_folder(tmp_path, {"robot.urdf": ZERO_EFFORT.format(body=body), **files},
                                   select=("U212",))
    [finding] = findings
    assert finding.severity.name == severity, finding.message
    assert said in finding.message, finding.message


@pytest.mark.parametrize("lower, upper, swapped", [("inf", "1", False), ("1", "-inf", False),
                                                   ("nan", "1", False), ("2", "1", True),
                                                   ("1e308", "-1e308", True)])
def test_limits_inverted_are_swapped_only_when_both_are_finite(tmp_path, lower, upper, swapped):
    """session 9: lower="inf" upper="1" was U204 with a safe fix swapping them, which `--fix`
    applied: upper="inf", the robot as broken as before (U208 says what is wrong)."""
    text = MIMIC.format(driver_type="revolute", lower=lower, upper=upper, mimic="")
    found, findings = check_folder(tmp_path, {"robot.urdf": text}, select=("U204",))
    assert bool(found) == swapped, [f.message for f in findings]


def test_a_mimic_driven_past_the_largest_float_says_so_not_inf(tmp_path):
    """Session 20 (attack20b; attack20's R1): multiplier and offset 1e308 drive the mimic joint
    to 1.8e308, past what a float holds: U216 said "goes over [1e+308, inf]", an ``inf`` the
    file never wrote. A computed end past the float range is said as such."""
    text = MIMIC.format(driver_type="revolute", lower=0, upper=0.88,
                        mimic='multiplier="1e308" offset="1e308"')
    found, findings = check_folder(tmp_path, {"robot.urdf": text}, select=("U216",))
    [message] = [f.message for f in findings]
    assert "inf" not in message.replace("infinite", "") and "largest float" in message, message
