"""U70x joint spec table: format, units, tolerance, and a widened humanoid limit."""

from __future__ import annotations

import pytest

from conftest import ROBOTS
from crossfile_helpers import HEAD_ROBOT, broken_copy, case_messages, check_folder, line_of

ROBOT = HEAD_ROBOT.format(body="")


@pytest.mark.parametrize("spec, expected", [
    ("unit: rad\njoints:\n  head_joint: {lower: -1.2, upper: 1.2}\n", []),
    ("unit: rad\ntolerance: 0.1\njoints:\n  head_joint: {lower: -0.95, upper: 0.95}\n", []),
    ("unit: rad\ntolerance: 0.01\njoints:\n  head_joint: {lower: -0.95, upper: 1}\n",
     [("robot.urdf", 5, "U703")]),
    ("unit: rad\njoints:\n  head_joint: {lower: -1, upper: 1, effort: 4}\n", [("robot.urdf", 5, "U703")]),
    ("unit: grad\njoints:\n  head_joint: {lower: -1, upper: 1}\n", [("joint_limits.yaml", 1, "U701")]),
    ("unit: deg\njoints: [head_joint]\n", [("joint_limits.yaml", 2, "U701")]),
    ("unit: deg\njoints:\n  head_joint: {lower: 10, upper: -10}\n", [("joint_limits.yaml", 3, "U701")]),
    ("unit: deg\njoints:\n  head_joint: {servo_id: one, lower: -60, upper: 60}\n",
     [("joint_limits.yaml", 3, "U701")]),
    ("unit: deg\njoints:\n  head_joint: {lower: -60, upper: 60\n", [("joint_limits.yaml", 3, "U701")]),
    ("unit: deg\nunits: rad\njoints: {}\n", [("joint_limits.yaml", 2, "U701")]),
])
def test_spec_format_and_limits(tmp_path, spec, expected):
    assert check_folder(tmp_path, {"robot.urdf": ROBOT, "joint_limits.yaml": spec})[0] == expected


@pytest.mark.parametrize("unit", ["{deg: 1}", "[deg]", "!!set {deg}"])
def test_a_unit_that_is_no_word_is_the_specs_one_finding(tmp_path, unit):
    """attack30: a unit that YAML reads as a mapping, a list or a set was looked up among the
    units: unhashable, every rule reading the spec crashed (U900). U701 at its line."""
    spec = f"unit: {unit}\njoints:\n  head_joint: {{lower: -60, upper: 60}}\n"
    assert check_folder(tmp_path, {"robot.urdf": ROBOT, "joint_limits.yaml": spec})[0] == [
        ("joint_limits.yaml", 1, "U701")]


def test_limit_outside_spec_says_by_how_much_in_the_spec_unit(tmp_path):
    spec = "unit: deg\ntolerance: 1\njoints:\n  head_joint: {lower: -50, upper: 50}\n"
    _, findings = check_folder(tmp_path, {"robot.urdf": ROBOT, "joint_limits.yaml": spec})
    assert [f.message for f in findings] == [
        "joint 'head_joint': lower limit -57.3 deg is 7.296 deg beyond the spec's -50 deg (tolerance 1 deg)",
        "joint 'head_joint': upper limit 57.3 deg is 7.296 deg beyond the spec's 50 deg (tolerance 1 deg)"]


def test_spec_given_on_the_command_line_under_another_name(tmp_path):
    spec = "unit: rad\njoints:\n  head_joint: {servo_id: 3, lower: -1, upper: 1}\n  neck: {lower: 0, upper: 1}\n"
    found, findings = check_folder(tmp_path, {"robot.urdf": ROBOT, "specs/head.yaml": spec},
                                   spec=str(tmp_path / "specs/head.yaml"))
    assert found == [("head.yaml", 4, "U702")]
    assert "available joints: cam_joint, head_joint" in findings[0].message


