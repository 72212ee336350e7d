"""Reading numbers out of URDF attributes the way urdfdom does, with reasons when it cannot."""

from __future__ import annotations

import functools
import math
import re
import sys
from collections import namedtuple

from urdftool.description.urdf import LIMITED
from urdftool.description.xml import first_child

# What urdfdom's parser accepts as a double (no hex, no digit separators, ASCII digits only:
# C++'s stream reads no other script's, where re's \d and Python's float() take full-width and
# Arabic-Indic digits), plus the non-finite spellings, which are parsed so that a rule can say
# "not finite" instead of "not a number".
_DECIMAL = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_NON_FINITE = re.compile(r"[+-]?(?:inf|infinity|nan)", re.IGNORECASE)
# What separates a URDF's numbers: ASCII white space, as C's isspace in the classic locale
# (urdfdom splits at spaces and its stream skips the others before a number). Not str.split's
# or re's \s, which split at a NO-BREAK SPACE, an EM SPACE, NEL and \x1c-\x1f too: a part
# "1\xa00" is one component urdfdom cannot parse, not two numbers.
_SPACE = " \t\n\r\f\v"
SPACE = _SPACE  # (for readers of other grammars: ros2_control strips these)
_SPACES = re.compile(f"[{_SPACE}]+")
# A text whose parts are all _DECIMAL, matched at once: each part is then to_float's float(part).
_DECIMALS = re.compile(rf"[{_SPACE}]*(?:{_DECIMAL.pattern})(?:[{_SPACE}]+(?:{_DECIMAL.pattern}))*[{_SPACE}]*")


def to_float(text: str) -> float:
    """``text`` as a float under urdfdom's grammar; ValueError otherwise."""
    if _DECIMAL.fullmatch(text) or _NON_FINITE.fullmatch(text):
        return float(text)
    raise ValueError(text)


def parse_numbers(text: str | None, count: int | None = None):
    """(values, problem): values is None when ``text`` is not ``count`` finite-or-not numbers."""
    values, problem = number_tuple(text, count)
    return (list(values) if values is not None else None), problem


@functools.lru_cache(maxsize=65536)
def number_tuple(text: str | None, count: int | None = None):
    """:func:`parse_numbers` with the values as a tuple, worked out once per distinct text:
    every rule family reads the same origins, limits and inertias, and real robots repeat their
    values. The tuple is shared by every caller; the rules that only read the numbers take it
    as it is (a large robot asks 390,000 times, and the copy into a list costs a third of a
    call)."""
    if text is None:
        return None, "missing"
    plain = not text.strip(_PLAIN)  # ASCII digits, signs, points, exponents and spaces only
    parts = text.split() if plain else split(text)  # (str.split is split's there)
    if count is not None and len(parts) != count:  # (a part no number said first, as urdfdom
        unread = _part_by_part(text, parts)[1]  # does: "1\xa00 0" is no two numbers and a gap)
        return None, unread or f"expected {count} numbers, found {len(parts)} in '{text}'"
    if plain:
        try:  # (float reads such a part exactly when it is _DECIMAL: no regular expression
            return tuple(map(float, parts)), None  # for the 10,000 origins of a large robot)
        except ValueError:
            return _part_by_part(text, parts)
    if _DECIMALS.fullmatch(text):  # every part decimal, as nearly all are: one match for all
        return tuple(map(float, parts)), None
    return _part_by_part(text, parts)


def split(text: str) -> list[str]:
    """The parts of a text of numbers, as urdfdom separates them (ASCII white space only)."""
    stripped = text.strip(_SPACE)
    return _SPACES.split(stripped) if stripped else []


# urdfdom's grammar is narrower than the one above in its white space alone (urdf_model's
# utils.h strToDouble, pose.h Vector3::init, color.h Color::init). A scalar is a C++ stream's
# read of the whole text: white space before the number is skipped, anything after it, a
# space too, makes it "not a float". A vector is split at spaces (' ') only, empty parts
# skipped, each part read as a scalar: a tab, line break or carriage return after a digit and
# before the next space leaves a part that is no number ("Unable to parse component").
def urdfdom_refuses(text: str, count: int) -> str | None:
    """The part of ``text`` (``count`` numbers to :func:`number_tuple`) that urdfdom reads as no
    number for its white space alone: the whole text for a scalar (``count`` 1) with white
    space after its number, else a vector's first part holding white space after a number;
    None when urdfdom reads it as this module does, or when this module does not (another
    rule's finding)."""
    if count == 1:
        refused = text if text[-1:] in _SPACE and text.strip(_SPACE) else None
    elif text.isprintable():  # (no tab, line break or carriage return: as nearly every text)
        return None
    else:
        refused = next((part for part in text.split(" ")
                        if any(c in _SPACE for c in part.lstrip(_SPACE))), None)
    return refused if refused and not number_tuple(text, count)[1] else None


