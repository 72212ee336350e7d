"""``urdftool dynamics``: mass, centre of mass, M(q), G(q), C(q, v), tau, gravity margins."""

from __future__ import annotations

import typer

from urdftool.cli._common import (PackageOption, XacroArgOption, budgeted, fail_at, fail_config,
                                  joint_words, single_robot, warn)


FORMATS = ("text", "json")


def register(app: typer.Typer) -> None:
    app.command("dynamics", help="Mass, centre of mass, M(q), G(q), C(q,v), torques and "
                                 "gravity margins against effort limits.")(budgeted(dynamics))


def dynamics(
    words: list[str] = typer.Argument(..., metavar="ROBOT [NAME:=VALUE...]"),
    q: list[str] = typer.Option([], "--q", metavar="JOINT=VALUE", help="Joint position "
                                "(repeatable); others are 0."),
    v: list[str] = typer.Option([], "--v", metavar="JOINT=VALUE", help="Joint velocity."),
    a: list[str] = typer.Option([], "--a", metavar="JOINT=VALUE", help="Joint acceleration."),
    deg: bool = typer.Option(False, "--deg", help="Angles in degrees (and deg/s, deg/s^2)."),
    samples: int = typer.Option(0, "--samples", metavar="N", help="Worst gravity torque per "
                                "joint over N random poses within limits (and the zero pose)."),
    seed: int = typer.Option(0, "--seed", help="Random seed for --samples."),
    output_format: str = typer.Option("text", "--format", "-f", help="text or json."),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
) -> None:
    from urdftool.kinematics.configuration import ConfigError, joint_values
    from urdftool.physics.dynamics import (DynamicsError, build, gravity_loads, gravity_variables,
                                           state)
    from urdftool.report import dynamics as render

    robot = single_robot("dynamics", words, arg, package, {"--format": (output_format, FORMATS)},
                         [(samples < 0, "--samples must be 0 or more")])
    try:
        model = build(robot)
    except DynamicsError as error:
        fail_at(robot, error)
    given = {name: joint_words(values, f"--{name}") for name, values in (("q", q), ("v", v),
                                                                         ("a", a))}
    try:
        values = joint_values(robot, **given, degrees=deg)
    except ConfigError as error:
        fail_config(error, f"--{error.argument}")
    result = state(model, values.q, values.v, values.a)
    warn(values.warnings + result.warnings)
    loads = gravity_loads(model, samples, seed) if samples else []
    if output_format == "json":
        from urdftool.report.json_output import write_json

        write_json(render.json_document(result, loads))
    else:
        # --samples alone asks for gravity margins: M and G at the zero pose would be noise
        least = render.weakest(loads)
        relevant = gravity_variables(model, least.joint) if least is not None else set()
        typer.echo(render.text(result, loads, samples, matrices=bool(q or v or a or not samples),
                               relevant=relevant), nl=False)
    raise typer.Exit(1 if any(load.holds is False for load in loads) else 0)
