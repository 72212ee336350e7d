"""``urdftool inertia``: declared inertials beside those computed from geometry."""

from __future__ import annotations

import json
from pathlib import Path

import typer

from urdftool.cli._common import (PackageOption, XacroArgOption, budgeted, fail_usage,
                      refuse_bad_outputs, single_robot, write_output)
from urdftool.errors import UsageError


FORMATS = ("text", "json")


def register(app: typer.Typer) -> None:
    app.command("inertia", help="Compare each link's inertial with its geometry's; fix them.")(
        budgeted(inertia))


def inertia(
    words: list[str] = typer.Argument(..., metavar="ROBOT [NAME:=VALUE...]"),
    density: float = typer.Option(None, "--density", metavar="KG_PER_M3",
                                  help="Compute masses from this density instead of keeping "
                                       "the declared ones."),
    keep_mass: bool = typer.Option(True, "--keep-mass/--no-keep-mass",
                                   help="Keep declared masses (default; --density overrides; "
                                        "--no-keep-mass alone uses 1000 kg/m^3)."),
    link: list[str] = typer.Option([], "--link", help="Only this link (repeatable)."),
    all_links: bool = typer.Option(False, "--all", help="With --write: correct every link."),
    write: Path = typer.Option(None, "--write", metavar="OUT",
                               help="Write a URDF with corrected <inertial> blocks for the "
                                    "--link selection or --all (xacro input: print them)."),
    output_format: str = typer.Option("text", "--format", "-f", help="text or json."),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
) -> None:
    from urdftool.physics.inertia_compare import compare, corrected_urdf, inertial_xml

    refuse_bad_outputs(write)
    robot = single_robot("inertia", words, arg, package, {"--format": (output_format, FORMATS)}, [
        (density is not None and density <= 0, "--density must be positive"),
        (write is not None and not (link or all_links),
         "--write needs --link NAME (repeatable) or --all")])
    unknown = [name for name in link if name not in robot.links]
    if unknown:
        from urdftool.errors import available

        fail_usage(UsageError(f"link '{unknown[0]}' does not exist; "
                              f"{available('links', unknown[0], robot.links)}"))
    if not keep_mass and density is None:
        density = 1000.0  # --no-keep-mass without --density: water, as the help says
    results = compare(robot, density=density, links=link or None)
    if write is not None:
        chosen = [r for r in results if r.computed is not None]
        if robot.from_xacro:
            for result in chosen:
                where = robot.locate(result.element) if result.element is not None else \
                    robot.locate(robot.links[result.link])
                what = "replaces the <inertial> at" if result.element is not None else \
                    "goes into the link at"
                via = "".join(f", expanded from the macro call at {site}" for site in where.via)
                typer.echo(f"<!-- link '{result.link}': {what} {where}{via} -->")
                typer.echo(inertial_xml(result.computed))
        else:
            write_output(write, corrected_urdf(robot, chosen))
            typer.echo(f"wrote {write} ({len(chosen)} inertials corrected)", err=True)
    elif output_format == "json":
        typer.echo(json.dumps({"links": [r.as_dict() for r in results]}, indent=2))
    else:
        typer.echo(_text(results), nl=False)
    raise typer.Exit(1 if any(r.verdict == "invalid" for r in results) else 0)


def _fmt(properties) -> tuple[str, str, str]:
    if properties is None:
        return "-", "-", "-"
    i = properties.inertia
    return (f"{properties.mass:.4g}", " ".join(f"{v:.4g}" for v in properties.com),
            " ".join(f"{v:.4g}" for v in (i[0, 0], i[1, 1], i[2, 2], i[0, 1], i[0, 2], i[1, 2])))


def _text(results) -> str:
    lines = []
    for result in results:
        if result.declared is None and result.computed is None and not result.notes:
            lines.append(f"{result.link}: {result.verdict} (a frame: no inertial, no geometry)")
            continue
        lines.append(f"{result.link}: {result.verdict} (computed from {result.source} geometry)"
                     if result.source != "none" else f"{result.link}: {result.verdict} "
                                                     "(no geometry)")
        for label, properties in (("declared", result.declared), ("computed", result.computed)):
            mass, com, tensor = _fmt(properties)
            lines.append(f"  {label:9s} mass {mass:>9s} kg  com {com:28s}  "
                         f"ixx iyy izz ixy ixz iyz {tensor}")
        if result.differences:
            diff = ", ".join(f"{k} {v:.1%}" for k, v in result.differences.items())
            lines.append(f"  difference {diff}")
        lines.extend(f"  note: {note}" for note in result.notes)
    counts = {v: sum(r.verdict == v for r in results) for v in ("agrees", "differs", "invalid",
                                                                "unknown")}
    plural = "" if len(results) == 1 else "s"
    lines.append(", ".join(f"{n} {v}" for v, n in counts.items() if n) +
                 f" ({len(results)} link{plural})")
    return "\n".join(lines) + "\n"
