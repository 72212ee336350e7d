"""``urdftool collisions`` for people (text) and programs (JSON): a pose, or the matrix."""

from __future__ import annotations

from collections import Counter

from urdftool.numbers import number
from urdftool.report.console import fixed, plain_console
from urdftool.report.escape import markup
from urdftool.report.summary import counted


def write_pose(robot_name: str, report, output_format: str, custom: bool, stream=None) -> None:
    """A PoseReport as ``output_format`` (text or json); custom: the configuration was given"""
    if output_format == "json":
        from urdftool.report.json_output import write_json

        write_json(pose_json(robot_name, report), stream)
    else:
        pose_text(robot_name, report, custom, stream)


def write_matrix(robot_name: str, outcome, output_format: str, all_pairs: bool = False,
                 written=(), stream=None) -> None:
    """A MatrixOutcome as ``output_format`` (text or json); see matrix_text"""
    if output_format == "json":
        from urdftool.report.json_output import write_json

        write_json(matrix_json(robot_name, outcome.matrix, outcome.stale), stream)
    else:
        matrix_text(robot_name, outcome.matrix, outcome.stale, all_pairs, written, stream)


def _notes(console, geometry_problems, visual_only) -> None:
    for problem in geometry_problems:
        console.print(f"{markup(problem.location)}: [yellow]warning[/] "
                      f"{markup(problem.message)}")
    if visual_only:
        console.print(f"[yellow]Links with a visual but no collision geometry[/] (they escape "
                      f"every check): {', '.join(map(markup, visual_only))}")


def _table(*headers):
    """A table whose cells never wrap (a name's blank would start a line of its own)."""
    from rich.table import Table

    table = Table(*headers, box=None, pad_edge=False)
    for column in table.columns:
        column.no_wrap = True
    return table


def _problems(problems) -> list[dict]:
    return [{"location": str(p.location), "message": p.message} for p in problems]


def pose_json(robot_name: str, report) -> dict:
    from urdftool.collision.pairs import TOUCHING

    return {"robot": robot_name, "q": report.q, "srdf": report.srdf,
            "touching_depth": TOUCHING,
            "colliding": [{**vars(c), "touching": c.touching} for c in report.colliding],
            "closest": [vars(c) for c in report.closest],
            "visual_only": report.visual_only,
            "problems": _problems(report.problems)}


def _depth(contact) -> str:
    """A colliding pair's depth [mm] as the table shows it: known, bounded or unknown."""
    if contact.depth is not None:
        return fixed(contact.depth * 1000, 2)
    if contact.depth_at_most is not None:
        return f"<= {fixed(contact.depth_at_most * 1000, 2)} (hulls)"
    return "? (flat mesh)"


def pose_text(robot_name: str, report, custom: bool, stream=None) -> None:
    """custom: the configuration was given (else it is the default one)"""
    console = plain_console(stream)
    where = "the given configuration" if custom else "the default configuration"
    console.print(f"[bold]{markup(robot_name)}[/] at {where} ({counted(len(report.q) if report.joints is None else report.joints, 'joint')}), "
                  f"SRDF: {markup(report.srdf or 'none')}")
    from urdftool.collision.pairs import TOUCHING

    touching = [c for c in report.colliding if c.allowed == "Adjacent"]
    listed = [c for c in report.colliding if c.allowed != "Adjacent"]
    if listed:
        table = _table("link 1", "link 2", "depth (mm)", "status")
        for c in listed:
            status = f"allowed ({c.allowed})" if c.allowed else \
                "touching" if c.touching else "[bold red]COLLIDING[/]"
            table.add_row(markup(c.link1), markup(c.link2), _depth(c), status)
        console.print(table)
        if any(c.depth is None and c.depth_at_most is not None for c in listed):
            console.print("<= (hulls): a non-convex mesh's contact, whose depth is not known "
                          "(FCL's contacts between triangles carry none): at most that of the "
                          "convex hulls, a collision unless the hulls only touch")
        if any(c.depth_at_most is None for c in listed):
            console.print("? (flat mesh): a mesh without volume, whose contact is a collision "
                          "of unknown depth")
        if any(c.allowed == "Welded" for c in listed):
            console.print("Welded: held together by fixed joints alone (one rigid body), so in "
                          "contact in every configuration, which no motion changes; MoveIt "
                          "checks the pair unless the SRDF disables it (its Setup Assistant "
                          "does, 'Default')")
        if any(c.allowed == "Closing" for c in listed):
            console.print("Closing: joined by a joint written in a <gazebo> block, which closes "
                          "a loop (a parallel robot's legs on their platform): Gazebo joins "
                          "them and does not collide them; the URDF's tree, and MoveIt, do not "
                          "know the joint: MoveIt checks the pair unless the SRDF disables it")
        if any(c.touching and not c.allowed for c in listed):
            console.print(f"touching: in contact at most {number(TOUCHING * 1000)} mm deep, "
                          "surfaces that meet, not a collision; MoveIt (FCL, padding 0) "
                          "counts the contact as one unless the SRDF disables the pair (its "
                          "Setup Assistant does, 'Default', for pairs in contact at the "
                          "default pose)")
    if touching:
        console.print(f"{len(touching)} adjacent pair(s) overlap at their joints (allowed): "
                      + ", ".join(f"{markup(c.link1)}/{markup(c.link2)}" for c in touching))
    if report.closest:
        console.print("Closest pairs apart:")
        table = _table("link 1", "link 2", "distance (mm)", "status")
        for c in report.closest:
            table.add_row(markup(c.link1), markup(c.link2), fixed(c.distance * 1000, 2),
                          f"disabled ({c.allowed})" if c.allowed else "")
        console.print(table)
    _notes(console, report.problems, report.visual_only)
    bad = report.forbidden
    if bad:
        console.print(f"[bold red]{len(bad)} colliding pair(s) not allowed by adjacency or the "
                      "SRDF[/]")
    elif report.problems:
        console.print(f"[bold red]not established[/]: no self-collision among the geometry "
                      f"checked, but {len(report.problems)} collision element(s) were left out "
                      "(above), and they may collide")
    else:
        meeting = sum(c.touching and not c.allowed for c in report.colliding)
        allowed = len(report.colliding) - meeting
        said = [f"{allowed} allowed contact(s)"] * bool(allowed) + \
            [f"{meeting} pair(s) touching"] * bool(meeting)
        console.print("[bold green]no self-collision[/]"
                      + (f" ({', '.join(said)})" if said else ""))


