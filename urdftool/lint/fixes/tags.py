"""Where the start tags of a file the user wrote are, read from its bytes.

A fix lands in the file where an element was written, at its start tag (for xacro, through
includes and macros: :meth:`Robot.locate` keeps where each expanded element came from). The
file is parsed with expat as far as the tags asked for; each tag's parts (name, attributes with
their byte spans, end tag) are read only for the tags a fix asks for. A URDF whose start tags
the loader found by scanning its bytes (:func:`~urdftool.description.xml.parse`) gives each
element's tag from that offset, and is parsed (a handler call per tag before it) only as far
as the end tag of an element holding more than text, when asked for: the corpus's fixes
parsed 8,161 tags for their 404 inertial edits and 60 interface prefixes, 133 M of 6.64 G
instructions.
"""

from __future__ import annotations

import bisect
import functools

import re
from dataclasses import dataclass, field
from xml.parsers import expat

from urdftool.description.xml import newlines
from urdftool.diagnostics import Edit, line_start


_ATTRIBUTE = re.compile(rb"""(\s+)([^\s/>=]+)(\s*=\s*)("([^"]*)"|'([^']*)')""")
_TAG_END = re.compile(rb"\s*(/?)>")
_NAME = re.compile(rb"<([^\s/>]+)")
EXPRESSION = re.compile(r"\$\{|\$\(")


@dataclass(frozen=True)
class Unfixable:
    """Why a finding has no fix: ``reason`` reads as the end of a sentence."""

    reason: str


@dataclass
class Tag:
    """A start tag in a source file: byte offsets of its parts."""

    start: int
    end: int  # after the '>'
    line: int
    name: str
    name_span: tuple[int, int]
    attributes: dict[str, tuple[tuple[int, int], tuple[int, int], str]] = field(default_factory=dict)
    self_closing: bool = False
    # the name in the end tag (None without one), or what finds it when first asked
    _close: object = field(default=None, repr=False)

    @property
    def close_name(self) -> tuple[int, int] | None:
        """The byte span of the name in the end tag; None for an empty-element tag."""
        if callable(self._close):
            self._close = self._close()
        return self._close


