"""U812-U818: MoveIt's kinematics.yaml, joint_limits.yaml and controller list."""

from __future__ import annotations

import shutil

import pytest

from conftest import ROBOTS
from crossfile_helpers import HEAD_ROBOT, check_folder, line_of
from urdftool.lint.engine import CheckOptions, load_and_check

ROBOT = HEAD_ROBOT.format(body="")
SRDF = '<robot name="r">\n<group name="head">\n<chain base_link="base_link" tip_link="head"/>\n</group>\n</robot>\n'
KDL = "kdl_kinematics_plugin/KDLKinematicsPlugin"


def test_moveit_files_are_found_beside_an_srdf_in_another_package(tmp_path):
    files = {"robot.urdf": ROBOT, "r_moveit_config/config/r.srdf": SRDF,
             "r_moveit_config/config/kinematics.yaml": f"heda:\n  kinematics_solver: {KDL}\n",
             "r_moveit_config/config/joint_limits.yaml":
                 "joint_limits:\n  head_joint:\n    has_velocity_limits: true\n    max_velocity: 1.5\n"}
    found, findings = check_folder(tmp_path, files, srdf=str(tmp_path / "r_moveit_config/config/r.srdf"))
    assert found == [("joint_limits.yaml", 4, "U816"), ("kinematics.yaml", 1, "U813")]
    assert "did you mean 'head'?" in findings[1].message


def test_moveit2_layouts_under_ros_parameters(tmp_path):
    files = {"robot.urdf": ROBOT, "robot.srdf": SRDF,
             "kinematics.yaml": f"/**:\n  ros__parameters:\n    robot_description_kinematics:\n"
                                f"      head:\n        kinematics_solver: {KDL}\n"
                                f"        kinematics_solver_timeout: -1\n",
             "joint_limits.yaml": "robot_description_planning:\n  joint_limits:\n    head_joint:\n"
                                  "      has_position_limits: true\n      max_position: !degrees 360\n"
                                  "      min_position: -2\n",
             "config/ros2_controllers.yaml":
                 "controller_manager:\n  ros__parameters:\n    head_controller:\n"
                 "      type: joint_trajectory_controller/JointTrajectoryController\n"
                 "head_controller:\n  ros__parameters:\n    joints: [head_joint]\n",
             "moveit_controllers.yaml":
                 "moveit_simple_controller_manager:\n  controller_names: [head_controller, neck]\n"
                 "  head_controller:\n    type: FollowJointTrajectory\n    joints: [head_joint, cam_joint]\n"
                 "    action_ns: follow_joint_trajectory\n"}
    found, findings = check_folder(tmp_path, files, select=("U81", "U601"))
    # the timeout, max_position (!degrees 360: 2 pi to rosparam and to ROS 2's MoveIt, whose
    # launch_param_builder reads the tag alike) and min_position, the neck controller without
    # a block (U812 too where the file is among the robot's controller files: MoveIt's lists
    # have one reader, moveit_config's, and one rule), and cam_joint that ros_control does not drive
    assert found == [("joint_limits.yaml", 5, "U816"), ("joint_limits.yaml", 6, "U816"),
                     ("kinematics.yaml", 6, "U812"), ("moveit_controllers.yaml", 2, "U812"),
                     ("moveit_controllers.yaml", 5, "U818")]
    assert "6.28319 is above" in findings[0].message and "adds cam_joint" in findings[4].message


def test_a_gripper_command_controller_may_list_the_mimicking_finger(tmp_path):
    files = {"robot.urdf": ROBOT, "robot.srdf": SRDF,
             "config/c.yaml": "grip:\n  type: position_controllers/GripperActionController\n  joint: head_joint\n",
             "ros_controllers.yaml": "controller_list:\n  - name: grip\n    type: GripperCommand\n"
                                     "    action_ns: gripper_cmd\n    joints: [head_joint, cam_joint]\n"}
    assert check_folder(tmp_path, files, select=("U81",))[0] == []