def matrix_json(robot_name: str, result, stale) -> dict:
    return {
        "robot": robot_name, "samples": result.samples, "seed": result.seed,
        "margin": result.margin, "min_fraction": result.min_fraction,
        "converged": result.converged,
        "rounds": [{"samples": n, "changed": c} for n, c in result.rounds],
        "unsettled": [{"link1": a, "link2": b, "first_half": x, "all": y}
                      for a, b, x, y in result.unsettled],
        "pairs": [{"link1": p.link1, "link2": p.link2, "class": p.reason or "enabled",
                   "collisions": p.collisions, "samples": p.samples,
                   "fraction": p.fraction, "min_distance": p.min_distance}
                  for p in result.pairs],
        "visual_only": result.visual_only,
        "problems": _problems(result.problems),
        "stale": _problems(stale),
    }


def matrix_text(robot_name: str, result, stale, all_pairs: bool = False, written=(),
                stream=None) -> None:
    """all_pairs: list every pair, not only those a planner must check; written: files made"""
    console = plain_console(stream)
    counts = Counter(p.reason for p in result.pairs)
    console.print(f"[bold]{markup(robot_name)}[/]: {len(result.links)} links with geometry, "
                  f"{len(result.pairs)} pairs, {result.samples} samples (seed {result.seed}, "
                  f"margin {result.margin * 1000:g} mm)")
    console.print("  " + ", ".join(f"{counts[c]} {c or 'enabled'}" for c in
                                  ("Adjacent", "Default", "Always", "Never", "")))
    shown = [p for p in result.pairs if all_pairs or p.reason in ("", "Default", "Always")]
    near = [p for p in result.pairs if p.reason == "" and p.collisions == 0]
    if shown:
        table = _table("link 1", "link 2", "class", "collisions", "min distance (mm)")
        for p in sorted(shown, key=lambda p: (-p.fraction, p.min_distance or 0)):
            distance = "" if p.min_distance is None else fixed(p.min_distance * 1000, 2)
            count = f"{p.collisions}/{p.samples}" if p.samples else ""
            table.add_row(markup(p.link1), markup(p.link2), p.reason or "enabled", count,
                          distance)
        console.print(table)
    if near:
        console.print(f"{len(near)} pair(s) never collided but came within the margin, so they "
                      "stay enabled (MoveIt would disable them as Never): "
                      + ", ".join(f"{markup(p.link1)}/{markup(p.link2)} "
                                  f"({fixed(p.min_distance * 1000, 1)} mm)"
                                  for p in near))
    for n, changed in result.rounds:
        console.print(f"after {n} samples: {changed} pair(s) changed class in the second half")
    if result.converged:
        console.print("[green]converged[/]: no pair changed class in the second half")
    else:
        console.print("[yellow]not converged[/]: " + ", ".join(
            f"{markup(a)}/{markup(b)} {x or 'enabled'} -> {y or 'enabled'}"
            for a, b, x, y in result.unsettled)
            + f"; these pairs are rare events: more samples (--until-converged, --max-samples) "
            "would settle them")
    _notes(console, result.problems, result.visual_only)
    for item in stale:
        console.print(f"{markup(item.location)}: [bold red]stale[/] {markup(item.message)}")
    for path in written:
        console.print(f"wrote {markup(path)}")
