"""U02x: the URDF vocabulary (misspelt elements and attributes, content urdfdom ignores)."""

from __future__ import annotations

import pytest

from crossfile_helpers import check_folder
from urdftool.description.urdf import EXTENSIONS, VOCABULARY, where_valid

ISSUE_EXAMPLE = """<robot name="r"><link name="a"/><link name="b"/>
<joint name="j" type="revolute"><parent link="a"/><child link="b"/>
  <orgin xyz="0 0 1"/>
  <limit lower="-1" uper="1" effort="1" velocity="1"/>
  <dynamics><damping>100</damping></dynamics>
</joint>
</robot>
"""


def _check(tmp_path, text):
    return check_folder(tmp_path, {"robot.urdf": text}, select=("U02",))


def test_the_issue_example_names_each_misspelling_at_its_line(tmp_path):
    found, findings = _check(tmp_path, ISSUE_EXAMPLE)
    assert found == [("robot.urdf", 3, "U020"), ("robot.urdf", 4, "U021"),
                     ("robot.urdf", 5, "U020")]
    messages = [f.message for f in findings]
    assert "did you mean 'origin'?" in messages[0]
    assert "did you mean 'upper'?" in messages[1]
    assert 'reads damping as an attribute: <dynamics damping="100"/>' in messages[2]


def test_unknown_names_deep_in_known_elements_are_found_in_document_order(tmp_path):
    # leaves judged in their parent's loop, attributes compared as a set first: an unknown
    # one among known ones, on a leaf and on an element with children, is still each reported
    found, findings = _check(tmp_path, """<robot name="r">
      <link name="a"><visual><origin xyz="0 0 0" rpi="0 0 0"/>
        <geometry><box size="1 1 1" sise="1"/></geometry></visual>
        <inertial><mas value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
        </inertial></link>
      <link name="b" typ="x"/></robot>""")
    assert [(line, code) for _, line, code in found] == [(2, "U022"), (3, "U021"),
                                                         (4, "U020"), (6, "U021")]
    assert ["'rpi' has no effect" in findings[0].message, "'size'" in findings[1].message,
            "'mass'" in findings[2].message, "'type'" in findings[3].message] == [True] * 4


def test_an_attribute_written_for_an_element_says_so(tmp_path):
    found, findings = _check(tmp_path, """<robot name="r"><link name="a"/><link name="b"/>
      <joint name="j" type="fixed" child="b"><parent link="a"/><child link="b"/></joint></robot>""")
    assert [c for _, _, c in found] == ["U021"]
    assert "reads child as an element" in findings[0].message


def test_an_attribute_another_program_reads_is_a_note_saying_which(tmp_path):
    """Isaac Gym's assets (legged_gym, unitree_rl_gym) and the Go2 and ANYmal descriptions
    copied from them mark feet and sensor frames ``dont_collapse="true"``: 233 U022 warnings,
    each judged DEBATABLE, on an attribute written on purpose for the importer that reads it.
    An unknown attribute beside it is still a warning of its own."""
    from urdftool.diagnostics import Severity

    found, findings = _check(tmp_path, """<robot name="r"><link name="a"/><link name="b"/>
      <joint name="j" type="fixed" dont_collapse="true" colour="red"><parent link="a"/>
        <child link="b"/></joint></robot>""")
    assert [(line, code) for _, line, code in found] == [(2, "U022"), (2, "U022")]
    by_severity = {f.severity: f.message for f in findings}
    assert "'dont_collapse'" in by_severity[Severity.INFO]
    assert "Isaac Gym's and Isaac Sim's URDF importers" in by_severity[Severity.INFO]
    assert "'colour'" in by_severity[Severity.WARNING]
    assert "dont_collapse" not in by_severity[Severity.WARNING]


@pytest.mark.parametrize("body", [
    '<gazebo reference="a"><mu1>1</mu1><material>Gazebo/Red</material><whatever x="1"/></gazebo>',
    '<sensor name="cam" update_rate="30"><parent link="a"/><camera><image width="640"/></camera></sensor>',
    '<mujoco><compiler meshdir="meshes" balanceinertia="true"/></mujoco>',
    '<drake:collision_filter_group name="g"><drake:member link="a"/></drake:collision_filter_group>',
    '<ros2_control name="s" type="system"><hardware><plugin>p</plugin></hardware></ros2_control>',
])
def test_extension_blocks_are_left_alone(tmp_path, body):
    found, _ = _check(tmp_path, f'<robot name="r" xmlns:drake="http://drake.mit.edu">'
                                f'<link name="a"/>{body}</robot>')
    assert found == []


