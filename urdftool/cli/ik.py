"""``urdftool ik``: joint values that put a link at a pose, and which targets a limb reaches."""

from __future__ import annotations

import typer

from urdftool.cli._common import (PackageOption, XacroArgOption, budgeted, fail_at, fail_config,
                                  joint_words, show, single_robot, warn)

FORMATS = ("text", "json", "csv")
METHODS = ("auto", "numeric", "closed-form")
SEEDS = 16  # as urdftool.kinematics.ik.SEEDS (not imported here: it loads numpy)


def register(app: typer.Typer) -> None:
    app.command("ik", help="Inverse kinematics: joint values that put --tip at a pose relative "
                           "to --base; --check-reach FILE: which targets the limb reaches."
                )(budgeted(ik))


Triple = tuple[float, float, float]
# the limb, as ik and workspace name it
TipOption = typer.Option(..., "--tip", metavar="LINK", help="The end of the limb.")
BaseOption = typer.Option(None, "--base", metavar="LINK",
                          help="Poses are relative to this link (default: the root).")
PointOption = typer.Option(None, "--point", metavar="X Y Z",
                           help="The point [m] in --tip's frame to place (default: its origin).")


def ik(
    words: list[str] = typer.Argument(..., metavar="FILE [NAME:=VALUE...]"),
    tip: str = TipOption,
    base: str = BaseOption,
    point: Triple = PointOption,
    xyz: Triple = typer.Option(None, "--xyz", metavar="X Y Z", help="Target position [m]."),
    rpy: Triple = typer.Option(None, "--rpy", metavar="R P Y",
                               help="Target orientation (fixed X, Y, Z as in URDF) [rad]; "
                                    "without --rpy or --quat: position only."),
    quat: tuple[float, float, float, float] = typer.Option(
        None, "--quat", metavar="X Y Z W", help="Target orientation as a quaternion."),
    target_frame: str = typer.Option(None, "--target-frame", metavar="LINK",
                                     help="Target: the pose of LINK at --target-q."),
    target_q: list[str] = typer.Option([], "--target-q", metavar="JOINT=VALUE",
                                       help="With --target-frame: the configuration it is at."),
    targets: str = typer.Option(None, "--targets", metavar="FILE",
                                help="Many targets: CSV or JSON with x, y, z and optionally "
                                     "roll, pitch, yaw or qx, qy, qz, qw."),
    check_reach: str = typer.Option(None, "--check-reach", metavar="FILE",
                                    help="Which targets of FILE (as --targets) are reachable; "
                                         "exit 1 if one is not."),
    q: list[str] = typer.Option([], "--q", metavar="JOINT=VALUE",
                                help="Joint value (repeatable): the first seed, and where the "
                                     "joints off the limb stay (a planar joint's as JOINT.x, "
                                     ".y, .yaw; a limb through one is refused: choose a --base "
                                     "below it)."),
    deg: bool = typer.Option(False, "--deg", help="Angles (--q, --rpy, files) in degrees."),
    seeds: int = typer.Option(SEEDS, "--seeds", metavar="N",
                              help="Starting points: --q, then N-1 random ones in limits."),
    seed: int = typer.Option(0, "--seed", help="Seed of the random starting points."),
    tol: float = typer.Option(1e-6, "--tol", help="Solved within this [m] and [rad]."),
    iterations: int = typer.Option(100, "--iterations", metavar="N",
                                   help="Iterations per starting point."),
    method: str = typer.Option("auto", "--method",
                               help="auto (closed form for planar 2-3 joint limbs and 6-joint "
                                    "arms with a spherical wrist, else "
                                    "numeric), numeric or closed-form."),
    output_format: str = typer.Option("text", "--format", "-f", help="text, json or csv."),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
) -> None:
    from urdftool.errors import ConfigError, FKError, IKError, UnknownName
    from urdftool.kinematics.ik import solve_limb
    from urdftool.report import ik as render

    sources = [xyz is not None, target_frame is not None, targets is not None,
               check_reach is not None]
    robot = single_robot("ik", words, arg, package, {"--format": (output_format, FORMATS),
                                                     "--method": (method, METHODS)}, (
        (sum(sources) != 1, "give one target: --xyz, --target-frame, --targets or --check-reach"),
        (rpy is not None and quat is not None, "give --rpy or --quat, not both"),
        ((rpy is not None or quat is not None) and xyz is None, "--rpy and --quat need --xyz"),
        (bool(target_q) and target_frame is None, "--target-q needs --target-frame"),
        (seeds < 1, "--seeds must be at least 1"),
        (iterations < 1, "--iterations must be at least 1"),
        (not tol > 0, "--tol must be more than 0")))
    given = joint_words(q, "--q")
    frame_q = joint_words(target_q, "--target-q")
    try:
        found = solve_limb(robot, tip, base, point, given, xyz=xyz, rpy=rpy, quaternion=quat,
                           frame=target_frame, frame_q=frame_q,
                           targets_file=targets or check_reach,
                           name=f"{target_frame} at --target-q" if target_frame else "",
                           degrees=deg, seeds_count=seeds, seed=seed, tolerance=tol,
                           iterations=iterations, method=method.replace("-", " "))
    except ConfigError as error:
        fail_config(error, {"q": "--q", "xyz": "--xyz", "orientation": "--quat", "frame_q": "--target-q",
                            "point": "--point",
                            "targets": "--targets" if targets else "--check-reach"
                            }[error.argument])
    except (FKError, IKError, UnknownName) as error:
        fail_at(robot, error)
    warn(found.warnings)
    chain, solutions = found.chain, _Tally(found.solutions)
    # each target solved as its output is written: what is held is one target's, whatever the
    # targets of a file (every solution and the whole text were held until the end); one
    # target is solved first, and --method closed-form's warning said before its output
    warned = found.count == 1 and solutions.hold() and _closed_form_warning(method, solutions)
    if output_format == "json":
        from urdftool.report.json_output import write_json, write_json_list

        documents = (render.as_dict(chain, s, given) for s in solutions)
        if xyz is not None or target_frame:
            write_json(next(documents))
            for _ in documents:  # (none: one target)
                pass
        else:
            write_json_list(documents)
    else:
        pieces = render.csv_text(chain, solutions) if output_format == "csv" else \
            render.reach_text(chain, solutions, tol) if check_reach else \
            render.text(chain, solutions, given)
        for piece in pieces:
            show(piece, nl=False)
    if not warned:
        _closed_form_warning(method, solutions)
    raise typer.Exit(0 if solutions.solved == solutions.count else 1)


def _closed_form_warning(method: str, solutions: "_Tally") -> bool:
    """Warn when --method closed-form solved targets numerically; True (said or not)."""
    if method == "closed-form" and solutions.numeric:
        which = "the target was" if solutions.count == 1 else \
            f"{solutions.numeric} of {solutions.count} targets were"
        warn([f"--method closed-form: {which} solved numerically: the closed form takes a "
              "planar limb of 2 parallel revolute joints (3 given an orientation), or a 6-joint "
              "arm with a spherical wrist given an orientation, and a branch of it within the "
              "limits"])
    return True


class _Tally:
    """The solutions as they are solved, counted: how many, how many solved, how many
    numerically (the exit status and --method closed-form's warning, said after them)."""

    def __init__(self, solutions):
        self._solutions, self.count, self.solved, self.numeric = solutions, 0, 0, 0
        self._held = None

    def hold(self) -> bool:
        """Solve every target now (one), counted, and keep the solutions; True."""
        self._held = list(self)
        return True

    def __iter__(self):
        if self._held is not None:
            yield from self._held
            return
        for solution in self._solutions:
            self.count += 1
            self.solved += bool(solution.solved)
            self.numeric += solution.method != "closed form"
            yield solution
