"""``diff``: planted changes and the effects reported for them."""

from __future__ import annotations

import math

import pytest

from conftest import load_text
from urdftool.compare.diff import DiffOptions, chain_ends, diff
from urdftool.errors import UsageError

ARM = """<?xml version="1.0"?>
<robot name="arm">
  <!-- a three-link arm -->
  <material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>
  <link name="base">
    <inertial><mass value="2.0"/><origin xyz="0 0 0.05"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <visual><geometry><box size="0.2 0.2 0.1"/></geometry><material name="grey"/></visual>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
  </link>
  <link name="upper">
    <inertial><mass value="1.0"/><origin xyz="0 0 0.2"/>
      <inertia ixx="0.02" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.001"/></inertial>
    <visual><origin xyz="0 0 0.2"/><geometry><cylinder radius="0.04" length="0.3"/></geometry>
    </visual>
    <collision><origin xyz="0 0 0.2"/><geometry><cylinder radius="0.04" length="0.3"/>
    </geometry></collision>
  </link>
  <link name="fore">
    <inertial><mass value="0.5"/><origin xyz="0 0 0.15"/>
      <inertia ixx="0.005" ixy="0" ixz="0" iyy="0.005" iyz="0" izz="0.0005"/></inertial>
    <collision><origin xyz="0 0 0.15"/><geometry><box size="0.05 0.05 0.25"/></geometry>
    </collision>
  </link>
  <link name="hand"/>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/><origin xyz="0 0 0.05"/><axis xyz="0 1 0"/>
    <limit lower="-1.5" upper="1.5" effort="10" velocity="1"/>
  </joint>
  <joint name="elbow" type="revolute">
    <parent link="upper"/><child link="fore"/><origin xyz="0 0 0.4"/><axis xyz="0 1 0"/>
    <limit lower="-2.0" upper="2.0" effort="5" velocity="1"/>
  </joint>
  <joint name="wrist" type="fixed">
    <parent link="fore"/><child link="hand"/><origin xyz="0 0 0.3"/>
  </joint>
</robot>
"""


def compare(tmp_path, new_text, old_text=ARM, **options):
    old, new = load_text(tmp_path / "old", old_text), load_text(tmp_path / "new", new_text)
    return diff(old, new, DiffOptions(**options))


def _fields(result):
    return {(c.kind, c.element, c.name, c.field) for c in result.changes}


def test_formatting_comments_attribute_order_and_defaults_are_no_change(tmp_path):
    reformatted = (ARM.replace("<!-- a three-link arm -->", "<!-- reworded -->")
                   .replace('<limit lower="-1.5" upper="1.5" effort="10" velocity="1"/>',
                            '<limit  velocity="1.0" effort="10.00"\n upper="1.5" lower="-1.50"/>')
                   .replace('<parent link="fore"/><child link="hand"/><origin xyz="0 0 0.3"/>',
                            '<parent link="fore"/><child link="hand"/>'
                            '<origin rpy="0 0 0" xyz="0 0 0.30"/>'))
    result = compare(tmp_path, reformatted)
    assert result.equivalent and result.changes == [] and result.effects is None


def test_an_origin_moved_3_mm_moves_every_frame_below_it_3_mm(tmp_path):
    result = compare(tmp_path, ARM.replace('<origin xyz="0 0 0.4"/>', '<origin xyz="0 0 0.403"/>'))
    [change] = result.changes
    assert (change.element, change.name, change.field) == ("joint", "elbow", "origin.xyz")
    assert change.delta == pytest.approx(0.003) and change.unit == "m"
    moved = {frame.link: frame for frame in result.effects.frames}
    assert set(moved) == {"fore", "hand"}  # base and upper stay
    assert moved["hand"].zero_position == pytest.approx(0.003, abs=1e-9)
    assert moved["hand"].max_position == pytest.approx(0.003, abs=1e-9)
    assert moved["hand"].max_rotation == pytest.approx(0.0, abs=1e-9)
    assert not result.equivalent


def test_a_changed_mass_is_reported_in_percent_with_the_total_and_com(tmp_path):
    result = compare(tmp_path, ARM.replace('<mass value="1.0"/>', '<mass value="1.25"/>'))
    [change] = result.changes
    assert (change.name, change.field, change.percent) == ("upper", "inertial.mass", 25.0)
    effects = result.effects
    assert effects.frames == []
    assert (effects.old_mass, effects.new_mass) == (3.5, 3.75)
    # com z: (2 * 0.05 + m * 0.25 + 0.5 * 0.6) / total, upper's com at 0.05 + 0.2
    assert effects.old_com[2] == pytest.approx((0.1 + 0.25 + 0.3) / 3.5)
    assert effects.new_com[2] == pytest.approx((0.1 + 1.25 * 0.25 + 0.3) / 3.75)


