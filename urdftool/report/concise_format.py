"""``--format concise``: one line per finding, ``file:line:col: CODE message``, the shape editors'
problem matchers and ``grep`` expect (ruff's and flake8's). The column is left out when it is
not known, the line too when the finding is about the whole file."""

from __future__ import annotations

from urdftool.report.escape import text
from urdftool.report.summary import all_findings


def render(results, stream) -> None:
    for finding in all_findings(results):
        place = ":".join(str(part) for part in (finding.file, finding.line, finding.column)
                         if part is not None) if finding.line is not None else finding.file
        stream.write(text(f"{place}: {finding.code} [{finding.severity.value}] "
                          f"{finding.message}") + "\n")
