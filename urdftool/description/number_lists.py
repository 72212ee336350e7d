"""Long lists of numbers read in bulk with numpy: COLLADA's ``<p>`` and ``<vcount>`` texts, to
the bit what ``np.fromstring(text, dtype="int64", sep=" ")`` reads of them, and only the
numbers asked for.

``np.fromstring`` reads a number at a time in C, about 230 instructions each. A ``<p>``
interleaves one index per input of its primitive (VERTEX, NORMAL, TEXCOORD, ...) and only
the VERTEX column is ever used: here a text is read as bytes in a few whole-array passes (its
runs of digits found at once, about 40 instructions a number: what remains is numpy's
``nonzero``), and only the runs asked for are turned into numbers, each from the eight bytes
where it starts (its digits xor "0" as bytes of a 64-bit word, shifted to its top, added in
pairs, fours and eights by three multiplications).

Only a plain text is read so: ASCII digits between C white space (what ``sep=" "`` skips:
space, tab, line feed, vertical tab, form feed, carriage return), each number of at most
sixteen digits. :func:`whole_numbers` returns None for anything else (a sign, a point, a
letter, a digit that is not ASCII, seventeen digits), and its caller reads that text with
``np.fromstring`` as before, so what is malformed is refused with the same words and what
numpy reads some other way is read by numpy.
"""

from __future__ import annotations

import numpy as np

# [characters] a shorter text is left to np.fromstring: the two dozen numpy calls made here
# cost about 150,000 instructions whatever the length, what fromstring spends on 650 numbers
BULK = 4096

_U64 = np.uint64
_ZEROS = _U64(0x3030303030303030)  # b"00000000"


def _eights(words, starts, lengths):
    """The int64 values of the runs of 0..8 digits at ``starts`` (indices into ``words``,
    the 64-bit little-endian word at each byte) of ``lengths`` digits each."""
    value = words[starts]
    value ^= _ZEROS  # digits 0..9, the first the lowest byte
    shifts = 8 - lengths
    shifts <<= 3
    value <<= shifts.view(_U64)  # the run's digits to the top bytes, what follows it out
    value *= _U64(10 * 256 + 1)  # pairs
    value >>= _U64(8)
    value &= _U64(0x00FF00FF00FF00FF)
    value *= _U64(100 * 65536 + 1)  # fours
    value >>= _U64(16)
    value &= _U64(0x0000FFFF0000FFFF)
    value *= _U64(10000 * 2 ** 32 + 1)  # eights
    value >>= _U64(32)
    return value.view(np.int64)


def whole_numbers(text: str, stride: int = 1, offset: int = 0):
    """(how many numbers ``text`` holds, the int64 array of its numbers ``offset``,
    ``offset + stride``, ...) when it holds only unsigned whole numbers of at most sixteen
    ASCII digits between C white space; None otherwise (the module docstring)."""
    if not text.isascii():
        return None
    data = f" {text}        ".encode("ascii")  # a space first, and 8 bytes after each number
    buffer = np.frombuffer(data, dtype=np.uint8)
    words = np.ndarray((len(data) - 8,), dtype="<u8", buffer=data, offset=1, strides=(1,))
    digit = (buffer ^ np.uint8(48)) < 10
    # where digit changes: a run of digits starts after the first of each pair, ends after
    # the second (the text begins and ends with a space, so they alternate)
    changes = np.flatnonzero(digit[1:] != digit[:-1])
    count = len(changes) // 2
    if np.count_nonzero(digit) + np.count_nonzero(buffer == 32) != len(buffer):
        white = (buffer == 32) | ((buffer - np.uint8(9)) < 5)
        if not (digit | white).all():
            return None
    starts = changes[2 * offset::2 * stride]
    lengths = changes[2 * offset + 1::2 * stride] - starts
    if len(lengths) == 0:
        return count, np.zeros(0, dtype=np.int64)
    longest = lengths.max()
    if longest <= 8:
        return count, _eights(words, starts, lengths)
    if longest > 16:
        return None
    high = np.maximum(lengths - 8, 0)  # the digits before the last eight
    values = _eights(words, starts, high)
    values *= 100_000_000
    values += _eights(words, starts + high, lengths - high)
    return count, values