def test_buoyancy_in_a_link_is_freefloating_gazebos_and_left_alone(tmp_path):
    # Xue1iang/mallard_urdf: freefloating_gazebo's fluid plugin reads the robot_description's
    # <link><buoyancy><compensation> (its ParseNewModel); only in a <link>: at the top level
    # nobody reads it (mallard's thruster.xacro writes one there, after its link)
    buoyancy = "<buoyancy><compensation>0.6</compensation></buoyancy>"
    found, _ = _check(tmp_path, f'<robot name="r"><link name="a">{buoyancy}</link></robot>')
    assert found == []
    found, findings = _check(tmp_path, f'<robot name="r"><link name="a"/>\n{buoyancy}</robot>')
    assert [(line, code) for _, line, code in found] == [(2, "U022")]
    assert findings[0].message.endswith("freefloating_gazebo's fluid plugin (ROS 1; origin, "
                                        "compensation, limit, damping) reads it only inside <link>")


def test_a_misspelling_in_a_known_extension_vocabulary_is_reported(tmp_path):
    found, findings = _check(tmp_path, """<robot name="r"><link name="a"/>
      <ros2_control name="s" type="system"><hardware><plugin>p</plugin></hardware>
        <joint name="j"><comand_interface name="position"/></joint></ros2_control></robot>""")
    assert [c for _, _, c in found] == ["U020"]
    assert "did you mean 'command_interface'?" in findings[0].message


def test_a_zero_axis_rpy_misleads_nobody_and_is_not_reported(tmp_path):
    joint = ('<joint name="j" type="continuous"><parent link="a"/><child link="b"/>'
             '<axis xyz="0 0 1" rpy="{rpy}"/></joint>')
    robot = '<robot name="r"><link name="a"/><link name="b"/>{joint}</robot>'
    assert _check(tmp_path, robot.format(joint=joint.format(rpy="0 0 0")))[0] == []
    found, findings = _check(tmp_path, robot.format(joint=joint.format(rpy="0 1.57 0")))
    assert [c for _, _, c in found] == ["U022"]
    assert "rotate the frame with the joint's <origin rpy>" in findings[0].message


def test_unread_attributes_of_one_element_are_one_finding(tmp_path):
    found, findings = _check(tmp_path, """<robot name="r"><link name="a"><inertial><mass value="1"/>
      <inertia ixx="1" ixy="0" ixz="0" iyx="0" iyy="1" iyz="0" izx="0" izy="0" izz="1"/>
      </inertial></link></robot>""")
    assert [c for _, _, c in found] == ["U022"]
    assert "attributes 'iyx', 'izx', 'izy' have no effect" in findings[0].message


def test_an_attribute_of_an_element_that_has_none_says_so(tmp_path):
    # ros2_jazzy_p3at's <geometry name="pioneer_geom">: the message ended "; it reads " and
    # nothing, <geometry> having no attributes to list
    found, findings = _check(tmp_path, """<robot name="r"><link name="a"><visual>
      <geometry name="g"><box size="1 1 1"/></geometry></visual></link></robot>""")
    assert [c for _, _, c in found] == ["U022"]
    assert findings[0].message.endswith("; URDF gives <geometry> no attributes"), findings[0].message


def test_an_element_in_the_wrong_place_says_where_it_belongs(tmp_path):
    found, findings = _check(tmp_path, """<robot name="r"><link name="a">
      <limit lower="0" upper="1" effort="1" velocity="1"/></link></robot>""")
    assert [c for _, _, c in found] == ["U022"]
    assert "urdfdom reads it only in <joint>" in findings[0].message


def test_only_the_first_shape_of_a_geometry_is_read(tmp_path):
    found, findings = _check(tmp_path, """<robot name="r"><link name="a"><visual><geometry>
      <box size="1 1 1"/>
      <sphere radius="1"/></geometry></visual></link></robot>""")
    assert found == [("robot.urdf", 3, "U022")]
    assert "only the first shape" in findings[0].message


