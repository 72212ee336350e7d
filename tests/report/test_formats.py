"""Every output format is fed from the same findings; the json shape is a public contract."""

from __future__ import annotations

import io
import json

import pytest
from lxml import etree

import sarif_schema
from rule_links import assert_rule_page

from urdftool.diagnostics import Finding, Location, Severity
from urdftool.lint.engine import FileResult
from urdftool.report import render

RESULTS = [
    FileResult("a.urdf", [
        Finding("U204", "inverted-limits", Severity.ERROR, "lower above upper, 100%",
                Location("a.urdf", 7)),
        Finding("U206", "axis-not-unit", Severity.WARNING, "axis: length 2,\nnot 1",
                Location("parts.xacro", 3, (Location("a.urdf", 9),))),
    ]),
    FileResult("b.urdf", []),
]


def rendered(format_name: str) -> str:
    stream = io.StringIO()
    render(format_name, RESULTS, stream)
    return stream.getvalue()


def test_json_is_exactly_the_documented_shape():
    data = json.loads(rendered("json"))
    assert data == {
        "version": 1,
        "diagnostics": [
            {"file": "a.urdf", "line": 7, "column": None, "code": "U204",
             "name": "inverted-limits", "severity": "error",
             "message": "lower above upper, 100%", "via": []},
            {"file": "parts.xacro", "line": 3, "column": None, "code": "U206",
             "name": "axis-not-unit", "severity": "warning", "message": "axis: length 2,\nnot 1",
             "via": [{"file": "a.urdf", "line": 9, "column": None}]},
        ],
        "summary": {"files": 2, "errors": 1, "warnings": 1, "notes": 0,
                    "lines": {"errors": 1, "warnings": 1, "notes": 0}},
    }


def test_github_annotations_escape_data_and_properties():
    lines = rendered("github").splitlines()
    assert lines[0] == "::error file=a.urdf,line=7,title=U204 inverted-limits::lower above upper, 100%25"
    # a line break of the message's own is escaped; %0A only before each macro call site
    assert lines[1] == ("::warning file=parts.xacro,line=3,title=U206 axis-not-unit::axis: length 2,"
                        "\\nnot 1%0Aexpanded from macro call at a.urdf:9")
    assert lines[2] == "urdftool: 2 files, 1 error, 1 warning, 0 notes"


def test_junit_has_a_suite_per_file_and_a_failure_per_failing_finding():
    root = etree.fromstring(rendered("junit").encode())
    suites = root.findall("testsuite")
    assert [s.get("name") for s in suites] == ["a.urdf", "b.urdf"]
    [failure] = suites[0].findall("testcase/failure")  # the warning passes: the run exits 0 on it
    assert failure.get("message") == "a.urdf:7: lower above upper, 100%"
    assert suites[0].findall("testcase/system-out")[0].text.startswith(
        "parts.xacro:3: warning U206 axis: length 2,\\nnot 1\nexpanded from macro call at a.urdf:9")
    assert suites[1].findall("testcase/failure") == [] and len(suites[1].findall("testcase")) == 1
    assert root.get("failures") == "1"


def test_junit_fails_warnings_only_when_checked_strictly():
    strict = [FileResult(r.path, r.findings, strict=True) for r in RESULTS]
    stream = io.StringIO()
    render("junit", strict, stream)
    assert etree.fromstring(stream.getvalue().encode()).get("failures") == "2"
    notes = [FileResult("n.urdf", [Finding("U999", "x", Severity.INFO, "m", Location("n.urdf"))],
                        strict=True)]
    stream = io.StringIO()
    render("junit", notes, stream)
    assert etree.fromstring(stream.getvalue().encode()).get("failures") == "0"


@pytest.mark.parametrize("results", [RESULTS, [FileResult(r.path, r.findings, strict=True)
                                               for r in RESULTS]])
def test_junit_is_valid_against_junit_10(results):
    from junit10 import validate

    stream = io.StringIO()
    render("junit", results, stream)
    validate(stream.getvalue())


def test_junit_10_validation_can_fail():
    from junit10 import validate

    document = rendered("junit").replace('<testcase name="U204', '<testcase file="a.urdf" name="U204')
    with pytest.raises(AssertionError, match="file"):
        validate(document)


