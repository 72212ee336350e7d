"""U70x: the joint spec table (servo IDs and the limits each joint must have).

The spec is YAML: top-level ``unit`` (deg or rad, for lower/upper and tolerance), optional
``tolerance`` (default 0), and ``joints``: a map of URDF joint name to ``servo_id``, ``lower``,
``upper`` (a continuous joint may leave out both) and optional ``effort`` [N m or N] and
``velocity`` [rad/s or m/s].
"""

from __future__ import annotations

import math

from urdftool.description.companions import companions, is_spec
from urdftool.description.documents import YamlMap
from urdftool.lint.catalogue import Severity, rule
from urdftool.numbers import decimal_slip, number
from urdftool.description.actuation import moving_joints
from urdftool.errors import available
from urdftool.description.urdf import MOVING
from urdftool.description.values import limit_value
from urdftool.records import Record

UNITS = {"deg": math.pi / 180, "rad": 1.0}
TOP_KEYS = ("unit", "tolerance", "joints")
JOINT_KEYS = ("servo_id", "lower", "upper", "effort", "velocity")
SI_TOLERANCE = 1e-3  # relative, for effort and velocity


class SpecJoint(Record):
    """A joint of a joint spec: its name, line, entry and the lines of its keys."""

    name: str
    line: int
    entry: dict
    lines: dict

    __slots__ = ("name", "line", "entry", "lines")

    def __init__(self, name: str, line: int, entry: dict, lines: dict) -> None:
        self.name = name
        self.line = line
        self.entry = entry
        self.lines = lines


def _spec(robot):
    """(file, problems, joints, unit, tolerance) of the robot's spec, or None without one."""
    parsed = robot.memo(_spec, lambda: _parse(companions(robot).spec, robot.joints))
    return parsed if parsed[0] is not None else None


def _parse(file, urdf_joints):
    if file is None:
        return (None, [], [], None, 0.0)
    if file.problem:
        return (file, [(file.line, file.problem)], [], None, 0.0)
    data, problems = file.data, []
    if not is_spec(data):
        hint = (" (this is a ROS joint_limits.yaml with 'joint_limits:', not a urdftool spec)"
                if isinstance(data, dict) and "joint_limits" in data else "")
        return (file, [(getattr(data, "line", 1) or 1,
                        f"not a joint spec: needs top-level {', '.join(TOP_KEYS)}{hint}")], [], None, 0.0)
    for key in data:
        if key not in TOP_KEYS:
            problems.append((data.lines[key], f"unknown key '{key}'; valid keys: {', '.join(TOP_KEYS)}"))
    unit = data.get("unit")
    if not isinstance(unit, str) or unit not in UNITS:  # ('unit: [deg]' is unhashable: U900)
        problems.append((data.lines["unit"], f"unit '{unit}' must be deg or rad"))
        unit = None
    tolerance = data.get("tolerance", 0)
    if not isinstance(tolerance, (int, float)) or isinstance(tolerance, bool) \
            or not 0 <= tolerance < math.inf:  # (.inf held every limit within it: U703 silent)
        problems.append((data.lines.get("tolerance"), f"tolerance '{tolerance}' must be a finite "
                         f"number >= 0{_text_hint(tolerance)}"))
        tolerance = 0.0
    joints = []
    table = data.get("joints")
    if not isinstance(table, YamlMap):
        problems.append((data.lines["joints"], "joints must be a map of joint name to "
                         "{servo_id, lower, upper, effort, velocity}"))
        table = {}
    for name, entry in table.items():
        line = table.lines[name]
        if not isinstance(entry, YamlMap):
            problems.append((line, f"joint '{name}' must map to {{{', '.join(JOINT_KEYS)}}}"))
            continue
        bad = _entry_problems(name, entry, urdf_joints.get(str(name)))
        problems.extend(bad)
        if not bad:
            joints.append(SpecJoint(str(name), line, entry, entry.lines))
    return (file, problems, joints, unit, float(tolerance))


def _text_hint(value) -> str:
    """Why a number as written is text: YAML 1.1 (the spec's reader, PyYAML) reads ``1e308``,
    with no point in its mantissa, as a string ("'1e308' must be a finite number", of a finite
    number); or nothing."""
    if isinstance(value, str):
        try:
            finite = math.isfinite(float(value))
        except ValueError:
            return ""
        if finite:
            return f" (YAML 1.1 reads '{value}' as text: write it with a point, as 1.0e3)"
    return ""


