"""Fixes (``check --fix / --unsafe-fixes / --diff``): each fix removes its finding, edits only
the text it must (the fixed file expands to the same URDF but for the fixed values), lands in the
file the user wrote (a xacro macro file too), and never in a file outside the repository."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from conftest import CASES
from urdftool.description.load import load
from urdftool.description.xml import attribute as escape_attribute
from urdftool.lint import fixes
from urdftool.lint.engine import CheckOptions, load_and_check

FIXES = Path(__file__).parent.parent / "fixes"

# case (in tests/cases, or tests/fixes), code fixed, unsafe?, what may differ in the expansion:
# {(tag, attribute)} (attribute None: the element's tag itself)
CASES_FIXED = [
    (CASES / "U020_misspelt_element.urdf", "U020", False, {
        ("orgin", None), ("hardwareInterfce", None), ("dynamics", "damping"),
        ("dynamics", "#children")}),
    (CASES / "U021_misspelt_attribute.urdf", "U021", False, {("limit", "uper"), ("limit", "upper")}),
    (CASES / "U204_inverted_limits.urdf", "U204", False, {("limit", "lower"), ("limit", "upper")}),
    (CASES / "U206_axis_not_unit.urdf", "U206", False, {("axis", "xyz")}),
    (CASES / "U413_mesh_implausible_size", "U413", False, {("mesh", "scale")}),
    (CASES / "U901_unused_suppression", "U901", False, {("axis", "xyz")}),
    (CASES / "U508_hardware_interface_prefix.urdf", "U508", False,
     {("hardwareInterface", "#text")}),
    (CASES / "U507_unactuated_joint.urdf", "U507", True, {("robot", "#children")}),
    (FIXES / "U507_ros2_control.urdf", "U507", True, {("ros2_control", "#children")}),
    (CASES / "U309_inertia_unit_mistake.urdf", "U309", True, {("inertia", a) for a in (
        "ixx", "iyy", "izz")}),
    (FIXES / "U305_inertia_indefinite.urdf", "U305", True, {("inertia", a) for a in (
        "ixx", "ixy", "iyy", "izz")} | {("origin", "xyz"), ("origin", "rpy")}),
]


def _copy(case: Path, folder: Path) -> Path:
    """The case copied into ``folder``; its robot file."""
    if case.is_dir():
        shutil.copytree(case, folder / case.name)
        robots = sorted(p for p in (folder / case.name).iterdir()
                        if p.name.endswith((".urdf", ".urdf.xacro")))
        return robots[0]
    shutil.copy(case, folder / case.name)
    return folder / case.name


def _differences(before, after) -> set:
    """(tag, attribute) pairs where two expanded trees differ (attribute None: the tag)."""
    found = set()
    if before.tag != after.tag:
        found.add((before.tag, None))
    for name in set(before.attrib) | set(after.attrib):
        if before.get(name) != after.get(name):
            found.add((before.tag, name))
    if (before.text or "").strip() != (after.text or "").strip():
        found.add((before.tag, "#text"))
    elements = lambda e: [c for c in e if isinstance(c.tag, str)]  # noqa: E731
    old, new = elements(before), elements(after)
    if len(old) != len(new):
        found.add((before.tag, "#children"))
    for a, b in zip(old, new):
        found |= _differences(a, b)
    return found


@pytest.mark.parametrize("case, code, unsafe, allowed", CASES_FIXED,
                         ids=[c[0].name for c in CASES_FIXED])
def test_a_fix_removes_its_finding_and_changes_nothing_else(tmp_path, case, code, unsafe, allowed):
    robot = _copy(case, tmp_path)
    before = load_and_check(str(robot), CheckOptions())
    fixed = [f for f in before.findings if f.code == code and f.fix is not None]
    assert fixed and all(f.fix.safe is not unsafe for f in fixed)
    # U901's case also names an unknown code: a misspelling to correct by hand, kept
    kept = [f.message for f in before.findings if f.code == code and f.fix is None]
    assert bool(fixes.plan([before]).changed) is not unsafe  # unsafe: only --unsafe-fixes
    [after], applied, _, skipped = fixes.apply(
        [before], lambda: [load_and_check(str(robot), CheckOptions())], unsafe=True)
    assert applied and not skipped
    assert [f.message for f in after.findings if f.code == code] == kept
    assert {f.code for f in after.findings} <= {f.code for f in before.findings}
    differences = _differences(before.robot.root, load(str(robot)).root)
    assert differences and differences <= allowed


def test_fixes_keep_comments_formatting_and_attribute_order(tmp_path):
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r">\n  <link name="a"/>  <!-- keep me -->\n  <link name="b"/>\n'
                     "  <joint name='j'   type='revolute'><parent link='a'/><child link='b'/>\n"
                     "    <limit effort='1'  uper='1'\n           lower='-1' velocity='1'/>\n"
                     "  </joint>\n</robot>")
    result = load_and_check(str(robot), CheckOptions())
    fixes.write(fixes.plan([result]))
    assert robot.read_text() == robot.read_text().replace("uper=", "upper=")
    assert robot.read_text() == ('<robot name="r">\n  <link name="a"/>  <!-- keep me -->\n'
                                 '  <link name="b"/>\n'
                                 "  <joint name='j'   type='revolute'><parent link='a'/>"
                                 "<child link='b'/>\n"
                                 "    <limit effort='1'  upper='1'\n           lower='-1' "
                                 "velocity='1'/>\n  </joint>\n</robot>")


def test_a_value_from_a_macro_argument_is_not_edited_and_the_finding_says_where(tmp_path):
    robot = _copy(FIXES / "xacro_macro", tmp_path)
    result = load_and_check(str(robot), CheckOptions())
    [argument] = [f for f in result.findings if f.code == "U206" and f.fix is None]
    assert "xyz is the macro argument axis=\"0 3 0\" of the call at " in argument.message
    assert argument.message.endswith("robot.urdf.xacro:7; change it there)")


def test_an_edit_outside_the_repository_or_of_a_changed_file_is_refused(tmp_path):
    repository = tmp_path / "repo"
    (repository / ".git").mkdir(parents=True)
    outside = tmp_path / "elsewhere.urdf"
    outside.write_text(shutil.os.linesep.join(["x"] * 3))
    robot = _copy(CASES / "U204_inverted_limits.urdf", repository)
    result = load_and_check(str(robot), CheckOptions())
    [finding] = [f for f in result.findings if f.code == "U204"]
    edit = finding.fix.edits[0]
    moved = type(finding.fix)(finding.fix.description, (
        type(edit)(str(outside), 0, 1, "y", "x", 1, 0),), True)
    result.findings[result.findings.index(finding)] = type(finding)(
        finding.code, finding.name, finding.severity, finding.message, finding.location, moved)
    changes = fixes.plan([result])
    assert not changes.changed and "outside the repository" in changes.skipped[0][1]
    robot.write_text(robot.read_text().replace('lower="1.57"', 'lower="1.5"'))
    changes = fixes.plan([load_and_check(str(robot), CheckOptions())])
    assert changes.changed  # checked again: applies
    stale = load_and_check(str(robot), CheckOptions())
    robot.write_text(robot.read_text().replace('lower="1.5"', 'lower="1.4"'))
    changes = fixes.plan([stale])
    assert not changes.changed and "changed since it was checked" in changes.skipped[0][1]


XACRO_DIFF = """\
--- a/{arm}
+++ b/{arm}
@@ -11,14 +11,14 @@
     <link name="${{prefix}}_lower"/>
     <joint name="${{prefix}}_shoulder" type="revolute">
       <parent link="base_link"/><child link="${{prefix}}_upper"/>
