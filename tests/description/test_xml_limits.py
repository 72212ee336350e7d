"""A document past libxml2's limits is refused, not read in part (docs/attacks.md, session 8,
second wave). expat, which decides well-formedness, has no limit on a name, an attribute value,
a text or a comment; libxml2 (lxml, which builds the tree) recovers past its own by dropping
the rest of the document, cutting a text, or reading the markup inside a cut comment as
elements: the check ran on another robot than the file's (a link hidden in a comment was
checked; the links after a long attribute were not) or crashed (no root: U900)."""

from __future__ import annotations

import pytest

from urdftool.description.xml import XmlProblem, parse

BIG = 10_500_000  # over libxml2's 10,000,000 (XML_MAX_TEXT_LENGTH), under our 16 MiB files


@pytest.mark.parametrize("data", [
    b'<robot name="r"><link name="a" x="' + b"x" * BIG + b'"/><link name="b"/></robot>',
    b'<robot name="r"><link name="b"/><' + b"a" * 60_000 + b'/><joint name="j"/></robot>',
    b'<robot name="r">\n<link name="b">' + b"x" * BIG + b'</link><joint name="j"/></robot>',
    b'<robot name="r"><!--' + b"x" * BIG + b' <link name="hidden"/> --></robot>',
    b'<robot name="r">\r\n<!--' + b"x" * BIG + b' <link name="hidden"/> --></robot>',
], ids=["attribute", "name", "text", "comment", "comment, not plain"])
def test_a_document_past_libxml2s_limits_is_refused_not_read_in_part(data):
    with pytest.raises(XmlProblem, match="cannot be read whole"):
        parse(data)


def test_a_document_within_the_limits_is_read_whole():
    root, _ = parse(b'<robot name="r"><!--' + b"x" * 1_000_000 + b'--><link name="a" x="' +
                    b"y" * 1_000_000 + b'"/></robot>')
    assert [element.tag for element in root.iter() if isinstance(element.tag, str)] == [
        "robot", "link"]
