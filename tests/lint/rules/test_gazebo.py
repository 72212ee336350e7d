"""U61x Gazebo rules: references, diff-drive geometry (ROS 1 and ROS 2 tags), sensors."""

from __future__ import annotations

from pathlib import Path

import pytest

from crossfile_helpers import broken_copy, case_messages, check_folder

WHEELS = """<robot name="r">
  <link name="base_link"/>
  <link name="l"><collision><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision></link>
  <link name="r"><collision><geometry><sphere radius="0.05"/></geometry></collision></link>
  <joint name="lj" type="continuous"><parent link="base_link"/><child link="l"/>
    <origin xyz="0 0.1 0" rpy="0 0 1.5707963"/><axis xyz="1 0 0"/></joint>
  <joint name="rj" type="continuous"><parent link="base_link"/><child link="r"/>
    <origin xyz="0.03 -0.1 0" rpy="0 0 1.5707963"/><axis xyz="1 0 0"/></joint>
  <gazebo><plugin name="d" filename="{filename}">
{tags}
  </plugin></gazebo>
</robot>
"""


@pytest.mark.parametrize("filename, tags, expected", [
    ("libgazebo_ros_diff_drive.so", "<leftJoint>lj</leftJoint><rightJoint>rj</rightJoint>"
     "<wheelSeparation>0.2</wheelSeparation><wheelDiameter>0.1</wheelDiameter>", []),
    ("libgazebo_ros_diff_drive.so", "<left_joint>lj</left_joint><right_joint>rj</right_joint>"
     "<wheel_separation>0.209</wheel_separation><wheel_diameter>0.096</wheel_diameter>", []),
    ("libgazebo_ros_diff_drive.so", "<left_joint>lj</left_joint><right_joint>rj</right_joint>\n"
     "<wheel_separation>0.22</wheel_separation>", [11]),
    ("gz-sim-diff-drive-system", "<left_joint>lj</left_joint><right_joint>rj</right_joint>\n"
     "<wheel_radius>0.1</wheel_radius>", [11]),
])
def test_diff_drive_geometry_along_the_wheel_axis(tmp_path, filename, tags, expected):
    found, _ = check_folder(tmp_path, {"robot.urdf": WHEELS.format(filename=filename, tags=tags)})
    assert [line for _, line, code in found if code == "U614"] == expected
    assert {code for _, _, code in found} <= {"U614"}


def test_force_torque_sensor_on_a_joint_is_fine(tmp_path):
    tags = "<left_joint>lj</left_joint><right_joint>rj</right_joint>"
    robot = WHEELS.format(filename="x", tags=tags).replace(
        "</robot>", '<gazebo reference="lj"><sensor type="force_torque" name="ft"/></gazebo>\n'
                    '<gazebo reference="rj"><sensor type="imu" name="imu"/></gazebo>\n</robot>')
    found, _ = check_folder(tmp_path, {"robot.urdf": robot})
    assert found == [("robot.urdf", 13, "U615")]


def test_a_sensor_in_an_sdf_link_of_a_gazebo_block_is_that_links(tmp_path):
    # hamster_gazebo writes an SDF <link> with its ray sensor (and the <joint> holding it) in a
    # <gazebo> without a reference, which Gazebo copies into the model: the sensor is on it
    tags = "<left_joint>lj</left_joint><right_joint>rj</right_joint>"
    robot = WHEELS.format(filename="x", tags=tags).replace(
        "</robot>", '<gazebo><link name="hokuyo"><sensor type="ray" name="laser"/></link>\n'
                    '<sensor type="imu" name="imu"/></gazebo>\n</robot>')
    found, _ = check_folder(tmp_path, {"robot.urdf": robot}, select=("U615",))
    assert found == [("robot.urdf", 13, "U615")]