def humanoid_with_kdl(tmp_path, srdf_old=None, srdf_new=None):
    folder = tmp_path / "humanoid"
    shutil.copytree(ROBOTS / "humanoid", folder)
    (folder / "kinematics.yaml").write_text("".join(
        f"{group}:\n  kinematics_solver: {KDL}\n  kinematics_solver_timeout: 0.005\n"
        for group in ("left_arm", "left_leg")))
    if srdf_old:
        srdf = folder / "humanoid.srdf"
        srdf.write_text(srdf.read_text().replace(srdf_old, srdf_new))
    findings = load_and_check(str(folder / "humanoid.urdf.xacro"), CheckOptions()).findings
    return folder, [f for f in findings if f.code.startswith("U81")]


def test_humanoid_left_arm_and_leg_solved_by_kdl(tmp_path):
    assert humanoid_with_kdl(tmp_path)[1] == []


def test_humanoid_leg_chain_written_backwards(tmp_path):
    folder, findings = humanoid_with_kdl(tmp_path, '<chain base_link="body_link" tip_link="l_foot_link"/>',
                                         '<chain base_link="l_foot_link" tip_link="body_link"/>')
    assert [(f.code, f.line) for f in findings] == [("U814", line_of(folder / "humanoid.srdf", "l_foot_link"))]
    assert "base_link 'l_foot_link' is below tip_link 'body_link'" in findings[0].message


def test_humanoid_arm_chain_across_to_the_other_arm(tmp_path):
    _, findings = humanoid_with_kdl(tmp_path, '<chain base_link="body_link" tip_link="l_forearm_link"/>',
                                    '<chain base_link="r_forearm_link" tip_link="l_forearm_link"/>')
    assert [f.code for f in findings] == ["U814"] and "at link 'body_link'" in findings[0].message


def test_broken_moveit_yaml_is_located_inside_the_file(tmp_path):
    files = {"robot.urdf": ROBOT, "robot.srdf": SRDF,
             "kinematics.yaml": f"head:\n  kinematics_solver: {KDL}\n  kinematics_solver_timeout: [0.005\n",
             "moveit_controllers.yaml": "moveit_simple_controller_manager:\n  controller_names: 'head\n"}
    found, _ = check_folder(tmp_path, files, select=("U81",))
    assert found == [("kinematics.yaml", 3, "U812"), ("moveit_controllers.yaml", 2, "U812")]


def test_a_kinematics_yaml_that_does_not_read_is_said_not_skipped(tmp_path):
    """A kinematics.yaml in a folder companions are looked for in, away from the SRDF, was
    taken only when it read: one MoveIt cannot read was passed over in silence (no finding,
    and no solver checked); beside the SRDF it was U812."""
    files = {"robot.urdf": ROBOT, "robot.srdf": SRDF,
             "config/kinematics.yaml": f"head:\n  kinematics_solver: {KDL}\n"
                                                       "  kinematics_solver_timeout: 2001-02-30\n"}
    found, findings = check_folder(tmp_path, files, select=("U81",))
    assert found == [("kinematics.yaml", 3, "U812")] and "day is out of range" in findings[0].message


@pytest.mark.parametrize("key, flag", [("max_velocity", "has_velocity_limits"),
                                       ("max_acceleration", "has_acceleration_limits")])
def test_a_moveit_limit_of_nan_is_no_number(tmp_path, key, flag):
    """``.nan`` passed every comparison of a limit (above 0, at most the URDF's): no finding,
    and MoveIt plans with a NaN limit."""
    files = {"robot.urdf": ROBOT, "robot.srdf": SRDF,
             "joint_limits.yaml": f"joint_limits:\n  head_joint:\n    {flag}: true\n    {key}: .nan\n"}
    found, findings = check_folder(tmp_path, files, select=("U81",))
    assert found == [("joint_limits.yaml", 4, "U812")] and "'nan' must be a number" in findings[0].message


