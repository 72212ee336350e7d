"""``urdftool dynamics``: mass, centre of mass, M(q), G(q), C(q, v), tau, gravity margins."""

from __future__ import annotations

import typer

from urdftool.cli._common import (PackageOption, UsageError, XacroArgOption, budgeted, fail_at,
                                  fail_config, fail_over_limit, fail_usage, joint_words,
                                  only_with, refuse_bad_outputs, show, single_robot, warn)


FORMATS = ("text", "json")
MAX_MATRIX_ROWS = 1000  # urdftool.physics.dynamics.MAX_MATRIX_SIZE (not imported: numpy)


def register(app: typer.Typer) -> None:
    app.command("dynamics", help="Mass, centre of mass, energies K, P, L, M(q), G(q), C(q,v), "
                                 "torques with damping and friction, with a fixed or a "
                                 "--floating base, standing on --support, and gravity margins "
                                 "against effort limits. The total mass and centre of mass "
                                 "count every link, the root link and the links fixed to it "
                                 "too (Pinocchio's computeTotalMass and centerOfMass leave "
                                 "those out: 'fixed_mass' in JSON).")(budgeted(dynamics))


def dynamics(
    words: list[str] = typer.Argument(..., metavar="FILE [NAME:=VALUE...]"),
    q: list[str] = typer.Option([], "--q", metavar="JOINT=VALUE", help="Joint position "
                                "(repeatable); others take 0, or mid-range when 0 is outside "
                                "their limits. A planar joint is three: JOINT.x, JOINT.y [m] "
                                "in its frame's xy plane and JOINT.yaw [rad] about its z; a "
                                "floating joint (and --floating's root_joint) six: JOINT.x, "
                                ".y, .z [m] and .roll, .pitch, .yaw [rad] (fixed axes, as "
                                "URDF's rpy)."),
    v: list[str] = typer.Option([], "--v", "--qd", metavar="JOINT=VALUE",
                                help="Joint velocity (for C, tau and the kinetic energy K); on "
                                     "a planar or floating joint's names (JOINT.x, ...) the "
                                     "child's twist in its own frame."),
    a: list[str] = typer.Option([], "--a", metavar="JOINT=VALUE", help="Joint acceleration."),
    deg: bool = typer.Option(False, "--deg", help="Angles in degrees (and deg/s, deg/s^2)."),
    samples: int = typer.Option(0, "--samples", metavar="N", help="Worst gravity torque per "
                                "joint over the joint ranges: N random poses within limits (and "
                                "the zero pose), then climbed from the worst to a maximum."),
    seed: int = typer.Option(0, "--seed", help="Random seed for --samples."),
    support: list[str] = typer.Option([], "--support", metavar="LINK",
                                      help="Standing on this link (repeatable: feet, wheels): "
                                           "torques with the ground carrying the robot, centre "
                                           "of mass against the support polygon; exit 1 when "
                                           "it tips over or a joint cannot hold."),
    plot: str = typer.Option(None, "--plot", metavar="FILE.png|svg",
                             help="With --support: the support polygon and centre of mass seen "
                                  "from above, as .svg or .png."),
    floating: bool = typer.Option(False, "--floating", help="A free-flying base: a free-flyer "
                                  "root joint 'root_joint' (as fk --floating), placed with --q "
                                  "root_joint.x/.y/.z/.roll/.pitch/.yaw; --v and --a on it are "
                                  "its twist in its own frame (x, y, z, then roll, pitch, yaw: "
                                  "about its x, y, z axes); its six rows are the force and "
                                  "moment on the base. A robot hung from a massless root by a "
                                  "floating joint of its own has that joint as its free base "
                                  "(JOINT.x, ...), held fixed without --floating."),
    output_format: str = typer.Option("text", "--format", "-f", help="text or json."),
    max_matrix_rows: int = typer.Option(MAX_MATRIX_ROWS, "--max-matrix-rows", min=0, metavar="N",
                                        help="Refuse, before any work, a robot with more joint "
                                             "velocities (rows of M(q) and C(q, v): memory and "
                                             "text grow with their square); 0 for no limit."),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
) -> None:
    from urdftool.errors import OverLimit, UnknownLink
    from urdftool.kinematics.configuration import ConfigError, joint_values
    from urdftool.physics.dynamics import DynamicsError, build, gravity_variables, state
    from urdftool.physics.gravity_bound import worst_loads
    from urdftool.report import dynamics as render

    robot = single_robot("dynamics", words, arg, package, {"--format": (output_format, FORMATS)},
                         [(samples < 0, "--samples must be 0 or more"),
                          (plot is not None and not support, "--plot needs --support"),
                          only_with(("seed",), samples > 0, "--samples"),
                          only_with(("deg",), bool(q or v or a), "--q, --v or --a"),
                          (plot is not None and not str(plot).lower().endswith((".svg", ".png")),
                           "--plot must end in .svg or .png"),
                          (floating and bool(support), "--floating does not go with --support "
                                                       "(standing frees the base itself)"),
                          (floating and samples > 0, "--floating does not go with --samples "
                                                     "(the gravity margins hold the base fixed; "
                                                     "a free base stands with --support)")])
    refuse_bad_outputs(plot, inputs=words)
    try:  # the question before the robot: a --support that names no link is the user's
        UnknownLink.unless_among(support, robot.links)
        model = build(robot, floating=floating,
                      max_rows=None if support else max_matrix_rows or None)
    except (DynamicsError, UnknownLink) as error:
        fail_at(robot, error)
    except OverLimit as error:  # (counted before the model is built)
        fail_over_limit(error, "--max-matrix-rows")
    if samples:
        from urdftool.errors import listed
        from urdftool.physics.dynamics import held_coordinates

        held = [model.variables[k].name for k in held_coordinates(model)]
        if held:
            warn([f"{listed(held)} {'has' if len(held) == 1 else 'have'} no range (the "
                  "coordinates of a planar or floating joint): held at 0 in every pose "
                  "--samples draws; the margins are over the ranges of the other joints"])
    given = {name: joint_words(values, f"--{name}") for name, values in (("q", q), ("v", v),
                                                                         ("a", a))}
    try:
        values = joint_values(robot, **given, degrees=deg, variables=model.variables)
    except ConfigError as error:
        fail_config(error, f"--{error.argument}")
    if support:
        _standing(robot, support, values, samples, seed, output_format, plot)
    try:
        result = state(model, values.q, values.v, values.a, max_matrix_rows or None)
    except OverLimit as error:
        fail_over_limit(error, "--max-matrix-rows")
    except DynamicsError as error:  # (a product of the values given past the float range)
        fail_usage(UsageError(f"--v, --a: {error}"))
    warn(values.warnings + result.warnings)
    loads = []
    if samples:
        from urdftool.report.progress import sampling_progress

        with sampling_progress(samples + 1, machine=output_format != "text") as moved:
            loads = worst_loads(model, samples, seed, progress=moved)
    if output_format == "json":
        from urdftool.report.json_output import write_json

        write_json(render.json_document(result, loads))
    else:
        # --samples alone asks for gravity margins: M and G at the zero pose would be noise
        least = render.weakest(loads)
        relevant = gravity_variables(model, least.joint) if least is not None else set()
        show(render.text(result, loads, samples, matrices=bool(q or v or a or not samples),
                               relevant=relevant), nl=False)
    raise typer.Exit(1 if any(load.holds is False for load in loads) else 0)


