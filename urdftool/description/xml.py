"""Safe XML parsing that knows the line on which each element's ``<`` stands.

expat decides whether a document is well formed and where every start tag begins (lxml's
``sourceline`` is the line of the closing ``>``, wrong for tags written across lines). lxml then
builds the tree the rules read. Entity declarations are refused outright, so no entity is ever
expanded and nothing outside the file is fetched: this is what stops entity bombs and
``file:///etc/passwd`` entities.
"""

from __future__ import annotations

import bisect
import functools
import re
import sys
from collections.abc import Mapping
from dataclasses import dataclass
from xml.parsers import expat

from urdftool.diagnostics import AT_LINE_START_BYTES, LineNumbers, line_at, line_ends

BINARY_SNIFF_BYTES = 8192
MAX_DEPTH = 256  # element nesting libxml2 accepts without its "huge" option


@dataclass
class XmlProblem(Exception):
    """Why a document was refused: ``kind`` is 'empty', 'binary', 'syntax' or 'entity'."""

    kind: str
    message: str
    line: int | None = None
    column: int | None = None


class _Refused(Exception):
    pass


class _TooDeep(Exception):
    pass


_ESCAPES = {"&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&apos;"}


def attribute(value: str) -> str:
    """``value`` written by hand into an XML file (a fix's edit, a new SRDF) as an attribute
    value in either quotes, or as text: markup escaped, and as character references the
    characters a parser would change (line breaks and tabs become spaces in an attribute) or
    that act in a terminal or reorder text (other controls, format characters, separators), so
    that the file reads back the same value and injects nothing."""
    if value.isascii() and value.isprintable():
        return "".join(_ESCAPES.get(char, char) for char in value) if \
            any(char in _ESCAPES for char in value) else value
    import unicodedata

    return "".join(_ESCAPES.get(char) or (f"&#{ord(char)};" if unicodedata.category(char) in
                                         ("Cc", "Cf", "Zl", "Zp") else char)
                   for char in value)


# (the words of each refusal are for every XML urdftool reads: robot files, launch files)
def external_dtd_message(where: str) -> str:
    return (f"external DTD '{where}' refused: urdftool loads no DTD (a DTD can read local "
            "files or reach the network)")


def entity_message(name: str) -> str:
    return (f"entity declaration '{name}' refused: urdftool reads no XML that declares entities "
            "(they are how XML bombs and local file reads are built)")


def too_deep_message() -> str:
    return (f"elements nested deeper than {MAX_DEPTH} levels: refused (libxml2-based parsers "
            "refuse it too, and no robot description or launch file needs it)")


# git's conflict markers: seven of one character at the start of a line ("|||||||" is diff3's),
# a line as every Location numbers them (a file whose lines end with CR alone has its markers too)
_CONFLICT = re.compile(AT_LINE_START_BYTES + rb"(<{7}|\|{7}|={7}|>{7})(?=[ \t\r\n]|\Z)[^\r\n]*")


def malformed(data: bytes, reason: str, line: int | None,
              column: int | None = None) -> XmlProblem:
    """The XmlProblem of a document that is not well-formed: the parser's ``reason`` at
    ``line``, or the unresolved merge conflict it holds (:func:`merge_conflict`). An empty
    file says so (expat's "no element found" for OUXT-Polaris/wamv_description's 0-byte
    wamv.ros2_control.xacro, which its robots include)."""
    if not data.strip():
        reason = f"{reason} (the file is {'empty' if not data else 'only white space'})"
    elif reason == "mismatched tag":
        reason += _mismatch(data)
    elif reason == "no element found" and not _COMMENTS.sub(b"", data).strip():
        reason += " (the file holds only comments)"  # match_mobile_robotics_jazzy's, all one
    elif reason in _EXPLAINED and line is not None:
        reason += _EXPLAINED[reason](data, _offset(data, line, column))
    return merge_conflict(data) or XmlProblem("syntax", f"malformed XML: {reason}", line, column)


def _offset(data: bytes, line: int, column: int | None) -> int:
    """The offset in ``data`` of expat's place (``line`` from 1, as a Location numbers them;
    ``column`` from 1 in bytes of that line: the line's start when there is none)."""
    return min(LineNumbers(data).start(line) + max((column or 1) - 1, 0), len(data))


