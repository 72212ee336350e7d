"""``urdftool.kinematics.configuration``: which values a robot's joints take when not given."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import ROBOTS
from urdftool.kinematics import configuration as config
from urdftool.description.load import load

# 'shoulder' cannot be at 0 (its limits are 0.5 to 1.5); 'elbow' can
ARM = """<robot name="arm">
  <link name="base"/>
  <link name="upper"><inertial><origin xyz="0.2 0 0"/><mass value="1"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="fore"><inertial><origin xyz="0.1 0 0"/><mass value="0.5"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 1 0"/>
    <limit lower="0.5" upper="1.5" effort="10" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/>
    <origin xyz="0.4 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="1"/></joint>
</robot>
"""


@pytest.fixture
def arm(tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(ARM)
    return load(str(path))


def test_joint_values_pose_an_unnamed_joint_as_every_command_does(arm):
    # dynamics computed G(q) at shoulder=0, outside its limits, where fk, collisions and
    # render pose it mid-range
    variables = config.variables_of(arm)
    drawn = config.from_words(variables, {}).values[0].tolist()
    values = config.joint_values(arm, {})
    assert values.q == {"shoulder": 1.0}
    assert drawn == [values.q.get(v.name, 0.0) for v in variables] == [1.0, 0.0]
    assert values.warnings == []


def test_joint_values_keep_what_is_given_and_warn_only_about_it(arm):
    values = config.joint_values(arm, {"shoulder": "2", "elbow": "0.5"}, {"elbow": "1"})
    assert values.q == {"shoulder": 2.0, "elbow": 0.5} and values.v == {"elbow": 1.0}
    assert len(values.warnings) == 1 and "shoulder" in values.warnings[0]
    assert config.joint_values(arm, {"elbow": "0.5"}).q == {"shoulder": 1.0, "elbow": 0.5}


@pytest.mark.parametrize("v, a", [({"elbow": "1e308"}, None), ({"elbow": "-1e151"}, None),
                                  (None, {"shoulder": "1e200"})])
def test_a_velocity_or_acceleration_the_dynamics_cannot_square_is_refused(arm, v, a):
    # dynamics --v 1e308 gave numpy's overflow warnings and torques of "inf N m" (the class of
    # ik's targets past numbers.SQUARABLE, session 14)
    from urdftool.errors import ConfigError

    with pytest.raises(ConfigError, match="past what the dynamics computes with") as raised:
        config.joint_values(arm, {}, v, a)
    assert raised.value.argument == ("v" if v else "a")
    assert config.joint_values(arm, {}, {"elbow": "1e150"}).v == {"elbow": 1e150}


def test_a_row_lacking_many_names_lists_a_dozen_and_how_many():
    """Cut as every list is (``errors.listed``): it had its own copy of the cut."""
    import json

    from urdftool.errors import ConfigError

    names = {f"j{i}": 0 for i in range(13)}
    with pytest.raises(ConfigError) as error:
        config._json_rows(json.dumps([names, {}]).encode(), "q.json", "joint")
    assert str(error.value) == ("q.json: row 2: row lacks j0, j1, j2, j3, j4, j5, j6, j7, j8, j9, "
                                "j10, j11, ... (13 in all) (every row must name the same joints)")


def test_every_draw_between_limits_is_one_that_takes_any_span():
    """Limits of -1e308 and 1e308 (a span past the largest float) made numpy's uniform raise
    "Range exceeds valid bounds": a traceback of workspace, ik and dynamics --samples. Every
    draw between limits is configuration.within (an ast scan holds it), which draws within
    numbers.MAX_COORDINATE (session 24: limits of +-1e200 placed a link at 1e199, a workspace
    "max reach inf m") and any other span as numpy draws it."""
    import ast
    import math
    from pathlib import Path

    import numpy as np

    import urdftool

    from urdftool.numbers import MAX_COORDINATE

    wide = config.within(config.random_stream(0), [-1e308, 0.0], [1e308, 1.0], (200, 2))
    assert (abs(wide) < MAX_COORDINATE).all()
    assert wide[:, 0].min() < -MAX_COORDINATE / 2 and wide[:, 0].max() > MAX_COORDINATE / 2
    assert (0 <= wide[:, 1]).all() and (wide[:, 1] <= 1).all()
    assert (config.within(config.random_stream(3), [2.0, -1.0], [1.0, math.pi], (5, 2)) ==
            config.random_stream(3).uniform([1.0, -1.0], [2.0, math.pi], (5, 2))).all()
    draws = [f"{path.name}:{node.lineno}" for path in Path(urdftool.__file__).parent.rglob("*.py")
             for node in ast.walk(ast.parse(path.read_text()))
             if isinstance(node, ast.Attribute) and node.attr == "uniform"]
    assert [d for d in draws if not d.startswith("configuration.py:")] == [] and draws


def test_a_joint_whose_limits_span_past_the_largest_float_is_sampled(tmp_path):
    robot = tmp_path / "p.urdf"
    robot.write_text(
        '<robot name="p"><link name="a"/><link name="b"/><joint name="s" type="prismatic">'
        '<parent link="a"/><child link="b"/><axis xyz="0 0 1"/>'
        '<limit lower="-1e308" upper="1e308" effort="1" velocity="1"/></joint></robot>')
    from urdftool.numbers import MAX_COORDINATE

    values = config.random(config.variables_of(load(str(robot))), 50, 0).values
    assert (abs(values) < MAX_COORDINATE).all()
    assert values.min() < -MAX_COORDINATE / 2 < MAX_COORDINATE / 2 < values.max()


@pytest.mark.parametrize("mimics, message", [
    ({"b": "a"}, "joint 'b' mimics 'a': set 'a' instead"),
    # a mimic of a mimic: the joint at the end of the chain (it said "set 'b'", refused in turn)
    ({"c": "b", "b": "a"}, "joint 'c' mimics 'b', which mimics 'a': set 'a' instead"),
    ({"d": "c", "c": "b", "b": "a"},
     "joint 'd' mimics 'c', which follows 'a' through 1 more mimic joint(s): set 'a' instead"),
    ({"c": "b", "b": "c"}, "joint 'c' mimics 'b', in a cycle of mimic joints: no joint sets it"),
    ({"c": "b", "b": "fixed_one"}, "joint 'c' mimics 'b', which mimics 'fixed_one'; "
                                   "'fixed_one' takes no value"),
])
def test_setting_a_mimic_joint_names_the_joint_to_set(mimics, message):
    variables = [config.Variable("a", "a", "revolute", -1.0, 1.0)]
    given = next(iter(mimics))
    with pytest.raises(config.ConfigError) as error:
        config.from_words(variables, {given: "0.5"}, mimics=mimics)
    assert str(error.value) == message


@pytest.mark.parametrize("given", ["words", "file", "joint values", "default"])
def test_a_joint_value_past_the_farthest_coordinate_is_refused_however_given(tmp_path, given):
    """--q s=1e200 of a prismatic joint (or its default, the middle of limits at 1e200 and
    3e200) placed its link at 1e200: a workspace "max reach inf m", dynamics torques of NaN.
    configuration.placeable, the one check of the values given (words, a q-file, dynamics'
    joint values), refuses it at numbers.MAX_COORDINATE."""
    from urdftool.errors import ConfigError

    lower, upper = ("1e200", "3e200") if given == "default" else ("-1", "1")
    robot = tmp_path / "p.urdf"
    robot.write_text(
        '<robot name="p"><link name="a"/><link name="b"/><joint name="s" type="prismatic">'
        '<parent link="a"/><child link="b"/><axis xyz="0 0 1"/>'
        f'<limit lower="{lower}" upper="{upper}" effort="1" velocity="1"/></joint></robot>')
    loaded = load(str(robot))
    variables = config.variables_of(loaded)
    (tmp_path / "q.csv").write_text("s\n0.5\n1e200\n")
    ask = {"words": lambda: config.from_words(variables, {"s": "1e200"}),
           "file": lambda: config.from_file(variables, str(tmp_path / "q.csv")),
           "joint values": lambda: config.joint_values(loaded, {"s": "-1e200"}),
           "default": lambda: config.from_words(variables, {})}[given]
    with pytest.raises(ConfigError, match=r"joint 's' = -?[12]e\+200.* is past the 4\.612e\+10 "
                                          r"\(m or rad\) urdftool places a link within"):
        ask()
    if given != "default":
        assert config.from_words(variables, {"s": "4e10"}).values[0, 0] == 4e10


def test_a_q_file_value_past_the_farthest_coordinate_is_said_as_the_files(run_cli, tmp_path):
    """attack25: a --q-file row of 1e308 was refused as "--q: joint 'l_knee' = 1e+308", an
    option not given; the refusal names the file."""
    table = tmp_path / "q.csv"
    table.write_text("l_knee,l_hip_yaw\n1e308,0\n")
    result = run_cli("fk", ROBOTS / "humanoid" / "humanoid.urdf.xacro", "--q-file", table)
    assert result.exit_code == 2, result.output
    assert f"{table}: joint 'l_knee' = 1e+308 is past" in result.output
    assert "--q:" not in result.output


def _read_measured(path):
    """(names, table, the peak of memory allocated [bytes]) of reading the file of numbers
    at ``path``."""
    import tracemalloc

    tracemalloc.start()
    try:
        read, table = config.read_table(str(path), "q-file", "joint")
        return read, table, tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_a_file_of_numbers_is_converted_a_chunk_of_rows_at_a_time(tmp_path):
    """Every cell of a --q-file was held as a string at once, then as a float (433 MB for a
    16 MB file of 12,000 rows of 300 joints): what reading holds now is the text, the table
    and a chunk of rows, and the table is the one every row at once gives."""
    names = [f"j{i}" for i in range(300)]
    rows = [[("0.1", "-0.25", "1", "3e-2")[(r + c) % 4] for c in range(300)] for r in range(4000)]
    path = tmp_path / "q.csv"
    path.write_text(",".join(names) + "\n" + "".join(",".join(row) + "\n" for row in rows))
    read, table, peak = _read_measured(path)
    assert read == names and np.array_equal(table, np.array(rows, dtype=float))
    assert peak < 4 * table.nbytes, (peak, table.nbytes)  # (every cell at once: 7.6 times)


def test_a_json_file_of_numbers_is_read_an_element_of_its_list_at_a_time(tmp_path):
    """The whole document was made at once as json reads it, every row a dict of floats (and
    its text besides): 6.4 times the file's size at the peak; what reading holds now is the
    file's bytes, a piece of its text, the table and a chunk of rows."""
    import json

    names = [f"j{i}" for i in range(50)]
    rows = [[(0.1, -0.25, 1.0, 3e-2)[(r + c) % 4] for c in range(50)] for r in range(4000)]
    path = tmp_path / "q.json"
    path.write_text(json.dumps([dict(zip(names, row)) for row in rows]))
    read, table, peak = _read_measured(path)
    assert read == names and np.array_equal(table, np.array(rows))
    assert peak < 3 * path.stat().st_size, (peak, path.stat().st_size)