def urdfdom_spelling(text: str) -> str:
    """``text``'s numbers as every reader takes them: one space between them, none around."""
    return " ".join(split(text))


# The characters of a text of plain decimals (white space as str.split and re's \s read it,
# ASCII's): strip() of them leaves nothing of such a text. Over these characters, float()
# takes a part exactly when _DECIMAL matches it (no underscore, letter of inf or nan, nor
# digit of another script: those texts are matched as before)
_PLAIN = "0123456789+-.eE \t\n\r\f\v"


def _part_by_part(text: str, parts: list[str]):
    """:func:`number_tuple` of ``text`` split into ``parts``, each read by :func:`to_float`. The
    problem quotes the part that is no number, and the whole text only when it holds more (a
    one-part text said twice, ``'x' is not a number (in 'x')``, reads as two values)."""
    values = []
    for part in parts:
        try:
            values.append(to_float(part))
        except ValueError:
            whole = "" if part == text.strip(_SPACE) else f" (in '{text}')"
            return None, f"'{part}' is not a number{_unseen_space(part)}{whole}"
    return tuple(values), None


def _unseen_space(part: str) -> str:
    """Why a part that looks like numbers and a gap is one part: the first white space in it
    that is not ASCII's (it prints as a blank), by its code and name; empty when none."""
    for character in part:
        if character.isspace() and character not in _SPACE:
            import unicodedata  # (only for such a part)

            name = unicodedata.name(character, "white space")
            return f": U+{ord(character):04X} {name} separates no numbers"
    return ""


def finite(values) -> bool:
    """Whether every value is finite: their sum is, unless one is not (inf or nan makes the
    sum inf or nan) or the sum overflows (then each is looked at)."""
    return math.isfinite(sum(values)) or all(map(math.isfinite, values))


def number(element, attribute: str, default: float | None = None):
    """A single numeric attribute as float, ``default`` when absent, None when malformed."""
    text = element.get(attribute)
    if text is None:
        return default
    values, problem = parse_numbers(text, 1)
    return values[0] if values else None


def limit_range(kind: str | None, limit, texts: tuple | None = None
                ) -> tuple[float, float] | None:
    """(lower, upper) of a joint's ``<limit>``, as urdfdom reads them (joint.cpp,
    parseJointLimits): each bound as :func:`limit_bound` reads it; None when the joint is not
    revolute or prismatic (``kind``: :data:`~urdftool.description.urdf.LIMITED`, the types
    whose range limits them), has no ``<limit>``, or either bound is no number. The one
    reading of a joint's range: the joint rules, Drake's inverted limits, SRDF states, MoveIt's
    and the spec's limits, symmetry and the crosscheck's poses all compare against it.

    ``texts``: (lower, upper) as written, for a caller that has them read already."""
    if limit is None or kind not in LIMITED:
        return None
    lower_text, upper_text = (limit.get("lower"), limit.get("upper")) if texts is None \
        else texts
    lower, upper = _bound(lower_text), _bound(upper_text)
    return (lower, upper) if lower is not None and upper is not None else None


def limit_bound(limit, name: str) -> float | None:
    """Bound ``name`` ("lower" or "upper") of a revolute or prismatic joint's ``<limit>`` as
    urdfdom reads it: 0 when it is not written (urdfdom's default, which the joint then
    keeps: a planner stops there); None when it is no number. A number not finite is one
    here. For a caller that compares each bound on its own (:func:`limit_range` for both)."""
    return _bound(limit.get(name))


def limit_value(joint, attribute: str) -> float | None:
    """The number of ``attribute`` of ``joint``'s ``<limit>``, None without a ``<limit>``: a
    bound (lower, upper) as :func:`limit_bound` reads it, 0 when not written; an effort or a
    velocity when written and a number. What the URDF says a joint allows, as the limits of
    another file (a spec, MoveIt's joint_limits.yaml) are compared with it."""
    limit = joint.find("limit")
    if limit is None:
        return None
    if attribute in ("lower", "upper"):
        return limit_bound(limit, attribute)
    values, _ = number_tuple(limit.get(attribute), 1)
    return values[0] if values else None