def _declaration_late(data: bytes, offset: int) -> str:
    """Why an XML declaration not at the file's start is refused: what comes before it (expat's
    "XML or text declaration not at start of entity": Shadow's MuJoCo URDFs' licence comment,
    a comment line above victor's gripper_only.xacro)."""
    first = len(data) - len(data.lstrip())  # (the file's first text)
    what = "a comment" if data.startswith(b"<!--", first) else \
        "another XML declaration (two files joined?)" if data.startswith(b"<?xml", first) \
        else "text"
    return (f": the file's <?xml ...?> declaration must be its first text, and {what} comes "
            f"before it, at line {line_at(data, first)}; move the declaration to the top of the "
            "file or remove it")


# a name with a prefix: an element's (after < or </) or an attribute's (after white space)
_PREFIXED = re.compile(rb"(?:</?|\s)([A-Za-z_][\w.-]*):([A-Za-z_][\w.-]*)")
_DECLARED = re.compile(rb"\bxmlns:([A-Za-z_][\w.-]*)\s*=")
_NAMESPACES = {"xacro": "http://www.ros.org/wiki/xacro"}  # prefix -> the URI to declare


def _unbound(data: bytes, offset: int) -> str:
    """Which prefix no ``xmlns:`` declares, in the tag at expat's place ("unbound prefix":
    talos's calibration.xacro and ros2_mobile_manipulator's mobile_base.xacro use <xacro:...>
    in a <robot> declaring no xacro namespace; reemc's openni.gazebo.xacro old Gazebo's
    <sensor:camera>), and how to declare it."""
    declared = set(_DECLARED.findall(data)) | {b"xml", b"xmlns"}
    end = data.find(b">", offset)
    for found in _PREFIXED.finditer(data, offset, len(data) if end < 0 else end + 1):
        prefix = found.group(1)
        if prefix not in declared:
            name = found.group(0).lstrip().decode("utf-8", "replace")
            said = f"<{name.lstrip('<')}>" if name.startswith("<") else f"attribute '{name}'"
            prefix = prefix.decode("utf-8", "replace")
            uri = _NAMESPACES.get(prefix, "URI")
            return (f": '{prefix}:' of {said} is declared nowhere in the file; declare it on "
                    f"the root element (<robot xmlns:{prefix}=\"{uri}\">)")
    return ""


_NAMESPACE = re.compile(rb"\sxmlns(?::([A-Za-z_][\w.-]*))?\s*=\s*(\"[^\"]*\"|'[^']*')")


def _syntax(data: bytes, offset: int) -> str:
    """What expat's bare "syntax error" met, where it can be told: a namespace URI holding
    white space, which expat refuses (amr-ros-config's pioneer3dx_body.xacro declares
    xmlns:controller across two lines)."""
    end = data.find(b">", offset)
    for found in _NAMESPACE.finditer(data, offset, len(data) if end < 0 else end + 1):
        if re.search(rb"\s", found.group(2)):
            prefix = (found.group(1) or b"").decode("utf-8", "replace")
            return (f": the URI of namespace {f'{prefix!r}' if prefix else 'xmlns'} holds white "
                    f"space (at line {line_at(data, found.start(2))}); write it without")
    return ""


def _invalid_token(data: bytes, offset: int) -> str:
    """What expat's "not well-formed (invalid token)" met at its place: a byte that is not
    UTF-8 (a file saved as Latin-1: URDF_exploring's 'R\\xe9volution'), '--' inside a comment
    (uuv_simulator's rule of dashes, a comment nested in one), a '<' where a tag is still open
    (a '>' missing: rb1_base's <joint ..., braccio's </inertial)."""
    byte = data[offset:offset + 1]
    if byte and byte[0] >= 0x80:
        return (f": byte 0x{byte[0]:02X} is not UTF-8 (the file is saved in another encoding, "
                "Latin-1 or Windows-1252?); save it as UTF-8, or name its encoding in the XML "
                "declaration (<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>)")
    opened = data.rfind(b"<!--", 0, max(offset - 2, 0))
    if opened >= 0 and data.find(b"-->", opened + 4, offset) < 0 and \
            b"--" in data[max(offset - 2, opened + 2):offset + 2]:
        return (f": '--' inside the comment opened at line {line_at(data, opened)}: XML allows "
                "no '--' within a comment (a comment nested in it has one); remove it")
    tag = data.rfind(b"<", 0, offset)
    if byte == b"<" and tag >= 0 and data.find(b">", tag, offset) < 0:
        name = re.match(rb"</?[^\s<>/]*", data[tag:offset]).group(0).decode("utf-8", "replace")
        kind = "end" if name.startswith("</") else "start"
        return (f": '<' inside the {kind} tag {name}... opened at line {line_at(data, tag)}, "
                "whose '>' is missing")
    return ""