def test_a_renamed_link_is_a_rename_not_a_removal_and_an_addition(tmp_path):
    renamed = ARM.replace('"fore"', '"forearm"')
    result = compare(tmp_path, renamed)
    assert _fields(result) == {("renamed", "link", "forearm", "")}
    assert result.changes[0].old_name == "fore"
    assert result.renames.links == {"fore": "forearm"}
    assert result.effects.frames == []  # the renamed link is the same frame


def test_a_renamed_joint_and_its_child_are_both_renames(tmp_path):
    renamed = ARM.replace('"elbow"', '"elbow_joint"').replace('"hand"', '"tool"')
    result = compare(tmp_path, renamed)
    assert {(c.kind, c.old_name, c.name) for c in result.changes} == {
        ("renamed", "elbow", "elbow_joint"), ("renamed", "hand", "tool")}


def test_a_widened_limit_is_a_change_that_moves_no_frame_in_the_common_range(tmp_path):
    result = compare(tmp_path, ARM.replace('lower="-2.0" upper="2.0"', 'lower="-2.0" upper="2.5"'))
    [change] = result.changes
    assert (change.field, change.old, change.new, change.unit) == ("limit.upper", 2.0, 2.5,
                                                                   "rad")
    assert result.effects.frames == []
    assert result.effects.samples == 200


def test_added_and_removed_links_joints_and_geometry(tmp_path):
    extra = ARM.replace('  <link name="hand"/>', '  <link name="hand"/>\n  <link name="camera"/>')\
        .replace("</robot>", '<joint name="cam" type="fixed"><parent link="hand"/>'
                             '<child link="camera"/></joint></robot>')\
        .replace('<cylinder radius="0.04" length="0.3"/></geometry>\n    </visual>',
                 '<cylinder radius="0.05" length="0.3"/></geometry>\n    </visual>')
    result = compare(tmp_path, extra)
    assert _fields(result) == {("added", "link", "camera", ""), ("added", "joint", "cam", ""),
                               ("changed", "link", "upper", "visual[0].radius")}
    removed = compare(tmp_path / "r", ARM, old_text=extra)
    assert ("removed", "link", "camera", "") in _fields(removed)


def test_an_axis_is_compared_as_a_direction(tmp_path):
    longer = ARM.replace('<axis xyz="0 1 0"/>', '<axis xyz="0 2 0"/>', 1)
    result = compare(tmp_path / "a", longer)
    assert result.equivalent and result.changes == []
    turned = ARM.replace('<axis xyz="0 1 0"/>', '<axis xyz="1 1 0"/>', 1)
    [change] = compare(tmp_path / "b", turned).changes
    assert (change.name, change.field, change.unit) == ("shoulder", "axis", "rad")
    assert change.delta == pytest.approx(math.pi / 4)
    assert compare(tmp_path / "c", ARM.replace('<axis xyz="0 1 0"/>', '<axis xyz="0 -1 0"/>',
                                               1)).changes[0].delta == pytest.approx(math.pi)


def test_an_rpy_is_compared_as_a_rotation(tmp_path):
    # (pi, pi, 0) turns as (0, 0, pi) does; (0, 0, 2 pi) as (0, 0, 0): the same frames
    same = (ARM.replace('<origin xyz="0 0 0.4"/>',
                        f'<origin xyz="0 0 0.4" rpy="{math.pi!r} {math.pi!r} 0"/>')
            .replace('<origin xyz="0 0 0.3"/>',
                     f'<origin xyz="0 0 0.3" rpy="0 0 {2 * math.pi!r}"/>'))
    old = ARM.replace('<origin xyz="0 0 0.4"/>', f'<origin xyz="0 0 0.4" rpy="0 0 {math.pi!r}"/>')
    result = compare(tmp_path / "a", same, old)
    assert result.changes == [], result.changes
    tilted = old.replace(f'rpy="0 0 {math.pi!r}"', f'rpy="0.01 0 {math.pi!r}"')
    [change] = compare(tmp_path / "b", tilted, old).changes
    assert (change.name, change.field, change.unit) == ("elbow", "origin.rpy", "rad")
    assert change.delta == pytest.approx(0.01)


