"""``urdftool crosscheck``: load a robot with every real loader installed and compare."""

from __future__ import annotations

import typer

from urdftool.cli._common import (PackageOption, XacroArgOption, fail_usage,
                                  max_memory_option, robot_inputs, show, timeout_option)

FORMATS = ("text", "json")


def register(app: typer.Typer) -> None:
    app.command("crosscheck", help="Load the robot with each real loader installed (Pinocchio, "
                                   "MuJoCo, PyBullet, Drake, sdformat's gz sdf), each in a "
                                   "process of its own, and compare: loaded or why not (at the "
                                   "line), mass, degrees of freedom, base, links dropped, frame "
                                   "positions, inertia. Exit 1 when a loader fails or they "
                                   "disagree.")(crosscheck)


def crosscheck(
    words: list[str] = typer.Argument(..., metavar="FILE [NAME:=VALUE...]"),
    loader: list[str] = typer.Option([], "--loader", "-l", metavar="NAME",
                                     help="Only this loader (repeatable): pinocchio, mujoco, "
                                          "pybullet, drake, sdformat [default: all]."),
    output_format: str = typer.Option("text", "--format", "-f", help="text or json."),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
    timeout: float = timeout_option("each loader", "the loader is stopped and counts as not "
                                                   "loading, exit 1"),
    max_memory: str = max_memory_option("each loader", "the loader is stopped and counts as "
                                        "not loading, exit 1"),
) -> None:
    from urdftool.budget import Budget
    from urdftool.crosscheck import crosscheck as run
    from urdftool.errors import LoadError, UsageError
    from urdftool.report import crosscheck as render
    try:
        paths, args, packages = robot_inputs(words, arg, package)
        if len(paths) != 1:
            raise UsageError("give one robot file")
        if output_format not in FORMATS:
            raise UsageError(f"unknown format '{output_format}'; choose text or json")
        budget = Budget.of(timeout, max_memory)
        result = run(paths[0], [name for value in loader for name in value.split(",")],
                     xacro_args=args, packages=packages, budget=budget)
    except UsageError as error:
        fail_usage(error)
    except LoadError as error:
        from urdftool.cli._common import refuse_unloaded

        refuse_unloaded(paths[0], error)
    if output_format == "json":
        from urdftool.report.json_output import write_json

        write_json(result.as_dict())
    else:
        show(render.text(result), nl=False)
    raise typer.Exit(result.exit_code)
