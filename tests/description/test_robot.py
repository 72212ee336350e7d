"""The loaded Robot: typed companion paths and mesh limits, and one memo for derived values."""

from __future__ import annotations

from pathlib import Path

from urdftool.description.companions import companions
from urdftool.description.load import load
from urdftool.description.meshes import MeshLimits
from urdftool.description.robot import CompanionPaths
from urdftool.lint.engine import CheckOptions, Selection, load_and_check

ROBOT = ('<robot name="r"><link name="a"><collision><geometry><mesh filename="ball.stl"/>'
         '</geometry></collision><inertial><mass value="1"/>'
         '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link></robot>')


def _folder(tmp_path) -> Path:
    import trimesh

    (tmp_path / ".git").mkdir()
    trimesh.creation.icosphere(subdivisions=3).export(tmp_path / "ball.stl")  # 1280 triangles
    (tmp_path / "r.urdf").write_text(ROBOT)
    (tmp_path / "joint_limits.yaml").write_text("joints: {}\n")
    return tmp_path / "r.urdf"


def test_places_located_together_are_where_each_is_located(tmp_path):
    from lxml import etree

    from urdftool.diagnostics import Location

    text = '<robot name="r">\n<link name="a">\n  <visual/></link>\n<joint name="j"/>\n</robot>\n'
    (tmp_path / "r.urdf").write_text(text)
    (tmp_path / "x.urdf.xacro").write_text(text.replace('<robot name="r">', '<robot name="r" '
                                           'xmlns:xacro="http://www.ros.org/wiki/xacro">'))
    for robot in (load(tmp_path / "r.urdf"), load(tmp_path / "x.urdf.xacro")):
        link = robot.root.find("link")
        added = etree.SubElement(link, "collision")  # (not loaded: located as its parent)
        places = [link, link[0], None, Location("other.urdf", 3), added, robot.root.find("joint"),
                  robot.root]
        located = robot.locate_all(places)
        assert located == [p if isinstance(p, Location) else robot.locate(p) for p in places]
        assert [(p.line, p.column) for p in located] == [(2, 1), (3, 3), (None, None), (3, None),
                                                         (2, 1), (4, 1), (1, 1)]


def test_memo_computes_once_per_key(tmp_path):
    (tmp_path / "r.urdf").write_text('<robot name="r"><link name="a"/></robot>')
    robot = load(tmp_path / "r.urdf")
    calls = []
    assert robot.memo(len, lambda: calls.append(1) or "x") == "x"
    assert robot.memo(len, lambda: calls.append(2) or "y") == "x"
    assert robot.memo(min, lambda: "z") == "z" and calls == [1]


def test_rules_keep_what_they_derive_in_the_memo_not_on_the_robot(tmp_path):
    robot = load_and_check(str(_folder(tmp_path)), CheckOptions()).robot
    assert companions(robot) is companions(robot)
    assert not {"_companions", "_spec", "_controllers"} & set(vars(robot))
    assert not {"_mesh_cache", "_mesh_outcomes", "_link_solids", "max_triangles", "spec",
                "srdf", "controllers"} & set(vars(robot).get("options", {}))
    assert len(robot._memo) >= 4  # companions, spec, mesh outcomes, mesh cache, link solids


def test_typed_options_reach_the_robot_and_the_rules(tmp_path):
    path = _folder(tmp_path)
    spec = tmp_path / "limits" / "head.yaml"
    spec.parent.mkdir()
    spec.write_text("joints: [\n")
    options = CheckOptions(selection=Selection(("U411", "U701")), mesh_limits=MeshLimits(1000),
                           companions=CompanionPaths(spec=spec))
    result = load_and_check(str(path), options)
    assert result.robot.mesh_limits.max_triangles == 1000
    assert result.robot.companion_paths == CompanionPaths(spec=spec)
    assert sorted(f.code for f in result.findings) == ["U411", "U701"]
    assert "1280 triangles" in next(f.message for f in result.findings if f.code == "U411")
    assert load_and_check(str(path), CheckOptions(selection=Selection(("U411",)))).findings == []


def test_the_command_line_names_win_over_the_settings_file():
    settings = CompanionPaths((Path("a.yaml"),), Path("r.srdf"), Path("s.yaml"))
    assert settings.overridden_by(CompanionPaths(spec=Path("t.yaml"))) == \
        CompanionPaths((Path("a.yaml"),), Path("r.srdf"), Path("t.yaml"))
    assert settings.overridden_by(CompanionPaths()) == settings


