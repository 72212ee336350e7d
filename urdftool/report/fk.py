"""``urdftool fk``: link poses as text tables, JSON or CSV, and the D-H check's verdict."""

from __future__ import annotations

import sys

from urdftool.report.console import fixed, print_table, wide_console


def verify_line(count: int, seed, position: float, rotation: float, tolerance: float) -> str:
    """The verdict of comparing D-H and URDF forward kinematics; errors in [m] and [rad]."""
    ok = position <= tolerance and rotation <= tolerance
    return (f"D-H vs URDF over {count} random configurations (seed {seed}): worst position "
            f"error {position:.3g} m, worst orientation error {rotation:.3g} rad: "
            f"{'agree' if ok else 'DISAGREE'} (tolerance {tolerance:g})")


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
    return " ".join(f"--q {name}={float(v)!r}" for name, v in zip(names, values[row]))


def _csv(result, positions, rpys, quaternions, matrix, stream, drawn=None) -> None:
    import csv

    import numpy as np

    header = ["row", "base", "frame", "x", "y", "z", "roll", "pitch", "yaw",
              "qx", "qy", "qz", "qw"]
    if matrix:
        header += [f"m{i}{j}" for i in range(3) for j in range(4)]
    if drawn is not None:
        header += drawn[0]  # the joint values drawn, one column per variable
    writer = csv.writer(stream, lineterminator="\n")
    writer.writerow(header)
    numbers = np.concatenate([positions, rpys, quaternions], axis=-1)
    if matrix:
        numbers = np.concatenate([numbers, result.matrices[..., :3, :].reshape(
            numbers.shape[:2] + (12,))], axis=-1)
    for row in range(len(numbers)):
        joints = [repr(float(v)) for v in drawn[1][row]] if drawn is not None else []
        for k, name in enumerate(result.frames):
            writer.writerow([row + 1, result.base, name,
                             *(repr(float(v)) for v in numbers[row, k]), *joints])


HEADERS = ["frame", "x [m]", "y [m]", "z [m]", "roll [rad]", "pitch [rad]", "yaw [rad]",
           "qx [-]", "qy [-]", "qz [-]", "qw [-]"]


def _text(result, positions, rpys, quaternions, matrix, drawn=None) -> None:
    from rich.markup import escape

    console = wide_console()
    for row in range(len(positions)):
        title = f"poses relative to {result.base}" + (
            f" (configuration {row + 1})" if len(positions) > 1 else "")
        if drawn is not None:
            console.print(escape(f"configuration {row + 1} (--random, --seed {drawn[2]}): "
                                 f"{_drawn_words(drawn, row)}"), soft_wrap=True)
        print_table(console, title, HEADERS, [
            [name, *(fixed(v) for v in (*positions[row, k], *rpys[row, k], *quaternions[row, k]))]
            for k, name in enumerate(result.frames)])
        if matrix:
            for k, name in enumerate(result.frames):
                console.print(f"{escape(name)}:")
                for line in result.matrices[row, k]:
                    console.print("  " + " ".join(f"{v: .6f}" for v in line))
