"""``urdftool workspace``: where a limb's tip can go, from sampled in-limit configurations."""

from __future__ import annotations

import typer

from urdftool.cli._common import (PackageOption, XacroArgOption, budgeted, fail_at, fail_config,
                                  joint_words, only_with, refuse_bad_outputs, show, single_robot,
                                  warn)
from urdftool.cli.ik import BaseOption, PointOption, TipOption, Triple

FORMATS = ("text", "json")


def register(app: typer.Typer) -> None:
    app.command("workspace", help="Reach envelope of --tip relative to --base from sampled "
                                  "configurations, with a picture.")(budgeted(workspace))


def workspace(
    words: list[str] = typer.Argument(..., metavar="FILE [NAME:=VALUE...]"),
    tip: str = TipOption,
    base: str = BaseOption,
    point: Triple = PointOption,
    samples: int = typer.Option(2000, "--samples", metavar="N", help="Configurations drawn."),
    seed: int = typer.Option(0, "--seed", help="Random seed."),
    q: list[str] = typer.Option([], "--q", metavar="JOINT=VALUE",
                                help="Value of a joint off the limb (repeatable; a planar "
                                     "joint's as JOINT.x, .y, .yaw: a limb through one is "
                                     "refused, choose a --base below it)."),
    deg: bool = typer.Option(False, "--deg", help="--q angles in degrees."),
    plot: str = typer.Option(None, "--plot", metavar="FILE.png|svg",
                             help="Top and side views shaded by manipulability, .svg or .png."),
    output_format: str = typer.Option("text", "--format", "-f", help="text or json."),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
) -> None:
    from urdftool.errors import ConfigError, FKError, IKError, UnknownName
    from urdftool.kinematics import configuration as config
    from urdftool.kinematics.chain import build_chain
    from urdftool.kinematics.fk import KinematicModel
    from urdftool.kinematics.workspace import sample
    from urdftool.report import workspace as render

    robot = single_robot("workspace", words, arg, package, {"--format": (output_format, FORMATS)},
                         ((samples < 1, "--samples must be at least 1"),
                          only_with(("deg",), bool(q), "--q"),
                          (plot is not None and not str(plot).lower().endswith((".svg", ".png")),
                           "--plot must end in .svg or .png")))
    refuse_bad_outputs(plot, inputs=words)
    try:
        kinematics = KinematicModel(robot)
        start = config.from_words(kinematics.variables, joint_words(q, "--q"), deg,
                                  kinematics.mimics)
        chain = build_chain(robot, base, tip, start.values[0], kinematics, point)
    except ConfigError as error:
        fail_config(error, "--point" if error.argument == "point" else "--q")
    except (FKError, IKError, UnknownName) as error:
        fail_at(robot, error)
    warn(start.warnings)
    if chain.held:
        from urdftool.errors import listed

        what = ("the limb cannot move: its workspace is one point"
                if len(chain.held) == len(chain.variables) else "held there in every sample")
        warn([f"{listed(chain.held)} {'has' if len(chain.held) == 1 else 'have'} no range "
              f"(lower = upper): {what}"])
    from urdftool.report.progress import sampling_progress

    try:
        with sampling_progress(samples, machine=output_format != "text") as moved:
            space = sample(chain, samples, seed, moved)
    except ConfigError as error:  # (a measure past the float range: --point too far)
        fail_config(error, "--point")
    if plot:
        from urdftool.report.plot import write_items

        write_items(plot, *render.picture(space, f"{robot.name}: {chain.tip} relative to "
                                                 f"{chain.base}"))
    if output_format == "json":
        from urdftool.report.json_output import write_json

        write_json(space.as_dict())
    else:
        show(render.text(space), nl=False)