class Source:
    """One file as read: where each start tag is (read from the file as expat finds it), and
    each tag's parts, read only for the tags a fix asks for.

    The file is parsed as far as the tags asked for, a chunk at a time: a fix near the top of a
    large file (the root link's) does not pay for the rest. The chunks grow from
    :data:`_FIRST_CHUNK` to :data:`_CHUNK` (doubling): a handler call for each tag of a first
    64 kB chunk cost the root link's fix of the corpus's robots 8,555 calls for tags no fix
    asked for. A file that turns out not to be well formed has the tags before the error (the
    loader has refused such files already).
    """

    _FIRST_CHUNK = 4 * 1024  # [bytes] parsed first
    _CHUNK = 64 * 1024  # [bytes] parsed at a time at most

    def __init__(self, file: str, data: bytes):
        self.file, self.data = file, data
        self._starts: list[tuple[int, int, str]] = []  # (offset of '<', line, name) in order
        self._ends: dict[int, int] = {}  # tag index -> offset where its end tag (or what
        # follows it) is
        self._lines: dict[int, list[int]] = {}  # line -> indexes of the tags starting on it
        self._read: dict[int, Tag] = {}
        self._at: dict[int, Tag] = {}  # offset of '<' -> its tag, read from there (tag_at)
        self._fed, self._well_formed = 0, True
        stack: list[int] = []
        parser = self._parser = expat.ParserCreate()

        def on_start(name, attributes):
            stack.append(len(self._starts))
            line = parser.CurrentLineNumber
            self._lines.setdefault(line, []).append(len(self._starts))
            self._starts.append((parser.CurrentByteIndex, line, name))

        def on_end(name):
            self._ends[stack.pop()] = parser.CurrentByteIndex

        parser.StartElementHandler = on_start
        parser.EndElementHandler = on_end

    def __len__(self) -> int:
        """How many start tags the file has (parsing all of it)."""
        self.parse_until(lambda: False)
        return len(self._starts)

    def parse_until(self, done) -> bool:
        """Parse on until ``done()`` or the end of the file; False when the file is not well
        formed as far as it was parsed."""
        while self._parser is not None and not done():
            size = min(max(self._fed, self._FIRST_CHUNK), self._CHUNK)  # (doubling)
            chunk = self.data[self._fed:self._fed + size]
            self._fed += len(chunk)
            final = self._fed >= len(self.data)
            try:
                self._parser.Parse(chunk, final)
            except (expat.ExpatError, ValueError, LookupError):
                self._well_formed, final = False, True
            if final:
                self._parser = None
        return self._well_formed

    def tag(self, index: int) -> Tag | None:
        """The ``index``-th start tag of the file, its attributes and end tag read; None when
        the file has fewer."""
        if index not in self._read:
            self.parse_until(lambda: index in self._ends)
            if index >= len(self._starts):
                return None
            start, line, name = self._starts[index]
            tag = _read_tag(self.data, start, line)
            if not tag.self_closing:
                tag._close = self._closing(index)
            self._read[index] = tag
        return self._read[index]

    def _closing(self, index: int) -> tuple[int, int] | None:
        """The name span in the end tag of the ``index``-th start tag (which is not an
        empty-element tag), parsing on to it; None when none is found."""
        self.parse_until(lambda: index in self._ends)
        at = self._ends.get(index)
        if at is None or self.data[at:at + 2] != b"</":
            return None
        return at + 2, at + 2 + len(self._starts[index][2].encode("utf-8"))

    def tag_at(self, start: int, index) -> Tag:
        """The start tag whose ``<`` is at byte ``start`` (known from the loader's scan of this
        very buffer: nothing is parsed to find it), which is the file's ``index()``-th: asked
        only for the end tag of an element holding more than text, when :attr:`Tag.close_name`
        is first read. The same tag as :meth:`tag` of that index reads."""
        tag = self._at.get(start)
        if tag is None:
            tag = self._at[start] = _read_tag(self.data, start,
                                              bisect.bisect_left(_newlines(self.data), start) + 1)
            if not tag.self_closing:
                # the next markup (a "<" is nothing else in a well-formed document) is its end
                # tag when it holds nothing but text: found there, else by parsing on to it
                at = self.data.find(b"<", start + 1)
                if self.data[at:at + 2] == b"</":
                    tag._close = (at + 2, at + 2 + len(tag.name.encode("utf-8")))
                else:
                    tag._close = lambda: self._closing(index())
        return tag

    def on_line(self, line: int) -> list[Tag]:
        """The start tags whose ``<`` is on ``line``."""
        self.parse_until(lambda: bool(self._starts) and self._starts[-1][1] > line)
        return [self.tag(index) for index in self._lines.get(line, ())]

    def position(self, offset: int) -> tuple[int, int]:
        return _position(self.data, offset)

    @property
    def newline(self) -> str:
        """The file's line ending (CRLF when it has any; CR when it ends its lines with CR
        alone)."""
        return "\r\n" if b"\r\n" in self.data else "\r" if b"\r" in self.data and \
            b"\n" not in self.data else "\n"

    def edit(self, start: int, end: int, text: str) -> Edit:
        return edit_of(self.file, self.data, start, end, text)


def _position(data: bytes, offset: int) -> tuple[int, int]:
    """1-based line and 0-based column (in characters) of a byte offset: its line from an
    index of the file's newlines (counting them up to each edit made the fixes of a big
    generated robot quadratic, and the corpus's 824 edits in files under 64 kB counted
    their lines again each time: 65 M instructions)."""
    column = len(data[line_start(data, offset):offset].decode("utf-8", errors="replace"))
    return bisect.bisect_left(_newlines(data), offset) + 1, column  # line ends before it


@functools.lru_cache(maxsize=4)
def _newlines(data: bytes) -> list[int]:
    """The offsets of every newline of ``data`` (:func:`urdftool.description.xml.newlines`),
    once per file checked (bytes keep their hash: a later call with the same object hashes
    nothing)."""
    return newlines(data)


def edit_of(file: str, data: bytes, start: int, end: int, text: str) -> Edit:
    """An edit replacing bytes [start, end) of ``data`` (the contents of ``file``)."""
    old = data[start:end].decode("utf-8", errors="replace")
    return Edit(file, start, end, text, old, *_position(data, start), *_position(data, end))


