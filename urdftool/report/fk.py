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


def write_poses(result, output_format: str, matrix: bool, single: bool, stream=None) -> None:
    """``result`` (urdftool.kinematics.fk.FKResult) in ``output_format``: text, json or csv.

    matrix: also each pose as a 4x4 matrix; single: JSON gives one document, not a list
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
        write_json(documents[0] if single else documents, stream)
    elif output_format == "csv":
        _csv(result, positions, rpys, quaternions, matrix, stream)
    else:
        _text(result, positions, rpys, quaternions, matrix)


def _frame_entry(name, position, rpy, quaternion, matrix) -> dict:
    entry = {"frame": name, "position": position.tolist(), "rpy": rpy.tolist(),
             "quaternion": quaternion.tolist()}
    if matrix is not None:
        entry["matrix"] = matrix.tolist()
    return entry


def _csv(result, positions, rpys, quaternions, matrix, stream) -> None:
    import csv

    import numpy as np

    header = ["row", "base", "frame", "x", "y", "z", "roll", "pitch", "yaw",
              "qx", "qy", "qz", "qw"]
    if matrix:
        header += [f"m{i}{j}" for i in range(3) for j in range(4)]
    writer = csv.writer(stream, lineterminator="\n")
    writer.writerow(header)
    numbers = np.concatenate([positions, rpys, quaternions], axis=-1)
    if matrix:
        numbers = np.concatenate([numbers, result.matrices[..., :3, :].reshape(
            numbers.shape[:2] + (12,))], axis=-1)
    for row in range(len(numbers)):
        for k, name in enumerate(result.frames):
            writer.writerow([row + 1, result.base, name, *(repr(float(v)) for v in numbers[row, k])])


HEADERS = ["frame", "x [m]", "y [m]", "z [m]", "roll [rad]", "pitch [rad]", "yaw [rad]",
           "qx [-]", "qy [-]", "qz [-]", "qw [-]"]


def _text(result, positions, rpys, quaternions, matrix) -> None:
    plain = plain_tables(len(result.frames))
    console = None if plain else wide_console()
    for row in range(len(positions)):
        title = f"poses relative to {result.base}" + (
            f" (configuration {row + 1})" if len(positions) > 1 else "")
        rows = [[name, *(fixed(v) for v in (*positions[row, k], *rpys[row, k],
                                            *quaternions[row, k]))]
                for k, name in enumerate(result.frames)]
        if plain:
            write_table(sys.stdout, title, HEADERS, rows)
            if matrix:
                _plain_matrices(result, row)
            continue
        print_table(console, title, HEADERS, rows)
        if matrix:
            from rich.markup import escape

            for k, name in enumerate(result.frames):
                console.print(f"{escape(name)}:")
                for line in result.matrices[row, k]:
                    console.print("  " + " ".join(f"{fixed(v):>9s}" for v in line))


def _plain_matrices(result, row: int) -> None:
    from urdftool.report.summary import printable

    lines = []
    for k, name in enumerate(result.frames):
        lines.append(f"{printable(name)}:")
        lines += ["  " + " ".join(f"{fixed(v):>9s}" for v in line) for line in result.matrices[row, k]]
    sys.stdout.write("\n".join(lines) + "\n")
