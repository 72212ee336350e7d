"""``urdftool dynamics``: mass, centre of mass, M(q), G(q), C(q, v), tau, gravity margins."""

from __future__ import annotations

import json

import typer

from urdftool.cli._common import (PackageOption, XacroArgOption, budgeted, fail_at, fail_usage, pairs,
                      single_robot)
from urdftool.errors import UsageError


FORMATS = ("text", "json")


def register(app: typer.Typer) -> None:
    app.command("dynamics", help="Mass, centre of mass, M(q), G(q), C(q,v), torques and "
                                 "gravity margins against effort limits.")(budgeted(dynamics))


def _values(robot, q: list[str], v: list[str], a: list[str], degrees: bool):
    """{joint: value} for --q, --v (None if not given), --a (None), and limit warnings for --q."""
    import numpy as np

    from urdftool.kinematics import configuration as config

    variables, mimics = config.variables_of(robot), config.mimics_of(robot)
    try:
        values = [config.assignments(variables, pairs(words, option, strip=True), option,
                                     degrees, mimics)
                  if words or option == "--q" else None
                  for words, option in ((q, "--q"), (v, "--v"), (a, "--a"))]
    except config.ConfigError as error:
        raise UsageError(str(error)) from None
    given = [variable for variable in variables if variable.name in values[0]]
    row = np.array([[values[0][variable.name] for variable in given]])
    return (*values, config.limit_warnings(given, row))


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
    from urdftool.physics.dynamics import DynamicsError, build, gravity_loads, gravity_variables, state

    robot = single_robot("dynamics", words, arg, package, {"--format": (output_format, FORMATS)},
                         [(samples < 0, "--samples must be 0 or more")])
    try:
        model = build(robot)
    except DynamicsError as error:
        fail_at(robot, error)
    try:
        q_values, v_values, a_values, warnings = _values(robot, q, v, a, deg)
    except UsageError as error:
        fail_usage(error)
    result = state(model, q_values, v_values, a_values)
    if result.mass <= 0:
        warnings.append("no link has a mass (no <inertial>): M(q) and every gravity torque are "
                        "zero; check the description (xacro arguments?) with 'urdftool check'")
    for warning in warnings:
        typer.echo(f"urdftool: warning: {warning}", err=True)
    loads = gravity_loads(model, samples, seed) if samples else []
    if output_format == "json":
        data = result.as_dict()
        data["gravity_loads"] = [load.as_dict() for load in loads]
        typer.echo(json.dumps(data, indent=2))
    else:
        # --samples alone asks for gravity margins: M and G at the zero pose would be noise
        relevant = gravity_variables(model, _weakest(loads).joint) if loads else set()
        typer.echo(_text(result, loads, samples, matrices=bool(q or v or a or not samples),
                         relevant=relevant), nl=False)
    raise typer.Exit(1 if any(not load.holds for load in loads) else 0)


def _row(values) -> str:
    return " ".join(f"{v:10.4g}" for v in values)


def _weakest(loads):
    return min(loads, key=lambda load: load.margin / load.effort if load.effort else 0)


def _text(result, loads, samples, matrices: bool = True, relevant=()) -> str:
    width = max((len(j) for j in result.joints), default=5)
    com = " ".join(f"{c if abs(c) > 1e-12 else 0.0:.4g}" for c in result.com)
    lines = [f"total mass {result.mass:.4g} kg, centre of mass ({com}) m in the root frame"]
    if matrices:
        lines += ["", "G(q): gravity torque per joint [N m or N]"]
        lines += [f"  {name:{width}s} {g:10.4g}" for name, g in zip(result.joints, result.G)]
        lines += ["", "M(q): joint-space mass matrix"]
        lines += [f"  {name:{width}s} {_row(row)}" for name, row in zip(result.joints, result.M)]
    if result.C is not None:
        lines += ["", "C(q, v): Coriolis matrix"]
        lines += [f"  {name:{width}s} {_row(row)}" for name, row in zip(result.joints, result.C)]
        lines += ["", "tau = M(q) a + C(q, v) v + G(q)"]
        lines += [f"  {name:{width}s} {t:10.4g}" for name, t in zip(result.joints, result.tau)]
        lines.append(f"  (matches rnea to {result.rnea_residual:.2g})")
    if loads:
        lines += ["", f"static gravity load over the zero pose and {samples} random poses:",
                  f"  {'joint':{width}s} {'effort':>8s} {'zero pose':>10s} {'worst':>10s} "
                  f"{'margin':>10s}"]
        for load in loads:
            flag = "" if load.holds else "  ERROR: cannot hold itself against gravity"
            lines.append(f"  {load.joint:{width}s} {load.effort:8.4g} {load.zero_pose:10.4g} "
                         f"{load.worst:10.4g} {load.margin:10.4g}{flag}")
        weakest = _weakest(loads)
        # only the joints that change its load: the others' values are noise
        pose = ", ".join(f"{k}={v:.3f}" for k, v in weakest.worst_pose.items()
                         if v and k in relevant)
        lines.append(f"  smallest margin: {weakest.joint} ({weakest.margin:.3g} of "
                     f"{weakest.effort:.3g}) at {pose or 'the zero pose'}")
        failing = [load.joint for load in loads if not load.holds]
        lines.append(f"  {len(failing)} joint{'s' if len(failing) > 1 else ''} cannot hold "
                     f"{'themselves' if len(failing) > 1 else 'itself'}: {', '.join(failing)}"
                     if failing else "  every joint holds the robot against gravity")
    return "\n".join(lines) + "\n"
