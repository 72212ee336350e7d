"""Reading attribute values: the one ``<origin>`` reader and its converters."""

from __future__ import annotations

import math

import numpy as np
import pytest
from lxml import etree

from urdftool.description.load import load
from urdftool.description.values import (Origin, axis_xyz, from_chars_double, limit_bound,
                                         limit_range, number_tuple, origin, origin_pose,
                                         parse_numbers, stream_double, strtod_double,
                                         urdfdom_refuses, urdfdom_spelling)
from urdftool.kinematics import dh, transforms
from urdftool.physics import mass, mat3


def _element(text: str):
    return etree.fromstring(text)


def test_absent_origin_is_the_identity():
    assert origin(_element("<joint/>")) == Origin((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), None, None)
    assert origin(None) == Origin()
    assert origin(_element('<joint><origin xyz="1 2 3"/></joint>')).rpy == (0.0, 0.0, 0.0)


@pytest.mark.parametrize("text", [
    "<joint/>", '<joint><origin xyz="1 2 3"/></joint>', '<joint><origin rpy="0 0.5 -1"/></joint>',
    '<joint><origin xyz="1 2" rpy="0 x 0"/></joint>', '<joint><!-- c --><origin xyz="inf 0 0"/>'
    '<origin xyz="9 9 9"/></joint>', '<joint><origin xyz="-0.0 0 1e400"/></joint>'])
def test_origin_pose_is_what_origin_reads(text):
    element = _element(text)
    found = origin(element)
    xyz, rpy = origin_pose(element)
    assert (xyz, rpy) == (found.xyz, found.rpy)
    assert [math.copysign(1, v) for v in xyz] == [math.copysign(1, v) for v in found.xyz]
    assert origin_pose(None) == (origin(None).xyz, origin(None).rpy)


def test_a_malformed_part_reads_as_zero_and_says_why():
    found = origin(_element('<joint><origin xyz="1 2 3" rpy="0 x 0"/></joint>'))
    assert found.xyz == (1.0, 2.0, 3.0) and found.rpy == (0.0, 0.0, 0.0)
    assert found.problem == "rpy: 'x' is not a number (in '0 x 0')"
    assert found.element.tag == "origin"
    assert origin(_element('<joint><origin xyz="1 2"/></joint>')).problem == \
        "xyz: expected 3 numbers, found 2 in '1 2'"


def test_the_converters_agree():
    found = origin(_element('<joint><origin xyz="1 -2 0.5" rpy="0.3 -1.1 2.0"/></joint>'))
    xyz, rotation = mat3.placement(found)
    matrix = transforms.from_origin(found)
    assert np.allclose(matrix[:3, :3], rotation) and np.allclose(matrix[:3, 3], xyz)


ARM = """<robot name="r"><link name="a"/><link name="b"/>
<joint name="j" type="revolute"><parent link="a"/><child link="b"/>
<origin xyz="0 0 1" rpy="{rpy}"/><axis xyz="0 0 1"/>
<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>"""


def test_dh_refuses_a_malformed_origin_at_the_origin_element(tmp_path):
    path = tmp_path / "arm.urdf"
    path.write_text(ARM.format(rpy="0 0 nope"))
    with pytest.raises(dh.DHError, match="joint 'j': <origin> rpy: 'nope' is not a number") \
            as raised:  # (fk's words, since attack25: dh reads origins as fk does)
        dh.extract(load(path), "a", "b")
    assert raised.value.element.tag == "origin"


def test_an_inertial_counts_a_malformed_part_as_zero():
    link = _element('<link name="l"><inertial><origin xyz="0 0 1" rpy="a b c"/>'
                    '<mass value="2"/><inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3"/>'
                    "</inertial></link>")
    body = mass.declared(link)
    assert body.com == (0.0, 0.0, 1.0)
    assert body.inertia == mat3.diagonal((1.0, 2.0, 3.0)) and not math.isnan(body.mass)