def test_humanoid_limit_widened_beyond_the_spec(tmp_path):
    findings = broken_copy(tmp_path, "humanoid", "humanoid.urdf.xacro",
                           'axis="0 0 1" lower="-90" upper="90"', 'axis="0 0 1" lower="-90" upper="100"')
    assert [(f.code, f.file.endswith("parts.xacro"), f.line) for f in findings] == [("U703", True, 18)]
    assert f"{findings[0].location.via[0].file}".endswith("humanoid.urdf.xacro")
    assert "upper limit 100 deg is 10 deg beyond the spec's 90 deg" in findings[0].message


def test_humanoid_duplicate_servo_id_and_missing_joint(tmp_path):
    findings = broken_copy(tmp_path, "humanoid", "joint_limits.yaml", "l_knee:      {servo_id: 14",
                           "l_kne:       {servo_id: 13")
    spec_line = next(n for n, line in enumerate((ROBOTS / "humanoid/joint_limits.yaml").read_text()
                                                .splitlines(), 1) if "l_knee:" in line)
    assert sorted((f.code, f.line, f.file.endswith(("parts.xacro", "joint_limits.yaml")))
                  for f in findings) == [("U702", spec_line, True), ("U704", 13, True),
                                         ("U705", spec_line, True)]


@pytest.mark.parametrize("value", ["2001-02-30", "1" * 400])
def test_a_spec_value_that_does_not_read_is_the_specs_one_finding(tmp_path, value):
    """An effort PyYAML cannot construct: a date that is none crashed every spec rule (U900:
    ValueError), an integer past a double each of them (math.isfinite's OverflowError);
    then the spec beside the SRDF was also read as MoveIt's joint_limits.yaml and said again
    (U812). Once, U701, at its line."""
    findings = broken_copy(tmp_path, "humanoid", "joint_limits.yaml", "effort: 2.5, velocity: 5.76}\n  head_tilt",
                           f"effort: {value}, velocity: 5.76}}\n  head_tilt")
    line = line_of(ROBOTS / "humanoid/joint_limits.yaml", "head_pan:")
    assert [(f.code, f.line) for f in findings] == [("U701", line)]


WHEELED = HEAD_ROBOT.format(body='<link name="wheel"/><joint name="wheel_joint" type="continuous">'
                                 '<parent link="base_link"/><child link="wheel"/><axis xyz="0 1 0"/>'
                                 '<limit effort="2" velocity="10"/></joint>')
HEAD_SPEC = "unit: deg\njoints:\n  head_joint: {lower: -60, upper: 60}\n"


@pytest.mark.parametrize("wheel, expected, message", [
    ("{servo_id: 1, effort: 2, velocity: 10}", [], None),
    ("{velocity: 5}", [("robot.urdf", 8, "U703")], "velocity limit 10 exceeds the spec's 5 by 5"),
    ("{lower: -90, upper: 90}", [("robot.urdf", 8, "U703")],
     "joint 'wheel_joint' is continuous (no position limit) but the spec limits it to -90 .. 90 deg"),
    ("{lower: -90}", [("joint_limits.yaml", 4, "U701")], "joint 'wheel_joint' has no upper"),
], ids=["no-range", "too-fast", "range-on-continuous", "half-a-range"])
def test_continuous_joint_in_the_spec_needs_no_range(tmp_path, wheel, expected, message):
    spec = HEAD_SPEC + f"  wheel_joint: {wheel}\n"
    found, findings = check_folder(tmp_path, {"robot.urdf": WHEELED, "joint_limits.yaml": spec})
    assert found == expected
    assert message is None or message in findings[0].message


def test_revolute_joint_in_the_spec_needs_a_range(tmp_path):
    spec = "unit: deg\njoints:\n  head_joint: {servo_id: 1, effort: 5}\n"
    found, findings = check_folder(tmp_path, {"robot.urdf": ROBOT, "joint_limits.yaml": spec})
    assert found == [("joint_limits.yaml", 3, "U701"), ("joint_limits.yaml", 3, "U701")]
    assert "only a continuous joint may leave out both" in findings[0].message


