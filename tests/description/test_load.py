"""The loader: safe XML, the line of each element's '<', xacro locations through includes and
macros, package resolution, stdin, size limits."""

from __future__ import annotations

import io
import sys

import pytest

from urdftool.diagnostics import Location
from urdftool.errors import LoadError
from urdftool.description.load import load


def write(tmp_path, name, text):
    path = tmp_path / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


def kinds(error) -> list[tuple[str, int | None]]:
    return [(error.value.kind, error.value.location.line)]


def test_start_tag_line_not_closing_bracket_line(tmp_path):
    path = write(tmp_path, "r.urdf", '<robot name="r">\n  <link\n     name="a"\n  >\n  </link>\n</robot>\n')
    robot = load(path)
    assert robot.locate(robot.links["a"]).line == 2


def test_undeclared_prefix_is_accepted_like_check_urdf(tmp_path):
    path = write(tmp_path, "r.urdf", '<robot name="r"><link name="a"/><gazebo><sensor:camera/></gazebo></robot>')
    assert "a" in load(path).links


@pytest.mark.parametrize("text, kind", [
    ("", "empty"), ("   \n", "empty"), ("\x00\x01binary", "binary"),
    ("<robot name='r'><link name='a'></robot>", "syntax"),
    ("<sdf version='1.6'/>", "root"),
    ('<!DOCTYPE r [<!ENTITY a "aaaa">]><robot name="&a;"/>', "entity"),
])
def test_bad_files_are_located_errors(tmp_path, text, kind):
    path = tmp_path / "bad.urdf"
    path.write_bytes(text.encode())
    with pytest.raises(LoadError) as error:
        load(path)
    assert error.value.kind == kind
    assert error.value.location.line is not None


def test_entity_bomb_refused_quickly(tmp_path):
    entities = "".join(f'<!ENTITY e{i} "{"&e%d;" % (i - 1) * 10}">' for i in range(1, 10))
    bomb = f'<?xml version="1.0"?><!DOCTYPE r [<!ENTITY e0 "lol">{entities}]><robot name="&e9;"/>'
    for name in ("bomb.urdf", "bomb.urdf.xacro"):
        path = tmp_path / name
        path.write_text(bomb)
        with pytest.raises(LoadError) as error:
            load(path)
        assert kinds(error)[0][0] == "entity"


def test_file_size_limit(tmp_path):
    path = write(tmp_path, "big.urdf", "<robot name='r'>" + " " * 2000 + "<link name='a'/></robot>")
    with pytest.raises(LoadError) as error:
        load(path, max_file_size=1000)
    assert kinds(error) == [("too-large", None)]
    assert error.value.message == "file is 2040 bytes, over the limit of 1000"  # no option named


XACRO_PARTS = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="leg" params="side">
    <link name="${side}_leg"/>
    <joint
        name="${side}_joint" type="fixed">
      <parent link="base"/>
      <child link="${side}_leg"/>
    </joint>
  </xacro:macro>
  <xacro:macro name="two">
    <xacro:leg side="a"/>
  </xacro:macro>
</robot>
"""

XACRO_TOP = """<?xml version="1.0"?>
<robot name="t" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="parts.xacro"/>
  <link name="base"/>
  <xacro:two/>
  <xacro:leg side="b"/>
