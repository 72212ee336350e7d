"""``--format sarif``: SARIF 2.1.0 for code scanning; each result links to its rule's help."""

from __future__ import annotations

from urdftool import __version__
from urdftool.report.summary import all_findings, write_json

SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"
_LEVELS = {"error": "error", "warning": "warning", "info": "note"}


def _rule_descriptor(rule) -> dict:
    return {
        "id": rule.code,
        "name": rule.name,
        "shortDescription": {"text": rule.summary},
        "fullDescription": {"text": rule.doc or rule.summary},
        "help": {"text": rule.doc or rule.summary, "markdown": rule.doc or rule.summary},
        "defaultConfiguration": {"level": _LEVELS[rule.severity.value]},
        "properties": {"family": rule.family},
    }


def _location(location) -> dict:
    physical = {"artifactLocation": {"uri": location.file.replace("\\", "/")}}
    if location.line is not None:
        physical["region"] = {"startLine": location.line}
    return {"physicalLocation": physical}


def as_dict(results) -> dict:
    from urdftool.lint.rules import CATALOGUE  # the rule families load only for sarif

    rules = CATALOGUE.rules
    index = {rule.code: i for i, rule in enumerate(rules)}
    sarif_results = []
    for finding in all_findings(results):
        entry = {
            "ruleId": finding.code,
            "ruleIndex": index[finding.code],
            "level": _LEVELS[finding.severity.value],
            "message": {"text": finding.message},
            "locations": [_location(finding.location)],
        }
        if finding.location.via:
            entry["relatedLocations"] = [
                {"id": i, **_location(site), "message": {"text": "expanded from this macro call"}}
                for i, site in enumerate(finding.location.via)
            ]
        sarif_results.append(entry)
    return {
        "$schema": SCHEMA,
        "version": "2.1.0",
        "runs": [{
            "tool": {"driver": {
                "name": "urdftool",
                "version": __version__,
                "informationUri": "https://pypi.org/project/urdftool/",
                "rules": [_rule_descriptor(rule) for rule in rules],
            }},
            "results": sarif_results,
            "columnKind": "unicodeCodePoints",
        }],
    }


def render(results, stream) -> None:
    write_json(as_dict(results), stream)
