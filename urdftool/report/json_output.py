"""JSON as urdftool writes it: the finding formats (json, sarif, gitlab, rdjson) and the
documents that analysis commands (collisions, dh, dynamics, fk, inertia) print."""

from __future__ import annotations

import json
import math
import re
import sys

WIDTH = 100  # a value whose JSON fits on a line this wide is written on one line
RECORD = 4000  # an object in a list (a finding, a link's pose) up to this long is one line too


def dumps(data) -> str:
    """``data`` as indented JSON: a list or object that fits in :data:`WIDTH` columns stays on
    one line, and so does an object in a list up to :data:`RECORD` characters (a record a line);
    a longer one has an item a line. Each line is encoded by json's C encoder
    (``json.dumps(indent=...)`` runs the slower pure-Python one). Always JSON (RFC 8259): a
    float that is infinite or NaN (a declared mass of ``inf``, a pose past what a float holds)
    is written null, which every reader takes (``NaN``/``Infinity`` are no JSON: `inertia -f
    json` of such a robot was refused by every strict reader). No zero is signed: ``-0.0`` is
    written ``0.0`` (:func:`urdftool.numbers.exact`)."""
    try:
        text = _dumps(data, _ENCODE)
    except ValueError:  # (rare: looked for by the encoder, and only then the data cleaned)
        data = _finite(data)
        text = _dumps(data, _ENCODE)
    if _signed_zero(text):  # as numbers.exact writes a float: looked for, then cleaned
        data = _unsigned(data)
        text = _dumps(data, _ENCODE)
    # json writes a surrogate code point (a file name's undecodable byte, a YAML "\\ud800") as
    # an escape no strict reader takes (I-JSON, RFC 7493; SARIF uploads, serde, Go): rare, so
    # looked for in the text, and only then the data cleaned and written again
    return _dumps(_whole(data), _ENCODE) if "\\ud" in text else text


def line(data) -> str:
    """``data`` as one line of compact JSON (json-lines): ASCII, exact, no lone surrogate and
    no NaN (as :func:`dumps`)."""
    try:
        text = _ENCODE(data)
    except ValueError:
        data = _finite(data)
        text = _ENCODE(data)
    if _signed_zero(text):
        data = _unsigned(data)
        text = _ENCODE(data)
    return _ENCODE(_whole(data)) if "\\ud" in text else text


_ENCODE = json.JSONEncoder(allow_nan=False).encode


# a \u escape of a surrogate, the backslashes before it (even: an escaped backslash's text)
# and a low surrogate's escape after a high one (a pair: a character past U+FFFF)
_SURROGATE_ESCAPE = re.compile(rb"(\\+)u(d[89ab][0-9a-f]{2}(?:\\ud[c-f][0-9a-f]{2})?|"
                               rb"d[c-f][0-9a-f]{2})", re.IGNORECASE)


def paired(data: bytes) -> bytes:
    """JSON another library wrote (pygls: the language server's messages, with their headers)
    with each escape of a lone surrogate written ``\\ufffd``, as :func:`dumps` writes the
    character a strict reader would read: the same length, so a ``Content-Length`` before it
    stays true; a pair (a character past U+FFFF) and an escaped backslash's text are left."""
    if b"\\u" not in data:
        return data

    def one(match) -> bytes:
        slashes, code = match.group(1), match.group(2)
        if len(slashes) % 2 == 0 or len(code) > 4:
            return match.group(0)
        return slashes + b"ufffd"

    return _SURROGATE_ESCAPE.sub(one, data)


_SURROGATE = re.compile("[\ud800-\udfff]")


def _whole(value):
    """``value`` with every surrogate code point of its strings (keys too) replaced by U+FFFD,
    as a strict reader of the JSON would read it."""
    if isinstance(value, str):
        return _SURROGATE.sub("\ufffd", value)
    if isinstance(value, dict):
        return {_whole(key): _whole(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_whole(item) for item in value]
    return value


def _dumps(data, encode) -> str:
    parts: list[str] = []

    def write(value, indent: str, in_list: bool = False) -> None:
        record = in_list and isinstance(value, dict)
        fits = RECORD if record else WIDTH - len(indent)
        container = isinstance(value, (dict, list, tuple)) and value
        # a container surely too long is not encoded whole (a record nearly always fits)
        if not container or record or _least_length(value, fits) <= fits:
            text = encode(value)
            if len(text) <= fits or not container:
                parts.append(text)
                return
        inner = indent + "  "
        if isinstance(value, dict):
            parts.append("{")
            for number, (key, member) in enumerate(value.items()):
                # the key as json writes it (a number or a boolean key becomes a string)
                name = encode(key) if isinstance(key, str) else encode({key: 0})[1:-4]
                parts.append(f"{',' if number else ''}\n{inner}{name}: ")
                write(member, inner)
            parts.append(f"\n{indent}}}")
        else:
            parts.append("[")
            for number, member in enumerate(value):
                parts.append(f"{',' if number else ''}\n{inner}")
                write(member, inner, in_list=True)
            parts.append(f"\n{indent}]")

    write(data, "")
    return "".join(parts)


def _least_length(value, cap: int) -> int:
    """A lower bound of the length of ``value``'s JSON, counted only until it passes ``cap``."""
    if isinstance(value, str):
        return len(value) + 2
    if isinstance(value, dict):
        total = 1
        for key, member in value.items():
            total += 5 + (len(key) if isinstance(key, str) else 0) + _least_length(member,
                                                                                  cap - total)
            if total > cap:
                break
        return total
    if isinstance(value, (list, tuple)):
        total = 0  # [] and the separators: 2 + 2 (n - 1)
        for member in value:
            total += 2 + _least_length(member, cap - total)
            if total > cap:
                break
        return total
    return 1


def write_json(data, stream=None) -> None:
    """``data`` as :func:`dumps` writes it and a newline on ``stream`` (default: standard output),
    in one write (``json.dump`` writes token by token)."""
    (stream or sys.stdout).write(dumps(data) + "\n")


# a number token -0.0 (json writes a float as repr does); in a string too, which only costs the
# cleaning, never changes the string
_NEGATIVE_ZERO = re.compile(r"(?<![\w.])-0\.0(?![\w.])")


def _signed_zero(text: str) -> bool:
    """Whether ``text`` holds a number token -0.0 (:data:`_NEGATIVE_ZERO`), as its search says:
    each "-0.0" found at memchr's pace, then the pattern matched there (it looks behind into
    the text before). Its search tried it at every character (the lookbehind leaves sre no
    literal to skip to): 0.6 s over the 3 MB of a 10,000-link robot's findings, where a
    "-0.05" in a message is found too."""
    at = text.find("-0.0")
    while at >= 0:
        if _NEGATIVE_ZERO.match(text, at):
            return True
        at = text.find("-0.0", at + 1)
    return False


def _unsigned(value):
    """``value`` with every float zero unsigned (``-0.0`` -> ``0.0``, :func:`urdftool.numbers.exact`)."""
    if isinstance(value, float):
        return value + 0.0
    if isinstance(value, dict):
        return {key: _unsigned(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_unsigned(item) for item in value]
    return value


def _finite(value):
    if isinstance(value, dict):
        return {key: _finite(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(item) for item in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value
