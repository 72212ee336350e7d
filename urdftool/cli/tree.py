"""``urdftool tree``: the kinematic tree, printed the way check_urdf prints it."""

from __future__ import annotations

import typer

from urdftool.cli._common import (PackageOption, XacroArgOption, budgeted, fail_at,
                                  refuse_refused, show, single_robot)


def register(app: typer.Typer) -> None:
    app.command("tree", help="Print the kinematic tree in check_urdf's format.")(budgeted(tree))


def tree(
    words: list[str] = typer.Argument(..., metavar="FILE [NAME:=VALUE...]"),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
) -> None:
    from urdftool.kinematics.tree import TreeError
    from urdftool.report.tree import tree_text

    robot = single_robot("tree", words, arg, package)
    if any(note.kind == "xacro-in-urdf" for note in robot.notes):
        robot = single_robot("tree", words, arg, package, as_written=True)  # as check_urdf
    refuse_refused(robot)  # check_urdf prints no tree of such a file
    try:
        show(tree_text(robot), nl=False)
    except TreeError as error:
        fail_at(robot, error)
