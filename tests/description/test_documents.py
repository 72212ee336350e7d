"""Companion documents read with their lines: where a YAML syntax error is reported."""

from __future__ import annotations

import math

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


def test_a_control_character_in_yaml_is_a_located_yaml_error(tmp_path):
    """PyYAML's reader refuses a control character (a BEL in a controllers file) as the loader
    is made: the ReaderError left read_yaml, and every rule reading the robot's companions
    crashed (60 U900 on r2d2 with such a file). A YAML problem at its line instead."""
    path = tmp_path / "c.yaml"
    path.write_text("controller_manager:\n  ros__parameters:\n    update_rate: 50\x07\n")
    parsed = read_yaml(path)
    assert parsed.data is None and parsed.line == 3
    assert parsed.problem == "unacceptable character #x0007: special characters are not allowed"


def test_an_srdf_left_open_is_located_where_the_open_tag_is(tmp_path):
    path = tmp_path / "r.srdf"
    path.write_text('<robot name="r">\n  <group name="a">\n')
    parsed = read_srdf(path)
    assert parsed.data is None and "Premature end" in parsed.problem and parsed.line == 2


def test_an_srdf_past_line_65535_is_read_with_lxmls_lines_there(tmp_path):
    """lxml's sourceline setter takes an unsigned short: an SRDF of 100,000 entries (8 MB,
    under the size limit) crashed 61 rules with OverflowError (U900 each). Past line 65,535 an
    element keeps lxml's own line (libxml2 counts one more than the file there)."""
    from lxml import etree

    path = tmp_path / "r.srdf"
    path.write_text('<robot name="r">\n<group\n  name="g"/>\n' + '<disable_collisions '
                    'link1="a" link2="b" reason="Never"/>\n' * 70_000 + '</robot>\n')
    parsed = read_srdf(path)
    assert parsed.problem is None
    assert parsed.data.find("group").sourceline == 2  # its "<", not lxml's ">" (line 3)
    entries = [element.sourceline for element in parsed.data.iter("disable_collisions")]
    lxml = [element.sourceline for element in etree.parse(str(path)).iter("disable_collisions")]
    assert entries[:65_531] == list(range(4, 65_535)) and entries[65_532:] == lxml[65_532:]


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
    assert yaml.load("a: 0x" + "f" * 250, Loader=BoundedLoader)["a"] == 16 ** 250 - 1  # noqa: S506


# values YAML's grammar lets through that PyYAML's constructors raise Python's own errors for
# (or refuse): each was a traceback (U900 from every rule reading companions, fk --dh's own)
UNCONSTRUCTABLE = [
    ("a: 2001-02-30\n", "a date (tag:yaml.org,2002:timestamp): day is out of range for month"),
    ("a: 2001-01-01 00:00:00 +99:00\n", "a date"),
    ("a: !!timestamp x\n", "'x' cannot be constructed as a date"),
    ("a: !!float junk\n", "'junk' cannot be constructed as a float"),
    ("a: !!int junk\n", "'junk' cannot be constructed as an integer"),
    ("a: 0b_\n", "'0b_' cannot be constructed as an integer"),
    ("a: !!bool maybe\n", "'maybe' cannot be constructed as a boolean"),
    ("a: !!map abc\n", "expected a mapping node, but found scalar"),
    ("a: !!seq abc\n", "expected a sequence node, but found scalar"),
    ("a: !!map [a, b]\n", "expected a mapping node, but found sequence"),
    ("a: !!python/name:os.system x\n", "could not determine a constructor"),
    ("a: {<<: 5}\n", "expected a mapping or list of mappings for merging"),
    ("a: " + "1" * 400 + "\n", "an integer of 400 digits, past the largest double"),
]


@pytest.mark.parametrize("text, words", UNCONSTRUCTABLE)
def test_a_value_pyyaml_cannot_construct_is_a_located_yaml_error_in_every_loader(tmp_path, text, words):
    """``2001-02-30`` (a date to YAML 1.1, and none), ``!!float junk``, ``!!bool maybe``, a
    ``!!map`` of a scalar: PyYAML's constructors raised ValueError, KeyError, AttributeError,
    TypeError, which no reader caught (U900 from 61 rules, fk --dh's traceback). The one guard
    of every loader (yaml_limits.DepthLimit.construct_object) makes each a YAML error at the
    value's line, saying what was written and what YAML made of it; an integer past a double
    too (float() of it raised OverflowError in the rules reading numbers)."""
    import yaml

    from urdftool.description.yaml_limits import BoundedLoader, OnceLoader

    path = tmp_path / "c.yaml"
    path.write_text("first: 1\n" + text)
    parsed = read_yaml(path)
    assert parsed.data is None and parsed.line == 2 and words in parsed.problem
    for loader in (BoundedLoader, OnceLoader):
        with pytest.raises(yaml.YAMLError) as raised:
            yaml.load(path.read_text(), Loader=loader)  # noqa: S506 - the safe loaders
        assert raised.value.problem_mark.line == 1


