"""Inline ``<!-- urdftool: ignore ... -->`` suppressions (the U901 case is in tests/cases)."""

from __future__ import annotations

from urdftool.diagnostics import Finding, Location, Severity
from urdftool.lint.engine import CheckOptions, Selection, load_and_check
from urdftool.lint.rules import CATALOGUE
from urdftool.lint.suppressions import apply, parse

TEXT = """<robot name="r">
  <!-- urdftool: ignore U206 -->

  <!-- another comment -->
  <joint name="a"/>
  <link name="b"/> <!-- urdftool: ignore U203, axis-not-unit -->
  <!-- urdftool: ignore-file U1 -->
  <!--
       urdftool: ignore U204
  -->
  <joint name="c"/>
</robot>
"""


def test_parse_targets_the_next_element_or_the_trailed_line():
    found = {s.line: (s.target, s.selectors) for s in parse(TEXT, "r.urdf")}
    assert found == {
        2: (5, ("U206",)),                       # skips blank and comment-only lines
        6: (6, ("U203", "axis-not-unit")),       # a trailing comment covers its own line
        7: (None, ("U1",)),                      # file level
        8: (11, ("U204",)),                      # a comment across lines
    }


def test_lines_are_numbered_as_findings_are_at_cr_lf_or_cr_only():
    """A LINE SEPARATOR or NEL in a comment above (str.splitlines ends a line there, XML does
    not) made the suppression cover a later line than the one below it: a reviewer saw it over
    one element while it silenced another. A file ending its lines with CR made each line 1."""
    for separator in ("\u2028", "\x85", "\x0c", "\u2029"):
        text = TEXT.replace("<robot name=\"r\">", f"<robot name=\"r\"> <!-- a{separator}b -->")
        assert {s.line: s.target for s in parse(text, "r.urdf")} == {2: 5, 6: 6, 7: None, 8: 11}
    for end in ("\r", "\r\n"):
        assert {s.line: s.target for s in parse(TEXT.replace("\n", end), "r.urdf")} == \
            {2: 5, 6: 6, 7: None, 8: 11}


