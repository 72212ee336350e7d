"""Mass properties against closed forms, frames, and the inertia command."""

from __future__ import annotations

import io
import json
import math
from pathlib import Path

import numpy as np
import pytest

from conftest import ROBOTS
from urdftool.physics import inertia as mp
from urdftool.physics import mat3
from urdftool.description.load import load


def test_box_closed_form():
    solid = mp.box((0.1, 0.2, 0.3)).scaled_to(2.0)
    a, b, c = 0.1, 0.2, 0.3
    assert np.allclose(np.diag(solid.inertia), [2 / 12 * (b * b + c * c), 2 / 12 * (a * a + c * c),
                                                2 / 12 * (a * a + b * b)])


def test_cylinder_and_sphere_closed_forms():
    cylinder = mp.cylinder(0.05, 0.2).scaled_to(3.0)
    side = 3.0 * (3 * 0.05 ** 2 + 0.2 ** 2) / 12
    assert np.allclose(np.diag(cylinder.inertia), [side, side, 3.0 * 0.05 ** 2 / 2])
    sphere = mp.sphere(0.1).scaled_to(5.0)
    assert np.allclose(np.diag(sphere.inertia), [2 / 5 * 5.0 * 0.01] * 3)
    assert math.isclose(mp.sphere(0.1).mass, 4 / 3 * math.pi * 1e-3)


def test_offset_box_parallel_axis():
    box = mp.box((0.1, 0.1, 0.1)).scaled_to(1.0)
    moved = mp.transformed(box, np.array([0.0, 0.0, 0.5]), np.eye(3))
    pair = mp.combine([moved, mp.transformed(box, np.array([0.0, 0.0, -0.5]), np.eye(3))])
    about_origin = box.inertia[0, 0] + 1.0 * 0.5 ** 2
    assert np.allclose(pair.com, 0)
    assert math.isclose(pair.inertia[0, 0], 2 * about_origin)
    assert math.isclose(pair.inertia[2, 2], 2 * box.inertia[2, 2])


def test_rotated_cylinder_lies_along_x():
    lying = mp.transformed(mp.cylinder(0.05, 0.4), np.zeros(3), mat3.rpy_matrix((0, math.pi / 2, 0)))
    upright = mp.cylinder(0.05, 0.4)
    assert np.allclose(np.diag(lying.inertia), np.diag(upright.inertia)[[2, 1, 0]])


def test_tessellated_cylinder_mesh_within_1e_3():
    trimesh = pytest.importorskip("trimesh")
    mesh = trimesh.creation.cylinder(radius=0.05, height=0.2, sections=256)
    solid = mp.mesh_solid(mesh).scaled_to(1.0)
    exact = mp.cylinder(0.05, 0.2).scaled_to(1.0)
    assert mp.relative_difference(solid.inertia, exact.inertia) < 1e-3


def test_declared_inertial_with_rotated_origin():
    from lxml import etree

    link = etree.fromstring(
        '<link name="l"><inertial><origin xyz="1 2 3" rpy="0 0 1.5707963267948966"/>'
        '<mass value="2"/><inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3"/>'
        '</inertial></link>')
    found = mp.declared(link)
    assert np.allclose(found.com, [1, 2, 3])
    assert np.allclose(np.diag(found.inertia), [2, 1, 3])  # x and y swap under a 90 deg yaw


def test_triangle_inequality():
    assert mp.triangle_violation([0.1, 0.1, 0.5]) is not None
    assert mp.triangle_violation([0.3, 0.3, 0.5]) is None


def _robot(body: str, tmp_path):
    path = tmp_path / "r.urdf"
    path.write_text(f'<robot name="r"><link name="w"/>{body}</robot>')
    return load(path)


