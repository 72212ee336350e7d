"""``urdftool fk``: link poses for joint configurations, from the URDF or from a D-H table."""

from __future__ import annotations

import typer

from urdftool.errors import UnknownName

from urdftool.cli._common import (PackageOption, XacroArgOption, budgeted, fail_at, fail_config,
                                  joint_words, only_with, say, single_robot, warn)

FORMATS = ("text", "json", "csv")
VERIFY_TOLERANCE = 1e-9  # [m] and [rad]
VERIFY_DEFAULT_COUNT = 1000


def register(app: typer.Typer) -> None:
    app.command("fk", help="Forward kinematics: link poses for joint configurations.")(budgeted(fk))


def fk(
    words: list[str] = typer.Argument(..., metavar="FILE [NAME:=VALUE...]"),
    q: list[str] = typer.Option([], "--q", metavar="JOINT=VALUE",
                                help="Joint value [rad or m] (repeatable); others take 0 or mid-range."),
    deg: bool = typer.Option(False, "--deg", help="Angles are in degrees."),
    q_file: str = typer.Option(None, "--q-file", metavar="FILE",
                               help="CSV (header = joint names) or JSON configurations, one per row."),
    random: int = typer.Option(None, "--random", metavar="N", help="N random configurations "
                               "within the limits, each given with the joint values drawn."),
    seed: int = typer.Option(0, "--seed", help="Seed for --random and --verify."),
    frame: list[str] = typer.Option([], "--frame", metavar="LINK", help="Only this link (repeatable)."),
    base: str = typer.Option(None, "--base", metavar="LINK", help="Poses relative to this link."),
    matrix: bool = typer.Option(False, "--matrix", help="Also give each pose as a 4x4 matrix."),
    floating: bool = typer.Option(False, "--floating",
                                  help="Add a free-flyer root joint 'root_joint' (.x .y .z "
                                       ".roll .pitch .yaw); a robot hung from a massless root "
                                       "by a floating joint of its own has that one as its "
                                       "free base."),
    dh: str = typer.Option(None, "--dh", metavar="TABLE", help="Compute the chain from this D-H table."),
    verify: bool = typer.Option(False, "--verify",
                                help="With --dh: compare D-H and URDF FK on random configurations."),
    output_format: str = typer.Option("text", "--format", "-f", help="text, json or csv."),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
) -> None:
    from urdftool.kinematics import configuration as config
    from urdftool.kinematics.dh import DHError, load_table, table_forward, verify as dh_verify
    from urdftool.kinematics.fk import FKError, KinematicModel, forward_kinematics_blocks
    from urdftool.report.fk import verify_line, write_poses

    robot = single_robot("fk", words, arg, package, {"--format": (output_format, FORMATS)}, (
        (sum(bool(x) for x in (q, q_file, random is not None and not verify)) > 1,
         "give one of --q, --q-file, --random"),
        (verify and not dh, "--verify needs --dh TABLE"),
        (dh and len(frame) > 1, "--dh computes one chain: give at most one --frame (its tip)"),
        (random is not None and random < 1, "--random must be at least 1"),
        only_with(("seed",), random is not None or verify, "--random or --verify"),
        (bool(dh) and floating, "--floating does not go with --dh (the table's poses are "
                                "relative to its base link, which the free-flyer moves too)"),
        only_with(("deg",), bool(q or q_file), "--q or --q-file")))
    tip = frame[0] if frame else None
    try:
        table = load_table(dh) if dh else None
        model = KinematicModel(robot, floating=floating)
        if verify:
            count = random or VERIFY_DEFAULT_COUNT
            errors = dh_verify(table, model, config.random(model.variables, count, seed), base,
                               tip)
            say(verify_line(count, seed, *errors, VERIFY_TOLERANCE))
            raise typer.Exit(0 if all(e <= VERIFY_TOLERANCE for e in errors) else 1)
        configurations = config.configurations(model, joint_words(q, "--q"), deg, q_file,
                                               random, seed)
        if table is not None:
            result = table_forward(table, model, configurations, base, tip)
        else:
            result = forward_kinematics_blocks(model, configurations, frame or None, base)
    except config.ConfigError as error:
        fail_config(error, "--q")
    except DHError as error:
        if error.element is None and error.where is None and dh:
            error.where = dh  # about the table, not the robot
        fail_at(robot, error)
    except (FKError, UnknownName) as error:
        fail_at(robot, error)
    warn(result.warnings)
    drawn = None
    if random is not None:  # the values drawn, so that each pose can be computed again
        drawn = ([variable.name for variable in configurations.variables],
                 configurations.values, seed)
    write_poses(result, output_format, matrix, single=not (q_file or random), drawn=drawn)