def test_an_unused_suppression_on_a_line_ended_by_cr_is_removed_with_its_line(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_bytes(b"<robot>\r  <!-- urdftool: ignore U204 -->\r<joint/>\r</robot>\r")
    [unused] = apply([], _sources(path), lambda code: True, CATALOGUE)
    [edit] = unused.fix.edits
    assert (unused.location.line, edit.old) == (2, "  <!-- urdftool: ignore U204 -->\r")


def _finding(code, file, line, via=()):
    return Finding(code, "x", Severity.ERROR, "m", Location(file, line, via))


def _sources(*paths):
    return {str(path): path.read_bytes() for path in paths}


def test_apply_silences_by_code_prefix_and_call_site(tmp_path):
    robot, macro = tmp_path / "robot.xacro", tmp_path / "macro.xacro"
    robot.write_text("<robot>\n<!-- urdftool: ignore U2 -->\n<xacro:wheel/>\n</robot>\n")
    macro.write_text("<robot>\n<joint/>\n</robot>\n")
    call = Location(str(robot), 3)
    kept = apply([_finding("U206", str(macro), 2, (call,)),
                  _finding("U206", str(macro), 2, (Location(str(robot), 4),)),
                  _finding("U101", str(macro), 2, (call,))],
                 _sources(robot, macro), lambda code: True, CATALOGUE)
    assert [(f.code, f.location.via[0].line) for f in kept] == [("U206", 4), ("U101", 3)]


def test_unused_is_reported_only_when_its_rules_ran(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_text("<robot>\n<!-- urdftool: ignore U204 -->\n<joint/>\n</robot>\n")
    assert [f.code for f in apply([], _sources(path), lambda code: True, CATALOGUE)] == ["U901"]
    assert apply([], _sources(path), lambda code: code != "U204", CATALOGUE) == []
    assert apply([], _sources(path), lambda code: code != "U901", CATALOGUE) == []


def test_suppressions_are_found_beside_bytes_decoding_replaces(tmp_path):
    # the bytes are searched for the word before any decoding: a broken UTF-8 sequence right
    # before the comment (decoded as U+FFFD) neither hides it nor makes one of a file without
    path, plain = tmp_path / "r.urdf", tmp_path / "p.urdf"
    path.write_bytes(b"<robot>\n\xe2\x82<!-- urdftool: ignore U204 -->\n<joint/>\n</robot>\n")
    plain.write_bytes(b"<robot>\n\xe2\x82<!-- urdftool ignore U204 -->\n<joint/>\n</robot>\n")
    found = apply([], _sources(path), lambda code: True, CATALOGUE)
    assert [(f.code, f.location.line) for f in found] == [("U901", 2)]
    assert apply([], _sources(plain), lambda code: True, CATALOGUE) == []


def test_check_file_applies_suppressions_and_selection(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_text("""<robot name="r">
  <link name="a"/><link name="b"/>
  <!-- urdftool: ignore inverted-limits -->
  <joint name="j" type="revolute">
    <parent link="a"/><child link="b"/>
    <limit lower="1" upper="-1" effort="1" velocity="1"/> <!-- urdftool: ignore U204 -->
  </joint>
</robot>
""")
    codes = lambda options: [(f.code, f.line) for f in load_and_check(str(path), options).findings]  # noqa: E731
    # U204 is located at <limit>: the trailing comment silences it, the one above <joint> is unused
    assert codes(CheckOptions()) == [("U901", 3)]
    assert codes(CheckOptions(selection=Selection(ignore=("U204",)))) == []


LIMITS = """<robot name="r">
  <link name="a"/><link name="b"/>
  <joint name="j" type="revolute">
    <parent link="a"/><child link="b"/>
    {comment}<limit lower="1" upper="-1" effort="1" velocity="1"/>
  </joint>
</robot>
"""
COMMENT = "<!-- urdftool: ignore U204 -->\n    "


def test_suppression_only_in_the_data_given_is_honoured(tmp_path):
    """An editor's unsaved buffer: the comment is in ``data``, not yet on disk."""
    path = tmp_path / "r.urdf"
    path.write_text(LIMITS.format(comment=""))
    data = LIMITS.format(comment=COMMENT).encode()
    result = load_and_check(str(path), CheckOptions(), data=data)
    assert [(f.code, f.line) for f in result.findings] == []


def test_suppression_only_on_disk_is_not_applied_to_the_data_given(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_text(LIMITS.format(comment=COMMENT))
    data = LIMITS.format(comment="").encode()
    result = load_and_check(str(path), CheckOptions(), data=data)
    assert [(f.code, f.line) for f in result.findings] == [("U204", 5)]


def test_suppressions_in_included_files_come_from_the_bytes_loaded(tmp_path, monkeypatch):
    """A xacro include is read once, by the loader; suppressions are not read again from disk
    (the file changed on disk after loading is not what was checked)."""
    (tmp_path / "joint.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <joint name="j" type="revolute">\n'
        '    <parent link="a"/><child link="b"/>\n'
        '    <!-- urdftool: ignore U204 -->\n'
        '    <limit lower="1" upper="-1" effort="1" velocity="1"/>\n'
        '  </joint>\n</robot>\n')
    robot = tmp_path / "r.urdf.xacro"
    robot.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                     '  <link name="a"/><link name="b"/>\n'
                     '  <xacro:include filename="joint.xacro"/>\n</robot>\n')
    from urdftool.lint import suppressions

    def no_disk(name, *args, **kwargs):
        raise AssertionError(f"suppressions re-read {name} from disk")

    monkeypatch.setattr(suppressions, "read_regular", no_disk)
    assert load_and_check(str(robot), CheckOptions()).findings == []


def test_suppressions_in_standard_input_count():
    """Read from the bytes loaded, a comment in piped input works like one in a file."""
    data = LIMITS.format(comment=COMMENT).encode()
    assert load_and_check("-", CheckOptions(), data=data).findings == []
    unused = LIMITS.format(comment="").replace("<link", COMMENT + "<link", 1).encode()
    assert [(f.code, f.file) for f in load_and_check("-", CheckOptions(), data=unused).findings] \
        == [("U901", "<stdin>"), ("U204", "<stdin>")]


def test_each_finding_is_held_against_the_suppressions_of_its_lines_only(tmp_path, monkeypatch):
    """A robot with a suppression above each of its 8,000 joints took 40 s to check (2,000:
    6 s): each finding was held against every suppression of its file, each comment's line
    counted from the file's start, each unused one's codes matched against every rule and the
    file decoded again for each removal. The findings kept and the U901s are the same."""
    import urdftool.lint.suppressions as suppressions

    path = tmp_path / "r.urdf"
    count = 3000
    path.write_text("<robot>\n<!-- urdftool: ignore-file U1 -->\n" + "".join(
        f"<!-- urdftool: ignore U206 -->\n<joint name='j{i}'/>\n" for i in range(count))
        + "</robot>\n")
    findings = [_finding("U206", str(path), 4 + 2 * i) for i in range(0, count, 2)] + \
        [_finding("U101", str(path), 4), _finding("U204", str(path), 4)]
    held, counted = [], []
    covers = suppressions.Suppression.covers
    monkeypatch.setattr(suppressions.Suppression, "covers",
                        lambda self, *args: held.append(1) or covers(self, *args))
    monkeypatch.setattr(suppressions, "_checkable",
                        lambda s, ran, catalogue, real=suppressions._checkable:
                        counted.append(1) or real(s, ran, catalogue))
    kept = apply(findings, _sources(path), lambda code: True, CATALOGUE)
    assert [f.code for f in kept] == ["U204"] + ["U901"] * (count // 2)
    assert [f.location.line for f in kept[1:4]] == [5, 9, 13]
    assert kept[1].fix.edits[0].line == 5
    assert len(held) <= 2 * len(findings) and len(counted) == 1
