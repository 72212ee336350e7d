"""SARIF for GitHub code scanning: URI references, help links, and the GitHub rules of Microsoft's
SARIF validator (Sarif.Multitool ``validate``, rule kind GHAS), re-stated here as checks."""

from __future__ import annotations

import io
import json
import re

import pytest

import sarif_schema
from rule_links import assert_rule_page, page_of

from urdftool.diagnostics import Finding, Location, Severity
from urdftool.lint.engine import FileResult
from urdftool.lint.rules import CATALOGUE
from urdftool.report import render

# RFC 3986 URI-reference characters: unreserved, reserved, and %HH escapes.
_URI_REFERENCE = re.compile(r"^(?:[A-Za-z0-9\-._~:/?#\[\]@!$&'()*+,;=]|%[0-9A-Fa-f]{2})*$")


def sarif(results) -> dict:
    stream = io.StringIO()
    render("sarif", results, stream)
    return json.loads(stream.getvalue())


def finding(file: str, line: int | None = 3, via=()) -> Finding:
    return Finding("U204", "inverted-limits", Severity.ERROR, "swap them",
                   Location(file, line, tuple(via)))


def github_problems(log: dict) -> list[str]:
    """What the validator's GH rules would report (GH1001, GH1003, GH1005, GH1007, GH1011,
    GH1013-GH1018, GH2012)."""
    problems = []
    if log.get("version") != "2.1.0" or "sarif-2.1.0" not in log.get("$schema", ""):
        problems.append("GH1011/GH1013: version and final $schema")
    for run in log["runs"]:
        driver = run["tool"]["driver"]
        if not driver.get("name") or not (driver.get("version") or driver.get("semanticVersion")):
            problems.append("GH1018: tool name and version")
        bases = run.get("originalUriBaseIds", {})
        for rule in driver.get("rules", []):
            for key in ("shortDescription", "fullDescription"):
                if not rule.get(key, {}).get("text", "").strip():
                    problems.append(f"GH2012: {rule['id']} {key}")
            if not rule.get("help", {}).get("text", "").strip() or not rule.get("helpUri"):
                problems.append(f"GH2012: {rule['id']} help")
        for result in run["results"]:
            if not result.get("message", {}).get("text") or "{0}" in result["message"]["text"]:
                problems.append("GH1007/GH1015: flattened message")
            if not result.get("ruleId"):
                problems.append("GH1015: ruleId")
            locations = result.get("locations", [])
            if not locations:
                problems.append("GH1001: no location")
            for location in [*locations, *result.get("relatedLocations", [])]:
                physical = location.get("physicalLocation", {})
                artifact = physical.get("artifactLocation", {})
                uri = artifact.get("uri")
                if not uri or not _URI_REFERENCE.match(uri):
                    problems.append(f"GH1017/SARIF1002: not a URI reference: {uri!r}")
                elif ":" in uri.split("/")[0] and not uri.startswith("file:"):
                    problems.append(f"GH1005: not a relative or file URI: {uri}")
                if "uriBaseId" in artifact and artifact["uriBaseId"] not in bases:
                    problems.append(f"GH1006/SARIF1004: undefined uriBaseId {artifact['uriBaseId']}")
                if not isinstance(physical.get("region", {}).get("startLine"), int):
                    problems.append("GH1003: region.startLine")
    return problems


HARD_NAMES = ["robots/my robot,v2:final 100%.urdf", "a.urdf", "m\udce9.xacro"]


def test_uris_are_percent_encoded_relative_references_under_srcroot():
    results = [FileResult(name, [finding(name, via=[Location("a.urdf", 9)])])
               for name in HARD_NAMES]
    log = sarif(results)
    sarif_schema.validate(log)
    assert github_problems(log) == []
    uris = [r["locations"][0]["physicalLocation"]["artifactLocation"]
            for r in log["runs"][0]["results"]]
    assert uris[0] == {"uri": "robots/my%20robot%2Cv2%3Afinal%20100%25.urdf",
                       "uriBaseId": "%SRCROOT%"}
    assert uris[2]["uri"] == "m%E9.xacro"  # the file name's own byte
    base = log["runs"][0]["originalUriBaseIds"]["%SRCROOT%"]["uri"]
    assert base.startswith("file:///") and base.endswith("/")


def test_absolute_paths_are_file_uris_and_stdin_is_named(tmp_path):
    outside = str(tmp_path / "x y.urdf")
    log = sarif([FileResult(outside, [finding(outside)]),
                 FileResult("-", [finding("<stdin>", line=None)])])
    assert github_problems(log) == []
    first, second = (r["locations"][0]["physicalLocation"] for r in log["runs"][0]["results"])
    assert first["artifactLocation"] == {"uri": (tmp_path / "x y.urdf").as_uri()}
    assert "%20" in first["artifactLocation"]["uri"]
    assert second == {"artifactLocation": {"uri": "stdin"}, "region": {"startLine": 1}}


def test_every_rule_has_a_help_uri_to_its_page_and_descriptions():
    log = sarif([])
    rules = log["runs"][0]["tool"]["driver"]["rules"]
    assert len(rules) == len(CATALOGUE)
    for rule in rules:
        assert_rule_page(rule["helpUri"], rule["id"])
    assert page_of(log["runs"][0]["tool"]["driver"]["informationUri"]).is_file()
    assert github_problems(log) == []


def test_the_github_checks_can_fail():
    log = sarif([FileResult("a.urdf", [finding("a.urdf")])])
    log["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["artifactLocation"] = {
        "uri": "a b.urdf", "uriBaseId": "%NOPE%"}
    log["runs"][0]["tool"]["driver"]["rules"][0].pop("helpUri")
    problems = github_problems(log)
    assert any(p.startswith("GH1017") for p in problems)
    assert any(p.startswith("GH2012") for p in problems)


@pytest.mark.parametrize("column", [None, 5])
def test_regions_carry_the_column_when_known(column):
    log = sarif([FileResult("a.urdf", [Finding("U204", "inverted-limits", Severity.ERROR, "m",
                                               Location("a.urdf", 3, column=column))])])
    region = log["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["region"]
    assert region == ({"startLine": 3} if column is None else {"startLine": 3, "startColumn": 5})


@pytest.mark.parametrize("name", ["[click](0)", "[x](https://example.com/a)", "{0}", "}{1}{",
                                  "\\[x\\](0)", "a\\", "[[{{}}]]"])
def test_a_message_quoting_sarif_syntax_is_text_to_a_viewer_not_a_link_or_placeholder(name):
    message = f"link '{name}' has no parent joint"
    found = Finding("U108", "two-roots", Severity.ERROR, message,
                    Location("a.urdf", 3, (Location("m.xacro", 2),)))
    log = sarif([FileResult("a.urdf", [found])])
    result = log["runs"][0]["results"][0]
    text = result["message"]["text"]
    assert sarif_schema.as_a_viewer_reads(text) == (message, [])
    assert result["relatedLocations"][0]["message"]["text"] == "expanded from this macro call"
