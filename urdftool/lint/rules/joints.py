"""U2xx: joints (types, limits, axes, numbers, mimic)."""

from __future__ import annotations

import math

from urdftool.lint.catalogue import Conditional, Severity, UrdfdomAlone, rule
from urdftool.numbers import computed, length, number, unit
from urdftool.errors import available
from urdftool.description.urdf import (AXIS, JOINT_NUMBER_PLACES, JOINT_TYPES, LIMITED, MOVING,
                                       NUMBERS)
from urdftool.description.values import finite, limit_range, number_tuple, parse_numbers

# An axis is a unit vector when its length is within this of 1. CAD exporters round each
# component to 5 or 6 significant digits, which leaves the length a few 1e-6 off (moveo_ros,
# nao_robot); an axis 1e-4 off scales the motion by 0.01 %, which no tool can feel, while the
# mistakes worth a warning ("0 0 2", "1 1 0") are off by 0.4 or more.
UNIT_TOLERANCE = 1e-4

# (child tag, attribute, how many numbers) read as numbers in a joint
NUMERIC_FIELDS = tuple((tag, attribute, count) for tag in JOINT_NUMBER_PLACES
                       for attribute, count in NUMBERS[tag])  # (urdf.NUMBERS: one owner)


# The readers other than urdfdom (description.readers.Reader.kind) that take a revolute or
# prismatic joint without <limit>, or a <limit> without effort or velocity: Drake (unbounded),
# three.js urdf-loader (it reads lower and upper alone, 0 when missing)
TAKEN_ELSEWHERE = frozenset({"drake", "browser"})
# ... and a <limit> without effort or velocity: Genesis too (its urdfpy reads them as 0)
EFFORT_TAKEN_ELSEWHERE = TAKEN_ELSEWHERE | {"genesis"}


def _name(joint) -> str:
    return joint.get("name") or "?"


@rule("U201", "unknown-joint-type", Severity.ERROR)
def unknown_joint_type(robot):
    """A joint's ``type`` is missing or not one of the six URDF types.

    Bad: ``<joint name="j" type="hinge">``
    Good: ``<joint name="j" type="revolute">`` (or continuous, prismatic, fixed, floating, planar)
    """
    kinds = robot.kinds()
    for joint in robot.children("joint"):
        kind = kinds[joint]
        if kind not in JOINT_TYPES:
            what = f"type '{kind}'" if kind is not None else "no type"
            yield joint, f"joint '{_name(joint)}' has {what}; valid types: {', '.join(JOINT_TYPES)}"


def _limits(robot) -> list:
    """(joint, its type, its first ``<limit>`` or None) of every joint; once per robot (three
    rules ask)."""
    kinds = robot.kinds()
    return robot.memo(_limits, lambda: [(joint, kinds[joint], robot.child(joint, "limit"))
                                        for joint in robot.children("joint")])


@rule("U202", "missing-limit", Severity.ERROR)
def missing_limit(robot):
    """A revolute or prismatic joint has no ``<limit>``.

    urdfdom refuses it; MoveIt and controllers need the range, effort and velocity.

    A **warning** naming the condition in a file Drake or a web page reads, as its files say
    and nothing says ROS runs it (``xmlns:drake``; a web application's served copy that its
    source fetches): Drake reads the joint as unbounded, three.js urdf-loader with a range of 0;
    still urdfdom's refusal, which the commands that pose a robot refuse.

    Bad: ``<joint name="elbow" type="revolute">`` without ``<limit>``
    Good: ``<limit lower="-1.57" upper="1.57" effort="10" velocity="2"/>``
    """
    for joint, kind, limit in _limits(robot):
        if kind in LIMITED and limit is None:
            yield joint, UrdfdomAlone(f"{kind} joint '{_name(joint)}' has no <limit>; add "
                                      "<limit lower=... upper=... effort=... velocity=.../>",
                                      TAKEN_ELSEWHERE)


