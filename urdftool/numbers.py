"""How numbers are printed for people: one function, :func:`number`, for every table, report
line, message and generated XML value that shows a float; and for machines, :func:`exact`
(every digit, never ``-0.0``), for every CSV cell and JSON number.

A number is rounded to the precision it is printed with before it is written, and the sign of
a value that rounds to zero is dropped: an inertia tensor whose off-diagonal is ``-9e-21``
(round-off of a rotation) prints ``0``, never ``-9e-21``, ``-0`` or ``-0.000``. The precision
is either a number of decimals (``places``) or of significant digits (``digits``); with
significant digits, ``scale`` is the size of the largest number printed beside it (the same
vector, tensor or table column), so that a value far below that size's last printed digit is
noise and prints ``0``.

:func:`power` is the one float power of the package: Python's ``x ** n`` raises OverflowError
where IEEE arithmetic (and numpy) gives infinity, so a robot's ``radius="1e103"`` would stop a
rule instead of reaching the rule's own test for non-finite values.

:func:`length` and :func:`unit` are the one length and direction of a vector read from a file
(joint axes, directions in meshes, quaternions): ``sqrt(x*x + y*y + z*z)`` (numpy's
``linalg.norm``, Eigen's ``normalized``) squares each part first, so an axis ``1e308 1e308
1e308`` squares to infinity and its direction comes out ``0 0 0`` or NaN, and ``1e-170 0 0``
squares to zero and looks like no direction at all. Scaled by its largest part first, every
finite vector that is not zero has a length (infinite only when the length itself is beyond
the largest float) and a direction.

:func:`integer` is the one conversion of a stranger's text to an integer (YAML, the command
line's counts and seeds; TOML and JSON convert their own, and their readers ask
:func:`long_integer` where the one too long is): Python's ``int()`` refuses a decimal of more
than :data:`MAX_INT_DIGITS` digits with a ValueError no reader expected (a traceback).
:func:`double_problem` says an integer no double holds (``float()`` of it raises
OverflowError, where a number written ``1e400`` is ``inf``); :data:`INT64` is what an integer
parameter of ROS 2 (and a numpy count) holds.
"""

from __future__ import annotations

import math
import re
import sys
from collections.abc import Iterable

# The largest magnitude a computation may square, a number from the command line or a file the
# user gives (an ik target's coordinate, a joint velocity or acceleration of dynamics): the
# square root of the largest float is 1.3e154, and past it numpy warns of an overflow and the
# answer is inf (a target "inf m" away, a torque of "inf N m").
SQUARABLE = 1e150

# The farthest coordinate urdftool places or measures geometry at ([m], or a mesh's own unit):
# a mesh's vertices merge at 1e-8 as 64-bit integers (mesh_arrays.KEY_RANGE, this number), and
# a joint or a part placed farther (an <origin xyz="1e200 0 0">) left every pose below it
# rounded to nothing (a reach of 0 m), squared to inf (ik, collisions' distances) or NaN
# (dynamics, render), and FCL's matrix failed with a message of its own
MAX_COORDINATE = 2.0 ** 62 / 1e8


# Python's int() converts a decimal of at most this many digits (sys.int_info's default; the
# conversion is quadratic, so Python refuses longer ones with a ValueError)
MAX_INT_DIGITS = 4300
INT64 = (-2 ** 63, 2 ** 63 - 1)  # what a ROS 2 integer parameter (int64_t), and numpy's sizes, hold
INT32 = (-2 ** 31, 2 ** 31 - 1)  # what a ROS 1 integer parameter holds (XML-RPC's <i4>)
_DIGITS = re.compile(r"[0-9](?:_?[0-9])*")


class NumberRefused(ValueError):
    """A number read from a file that no reader of it holds; the message says why."""


class TooLong(NumberRefused):
    """A decimal integer longer than Python converts (:data:`MAX_INT_DIGITS`)."""


def too_long(characters: int) -> TooLong:
    return TooLong(f"an integer of {characters:,} characters, longer than any number a "
                   f"configuration holds (Python converts {MAX_INT_DIGITS:,} digits)")


def long_integers(text: str):
    """The runs of decimal digits in ``text`` longer than Python converts (matches: their
    ``start()`` locates them): where a reader that converts its own numbers (tomllib) raised
    its ValueError."""
    for found in _DIGITS.finditer(text):
        if len(found.group()) > MAX_INT_DIGITS and \
                len(found.group().replace("_", "")) > MAX_INT_DIGITS:
            yield found


def long_integer(text: str):
    """The first of :func:`long_integers`, or None."""
    return next(long_integers(text), None)


def is_decimal(text: str) -> bool:
    """Whether ``text`` is ASCII digits 0-9 alone (one at least): a number as C's strtol and a
    file format read it. ``str.isdigit()`` also takes ``'²'`` (which ``int()`` refuses with a
    ValueError) and ``'٣'`` (which ``int()`` reads and C does not)."""
    return text.isascii() and text.isdigit()


