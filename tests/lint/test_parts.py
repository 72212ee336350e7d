"""A part of a robot defined elsewhere, checked alone (urdftool/lint/parts.py): what it cannot be
right about alone is a note, decided once for every rule."""

from __future__ import annotations

import ast
import inspect
import textwrap

from crossfile_helpers import check_folder
from urdftool.lint.parts import ABOUT_THE_ROBOT
from urdftool.lint.rules import FAMILY_MODULES

# Only <gazebo>, <transmission> and <ros2_control> blocks, naming links and joints the robot
# that includes it writes; with the companions that robot is checked with
BLOCKS = """<robot>
  <gazebo reference="base_link"><mu1>0.5</mu1></gazebo>
  <gazebo reference="laser">
    <sensor type="ray" name="laser">
      <plugin name="laser" filename="libgazebo_ros_laser.so">
        <frameName>laser</frameName><topicName>scan</topicName>
      </plugin>
    </sensor>
  </gazebo>
  <gazebo>
    <plugin name="drive" filename="libgazebo_ros_diff_drive.so">
      <leftJoint>left_wheel_joint</leftJoint><rightJoint>right_wheel_joint</rightJoint>
      <wheelSeparation>0.4</wheelSeparation><wheelDiameter>0.2</wheelDiameter>
      <robotBaseFrame>base_footprint</robotBaseFrame>
    </plugin>
  </gazebo>
  <gazebo><plugin name="control" filename="libgazebo_ros_control.so"/></gazebo>
  <transmission name="head_transmission">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="head_joint">
      <hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface>
    </joint>
    <actuator name="head_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
</robot>
"""
CONTROLLERS = """head_controller:
  type: position_controllers/JointTrajectoryController
  joints: [head_joint]
joint_state_controller:
  type: joint_state_controller/JointStateController
  publish_rate: 50
"""
SRDF = """<robot name="r">
  <group name="head"><joint name="head_joint"/><link name="head"/></group>
  <disable_collisions link1="base_link" link2="head" reason="Adjacent"/>
</robot>
"""
SPEC = """unit: deg
joints:
  head_joint: {lower: -60, upper: 60}
"""


def _blocks(tmp_path, robot=BLOCKS):
    return check_folder(tmp_path, {"robot.urdf": robot, "config/controllers.yaml": CONTROLLERS},
                        select=("U",), controllers=(str(tmp_path / "config/controllers.yaml"),),
                        srdf=_write(tmp_path / "robot.srdf", SRDF),
                        spec=_write(tmp_path / "joint_limits.yaml", SPEC))[1]


def _write(path, text):
    path.write_text(text)
    return str(path)


def test_a_robot_of_extension_blocks_only_is_a_part_every_rule_notes(tmp_path):
    findings = _blocks(tmp_path)
    loud = [f"{f.code} {f.severity.value} {f.message}" for f in findings
            if f.severity.value != "info"]
    assert not loud, loud
    codes = {f.code for f in findings}
    assert {"U011", "U106", "U501", "U611", "U612", "U615", "U616", "U702", "U803",
            "U804"} <= codes, codes
    assert all(f.message.startswith("a part of a robot defined elsewhere (no link of its own, "
                                    "only <gazebo> and <transmission> blocks)")
               for f in findings if f.code in ABOUT_THE_ROBOT)


def test_what_the_blocks_say_of_themselves_stays(tmp_path):
    """A part's own mistakes hold inside any robot: an unknown plugin parameter, a hardware
    interface misspelt."""
    robot = BLOCKS.replace("<wheelDiameter>", "<wheelDiametre>").replace(
        "</wheelDiameter>", "</wheelDiametre>").replace("PositionJointInterface",
                                                        "PositionJointInterfce")
    loud = {f.code: f.severity.value for f in _blocks(tmp_path, robot)
            if f.severity.value != "info"}
    assert loud == {"U503": "error", "U641": "warning"}, loud


def test_a_robot_with_a_link_of_its_own_is_judged_as_a_robot(tmp_path):
    robot = BLOCKS.replace("<robot>", '<robot name="r"><link name="base_link"/>')
    loud = {f.code for f in _blocks(tmp_path, robot) if f.severity.value == "error"}
    assert {"U501", "U611", "U612", "U615", "U616", "U702", "U803", "U804"} <= loud, loud


def test_a_robot_with_nothing_in_it_is_not_a_part(tmp_path):
    findings = check_folder(tmp_path, {"robot.urdf": '<robot name="r"><material name="m"/></robot>'},
                            select=("U1",))[1]
    assert [(f.code, f.severity.value) for f in findings] == [("U106", "error")]


LAUNCH = """
from launch import LaunchDescription
from launch.substitutions import Command, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare

def generate_launch_description():
    robot = Command(["xacro ", PathJoinSubstitution([FindPackageShare("p"), "robot.urdf"])])
    return LaunchDescription([Node(package="robot_state_publisher",
                                   executable="robot_state_publisher",
                                   parameters=[{"robot_description": robot}])])
"""


def test_a_robot_a_launch_file_runs_as_it_is_checked_is_no_part(tmp_path):
    """What a launch file gives robot_state_publisher as the robot description, unconditionally
    and with the arguments it was checked with, is a whole robot, however little it writes:
    no link is an error there (it is certain), not a part's note."""
    files = {"robot.urdf": BLOCKS, "package.xml": "<package format='3'><name>p</name></package>",
             "launch/robot.launch.py": LAUNCH}
    (tmp_path / ".git").mkdir(parents=True, exist_ok=True)
    errors = {f.code for f in check_folder(tmp_path, files, select=("U1",))[1]
              if f.severity.value == "error"}
    assert "U106" in errors, errors
    other = tmp_path / "other"
    (other / ".git").mkdir(parents=True)
    files["launch/robot.launch.py"] = LAUNCH.replace('"robot.urdf"', '"other.urdf"')
    assert not [f for f in check_folder(other, files, select=("U1",))[1]
                if f.severity.value == "error"]


