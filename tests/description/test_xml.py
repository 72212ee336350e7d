"""description.xml helpers."""

from __future__ import annotations

import pytest
from lxml import etree

from urdftool.description.xml import child_list, children_named, first_child


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
    root = etree.fromstring(b'<transmission><!-- hardwareInterface --><hardwareInterface n="1"/>'
                            b'<joint><hardwareInterface n="deep"/></joint><?hardwareInterface?>'
                            b'<hardwareInterface n="2"/></transmission>')
    for element in (root, root.find("joint"), root.find("hardwareInterface")):
        for tag in ("hardwareInterface", "joint", "actuator"):
            assert children_named(element, tag) == element.findall(tag)
    assert [e.get("n") for e in children_named(root, "hardwareInterface")] == ["1", "2"]


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
        elements = [*root.iter(etree.Element), etree.Element("elsewhere")]
        assert positions.positions(elements) == [positions.get(e) for e in elements]
        assert positions.positions(elements)[-1] is None


_TOKENS = [b"<", b">", b"&", b"&amp;", b"&#0;", b"&#x41;", b"--", b"]]>", b'"', b"'", b"=", b" ",
           b"\n", b"<!--", b"-->", b"<?", b"?>", b"</a>", b"<a>", b'xmlns:p="u"', b"p:x", b"\x01",
           b"\x7f", b'encoding="Shift_JIS"', b'version="1.1"', b'<?xml version="1.0"?>', b"\t",
           b"<![CDATA[", b"a:b:c", b'xmlns=""', b'xmlns:p=""', b"1x", b"-", b".", b":"]
_SEEDS = [b'<?xml version="1.0"?>\n<robot name="r">\n  <link name="a"><visual><geometry><box '
          b'size="1 1 1"/></geometry></visual></link>\n  <joint name="j" type="fixed"><parent '
          b'link="a"/><child link="b"/></joint>\n  <link name="b"/>\n<!-- c --></robot>\n',
          b'<robot name="r" xmlns:xacro="http://x"><xacro:property name="p" value="1"/>'
          b'<link name="a"/><?pi x?><![CDATA[ <x> ]]></robot>']


def _mutated(rng, count: int, fewest: int, inserted: float):
    """``count`` documents, each a seed with ``fewest`` to 3 tokens inserted (with chance
    ``inserted``) or a few bytes deleted."""
    for _ in range(count):
        data = bytearray(rng.choice(_SEEDS))
        for _ in range(rng.randint(fewest, 3)):
            at = rng.randrange(len(data) + 1)
            if rng.random() < inserted:
                data[at:at] = rng.choice(_TOKENS)
            else:
                del data[at:at + rng.randint(1, 4)]
        yield bytes(data)


def test_a_plain_document_libxml2_parses_without_a_word_is_one_expat_accepts():
    """What lets parse skip expat's pass (_clean): over mutated documents (markup, entities,
    control characters, namespaces, versions and encodings declared), each plain one that
    libxml2 parsed without an error or warning, or a declared encoding, is one expat accepts."""
    import random

    from urdftool.description import xml

    clean = 0
    for data in _mutated(random.Random(7), 4000, 1, 0.5):
        if xml._plain_start_tags(data) is None:
            continue
        parser = etree.XMLParser(**xml._LXML_PARSER_OPTIONS)
        try:
            etree.fromstring(data, parser)
        except etree.XMLSyntaxError:
            continue
        if xml._clean(parser, data):
            clean += 1
            assert xml._accepted(data), data
    assert clean > 100


def test_the_bulk_scan_finds_the_start_tags_the_patterns_find(monkeypatch):
    """A document scanned in bulk (large, or once numpy is imported) has its start tags
    found by numpy (_bulk_start_tags): over mutated documents expat accepts (comments, CDATA,
    instructions, a "<" in each, or none of them), the same offsets as the patterns', and
    the same newlines."""
    import random

    from urdftool.description import xml

    compared = 0
    for data in _mutated(random.Random(11), 3000, 0, 0.6):
        monkeypatch.setattr(xml, "_in_bulk", lambda data: False)
        scanned = xml._plain_start_tags(data)
        if scanned is None or not xml._accepted(data):
            continue
        newlines = xml.newlines(data)
        monkeypatch.setattr(xml, "_in_bulk", lambda data: True)
        assert xml._plain_start_tags(data) == scanned, data
        assert xml.newlines(data) == newlines
        compared += 1
    assert compared > 500


