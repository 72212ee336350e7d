"""``urdftool fk``: link poses for joint configurations, from the URDF or from a D-H table."""

from __future__ import annotations

import sys

import typer

from urdftool.cli._common import (PackageOption, XacroArgOption, budgeted, fail_at, fail_usage, fixed,
                      pairs, single_robot, wide_console)
from urdftool.errors import UsageError

FORMATS = ("text", "json", "csv")
VERIFY_TOLERANCE = 1e-9  # [m] and [rad]
VERIFY_DEFAULT_COUNT = 1000


def register(app: typer.Typer) -> None:
    app.command("fk", help="Forward kinematics: link poses for joint configurations.")(budgeted(fk))


def fk(
    words: list[str] = typer.Argument(..., metavar="FILE [NAME:=VALUE...]"),
    q: list[str] = typer.Option([], "--q", metavar="NAME=VALUE",
                                help="Joint value [rad or m] (repeatable); others take 0 or mid-range."),
    deg: bool = typer.Option(False, "--deg", help="Angles are in degrees."),
    q_file: str = typer.Option(None, "--q-file", metavar="FILE",
                               help="CSV (header = joint names) or JSON configurations, one per row."),
    random: int = typer.Option(None, "--random", metavar="N", help="N random configurations."),
    seed: int = typer.Option(0, "--seed", help="Seed for --random and --verify."),
    frame: list[str] = typer.Option([], "--frame", metavar="LINK", help="Only this link (repeatable)."),
    base: str = typer.Option(None, "--base", metavar="LINK", help="Poses relative to this link."),
    matrix: bool = typer.Option(False, "--matrix", help="Also give each pose as a 4x4 matrix."),
    floating: bool = typer.Option(False, "--floating",
                                  help="Add a free-flyer root joint 'root_joint' (.x .y .z .roll .pitch .yaw)."),
    dh: str = typer.Option(None, "--dh", metavar="TABLE", help="Compute the chain from this D-H table."),
    verify: bool = typer.Option(False, "--verify",
                                help="With --dh: compare D-H and URDF FK on random configurations."),
    output_format: str = typer.Option("text", "--format", "-f", help="text, json or csv."),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
) -> None:
    from urdftool.kinematics import configuration as config
    from urdftool.kinematics.dh import DHError, load_table, table_forward
    from urdftool.kinematics.fk import FKError, KinematicModel, forward_kinematics

    robot = single_robot("fk", words, arg, package, {"--format": (output_format, FORMATS)}, (
        (sum(bool(x) for x in (q, q_file, random is not None and not verify)) > 1,
         "give one of --q, --q-file, --random"),
        (verify and not dh, "--verify needs --dh TABLE"),
        (dh and len(frame) > 1, "--dh computes one chain: give at most one --frame (its tip)"),
        (random is not None and random < 1, "--random must be at least 1")))
    try:
        table = load_table(dh) if dh else None
        model = KinematicModel(robot, floating=floating)
        if verify:
            _verify(table, model, random or VERIFY_DEFAULT_COUNT, seed, base, frame)
        configurations = _configurations(model, q, deg, q_file, random, seed)
        if table is not None:
            result = table_forward(table, model, configurations, base, frame[0] if frame else None)
        else:
            result = forward_kinematics(model, configurations, frame or None, base)
    except config.ConfigError as error:
        fail_usage(UsageError(str(error)))
    except UsageError as error:
        fail_usage(error)
    except DHError as error:
        if error.element is None and error.where is None and dh:
            error.where = dh  # about the table, not the robot
        fail_at(robot, error)
    except FKError as error:
        fail_at(robot, error)
    for warning in result.warnings:
        typer.echo(f"urdftool: warning: {warning}", err=True)
    _render(result, output_format, matrix, single=not (q_file or random))


def _configurations(model, q, deg, q_file, random, seed):
    from urdftool.kinematics import configuration as config

    if q_file:
        return config.from_file(model.variables, q_file, deg, model.mimics)
    if random is not None:
        return config.random(model.variables, random, seed)
    return config.from_words(model.variables, pairs(q, "--q", strip=True), deg, model.mimics)


def _verify(table, model, count, seed, base, frame) -> None:
    from urdftool.kinematics import configuration as config
    from urdftool.kinematics.dh import verify

    configurations = config.random(model.variables, count, seed)
    position, rotation = verify(table, model, configurations, base, frame[0] if frame else None)
    ok = position <= VERIFY_TOLERANCE and rotation <= VERIFY_TOLERANCE
    typer.echo(f"D-H vs URDF over {count} random configurations (seed {seed}): worst position "
               f"error {position:.3g} m, worst orientation error {rotation:.3g} rad: "
               f"{'agree' if ok else 'DISAGREE'} (tolerance {VERIFY_TOLERANCE:g})")
    raise typer.Exit(0 if ok else 1)


def _render(result, output_format: str, matrix: bool, single: bool) -> None:
    from urdftool.kinematics.fk import pose_components

    positions, rpys, quaternions = pose_components(result.matrices)
    if output_format == "json":
        import json

        documents = [{"base": result.base, "frames": [
            _frame_entry(name, positions[row, k], rpys[row, k], quaternions[row, k],
                         result.matrices[row, k] if matrix else None)
            for k, name in enumerate(result.frames)]} for row in range(len(positions))]
        typer.echo(json.dumps(documents[0] if single else documents, indent=2))
    elif output_format == "csv":
        _csv(result, positions, rpys, quaternions, matrix)
    else:
        _text(result, positions, rpys, quaternions, matrix)


def _frame_entry(name, position, rpy, quaternion, matrix) -> dict:
    entry = {"frame": name, "position": position.tolist(), "rpy": rpy.tolist(),
             "quaternion": quaternion.tolist()}
    if matrix is not None:
        entry["matrix"] = matrix.tolist()
    return entry


def _csv(result, positions, rpys, quaternions, matrix) -> None:
    import csv

    import numpy as np

    header = ["row", "base", "frame", "x", "y", "z", "roll", "pitch", "yaw",
              "qx", "qy", "qz", "qw"]
    if matrix:
        header += [f"m{i}{j}" for i in range(3) for j in range(4)]
    writer = csv.writer(sys.stdout, lineterminator="\n")
    writer.writerow(header)
    numbers = np.concatenate([positions, rpys, quaternions], axis=-1)
    if matrix:
        numbers = np.concatenate([numbers, result.matrices[..., :3, :].reshape(
            numbers.shape[:2] + (12,))], axis=-1)
    for row in range(len(numbers)):
        for k, name in enumerate(result.frames):
            writer.writerow([row + 1, result.base, name, *(repr(float(v)) for v in numbers[row, k])])


def _text(result, positions, rpys, quaternions, matrix) -> None:
    from rich.markup import escape
    from rich.table import Table

    console = wide_console()
    for row in range(len(positions)):
        title = f"poses relative to {result.base}" + (
            f" (configuration {row + 1})" if len(positions) > 1 else "")
        table = Table(title=title, title_justify="left")
        for column in ("frame", "x [m]", "y [m]", "z [m]", "roll", "pitch", "yaw",
                       "qx", "qy", "qz", "qw"):
            table.add_column(escape(column), justify="left" if column == "frame" else "right")
        for k, name in enumerate(result.frames):
            table.add_row(name, *(fixed(v) for v in
                                  (*positions[row, k], *rpys[row, k], *quaternions[row, k])))
        console.print(table)
        if matrix:
            for k, name in enumerate(result.frames):
                console.print(f"{name}:")
                for line in result.matrices[row, k]:
                    console.print("  " + " ".join(f"{v: .6f}" for v in line))