def test_the_vocabulary_is_consistent_data():
    for name, place in VOCABULARY.items():
        assert place.source, f"{name} has no source"
        assert set(place.required) <= set(place.attributes), name
        assert all(child in VOCABULARY for child in place.children.values()), name
        assert not set(place.ignored) & set(place.names()), name
    assert where_valid("limit") == ["joint"]
    assert not set(EXTENSIONS) & set(VOCABULARY["robot"].children)


def test_xacro_left_in_a_urdf_is_u007s_not_the_vocabulary(tmp_path):
    found, _ = check_folder(tmp_path, {"robot.urdf": """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:property name="w" value="1"/>
      <link name="a"><xacro:grey/></link></robot>"""}, select=("U0",))
    assert {code for _, _, code in found} == {"U007"}


def test_a_known_name_with_a_word_added_is_an_extension_not_a_misspelling(tmp_path):
    """ANYmal-Kinova writes <limit gear_velocity=...> on purpose: it has no effect (a warning),
    it is not 'velocity' misspelt (an error); 'uper' still is."""
    robot = ('<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="revolute">'
             '<parent link="a"/><child link="b"/><limit lower="-1" uper="1" effort="1" '
             'velocity="1" gear_velocity="3"/></joint></robot>')
    found, findings = check_folder(tmp_path, {"robot.urdf": robot}, select=("U02",))
    assert [f.code for f in findings] == ["U021", "U022"]
    assert "'uper'" in findings[0].message and "'gear_velocity'" in findings[1].message


def test_a_word_of_a_known_name_is_not_its_misspelling(tmp_path):
    """franka's fr3 writes <joint mimic="..."> in <ros2_control>, beside the known is_mimic:
    another version's name, not a misspelling (was U021, found by the sweep)."""
    robot = ('<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="revolute">'
             '<parent link="a"/><child link="b"/><limit lower="-1" upper="1" effort="1" '
             'velocity="1"/></joint><ros2_control name="s" type="system"><hardware><plugin>'
             'mock_components/GenericSystem</plugin></hardware><joint name="j" mimic="true">'
             '<command_interface name="position"/></joint></ros2_control></robot>')
    assert check_folder(tmp_path, {"robot.urdf": robot}, select=("U021",))[0] == []


GROUPED = """<robot name="r"><!-- c --><link name="a"><visual><origin xyz="1 0 0"/><!-- v -->
<geometry><box size="1 1 1"/><sphere radius="1"/></geometry><origin xyz="2 0 0"/></visual>
<visual><geometry/></visual><colision/><inertial><mass value="1"/><?pi x?><mass value="2"/>
</inertial><gazebo><x/></gazebo></link><joint name="j" type="fixed"><parent link="a"/>
<child link="b"/><child link="c"/><orgin/></joint><link name="b"/><material name="m">
<color rgba="1 1 1 1"/></material><gazebo reference="a"><mu1>1</mu1></gazebo></robot>
"""


def test_elements_the_walk_listed_are_grouped_from_its_lists_as_lxml_lists_them(tmp_path,
                                                                              monkeypatch):
    """The vocabulary walk leaves the children it listed grouped by tag for Robot.grouped,
    which neither lists nor groups them again; the groups are those of its children listed
    afresh (comments, instructions, repeats, unknown and extension elements)."""
    from urdftool.description import robot as robots
    from urdftool.description.load import load
    from urdftool.lint.rules.vocabulary import _unknowns

    (tmp_path / "r.urdf").write_text(GROUPED)
    walked, fresh = load(str(tmp_path / "r.urdf")), load(str(tmp_path / "r.urdf"))
    _unknowns(walked)
    listings, child_list, by_tag = [], robots.child_list, robots._by_tag
    monkeypatch.setattr(robots, "child_list", lambda e: listings.append(e) or child_list(e))
    monkeypatch.setattr(robots, "_by_tag", lambda c: listings.append(c) or by_tag(c))
    for robot in (walked, fresh):
        shown = {}
        for element in robot.root.iter():
            if element.tag in ("robot", "link", "visual", "inertial", "joint", "material") \
                    and len(element):  # (what the walk walks into, but a <geometry>)
                shown[robot.locate(element)] = {tag: [robot.locate(e) for e in group]
                                                for tag, group in robot.grouped(element).items()}
        if robot is walked:
            assert not listings  # every one grouped by the walk, as it met the children
            found = shown
    assert found == shown and len(found) > 5, len(found)


