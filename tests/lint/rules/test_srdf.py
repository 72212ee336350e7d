"""U80x SRDF rules, on tiny models and on the humanoid's SRDF."""

from __future__ import annotations

from conftest import CASES
from crossfile_helpers import HEAD_ROBOT, broken_copy, check_folder

ROBOT = HEAD_ROBOT.format(body="")


def srdf(body: str, name: str = "r") -> str:
    return f"<robot name='{name}'>\n{body}\n</robot>\n"


def test_valid_srdf_with_virtual_and_pinocchio_root_joints(tmp_path):
    body = """<virtual_joint name="world_joint" type="floating" parent_frame="world" child_link="base_link"/>
<group name="head"><chain base_link="base_link" tip_link="head"/></group>
<group name="all"><group name="head"/><joint name="world_joint"/></group>
<group_state name="home" group="all"><joint name="head_joint" value="1"/><joint name="root_joint" value="0 0 0 0 0 0 1"/></group_state>
<end_effector name="eef" parent_link="head" group="head"/>
<disable_collisions link1="base_link" link2="cam" reason="Never"/>"""
    assert check_folder(tmp_path, {"robot.urdf": ROBOT, "robot.srdf": srdf(body)})[0] == []


def test_srdf_names_are_read_trimmed_as_srdfdom_reads_them(tmp_path):
    """srdfdom trims every name it reads (boost::trim): the group "arm " is the group "arm",
    its link " head" the URDF's head (a false U805/U804 before)."""
    body = """<group name="arm "><chain base_link=" base_link" tip_link="head "/></group>
<group name="all"><group name=" arm"/></group>
<group_state name="up" group="arm\t"><joint name=" head_joint" value="1"/></group_state>
<disable_collisions link1="base_link " link2=" head" reason="Adjacent"/>"""
    assert check_folder(tmp_path, {"robot.urdf": ROBOT, "robot.srdf": srdf(body)})[0] == []


def test_each_srdf_reference_is_located_in_the_srdf(tmp_path):
    body = """<group name="arm">
  <joint name="elbow"/>
  <link name="hand"/>
  <group name="legs"/>
</group>
<group_state name="home" group="arm"><joint name="head_joint" value="2"/></group_state>
<passive_joint name="wheel"/>"""
    found, _ = check_folder(tmp_path, {"robot.urdf": ROBOT, "robot.srdf": srdf(body, "other")})
    assert found == [("robot.srdf", 1, "U802"), ("robot.srdf", 3, "U803"), ("robot.srdf", 4, "U804"),
                     ("robot.srdf", 5, "U805"), ("robot.srdf", 7, "U806"), ("robot.srdf", 8, "U803")]


def test_srdf_given_on_the_command_line(tmp_path):
    found, _ = check_folder(tmp_path, {"robot.urdf": ROBOT, "moveit/x.srdf": "<robot name='r'><group"},
                            srdf=str(tmp_path / "moveit/x.srdf"))
    assert found == [("x.srdf", 1, "U801")]


def test_a_double_hyphen_in_a_comment_is_read_as_srdfdom_reads_it(tmp_path):
    """UM-ARM-Lab's victor.srdf (<!-- ------ -->), loaded with ROS 1's textfile=: srdfdom's
    TinyXML2 reads it, so MoveIt does; it was a U801 error saying MoveIt refuses it, and nothing
    of the SRDF was checked. A warning (xacro, and so MoveItConfigsBuilder, refuses it), and the
    SRDF is checked as srdfdom reads it."""
    body = "<!-- ------------ -->\n<group name='arm'><link name='hed'/></group>"
    found, findings = check_folder(tmp_path, {"robot.urdf": ROBOT, "robot.srdf": srdf(body)})
    assert found == [("robot.srdf", 2, "U801"), ("robot.srdf", 3, "U804")]
    assert findings[0].severity.value == "warning" and "srdfdom reads it" in findings[0].message


def test_an_srdf_read_despite_a_double_hyphen_says_why_it_is_not_fixed(tmp_path):
    """The fixes' tag scanner reads no tag of khi_duaro.srdf ('--!>' in a comment): the
    entry U811 offers was not written 'as the SRDF has no </robot>', which it has."""
    from urdftool.description.documents import read_srdf
    from urdftool.lint.rules.srdf import _add_entry

    path = tmp_path / "r.srdf"
    path.write_text("<robot name='r'>\n<!-- <virtual_joint/> --!>\n<!-- x -->\n</robot>\n")
    srdf = read_srdf(path)
    assert srdf.problem is None and srdf.caution
    assert "holds '--' in a comment" in _add_entry(srdf, ("a", "b"), "Default").reason


