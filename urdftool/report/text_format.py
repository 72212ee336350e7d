"""``--format text``: findings grouped by file, with the macro call chain and a summary."""

from __future__ import annotations

from rich.console import Console
from rich.markup import escape

from ..diagnostics import display_path
from . import Summary

_STYLES = {"error": "bold red", "warning": "yellow", "info": "cyan"}


def render(results, stream, console: Console | None = None) -> None:
    # emoji=False: messages are printed as written (":bee:" stays text), and rich's 28 ms
    # emoji table is never imported
    console = console or Console(file=stream, highlight=False, soft_wrap=True, emoji=False)
    for result in results:
        if not result.findings:
            continue
        console.print(f"[bold underline]{escape(display_path(result.path))}[/]")
        for finding in result.findings:
            style = _STYLES[finding.severity.value]
            console.print(
                f"  {escape(str(finding.location))}: [{style}]{finding.severity.value}[/] "
                f"[bold]{finding.code}[/] {escape(finding.message)} [dim]({finding.name})[/]")
            for site in finding.location.via:
                console.print(f"      [dim]expanded from macro call at {escape(str(site))}[/]")
        console.print()
    summary = Summary.of(results)
    style = "bold red" if summary.errors else ("yellow" if summary.warnings else "bold green")
    verdict = "no problems found" if not (summary.errors or summary.warnings or summary.infos) \
        else ", ".join([_count(summary.errors, "error"), _count(summary.warnings, "warning"),
                        _count(summary.infos, "note")])
    console.print(f"[{style}]{_count(summary.files, 'file')} checked: {verdict}[/]")


def _count(number: int, noun: str) -> str:
    return f"{number} {noun}" if number == 1 else f"{number} {noun}s"
