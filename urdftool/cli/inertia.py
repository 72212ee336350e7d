"""``urdftool inertia``: declared inertials beside those computed from geometry."""

from __future__ import annotations

from pathlib import Path

import typer

from urdftool.cli._common import (PackageOption, XacroArgOption, budgeted, fail_at,
                                  only_with, refuse_bad_outputs, say, show, single_robot, write_output)


FORMATS = ("text", "json")


def register(app: typer.Typer) -> None:
    app.command("inertia", help="Compare each link's inertial with its geometry's; fix them.")(
        budgeted(inertia))


def inertia(
    words: list[str] = typer.Argument(..., metavar="FILE [NAME:=VALUE...]"),
    density: float = typer.Option(None, "--density", metavar="KG_PER_M3",
                                  help="Compute masses from this density instead of keeping "
                                       "the declared ones."),
    keep_mass: bool = typer.Option(True, "--keep-mass/--no-keep-mass",
                                   help="Keep declared masses (--density overrides; "
                                        "--no-keep-mass alone uses 1000 kg/m^3)."),
    link: list[str] = typer.Option([], "--link", help="Only this link (repeatable)."),
    all_links: bool = typer.Option(False, "--all", help="With --write: correct every link."),
    write: Path = typer.Option(None, "--write", metavar="FILE",
                               help="Write the URDF with the <inertial> blocks of the --link "
                                    "selection or --all computed from geometry, as edits of "
                                    "the file (formatting kept); xacro input: a unified diff "
                                    "of the xacro files."),
    output_format: str = typer.Option("text", "--format", "-f", help="text or json."),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
) -> None:
    from urdftool.physics.inertia_compare import UnknownLink, compare
    from urdftool.report import inertia as render

    refuse_bad_outputs(write)
    robot = single_robot("inertia", words, arg, package, {"--format": (output_format, FORMATS)}, [
        (density is not None and density <= 0, "--density must be positive"),
        (write is not None and not (link or all_links),
         "--write needs --link NAME (repeatable) or --all"),
        only_with(("all_links",), write is not None, "--write"),
        (write is not None and output_format != "text",
         f"--format {output_format} does not go with --write (it writes the file, no report)")])
    if not keep_mass and density is None:
        density = 1000.0  # --no-keep-mass without --density: water, as the help says
    try:
        results = compare(robot, density=density, links=link or None)
    except UnknownLink as error:
        fail_at(robot, error)
    if write is not None:
        from urdftool.description.files import identity
        from urdftool.lint.fixes import inertia_rewrite
        from urdftool.report.unified import unified

        chosen = [r for r in results if r.computed is not None]
        changes, unwritten = inertia_rewrite(robot, chosen)
        if robot.from_xacro:  # the edits land in the xacro files: written as a patch of them
            write_output(write, unified(changes.changed, changes.spans))
            say(f"wrote {write}: a unified diff of the xacro files ({len(changes.applied)} "
                       "inertials corrected; `urdftool check --fix --unsafe-fixes` applies "
                       "such edits in place)", err=True)
            shown = {link for link, _ in unwritten}
            show(render.xacro_blocks(robot, [r for r in chosen if r.link in shown]),
                       nl=False)
        else:
            data = changes.changed.get(robot.display, (robot.sources[robot.display],) * 2)[1]
            write_output(write, data.decode("utf-8"),  # over the robot itself: meant
                         rewrites=identity(write) == identity(robot.path))
            say(f"wrote {write} ({len(changes.applied)} inertials corrected)", err=True)
        for link, why in unwritten:
            say(f"urdftool: {link}: not written: {why}", err=True)
    elif output_format == "json":
        from urdftool.report.json_output import write_json

        write_json({"links": [r.as_dict() for r in results]})
    else:
        show(render.text(results), nl=False)
    raise typer.Exit(1 if any(r.fails for r in results) else 0)
