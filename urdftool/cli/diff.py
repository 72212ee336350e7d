"""``urdftool diff``: what changed between two robot descriptions, and what it does."""

from __future__ import annotations

from pathlib import Path

import typer

from urdftool.cli._common import (MaxSceneTrianglesOption, PackageOption, XacroArgOption,
                                  budgeted, fail_at, fail_over_limit, fail_usage,
                                  load_robot, refuse_bad_outputs, robot_inputs, warn,
                                  write_output)
from urdftool.errors import UsageError

HELP = ("Compare two robot descriptions (OLD NEW, or --rev REV FILE: FILE as it was at git "
        "revision REV, includes from the same revision): links and joints added, removed or "
        "renamed, changed joints, inertials, geometry and materials; then the effect: how far "
        "every frame moves at zero and over sampled configurations, mass and centre of mass, "
        "reach of --chain, pairs that newly collide or no longer do; the SRDF's groups and "
        "disabled pairs and the controller YAML beside each. Exit 0 equivalent, 1 "
        "different, 2 when a file beside them could not be read or parsed on a side (not "
        "compared, said which) or a usage error. Formatting, comments and attribute order are "
        "no change.")
FORMATS = ("text", "json", "markdown")


def register(app: typer.Typer) -> None:
    app.command("diff", help=HELP)(budgeted(diff))


def diff(
    words: list[str] = typer.Argument(..., metavar="OLD NEW | FILE [NAME:=VALUE...]"),
    rev: str = typer.Option(None, "--rev", metavar="REV",
                            help="Compare FILE at git revision REV (old) with FILE now (new)."),
    tolerance: float = typer.Option(1e-9, "--tolerance", min=0.0,
                                    help="Numbers closer than this are equal (m, rad, kg, ...)."),
    samples: int = typer.Option(200, "--samples", min=0,
                                help="Configurations drawn within the common limits."),
    seed: int = typer.Option(0, "--seed", help="Seed of the sampled configurations."),
    chain: list[str] = typer.Option([], "--chain", metavar="BASE:TIP",
                                    help="Compare the reach of this chain (repeatable)."),
    no_collisions: bool = typer.Option(False, "--no-collisions",
                                       help="Do not compare self-collisions."),
    no_companions: bool = typer.Option(False, "--no-companions",
                                       help="Do not compare the SRDF and controller YAML "
                                            "found beside each side (as check finds them)."),
    render: Path = typer.Option(None, "--render", metavar="FILE.png|svg",
                                help="Draw old and new overlaid in two colours where they "
                                     "differ most."),
    max_scene_triangles: int = MaxSceneTrianglesOption,
    output_format: str = typer.Option("text", "--format", "-f", help="text, json or markdown."),
    output: Path = typer.Option(None, "--output", "-o", help="Write the report here."),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
) -> None:
    from urdftool.compare.diff import DiffOptions, chain_ends

    refuse_bad_outputs(output, render, inputs=words)
    try:
        paths, args, packages = robot_inputs(words, arg, package)
        if len(paths) != (1 if rev else 2):
            raise UsageError("diff takes OLD NEW, or --rev REV FILE")
        if "-" in paths:
            raise UsageError("diff reads files, not standard input")
        if output_format not in FORMATS:
            raise UsageError(f"--format must be one of {', '.join(FORMATS)}, not "
                             f"'{output_format}'")
        if render is not None and render.suffix.lower() not in (".png", ".svg"):
            raise UsageError(f"--render: '{render.name}' must end in .png or .svg")
        for text in chain:
            chain_ends(text, ())  # BASE:TIP before anything is loaded; split when it is
    except UsageError as error:
        fail_usage(error)
    options = DiffOptions(tolerance, samples, seed, (), not no_collisions, not no_companions)
    if rev:
        from urdftool.description.revision import checkout

        try:
            with checkout(paths[0], rev) as (tree, old_path):
                old = load_robot(str(old_path), args, _packages_at(packages, paths[0], tree))
                old.display = f"{rev}:{old_path.relative_to(tree).as_posix()}"
                new = load_robot(paths[0], args, packages)
                code = _compare(old, new, options, chain, output_format, output,
                                (render, max_scene_triangles or None))
        except UsageError as error:
            fail_usage(error)
    else:
        old = load_robot(paths[0], args, packages)
        new = load_robot(paths[1], args, packages)
        code = _compare(old, new, options, chain, output_format, output,
                        (render, max_scene_triangles or None))
    raise typer.Exit(code)


def _packages_at(packages: dict, path: str, tree: Path) -> dict:
    """``--package`` folders inside the repository, moved to the same place in ``tree``."""
    from urdftool.description.files import real_path
    from urdftool.description.revision import repository_of

    root = Path(real_path(repository_of(path)[0]))
    moved = {}
    for name, folder in packages.items():
        try:
            moved[name] = tree / Path(real_path(folder)).relative_to(root)
        except ValueError:
            moved[name] = folder  # outside the repository: as it is now
    return moved


def _compare(old, new, options, chains, output_format, output, drawing) -> int:
    """``chains``: the ``--chain`` values as written (``BASE:TIP``), split among ``new``'s
    links here (a link name may hold ':')."""
    import io
    from dataclasses import replace

    from urdftool.compare.diff import chain_ends, diff as compare
    from urdftool.errors import FKError, UnknownName
    from urdftool.report.diff import write

    try:
        options = replace(options, chains=tuple(chain_ends(text, new.links) for text in chains))
        result = compare(old, new, options)
    except UsageError as error:
        fail_usage(error)
    except UnknownName as error:
        fail_at(new, error, "--chain")
    except FKError as error:
        fail_at(new, error)
    warn(result.warnings + (result.effects.warnings if result.effects is not None else []))
    if output is None:
        write(result, output_format)
    else:
        buffer = io.StringIO()
        write(result, output_format, buffer)
        write_output(output, buffer.getvalue())
    if drawing[0] is not None:
        _render(old, new, result, *drawing)
    return 2 if result.not_compared else 0 if result.equivalent else 1


def _render(old, new, result, path, max_triangles) -> None:
    """Old and new tinted, at the configuration where they differ most; a side yourdfpy
    cannot read exits 1, located in that side's file, a side over ``max_triangles`` exits 2."""
    from urdftool.errors import OverLimit, SceneError
    from urdftool.kinematics.scene import refuse_over, scene_model
    from urdftool.report.diff import change_detail
    from urdftool.report.picture import NEW, OLD, Layer, PictureOptions, write

    worst, old_q = ((result.effects.worst, result.effects.worst_old)
                    if result.effects is not None else ({}, {}))
    scenes = []
    for robot, q in ((old, old_q), (new, worst)):
        try:
            refuse_over(robot, False, max_triangles)  # both, before either is built
        except OverLimit as error:
            fail_over_limit(error, "--max-scene-triangles")
    for robot, q in ((old, old_q), (new, worst)):
        try:
            scenes.append(scene_model(robot).pose(q, max_triangles))
        except SceneError as error:
            fail_at(robot, error)
        except OverLimit as error:
            fail_over_limit(error, "--max-scene-triangles")
    warn(scenes[0].problems + scenes[1].problems)
    warn(write(path, [Layer(scenes[0], tint=OLD, label=f"old: {result.old}"),
                      Layer(scenes[1], tint=NEW, label=f"new: {result.new}")],
               PictureOptions(detail=change_detail(result))))
