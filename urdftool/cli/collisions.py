"""``urdftool collisions``: self-collision at a pose, and the MoveIt-style collision matrix."""

from __future__ import annotations

from pathlib import Path

import typer

from urdftool.errors import OverLimit, UnknownName

from urdftool.cli._common import (MaxSceneTrianglesOption, PackageOption, XacroArgOption,
                                  budgeted, fail_at, fail_config, fail_over_limit, fail_usage,
                                  given, joint_words, only_with, refuse_bad_outputs,
                                  single_robot, warn, write_output)
from urdftool.errors import UsageError

MAX_PAIRS = 250_000  # urdftool.collision.matrix.MAX_PAIRS (not imported: numpy, FCL)

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
                              "[default: the robot's .srdf in its folder or config/, as check "
                              "finds it]."),
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
    max_pairs: int = typer.Option(MAX_PAIRS, "--max-pairs", min=0, metavar="N",
                                  help="Refuse, before any work, a robot whose links with "
                                       "collision geometry make more pairs (memory and time "
                                       "grow with them); 0 for no limit."),
    workers: int = typer.Option(2, "--workers", min=1, help="Worker processes."),
    write_srdf: Path = typer.Option(None, "--write-srdf", metavar="FILE",
                                    help="Write disable_collisions here; an existing SRDF keeps "
                                         "its other content."),
    check_srdf: Path = typer.Option(None, "--check-srdf", metavar="FILE",
                                    help="Report stale disable_collisions in FILE (exit 1)."),
    plot: Path = typer.Option(None, "--plot", metavar="FILE.png|svg", help="Draw the matrix."),
    render: Path = typer.Option(None, "--render", metavar="FILE.png|svg",
                                help="Pose mode: draw the collision geometry at the pose, the "
                                     "links of colliding pairs that are not allowed in red."),
    max_scene_triangles: int = MaxSceneTrianglesOption,
    all_pairs: bool = typer.Option(False, "--all", help="List every pair in text output."),
    format: str = typer.Option("text", "--format", "-f", help="text or json."),
) -> None:
    from urdftool.collision.srdf import SrdfError
    from urdftool.description.files import kind_of, unreachable
    from urdftool.errors import SceneError
    from urdftool.kinematics.configuration import ConfigError
    from urdftool.kinematics.fk import FKError
    from urdftool.report.plot import PlotError

    refuse_bad_outputs(write_srdf)  # an SRDF written over the one it read is meant
    refuse_bad_outputs(plot, render, inputs=words, also=(write_srdf,))
    robot = single_robot("collisions", words, arg, package, {"--format": (format, FORMATS)}, [
        (not matrix and (write_srdf or check_srdf or plot or until_converged),
         "--write-srdf, --check-srdf, --plot and --until-converged need --matrix"),
        (matrix and deg, "--deg goes with --q, not with --matrix"),
        (matrix and q, "--q sets the pose of a single check; it does not go with --matrix"),
        (matrix and render, "--render draws one pose; it does not go with --matrix (--plot "
                            "draws the matrix)"),
        (matrix and bool(given("srdf")), "--srdf allows pairs at one pose; --matrix reads no "
                                         "SRDF (--check-srdf FILE compares one with it)"),
        only_with(("samples", "seed", "min_fraction", "margin", "max_samples", "workers",
                   "all_pairs"), matrix, "--matrix"),
        only_with(("deg",), bool(q) or matrix, "--q"),
        only_with(("max_scene_triangles",), render is not None, "--render"),
        (render is not None and render.suffix.lower() not in (".png", ".svg"),
         f"--render: '{render.name if render else ''}' must end in .png or .svg"),
        *((kind_of(given) != "file",
           f"{name}: '{given}' " + ("is no file" if kind_of(given) else unreachable(given)))
          for given, name in ((srdf, "--srdf"), (check_srdf, "--check-srdf"))
          if given is not None)])
    try:
        if matrix:
            from urdftool.collision.classify import MatrixOptions

            options = MatrixOptions(samples, seed, min_fraction, margin, until_converged,
                                    max_samples, workers, check_srdf, max_pairs or None)
            code = _matrix(robot, options, write_srdf, plot, all_pairs, format)
        else:
            code = _pose(robot, joint_words(q, "--q"), deg, srdf, format, render,
                         max_pairs or None, max_scene_triangles or None)
    except ConfigError as error:
        fail_config(error, "--q")
    except SrdfError as error:
        fail_usage(UsageError(str(error)))
    except PlotError as error:
        fail_usage(UsageError(f"--plot: {error}"))
    except UsageError as error:
        fail_usage(error)
    except OverLimit as error:
        fail_over_limit(error, "--max-scene-triangles" if error.unit == "triangles"
                        else "--max-pairs")
    except (FKError, SceneError, UnknownName) as error:
        fail_at(robot, error)
    raise typer.Exit(code)


def _pose(robot, values, degrees, srdf, format, render, max_pairs, max_triangles) -> int:
    from urdftool.collision.pose import check_pose
    from urdftool.report.collisions import write_pose

    if render:  # a picture over the limit is refused before the pairs are checked
        from urdftool.kinematics.scene import refuse_over

        refuse_over(robot, True, max_triangles)
    report = check_pose(robot, values, degrees, srdf, max_pairs)
    warn(report.warnings)
    if render:
        from urdftool.kinematics.scene import scene_model
        from urdftool.report.picture import Layer, write

        scene = scene_model(robot, True, max_triangles).pose(report.q, max_triangles)
        warn(scene.problems)
        colliding = {name for c in report.forbidden for name in (c.link1, c.link2)}
        warn(write(render, [Layer(scene, highlight=colliding, label=robot.name)]))
    write_pose(robot.name, report, format, custom=bool(values))
    return 1 if report.forbidden or report.problems else 0  # left out: not established


def _matrix(robot, options, write_srdf, plot, all_pairs, format) -> int:
    from urdftool.collision.classify import classify
    from urdftool.collision.srdf import REWRITES, check_update, updated
    from urdftool.report import plot as plot_module
    from urdftool.report.collisions import write_matrix
    from urdftool.report.progress import sampling_progress

    if write_srdf:
        check_update(write_srdf)  # before the work, what writing it would refuse
    with sampling_progress(options.samples, machine=format != "text") as on_progress:
        outcome = classify(robot, options, on_progress)
    warn(outcome.matrix.assumed)
    if write_srdf:
        write_output(write_srdf, updated(outcome.matrix, robot.name, write_srdf),  # an SRDF
                     rewrites=REWRITES)  # updated: meant, of a file read as an SRDF only
    if plot:
        plot_module.write(outcome.matrix, plot, f"{robot.name}: {outcome.matrix.samples} "
                                                f"samples, seed {options.seed}")
    write_matrix(robot.name, outcome, format, all_pairs, [p for p in (write_srdf, plot) if p])
    return 1 if outcome.stale else 0
