"""The symmetry, conventions and inertials-against-geometry rules on malformed robots: each
reports what it can and never crashes (U900). Found by the fuzzer: a joint without a name in a
limb crashed U218-U220 (tests/fuzz/regressions/d8fab2f8a8fc)."""

from __future__ import annotations

import pytest

from urdftool.lint.engine import CheckOptions, Selection, load_and_check

CODES = ("U218", "U219", "U220", "U221", "U222", "U312", "U313", "U314", "U315", "U316",
         "U417", "U418", "U419", "U420", "U421", "U900")
LIMIT = '<limit lower="-1" upper="1" effort="1" velocity="1"/>'
LEGS = (f'<link name="torso"/>'
        f'<joint name="l_hip" type="revolute"><parent link="torso"/><child link="l_leg"/>'
        f'<origin xyz="0 0.1 0"/><axis xyz="1 0 0"/>{LIMIT}</joint><link name="l_leg"/>'
        f'<joint name="r_hip" type="revolute"><parent link="torso"/><child link="r_leg"/>'
        f'<origin xyz="0 -0.1 0"/><axis xyz="1 0 0"/>{LIMIT}</joint><link name="r_leg"/>'
        f'<joint name="l_knee" type="revolute"><parent link="l_leg"/><child link="l_shin"/>'
        f'<origin xyz="0 0 -0.3"/><axis xyz="0 1 0"/>{LIMIT}</joint><link name="l_shin"/>'
        f'<joint name="r_knee" type="revolute"><parent link="r_leg"/><child link="r_shin"/>'
        f'<origin xyz="0 0 -0.3"/><axis xyz="0 1 0"/>{LIMIT}</joint><link name="r_shin"/>')
WHEEL = ('<link name="{s}_wheel"><inertial><mass value="{m}"/><inertia ixx="{i}" ixy="0" ixz="0" '
         'iyy="{i}" iyz="0" izz="{i}"/></inertial><collision><origin rpy="{rpy}"/>'
         '<geometry><cylinder radius="{r}" length="0.02"/></geometry></collision></link>'
         '<joint name="{s}_wheel_joint" type="continuous"><parent link="{p}"/>'
         '<child link="{s}_wheel"/><origin xyz="0 {y} 0"/><axis xyz="{axis}"/></joint>')


@pytest.mark.parametrize("body", [
    # a joint without a name above the limbs (U103)
    f'<link name="base"/><joint type="revolute"><parent link="base"/><child link="torso"/>'
    f'<axis xyz="0 0 1"/>{LIMIT}</joint>' + LEGS,
    # a joint naming a link that does not exist, and one without a child
    LEGS + f'<joint name="l_foot" type="fixed"><parent link="l_shin"/><child link="nowhere"/></joint>'
           '<joint name="r_foot" type="fixed"><parent link="r_shin"/></joint>',
    # a cycle (U109)
    LEGS + '<joint name="l_back" type="fixed"><parent link="l_shin"/><child link="torso"/></joint>',
    # wheels with malformed numbers, a zero axis, NaN, a missing radius, a nameless link
    '<link name="base_footprint"/><link name="base_link"/><joint name="f" type="fixed">'
    '<parent link="base_footprint"/><child link="base_link"/><origin xyz="0 0 nan"/></joint>'
    + WHEEL.format(s="left", m="x", i="1", rpy="1.57 0 0", r="0.05", p="base_link", y="0.1",
                   axis="0 0 0")
    + WHEEL.format(s="right", m="1", i="nan", rpy="a b c", r="", p="base_link", y="-0.1",
                   axis="0 1 0") + '<link><inertial><mass value="1"/></inertial></link>',
    # a camera plugin naming nothing, an optical frame that is the root, a sensor <pose> of words
    '<link name="camera_optical_frame"/><joint name="c" type="fixed"><parent link="camera_optical_frame"/>'
    '<child link="camera_link"/></joint><link name="camera_link"/>'
    '<gazebo reference="camera_link"><sensor type="camera"><pose>a b c d e f</pose>'
    '<plugin><frame_name></frame_name><frameName>/camera_link</frameName></plugin></sensor>'
    '</gazebo><gazebo reference="nowhere"><sensor type="depth"/></gazebo>',
    # inertials against geometry: inf, huge, zero-volume meshes, a mesh that is missing
    '<link name="a"><inertial><origin xyz="1e308 0 0"/><mass value="1e308"/><inertia ixx="1e308" '
    'ixy="0" ixz="0" iyy="1e308" iyz="0" izz="1e308"/></inertial><collision><geometry>'
    '<box size="1e-300 1 1"/></geometry></collision><visual><geometry><mesh filename="no.stl"/>'
    '</geometry></visual></link>',
])
def test_no_crash_on_malformed_robots(tmp_path, body):
    (tmp_path / "r.urdf").write_text(f'<robot name="r">{body}</robot>')
    result = load_and_check(str(tmp_path / "r.urdf"), CheckOptions(selection=Selection(CODES)))
    assert not [f for f in result.findings if f.code == "U900"], \
        [f.message for f in result.findings]


def test_no_rule_of_any_target_recurses_as_deep_as_a_chain_written_leaf_first(tmp_path):
    """Walks of what the robot defines by name (joint chains, SRDF subgroups) were recursive:
    a 1,100-link chain written leaf first (and a chain of subgroups likewise) ended U614 and
    U617 (gazebo.py's frames), U950/U951/U960/U961 (portability's lumping of fixed joints,
    however the chain is written) and U808/U809 (groups) in RecursionError. Every rule, every
    target: no U900."""
    from urdftool.simulators import TARGETS

    count = 1100  # past the recursion limit
    inertial = ('<inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" '
                'iyz="0" izz="0.01"/></inertial>')
    links = "".join(f'<link name="l{i}">{inertial}</link>' for i in range(count))
    joints = "".join(f'<joint name="j{i}" type="{"fixed" if i % 2 else "revolute"}"><parent link="l{i - 1}"/>'
                     f'<child link="l{i}"/><origin xyz="0 0 0.01"/><axis xyz="0 0 1"/>{LIMIT}</joint>'
                     for i in range(count - 1, 0, -1))
    wheels = "".join(WHEEL.format(s=side, m=1, i=0.01, rpy="1.5708 0 0", r=0.05, p=f"l{count - 1}",
                                  y=y, axis="0 1 0") for side, y in (("left", 0.15), ("right", -0.15)))
    drive = ('<gazebo><plugin name="d" filename="libgazebo_ros_diff_drive.so"><left_joint>left_wheel_joint'
             '</left_joint><right_joint>right_wheel_joint</right_joint><wheel_separation>0.5'
             '</wheel_separation><wheel_diameter>0.1</wheel_diameter></plugin></gazebo>')
    (tmp_path / "r.urdf").write_text(f'<robot name="r">{wheels}{links}{joints}{drive}</robot>')
    groups = "".join(f'<group name="g{i}"><group name="g{i - 1}"/></group>' for i in range(1100, 0, -1))
    (tmp_path / "r.srdf").write_text(f'<robot name="r">{groups}<group name="g0"><joint name="j2"/></group>'
                                     '<group_state name="s" group="g1100"><joint name="j2" value="0"/>'
                                     '</group_state></robot>')
    result = load_and_check(str(tmp_path / "r.urdf"), CheckOptions(selection=Selection(targets=TARGETS)))
    assert {f.code for f in result.findings} >= {"U614"}, [f.code for f in result.findings]
    assert not [f for f in result.findings if f.code == "U900"], \
        [f.message for f in result.findings if f.code == "U900"]