def test_concise_is_one_line_per_finding_with_line_and_column():
    findings = [Finding("U204", "inverted-limits", Severity.ERROR, "swap, them\nnow",
                        Location("a b.urdf", 7, column=5)),
                Finding("U002", "empty-file", Severity.ERROR, "empty", Location("c.urdf"))]
    stream = io.StringIO()
    render("concise", [FileResult("a b.urdf", findings)], stream)
    assert stream.getvalue().splitlines() == [
        "a b.urdf:7:5: U204 [error] swap, them\\nnow", "c.urdf: U002 [error] empty"]
    assert rendered("concise").splitlines()[1] == \
        "parts.xacro:3: U206 [warning] axis: length 2,\\nnot 1"


def test_json_lines_is_one_json_diagnostic_per_line():
    lines = rendered("json-lines").splitlines()
    assert [json.loads(line) for line in lines] == json.loads(rendered("json"))["diagnostics"]


def test_gitlab_code_quality_has_stable_fingerprints():
    issues = json.loads(rendered("gitlab"))
    assert [i["severity"] for i in issues] == ["major", "minor"]
    assert issues[1]["location"] == {"path": "parts.xacro", "lines": {"begin": 3}}
    assert issues[0]["check_name"] == "U204 inverted-limits"
    moved = [FileResult("a.urdf", [Finding(f.code, f.name, f.severity, f.message,
                                           Location(f.file, (f.line or 0) + 40, f.location.via))
                                   for f in RESULTS[0].findings]), RESULTS[1]]
    stream = io.StringIO()
    render("gitlab", moved, stream)
    assert [i["fingerprint"] for i in json.loads(stream.getvalue())] == \
        [i["fingerprint"] for i in issues]  # a finding moved by an edit above it is the same
    twice = [FileResult("a.urdf", [RESULTS[0].findings[0]] * 2)]
    stream = io.StringIO()
    render("gitlab", twice, stream)
    assert len({i["fingerprint"] for i in json.loads(stream.getvalue())}) == 2


def test_gitlab_report_matches_the_code_quality_schema():
    import jsonschema

    schema = {"type": "array", "items": {
        "type": "object", "required": ["description", "check_name", "fingerprint", "severity",
                                       "location"],
        "properties": {
            "description": {"type": "string"}, "check_name": {"type": "string"},
            "fingerprint": {"type": "string", "pattern": "^[0-9a-f]{64}$"},
            "severity": {"enum": ["info", "minor", "major", "critical", "blocker"]},
            "location": {"type": "object", "required": ["path", "lines"], "properties": {
                "path": {"type": "string"},
                "lines": {"type": "object", "required": ["begin"],
                          "properties": {"begin": {"type": "integer", "minimum": 1}}}}}}}}
    jsonschema.validate(json.loads(rendered("gitlab")), schema)


def test_rdjson_carries_severity_code_url_and_macro_call_sites():
    data = json.loads(rendered("rdjson"))
    assert data["source"]["name"] == "urdftool"
    first, second = data["diagnostics"]
    assert first["severity"] == "ERROR" and first["code"]["value"] == "U204"
    assert_rule_page(first["code"]["url"], "U204")
    assert first["location"] == {"path": "a.urdf", "range": {"start": {"line": 7}}}
    assert second["related_locations"] == [{"message": "expanded from this macro call",
                                            "location": {"path": "a.urdf",
                                                         "range": {"start": {"line": 9}}}}]


def test_sarif_results_point_at_rules_and_macro_call_sites():
    data = json.loads(rendered("sarif"))
    run = data["runs"][0]
    rules = run["tool"]["driver"]["rules"]
    for result in run["results"]:
        assert rules[result["ruleIndex"]]["id"] == result["ruleId"]
        assert rules[result["ruleIndex"]]["help"]["text"]
    second = run["results"][1]
    assert second["locations"][0]["physicalLocation"]["region"]["startLine"] == 3
    assert second["relatedLocations"][0]["physicalLocation"]["artifactLocation"]["uri"] == "a.urdf"