def _alike_robot(joints: list[str], links: list[str]) -> str:
    """A robot of these joints' and links' inner text (one base link ``b``)."""
    parts = ['<robot name="r"><link name="b"/>']
    parts += [f'<link name="l{i}">{text}</link>' for i, text in enumerate(links)]
    parts += [f'<joint name="j{i}" type="revolute"><parent link="b"/><child link="l{i}"/>{text}'
              f'</joint>' for i, text in enumerate(joints)]
    return "\n".join(parts) + "\n</robot>\n"


ALIKE_JOINTS = ['<axis xyz="1 0 0" rpy="0 0 0"/>', '<axis xyz="1 0 0" rpy="0 0.5 0"/>',
                '<origin xyz="1 &quot;2&gt;&lt; 3"/>', '<origin xyz="1 2 3" rpi="0"/>',
                '<origin xyz="1 2 3"/>text a="b"', '<origin xyz="1 2 3"/><orgin/>',
                '<origin xmlns="urn:x" foo="1"/>', '<origin xmlns="" foo="1"/>',
                '<limit lower="0" upper="1" effort="1" velocity="1"/>',
                '<limit lower="0" upper="1" effort="1" velocity="1" uper="1"/>',
                '<limit lower="0" upper="1" effort="1" velocity="1"/>']
ALIKE_LINKS = ['<visual><geometry><box size="1 1 1"/></geometry></visual>',
               '<visual><geometry><box size="1 1 1"/><sphere radius="1"/></geometry></visual>',
               '<visual><geometry><box size="2 2 2"/></geometry></visual>',
               '<visual><geometry><box size="2 2 2"/></geometry><material name="m" '
               'colour="red"/></visual>'] * 2


def test_links_and_joints_of_one_shape_walked_once_give_the_findings_of_walking_each(
        tmp_path, monkeypatch):
    """A large robot's links and joints are walked once per shape (their markup without
    attribute values): a shape found clean is clean wherever it is, and what makes two of one
    shape differ for the walk (an axis rpy's value, a namespace declared) is walked each
    time. The findings, as many robots as shapes apart, are those of the walk of every
    element."""
    from urdftool.lint.rules import vocabulary

    text = _alike_robot(ALIKE_JOINTS * 2, ALIKE_LINKS)
    walks, walk = [], vocabulary._walk_children
    monkeypatch.setattr(vocabulary, "_walk_children", lambda *a: walks.append(a[0]) or walk(*a))
    everyone = _check(tmp_path / "every", text)
    walked = len(walks)
    monkeypatch.setattr(vocabulary, "ALIKE", 2)
    once = _check(tmp_path / "once", text)
    assert [(f.line, f.code, f.message) for f in once[1]] == \
        [(f.line, f.code, f.message) for f in everyone[1]]
    assert [code for _, _, code in once[0]].count("U022") >= 4  # two rpy, two rpi, ...
    assert len(once[0]) > 12, once[0]
    # not walked, each after one of its shape found clean: three links of a box (the link,
    # its visual, its geometry: 9 walks), and of the joints the second of each clean origin
    # (2), the second and third limit (the fourth, the last element, is walked: its markup
    # ends nowhere)
    assert len(walks) - walked == walked - 13, (walked, len(walks))


def test_a_robot_not_plain_enough_is_walked_whole(tmp_path, monkeypatch):
    from urdftool.lint.rules import vocabulary

    monkeypatch.setattr(vocabulary, "ALIKE", 2)
    walks, walk = [], vocabulary._walk_children
    monkeypatch.setattr(vocabulary, "_walk_children", lambda *a: walks.append(a[0]) or walk(*a))
    for extra in ("", "<!-- a -->", "<x a='1'/>", '<x>"</x>', '<x a=">"/>', "<?pi?>"):
        text = _alike_robot(ALIKE_JOINTS[8:] + ALIKE_JOINTS[8:9], [])
        walks.clear()
        _check(tmp_path / str(len(extra)), text.replace("</robot>", f"{extra}</robot>"))
        # the robot and its four joints, or (plain) the third (as the first) not walked
        assert len(walks) == (4 if not extra else 5), extra