-      <orgin xyz="0 0 0.1"/>
-      <axis xyz="0 0 2"/>
-      <limit lower="1.5" upper="-1.5" effort="10" velocity="1"/>
+      <origin xyz="0 0 0.1"/>
+      <axis xyz="0 0 1"/>
+      <limit lower="-1.5" upper="1.5" effort="10" velocity="1"/>
     </joint>
     <joint name="${{prefix}}_elbow" type="revolute">
       <parent link="${{prefix}}_upper"/><child link="${{prefix}}_lower"/>
       <axis xyz="${{axis}}"/>
-      <limit lower="-1" uper="1" effort="10" velocity="1"/>
+      <limit lower="-1" upper="1" effort="10" velocity="1"/>
     </joint>
   </xacro:macro>
 </robot>
"""


def test_fix_diff_on_a_xacro_robot_edits_the_included_macro_file(tmp_path, run_cli, monkeypatch):
    """The issue's proof: ``check --fix --diff`` on a xacro robot whose findings are in an
    included macro file: the diff is of that file, at the literals, once for both macro
    calls; nothing is written."""
    robot = _copy(FIXES / "xacro_macro", tmp_path)
    monkeypatch.chdir(tmp_path)
    before = {p.name: p.read_bytes() for p in robot.parent.iterdir()}
    result = run_cli("check", "--fix", "--diff", "-j1", robot.relative_to(tmp_path))
    assert result.exit_code == 1
    assert result.stdout == XACRO_DIFF.format(arm="xacro_macro/arm.xacro")
    assert {p.name: p.read_bytes() for p in robot.parent.iterdir()} == before
    result = run_cli("check", "--fix", "-j1", robot.relative_to(tmp_path))
    assert result.exit_code == 1  # what remains: U303, U309 (unsafe) and the argument's U206
    remaining = {line.split()[2 if "[" not in line.split()[2] else 3]
                 for line in result.stdout.splitlines() if ": error " in line or ": warning " in line}
    assert remaining == {"U303", "U309", "U206"}
    assert "[~] 2 fixable with --unsafe-fixes" in result.stdout  # (none safe left: not "more")


def test_exit_code_after_fix_reflects_what_remains(tmp_path, run_cli):
    robot = _copy(CASES / "U204_inverted_limits.urdf", tmp_path)
    assert run_cli("check", "-j1", robot).exit_code == 1
    result = run_cli("check", "--fix", "-j1", robot)
    assert result.exit_code == 0, result.stdout
    assert "no problems found" in result.stdout
    assert 'lower="-1.57"' in robot.read_text()


def test_unsafe_fixes_alone_is_a_usage_error(tmp_path, run_cli):
    robot = _copy(CASES / "U204_inverted_limits.urdf", tmp_path)
    assert run_cli("check", "--unsafe-fixes", robot).exit_code == 2


def test_json_carries_the_fix_as_data(tmp_path, run_cli):
    import json

    robot = _copy(CASES / "U021_misspelt_attribute.urdf", tmp_path)
    data = json.loads(run_cli("check", "-f", "json", "-j1", robot).stdout)
    [diagnostic] = data["diagnostics"]
    assert diagnostic["fix"]["safe"] is True
    [edit] = diagnostic["fix"]["edits"]
    assert (edit["old"], edit["new"], edit["line"]) == ("uper", "upper", 6)


def test_a_massless_root_is_added_before_a_root_with_mass(tmp_path):
    robot = _copy(CASES / "U308_root_link_inertia.urdf", tmp_path)
    before = load_and_check(str(robot), CheckOptions())
    [finding] = [f for f in before.findings if f.code == "U308"]
    assert finding.fix is not None and not finding.fix.safe
    [after], applied, _, _ = fixes.apply(
        [before], lambda: [load_and_check(str(robot), CheckOptions())], unsafe=True)
    assert applied == 1 and "U308" not in {f.code for f in after.findings}
    fixed = load(str(robot))
    assert fixed.joints["base_footprint_joint"].find("child").get("link") == "base"
    for added in (fixed.links["base_footprint"], fixed.joints["base_footprint_joint"]):
        fixed.root.remove(added)
    assert _differences(before.robot.root, fixed.root) == set()


# A name that would break out of an attribute written by hand, and characters a parser turns
# into spaces (line breaks, tabs) or that splitlines() splits at (NEL, LINE SEPARATOR).
INJECTED = 'b"/><link name="injected"/><x a="\n::error::x\r\t\x85\u2028\'&amp;<>'


def test_a_fix_writes_a_hostile_name_back_exactly_and_injects_nothing(tmp_path):
    """U308 writes the root's name into a new joint, U507 the joint's name into a new
    transmission: the file stays well formed and reads back the same names (it was
    malformed, the name cut at its first quote)."""
    (tmp_path / ".git").mkdir()
    name = escape_attribute(INJECTED)
    robot = tmp_path / "robot.urdf"
    robot.write_text(f"""<robot name="r">
  <link name="{name}"><inertial><mass value="1"/>
    <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="c"/>
  <joint name="{name}" type="revolute"><parent link="{name}"/><child link="c"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <gazebo><plugin name="g" filename="libgazebo_ros_control.so"/></gazebo>