def test_mesh_link_with_scale_and_origin(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    trimesh.creation.box(extents=(100, 200, 300)).export(tmp_path / "box_mm.stl")
    robot = _robot('<link name="a"><collision><origin xyz="0 0 1"/><geometry>'
                   '<mesh filename="box_mm.stl" scale="0.001 0.001 0.001"/></geometry>'
                   '</collision></link>', tmp_path)
    from urdftool.physics.solids import computed, link_solid

    result = computed(link_solid(robot, robot.links["a"]), mass=2.0)
    exact = mp.box((0.1, 0.2, 0.3)).scaled_to(2.0)
    assert np.allclose(result.com, [0, 0, 1])
    assert np.allclose(result.inertia, exact.inertia, rtol=1e-6)



@pytest.mark.parametrize("points", ["0 0 0|0 0 0|0 0 0", "0 0 0|1 0 0|2 0 0"],
                         ids=["point", "line"])
def test_mesh_without_volume_is_a_problem_not_a_qhull_crash(tmp_path, points):
    # fuzz: a triangle collapsed to a point or a line has no convex hull; check gave U900
    vertices = "".join(f"vertex {p}\n" for p in points.split("|"))
    (tmp_path / "flat.stl").write_text(f"solid x\nfacet normal 0 0 1\nouter loop\n{vertices}"
                                       "endloop\nendfacet\nendsolid x\n")
    robot = _robot('<link name="a"><collision><geometry><mesh filename="flat.stl"/></geometry>'
                   '</collision></link>', tmp_path)
    from urdftool.physics.solids import link_solid

    solid = link_solid(robot, robot.links["a"])
    assert [message for _, message in solid.problems] == [
        "mesh 'flat.stl' is flat or a single point: it encloses no volume"]

@pytest.fixture(scope="module")
def humanoid():
    return str(ROBOTS / "humanoid" / "humanoid.urdf.xacro")


def test_inertia_command_json_shape(run_cli, humanoid):
    result = run_cli("inertia", humanoid, "--format", "json")
    assert result.exit_code == 0, result.output
    links = json.loads(result.output)["links"]
    body = next(l for l in links if l["link"] == "body_link")
    assert set(body) >= {"link", "declared", "computed", "source", "verdict"}
    assert body["source"] == "collision" and body["verdict"] == "agrees"
    assert set(body["declared"]) == {"mass", "com", "inertia"}


def test_inertia_write_corrects_selected_link(run_cli, tmp_path):
    source = tmp_path / "r.urdf"
    source.write_text(
        '<robot name="r"><link name="a"><inertial><mass value="2"/>'
        '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>'
        '<collision><geometry><box size="0.1 0.2 0.3"/></geometry></collision></link></robot>')
    out = tmp_path / "fixed.urdf"
    result = run_cli("inertia", source, "--write", out, "--link", "a")
    assert result.exit_code == 0, result.output
    fixed = load(out)
    assert np.allclose(mp.declared(fixed.links["a"]).inertia,
                       mp.box((0.1, 0.2, 0.3)).scaled_to(2.0).inertia, rtol=1e-5)


def test_inertia_write_xacro_prints_blocks_with_source_line(run_cli, humanoid, tmp_path):
    # head_link's inertial comes from macro arguments: printed with where it goes, not edited
    result = run_cli("inertia", humanoid, "--write", tmp_path / "inertia.patch",
                     "--link", "head_link")
    assert result.exit_code == 0, result.output
    assert "replaces the <inertial> at" in result.output and "inertial.xacro:" in result.output
    assert "<mass value=\"0.16\"/>" in result.output
    assert "head_link: not written: xyz is the macro argument" in result.output
    assert (tmp_path / "inertia.patch").read_text() == ""


def test_inertia_write_needs_a_selection(run_cli, humanoid):
    assert run_cli("inertia", humanoid, "--write", "x.urdf").exit_code == 2


def test_inertia_text_summary_counts_one_link_in_the_singular(run_cli, humanoid):
    result = run_cli("inertia", humanoid, "--link", "head_link")
    assert result.exit_code == 0, result.output
    assert result.output.splitlines()[-1] == "1 agrees (1 link)"


def test_inertia_text_gives_a_frame_one_line(run_cli, tmp_path):
    path = tmp_path / "frame.urdf"
    path.write_text('<robot name="f"><link name="base"/><link name="tool0"/>'
                    '<joint name="j" type="fixed"><parent link="base"/><child link="tool0"/>'
                    '</joint></robot>')
    result = run_cli("inertia", path)
    assert result.output.splitlines() == [
        "base: unknown (a frame: no inertial, no geometry)",
        "tool0: unknown (a frame: no inertial, no geometry)", "2 unknown (2 links)"]


def test_compare_refuses_an_unknown_link_and_lists_the_others(run_cli, humanoid):
    from urdftool.physics.inertia_compare import UnknownLink, compare

    robot = load(str(humanoid))
    with pytest.raises(UnknownLink, match="^link 'body_lnk' does not exist; did you mean "
                                          "'body_link'"):
        compare(robot, links=["body_link", "body_lnk"])
    result = run_cli("inertia", humanoid, "--link", "body_lnk")
    assert result.exit_code == 2
    assert result.stderr.startswith("urdftool: error: link 'body_lnk' does not exist;")


MOVING_WITHOUT_INERTIAL = """<robot name="arm">
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="arm"><collision><origin xyz="0.2 0 0"/><geometry><box size="0.4 0.05 0.05"/></geometry></collision></link>
  <link name="tool"/>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
  <joint name="t" type="fixed"><parent link="arm"/><child link="tool"/></joint>
</robot>"""


def test_inertia_of_a_link_without_inertial_is_missing_not_agrees(run_cli, tmp_path):
    """Nothing declared: no agreement. A moving body with no mass anywhere fails (exit 1); mass
    on a link fixed to it, or a robot that declares no inertial at all, does not."""
    path = tmp_path / "arm.urdf"
    path.write_text(MOVING_WITHOUT_INERTIAL)
    result = run_cli("inertia", path, "--link", "arm")
    assert result.exit_code == 1 and result.stdout.startswith("arm: missing")
    assert "nothing declared to compare" in result.stdout and "moved by joint 'j'" in result.stdout
    path.write_text(MOVING_WITHOUT_INERTIAL.replace(
        '<link name="tool"/>', '<link name="tool"><inertial><mass value="0.5"/><inertia ixx="0.01"'
        ' ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>'))
    result = run_cli("inertia", path, "--link", "arm")
    assert result.exit_code == 0 and result.stdout.startswith("arm: missing")
    assert "moved by joint" not in result.stdout
    path.write_text(MOVING_WITHOUT_INERTIAL.replace(
        MOVING_WITHOUT_INERTIAL.split("\n")[1], '<link name="base"/>'))
    result = run_cli("inertia", path, "--link", "arm")
    assert result.exit_code == 0 and result.stdout.startswith("arm: missing")
def test_inertia_write_edits_the_text_keeping_comments_and_layout(run_cli, tmp_path):
    source = tmp_path / "r.urdf"
    text = ('<robot name="r">\n  <!-- hand-written -->\n  <link name="a">\n    <inertial>'
            '<mass value="2"/>\n      <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'
            '</inertial>\n    <collision><geometry><box size="0.1 0.2 0.3"/></geometry>'
            '</collision>\n  </link>\n</robot>\n')
    source.write_text(text)
    out = tmp_path / "fixed.urdf"
    assert run_cli("inertia", source, "--write", out, "--link", "a").exit_code == 0
    written = out.read_text()
    assert written.startswith('<robot name="r">\n  <!-- hand-written -->\n  <link name="a">\n')
    assert written.count("\n") == text.count("\n")
    assert 'ixx="0.0216667"' in written and '<mass value="2"/>' in written


def test_inertia_write_xacro_is_a_diff_of_the_macro_file(run_cli, tmp_path):
    import shutil

    shutil.copytree(Path(__file__).parent.parent / "fixes" / "xacro_macro", tmp_path / "r")
    out = tmp_path / "inertia.patch"
    result = run_cli("inertia", tmp_path / "r" / "robot.urdf.xacro", "--write", out,
                     "--link", "left_upper")
    assert result.exit_code == 0, result.output
    patch = out.read_text()
    assert patch.splitlines()[0].endswith("r/arm.xacro")
    assert '-        <inertia ixx="1666.7"' in patch and 'ixx="0.00166667"' in patch


def test_inertia_of_many_links_without_inertial_reads_the_robot_once(tmp_path, monkeypatch):
    """Whether a link is a moving body without mass is decided from what is read of the robot
    once (its joints, whether it declares any inertial, each body's mass), not by a walk of
    every joint and link for each link (quadratic: a generated robot of 10,000 links)."""
    from conftest import load_text
    from urdftool.physics.inertia_compare import compare

    links = "".join(f'<link name="l{i}"/>' for i in range(1, 200))
    joints = "".join(f'<joint name="j{i}" type="{"fixed" if i % 2 else "revolute"}">'
                     f'<parent link="l{i - 1}"/><child link="l{i}"/><axis xyz="0 0 1"/>'
                     '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
                     for i in range(1, 200))
    robot = load_text(tmp_path, '<robot name="r"><link name="l0"><inertial><mass value="1"/>'
                                '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'
                                f'</inertial></link>{links}{joints}</robot>')
    asked = []
    children = type(robot).children
    monkeypatch.setattr(type(robot), "children",
                        lambda self, tag: asked.append(tag) or children(self, tag))
    found = {result.link: result for result in compare(robot)}
    assert len(asked) < 10
    assert any("moved by joint 'j2'" in note for note in found["l2"].notes)  # l2, l3: no mass
    assert not any("moved by joint" in note for note in found["l1"].notes)  # fixed to l0


def test_a_declared_mass_past_what_its_geometry_holds_proposes_no_inertial(run_cli, tmp_path):
    """session 9: a mass of 1e308 over a box's volume overflowed the density, and `inertia
    --write` wrote ixx="inf" ixy="nan" into the robot (no loader reads it); a computed inertial
    that is not finite is no proposal."""
    robot = tmp_path / "robot.urdf"
    robot.write_text('<robot name="r"><link name="a"><inertial><mass value="1e308"/>'
                     '<inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/>'
                     '</inertial><collision><geometry><box size="0.1 0.1 0.1"/></geometry>'
                     '</collision></link></robot>\n')
    before = robot.read_text()
    result = run_cli("inertia", robot, "--all", "--write", robot)
    assert result.exit_code in (0, 1), result.output
    assert robot.read_text() == before
    shown = run_cli("inertia", robot, "-f", "json")
    assert "<inertial><mass> 1e+308 kg is past the 1e+30 kg urdftool" in shown.stdout
    json.loads(shown.stdout, parse_constant=lambda word: pytest.fail(word))
