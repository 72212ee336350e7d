"""``--format json-lines``: one JSON object per finding and line, as the json format's
``diagnostics`` entries, for tools that stream (``jq -c``, log shippers). Nothing else is
written: a clean run is an empty output."""

from __future__ import annotations

from urdftool.report.json_format import diagnostic
from urdftool.report.json_output import line
from urdftool.report.summary import all_findings


def render(results, stream) -> None:
    for finding in all_findings(results):
        stream.write(line(diagnostic(finding)) + "\n")