_DOCUMENTS = [
    '[{"a": 1, "b": 2e-5}, {"b": -1.5E+3, "a": 12345678}]', '[\n {"a": 1}\n ,\n {"a": 2} \n]\n',
    '{"a": 1}', '[]', '', '  \n ', '[{"a": 1},]', '[{"a": 1}\n\n{"a": 2}]', '[{"a": 1}] x',
    '[{"a": 1}\n, {"a": 2}\n, {"a": 3}\n, {"a": ]', '[{"a": 1e}]', '[{"a": "x\n', '[\n\n',
    '[{"a": 1}, 2]', '5', '[{"a": 1}, {"b": 1}]', '[{"a": 1, "b": 2}, {"a": 1}, {"a": 1, "b": 2}]',
    '[{"a": 1}, {"a": 1, "a": 2}, x]', '[{"a": 1}, x, {"a": 1, "a": 2}]', '\ufeff[{"a": 1}]',
    '[{"a": NaN, "b": -Infinity}]', '[{"a": 1.5}, {"a": ' + "9" * 40 + '.25}]', '[{"a": tru',
]


@pytest.mark.parametrize("piece", [1, 2, 3, 5, 1 << 18])
def test_the_json_reader_says_what_the_whole_document_read_at_once_says(monkeypatch, piece):
    """Read a piece of text at a time (of ``piece`` bytes: a number, a word, a string or a
    line break cut anywhere), a JSON file of numbers gives the table, or the error and its
    line, that reading the whole document with json gives, in the same order."""
    import json

    from urdftool.errors import ConfigError

    def whole(text):  # (main's reader, as it was: json.loads, then the rows' checks; its
        # numbers kept as written, as the reader keeps them)
        try:
            data = json.loads(text, object_pairs_hook=config._once_each,
                              parse_int=config._Number, parse_float=config._Number)
        except config._Twice as error:
            return f"q.json: joint '{error.args[0]}' is given twice in one object"
        except json.JSONDecodeError as error:
            return f"q.json:{error.lineno}: invalid JSON: {error.msg}"
        data = [data] if isinstance(data, dict) else data
        if not isinstance(data, list) or not data:
            return "q.json: expected a JSON list of objects {joint name: value}"
        bad = next((n for n, row in enumerate(data, 1) if not isinstance(row, dict)), None)
        if bad:
            return f"q.json: row {bad}: expected an object {{joint name: value}}"
        names = list(dict.fromkeys(name for row in data for name in row))
        short = next((n for n, row in enumerate(data, 1) if len(row) < len(names)), None)
        if short:
            lacking = ", ".join(n for n in names if n not in data[short - 1])
            return f"q.json: row {short}: row lacks {lacking} (every row must name the same joints)"
        return names, [[row[name] for name in names] for row in data]

    monkeypatch.setattr(config, "DECODED_AT_ONCE", piece)
    for text in _DOCUMENTS:
        try:
            names, count, rows = config._json_rows(text.encode(), "q.json", "joint")
            said = names, list(rows())
            assert count == len(said[1])
        except ConfigError as error:
            said = str(error)
        assert said == whole(text.encode().decode("utf-8-sig")), text
