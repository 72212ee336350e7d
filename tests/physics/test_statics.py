"""Statics of a standing robot: against a hand-derived leg on its foot, against Pinocchio with
the same leg rooted and fixed at the foot, the humanoid crouched on one foot, two supports, the
support polygon and its margin, and ``dynamics --support``."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from conftest import ROBOTS
from urdftool.description.load import load
from urdftool.errors import DynamicsError
from urdftool.physics.statics import build_standing, convex_hull, margin, stand, standing_loads

HUMANOID = ROBOTS / "humanoid" / "humanoid.urdf.xacro"
G = 9.81
L1, L2 = 0.3, 0.25  # thigh and shin [m]
MT, M1, M2, MF = 3.0, 1.0, 0.7, 0.4  # torso, thigh, shin, foot [kg]
TORSO_COM = (0.02, 0.0, 0.05)


def _inertial(mass, xyz):
    return (f'<inertial><origin xyz="{xyz}"/><mass value="{mass}"/>'
            '<inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>')


def _limit():
    return '<limit lower="-3" upper="3" effort="100" velocity="1"/>'


# torso -> hip -> thigh -> knee -> shin -> ankle -> foot, every axis +y
LEG = f"""<robot name="leg">
  <link name="torso">{_inertial(MT, "0.02 0 0.05")}</link>
  <link name="thigh">{_inertial(M1, f"0 0 {-L1 / 2}")}</link>
  <link name="shin">{_inertial(M2, f"0 0 {-L2 / 2}")}</link>
  <link name="foot">{_inertial(MF, "0.02 0 -0.02")}
    <collision><origin xyz="0.02 0 -0.03"/><geometry><box size="0.1 0.05 0.02"/></geometry>
    </collision></link>
  <joint name="hip" type="revolute"><parent link="torso"/><child link="thigh"/>
    <axis xyz="0 1 0"/>{_limit()}</joint>
  <joint name="knee" type="revolute"><parent link="thigh"/><child link="shin"/>
    <origin xyz="0 0 {-L1}"/><axis xyz="0 1 0"/>{_limit()}</joint>
  <joint name="ankle" type="revolute"><parent link="shin"/><child link="foot"/>
    <origin xyz="0 0 {-L2}"/><axis xyz="0 1 0"/>{_limit()}</joint>
</robot>"""

# the same leg rooted at the foot: each joint turned round (axis -y, so the same angle gives the
# same shape), links' frames at their lower joint
ROOTED = f"""<robot name="rooted">
  <link name="foot">{_inertial(MF, "0.02 0 -0.02")}</link>
  <link name="shin">{_inertial(M2, f"0 0 {L2 / 2}")}</link>
  <link name="thigh">{_inertial(M1, f"0 0 {L1 / 2}")}</link>
  <link name="torso">{_inertial(MT, "0.02 0 0.05")}</link>
  <joint name="ankle" type="revolute"><parent link="foot"/><child link="shin"/>
    <axis xyz="0 -1 0"/>{_limit()}</joint>
  <joint name="knee" type="revolute"><parent link="shin"/><child link="thigh"/>
    <origin xyz="0 0 {L2}"/><axis xyz="0 -1 0"/>{_limit()}</joint>
  <joint name="hip" type="revolute"><parent link="thigh"/><child link="torso"/>
    <origin xyz="0 0 {L1}"/><axis xyz="0 -1 0"/>{_limit()}</joint>