@rule("U203", "limit-missing-effort-velocity", Severity.ERROR)
def limit_missing_effort_velocity(robot):
    """A ``<limit>`` lacks ``effort`` or ``velocity``.

    Both are required by the URDF specification; urdfdom refuses the joint without them.
    A **warning** naming the condition in a file Drake, a web page or Genesis reads (see U202;
    Genesis: its own assets): Drake reads no effort or velocity as unbounded, three.js
    urdf-loader reads neither, Genesis's urdfpy reads them as 0.

    Bad: ``<limit lower="0" upper="1"/>``
    Good: ``<limit lower="0" upper="1" effort="5" velocity="1"/>``
    """
    read = _texts(robot)  # (once, not once per joint)
    for joint, _, limit in _limits(robot):
        if limit is None:
            continue
        texts = read[limit]
        missing = [a for a, text in (("effort", texts[_EFFORT]), ("velocity", texts[_VELOCITY]))
                   if text is None]
        if missing:
            yield limit, UrdfdomAlone(f"joint '{_name(joint)}': <limit> has no "
                                      f"{' or '.join(missing)}", EFFORT_TAKEN_ELSEWHERE)


def _bounds(robot, kind: str | None, limit, read: dict | None = None
            ) -> tuple[float, float] | None:
    """(lower, upper) of a revolute or prismatic joint (``kind``) whose ``<limit>`` range
    parses (:func:`~urdftool.description.values.limit_range`, its texts read once per robot).
    ``read``: :func:`_texts`, for a caller asking of every joint."""
    if limit is None or kind not in LIMITED:
        return None
    texts = (_texts(robot) if read is None else read)[limit]
    return limit_range(kind, limit, (texts[_LOWER], texts[_UPPER]))


def _ranges(robot) -> list:
    """(joint, limit, lower, upper) of revolute and prismatic joints whose range parses; once
    per robot (three rules ask)."""
    def build():
        read = _texts(robot)  # (once, not once per joint)
        return [(joint, limit, *bounds) for joint, kind, limit in _limits(robot)
                if (bounds := _bounds(robot, kind, limit, read)) is not None]

    return robot.memo(_ranges, build)


@rule("U204", "inverted-limits", Severity.ERROR)
def inverted_limits(robot):
    """A joint's lower limit is above its upper limit.

    The joint can reach no position: planners fail and controllers clamp to nonsense.

    Fix (safe): the two values swapped where they are written.

    Bad: ``<limit lower="1.57" upper="-1.57" .../>``
    Good: ``<limit lower="-1.57" upper="1.57" .../>``
    """
    for joint, limit, lower, upper in _ranges(robot):
        if lower > upper and math.isfinite(lower) and math.isfinite(upper):  # (else U208)
            from urdftool.lint.fixes import offer, swap_attributes  # (only for a finding)
            yield offer(limit, (f"joint '{_name(joint)}': lower limit {lower:g} is above upper "
                                f"limit {upper:g}; swap them"), "swap lower and upper",
                        swap_attributes(robot, limit, "lower", "upper", default="0"))


def _axes(robot) -> list:
    """(joint, axis, xyz, length, whether its squares vanish: :func:`_vanishes`) of each moving
    joint whose axis is three finite numbers; once per robot (U205 and U206 ask), each text
    measured once (robots repeat their axes: 10,000 joints, a few axes)."""
    def read():
        found, kinds, texts = [], robot.kinds(), _texts(robot)
        measured = {}  # an axis's xyz text -> (xyz, length, vanishes), or None when not finite
        for joint in robot.children("joint"):
            axis = robot.child(joint, "axis")
            if axis is None or kinds[joint] not in AXIS:
                continue
            text = texts[axis][0]  # (its xyz; None for an <axis> without one: urdfdom's
            known = measured.get(text, _UNMEASURED)  # cleared 0 0 0, values.axis_xyz)
            if known is _UNMEASURED:
                values, _ = number_tuple("0 0 0" if text is None else text, 3)
                known = measured[text] = (values, length(values), _vanishes(values)) \
                    if values is not None and finite(values) else None
            if known is not None:
                found.append((joint, axis, *known))
        return found

    return robot.memo(_axes, read)