def test_an_inertia_is_compared_as_the_tensor_in_the_link_frame(tmp_path):
    # the upper arm's principal moments (0.02, 0.02, 0.001) along z, written turned a quarter
    # about y: the same body as the tensor written unturned
    turned = ARM.replace(
        '<mass value="1.0"/><origin xyz="0 0 0.2"/>\n      <inertia ixx="0.02" ixy="0" ixz="0" '
        'iyy="0.02" iyz="0" izz="0.001"/>',
        f'<mass value="1.0"/><origin xyz="0 0 0.2" rpy="0 {math.pi / 2!r} 0"/>\n      '
        '<inertia ixx="0.001" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/>')
    assert turned != ARM
    assert compare(tmp_path / "a", turned).changes == []
    # turned the other way round without swapping the moments: a different body, field by field
    wrong = turned.replace('ixx="0.001" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"',
                           'ixx="0.02" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.001"')
    assert {c.field for c in compare(tmp_path / "b", wrong).changes} == {"inertial.origin.rpy"}


def test_the_total_mass_is_summed_exactly(tmp_path):
    # ten links of 0.1 kg weigh 1 kg (0.9999999999999999 summed one by one)
    links = "".join(f'<link name="l{i}"><inertial><mass value="0.1"/><inertia ixx="0.001" '
                    f'iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>'
                    f'<joint name="j{i}" type="fixed"><parent link="base"/><child link="l{i}"/>'
                    f'</joint>' for i in range(10))
    tens = f'<robot name="r"><link name="base"/>{links}</robot>'
    moved = tens.replace('<child link="l9"/>', '<child link="l9"/><origin xyz="0 0 1"/>')
    effects = compare(tmp_path, moved, tens).effects
    assert (effects.old_mass, effects.new_mass) == (1.0, 1.0)


def test_tolerance_hides_numeric_noise(tmp_path):
    noisy = ARM.replace('<origin xyz="0 0 0.4"/>', '<origin xyz="0 0 0.4000001"/>')
    assert not compare(tmp_path / "x", noisy).equivalent
    assert compare(tmp_path / "y", noisy, tolerance=1e-6).equivalent


def test_a_pair_that_newly_collides(tmp_path):
    # the forearm folded back into the base: the elbow's range now reaches it
    crashing = ARM.replace('<origin xyz="0 0 0.4"/>', '<origin xyz="0 0 0.12"/>')
    result = compare(tmp_path, crashing, samples=300)
    pairs = {(c.link1, c.link2): c for c in result.effects.collisions}
    assert ("base", "fore") in pairs
    assert pairs[("base", "fore")].old_count == 0 < pairs[("base", "fore")].new_count


@pytest.mark.parametrize("text, links, ends", [
    ("base:tip", {"base", "tip"}, ("base", "tip")),
    ("ns:base:ns:tip", {"ns:base", "ns:tip"}, ("ns:base", "ns:tip")),
    ("a::b", {"a:", "b", "a", ":b"}, None),  # two splits name links: ambiguous
    ("a:b:c", {"a:b", "c"}, ("a:b", "c")),
    ("nope:tip", {"base", "tip"}, ("nope", "tip")),  # none: the first ':', reported unknown
    ("ns:base:ns:tp", {"ns:base", "ns:tip"}, ("ns:base", "ns:tp")),  # one known end: 'ns:tp'
])
def test_a_chain_splits_at_the_colon_that_names_two_links(text, links, ends):
    if ends is None:
        with pytest.raises(UsageError, match="more than one chain"):
            chain_ends(text, links)
    else:
        assert chain_ends(text, links) == ends


@pytest.mark.parametrize("text", ["base", "base:", ":tip"])
def test_a_chain_without_two_ends_is_a_usage_error(text):
    with pytest.raises(UsageError, match="must be BASE:TIP"):
        chain_ends(text, {"base", "tip"})


@pytest.mark.parametrize("text, links", [("tip:tip", {"base", "tip"}), ("a:a", ()),
                                         ("x:y:x:y", {"x:y", "x"})])
def test_a_chain_from_a_link_to_itself_is_a_usage_error(text, links):
    """Its reach is 0 on both sides: it was compared as "equal", where ik and workspace refuse a
    limb no joint moves (checked once the ends are split among the links: 'x:y' twice)."""
    with pytest.raises(UsageError, match="at both ends"):
        chain_ends(text, links)


def test_chain_reach(tmp_path):
    longer = ARM.replace('<origin xyz="0 0 0.3"/>', '<origin xyz="0 0 0.35"/>')
    result = compare(tmp_path, longer, chains=(("base", "hand"),))
    [chain] = result.effects.chains
    assert chain.old_zero == pytest.approx(0.75) and chain.new_zero == pytest.approx(0.8)
    assert chain.new_reach - chain.old_reach == pytest.approx(0.05, abs=1e-3)


def test_the_worst_configuration_is_where_frames_differ_most(tmp_path):
    turned = ARM.replace('<axis xyz="0 1 0"/>\n    <limit lower="-2.0"',
                         '<axis xyz="1 0 0"/>\n    <limit lower="-2.0"')
    result = compare(tmp_path, turned)
    # the elbow turns about x instead of y: the forearm moves most at a large elbow angle
    assert abs(result.effects.worst["elbow"]) > 1.0
    assert math.isclose(result.effects.frames[0].max_position,
                        max(f.max_position for f in result.effects.frames))


