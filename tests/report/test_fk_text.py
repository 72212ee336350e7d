"""``urdftool fk``'s text tables: every configuration's, as each is printed alone."""

from __future__ import annotations

import io
import sys

import numpy as np

from urdftool.kinematics import transforms
from urdftool.kinematics.fk import FKResult
from urdftool.report.fk import HEADERS, write_poses


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def _result(configurations: int, frames: int) -> FKResult:
    rng = np.random.default_rng(0)
    matrices = np.tile(np.eye(4), (configurations, frames, 1, 1))
    matrices[..., :3, :3] = transforms.rotation_from_rpy(
        rng.uniform(-3, 3, (configurations, frames, 3)))
    matrices[..., :3, 3] = rng.uniform(-1, 1, (configurations, frames, 3))
    matrices[0, 0, :3, 3] = (-1e-9, 0.0, -0.0)  # round-off: printed 0.000000, no minus
    return FKResult("base", [f"link_{k}" for k in range(frames)], matrices)


def _text(result: FKResult, monkeypatch) -> str:
    stream = _Terminal()
    monkeypatch.setattr(sys, "stdout", stream)
    write_poses(result, "text", matrix=False, single=False)
    return stream.getvalue()


def test_many_configurations_on_a_terminal_are_plain_tables(monkeypatch):
    """Twenty short tables are as long as one long one: plain text, not a rich table each
    (rich costs ~2 ms a row: 10,000 rows of a --q-file took seconds)."""
    def headers(text: str) -> int:  # write_table's header lines
        return sum(line.split()[:3] == ["frame", "x", "[m]"] for line in text.splitlines())

    many = _text(_result(20, 3), monkeypatch)
    assert headers(many) == 20
    assert many.count("poses relative to base (configuration ") == 20
    assert headers(_text(_result(1, 3), monkeypatch)) == 0  # one short table: rich's layout


def test_every_table_is_the_one_printed_alone(monkeypatch):
    """The numbers of all configurations, formatted at once, are those of each table printed
    by itself (urdftool.numbers.number with six places, round-off without its minus)."""
    from urdftool.report.console import fixed, write_table

    from urdftool.kinematics.fk import pose_components
    from urdftool.report.escape import text as escaped

    result = _result(60, 4)
    result.frames[1] = ":name"  # escaped (a line of its own cannot start with ':')
    positions, rpys, quaternions = pose_components(result.matrices)
    for matrix in (False, True):
        stream = _Terminal()
        monkeypatch.setattr(sys, "stdout", stream)
        write_poses(result, "text", matrix=matrix, single=False)
        expected = io.StringIO()
        for row in range(len(result.matrices)):
            rows = [[name, *(fixed(v) for v in (*positions[row, k], *rpys[row, k],
                                                 *quaternions[row, k]))]
                    for k, name in enumerate(result.frames)]
            write_table(expected, f"poses relative to base (configuration {row + 1})", HEADERS,
                        rows)
            for k, name in enumerate(result.frames) if matrix else ():
                expected.write(f"{escaped(name)}:\n" + "".join(
                    "  " + " ".join(f"{fixed(v):>9s}" for v in line) + "\n"
                    for line in result.matrices[row, k]))
        assert stream.getvalue() == expected.getvalue()
        assert "-0.000000" not in stream.getvalue() and "\n:name" not in stream.getvalue()