def test_frames_are_judged_where_their_plugins_read_them(tmp_path):
    """A sensor plugin's frame (``frame_name``, ``frameName``) in a ``<sensor>``, a nested one
    too, not in a model plugin beside it; a ``bodyName`` anywhere in the block; with the
    sensors, in the one walk of the block the rule makes."""
    robot = """<robot name="r"><link name="a"/><joint name="j" type="fixed"><parent link="a"/>
      <child link="a2"/></joint><link name="a2"/>
      <gazebo reference="a"><plugin name="m" filename="x"><frame_name>nowhere</frame_name></plugin>
        <sensor type="imu" name="s"><sensor type="imu" name="t"><plugin name="p" filename="x">
          <frame_name>missing_frame</frame_name></plugin></sensor></sensor>
        <plugin name="b" filename="x"><bodyName>no_body</bodyName></plugin></gazebo>
      <gazebo reference="j"><sensor type="imu" name="u"><plugin name="q" filename="x">
        <frameName>a2</frameName></plugin></sensor></gazebo></robot>"""
    found, findings = check_folder(tmp_path, {"robot.urdf": robot}, select=("U615",))
    assert found == [("robot.urdf", 5, "U615"), ("robot.urdf", 6, "U615"),
                     ("robot.urdf", 7, "U615")]
    assert [f.message.split(";")[0] for f in findings] == [
        "<frame_name> 'missing_frame' is not a link, so TF cannot place the data stamped with it",
        "<bodyName> 'no_body' is not a link, so TF cannot place the data stamped with it",
        "sensor 'u' is on joint 'j', not a link"]


def test_diffbot_wheel_separation_changed(tmp_path):
    findings = broken_copy(tmp_path, "diffbot", "diffbot.urdf.xacro",
                           "<wheel_separation>${wheel_separation}</wheel_separation>",
                           "<wheel_separation>${wheel_separation * 1.1}</wheel_separation>")
    assert [(f.code, f.file.endswith("diffbot.urdf.xacro")) for f in findings] == [("U614", True)]
    assert "is 0.286 m but the URDF gives 0.26 m (+10.0 %)" in findings[0].message


def test_diffbot_camera_reference_misspelt(tmp_path):
    findings = broken_copy(tmp_path, "diffbot", "diffbot.urdf.xacro", '<gazebo reference="camera_link">',
                           '<gazebo reference="camera">')
    assert [f.code for f in findings] == ["U611"]
    assert "did you mean 'camera_link'" in findings[0].message


def test_an_unknown_reference_offers_the_joints_it_may_name_too(tmp_path):
    """A <gazebo reference> names a link or a joint (a joint's <provideFeedback>): the
    message said so and offered links alone (sweep: go1's 'names no link or joint; ...
    available links: FL_calf, ...'), and looked for a misspelt joint's name among links."""
    [message] = case_messages("U611_gazebo_unknown_reference.urdf", "U611")
    assert message == ("<gazebo reference='hed'> names no link or joint, so Gazebo drops the "
                       "block: its sensors, plugins, friction and colours never apply; did you "
                       "mean 'head'? available links: base_link, cam, head; available joints: "
                       "cam_joint, head_joint")
    case = Path(__file__).parents[2] / "cases" / "U611_gazebo_unknown_reference.urdf"
    text = case.read_text().replace('reference="hed"', 'reference="head_jiont"')
    _, [finding] = check_folder(tmp_path, {"robot.urdf": text}, select=("U611",))
    assert finding.message.startswith("<gazebo reference='head_jiont'> names no link or joint, "
                                      "so Gazebo drops the block: its sensors, plugins, friction "
                                      "and colours never apply; did you mean 'head_joint'? "
                                      "available links: ")


def test_wheel_not_continuous_says_what_would_be_right():
    messages = case_messages("U613_diff_drive_joint_not_continuous.urdf", "U613")
    assert messages == ["diff-drive wheel joint 'left_wheel_joint' is revolute, not continuous; "
                        'make it type="continuous" (a wheel turns without limit)']


def test_unknown_frame_name_suggests_the_sensor_link():
    messages = case_messages("U615_sensor_unknown_link.urdf", "U615")
    assert "<frame_name> 'cam_optical' is not a link, so TF cannot place the data stamped with it; " \
           "use 'cam', the link it sits on, or add a link 'cam_optical'" in messages