def test_a_small_document_is_scanned_in_bulk_only_once_numpy_is_imported(monkeypatch):
    """A robot checked before anything imports numpy is scanned by the patterns (no import
    for the scan), any later one by numpy, as a large document always is."""
    import sys

    import numpy  # noqa: F401 - (imported: a later robot's case)

    from urdftool.description import xml

    small = b'<robot name="r">\n<link name="a"/>\n</robot>\n'
    assert xml._in_bulk(small) and xml._in_bulk(b" " * xml.BULK_SCAN)
    monkeypatch.delitem(sys.modules, "numpy")
    assert not xml._in_bulk(small) and xml._in_bulk(b" " * xml.BULK_SCAN)


def test_a_large_plain_document_is_scanned_in_bulk_where_expat_puts_its_tags(monkeypatch):
    from urdftool.description import xml

    bulk = []
    scan = xml._bulk_start_tags
    monkeypatch.setattr(xml, "_bulk_start_tags", lambda *a: bulk.append(a) or scan(*a))
    data = (b'<?xml version="1.0"?>\n<!-- <link name="commented"/> -->\n<robot name="r">\n'
            b'  <link\n     name="a" note="x > y"><?pi <b/> ?><visual/></link>\n'
            b'<![CDATA[ <joint/> ]]>\n\t<joint name="j"><parent link="a"/></joint>' +
            b'<link name="l"><!-- %s --><visual/></link>\n' % (b"x" * xml.BULK_SCAN) + b'</robot>\n')
    root, positions = xml.parse(data)
    assert bulk and isinstance(positions, xml._StartOffsets)
    assert [positions[e] for e in root.iter(etree.Element)] == xml.start_tag_positions(data)


def test_a_plain_document_libxml2_parses_cleanly_is_not_parsed_again(monkeypatch):
    """expat's second pass only for what libxml2 said a word about, or that declares its
    encoding (Shift_JIS: libxml2 reads it, expat refuses it)."""
    from urdftool.description import xml

    passes = []
    accepted = xml._accepted
    monkeypatch.setattr(xml, "_accepted", lambda data: passes.append(data) or accepted(data))
    root, positions = xml.parse(b'<robot name="r">\n<!-- a -->\n  <link name="a"/></robot>')
    assert not passes and positions[root.find("link")] == (3, 3)
    for declared in (b'<?xml version="1.0" encoding="Shift_JIS"?>', b'<?xml version="1.1"?>'):
        with pytest.raises(xml.XmlProblem) if b"Shift" in declared else \
                __import__("contextlib").nullcontext():
            xml.parse(declared + b'<robot name="r"/>')
        assert passes[-1].startswith(declared)


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


def test_an_empty_included_file_says_it_is_empty(tmp_path):
    """OUXT-Polaris/wamv_description's wamv.urdf.xacro includes wamv.ros2_control.xacro, a
    file of 0 bytes: xacro fails on it with expat's bare 'no element found'."""
    from urdftool.description.load import load
    from urdftool.errors import LoadError

    (tmp_path / "control.xacro").write_bytes(b"")
    (tmp_path / "blank.xacro").write_bytes(b"\n  \n")
    for name, said in (("control.xacro", "empty"), ("blank.xacro", "only white space")):
        (tmp_path / "top.urdf.xacro").write_text(
            '<robot name="t" xmlns:xacro="http://ros.org/wiki/xacro"><link name="a"/>\n'
            f'  <xacro:include filename="{name}"/>\n</robot>\n')
        with pytest.raises(LoadError) as caught:
            load(tmp_path / "top.urdf.xacro")
        assert caught.value.location.file.endswith(name)
        assert caught.value.message.endswith(f"(the file is {said})"), caught.value.message


