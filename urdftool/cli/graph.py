"""``urdftool graph``: the kinematic tree as a Graphviz picture, coloured by ``check``."""

from __future__ import annotations

from pathlib import Path

import typer

from urdftool.cli._common import (PackageOption, XacroArgOption, budgeted, fail_usage,
                                  refuse_bad_outputs, say, show, single_robot)
from urdftool.errors import UsageError


def register(app: typer.Typer) -> None:
    app.command("graph", help="Draw the kinematic tree as Graphviz DOT: links as boxes (red: "
                              "errors, orange: warnings), joints as edges labelled with type "
                              "and limits. --output x.svg/x.png renders it with Graphviz's "
                              "dot.")(budgeted(graph))


def graph(
    words: list[str] = typer.Argument(..., metavar="FILE [NAME:=VALUE...]"),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
    output: Path = typer.Option(None, "--output", "-o",
                                help="Write to x.dot (or .gv), or render x.svg, x.png, x.pdf; "
                                     "default: DOT on stdout."),
) -> None:
    from urdftool.lint.engine import check_robot
    from urdftool.report.dot import DotMissing, dot_missing_advice, to_dot, write

    refuse_bad_outputs(output, inputs=words)
    robot = single_robot("graph", words, arg, package)
    dot = to_dot(robot, check_robot(robot))
    if output is None:
        show(dot, nl=False)
        return
    try:
        written = write(dot, output)
    except DotMissing as missing:  # (a program the install lacks, as an extra: exit 2)
        say(f"urdftool: {dot_missing_advice(missing, output)}", err=True)
        raise typer.Exit(2)
    except (ValueError, OSError, UsageError) as error:
        fail_usage(UsageError(str(error)))
    say(f"wrote {written}", err=True)
