"""``urdftool fk``: link poses as text tables, JSON or CSV, and the D-H check's verdict."""

from __future__ import annotations

import sys

from urdftool.numbers import exact, fixed_texts, number
from urdftool.report.console import plain_tables, print_table, wide_console, write_table


def verify_line(count: int, seed, position: float, rotation: float, tolerance: float) -> str:
    """The verdict of comparing D-H and URDF forward kinematics; errors in [m] and [rad]."""
    ok = position <= tolerance and rotation <= tolerance
    return (f"D-H vs URDF over {count} random configurations (seed {seed}): worst position "
            f"error {number(position, 3)} m, worst orientation error {number(rotation, 3)} rad: "
            f"{'agree' if ok else 'DISAGREE'} (tolerance {number(tolerance, 6)})")


def write_poses(result, output_format: str, matrix: bool, single: bool, stream=None,
                drawn=None) -> None:
    """``result`` (urdftool.kinematics.fk.FKResult or PoseBlocks) in ``output_format``: text,
    json or csv, a block of rows at a time (``result.blocks()``): what is held is one block's
    poses and texts, whatever the rows (12,000 rows of a 300-link chain held every pose and its
    text at once: out of memory).

    matrix: also each pose as a 4x4 matrix; single: JSON gives one document, not a list;
    drawn: (variable names, values [rows, variables], seed) of random configurations, written
    with each pose (full precision: ``--q NAME=VALUE`` with them gives the pose again)
    """
    stream = stream or sys.stdout
    if output_format == "json":
        from urdftool.report.json_output import write_json, write_json_list

        documents = _documents(result, matrix, drawn)
        if single:
            write_json(next(documents), stream)
        else:
            write_json_list(documents, stream)
    elif output_format == "csv":
        _csv(result, matrix, stream, drawn)
    else:
        _text(result, matrix, drawn)


def _documents(result, matrix: bool, drawn):
    """Each configuration's JSON document, a block's computed at a time."""
    from urdftool.kinematics.fk import pose_components

    for start, matrices in result.blocks():
        positions, rpys, quaternions = pose_components(matrices)
        # Python floats in one conversion per array, not three per pose
        lists = [positions.tolist(), rpys.tolist(), quaternions.tolist(),
                 matrices.tolist() if matrix else None]
        for row in range(len(positions)):
            document = {"base": result.base, "frames": [
                _frame_entry(name, lists[0][row][k], lists[1][row][k], lists[2][row][k],
                             lists[3][row][k] if matrix else None)
                for k, name in enumerate(result.frames)]}
            if drawn is not None:
                names, values, seed = drawn
                document["seed"] = seed
                document["q"] = {name: float(v) for name, v in zip(names, values[start + row])}
            yield document


def _frame_entry(name, position, rpy, quaternion, matrix) -> dict:
    """One frame's pose in a JSON document (lists of floats)."""
    entry = {"frame": name, "position": position, "rpy": rpy, "quaternion": quaternion}
    if matrix is not None:
        entry["matrix"] = matrix
    return entry


def _drawn_words(drawn, row: int) -> str:
    """``--q NAME=VALUE ...`` of a drawn configuration, every value at full precision."""
    names, values, _ = drawn
    import shlex

    return " ".join(f"--q {shlex.quote(f'{name}={exact(v)}')}"
                    for name, v in zip(names, values[row]))


