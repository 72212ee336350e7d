"""U2xx: joints (types, limits, axes, numbers, mimic)."""

from __future__ import annotations

import math

from urdftool.lint.catalogue import Severity, rule
from urdftool.errors import available
from urdftool.description.urdf import AXIS, JOINT_TYPES, LIMITED, MOVING
from urdftool.description.values import finite, parse_numbers

UNIT_TOLERANCE = 1e-6

# (child tag, attribute, how many numbers) read as numbers in a joint
NUMERIC_FIELDS = (
    ("origin", "xyz", 3), ("origin", "rpy", 3), ("axis", "xyz", 3),
    ("limit", "lower", 1), ("limit", "upper", 1), ("limit", "effort", 1), ("limit", "velocity", 1),
    ("dynamics", "damping", 1), ("dynamics", "friction", 1),
    ("mimic", "multiplier", 1), ("mimic", "offset", 1),
    ("calibration", "rising", 1), ("calibration", "falling", 1),
    ("safety_controller", "soft_lower_limit", 1), ("safety_controller", "soft_upper_limit", 1),
    ("safety_controller", "k_position", 1), ("safety_controller", "k_velocity", 1),
)


def _name(joint) -> str:
    return joint.get("name") or "?"


@rule("U201", "unknown-joint-type", Severity.ERROR)
def unknown_joint_type(robot):
    """A joint's ``type`` is missing or not one of the six URDF types.

    Bad: ``<joint name="j" type="hinge">``
    Good: ``<joint name="j" type="revolute">`` (or continuous, prismatic, fixed, floating, planar)
    """
    for joint in robot.children("joint"):
        kind = joint.get("type")
        if kind not in JOINT_TYPES:
            what = f"type '{kind}'" if kind is not None else "no type"
            yield joint, f"joint '{_name(joint)}' has {what}; valid types: {', '.join(JOINT_TYPES)}"


@rule("U202", "missing-limit", Severity.ERROR)
def missing_limit(robot):
    """A revolute or prismatic joint has no ``<limit>``.

    urdfdom refuses it; MoveIt and controllers need the range, effort and velocity.

    Bad: ``<joint name="elbow" type="revolute">`` without ``<limit>``
    Good: ``<limit lower="-1.57" upper="1.57" effort="10" velocity="2"/>``
    """
    for joint in robot.children("joint"):
        if joint.get("type") in LIMITED and joint.find("limit") is None:
            yield joint, (f"{joint.get('type')} joint '{_name(joint)}' has no <limit>; add "
                          "<limit lower=... upper=... effort=... velocity=.../>")


@rule("U203", "limit-missing-effort-velocity", Severity.ERROR)
def limit_missing_effort_velocity(robot):
    """A ``<limit>`` lacks ``effort`` or ``velocity``.

    Both are required by the URDF specification; urdfdom refuses the joint without them.

    Bad: ``<limit lower="0" upper="1"/>``
    Good: ``<limit lower="0" upper="1" effort="5" velocity="1"/>``
    """
    for joint in robot.children("joint"):
        limit = joint.find("limit")
        if limit is None:
            continue
        missing = [a for a in ("effort", "velocity") if limit.get(a) is None]
        if missing:
            yield limit, f"joint '{_name(joint)}': <limit> has no {' or '.join(missing)}"


def _ranges(robot):
    """(joint, limit, lower, upper) of revolute and prismatic joints whose range parses; a
    missing bound is 0, as in urdfdom."""
    for joint in robot.children("joint"):
        limit = joint.find("limit")
        if limit is None or joint.get("type") not in LIMITED:
            continue
        lower, _ = parse_numbers(limit.get("lower", "0"), 1)
        upper, _ = parse_numbers(limit.get("upper", "0"), 1)
        if lower and upper:
            yield joint, limit, lower[0], upper[0]


@rule("U204", "inverted-limits", Severity.ERROR)
def inverted_limits(robot):
    """A joint's lower limit is above its upper limit.

    The joint can reach no position: planners fail and controllers clamp to nonsense.

    Bad: ``<limit lower="1.57" upper="-1.57" .../>``
    Good: ``<limit lower="-1.57" upper="1.57" .../>``
    """
    for joint, limit, lower, upper in _ranges(robot):
        if lower > upper:
            yield limit, (f"joint '{_name(joint)}': lower limit {lower:g} is above upper limit "
                          f"{upper:g}; swap them")


def _axis(joint):
    axis = joint.find("axis")
    if axis is None or joint.get("type") not in AXIS:
        return axis, None
    values, _ = parse_numbers(axis.get("xyz"), 3)
    return axis, values