def test_a_side_without_a_kinematic_model_still_gets_its_structure(tmp_path):
    broken = ARM.replace('<parent link="fore"/><child link="hand"/>',
                         '<parent link="nowhere"/><child link="hand"/>')
    result = compare(tmp_path, broken)
    assert ("changed", "joint", "wrist", "parent") in _fields(result)
    assert result.effects is None
    assert result.warnings and result.warnings[0].startswith("effects not computed:")


def test_an_appearance_change_has_no_effects_to_compute(tmp_path):
    recoloured = ARM.replace('rgba="0.5 0.5 0.5 1"', 'rgba="0.2 0.5 0.5 1"')
    result = compare(tmp_path, recoloured)
    assert _fields(result) == {("changed", "link", "base", "visual[0].colour"),
                               ("changed", "material", "grey", "color")}
    assert result.effects is None and not result.equivalent


def test_a_nan_compared_with_itself_is_no_change(tmp_path):
    """``nan != nan``: a robot holding ``nan`` (a mass, an origin, a limit) diffed with itself
    said "mass nan -> nan kg"; ``structure.same_value`` is the one judge of a change."""
    nan = ARM.replace('<mass value="1.0"/>', '<mass value="nan"/>').replace(
        '<origin xyz="0 0 0.4"/>', '<origin xyz="nan 0 0.4"/>').replace(
        'lower="-2.0"', 'lower="nan"')
    result = compare(tmp_path, nan, old_text=nan)
    assert result.equivalent and result.changes == []
    assert _fields(compare(tmp_path / "other", nan.replace('upper="2.0"', 'upper="2.5"'),
                           old_text=nan)) == {("changed", "joint", "elbow", "limit.upper")}


def _asked(monkeypatch):
    """The link pairs FCL is asked about, per side, as diff's collision comparison runs."""
    from urdftool.collision.pairs import PairChecker

    asked, tally = [], PairChecker.tally

    def recording(self, *args, **kwargs):
        asked.append(set(self.link_pairs))
        return tally(self, *args, **kwargs)

    monkeypatch.setattr(PairChecker, "tally", recording)
    return asked


def test_collisions_are_compared_only_for_pairs_a_change_can_move(tmp_path, monkeypatch):
    asked = _asked(monkeypatch)
    compare(tmp_path, ARM.replace('<mass value="0.5"/>', '<mass value="0.7"/>'))
    assert asked == [set(), set()]  # a mass moves no part: nothing can collide otherwise
    asked.clear()
    compare(tmp_path, ARM.replace('<origin xyz="0 0 0.4"/>', '<origin xyz="0 0 0.12"/>'))
    assert asked == [{("base", "fore"), ("fore", "upper")}] * 2  # the elbow moves only 'fore'
    asked.clear()
    compare(tmp_path, ARM.replace('<box size="0.05 0.05 0.25"/>', '<box size="0.05 0.05 0.3"/>'))
    assert asked == [{("base", "fore"), ("fore", "upper")}] * 2  # its shape, not its pose



def test_a_mass_past_the_bounds_is_not_summed_and_no_percent_overflows(tmp_path):
    """attack25: 1 kg -> 1e308 kg was "+inf %" (the change's and the total's); once physics.mass
    gives no body past its bounds, the total read "3.5 -> 2.5 kg (-28.6 %)", the link left out
    silently. The percent that is past a float is left out (the change in kg stays), and the
    masses are not compared, saying which inertial."""
    from urdftool.report import diff as report

    result = compare(tmp_path, ARM.replace('<mass value="1.0"/>', '<mass value="1e308"/>'),
                     collisions=False)
    [change] = result.changes
    assert (change.field, change.delta, change.percent) == ("inertial.mass", 1e308, None)
    assert result.effects.mass_unknown == ("new: link 'upper': <inertial><mass> 1e+308 kg is "
                                           "past the 1e+30 kg urdftool computes mass "
                                           "properties with")
    shown = report.text(result)
    assert "inf" not in shown and "total mass and centre of mass not compared: new: link" in shown
    assert report.as_json(result)["effects"]["mass_kg"] is None


def test_a_large_percent_that_a_float_holds_is_kept(tmp_path):
    result = compare(tmp_path, ARM.replace('<mass value="1.0"/>', '<mass value="1e29"/>'),
                     collisions=False)
    [change] = result.changes
    assert change.percent == pytest.approx(1e31)
    assert result.effects.mass_unknown is None and result.effects.new_mass == pytest.approx(1e29)
