"""The rule catalogue for a terminal: a table of every rule, and one rule's page."""

from __future__ import annotations

from rich.markup import escape
from rich.table import Table
from rich.text import Text

from urdftool.report.summary import STYLES


def _plain(text: str) -> str:
    """Docstring text for a terminal: reST ````code```` becomes `code`, as in Markdown."""
    return text.replace("``", "`")


def rules_table(rules) -> Table:
    table = Table(title="urdftool rules", title_justify="left")
    table.add_column("code", no_wrap=True)
    table.add_column("name", no_wrap=True)
    table.add_column("severity", no_wrap=True)
    table.add_column("what it finds")
    for rule in rules:
        severity = rule.severity.value
        table.add_row(rule.code, rule.name, Text(severity, style=STYLES[severity]),
                      Text(_plain(rule.summary)))
    return table


def rule_page(rule) -> str:
    """Rich markup: the heading line, then the docstring as written."""
    style = STYLES[rule.severity.value]
    heading = (f"[bold]{rule.code} {escape(rule.name)}[/] [{style}]({rule.severity.value})[/]"
               f" [dim]{escape(rule.family)}[/]")
    return f"{heading}\n\n{escape(_plain(rule.doc or rule.summary))}"


def print_catalogue(rules, stream=None) -> None:
    """The table of ``rules`` on ``stream`` (default: standard output)."""
    from urdftool.report.console import plain_console

    plain_console(stream).print(rules_table(rules))


def print_rule(rule, stream=None) -> None:
    """One rule's page on ``stream`` (default: standard output)."""
    from urdftool.report.console import plain_console

    plain_console(stream).print(rule_page(rule))