def test_moveit_files_are_not_read_through_a_link_out_of_the_srdf_folder(tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "kinematics.yaml").write_text(f"nope:\n  kinematics_solver: {KDL}\n")
    robot = tmp_path / "robot"
    files = {"robot.urdf": ROBOT, "robot.srdf": SRDF}
    robot.mkdir()
    (robot / "kinematics.yaml").symlink_to(outside / "kinematics.yaml")
    assert check_folder(robot, files, select=("U81",))[0] == []
    (robot / "kinematics.yaml").unlink()
    (robot / "kinematics.yaml").write_text(f"nope:\n  kinematics_solver: {KDL}\n")
    assert check_folder(robot, files, select=("U81",))[0] == [("kinematics.yaml", 1, "U813")]


def test_kinematics_yaml_in_the_robots_config_folder_with_the_srdf_beside_the_robot(tmp_path):
    files = {"robot.urdf": ROBOT, "robot.srdf": SRDF.replace("<chain base_link=\"base_link\" tip_link=\"head\"/>",
                                                             "<chain base_link=\"cam\" tip_link=\"base_link\"/>"),
             "config/kinematics.yaml": f"head:\n  kinematics_solver: {KDL}\n",
             "config/joint_limits.yaml": "joint_limits:\n  nope: {has_velocity_limits: true}\n"}
    # the backwards chain is found; a joint_limits.yaml outside the SRDF's folder is not MoveIt's
    assert check_folder(tmp_path, files, select=("U81",))[0] == [("robot.srdf", 3, "U814")]


@pytest.mark.parametrize("written, reported", [(2.53073, False), (9.6, False), (2.5308, True),
                                               (7.85, True)])
def test_a_limit_rounded_from_the_urdfs_is_the_same_limit(written, reported):
    # MoveIt Setup Assistant writes the URDF's limit rounded: 2.53073 for ${radians(145)}, 9.6
    # for 9.59931 (motoman, fanuc); the same limit, not one above it
    from urdftool.lint.rules.moveit import TOLERANCE, _rounded

    urdf = {2.53073: 2.5307274153917776, 9.6: 9.59931, 2.5308: 2.5307274153917776, 7.85: 6.45772}[written]
    assert (written - urdf > TOLERANCE and not _rounded(written, urdf)) is reported


DRIVER_LAUNCH = """<launch>
  <param name="robot_description" textfile="$(find arm)/robot.urdf"/>
  <rosparam file="$(find arm)/config/controllers.yaml" command="load"/>
  <rosparam file="$(find arm)/config/moveit_list.yaml" command="load" ns="move_group"/>
  <node name="s" pkg="controller_manager" type="spawner" args="jsc arm_controller"/>
  {driver}
  <node name="move_group" pkg="moveit_ros_move_group" type="move_group"/>
</launch>"""


def _arm_package(tmp_path, launch: str, joints: str = "head_joint") -> dict:
    """An arm package whose MoveIt list names arm_driver_controller (with ``joints``) and whose
    ros_control YAML declares arm_controller, started by ``launch``."""
    (tmp_path / ".git").mkdir()
    return {"package.xml": "<package format='2'><name>arm</name></package>",
            "robot.urdf": HEAD_ROBOT.format(body="""<transmission name="t">
               <type>transmission_interface/SimpleTransmission</type>
               <joint name="head_joint"><hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface></joint>
               <actuator name="m"/></transmission>"""),
            "config/controllers.yaml": "jsc: {type: joint_state_controller/JointStateController, publish_rate: 50}\n"
                                       "arm_controller: {type: position_controllers/JointTrajectoryController, joints: [head_joint]}\n",
            "config/moveit_list.yaml": "controller_list:\n- {name: arm_driver_controller, action_ns: follow_joint_trajectory,"
                                       f" type: FollowJointTrajectory, joints: [{joints}]}}\n",
            "launch/moveit.launch": launch}


@pytest.mark.parametrize("driver, expected", [
    ("", ("U817", "error")),  # MoveIt and ros_control alone: the name misses for certain
    ('<node name="d" pkg="arm_driver" type="trajectory_action_server"/>', None),  # the driver's
])
def test_a_moveit_controller_a_driver_serves_is_not_ros_controls(tmp_path, driver, expected):
    files = _arm_package(tmp_path, DRIVER_LAUNCH.format(driver=driver))
    _, findings = check_folder(tmp_path, files, select=("U817",))
    assert [(f.code, f.severity.value) for f in findings] == ([expected] if expected else [])


