"""``urdftool.kinematics.tree``: the kinematic tree; here, a robot's own free base."""

from __future__ import annotations

import pytest

from conftest import load_text
from urdftool.kinematics.tree import own_free_base

BODY = ('<link name="body"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" '
        'ixy="0" ixz="0" iyz="0"/></inertial></link><link name="arm"/>'
        '<joint name="shoulder" type="revolute"><parent link="body"/><child link="arm"/>'
        '<axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>')
FREE = '<joint name="free" type="floating"><parent link="world"/><child link="body"/></joint>'


@pytest.mark.parametrize("world, joints, expected", [
    ('<link name="world"/>', FREE, "free"),  # a simulator's free body
    ('<link name="world"/>', FREE.replace("floating", "fixed"), None),  # welded
    # a root with a mass stays in the world: the floating joint frees what hangs from it only
    ('<link name="world"><inertial><mass value="5"/><inertia ixx="1" iyy="1" izz="1" ixy="0" '
     'ixz="0" iyz="0"/></inertial></link>', FREE, None),
    # a second joint below the root: the root carries more than the free body
    ('<link name="world"/><link name="post"/>', FREE + '<joint name="post_joint" type="fixed">'
     '<parent link="world"/><child link="post"/></joint>', None),
    ("", "", None),  # no world: the body is the root, its joints revolute
])
def test_own_free_base_is_the_floating_joint_of_a_massless_root(tmp_path, world, joints,
                                                                 expected):
    robot = load_text(tmp_path, f'<robot name="r">{world}{BODY}{joints}</robot>')
    assert own_free_base(robot) == expected