@pytest.mark.parametrize("text, words", UNCONSTRUCTABLE)
def test_what_pyyaml_cannot_construct_in_a_ros2_parameter_file_is_read_as_ros2_reads_it(tmp_path, text, words):
    """rcl_yaml_param_parser types each plain scalar itself (a boolean, an integer, a double,
    else a string), reads no dates and constructs no tag but ``!!str``: ``2001-02-30`` is a
    string parameter to ROS 2, and a node given the file loads it. Only what loads it with
    PyYAML fails (a Python launch file), so such a value is read as its text with a caution
    saying so at its line, not the file's error; a launch file, which only PyYAML reads, keeps
    the error."""
    path = tmp_path / "c.yaml"
    indented = text.replace("\n", "\n    ").rstrip(" ")
    path.write_text("node:\n  ros__parameters:\n    first: 1\n    " + indented)
    parsed = read_yaml(path)
    assert parsed.problem is None and parsed.line == 4
    assert words in parsed.caution and "ROS 2's parameter parser reads it as written" in parsed.caution
    assert "PyYAML (yaml.safe_load) fails" in parsed.caution
    value = parsed.data["node"]["ros__parameters"]["a"]
    assert isinstance(value, (str, list)) or value == {"<<": 5}
    if "past the largest double" not in words:  # (to a launch file an integer is text)
        assert read_yaml(path, parameters=False).line == 4 and read_yaml(path, parameters=False).problem


def test_an_alias_in_a_ros2_parameter_file_is_a_caution_naming_who_refuses_it(tmp_path):
    """rcl_yaml_param_parser refuses every alias ("Will not support aliasing"): a node given
    such a file as its parameters fails to start, which nothing said; a launch file loading it
    with PyYAML reads it, so a caution, at the alias, not the file's error."""
    path = tmp_path / "c.yaml"
    path.write_text("defaults: &d {p: 1}\nnode:\n  ros__parameters:\n    <<: *d\n    q: 2\n")
    parsed = read_yaml(path)
    assert parsed.problem is None and parsed.data["node"]["ros__parameters"] == {"p": 1, "q": 2}
    assert parsed.line == 4 and "refuses every alias" in parsed.caution
    path.write_text("defaults: &d {p: 1}\nnode:\n  params: *d\n")  # ROS 1: rosparam reads it
    assert read_yaml(path).caution is None


def test_merge_keys_and_unknown_tags_are_read_as_pyyaml_reads_them(tmp_path):
    """The companions' loader never flattened merge keys (``<<: *defaults``, which rosparam
    reads): every file using one was "could not determine a constructor for the tag
    'tag:yaml.org,2002:merge'" (U601); and a mapping under an unknown tag (``!foo {type:
    ...}``) was read empty (its constructor's generator cut at its first step)."""
    path = tmp_path / "c.yaml"
    path.write_text("base: &b {joints: [a], rate: 1}\nc:\n  <<: *b\n  rate: 2\n"
                    "d: !foo {type: x/Y, joints: !bar [j]}\n")
    data = read_yaml(path).data
    assert data["c"] == {"joints": ["a"], "rate": 2} and data["c"].lines == {"joints": 1, "rate": 4}
    assert data["d"] == {"type": "x/Y", "joints": ["j"]} and data["d"].lines["joints"] == 5


def test_an_integer_past_a_double_is_an_integer_to_a_launch_file(tmp_path):
    """A launch file's readers take an integer as text (ROS 2's launch YAML turns a value into
    a string): no double bounds it there."""
    path = tmp_path / "x.launch.yaml"
    path.write_text("launch:\n- arg: {name: n, default: " + "1" * 400 + "}\n")
    assert read_yaml(path, parameters=False).data["launch"][0]["arg"]["default"] == int("1" * 400)