def _names_the_robot(function) -> bool:
    """Whether a rule compares a name with the robot's links or joints, saying which exist
    (``available('links', name, robot.links)``)."""
    for node in ast.walk(ast.parse(textwrap.dedent(inspect.getsource(function)))):
        if isinstance(node, ast.Call) and getattr(node.func, "id", None) == "available" and \
                len(node.args) == 3 and isinstance(node.args[2], ast.Attribute) and \
                getattr(node.args[2].value, "id", None) == "robot" and \
                node.args[2].attr in ("links", "joints"):
            return True
    return False


# Rules that compare names with the robot's and cannot fire on a robot with no link and no joint
# (a joint's ends, a mimic joint): judged on a part by themselves
_JUDGED_BY_THEMSELVES = {"U105", "U209"}


def test_every_rule_comparing_names_with_the_robot_notes_them_on_a_part():
    """The guard for a new rule: one that says a link or joint is not the robot's must be in
    ABOUT_THE_ROBOT (or say why not here)."""
    naming = {value.rule.code for module in FAMILY_MODULES for value in vars(module).values()
              if callable(value) and hasattr(value, "rule") and
              getattr(value, "__module__", None) == module.__name__ and _names_the_robot(value)}
    assert naming, "the guard finds nothing: the rules no longer say names this way"
    missing = naming - ABOUT_THE_ROBOT - _JUDGED_BY_THEMSELVES
    assert not missing, f"rules comparing names with the robot's, not judged on a part: {missing}"


# Robots whose text shows every link and joint (no macro call, no include): the walk reads
# the text (targets._root_elsewhere), a check the expansion (parts.part); name -> (text, part?)
_ROOTS = {
    "hangs": ('<link name="cam"/><joint name="j" type="fixed"><parent link="front_mount"/>'
              '<child link="cam"/></joint>', True),
    "joints only": ('<joint name="j" type="fixed"><parent link="front_mount"/>'
                    '<child link="cam"/></joint>', True),
    "fixed to the world, joints only": ('<joint name="j" type="fixed"><parent link="world"/>'
                                        '<child link="base_link"/></joint>', True),
    "fixed to the world": ('<link name="a"/><joint name="j" type="fixed"><parent link="world"/>'
                           '<child link="a"/></joint>', False),
    "the world and a mount": ('<link name="a"/><link name="b"/><joint name="j" type="fixed">'
                              '<parent link="world"/><child link="a"/></joint><joint name="k" '
                              'type="fixed"><parent link="torso"/><child link="b"/></joint>', True),
    "a misspelt parent": ('<link name="base"/><link name="cam"/><joint name="j" type="fixed">'
                          '<parent link="bsae"/><child link="cam"/></joint>', False),
    "a root of its own": ('<link name="base"/><link name="cam"/><joint name="j" type="fixed">'
                          '<parent link="base"/><child link="cam"/></joint>', False),
    "no joint": ('<link name="base"/>', False),
}


def test_the_walk_and_a_check_decide_a_root_elsewhere_alike(tmp_path):
    """One owner (parts.rootless) for 'no root link of its own', whether the text is read (the
    folder walk skips the file) or the expansion (a check notes what the part cannot be
    right about): a robot with joints and no link is a part either way."""
    from conftest import load_text
    from urdftool.lint.parts import part
    from urdftool.lint.targets import _root_elsewhere

    decided, said = {}, {}
    for name, (body, _) in _ROOTS.items():
        text = f'<robot name="r">{body}</robot>'
        walked = _root_elsewhere(text.encode(), expanded=False)
        found = part(load_text(tmp_path, text))
        decided[name] = (bool(walked), found is not None)
        said[name] = (walked, found.condition if found else None)
    assert decided == {name: (expected, expected) for name, (_, expected) in _ROOTS.items()}
    assert all(walked == checked for walked, checked in said.values()), said


def test_a_part_with_joints_and_no_link_notes_what_only_its_includer_writes(tmp_path):
    """A mount's joints between links other files write (jackal's custom_example.urdf, built
    by a macro): U106, U105 on both ends, and every name compared with the robot's are notes."""
    robot = ('<robot name="r"><joint name="head_joint" type="revolute"><parent link="torso"/>'
             '<child link="head"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" '
             'velocity="1"/></joint>' + BLOCKS.split("<robot>", 1)[1])
    findings = _blocks(tmp_path, robot)
    loud = [f"{f.code} {f.severity.value} {f.message}" for f in findings
            if f.severity.value != "info"]
    assert not loud, loud
    assert {"U105", "U106", "U611"} <= {f.code for f in findings}


def test_a_library_of_colours_named_urdf_is_a_part(tmp_path):
    """TurtleBot3's common_properties.urdf: only <material> definitions, for xacro to include
    (its include is commented out); no link is a note, what its colours say stays."""
    robot = ('<robot name="xacro_properties"><material name="black"><color rgba="0 0 0 1"/>'
             '</material><material name="grey"><color rgba="0.5 0.5 0.5 1"/></material></robot>')
    findings = check_folder(tmp_path, {"robot.urdf": robot}, select=("U1",))[1]
    assert [(f.code, f.severity.value) for f in findings] == [("U106", "info")]
    assert findings[0].message.startswith("a part of a robot defined elsewhere (no link of its "
                                          "own, only <material> definitions")
