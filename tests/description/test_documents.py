"""Companion documents read with their lines: where a YAML syntax error is reported."""

from __future__ import annotations

import pytest

from urdftool.description.documents import read_srdf, read_yaml

CONTROLLERS_7_LINES = """\
humanoid_robot:
  head_controller:
    type: position_controllers/JointTrajectoryController
    joints: [head_pan, head_tilt]
    constraints:
      goal_time: 0.6
      head_pan: {trajectory: 0.1, goal: "0.1}
"""


@pytest.mark.parametrize("text, line", [
    (CONTROLLERS_7_LINES, 7),                   # unclosed quote: where it opened, not line 8
    ("a: 1\nb: [\n", 2),                        # the stream ends inside a bracket
    ("a: {b: 1\n\n\n", 1),                      # where the brace opened
    ("a:\n  b: 'x\n  c: 1\n", 2),               # where the quote opened
    ("a:\n  b: 1\n c: 2\n", 3),                 # a misindented key: its own line
    ("a: 1\nb: [1, 2\nc: 3\n", 2),
])
def test_a_yaml_error_is_located_on_a_line_of_the_file(tmp_path, text, line):
    path = tmp_path / "c.yaml"
    path.write_text(text)
    parsed = read_yaml(path)
    assert parsed.data is None and parsed.problem
    assert parsed.line == line and 1 <= parsed.line <= len(text.splitlines())


def test_an_srdf_left_open_is_located_where_the_open_tag_is(tmp_path):
    path = tmp_path / "r.srdf"
    path.write_text('<robot name="r">\n  <group name="a">\n')
    parsed = read_srdf(path)
    assert parsed.data is None and "Premature end" in parsed.problem and parsed.line == 2


def _alias_chain(count: int) -> str:
    return "c0: &c0 [x]\n" + "".join(f"c{i}: &c{i} [*c{i - 1}]\n" for i in range(1, count))


def _alias_bomb() -> str:
    text = "a0: &a0 [j, j, j, j, j, j, j, j, j]\n"
    return text + "".join(f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 9) + "]\n" for i in range(1, 10))


@pytest.mark.parametrize("text, line, words", [
    (_alias_chain(1000), 201, "nest collections deeper than 200"),
    (_alias_bomb(), 6, "a YAML bomb"),
])
def test_aliases_past_the_limits_are_a_located_yaml_error_in_every_loader(tmp_path, text, line, words):
    """An alias chain (``c1: &c1 [*c0]``...) built data 1,000 levels deep from text two deep:
    every walker of controllers and MoveIt YAML crashed with RecursionError (U900); nine
    lines of aliases (9^10 items) ran a check to its time or memory budget. Every loader built
    on yaml_limits.DepthLimit refuses both at their line, the companions' and xacro's alike."""
    import yaml

    from urdftool.description.xacro_sandbox import SandboxViolation, refuse_yaml_bomb
    from urdftool.description.yaml_limits import BoundedLoader

    path = tmp_path / "c.yaml"
    path.write_text(text)
    parsed = read_yaml(path)
    refused, problem, where = parsed.data is None, parsed.problem, parsed.line  # no repr of a bomb
    assert refused and where == line and words in problem
    with pytest.raises(yaml.YAMLError, match=words):
        yaml.load(text, Loader=BoundedLoader)  # noqa: S506 - the safe loader
    with pytest.raises(SandboxViolation, match=f"c.yaml:{line}: .*{words}"):
        refuse_yaml_bomb(text, "c.yaml")
    path.write_text(_alias_chain(150))  # shared and as deep as the limit allows: read
    value = read_yaml(path).data["c149"]
    for _ in range(149):
        value = value[0]
    assert value == ["x"]


def test_a_key_repeated_in_a_ros2_file_is_merged_without_copying_all_before_it(tmp_path, monkeypatch):
    """20,000 ``/**:`` blocks each adding a parameter (750 KB) took 22.8 s to read: each merge
    copied every parameter merged before it (quadratic; 40,000 blocks reach the 60 s budget).
    The maps a mapping's merges made are merged into in place: the items copied are linear."""
    from urdftool.description import documents

    copied = [0]

    class Counting(documents.YamlMap):
        def __init__(self, *args):
            super().__init__(*args)
            copied[0] += len(self)

    monkeypatch.setattr(documents, "YamlMap", Counting)
    path = tmp_path / "c.yaml"
    path.write_text("".join(f"/**:\n  ros__parameters:\n    p{i}: {i}\n    n: {{a{i}: {i}}}\n"
                            for i in range(2000)))
    data = read_yaml(path).data["/**"]["ros__parameters"]
    assert data["p1999"] == 1999 and data["n"] == {f"a{i}": i for i in range(2000)}
    assert data.lines["p0"] == 3 and data.lines["p1999"] == 4 * 1999 + 3
    assert copied[0] < 20 * 2000  # was 4,000,000


def test_merged_never_changes_a_map_an_alias_shares(tmp_path):
    path = tmp_path / "c.yaml"
    path.write_text("base: &b\n  ros__parameters: {a: 1}\n/**: *b\n/**:\n  ros__parameters: {c: 3}\n"
                    "/**:\n  ros__parameters: {d: 4}\nagain: *b\n")
    data = read_yaml(path).data
    assert data["/**"]["ros__parameters"] == {"a": 1, "c": 3, "d": 4}
    assert data["base"] == data["again"] == {"ros__parameters": {"a": 1}}


def test_an_integer_past_pythons_digits_is_a_located_yaml_error(tmp_path):
    """int() refuses a decimal of more than 4,300 digits with a ValueError, which YAML readers
    do not catch (fk --dh ended in a traceback): every loader built on yaml_limits.DepthLimit
    makes it a YAML error at its line."""
    import yaml

    from urdftool.description.yaml_limits import BoundedLoader

    path = tmp_path / "c.yaml"
    path.write_text("a: 1\nb: " + "9" * 5000 + "\n")
    parsed = read_yaml(path)
    assert parsed.data is None and parsed.line == 2 and "5,000 characters" in parsed.problem
    with pytest.raises(yaml.YAMLError, match="5,000 characters"):
        yaml.load(path.read_text(), Loader=BoundedLoader)  # noqa: S506 - the safe loader
    assert yaml.load("a: 0x" + "f" * 5000, Loader=BoundedLoader)["a"] == 16 ** 5000 - 1  # noqa: S506
