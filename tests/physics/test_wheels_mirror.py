"""Wheels and casters (physics/wheels.py) and left/right mirror pairs (physics/mirror.py)."""

from __future__ import annotations

import math

import pytest

from conftest import load_text
from urdftool.physics.mirror import fit, mirror_names, pairs
from urdftool.physics.wheels import lowest, wheels

CYLINDER = '<collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision>'


def _joint(name, parent, child, kind="continuous", xyz="0 0 0", axis="0 1 0"):
    limit = '<limit lower="-1" upper="1" effort="1" velocity="1"/>' if kind == "revolute" else ""
    return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
            f'<origin xyz="{xyz}"/><axis xyz="{axis}"/>{limit}</joint>')


def test_wheels_by_name_by_drive_and_casters_in_a_fork(tmp_path):
    robot = load_text(tmp_path, f"""<robot name="r"><link name="base_link"/>
      <link name="WheelLeft">{CYLINDER}</link>{_joint("j_left", "base_link", "WheelLeft")}
      <link name="drive_r">{CYLINDER}</link>{_joint("j_r", "base_link", "drive_r")}
      <link name="caster_swivel"/>{_joint("caster_swivel_joint", "base_link", "caster_swivel", axis="0 0 1")}
      <link name="caster_wheel">{CYLINDER}</link>{_joint("caster_wheel_joint", "caster_swivel", "caster_wheel")}
      <link name="rear_caster"><collision><geometry><sphere radius="0.02"/></geometry></collision></link>
      {_joint("rear_caster_joint", "base_link", "rear_caster", kind="fixed")}
      <link name="steering_wheel"/>{_joint("steering_wheel_joint", "base_link", "steering_wheel")}
      <link name="flywheel"/>{_joint("flywheel_joint", "base_link", "flywheel")}
      <link name="wrist"/>{_joint("wrist_roll", "base_link", "wrist")}
      <gazebo><plugin name="d" filename="libgazebo_ros_diff_drive.so">
        <left_joint>j_left</left_joint><right_joint>j_r</right_joint></plugin></gazebo>
      </robot>""")
    found = {wheel.link: (wheel.kind, wheel.why) for wheel in wheels(robot)}
    assert found == {"WheelLeft": ("wheel", "a differential drive names it"),
                     "drive_r": ("wheel", "a differential drive names it"),
                     "caster_wheel": ("wheel", "its name"),
                     "rear_caster": ("caster", "its name")}


def test_a_caster_wheels_hubcap_is_part_of_the_wheel(tmp_path):
    # pioneer3dx: caster_wheel_joint is a fixed joint holding the hubcap on the caster wheel
    robot = load_text(tmp_path, f"""<robot name="r"><link name="base_link"/>
      <link name="caster_swivel"/>{_joint("swivel", "base_link", "caster_swivel", axis="0 0 1")}
      <link name="caster_wheel">{CYLINDER}</link>{_joint("caster_swivel_hubcap_joint", "caster_swivel", "caster_wheel")}
      <link name="caster_hubcap">{CYLINDER}</link>
      {_joint("caster_wheel_joint", "caster_wheel", "caster_hubcap", kind="fixed")}</robot>""")
    assert [(w.link, w.kind) for w in wheels(robot)] == [("caster_wheel", "wheel")]


def test_the_mount_beside_a_caster_wheel_is_no_caster(tmp_path):
    # andino: caster_base_link is a block fixed beside the swivel that holds the caster wheel
    robot = load_text(tmp_path, f"""<robot name="r"><link name="base_link"/>
      <link name="caster_base_link"><collision><geometry><box size="0.03 0.03 0.01"/></geometry>
      </collision></link>{_joint("caster_base_joint", "base_link", "caster_base_link", kind="fixed")}
      <link name="caster_rotation_link"/>{_joint("caster_rotation_joint", "base_link", "caster_rotation_link", axis="0 0 1")}
      <link name="caster_wheel_link">{CYLINDER}</link>{_joint("caster_wheel_joint", "caster_rotation_link", "caster_wheel_link")}
      </robot>""")
    assert [(w.link, w.kind) for w in wheels(robot)] == [("caster_wheel_link", "wheel")]