def _junk(data: bytes, offset: int) -> str:
    """What comes after the root element (expat's "junk after document element": reflex's
    rhr_visualization.URDF, <link> after <link>, a robot written without its <robot>)."""
    root = re.search(rb"<([A-Za-z_][\w:.-]*)", _COMMENTS.sub(b"", data))
    after = re.match(rb"\s*<([A-Za-z_][\w:.-]*)", data[offset:])
    if root is None:
        return ""
    first = root.group(1).decode("utf-8", "replace")
    what = f"another element, <{after.group(1).decode('utf-8', 'replace')}>," if after else "text"
    return (f": {what} comes after the end of the root element <{first}>, and an XML file has "
            f"one root" + (" (a robot description's is <robot>)" if first != "robot" else ""))


# expat's reasons explained at the place they are met (:func:`malformed`)
_EXPLAINED = {"XML or text declaration not at start of entity": _declaration_late,
              "unbound prefix": _unbound, "not well-formed (invalid token)": _invalid_token,
              "junk after document element": _junk, "syntax error": _syntax}


_COMMENTS = re.compile(rb"<!--.*?(?:-->|\Z)|<\?.*?(?:\?>|\Z)", re.S)


def _mismatch(data: bytes) -> str:
    """Which element a mismatched closing tag meets still open, and where it was opened
    (delta_robot_simulation's codian.urdf: ``</robot>`` at its end, with a ``<gazebo>``
    opened 184 lines above and never closed), read again on the failure path only; "" when
    that cannot be told."""
    open_elements: list[tuple[str, int]] = []
    parser = expat.ParserCreate()

    def refuse(*args):  # no entity is expanded here either (an XML bomb before the mismatch)
        raise _Refused(args[0])

    _refusing(parser, None, refuse)
    parser.StartElementHandler = lambda name, attributes: open_elements.append(
        (name, parser.CurrentLineNumber))
    parser.EndElementHandler = lambda name: open_elements.pop()
    try:
        parser.Parse(data, True)
    except Exception:  # noqa: BLE001 - the error being explained, or one before it
        pass
    if not open_elements or expat.ErrorString(parser.ErrorCode) != "mismatched tag":
        return ""
    name, opened = open_elements[-1]
    row = data.split(b"\n")[parser.ErrorLineNumber - 1]  # expat points at the end tag's name
    closing = re.match(rb"</([^\s>/]+)", row[max(parser.ErrorColumnNumber - 2, 0):])
    closes = f"</{closing.group(1).decode('utf-8', 'replace')}>" if closing else "another end tag"
    return f": {closes} comes while <{name}>, opened at line {opened}, is still open"


def merge_conflict(data: bytes) -> XmlProblem | None:
    """A document holding an unresolved merge conflict (a ``<<<<<<<`` line, which is never
    XML), said as such at its first marker's line with the other markers' lines; else None."""
    lines = LineNumbers(data)
    markers = [(lines(found.start()), found.group(0)) for found in _CONFLICT.finditer(data)]
    opening = next((marker for marker in markers if marker[1].startswith(b"<")), None)
    if opening is None:
        return None
    shown = opening[1].decode("utf-8", "replace").strip()
    others = [str(number) for number, _ in markers if number != opening[0]]
    more = f"; the other markers at line{'s' if len(others) > 1 else ''} " \
           f"{', '.join(others[:10])}{', ...' if len(others) > 10 else ''}" if others else ""
    return XmlProblem("syntax", (
        f"unresolved merge conflict: git's conflict marker '{shown[:60]}' at this line{more}; "
        "keep one side of each conflict and remove the markers"), opening[0], 1)