def _csv(result, matrix, stream, drawn=None) -> None:
    import csv

    import numpy as np

    from urdftool.kinematics.fk import pose_components
    from urdftool.report.escape import csv_cell

    header = ["row", "base", "frame", "x", "y", "z", "roll", "pitch", "yaw",
              "qx", "qy", "qz", "qw"]
    if matrix:
        header += [f"m{i}{j}" for i in range(3) for j in range(4)]
    if drawn is not None:
        header += [csv_cell(name) for name in drawn[0]]  # the values drawn, a column each
    writer = csv.writer(stream, lineterminator="\n")
    writer.writerow(header)
    base, names = csv_cell(result.base), [csv_cell(name) for name in result.frames]
    for start, matrices in result.blocks():
        numbers = np.concatenate(pose_components(matrices), axis=-1)
        if matrix:
            numbers = np.concatenate([numbers, matrices[..., :3, :].reshape(
                numbers.shape[:2] + (12,))], axis=-1)
        drawn_values = (drawn[1][start:start + len(matrices)] + 0.0).tolist() \
            if drawn is not None else None
        # Python floats in one conversion, zeros unsigned at once (+ 0.0): repr of each is then
        # numbers.exact's text, without a call per cell (a million cells at 10,000 rows)
        for row, poses in enumerate((numbers + 0.0).tolist()):
            joints = list(map(repr, drawn_values[row])) if drawn is not None else []
            writer.writerows([start + row + 1, base, name, *map(repr, pose), *joints]
                             for name, pose in zip(names, poses))


HEADERS = ["frame", "x [m]", "y [m]", "z [m]", "roll [rad]", "pitch [rad]", "yaw [rad]",
           "qx [-]", "qy [-]", "qz [-]", "qw [-]"]


def _text(result, matrix, drawn=None) -> None:
    import numpy as np

    from urdftool.kinematics.fk import pose_components
    from urdftool.report.escape import markup, text

    # plain past a long table's worth of rows in all: 10,000 configurations are 10,000 tables
    plain = plain_tables(len(result.frames) * result.rows)
    console = None if plain else wide_console()
    columns = len(HEADERS) - 1
    per_row = columns * len(result.frames)
    names = [text(name) for name in result.frames] if matrix else None  # escaped once
    for start, matrices in result.blocks():
        # every number of a block's tables formatted at once (numbers.fixed_texts), as fixed()
        # would
        cells = fixed_texts(np.concatenate(pose_components(matrices), axis=-1).ravel().tolist())
        if matrix:  # 16 numbers a frame, formatted at once too
            entries = fixed_texts(matrices.ravel().tolist())
        for at in range(len(matrices)):
            row = start + at
            title = f"poses relative to {result.base}" + (
                f" (configuration {row + 1})" if result.rows > 1 else "")
            first = at * per_row
            rows = [[name, *cells[first + k * columns:first + (k + 1) * columns]]
                    for k, name in enumerate(result.frames)]
            drawn_line = None if drawn is None else (
                f"configuration {row + 1} (--random, --seed {drawn[2]}): "
                f"{_drawn_words(drawn, row)}")
            if plain:
                out = sys.stdout
                if drawn_line is not None:
                    out.write(text(drawn_line) + "\n")
                write_table(out, title, HEADERS, rows)
                if matrix:
                    _plain_matrices(names, entries, at * 16 * len(names), out)
                continue
            if drawn_line is not None:
                console.print(markup(drawn_line), soft_wrap=True)
            print_table(console, title, HEADERS, rows)
            if matrix:
                for k, name in enumerate(result.frames):
                    console.print(f"{markup(name)}:")
                    entry = (at * len(result.frames) + k) * 16
                    for line in range(4):
                        console.print(_matrix_line(entries[entry + 4 * line:entry + 4 * line + 4]))


def _matrix_line(texts) -> str:
    """One row of a 4x4 pose matrix (its four numbers as fixed() writes them), as both table
    styles print it."""
    return "  " + " ".join(f"{entry:>9s}" for entry in texts)


def _plain_matrices(names: list[str], entries: list[str], start: int, stream) -> None:
    """One configuration's 4x4 matrices: each frame's (escaped) name, then its four rows, from
    ``entries[start:]`` (16 texts a frame)."""
    lines = []
    for k, name in enumerate(names):
        lines.append(f"{name}:")
        at = start + 16 * k
        lines += [_matrix_line(entries[at + 4 * line:at + 4 * line + 4]) for line in range(4)]
    stream.write("\n".join(lines) + "\n")