</robot>"""


def _robot(tmp_path, text, name="robot.urdf"):
    path = tmp_path / name
    path.write_text(text)
    return load(path)


def _ry(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def _by_hand(hip, knee, ankle):
    """Joint torques [N m] of the leg standing on its flat foot, derived on paper: each joint
    holds the gravity moment, about its axis (y), of everything above it. Moment of a weight m g
    at horizontal offset dx from the joint: m g dx (r x F with F = (0, 0, -m g))."""
    shin_rotation = _ry(-ankle)  # foot = shin Ry(ankle), the foot level
    thigh_rotation = shin_rotation @ _ry(-knee)
    torso_rotation = thigh_rotation @ _ry(-hip)
    ankle_at = np.zeros(3)
    knee_at = ankle_at + shin_rotation @ np.array([0, 0, L2])
    hip_at = knee_at + thigh_rotation @ np.array([0, 0, L1])
    shin_com = knee_at + shin_rotation @ np.array([0, 0, -L2 / 2])
    thigh_com = hip_at + thigh_rotation @ np.array([0, 0, -L1 / 2])
    torso_com = hip_at + torso_rotation @ np.array(TORSO_COM)
    above_hip = [(MT, torso_com)]
    above_knee = above_hip + [(M1, thigh_com)]
    above_ankle = above_knee + [(M2, shin_com)]

    def moment(bodies, joint):
        return sum(m * G * (at[0] - joint[0]) for m, at in bodies)

    return {"hip": moment(above_hip, hip_at), "knee": moment(above_knee, knee_at),
            "ankle": moment(above_ankle, ankle_at)}


ANGLES = [(0.0, 0.0, 0.0), (-0.4, 0.8, -0.4), (0.3, 0.5, -0.2), (-1.0, 1.2, 0.1)]


@pytest.mark.parametrize("hip,knee,ankle", ANGLES)
def test_leg_on_its_foot_matches_the_hand_derivation(tmp_path, hip, knee, ankle):
    standing = build_standing(_robot(tmp_path, LEG), ["foot"])
    stance = stand(standing, {"hip": hip, "knee": knee, "ankle": ankle})
    expected = _by_hand(hip, knee, ankle)
    got = dict(zip(stance.joints, stance.torques))
    for joint in ("hip", "knee", "ankle"):
        assert got[joint] == pytest.approx(expected[joint], abs=1e-9)
    # the ground carries the whole weight, straight up
    force = stance.wrenches["foot"][:3]
    assert np.allclose(force, [0, 0, (MT + M1 + M2 + MF) * G], atol=1e-9)


@pytest.mark.parametrize("hip,knee,ankle", ANGLES)
def test_leg_on_its_foot_matches_pinocchio_rooted_at_the_foot(tmp_path, hip, knee, ankle):
    import pinocchio as pin

    standing = build_standing(_robot(tmp_path, LEG), ["foot"])
    stance = stand(standing, {"hip": hip, "knee": knee, "ankle": ankle})
    rooted = pin.buildModelFromXML(ROOTED)
    q = np.zeros(rooted.nq)
    for name, value in (("hip", hip), ("knee", knee), ("ankle", ankle)):
        q[rooted.joints[rooted.getJointId(name)].idx_q] = value
    gravity = pin.computeGeneralizedGravity(rooted, rooted.createData(), q)
    got = dict(zip(stance.joints, stance.torques))
    for name in ("hip", "knee", "ankle"):
        expected = gravity[rooted.joints[rooted.getJointId(name)].idx_v]
        assert got[name] == pytest.approx(expected, abs=1e-9)


def test_standing_differs_from_the_root_fixed(tmp_path):
    stance = stand(build_standing(_robot(tmp_path, LEG), ["foot"]),
                   {"hip": -0.4, "knee": 0.8, "ankle": -0.4})
    fixed = dict(zip(stance.joints, stance.fixed_base))
    standing = dict(zip(stance.joints, stance.torques))
    # with the torso fixed the ankle carries only the (level) foot, its centre 20 mm ahead;
    # standing, it carries the rest
    assert abs(fixed["ankle"]) == pytest.approx(MF * G * 0.02)
    assert abs(standing["ankle"]) > 5 * abs(fixed["ankle"])


def test_a_leg_with_its_own_free_base_stands_as_the_leg_does(tmp_path):
    """The leg hung from a massless 'world' by a floating joint of its own (a simulator's free
    body): standing frees that joint, as it frees the leg's root (it was refused, 'of 6 degrees
    of freedom'); the same joints, torques and wrenches."""
    own = LEG.replace("</robot>", '<link name="world"/><joint name="free" type="floating">'
                                  '<parent link="world"/><child link="torso"/></joint></robot>')
    angles = {"hip": -0.4, "knee": 0.8, "ankle": -0.4}
    stances = [stand(build_standing(_robot(tmp_path, text, name), ["foot"]), angles)
               for text, name in ((LEG, "leg.urdf"), (own, "own.urdf"))]
    assert stances[1].joints == stances[0].joints == ["hip", "knee", "ankle"]
    assert np.allclose(stances[1].torques, stances[0].torques, atol=1e-12)
    assert np.allclose(stances[1].fixed_base, stances[0].fixed_base, atol=1e-12)
    assert np.allclose(stances[1].wrenches["foot"], stances[0].wrenches["foot"], atol=1e-9)


