"""description.xml helpers."""

from __future__ import annotations

from lxml import etree

from urdftool.description.xml import first_child


def test_child_is_find_for_a_plain_tag():
    root = etree.fromstring(b'<link><!-- a comment --><visual n="1"/><origin/><visual n="2"/>'
                            b'<geometry><origin n="deep"/></geometry></link>')
    for tag in ("visual", "origin", "geometry", "collision", "box"):
        assert first_child(root, tag) is root.find(tag)
    assert first_child(root, "visual").get("n") == "1"  # the first of several
    assert first_child(root.find("geometry"), "origin").get("n") == "deep"
    assert first_child(root.find("origin"), "origin") is None  # a leaf has no children
    assert first_child(etree.Comment("c"), "origin") is None


def test_children_named_is_findall_for_a_plain_tag():
    from urdftool.description.xml import children_named

    root = etree.fromstring(b'<joint><child link="a"/><!-- c --><origin/><child link="b"/>'
                            b'<x><child link="deep"/></x></joint>')
    for tag in ("child", "origin", "limit"):
        assert children_named(root, tag) == root.findall(tag)
    assert [c.get("link") for c in children_named(root, "child")] == ["a", "b"]