def integer(text: str, base: int = 10) -> int:
    """``int(text, base)``: :class:`TooLong` for a decimal longer than Python converts (in a
    base that is a power of two Python converts any length in linear time), ValueError for
    text that is no integer."""
    if base not in (2, 4, 8, 16, 32) and len(text) > MAX_INT_DIGITS and \
            sum(character.isdigit() for character in text) > MAX_INT_DIGITS:
        raise too_long(len(text))
    return int(text, base)


def double_problem(value: int) -> NumberRefused | None:
    """Why the integer ``value`` is no number a double holds (past 1.8e308: ``float()`` raises
    OverflowError), or None."""
    try:
        float(value)
    except OverflowError:
        bits = abs(value).bit_length()  # (str() of one past 4,300 digits raises: a
        # hexadecimal integer has no limit)
        digits = f"{len(str(abs(value))):,}" if bits < 14_000 else \
            f"some {math.floor((bits - 1) * math.log10(2)) + 1:,}"
        return NumberRefused(f"an integer of {digits} digits, past the largest double "
                             f"({sys.float_info.max:.2g}): no number a configuration holds is "
                             "that large (a ROS integer parameter is an int64 at most)")
    return None


def in_int64(value: int) -> bool:
    """Whether the integer ``value`` is one an int64 holds (:data:`INT64`)."""
    return INT64[0] <= value <= INT64[1]


def in_int32(value: int) -> bool:
    """Whether the integer ``value`` is one an int32 holds (:data:`INT32`)."""
    return INT32[0] <= value <= INT32[1]


def power(base, exponent):
    """``base ** exponent`` as IEEE arithmetic: an infinity of the right sign where the result
    is too large for a float (Python raises OverflowError there), else exactly ``**``'s bits.
    Works as ``**`` on numpy values and arrays (which never raise)."""
    try:
        return base ** exponent
    except OverflowError:
        odd = float(exponent).is_integer() and int(exponent) % 2 == 1
        return -math.inf if odd and base < 0 else math.inf


def length(values) -> float:
    """The Euclidean length of ``values`` (any count), scaled: ``inf`` only when it exceeds the
    largest float, 0 only for a zero vector; NaN when a part is."""
    values = [float(v) for v in values]
    largest = max((abs(v) for v in values), default=0.0)
    if largest == 0 or not math.isfinite(largest):
        return largest if not any(math.isnan(v) for v in values) else math.nan
    return largest * math.sqrt(math.fsum((v / largest) ** 2 for v in values))


def unit(values) -> tuple | None:
    """``values`` divided by its length (scaled first, so that no square overflows or
    underflows); None for a zero vector, or one with a part not finite."""
    values = [float(v) for v in values]
    largest = max((abs(v) for v in values), default=0.0)
    if largest == 0 or not all(math.isfinite(v) for v in values):
        return None
    scaled = [v / largest for v in values]
    norm = math.sqrt(math.fsum(v * v for v in scaled))
    return tuple(v / norm for v in scaled)


def number(value: float, digits: int = 4, *, places: int | None = None,
           scale: float | None = None, plus: bool = False, grouped: bool = False) -> str:
    """``value`` as text, rounded to what is printed, never ``-0``.

    digits: significant digits (as the ``g`` format) when ``places`` is None
    places: decimals after the point (as the ``f`` format)
    scale: with ``digits``, the magnitude the digits are counted from (default: the value
        itself); e.g. ``number(2e-14, 4, scale=0.19)`` is ``0``
    plus: write ``+`` before a positive value (a change), never before zero
    grouped: with ``places``, thousands separated by commas (``22,590``)

    A value of 1e15 or more is written with ``digits`` significant digits even with ``places``:
    a float holds no more, and a density of 1e100 would otherwise print a hundred digits.
    """
    value = float(value)
    if not math.isfinite(value):
        return ("+" if plus and value > 0 else "") + repr(value)
    if places is not None and abs(value) >= 1e15:  # past float's integers: its digits are noise
        places = None
    if places is not None:
        value = round(value, places)
        text = f"{value:,.{places}f}" if grouped else f"{value:.{places}f}"
    else:
        reference = abs(scale) if scale is not None and math.isfinite(scale) else abs(value)
        if reference > 0:
            quantum = 10.0 ** (math.floor(math.log10(reference)) - digits + 1)
            if abs(value) < quantum / 2:
                value = 0.0
        text = f"{value:.{digits}g}"
    if text.startswith("-") and not text.strip("-0.,e+"):
        text = text[1:]  # -0, -0.000: zero after rounding
    if plus and not text.startswith("-") and text.strip("0.e+"):
        text = "+" + text
    return text


