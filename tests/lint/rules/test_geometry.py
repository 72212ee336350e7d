"""U4xx geometry rules: how a shape is found inside its <geometry>."""

from __future__ import annotations

from lxml import etree

from urdftool.lint.rules.geometry import _first_element


def test_the_shape_is_the_first_element_of_its_geometry_comments_passed_over():
    geometry = etree.fromstring('<geometry><!-- a note --><?pi x?><box size="1 1 1"/>'
                                '<sphere radius="1"/></geometry>')
    assert _first_element(geometry).tag == "box"
    assert _first_element(etree.fromstring("<geometry><!-- only --></geometry>")) is None
    assert _first_element(etree.fromstring("<geometry/>")) is None
    assert _first_element(None) is None


def test_a_mesh_the_size_of_its_links_primitive_shapes_is_the_size_it_means(tmp_path):
    """robot_properties_bolt's ground plane: a one-link robot whose 30 m plane.obj sits beside
    its 30 x 30 x 10 m collision box is not a millimetre slip (U413); alone it may be."""
    from urdftool.lint.engine import CheckOptions, load_and_check

    (tmp_path / "plane.obj").write_text("v -15 -15 0\nv 15 -15 0\nv 15 15 0\nv -15 15 0\n"
                                        "f 1 2 3\nf 1 3 4\n")
    visual = '<visual><geometry><mesh filename="plane.obj"/></geometry></visual>'
    box = '<collision><geometry><box size="30 30 10"/></geometry></collision>'

    def codes(shapes):
        (tmp_path / "plane.urdf").write_text(f'<robot name="plane"><link name="p">{shapes}'
                                             "</link></robot>")
        result = load_and_check(str(tmp_path / "plane.urdf"), CheckOptions())
        return {f.code for f in result.findings}

    assert "U413" not in codes(visual + box)
    assert "U413" in codes(visual)