def test_text_groups_by_file_and_shows_the_macro_call_chain():
    text = rendered("text")
    assert "a.urdf:7: error U204 lower above upper" in text
    assert "expanded from macro call at a.urdf:9" in text
    assert text.strip().endswith("2 files checked: 1 error, 1 warning, 0 notes")


def test_a_macro_calling_itself_is_one_line_of_its_call_chain():
    # ICube-Robotics/staubli_driver_ros2: staubli_macro.xacro:41 calls its own macro once a
    # link, so a finding in the sixth link came through six calls there, said once
    from urdftool.report.summary import via_text

    site, outer = Location("m.xacro", 41), Location("r.urdf.xacro", 50)
    assert via_text(Location("h.xacro", 3, via=(site,) * 6 + (outer,))) == [
        "expanded from 6 nested calls of a macro calling itself at m.xacro:41",
        "expanded from macro call at r.urdf.xacro:50"]


def test_sarif_validates_against_the_official_schema():
    sarif_schema.validate(json.loads(rendered("sarif")))


def test_schema_validation_can_fail():
    import jsonschema
    import pytest

    log = json.loads(rendered("sarif"))
    log["runs"][0]["results"][0]["level"] = "fatal"
    with pytest.raises(jsonschema.ValidationError):
        sarif_schema.validate(log)


def test_text_is_plain_off_a_terminal_and_coloured_on_one(monkeypatch):
    plain = rendered("text")
    assert "\x1b[" not in plain
    monkeypatch.setenv("FORCE_COLOR", "1")
    monkeypatch.delenv("NO_COLOR", raising=False)
    coloured = rendered("text")
    assert "\x1b[" in coloured
    import re

    assert re.sub(r"\x1b\[[0-9;]*m", "", coloured) == plain


# A name written to forge report lines: a GitHub workflow command, a fake verdict, a carriage
# return that overwrites the line on a terminal, ANSI escapes that hide or recolour text, a
# right-to-left override, a NUL and a lone surrogate (an undecodable byte in a file name).
HOSTILE = ("j\n::error file=a.urdf,line=1::pwned\r\n1 file checked: no problems found\n"
           "\x1b[8mhidden\x1b[0m\x1b]0;title\x07\u202eevil\x00\udce9")
HOSTILE_FILE = "x\n::warning::y,z.urdf"
HOSTILE_RESULTS = [FileResult(HOSTILE_FILE, [
    Finding("U204", "inverted-limits", Severity.ERROR, f"joint '{HOSTILE}': swap them",
            Location(HOSTILE_FILE, 7, (Location(f"m{HOSTILE}.xacro", 2),))),
])]


def hostile(format_name: str) -> str:
    stream = io.StringIO()
    render(format_name, HOSTILE_RESULTS, stream)
    return stream.getvalue()


def _control_characters(text: str) -> set[str]:
    import unicodedata

    return {c for c in text if unicodedata.category(c) in ("Cc", "Cf", "Cs", "Zl", "Zp")}


def test_text_escapes_what_could_forge_a_line():
    text = hostile("text")
    assert _control_characters(text) == {"\n"}
    lines = text.splitlines()
    assert len(lines) == 5  # file, finding, macro call site, blank, verdict
    assert lines[1].startswith("  x\\n::warning::y,z.urdf:7: error U204 joint 'j\\n::error ")
    assert "\\r\\n1 file checked: no problems found\\n\\x1b[8mhidden" in lines[1]
    assert "\\u202eevil\\x00\\udce9': swap them (inverted-limits)" in lines[1]
    assert lines[-1] == "1 file checked: 1 error, 0 warnings, 0 notes"
    assert not any(line.startswith(("::", "1 file checked: no")) for line in lines)


def test_text_escapes_on_a_terminal_too(monkeypatch):
    monkeypatch.setenv("FORCE_COLOR", "1")
    monkeypatch.delenv("NO_COLOR", raising=False)
    import re

    coloured = re.sub(r"\x1b\[[0-9;]*m", "", hostile("text"))  # rich's own styles
    assert _control_characters(coloured) == {"\n"} and len(coloured.splitlines()) == 5