def test_a_mismatched_end_tag_names_the_element_still_open_and_its_line(tmp_path):
    """delta_robot_simulation's codian.urdf said only 'malformed XML: mismatched tag' at its
    last line: the <gazebo> left open 184 lines above is what to look for. The same through
    xacro (an included file); a file of comments only says so (match_mobile_robotics_jazzy's
    common_wheel.gazebo.xacro, every macro commented out)."""
    from urdftool.description.load import load
    from urdftool.errors import LoadError

    (tmp_path / "r.urdf").write_text('<robot name="r">\n  <link name="a">\n  <gazebo>\n'
                                     '  </gazebo>\n</robot>\n')
    with pytest.raises(LoadError) as caught:
        load(tmp_path / "r.urdf")
    assert caught.value.message.endswith("mismatched tag: </robot> comes while <link>, opened "
                                         "at line 2, is still open"), caught.value.message
    (tmp_path / "part.xacro").write_text('<robot xmlns:xacro="http://ros.org/wiki/xacro">\n'
                                         '<link name="b"></joint></robot>\n')
    (tmp_path / "gone.xacro").write_text("<!-- <xacro:macro name='m'/> -->\n")
    for name, said in (("part.xacro", "</joint> comes while <link>, opened at line 2, is still open"),
                       ("gone.xacro", "no element found (the file holds only comments)")):
        (tmp_path / "top.urdf.xacro").write_text(
            '<robot name="t" xmlns:xacro="http://ros.org/wiki/xacro"><link name="a"/>\n'
            f'  <xacro:include filename="{name}"/>\n</robot>\n')
        with pytest.raises(LoadError) as caught:
            load(tmp_path / "top.urdf.xacro")
        assert caught.value.message.endswith(said), caught.value.message


# A file's lines end as a Location numbers them: LF, CR LF, or CR alone; a LINE SEPARATOR in
# a comment ends none (a file ended by CR alone said every message on line 1, and its merge
# conflict was "malformed XML": the markers were not at a line start by LF)
LINE_ENDS = [("\n", ""), ("\r\n", ""), ("\r", ""), ("\n", "<!-- a\u2028b -->")]


@pytest.mark.parametrize("end, comment", LINE_ENDS)
def test_the_messages_of_a_document_say_its_lines_whatever_ends_them(tmp_path, end, comment):
    from urdftool.description.xml import XmlProblem, merge_conflict, parse, tinyxml2_comments

    def data(text: str) -> bytes:
        return text.replace("\n", end).replace("<robot", comment + "<robot", 1).encode()

    conflicted = data(CONFLICTED.decode())
    with pytest.raises(XmlProblem) as caught:
        parse(conflicted)
    assert caught.value.message.startswith("unresolved merge conflict") and \
        caught.value.line == 3 and "at lines 5, 7" in caught.value.message
    assert merge_conflict(conflicted).line == 3
    commented = data('<robot name="r">\n\n  <!-- a -- b -->\n  <link name="a"/>\n</robot>\n')
    assert tinyxml2_comments(commented)[1] == 3


def _shapes(text: str):
    from urdftool.description.xml import parse

    root, positions = parse(text.encode("utf-8"))
    shapes = getattr(positions, "shapes", None)  # (a plain document's: see parse)
    return shapes(child_list(root)) if shapes is not None else None


def test_the_shapes_of_siblings_are_their_markup_without_attribute_values():
    """Each sibling's markup from its start tag to the next one's, values left out: the same
    bytes for elements of the same tags, attribute names and nesting, whatever their values
    (entities, huge or not-a-number texts, namespaced attributes keep their names)."""
    shapes = _shapes('<?xml version="1.0"?>\n<r xmlns:x="urn:x">'
                     '<a n="1e400" x:m="NaN"><b v="&quot;&lt;&#x3e;&amp;"/></a>\n'
                     '<a n="1" x:m="-0"><b v=""/></a>\n'
                     '<a n="1"><c v="1"/></a>'
                     '<a n="?"/>text a="b"<z/></r>')
    assert shapes == [b'<a n= x:m=><b v=/></a>\n', b'<a n= x:m=><b v=/></a>\n',
                      b'<a n=><c v=/></a>', b'<a n=/>text a=']