def _bound(text: str | None) -> float | None:
    """A ``<limit>`` bound's text as urdfdom reads it: 0 when not written, None when no number."""
    values, _ = number_tuple("0" if text is None else text, 1)
    return values[0] if values else None


def axis_xyz(joint) -> tuple[float, float, float] | None:
    """The three numbers of a joint's axis as urdfdom reads them (joint.cpp, parseJoint):
    ``1 0 0`` without an ``<axis>``; ``0 0 0`` for an ``<axis>`` without ``xyz`` (urdfdom keeps
    the axis it cleared: the joint has no direction, and moves nothing in RViz or Pinocchio);
    None when ``xyz`` is not three numbers (urdfdom refuses the joint). Not finite is a number
    here. The one reading of an axis: physics.frames' (the rules') and the kinematics' unit
    axes and dynamics' words on Pinocchio's all start from it."""
    element = first_child(joint, "axis")
    if element is None:
        return (1.0, 0.0, 0.0)
    text = element.get("xyz")
    if text is None:
        return (0.0, 0.0, 0.0)
    return number_tuple(text, 3)[0]


_UNREAD = object()  # (origin_pose: the first <origin> not looked for yet)


class Origin(namedtuple("Origin", ("xyz", "rpy", "problem", "element"),
                        defaults=((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), None, None))):
    """An element's ``<origin>``: xyz in [m], rpy in [rad] (URDF roll-pitch-yaw).

    Identity when there is no ``<origin>``. A malformed ``xyz`` or ``rpy`` reads as zeros and sets
    ``problem`` (the first one), so each caller chooses: count it as 0, or refuse it.
    xyz, rpy: 3-tuples of floats; problem: str or None
    element: the ``<origin>`` element, None when absent

    A named tuple, immutable: a third of a frozen dataclass's cost to make (a 10,000-link
    robot's inertials and shapes read 30,000). collections' (typing's NamedTuple would import
    typing into every check).
    """

    __slots__ = ()


def origin(element) -> Origin:
    """The ``<origin>`` child of ``element`` (which may be None) as an :class:`Origin`."""
    found = first_child(element, "origin") if element is not None else None
    if found is None:
        return _NO_ORIGIN
    xyz, xyz_problem = number_tuple(found.get("xyz", "0 0 0"), 3)  # tuples, as an Origin holds
    rpy, rpy_problem = number_tuple(found.get("rpy", "0 0 0"), 3)
    problem = f"xyz: {xyz_problem}" if xyz_problem else f"rpy: {rpy_problem}" if rpy_problem else None
    return Origin(xyz or _ZEROS, rpy or _ZEROS, problem, found)


def origin_pose(element, found=_UNREAD) -> tuple[tuple[float, float, float],
                                                 tuple[float, float, float]]:
    """(xyz, rpy) of :func:`origin` (zeros for a malformed part), without the rest: the solids
    and inertials place 30,000 shapes and inertials of a 10,000-link robot, and count a
    malformed part as 0 (the rules that judge it read :func:`origin`). ``found``: the first
    ``<origin>`` of ``element`` (or None), when the caller has its children at hand."""
    if found is _UNREAD:
        found = first_child(element, "origin") if element is not None else None
    if found is None:
        return _ZEROS, _ZEROS
    get = found.get
    return number_tuple(get("xyz", "0 0 0"), 3)[0] or _ZEROS, \
        number_tuple(get("rpy", "0 0 0"), 3)[0] or _ZEROS


def pose_of(xyz: str = "0 0 0", rpy: str = "0 0 0") -> tuple[tuple[float, float, float],
                                                            tuple[float, float, float]]:
    """:func:`origin_pose` of an ``<origin>`` whose ``xyz`` and ``rpy`` texts were read (their
    defaults: none written, or no ``<origin>``), for a caller that keeps the texts."""
    return number_tuple(xyz, 3)[0] or _ZEROS, number_tuple(rpy, 3)[0] or _ZEROS


_ZEROS = (0.0, 0.0, 0.0)
_NO_ORIGIN = Origin()