</robot>
""")
    before = load_and_check(str(robot), CheckOptions())
    assert {"U308", "U507"} <= {f.code for f in before.findings}
    [after], applied, _, _ = fixes.apply(
        [before], lambda: [load_and_check(str(robot), CheckOptions())], unsafe=True)
    assert applied >= 2 and after.robot is not None, [f.message for f in after.findings]
    fixed = load(str(robot))
    assert set(fixed.links) == {INJECTED, "c", "base_footprint"}
    assert fixed.joints["base_footprint_joint"].find("child").get("link") == INJECTED
    [transmission] = fixed.root.iter("transmission")
    assert transmission.find("joint").get("name") == INJECTED


def test_a_fix_that_would_write_anything_but_one_element_is_refused(tmp_path):
    """The inserting functions' own guard: a name written without attribute() (in a fix to
    come) would end the attribute or add an element; such an edit is never made."""
    (tmp_path / ".git").mkdir()
    (tmp_path / "robot.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    robot = load(str(tmp_path / "robot.urdf"))
    link = robot.links["a"]
    injected = '<link name="b"/><link name="injected"/>'
    for edits in (fixes.insert_before(robot, link, injected),
                  fixes.insert_before(robot, link, '<link name="a"b"/>'),
                  fixes.append_child(robot, robot.root, '<link name="<"/>')):
        assert isinstance(edits, fixes.Unfixable), edits
    assert not isinstance(fixes.insert_before(robot, link, '<link name="b"/>'), fixes.Unfixable)


def test_a_macro_literal_that_would_need_two_values_is_not_fixed(tmp_path):
    (tmp_path / "robot.urdf.xacro").write_text("""<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="part" params="name size">
    <link name="${name}">
      <inertial><mass value="1"/>
        <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="3"/></inertial>
      <collision><geometry><box size="${size}"/></geometry></collision>
    </link>
  </xacro:macro>
  <link name="base_link"/>
  <xacro:part name="a" size="0.1 0.1 0.1"/>
  <xacro:part name="b" size="0.1 0.2 0.3"/>
  <joint name="ja" type="fixed"><parent link="base_link"/><child link="a"/></joint>
  <joint name="jb" type="fixed"><parent link="base_link"/><child link="b"/></joint>
