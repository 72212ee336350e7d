"""JSON as urdftool writes it: the finding formats (json, sarif, gitlab, rdjson) and the
documents that analysis commands (collisions, dh, dynamics, fk, inertia) print."""

from __future__ import annotations

import itertools
import json
import math
import re
import sys

from urdftool.numbers import number

WIDTH = 100  # a value whose JSON fits on a line this wide is written on one line
RECORD = 4000  # an object in a list (a finding, a link's pose) up to this long is one line too


def dumps(data, indent: str = "", in_list: bool = False, *, spelt: bool = False) -> str:
    """``data`` as indented JSON: a list or object that fits in :data:`WIDTH` columns stays on
    one line, and so does an object in a list up to :data:`RECORD` characters (a record a line);
    a longer one has an item a line. Each line is encoded by json's C encoder
    (``json.dumps(indent=...)`` runs the slower pure-Python one). Always JSON (RFC 8259): a
    float that is infinite or NaN (a declared mass of ``inf``, a pose past what a float holds)
    is written null, which every reader takes (``NaN``/``Infinity`` are no JSON: `inertia -f
    json` of such a robot was refused by every strict reader); with ``spelt``, the string the
    text reports write (``"inf"``, ``"-inf"``, ``"nan"``: :func:`urdftool.numbers.number`), for
    a document where null says a value is none (a file's ``~``: ``diff``). No zero is signed: ``-0.0`` is
    written ``0.0`` (:func:`urdftool.numbers.exact`). ``indent``, ``in_list``: the text of
    ``data`` as a member of a list so indented (:func:`write_json_list`); each cleaning is of
    one value, so a list's members cleaned one by one are the list cleaned whole."""
    try:
        text = _dumps(data, _ENCODE, indent, in_list)
    except ValueError:  # (rare: looked for by the encoder, and only then the data cleaned)
        data = _finite(data, spelt)
        text = _dumps(data, _ENCODE, indent, in_list)
    if _signed_zero(text):  # as numbers.exact writes a float: looked for, then cleaned
        data = _unsigned(data)
        text = _dumps(data, _ENCODE, indent, in_list)
    # json writes a surrogate code point (a file name's undecodable byte, a YAML "\\ud800") as
    # an escape no strict reader takes (I-JSON, RFC 7493; SARIF uploads, serde, Go): rare, so
    # looked for in the text, and only then the data written again as :func:`named` spells it
    return _dumps(_whole(data), _ENCODE, indent, in_list) \
        if _NOT_TEXT_ESCAPE in text or "\\ufffd" in text else text


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
    return _ENCODE(_whole(data)) if _NOT_TEXT_ESCAPE in text or "\\ufffd" in text else text


_ENCODE = json.JSONEncoder(allow_nan=False).encode
_NOT_TEXT_ESCAPE = "\\ud"  # how json writes a surrogate code point (an escape, ASCII output)

# JSON's one spelling of what is not text. A file name is bytes; Python reads one that is not
# UTF-8 with each undecodable byte a lone surrogate (os.fsdecode: 0xff is U+DCFF), which JSON
# cannot carry to a strict reader (I-JSON). Every JSON document urdftool writes (json,
# json-lines, gitlab, rdjson, the analysis commands' documents, the language server's
# messages) spells each such byte U+FFFD followed by its two hexadecimal digits (``bad\xff``
# is "bad\ufffdFF"), and a U+FFFD of the text itself as its own three bytes so spelt
# ("\ufffdEF\ufffdBF\ufffdBD"): a strict reader sees a replacement character where the
# bytes were, as it always would, and the spelling is one to one (:func:`name_bytes` gives the
# bytes back), so two names never print as one (two files' GitLab fingerprints were one). A
# lone surrogate that is no byte (a YAML "\\ud800") is spelt as its UTF-8 bytes the same way.
# SARIF's artifact locations are URIs and say the same bytes percent-encoded (``%FF``).
_NOT_TEXT = re.compile("[\ud800-\udfff\ufffd]")


def _spelt(match) -> str:
    char = match.group()
    data = char.encode("utf-8", "surrogateescape" if "\udc80" <= char <= "\udcff" else
                       "surrogatepass")
    return "".join(f"\ufffd{byte:02X}" for byte in data)