NUMBERS_SPACED = """<robot name="r"><link name="a"/>
<link name="b"><visual><origin xyz="0.1\t0 0"/><geometry><box size="1 1 1&#9;"/></geometry>
  <material name="m"><color rgba="1 1 1 1&#9;"/></material></visual>
  <inertial><origin xyz=" 0 0 0.1 " rpy="\t0 0 0"/><mass value="2 "/>
  <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
<joint name="j" type="revolute"><parent link="a"/><child link="b"/>
  <origin xyz="0.1&#10;0 0"/><limit lower="-1 " upper="1" effort="1" velocity="1"/></joint>
<gazebo reference="b"><origin xyz="1\t0 0"/><mu1>0.5 </mu1></gazebo>
</robot>
"""


def test_numbers_with_white_space_urdfdom_refuses_are_found_as_written(tmp_path):
    # a raw tab inside a vector is a space to lxml and a tab to TinyXML2 (urdfdom): the file's
    # bytes are judged; white space before a number and spaces around a vector are read by
    # all; a <gazebo> block is not urdfdom's
    found, findings = check_folder(tmp_path, {"robot.urdf": NUMBERS_SPACED}, select=("U023",))
    assert found == [("robot.urdf", 2, "U023"), ("robot.urdf", 2, "U023"),
                     ("robot.urdf", 3, "U023"), ("robot.urdf", 4, "U023"), ("robot.urdf", 7, "U023"),
                     ("robot.urdf", 7, "U023")]
    messages = {f.line: [] for f in findings}
    for f in findings:
        messages[f.line].append(f.message)
    # measured with urdfdom 6.0's check_urdf and Pinocchio 4.1: a joint's number refuses the
    # robot, a link's inertial or visual ends the link's reading there, a colour is dropped
    assert any('<origin xyz="0.1\\t0 0">' in m and "refuses the robot" not in m and
               "PyBullet reads the vector as zeros" in m and 'write "0.1 0 0"' in m
               for m in messages[2])
    assert "drops the colour" in messages[3][0]
    assert any('<mass value="2 ">' in m and "without its mass (0 to KDL and Pinocchio)" in m
               and "PyBullet" not in m for m in messages[4])
    assert all("refuses the robot" in m for m in messages[7])
    assert sorted(edit.text for f in findings for edit in f.fix.edits) == \
        ["-1", "0.1 0 0", "0.1 0 0", "1 1 1", "1 1 1 1", "2"]


def test_numbers_with_white_space_in_a_xacro_are_judged_as_expanded(tmp_path):
    from urdftool.lint.options import CheckOptions, Selection
    from urdftool.lint.engine import load_and_check

    (tmp_path / "robot.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:property name="m" value="2"/><link name="a"/><link name="b"><inertial>'
        '<mass value="${m} "/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'
        '</inertial><visual><origin xyz="0\t0 0"/><geometry><sphere radius="1"/></geometry>'
        '</visual></link><joint name="j" type="fixed"><parent link="a"/><child link="b"/>'
        '</joint></robot>')
    result = load_and_check(str(tmp_path / "robot.urdf.xacro"),
                            CheckOptions(selection=Selection(("U023",))))
    # xacro's parser makes the raw tab a space, as urdfdom then reads it; the expression's
    # space stays, and the fix cannot edit an expression
    assert [(f.line, f.code) for f in result.findings] == [(1, "U023")]
    assert "no automatic fix" in result.findings[0].message


def test_a_vector_written_across_lines_is_found_among_values_of_the_same_text(tmp_path):
    # the only sign in the file is a line break after a number (no tab, no space before a
    # quote): the byte search passed it over; and 300 origins "0 0 0" written on one line
    # are the same text to lxml, which only the one written across lines is
    joints = "".join(f'<link name="l{i}"/><joint name="j{i}" type="fixed"><parent link="a"/>'
                     f'<child link="l{i}"/><origin xyz="0 0 0"/></joint>\n' for i in range(300))
    text = (f'<robot name="r"><link name="a"><visual><origin xyz="0\n0 0"/><geometry>'
            f'<box size="1 1 1"/></geometry></visual></link>\n{joints}</robot>\n')
    found, findings = check_folder(tmp_path, {"robot.urdf": text}, select=("U023",))
    assert found == [("robot.urdf", 1, "U023")]
    assert '"0\\n0"' in findings[0].message


