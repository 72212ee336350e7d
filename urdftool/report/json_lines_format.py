"""``--format json-lines``: one JSON object per finding and line, as the json format's
``diagnostics`` entries, for tools that stream (``jq -c``, log shippers). Nothing else is
written: a clean run is an empty output."""

from __future__ import annotations

import json

from urdftool.report.json_format import diagnostic
from urdftool.report.summary import all_findings


def render(results, stream) -> None:
    for finding in all_findings(results):
        # ASCII: the data exact, no raw bidi override or C1 control in a terminal or a log
        stream.write(json.dumps(diagnostic(finding)) + "\n")