def test_github_commands_cannot_be_forged():
    lines = hostile("github").splitlines()
    assert len(lines) == 2 and lines[1] == "urdftool: 1 file, 1 error, 0 warnings, 0 notes"
    command, _, message = lines[0].partition("::")[2].partition("::")
    assert command == ("error file=x%0A%3A%3Awarning%3A%3Ay%2Cz.urdf,line=7,"
                       "title=U204 inverted-limits")
    assert message.startswith("joint 'j\\n::error file=a.urdf,line=1::pwned\\r\\n1 file")
    assert "\\x1b[8mhidden" in message and "\\u202eevil\\x00\\udce9" in message
    assert _control_characters(hostile("github")) == {"\n"}


def test_junit_stays_valid_xml_with_control_characters():
    document = hostile("junit")
    root = etree.fromstring(document.encode())
    failure = root.find("testsuite/testcase/failure")
    assert failure.get("message").startswith("x\\n::warning::y,z.urdf:7: joint 'j\\n::error file=")
    assert "\\x1b[8mhidden" in failure.get("message")
    assert root.find("testsuite").get("name") == "x\\n::warning::y,z.urdf"
    assert _control_characters(document) <= {"\n"}


@pytest.mark.parametrize("format_name", ["json", "sarif"])
def test_json_formats_keep_the_exact_text_in_valid_json(format_name):
    document = hostile(format_name)
    assert _control_characters(document) == {"\n"}  # json escapes every other one
    data = json.loads(document)
    if format_name == "sarif":
        sarif_schema.validate(data)
        message, syntax = sarif_schema.as_a_viewer_reads(
            data["runs"][0]["results"][0]["message"]["text"])
        assert syntax == []  # HOSTILE's "[8m" and "]0;" are brackets, not a link
    else:
        message = data["diagnostics"][0]["message"]
    # exact, but for the file name's undecodable byte (a surrogate code point), which no
    # strict JSON reader takes unpaired: U+FFFD and the byte's hex digits (json_output.named)
    assert message == f"joint '{HOSTILE[:-1]}\ufffdE9': swap them"


def test_printable_escapes_every_control_format_and_separator_character():
    import sys
    import unicodedata

    from urdftool.report import printable

    unsafe = "".join(chr(c) for c in range(sys.maxunicode + 1)
                     if unicodedata.category(chr(c)) in ("Cc", "Cf", "Cs", "Zl", "Zp"))
    assert _control_characters(printable(unsafe)) == set()
    assert printable("a\tb\x1b\u2028\U000e0041") == "a\\tb\\x1b\\u2028\\U000e0041"
    assert printable("naïve 机器人 ✓") == "naïve 机器人 ✓"


def test_printable_escapes_each_ascii_control_character_alone_and_in_text():
    from urdftool.report import printable

    # plain ASCII text is returned as it is without the regular expression: each C0 character
    # and DEL, alone or among printable ones, must still be escaped
    for code in [*range(0x20), 0x7f]:
        escaped = printable(f"link{chr(code)}x")
        assert chr(code) not in escaped and escaped.startswith("link\\") and escaped.endswith("x")
    text = "".join(chr(c) for c in range(0x20, 0x7f))
    assert printable(text) is text


def test_a_joint_name_cannot_forge_the_report(tmp_path, run_cli):
    robot = tmp_path / "r.urdf"
    robot.write_text(
        '<robot name="r">\n  <link name="a"/><link name="b"/>\n'
        '  <joint name="j&#10;::error file=r.urdf,line=1::pwned&#10;1 file checked: no problems '
        'found&#10;" type="revolute">\n    <parent link="a"/><child link="b"/>\n'
        '    <limit lower="1" upper="-1" effort="1" velocity="1"/>\n  </joint>\n</robot>\n')
    for format_name in ("text", "github"):
        lines = run_cli("check", robot, "-f", format_name).output.splitlines()
        assert not [line for line in lines if line.startswith("::error file=r.urdf,line=1")]
        assert "1 file checked: no problems found" not in lines