def test_humanoid_crouched_on_its_left_foot():
    standing = build_standing(load(HUMANOID), ["l_foot_link"])
    crouch = {"l_hip_pitch": math.radians(-30), "l_knee": math.radians(60),
              "l_ank_pitch": math.radians(-30)}
    stance = stand(standing, crouch)
    torques = dict(zip(stance.joints, stance.torques))
    fixed = dict(zip(stance.joints, stance.fixed_base))
    assert abs(torques["l_knee"]) == pytest.approx(1.152, abs=1e-3)
    assert abs(fixed["l_knee"]) == pytest.approx(0.1282, abs=1e-3)
    assert stance.holds  # 1.15 of 2.5 N m
    # the body hangs 37 mm to the right of the left foot's centre line; the foot is 66 mm wide
    assert stance.com[1] == pytest.approx(-0.037, abs=1e-6)
    assert stance.margin == pytest.approx(-0.004, abs=1e-6) and not stance.stands
    assert len(stance.polygon) == 4
    assert stance.wrenches["l_foot_link"][2] == pytest.approx(stance.mass * 9.81, rel=1e-9)


def test_two_feet_share_the_load_and_say_how(tmp_path):
    standing = build_standing(load(HUMANOID), ["l_foot_link", "r_foot_link"])
    stance = stand(standing, {})
    left, right = stance.wrenches["l_foot_link"], stance.wrenches["r_foot_link"]
    assert left[2] == pytest.approx(right[2]) == pytest.approx(stance.mass * 9.81 / 2)
    assert "statically indeterminate" in stance.assumption
    assert stance.stands and stance.margin == pytest.approx(0.052, abs=1e-6)
    assert np.allclose(stance.torques, 0.0, atol=1e-9)  # straight legs: nothing to hold


def test_a_raised_support_is_reported(tmp_path):
    standing = build_standing(load(HUMANOID), ["l_foot_link", "r_foot_link"])
    stance = stand(standing, {"r_knee": 1.0})
    assert stance.lifted["r_foot_link"] > 0.01 and stance.lifted["l_foot_link"] == 0.0
    assert any("r_foot_link" in warning and "above the ground" in warning
               for warning in stance.warnings)


def test_standing_loads_over_the_poses_that_stand(tmp_path):
    standing = build_standing(_robot(tmp_path, LEG), ["foot"])
    result = standing_loads(standing, 60, seed=3)
    assert result.poses == 61 and result.zero_stands
    assert 1 < result.stable < 61  # some random poses tip the leg over its foot
    loads = {load.joint: load for load in result.loads}
    assert loads["ankle"].zero_pose == pytest.approx(abs(_by_hand(0, 0, 0)["ankle"]), abs=1e-9)
    pose = loads["knee"].worst_pose
    assert stand(standing, pose).stands
    assert loads["knee"].worst == pytest.approx(
        abs(_by_hand(pose["hip"], pose["knee"], pose["ankle"])["knee"]), abs=1e-9)


def test_unknown_or_bare_support(tmp_path):
    from urdftool.errors import UnknownLink

    with pytest.raises(UnknownLink, match="did you mean 'l_foot_link'"):
        build_standing(load(HUMANOID), ["l_fot_link"])
    with pytest.raises(DynamicsError, match="'thigh' has no collision or visual geometry"):
        build_standing(_robot(tmp_path, LEG), ["thigh"])


