"""``urdftool fk`` over a table of configurations: written a block of rows at a time, in memory
that does not grow with the rows, and the same bytes whatever the blocks."""

from __future__ import annotations

import io
import sys
import tracemalloc

import pytest

from urdftool.cli.fk import fk as fk_command
from urdftool.kinematics import fk as fk_module

MOVING, FIXED = 6, 60  # a chain of few variables and many frames: the poses outweigh the input


def _chain(tmp_path, rows: int):
    """A chain of MOVING revolute joints, each link carrying FIXED // MOVING fixed links, and a
    --q-file of ``rows`` configurations."""
    parts, parent = ['<robot name="chain">', '<link name="l0"/>'], "l0"
    for joint in range(1, MOVING + 1):
        parts.append(f'<link name="l{joint}"/><joint name="j{joint}" type="revolute">'
                     f'<parent link="{parent}"/><child link="l{joint}"/>'
                     f'<origin xyz="0.1 0.02 0.03" rpy="0.1 -0.2 0.3"/>'
                     f'<axis xyz="{("1 0 0", "0 1 0", "0 0 1")[joint % 3]}"/>'
                     '<limit lower="-3" upper="3" effort="1" velocity="1"/></joint>')
        for k in range(FIXED // MOVING):
            parts.append(f'<link name="f{joint}_{k}"/><joint name="x{joint}_{k}" type="fixed">'
                         f'<parent link="l{joint}"/><child link="f{joint}_{k}"/>'
                         f'<origin xyz="0.0{k} -0.01 0.2" rpy="0 0.{k} 0"/></joint>')
        parent = f"l{joint}"
    robot = tmp_path / "chain.urdf"
    robot.write_text("\n".join(parts + ["</robot>"]))
    table = tmp_path / f"q{rows}.csv"
    table.write_text(",".join(f"j{j}" for j in range(1, MOVING + 1)) + "\n" + "".join(
        ",".join(f"{((row * 7 + j * 3) % 11 - 5) * 0.37:.4f}" for j in range(1, MOVING + 1))
        + "\n" for row in range(rows)))
    return robot, table


class _Sink:
    """Standard output that keeps nothing: what is measured is what fk holds."""

    def __init__(self):
        self.written = 0

    def write(self, text: str) -> int:
        self.written += len(text)
        return len(text)

    def flush(self) -> None:
        pass

    def isatty(self) -> bool:
        return False


def _fk(robot, output_format: str, **options) -> None:
    """The fk command itself, in this process (no worker, no captured output)."""
    given = dict(q=[], deg=False, q_file=None, random=None, seed=0, frame=[], base=None,
                 matrix=False, floating=False, dh=None, verify=False, arg=[], package=[])
    given.update(options)
    fk_command([str(robot)], output_format=output_format, **given)


@pytest.mark.parametrize("output_format", ["text", "json", "csv"])
def test_memory_does_not_grow_with_the_rows(tmp_path, monkeypatch, output_format):
    """Ten times the rows, not ten times the memory: every pose of a --q-file and its text
    were held at once (12,000 rows of a 300-link chain: out of memory). Blocks of 5 rows
    here, so that both runs write many."""
    monkeypatch.setattr(fk_module, "POSES_PER_BLOCK", 5 * (FIXED + MOVING + 1), raising=False)
    peaks = []
    for rows in (20, 200):
        robot, table = _chain(tmp_path, rows)
        sink = _Sink()
        monkeypatch.setattr(sys, "stdout", sink)
        if not peaks:
            _fk(robot, output_format, q_file=str(table))  # (warmed: imports, caches)
        tracemalloc.start()
        try:
            _fk(robot, output_format, q_file=str(table), matrix=True)
            peaks.append(tracemalloc.get_traced_memory()[1])
        finally:
            tracemalloc.stop()
        assert sink.written > rows * (FIXED + MOVING) * 50
    assert peaks[1] < 2 * peaks[0], peaks


@pytest.mark.parametrize("options", [
    dict(q_file=True), dict(q_file=True, matrix=True, base="f3_2"),
    dict(random=23, seed=4, matrix=True), dict(random=9, frame=["l6", "f2_1"], base="l1"),
    dict(random=1)])
def test_the_same_bytes_whatever_the_blocks(tmp_path, monkeypatch, options):
    """Blocks of two rows (the fewest), of three, of five with one row left over (given to the
    block before: urdftool.kinematics.fk.block_ranges), and every row at once: the same text,
    JSON and CSV, to the last bit."""
    robot, table = _chain(tmp_path, 16)
    chosen = options.get("frame")
    frames = len(chosen) if chosen else FIXED + MOVING + 1
    if options.get("q_file"):
        options = {**options, "q_file": str(table)}
    for output_format in ("text", "json", "csv"):
        outputs = []
        for poses in (1, 3 * frames, 5 * frames, 10 ** 9):
            monkeypatch.setattr(fk_module, "POSES_PER_BLOCK", poses)
            stream = io.StringIO()
            monkeypatch.setattr(sys, "stdout", stream)
            _fk(robot, output_format, **options)
            outputs.append(stream.getvalue())
        assert outputs[0] == outputs[1] == outputs[2] == outputs[3], output_format
        rows = options.get("random") or 16  # (16 = 5 x 3 + 1 = 3 x 5 + 1: a row left over)
        assert len(outputs[0]) > 100 * rows  # (every row written)


def test_one_frame_of_a_long_chain_is_computed_a_block_of_its_joints_at_a_time(tmp_path,
                                                                               monkeypatch):
    """A block was sized by the frames written alone, while every joint's pose of its rows is
    computed and held on the way: 12,000 rows of a 300-joint chain at one --frame were one
    block of 460 MB. Each block now holds at most POSES_HELD_PER_BLOCK of them, and the poses
    are the same as in one block."""
    import numpy as np

    from conftest import synthetic_robot
    from urdftool.description.load import load
    from urdftool.kinematics import configuration as config

    model = fk_module.KinematicModel(load(str(synthetic_robot(tmp_path, 101))))
    configurations = config.random(model.variables, 1000, 3)
    whole = fk_module.forward_kinematics(model, configurations, ["l100"]).matrices
    monkeypatch.setattr(fk_module, "POSES_HELD_PER_BLOCK", 50 * 101, raising=False)
    blocks = fk_module.forward_kinematics_blocks(model, configurations, ["l100"])
    sizes = [len(poses) for _, poses in blocks.blocks()]
    assert sum(sizes) == 1000 and max(sizes) <= 50, sizes
    assert np.array_equal(np.concatenate([poses for _, poses in blocks.blocks()]), whole)