_UNMEASURED = object()


@rule("U205", "zero-axis", Severity.ERROR)
def zero_axis(robot):
    """A moving joint's axis has zero length, or one too small for loaders to normalise.

    The joint has no direction to move in; normalising it divides by zero. Loaders normalise
    with the sum of the squares (Eigen in Pinocchio and MoveIt, gz-math in Gazebo, MuJoCo);
    when it underflows to 0 (``5e-324 5e-324 5e-324``), the axis they get is left as written
    (the joint does not move) or replaced by x (KDL, MuJoCo), and urdftool's fk and dynamics
    refuse it.

    An ``<axis>`` without ``xyz`` is the same: urdfdom reads it as ``0 0 0`` (the axis it
    cleared; 1 0 0 is only for a joint with no ``<axis>`` at all), Pinocchio builds a revolute
    joint about no axis, PyBullet reads memory it never set, and MuJoCo refuses the file.

    Bad: ``<axis xyz="0 0 0"/>``, ``<axis xyz="0 0 1e-200"/>``, ``<axis/>``
    Good: ``<axis xyz="0 0 1"/>``
    """
    for joint, axis, values, length, vanishes in _axes(robot):
        if length == 0 and _texts(robot)[axis][0] is None:
            yield axis, (f"joint '{_name(joint)}' has an <axis> without xyz, which urdfdom "
                         "(ROS, Gazebo, MoveIt, Pinocchio) reads as 0 0 0, no direction, and "
                         "MuJoCo refuses; write xyz as a unit vector")
        elif length == 0:
            yield axis, f"joint '{_name(joint)}' has a zero-length axis; give a unit vector"
        elif vanishes:
            yield axis, (f"joint '{_name(joint)}' has an axis of length {number(length, 3)}, "
                         "whose squared length underflows to 0: loaders that normalise it "
                         "(Pinocchio, Gazebo, MuJoCo, KDL) get no direction or another; give a "
                         "unit vector")


def _vanishes(values) -> bool:
    """Whether the sum of the squares of ``values``, as loaders compute it, is 0 (session 9:
    check passed an axis of 5e-324 that fk and dynamics refuse)."""
    return sum(v * v for v in values) == 0


@rule("U206", "axis-not-unit", Severity.WARNING)
def axis_not_unit(robot):
    """A moving joint's axis is not a unit vector.

    Some parsers normalise it and some do not, so the same joint value moves the robot by
    different amounts in different tools.

    An axis within 1e-4 of unit length is one, as CAD exporters round it to 5 or 6 digits.

    Fix (safe): the axis divided by its length, written with as many digits as make it a unit
    vector to 1e-5.

    Bad: ``<axis xyz="0 0 2"/>``
    Good: ``<axis xyz="0 0 1"/>``
    """
    for joint, axis, values, norm, vanishes in _axes(robot):
        if norm > 0 and abs(norm - 1) > UNIT_TOLERANCE and not vanishes:  # (U205)
            unit = _unit_text(values, norm)
            from urdftool.lint.fixes import offer, set_attribute  # (only for a finding)
            yield offer(axis, (f"joint '{_name(joint)}' axis has length {number(norm, 6)}, not 1; "
                               f"write xyz=\"{unit}\""), f"normalise the axis to {unit}",
                        set_attribute(robot, axis, "xyz", unit))


def _unit_text(values, norm: float) -> str:
    """The unit vector of ``values`` as text: the fewest digits (6 or more) that keep its
    length within UNIT_TOLERANCE of 1."""
    direction = unit(values)  # scaled: 1e308 1e308 1e308 is 0.57735 0.57735 0.57735, not 0 0 0
    for digits in (6, 9, 12, 17):
        text = " ".join(f"{v:.{digits}g}" for v in direction)
        if abs(math.hypot(*(float(part) for part in text.split())) - 1) <= UNIT_TOLERANCE / 10:
            return text
    return text


