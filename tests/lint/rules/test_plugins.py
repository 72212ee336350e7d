"""U640-U643 (Gazebo plugins per version) and U517-U519 (ros2_control and its simulator plugin)."""

from __future__ import annotations

from crossfile_helpers import HEAD_ROBOT, check_folder
from urdftool.description import gazebo_plugins as vocabulary
from urdftool.diagnostics import Severity

PACKAGE = """<package format="3"><name>bot</name><version>0.0.0</version><description>d</description>
  <maintainer email="a@b.c">a</maintainer><license>BSD</license>
  <buildtool_depend>{tool}</buildtool_depend></package>"""
DIFF_DRIVE = """<gazebo><plugin name="dd" filename="libgazebo_ros_diff_drive.so">
    {tags}
  </plugin></gazebo>"""


def _check(tmp_path, body, files=None, select=("U517", "U518", "U519", "U64")):
    return check_folder(tmp_path, {"robot.urdf": HEAD_ROBOT.format(body=body), **(files or {})},
                        select=select)


def test_the_other_rosversions_names_with_the_version_from_the_package(tmp_path):
    body = DIFF_DRIVE.format(tags="<leftJoint>head_joint</leftJoint><wheelTorque>5</wheelTorque>")
    found, findings = _check(tmp_path, body, {"package.xml": PACKAGE.format(tool="ament_cmake")})
    assert [f.code for f in findings] == ["U640", "U640"]
    assert findings[0].severity == Severity.ERROR and "write <left_joint>" in findings[0].message
    assert "its package builds with ament_cmake" in findings[0].message
    # ROS 2's diff drive has no torque limit of that name: nothing of the value is lost
    assert findings[1].severity == Severity.WARNING and "remove it" in findings[1].message
    # the evidence each line of the plugin gives, named for a report to say once per file
    [(kind, evidence, _)] = findings[0].repeated
    assert kind == "why" and evidence.startswith(" (its package builds with ament_cmake")
    assert findings[1].repeated == findings[0].repeated and evidence in findings[1].message


def test_a_ros1_camera_value_that_asks_for_what_ros2_does_without_it_loses_nothing(tmp_path):
    # HrithikDhongadi's diff drive (ROS 2): <Cx>0</Cx> asks ROS 1's camera to compute the
    # centre, which ROS 2's computes with no <cx>; writing <cx>0</cx> would break it
    body = """<gazebo reference="head"><sensor type="depth" name="c"><camera><image><width>640</width>
      </image></camera><plugin name="cam" filename="libgazebo_ros_camera.so"><Cx>0</Cx>
      <Cy>320.5</Cy><focalLength>0.0</focalLength></plugin></sensor></gazebo>"""
    found, findings = _check(tmp_path, body, {"package.xml": PACKAGE.format(tool="ament_cmake")})
    said = {f.message.split("<", 2)[1].split(">")[0]: f for f in findings}
    assert sorted(said) == ["Cx", "Cy", "focalLength"]
    for name in ("Cx", "focalLength"):
        assert said[name].severity == Severity.WARNING, said[name].message
        assert "loses nothing" in said[name].message and "write <" not in said[name].message
    assert said["Cy"].severity == Severity.ERROR and "write <cy>" in said["Cy"].message


def test_a_ros1_robot_with_ros2_names(tmp_path):
    body = DIFF_DRIVE.format(tags="<left_joint>head_joint</left_joint><ros><namespace>x</namespace></ros>")
    found, findings = _check(tmp_path, body, {"package.xml": PACKAGE.format(tool="catkin")})
    assert [f.code for f in findings] == ["U640", "U640"]
    assert "write <leftJoint>" in findings[0].message and "write <robotNamespace>" not in findings[0].message


def test_without_a_version_only_a_mixed_plugin_is_reported(tmp_path):
    consistent = DIFF_DRIVE.format(tags="<leftJoint>head_joint</leftJoint><wheelSeparation>1</wheelSeparation>")
    assert _check(tmp_path / "a", consistent)[0] == []
    mixed = DIFF_DRIVE.format(tags="<leftJoint>head_joint</leftJoint><wheel_separation>1</wheel_separation>")
    found, findings = _check(tmp_path / "b", mixed)
    assert [f.code for f in findings] == ["U640"] and findings[0].severity == Severity.WARNING
    assert "<leftJoint>" in findings[0].message and "<wheel_separation>" in findings[0].message


