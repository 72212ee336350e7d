"""``urdftool dh``: the Denavit-Hartenberg table of a serial chain in a URDF."""

from __future__ import annotations

import typer

from urdftool.errors import UnknownName

from urdftool.cli._common import PackageOption, XacroArgOption, budgeted, fail_at, single_robot

FORMATS = ("text", "json", "yaml")


def register(app: typer.Typer) -> None:
    app.command("dh", help="Extract the D-H table of the chain from --base to --tip.")(budgeted(dh))


def dh(
    words: list[str] = typer.Argument(..., metavar="FILE [NAME:=VALUE...]"),
    base: str = typer.Option(None, "--base", metavar="LINK",
                             help="First link of the chain (default: the root)."),
    tip: str = typer.Option(..., "--tip", metavar="LINK", help="Last link of the chain."),
    convention: str = typer.Option("standard", "--convention",
                                   help="standard, or modified (Craig)."),
    textbook: bool = typer.Option(False, "--textbook", help="Every link length a >= 0, the "
                                  "sign in alpha and theta, as textbook tables write them."),
    output_format: str = typer.Option("text", "--format", "-f", help="text, json or yaml."),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
) -> None:
    from urdftool.errors import TreeError
    from urdftool.kinematics.dh import CONVENTIONS, DHError, extract
    from urdftool.kinematics.tree import root_link
    from urdftool.report.dh import write_table

    robot = single_robot(
        "dh", words, arg, package,
        {"--format": (output_format, FORMATS), "--convention": (convention, CONVENTIONS)})
    try:
        table = extract(robot, base or root_link(robot), tip, convention, textbook=textbook)
    except (DHError, UnknownName, TreeError) as error:
        fail_at(robot, error)
    write_table(table, output_format)