REMAP_LAUNCH = """<launch>
  <arg name="sim" default="true"/>
  <param name="robot_description" textfile="$(find arm)/robot.urdf"/>
  <rosparam file="$(find arm)/config/controllers.yaml" command="load"/>
  <rosparam file="$(find arm)/config/moveit_list.yaml" command="load" ns="move_group"/>
  <node name="s" pkg="controller_manager" type="spawner" args="jsc arm_controller"/>
  {before}
  <node name="move_group" pkg="moveit_ros_move_group" type="move_group">{inside}</node>
</launch>"""
SENT = "arm_driver_controller/follow_joint_trajectory"


@pytest.mark.parametrize("before, inside, expected, joints", [
    ("", "", ("U817", "error"), "head_joint"),  # the name misses for certain
    # xArm's Gazebo launch: remapped before move_group (and so into an include) to the served one
    (f'<remap from="/{SENT}" to="/arm_controller/follow_joint_trajectory"/>', "", None, "head_joint"),
    ("", f'<remap from="{SENT}" to="arm_controller/follow_joint_trajectory"/>', None, "head_joint"),
    # ... and then the joints are compared with that controller's
    ("", f'<remap from="{SENT}" to="arm_controller/follow_joint_trajectory"/>', ("U818", "error"),
     "head_joint, nope"),
    # remapped with some launch arguments only: a warning naming the condition
    (f'<remap if="$(arg sim)" from="{SENT}" to="arm_controller/follow_joint_trajectory"/>', "",
     ("U817", "warning"), "head_joint"),
    (f'<remap from="{SENT}" to="$(arg sim)/follow_joint_trajectory"/>', "", ("U817", "warning"),
     "head_joint"),
    # remapped to what no ros_control controller serves: still the error
    (f'<remap from="{SENT}" to="other/follow_joint_trajectory"/>', "", ("U817", "error"), "head_joint"),
    # a remap of a group that ended before move_group does not hold for it
    (f'<group><remap from="{SENT}" to="arm_controller/follow_joint_trajectory"/></group>', "",
     ("U817", "error"), "head_joint"),
])
def test_a_launch_remap_of_moveits_action_to_a_served_controller(tmp_path, before, inside, expected,
                                                                  joints):
    files = _arm_package(tmp_path, REMAP_LAUNCH.format(before=before, inside=inside), joints)
    _, findings = check_folder(tmp_path, files, select=("U817", "U818"))
    assert [(f.code, f.severity.value) for f in findings] == ([expected] if expected else [])
    if expected and expected[1] == "warning":
        assert "sim" in findings[0].message and "remap" in findings[0].message, findings[0].message


def _kinematics(tmp_path, solver):
    files = {"robot.urdf": ROBOT, "robot.srdf": SRDF, "kinematics.yaml": f"head:\n  kinematics_solver: {solver}\n"}
    return check_folder(tmp_path, files, select=("U819",))[0]


def test_kinematics_solver_names(tmp_path):
    assert _kinematics(tmp_path / "a", "kdl_kinematics_plugin/KDLKinematicPlugin") == [("kinematics.yaml", 2, "U819")]
    assert _kinematics(tmp_path / "b", "kdl_kinematics_plugin/Other") == [("kinematics.yaml", 2, "U819")]
    for fine in ("pick_ik/PickIkPlugin", "r_head_ikfast_plugin/IKFastKinematicsPlugin",
                 "ur_kinematics/UR5KinematicsPlugin", "vendor_ik/VendorPlugin"):
        assert _kinematics(tmp_path / fine.split("/")[0], fine) == [], fine


def _controllers(tmp_path, ros_control, moveit, select=("U820", "U821")):
    files = {"robot.urdf": ROBOT, "robot.srdf": SRDF, "config/controllers.yaml": ros_control,
             "moveit_controllers.yaml": moveit}
    return check_folder(tmp_path, files, select=select)