def test_a_value_written_raw_far_before_its_tags_end_is_found(tmp_path):
    # lxml's line of an element is its start tag's '>': 70 blank lines after a raw tab or line
    # break inside a value (and a later value holding a raw '>', which XML allows) put it past
    # any fixed number of lines; the '>' is found in the bytes instead (session 19 left it)
    blank = "\n" * 70
    text = ('<robot name="r"><link name="a"/><link name="b"><inertial>'
            f'<mass value="2\t"{blank}/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" '
            'izz="1"/></inertial></link>\n<joint name="j" type="fixed"><parent link="a"/>'
            f'<child link="b"/>\n<origin xyz="0\t0 0"{blank} rpy="0\n0 0" a="x>y"{blank}/>'
            '</joint></robot>\n')
    found, findings = check_folder(tmp_path, {"robot.urdf": text}, select=("U023",))
    assert found == [("robot.urdf", 1, "U023"), ("robot.urdf", 73, "U023"),
                     ("robot.urdf", 73, "U023")]
    assert '<mass value="2\\t">' in findings[0].message  # (as written, not lxml's space)
    assert {'<origin xyz="0\\t0 0">', '<origin rpy="0\\n0 0">'} == \
        {m[m.index("<"):m.index(">") + 1] for m in (f.message for f in findings[1:])}


def test_a_raw_value_outside_any_tag_is_not_followed_past_the_next_markup(tmp_path):
    # a comment's look-alike of a value, an apostrophe after it that no quote closes, then
    # 2,000 origins of the same text written on one line: none is looked up in the source
    from urdftool.lint.fixes import tags

    looked = []
    joints = "".join(f'<link name="l{i}"/><joint name="j{i}" type="fixed"><parent link="a"/>'
                     f'<child link="l{i}"/><origin xyz="0 0 0"/></joint>\n' for i in range(2000))
    text = (f'<robot name="r"><link name="a"/><!-- xyz="0\n0 0" isn\'t one -->\n{joints}'
            '</robot>\n')
    source_tag = tags.source_tag
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(tags, "source_tag", lambda *a: looked.append(a) or source_tag(*a))
        found, _ = check_folder(tmp_path, {"robot.urdf": text}, select=("U023",))
    assert found == [] and len(looked) <= 1


def test_a_number_urdfdom_refuses_is_an_error_in_a_joint_and_a_warning_elsewhere(tmp_path):
    # urdfdom refuses the robot for a joint's number (as for every URDFDOM_REFUSES error: tree
    # fails as check_urdf does) and loads it without a link's part or a colour otherwise
    found, findings = check_folder(tmp_path, {"robot.urdf": NUMBERS_SPACED}, select=("U023",))
    assert {f.line: f.severity.value for f in findings} == \
        {2: "warning", 3: "warning", 4: "warning", 7: "error"}


def test_a_vector_across_lines_of_a_file_whose_lines_end_with_cr_is_found_on_its_line(tmp_path):
    # lxml's sourceline counts LF only (line 1 here), which the value's place is compared
    # with; the finding's line is the one owner's (a CR ends a line)
    lines = ['<robot name="r">', '<link name="a"/>', '<link name="b"><visual>',
             '<origin xyz="0', '0 0"/>', '<geometry><box size="1 1 1"/></geometry>',
             '</visual></link>', '<joint name="j" type="fixed"><parent link="a"/>',
             '<child link="b"/></joint>', '</robot>', '']
    found, findings = check_folder(tmp_path, {"robot.urdf": "\r".join(lines)}, select=("U023",))
    assert found == [("robot.urdf", 4, "U023")]  # (where its start tag starts)


