"""``--format text``: findings grouped by file, with the macro call chain and a summary.

The lines are built once as styled spans. On a terminal (or with FORCE_COLOR) rich renders them
in colour; anywhere else (CI logs, pipes, files) they are written as plain text, which is what
rich would write there too, without paying for importing it.
"""

from __future__ import annotations

import os

from urdftool.diagnostics import display_path
from urdftool.report.summary import STYLES, Summary, counted, printable, via_text

Line = list[tuple[str, str]]  # (text, rich style or "")


def lines(results, quiet: bool = False) -> list[Line]:
    """The report as lines of (text, style) spans; names, paths and messages come from the
    files checked, so their control characters are escaped (one finding, one line)."""
    out: list[Line] = []
    for result in results:
        if not result.findings:
            continue
        out.append([(display_path(result.path), "bold underline")])
        for finding in result.findings:
            location, severity = finding.location, finding.severity.value
            out.append([(f"  {location}: ", ""), (severity, STYLES[severity]),
                        (" ", ""), *_marker(finding), (finding.code, "bold"),
                        (f" {finding.message} ", ""),
                        (f"({finding.name}, {finding.target})" if finding.target else
                         f"({finding.name})", "dim")])
            if location.via:  # a macro's: its call sites (10,000 findings may have none)
                out.extend([(f"      {line}", "dim")] for line in via_text(location))
        if not quiet:
            out.append([])
    if quiet:
        return [_printable(line) for line in out]
    summary = Summary.of(results)
    style = "bold red" if summary.errors else ("yellow" if summary.warnings else "bold green")
    verdict = "no problems found" if not (summary.errors or summary.warnings or summary.infos) \
        else ", ".join([counted(summary.errors, "error"), counted(summary.warnings, "warning"),
                        counted(summary.infos, "note")])
    out.append([(f"{counted(summary.files, 'file')} checked: {verdict}", style)])
    fixable = [f.fix.safe for result in results for f in result.findings if f.fix is not None]
    if fixable:
        safe, unsafe = fixable.count(True), fixable.count(False)
        parts = [f"[*] {safe} fixable with --fix"] if safe else []
        parts += [f"[~] {unsafe} more with --unsafe-fixes"] if unsafe else []
        out.append([("; ".join(parts), "")])
    return [_printable(line) for line in out]


def _printable(line: Line) -> Line:
    """The line with each span :func:`printable`; one look at the whole line first (escaping
    is per character, so a line that needs none is kept as it is: 10,000 findings are 60,000
    spans)."""
    whole = "".join([text for text, _ in line])
    if printable(whole) == whole:
        return line
    return [(printable(text), style) for text, style in line]


def _marker(finding) -> Line:
    """``[*]`` before the code of a finding that ``--fix`` removes, ``[~]`` for one only
    ``--unsafe-fixes`` removes (as ruff marks them)."""
    if finding.fix is None:
        return []
    return [("[*] " if finding.fix.safe else "[~] ", "bold cyan")]


def render(results, stream, quiet: bool = False) -> None:
    report = lines(results, quiet)
    if not _colour(stream):
        stream.write("".join("".join(text for text, _ in line) + "\n" for line in report))
        return
    from rich.console import Console
    from rich.text import Text

    # emoji=False, highlight=False, Text spans: messages are printed exactly as written
    console = Console(file=stream, highlight=False, soft_wrap=True, emoji=False)
    for line in report:
        console.print(Text.assemble(*line))


def _colour(stream) -> bool:
    if os.environ.get("NO_COLOR"):
        return False
    if os.environ.get("FORCE_COLOR"):
        return True
    return hasattr(stream, "isatty") and stream.isatty()

