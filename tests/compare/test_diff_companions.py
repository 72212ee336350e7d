"""``diff`` of the companions: SRDF groups and disabled pairs, controller YAML."""

from __future__ import annotations

from pathlib import Path

import pytest

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


def test_a_controller_value_yaml_builds_beyond_json_is_written_exact_in_every_format(tmp_path):
    """attack30: a set, a date, bytes and an ordered map's pairs in controller YAML were a
    TypeError traceback of ``diff -f json`` (no JSON value) and their repr, unquoted, in the
    text and Markdown reports; a key is the file's words: one line, a code span in Markdown."""
    import json

    from urdftool.report import diff as report

    values = ("set_of: !!set {b, a}\n    day: 2001-02-03\n    blob: !!binary aGk=\n"
              "    pairs: !!omap [{x: 1}, {y: 2}]\n    \"k\\n![I](https://e/x)\": 1\n")
    new = CONTROLLERS.replace("    constraints:", "    " + values + "    constraints:")
    result = diff(side(tmp_path / "old"), side(tmp_path / "new", controllers=new))
    data = json.loads(json.dumps(report.as_json(result)))
    assert {c["field"].rpartition(".")[2]: c["new"] for c in data["changes"]} == {
        "set_of": ["a", "b"], "day": "2001-02-03", "blob": "hi", "pairs": [["x", 1], ["y", 2]],
        "k\n![I](https://e/x)": 1}
    text, markdown = report.text(result), report.markdown(result)
    assert "arm.arm_controller.k\\n![I](https://e/x) (none) -> 1\n" in text
    assert "arm.arm_controller.day (none) -> '2001-02-03'" in text
    assert "- controllers `config/controllers.yaml`: `arm.arm_controller.k\\n![I](https://e/x)` " \
        "(none) -> 1\n" in markdown
    assert "`arm.arm_controller.set_of` (none) -> (`a`, `b`)" in markdown


def test_a_value_json_cannot_hold_is_spelt_as_the_text_report_writes_it(tmp_path):
    """JSON has no infinity: ``diff -f json`` wrote YAML's ``.inf``, ``-.inf`` and ``.nan`` as
    null, which is also its spelling of a value that is none (``~``): ``.inf -> ~`` was null
    -> null. Each is the string the text and Markdown reports write (``inf``, ``-inf``,
    ``nan``, :func:`urdftool.numbers.number`); none stays null."""
    import io
    import json

    from urdftool.report import diff as report

    values = "  a: .inf\n  b: -.inf\n  c: .nan\n  d: 1.0\n"
    result = diff(side(tmp_path / "old", controllers=CONTROLLERS + values),
                  side(tmp_path / "new", controllers=CONTROLLERS + values.replace(
                      ".inf\n  b", "~\n  b").replace("-.inf", "2.0").replace(".nan", "3.0")
                      .replace("1.0", "-.inf")))
    stream = io.StringIO()
    report.write(result, "json", stream)
    data = json.loads(stream.getvalue(), parse_constant=lambda name: pytest.fail(name))
    assert {c["field"]: (c["old"], c["new"]) for c in data["changes"]} == {
        "arm.a": ("inf", None), "arm.b": ("-inf", 2.0), "arm.c": ("nan", 3.0),
        "arm.d": (1.0, "-inf")}
    shown = report.text(result) + report.markdown(result)
    for old, new in (("inf", "(none)"), ("-inf", "2"), ("nan", "3"), ("1", "-inf")):
        assert f" {old} -> {new}" in shown


def _unreadable(path, kind, outside):
    """Replace the file at ``path`` by something no side can compare: ``kind`` names it."""
    import os

    path.unlink()
    if kind == "fifo":
        os.mkfifo(path)
    elif kind == "folder":
        path.mkdir()
    elif kind == "link out":  # (to a file of the right kind, outside the repository)
        outside.write_text(path.suffix == ".srdf" and SRDF or CONTROLLERS)
        path.symlink_to(outside)
    elif kind == "invalid UTF-8":
        path.write_bytes(b"arm: \xff\xfe\n" if path.suffix == ".yaml" else b"<robot>\xff")
    else:  # "not parsed": well-formed on neither reader
        path.write_text("arm: [" if path.suffix == ".yaml" else "<robot name='arm'>")


KINDS = ("fifo", "folder", "link out", "invalid UTF-8", "not parsed")


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("which", ("old", "new"))
@pytest.mark.parametrize("place", ("arm.srdf", "config/controllers.yaml"))
def test_a_companion_one_side_cannot_read_is_not_compared_not_removed_or_equal(tmp_path, kind,
                                                                            which, place):
    sides = {name: tmp_path / name for name in ("old", "new")}
    robots = {name: side(folder) for name, folder in sides.items()}
    _unreadable(sides[which] / place, kind, tmp_path / f"outside{Path(place).suffix}")
    robots[which] = load_text(sides[which], ARM, "arm.urdf")  # (its companions found anew)
    result = diff(robots["old"], robots["new"])
    [item] = result.not_compared
    assert (item.element, item.name) == (("srdf", "arm.srdf") if place == "arm.srdf" else
                                         ("controllers", place))
    assert getattr(item, which) and getattr(item, "new" if which == "old" else "old") is None
    assert result.companions == [] and not result.equivalent
    assert str(tmp_path / "outside") not in repr(item)  # (a link leading out: never where)


def test_a_file_neither_side_parses_is_the_same_file_when_its_bytes_are(tmp_path):
    broken = "arm: [\n"
    same = diff(side(tmp_path / "a", controllers=broken), side(tmp_path / "b", controllers=broken))
    assert same.equivalent and same.not_compared == []
    other = diff(side(tmp_path / "c", controllers=broken),
                 side(tmp_path / "d", controllers=broken + "# a comment\n"))
    assert [(i.element, i.name) for i in other.not_compared] == [
        ("controllers", "config/controllers.yaml")]


@pytest.mark.parametrize("which", ("old", "new"))
def test_a_companion_in_a_folder_that_is_a_link_is_not_compared(tmp_path, which):
    """The config folder of a side a link to a folder holding the same file (outside the
    repository): discovery never enters it, and the file was 'removed' (exit 1)."""
    import shutil

    sides = {name: tmp_path / name for name in ("old", "new")}
    robots = {name: side(folder) for name, folder in sides.items()}
    shutil.move(sides[which] / "config", tmp_path / "elsewhere")
    (sides[which] / "config").symlink_to(tmp_path / "elsewhere")
    robots[which] = load_text(sides[which], ARM, "arm.urdf")
    result = diff(robots["old"], robots["new"])
    assert [(i.element, i.name, bool(getattr(i, which))) for i in result.not_compared] == [
        ("controllers", "config/controllers.yaml", True)]
    assert result.companions == [] and "elsewhere" not in repr(result.not_compared)
