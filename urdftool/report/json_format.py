"""``--format json``: the stable machine-readable form (version 1; keys are only ever added)."""

from __future__ import annotations

from urdftool.report.json_output import write_json
from urdftool.report.summary import Summary, all_findings, location_dict


def diagnostic(finding) -> dict:
    """One finding as the json and json-lines formats write it."""
    where = location_dict(finding.location)
    return {"file": where["file"], "line": where["line"], "column": where["column"],
            "code": finding.code, "name": finding.name, "severity": finding.severity.value,
            "message": finding.message, "via": where["via"],
            **({"target": finding.target} if finding.target is not None else {}),
            **({"fix": _fix(finding.fix)} if finding.fix is not None else {})}


def as_dict(results) -> dict:
    summary = Summary.of(results)
    return {
        "version": 1,
        "diagnostics": [diagnostic(f) for f in all_findings(results)],
        "summary": {"files": summary.files, "errors": summary.errors,
                    "warnings": summary.warnings, "notes": summary.infos,
                    "lines": {"errors": summary.error_lines, "warnings": summary.warning_lines,
                              "notes": summary.info_lines}},
    }


def error_document(results=(), message: str | None = None, location=None) -> dict:
    """What an analysis command (fk, dynamics, ... with ``--format json``) writes on standard
    output when it cannot compute, as ruff and mypy write a file they cannot read among their
    JSON diagnostics: :func:`as_dict`'s document (the findings of a robot that does not load,
    as ``check`` gives them) with ``error``, the reason in one line; an error that is no finding
    (``message``: a joint dynamics refuses, a support without geometry) is a diagnostic of its
    own at ``location`` (a Location, or a file name), without a code. Usage errors (exit 2)
    are not documents: as for ruff and mypy, they go to standard error only."""
    document = as_dict(results)
    if message is not None:
        where = location_dict(location) if hasattr(location, "via") else \
            {"file": None if location is None else str(location), "line": None, "column": None,
             "via": []}
        document["diagnostics"].append({"file": where["file"], "line": where["line"],
                                        "column": where["column"], "code": None, "name": None,
                                        "severity": "error", "message": message,
                                        "via": where["via"]})
        document["summary"]["errors"] += 1
        document["summary"]["lines"]["errors"] += 1  # (a place of its own: no finding's)
        document["summary"]["files"] = max(document["summary"]["files"], 1)
    first = document["diagnostics"][0]["message"] if document["diagnostics"] else None
    document["error"] = message or first
    return document


def _fix(fix) -> dict:
    """A fix as data: what it does, whether --fix applies it (safe) or only --unsafe-fixes,
    and its edits (byte offsets; 1-based lines and 0-based columns in characters)."""
    return {"description": fix.description, "safe": fix.safe, "edits": [
        {"file": e.file, "line": e.line, "column": e.column, "end_line": e.end_line,
         "end_column": e.end_column, "start": e.start, "end": e.end, "old": e.old,
         "new": e.text} for e in fix.edits]}


def render(results, stream) -> None:
    write_json(as_dict(results), stream)