def _entry_problems(name, entry, joint) -> list:
    """The format problems of one spec joint; ``joint`` is the URDF joint of that name, if any."""
    problems = []
    for key, value in entry.items():
        line = entry.lines[key]
        if key not in JOINT_KEYS:
            problems.append((line, f"joint '{name}': unknown key '{key}'; valid keys: "
                             f"{', '.join(JOINT_KEYS)}"))
        elif key == "servo_id" and (not isinstance(value, int) or isinstance(value, bool)):
            problems.append((line, f"joint '{name}': servo_id '{value}' must be an integer"))
        elif key != "servo_id" and (not isinstance(value, (int, float)) or isinstance(value, bool)
                                    or not math.isfinite(value)):
            problems.append((line, f"joint '{name}': {key} '{value}' must be a finite number"
                             f"{_text_hint(value)}"))
    missing = [key for key in ("lower", "upper") if key not in entry]
    unlimited = joint is not None and joint.get("type") == "continuous"
    if missing and (len(missing) == 1 or not unlimited):  # a continuous joint may have no range
        for key in missing:
            problems.append((entry.line, f"joint '{name}' has no {key}; give lower and upper "
                             "(only a continuous joint may leave out both)"))
    if not problems and not missing and entry["lower"] > entry["upper"]:
        problems.append((entry.lines["lower"], f"joint '{name}': lower {entry['lower']} is above "
                         f"upper {entry['upper']}"))
    return problems


def spec_joints(robot) -> list[tuple[str, object, object]]:
    """(joint name, servo_id as written, where) of each well-formed joint of the robot's spec
    table (none without one): the symmetry rules read the servo IDs."""
    spec = _spec(robot)
    if spec is None:
        return []
    return [(joint.name, joint.entry.get("servo_id"),
             spec[0].at(joint.lines.get("servo_id", joint.line))) for joint in spec[2]]


@rule("U701", "malformed-spec", Severity.ERROR)
def malformed_spec(robot):
    """The joint spec file is not valid YAML or not in the spec format.

    A spec that does not parse checks nothing, so it is an error rather than silence.
    See docs/companions.md for the format (``unit``, ``tolerance``, ``joints``).

    Bad: ``head_pan: {servo_id: 19, lower: -90, uper: 90}``
    Good: ``head_pan: {servo_id: 19, lower: -90, upper: 90}``
    """
    spec = _spec(robot)
    if spec is not None:
        file, problems = spec[0], spec[1]
        for line, problem in problems:
            yield file.at(line), problem


@rule("U702", "spec-joint-missing", Severity.ERROR)
def spec_joint_missing(robot):
    """A joint listed in the spec is not in the URDF.

    Bad: spec lists ``head_yaw`` but the URDF calls it ``head_pan``
    Good: the same joint names in both
    """
    spec = _spec(robot)
    if spec is None:
        return
    for joint in spec[2]:
        if joint.name not in robot.joints:
            yield spec[0].at(joint.line), (f"spec joint '{joint.name}' is not in the URDF; "
                                           + available('joints', joint.name, robot.joints))


@rule("U703", "limit-outside-spec", Severity.ERROR)
def limit_outside_spec(robot):
    """A URDF joint limit goes beyond the spec by more than its tolerance.

    Planners and controllers would drive the servo past its range. Lower and upper are
    compared in the spec's unit with its tolerance; effort and velocity must not exceed the
    spec (0.1 % slack). The finding is located at the URDF limit.

    Bad: spec ``upper: 90`` (deg), URDF ``upper="1.75"`` (100.3 deg)
    Good: URDF ``upper="1.5708"``
    """
    spec = _spec(robot)
    if spec is None or spec[3] is None:
        return
    _, _, joints, unit, tolerance = spec
    scale = UNITS[unit]
    for entry in joints:
        joint = robot.joints.get(entry.name)
        if joint is None or joint.get("type") not in MOVING:
            continue
        where = joint.find("limit") if joint.find("limit") is not None else joint
        if joint.get("type") == "continuous":
            if "lower" in entry.entry:
                yield joint, (f"joint '{entry.name}' is continuous (no position limit) but the "
                              f"spec limits it to {entry.entry['lower']:g} .. {entry.entry['upper']:g} "
                              f"{unit}; make it revolute with those limits")
        for key, sign in (() if joint.get("type") == "continuous" else (("lower", -1), ("upper", 1))):
            value = limit_value(joint, key)
            if value is None:
                continue
            urdf = value / scale if joint.get("type") == "revolute" else value
            beyond = sign * (urdf - entry.entry[key])
            if beyond > tolerance + 1e-9:
                yield where, (f"joint '{entry.name}': {key} limit {number(urdf)} {unit} is "
                              f"{number(beyond)} {unit} beyond the spec's {entry.entry[key]:g} "
                              f"{unit} "
                              f"(tolerance {tolerance:g} {unit})"
                              + decimal_slip(sign * urdf, sign * entry.entry[key]))
        for key in ("effort", "velocity"):
            value, allowed = limit_value(joint, key), entry.entry.get(key)
            if value is not None and allowed is not None and value > allowed * (1 + SI_TOLERANCE):
                yield where, (f"joint '{entry.name}': {key} limit {value:g} exceeds the spec's "
                              f"{allowed:g} by {number(value - allowed)}"
                              + decimal_slip(value, allowed))


