"""``check --statistics``: how often each rule fired, most first (ruff's ``--statistics``)."""

from __future__ import annotations

from collections import Counter

from urdftool.report.escape import text
from urdftool.report.summary import all_findings


def counts(results) -> list[tuple[int, str, str, str]]:
    """(count, code, name, severity) per rule that fired, most first, then by code."""
    found = Counter((f.code, f.name, f.severity.value) for f in all_findings(results))
    return sorted(((n, *key) for key, n in found.items()), key=lambda row: (-row[0], row[1]))


def render(results, stream) -> None:
    rows = counts(results)
    width = max((len(str(n)) for n, *_ in rows), default=1)
    for number, code, name, severity in rows:
        stream.write(text(f"{number:>{width}}  {code}  {severity:<7}  {name}") + "\n")
