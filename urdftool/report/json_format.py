"""``--format json``: the stable machine-readable form (version 1)."""

from __future__ import annotations

from urdftool.report.summary import Summary, all_findings, write_json


def as_dict(results) -> dict:
    summary = Summary.of(results)
    return {
        "version": 1,
        "diagnostics": [
            {"file": f.file, "line": f.line, "code": f.code, "name": f.name,
             "severity": f.severity.value, "message": f.message}
            for f in all_findings(results)
        ],
        "summary": {"files": summary.files, "errors": summary.errors,
                    "warnings": summary.warnings},
    }


def render(results, stream) -> None:
    write_json(as_dict(results), stream)