def _numeric_problems(robot) -> list:
    """(joint, element, attribute, values, problem) of every joint number that does not parse
    (``problem``) or is not finite, in document order; once per robot (U207 and U208 ask). The
    numbers that are fine are not kept: most are, and a 10,000-joint robot has 60,000."""
    return _numbers(robot)[1]


def _texts(robot) -> dict:
    """Element -> the texts of its numeric attributes (None for one not written), in the
    order of :data:`NUMERIC_FIELDS` for its tag, of every child of every joint that has
    them: each read from lxml once per robot (U203, U204, U205, U207, U212 ask for the same
    limits and axes, 100,000 reads on a 10,000-joint robot)."""
    return _numbers(robot)[0]


def origin_xyz(robot, joint) -> tuple[float, float, float]:
    """The xyz of ``joint``'s first ``<origin>`` as :func:`~urdftool.description.values.
    origin_pose` reads it (zeros without one, or for a malformed text), from its text as read
    once per robot (:func:`_texts`): the inertia rules compare it with each link's centre of
    mass (10,000 joints read again)."""
    origin = robot.child(joint, "origin")
    if origin is None:
        return _ZEROS
    text = _texts(robot)[origin][0]  # (its xyz)
    return number_tuple("0 0 0" if text is None else text, 3)[0] or _ZEROS


_ZEROS = (0.0, 0.0, 0.0)


def _numbers(robot) -> tuple[dict, list]:
    """(:func:`_texts`, :func:`_numeric_problems`), read and judged in one pass over the
    joints, once per robot."""
    return robot.memo(_numbers, lambda: _read_numbers(robot))


def _read_numbers(robot) -> tuple[dict, list]:
    texts, found = {}, []
    sound = {count: set() for _, _, count in NUMERIC_FIELDS}  # count -> texts already found
    # to be that many finite numbers (robots repeat their values)
    for joint in robot.children("joint"):
        for tag, elements in robot.grouped(joint).items():
            names = _NAMES_BY_TAG.get(tag)
            if names is None:
                continue  # parent, child: no numbers
            for element in elements:
                texts[element] = tuple(map(element.get, names))
            for index, attribute, count in _FIELDS_BY_TAG[tag]:
                known = sound[count]
                for element in elements:
                    text = texts[element][index]
                    if text is not None and text not in known:
                        values, problem = number_tuple(text, count)
                        if problem or not finite(values):
                            found.append((joint, element, attribute, values, problem))
                        else:
                            known.add(text)
    return texts, found


_FIELDS_BY_TAG: dict[str, list[tuple[int, str, int]]] = {}  # tag -> (index, attribute, count)
for _tag, _attribute, _count in NUMERIC_FIELDS:
    _fields = _FIELDS_BY_TAG.setdefault(_tag, [])
    _fields.append((len(_fields), _attribute, _count))
_NAMES_BY_TAG = {tag: tuple(attribute for _, attribute, _ in fields)
                 for tag, fields in _FIELDS_BY_TAG.items()}
_LOWER, _UPPER, _EFFORT, _VELOCITY = (_NAMES_BY_TAG["limit"].index(name) for name in
                                      ("lower", "upper", "effort", "velocity"))


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


def _mimics(robot) -> list:
    """(joint, its first ``<mimic>``, the joint it names) of every mimic joint; once per robot
    (four rules ask, and most joints mimic none)."""
    return robot.memo(_mimics, lambda: [
        (joint, mimic, mimic.get("joint")) for joint in robot.children("joint")
        if (mimic := robot.child(joint, "mimic")) is not None])


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
                          + available('joints', target, robot.joints))


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
    done: set[str] = set()  # walked from before: what follows them is known (linear, not the
    # cube of a chain's length: 3,000 mimics in a row took minutes)
    for start in follows:
        chain, at, name = [], {}, start
        while name in follows and name not in at and name not in done:
            at[name] = len(chain)
            chain.append(name)
            name = follows[name]
        if name in at and name not in reported:
            loop = chain[at[name]:]
            reported.update(loop)
            yield robot.joints[name].find("mimic"), "mimic joints form a cycle: " + " -> ".join(
                [*loop, name])
        done.update(chain)