def test_evidence_that_disagrees_gives_no_version(tmp_path):
    # a ROS 1 controller file beside a package that builds with ament: no version
    body = DIFF_DRIVE.format(tags="<leftJoint>head_joint</leftJoint>")
    files = {"package.xml": PACKAGE.format(tool="ament_cmake"),
             "config/c.yaml": "jsc: {type: joint_state_controller/JointStateController, publish_rate: 50}\n"}
    assert _check(tmp_path, body, files)[0] == []


def test_near_misses_and_what_is_not_one(tmp_path):
    tags = ("<leftJoint>head_joint</leftJoint><wheelSeperation>1</wheelSeperation>"
            "<alwaysOn>true</alwaysOn><legacyMode>false</legacyMode><odometryrate>5</odometryrate>")
    found, findings = _check(tmp_path, DIFF_DRIVE.format(tags=tags))
    assert [f.code for f in findings] == ["U641"]  # alwaysOn, legacyMode: no near miss
    assert "did you mean <wheelSeparation>" in findings[0].message


def test_classic_names_in_a_gz_system(tmp_path):
    body = """<gazebo><plugin filename="gz-sim-diff-drive-system" name="gz::sim::systems::DiffDrive">
      <left_joint>head_joint</left_joint><wheel_diameter>0.2</wheel_diameter><name>x</name>
    </plugin></gazebo>"""
    found, findings = _check(tmp_path, body)
    assert [f.code for f in findings] == ["U641"]  # <name>: no gazebo_ros_diff_drive name
    assert "Gazebo Classic's name" in findings[0].message


def test_a_plugin_is_made_once_for_each_library_and_read_the_same():
    """The rules ask ``plugin`` of each ``<plugin>`` element, several times (613 asks on the
    corpus): the same Plugin for every element loading the same library, whatever its path."""
    from lxml import etree

    first, second = (etree.fromstring(f'<plugin name="d" filename="{name}"/>') for name in
                     ("libgazebo_ros_diff_drive.so", "/opt/ros/lib/libgazebo_ros_diff_drive.so"))
    made = vocabulary.plugin(first)
    assert made is vocabulary.plugin(second)
    assert (made.key, made.family) == ("gazebo_ros_diff_drive", "classic")
    assert "wheelSeparation" in made.versions["ros1"]
    assert vocabulary.plugin(etree.fromstring('<plugin filename="libvendor.so"/>')) is None


def test_plugin_keys():
    assert vocabulary.plugin_key("libgazebo_ros_diff_drive.so") == "gazebo_ros_diff_drive"
    assert vocabulary.plugin_key("libignition-gazebo6-diff-drive-system.so") == "gz-sim:diff-drive"
    assert vocabulary.plugin_key("gz-sim-diff-drive-system") == "gz-sim:diff-drive"
    assert vocabulary.plugin_key("libgz_ros2_control-system.so") == "gz_ros2_control-system"
    assert vocabulary.plugin_key("libvendor_plugin.so") is None
    assert vocabulary.counterpart("robotNamespace", {"ros", "left_joint"}, "ros2") == "<ros><namespace>"


def test_gazebo_ros_control_missing_or_without_filename(tmp_path):
    tx = ('<transmission name="t"><type>transmission_interface/SimpleTransmission</type>'
          '<joint name="head_joint"><hardwareInterface>hardware_interface/PositionJointInterface'
          '</hardwareInterface></joint><actuator name="m"/></transmission>'
          '<gazebo reference="head"><material>Gazebo/White</material></gazebo>')
    yaml = {"config/c.yaml": "h: {type: position_controllers/JointPositionController, joint: head_joint}\n"}
    found, _ = _check(tmp_path / "a", tx, yaml)
    assert found == [("c.yaml", 1, "U642")]
    nameless = tx + '<gazebo><plugin name="gazebo_ros_control"><robotNamespace>/</robotNamespace></plugin></gazebo>'
    found, findings = _check(tmp_path / "b", nameless, yaml)
    assert [f.code for f in findings] == ["U642"] and "has no filename" in findings[0].message
    loaded = tx + '<gazebo><plugin name="g" filename="libgazebo_ros_control.so"/></gazebo>'
    assert _check(tmp_path / "c", loaded, yaml)[0] == []