def test_number_tuple_is_the_shared_reading_and_parse_numbers_a_fresh_list():
    assert number_tuple("1 2.5 -3", 3) == ((1.0, 2.5, -3.0), None)
    assert number_tuple("1 2", 3) == (None, "expected 3 numbers, found 2 in '1 2'")
    first, _ = parse_numbers("4 5 6", 3)
    first.append(7.0)  # a caller's own list: the cached reading is not changed by it
    assert parse_numbers("4 5 6", 3) == ([4.0, 5.0, 6.0], None)
    assert number_tuple("4 5 6", 3)[0] == (4.0, 5.0, 6.0)


def test_finite_looks_at_each_value_when_the_sum_is_not_finite():
    from urdftool.description.values import finite

    assert finite((1e308, 1e308, 1e308))  # the sum overflows; each value is finite
    assert finite(()) and finite((0.0, -2.5))
    for bad in (float("inf"), float("-inf"), float("nan")):
        assert not finite((1.0, bad, 2.0)) and not finite([bad])
    assert not finite((float("inf"), float("-inf")))  # the sum is nan


def _parts_one_by_one(text, count):
    """number_tuple reading each part with to_float, without the one match of a whole text
    (the reference)."""
    from urdftool.description.values import _part_by_part, split

    parts = split(text) if text is not None else []
    if text is None or count is not None and len(parts) != count:
        return number_tuple.__wrapped__(text, count)  # (no number read: nothing to compare)
    return _part_by_part(text, parts)


def test_number_tuple_reads_every_text_as_part_by_part_to_the_bit():
    import random

    rng = random.Random(34)
    pieces = ["0", "1", "7", "12", ".", "-", "+", "e", "E", "e-", "inf", "NaN", "x", "_", "0x1",
              "\u0663", "1e308", "1e309", "-0", "4.", ".5"]
    spaces = [" ", "  ", "\t", "\n", "\xa0", "\u2003", "\x1c", "\x85", ""]
    texts = ["", " ", "1 2 3", " -0 +.5 4.e-3 ", "1\u20032\xa03", "1 2 3 4", "1,2,3", "nan inf -inf"]
    for _ in range(6000):
        words = ["".join(rng.choice(pieces) for _ in range(rng.randrange(1, 4)))
                 for _ in range(rng.randrange(0, 5))]
        texts.append(rng.choice(spaces) + "".join(w + rng.choice(spaces) for w in words))
    for text in texts:
        for count in (None, 1, 3):
            assert repr(number_tuple.__wrapped__(text, count)) == \
                repr(_parts_one_by_one(text, count)), (text, count)


def test_a_text_of_decimals_is_read_in_one_match_not_part_by_part(monkeypatch):
    import urdftool.description.values as values

    def refused(part):
        raise AssertionError(f"read part by part: {part}")

    monkeypatch.setattr(values, "to_float", refused)
    assert number_tuple.__wrapped__("1 -2.5e3\t.5", 3) == ((1.0, -2500.0, 0.5), None)
    with pytest.raises(AssertionError):  # what is not all decimal is read part by part
        number_tuple.__wrapped__("1 inf 3", 3)


def test_a_text_of_plain_decimals_is_read_without_a_regular_expression(monkeypatch):
    """A text of ASCII digits, signs, points, exponents and spaces is read by float alone (the
    10,000 distinct origins of a large robot: a match of the whole text cost as much as the
    rest of its reading); float refusing a part (``1e``, ``+-1``) reads it part by part."""
    import urdftool.description.values as values

    class Unmatched:
        def fullmatch(self, text):
            raise AssertionError(f"matched: {text}")

    monkeypatch.setattr(values, "_DECIMALS", Unmatched())
    assert number_tuple.__wrapped__(" 1 -2.5E3\t.5 ", 3) == ((1.0, -2500.0, 0.5), None)
    assert number_tuple.__wrapped__("1 1e 3", 3) == (None, "'1e' is not a number (in '1 1e 3')")
    with pytest.raises(AssertionError):  # another script's digit: matched as before
        number_tuple.__wrapped__("1 \u0663 3", 3)