def test_no_wheel_on_an_arm_or_a_legged_robot(tmp_path):
    robot = load_text(tmp_path, f"""<robot name="r"><link name="base"/>
      <link name="lf_foot"><collision><geometry><sphere radius="0.02"/></geometry></collision>
      </link>{_joint("lf_foot_joint", "base", "lf_foot", kind="fixed")}
      <link name="r_wrist_roll_link">{CYLINDER}</link>{_joint("r_wrist_roll_joint", "base", "r_wrist_roll_link")}
      <link name="gripper_finger"/>{_joint("gripper_finger_joint", "base", "gripper_finger", kind="revolute")}
      </robot>""")
    assert wheels(robot) == []


def test_lowest_point_in_a_frame(tmp_path):
    robot = load_text(tmp_path, f"""<robot name="r"><link name="base_link"/>
      <link name="left_wheel">{CYLINDER}</link>
      {_joint("left_wheel_joint", "base_link", "left_wheel", xyz="0 0.1 0.05")}</robot>""")
    z, reach = lowest(robot, "left_wheel")
    assert math.isclose(z, 0.0, abs_tol=1e-6) and reach.complete
    z, _ = lowest(robot, "left_wheel", ((0.0, 0.0, -0.2), ((1, 0, 0), (0, 1, 0), (0, 0, 1))))
    assert math.isclose(z, 0.2, abs_tol=1e-6)


@pytest.mark.parametrize("name,expected", [
    ("l_sho_pitch", ["r_sho_pitch"]),
    ("j_shoulder_l", ["j_shoulder_r"]),
    ("arm_left_1_joint", ["arm_right_1_joint"]),
    ("LShoulderPitch_joint", ["RShoulderPitch_joint"]),
    ("RLEG_HIP_R", ["LLEG_HIP_L", "LLEG_HIP_R", "RLEG_HIP_L"]),
    ("LF_HAA", ["RF_HAA"]),
    ("fl_caster_l_wheel_joint", ["fr_caster_r_wheel_joint", "fr_caster_l_wheel_joint",
                                 "fl_caster_r_wheel_joint"]),
    ("WheelLeft", ["WheelRight"]),
    ("base_link", []),
    ("link1", []),
])
def test_mirror_names(name, expected):
    assert mirror_names(name) == expected


def test_pairs_swap_every_side_word_first_and_pick_the_left():
    names = ["RLEG_HIP_R", "LLEG_HIP_R", "l_gripper_r_finger", "r_gripper_l_finger",
             "r_gripper_r_finger", "l_gripper_l_finger", "torso"]
    assert pairs(names) == [("LLEG_HIP_R", "RLEG_HIP_R"), ("l_gripper_r_finger", "r_gripper_l_finger"),
                            ("l_gripper_l_finger", "r_gripper_r_finger")]
    # a later side word alone names parts of one side: the SVH hand's little and ring fingers
    assert pairs(["left_hand_l", "left_hand_r", "hand_l_finger", "hand_r_finger"]) == [
        ("hand_l_finger", "hand_r_finger")]
    # DARwIn's MP_ARM_LOW_L: the L of LOW starts a word in capitals, and is no side
    assert pairs(["MP_ARM_LOW_L", "MP_ARM_LOW_R", "LLEG", "RLEG"]) == [
        ("MP_ARM_LOW_L", "MP_ARM_LOW_R"), ("LLEG", "RLEG")]


def test_the_plane_is_what_most_pairs_agree_with():
    # three pairs mirrored about x = 0.1, one pair off (a limb of another length)
    points = [((0.2, 1, 0), (0.0, 1, 0)), ((0.3, 0, 2), (-0.1, 0, 2)), ((0.15, 5, 5), (0.05, 5, 5)),
              ((0.5, 0, 0), (-0.1, 0.1, 0))]
    found = fit(points)
    assert found.normal == (1.0, 0.0, 0.0) and math.isclose(found.offset, 0.1)
    assert found.reflect((0.2, 1, 0)) == pytest.approx((0.0, 1, 0))


def _partner_names_two_passes(name):
    """partner_names as first written: the side words found twice, each candidate built."""
    from urdftool.physics.mirror import _SWAPS, _WORD, _replaced

    def side_words(strong):
        found = []
        for match in _WORD.finditer(name):
            word = match.group(0)
            if word in _SWAPS:
                after = name[match.end():match.end() + 2]
                weak = len(word) == 1 and word in "LR" and after[:1].isupper() and \
                    not after[1:2].islower()
                if not (strong and weak):
                    found.append((match.start(), match.end(), _SWAPS[word]))
        return found

    words, strong = side_words(False), side_words(True)
    candidates = []
    for chosen in (words, strong, words[:1], strong[:1]):
        if chosen:
            candidate = _replaced(name, chosen)
            if candidate != name and candidate not in candidates:
                candidates.append(candidate)
    return candidates, words, strong


