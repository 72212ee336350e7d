"""``urdftool xacro``: expand xacro to URDF with ROS-free package resolution; a drop-in for ROS
``xacro`` (its banner, ``-o``, ``--deps``, ``-q``, and ``--inorder``/``--check-order`` as no-ops)."""

from __future__ import annotations

from pathlib import Path

import typer

from urdftool.cli._common import (PackageOption, XacroArgOption, budgeted, document,
                                  refuse_bad_outputs, say, show, single_robot, write_output)


def register(app: typer.Typer) -> None:
    app.command("xacro", help="Expand a xacro file to URDF; $(find) and package:// resolve "
                              "without ROS.")(budgeted(xacro))


def xacro(
    words: list[str] = typer.Argument(..., metavar="FILE [NAME:=VALUE...]"),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
    output: Path = typer.Option(None, "--output", "-o", help="Write the URDF here."),
    no_env: bool = typer.Option(False, "--no-env",
                                help="Never read the environment: $(env) is an error, "
                                     "$(optenv NAME DEFAULT) its default."),
    deps: bool = typer.Option(False, "--deps", help="Print the files it includes, "
                                                    "space-separated, instead of the URDF."),
    quiet: bool = typer.Option(False, "-q", help="Do not print xacro's warnings."),
    inorder: bool = typer.Option(False, "--inorder", "-i", hidden=True,
                                 help="Accepted as ROS xacro does: in-order is the only order."),
    check_order: bool = typer.Option(False, "--check-order", hidden=True,
                                     help="Accepted for ROS 1 scripts; nothing to check."),
) -> None:
    from urdftool.report.escape import xml_document
    from urdftool.report.urdf import dependencies, expanded_urdf

    refuse_bad_outputs(output, inputs=words)
    robot = single_robot("xacro", words, arg, package, allow_env=False if no_env else None)
    if not quiet:
        for note in robot.notes:
            say(f"{note.location}: warning: {note.message}", err=True)
    text = dependencies(robot) if deps else expanded_urdf(robot, robot.path)
    if output:
        write_output(output, text)
    elif deps:
        show(text, nl=False)
    else:  # the XML exact, its lines safe in a terminal or a log
        document(xml_document(text, robot.root), xml=True)