def _standing(robot, supports, values, samples, seed, output_format, plot) -> None:
    """``--support``: the robot standing on ``supports``; exits."""
    from urdftool.physics.statics import DynamicsError, build_standing, stand, standing_loads
    from urdftool.report import dynamics as render

    from urdftool.errors import UnknownName

    try:
        standing = build_standing(robot, supports)
    except (DynamicsError, UnknownName) as error:
        fail_at(robot, error)
    stance = stand(standing, values.q)
    warn(values.warnings + stance.warnings)
    standing_load = None
    if samples:
        from urdftool.report.progress import sampling_progress

        with sampling_progress(samples + 1, machine=output_format != "text") as moved:
            standing_load = standing_loads(standing, samples, seed, moved)
    loads = standing_load.loads if standing_load else []
    if plot:
        from urdftool.report.plot import write_items

        write_items(plot, *render.stance_picture(stance, f"{robot.name} standing on "
                                                         f"{', '.join(supports)}"))
    if output_format == "json":
        from urdftool.report.json_output import write_json

        document = stance.as_dict()
        document["gravity_loads"] = [load.as_dict() for load in loads]
        if standing_load:
            document["poses_standing"] = standing_load.stable
            document["poses_drawn"] = standing_load.poses
        write_json(document)
    else:
        show(render.stance_text(stance, standing_load), nl=False)
    holds = stance.holds and all(load.holds is not False for load in loads)
    raise typer.Exit(0 if stance.stands and holds else 1)