def test_no_gazebo_ros_control_wanted_in_a_urdf_when_gazebo_spawns_an_sdf(tmp_path):
    """quad-sdk: the launch file spawns robot_description_sdf (an SDF that loads
    gazebo_ros_control itself) into Gazebo; the URDF feeds robot_state_publisher only. A launch
    file spawning the robot description (-urdf -param robot_description) wants it."""
    tx = ('<transmission name="t"><type>transmission_interface/SimpleTransmission</type>'
          '<joint name="head_joint"><hardwareInterface>hardware_interface/PositionJointInterface'
          '</hardwareInterface></joint><actuator name="m"/></transmission>'
          '<gazebo reference="head"><material>Gazebo/White</material></gazebo>')
    launch = """<launch>
      <param name="robot_description" command="cat $(find bot)/robot.urdf"/>
      <param name="robot_description_sdf" textfile="$(find bot)/robot.sdf"/>
      <rosparam file="$(find bot)/config/c.yaml" command="load"/>
      <node name="spawn" pkg="gazebo_ros" type="spawn_model" args="{args} -model r"/>
    </launch>"""
    files = {"config/c.yaml": "h: {type: position_controllers/JointPositionController, joint: head_joint}\n",
             "package.xml": PACKAGE.format(tool="catkin"), ".git/HEAD": ""}
    sdf = {**files, "launch/sim.launch": launch.format(args="-sdf -param robot_description_sdf")}
    assert _check(tmp_path / "sdf", tx, sdf)[0] == []
    urdf = {**files, "launch/sim.launch": launch.format(args="-urdf -param robot_description")}
    assert _check(tmp_path / "urdf", tx, urdf)[0] == [("c.yaml", 1, "U642")]


ROS2_CONTROL = """<ros2_control name="s" type="system"><hardware><plugin>{hardware}</plugin></hardware>
    <joint name="head_joint"><command_interface name="position"/>{state}</joint></ros2_control>"""
STATE = '<state_interface name="position"/>'


def _plugin(filename, parameters="/nonexistent/outside/c.yaml"):
    return (f'<gazebo><plugin name="c" filename="{filename}"><parameters>{parameters}</parameters>'
            '</plugin></gazebo>')


def test_parameters_paths(tmp_path):
    control = ROS2_CONTROL.format(hardware="gazebo_ros2_control/GazeboSystem", state=STATE)
    inside = tmp_path / "a" / "config" / "missing.yaml"
    cases = {"package://bot/config/c.yaml": Severity.ERROR, "config/c.yaml": Severity.WARNING,
             str(inside): Severity.ERROR, "/nonexistent/outside/c.yaml": None}
    for value, severity in cases.items():
        (tmp_path / "a" / ".git").mkdir(parents=True, exist_ok=True)
        _, findings = _check(tmp_path / "a", control + _plugin("libgazebo_ros2_control.so", value))
        assert [f.severity for f in findings] == ([severity] if severity else []), value
        if value.startswith("package://"):  # the path to write, as xacro makes it (one owner)
            assert findings[0].message.endswith("write $(find bot)/config/c.yaml"), findings


def test_a_joint_commanded_and_never_read(tmp_path):
    found, findings = _check(tmp_path, ROS2_CONTROL.format(hardware="mock_components/GenericSystem", state=""))
    assert [f.code for f in findings] == ["U517"]
    assert _check(tmp_path / "b", ROS2_CONTROL.format(hardware="mock_components/GenericSystem",
                                                      state=STATE))[0] == []