@rule("U205", "zero-axis", Severity.ERROR)
def zero_axis(robot):
    """A moving joint's axis has zero length.

    The joint has no direction to move in; normalising it divides by zero.

    Bad: ``<axis xyz="0 0 0"/>``
    Good: ``<axis xyz="0 0 1"/>``
    """
    for joint in robot.children("joint"):
        axis, values = _axis(joint)
        if values is not None and finite(values) and math.hypot(*values) == 0:
            yield axis, f"joint '{_name(joint)}' has a zero-length axis; give a unit vector"


@rule("U206", "axis-not-unit", Severity.WARNING)
def axis_not_unit(robot):
    """A moving joint's axis is not a unit vector.

    Some parsers normalise it and some do not, so the same joint value moves the robot by
    different amounts in different tools.

    Bad: ``<axis xyz="0 0 2"/>``
    Good: ``<axis xyz="0 0 1"/>``
    """
    for joint in robot.children("joint"):
        axis, values = _axis(joint)
        if values is None or not finite(values):
            continue
        norm = math.hypot(*values)
        if norm > 0 and abs(norm - 1) > UNIT_TOLERANCE:
            unit = " ".join(f"{v / norm:.6g}" for v in values)
            yield axis, (f"joint '{_name(joint)}' axis has length {norm:.6g}, not 1; "
                         f"write xyz=\"{unit}\"")


def _numeric_problems(robot) -> list:
    """(joint, element, attribute, values, problem) of every joint number; once per robot."""
    return robot.memo(_numeric_problems, lambda: list(_numeric_fields(robot)))


def _numeric_fields(robot):
    for joint in robot.children("joint"):
        for element in joint:  # one pass over the children, not a findall per field
            for attribute, count in _FIELDS_BY_TAG.get(element.tag, ()):
                text = element.get(attribute)
                if text is None:
                    continue
                values, problem = parse_numbers(text, count)
                yield joint, element, attribute, values, problem


_FIELDS_BY_TAG: dict[str, list[tuple[str, int]]] = {}
for _tag, _attribute, _count in NUMERIC_FIELDS:
    _FIELDS_BY_TAG.setdefault(_tag, []).append((_attribute, _count))


@rule("U207", "malformed-number", Severity.ERROR)
def malformed_number(robot):
    """A number in a joint's origin, axis, limit, dynamics, mimic or calibration does not parse.

    Bad: ``<origin xyz="0 0.1"/>`` (two numbers), ``<limit effort="ten" .../>``
    Good: ``<origin xyz="0 0.1 0"/>``, ``<limit effort="10" .../>``
    """
    for joint, element, attribute, values, problem in _numeric_problems(robot):
        if problem:
            yield element, f"joint '{_name(joint)}': <{element.tag} {attribute}>: {problem}"


@rule("U208", "non-finite-number", Severity.ERROR)
def non_finite_number(robot):
    """A joint number is ``inf`` or ``nan``.

    Infinite limits belong to continuous joints; NaN poisons every computation downstream.

    Bad: ``<limit lower="-inf" upper="inf" .../>`` on a revolute joint
    Good: ``type="continuous"`` for unlimited rotation, finite limits otherwise
    """
    for joint, element, attribute, values, problem in _numeric_problems(robot):
        if values is not None and not finite(values):
            yield element, (f"joint '{_name(joint)}': <{element.tag} {attribute}="
                            f"\"{element.get(attribute)}\"> is not finite")


def _mimics(robot):
    for joint in robot.children("joint"):
        mimic = joint.find("mimic")
        if mimic is not None:
            yield joint, mimic, mimic.get("joint")


@rule("U209", "mimic-unknown-joint", Severity.ERROR)
def mimic_unknown_joint(robot):
    """A ``<mimic>`` names a joint that does not exist (or names none).

    Bad: ``<mimic joint="finger_jont"/>``
    Good: ``<mimic joint="finger_joint" multiplier="1"/>``
    """
    for joint, mimic, target in _mimics(robot):
        if not target:
            yield mimic, f"joint '{_name(joint)}': <mimic> has no joint attribute"
        elif target not in robot.joints:
            yield mimic, (f"joint '{_name(joint)}' mimics '{target}', which does not exist; "
                          f"{available('joints', target, robot.joints)}")