def test_children_by_tag_in_document_order_and_a_list_of_ones_own(tmp_path):
    (tmp_path / "r.urdf").write_text(
        '<robot name="r"><link name="a"/><joint name="j" type="fixed"><parent link="a"/>'
        '<child link="b"/></joint><!-- c --><link name="b"/><material name="m"/></robot>')
    robot = load(tmp_path / "r.urdf")
    links = robot.children("link")
    assert [link.get("name") for link in links] == ["a", "b"]
    links.clear()  # the caller's list: the robot's grouping is not changed by it
    assert [link.get("name") for link in robot.children("link")] == ["a", "b"]
    assert [j.get("name") for j in robot.children("joint")] == ["j"]
    assert robot.children("transmission") == []


def test_an_elements_children_grouped_by_tag_once_comments_left_out(tmp_path):
    (tmp_path / "r.urdf").write_text(
        '<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="revolute">'
        '<!-- limit --><limit effort="1" velocity="1"/><parent link="a"/><child link="b"/>'
        '<limit effort="2" velocity="2"/></joint></robot>')
    robot = load(tmp_path / "r.urdf")
    joint = robot.joints["j"]
    groups = robot.grouped(joint)
    assert list(groups) == ["limit", "parent", "child"]
    assert [limit.get("effort") for limit in groups["limit"]] == ["1", "2"]
    assert robot.grouped(joint) is groups  # grouped once
    assert robot.child(joint, "limit").get("effort") == "1"
    assert robot.child(joint, "axis") is None


def _awkward_robot(rng) -> str:
    """A random robot of links with and without names (some repeated) and joints with none,
    one or several ``<parent>``/``<child>`` elements, some without a ``link``, among comments."""
    parts = ['<robot name="r">']
    for i in range(rng.randrange(1, 12)):
        name = rng.choice([f' name="l{i}"', f' name="l{rng.randrange(4)}"', '', ' name="?"'])
        parts.append(f"<link{name}/>")
        if rng.random() < 0.7:
            ends = []
            for tag in ("parent", "child"):
                for _ in range(rng.choice([0, 1, 1, 1, 2, 3])):
                    link = rng.choice([f' link="l{rng.randrange(8)}"', "", ' link=""'])
                    ends.append(f"<{tag}{link}/>")
            rng.shuffle(ends)
            joint = rng.choice([f' name="j{i}"', "", f' name="j{rng.randrange(3)}"'])
            kind = rng.choice([' type="fixed"', ' type="revolute"', "", ' type=""'])
            parts.append(f'<joint{joint}{kind}><!-- c -->{"".join(ends)}</joint>')
    return "".join(parts) + "</robot>"


def test_the_links_hanging_from_joints_and_the_names_read_once_as_lxml_gives_them(tmp_path):
    import random

    rng = random.Random(34)
    for case in range(200):
        path = tmp_path / f"r{case}.urdf"
        path.write_text(_awkward_robot(rng))
        robot = load(path)
        # the straightforward reading: lxml's own findall over every joint
        assert robot.hanging() == {child.get("link") for joint in robot.root.findall("joint")
                                   for child in joint.findall("child")}, path.read_text()
        assert robot.names() == {element: element.get("name") for element in robot.root
                                 if element.tag in ("link", "joint")}
        assert robot.kinds() == {joint: joint.get("type") for joint in robot.root
                                 if joint.tag == "joint"}
        first = robot.ends()  # ends unchanged: each joint's first <parent> and <child>
        for joint in robot.root.findall("joint"):
            for side in ("parent", "child"):
                element = joint.find(side)
                assert first[joint][side] == (element, element.get("link") if element is not None
                                              else None)


def test_the_tree_and_joint_rules_read_each_name_and_number_from_lxml_once(tmp_path,
                                                                          attribute_reads):
    """Robot.links, .joints and the U1/U2 rules take each link's and joint's name from
    Robot.names, and the joint rules each limit and axis number from one reading
    (joints._texts): lxml's get is a C call, a string made and a lookup, 500,000 times over
    a 10,000-link robot; read once each, the findings the same."""
    from conftest import synthetic_robot
    from urdftool.lint.engine import check_robot

    path = synthetic_robot(tmp_path, 30, "star")
    expected = check_robot(load(path), Selection(select=("U1", "U2")))
    attribute_reads.clear()
    robot = load(path)
    assert type(robot.root).__name__ == "Counted"
    assert check_robot(robot, Selection(select=("U1", "U2"))) == expected
    assert robot.links and robot.joints
    again = {(element.tag, key): n for (element, key), n in attribute_reads.items() if n > 1}
    assert not again, again
