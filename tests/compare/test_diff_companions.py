"""``diff`` of the companions: SRDF groups and disabled pairs, controller YAML."""

from __future__ import annotations

from conftest import load_text
from compare.test_diff import ARM  # tests/ is on the path: the arm of the diff tests
from urdftool.compare.diff import DiffOptions, diff

SRDF = """<robot name="arm">
  <group name="arm"><chain base_link="base" tip_link="hand"/></group>
  <group name="wrist"><joint name="elbow"/><link name="fore"/></group>
  <disable_collisions link1="base" link2="upper" reason="Adjacent"/>
  <disable_collisions link1="upper" link2="fore" reason="Adjacent"/>
</robot>
"""
CONTROLLERS = """arm:
  arm_controller:
    type: position_controllers/JointTrajectoryController
    joints: [shoulder, elbow]
    constraints:
      goal_time: 0.6
      elbow: {goal: 0.1}
"""


def side(folder, robot=ARM, srdf=SRDF, controllers=CONTROLLERS):
    folder.mkdir(parents=True)
    (folder / "arm.srdf").write_text(srdf)
    (folder / "config").mkdir()
    (folder / "config" / "controllers.yaml").write_text(controllers)
    return load_text(folder, robot, "arm.urdf")


def changes(result):
    return {(c.kind, c.element, c.name, c.field) for c in result.companions}


def test_unchanged_companions_are_no_change(tmp_path):
    result = diff(side(tmp_path / "old"), side(tmp_path / "new", srdf=SRDF.replace(
        'reason="Adjacent"/>\n  <disable', 'reason="Adjacent" />\n\n  <disable')))
    assert result.equivalent and result.companions == []


def test_groups_pairs_and_controller_keys(tmp_path):
    new_srdf = SRDF.replace('tip_link="hand"', 'tip_link="fore"').replace(
        '  <disable_collisions link1="upper" link2="fore" reason="Adjacent"/>\n', "")
    new_controllers = CONTROLLERS.replace("[shoulder, elbow]", "[elbow]").replace("0.6", "0.7")
    result = diff(side(tmp_path / "old"), side(tmp_path / "new", srdf=new_srdf,
                                               controllers=new_controllers))
    assert changes(result) == {
        ("changed", "group", "arm", "members"),
        ("removed", "disable_collisions", "fore/upper", ""),
        ("changed", "controllers", "config/controllers.yaml", "arm.arm_controller.joints"),
        ("changed", "controllers", "config/controllers.yaml",
         "arm.arm_controller.constraints.goal_time")}
    [group] = [c for c in result.companions if c.element == "group"]
    assert (group.old, group.new) == (("chain base -> hand",), ("chain base -> fore",))
    assert not result.equivalent and result.changes == []


def test_names_renamed_in_the_urdf_are_renamed_in_the_companions(tmp_path):
    new = side(tmp_path / "new", ARM.replace('"fore"', '"forearm"').replace('"elbow"',
                                                                             '"elbow_joint"'),
               SRDF.replace('"fore"', '"forearm"').replace('"elbow"', '"elbow_joint"'),
               CONTROLLERS.replace("elbow", "elbow_joint"))
    result = diff(side(tmp_path / "old"), new)
    assert {c.kind for c in result.changes} == {"renamed"}
    assert result.companions == []


def test_companions_can_be_left_out(tmp_path):
    result = diff(side(tmp_path / "old"), side(tmp_path / "new", srdf=SRDF.replace("wrist", "w")),
                  DiffOptions(companions=False))
    assert result.equivalent


def test_a_nan_in_the_controller_yaml_compared_with_itself_is_no_change(tmp_path):
    nan = CONTROLLERS.replace("goal_time: 0.6", "goal_time: .nan").replace(
        "joints: [shoulder, elbow]", "joints: [shoulder, elbow]\n    gains: [.nan, 1]")
    result = diff(side(tmp_path / "old", controllers=nan), side(tmp_path / "new", controllers=nan))
    assert changes(result) == set()