# a comment as TinyXML2 reads it: from "<!--" to the first "-->", whatever comes between
_TINYXML2_COMMENT = re.compile(rb"<!--(.*?)(-->|\Z)", re.DOTALL)


def tinyxml2_comments(data: bytes) -> tuple[bytes, int] | None:
    """(``data`` with each comment that holds ``--``, or ends in ``-``, blanked, the line of
    the first such ``--``) when there is one; else None.

    The XML standard forbids ``--`` inside a comment (``<!-- ---- -->``, ``<!-- a --!>``), and
    parsers that follow it refuse the document (expat: xacro, urdf_parser_py; libxml2: lxml,
    yourdfpy). TinyXML2, which urdfdom (check_urdf, robot_state_publisher) and srdfdom (MoveIt)
    read with, ends a comment at the first ``-->`` and keeps whatever came before it as its
    text: the returned document is the one it reads (only hyphens become spaces, so lines and
    columns stay)."""
    first = None

    def blanked(found):
        nonlocal first
        body = found.group(1)
        if not found.group(2) or b"--" not in body and not body.endswith(b"-"):
            return found.group(0)
        if first is None:
            at = body.find(b"--")
            first = found.start(1) + (at if at >= 0 else len(body) - 1)
        return b"<!--" + body.replace(b"-", b" ") + b"-->"

    rewritten = _TINYXML2_COMMENT.sub(blanked, data)
    return None if first is None else (rewritten, line_at(data, first))


def entity_uses(data: bytes) -> list[tuple[bytes, int]]:
    """Each reference to a general entity the document declares, after its DOCTYPE, as
    (``b"&name;"``, its offset): what libxml2 (lxml, pycollada) and expat expand and TinyXML2
    (urdfdom, srdfdom, Gazebo's COLLADA loader) and pugixml (Assimp: RViz) keep as those
    characters. [] for nearly every document (one byte search)."""
    if b"<!ENTITY" not in data:
        return []
    declared = set(_DECLARED.findall(data))
    body = max(0, data.find(b"]>", data.rfind(b"<!ENTITY")))  # (what follows the DOCTYPE)
    return [(found.group(0), found.start()) for found in _REFERENCE.finditer(data, body)
            if found.group(1) in declared]


_DECLARED = re.compile(rb"<!ENTITY\s+([^\s%]\S*)")  # (a general entity; '%' a parameter one)
_REFERENCE = re.compile(rb"&([^\s;&<#]+);")


def refuse_empty_or_binary(data: bytes) -> None:
    """Raise XmlProblem for input that is empty or not text at all."""
    if not data.strip():
        raise XmlProblem("empty", "file is empty: expected a <robot> element", 1)
    if b"\x00" in data[:BINARY_SNIFF_BYTES]:
        raise XmlProblem("binary", "file is binary (contains NUL bytes), not XML text", 1)


def start_tag_lines(data: bytes) -> list[int]:
    """Line of each element's ``<`` in document order; raises XmlProblem when not well formed."""
    return [line for line, _ in start_tag_positions(data)]


def start_tag_positions(data: bytes) -> list[tuple[int, int]]:
    """(line, 1-based column) of each element's ``<`` in document order; raises XmlProblem
    when not well formed."""
    refuse_empty_or_binary(data)
    parser = expat.ParserCreate()
    lines: list[tuple[int, int]] = []
    refused: list[str] = []
    depth = [0]

    def on_start(name, attributes):
        lines.append((parser.CurrentLineNumber, parser.CurrentColumnNumber + 1))
        depth[0] += 1
        if depth[0] > MAX_DEPTH:
            raise _TooDeep()

    def on_end(name):
        depth[0] -= 1

    def on_entity(name, is_parameter, value, base, system_id, public_id, notation):
        refused.append(name)
        raise _Refused(name)

    def on_doctype(name, system_id, public_id, has_internal_subset):
        if system_id or public_id:
            raise XmlProblem("entity", external_dtd_message(system_id or public_id),
                             parser.CurrentLineNumber, parser.CurrentColumnNumber + 1)

    _refusing(parser, on_doctype, on_entity)
    parser.StartElementHandler = on_start
    parser.EndElementHandler = on_end
    try:
        parser.Parse(data, True)
    except _Refused:
        raise XmlProblem("entity", entity_message(refused[0]), parser.CurrentLineNumber,
                         parser.CurrentColumnNumber + 1) from None
    except (LookupError, ValueError) as error:  # an unknown encoding= in the declaration
        raise malformed(data, str(error), 1) from None
    except _TooDeep:
        raise XmlProblem("syntax", too_deep_message(), parser.CurrentLineNumber) from None
    except expat.ExpatError as error:
        message = expat.ErrorString(error.code)
        if message == "undefined entity":
            message += " (only the five predefined XML entities are allowed)"
        raise malformed(data, message, error.lineno, error.offset + 1) from None
    return lines


