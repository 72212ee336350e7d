"""Reading numbers out of URDF attributes the way urdfdom does, with reasons when it cannot."""

from __future__ import annotations

import functools
import math
import re
from collections import namedtuple

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
