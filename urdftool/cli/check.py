"""``urdftool check``: the linter and CI step."""

from __future__ import annotations

import dataclasses
import os
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
) -> None:
    from urdftool.budget import Budget
    from urdftool.lint.settings import checked_file_size
    from urdftool.description.meshes import MeshLimits
    from urdftool.lint.engine import CheckOptions, Selection
    from urdftool.lint.runner import check_files
    from urdftool.report import FORMATS, Summary, render

    try:
        paths, args, packages = robot_inputs(words, arg, package)
        if jobs < 0:
            raise UsageError("--jobs must not be negative")
        if not paths:
            raise UsageError("no PATH given")
        if format not in (*FORMATS, "auto"):
            raise UsageError(f"unknown format '{format}'; choose from auto, {', '.join(FORMATS)}")
        refuse_bad_outputs(output)
        config = _config_for(paths[0])
        if max_file_size is not None:
            checked_file_size(max_file_size, "--max-file-size")
        limit = max_file_size or config.max_file_size or CheckOptions.max_file_size
        budget = Budget.of(timeout, max_memory if max_memory is not None else config.max_memory)
        files, skipped = _expand_paths(paths, packages, limit)
        # Command-line companions win over the settings file's.
        companions = _settings_companions(config).overridden_by(
            _companion_options(controllers, srdf, spec))
    except UsageError as error:
        fail_usage(error)
    if verbose:
        from urdftool.report import printable  # a file name can hold a line break

        for path, reason in skipped.items():
            typer.echo(printable(f"skipped {path}: {reason}"), err=True)
    # --select replaces the settings' select; --ignore adds to their ignore.
    base_selection = Selection(tuple(_codes(select or config.select)),
                               tuple(_codes([*config.ignore, *ignore])))
    options = CheckOptions(
        xacro_args=args, packages={**config.packages, **packages}, selection=base_selection,
        allow_env=env_allowed(allow_env),
        max_file_size=limit,
        companions=companions, mesh_limits=MeshLimits(max_triangles=max_triangles),
    )

    def options_for(path: str) -> CheckOptions:
        per_file = config.ignores_for(path)
        if not per_file:
            return options
        return dataclasses.replace(options, selection=Selection(
            base_selection.select, (*base_selection.ignore, *_codes(per_file))))

    results = check_files(files, options_for, jobs=jobs or None, timeout=budget.seconds,
                          memory=budget.memory)
    if output:
        import io

        report = io.StringIO()
        render(format, results, report)
        write_output(output, report.getvalue())
    else:
        render(format, results, sys.stdout)
    summary = Summary.of(results)
    failed = summary.errors or ((strict or config.strict) and summary.warnings)
    raise typer.Exit(1 if failed else 0)


def env_allowed(flag: bool | None) -> bool:
    """``--allow-env``/``--no-env`` as given; unset, the safe mode when ``CI`` is set.

    A CI job on a pull request checks files a stranger wrote, and its environment holds
    tokens and secrets: ``$(env)`` or an include of a file outside the checkout would print
    them in the job's public log. GitHub Actions, GitLab CI and most other services set
    ``CI=true``; on a developer's machine the files are their own.
    """
    if flag is not None:
        return flag
    return os.environ.get("CI", "").strip().lower() in ("", "0", "false", "no")


def _companion_options(controllers: list[Path], srdf: Path | None, spec: Path | None):
    """Companion files named on the command line, checked to exist (else a usage error)."""
    from urdftool.description.robot import CompanionPaths

    for path in [*controllers, srdf, spec]:
        if path is not None and not path.is_file():
            raise UsageError(f"companion file '{path}' does not exist")
    return CompanionPaths(tuple(controllers), srdf, spec)


def _settings_companions(config):
    """``spec``/``controllers``/``srdf`` from the settings file."""
    from urdftool.description.robot import CompanionPaths

    controllers = config.companions.get("controllers") or []
    return CompanionPaths(tuple(controllers if isinstance(controllers, list) else [controllers]),
                          config.companions.get("srdf"), config.companions.get("spec"))


def _codes(values: list[str]) -> list[str]:
    return [part.strip() for value in values for part in value.split(",") if part.strip()]


def _config_for(path: str):
    from urdftool.lint.settings import find_config

    return find_config(Path.cwd() if path == "-" else Path(path))


def _expand_paths(paths: list[str], packages, max_file_size: int) -> tuple[list[str], dict]:
    """Files to check, in a stable order, and the files skipped in folders with the reason.
    Files over ``max_file_size`` [bytes] are not read to classify them."""
    from urdftool.diagnostics import display_path
    from urdftool.lint.targets import (explicit_targets, includers_below, project_root, resolved_path,
                            robot_files, split_top_level)
    from urdftool.description.packages import PackageResolver

    resolver_for = lambda p: PackageResolver(packages, start=p.parent)  # noqa: E731
    includers = {}  # project root -> its include graph, built once
    files, skipped = [], {}
    for path in paths:
        if path == "-" or not Path(path).is_file() and not Path(path).is_dir():
            files.append(path)
            continue
        if Path(path).is_file():
            root = project_root(Path(path))
            if root not in includers:
                includers[root] = includers_below(root, resolver_for, max_file_size)
            targets, reason = explicit_targets(Path(path), includers[root], root, max_file_size)
            files.extend(display_path(p) if p != Path(path) else path for p in targets)
            if reason:
                from urdftool.report import printable

                typer.echo(printable(f"urdftool: {path}: {reason}"), err=True)
            continue
        found = robot_files(Path(path))
        top, skipped_here = split_top_level(found, resolver_for, max_file_size)
        files.extend(str(p) for p in top)
        skipped.update({str(p): reason for p, reason in skipped_here.items()})
        if not found:
            raise UsageError(f"no .urdf or .xacro files found in '{path}'")
    unique = {}  # the same file named twice, or a robot and a macro it includes: check it once
    for file in files:
        unique.setdefault(file if file == "-" else resolved_path(Path(file)), file)
    return list(unique.values()), skipped