# Where elements start, without a Python call per element (expat's handler is one for each of
# a large robot's hundreds of thousands of elements). In an ASCII document without carriage
# returns or a DOCTYPE that expat accepts, a "<" stands for itself only in markup (never in
# text or attribute values), so each "<" outside comments, CDATA and processing instructions
# that no "/", "!" or "?" follows opens a start tag; its line counts the newlines before it
# and its column the bytes since the last one, as expat counts them, worked out when asked.
# Any other document, and any expat refuses, takes the full pass (start_tag_positions), which
# says why.
_START = re.compile(rb"<[^/!?]")
_SKIPPED = re.compile(rb"<!--.*?(?:-->|\Z)|<!\[CDATA\[.*?(?:\]\]>|\Z)|<\?.*?(?:\?>|\Z)", re.DOTALL)
_OPENING = re.compile(rb"<(?![/!?])")
_NEWLINE = re.compile(rb"\n")
_LONE_CR = re.compile(rb"\r(?!\n)")
_TOO_DEEP = "boolean(/" + "/".join(["*"] * (MAX_DEPTH + 1)) + ")"  # an element below MAX_DEPTH
# A document of this size or more is scanned with numpy (a match object per "<" costs 2,000
# instructions; numpy's comparisons of the whole buffer a fiftieth of that): such a document
# is a robot of thousands of elements, whose rules import numpy anyway.
BULK_SCAN = 1 << 20  # [bytes]


def _in_bulk(data: bytes) -> bool:
    """Whether ``data`` is scanned with numpy (:func:`_bulk_start_tags`, :func:`newlines`):
    a document of :data:`BULK_SCAN` bytes or more, or any once numpy is imported (a robot
    with meshes imports it for its rules): the same offsets, for a few instructions a byte
    instead of 1,300 a match (the corpus's 46 URDFs: 58,000 newlines and start tags; with
    the fixes' lines found in this index, :mod:`urdftool.lint.fixes.tags`, 161 M of 7.02 G
    instructions). A robot checked before numpy's import is scanned by the patterns, so
    that none imports it for this (50 ms)."""
    return len(data) >= BULK_SCAN or "numpy" in sys.modules


def _plain_start_tags(data: bytes) -> list[int] | None:
    """The byte offset of each start tag's "<", or None when the document is not plain enough
    for the scan to be sure (see above)."""
    if not data.isascii() or b"\r" in data:
        return None
    # (a DOCTYPE, comment or CDATA: else no DOCTYPE to look for; "!" looked for first, at
    # memchr's pace: most large robot files hold none)
    marked = b"!" in data and b"<!" in data
    if marked and b"<!DOCTYPE" in data:
        return None
    unmarked = not marked and data.find(b"<?", 1) < 0  # no comment, CDATA or PI to skip
    if _in_bulk(data):
        return _bulk_start_tags(data, unmarked)
    if unmarked:
        return [match.start() for match in _START.finditer(data)]
    # between the comments, CDATA sections and processing instructions (no "<" stands for a
    # tag in them), scanned as one: a match object for each of those, not for every "<"
    found, at = [], 0
    for skipped in _SKIPPED.finditer(data):
        found += [match.start() for match in _OPENING.finditer(data, at, skipped.start())]
        at = skipped.end()
    found += [match.start() for match in _OPENING.finditer(data, at)]
    return found


