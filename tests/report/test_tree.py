"""``urdftool tree``'s listing, as check_urdf prints it."""

from __future__ import annotations

import pytest

from urdftool.description.load import load
from urdftool.kinematics.tree import TreeError
from urdftool.report.tree import tree_text


def _robot(tmp_path, joints: str):
    path = tmp_path / "r.urdf"
    path.write_text('<robot name="r"><link name="base"/><link name="a"/><link name="b"/>'
                    f'{joints}</robot>')
    return load(str(path))


def test_children_listed_by_joint_name_at_each_depth(tmp_path):
    robot = _robot(tmp_path, '<joint name="z" type="fixed"><parent link="base"/>'
                             '<child link="a"/></joint><joint name="y" type="fixed">'
                             '<parent link="base"/><child link="b"/></joint>')
    assert tree_text(robot) == ("robot name is: r\n"
                                "---------- Successfully Parsed XML ---------------\n"
                                "root Link: base has 2 child(ren)\n"
                                "    child(1):  b\n"
                                "    child(2):  a\n")


def test_several_roots_are_a_tree_error(tmp_path):
    with pytest.raises(TreeError, match="3 root links"):
        tree_text(_robot(tmp_path, ""))


def test_a_3000_link_chain_is_listed_without_recursion(tmp_path):
    from conftest import synthetic_robot

    robot = load(str(synthetic_robot(tmp_path, 3000)))
    lines = tree_text(robot).splitlines()
    assert len(lines) == 3 + 2999
    assert lines[3 + 63] == "    " * 64 + "child(1):  l64"  # check_urdf's, as deep as robots go
    assert lines[-1] == "    " * 64 + "[depth 2999] child(1):  l2999"


def test_a_deep_chain_is_listed_in_space_that_grows_with_its_links_not_their_square(tmp_path):
    """A 30,000-link chain (3 MB) was 1.8 GB of indentation: out of memory (U018)."""
    from conftest import synthetic_robot

    robot = load(str(synthetic_robot(tmp_path, 4000)))
    listing = tree_text(robot)
    assert max(map(len, listing.splitlines())) < 4 * 64 + 40
    assert len(listing) < 4000 * (4 * 64 + 40)


def test_a_cycle_below_the_root_is_listed_once(tmp_path):
    robot = _robot(tmp_path, '<joint name="j1" type="fixed"><parent link="base"/><child link="a"/>'
                             '</joint><joint name="j2" type="fixed"><parent link="a"/>'
                             '<child link="b"/></joint><joint name="j3" type="fixed">'
                             '<parent link="b"/><child link="a"/></joint>')
    assert tree_text(robot).splitlines()[3:] == ["    child(1):  a", "        child(1):  b",
                                                 "            child(1):  a"]