def test_a_scalar_ending_with_a_raw_line_break_is_quoted_as_written(tmp_path):
    # lxml reads the CR LF before the closing quote as a space; the message quotes the line
    # break the file has (unitree_ros' hands: ixz="-3.261e-11<CR><LF>"), and the fix removes it
    text = ('<robot name="r"><link name="a"><inertial><mass value="1"/>\r\n'
            '<inertia ixx="1" ixy="0" ixz="-0.5\r\n" iyy="1" iyz="0" izz="1"/></inertial>'
            '</link></robot>\r\n')
    found, findings = check_folder(tmp_path, {"robot.urdf": text}, select=("U023",))
    assert found == [("robot.urdf", 2, "U023")]
    assert '<inertia ixz="-0.5\\n">' in findings[0].message  # (a line break, CR LF or LF)
    assert [edit.text for edit in findings[0].fix.edits] == ["-0.5"]


def test_a_place_is_named_once_though_urdfdom_reads_the_element_in_two_kinds_of_it(tmp_path):
    """LimX's exporter writes <color> directly in <visual>: urdfdom reads <color> in a visual's
    <material> and in a <robot>'s global <material>, both <material>; it said 'only in
    <material>, <material>'."""
    found, findings = _check(tmp_path, """<robot name="r"><link name="a"><visual>
      <geometry><box size="1 1 1"/></geometry><color rgba="1 0 0 1"/></visual></link></robot>""")
    assert [c for _, _, c in found] == ["U022"]
    assert findings[0].message.endswith("urdfdom reads it only in <material>"), findings[0].message


def test_the_number_gate_finds_each_spelling_its_needles_name():
    # U023's gate looks for a two-byte needle only where its rarer byte is: each spelling,
    # alone or beside texts holding that byte elsewhere, is found as a plain search finds it
    from urdftool.lint.rules.vocabulary import _suspect

    needles = (b"\t", b"\r", b"&#", b' "', b" '", b'\n"', b"\n'")
    plain = b'<robot name="r"><link name="a"/></robot>\n'
    texts = [plain, plain + b"<!-- & ' -->", plain.replace(b'"', b"'"), b"&amp;'x'\n"]
    texts += [text[:9] + needle + text[9:] for text in list(texts) for needle in needles]
    for text in texts:
        assert _suspect(text) == any(needle in text for needle in needles), text


def test_an_element_named_for_an_included_files_root_macro_says_it_calls_none(tmp_path):
    """Quori's quori.xacro includes quori_kinematics.xacro, whose root element is
    <xacro:macro name="quori_kinematics">, and writes <quori_kinematics/>: xacro inserts the
    root's children at the include (the links are there) and defines no macro, so the element
    stays in the output. "has no effect" alone did not say why."""
    macro = ('<?xml version="1.0"?>\n<xacro:macro name="arm" xmlns:xacro="http://ros.org/wiki/xacro">'
             '<link name="arm"/><joint name="j" type="fixed"><parent link="base_link"/>'
             '<child link="arm"/></joint></xacro:macro>\n')
    robot = ('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="base_link"/>'
             '<xacro:include filename="arm.xacro"/>\n<arm/>\n</robot>\n')
    from urdftool.lint.engine import CheckOptions, load_and_check

    (tmp_path / "arm.xacro").write_text(macro)
    (tmp_path / "robot.urdf.xacro").write_text(robot)
    result = load_and_check(str(tmp_path / "robot.urdf.xacro"), CheckOptions())
    [finding] = [f for f in result.findings if f.code == "U022"]
    assert "it calls no macro: arm.xacro's root element is <xacro:macro name=\"arm\">" in \
        finding.message, finding.message


def test_the_first_element_of_a_file_is_found_past_its_prologue_by_searches():
    """The root element _macro_file_root asks about: past white space, the declaration,
    comments (one holding '>' and '--'), a DOCTYPE; a regular expression matching them all had
    a generated URDF of many comments (match-ROS's mur620.urdf) take minutes to not match."""
    from urdftool.lint.rules.vocabulary import _first_element

    data = (b'<?xml version="1.0"?>\n<!-- a -> b -- c -->\n<!DOCTYPE robot>\n'
            b'<!-- again -->\n  <xacro:macro name="m"/>')
    assert data[_first_element(data):].startswith(b"<xacro:macro")
    assert _first_element(b"<!-- " * 10000) is None
    assert _first_element(b"<!-- x -->" * 10000 + b"<robot/>") == 100000