def _bulk_start_tags(data: bytes, unmarked: bool) -> list[int]:
    """:func:`_plain_start_tags` of a document scanned in bulk (``unmarked``: it holds no comment, CDATA
    or processing instruction past its declaration), the same offsets found by numpy: each
    "<" that no "/", "!" or "?" follows (unmarked: that some byte follows, as ``_START``
    asks), outside the comments, CDATA sections and processing instructions ``_SKIPPED``
    finds."""
    import numpy as np

    text = np.frombuffer(data, dtype=np.uint8)
    opening = np.flatnonzero(text == ord("<"))
    following = text[np.minimum(opening + 1, len(text) - 1)]
    last = opening == len(text) - 1  # ("<" the last byte: nothing follows it)
    kept = (following != ord("/")) & (following != ord("!")) & (following != ord("?"))
    kept = kept & ~last if unmarked else kept | last
    opening = opening[kept]
    if not unmarked:  # drop those inside a skipped stretch: [start, end) of each, in order
        stretches = [(found.start(), found.end()) for found in _SKIPPED.finditer(data)]
        if stretches:
            starts, ends = np.array(stretches, dtype=np.intp).T
            before = np.searchsorted(starts, opening, side="right") - 1  # the last starting at or before
            inside = (before >= 0) & (opening < ends[np.maximum(before, 0)])
            opening = opening[~inside]
    return opening.tolist()


def _accepted(data: bytes) -> bool:
    """Whether expat accepts the document, refusing what the full pass refuses (a DOCTYPE is
    not scanned, so any is refused here), without a handler per element."""
    parser = expat.ParserCreate()

    def refuse(*args):
        raise _Refused("")

    _refusing(parser, refuse, refuse)
    try:
        parser.Parse(data, True)
    except Exception:  # noqa: BLE001 - the full pass finds and says what it was
        return False
    return True


def _clean(parser, data: bytes) -> bool:
    """Whether libxml2 parsed a plain document (:func:`_plain_start_tags`) without a word: no
    error or warning recovered from, nor an encoding declared (libxml2 reads multi-byte
    encodings through iconv that expat refuses). Such a document is one expat accepts too
    (tests/description/test_xml.py: mutated documents), which then need not parse it again."""
    if len(parser.error_log):
        return False
    return not (data.startswith(b"<?xml") and b"encoding" in data[:data.find(b">")])


class _StartOffsets(Mapping):
    """Element -> (line, 1-based column) of its start tag, from its byte offset when asked."""

    def __init__(self, data: bytes, elements: list, offsets: list[int]):
        self._offsets = dict(zip(elements, offsets))
        self._data, self._newlines, self._skeleton = data, None, None

    def __getitem__(self, element) -> tuple[int, int]:
        return self._position(self._offsets[element])

    def get(self, element, default=None):
        """As Mapping's, without its exception for an element not found (every finding asks)."""
        offset = self._offsets.get(element)
        return default if offset is None else self._position(offset)

    def positions(self, elements: list) -> list:
        """:meth:`get` of each of ``elements`` (None for one not found), without a call for
        each: the findings of one rule are located together (10,000 on a large robot)."""
        if self._newlines is None:
            self._newlines = newlines(self._data)
        offsets, ends, found = self._offsets, self._newlines, []
        for element in elements:  # (as _position, written out)
            offset = offsets.get(element)
            if offset is None:
                found.append(None)
                continue
            before = bisect.bisect_left(ends, offset)  # newlines before the "<"
            found.append((before + 1, offset - (ends[before - 1] + 1 if before else 0) + 1))
        return found

    def offset(self, element, data: bytes) -> int | None:
        """The byte offset of ``element``'s start tag when ``data`` is the very buffer scanned
        (the fixes find a tag there without parsing up to it), else None."""
        return self._offsets.get(element) if data is self._data else None

    def shapes(self, elements: list) -> list | None:
        """For ``elements``, siblings in document order: the markup of each but the last, from
        its start tag to the next one's, with every attribute value left out (``name=``), as
        bytes (:func:`_skeleton`); None for a document not plain enough to be sure."""
        if self._skeleton is None:
            self._skeleton = _skeleton(self._data) or ()
        if not self._skeleton:
            return None
        text, moved = self._skeleton
        offsets = self._offsets
        at = moved([offsets[element] for element in elements])
        return [text[start:end] for start, end in zip(at, at[1:])]

    def _position(self, offset: int) -> tuple[int, int]:
        if self._newlines is None:
            self._newlines = newlines(self._data)
        before = bisect.bisect_left(self._newlines, offset)  # newlines before the "<"
        line_start = self._newlines[before - 1] + 1 if before else 0
        return before + 1, offset - line_start + 1

    def __iter__(self):
        return iter(self._offsets)

    def __len__(self) -> int:
        return len(self._offsets)