def test_a_ros1_frame_name_without_the_namespace_its_link_carries_names_the_tf_prefix(tmp_path):
    """RotorS writes its links ``${namespace}/camera_depth_optical_center_link`` and the
    openni plugin's ``<frameName>camera_depth_optical_center_link</frameName>``: ROS 1's
    sensor plugins prefix the frame with their ``tf_prefix`` parameter (spawn_mav.launch sets
    it, from $(optenv ROS_NAMESPACE)), so the error held only without it: a warning naming
    it. A frame no link ends with stays an error."""
    from urdftool.diagnostics import Severity

    robot = """<robot name="r"><link name="ns/base"/><link name="ns/cam"/>
      <joint name="j" type="fixed"><parent link="ns/base"/><child link="ns/cam"/></joint>
      <gazebo reference="ns/cam"><sensor type="depth" name="d">
        <plugin name="p" filename="libgazebo_ros_openni_kinect.so">
          <frameName>{frame}</frameName></plugin></sensor></gazebo></robot>"""
    found, findings = check_folder(tmp_path, {"robot.urdf": robot.format(frame="cam")},
                                   select=("U615",))
    assert [(f.severity, "tf_prefix parameter is 'ns'" in f.message) for f in findings] == \
        [(Severity.WARNING, True)], findings
    found, findings = check_folder(tmp_path / "b", {"robot.urdf": robot.format(frame="camx")},
                                   select=("U615",))
    assert [f.severity for f in findings] == [Severity.ERROR]
    # with <robotNamespace>ns</robotNamespace> the plugin falls back to it: right as written
    spaced = robot.format(frame="cam").replace(
        "<frameName>", "<robotNamespace>/ns</robotNamespace><frameName>")
    found, findings = check_folder(tmp_path / "c", {"robot.urdf": spaced}, select=("U615",))
    assert findings == []


def test_vertical_wheel_axis_is_reported_and_separation_still_measured(tmp_path):
    # issue 14: a wheel whose axis is vertical made the separation along it 0 and the check skip
    robot = WHEELS.format(filename="libgazebo_ros_diff_drive.so", tags=(
        "<left_joint>lj</left_joint><right_joint>rj</right_joint>\n"
        "<wheel_separation>0.3</wheel_separation>")).replace('<axis xyz="1 0 0"/>', '<axis xyz="0 0 1"/>')
    found, findings = check_folder(tmp_path, {"robot.urdf": robot})
    assert ("robot.urdf", 11, "U614") in found
    assert [f.message for f in findings if f.code == "U617" and "not a horizontal axis" in f.message]


def test_left_wheel_on_the_right_side(tmp_path):
    robot = WHEELS.format(filename="libgazebo_ros_diff_drive.so",
                          tags="<left_joint>rj</left_joint><right_joint>lj</right_joint>")
    found, findings = check_folder(tmp_path, {"robot.urdf": robot})
    assert found == [("robot.urdf", 10, "U617")]
    assert "left wheel 'rj' is on the right (y = -0.1 m" in findings[0].message


def test_axles_along_x_are_said_to_be_not_sideways_rather_than_left_on_the_right(tmp_path):
    """ros2_jazzy_p3at turns its base_link -90 degrees under base_footprint, so the axles point
    along the root's x and the wheels' y differ by their front/back offset: U617 said 'left
    wheel is on the right (y = 1.86 m, right wheel at y = 1.87 m); swap them', which swapping
    does not mend."""
    robot = WHEELS.format(filename="libgazebo_ros_diff_drive.so",
                          tags="<left_joint>lj</left_joint><right_joint>rj</right_joint>")
    for old, new in (('xyz="0 0.1 0" rpy="0 0 1.5707963"', 'xyz="0.1 0 0"'),
                     ('xyz="0.03 -0.1 0" rpy="0 0 1.5707963"', 'xyz="-0.1 0.01 0"')):
        robot = robot.replace(old, new)
    found, findings = check_folder(tmp_path, {"robot.urdf": robot})
    assert found == [("robot.urdf", 10, "U617")]
    assert "wheel joint 'lj' turns about (1, 0, 0) in the root frame, not sideways" in \
        findings[0].message and "swap" not in findings[0].message


