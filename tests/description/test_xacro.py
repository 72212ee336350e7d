"""description.xacro: what the in-process expansion relies on in the xacro library."""

from __future__ import annotations

import pytest

from urdftool.description.load import load


@pytest.mark.parametrize("text", ["0 0 0.1", "base_link", "", " spaced  out ", "a{b}(c)",
                                  "package://pkg/mesh.stl", "1e-3", "true"])
def test_xacro_returns_text_without_a_dollar_as_it_is(text):
    # The expansion hands such text back without running xacro's lexer (description.xacro's
    # eval_text): right only while xacro itself returns it unchanged, as checked here.
    import xacro

    assert xacro.eval_text(text, xacro.Table()) == text


def test_attributes_keep_their_order_values_and_namespaces_after_expansion(tmp_path):
    (tmp_path / "r.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro" '
        'xmlns:gz="http://gazebosim.org/schema">\n'
        '  <xacro:property name="w" value="0.5"/>\n'
        '  <link name="a"><visual><geometry><box size="${w} 1 $${x}" gz:kind="plain"/>'
        '</geometry></visual></link>\n</robot>\n')
    robot = load(tmp_path / "r.urdf.xacro")
    box = robot.root.find("link/visual/geometry/box")
    assert list(box.attrib.items()) == [("size", "0.5 1 ${x}"),
                                        ("{http://gazebosim.org/schema}kind", "plain")]
    assert robot.locate(box).line == 3