@pytest.mark.parametrize("text", [
    "<r><a n='1'/><b/></r>",  # an apostrophe (around a value, or in a text)
    '<r><a n="1"/><!-- c --><b/></r>', '<r><a n="1"/><![CDATA[x]]><b/></r>',
    '<r><a n="1"/><?pi x?><b/></r>',
    '<r><a n=">"/><b/></r>',  # a ">" in a value
    '<r><a n = "1"/><b/></r>', '<r><a>"</a><b/></r>',  # a quote after no "="
    '<r><a n="\u0661"/><b/></r>',  # not ASCII: the document's places are not scanned
])
def test_a_document_not_plain_enough_has_no_shapes(text):
    assert _shapes(text) is None
    assert _shapes('<r><a n="1"/><b/></r>') == [b'<a n=/>']


@pytest.mark.parametrize("name, text, said", [
    # talos's calibration.xacro: <xacro:...> in a <robot> that declares no xacro namespace
    ("r.urdf.xacro", '<robot name="r">\n  <xacro:property name="p" value="1"/>\n</robot>\n',
     "unbound prefix: 'xacro:' of <xacro:property> is declared nowhere in the file; declare it "
     "on the root element (<robot xmlns:xacro=\"http://www.ros.org/wiki/xacro\">)"),
    # Shadow's MuJoCo URDFs: a licence comment above the declaration
    ("r.urdf", '<!-- licence -->\n\n<?xml version="1.0"?>\n<robot name="r"/>\n',
     "XML or text declaration not at start of entity: the file's <?xml ...?> declaration must "
     "be its first text, and a comment comes before it, at line 1; move the declaration to the "
     "top of the file or remove it"),
    # URDF_exploring's ENS_macro.urdf.xacro, saved as Latin-1
    ("r.urdf", '<robot name="r">\n  <link name="R\xe9volution"/>\n</robot>\n',
     "not well-formed (invalid token): byte 0xE9 is not UTF-8 (the file is saved in another "
     "encoding, Latin-1 or Windows-1252?); save it as UTF-8, or name its encoding in the XML "
     "declaration (<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>)"),
    # uuv_simulator's comment ruled with dashes (urdfdom reads it in a plain URDF: U001's warning)
    ("r.urdf.xacro", '<robot name="r">\n  <!--\n  ------\n  -->\n  <link name="a"/>\n</robot>\n',
     "not well-formed (invalid token): '--' inside the comment opened at line 2: XML allows no "
     "'--' within a comment (a comment nested in it has one); remove it"),
    # rb1_base's omni_wheel.transmission.xacro: a start tag's '>' missing
    ("r.urdf", '<robot name="r">\n  <joint name="j"\n    <parent link="a"/>\n  </joint>\n</robot>\n',
     "not well-formed (invalid token): '<' inside the start tag <joint... opened at line 2, "
     "whose '>' is missing"),
    # reflex's rhr_visualization.URDF: links written without their <robot>
    ("r.urdf", '<link name="a">\n</link>\n<link name="b"/>\n',
     "junk after document element: another element, <link>, comes after the end of the root "
     "element <link>, and an XML file has one root (a robot description's is <robot>)"),
    # amr-ros-config's pioneer3dx_body.xacro: a namespace URI written across two lines
    ("r.urdf.xacro", '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"\n'
     '  xmlns:controller="http://example.com/gazebo/\n  xmlschema/#controller">\n'
     '  <link name="a"/>\n</robot>\n',
     "syntax error: the URI of namespace 'controller' holds white space (at line 2); write it "
     "without"),
])
def test_the_parsers_reason_is_said_with_what_it_met(tmp_path, name, text, said):
    """expat's bare reasons ("unbound prefix", "not well-formed (invalid token)") named neither
    the prefix, the byte nor the tag: each is said with what was met there and what to do,
    in a plain URDF and through xacro alike (20 of the sweep's 30 U001 rows said only expat's
    words)."""
    from urdftool.description.load import load
    from urdftool.errors import LoadError

    (tmp_path / name).write_bytes(text.encode("latin-1"))
    with pytest.raises(LoadError) as caught:
        load(tmp_path / name)
    assert caught.value.message == f"malformed XML: {said}", caught.value.message
