"""Every output format is fed from the same findings; the json shape is a public contract."""

from __future__ import annotations

import io
import json

from lxml import etree

import sarif_schema

from urdftool.diagnostics import Finding, Location, Severity
from urdftool.engine import FileResult
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