ROSPARAM_ANGLES = [  # (value written, what rosparam makes of it: radians, or its error)
    ("!degrees 180", math.pi), ("!degrees ' 90 '", math.pi / 2), ("!degrees deg(90)", math.pi / 2),
    ("!degrees 1_80", math.pi), ("!radians 2*pi", 2 * math.pi), ("!radians -pi/2", -math.pi / 2),
    ("!radians rad(pi/4)", math.pi / 4), ("!radians 1.5", 1.5), ("!radians (1+1)**2", 4.0),
    ("!degrees abc", "invalid degree value: abc"), ("!degrees ''", "invalid degree value: "),
    ("!degrees 90deg", "invalid degree value: 90deg"),
    ("!degrees deg(ninety)", "invalid degree value: deg(ninety)"),
    ("!radians 2*", "invalid radian expression: 2*"), ("!radians abc", "name 'abc' is not defined"),
    ("!radians 1/0", "division by zero"), ("!radians pipe", "no attribute 'pipe'"),
    ("!radians '\"x\"'", "could not convert string to float"), ("!radians 10**400", "too large"),
    ("!degrees [1]", "expected a scalar node, but found sequence"),
]


@pytest.mark.parametrize("written, made", ROSPARAM_ANGLES)
def test_rosparams_angles_are_read_as_rosparam_reads_them_in_a_ros1_parameter_file(tmp_path, written,
                                                                                    made):
    """rosparam (ROS 1: roslaunch's <rosparam> and ``rosparam load``) adds ``!degrees`` and
    ``!radians`` to PyYAML's safe loader, and reads ``deg(N)`` and ``rad(EXPR)`` as them:
    ``float(N) * pi / 180``, ``float(eval(EXPR))`` with ``pi`` for math.pi. A value it cannot
    make a number of raises, and roslaunch refuses the file ("contains invalid YAML"): no
    parameter of it is set. Each was read as its text, silently; now a number as rosparam
    makes it, or the file's YAML error at its line in rosparam's (Python's) words. A ROS 2
    parameter file, and a launch file, read them as before (their readers have no such tags)."""
    path = tmp_path / "c.yaml"
    path.write_text(f"first: 1\nangle: {written}\n")
    parsed = read_yaml(path)
    if isinstance(made, float):
        assert parsed.problem is None and parsed.data["angle"] == pytest.approx(made)
    else:
        assert parsed.data is None and parsed.line == 2 and made in parsed.problem, parsed.problem
    path.write_text(f"n:\n  ros__parameters:\n    angle: {written}\n")
    assert not isinstance(read_yaml(path).data["n"]["ros__parameters"]["angle"], float)
    path.write_text(f"launch:\n- arg: {{name: n, default: {written}}}\n")
    assert read_yaml(path, parameters=False).problem is None


def test_a_radian_expression_rosparam_evaluates_beyond_arithmetic_is_left_as_written(tmp_path):
    """``float(eval(EXPR))`` runs any Python: an expression past numbers, pi and arithmetic
    (a call, a name rosparam's module may hold, a power too large to compute) is neither
    evaluated nor judged; it is read as its text, as before. So is what ROS 2's MoveIt reads
    and rosparam not (``inf``: launch_param_builder's ``float(text)``), and ``deg(90)`` written
    plain (rosparam's, text to ROS 2's readers)."""
    path = tmp_path / "c.yaml"
    for written in ("!radians math.sin(1)", "!radians abs(-1)", "!radians os", "!radians 9**9**9",
                    "!radians NS", "!radians inf", "deg(90)", "rad(x)"):
        path.write_text(f"angle: {written}\n")
        parsed = read_yaml(path)
        assert parsed.problem is None and isinstance(parsed.data["angle"], str), written


def _shape(value):
    """A value read from YAML with its types and lines (YamlMap's and YamlList's), to compare."""
    from urdftool.description.documents import YamlList, YamlMap

    if isinstance(value, YamlMap):
        return ("map", value.line, [(k, _shape(v), value.lines.get(k)) for k, v in value.items()])
    if isinstance(value, YamlList):
        return ("list", value.line, value.lines, [_shape(v) for v in value])
    return (type(value).__name__, value)