def test_convex_hull_and_margin():
    square = [(0, 0), (1, 0), (1, 1), (0, 1), (0.5, 0.5), (0.5, 0), (1, 1)]
    hull = convex_hull(np.array(square, dtype=float))
    assert hull.tolist() == [[0, 0], [1, 0], [1, 1], [0, 1]]  # counter-clockwise, no extras
    assert margin(hull, np.array([0.5, 0.4])) == pytest.approx(0.4)
    assert margin(hull, np.array([1.5, 0.5])) == pytest.approx(-0.5)
    assert margin(hull, np.array([2.0, 2.0])) == pytest.approx(-math.sqrt(2))
    line = convex_hull(np.array([(0, 0), (1, 0)], dtype=float))
    assert len(line) == 2 and margin(line, np.array([0.5, 0.0])) == pytest.approx(0.0)
    assert margin(line, np.array([0.5, 0.2])) == pytest.approx(-0.2)


def test_cylinder_and_sphere_feet_touch_at_their_lowest_points(tmp_path):
    feet = LEG.replace('<box size="0.1 0.05 0.02"/>', '<cylinder radius="0.03" length="0.02"/>')
    stance = stand(build_standing(_robot(tmp_path, feet), ["foot"]), {})
    # a disc lying flat: its whole rim touches; the polygon is (nearly) the disc
    assert len(stance.polygon) > 20
    assert np.allclose(np.linalg.norm(stance.polygon - [0.02, 0.0], axis=1), 0.03)
    ball = LEG.replace('<box size="0.1 0.05 0.02"/>', '<sphere radius="0.03"/>')
    stance = stand(build_standing(_robot(tmp_path, ball, "ball.urdf"), ["foot"]), {})
    # a ball touches at a point; the points within the 1 mm contact tolerance ring it closely
    assert np.linalg.norm(stance.polygon - [0.02, 0.0], axis=1).max() < 0.008
    assert stance.com[0] < 0.0135 and not stance.stands


# -- dynamics --support --------------------------------------------------------------------

CROUCH = ["--q", "l_hip_pitch=-30", "--q", "l_knee=60", "--q", "l_ank_pitch=-30", "--deg"]


def test_cli_support_text_and_picture(run_cli, tmp_path):
    picture = tmp_path / "stance.svg"
    result = run_cli("dynamics", HUMANOID, "--support", "l_foot_link", *CROUCH,
                     "--plot", picture)
    assert result.exit_code == 1  # it tips over
    assert "4.0 mm OUTSIDE" in result.output
    knee = next(line for line in result.output.splitlines() if line.strip().startswith("l_knee"))
    assert knee.split()[1:4] == ["-1.152", "0.1282", "2.5"]
    text = picture.read_text()
    assert "<polygon" in text and "OUTSIDE" in text


def test_cli_support_json_two_feet_stands(run_cli):
    result = run_cli("dynamics", HUMANOID, "--support", "l_foot_link", "--support",
                     "r_foot_link", "-f", "json", "--samples", "5")
    assert result.exit_code == 0, result.output
    document = json.loads(result.output)
    assert document["stands"] and document["holds"]
    assert document["com_margin"] == pytest.approx(0.052, abs=1e-6)
    assert len(document["gravity_loads"]) == 20
    assert 1 <= document["poses_standing"] <= document["poses_drawn"] == 6
    assert "statically indeterminate" in document["assumption"]


def test_cli_support_usage(run_cli, tmp_path):
    result = run_cli("dynamics", HUMANOID, "--plot", tmp_path / "x.svg")
    assert result.exit_code == 2 and "--plot needs --support" in result.output
    result = run_cli("dynamics", HUMANOID, "--support", "l_foot_link", "--plot",
                     tmp_path / "x.pdf")
    assert result.exit_code == 2 and ".svg or .png" in result.output
    result = run_cli("dynamics", HUMANOID, "--support", "l_fot")  # a name given: exit 2
    assert result.exit_code == 2 and "link 'l_fot' does not exist" in result.output