def named(value: str) -> str:
    """``value`` (a name as Python decodes it) as every JSON document urdftool writes spells it:
    each undecodable byte (a lone surrogate) and each U+FFFD as U+FFFD and the byte's two
    hexadecimal digits; any other text as it is."""
    return _NOT_TEXT.sub(_spelt, value)


_SPELT_BYTE = re.compile("\ufffd([0-9A-F]{2})")


def name_bytes(value: str) -> bytes:
    """The bytes of a name :func:`named` spelt (``os.fsdecode`` of them is the name urdftool
    read): its inverse, for a reader of urdftool's JSON that needs the file."""
    parts = _SPELT_BYTE.split(value)
    return b"".join(bytes([int(part, 16)]) if index % 2 else part.encode("utf-8")
                    for index, part in enumerate(parts))


# a \u escape of a surrogate or of U+FFFD, the backslashes before it (even: an escaped
# backslash's text) and a low surrogate's escape after a high one (a pair: a character past
# U+FFFF); a run of backslashes from its first only (from each: quadratic in the run)
_SURROGATE_ESCAPE = re.compile(rb"(?<!\\)(\\++)u(d[89ab][0-9a-f]{2}(?:\\ud[c-f][0-9a-f]{2})?|"
                               rb"d[c-f][0-9a-f]{2}|fffd)", re.IGNORECASE)
_CONTENT_LENGTH = re.compile(rb"Content-Length: ([0-9]+)\r\n")


def paired(data: bytes) -> bytes:
    """A message another library wrote (pygls: the language server's, its headers and its JSON
    body) with each escape of a lone surrogate, and of U+FFFD, spelt as :func:`named` spells
    it, and its ``Content-Length`` made the body's new length; a pair (a character past
    U+FFFF) and an escaped backslash's text are left."""
    if b"\\u" not in data:
        return data

    def one(match) -> bytes:
        slashes, code = match.group(1), match.group(2)
        if len(slashes) % 2 == 0 or len(code) > 4:
            return match.group(0)
        spelt = named(chr(int(code, 16)))
        return slashes[:-1] + json.dumps(spelt).encode()[1:-1]

    head, blank, body = data.partition(b"\r\n\r\n")
    if not blank:
        return _SURROGATE_ESCAPE.sub(one, data)
    new = _SURROGATE_ESCAPE.sub(one, body)
    if new == body:
        return data
    return _CONTENT_LENGTH.sub(b"Content-Length: %d\r\n" % len(new), head + b"\r\n", 1) + \
        b"\r\n" + new


def _whole(value):
    """``value`` with every string (keys too) spelt as :func:`named` spells it."""
    if isinstance(value, str):
        return named(value)
    if isinstance(value, dict):
        return {_whole(key): _whole(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_whole(item) for item in value]
    return value


def _dumps(data, encode, indent: str = "", in_list: bool = False) -> str:
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

    write(data, indent, in_list)
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


def write_json(data, stream=None, *, spelt: bool = False) -> None:
    """``data`` as :func:`dumps` writes it (``spelt`` as there) and a newline on ``stream``
    (default: standard output), in one write (``json.dump`` writes token by token)."""
    (stream or sys.stdout).write(dumps(data, spelt=spelt) + "\n")


def write_json_list(items, stream=None) -> None:
    """The list of ``items`` (an iterable) as :func:`write_json` writes it, each member written
    as it comes: a list of thousands of large documents (``fk --q-file -f json``) is never held,
    nor its text. A list short enough for one line is written whole, as there: the members
    are held until their least length (:func:`_least_length`, counted as :func:`_dumps` counts
    it) is past :data:`WIDTH`."""
    stream = stream or sys.stdout
    held, total = [], 0
    items = iter(items)
    for item in items:
        held.append(item)
        total += 2 + _least_length(item, WIDTH - total)
        if total > WIDTH:
            break
    else:
        write_json(held, stream)
        return
    stream.write("[")
    for number, item in enumerate(itertools.chain(held, items)):
        stream.write(f"{',' if number else ''}\n  " + dumps(item, "  ", in_list=True))
    stream.write("\n]\n")


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


def _finite(value, spelt: bool = False):
    """``value`` with each float that is infinite or NaN null, or ``spelt`` as text
    (:func:`dumps`)."""
    if isinstance(value, dict):
        return {key: _finite(item, spelt) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(item, spelt) for item in value]
    if isinstance(value, float) and not math.isfinite(value):
        return number(value) if spelt else None
    return value