def fixed_texts(values: Iterable[float], places: int = 6) -> list[str]:
    """``number(v, places=places)`` of each of ``values`` (floats), the same texts at a tenth of
    the cost, for tables of hundreds of thousands of numbers (``fk --q-file``): Python's
    ``round(v, places)`` and the ``f`` format both round the float's exact value to the nearest
    decimal (ties to even), so formatting alone gives the same digits; what rounds to zero
    loses its sign, as in :func:`number`; a value that is not finite, or of 1e15 or more, is
    written as there."""
    form = f"%.{places}f"
    negative_zero, zero = form % -0.0, form % 0.0
    texts = [form % value if -1e15 < value < 1e15 else number(value, places=places)
             for value in values]  # (past 1e15, and not finite: as number writes them)
    return [zero if text == negative_zero else text for text in texts]


def exact(value: float) -> str:
    """A float as a machine format writes it (CSV cells; JSON through
    :func:`urdftool.report.json_output.dumps`, which writes the same): every digit (``repr``,
    read back to the same float), and no sign on a zero (``-0.0`` is written ``0.0``: a pitch
    of ``-0.0`` from ``atan2`` is no rotation, and a script comparing texts or signs, or a
    spreadsheet showing ``-0``, read it as one)."""
    return repr(float(value) + 0.0)


MILLIMETRE = 1e-3  # [m] the smallest scale of a position: a centre of mass of round-off only


ROUND_OFF = 1e-9  # of a matrix's largest entry: the scale below which an entry is round-off


def symmetric_texts(matrix, digits: int = 4) -> list[list[str]]:
    """A symmetric positive (semi)definite matrix's entries (an inertia tensor, a joint-space
    mass matrix) with :func:`number`, entry ``(i, j)`` counted from ``sqrt(|a_ii a_jj|)``, the
    size that bounds it, and at least :data:`ROUND_OFF` of the largest entry: a thin rod's
    2e-6 beside its 0.08, or a wrist's 1e-4 beside a shoulder's 3, is printed, not rounded to
    0 as it would be counted from the largest; the round-off beside them still is."""
    rows = [[float(v) for v in row] for row in matrix]
    finite = [abs(v) for row in rows for v in row if math.isfinite(v)]
    floor = max(finite, default=0.0) * ROUND_OFF
    diagonal = [abs(rows[i][i]) for i in range(len(rows))]
    texts = []
    for i, row in enumerate(rows):
        line = []
        for j, value in enumerate(row):
            own = math.sqrt(diagonal[i] * diagonal[j])
            scale = max(own, floor) if math.isfinite(own) else floor
            line.append(number(value, digits, scale=scale or None))
        texts.append(line)
    return texts


def computed(value: float, digits: int = 4) -> str:
    """A value urdftool computed from finite ones, with :func:`number`; one past the float range
    (1e308 x 2 is ``inf``) is said as such, not as an ``inf`` the file never wrote."""
    if math.isinf(value):
        return (f"past -{sys.float_info.max:.2g}, the lowest float" if value < 0 else
                f"past {sys.float_info.max:.2g}, the largest float")
    return number(value, digits)


def numbers(values: Iterable[float], digits: int = 4, separator: str = " ",
            floor: float = 0.0) -> str:
    """A vector or tensor's components with :func:`number`, all counted from the largest one
    (``0.3 1e-17`` -> ``0.3 0``), or from ``floor`` when that is larger: a position whose
    components are all round-off (``1e-17 -2e-17 0`` with ``floor=MILLIMETRE``) is ``0 0 0``."""
    values = [float(v) for v in values]
    finite = [abs(v) for v in values if math.isfinite(v)]
    scale = max([*finite, floor]) or None
    return separator.join(number(v, digits, scale=scale) for v in values)


def decimal_slip(a: float, b: float) -> str:
    """What a message comparing two values of one quantity adds when they are the same digits
    a power of ten apart (ROBOTIS-OP's MP_TIBIA_L 0.0070309794 kg and MP_TIBIA_R 0.070309794,
    a wheel radius 0.0325 against the URDF's 0.325): a decimal point slipped, not a design;
    empty otherwise, and for a value of one significant digit (an effort of 300 against 30
    may be a zero too many, or two numbers chosen apart)."""
    ratio = b / a if a > 0 and b > 0 and math.isfinite(a) and math.isfinite(b) else 0.0
    if not 0.0 < ratio < math.inf:
        return ""
    power = round(math.log10(ratio))
    if power == 0 or abs(ratio / 10.0 ** power - 1) > 1e-6 or _significant(min(a, b)) < 2:
        return ""
    return f": the same digits {10 ** abs(power):g} times apart, a decimal point slipped"


def _significant(value: float) -> int:
    """How many significant digits ``value`` is written with at its shortest (0.0703 -> 3)."""
    mantissa = f"{value:.15g}".split("e")[0].replace("-", "").replace(".", "")
    return len(mantissa.strip("0"))