def _skeleton(data: bytes) -> tuple | None:
    """(``data`` with every attribute value left out, a function of start tag offsets in
    ``data`` giving theirs in it) for a plain document (see above) without comments, CDATA,
    processing instructions past its declaration or apostrophes, and whose every quote is
    one of a pair that follows a "=" and holds no "<" or ">"; else None.

    Such a pair is an attribute's value (within one start tag: it crosses no "<" or ">") or
    a pair of quotes in one text (left out too: no rule reads a text through this): what is
    left is every tag, attribute name and end tag as written."""
    import numpy as np

    if b"'" in data or (b"!" in data and b"<!" in data):
        return None
    # (a processing instruction past the declaration: a "?" after it looked for first, at
    # memchr's pace, then "<?")
    if data.find(b"?", data.find(b"?>") + 2 if data.startswith(b"<?") else 0) >= 0 and \
            data.find(b"<?", 1) >= 0:
        return None
    pieces = data.split(b'"')  # (outside, inside, outside, ... quotes)
    values = b"".join(pieces[1::2])
    if len(pieces) % 2 == 0 or b"<" in values or b">" in values:
        return None
    quotes = np.flatnonzero(np.frombuffer(data, dtype=np.uint8) == ord('"'))
    opens, closes = quotes[0::2], quotes[1::2]
    if len(opens) and (opens[0] == 0 or (np.frombuffer(data, dtype=np.uint8)[opens - 1] !=
                                         ord("=")).any()):
        return None
    removed = np.concatenate(([0], np.cumsum(closes - opens + 1)))

    def at(offsets: list) -> list:
        """Where each start tag at these offsets is in the text left (none is in a value)."""
        asked = np.asarray(offsets, dtype=np.intp)
        return (asked - removed[np.searchsorted(closes, asked)]).tolist()

    return b"".join(pieces[0::2]), at


def newlines(data: bytes) -> list[int]:
    """The byte offset where each line of ``data`` ends, as every Location numbers lines
    (:func:`urdftool.diagnostics.line_ends`: a CR LF's LF, a CR alone); without a CR, of each
    LF (numpy's for a document scanned in bulk: see :func:`_in_bulk`)."""
    if b"\r" in data and _LONE_CR.search(data):  # a CR alone ends a line
        return line_ends(data)  # (CR LF's end is its LF: a file of CR LF lines is LF's)
    if not _in_bulk(data):
        return [match.start() for match in _NEWLINE.finditer(data)]
    import numpy as np

    return np.flatnonzero(np.frombuffer(data, dtype=np.uint8) == ord("\n")).tolist()


def _refusing(parser, on_doctype, on_entity) -> None:
    """Set an expat parser to call these on a DOCTYPE and on an entity declaration, and never
    to read an external entity or parameter entities."""
    parser.StartDoctypeDeclHandler = on_doctype
    parser.EntityDeclHandler = on_entity
    parser.ExternalEntityRefHandler = lambda *args: 0
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)


def child_list(element) -> list:
    """The children of ``element`` as iterating it gives them (elements, comments and
    processing instructions, in order), as one list built by lxml (``element[:]``): the slice
    costs a fraction of lxml's child iterator, and the rules walk every element of the robot."""
    return element[:]


def children_named(element, tag: str) -> list:
    """``element.findall(tag)`` for a plain tag (the direct children so named, in order), from
    :func:`child_list`: lxml's ``findall`` parses its path on each call, which costs more than
    the few children of a transmission or a material take to walk."""
    return [child for child in child_list(element) if child.tag == tag]