def parse_source(file: str, data: bytes) -> Source | None:
    """Where the start tags of ``data`` are (found as they are asked for); None when it does
    not begin as well-formed XML."""
    source = Source(file, data)
    return source if source.parse_until(lambda: len(source._starts) > 0) else None


def _read_tag(data: bytes, start: int, line: int) -> Tag:
    name = _NAME.match(data, start)
    tag = Tag(start, start, line, name.group(1).decode("utf-8"), name.span(1))
    at = name.end()
    while True:
        match = _ATTRIBUTE.match(data, at)
        if match is None:
            break
        quoted = match.span(4)
        tag.attributes[match.group(2).decode("utf-8")] = (
            match.span(2), (quoted[0] + 1, quoted[1] - 1),
            (match.group(5) if match.group(5) is not None else match.group(6)).decode("utf-8"))
        at = match.end()
    end = _TAG_END.match(data, at)
    tag.self_closing = bool(end and end.group(1))
    tag.end = end.end() if end else at
    return tag


def source(robot, file: str) -> Source | None:
    """The source of one file the robot was built from (parsed once per robot)."""
    def read():
        data = robot.sources.get(file)
        if data is not None and _start_offset(robot, robot.root, data) is not None:
            return Source(file, data)  # a file the loader scanned: expat accepts all of it
        return parse_source(file, data) if data is not None else None
    return robot.memo(("fixes.source", file), read)


def local_name(name: str) -> str:
    return name.rsplit("}", 1)[-1].rsplit(":", 1)[-1]


class _DocumentOrder:
    """Each element's place among the document's elements (comments left out), learnt only as
    far as asked: a fix is usually wanted for a few elements near the top (the root link), and
    numbering every element of a large robot for it costs more than the fix. The walk resumes
    where the last question left it, so many questions still cost one walk in all."""

    def __init__(self, root):
        self._walk = enumerate(e for e in root.iter() if isinstance(e.tag, str))
        self._seen: dict = {}

    def index(self, element) -> int | None:
        found = self._seen.get(element)
        while found is None:
            step = next(self._walk, None)
            if step is None:
                return None
            self._seen[step[1]] = step[0]
            if step[1] is element:
                found = step[0]
        return found


def _start_offset(robot, element, data: bytes) -> int | None:
    """The byte offset of ``element``'s start tag in ``data`` (the robot's one file as loaded),
    when the loader found it by scanning that very buffer, else None."""
    offset = getattr(robot.locations, "start_offset", None)
    return offset(element, data) if offset is not None else None


def source_tag(robot, element) -> tuple[Source, Tag] | Unfixable:
    """The start tag where ``element`` of the robot was written."""
    location = robot.locations.get(element)
    if location is None or location.line is None:
        return Unfixable("urdftool does not know where this element was written")
    found = source(robot, location.file)
    if found is None:
        return Unfixable(f"{location.file} was not read as XML")
    if not robot.from_xacro:  # one file, parsed as loaded: elements and tags in the same order
        order = robot.memo(_DocumentOrder, lambda: _DocumentOrder(robot.root))
        offset = _start_offset(robot, element, found.data)
        if offset is not None:  # where the loader's scan found it: no handler call per tag
            tag = found.tag_at(offset, lambda: order.index(element))
        else:
            index = order.index(element)
            tag = found.tag(index) if index is not None else None
        if tag is not None and local_name(tag.name) == local_name(element.tag):
            return found, tag
        return Unfixable("its start tag was not found")
    candidates = [t for t in found.on_line(location.line) if local_name(t.name) == local_name(element.tag)]
    if len(candidates) > 1:  # several on one line: the one whose literals match
        candidates = [t for t in candidates if all(
            element.get(name) == raw for name, (_, _, raw) in t.attributes.items()
            if not EXPRESSION.search(raw) and not name.startswith(("xmlns", "xacro:")))]
    if len(candidates) != 1:
        return Unfixable(f"its start tag at {location} is not the only <{local_name(element.tag)}> "
                         "there")
    return found, candidates[0]