def test_an_entity_the_srdf_declares_is_read_as_srdfdom_reads_it(tmp_path):
    """libxml2 (lxml) expanded <group name="&g;"> to "head" where srdfdom's TinyXML2 keeps the
    characters "&g;" (check_urdf 6.0, the same TinyXML2, reads <link name="&g;"> so): every
    SRDF rule judged a group MoveIt does not have, silently. A warning, and the SRDF checked as
    srdfdom reads it; an external entity is no error either (lxml refused it: "MoveIt refuses
    to start with it", which srdfdom reads as text), nor a bomb expanded; a declaration never
    used changes nothing."""
    lol = "".join(f'<!ENTITY a{i} "{"&a%d;" % (i - 1) * 10 if i else "lol"}">' for i in range(10))
    for doctype, use, warned in (
            ('<!ENTITY g "head">', "&g;", True),
            ('<!ENTITY g SYSTEM "file:///etc/hostname">', "&g;", True),
            (lol, "&a9;", True),
            ('<!ENTITY g "x"><!ENTITY % p "y">', "head", False)):
        body = (f'<group name="{use}"><chain base_link="base_link" tip_link="head"/></group>\n'
                '<group_state name="up" group="head"><joint name="head_joint" value="1"/>'
                '</group_state>')
        text = f"<!DOCTYPE robot [{doctype}]>\n{srdf(body)}"
        found, findings = check_folder(tmp_path / str(len(text)),
                                       {"robot.urdf": ROBOT, "robot.srdf": text})
        if not warned:
            assert found == [], doctype
            continue
        assert found == [("robot.srdf", 3, "U801"), ("robot.srdf", 4, "U805")], doctype
        assert findings[0].severity.value == "warning" and "TinyXML2" in findings[0].message
        assert f"available groups: {use}" in findings[1].message


def test_srdf_that_is_not_a_robot(tmp_path):
    found, findings = check_folder(tmp_path, {"robot.urdf": ROBOT, "robot.srdf": "<?xml version='1.0'?>\n<group/>"})
    assert found == [("robot.srdf", 2, "U801")] and "<group>" in findings[0].message


def test_humanoid_home_pose_outside_limits(tmp_path):
    findings = broken_copy(tmp_path, "humanoid", "humanoid.srdf", '<joint name="l_knee" value="0"/>',
                           '<joint name="l_knee" value="-0.5"/>')
    assert [(f.code, f.file.endswith("humanoid.srdf")) for f in findings] == [("U806", True)]
    assert "outside its URDF limits [0, 2.26893]" in findings[0].message


def test_a_tag_written_across_lines_is_located_where_it_begins(tmp_path):
    body = """<disable_collisions link1="base_link"
    link2="hed"
    reason="Never"/>"""
    found, _ = check_folder(tmp_path, {"robot.urdf": ROBOT, "robot.srdf": srdf(body)})
    assert found == [("robot.srdf", 2, "U804")]


ARM = """<robot name="r">
  <link name="base_link"/><link name="shoulder"/><link name="upper"/><link name="hand"/><link name="cam"/>
  <joint name="pan" type="revolute"><parent link="base_link"/><child link="shoulder"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="5" velocity="1"/></joint>
  <joint name="lift" type="revolute"><parent link="shoulder"/><child link="upper"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="5" velocity="1"/></joint>
  <joint name="wrist" type="revolute"><parent link="upper"/><child link="hand"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="5" velocity="1"/></joint>
  <joint name="cam_joint" type="fixed"><parent link="base_link"/><child link="cam"/></joint>
</robot>
"""


def test_group_membership_follows_moveit(tmp_path):
    # a link implies its parent joint; a subgroup brings its joints; a chain brings the joints
    # from its tip up to (not above) its base
    body = """<group name="by_links"><link name="upper"/><link name="hand"/></group>
<group name="chain"><chain base_link="shoulder" tip_link="hand"/></group>
<group name="all"><group name="chain"/><joint name="pan"/></group>
<group_state name="a" group="by_links"><joint name="lift" value="0"/><joint name="wrist" value="0"/></group_state>
<group_state name="b" group="all"><joint name="pan" value="0"/><joint name="lift" value="0"/></group_state>
<group_state name="c" group="chain"><joint name="pan" value="0"/></group_state>
<end_effector name="e" parent_link="hand" parent_group="by_links" group="chain"/>
<end_effector name="f" parent_link="shoulder" parent_group="chain" group="all"/>"""
    found, findings = check_folder(tmp_path, {"robot.urdf": ARM, "robot.srdf": srdf(body)})
    assert found == [("robot.srdf", 7, "U808"), ("robot.srdf", 9, "U809")]
    assert "not part of group 'chain' (its joints: lift, wrist)" in findings[0].message
    assert "parent_link 'shoulder'" in findings[1].message


