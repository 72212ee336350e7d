"""``urdftool collisions``: self-collision at a pose, and the MoveIt-style collision matrix."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import typer

from urdftool.errors import UsageError
from urdftool.cli._common import (PackageOption, XacroArgOption, budgeted, fail_at, fail_usage,
                      pairs, refuse_bad_outputs, single_robot)

HELP = ("Self-collision with FCL. Without --matrix: colliding link pairs at one configuration "
        "(default: 0, or mid-range when 0 is outside the limits), exit 1 when a pair collides "
        "that neither adjacency nor the SRDF allows. With --matrix: classify every link pair "
        "as MoveIt's Setup Assistant does (Adjacent, Default, Always, Never) from random "
        "samples, with each pair's collision count, minimum distance and convergence.")


FORMATS = ("text", "json")


def register(app: typer.Typer) -> None:
    app.command("collisions", help=HELP)(budgeted(collisions))


def collisions(
    words: list[str] = typer.Argument(..., metavar="FILE [NAME:=VALUE...]"),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
    q: list[str] = typer.Option([], "--q", metavar="JOINT=VALUE",
                                help="Joint value in rad or m (repeatable); pose mode."),
    deg: bool = typer.Option(False, "--deg", help="--q angles are in degrees."),
    srdf: Path = typer.Option(None, "--srdf", help="SRDF whose disable_collisions allow pairs "
                              "[default: the .srdf beside the robot]."),
    matrix: bool = typer.Option(False, "--matrix", help="Compute the collision matrix."),
    samples: int = typer.Option(10000, "--samples", min=2,
                                help="Random configurations (rounded up to a multiple of 500)."),
    seed: int = typer.Option(0, "--seed", help="Random seed; the same seed gives the same matrix."),
    min_fraction: float = typer.Option(0.95, "--min-fraction", min=0.0, max=1.0,
                                       help="Colliding in at least this fraction: Always."),
    margin: float = typer.Option(0.005, "--margin", min=0.0, metavar="METERS",
                                 help="Pairs that came closer than this are never Never."),
    until_converged: bool = typer.Option(False, "--until-converged",
                                         help="Double the samples until no pair changes class "
                                              "in the second half."),
    max_samples: int = typer.Option(160000, "--max-samples", help="Limit for --until-converged."),
    workers: int = typer.Option(2, "--workers", min=1, help="Worker processes."),
    write_srdf: Path = typer.Option(None, "--write-srdf", metavar="OUT",
                                    help="Write disable_collisions here; an existing SRDF keeps "
                                         "its other content."),
    check_srdf: Path = typer.Option(None, "--check-srdf", metavar="FILE",
                                    help="Report stale disable_collisions in FILE (exit 1)."),
    plot: Path = typer.Option(None, "--plot", metavar="FILE.svg|png", help="Draw the matrix."),
    all_pairs: bool = typer.Option(False, "--all", help="List every pair in text output."),
    format: str = typer.Option("text", "--format", "-f", help="text or json."),
) -> None:
    from urdftool.kinematics.fk import FKError

    refuse_bad_outputs(write_srdf, plot)
    robot = single_robot("collisions", words, arg, package, {"--format": (format, FORMATS)}, [
        (not matrix and (write_srdf or check_srdf or plot or until_converged),
         "--write-srdf, --check-srdf, --plot and --until-converged need --matrix"),
        (matrix and deg, "--deg goes with --q, not with --matrix"),
        (matrix and q, "--q sets the pose of a single check; it does not go with --matrix"),
        *((given is not None and not given.is_file(), f"{name}: '{given}' does not exist")
          for given, name in ((srdf, "--srdf"), (check_srdf, "--check-srdf")))])
    try:
        if matrix:
            code = _matrix(robot, samples, seed, min_fraction, margin, until_converged,
                           max_samples, workers, write_srdf, check_srdf, plot, all_pairs,
                           format)
        else:
            code = _pose(robot, q, deg, srdf, format)
    except UsageError as error:
        fail_usage(error)
    except FKError as error:
        fail_at(robot, error)
    raise typer.Exit(code)


def _scene(robot, margin: float):
    from urdftool.collision.matrix import Scene

    return Scene(robot, margin)


def _srdf_entries(path: Path):
    from urdftool.collision import srdf as srdf_module

    try:
        return srdf_module.read(path)
    except srdf_module.SrdfError as error:
        raise UsageError(str(error)) from None


def _pose(robot, words, degrees, srdf_path, format) -> int:
    from urdftool.collision import pose, srdf
    from urdftool.diagnostics import display_path

    scene = _scene(robot, 0.0)
    configuration = pose.configuration(scene, pairs(words, "--q", strip=True), degrees)
    for warning in configuration.warnings:
        typer.echo(f"urdftool: warning: {warning}", err=True)
    q = configuration.values[0]
    srdf_path = srdf_path or srdf.beside(robot)
    allowed = srdf.allowed_pairs(_srdf_entries(srdf_path)[0]) if srdf_path else {}
    report = pose.check(scene, q, allowed, srdf=display_path(srdf_path) if srdf_path else None)
    if format == "json":
        _json({"robot": robot.name, "q": report.q, "srdf": report.srdf,
               "colliding": [vars(c) for c in report.colliding],
               "closest": [vars(c) for c in report.closest],
               "visual_only": report.visual_only,
               "problems": [{"location": str(p.location), "message": p.message}
                            for p in report.problems]})
    else:
        _pose_text(robot, report, bool(words))
    return 1 if report.forbidden else 0


def _console():
    from rich.console import Console

    return Console(file=sys.stdout, highlight=False, soft_wrap=True)


def _notes(console, geometry_problems, visual_only) -> None:
    from rich.markup import escape

    for problem in geometry_problems:
        console.print(f"{escape(str(problem.location))}: [yellow]warning[/] "
                      f"{escape(problem.message)}")
    if visual_only:
        console.print(f"[yellow]Links with a visual but no collision geometry[/] (they escape "
                      f"every check): {', '.join(visual_only)}")


def _pose_text(robot, report, custom: bool) -> None:
    from rich.table import Table

    console = _console()
    where = "the given configuration" if custom else "the default configuration"
    console.print(f"[bold]{robot.name}[/] at {where} ({len(report.q)} joints), "
                  f"SRDF: {report.srdf or 'none'}")
    touching = [c for c in report.colliding if c.allowed == "Adjacent"]
    listed = [c for c in report.colliding if c.allowed != "Adjacent"]
    if listed:
        table = Table("link 1", "link 2", "depth (mm)", "status", box=None, pad_edge=False)
        for c in listed:
            status = f"allowed ({c.allowed})" if c.allowed else "[bold red]COLLIDING[/]"
            table.add_row(c.link1, c.link2, f"{c.depth * 1000:.2f}", status)
        console.print(table)
    if touching:
        console.print(f"{len(touching)} adjacent pair(s) overlap at their joints (allowed): "
                      + ", ".join(f"{c.link1}/{c.link2}" for c in touching))
    if report.closest:
        console.print("Closest pairs apart:")
        table = Table("link 1", "link 2", "distance (mm)", "status", box=None, pad_edge=False)
        for c in report.closest:
            table.add_row(c.link1, c.link2, f"{c.distance * 1000:.2f}",
                          f"disabled ({c.allowed})" if c.allowed else "")
        console.print(table)
    _notes(console, report.problems, report.visual_only)
    bad = report.forbidden
    if bad:
        console.print(f"[bold red]{len(bad)} colliding pair(s) not allowed by adjacency or the "
                      "SRDF[/]")
    else:
        allowed = len(report.colliding)
        console.print(f"[bold green]no self-collision[/]"
                      + (f" ({allowed} allowed contact(s))" if allowed else ""))


def _matrix(robot, samples, seed, min_fraction, margin, until_converged, max_samples, workers,
            write_srdf, check_srdf, plot, all_pairs, format) -> int:
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, \
        TimeElapsedColumn

    from urdftool.collision import matrix as matrix_module
    from urdftool.collision import srdf

    scene = _scene(robot, margin)
    err = Console(stderr=True)
    progress = Progress(TextColumn("sampling"), BarColumn(), MofNCompleteColumn(),
                        TextColumn("configurations"), TimeElapsedColumn(), console=err,
                        transient=True, disable=not err.is_terminal)
    with progress:
        task = progress.add_task("sampling", total=samples)

        def update(done: int, planned: int) -> None:
            progress.update(task, completed=done, total=planned)

        result = matrix_module.compute(robot, samples, seed, min_fraction, margin,
                                       until_converged, max_samples, workers, update, scene)
    stale = []
    if check_srdf:
        entries, root = _srdf_entries(check_srdf)
        stale = srdf.stale(result, entries, robot.links, root)
    if write_srdf:
        from urdftool.description.files import write_file

        # Merged only into a regular file: a link planted there is replaced, its target unread.
        existing = write_srdf if write_srdf.is_file() and not write_srdf.is_symlink() else None
        if existing:
            _srdf_entries(existing)  # refuse a broken file before overwriting it
        write_file(write_srdf, srdf.render(result, robot.name, existing))
    if plot:
        from urdftool.report import plot as plot_module

        plot_module.write(result, plot, f"{robot.name}: {result.samples} samples, seed {seed}")
    if format == "json":
        _json(_matrix_json(robot, result, stale))
    else:
        _matrix_text(robot, result, stale, all_pairs, write_srdf, plot)
    return 1 if stale else 0


def _matrix_json(robot, result, stale) -> dict:
    return {
        "robot": robot.name, "samples": result.samples, "seed": result.seed,
        "margin": result.margin, "min_fraction": result.min_fraction,
        "converged": result.converged,
        "rounds": [{"samples": n, "changed": c} for n, c in result.rounds],
        "unsettled": [{"link1": a, "link2": b, "first_half": x, "all": y}
                      for a, b, x, y in result.unsettled],
        "pairs": [{"link1": p.link1, "link2": p.link2, "class": p.reason or "enabled",
                   "collisions": p.collisions, "samples": p.samples,
                   "fraction": p.fraction, "min_distance": p.min_distance}
                  for p in result.pairs],
        "visual_only": result.visual_only,
        "problems": [{"location": str(p.location), "message": p.message}
                     for p in result.problems],
        "stale": [{"location": str(s.location), "message": s.message} for s in stale],
    }


def _matrix_text(robot, result, stale, all_pairs, write_srdf, plot) -> None:
    from collections import Counter

    from rich.markup import escape
    from rich.table import Table

    console = _console()
    counts = Counter(p.reason for p in result.pairs)
    console.print(f"[bold]{robot.name}[/]: {len(result.links)} links with geometry, "
                  f"{len(result.pairs)} pairs, {result.samples} samples (seed {result.seed}, "
                  f"margin {result.margin * 1000:g} mm)")
    console.print("  " + ", ".join(f"{counts[c]} {c or 'enabled'}" for c in
                                  ("Adjacent", "Default", "Always", "Never", "")))
    shown = [p for p in result.pairs if all_pairs or p.reason in ("", "Default", "Always")]
    near = [p for p in result.pairs if p.reason == "" and p.collisions == 0]
    if shown:
        table = Table("link 1", "link 2", "class", "collisions", "min distance (mm)", box=None,
                      pad_edge=False)
        for p in sorted(shown, key=lambda p: (-p.fraction, p.min_distance or 0)):
            distance = "" if p.min_distance is None else f"{p.min_distance * 1000:.2f}"
            count = f"{p.collisions}/{p.samples}" if p.samples else ""
            table.add_row(p.link1, p.link2, p.reason or "enabled", count, distance)
        console.print(table)
    if near:
        console.print(f"{len(near)} pair(s) never collided but came within the margin, so they "
                      "stay enabled (MoveIt would disable them as Never): "
                      + ", ".join(f"{p.link1}/{p.link2} ({p.min_distance * 1000:.1f} mm)"
                                  for p in near))
    for n, changed in result.rounds:
        console.print(f"after {n} samples: {changed} pair(s) changed class in the second half")
    if result.converged:
        console.print("[green]converged[/]: no pair changed class in the second half")
    else:
        console.print("[yellow]not converged[/]: " + ", ".join(
            f"{a}/{b} {x or 'enabled'} -> {y or 'enabled'}" for a, b, x, y in result.unsettled)
            + f"; these pairs are rare events: more samples (--until-converged, --max-samples) "
            "would settle them")
    _notes(console, result.problems, result.visual_only)
    for item in stale:
        console.print(f"{escape(str(item.location))}: [bold red]stale[/] {escape(item.message)}")
    if write_srdf:
        console.print(f"wrote {write_srdf}")
    if plot:
        console.print(f"wrote {plot}")


def _json(data) -> None:
    typer.echo(json.dumps(_finite(data), indent=2, allow_nan=False))


def _finite(value):
    """``value`` with infinite or NaN floats as null, which JSON can carry."""
    import math

    if isinstance(value, dict):
        return {key: _finite(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(item) for item in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value