@pytest.mark.parametrize("text", ["\uff11 0 0", "0 \u0661 0", "0 0 1e\uff15", "\u0967.5 0 0"])
def test_digits_of_another_script_are_no_number_urdfdom_reads(text):
    """Python's float() and re's \\d take full-width, Arabic-Indic and Devanagari digits; urdfdom
    reads with a C++ stream in the classic locale, which takes ASCII digits only (the robot
    does not load: 'Unable to parse component'). check passed ``xyz="１ 0 0"`` as 1 m."""
    values, problem = number_tuple(text, 3)
    assert values is None and "is not a number" in problem


@pytest.mark.parametrize("text", ["1\xa00 0", "1\u20030 0", "1\u30000 0", "1 0\x850", "1\x1c0 0",
                                  "\xa01 0 0", "1 0 0\u2028"])
def test_white_space_not_asciis_separates_no_numbers_as_urdfdom_reads(text):
    """urdfdom splits a vector at spaces and reads each part with a C++ stream in the classic
    locale, whose white space is ASCII's: "1\xa00" is one component it cannot parse (the robot
    does not load). str.split() and re's \\s split at a NO-BREAK SPACE, an IDEOGRAPHIC SPACE,
    NEL, \\x1c and a LINE SEPARATOR too: check read ``xyz="1\xa00 0"`` as 1 0 0."""
    values, problem = number_tuple.__wrapped__(text, 3)
    assert values is None and "is not a number" in problem and "separates no numbers" in problem
    assert number_tuple.__wrapped__(text, None)[0] is None


def test_ascii_white_space_between_numbers_is_a_separator():
    for text in ("1 0 0", " 1\t0\n0 ", "1  0\r\n0", "1\f0\v0"):
        assert number_tuple.__wrapped__(text, 3) == ((1.0, 0.0, 0.0), None), text


@pytest.mark.parametrize("text, count, refused", [
    ("2 ", 1, "2 "), ("2\t", 1, "2\t"), ("2\n", 1, "2\n"),  # strToDouble: nothing after it
    (" 2", 1, None), ("\t2", 1, None), ("2", 1, None),  # white space before is skipped
    ("0.1\t0 0", 3, "0.1\t0"), ("0.1\n0 0", 3, "0.1\n0"), ("0.1 0 0\t", 3, "0\t"),
    ("1 0\t 0", 3, "0\t"), ("1 1 1 1\r", 4, "1\r"),  # a part holding white space after a digit
    ("\t0.1 0 0", 3, None), ("0.1 \t0 0", 3, None), (" 0 0 0 ", 3, None),  # split at spaces
    ("x ", 1, None), ("1\t1 1", 4, None), ("1\xa00 0", 3, None),  # malformed: another rule's
])
def test_urdfdom_refuses_white_space_after_a_number_only(text, count, refused):
    # urdf_model's strToDouble (a stream that must reach the end) and Vector3/Color's split
    # at ' ': measured with Pinocchio 4.1's urdfdom in session 18
    assert urdfdom_refuses(text, count) == refused
    if refused:
        assert urdfdom_refuses(urdfdom_spelling(text), count) is None
        assert number_tuple(urdfdom_spelling(text), count) == number_tuple(text, count)


def test_a_text_that_is_one_part_is_quoted_once():
    """A property name written without ``${}`` (``length="laser_frame_length"``) is no number:
    the problem names it once, not as a part and again as the text it is in (sweep: U402 on
    ROS2-Forklift-Simulation's lidar.xacro read "'laser_frame_length' is not a number (in
    'laser_frame_length')"). A text of several parts still says which text the part is in."""
    assert number_tuple.__wrapped__("laser_frame_length", 1) == (
        None, "'laser_frame_length' is not a number")
    assert number_tuple.__wrapped__(" width ", 1) == (None, "'width' is not a number")
    assert number_tuple.__wrapped__("0 x 0", 3) == (None, "'x' is not a number (in '0 x 0')")


