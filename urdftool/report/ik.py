"""``urdftool ik``: joint values, residuals and verdicts as text, JSON or CSV."""

from __future__ import annotations

import math

from urdftool.numbers import exact, number, numbers
from urdftool.report.escape import csv_cell, text as _text
from urdftool.report.summary import counted


def q_words(chain, solution, given: dict[str, str] | None = None) -> str:
    """``--q NAME=VALUE`` words for ``urdftool fk``: the limb's values [rad or m] and the other
    joints the user set (``given``: {name: text as typed})."""
    scale = max([1.0, *(abs(float(value)) for value in solution.x)])  # [rad] or [m]
    limb = {v.name: number(value, 12, scale=scale)
            for v, value in zip(chain.variables, solution.x)}
    others = {name: text for name, text in (given or {}).items() if name not in limb}
    return " ".join(f"--q {name}={value}" for name, value in {**limb, **others}.items())


def _pose(matrix) -> str:
    from urdftool.kinematics.fk import pose_components

    position, rpy, _ = pose_components(matrix[None])
    return f"xyz ({numbers(position[0], 6)}) m, rpy ({numbers(rpy[0], 6)}) rad"


def _verdict(solution) -> str:
    residual = f"position {number(solution.position_error, 2)} m"
    if solution.target.rotation is not None:
        residual += f", orientation {number(solution.rotation_error, 2)} rad"
    return residual


def as_dict(chain, solution, given=None) -> dict:
    target = solution.target
    return {"target": target.name or None, "position": target.position.tolist(),
            "rotation": None if target.rotation is None else target.rotation.tolist(),
            "solved": bool(solution.solved), "method": solution.method,
            "joints": {v.name: float(value) for v, value in zip(chain.variables, solution.x)},
            "position_error": solution.position_error,
            "rotation_error": solution.rotation_error, "iterations": solution.iterations,
            "seeds": solution.seeds,
            "at_limits": [{"joint": name, "limit": side} for name, side in solution.at_limits],
            "pose": solution.pose.tolist(), "reason": solution.reason,
            "q_words": q_words(chain, solution, given)}


def text(chain, solutions, given=None):
    """One block per target: joint values, residuals, limits hit, the words for ``fk``; a
    target's lines at a time (``solutions``: an iterable, each solution written as it comes),
    then how many were solved."""
    width = max((len(_text(v.name)) for v in chain.variables), default=5)
    tip, base = _text(chain.tip), _text(chain.base)
    count = solved = 0
    for solution in solutions:
        head = f"{_text(solution.target.name)}: " if solution.target.name else ""
        mode = "position only" if solution.target.rotation is None else "position and orientation"
        lines = [f"{head}{tip} relative to {base} ({mode}, {solution.method}): "
                 + ("solved" if solution.solved else "UNREACHABLE")]
        lines.append(f"  {'joint':{width}s} {'value':>12s} {'[deg]':>9s} {'lower':>9s} "
                     f"{'upper':>9s}")
        for variable, value in zip(chain.variables, solution.x):
            degrees = f"{number(math.degrees(value), places=3):>9s}" if variable.angular \
                else " " * 9
            lines.append(f"  {_text(variable.name):{width}s} {number(value, places=6):>12s} "
                         f"{degrees} {number(variable.lower):>9s} {number(variable.upper):>9s}")
        lines.append(f"  residual: {_verdict(solution)}; {solution.iterations} iterations, "
                     f"{solution.seeds} seed{'s' if solution.seeds != 1 else ''}")
        if solution.at_limits:
            lines.append("  at a limit: " + ", ".join(f"{_text(name)} ({side})"
                                                       for name, side in solution.at_limits))
        if not solution.solved:
            lines.append(f"  closest pose reached: {_pose(solution.pose)}")
            lines.append(f"  why: {_text(solution.reason)}")
        lines.append(f"  fk: {_text(q_words(chain, solution, given))}")
        yield ("\n" if count else "") + "\n".join(lines) + "\n"  # (a blank line between)
        count, solved = count + 1, solved + bool(solution.solved)
    if count > 1:
        yield f"\n{solved} of {count} targets solved\n"
    elif not count:
        yield "\n"


def csv_text(chain, solutions):
    """The header, then a target's row at a time (``solutions``: an iterable)."""
    import csv
    import io

    stream = io.StringIO()
    writer = csv.writer(stream, lineterminator="\n")
    writer.writerow(["target", "solved", "position_error", "rotation_error", "iterations",
                     *(csv_cell(v.name) for v in chain.variables)])
    for number, solution in enumerate(solutions, start=1):
        writer.writerow([csv_cell(solution.target.name) if solution.target.name else number,
                         int(solution.solved),
                         exact(solution.position_error), exact(solution.rotation_error),
                         solution.iterations, *(exact(v) for v in solution.x)])
        yield stream.getvalue()
        stream.seek(0)
        stream.truncate()
    yield stream.getvalue()  # (the header alone, without targets)


def reach_text(chain, solutions, tolerance: float):
    """``--check-reach``: one line per target, reachable or not, with its residual, a line at a
    time (``solutions``: an iterable), then how many are reachable."""
    yield (f"reach of {_text(chain.tip)} relative to {_text(chain.base)} "
           f"({counted(len(chain.variables), 'joint')}), tolerance {number(tolerance, 6)}:\n")
    count = reached = 0
    for solution in solutions:
        x, y, z = solution.target.position
        verdict = "reachable" if solution.solved else "UNREACHABLE"
        line = (f"  {_text(solution.target.name):12s} ({numbers((x, y, z))}) {verdict:11s} "
                f"{_verdict(solution)}")
        if not solution.solved:
            line += f"; {_text(solution.reason)}"
        yield line + "\n"
        count, reached = count + 1, reached + bool(solution.solved)
    yield f"{reached} of {count} targets reachable\n"
