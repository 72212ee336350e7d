"""One way to print a float for people: rounded to what is printed, never -0; and a guard that
no other module formats floats its own way."""

from __future__ import annotations

import ast
import math
import re
import struct
from pathlib import Path

import pytest

from conftest import load_text, walked
from urdftool.numbers import MILLIMETRE, fixed_texts, number, numbers, symmetric_texts

PACKAGE = Path(__file__).resolve().parent.parent / "urdftool"


@pytest.mark.parametrize("value, kwargs, text", [
    (-9.0e-21, {"scale": 0.19}, "0"),
    (2e-14, {"scale": 0.19}, "0"),
    (6.896e-05, {"scale": 0.3709}, "6.896e-05"),  # above the last digit of 0.3709: kept
    (-0.0, {}, "0"),
    (-1e-9, {"places": 6}, "0.000000"),
    (-0.5, {"places": 6}, "-0.500000"),
    (1.23456789, {"places": 3}, "1.235"),
    (-4e-5, {"places": 3, "plus": True}, "0.000"),
    (4.0, {"plus": True}, "+4"),
    (-4.0, {"plus": True}, "-4"),
    (0.0, {"plus": True}, "0"),
    (1e-17, {}, "1e-17"),  # alone, a number is its own scale
    (float("nan"), {}, "nan"),
    (float("-inf"), {}, "-inf"),
    (22590.4, {"places": 0, "grouped": True}, "22,590"),
    (1e100, {"places": 0, "grouped": True}, "1e+100"),  # not a hundred digits a float lacks
    (-2.5e15, {"places": 3}, "-2.5e+15"),
    (999999999999999.0, {"places": 0}, "999999999999999"),
])
def test_number(value, kwargs, text):
    assert number(value, **kwargs) == text


@pytest.mark.parametrize("places", [0, 3, 6])
def test_fixed_texts_are_number_with_places(places):
    """Formatted at once, the texts of number(v, places=...) to the character: round-off
    without its minus, ties (2**-7 at six places) as Python rounds them, values that are not
    finite, large and tiny ones, and a spread of random ones."""
    import numpy as np

    values = [-1e-9, -0.0, 0.0, -0.4, -0.5, 0.5, 2.5, 2.0 ** -7, -(2.0 ** -7), 1.0000005,
              -4e-4, 1e300, -1e300, 1e15, -1e15, 999999999999999.9, 5e-324, float("nan"), float("inf"), float("-inf")]
    values += np.random.default_rng(places).uniform(-4, 4, 2000).tolist()
    assert fixed_texts(values, places) == [number(v, places=places) for v in values]

def test_numbers_count_digits_from_the_largest_component():
    assert numbers((0.3, 1e-17, -2e-18)) == "0.3 0 0"
    assert numbers((1e-17, -2e-17, 0.0), floor=MILLIMETRE) == "0 0 0"
    assert numbers((0.0002279, 0.0001225, 0.0002279, 0, 0, 6.455e-21)) == \
        "0.0002279 0.0001225 0.0002279 0 0 0"


WHEEL = """<robot name="r"><link name="wheel">
  <inertial><mass value="0.2"/><origin rpy="1.5707963267948966 0 0"/>
    <inertia ixx="0.0002279" iyy="0.0001225" izz="0.0002279" ixy="0" ixz="0" iyz="0"/></inertial>
  <collision><origin rpy="1.5707963267948966 0 0"/>
    <geometry><cylinder radius="0.035" length="0.1"/></geometry></collision></link></robot>"""


def test_inertia_prints_round_off_as_zero(tmp_path):
    """A cylinder turned a quarter turn: its computed tensor's off-diagonal is round-off
    (it printed 6.455e-21 before), in the table and in the corrected <inertial> block."""
    from urdftool.physics.inertia_compare import compare, inertial_xml
    from urdftool.report.inertia import text

    results = compare(load_text(tmp_path, WHEEL))
    table = text(results)
    assert "e-2" not in table and "e-1" not in table and "-0 " not in table, table
    block = inertial_xml(results[0].computed)
    assert "e-" not in block and '"-0"' not in block, block