@rule("U704", "joint-not-in-spec", Severity.WARNING)
def joint_not_in_spec(robot):
    """An actuated joint of the URDF is missing from the spec.

    Its limits are checked against nothing, and it has no servo ID.

    Bad: the URDF has ``head_tilt`` but the spec lists only ``head_pan``
    Good: every revolute, continuous and prismatic (non-mimic) joint in the spec
    """
    spec = _spec(robot)
    if spec is None or spec[1]:
        return
    listed = {joint.name for joint in spec[2]}
    for name, joint in moving_joints(robot).items():
        if name not in listed:
            yield joint, (f"joint '{name}' is not in the spec {spec[0].display}; add it with "
                          "its servo_id and range")


@rule("U705", "duplicate-servo-id", Severity.ERROR)
def duplicate_servo_id(robot):
    """Two spec joints share a servo ID.

    Both joints would answer to the same bus address; one of them never moves as commanded.

    Bad: ``r_knee: {servo_id: 13, ...}`` and ``l_knee: {servo_id: 13, ...}``
    Good: distinct IDs (DARwIn-OP: left ID, right ID = left - 1)
    """
    spec = _spec(robot)
    if spec is None:
        return
    owner: dict[int, str] = {}
    for joint in spec[2]:
        servo = joint.entry.get("servo_id")
        if servo is None:
            continue
        if servo in owner:
            yield spec[0].at(joint.lines["servo_id"]), (
                f"joint '{joint.name}' has servo_id {servo}, already used by '{owner[servo]}'")
        else:
            owner[servo] = joint.name


DEGREE = math.pi / 180
DEGREE_MATCH = 0.05  # relative to the span: how closely the URDF must match spec x pi/180


@rule("U706", "limit-spec-degree-slip", Severity.WARNING)
def limit_spec_degree_slip(robot):
    """A revolute joint's URDF range is the spec's range times pi/180: a degrees slip.

    The URDF and the spec agree only after one of them is scaled by pi/180 once more: the spec
    says ``unit: rad`` over values typed in degrees, or the URDF limits were converted from
    degrees twice. U703 cannot see it (the URDF is inside the spec, just 57 times narrower),
    and the joint would stop at a 57th of its travel. Each URDF bound must match the spec
    bound times pi/180 within 5 % of the span; a URDF merely narrower than its spec (a safety
    margin) is not reported.

    Bad: ``unit: rad`` with ``head_pan: {lower: -90, upper: 90}`` for a URDF ``-1.5708 .. 1.5708``
    Good: ``unit: deg`` (or the spec in radians: ``lower: -1.5708, upper: 1.5708``)
    """
    spec = _spec(robot)
    if spec is None or spec[3] is None:
        return
    _, _, joints, unit, _ = spec
    for entry in joints:
        joint = robot.joints.get(entry.name)
        if joint is None or joint.get("type") != "revolute":
            continue
        bounds = [limit_value(joint, key) for key in ("lower", "upper")]
        if None in bounds:
            continue
        urdf = [value / UNITS[unit] for value in bounds]  # in the spec's unit
        table = [entry.entry["lower"], entry.entry["upper"]]
        span = (table[1] - table[0]) * DEGREE
        if span <= 0 or urdf[1] - urdf[0] <= 0:
            continue
        if all(abs(u - t * DEGREE) <= DEGREE_MATCH * span for u, t in zip(urdf, table)):
            yield joint.find("limit"), (
                f"joint '{entry.name}': URDF range {number(urdf[0])} .. {number(urdf[1])} {unit} is "
                "the "
                f"spec's {table[0]:g} .. {table[1]:g} {unit} times pi/180: the spec's values "
                f"look like degrees{' under unit: rad' if unit == 'rad' else ''}, or the URDF "
                "was converted from degrees twice")
