"""What every report format shares: the counts, the severity styles, the macro call sites."""

from __future__ import annotations

from itertools import groupby

from urdftool.diagnostics import Finding, Severity
from urdftool.records import Frozen

STYLES = {"error": "bold red", "warning": "yellow", "info": "cyan"}  # rich style per severity


class Summary(Frozen):
    """How many files were checked, and their findings by severity."""

    files: int
    errors: int
    warnings: int
    infos: int

    __slots__ = ("files", "errors", "warnings", "infos")

    def __init__(self, files: int, errors: int, warnings: int, infos: int) -> None:
        set_field = object.__setattr__
        set_field(self, "files", files)
        set_field(self, "errors", errors)
        set_field(self, "warnings", warnings)
        set_field(self, "infos", infos)

    @classmethod
    def of(cls, results) -> "Summary":
        findings = all_findings(results)
        count = lambda level: sum(1 for f in findings if f.severity is level)  # noqa: E731
        return cls(len(results), count(Severity.ERROR), count(Severity.WARNING),
                   count(Severity.INFO))


def via_text(location) -> list[str]:
    """The macro call chain of a location as lines, innermost call first; a call site repeated
    in a row (a macro calling itself, xacro's way of looping: ICube's staubli_macro.xacro:41
    six times over for six links) is one line saying how many calls."""
    lines = []
    for site, run in groupby(str(site) for site in location.via):
        calls = len(list(run))
        lines.append(f"expanded from macro call at {site}" if calls == 1 else
                     f"expanded from {calls} nested calls of a macro calling itself at {site}")
    return lines


def location_dict(location) -> dict:
    """A location as the JSON formats write it: file, line, column (null when unknown) and the
    macro call sites it was expanded from (``via``, innermost first)."""
    return {"file": location.file, "line": location.line, "column": location.column,
            "via": [{"file": site.file, "line": site.line, "column": site.column}
                    for site in location.via]}


def counted(number: int, noun: str) -> str:
    """``1 error``, ``2 errors``."""
    return f"{number} {noun}" if number == 1 else f"{number} {noun}s"


def all_findings(results) -> list[Finding]:
    return [finding for result in results for finding in result.findings]