# What the C++ parsers of ros2_control and its Gazebo plugins make of a <param>'s text, as g++ 12
# compiled lexical_casts.cpp's two builds (istringstream; from_chars after one '+') and
# std::stod: (text, stream, from_chars, std::stod), None where the parser refuses the text.
CXX_READS = [
    ("1", 1.0, 1.0, 1.0), ("-1", -1.0, -1.0, -1.0), ("+1", 1.0, 1.0, 1.0),
    ("+-1", None, -1.0, None), ("-+1", None, None, None), ("++1", None, None, None),
    ("1.", 1.0, 1.0, 1.0), (".5", 0.5, 0.5, 0.5), (".", None, None, None), ("-", None, None, None),
    ("1e5", 1e5, 1e5, 1e5), ("1E+5", 1e5, 1e5, 1e5), ("1e", None, None, 1.0), ("1e+", None, None, 1.0),
    ("inf", None, None, math.inf), ("-inf", None, None, -math.inf), ("INF", None, None, math.inf),
    ("infinity", None, None, math.inf), ("0x10", None, None, 16.0), ("0x1p3", None, None, 8.0),
    (" 1", 1.0, None, 1.0), ("\t1", 1.0, None, 1.0), ("1 ", None, None, 1.0), ("\n1\n", None, None, 1.0),
    ("1,5", None, None, 1.0), ("1_0", None, None, 1.0), ("1.0f", None, None, 1.0), ("1.5rad", None, None, 1.5),
    ("0.0 # x", None, None, 0.0), ("1 2", None, None, 1.0), ("1e400", None, None, None),
    ("-1e400", None, None, None), ("1.7976931348623159e308", None, None, None),
    ("1e-400", 0.0, None, None), ("2e-324", 0.0, None, None), ("4.9e-324", 5e-324, 5e-324, None),
    ("0x1p-1074", None, None, 5e-324), ("0x0e5p-5000", None, None, None),
    ("1e-999999999", 0.0, None, None),  # (no 10**999999999 made to say it is not exact) ("00012", 12.0, 12.0, 12.0), ("1e0001", 10.0, 10.0, 10.0),
    ("{-2*pi}", None, None, None), ("", None, None, None), ("true", None, None, None),
    ("١", None, None, None), ("１", None, None, None),  # digits of other scripts
]


@pytest.mark.parametrize("text, stream, chars, stod", CXX_READS)
def test_ros2_control_parsers_read_as_the_cxx_does(text, stream, chars, stod):
    def same(value, expected):
        return value == expected if expected is None or not math.isnan(expected) else math.isnan(value)
    assert same(stream_double(text), stream)
    assert same(from_chars_double(text), chars)
    assert same(strtod_double(text), stod)


@pytest.mark.parametrize("kind, limit, expected", [
    ("revolute", '<limit lower="-1" upper="2"/>', (-1.0, 2.0)),
    ("prismatic", '<limit upper="0.5"/>', (0.0, 0.5)),  # a bound not written is urdfdom's 0
    ("revolute", '<limit lower="-inf" upper="1"/>', (-math.inf, 1.0)),  # a number, not finite
    ("revolute", '<limit lower="a" upper="1"/>', None),
    ("continuous", '<limit lower="-1" upper="1"/>', None),  # no range limits it
    ("fixed", '<limit lower="-1" upper="1"/>', None),
])
def test_limit_range_is_urdfdoms(kind, limit, expected):
    element = etree.fromstring(limit)
    assert limit_range(kind, element) == expected
    if expected is not None:
        assert (limit_bound(element, "lower"), limit_bound(element, "upper")) == expected


@pytest.mark.parametrize("joint, expected", [
    ('<joint><axis xyz="0 0 2"/></joint>', (0.0, 0.0, 2.0)),
    ("<joint/>", (1.0, 0.0, 0.0)),  # no <axis>: urdfdom's default x
    ("<joint><axis/></joint>", (0.0, 0.0, 0.0)),  # no xyz: the axis urdfdom cleared
    ('<joint><axis xyz="0 1"/></joint>', None),  # urdfdom refuses the joint
])
def test_axis_xyz_is_urdfdoms(joint, expected):
    assert axis_xyz(etree.fromstring(joint)) == expected
