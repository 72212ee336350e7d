"""``urdftool dh``: the Denavit-Hartenberg table of a serial chain in a URDF."""

from __future__ import annotations

import typer

from urdftool.cli._common import (PackageOption, XacroArgOption, budgeted, fail_at, fixed, single_robot,
                      wide_console)

FORMATS = ("text", "json", "yaml")


def register(app: typer.Typer) -> None:
    app.command("dh", help="Extract the D-H table of the chain from --base to --tip.")(budgeted(dh))


def dh(
    words: list[str] = typer.Argument(..., metavar="FILE [NAME:=VALUE...]"),
    base: str = typer.Option(..., "--base", metavar="LINK", help="First link of the chain."),
    tip: str = typer.Option(..., "--tip", metavar="LINK", help="Last link of the chain."),
    convention: str = typer.Option("standard", "--convention",
                                   help="standard, or modified (Craig)."),
    output_format: str = typer.Option("text", "--format", "-f", help="text, json or yaml."),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
) -> None:
    from urdftool.kinematics.dh import CONVENTIONS, DHError, extract

    robot = single_robot(
        "dh", words, arg, package,
        {"--format": (output_format, FORMATS), "--convention": (convention, CONVENTIONS)})
    try:
        table = extract(robot, base, tip, convention)
    except DHError as error:
        fail_at(robot, error)
    if output_format == "json":
        import json

        typer.echo(json.dumps(table.as_dict(), indent=2))
    elif output_format == "yaml":
        import yaml

        typer.echo(yaml.safe_dump(table.as_dict(), sort_keys=False), nl=False)
    else:
        _text(table)


def _text(table) -> None:
    from rich.markup import escape
    from rich.table import Table

    from urdftool.kinematics.fk import pose_components

    console = wide_console()
    modified = table.convention == "modified"
    grid = Table(title=f"D-H parameters ({table.convention}), {table.base_link} -> "
                       f"{table.tip_link}", title_justify="left")
    for column in ("joint", "type", "theta [rad]", "d [m]",
                   "a(i-1) [m]" if modified else "a [m]",
                   "alpha(i-1) [rad]" if modified else "alpha [rad]"):
        grid.add_column(escape(column), justify="left" if column in ("joint", "type") else "right")
    for joint in table.joints:
        grid.add_row(joint.joint, joint.type,
                     *(fixed(v) for v in (joint.theta, joint.d, joint.a, joint.alpha)))
    console.print(grid)
    for name, matrix in (("base", table.base), ("tool", table.tool)):
        position, rpy, _ = pose_components(matrix)
        console.print(f"{name}: xyz {_triple(position)}  rpy {_triple(rpy)}")
    console.print(f"base * D-H chain * tool reproduces the URDF chain to {table.residual:.1g}")


def _triple(values) -> str:
    return " ".join(fixed(v) for v in values)