def test_simulator_hardware_and_the_plugin_that_loads_it(tmp_path):
    def codes(hardware, plugin, folder):
        body = ROS2_CONTROL.format(hardware=hardware, state=STATE) + plugin
        return [f.code for f in _check(tmp_path / folder, body, select=("U518", "U519"))[1]]

    assert codes("gazebo_ros2_control/GazeboSystem", _plugin("libgz_ros2_control-system.so"), "a") == ["U518"]
    # from Jazzy gz_ros2_control loads the Ignition name too; Humble's ign plugin not the gz one
    assert codes("ign_ros2_control/IgnitionSystem", _plugin("libgz_ros2_control-system.so"), "b") == []
    assert codes("gz_ros2_control/GazeboSimSystem", _plugin("libign_ros2_control-system.so"), "c") == ["U518"]
    assert codes("gz_ros2_control/GazeboSimSystem", "", "d") == ["U519"]
    assert codes("mock_components/GenericSystem", "", "e") == []
    # ROS 1's gazebo_ros_control in a ROS 2 robot is U618's to name
    assert codes("gazebo_ros2_control/GazeboSystem",
                 '<gazebo><plugin name="g" filename="libgazebo_ros_control.so"/></gazebo>', "f") == []


def test_a_joint_read_by_a_sensor_component_has_its_state(tmp_path):
    """ros2_control_demos example 14: an actuator without feedback, and a sensor component
    reporting the same joint's position: joint_state_broadcaster publishes it (no U517)."""
    actuator = ROS2_CONTROL.format(hardware="demo/ActuatorWithoutFeedback", state="")
    sensor = ('<ros2_control name="p" type="sensor"><hardware><plugin>demo/Sensor</plugin>'
              f'</hardware><joint name="head_joint">{STATE}</joint></ros2_control>')
    assert _check(tmp_path, actuator + sensor)[0] == []


def test_a_mimic_joint_is_placed_from_the_joint_it_mimics(tmp_path):
    """Seeed's starai cello arm: the gripper's joint7_right, a URDF <mimic> of joint7_left,
    commanded through gazebo_ros2_control's ``mimic`` parameter with no state interface of its
    own: robot_state_publisher places it from joint7_left's state (no U517); a mimic of a
    joint with no state interface is still reported."""
    finger = ('<link name="finger"/><joint name="finger_joint" type="revolute"><parent link="head"/>'
              '<child link="finger"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="5" '
              'velocity="1"/><mimic joint="head_joint"/></joint>')
    control = ('<ros2_control name="s" type="system"><hardware><plugin>gazebo_ros2_control/GazeboSystem'
               '</plugin></hardware><joint name="head_joint"><command_interface name="position"/>{state}'
               '</joint><joint name="finger_joint"><command_interface name="position"/>'
               '<param name="mimic">head_joint</param></joint></ros2_control>')
    assert _check(tmp_path / "a", finger + control.format(state=STATE), select=("U517",))[1] == []
    findings = _check(tmp_path / "b", finger + control.format(state=""), select=("U517",))[1]
    assert sorted(f.message.split("'")[1] for f in findings) == ["finger_joint", "head_joint"]


def test_a_near_miss_of_a_name_the_plugin_is_given_is_not_suggested(tmp_path):
    """ESA's ExoMy gives gazebo_ros_p3d <body_name> and <body_tf_name>: the second is ignored,
    and 'did you mean <body_name>?' suggested the name given one line above it."""
    body = """<gazebo><plugin name="p3d" filename="libgazebo_ros_p3d.so">
      <body_name>head</body_name><body_tf_name>odom</body_tf_name><frame_name>map</frame_name>
    </plugin></gazebo>"""
    found, findings = _check(tmp_path, body, {"package.xml": PACKAGE.format(tool="ament_cmake")})
    [finding] = [f for f in findings if f.code == "U641"]
    assert "did you mean" not in finding.message, finding.message
    assert finding.message.endswith("does not read <body_tf_name>, so it is ignored; "
                                    "<body_name>, the name it reads, is given beside it: remove "
                                    "<body_tf_name>"), finding.message