# who holds a joint still at a zero limit, and who does not read it
_HELD_STILL_BY = {
    "effort": "what clamps commands to it holds the joint still (gazebo_ros_control, "
              "ros2_control's joint limits, a dynamics simulator); MoveIt and "
              "robot_state_publisher do not read effort",
    "velocity": "MoveIt's time parameterisation and what clamps commands to it "
                "(ros2_control's joint limits, a simulator) hold the joint still",
}


@rule("U212", "zero-effort-or-velocity", Severity.WARNING)
def zero_effort_or_velocity(robot):
    """A moving joint's limit allows zero (or negative) effort or velocity.

    Controllers clamp commands to these limits, and MoveIt time-parameterises with the velocity:
    a zero makes the joint immovable for them (MoveIt plans with the robot's joint_limits.yaml
    instead when that switches on a velocity for the joint, and the message says so). An effort of 0 is the ROS-Industrial exporters'
    "unknown": MoveIt and robot_state_publisher do not read effort, so the message names who
    holds the joint still, as a warning naming what simulates the robot (a Gazebo plugin in
    it, a launch file spawning it, ``--target``) or the ``<ros2_control>`` hardware that takes
    the joint's effort commands (ros2_control's joint limits read ``<limit effort>`` and clamp
    the command to it, on real hardware too), and as a **note** when nothing here does (a
    joint commanded by position: the hardware closes the loop).

    A negative limit means something different to each consumer, so it is a warning, not an
    error: the URDF specification bounds the applied effort by its absolute value; SDFormat
    (Gazebo's import of the URDF) and gazebo_ros_control enforce no limit when it is negative
    (the "no limit" marker some exporters write, ``velocity="-1"``); urdfdom accepts it; and
    Pinocchio refuses the whole model ("Some components of min_velocity are greater than
    max_velocity"). No reading is wrong in every tool, none is right in all of them.

    Bad: ``<limit lower="-1" upper="1" effort="0" velocity="0"/>``
    Good: the actuator's real stall torque and no-load speed
    """
    read = _texts(robot)  # (once, not once per joint)
    for joint, kind, limit in _limits(robot):
        if limit is None or kind not in MOVING:
            continue
        texts = read[limit]
        for attribute, text in (("effort", texts[_EFFORT]), ("velocity", texts[_VELOCITY])):
            values, _ = number_tuple(text, 1)
            if values and values[0] == 0 and attribute == "effort":
                yield limit, _zero_effort(robot, _name(joint))
            elif values and values[0] == 0 and attribute == "velocity":
                yield limit, _zero_velocity(robot, _name(joint))
            elif values and values[0] == 0:
                yield limit, (f"joint '{_name(joint)}': {attribute} limit is 0; "
                              + _HELD_STILL_BY[attribute])
            elif values and values[0] < 0:
                yield limit, (f"joint '{_name(joint)}': {attribute} limit is {number(values[0])}: "
                              "Gazebo (SDFormat) and gazebo_ros_control enforce no limit when it "
                              "is negative, the URDF specification reads its absolute value, and "
                              f"Pinocchio refuses the model (min_{attribute} above max_{attribute}); "
                              f"write the real {attribute} limit")


