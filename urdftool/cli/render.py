"""``urdftool render``: a picture of the robot at a configuration, PNG or SVG, headless."""

from __future__ import annotations

from pathlib import Path

import typer

from urdftool.cli._common import (MaxSceneTrianglesOption, PackageOption, XacroArgOption,
                                  budgeted, fail_at, fail_config, fail_over_limit, fail_usage,
                                  joint_words, only_with, refuse_bad_outputs, say, single_robot,
                                  warn)
from urdftool.errors import UsageError

HELP = ("Draw the robot's visual (or --collision) geometry posed at a configuration (default: "
        "0, or mid-range when 0 is outside the limits) as PNG or SVG: flat shading, no GPU, "
        "no display. In SVG each link is named on hover.")
VIEWS = ("front", "side", "top", "iso")


def register(app: typer.Typer) -> None:
    app.command("render", help=HELP)(budgeted(render))


def parse_size(text: str) -> tuple[int, int]:
    """``WIDTHxHEIGHT`` (each 16 to 8192 pixels) as a pair; UsageError otherwise (``1²x100``
    and a side of 5,000 digits were int()'s ValueError, a traceback)."""
    from urdftool.errors import shown_word
    from urdftool.numbers import is_decimal

    sides = text.lower().partition("x")[::2]
    if not all(is_decimal(side) and len(side) < 6 and 16 <= int(side) <= 8192 for side in sides):
        raise UsageError(f"--size must be WIDTHxHEIGHT in pixels, each 16 to 8192, not "
                         f"'{shown_word(text)}'")
    return int(sides[0]), int(sides[1])


def render(
    words: list[str] = typer.Argument(..., metavar="FILE [NAME:=VALUE...]"),
    output: Path = typer.Option(..., "--output", "-o", metavar="FILE.png|svg",
                                help="The picture to write (.png or .svg)."),
    q: list[str] = typer.Option([], "--q", metavar="JOINT=VALUE",
                                help="Joint value in rad or m (repeatable)."),
    deg: bool = typer.Option(False, "--deg", help="--q angles are in degrees."),
    view: str = typer.Option("iso", "--view", help="front, side, top or iso."),
    collision: bool = typer.Option(False, "--collision",
                                   help="Draw the collision geometry instead of the visual."),
    frames: bool = typer.Option(False, "--frames", help="Draw every link frame (x y z: red "
                                                        "green blue)."),
    axes: bool = typer.Option(False, "--axes", help="Draw every moving joint's axis."),
    size: str = typer.Option("600x600", "--size", metavar="WxH", help="Picture size in pixels."),
    max_scene_triangles: int = MaxSceneTrianglesOption,
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
) -> None:
    from urdftool.errors import ConfigError, OverLimit, PlotError, SceneError
    from urdftool.kinematics.scene import posed
    from urdftool.report.picture import Layer, PictureOptions, write

    refuse_bad_outputs(output, inputs=words)
    try:
        dimensions = parse_size(size)
    except UsageError as error:
        fail_usage(error)
    robot = single_robot("render", words, arg, package, {"--view": (view, VIEWS)}, [
        (output.suffix.lower() not in (".png", ".svg"),
         f"--output: '{output.name}' must end in .png or .svg"),
        only_with(("deg",), bool(q), "--q")])
    try:
        scene, warnings = posed(robot, joint_words(q, "--q"), deg, collision,
                                max_scene_triangles or None)
        warn(warnings + scene.problems)
        warn(write(output, [Layer(scene, label=robot.name)],
                   PictureOptions(view, dimensions, frames, axes)))
    except ConfigError as error:
        fail_config(error, "--q")
    except OverLimit as error:
        fail_over_limit(error, "--max-scene-triangles")
    except (PlotError, UsageError) as error:
        fail_usage(UsageError(str(error)))
    except SceneError as error:
        fail_at(robot, error)
    say(f"wrote {output} ({len(scene.triangles)} triangles){_why_empty(robot, scene, collision)}",
        err=True)
    # a picture of nothing because every shape was left out (NAO, Pepper and iCub without their
    # mesh packages) is a failure, as collisions' "not established"; a partial one is drawn
    raise typer.Exit(1 if not len(scene.triangles) and scene.problems else 0)


def _why_empty(robot, scene, collision: bool) -> str:
    """Why a picture shows nothing: a robot whose geometry is all of the other kind (its
    collision shapes only: a picture of 0 triangles said nothing of --collision), or whose
    every shape was left out (the warnings above say why)."""
    if len(scene.triangles):
        return ""
    drawn, other = ("collision", "visual") if collision else ("visual", "collision")
    if not any(True for _ in robot.root.iter(drawn)):
        hint = "--collision draws it" if not collision else "without --collision it is drawn"
        return (f": the robot has no <{drawn}> geometry" +
                (f", only <{other}>; {hint}" if any(True for _ in robot.root.iter(other)) else ""))
    return f": every <{drawn}> shape was left out (the warnings say why)" if scene.problems else ""

