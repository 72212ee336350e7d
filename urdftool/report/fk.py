"""``urdftool fk``: link poses as text tables, JSON or CSV, and the D-H check's verdict."""

from __future__ import annotations

import sys

from urdftool.numbers import number
from urdftool.report.console import fixed, plain_tables, print_table, wide_console, write_table


def verify_line(count: int, seed, position: float, rotation: float, tolerance: float) -> str:
    """The verdict of comparing D-H and URDF forward kinematics; errors in [m] and [rad]."""
    ok = position <= tolerance and rotation <= tolerance
    return (f"D-H vs URDF over {count} random configurations (seed {seed}): worst position "
            f"error {number(position, 3)} m, worst orientation error {number(rotation, 3)} rad: "
            f"{'agree' if ok else 'DISAGREE'} (tolerance {number(tolerance, 6)})")


def write_poses(result, output_format: str, matrix: bool, single: bool, stream=None,
                drawn=None) -> None:
    """``result`` (urdftool.kinematics.fk.FKResult) in ``output_format``: text, json or csv.

    matrix: also each pose as a 4x4 matrix; single: JSON gives one document, not a list;
    drawn: (variable names, values [rows, variables], seed) of random configurations, written
    with each pose (full precision: ``--q NAME=VALUE`` with them gives the pose again)
    """
    from urdftool.kinematics.fk import pose_components

    stream = stream or sys.stdout
    positions, rpys, quaternions = pose_components(result.matrices)
    if output_format == "json":
        from urdftool.report.json_output import write_json

        documents = [{"base": result.base, "frames": [
            _frame_entry(name, positions[row, k], rpys[row, k], quaternions[row, k],
                         result.matrices[row, k] if matrix else None)
            for k, name in enumerate(result.frames)]} for row in range(len(positions))]
        if drawn is not None:
            names, values, seed = drawn
            for row, document in enumerate(documents):
                document["seed"] = seed
                document["q"] = {name: float(v) for name, v in zip(names, values[row])}
        write_json(documents[0] if single else documents, stream)
    elif output_format == "csv":
        _csv(result, positions, rpys, quaternions, matrix, stream, drawn)
    else:
        _text(result, positions, rpys, quaternions, matrix, drawn)


def _frame_entry(name, position, rpy, quaternion, matrix) -> dict:
    entry = {"frame": name, "position": position.tolist(), "rpy": rpy.tolist(),
             "quaternion": quaternion.tolist()}
    if matrix is not None:
        entry["matrix"] = matrix.tolist()
    return entry


def _drawn_words(drawn, row: int) -> str:
    """``--q NAME=VALUE ...`` of a drawn configuration, every value at full precision."""
    names, values, _ = drawn
    import shlex

    return " ".join(f"--q {shlex.quote(f'{name}={float(v)!r}')}"
                    for name, v in zip(names, values[row]))


def _csv(result, positions, rpys, quaternions, matrix, stream, drawn=None) -> None:
    import csv

    import numpy as np

    from urdftool.report.escape import csv_cell

    header = ["row", "base", "frame", "x", "y", "z", "roll", "pitch", "yaw",
              "qx", "qy", "qz", "qw"]
    if matrix:
        header += [f"m{i}{j}" for i in range(3) for j in range(4)]
    if drawn is not None:
        header += [csv_cell(name) for name in drawn[0]]  # the values drawn, a column each
    writer = csv.writer(stream, lineterminator="\n")
    writer.writerow(header)
    numbers = np.concatenate([positions, rpys, quaternions], axis=-1)
    if matrix:
        numbers = np.concatenate([numbers, result.matrices[..., :3, :].reshape(
            numbers.shape[:2] + (12,))], axis=-1)
    for row in range(len(numbers)):
        joints = [repr(float(v)) for v in drawn[1][row]] if drawn is not None else []
        for k, name in enumerate(result.frames):
            writer.writerow([row + 1, csv_cell(result.base), csv_cell(name),
                             *(repr(float(v)) for v in numbers[row, k]), *joints])


HEADERS = ["frame", "x [m]", "y [m]", "z [m]", "roll [rad]", "pitch [rad]", "yaw [rad]",
           "qx [-]", "qy [-]", "qz [-]", "qw [-]"]


def _text(result, positions, rpys, quaternions, matrix, drawn=None) -> None:
    from urdftool.report.escape import markup, text

    plain = plain_tables(len(result.frames))
    console = None if plain else wide_console()
    for row in range(len(positions)):
        title = f"poses relative to {result.base}" + (
            f" (configuration {row + 1})" if len(positions) > 1 else "")
        rows = [[name, *(fixed(v) for v in (*positions[row, k], *rpys[row, k],
                                            *quaternions[row, k]))]
                for k, name in enumerate(result.frames)]
        drawn_line = None if drawn is None else (
            f"configuration {row + 1} (--random, --seed {drawn[2]}): {_drawn_words(drawn, row)}")
        if plain:
            out = sys.stdout
            if drawn_line is not None:
                out.write(text(drawn_line) + "\n")
            write_table(out, title, HEADERS, rows)
            if matrix:
                _plain_matrices(result, row, out)
            continue
        if drawn_line is not None:
            console.print(markup(drawn_line), soft_wrap=True)
        print_table(console, title, HEADERS, rows)
        if matrix:
            for k, name in enumerate(result.frames):
                console.print(f"{markup(name)}:")
                for line in result.matrices[row, k]:
                    console.print(_matrix_line(line))


def _matrix_line(line) -> str:
    """One row of a 4x4 pose matrix, as both table styles print it."""
    return "  " + " ".join(f"{fixed(v):>9s}" for v in line)


def _plain_matrices(result, row: int, stream=None) -> None:
    from urdftool.report.escape import text

    lines = []
    for k, name in enumerate(result.frames):
        lines.append(f"{text(name)}:")
        lines += [_matrix_line(line) for line in result.matrices[row, k]]
    stream = stream or sys.stdout
    stream.write("\n".join(lines) + "\n")
