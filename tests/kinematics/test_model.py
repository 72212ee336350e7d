"""Pinocchio models are parsed on a stack sized for the robot, errors raised in the caller."""

from __future__ import annotations

import threading

import pytest

from conftest import synthetic_robot
from urdftool.description.load import load
from urdftool.kinematics import model


def test_the_parse_runs_on_a_stack_sized_for_the_links(tmp_path, monkeypatch):
    robot = load(str(synthetic_robot(tmp_path, 50)))
    sizes, threads = [], []
    real_size, real_start = threading.stack_size, threading.Thread.start
    monkeypatch.setattr(threading, "stack_size", lambda *size: sizes.append(size) or real_size(*size))
    monkeypatch.setattr(threading.Thread, "start",
                        lambda self: threads.append(self.name) or real_start(self))
    built = model.build_model(robot)
    assert built.njoints == 50
    assert threads == ["pinocchio-urdf"]
    assert sizes[0] == (model.stack_size(50),) and sizes[0][0] >= 64 * 1024 * 1024
    assert threading.stack_size() == 0  # put back for the threads that follow


def test_the_stack_grows_with_the_depth_well_past_what_overflowed():
    # ~1.6 kB a level measured: 5,000 levels overflowed the 8 MB main stack
    assert model.stack_size(10_000) >= 10_000 * 1600 * 4


def test_a_parse_error_is_raised_in_the_caller(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_text('<robot name="r"><link name="a"/><joint name="j" type="revolute">'
                    '<parent link="a"/><child link="nowhere"/></joint></robot>')
    with pytest.raises((ValueError, RuntimeError)):
        model.build_model(load(str(path)))
