"""``urdftool xacro``: expand xacro to URDF with ROS-free package resolution."""

from __future__ import annotations

from pathlib import Path

import typer

from urdftool.cli._common import (PackageOption, XacroArgOption, budgeted, refuse_bad_outputs,
                      single_robot, write_output)


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
    from urdftool.report.urdf import expanded_urdf

    refuse_bad_outputs(output)
    text = expanded_urdf(single_robot("xacro", words, arg, package, allow_env=False if no_env else None))
    if output:
        write_output(output, text)
    else:
        typer.echo(text, nl=False)