GRIPPER = "g:\n  type: position_controllers/GripperActionController\n  joint: head_joint\n"


def test_moveit_action_and_type_against_the_served_action(tmp_path):
    moveit = ("controller_list:\n  - name: g\n    action_ns: gripper_action\n    type: FollowJointTrajectory\n"
              "    joints: [head_joint]\n")
    found, findings = _controllers(tmp_path, GRIPPER, moveit)
    assert found == [("moveit_controllers.yaml", 2, "U820"), ("moveit_controllers.yaml", 3, "U820")]
    assert "write action_ns: gripper_cmd" in findings[1].message and "write type: GripperCommand" in findings[0].message
    right = ("controller_list:\n  - name: g\n    action_ns: gripper_cmd\n    type: GripperCommand\n"
             "    joints: [head_joint]\n")
    assert _controllers(tmp_path / "b", GRIPPER, right)[0] == []


def test_moveit_namespace_against_the_controller_yamls(tmp_path):
    nested = "robot1:\n" + "".join(f"  {line}\n" for line in GRIPPER.splitlines())
    moveit = ("controller_list:\n  - name: {name}\n    action_ns: gripper_cmd\n    type: GripperCommand\n"
              "    joints: [head_joint]\n")
    found, findings = _controllers(tmp_path / "a", nested, moveit.format(name="g"))
    assert found == [("moveit_controllers.yaml", 2, "U821")] and "unless move_group runs in /robot1" in findings[0].message
    assert _controllers(tmp_path / "b", nested, moveit.format(name="robot1/g"))[0] == []
    assert _controllers(tmp_path / "c", GRIPPER, moveit.format(name="g"))[0] == []


ARM = """<robot name="r">
  <link name="base_link"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="upper"><collision><origin xyz="0 0 0.25"/><geometry><box size="0.06 0.06 {length}"/></geometry></collision></link>
  <link name="flange"/>
  <link name="lower"><collision><origin xyz="0 0 0.15"/><geometry><box size="0.05 0.05 0.2"/></geometry></collision></link>
  <joint name="shoulder" type="revolute"><parent link="base_link"/><child link="upper"/>
    <origin xyz="0 0 0.05"/><axis xyz="1 0 0"/><limit lower="-1.6" upper="1.6" effort="5" velocity="2"/></joint>
  <joint name="mount" type="fixed"><parent link="upper"/><child link="flange"/><origin xyz="0 0 0.4"/></joint>
  <joint name="elbow" type="revolute"><parent link="flange"/><child link="lower"/>
    <axis xyz="1 0 0"/><limit lower="-2" upper="2" effort="5" velocity="2"/></joint>
</robot>
"""


def _srdf(tmp_path, length, entries):
    srdf = '<robot name="r">\n' + "".join(
        f'<disable_collisions link1="{a}" link2="{b}" reason="{r}"/>\n' for a, b, r in entries) + "</robot>\n"
    return check_folder(tmp_path, {"robot.urdf": ARM.format(length=length), "robot.srdf": srdf},
                        select=("U810", "U811", "U822", "U823"))


def test_adjacency_looks_through_links_without_geometry(tmp_path):
    # upper and lower are joined through flange, which has no geometry: Adjacent is right
    entries = [("base_link", "upper", "Adjacent"), ("lower", "upper", "Adjacent")]
    assert _srdf(tmp_path / "a", 0.4, entries)[0] == []
    found, findings = _srdf(tmp_path / "b", 0.4, [("base_link", "lower", "Adjacent")])
    assert found == [("robot.srdf", 2, "U822")] and "3 joints apart" in findings[0].message


def test_adjacent_overlap_without_an_entry_and_its_fix(tmp_path):
    found, findings = _srdf(tmp_path, 0.5, [("base_link", "upper", "Adjacent")])
    assert found == [("robot.srdf", 1, "U823")]  # and no U811: the pair is adjacent
    [edit] = findings[0].fix.edits
    assert edit.text.strip() == '<disable_collisions link1="lower" link2="upper" reason="Adjacent"/>'
    # disabled as Never, the adjacent overlap is no U810 either (contact at a joint is expected)
    assert _srdf(tmp_path / "b", 0.5, [("base_link", "upper", "Adjacent"), ("lower", "upper", "Never")])[0] == []


