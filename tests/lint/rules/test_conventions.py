"""U417-U421: ROS frame conventions and wheels, on small inline robots (each rule's case file is
in tests/cases); what must not be reported."""

from __future__ import annotations

import pytest

from urdftool.lint.engine import CheckOptions, Selection, load_and_check

CODES = ("U417", "U418", "U419", "U420", "U421")
WHEEL = """<link name="{side}_wheel">
  <inertial><mass value="0.2"/>
    <inertia ixx="{ixx}" ixy="0" ixz="0" iyy="{iyy}" iyz="0" izz="{izz}"/></inertial>
  <collision><origin rpy="{rpy}"/><geometry>{geometry}</geometry></collision></link>
<joint name="{side}_wheel_joint" type="continuous"><parent link="base_link"/>
  <child link="{side}_wheel"/><origin xyz="0 {y} {z}"/><axis xyz="0 1 0"/></joint>"""


def _found(tmp_path, body: str, codes=CODES) -> list[tuple[str, str]]:
    (tmp_path / "r.urdf").write_text(f'<robot name="r">{body}</robot>')
    result = load_and_check(str(tmp_path / "r.urdf"), CheckOptions(selection=Selection(codes)))
    return [(f.code, f.message) for f in result.findings]


def _base(z=0.05, footprint=True, caster_z=None, wheel=None) -> str:
    wheel = wheel or {}
    parts = ['<link name="base_link"><collision><geometry><box size="0.3 0.2 0.04"/></geometry>'
             '</collision></link>']
    if footprint:
        parts.append('<link name="base_footprint"/><joint name="base_footprint_joint" '
                     f'type="fixed"><parent link="base_footprint"/><child link="base_link"/>'
                     f'<origin xyz="0 0 {z}"/></joint>')
    for side, y in (("left", 0.12), ("right", -0.12)):
        values = dict(side=side, y=y, z=0.0, rpy="1.5708 0 0", ixx=0.00013, iyy=0.00025,
                      izz=0.00013, geometry='<cylinder radius="0.05" length="0.02"/>')
        values.update(wheel)
        parts.append(WHEEL.format(**values))
    if caster_z is not None:
        parts.append('<link name="caster_link"><collision><geometry><sphere radius="0.02"/>'
                     '</geometry></collision></link><joint name="caster_joint" type="fixed">'
                     '<parent link="base_link"/><child link="caster_link"/>'
                     f'<origin xyz="-0.12 0 {caster_z}"/></joint>')
    return "".join(parts)


def test_a_well_made_base_is_clean(tmp_path):
    assert _found(tmp_path, _base(caster_z=-0.03)) == []


def test_a_caster_clear_by_millimetres_touches(tmp_path):
    assert _found(tmp_path, _base(caster_z=-0.025)) == []  # 5 mm: within the 1 cm


def test_without_footprint_the_wheels_are_the_ground(tmp_path):
    assert _found(tmp_path, _base(footprint=False, caster_z=-0.03)) == []
    [(code, message)] = _found(tmp_path, _base(footprint=False, caster_z=0.0))
    assert code == "U419" and "30 mm above the lowest wheel" in message


def test_footprint_checks(tmp_path):
    [(code, message)] = _found(tmp_path, _base(z=0.08, caster_z=-0.03))
    assert code == "U418" and "30 mm below the lowest" in message and "move it up" in message
    shifted = _base(caster_z=-0.03).replace('<origin xyz="0 0 0.05"/></joint>',
                                            '<origin xyz="0.1 0 0.05"/></joint>', 1)
    [(code, message)] = _found(tmp_path, shifted)
    assert code == "U418" and "not right below 'base_link'" in message