</robot>""")
    result = load_and_check(str(tmp_path / "robot.urdf.xacro"), CheckOptions())
    assert [f.code for f in result.findings if f.fix is not None] == ["U306", "U306"]
    changes = fixes.plan([result], unsafe=True)
    assert not changes.changed and len(changes.skipped) == 2
    assert "would need different values for different elements" in changes.skipped[0][1]


def test_two_rules_fixing_one_attribute_are_applied_one_pass_after_the_other(tmp_path):
    """U023 respaces an ``xyz`` that U206 normalises and a ``lower`` U204 swaps: the overlap
    was taken for a macro literal serving two elements, none was applied, and the reason said
    "a macro used more than once?". One element's fixes wait their turn: the first is taken,
    the other overlaps it, and the next pass reads the text the first wrote."""
    robot = tmp_path / "r.urdf"
    robot.write_text(
        '<robot name="o"><link name="a"/><link name="b"><inertial><mass value="1"/>'
        '<inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>'
        '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
        '<axis xyz="0 0 2&#9;"/><limit lower="1 " upper="-1" effort="1" velocity="1"/>'
        '</joint></robot>\n')
    options = CheckOptions()
    result = load_and_check(str(robot), options)
    assert sorted(f.code for f in result.findings if f.fix) == ["U023", "U023", "U204", "U206"]
    changes = fixes.plan([result], unsafe=True)
    assert len(changes.applied) == 2
    assert all(why.startswith("it overlaps another fix") for _, why in changes.skipped)
    final, applied, _, _ = fixes.apply([result], lambda: [load_and_check(str(robot), options)],
                                       unsafe=True)
    assert not [f for f in final[0].findings if f.fix] and applied >= 3
    assert '<axis xyz="0 0 1"/><limit lower="-1" upper="1"' in robot.read_text()


def test_an_edit_knows_the_line_and_column_of_both_ends_and_keeps_crlf(tmp_path):
    robot = tmp_path / "r.urdf"
    robot.write_bytes(b'<robot name="r">\r\n  <link name="base">\r\n    <inertial>\r\n'
                      b'      <mass value="1"/>\r\n      <inertia ixx="0.01" ixy="0" ixz="0" '
                      b'iyy="0.01" iyz="0" izz="0.01"/>\r\n    </inertial>\r\n  </link>\r\n'
                      b'</robot>\r\n')
    result = load_and_check(str(robot), CheckOptions())
    [finding] = [f for f in result.findings if f.code == "U308"]
    [edit] = finding.fix.edits
    assert (edit.line, edit.column, edit.end_line, edit.end_column) == (2, 2, 2, 2)
    fixes.write(fixes.plan([result], unsafe=True))
    assert b'<link name="base_footprint"/>\r\n  <joint name="base_footprint_joint"' in \
        robot.read_bytes()
    assert b"\n" not in robot.read_bytes().replace(b"\r\n", b"")
    other = tmp_path / "u.urdf"
    other.write_text('<robot name="r"><link name="a"/><link name="b"/>\n<joint name="j" '
                     'type="revolute"><parent link="a"/><child link="b"/>\n  <limit lower="-1" '
                     'uper="1" effort="1" velocity="1"/></joint></robot>')
    [rename] = [f for f in load_and_check(str(other), CheckOptions()).findings if f.code == "U021"]
    [edit] = rename.fix.edits
    assert (edit.line, edit.column, edit.end_line, edit.end_column) == (3, 20, 3, 24)


def test_the_issue_example_is_fixed_to_what_urdfdom_reads(tmp_path):
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/><link name="b"/>\n'
                     '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>\n'
                     '  <orgin xyz="0 0 1"/>\n'
                     '  <limit lower="-1" uper="1" effort="1" velocity="1"/>\n'
                     '  <dynamics><damping>100</damping></dynamics>\n</joint>\n</robot>\n')
    [after], applied, _, _ = fixes.apply([load_and_check(str(robot), CheckOptions())],
                                         lambda: [load_and_check(str(robot), CheckOptions())])
    assert applied == 3 and not [f for f in after.findings if f.code.startswith("U02")]
    assert robot.read_text() == (
        '<robot name="r"><link name="a"/><link name="b"/>\n'
        '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>\n'
        '  <origin xyz="0 0 1"/>\n'
        '  <limit lower="-1" upper="1" effort="1" velocity="1"/>\n'
        '  <dynamics damping="100"/>\n</joint>\n</robot>\n')


def test_a_never_pair_that_collides_loses_its_entry(tmp_path):
    """U810's unsafe fix removes the stale <disable_collisions>: MoveIt then checks the pair."""
    robot = _copy(CASES / "U810_srdf_disabled_pair_collides", tmp_path)
    srdf = robot.parent / "robot.srdf"
    urdf_before = robot.read_bytes()
    before = load_and_check(str(robot), CheckOptions())
    [finding] = [f for f in before.findings if f.code == "U810"]
    assert finding.fix is not None and not finding.fix.safe
    assert not fixes.plan([before]).changed  # only with --unsafe-fixes
    [after], applied, _, skipped = fixes.apply(
        [before], lambda: [load_and_check(str(robot), CheckOptions())], unsafe=True)
    assert applied and not skipped
    assert "U810" not in {f.code for f in after.findings}
    assert 'link1="l_hand" link2="r_hand" reason="Never"' not in srdf.read_text()
    assert 'link1="base_link" link2="l_hand" reason="Never"' in srdf.read_text()  # the others
    assert robot.read_bytes() == urdf_before