PARAMETERS = """\
controller_manager:
  ros__parameters:
    update_rate: 50  # [Hz]
    arm_controller: {type: "joint_trajectory_controller/JointTrajectoryController"}

defaults: &defaults
  gains: {p: 100.0, i: 0.01, d: 10}
  enabled: yes
arm_controller:
  ros__parameters:
    <<: *defaults
    joints:
      - shoulder
      - 'elbow'
    limits: [1e3, -.5, 0x1F, .inf, ~, 2001-12-14]
    note: "a \\"quoted\\" word,
      folded"
/**:
  ros__parameters: {p: 1}
/**:
  ros__parameters: {q: 2}
"""


@pytest.mark.parametrize("text", [PARAMETERS, "a: 1\nb: [\n", "a: &x [*x]\n", "", "# only\n"])
def test_yaml_read_through_libyaml_is_read_as_pyyaml_reads_it(tmp_path, monkeypatch, text):
    """A text without the characters libyaml reads otherwise is read with libyaml's parser
    (C): the same data, types and lines as PyYAML's Python reader gives; when it fails,
    PyYAML's own reading answers (its message and line)."""
    from urdftool.description import documents

    path = tmp_path / "c.yaml"
    path.write_text(text)
    used = []
    fast = documents._fast_loader()
    monkeypatch.setattr(documents, "_fast_loader", lambda: used.append(text) or fast)
    read = read_yaml(path)
    monkeypatch.setattr(documents, "_fast_loader", lambda: None)
    expected = read_yaml(path)
    assert used == [text]
    assert (_shape(read.data), read.problem, read.line, read.ros2) == \
        (_shape(expected.data), expected.problem, expected.line, expected.ros2)


def _loaded(loader_class, text: str):
    """What a loader class reads of ``text`` (:func:`_shape`), or the error it raises."""
    loader = loader_class(text)
    loader.merge_repeated = False
    try:
        return _shape(loader.get_single_data())
    except Exception as error:  # noqa: BLE001 - whatever the parser says
        return error


@pytest.mark.parametrize("text", ["a: [1,\t2]\n", "a: b\t\n", "- 1\t\n", "|#\n", "a: !\n",
                                  "[a\n  +1? b]\n", "\n\ufeffa: 1\n"])
def test_what_libyaml_reads_otherwise_is_read_by_pyyaml(tmp_path, text):
    """libyaml takes a tab between tokens, a block scalar's header followed by a comment, a
    ``?`` in a flow scalar, and reads ``!`` alone or a byte order mark within the text
    otherwise: such a text is read by PyYAML alone (a tab there stays its error)."""
    from urdftool.description import documents

    path = tmp_path / "c.yaml"
    path.write_text(text, encoding="utf-8")
    libyaml, pyyaml = (_loaded(documents._fast_loader(), text), _loaded(documents._loader(), text))
    assert not isinstance(libyaml, Exception) and libyaml != pyyaml  # (the case is real)
    read = read_yaml(path)
    assert (_shape(read.data) if read.problem is None else read.problem) == \
        (pyyaml if not isinstance(pyyaml, Exception) else read.problem)
    assert (read.problem is None) == (not isinstance(pyyaml, Exception))


@pytest.mark.parametrize("end, comment", [("\n", ""), ("\r\n", ""), ("\r", ""),
                                          ("\n", 'x: "a\u2028b\x85c\u2029d"\n')])
def test_yaml_lines_are_the_files_whatever_ends_them(tmp_path, end, comment):
    """Every line a YAML file's finding or error says is the file's line as every Location
    numbers them (CR LF, LF, CR): PyYAML's marks also end a line at NEL, LINE and PARAGRAPH
    SEPARATOR (three lines down after the string here), and its reader's error was counted by
    LF (line 1 in a file ended by CR alone). A ROS 2 file ended by CR alone is ROS 2 (its
    ``ros__parameters`` was not at a line start by LF: read as ROS 1)."""
    path = tmp_path / "c.yaml"

    def write(text):
        path.write_bytes((comment + text).replace("\n", end).encode())
        return read_yaml(path)

    read = write("a:\n  ros__parameters:\n    joints:\n      - j1\n      - j2\n")
    first = 1 + bool(comment)
    assert read.ros2 and read.data["a"].lines["ros__parameters"] == first + 1
    assert read.data["a"]["ros__parameters"]["joints"].lines == [first + 3, first + 4]
    assert write("a: 1\nb: [\n").line == first + 1
    assert write("a: 1\nb: \x07\n").line == first + 1