</robot>
"""


def test_xacro_locations_through_includes_and_nested_macros(tmp_path):
    write(tmp_path, "parts.xacro", XACRO_PARTS)
    top = write(tmp_path, "top.urdf.xacro", XACRO_TOP)
    robot = load(top)
    parts = str(tmp_path / "parts.xacro")
    a_joint = robot.locate(robot.joints["a_joint"])
    assert (a_joint.file.endswith("parts.xacro"), a_joint.line) == (True, 5)
    assert [(site.file.endswith(name), site.line) for site, name in
            zip(a_joint.via, ["parts.xacro", "top.urdf.xacro"])] == [(True, 12), (True, 5)]
    b_joint = robot.locate(robot.joints["b_joint"])
    assert b_joint.line == 5 and [s.line for s in b_joint.via] == [6]
    assert robot.locate(robot.links["base"]) == Location(robot.display, 4, column=3)
    assert any(f.endswith("parts.xacro") for f in robot.files) and parts


@pytest.mark.parametrize("body, line, fragment", [
    ('<link name="${undefined_thing}"/>', 3, "undefined_thing"),
    ('<xacro:no_such_macro/>', 3, "unknown macro"),
    ('<xacro:include filename="missing.xacro"/>', 3, "missing.xacro"),
    ('<link name="${1/0}"/>', 3, "division"),
    ('<xacro:macro name="r"><xacro:r/></xacro:macro>\n  <xacro:r/>', 3, "nested deeper"),
])
def test_xacro_failures_are_located(tmp_path, body, line, fragment):
    path = write(tmp_path, "r.urdf.xacro",
                 f'<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n  {body}\n</robot>\n')
    with pytest.raises(LoadError) as error:
        load(path)
    assert error.value.kind == "xacro"
    assert error.value.location.line == line
    assert fragment in error.value.message.lower()


def test_include_cycle_is_an_error_not_a_recursion(tmp_path):
    write(tmp_path, "a.xacro", '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n<xacro:include filename="b.xacro"/>\n</robot>')
    write(tmp_path, "b.xacro", '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n<xacro:include filename="a.xacro"/>\n</robot>')
    top = write(tmp_path, "top.urdf.xacro", '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n<xacro:include filename="a.xacro"/>\n</robot>')
    with pytest.raises(LoadError) as error:
        load(top)
    assert "include cycle" in error.value.message


def test_xacro_args_and_find(tmp_path):
    pkg = tmp_path / "src" / "my_pkg"
    write(pkg, "package.xml", "<package><name>my_pkg</name></package>")
    write(pkg, "urdf/part.xacro", '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="$(arg part)"/></robot>')
    top = write(tmp_path, "robot/r.urdf.xacro",
                '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                '<xacro:arg name="part" default="x"/>'
                '<xacro:include filename="$(find my_pkg)/urdf/part.xacro"/></robot>')
    (tmp_path / ".git").mkdir()
    robot = load(top, xacro_args={"part": "gripper"})
    assert list(robot.links) == ["gripper"]


def test_unresolved_package_names_it_and_where_it_looked(tmp_path):
    top = write(tmp_path, "r.urdf.xacro",
                '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                '<xacro:include filename="$(find ghost_pkg)/x.xacro"/>\n</robot>')
    with pytest.raises(LoadError) as error:
        load(top)
    assert kinds(error) == [("package", 2)] and error.value.subject == "ghost_pkg"
    assert "ghost_pkg" in error.value.message and "--package ghost_pkg=PATH" in error.value.message


def test_stdin(monkeypatch):
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(b'<robot name="s"><link name="a"/></robot>')))
    robot = load("-")
    assert robot.display == "<stdin>" and list(robot.links) == ["a"]


def test_disguised_xacro_is_expanded_and_reported(tmp_path):
    path = write(tmp_path, "r.urdf", '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                 '<xacro:property name="n" value="base"/>\n<link name="${n}"/>\n</robot>')
    robot = load(path)
    assert list(robot.links) == ["base"]
    assert [(n.kind, n.location.line) for n in robot.notes] == [("xacro-in-urdf", 2)]


def test_commented_xacro_in_generated_urdf_is_plain(tmp_path):
    path = write(tmp_path, "r.urdf", '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                 '<!-- <xacro:if value="${x}"> -->\n<link name="a"/>\n</robot>')
    robot = load(path)
    assert not robot.from_xacro and robot.notes == []



_XACRO_NS = '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'


@pytest.mark.parametrize("body, first", [
    ('<!-- ${x} --><link name="a"/><xacro:property name="p" value="1"/>', "property"),
    ('<!-- ${x} --><link name="a"/><link name="b">$<![CDATA[{x}]]></link>', "b"),
    ('<!-- $(find x) --><link name="a"/><link name="&#36;{x}"/>', "${x}"),
    ('<!-- ${x} --><link name="a"/><link name="${x}"/>', "${x}"),
    ('<?pi <!-- ?><link name="$(arg a)"/><!-- -->', "$(arg a)"),
    ('<!-- ${x} --><link name="a"/>', None),
    ('<!--> ${x} --><link name="a"/><!-- -->', None),
    ('<!--> --><link name="${x}"/><!-- -->', "${x}"),
])
def test_the_first_xacro_use_whatever_the_bytes_hide(body, first):
    """The bytes spare the walk of attributes and texts only when no ``${``/``$(`` can be in
    them: one in a comment is not, one spelt by a reference, a CDATA section or behind a
    processing instruction is."""
    from lxml import etree

    from urdftool.description.load import _may_substitute, first_xacro_use

    data = f"{_XACRO_NS}{body}</robot>".encode()
    root = etree.fromstring(data)
    found = first_xacro_use(root, _may_substitute(data))
    assert found is first_xacro_use(root, True)
    if first is None:
        assert found is None
    else:
        assert first in (found.tag if "xacro" in found.tag else found.get("name"))


@pytest.mark.parametrize("document, first", [
    ('<robot xmlns:x="http://www.ros.org/wiki/xacro"><link name="a"/><x:if value="1"/></robot>',
     "{http://www.ros.org/wiki/xacro}if"),  # another prefix bound to xacro's URI
    ('<robot xmlns:xacro="http://playerstage.sourceforge.net/gazebo/xmlschema/#interface">'
     '<link name="a"/><xacro:macro name="m"/></robot>', "#interface}macro"),  # the prefix decides
    ('<robot><link name="a"/><xacro:if value="1"/></robot>', "xacro:if"),  # never declared
    ('<xacro:robot xmlns:xacro="http://wiki.ros.org/xacro"><link name="a"/></xacro:robot>',
     "xacro}robot"),  # the root itself
    ('<robot xmlns:xacro="http://www.ros.org/wiki/xacro" xmlns:d="http://drake.mit.edu">'
     '<link name="a"><d:x/></link></robot>', None),  # declared, used nowhere; another namespace
])
def test_the_first_xacro_tag_however_written(document, first):
    """Without a substitution to look for, only tags are asked: an element of a namespace, or
    whose name keeps a prefix, as every element is by :func:`is_xacro_element`."""
    from lxml import etree

    from urdftool.description.load import first_xacro_use
    from urdftool.description.urdf import is_xacro_element

    root = etree.fromstring(document.encode(), etree.XMLParser(recover=True))
    found = first_xacro_use(root, False)
    assert found is next((e for e in root.iter(etree.Element) if is_xacro_element(e)), None)
    assert (found is None) if first is None else found.tag.endswith(first)


def test_misspelt_property_suggests_the_defined_one(tmp_path):
    path = write(tmp_path, "r.urdf.xacro",
                 '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                 '  <xacro:property name="wheel_radius" value="0.05"/>\n'
                 '  <xacro:macro name="wheel" params="side">\n'
                 '    <link name="${side}_${wheel_radus}"/>\n'
                 '  </xacro:macro>\n'
                 '  <xacro:wheel side="left"/>\n</robot>\n')
    with pytest.raises(LoadError) as error:
        load(path)
    assert kinds(error) == [("xacro", 4)]
    assert "did you mean 'wheel_radius'?" in error.value.message
    assert "side" in error.value.message  # the macro's parameters are properties there too


def test_an_undefined_argument_is_named_and_no_option_is(tmp_path):
    path = write(tmp_path, "r.urdf.xacro", '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                 '<link name="$(arg part)"/>\n</robot>')
    with pytest.raises(LoadError) as error:
        load(path)
    assert kinds(error) == [("arg", 2)] and error.value.subject == "part"
    assert error.value.message == "Undefined substitution argument part"


def test_xacro_warnings_and_outside_files_are_notes(tmp_path):
    (tmp_path / "robot").mkdir()
    (tmp_path / "robot" / ".git").mkdir()
    write(tmp_path, "elsewhere/part.xacro",
          '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="b"/></robot>')
    top = write(tmp_path, "robot/r.urdf.xacro",
                '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                f'<xacro:include filename="{tmp_path}/elsewhere/part.xacro"/>\n'
                '<xacro:property name="p" value="1" bogus="2"/>\n<link name="a"/>\n</robot>')
    robot = load(top)
    assert sorted((n.kind, n.location.line) for n in robot.notes) == [
        ("outside-file", 2), ("xacro-warning", 3)]
    assert "part.xacro' is outside the repository" in robot.notes[-1].message


def test_xacro_prefix_without_namespace_is_located_with_xacros_reason(tmp_path):
    # lxml keeps the undeclared "xacro:property" as a tag name; naming it raised ValueError
    # (Invalid tag name). xacro says "unbound prefix": the note says so, at the line.
    path = write(tmp_path, "r.urdf", '<robot name="r">\n<link name="a"/>\n'
                 '<xacro:property name="w" value="1"/>\n</robot>')
    [note] = load(path).notes
    assert (note.kind, note.location.line) == ("xacro-in-urdf", 3)
    assert "<xacro:property>" in note.message and "unbound prefix" in note.message
    with pytest.raises(LoadError) as raised:  # named .xacro, it is xacro's error
        load(write(tmp_path, "r.urdf.xacro", path.read_text()))
    assert (raised.value.kind, raised.value.location.line) == ("syntax", 3)
    assert "unbound prefix" in raised.value.message


def test_locations_carry_the_column_of_the_start_tag(tmp_path):
    """Findings carry a column where the element starts (its ``<``), in plain URDF and through
    xacro macros (the call sites too)."""
    from urdftool.description.load import load

    plain = tmp_path / "r.urdf"
    plain.write_text('<robot name="r">\n  <link name="a"/>  <link name="b"/>\n</robot>\n')
    robot = load(str(plain))
    assert [(robot.locate(link).line, robot.locate(link).column)
            for link in robot.root.iter("link")] == [(2, 3), (2, 21)]
    xacro = tmp_path / "r.urdf.xacro"
    xacro.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                     '  <xacro:macro name="m" params="n">\n      <link name="${n}"/>\n'
                     '  </xacro:macro>\n    <xacro:m n="a"/>\n</robot>\n')
    robot = load(str(xacro))
    where = robot.locate(robot.links["a"])
    assert (where.line, where.column) == (3, 7)
    assert [(site.line, site.column) for site in where.via] == [(5, 5)]


def test_a_urdfs_locations_are_a_mapping_of_every_element(tmp_path):
    (tmp_path / "r.urdf").write_text('<robot name="r">\n  <link name="a">\n    <visual/>\n'
                                     '  </link>\n</robot>\n')
    robot = load(tmp_path / "r.urdf")
    visual = robot.root.find("link/visual")
    assert robot.locations.get(visual) == robot.locations[visual] == Location(
        robot.display, 3, column=5)
    assert len(robot.locations) == 3 and set(robot.locations) == set(robot.root.iter())
    assert robot.locations.get(robot.root.makeelement("link")) is None
    assert robot.locate(visual).line == 3


def test_xacro_in_a_urdf_names_the_attribute_holding_it(tmp_path):
    """TurtleBot3's common_properties.urdf: '(<color> at this line)' said nothing of the
    rgba="${255/255} ..." in it."""
    path = write(tmp_path, "r.urdf", '<robot name="r"><link name="a"/>\n<material name="m">'
                 '<color rgba="${255/255} 0 0 1"/></material>\n</robot>')
    [note] = load(path).notes
    assert 'rgba="${255/255} 0 0 1" in <color> at this line' in note.message, note.message


def test_white_space_before_the_declaration_is_read_as_urdfdom_reads_it(tmp_path):
    # urdfdom's TinyXML2 skips it (check_urdf parses NVIDIA's urdf-importer test robots
    # cube_dae.urdf and cube_obj.urdf); expat refused the file: a U001 error, nothing checked
    path = write(tmp_path, "r.urdf", '\n   \n<?xml version="1.0" encoding="UTF-8"?>\n'
                                     '<robot name="r">\n  <link name="base"/>\n</robot>\n')
    robot = load(path)
    assert [link.get("name") for link in robot.root.iter("link")] == ["base"]
    assert robot.locate(robot.root.find("link")).line == 5
    assert [(note.kind, note.location.line, note.severity.value) for note in robot.notes] == \
        [("late-declaration", 3, "warning")]


def test_a_double_hyphen_in_a_comment_is_read_as_urdfdom_reads_it(tmp_path):
    """A '--' inside a comment (a rule of dashes, or '--!>'): urdfdom's TinyXML2 ends the
    comment at the first '-->' and reads the robot (UM-ARM-Lab's victor.srdf, khi_duaro.srdf
    for srdfdom); expat refused it, a U001 error that checked nothing."""
    path = write(tmp_path, "r.urdf", '<?xml version="1.0"?>\n<robot name="r">\n'
                 '  <!-- ---------- -->\n  <link name="a"/>\n'
                 '  <!-- <link name="b"/> --!>\n  <!-- still a comment -->\n</robot>\n')
    robot = load(path)
    assert [link.get("name") for link in robot.root.iter("link")] == ["a"]
    assert robot.locate(robot.root.find("link")).line == 4
    assert [(note.kind, note.location.line, note.severity.value) for note in robot.notes] == \
        [("double-hyphen", 3, "warning")]
    assert "urdfdom reads the file" in robot.notes[0].message


def test_a_robot_in_a_default_namespace_is_read_as_urdfdom_reads_it(tmp_path):
    """JLSchol/omni_marco_gazebo's omni.urdf, <robot xmlns="http://www.ros.org/wiki/urdf">
    to validate it against urdf.xsd: check_urdf reads it (TinyXML2 knows no namespaces), and it
    was a U004 error that checked nothing; yourdfpy reads no link of it, hence a warning."""
    path = write(tmp_path, "r.urdf", '<?xml version="1.0"?>\n<robot\n'
                 '    xmlns="http://www.ros.org/wiki/urdf" name="r">\n  <link name="a"/>\n'
                 '  <link name="b"/>\n  <joint name="j" type="fixed"><parent link="a"/>'
                 '<child link="b"/></joint>\n  <u:link xmlns:u="urn:u" name="c"/>\n</robot>\n')
    robot = load(path)
    assert robot.root.tag == "robot"
    assert [link.get("name") for link in robot.root.iter("link")] == ["a", "b"]
    assert robot.root.find("joint/child").get("link") == "b"
    assert robot.locate(robot.root.find("link")).line == 4
    assert [(note.kind, note.location.line, note.severity.value) for note in robot.notes] == \
        [("root-namespace", 2, "warning")]


def test_another_root_in_a_default_namespace_stays_not_a_robot(tmp_path):
    path = write(tmp_path, "r.urdf", '<sdf xmlns="urn:sdf"><model name="m"/></sdf>\n')
    with pytest.raises(LoadError) as error:
        load(path)
    assert error.value.kind == "root"


@pytest.mark.parametrize("head", ['x<?xml version="1.0"?>',
                                  '\n<?xml version="1.0" encoding="ISO-8859-1"?>'])
def test_other_text_before_the_declaration_stays_malformed(tmp_path, head):
    path = write(tmp_path, "r.urdf", head + '\n<robot name="r"><link name="base"/></robot>\n')
    with pytest.raises(LoadError) as error:
        load(path)
    assert error.value.kind == "syntax"


def test_xacro_only_inside_gazebo_is_a_warning_naming_gazebo(tmp_path):
    """JAKA's jaka_a12.urdf: a $(find) only in a <gazebo> plugin's <parameters>, which URDF
    parsers skip: not certain to break anything (only Gazebo given the file itself reads it
    unexpanded), so a warning naming that, not an error. A substitution outside <gazebo>
    stays an error."""
    from urdftool.diagnostics import Severity
    gazebo = ('<robot name="r"><link name="a"/>\n<gazebo><plugin name="p" filename="x.so">\n'
              '<parameters>$(find pkg)/config/c.yaml</parameters></plugin></gazebo>\n</robot>')
    path = write(tmp_path, "pkg/package.xml", "<package><name>pkg</name></package>").parent
    [note] = load(write(path, "g.urdf", gazebo)).notes
    assert note.severity == Severity.WARNING and "only inside <gazebo>" in note.message, note
    outside = gazebo.replace('<link name="a"/>', '<link name="a"/><link name="$(find pkg)"/>')
    [note] = load(write(path, "o.urdf", outside)).notes
    assert note.severity is None and "URDF parsers will not" in note.message, note


def test_one_load_looks_for_a_repository_root_once(tmp_path, monkeypatch):
    # A load is one view of the file system, as a check's run is: a library caller's load of
    # a xacro with includes asks each question once (per_run answers remembered), and a
    # second load asks again (a .git made between two loads is seen).
    from urdftool.description import files

    (tmp_path / ".git").mkdir()
    (tmp_path / "part.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="b"/></robot>')
    (tmp_path / "r.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="a"/>'
        '<xacro:include filename="part.xacro"/><xacro:include filename="part.xacro"/>'
        '</robot>')
    from urdftool.description.run_memo import per_run

    asked, own = [], files.repository_root.__wrapped__
    monkeypatch.setattr(files, "repository_root",
                        per_run(lambda start: asked.append(start) or own(start)))
    for _ in range(2):
        robot = load(tmp_path / "r.urdf.xacro")
    assert [link.get("name") for link in robot.root.iter("link")] == ["a", "b", "b"]
    assert len(asked) == 2 * len(set(asked))


@pytest.mark.parametrize("end", ["\n", "\r\n", "\r"])
def test_text_before_the_declaration_is_said_at_its_line_whatever_ends_lines(tmp_path, end):
    """The late declaration's note is at the declaration's line, and the blanked document keeps
    every line end (a CR alone was blanked into a space: every line after it one up)."""
    from urdftool.description.load import _late_declaration

    data = "\n\n\n<?xml version='1.0'\n encoding='utf-8'?>\n<robot name='r'/>\n".replace(
        "\n", end).encode()
    blanked, line = _late_declaration(data)
    assert line == 4
    assert blanked.count(end.encode()) == data.count(end.encode()) and len(blanked) == len(data)


def test_what_a_xacro_prints_with_xacro_message_is_not_a_warning(tmp_path):
    """jhu-dvrk/dvrk_model's instrument macro prints which instrument it builds with
    ``xacro.message('Using instrument ...')``: U010 said "xacro printed a warning" of each
    ("Using instrument 400006: Large Needle Driver"). xacro.message() writes its author's words,
    xacro.warning() writes "warning: " before them (stderr being no terminal): only the latter
    is a warning."""
    ns = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
    path = write(tmp_path, "r.urdf.xacro",
                 f'<robot name="r" {ns}>\n<link name="a"/>\n'
                 "<xacro:if value=\"${xacro.message('Using instrument 400006') or True}\">"
                 '<link name="b"/></xacro:if>\n'
                 "<xacro:if value=\"${xacro.warning('careful') or True}\">"
                 '<link name="c"/></xacro:if>\n'
                 '<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>\n'
                 '<joint name="k" type="fixed"><parent link="a"/><child link="c"/></joint>\n'
                 '</robot>')
    notes = {(n.kind, n.message) for n in load(path).notes}
    assert notes == {("xacro-warning", "careful")}, notes
