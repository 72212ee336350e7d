"""``--format json``: the stable machine-readable form (version 1; keys are only ever added)."""

from __future__ import annotations

from urdftool.report.summary import Summary, all_findings, location_dict, write_json


def diagnostic(finding) -> dict:
    """One finding as the json and json-lines formats write it."""
    where = location_dict(finding.location)
    return {"file": where["file"], "line": where["line"], "column": where["column"],
            "code": finding.code, "name": finding.name, "severity": finding.severity.value,
            "message": finding.message, "via": where["via"]}


def as_dict(results) -> dict:
    summary = Summary.of(results)
    return {
        "version": 1,
        "diagnostics": [diagnostic(f) for f in all_findings(results)],
        "summary": {"files": summary.files, "errors": summary.errors,
                    "warnings": summary.warnings, "notes": summary.infos},
    }


def render(results, stream) -> None:
    write_json(as_dict(results), stream)