OVERLAPPING = ('<robot name="r"><link name="a"><collision><geometry><box size="0.1 0.1 0.1"/>'
               '</geometry></collision></link><link name="m"><collision><origin xyz="0 1 0"/>'
               '<geometry><sphere radius="0.01"/></geometry></collision></link><link name="b">'
               '<collision><origin xyz="0.09 0 0"/><geometry><box size="0.1 0.1 0.1"/></geometry>'
               '</collision></link><joint name="j1" type="revolute"><parent link="a"/>'
               '<child link="m"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
               '<joint name="j2" type="revolute"><parent link="m"/><child link="b"/>'
               '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>')


def test_a_pair_in_contact_at_the_default_pose_is_disabled_as_default(tmp_path):
    """U811's unsafe fix writes what MoveIt's Setup Assistant writes for a pair in contact at the
    default pose, indented as the file's other entries, before </robot>."""
    (tmp_path / ".git").mkdir()
    robot = tmp_path / "robot.urdf"
    robot.write_text(OVERLAPPING)
    srdf = tmp_path / "robot.srdf"
    srdf.write_text('<?xml version="1.0"?>\n<robot name="r">\n    <disable_collisions link1="a" '
                    'link2="m" reason="Adjacent"/>\n</robot>\n')
    before = load_and_check(str(robot), CheckOptions())
    [finding] = [f for f in before.findings if f.code == "U811"]
    assert finding.fix is not None and not finding.fix.safe
    [after], applied, _, _ = fixes.apply(
        [before], lambda: [load_and_check(str(robot), CheckOptions())], unsafe=True)
    assert applied and not {"U810", "U811"} & {f.code for f in after.findings}
    assert srdf.read_text().endswith('    <disable_collisions link1="a" link2="b" '
                                     'reason="Default"/>\n</robot>\n')