def first_child(element, tag: str):
    """``element.find(tag)`` for a plain tag (the first direct child so named, or None), a
    tenth of its cost: lxml's ``find`` parses its path on each call, and the rules ask for
    origins, inertials and geometry hundreds of thousands of times on a large robot. Walks
    the siblings with ``getnext`` (an iterator over the children costs more than the few
    steps it takes), over the same children iteration gives, comments included."""
    try:
        candidate = element[0]
    except IndexError:
        return None
    while candidate is not None:
        if candidate.tag == tag:
            return candidate
        candidate = candidate.getnext()
    return None


_LXML_PARSER_OPTIONS = dict(resolve_entities=False, no_network=True, load_dtd=False,
                            huge_tree=False, recover=True, collect_ids=False)


@functools.cache
def _lxml_builds_too_deep() -> bool:
    """Whether this libxml2 builds elements nested deeper than MAX_DEPTH. libxml2 2.14 stops
    at 256 levels (lxml in recover mode keeps the first 256), so a too deep document has fewer
    elements than start tags and takes the full pass that refuses it: searching every tree for
    a too deep element is needed only where it does not stop."""
    from lxml import etree

    nested = b"<a>" * (MAX_DEPTH + 1) + b"</a>" * (MAX_DEPTH + 1)
    try:
        root = etree.fromstring(nested, etree.XMLParser(**_LXML_PARSER_OPTIONS))
    except etree.XMLSyntaxError:
        return True  # not the behaviour counted on: search every tree
    return sum(1 for _ in root.iter()) > MAX_DEPTH


def _refuse_a_tree_cut(data: bytes, root, parser, expat_elements: int | None = None) -> None:
    """XmlProblem when libxml2 did not read the elements of the document expat accepted: past
    one of its limits (a name over 50,000 characters; an attribute value, a text or a comment
    over 10,000,000) it recovers by dropping the elements after it or reading markup inside a
    cut comment as elements: no tree at all, or (``expat_elements``) another count of
    elements than expat's. What expat says comes first (too deep: :data:`MAX_DEPTH`)."""
    if root is None or expat_elements is not None:
        if expat_elements is None:
            start_tag_positions(data)  # (raises what expat refuses)
        limit = next((error.message.strip() for error in parser.error_log
                      if error.level_name == "FATAL"), "")
        found = 0 if root is None else sum(1 for _ in root.iter(_element()))
        raise XmlProblem("syntax", f"cannot be read whole: {expat_elements or 'some'} elements "
                         f"for expat, {found} for libxml2, past its limits ({limit})", 1)


def _element():
    from lxml import etree

    return etree.Element


def parse(data: bytes) -> tuple:
    """Parse ``data``; return the root (an lxml element) and a mapping of each element to its
    start-tag (line, column)."""
    from lxml import etree

    offsets = _plain_start_tags(data)
    if offsets is None:
        lines = start_tag_positions(data)  # (raises XmlProblem for what it refuses)
    # recover=True only lets lxml keep prefixed names whose namespace was never declared
    # (check_urdf accepts those, so must we).
    parser = etree.XMLParser(**_LXML_PARSER_OPTIONS)
    try:
        root = etree.fromstring(data, parser)
    except etree.XMLSyntaxError:  # (libxml2 recovers from less than expat refuses)
        if offsets is not None and not _accepted(data):
            start_tag_positions(data)  # raises XmlProblem: what expat says
        raise
    if offsets is not None and not (_clean(parser, data) or _accepted(data)):
        lines, offsets = start_tag_positions(data), None  # (raises: expat refuses it)
    _refuse_a_tree_cut(data, root, parser)
    elements = list(root.iter(etree.Element))
    if offsets is not None:
        if len(offsets) == len(elements) and not (_lxml_builds_too_deep()
                                                   and root.xpath(_TOO_DEEP)):
            return root, _StartOffsets(data, elements, offsets)
        lines = start_tag_positions(data)  # only too deep a document: the full pass says so
    if len(elements) != len(lines):  # a comment libxml2 cut read as elements (over its limit)
        _refuse_a_tree_cut(data, root, parser, len(lines))
    return root, dict(zip(elements, lines))
