"""``--format rdjson``: reviewdog's Diagnostic Format (``reviewdog -f=rdjson``), which posts the
findings as review comments; the macro call sites are its ``related_locations``.

A diagnostic's ``message`` is Markdown where reviewdog posts it: its review comments (GitHub,
GitLab, Gitea) write the message as it is after their own prefix
(``commentutil.MarkdownComment``), so it is written by :func:`~urdftool.report.escape.markdown`,
the one escaper of Markdown: a code span, in which a link named ``![x](https://...)`` loads no
image, ``@team`` mentions nobody and ``<img>`` is text.

https://github.com/reviewdog/reviewdog/tree/master/proto/rdf
"""

from __future__ import annotations

from urdftool.report.escape import markdown
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


def _with_url(entry: dict, url: str | None) -> dict:
    return entry if url is None else {**entry, "url": url}


def as_dict(results) -> dict:
    from urdftool.origin import docs_index_url, rule_url

    diagnostics = []
    for finding in all_findings(results):
        url = rule_url(finding.code)  # the rule's page (urdftool.origin); None: no link
        entry = {"message": markdown(finding.message), "location": _location(finding.location),
                 "severity": _SEVERITIES[finding.severity.value],
                 "code": _with_url({"value": finding.code}, url)}
        if finding.target is not None:  # rdjson has no free properties: the source names it
            entry["source"] = _with_url({"name": f"urdftool --target {finding.target}"}, url)
        if finding.location.via:
            entry["related_locations"] = [
                {"message": "expanded from this macro call", "location": _location(site)}
                for site in finding.location.via]
        diagnostics.append(entry)
    return {"source": _with_url({"name": "urdftool"}, docs_index_url()),
            "diagnostics": diagnostics}


def render(results, stream) -> None:
    write_json(as_dict(results), stream)
