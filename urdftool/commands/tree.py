"""``urdftool tree``: the kinematic tree, printed the way check_urdf prints it."""

from __future__ import annotations

import typer

from ._common import PackageOption, XacroArgOption, fail_usage, load_one, robot_inputs
from ..errors import UsageError


def register(app: typer.Typer) -> None:
    app.command("tree", help="Print the kinematic tree in check_urdf's format.")(tree)


def tree(
    words: list[str] = typer.Argument(..., metavar="FILE [NAME:=VALUE...]"),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
) -> None:
    from ..kinematics.tree import TreeError, format_tree

    try:
        paths, args, packages = robot_inputs(words, arg, package)
        if len(paths) != 1:
            raise UsageError("tree takes exactly one FILE")
    except UsageError as error:
        fail_usage(error)
    robot = load_one(paths[0], args, packages)
    try:
        typer.echo(format_tree(robot), nl=False)
    except TreeError as error:
        typer.echo(f"{robot.locate(error.element)}: error: {error}", err=True)
        raise typer.Exit(1)
