"""``urdftool check``: the linter and CI step."""

from __future__ import annotations

import sys
from pathlib import Path

import typer

from urdftool.errors import UsageError
from urdftool.cli._common import (MaxMemoryOption, PackageOption, TimeoutOption, XacroArgOption,
                      fail_usage, refuse_bad_outputs, robot_inputs, write_output)


def register(app: typer.Typer) -> None:
    app.command(
        "check",
        help="Check robot descriptions (files or folders) and report problems. "
             "Exit code: 0 clean, 1 errors (or warnings with --strict), 2 usage error.",
    )(check)


def check(
    words: list[str] = typer.Argument(..., metavar="PATH... [NAME:=VALUE...]",
                                      help="URDF/xacro files or folders; '-' reads stdin."),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
    format: str = typer.Option("auto", "--format", "-f",
                               help="text, json, sarif, junit, github, or auto (github under "
                                    "GitHub Actions, else text)."),
    output: Path = typer.Option(None, "--output", "-o", help="Write the report to this file."),
    select: list[str] = typer.Option([], "--select", help="Only these codes, prefixes or names "
                                     "(comma-separated, repeatable)."),
    ignore: list[str] = typer.Option([], "--ignore", help="Skip these codes, prefixes or names."),
    strict: bool = typer.Option(False, "--strict", help="Exit 1 on warnings too."),
    verbose: bool = typer.Option(False, "--verbose", "-v", help="Say which files were skipped."),
    allow_env: bool = typer.Option(
        None, "--allow-env/--no-env", show_default=False,
        help="--no-env, the safe mode for untrusted input: $(env)/$(optenv) are errors and "
             "xacro reads no file outside the repository and its packages. --allow-env: "
             "both allowed. [default: --no-env when CI is set, as CI services do; else "
             "--allow-env]"),
    max_file_size: int = typer.Option(None, "--max-file-size", metavar="BYTES",
                                      help="Refuse input files larger than this [default: 16 MiB]."),
    controllers: list[Path] = typer.Option([], "--controllers", metavar="FILE",
                                           help="Controller configuration YAML (repeatable) "
                                                "[default: config/*.yaml beside the robot]."),
    srdf: Path = typer.Option(None, "--srdf", metavar="FILE",
                              help="MoveIt SRDF [default: the *.srdf beside the robot]."),
    spec: Path = typer.Option(None, "--spec", metavar="FILE",
                              help="Joint spec table [default: joint_limits.yaml beside the "
                                   "robot, when it is a urdftool spec]."),
    max_triangles: int = typer.Option(2_000_000, "--max-triangles", metavar="N",
                                      help="Refuse meshes with more triangles than this."),
    timeout: float = TimeoutOption,
    max_memory: str = typer.Option(None, "--max-memory", metavar="SIZE",
                                   help=f"{MaxMemoryOption.help} Per worker [default: 2G, or "
                                        "max-memory in the settings]."),
    jobs: int = typer.Option(0, "--jobs", "-j", metavar="N",
                             help="Check files in N worker processes [default: number of cores]."),
    no_cache: bool = typer.Option(False, "--no-cache", help="Neither read nor keep results."),
    cache_dir: Path = typer.Option(None, "--cache-dir", metavar="DIR",
                                   help="Keep results here between runs [default: "
                                        ".urdftool_cache; none when CI is set]."),
) -> None:
    from urdftool.budget import Budget
    from urdftool.errors import SettingsError, TargetError, UnknownName
    from urdftool.lint.cache import default_folder
    from urdftool.lint.runner import check_paths
    from urdftool.lint.settings import CheckRequest, Companions, checked_file_size
    from urdftool.report import FORMATS, printable, render

    try:
        paths, args, packages = robot_inputs(words, arg, package)
        if jobs < 0:
            raise UsageError("--jobs must not be negative")
        if not paths:
            raise UsageError("no PATH given")
        if format not in (*FORMATS, "auto"):
            raise UsageError(f"unknown format '{format}'; choose from auto, {', '.join(FORMATS)}")
        refuse_bad_outputs(output)
        if max_file_size is not None:
            checked_file_size(max_file_size, "--max-file-size")
        Budget.of(timeout, max_memory)  # --timeout and --max-memory are well formed
        run = check_paths(paths, CheckRequest(
            select=tuple(select), ignore=tuple(ignore), strict=strict, xacro_args=args,
            packages=packages, companions=Companions(tuple(controllers), srdf, spec),
            allow_env=allow_env, max_file_size=max_file_size, max_triangles=max_triangles,
            max_memory=max_memory, timeout=timeout, jobs=jobs or None,
            cache_dir=None if no_cache else cache_dir or default_folder()))
    except (UsageError, SettingsError, TargetError, UnknownName) as error:
        fail_usage(error)
    for note in run.notes:
        typer.echo(printable(f"urdftool: {note}"), err=True)
    if verbose:  # a file name can hold a line break: printable
        for path, reason in run.skipped.items():
            typer.echo(printable(f"skipped {path}: {reason}"), err=True)
    if output:
        import io

        report = io.StringIO()
        render(format, run.results, report)
        write_output(output, report.getvalue())
    else:
        render(format, run.results, sys.stdout)
    raise typer.Exit(run.exit_code)