def test_groups_wrapped_in_a_node_pattern_say_what_moveit_reads(tmp_path):
    """Rokae's kinematics.yaml: '/**: ros__parameters: rokae_arm: ...' without
    robot_description_kinematics: the finding names the wrapper, not 'group /**'."""
    files = {"robot.urdf": ROBOT, "robot.srdf": SRDF,
             "kinematics.yaml": f"/**:\n  ros__parameters:\n    head:\n      kinematics_solver: {KDL}\n"}
    found, findings = check_folder(tmp_path, files, select=("U813",))
    assert found == [("kinematics.yaml", 1, "U813")]
    assert "wraps its groups in '/**: ros__parameters:'" in findings[0].message, findings[0].message
    assert "(head) get no IK solver" in findings[0].message


def test_a_group_of_another_srdf_beside_it_is_a_note_and_a_group_of_none_an_error(tmp_path):
    """aip-primeca-occitanie/ros_yaskawa_hc10: one kinematics.yaml for yaskawa_LEFT.srdf and
    yaskawa_RIGHT.srdf, which planning_context.launch chooses by left_robot; MoveIt given one
    ignores the other's groups (a note), a group neither defines stays an error."""
    other = SRDF.replace('"head"', '"tail"', 1)
    files = {"robot.urdf": ROBOT, "robot.srdf": SRDF, "robot_right.srdf": other,
             "kinematics.yaml": "".join(f"{g}:\n  kinematics_solver: {KDL}\n"
                                        for g in ("head", "tail", "haed"))}
    found, findings = check_folder(tmp_path, files, srdf=str(tmp_path / "robot.srdf"),
                                   select=("U813",))
    assert found == [("kinematics.yaml", 3, "U813"), ("kinematics.yaml", 5, "U813")]
    assert [f.severity.name for f in findings] == ["INFO", "ERROR"]
    assert "robot_right.srdf beside it does" in findings[0].message, findings[0].message


def test_a_tree_group_is_said_at_its_kinematics_entry_without_naming_that_line_again(tmp_path):
    # RH-P12-RN-A's gripper group: "kinematics.yaml:2: error U814 group 'gripper' is solved
    # by KDLKinematicsPlugin (kinematics.yaml line 2) but is not one serial chain"
    folder, findings = humanoid_with_kdl(
        tmp_path, '<group name="left_arm">',
        '<group name="left_arm"><group name="right_arm"/>')
    [finding] = findings
    assert finding.file.endswith("kinematics.yaml") and finding.line == 2
    assert finding.message.startswith("group 'left_arm' is solved by KDLKinematicsPlugin but "
                                      "is not one serial chain: a tree"), finding.message


def test_a_moveit_limit_of_the_urdfs_digits_a_power_of_ten_off_is_a_slipped_decimal(tmp_path):
    robot = ROBOT.replace('effort="5" velocity="1"', 'effort="5" velocity="1.5"')
    files = {"robot.urdf": robot, "robot.srdf": SRDF, "joint_limits.yaml":
             "joint_limits:\n  head_joint:\n    has_velocity_limits: true\n    max_velocity: 15\n"
             "    has_effort_limits: true\n    max_effort: 6\n"}
    found, findings = check_folder(tmp_path, files, srdf=str(tmp_path / "robot.srdf"))
    said = sorted(f.message for f in findings if f.code == "U816")
    assert len(said) == 2 and not said[0].endswith("slipped")  # effort 6 against 5
    assert said[1].endswith("use at most 1.5: the same digits 10 times apart, a decimal point slipped")