def test_footprint_of_a_robot_without_wheels_is_below_all_its_geometry(tmp_path):
    legs = ('<link name="base_footprint"/><link name="base_link"><collision><origin xyz="0 0 -0.2"/>'
            '<geometry><box size="0.1 0.1 0.4"/></geometry></collision></link>'
            '<joint name="f" type="fixed"><parent link="base_footprint"/><child link="base_link"/>'
            '<origin xyz="0 0 {}"/></joint>')
    assert _found(tmp_path, legs.format(0.4)) == []
    # 10 cm above the footprint: it may stand on wheels or feet that are not drawn
    assert _found(tmp_path, legs.format(0.5)) == []
    [(code, message)] = _found(tmp_path, legs.format(0.3))
    assert code == "U418" and "100 mm above its lowest point" in message


def test_wheels_without_measurable_geometry_leave_the_ground_unknown(tmp_path):
    body = _base(z=0.3, wheel={"geometry": '<mesh filename="missing.stl"/>'})
    assert [code for code, _ in _found(tmp_path, body)] == []


def test_wheel_axle_and_inertia(tmp_path):
    # a wide roller (length over 0.6 diameter) turns hardest about a diameter: not judged
    roller = _base(caster_z=-0.03, wheel={"geometry": '<cylinder radius="0.05" length="0.2"/>',
                                          "ixx": 0.0008, "iyy": 0.00025, "izz": 0.0008})
    assert _found(tmp_path, roller) == []
    # a sphere wheel has no axis to be off
    ball = _base(caster_z=-0.03, wheel={"geometry": '<sphere radius="0.05"/>', "rpy": "0 0 0",
                                        "ixx": 0.0002, "iyy": 0.0002, "izz": 0.0002})
    assert _found(tmp_path, ball) == []
    turned = _base(caster_z=-0.03, wheel={"rpy": "0 0 0", "ixx": 0.00013, "iyy": 0.00013,
                                          "izz": 0.00025})
    codes = sorted(code for code, _ in _found(tmp_path, turned))
    # the cylinders lie flat (U420) and so hang above the caster's ground (U419); their tensor
    # is right for the cylinders as drawn, so U421 leaves it to U420
    assert codes == ["U419", "U419", "U420", "U420"]
    upright_but_swapped = _base(caster_z=-0.03, wheel={"ixx": 0.00013, "iyy": 0.00013,
                                                       "izz": 0.00025})
    assert sorted(code for code, _ in _found(tmp_path, upright_but_swapped)) == ["U421", "U421"]


CAMERA = """<link name="base_link"/>
<link name="camera_link"/><joint name="cj" type="fixed"><parent link="base_link"/>
  <child link="camera_link"/><origin xyz="0.1 0 0.2" rpy="{body}"/></joint>
<link name="camera_optical_frame"/><joint name="oj" type="fixed"><parent link="camera_link"/>
  <child link="camera_optical_frame"/><origin rpy="{optical}"/></joint>
<link name="camera_depth_optical_frame"/><joint name="dj" type="fixed">
  <parent link="camera_optical_frame"/><child link="camera_depth_optical_frame"/>
  <origin xyz="0.02 0 0"/></joint>
<gazebo reference="camera_link"><sensor name="c" type="{sensor}">{pose}
  <plugin name="p" filename="libgazebo_ros_camera.so"><{tag}>{frame}</{tag}></plugin>
</sensor></gazebo>"""


def _camera(**given) -> str:
    values = dict(body="0 0.3 0", optical="-1.5708 0 -1.5708", sensor="camera", pose="",
                  tag="frame_name", frame="camera_optical_frame")
    values.update(given)
    return CAMERA.format(**values)


@pytest.mark.parametrize("given", [
    {},  # the optical frame named, the camera tilted down (any body turn is fine)
    {"optical": "-1.57 0 -1.57"},  # printed pi/2: 0.05 deg off
    {"tag": "frameName", "sensor": "depth"},
    {"tag": "gz_frame_id", "sensor": "rgbd_camera"},
    {"sensor": "ray", "frame": "camera_link"},  # a lidar's frame is no image frame
    # curiosity_mars_rover: the <camera>'s own <pose> (after the sensor's) makes its link optical
    {"frame": "camera_link", "pose": "<camera><pose>0 0 0 0 -1.5708 1.5708</pose></camera>"},
])
def test_optical_frames_that_are_right(tmp_path, given):
    assert _found(tmp_path, _camera(**given), ("U417",)) == []