def test_partner_names_one_pass_gives_the_two_passes_answers():
    import random

    from urdftool.physics.mirror import _side_words, partner_names

    parts = ["l", "r", "L", "R", "LL", "LR", "RL", "LEG", "Leg", "leg", "left", "Right", "LEFT",
             "fl", "FR", "hl", "OW", "Ow", "x", "_", "-", "1", "2", ".", "/", "LOW", "RR", "lF"]
    chance = random.Random(34)
    names = ["".join(chance.choice(parts) for _ in range(chance.randint(1, 7)))
             for _ in range(3000)] + ["MP_ARM_LOW_L", "LLEG", "RLEG_HIP_R", "LRLeg", "l1", ""]
    for name in names:
        candidates, words, strong = _partner_names_two_passes(name)
        assert partner_names(name) == candidates, name
        assert _side_words(name) == words and _side_words(name, strong=True) == strong, name


def _pairs_asking_every_name(names):
    """pairs as first written: every name asked for its partners."""
    from urdftool.physics.mirror import _is_left, partner_names

    known, found, used = set(names), [], set()
    for name in names:
        if name in used:
            continue
        for mirror in partner_names(name):
            if mirror in known and mirror not in used:
                found.append((name, mirror) if _is_left(name, mirror) else (mirror, name))
                used.update((name, mirror))
                break
    order = {name: index for index, name in enumerate(names)}
    return sorted(found, key=lambda pair: order[pair[0]])


def test_pairs_ask_only_names_sharing_their_text_without_side_characters():
    import random

    from urdftool.physics.mirror import _SIDE_CHARACTERS, _SWAPS, partner_names

    parts = [*_SWAPS, "arm", "Hip", "HIP", "foot", "b", "e", "t", "ll", "x", "_", "-", "1", "2",
             ".", "/", "OW"]
    chance = random.Random(19)
    paired = 0
    for _ in range(2000):
        names = list(dict.fromkeys("".join(chance.choice(parts) for _ in range(
            chance.randint(1, 4))) for _ in range(chance.randint(1, 30))))
        expected = _pairs_asking_every_name(names)
        assert pairs(names) == expected, names
        paired += len(expected)
        for name in names:  # (what makes skipping the others exact)
            rest = name.translate(_SIDE_CHARACTERS)
            assert all(other.translate(_SIDE_CHARACTERS) == rest for other in partner_names(name))
    assert paired > 100  # (the names do pair)
    assert pairs([f"l{i}" for i in range(100)] + ["r7", "left7"]) == [("l7", "r7")]


def test_named_wheel_skips_only_names_without_a_wheel_word():
    import random
    import re

    from urdftool.physics.wheels import _NOT_WHEEL, _WHEEL, _named_wheel

    def by_every_name(*names):  # as first written: every name split and searched
        for name in names:
            text = re.sub(r"(?<=[a-z0-9])(?=[A-Z])", "_", name).lower()
            if _WHEEL.search(text) and not _NOT_WHEEL.search(text.replace("wheel", " ")):
                return True
        return False

    parts = ["wheel", "Wheel", "WHEEL", "wHeel", "tire", "Tyre", "TIRES", "wheels", "left",
             "Left", "_", "1", "steer", "Mount", "fly", "Σ", "İ", "x", "arm", "caster"]
    chance = random.Random(34)
    for _ in range(3000):
        names = ["".join(chance.choice(parts) for _ in range(chance.randint(1, 5)))
                 for _ in range(chance.randint(1, 2))]
        assert _named_wheel(*names) == by_every_name(*names), names


def test_a_name_without_l_or_r_is_not_searched_for_side_words(monkeypatch):
    """The shortcut of _marked_side_words: every side word holds l, r, L or R, so a name
    with none of them (most joint names of a large robot: 'j5', 'hip_pitch') has none, and
    the pattern is not run over it."""
    from urdftool.physics import mirror

    assert all(not mirror._SIDE_LETTERS.isdisjoint(word) for word in mirror._SWAPS)
    searched, pattern = [], mirror._WORD
    monkeypatch.setattr(mirror, "_WORD", type("Counted", (), {
        "finditer": lambda self, name: searched.append(name) or pattern.finditer(name)})())
    assert mirror.partner_names("j5") == [] and mirror.partner_names("hip_pitch") == []
    assert mirror.partner_names("l5") == ["r5"] and searched == ["l5"]
