"""The SDF gz sdf -p prints, read into what crosscheck compares."""

from __future__ import annotations

import math

from urdftool.crosscheck.sdf import model_summary


def _chain(count: int, leaf_first: bool) -> str:
    order = range(count - 1, -1, -1) if leaf_first else range(count)
    links = "".join(f'<link name="l{i}"><pose>0 0 0 0 0 0</pose></link>' for i in order)
    joints = "".join(f'<joint name="j{i}" type="revolute"><parent>l{i - 1}</parent><child>l{i}</child>'
                     f'<pose>0 0 0.01 0 0 0</pose><axis><xyz>0 0 1</xyz></axis></joint>' for i in order if i)
    return f'<sdf version="1.7"><model name="m">{links}{joints}</model></sdf>'


def test_a_chain_longer_than_the_recursion_limit_is_placed():
    """Each link was placed by recursion up its parents: a 3,000-link chain whose links are
    written leaf first ended in RecursionError. Placed in a loop, in either order."""
    for leaf_first in (False, True):
        summary = model_summary(_chain(3000, leaf_first), [{}, {"j1": math.pi / 2}])
        assert summary["loaded"] and summary["dof"] == 2999 + 6
        zero, turned = summary["frames"]
        assert math.isclose(zero["l2999"][2], 29.99) and math.isclose(turned["l2999"][2], 29.99)
        assert zero["l0"] == [0.0, 0.0, 0.0]