def test_duplicate_group_points_at_the_second_definition(tmp_path):
    body = '<group name="g"><joint name="pan"/></group>\n<group name="h"/>\n<group name="g"><joint name="lift"/></group>'
    found, findings = check_folder(tmp_path, {"robot.urdf": ARM, "robot.srdf": srdf(body)})
    assert found == [("robot.srdf", 4, "U807")] and "first at line 2" in findings[0].message


# two arms from base_link; the hands (fixed to the upper arms) meet when the arms swing in
BOXES = (CASES / "U810_srdf_disabled_pair_collides" / "robot.urdf").read_text()
ARMS = '<group name="arms"><joint name="l_sho"/><joint name="r_sho"/></group>\n'
HUG = ('<group_state name="hug" group="arms"><joint name="l_sho" value="0.7"/>'
       '<joint name="r_sho" value="-0.7"/><joint name="root_joint" value="0 0 0 0 0 0 1"/></group_state>\n')


def test_which_disable_reasons_may_hide_a_collision(tmp_path):
    for reason, expected in (("Never", ["U810"]), ("User", ["U810"]), ("", ["U810"]),
                             ("Default", []), ("Always", []), ("Adjacent", [])):
        body = ARMS + HUG + f'<disable_collisions link1="r_hand" link2="l_hand" reason="{reason}"/>'
        found, findings = check_folder(tmp_path, {"robot.urdf": BOXES, "robot.srdf": srdf(body)},
                                       select=("U810", "U811"))
        assert [code for _, _, code in found] == expected, reason
        if expected:
            assert found[0][1] == 4 and "at group state 'hug' of 'arms'" in findings[0].message


def test_an_overlap_at_the_default_pose_is_reported_at_robot(tmp_path):
    near = BOXES.replace('xyz="0 0.3 0"', 'xyz="0 0.04 0"').replace('xyz="0 -0.3 0"', 'xyz="0 -0.04 0"')
    found, findings = check_folder(tmp_path, {"robot.urdf": near, "robot.srdf": srdf(ARMS)},
                                   select=("U810", "U811"))
    # the hands overlap; base_link touches the upper arms, but they are adjacent: not reported
    assert found == [("robot.srdf", 1, "U811")] and "l_hand and r_hand collide" in findings[0].message
    assert "at the default configuration" in findings[0].message and 'reason="Default"' in findings[0].message


def test_no_pose_check_without_an_srdf_or_geometry(tmp_path):
    assert check_folder(tmp_path, {"robot.urdf": BOXES}, select=("U810", "U811"))[0] == []
    assert check_folder(tmp_path, {"robot.urdf": ARM, "robot.srdf": srdf("")}, select=("U810", "U811"))[0] == []


def _repository(root, files: dict) -> None:
    """A repository (its .git) at ``root`` holding ``files`` (relative path -> text)."""
    (root / ".git").mkdir()
    for name, text in files.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text)


def test_the_srdf_a_launch_file_gives_moveit_is_the_robots_and_judged_with_its_arguments(tmp_path):
    # MoveIt's launch file builds the robot with its gripper (gripper:=true) and gives it
    # config/arm.srdf: the finger the SRDF names is not in the robot as checked (gripper false),
    # which is a warning naming the launch file, not an error; robot.srdf beside it is not used
    from urdftool.diagnostics import Severity
    from urdftool.lint.engine import CheckOptions, load_and_check

    files = {
        "package.xml": "<package format='2'><name>arm_pkg</name></package>",
        "arm.urdf.xacro": """<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="gripper" default="false"/>
  <link name="base"/><link name="tool"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="tool"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <xacro:if value="$(arg gripper)">
    <link name="finger"/>
    <joint name="finger_joint" type="prismatic"><parent link="tool"/><child link="finger"/>
      <axis xyz="1 0 0"/><limit lower="0" upper="0.04" effort="1" velocity="1"/></joint>
  </xacro:if>
</robot>""",
        "arm.srdf": '<robot name="arm"><group name="other"><joint name="nope"/></group></robot>',
        "config/arm.srdf": '<robot name="arm"><group name="hand"><joint name="finger_joint"/></group></robot>',
        "launch/planning_context.launch": """<launch>
  <param name="robot_description" command="xacro $(find arm_pkg)/arm.urdf.xacro gripper:=true"/>
  <param name="robot_description_semantic" textfile="$(find arm_pkg)/config/arm.srdf"/>
</launch>"""}
    _repository(tmp_path, files)
    result = load_and_check(str(tmp_path / "arm.urdf.xacro"), CheckOptions())
    found = [(f.file.rsplit("/", 2)[-2:], f.code, f.severity) for f in result.findings if f.code.startswith("U8")]
    assert found == [(["config", "arm.srdf"], "U803", Severity.INFO)], result.findings
    assert "launch/planning_context.launch gives MoveIt this SRDF with the robot with other xacro " \
           "arguments (gripper:=true)" in result.findings[0].message
    assert any("srdf: " in line and "given to MoveIt by" in line for line in result.companions)


