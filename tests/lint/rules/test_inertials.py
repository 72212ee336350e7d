"""U3xx inertial rules on small inline robots (each rule's case file is in tests/cases)."""

from __future__ import annotations

from urdftool.lint.engine import CheckOptions, Selection, check_file

INERTIAL = """<inertial><origin xyz="{com}"/><mass value="1"/>
  <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>"""


def _u307(tmp_path, links, joints=""):
    (tmp_path / "r.urdf").write_text(f'<robot name="r">{links}{joints}</robot>')
    result = check_file(str(tmp_path / "r.urdf"), CheckOptions(selection=Selection(("U307",))))
    return [f.message for f in result.findings]


def test_com_is_measured_against_visual_and_collision_geometry(tmp_path):
    """A small collision box near the joint and a long visual arm holding the centre of mass:
    one link, and the centre of mass is inside it."""
    link = ('<link name="arm">' + INERTIAL.format(com="0.4 0 0") +
            '<visual><origin xyz="0.4 0 0"/><geometry><box size="0.8 0.05 0.05"/></geometry></visual>'
            '<collision><geometry><box size="0.05 0.05 0.05"/></geometry></collision></link>')
    assert _u307(tmp_path, link) == []


def test_com_is_measured_against_the_links_fixed_to_it(tmp_path):
    """The mass on a link without geometry, its shape on a link fixed to it (both ways)."""
    links = ('<link name="body">' + INERTIAL.format(com="0 0 0.6") + '</link>'
             '<link name="shell"><visual><geometry><cylinder radius="0.1" length="0.5"/></geometry>'
             '</visual></link>')
    joint = ('<joint name="f" type="fixed"><parent link="{}"/><child link="{}"/>'
             '<origin xyz="0 0 {}"/></joint>')
    assert _u307(tmp_path, links, joint.format("body", "shell", 0.6)) == []
    assert _u307(tmp_path, links, joint.format("shell", "body", -0.6)) == []
    [message] = _u307(tmp_path, links, joint.format("body", "shell", -0.6))
    assert "and of 'shell' fixed to it" in message


def test_com_is_not_judged_when_a_mesh_cannot_be_measured(tmp_path):
    link = ('<link name="arm">' + INERTIAL.format(com="0.4 0 0") +
            '<visual><geometry><mesh filename="missing.stl"/></geometry></visual>'
            '<collision><geometry><box size="0.05 0.05 0.05"/></geometry></collision></link>')
    assert _u307(tmp_path, link) == []