def test_plugin_base_frame_must_be_a_link(tmp_path):
    robot = WHEELS.format(filename="libgazebo_ros_diff_drive.so", tags=(
        "<left_joint>lj</left_joint><right_joint>rj</right_joint>\n"
        "<robot_base_frame>base_footprint</robot_base_frame><odometry_frame>odom</odometry_frame>"))
    found, _ = check_folder(tmp_path, {"robot.urdf": robot})
    assert found == [("robot.urdf", 11, "U616")]


def test_diff_drive_plugin_wheels_count_as_actuated(tmp_path):
    # gazebo_ros_control is loaded and only the head has a transmission: the wheels the
    # diff-drive plugin turns are driven, not limp (U507 used to list them)
    robot = WHEELS.format(filename="libgazebo_ros_diff_drive.so",
                          tags="<left_joint>lj</left_joint><right_joint>rj</right_joint>").replace(
        "</robot>", '<gazebo><plugin name="c" filename="libgazebo_ros_control.so"/></gazebo>\n'
                    '<link name="h"/><joint name="hj" type="continuous"><parent link="base_link"/>'
                    '<child link="h"/></joint>\n</robot>')
    found, _ = check_folder(tmp_path, {"robot.urdf": robot}, select=("U5", "U60", "U61"))
    assert found == [("robot.urdf", 13, "U507")]  # hj only


def test_a_frame_the_plugin_of_the_robots_ros_version_does_not_read_is_not_judged(tmp_path):
    """ros2_jazzy_p3at's pioneer3at.urdf (a ROS 2 package) keeps ROS 1's camera
    ``<frameName>camera</frameName>`` and ROS 1's ``libgazebo_ros_laser.so`` with
    ``<frameName>base_laser</frameName>``: the ROS 2 camera ignores frameName (U640 says so)
    and ROS 2 has no such laser plugin, so no data is stamped with either frame. The same
    names in a ROS 1 robot are errors."""
    robot = """<robot name="r"><link name="base"/><link name="cam"/><link name="hokuyo"/>
      <joint name="j" type="fixed"><parent link="base"/><child link="cam"/></joint>
      <joint name="k" type="fixed"><parent link="base"/><child link="hokuyo"/></joint>
      <gazebo reference="cam"><sensor type="camera" name="c">
        <plugin name="p" filename="libgazebo_ros_camera.so"><frameName>camera</frameName>
        </plugin></sensor></gazebo>
      <gazebo reference="hokuyo"><sensor type="ray" name="l">
        <plugin name="q" filename="libgazebo_ros_laser.so"><frameName>base_laser</frameName>
        </plugin></sensor></gazebo></robot>"""
    package = """<package format="3"><name>p</name><version>0.0.0</version><description>d</description>
      <maintainer email="a@b.c">m</maintainer><license>BSD</license>
      <buildtool_depend>{tool}</buildtool_depend><export><build_type>{tool}</build_type></export>
    </package>"""
    found, _ = check_folder(tmp_path / "ros2", {"robot.urdf": robot,
                                                "package.xml": package.format(tool="ament_cmake")},
                            select=("U615", "U640"))
    assert found == [("robot.urdf", 5, "U640")]
    found, _ = check_folder(tmp_path / "ros1", {"robot.urdf": robot,
                                                "package.xml": package.format(tool="catkin")},
                            select=("U615",))
    assert found == [("robot.urdf", 5, "U615"), ("robot.urdf", 8, "U615")]