def test_an_srdf_moveit_gets_only_with_another_robot_file_is_a_note_on_this_one(tmp_path):
    """UM-ARM-Lab's victor.urdf, generated long ago beside the victor.urdf.xacro that every
    launch file gives MoveIt with victor.srdf: the SRDF checked against the stale .urdf was
    U804 errors (its gripper links renamed since) and U823 warnings for a pairing MoveIt never
    runs. Notes saying so; checked against the .urdf alone (no launch file), still errors."""
    from urdftool.diagnostics import Severity
    from urdftool.lint.engine import CheckOptions, load_and_check

    files = {
        "package.xml": "<package format='2'><name>arm_pkg</name></package>",
        "urdf/arm.urdf": ROBOT, "urdf/arm.urdf.xacro": ROBOT,
        "config/arm.srdf": srdf('<group name="hand"><link name="r_palm"/></group>'),
        "launch/demo.launch": """<launch>
  <param name="robot_description" command="xacro $(find arm_pkg)/urdf/arm.urdf.xacro"/>
  <param name="robot_description_semantic" textfile="$(find arm_pkg)/config/arm.srdf"/>
</launch>"""}
    _repository(tmp_path, files)

    def u804(robot):
        return [(f.severity, f.message) for f in load_and_check(
            str(tmp_path / robot), CheckOptions()).findings if f.code == "U804"]

    [(severity, message)] = u804("urdf/arm.urdf")
    assert severity is Severity.INFO
    assert "launch/demo.launch gives MoveIt this SRDF with " in message, message
    assert "urdf/arm.urdf.xacro, another robot file): SRDF <link name='r_palm'>" in message
    assert [severity for severity, _ in u804("urdf/arm.urdf.xacro")] == [Severity.ERROR]
    (tmp_path / "launch/demo.launch").unlink()
    assert [severity for severity, _ in u804("urdf/arm.urdf")] == [Severity.ERROR]


def test_an_srdf_moveit_gets_only_with_a_package_arguments_default_is_a_warning_saying_so(tmp_path):
    # DENSO's and Elite's MoveIt launch files name the robot's package by a launch argument
    # (description_package): MoveIt runs with this SRDF and the robot as checked when it keeps
    # its default, so the mismatch is a warning naming that, not an error for every launch
    from urdftool.diagnostics import Severity

    (tmp_path / ".git").mkdir()
    _, findings = check_folder(tmp_path, {
        "package.xml": "<package format='2'><name>arm_pkg</name></package>", "robot.urdf": ARM,
        "config/arm.srdf": srdf('<group name="hand"><joint name="finger_joint"/></group>'),
        "launch/moveit.launch": """<launch>
          <arg name="description_package" default="arm_pkg"/>
          <param name="robot_description" textfile="$(find $(arg description_package))/robot.urdf"/>
          <param name="robot_description_semantic" textfile="$(find arm_pkg)/config/arm.srdf"/>
        </launch>"""}, select=("U803",))
    [finding] = findings
    assert finding.severity is Severity.WARNING
    assert "launch/moveit.launch gives MoveIt this SRDF with the robot as checked when launched " \
           "with description_package's default 'arm_pkg': " in finding.message


def test_a_collision_pair_naming_an_unknown_link_is_a_warning_a_group_link_an_error(tmp_path):
    """srdfdom drops a collision pair naming a link the URDF lacks with a warning (it has no
    effect; an SRDF shared by a robot's variants lists each one's pairs: deepwithin's YAM);
    a group's link, chain or end effector it drops with an error, and MoveIt plans without it."""
    body = """<group name="head"><link name="hed"/></group>
<disable_collisions link1="base_link" link2="gripper_base" reason="Adjacent"/>"""
    _, findings = check_folder(tmp_path, {"robot.urdf": ROBOT, "robot.srdf": srdf(body)})
    said = [(f.code, f.location.line, f.severity.value) for f in findings if f.code == "U804"]
    assert said == [("U804", 2, "error"), ("U804", 3, "warning")], said
    assert "MoveIt drops the pair (it has no effect)" in findings[-1].message