def test_symmetric_texts_count_each_entry_from_its_own_size():
    """A joint-space mass matrix (UR5, Pinocchio's crba): the wrist's 1.3e-4 beside the
    shoulder's 3.2 is printed (counted from the largest, it was 0), round-off is 0."""
    mass_matrix = [[3.1924, 1.1669, -2.7e-14], [1.1669, 0.5395, 1.3212e-04],
                   [-2.7e-14, 1.3212e-04, 1.3212e-04]]
    assert symmetric_texts(mass_matrix) == [["3.192", "1.167", "0"],
                                            ["1.167", "0.5395", "0.0001321"],
                                            ["0", "0.0001321", "0.0001321"]]
    # a massless last joint: no size of its own, the largest entry's round-off floor
    assert symmetric_texts([[2.0, 1e-20], [1e-20, 0.0]]) == [["2", "0"], ["0", "0"]]
    assert symmetric_texts([[0.0, 0.0], [0.0, 0.0]]) == [["0", "0"], ["0", "0"]]
    assert symmetric_texts([[math.inf, 1.0], [1.0, 2.0]])[1] == ["1", "2"]


def test_a_thin_rod_keeps_its_small_moment(tmp_path):
    """A 1 m rod of 2 mm radius: izz = m r2 / 2 = 2e-6 beside ixx = 0.083, printed and written
    as itself (it was 0, a tensor simulators refuse), in the table and the <inertial> block."""
    from urdftool.physics.inertia_compare import compare, inertial_xml
    from urdftool.report.inertia import text

    rod = load_text(tmp_path, """<robot name="r"><link name="rod">
  <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
  <collision><geometry><cylinder radius="0.002" length="1"/></geometry></collision></link></robot>""")
    results = compare(rod)
    assert "0.08333 0.08333 2e-06 0 0 0" in text(results), text(results)
    assert 'izz="2e-06"' in inertial_xml(results[0].computed)


def test_no_module_formats_floats_its_own_way():
    """Every float people read goes through urdftool.numbers.number: a format spec with a
    precision (``:.3g``, ``:+.1f``, ``:.0%``) anywhere else is a place that can print -0 or
    round-off. SVG coordinates and opacities (plot.py, picture.py) are not read by people; the
    language server's log line of elapsed seconds is never negative."""
    spec = re.compile(r"\{[^{}]*:[+ ]?\d*,?\.\d+[fgeG%]\}")
    allowed = {"numbers.py", "report/plot.py", "report/picture.py", "server.py"}
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        relative = path.relative_to(PACKAGE).as_posix()
        if relative in allowed:
            continue
        for number_, line in enumerate(path.read_text().splitlines(), 1):
            if spec.search(line):
                found.append(f"{relative}:{number_}: {line.strip()}")
    assert not found, "\n".join(found)


def test_power_is_ieee_where_python_raises():
    from urdftool.numbers import power

    assert power(1e103, 3) == math.inf and power(-1e103, 3) == -math.inf
    assert power(-1e200, 2) == math.inf and power(1e200, 2.0) == math.inf
    for value in (0.1, -3.7, 1e-300, 5e-324, 1.7e102, -0.0, math.inf, -math.inf):
        for exponent in (2, 3):
            got, expected = power(value, exponent), value ** exponent
            assert struct.pack("<d", got) == struct.pack("<d", expected), (value, exponent)
    assert math.isnan(power(math.nan, 2))


