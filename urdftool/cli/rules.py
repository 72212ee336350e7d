"""``urdftool rules``: the rule catalogue, and one rule's documentation."""

from __future__ import annotations

import typer

from urdftool.cli._common import fail_usage
from urdftool.errors import UnknownRule


def register(app: typer.Typer) -> None:
    app.command("rules", help="List every rule, or show one rule's documentation "
                              "(CODE or name).")(rules)


def rules(code: str = typer.Argument(None, metavar="[CODE]",
                                     help="A rule code (U204) or name (inverted-limits).")) -> None:
    from urdftool.lint.rules import CATALOGUE
    from urdftool.report.rules import print_catalogue, print_rule

    if code is None:
        print_catalogue(CATALOGUE.rules)
        return
    try:
        found = CATALOGUE.find(code)
    except UnknownRule as error:
        fail_usage(error)
    print_rule(found)