def _zero_velocity(robot, name: str) -> str:
    """U212's message for a velocity limit of 0: MoveIt's time parameterisation holds the joint
    still unless the robot's MoveIt joint_limits.yaml switches on a velocity of its own for it,
    which MoveIt plans with instead (the JAXA IVR's body joints: max_velocity 3.27 there, as
    U816 reads it); what clamps commands to the URDF's limit holds it still either way."""
    from urdftool.description import moveit_config
    from urdftool.description.companions import companions

    file = companions(robot).planning_limits
    entries = robot.memo(_zero_velocity, lambda: moveit_config.planning_limits(file)[0]
                         if file is not None else [])
    planned = next((entry.values.get("max_velocity") for entry in entries
                    if entry.joint == name), None)
    said = f"joint '{name}': velocity limit is 0; "
    if isinstance(planned, (int, float)) and not isinstance(planned, bool) and planned > 0:
        return (said + "what clamps commands to it (ros2_control's joint limits, a simulator) "
                f"holds the joint still; MoveIt plans with the max_velocity {planned:g} of its "
                f"joint_limits.yaml ({file.display}) instead")
    return said + _HELD_STILL_BY["velocity"]


def _zero_effort(robot, name: str):
    """U212's message for an effort limit of 0: a warning naming what simulates the robot
    (:func:`~urdftool.description.runtime.simulators`), which clamps the joint's force to it; a
    note when nothing here does, as MoveIt and robot_state_publisher do not read effort."""
    from urdftool.description.runtime import simulators

    said = f"joint '{name}': effort limit is 0; " + _HELD_STILL_BY["effort"]
    found = simulators(robot)
    if found:  # a plugin is a name, a launch file spawning the robot a clause of its own
        return Conditional(f"{said}; " + "; ".join(
            what if " spawns it into " in what else f"{what} simulates the robot"
            for what in found[:2]))
    hardware = _effort_hardware(robot, name)
    if hardware is not None:  # real hardware (or mock) driven by effort through ros2_control
        return Conditional(f"{said}; its <ros2_control> joint takes effort commands (hardware "
                           f"{hardware}), which ros2_control's controller manager clamps to this limit "
                           "(enforce_command_limits, true by default)")
    return Conditional(f"{said}; nothing here simulates the robot (no Gazebo plugin in it, no "
                       "launch file spawning it, no --target): the ROS-Industrial exporters' "
                       "'unknown', it matters only to an effort-limited controller or a "
                       "simulator loading it elsewhere", Severity.INFO)


def _effort_hardware(robot, name: str) -> str | None:
    """The hardware plugin of the ``<ros2_control>`` block whose joint ``name`` takes effort
    commands ("no plugin" when it names none), or None when no block commands it by effort."""
    from urdftool.description.actuation import exported_interface, hardware_plugin, \
        ros2_control_joints

    for block, joint in ros2_control_joints(robot):
        if joint.get("name") == name and any(
                exported_interface(robot, block, c.get("name")) == "effort"
                for c in joint.findall("command_interface") if c.get("name")):
            return hardware_plugin(block) or "no plugin"
    return None


@rule("U213", "safety-controller-incomplete", Severity.ERROR)
def safety_controller_incomplete(robot):
    """A ``<safety_controller>`` has no ``k_velocity``.

    urdfdom requires it and refuses the joint without it; the soft limits and ``k_position`` are
    optional.

    Bad: ``<safety_controller k_position="100" soft_lower_limit="-1" soft_upper_limit="1"/>``
    Good: ``<safety_controller k_velocity="10" k_position="100" .../>``
    """
    for joint in robot.children("joint"):
        for safety in robot.grouped(joint).get("safety_controller", ()):
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
        for tag, repeats in robot.grouped(joint).items():
            if len(repeats) > 1 and tag in SINGLE_CHILDREN:
                for extra in repeats[1:]:
                    yield extra, (f"joint '{_name(joint)}' has {len(repeats)} <{tag}> "
                                  f"elements; only the first (at {robot.locate(repeats[0])}) "
                                  "is used")


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


MIMIC_SLACK = 1e-3  # relative to the mimic joint's span: printed rounding of limits


def _range(robot, joint) -> tuple[float, float] | None:
    """Finite, ordered (lower, upper) of a revolute or prismatic joint, else None."""
    bounds = _bounds(robot, joint.get("type"), robot.child(joint, "limit"))
    return bounds if bounds is not None and finite(bounds) and bounds[0] <= bounds[1] else None