def test_the_only_srdf_of_a_repository_is_not_another_robots(tmp_path):
    """deepwithin/yam_ros2_control: its one SRDF (<robot name="i2rt_arm">) was checked against
    the other arm of the repository, alone in its folder and named 'output' (33 errors); the
    robot file named 'i2rt_arm', which looks for companions where it is, claims it; with no
    such robot it is ours."""
    (tmp_path / ".git").mkdir()
    other = HEAD_ROBOT.format(body="").replace("name='r'", "name='arm'").replace(
        'name="r"', 'name="arm"')
    files = {"robot.urdf": ROBOT, "config/arm.urdf": other,  # (it looks for companions there)
             "config/arm.srdf": srdf('<group name="g"><link name="hand"/></group>', "arm")}
    found, _ = check_folder(tmp_path, files)
    assert not [f for f in found if f[0] == "arm.srdf"], found
    files["config/arm.urdf"] = other.replace("name='arm'", "name='b'").replace('name="arm"', 'name="b"')
    found, _ = check_folder(tmp_path, files)
    assert ("arm.srdf", 1, "U802") in found, found  # the only SRDF, of no robot here: ours
    # a robot file over 1 MiB is not read for its name (a hostile repository's costs bounded)
    files["config/arm.urdf"] = other.replace("<link", "<!--" + "x" * (1 << 20) + "--><link", 1)
    found, _ = check_folder(tmp_path, files)
    assert ("arm.srdf", 1, "U802") in found, found


def test_a_cycle_of_subgroups_is_one_finding_each_as_srdfdom_drops_it(tmp_path):
    """srdfdom's ``loadGroups`` keeps a group once each of its subgroups is kept: a cycle is
    never kept, nor a group holding one. One finding a cycle, at the subgroup of its first
    group that closes it; a group held by an undefined name only is U805's."""
    body = """<group name="a"><group name="b"/><joint name="head_joint"/></group>
<group name="b"><group name="c"/></group>
<group name="c"><group name="a"/></group>
<group name="self"><group name="self"/></group>
<group name="holder"><group name="c"/></group>
<group name="lost"><group name="nowhere"/></group>
<group name="fine"><group name="head"/></group>
<group name="head"><joint name="head_joint"/></group>
<group><group/></group>
<group name="t "><group name="t "/></group>"""  # no name: srdfdom skips it
    found, findings = check_folder(tmp_path, {"robot.urdf": ROBOT, "robot.srdf": srdf(body)})
    assert found == [("robot.srdf", 2, "U824"), ("robot.srdf", 5, "U824"), ("robot.srdf", 7, "U805"),
                     ("robot.srdf", 11, "U824")]
    assert "('a' > 'b' > 'c' > 'a')" in findings[0].message and "holding one: holder" in findings[0].message
    assert "('self' > 'self')" in findings[1].message and "holding" not in findings[1].message


def test_subgroups_leading_to_a_cycle_through_a_long_chain_are_walked_without_recursion(tmp_path):
    """5,000 groups each holding the next, the last holding the first of a cycle of two,
    written deepest last (the order that was as deep as it was long in session 11)."""
    chain = "\n".join(f'<group name="g{i}"><group name="g{i + 1}"/></group>' for i in range(5000))
    body = chain + '\n<group name="g5000"><group name="x"/></group>\n<group name="x"><group name="g5000"/></group>'
    found, findings = check_folder(tmp_path, {"robot.urdf": ROBOT, "robot.srdf": srdf(body)})
    assert found == [("robot.srdf", 5002, "U824")]
    assert "('g5000' > 'x' > 'g5000')" in findings[0].message and findings[0].message.count(", g") == 4 \
        and "g4999, g4998" not in findings[0].message and ", ..." in findings[0].message


def test_an_unknown_srdf_joint_is_offered_moveits_joints_only(tmp_path):
    """StanleyInnovation's robotiq_85_gripper.srdf names kinova_robotiq_coupler_joint, which the
    URDF lacks: the joints offered are the URDF's and the SRDF's virtual joints, which MoveIt
    knows; Pinocchio's 'root_joint', accepted so that its group states pass, is no joint MoveIt
    has, and was offered as one."""
    body = """<virtual_joint name="world_joint" type="fixed" parent_frame="world" child_link="base_link"/>
<group name="gripper"><joint name="coupler_joint"/></group>"""
    found, findings = check_folder(tmp_path, {"robot.urdf": ROBOT, "robot.srdf": srdf(body)})
    [message] = [f.message for f in findings if f.code == "U803"]
    assert "world_joint" in message and "head_joint" in message
    assert "root_joint" not in message, message
