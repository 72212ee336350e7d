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