def test_no_module_raises_a_float_power_itself():
    """Every ``x ** n`` of the package with a computed base goes through numbers.power:
    Python's float power raises OverflowError where IEEE arithmetic gives infinity, and a
    robot's ``radius="1e103"`` then stopped U309-U316 with U900."""
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        relative = path.relative_to(PACKAGE).as_posix()
        for node in walked(path.read_text()):
            if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow) \
                    and not isinstance(node.left, ast.Constant) and relative != "numbers.py":
                found.append(f"{relative}:{node.lineno}: {ast.unparse(node)}")
            elif isinstance(node, ast.AugAssign) and isinstance(node.op, ast.Pow) or \
                    isinstance(node, ast.Call) and ast.unparse(node.func) in ("pow", "math.pow"):
                found.append(f"{relative}:{node.lineno}: {ast.unparse(node)}")
    assert not found, "\n".join(found)


def test_a_huge_sphere_is_judged_not_crashed(tmp_path):
    """A sphere too large for its volume's float: the inertia rules judge it (a non-finite
    volume) instead of stopping with U900."""
    from urdftool.lint.engine import load_and_check
    from urdftool.lint.options import CheckOptions

    robot = tmp_path / "huge.urdf"
    robot.write_text(
        '<robot name="huge"><link name="base"><inertial><mass value="1"/>'
        '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>'
        '<collision><geometry><sphere radius="1e103"/></geometry></collision></link>'
        '<link name="arm"><inertial><mass value="1"/>'
        '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>'
        '<joint name="j" type="fixed"><parent link="base"/><child link="arm"/></joint>'
        '</robot>')
    codes = [finding.code for finding in load_and_check(str(robot), CheckOptions()).findings]
    assert "U900" not in codes, codes


def test_length_and_unit_scale_before_they_square():
    """sqrt(x*x + y*y + z*z) overflows at 1e155 and underflows at 1e-162: scaled by its largest
    part first, a vector has its length and direction at any finite size."""
    import math

    from urdftool.numbers import length, unit

    assert length((3e300, 4e300)) == pytest.approx(5e300)
    assert length((3e-300, 4e-300)) == pytest.approx(5e-300)
    assert length((1.5e308, 1.5e308)) == math.inf  # the length itself is beyond a float
    assert unit((1e308, 1e308, 1e308)) == pytest.approx((3 ** -0.5,) * 3)
    assert unit((1e-320, 0, 0)) == (1.0, 0.0, 0.0)
    assert unit((0, 0, 0)) is None and unit((math.inf, 0, 0)) is None
    assert unit((1, math.nan, 0)) is None and math.isnan(length((math.nan, 1)))


@pytest.mark.parametrize("a, b, said", [
    (0.0070309794, 0.070309794, ": the same digits 10 times apart, a decimal point slipped"),
    (0.325, 0.000325, ": the same digits 1000 times apart, a decimal point slipped"),
    (0.325, 0.0326, ""), (0.8, 0.8, ""), (0.0, 0.5, ""), (-0.1, -1.0, ""), (300.0, 30.0, ""),
    (1.5, 15.0, ": the same digits 10 times apart, a decimal point slipped"),
    (float("inf"), 1.0, ""), (5e-324, 1e308, "")])
def test_decimal_slip_is_said_of_the_same_digits_a_power_of_ten_apart(a, b, said):
    from urdftool.numbers import decimal_slip

    assert decimal_slip(a, b) == said and decimal_slip(b, a) == said


def test_exact_is_every_digit_and_no_signed_zero():
    from urdftool.numbers import exact

    assert [exact(v) for v in (-0.0, 0.0, 0.1 + 0.2, -1e-300, 3)] == \
        ["0.0", "0.0", "0.30000000000000004", "-1e-300", "3.0"]


def test_the_farthest_coordinate_is_where_mesh_vertices_stop_merging():
    """numbers.MAX_COORDINATE bounds every placed part, joint and mesh vertex; meshes merge
    their vertices in integers up to mesh_arrays.KEY_RANGE: one number."""
    from urdftool.description.mesh_arrays import KEY_RANGE
    from urdftool.description.meshes.reading import MAX_COORDINATE as MESHES
    from urdftool.numbers import MAX_COORDINATE

    assert MAX_COORDINATE == KEY_RANGE == MESHES
