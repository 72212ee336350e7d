"""description.xml helpers."""

from __future__ import annotations

import pytest
from lxml import etree

from urdftool.description.xml import child_list, first_child


def test_child_is_find_for_a_plain_tag():
    root = etree.fromstring(b'<link><!-- a comment --><visual n="1"/><origin/><visual n="2"/>'
                            b'<geometry><origin n="deep"/></geometry></link>')
    for tag in ("visual", "origin", "geometry", "collision", "box"):
        assert first_child(root, tag) is root.find(tag)
    assert first_child(root, "visual").get("n") == "1"  # the first of several
    assert first_child(root.find("geometry"), "origin").get("n") == "deep"
    assert first_child(root.find("origin"), "origin") is None  # a leaf has no children
    assert first_child(etree.Comment("c"), "origin") is None


def test_child_list_is_what_iterating_gives():
    root = etree.fromstring(b'<link>text<!-- c --><visual/>tail<?pi x?><origin><box/></origin>'
                            b'<!-- d --></link>')
    for element in (root, root.find("origin"), root.find("visual")):
        assert child_list(element) == list(element)  # comments and instructions too, in order
    assert [getattr(c, "tag", None) for c in child_list(root)][1::2] == ["visual", "origin"]


def test_start_tags_found_by_scanning_are_where_expat_puts_them():
    from urdftool.description.xml import _StartOffsets, parse, start_tag_positions

    data = (b'<?xml version="1.0"?>\n<!-- <link name="commented"/> -->\n<robot name="r">\n'
            b'  <link\n     name="a" note="x > y"><?pi <b/> ?><visual/></link>\n'
            b'<![CDATA[ <joint/> ]]>\n\t<joint name="j"><parent link="a"/></joint></robot>\n')
    for document in (data, data.replace(b"<!-- <link name=\"commented\"/> -->", b"")
                     .replace(b"<?pi <b/> ?>", b"").replace(b"<![CDATA[ <joint/> ]]>", b"")):
        root, positions = parse(document)
        assert isinstance(positions, _StartOffsets)  # the scan, not a handler per element
        assert [positions[e] for e in root.iter(etree.Element)] == \
            start_tag_positions(document)
        assert positions[root.find("link")] == (4, 3)  # its "<", not its ">" (line 5)


def test_documents_the_scan_is_not_sure_of_take_the_full_pass():
    from urdftool.description.xml import _StartOffsets, parse

    for document in ('<robot name="r">\r\n<link name="a"/></robot>'.encode(),
                     '<robot name="\u00e9">\n<link name="a"/></robot>'.encode()):
        root, positions = parse(document)
        assert not isinstance(positions, _StartOffsets)
        assert positions[root.find("link")] == (2, 1)


def test_too_deep_a_plain_document_is_refused_where_expat_says():
    from urdftool.description.xml import MAX_DEPTH, XmlProblem, parse

    document = b"<robot>\n" + b"<a>" * MAX_DEPTH + b"</a>" * MAX_DEPTH + b"\n</robot>"
    with pytest.raises(XmlProblem) as refused:
        parse(document)
    assert refused.value.kind == "syntax" and "deeper than" in refused.value.message
    assert refused.value.line == 2


def test_a_too_deep_plain_document_is_refused_whether_or_not_lxml_builds_it(monkeypatch):
    from lxml import etree

    from urdftool.description import xml

    document = b"<robot>\n" + b"<a>" * xml.MAX_DEPTH + b"</a>" * xml.MAX_DEPTH + b"\n</robot>"
    if not xml._lxml_builds_too_deep():  # what parse counts on to skip the search
        root = etree.fromstring(document, etree.XMLParser(**xml._LXML_PARSER_OPTIONS))
        assert sum(1 for _ in root.iter()) < len(xml._plain_start_tags(document))
    for builds in {True, xml._lxml_builds_too_deep()}:  # searched, and as this lxml parses
        monkeypatch.setattr(xml, "_lxml_builds_too_deep", lambda: builds)
        with pytest.raises(xml.XmlProblem, match="deeper than"):
            xml.parse(document)


CONFLICTED = (b'<robot name="r">\n  <link name="base"/>\n<<<<<<< HEAD\n  <link name="arm"/>\n'
              b'=======\n  <link name="arm_2"/>\n>>>>>>> feature/arm\n</robot>\n')


def test_a_merge_conflict_is_said_to_be_one_at_its_first_marker(tmp_path):
    """A file left with git's conflict markers is not 'malformed XML: not well-formed (invalid
    token)' but an unresolved merge conflict, at the ``<<<<<<<`` line, with the other markers'
    lines: whether read as URDF, expanded as xacro (itself or included) or read as an SRDF."""
    from urdftool.description.documents import read_srdf
    from urdftool.description.load import load
    from urdftool.errors import LoadError

    (tmp_path / "arm.urdf").write_bytes(CONFLICTED)
    (tmp_path / "arm.urdf.xacro").write_bytes(CONFLICTED)
    (tmp_path / "top.urdf.xacro").write_text(
        '<robot name="t" xmlns:xacro="http://ros.org/wiki/xacro">\n\n'
        '  <xacro:include filename="arm.urdf"/>\n</robot>\n')
    for name in ("arm.urdf", "arm.urdf.xacro", "top.urdf.xacro"):
        with pytest.raises(LoadError) as caught:
            load(tmp_path / name)
        assert caught.value.kind == "syntax"
        assert caught.value.location.file.endswith(("arm.urdf", "arm.urdf.xacro"))
        assert caught.value.location.line == 3
        assert caught.value.message.startswith(
            "unresolved merge conflict: git's conflict marker '<<<<<<< HEAD' at this line; "
            "the other markers at lines 5, 7"), caught.value.message
    (tmp_path / "arm.srdf").write_bytes(CONFLICTED)
    srdf = read_srdf(tmp_path / "arm.srdf")
    assert (srdf.line, srdf.problem.split(":")[0]) == (3, "unresolved merge conflict")


def test_a_stray_marker_like_line_is_no_conflict_and_the_parser_is_believed():
    from urdftool.description.xml import XmlProblem, parse

    for data in (b'<robot name="r">\n=======\n<link name="a">\n</robot>\n',  # text, then a tag
                 b'<robot name="r">\n  <<<<<<<< eight\n</robot>\n',  # not seven
                 b'<robot name="r">\n  <<<<<<< indented\n</robot>\n'):  # not at a line start
        with pytest.raises(XmlProblem) as caught:
            parse(data)
        assert caught.value.message.startswith("malformed XML: "), data
