"""``urdftool xacro``: expand xacro to URDF with ROS-free package resolution."""

from __future__ import annotations

from pathlib import Path

import typer

from ._common import PackageOption, XacroArgOption, budgeted, single_robot


def register(app: typer.Typer) -> None:
    app.command("xacro", help="Expand a xacro file to URDF; $(find) and package:// resolve "
                              "without ROS.")(budgeted(xacro))


def xacro(
    words: list[str] = typer.Argument(..., metavar="FILE [NAME:=VALUE...]"),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
    output: Path = typer.Option(None, "--output", "-o", help="Write the URDF here."),
    no_env: bool = typer.Option(False, "--no-env", help="Make $(env)/$(optenv) errors."),
) -> None:
    from lxml import etree

    robot = single_robot("xacro", words, arg, package, allow_env=not no_env)
    etree.indent(robot.root, space="  ")
    text = etree.tostring(robot.root, encoding="unicode", xml_declaration=False)
    text = f'<?xml version="1.0" ?>\n{text}\n'
    if output:
        output.write_text(text, encoding="utf-8")
    else:
        typer.echo(text, nl=False)
