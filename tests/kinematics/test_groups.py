"""MoveIt planning groups: which joints a group stands for, and why a chain solver refuses it."""

from __future__ import annotations

from lxml import etree

from urdftool.description.load import load
from urdftool.kinematics.groups import ASSUMED_ROOT, Tree, groups, serial_problems

# base -> torso -> {l_arm -> l_hand, r_arm -> r_hand}; cam fixed on torso
ROBOT = """<robot name="r">
  <link name="base"/><link name="torso"/><link name="l_arm"/><link name="l_hand"/>
  <link name="r_arm"/><link name="r_hand"/><link name="cam"/>
  <joint name="waist" type="revolute"><parent link="base"/><child link="torso"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="l_sho" type="revolute"><parent link="torso"/><child link="l_arm"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="l_wri" type="continuous"><parent link="l_arm"/><child link="l_hand"/></joint>
  <joint name="r_sho" type="revolute"><parent link="torso"/><child link="r_arm"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="r_wri" type="prismatic"><parent link="r_arm"/><child link="r_hand"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="cam_joint" type="fixed"><parent link="torso"/><child link="cam"/></joint>
</robot>
"""


def model(tmp_path, srdf_body: str):
    path = tmp_path / "r.urdf"
    path.write_text(ROBOT)
    robot = load(str(path))
    root = etree.fromstring(f"<robot name='r'>{srdf_body}</robot>")
    return robot, Tree(robot, root), groups(robot, root)


def test_chain_kinds_follow_moveit(tmp_path):
    _, tree, _ = model(tmp_path, "")
    assert tree.chain("base", "l_hand") == ({"waist", "l_sho", "l_wri"}, "down")
    # backwards: MoveIt takes the tip's parent joint and the path down to the base
    assert tree.chain("l_hand", "torso") == ({"waist", "l_sho", "l_wri"}, "reversed")
    # across branches: both sides and the parent joint of the link where they meet
    assert tree.chain("l_hand", "r_hand") == ({"l_sho", "l_wri", "r_sho", "r_wri", "waist"}, "cross")
    assert tree.chain("torso", "torso") == (set(), "same")
    assert tree.joints[ASSUMED_ROOT].child == "base"


def test_links_subgroups_and_unknown_members(tmp_path):
    _, _, found = model(tmp_path, """<group name="a"><link name="l_arm"/><link name="base"/></group>
        <group name="b"><group name="a"/><joint name="r_sho"/></group>
        <group name="c"><group name="zz"/><joint name="waist"/></group>""")
    assert found["a"].joints == {"l_sho", ASSUMED_ROOT} and found["a"].complete
    assert found["b"].joints == {"l_sho", ASSUMED_ROOT, "r_sho"}
    assert found["c"].joints == {"waist"} and not found["c"].complete


def test_a_chain_of_subgroups_written_in_reverse_is_walked_without_recursion(tmp_path):
    """1,500 groups each holding the next one down, the deepest written last: the recursive
    walk ended every rule reading groups in RecursionError (U900 from U808, U809 and two
    more); cycles stay incomplete, as before."""
    chain = "".join(f'<group name="g{i}"><group name="g{i - 1}"/><link name="{link}"/></group>'
                    for i, link in zip(range(1499, 0, -1), ["cam", "l_hand"] * 750))
    cycle = ('<group name="x"><group name="y"/><joint name="waist"/></group>'
             '<group name="y"><group name="x"/><joint name="r_sho"/></group>')
    _, _, found = model(tmp_path, chain + '<group name="g0"><joint name="waist"/></group>' + cycle)
    assert found["g1499"].joints == {"waist", "cam_joint", "l_wri"} and found["g1499"].complete
    assert found["g1"].joints == {"waist", "cam_joint"} and found["g1"].complete
    assert found["x"].joints == {"waist", "r_sho"} and not found["x"].complete
    assert found["y"].joints == {"r_sho"} and not found["y"].complete


def shapes(tmp_path, body: str, name: str = "g"):
    robot, tree, found = model(tmp_path, body)
    return [(s.kind, s.message) for s in serial_problems(tree, found[name], robot.links)]


def test_a_serial_chain_has_no_problem(tmp_path):
    assert shapes(tmp_path, '<group name="g"><chain base_link="base" tip_link="l_hand"/></group>') == []
    assert shapes(tmp_path, '<group name="g"><link name="torso"/><link name="l_arm"/><link name="l_hand"/></group>') == []


def test_reversed_and_cross_branch_chains_name_their_links(tmp_path):
    [(kind, message)] = shapes(tmp_path, '<group name="g"><chain base_link="l_hand" tip_link="base"/></group>')
    assert kind == "reversed" and "'l_hand' is below tip_link 'base'" in message
    [(kind, message)] = shapes(tmp_path, '<group name="g"><chain base_link="l_hand" tip_link="r_hand"/></group>')
    assert kind == "cross" and "crosses branches at link 'torso'" in message


def test_gap_tree_and_multi_dof(tmp_path):
    [(kind, message)] = shapes(tmp_path, '<group name="g"><joint name="waist"/><joint name="l_wri"/></group>')
    assert kind == "gap" and "'torso' and 'l_arm'" in message and "'l_sho'" in message
    [(kind, message)] = shapes(tmp_path, '<group name="g"><link name="l_hand"/><link name="r_hand"/></group>')
    assert kind == "tree" and "at link 'torso' into 'l_hand', 'r_hand'" in message
    # a fixed side link branches too (MoveIt's isChain counts fixed joints)
    assert [k for k, _ in shapes(tmp_path, '<group name="g"><chain base_link="base" tip_link="l_arm"/><link name="cam"/></group>')] == ["tree"]
    body = ('<virtual_joint name="world" type="floating" parent_frame="w" child_link="base"/>'
            '<group name="g"><link name="base"/><link name="torso"/></group>')
    assert [k for k, _ in shapes(tmp_path, body)] == ["multi-dof"]
    assert [k for k, _ in shapes(tmp_path, '<group name="g"><link name="cam"/></group>')] == ["empty"]
