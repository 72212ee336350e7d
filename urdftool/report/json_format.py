"""``--format json``: the stable machine-readable form (version 1)."""

from __future__ import annotations

from urdftool.report.summary import Summary, all_findings, write_json


def as_dict(results) -> dict:
    summary = Summary.of(results)
    return {
        "version": 1,
        "diagnostics": [
            {"file": f.file, "line": f.line, "code": f.code, "name": f.name,
             "severity": f.severity.value, "message": f.message,
             **({"fix": _fix(f.fix)} if f.fix is not None else {})}
            for f in all_findings(results)
        ],
        "summary": {"files": summary.files, "errors": summary.errors,
                    "warnings": summary.warnings},
    }


def _fix(fix) -> dict:
    """A fix as data: what it does, whether --fix applies it (safe) or only --unsafe-fixes,
    and its edits (byte offsets; 1-based lines and 0-based columns in characters)."""
    return {"description": fix.description, "safe": fix.safe, "edits": [
        {"file": e.file, "line": e.line, "column": e.column, "end_line": e.end_line,
         "end_column": e.end_column, "start": e.start, "end": e.end, "old": e.old,
         "new": e.text} for e in fix.edits]}


def render(results, stream) -> None:
    write_json(as_dict(results), stream)
