"""``--format rdjson``: reviewdog's Diagnostic Format (``reviewdog -f=rdjson``), which posts the
findings as review comments; the macro call sites are its ``related_locations``.

https://github.com/reviewdog/reviewdog/tree/master/proto/rdf
"""

from __future__ import annotations

from urdftool.report.json_output import write_json
from urdftool.report.summary import all_findings

_SEVERITIES = {"error": "ERROR", "warning": "WARNING", "info": "INFO"}


def _location(location) -> dict:
    where: dict = {"path": location.file}
    if location.line is not None:
        start = {"line": location.line}
        if location.column is not None:
            start["column"] = location.column
        where["range"] = {"start": start}
    return where


def as_dict(results) -> dict:
    from urdftool.report.sarif_format import help_uri

    diagnostics = []
    for finding in all_findings(results):
        entry = {"message": finding.message, "location": _location(finding.location),
                 "severity": _SEVERITIES[finding.severity.value],
                 "code": {"value": finding.code, "url": help_uri(finding.code)}}
        if finding.target is not None:  # rdjson has no free properties: the source names it
            entry["source"] = {"name": f"urdftool --target {finding.target}",
                               "url": help_uri(finding.code)}
        if finding.location.via:
            entry["related_locations"] = [
                {"message": "expanded from this macro call", "location": _location(site)}
                for site in finding.location.via]
        diagnostics.append(entry)
    return {"source": {"name": "urdftool", "url": help_uri(None)}, "diagnostics": diagnostics}


def render(results, stream) -> None:
    write_json(as_dict(results), stream)
