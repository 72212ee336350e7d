"""``--format sarif``: SARIF 2.1.0 for code scanning; each result links to its rule's help.

Artifact locations are URI references (SARIF 3.10): a path below the working folder is a
relative reference, percent-encoded, resolved against ``%SRCROOT%`` (the working folder, given
in ``originalUriBaseIds``), which is what GitHub code scanning maps to the checkout; any other
path is an absolute ``file://`` URI. Standard input, which has no path, is ``stdin`` under no
base. Validated in the tests against the OASIS schema and the GitHub rules of Microsoft's SARIF
validator (GH1001-GH1018, GH2012).
"""

from __future__ import annotations

import os
from pathlib import Path
from urllib.parse import quote

from urdftool import __version__
from urdftool.report.escape import sarif_text
from urdftool.report.json_output import write_json
from urdftool.report.summary import all_findings

SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"
_LEVELS = {"error": "error", "warning": "warning", "info": "note"}
SRCROOT = "%SRCROOT%"


def artifact_location(file: str) -> dict:
    """``{"uri": ..., "uriBaseId": ...}`` for a path as the reports show it."""
    if file.startswith("<"):  # <stdin>
        return {"uri": "stdin"}
    if os.path.isabs(file):
        return {"uri": Path(file).as_uri()}
    # a name that is not UTF-8 (a lone surrogate here) is percent-encoded as its bytes
    return {"uri": quote(Path(file).as_posix(), safe="/", errors="surrogateescape"),
            "uriBaseId": SRCROOT}


def _rule_descriptor(rule) -> dict:
    from urdftool.origin import rule_url

    descriptor = {
        "id": rule.code,
        "name": rule.name,
        "shortDescription": {"text": rule.summary},
        "fullDescription": {"text": rule.doc or rule.summary},
        "help": {"text": rule.doc or rule.summary, "markdown": rule.doc or rule.summary},
        "defaultConfiguration": {"level": _LEVELS[rule.severity.value]},
        "properties": {"family": rule.family},
    }
    if (url := rule_url(rule.code)) is not None:  # the rule's page (urdftool.origin)
        descriptor["helpUri"] = url
    return descriptor


def _location(location) -> dict:
    physical = {"artifactLocation": artifact_location(location.file)}
    region = {"startLine": location.line or 1}  # a finding about a whole file: its first line
    if location.column is not None:
        region["startColumn"] = location.column
    physical["region"] = region
    return {"physicalLocation": physical}


def as_dict(results) -> dict:
    from urdftool.lint.rules import CATALOGUE  # the rule families load only for sarif
    from urdftool.origin import docs_index_url

    rules = CATALOGUE.rules
    index = {rule.code: i for i, rule in enumerate(rules)}
    sarif_results = []
    for finding in all_findings(results):
        entry = {
            "ruleId": finding.code,
            "ruleIndex": index[finding.code],
            "level": _LEVELS[finding.severity.value],
            "message": {"text": sarif_text(finding.message)},
            "locations": [_location(finding.location)],
        }
        if finding.target is not None:  # the simulator a portability finding is about
            entry["properties"] = {"target": finding.target}
        if finding.location.via:
            entry["relatedLocations"] = [
                {"id": i, **_location(site), "message": {"text": "expanded from this macro call"}}
                for i, site in enumerate(finding.location.via)
            ]
        sarif_results.append(entry)
    driver = {"name": "urdftool", "version": __version__, "semanticVersion": __version__,
              "rules": [_rule_descriptor(rule) for rule in rules]}
    if (home := docs_index_url()) is not None:
        driver["informationUri"] = home
    return {
        "$schema": SCHEMA,
        "version": "2.1.0",
        "runs": [{
            "tool": {"driver": driver},
            "originalUriBaseIds": {SRCROOT: {"uri": Path.cwd().as_uri().rstrip("/") + "/"}},
            "results": sarif_results,
            "columnKind": "unicodeCodePoints",
        }],
    }


def render(results, stream) -> None:
    write_json(as_dict(results), stream)