def test_joint_not_in_spec_says_what_to_add():
    messages = case_messages("U704_joint_not_in_spec", "U704")
    assert messages and all(m.endswith("; add it with its servo_id and range") for m in messages)


@pytest.mark.parametrize("spec, reported", [
    ("unit: rad\njoints:\n  head_joint: {lower: -57.3, upper: 57.3}\n", True),   # degrees as rad
    ("unit: deg\njoints:\n  head_joint: {lower: -3283, upper: 3283}\n", True),   # URDF converted twice
    ("unit: rad\njoints:\n  head_joint: {lower: -2, upper: 2}\n", False),        # a safety margin
    ("unit: rad\njoints:\n  head_joint: {lower: -57.3, upper: 80}\n", False),    # upper is not x pi/180
])
def test_urdf_range_is_the_spec_range_times_pi_over_180(tmp_path, spec, reported):
    found, findings = check_folder(tmp_path, {"robot.urdf": ROBOT, "joint_limits.yaml": spec},
                                   select=("U706",))
    assert bool(found) == reported, [f.message for f in findings]


def test_a_limit_of_the_spec_digits_a_power_of_ten_off_is_said_to_be_a_slipped_decimal_point(tmp_path):
    spec = "unit: rad\njoints:\n  head_joint: {lower: -0.125, upper: 0.3, velocity: 0.15}\n"
    robot = ROBOT.replace('lower="-1" upper="1" effort="5" velocity="1"',
                          'lower="-1.25" upper="1.25" effort="5" velocity="1.5"')
    _, findings = check_folder(tmp_path, {"robot.urdf": robot, "joint_limits.yaml": spec})
    said = [f.message.endswith(": the same digits 10 times apart, a decimal point slipped")
            for f in findings]
    assert len(findings) == 3 and said == [True, False, True]  # lower, upper, velocity


def test_an_infinite_tolerance_is_malformed_not_every_limit_within_it(tmp_path):
    """attack25: ``tolerance: .inf`` held every limit within it: U703 said nothing of a limit
    57 degrees past the spec's 30. It is U701, and the limits are judged at tolerance 0."""
    spec = "unit: deg\ntolerance: .inf\njoints:\n  head_joint: {lower: -30, upper: 30}\n"
    found, findings = check_folder(tmp_path, {"robot.urdf": ROBOT, "joint_limits.yaml": spec})
    assert ("joint_limits.yaml", 2, "U701") in found, found
    assert sum(code == "U703" for _, _, code in found) == 2, found


def test_a_number_yaml_1_1_reads_as_text_is_said_so(tmp_path):
    """attack25: ``effort: 1e3`` was "effort '1e3' must be a finite number", of a finite
    number: PyYAML (YAML 1.1) reads a mantissa without a point as text; the message says so."""
    spec = "unit: deg\njoints:\n  head_joint: {lower: -60, upper: 60, effort: 1e3}\n"
    _, findings = check_folder(tmp_path, {"robot.urdf": ROBOT, "joint_limits.yaml": spec})
    assert [f.message for f in findings] == [
        "joint 'head_joint': effort '1e3' must be a finite number (YAML 1.1 reads '1e3' as text: "
        "write it with a point, as 1.0e3)"]


def test_a_bound_not_written_is_urdfdoms_zero(tmp_path):
    """A ``<limit>`` without ``lower`` is lower 0 to urdfdom, and the joint stops there
    (description.values.limit_bound, the reading U204 and the others share); U703 skipped the
    bound as if there were none, so a spec from 10 deg up said nothing of a URDF from 0."""
    robot = ROBOT.replace('lower="-1" upper="1"', 'upper="1"')
    spec = "unit: deg\njoints:\n  head_joint: {lower: 10, upper: 57.3}\n"
    _, findings = check_folder(tmp_path, {"robot.urdf": robot, "joint_limits.yaml": spec})
    assert [(f.code, f.message) for f in findings] == [
        ("U703", "joint 'head_joint': lower limit 0 deg is 10 deg beyond the spec's 10 deg "
                 "(tolerance 0 deg)")]