def test_optical_frames_that_are_wrong(tmp_path):
    found = _found(tmp_path, _camera(optical="0 0 0", frame="camera_link"), ("U417",))
    messages = sorted(message for _, message in found)
    assert len(messages) == 2  # the depth lens fixed to the optical frame: judged through it
    assert "stamps its images with 'camera_link'" in messages[0]
    assert "optical frame 'camera_optical_frame' is turned" in messages[1]
    # the sensor's <pose> turns it: the frame it stamps is judged against the sensor
    [(_, message)] = _found(tmp_path, _camera(pose="<pose>0 0 0 0 0 1.5708</pose>"), ("U417",))
    assert "from the sensor" in message


def test_an_optical_frame_is_said_turned_as_the_file_writes_it_from_a_frame_named_neutrally(
        tmp_path):
    """elkapod's depth camera: rpy="3.14159265359  0 0" was printed as "-3.142 0 0", a number
    the file does not hold; its 'lidar_optical', a gpu_lidar's, was called fixed to a "camera
    link". The rpy is quoted as written (a xacro expression with its value), and the body
    frame is a camera's or a lidar's only as a Gazebo sensor says."""
    robot = """<link name="base_link"/><link name="{body}"/><joint name="bj" type="fixed">
  <parent link="base_link"/><child link="{body}"/></joint>
<link name="{body}_optical"/><joint name="oj" type="fixed"><parent link="{body}"/>
  <child link="{body}_optical"/><origin xyz="0 0 0.04" rpy="{rpy}"/></joint>{sensor}"""
    [(_, message)] = _found(tmp_path, robot.format(body="front_camera", rpy="3.14159265359  0 0",
                                                   sensor=""), ("U417",))
    assert message.startswith("optical frame 'front_camera_optical' is turned "
                              "rpy=\"3.14159265359  0 0\" from link 'front_camera'; "), message
    assert message.endswith("from the sensor's body frame (REP 103)")
    lidar = ('<gazebo reference="lidar_optical"><sensor name="l" type="gpu_lidar">'
             '<gz_frame_id>lidar_optical</gz_frame_id></sensor></gazebo>')
    [(_, message)] = _found(tmp_path, robot.format(body="lidar", rpy="0 0 0", sensor=lidar),
                            ("U417",))
    assert "is turned rpy=\"0 0 0\" from lidar link 'lidar'; " in message
    assert "camera" not in message and message.endswith("from the lidar's body frame (REP 103)")
    camera = '<gazebo reference="cam"><sensor name="c" type="depth"/></gazebo>'
    [(_, message)] = _found(tmp_path, robot.format(body="cam", rpy="0 0 0", sensor=camera),
                            ("U417",))
    assert "from camera link 'cam'; " in message and "the camera's body frame" in message
    # written with xacro: the expression as written, then its value
    (tmp_path / "r.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        + robot.format(body="cam", rpy="${pi/2} 0 ${pi/2}", sensor="") + "</robot>")
    result = load_and_check(str(tmp_path / "r.urdf.xacro"),
                            CheckOptions(selection=Selection(("U417",))))
    [finding] = result.findings
    assert 'is turned rpy="${pi/2} 0 ${pi/2}" (= 1.571 0 1.571) from link \'cam\'' in \
        finding.message, finding.message
    # frames between the body and the optical frame: the turn in all, and the joint's own
    text = robot.format(body="cam", rpy="-1.5708 0 -1.5708", sensor="") + (
        '<link name="cam_depth_optical"/><joint name="dj" type="fixed">'
        '<parent link="cam_optical"/><child link="cam_depth_optical"/>'
        '<origin rpy="0 0 1.5708"/></joint>')
    [(_, message)] = _found(tmp_path, text, ("U417",))
    assert message.startswith("optical frame 'cam_depth_optical' is turned rpy=\"") and (
        "in all (computed through the frames between; its joint 'dj' writes rpy=\"0 0 "
        "1.5708\") from link 'cam'; ") in message, message


def test_an_optical_frame_on_a_part_that_is_no_camera_body_is_not_judged_by_its_axes(tmp_path):
    """Reachy Mini (onshape-to-robot): 'camera_optical' is fixed to the servo 'xl_330', whose
    CAD axes are turned anyhow; in the root frame it is z forward, x right, y down."""
    servo = """<link name="base_link"/>
<link name="xl_330"/><joint name="sj" type="fixed"><parent link="base_link"/>
  <child link="xl_330"/><origin rpy="0.3 1.1 -2.0"/></joint>
<link name="{optical}"/><joint name="oj" type="fixed"><parent link="xl_330"/>
  <child link="{optical}"/><origin rpy="{rpy}"/></joint>"""
    # the servo's turn undone, then the optical turn: right in the root frame
    import numpy as np
    from urdftool.physics import mat3

    servo_turn = np.array(mat3.rpy_matrix((0.3, 1.1, -2.0)))
    wanted = np.array(mat3.rpy_matrix((-np.pi / 2, 0.0, -np.pi / 2)))
    r = servo_turn.T @ wanted
    rpy = (np.arctan2(r[2, 1], r[2, 2]), np.arctan2(-r[2, 0], np.hypot(r[0, 0], r[1, 0])),
           np.arctan2(r[1, 0], r[0, 0]))
    text = servo.format(optical="camera_optical", rpy=" ".join(f"{v:.6f}" for v in rpy))
    assert _found(tmp_path, text, ("U417",)) == []
    # the same optical frame on a link named for the camera is judged from its axes
    text = text.replace("xl_330", "camera_link")
    assert [code for code, _ in _found(tmp_path, text, ("U417",))] == ["U417"]


def test_a_link_sharing_only_a_place_word_with_an_optical_frame_is_no_camera_body(tmp_path):
    """rm_description's rail sentry: lower_camera_optical_frame is fixed to lower_pitch, the
    lower gimbal's pitch link, by a calibrated rotation (-1.6547 0.0528 -1.5597), and was
    judged from the pitch link's axes because both names hold 'lower' (a false U417). A side,
    a position or an index says where a part is, not that it is the camera; a shared word that
    names the part (high_def) still makes the body the camera's."""
    robot = """<link name="base_link"/>
<link name="{body}"/><joint name="bj" type="fixed"><parent link="base_link"/>
  <child link="{body}"/></joint>
<link name="{optical}"/><joint name="oj" type="fixed"><parent link="{body}"/>
  <child link="{optical}"/><origin rpy="-1.6547 0.0528 -1.5597"/></joint>"""
    for body, optical in (("lower_pitch", "lower_camera_optical_frame"),
                          ("left_2_link", "left_2_optical_frame")):
        assert _found(tmp_path, robot.format(body=body, optical=optical), ("U417",)) == [], body
    judged = robot.format(body="high_def_frame", optical="high_def_optical_frame")
    assert [code for code, _ in _found(tmp_path, judged, ("U417",))] == ["U417"]


def test_an_optical_frame_of_a_camera_tilted_in_its_mount_is_a_note(tmp_path):
    """Bit-Bots' Pi Plus: camera_link is a CAD part on the head, and the camera's 30-degree
    tilt is written into the optical joints (rpy="-2.093 0 -1.57"): the optical frames look
    where the camera does; a warning said to make them -pi/2 0 -pi/2, which would turn them
    off the view. A turn no tilt explains (a sign slip) stays a warning."""
    from urdftool.diagnostics import Severity

    robot = """<link name="base_link"/><link name="camera_link"/><joint name="cj" type="fixed">
  <parent link="base_link"/><child link="camera_link"/></joint>
<link name="camera_optical_frame_right"/><joint name="oj" type="fixed">
  <parent link="camera_link"/><child link="camera_optical_frame_right"/>
  <origin rpy="{rpy}"/></joint>"""

    def severities(rpy):
        (tmp_path / "r.urdf").write_text(f'<robot name="r">{robot.format(rpy=rpy)}</robot>')
        result = load_and_check(str(tmp_path / "r.urdf"),
                                CheckOptions(selection=Selection(("U417",))))
        return [(f.severity, f.message) for f in result.findings]

    [(severity, message)] = severities("-2.093 -0.0 -1.57")
    assert severity == Severity.INFO and "pitched 29.9 degrees" in message, message
    assert [s for s, _ in severities("1.5708 0 -1.5708")] == [Severity.WARNING]  # a sign slip
    assert [s for s, _ in severities("-2.093 0.4 -1.57")] == [Severity.WARNING]  # not a tilt


def _box_base(size: str) -> str:
    """A base_link of a box of ``size`` for wheels to hang from."""
    return (f'<link name="base_link"><collision><geometry><box size="{size}"/></geometry>'
            '</collision></link>')


def _rolling(link: str, parent: str, xyz="0 0 0", axis="0 1 0", rpy="0 0 0") -> str:
    """A cylinder ``link`` of radius 0.05 m turned by continuous joint ``LINK_joint``."""
    return (f'<link name="{link}"><collision><origin rpy="{rpy}"/><geometry><cylinder '
            'radius="0.05" length="0.02"/></geometry></collision></link>'
            f'<joint name="{link}_joint" type="continuous"><parent link="{parent}"/>'
            f'<child link="{link}"/><origin xyz="{xyz}"/><axis xyz="{axis}"/></joint>')


def test_wheels_whose_axles_stand_up_are_not_judged_against_the_ground(tmp_path):
    # fusion2urdf's Basic_Robot is modelled with y up: its wheels turn about z, side by side
    # along z (60 mm apart), and U419 said one hovers 63 mm above the other: 'lower it'
    body = _box_base("0.3 0.04 0.2")
    for side, z in (("left", 0.0), ("right", -0.06)):
        body += _rolling(f"{side}_wheel", "base_link", xyz=f"0 0 {z}", axis="0 0 1")
    assert _found(tmp_path, body, codes=("U419",)) == []


def test_a_link_named_for_a_wheel_that_holds_the_wheel_below_it_is_no_wheel(tmp_path):
    # a wheel-legged robot exported from SolidWorks (wheel_legged_sim_ros' CJ-003): the fixed
    # left_wheel_motor_Link on the calf carries the continuous left_wheel_joint's wheel; U419
    # took the motor for a welded wheel and said it hovers 59 mm above the wheel below it
    motors = "".join(
        f'<link name="{side}_wheel_motor_Link"><collision><geometry><box size="0.04 0.04 0.04"/>'
        f'</geometry></collision></link><joint name="{side}_wheel_motor" type="fixed"><parent '
        f'link="base_link"/><child link="{side}_wheel_motor_Link"/><origin xyz="0 {y} -0.1"/>'
        '</joint>' + _rolling(f"{side}_wheel_Link", f"{side}_wheel_motor_Link", rpy="1.5708 0 0")
        for side, y in (("left", 0.12), ("right", -0.12)))
    body = _box_base("0.1 0.1 0.1") + motors
    assert _found(tmp_path, body, codes=("U419",)) == []
    # a wheel welded in place with nothing below it is still one, and still hovers when it does
    welded = body + ('<link name="rear_wheel"><collision><origin rpy="1.5708 0 0"/><geometry>'
                     '<cylinder radius="0.05" length="0.02"/></geometry></collision></link>'
                     '<joint name="rear_fix" type="fixed"><parent link="base_link"/>'
                     '<child link="rear_wheel"/><origin xyz="-0.2 0 -0.07"/></joint>')
    [(code, message)] = _found(tmp_path, welded, codes=("U419",))
    assert "'rear_wheel' is 30 mm above the lowest wheel" in message


def test_a_wheel_standing_on_its_flat_face_is_told_to_turn_its_cylinder(tmp_path):
    # Omron's LD AMR: the wheels' collision cylinders lack the visual's rpy, so each stands
    # upright and reaches 44 mm less low than the casters; 'lower it by 0.044 m' was wrong
    casters = "".join(_rolling(f"{side}_caster_wheel", "base_link", xyz=f"0.2 {y} -0.1",
                               rpy="1.5708 0 0") for side, y in (("left", 0.1), ("right", -0.1)))
    drive = "".join(_rolling(f"{side}_wheel", "base_link", xyz=f"0 {y} -0.1")
                    for side, y in (("left", 0.2), ("right", -0.2)))
    found = _found(tmp_path, _box_base("0.1 0.1 0.1") + casters + drive, codes=("U419", "U420"))
    assert sorted(code for code, _ in found) == ["U419", "U419", "U420", "U420"]
    assert all("collision cylinder is turned off the axle (U420): turn it, and measure again"
               in message for code, message in found if code == "U419")


def test_a_wheel_is_the_body_of_links_fixed_to_its_rolling_link(tmp_path):
    # Upkie's wheel: joint 'left_wheel' turns the motor's rotor, to which the hub and the tyre
    # are fixed (all three named so). U419 judged each as a wheel and said the rotor and the
    # hub hover 16 and 11 mm above the tyre: they are parts of the one body that rolls.
    body = _box_base("0.1 0.1 0.1")
    for side, y in (("left", 0.12), ("right", -0.12)):
        body += (f'<link name="{side}_wheel_rotor"><collision><origin rpy="1.5708 0 0"/>'
                 '<geometry><cylinder radius="0.03" length="0.02"/></geometry></collision></link>'
                 f'<joint name="{side}_wheel" type="continuous"><parent link="base_link"/>'
                 f'<child link="{side}_wheel_rotor"/><origin xyz="0 {y} -0.1"/>'
                 '<axis xyz="0 1 0"/></joint>')
        for part, parent, radius in (("hub", "wheel_rotor", 0.04), ("tire", "wheel_hub", 0.06)):
            body += (f'<link name="{side}_wheel_{part}"><collision><origin rpy="1.5708 0 0"/>'
                     f'<geometry><cylinder radius="{radius}" length="0.02"/></geometry>'
                     f'</collision></link><joint name="{side}_{part}_fix" type="fixed">'
                     f'<parent link="{side}_{parent}"/><child link="{side}_wheel_{part}"/>'
                     '</joint>')
    assert _found(tmp_path, body, codes=("U419",)) == []
    # on a footprint, a rolling link without geometry of its own is measured by its body
    # (example-robot-data's TIAGo: U419 crashed comparing None, the link's own lowest point)
    bare = body.replace('<link name="left_wheel_rotor"><collision><origin rpy="1.5708 0 0"/>'
                        '<geometry><cylinder radius="0.03" length="0.02"/></geometry></collision>'
                        '</link>', '<link name="left_wheel_rotor"/>')
    footprint = ('<link name="base_footprint"/><joint name="f" type="fixed"><parent '
                 'link="base_footprint"/><child link="base_link"/><origin xyz="0 0 0.16"/></joint>')
    assert bare != body and _found(tmp_path, bare + footprint, codes=CODES) == []
    # a wheel that is its own body still hovers when it does
    lifted = body.replace('<origin xyz="0 -0.12 -0.1"/>', '<origin xyz="0 -0.12 -0.07"/>')
    [(code, message)] = _found(tmp_path, lifted, codes=("U419",))
    assert "'right_wheel_rotor' is 30 mm above the lowest wheel" in message


def test_the_camera_conventions_walk_the_gazebo_blocks_for_sensors_once(tmp_path, monkeypatch):
    """U417's three looks for camera sensors (the cameras, their frames, whether a link is a
    camera body) share one walk of the <gazebo> blocks per robot: the same findings."""
    from urdftool.description.robot import Robot

    asked = []
    children = Robot.children
    monkeypatch.setattr(Robot, "children", lambda robot, tag: asked.append(tag) or
                        children(robot, tag))
    found = _found(tmp_path, _camera(optical="0 0 0", frame="camera_link"), ("U417",))
    assert len(found) == 2
    assert asked.count("gazebo") == 1, asked  # one walk for the sensors and the plugins