def test_a_source_finds_the_same_tags_whatever_its_chunks(monkeypatch):
    # chunks of every size cut tags, attributes and end tags anywhere: the same offsets, lines,
    # names and end tags as one parse of the whole file
    links = "".join(f'\n  <link name="l{i}">\n    <visual a="{"x" * (i % 97)}"/>\n  </link>'
                    for i in range(2_000))
    data = f'<?xml version="1.0"?>\n<robot name="r">{links}\n</robot>\n'.encode()
    monkeypatch.setattr(fixes.Source, "_FIRST_CHUNK", len(data))
    whole = fixes.parse_source("r.urdf", data)
    wanted = [whole.tag(i) for i in range(len(whole))]
    for first, most in ((1, 7), (4096, 65536), (333, 1000)):
        monkeypatch.setattr(fixes.Source, "_FIRST_CHUNK", first)
        monkeypatch.setattr(fixes.Source, "_CHUNK", most)
        source = fixes.parse_source("r.urdf", data)
        assert [source.tag(i) for i in range(len(whole))] == wanted and len(source) == len(whole)


def test_a_plain_file_finds_its_tags_where_the_loader_scanned_them(tmp_path):
    # a URDF the loader scanned (plain: its start tags' offsets known) gives each element's tag
    # from its offset, the same tag (offset, line, name, attributes, end tag) as parsing up to
    # it finds, without parsing there: only the end tag of an element holding more than text
    # (children, a comment, CDATA), when asked for, parses on
    links = "".join(f'\n  <link name="l{i}"><!-- <fake/> --><visual><geometry><box size="1 1 1"/>'
                    f'</geometry></visual>\n  </link>\n  <joint name="j{i}" type="fixed">'
                    f'<parent link="l{i}"/><child link="l{i + 1}"/></joint>\n  <gazebo '
                    f'reference="l{i}"><mu1>0.{i}</mu1><kp></kp></gazebo>' for i in range(300))
    data = (f'<?xml version="1.0"?>\n<!-- a <comment> -->\n<robot name="r">{links}\n'
            '  <link name="l300"/>\n  <gazebo><![CDATA[ <notag> ]]></gazebo>\n</robot>\n').encode()
    path = tmp_path / "r.urdf"
    path.write_bytes(data)
    robot = load(str(path))
    file = robot.locations.get(robot.root).file
    assert robot.locations.start_offset(robot.root, robot.sources[file]) is not None
    elements = [element for element in robot.root.iter() if isinstance(element.tag, str)]
    found = [fixes.source_tag(robot, element) for element in elements]
    source = found[0][0]
    assert source._fed == 0  # nothing parsed to find them
    parsed = fixes.parse_source("r.urdf", data)
    for index, (text, tag) in enumerate(found):
        wanted = parsed.tag(index)
        assert text is source and tag.close_name == wanted.close_name  # (parses on to it)
        assert tag == wanted
    assert data[found[-1][1].start:found[-1][1].end] == b"<gazebo>"


def test_a_source_is_read_as_far_as_the_tags_asked_for():
    # 40,000 tags (over 1 MB) behind the root link, then text no XML parser accepts: the root
    # link's tag is found from the first chunks, so the broken tail is never reached (a source
    # used to be parsed whole first, and then this one was refused).
    links = "".join(f'\n  <link name="l{i}"/>' for i in range(1, 40_000))
    data = (f'<robot name="r">\n  <link name="l0">\n    <inertial/>\n  </link>{links}\n'
            '</robot>\n<<broken').encode()
    source = fixes.parse_source("big.urdf", data)
    first = source.tag(1)
    assert (first.name, first.line, first.attributes["name"][2]) == ("link", 2, "l0")
    assert data[first.close_name[0]:first.close_name[1]] == b"link"
    assert [t.attributes["name"][2] for t in source.on_line(5)] == ["l1"]
    assert source._fed <= 8 * 1024  # the first chunks are small: the root link is near the top
    far = source.tag(39_001)  # tags: robot, l0, inertial, l1, ...; later chunks parsed now
    assert far.attributes["name"][2] == "l38999" and far.self_closing
    assert source.tag(50_000) is None  # past the tags there are (and the broken tail)
    assert fixes.parse_source("bad.urdf", b"<robot><link></robot>") is None