@rule("U216", "mimic-outside-limits", Severity.ERROR)
def mimic_outside_limits(robot):
    """A mimic joint is driven outside its own limits.

    A mimic joint's position is ``multiplier * driver + offset``: over the driver's range
    ``[lower, upper]`` that sweeps ``multiplier * [lower, upper] + offset``, which must lie
    within the mimic joint's own ``<limit>`` (slack: 0.1 % of its span). Otherwise simulators
    hold the mimic joint at its limit against the constraint (the gripper does not close) and
    MoveIt reports states with the driver inside its bounds as out of bounds. Checked when
    both joints are revolute or prismatic; the multiplier defaults to 1 and the offset to 0.

    Bad: driver ``<limit lower="0" upper="0.8"/>``, mimic ``<mimic joint="finger"
    multiplier="-1"/>`` with ``<limit lower="0" upper="0.88"/>`` (it would go to -0.8)
    Good: the mimic joint's ``<limit lower="-0.88" upper="0"/>``, or ``multiplier="1"``
    """
    for joint, mimic, target in _mimics(robot):
        driver = robot.joints.get(target) if target else None
        own, driven = _range(robot, joint), _range(robot, driver) if driver is not None else None
        if own is None or driven is None or driver is joint:
            continue
        multiplier, _ = parse_numbers(mimic.get("multiplier", "1"), 1)
        offset, _ = parse_numbers(mimic.get("offset", "0"), 1)
        if not multiplier or not offset or not finite(multiplier + offset):
            continue
        ends = sorted(multiplier[0] * q + offset[0] for q in driven)
        slack = MIMIC_SLACK * max(own[1] - own[0], 1e-9)
        if ends[0] < own[0] - slack or ends[1] > own[1] + slack:
            yield mimic, (f"joint '{_name(joint)}' mimics '{target}' ({multiplier[0]:g} x "
                          f"[{driven[0]:g}, {driven[1]:g}] + {offset[0]:g}), so it goes over "
                          f"[{computed(ends[0])}, {computed(ends[1])}], outside its own limits "
                          f"[{own[0]:g}, {own[1]:g}]; fix the multiplier's sign or the limits")


MULTI_TURN = 7 * math.pi  # [rad]: revolute limits up to +-6 pi (three turns) are real
DEGREE_LIKE = 720.0  # beyond two turns in degrees, a bound is an "unlimited" stand-in (1e10)


@rule("U217", "revolute-range-in-degrees", Severity.WARNING)
def revolute_range_in_degrees(robot):
    """A revolute joint's limit is far beyond any turn count: degrees written as radians.

    URDF revolute limits are radians. A bound beyond 7 pi rad (3.5 turns) and at most 720 reads
    as degrees: ``upper="250"`` is 250 degrees (4.36 rad), not 40 turns. Planners sample the whole
    range and controllers let the joint wind up. Joints that really turn several times
    (``+-2 pi``, ``+-4 pi``, ``+-6 pi`` on wrists and turntables) stay below 7 pi; huge stand-ins
    for "unlimited" (``1e10``) are not degrees and are left alone (``continuous`` says it better).

    Bad: ``<limit lower="-250" upper="250" .../>`` on a revolute joint
    Good: ``<limit lower="-4.3633" upper="4.3633" .../>``
    """
    kinds = robot.kinds()
    for joint, limit, lower, upper in _ranges(robot):
        if kinds[joint] != "revolute" or not finite((lower, upper)):
            continue
        largest = max(abs(lower), abs(upper))
        if MULTI_TURN < largest <= DEGREE_LIKE:
            yield limit, (f"revolute joint '{_name(joint)}' has limits [{lower:g}, {upper:g}] "
                          f"rad ({number(largest / (2 * math.pi), places=1)} turns): degrees "
                          f"written as radians? In radians: lower=\"{number(math.radians(lower))}\" "
                          f"upper=\"{number(math.radians(upper))}\"")