# The number parsers of ros2_control and its Gazebo plugins, for the values of a <param> of a
# <ros2_control> interface (min, max, initial_value). ros2_control's is hardware_interface::stod
# (hardware_interface/src/lexical_casts.cpp): built as C++17 (and on macOS) an istringstream in
# the classic locale that must read the whole text, built as C++20 (ros2_control_cmake 0.4.0 and
# later set the standard) std::from_chars after one leading '+', a finite result either way.
# Humble's gazebo_ros2_control and ign_ros2_control read initial_value with std::stod (C's
# strtod): a number at the start of the text, whatever follows it. Each returns the value, or
# None where the parser refuses the text (checked against the C++ of both builds and of
# std::stod compiled with g++ 12: tests/description/test_values.py's table).
_UNSIGNED = r"(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"
_FROM_CHARS = re.compile(rf"-?({_UNSIGNED})")
_STRTOD = re.compile(rf"[{_SPACE}]*([+-]?)(?:(inf(?:inity)?|nan(?:\([0-9A-Za-z_]*\))?)|"
                     r"(0[xX](?:[0-9a-fA-F]+\.?[0-9a-fA-F]*|\.[0-9a-fA-F]+)(?:[pP][+-]?[0-9]+)?)|"
                     rf"({_UNSIGNED}))", re.IGNORECASE)


def stream_double(text: str) -> float | None:
    """``text`` as ``std::istringstream(text) >> double`` in the classic locale reads it when the
    stream must end at its end (white space before the number skipped, none after it taken),
    and the value is finite: ``' 1'`` is 1, ``'1 '``, ``'inf'``, ``'0x10'`` and ``'1e400'`` are
    not read; a value below the smallest double reads as 0."""
    body = text.lstrip(_SPACE)
    if not _DECIMAL.fullmatch(body):
        return None
    value = float(body)
    return value if math.isfinite(value) else None


def from_chars_double(text: str) -> float | None:
    """``text`` as ros2_control's C++20 build reads it: ``std::from_chars`` over the whole text
    after one leading ``+`` (so ``'+-1'`` is -1), no white space, a finite value; a text of
    nonzero digits whose value rounds to 0 (``'1e-400'``) is out of range, refused."""
    body = text[1:] if text[:1] == "+" else text
    match = _FROM_CHARS.fullmatch(body)
    if match is None:
        return None
    value = float(body)
    if not math.isfinite(value) or (value == 0 and _nonzero_digits(match.group(1))):
        return None
    return value


def strtod_double(text: str) -> float | None:
    """``text`` as ``std::stod`` reads it: white space skipped, then the longest number at the
    start (decimal, hexadecimal, ``inf``, ``nan``), anything after it ignored (``'1.5rad'`` is
    1.5); None when no number starts it (``invalid_argument``) or its value is out of range,
    above the largest double or below the smallest normal one (``out_of_range``: strtod's
    ERANGE)."""
    match = _STRTOD.match(text)
    if match is None:
        return None
    sign, special, hexadecimal, decimal = match.groups()
    if special:
        return float(sign + ("nan" if special.lower().startswith("nan") else "inf"))
    try:
        value = float.fromhex(sign + hexadecimal) if hexadecimal else float(sign + decimal)
    except OverflowError:
        return None
    if not math.isfinite(value) or (abs(value) < sys.float_info.min and
                                    not _exactly(value, hexadecimal or decimal)):
        return None
    return value


def _nonzero_digits(number: str, exponent: str = "[eE]") -> bool:
    """Whether the digits of ``number`` before its ``exponent`` hold one that is not 0."""
    return any(c not in "0." for c in re.split(exponent, number, maxsplit=1)[0])


def _exactly(value: float, number: str) -> bool:
    """Whether ``value`` is the exact value of the unsigned decimal or hexadecimal ``number``
    (strtod's ERANGE below the smallest normal double is for an inexact result: ``0x1p-1074``
    is exact, ``4.9e-324`` is not)."""
    from fractions import Fraction  # (only for a value that small)

    from urdftool.numbers import power

    if value == 0:  # (before any Fraction: '1e-999999999' would be 10**999999999 to it)
        hexadecimal = number[:2].lower() == "0x"
        return not (_nonzero_digits(number[2:], "[pP]") if hexadecimal else _nonzero_digits(number))
    if number[:2].lower() != "0x":  # (a nonzero value: its exponent is within the doubles')
        try:
            return Fraction(abs(value)) == Fraction(number)
        except ValueError:  # over Python's 4,300 digits of int(): no exact subnormal
            return False
    mantissa, _, exponent = number[2:].lower().partition("p")
    whole, _, fraction = mantissa.partition(".")
    digits = (whole + fraction) or "0"
    return Fraction(abs(value)) == Fraction(int(digits, 16), 16 ** len(fraction)) * \
        power(Fraction(2), int(exponent or "0"))