def test_ros1_gazebo_ros_control_in_a_ros2_robot(tmp_path):
    robot = WHEELS.format(filename="libgazebo_ros_control.so", tags="").replace("</robot>", """
      <ros2_control name="s" type="system"><hardware><plugin>gazebo_ros2_control/GazeboSystem</plugin></hardware>
        <joint name="lj"><command_interface name="velocity"/><state_interface name="velocity"/></joint>
        <joint name="rj"><command_interface name="velocity"/><state_interface name="velocity"/></joint>
      </ros2_control>
    </robot>""")
    found, findings = check_folder(tmp_path, {"robot.urdf": robot})
    assert found == [("robot.urdf", 9, "U618")]
    assert "use libgazebo_ros2_control.so" in findings[0].message


def test_caster_joint_naming_a_missing_link_is_not_a_crash(tmp_path):
    # found by make fuzz (tests/fuzz/regressions/120a502091a0): a joint whose child link does not
    # exist, named like a caster, crashed U617's caster check (KeyError, a U900)
    robot = WHEELS.format(filename="libgazebo_ros_diff_drive.so", tags=(
        "<left_joint>lj</left_joint><right_joint>rj</right_joint>")).replace(
        "</robot>", '<joint name="cj" type="fixed"><parent link="base_link"/>'
                    '<child link="front_caster"/></joint>\n</robot>')
    found, _ = check_folder(tmp_path, {"robot.urdf": robot}, select=("U1", "U6", "U9"))
    assert found == [("robot.urdf", 12, "U105")]


def test_a_frame_under_a_tf_prefix_is_the_link(tmp_path):
    """sjtu_drone: <frame_name>${namespace}/base_link</frame_name>, robot_state_publisher given
    frame_prefix NAMESPACE/ by the launch file: TF knows the frame. ROS 2's tf2 refuses a
    leading '/' (the drone's own namespace was '/simple_drone')."""
    tags = "<left_joint>lj</left_joint><right_joint>rj</right_joint>"
    sensor = ('<gazebo reference="base_link"><sensor type="imu" name="imu"><plugin name="p" '
              'filename="libgazebo_ros_imu_sensor.so"><frame_name>{}</frame_name></plugin>'
              '</sensor></gazebo>\n</robot>')
    robot = WHEELS.format(filename="x", tags=tags)
    for frame, expected in (("drone/base_link", []), ("drone/base_lnk", [12]), ("/drone/base_link", [12])):
        found, findings = check_folder(tmp_path / str(len(expected)) / frame.replace("/", "_"),
                                       {"robot.urdf": robot.replace("</robot>", sensor.format(frame))},
                                       select=("U615",))
        assert [line for _, line, _ in found] == expected, [f.message for f in findings]
    assert "starts with '/'" in findings[0].message


def test_the_gazebo_blocks_are_walked_once_for_plugins_sensors_and_frames(tmp_path, monkeypatch):
    """The plugins, the sensors and U615's frames come from one walk of each <gazebo> block
    (it walked the corpus's 806 blocks three times), whose tags hold U615's frame tags."""
    from urdftool.description import actuation
    from urdftool.description.load import load
    from urdftool.description.robot import Robot
    from urdftool.lint.rules import gazebo

    assert set(gazebo.FRAME_TAGS) <= set(actuation.GAZEBO_WALKED)
    asked = []
    children = Robot.children
    monkeypatch.setattr(Robot, "children", lambda robot, tag: asked.append(tag) or
                        children(robot, tag))
    (tmp_path / "r.urdf").write_text(
        '<robot name="r"><link name="base"/><gazebo reference="base"><sensor name="s" '
        'type="camera"><plugin name="p" filename="libgazebo_ros_camera.so"><frame_name>nowhere'
        '</frame_name></plugin></sensor></gazebo></robot>')
    robot = load(str(tmp_path / "r.urdf"))
    plugins, sensors = actuation.gazebo_plugins(robot), actuation.gazebo_sensors(robot)
    assert [p.get("name") for p in plugins] == ["p"]
    assert [s.get("name") for _, s in sensors] == ["s"]
    assert [(e.tag, m.split(";")[0]) for e, m in gazebo.sensor_unknown_link(robot)] == [
        ("frame_name", "<frame_name> 'nowhere' is not a link, so TF cannot place the data "
                       "stamped with it")]
    assert asked.count("gazebo") == 1, asked