def test_false_adjacent_entries_walk_the_tree_once_not_once_each(tmp_path, monkeypatch):
    """An SRDF of 100,000 ``Adjacent`` entries of a pair two joints apart: U822 built the
    robot's tree again for each entry's message and the check ran past its 60 s budget (U015);
    10,000 took 15 s."""
    from urdftool.kinematics import tree

    built = []
    children_by_link = tree.children_by_link
    monkeypatch.setattr(tree, "children_by_link",
                        lambda robot: built.append(1) or children_by_link(robot))
    found, findings = _srdf(tmp_path, 0.4, [("base_link", "lower", "Adjacent")] * 500)
    assert [code for _, _, code in found] == ["U822"] * 500
    assert all("3 joints apart" in finding.message for finding in findings)
    assert len(built) <= 3


def test_a_urdf_bound_not_written_is_urdfdoms_zero(tmp_path):
    """A ``<limit>`` without ``lower`` is lower 0 to urdfdom, and so to MoveIt's model
    (description.values.limit_bound); U816 skipped the bound as if there were none, so a
    min_position of -1 said nothing of MoveIt planning below the joint's stop."""
    robot = ROBOT.replace('lower="-1" upper="1"', 'upper="1"')
    files = {"robot.urdf": robot, "robot.srdf": SRDF,
             "joint_limits.yaml": "joint_limits:\n  head_joint:\n    has_position_limits: true\n"
                                  "    min_position: -1\n    max_position: 1\n"}
    found, findings = check_folder(tmp_path, files, select=("U816",))
    assert found == [("joint_limits.yaml", 4, "U816")]
    assert "min_position -1 is below the URDF's <limit lower=\"0\">" in findings[0].message


@pytest.mark.parametrize("manager, severity", [
    ("", "error"),
    ("moveit_controller_manager: moveit_simple_controller_manager/MoveItSimpleControllerManager\n",
     "error"),
    # moveit_ros_control_interface asks the controller manager and reads no list: a note
    ("moveit_controller_manager: moveit_ros_control_interface/Ros2ControlManager\n", "info"),
])
def test_a_moveit_list_among_the_controllers_is_u812s_wherever_it_is(tmp_path, manager, severity):
    """MoveIt's list in the controller YAML beside the robot (no SRDF beside it) is read by the
    one reader, and its problems are U812's, not U601's nor nobody's."""
    files = {"robot.urdf": ROBOT, "config/controllers.yaml": manager + (
        "moveit_simple_controller_manager:\n  controller_names: [head_controller]\n"
        "  head_controller:\n    type: FollowJointTrajectory\n    joints: [head_joint]\n")}
    found, findings = check_folder(tmp_path, files, select=("U6", "U8"),
                                   controllers=[str(tmp_path / "config/controllers.yaml")])
    line = 3 + bool(manager)
    assert found == [("controllers.yaml", line, "U812")], [f.message for f in findings]
    assert findings[0].severity.value == severity
    assert "'head_controller' has no action_ns" in findings[0].message


@pytest.mark.parametrize("controllers, found", [
    # ROS 2's ros2_control serves MoveIt 2's list: its controllers are compared
    ("controller_manager:\n  ros__parameters:\n    arm:\n"
     "      type: joint_trajectory_controller/JointTrajectoryController\n", True),
    # a ROS 1 file beside it (a Setup Assistant's leftover ros_controllers.yaml) serves no MoveIt 2
    ("arm:\n  type: position_controllers/JointTrajectoryController\n  joints: [head_joint]\n", False),
])
def test_moveit2s_list_meets_ros2_controllers_only(tmp_path, controllers, found):
    """rokae_ros2's xMatePro3 MoveIt 2 list (controller_names at the top of a file its launch
    loads into moveit_simple_controller_manager) beside a ROS 1 ros_controllers.yaml: no U817."""
    files = {"robot.urdf": ROBOT, "robot.srdf": SRDF, "config/c.yaml": controllers,
             "moveit_controllers.yaml": "controller_names: [head_controller]\nhead_controller:\n"
                                        "  action_ns: follow_joint_trajectory\n  type: FollowJointTrajectory\n"
                                        "  joints: [head_joint]\n"}
    codes = [code for _, _, code in check_folder(tmp_path, files, select=("U817",))[0]]
    assert codes == (["U817"] if found else [])