@rule("U210", "mimic-self", Severity.ERROR)
def mimic_self(robot):
    """A joint mimics itself.

    Bad: ``<joint name="j"> ... <mimic joint="j"/>``
    Good: mimic another joint
    """
    for joint, mimic, target in _mimics(robot):
        if target and target == joint.get("name"):
            yield mimic, f"joint '{target}' mimics itself"


@rule("U211", "mimic-cycle", Severity.ERROR)
def mimic_cycle(robot):
    """Mimic joints follow each other in a loop, so none of them has a driver.

    Bad: ``a`` mimics ``b`` and ``b`` mimics ``a``
    Good: ``b`` mimics ``a``, and ``a`` is actuated
    """
    follows = {joint.get("name"): target for joint, _, target in _mimics(robot)
               if target and target != joint.get("name")}
    reported: set[str] = set()
    for start in follows:
        chain, name = [], start
        while name in follows and name not in chain:
            chain.append(name)
            name = follows[name]
        if name in chain and name not in reported:
            loop = chain[chain.index(name):]
            reported.update(loop)
            yield robot.joints[name].find("mimic"), "mimic joints form a cycle: " + " -> ".join(
                [*loop, name])


@rule("U212", "zero-effort-or-velocity", Severity.WARNING)
def zero_effort_or_velocity(robot):
    """A moving joint's limit allows zero (or negative) effort or velocity.

    Controllers clamp commands to these limits, and MoveIt time-parameterises with the velocity:
    a zero makes the joint immovable.

    Bad: ``<limit lower="-1" upper="1" effort="0" velocity="0"/>``
    Good: the actuator's real stall torque and no-load speed
    """
    for joint in robot.children("joint"):
        limit = joint.find("limit")
        if limit is None or joint.get("type") not in MOVING:
            continue
        for attribute in ("effort", "velocity"):
            values, _ = parse_numbers(limit.get(attribute), 1)
            if values and values[0] <= 0:
                yield limit, (f"joint '{_name(joint)}': {attribute} limit is {values[0]:g}; "
                              "the joint cannot move")


@rule("U213", "safety-controller-incomplete", Severity.ERROR)
def safety_controller_incomplete(robot):
    """A ``<safety_controller>`` has no ``k_velocity``.

    urdfdom requires it and refuses the joint without it; the soft limits and ``k_position`` are
    optional.

    Bad: ``<safety_controller k_position="100" soft_lower_limit="-1" soft_upper_limit="1"/>``
    Good: ``<safety_controller k_velocity="10" k_position="100" .../>``
    """
    for joint in robot.children("joint"):
        for safety in joint.findall("safety_controller"):
            if safety.get("k_velocity") is None:
                yield safety, f"joint '{_name(joint)}': <safety_controller> has no k_velocity"


SINGLE_CHILDREN = ("origin", "parent", "child", "axis", "limit", "dynamics", "mimic",
                   "calibration", "safety_controller")


@rule("U214", "repeated-joint-element", Severity.WARNING)
def repeated_joint_element(robot):
    """A joint has two ``<origin>``, ``<limit>``, ``<axis>`` (or other single) elements.

    Parsers read the first and silently ignore the rest, so the second one, often the intended
    edit, has no effect.

    Bad: ``<origin xyz="0 0 0.1"/> ... <origin xyz="0 0 0.2"/>`` in one joint
    Good: one ``<origin>``
    """
    for joint in robot.children("joint"):
        for tag in SINGLE_CHILDREN:
            repeats = joint.findall(tag)
            for extra in repeats[1:]:
                yield extra, (f"joint '{_name(joint)}' has {len(repeats)} <{tag}> elements; "
                              f"only the first (at {robot.locate(repeats[0])}) is used")


@rule("U215", "zero-range", Severity.WARNING)
def zero_range(robot):
    """A revolute or prismatic joint's lower and upper limits are equal, so it cannot move.

    A ``<limit>`` without ``lower``/``upper`` defaults both to 0: the joint is silently frozen.
    If the joint really is rigid, make it ``fixed``; if it spins freely, make it ``continuous``.

    Bad: ``<joint type="revolute"> ... <limit effort="10" velocity="2"/>``
    Good: ``<limit lower="-1.57" upper="1.57" effort="10" velocity="2"/>``
    """
    for joint, limit, lower, upper in _ranges(robot):
        if lower == upper:
            defaulted = "" if limit.get("lower") and limit.get("upper") else \
                " (a missing lower/upper defaults to 0)"
            yield limit, (f"{joint.get('type')} joint '{_name(joint)}' has lower = upper = "
                          f"{lower:g}{defaulted}: it cannot move; give its range, or make it "
                          "fixed or continuous")