def test_file_names_said_on_stderr_cannot_forge_lines(tmp_path, run_cli):
    (tmp_path / ".git").mkdir()
    (tmp_path / "r.urdf").write_text('<robot name="r"><link name="a"/></robot>\n')
    (tmp_path / "m\n::error::x.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:macro name="m"><link name="b"/></xacro:macro></robot>\n')
    lines = run_cli("check", "-v", tmp_path).output.splitlines()
    assert [line for line in lines if "::error::x.xacro" in line] == [
        f"skipped {tmp_path}/m\\n::error::x.xacro: defines only macros or properties "
        "(a macro library)"]


TWO_NAMES = [FileResult(name, [Finding("U204", "inverted-limits", Severity.ERROR, "swap them",
                                       Location(name, 7, (Location(f"m{name}", 2),)))])
             for name in ("bad\udcff.urdf", "bad\udcfe.urdf", "bad\ufffdFF.urdf")]


@pytest.mark.parametrize("format_name", ["json", "json-lines", "gitlab", "rdjson", "sarif"])
def test_two_names_that_are_not_utf8_are_told_apart_in_every_json_format(format_name):
    """Session 20 left it: ``bad\\xff.urdf`` and ``bad\\xfe.urdf`` (and a name holding U+FFFD
    itself) were all ``bad\\ufffd.urdf`` in json, json-lines, gitlab and rdjson, so two files
    printed as one, and GitLab, which tells findings apart by fingerprint, had one fingerprint
    for both. Every JSON format spells a name one way (json_output.named; SARIF's URIs: %FF),
    its bytes given back by json_output.name_bytes."""
    import os

    stream = io.StringIO()
    render(format_name, TWO_NAMES, stream)
    text = stream.getvalue()
    assert text.isascii() and "\\ud" not in text
    documents = [json.loads(line) for line in text.splitlines()] if format_name == "json-lines" \
        else [json.loads(text)]
    if format_name == "sarif":
        results = documents[0]["runs"][0]["results"]
        names = [r["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] for r in results]
        assert names == ["bad%FF.urdf", "bad%FE.urdf", "bad%EF%BF%BDFF.urdf"]
        return
    found = {"json": lambda d: [(f["file"], f["via"][0]["file"]) for f in d["diagnostics"]],
             "json-lines": lambda d: [(d["file"], d["via"][0]["file"])],
             "gitlab": lambda d: [(i["location"]["path"], i["fingerprint"]) for i in d],
             "rdjson": lambda d: [(i["location"]["path"], i["related_locations"][0]["location"]
                                   ["path"]) for i in d["diagnostics"]]}[format_name]
    pairs = [pair for document in documents for pair in found(document)]
    assert len(pairs) == 3 and len({first for first, _ in pairs}) == 3
    assert len({second for _, second in pairs}) == 3  # the macro sites; gitlab: fingerprints
    from urdftool.report.json_output import name_bytes

    assert [os.fsdecode(name_bytes(first)) for first, _ in pairs] == \
        [result.path for result in TWO_NAMES]


MARKDOWN_NAMES = ("![x](https://example.com/p.png)", "@org/team", "#1 [link](javascript:x)",
                  "<img src=x onerror=alert(1)>", "**bold** _em_ `code` | cell", "# heading",
                  "``` fenced", "https://example.com/autolink", "a\n\n# b")


@pytest.mark.parametrize("name", MARKDOWN_NAMES)
def test_rdjson_messages_are_markdown_text_to_reviewdog(name):
    """reviewdog posts a diagnostic's message as it is into a Markdown review comment
    (``commentutil.MarkdownComment``): a link named ``![x](https://...)`` loaded an image in the
    pull request, ``@org/team`` notified a team. The message is escaper.markdown's code span:
    read by a Markdown parser, it is one piece of code holding the message."""
    from markdown_it import MarkdownIt

    results = [FileResult("a.urdf", [Finding("U204", "inverted-limits", Severity.ERROR,
                                             f"joint '{name}': swap them",
                                             Location("a.urdf", 7))])]
    stream = io.StringIO()
    render("rdjson", results, stream)
    message = json.loads(stream.getvalue())["diagnostics"][0]["message"]
    [paragraph] = [t for t in MarkdownIt("commonmark").parse(message) if t.type == "inline"]
    assert [child.type for child in paragraph.children] == ["code_inline"]
    assert paragraph.children[0].content.replace("\\|", "|") == \
        f"joint '{name}': swap them".replace("\n", "\\n")
