"""What every report format shares: the counts, the severity styles, the macro call sites."""

from __future__ import annotations

from itertools import groupby

from urdftool.diagnostics import Finding, Severity
from urdftool.records import Frozen

STYLES = {"error": "bold red", "warning": "yellow", "info": "cyan"}  # rich style per severity


class Summary(Frozen):
    """How many files were checked, and their findings by severity: how many, and on how many
    lines of the files (:func:`lines_of`: what a person changes, a macro line that several
    calls or robots expand once)."""

    files: int
    errors: int
    warnings: int
    infos: int
    error_lines: int
    warning_lines: int
    info_lines: int

    __slots__ = ("files", "errors", "warnings", "infos", "error_lines", "warning_lines",
                 "info_lines")

    def __init__(self, files: int, errors: int, warnings: int, infos: int,
                 error_lines: int | None = None, warning_lines: int | None = None,
                 info_lines: int | None = None) -> None:
        set_field = object.__setattr__
        set_field(self, "files", files)
        set_field(self, "errors", errors)
        set_field(self, "warnings", warnings)
        set_field(self, "infos", infos)
        set_field(self, "error_lines", errors if error_lines is None else error_lines)
        set_field(self, "warning_lines", warnings if warning_lines is None else warning_lines)
        set_field(self, "info_lines", infos if info_lines is None else info_lines)

    @classmethod
    def of(cls, results) -> "Summary":
        by_level: dict[Severity, list[Finding]] = {level: [] for level in Severity}
        for finding in all_findings(results):
            by_level[finding.severity].append(finding)
        errors, warnings, infos = (by_level[level] for level in
                                   (Severity.ERROR, Severity.WARNING, Severity.INFO))
        return cls(len(results), len(errors), len(warnings), len(infos), lines_of(errors),
                   lines_of(warnings), lines_of(infos))

    def counts(self) -> list[str]:
        """The findings by severity as every format's summary says them (:func:`tallies`):
        ``5 errors on 5 lines, 299 warnings on 64 lines, 3 notes on 1 line``."""
        return tallies([(self.errors, self.error_lines, "error"),
                        (self.warnings, self.warning_lines, "warning"),
                        (self.infos, self.info_lines, "note")])


def lines_of(findings) -> int:
    """On how many lines of the files ``findings`` are: what a person reading them changes.
    A line of a macro expanded by several calls, or in several robots checked, counts once;
    so does a companion file's line read with several robots; a finding about a whole file
    (no line) is its file's one place."""
    return len({(finding.location.file, finding.location.line) for finding in findings})


def tallies(counts: list[tuple[int, int, str]]) -> list[str]:
    """Findings by severity, each ``(how many, on how many lines, noun)``, as a summary says
    them: each with its lines (``299 warnings on 64 lines``) when some are fewer lines than
    findings (the text report folds those: ``[24 times ...]``, and says a macro line in each
    robot's report), so that the count of each says what there is to change; else the counts
    alone (``1 error, 0 warnings``)."""
    folded = any(lines < count for count, lines, _ in counts)
    return [f"{counted(count, noun)} on {counted(lines, 'line')}" if folded and count
            else counted(count, noun) for count, lines, noun in counts]


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