def test_edits_find_their_lines_in_an_index_not_by_counting_each_time():
    """An edit's line comes from one index of its file's newlines (counting them up to every
    edit made the fixes of a generated robot of 10,000 links quadratic: 9 of 20 s, and cost
    the corpus's small files 60 M instructions), and is the line counting gives, CRLF and
    multi-byte characters included, in a small file and a big one."""
    from urdftool.lint.fixes.tags import edit_of

    class Uncounted(bytes):
        def count(self, *args):
            raise AssertionError("newlines counted again")

    for count in (40, 5000):
        lines = [f'<link name="l{i}é"/>' + ("\r\n" if i % 3 else "\n") for i in range(count)]
        data = Uncounted("".join(lines).encode())
        for start in (0, 1, 17, len(data) // 3, len(data) - 5, len(data)):
            edit = edit_of("r.urdf", data, start, start, "")
            text = bytes(data)
            line_start = text.rfind(b"\n", 0, start) + 1
            assert (edit.line, edit.column) == (
                bytes.count(text, b"\n", 0, start) + 1,
                len(text[line_start:start].decode("utf-8", errors="replace")))


@pytest.mark.parametrize("end", ["\n", "\r\n", "\r"])
def test_an_edit_says_the_line_and_column_of_the_file_whatever_ends_its_lines(tmp_path, end):
    """An edit's line and column (JSON, the language server's quick fixes) and the lines it
    writes are the file's as every Location numbers them: in a file ended by CR alone an
    edit was at line 1, column of its offset in the file (an editor's change lands at the end
    of line 1), and U308's new lines were written with LF into a CR file."""
    robot = tmp_path / "r.urdf"
    robot.write_bytes((CASES / "U021_misspelt_attribute.urdf").read_text().replace(
        "\n", end).encode())
    [finding] = [f for f in load_and_check(str(robot), CheckOptions()).findings
                 if f.code == "U021"]
    [edit] = finding.fix.edits
    assert (edit.old, edit.line, edit.column) == ("uper", 6, 22), edit
    robot.write_bytes((CASES / "U308_root_link_inertia.urdf").read_text().replace(
        "\n", end).encode())
    before = load_and_check(str(robot), CheckOptions())
    [finding] = [f for f in before.findings if f.code == "U308"]
    written = "".join(edit.text for edit in finding.fix.edits)
    assert end in written and written.replace(end, "").count("\n") == written.replace(
        end, "").count("\r") == 0


def test_check_diff_of_a_cr_lf_file_is_a_patch_of_its_bytes(tmp_path, run_cli, monkeypatch):
    """``check --diff`` of a robot whose lines end with CR LF (written on Windows): each CR was
    printed ``\\r``, so no line of the diff was a line of the file and ``git apply`` refused
    it; the diff is now the file's bytes, as ``git diff`` writes it."""
    import difflib

    robot = tmp_path / "r.urdf"
    text = (CASES / "U204_inverted_limits.urdf").read_text().replace("\n", "\r\n")
    robot.write_bytes(text.encode())
    monkeypatch.chdir(tmp_path)
    result = run_cli("check", "--diff", "-j1", "r.urdf")
    assert result.exit_code == 1
    fixed = text.replace('lower="1.57"', 'lower="-1.57"').replace('upper="-1.57"', 'upper="1.57"')
    assert result.stdout_bytes.decode() == "".join(difflib.unified_diff(  # (click's .stdout
        text.splitlines(keepends=True), fixed.splitlines(keepends=True), "a/r.urdf", "b/r.urdf"))
    # reads CR LF as LF)


def test_a_fix_whose_edits_another_fix_took_is_taken_too(tmp_path):
    """Two findings whose fixes make the same edits under other descriptions (a macro's literal
    serving two elements): both are taken, each finding fixed, the file edited once. (A branch
    meant to leave the second out had been unreachable since fixes could create files: the
    creation's verdict replaced its "already taken".)"""
    from urdftool.diagnostics import Edit, Fix
    from urdftool.lint.fixes import applying

    robot = tmp_path / "r.urdf"
    edit = Edit(str(robot), 3, 4, "X", "d", 1, 3)
    one, other = Fix("link 'a': set it", (edit,), True), Fix("link 'b': set it", (edit,), True)
    plan = applying._take([(one, str(tmp_path)), (other, str(tmp_path))], lambda path: b"abcdef")
    assert plan.applied == [one, other] and not plan.skipped
    assert plan.changed == {str(robot): (b"abcdef", b"abcXef")}
    assert plan.spans == {str(robot): [(3, 4, 1)]}


def _plan_one_by_one(fixes_given, data: bytes):
    """The plan as it was made before: each fix's edits compared with every edit taken before
    (the reference of the test below)."""
    from urdftool.lint.fixes.applying import _disputed, _overlap

    applied, skipped, taken = [], [], []
    disputed = _disputed(fixes_given)
    for fix in fixes_given:
        if fix in applied or any(fix is other for other, _ in skipped):
            continue
        why = disputed.get(id(fix))
        if why is None and not all(edit in taken for edit in fix.edits):  # (taken again when
            for edit in fix.edits:  # all are, as the plan takes it)
                if data[edit.start:edit.end].decode("utf-8", errors="replace") != edit.old:
                    why = "changed"
                elif any(_overlap(edit, other) for other in taken):
                    why = "overlaps"
                if why:
                    break
        if why:
            skipped.append((fix, why))
            continue
        taken.extend(edit for edit in fix.edits if edit not in taken)
        applied.append(fix)
    after = data
    order = sorted(range(len(taken)), key=lambda i: (taken[i].start, taken[i].end, i))
    for edit in (taken[i] for i in reversed(order)):
        after = after[:edit.start] + edit.text.encode("utf-8") + after[edit.end:]
    return applied, [fix for fix, _ in skipped], after


def test_a_plan_of_thousands_of_fixes_compares_each_edit_with_its_neighbours_only(tmp_path,
                                                                                 monkeypatch):
    """``check --diff`` of a chain of 4,000 joints, each with two fixes, took 437 s (1,000:
    25 s): each fix was looked for among those applied (compared field by field) and each edit
    compared with every edit taken before it. The plan is the same as that one-by-one plan's on
    drawn edits (insertions at one point, overlaps, a fix given twice), and an edit is compared
    with its neighbours only."""
    import random

    from urdftool.diagnostics import Edit, Fix
    from urdftool.lint.fixes import applying

    robot = tmp_path / "r.urdf"
    data = bytes(random.Random(0).choice(b"abcdef \n") for _ in range(300))
    robot.write_bytes(data)
    rng = random.Random(17)
    for _ in range(300):
        given = []
        for _ in range(rng.randrange(1, 12)):
            edits = []
            for part in range(rng.randrange(1, 3)):  # (a fix's own edits never overlap)
                start = 40 * part + rng.randrange(0, 34)
                end = start + rng.choice([0, 0, 1, 2, 5])
                old = data[start:end].decode() if rng.random() < 0.95 else "?"
                edits.append(Edit(str(robot), start, end, rng.choice(["X", "YY", ""]), old, 1, 0))
            given.append(Fix("f", tuple(edits), True))
            if rng.random() < 0.2:
                given.append(rng.choice(given))
        plan = applying._take([(fix, str(tmp_path)) for fix in given], lambda path: data)
        applied, skipped, after = _plan_one_by_one(given, data)
        assert (plan.applied, [fix for fix, _ in plan.skipped]) == (applied, skipped)
        assert plan.changed.get(str(robot), (data, data))[1] == after
    compared = []
    monkeypatch.setattr(applying, "_overlap", lambda one, other: compared.append(1) or False)
    many = [Fix("f", (Edit(str(robot), 7 * i, 7 * i + 1, "x", "", 1, 0),), True)
            for i in range(4000)]
    plan = applying._take([(fix, str(tmp_path)) for fix in many], lambda path: b"\0" * 28000)
    assert len(plan.applied) == 0 and len(compared) == 0  # (the old text differs: refused)
    many = [Fix("f", (Edit(str(robot), 7 * i, 7 * i + 1, "x", "\0", 1, 0),), True)
            for i in range(4000)]
    plan = applying._take([(fix, str(tmp_path)) for fix in many], lambda path: b"\0" * 28000)
    assert len(plan.applied) == 4000 and len(compared) < 3 * 4000


def test_a_fix_that_cannot_be_written_says_which_files_were_fixed_before_it(
        tmp_path, run_cli, monkeypatch):
    """``check a.urdf b.urdf --fix`` on a disk that fills at b (``prlimit --fsize``): a.urdf was
    fixed and the run said only "cannot write 'b.urdf': File too large"."""
    from urdftool.description import files
    from urdftool.errors import UsageError

    first = _copy(CASES / "U204_inverted_limits.urdf", tmp_path)
    second = first.with_name("second.urdf")
    second.write_bytes(first.read_bytes())
    write_file = files.write_file

    def full_at_the_second(path, data, **options):
        if Path(path).name == "second.urdf":
            raise UsageError(f"cannot write '{path}': File too large")
        write_file(path, data, **options)

    monkeypatch.setattr(files, "write_file", full_at_the_second)
    monkeypatch.chdir(tmp_path)
    result = run_cli("check", "--fix", "-j1", "--no-cache", first.name, second.name)
    assert result.exit_code == 2
    said = result.stderr if hasattr(result, "stderr") else result.output
    assert "cannot write" in said and "File too large; fixed before it: " in said, said
    assert said.split("fixed before it: ")[1].strip() == f"'{first.name}'"
    assert 'lower="-1.57"' in first.read_text() and 'lower="-1.57"' not in second.read_text()
