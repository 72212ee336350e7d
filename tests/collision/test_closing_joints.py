"""A parallel robot whose loops are closed by SDF joints written in ``<gazebo>`` blocks (the
Codian delta of the real sweep): every command reads the URDF's tree (the closing joints are no
joint of it) and works on it; the collisions at a pose allow the pairs a closing joint joins."""

from __future__ import annotations

import json

import pytest

BOX = '<geometry><box size="0.02 0.02 0.2"/></geometry>'
INERTIAL = ('<inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" '
            'ixz="0" iyz="0"/></inertial>')


def _leg(i: int, y: float) -> str:
    """An upper arm driven from the base at ``y`` [m] and a lower leg hanging from it."""
    return (f'<link name="upper{i}">{INERTIAL}<collision><origin xyz="0 0 -0.1"/>{BOX}'
            f'</collision></link>'
            f'<joint name="motor{i}" type="revolute"><parent link="base"/>'
            f'<child link="upper{i}"/><origin xyz="0 {y} 0"/>'
            '<axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="5" velocity="1"/></joint>'
            f'<link name="lower{i}">{INERTIAL}<collision><origin xyz="0 0 -0.1"/>{BOX}'
            f'</collision></link>'
            f'<joint name="knee{i}" type="continuous"><parent link="upper{i}"/>'
            f'<child link="lower{i}"/><origin xyz="0 0 -0.2"/><axis xyz="1 0 0"/></joint>')


DELTA = ('<robot name="delta"><link name="base">' + INERTIAL + '</link>'
         + "".join(_leg(i, y) for i, y in enumerate((-0.1, 0.1)))
         # the platform under lower0, reaching 5 mm into lower1's foot, where close1 joins them
         + '<link name="platform">' + INERTIAL + '<collision><origin xyz="0 0.1 -0.005"/>'
         '<geometry><box size="0.05 0.3 0.02"/></geometry></collision></link>'
         '<joint name="knee_platform" type="continuous"><parent link="lower0"/>'
         '<child link="platform"/><origin xyz="0 0 -0.2"/><axis xyz="1 0 0"/></joint>'
         '<gazebo><joint name="close1" type="revolute"><parent>lower1</parent>'
         '<child>platform</child><pose>0 0 0 0 0 0</pose><axis><xyz>1 0 0</xyz></axis>'
         '</joint></gazebo></robot>')


@pytest.fixture
def delta(tmp_path):
    path = tmp_path / "delta.urdf"
    path.write_text(DELTA)
    return path


def test_a_pair_joined_by_a_closing_gazebo_joint_is_allowed_not_colliding(run_cli, delta):
    """lower1 and the platform meet where the loop-closing joint joins them (Gazebo does not
    collide them): COLLIDING, exit 1, was a finding on every delta robot for Gazebo."""
    result = run_cli("collisions", delta, "--q", "motor1=0", "-f", "json")
    assert result.exit_code == 0, result.output
    document = json.loads(result.stdout)
    [pair] = [c for c in document["colliding"] if {c["link1"], c["link2"]} ==
              {"lower1", "platform"}]
    assert pair["allowed"] == "Closing"
    text = run_cli("collisions", delta).stdout
    assert "allowed (Closing)" in text and "joined by a joint written in a <gazebo> block" \
        in text


@pytest.mark.parametrize("words", [
    ["tree"], ["graph"], ["fk", "--random", "2", "-f", "json"], ["inertia"],
    ["dynamics", "--samples", "5"], ["dynamics", "--floating", "--q", "motor0=0.1"],
    ["ik", "--tip", "platform", "--xyz", "0", "0.05", "-0.35"],
    ["workspace", "--tip", "platform", "--samples", "50"],
    ["collisions", "--matrix", "--samples", "50"], ["diff", "{robot}"]],
    ids=lambda words: "-".join(w for w in words if not w.startswith("{"))[:30])
def test_every_command_reads_the_urdfs_tree_past_the_closing_joint(run_cli, delta, words):
    """The closing joint is no joint of the tree: no command names it, none fails on it."""
    result = run_cli(words[0], delta, *[w.format(robot=delta) for w in words[1:]])
    assert result.exit_code in (0, 1), result.output
    assert "close1" not in result.output and "Traceback" not in result.output
    if words[0] == "fk":
        frames = json.loads(result.stdout)
        assert "close1" not in json.dumps(frames)


def test_shapes_that_only_touch_are_0_apart_not_minus_1000_mm(run_cli, tmp_path):
    """A lower leg whose top face is the next leg's upper arm's bottom face, in the plane
    z = -0.2 (boxes sharing a plane, crossing at an edge): FCL's collision test says apart and
    its distance -1 ('in collision'), shown as -1000 mm among the closest pairs apart."""
    path = tmp_path / "legs.urdf"
    path.write_text('<robot name="legs"><link name="base"/>' + _leg(0, 0.0)
                    + _leg(1, 0.0).replace("upper1", "side").replace(
                        '<origin xyz="0 0.0 0"/>', '<origin xyz="0 0 0" rpy="0 0 1.5708"/>')
                    + '</robot>')
    document = json.loads(run_cli("collisions", path, "-f", "json").stdout)
    gaps = {(c["link1"], c["link2"]): c["distance"] for c in document["closest"]}
    assert gaps and all(gap >= 0 for gap in gaps.values()), gaps
    assert gaps[("lower0", "side")] == 0.0
