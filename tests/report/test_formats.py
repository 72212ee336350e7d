"""Every output format is fed from the same findings; the json shape is a public contract."""

from __future__ import annotations

import io
import json

import pytest
from lxml import etree

import sarif_schema

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
            {"file": "a.urdf", "line": 7, "code": "U204", "name": "inverted-limits",
             "severity": "error", "message": "lower above upper, 100%"},
            {"file": "parts.xacro", "line": 3, "code": "U206", "name": "axis-not-unit",
             "severity": "warning", "message": "axis: length 2,\nnot 1"},
        ],
        "summary": {"files": 2, "errors": 1, "warnings": 1},
    }


def test_github_annotations_escape_data_and_properties():
    lines = rendered("github").splitlines()
    assert lines[0] == "::error file=a.urdf,line=7,title=U204 inverted-limits::lower above upper, 100%25"
    assert lines[1] == "::warning file=parts.xacro,line=3,title=U206 axis-not-unit::axis: length 2,%0Anot 1"


def test_junit_has_a_suite_per_file_and_a_failure_per_finding():
    root = etree.fromstring(rendered("junit").encode())
    suites = root.findall("testsuite")
    assert [s.get("name") for s in suites] == ["a.urdf", "b.urdf"]
    assert len(suites[0].findall("testcase/failure")) == 2
    assert suites[1].findall("testcase/failure") == [] and len(suites[1].findall("testcase")) == 1
    assert root.get("failures") == "2"


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
    assert len(lines) == 2 and lines[1] == "urdftool: 1 files, 1 errors, 0 warnings"
    command, _, message = lines[0].partition("::")[2].partition("::")
    assert command == ("error file=x%0A%3A%3Awarning%3A%3Ay%2Cz.urdf,line=7,"
                       "title=U204 inverted-limits")
    assert message.startswith("joint 'j%0A::error file=a.urdf,line=1::pwned%0D%0A1 file")
    assert "\\x1b[8mhidden" in message and "\\u202eevil\\x00\\udce9" in message
    assert _control_characters(hostile("github")) == {"\n"}


def test_junit_stays_valid_xml_with_control_characters():
    document = hostile("junit")
    root = etree.fromstring(document.encode())
    failure = root.find("testsuite/testcase/failure")
    assert failure.get("message").startswith("joint 'j\\n::error file=a.urdf")
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
        message = data["runs"][0]["results"][0]["message"]["text"]
    else:
        message = data["diagnostics"][0]["message"]
    assert message == f"joint '{HOSTILE}': swap them"


def test_printable_escapes_every_control_format_and_separator_character():
    import sys
    import unicodedata

    from urdftool.report import printable

    unsafe = "".join(chr(c) for c in range(sys.maxunicode + 1)
                     if unicodedata.category(chr(c)) in ("Cc", "Cf", "Cs", "Zl", "Zp"))
    assert _control_characters(printable(unsafe)) == set()
    assert printable("a\tb\x1b\u2028\U000e0041") == "a\\tb\\x1b\\u2028\\U000e0041"
    assert printable("naïve 机器人 ✓") == "naïve 机器人 ✓"


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
