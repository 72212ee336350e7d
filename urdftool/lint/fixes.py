"""Fixes: edits of the files the user wrote that remove a finding, and applying them.

A rule builds the fix of a finding with the helpers here, from the robot element it reports. The
edit lands in the file where that element was written, at its start tag (for xacro, through
includes and macros: :meth:`Robot.locate` keeps where each expanded element came from), at the
literal that produced the value. Text spans are replaced; the XML is never re-serialised, so
formatting, comments and attribute order stay as they were.

When the value came from an expression or a macro argument (``${...}``, ``$(arg ...)``) there is
no edit: the helper returns :class:`Unfixable`, whose reason says where the value came from, and
the rule adds it to its message (:func:`offer`).

:func:`plan` gathers the fixes of checked files (safe ones, or all with ``unsafe``), refuses
edits of files outside the checked robot's containment root and edits whose text is no longer
what was read, and gives the new contents; :func:`write` writes them atomically.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from xml.parsers import expat

from urdftool.description.files import kind_of
from urdftool.diagnostics import Edit, Fix

_ATTRIBUTE = re.compile(rb"""(\s+)([^\s/>=]+)(\s*=\s*)("([^"]*)"|'([^']*)')""")
_TAG_END = re.compile(rb"\s*(/?)>")
_NAME = re.compile(rb"<([^\s/>]+)")
EXPRESSION = re.compile(r"\$\{|\$\(")


@dataclass(frozen=True)
class Unfixable:
    """Why a finding has no fix: ``reason`` reads as the end of a sentence."""

    reason: str


@dataclass
class _Tag:
    """A start tag in a source file: byte offsets of its parts."""

    start: int
    end: int  # after the '>'
    line: int
    name: str
    name_span: tuple[int, int]
    attributes: dict[str, tuple[tuple[int, int], tuple[int, int], str]] = field(default_factory=dict)
    self_closing: bool = False
    close_name: tuple[int, int] | None = None  # the name in the end tag


class Source:
    """One file as read: where each start tag is (read from the file as expat finds it), and
    each tag's parts, read only for the tags a fix asks for.

    The file is parsed as far as the tags asked for, a chunk at a time: a fix near the top of a
    large file (the root link's) does not pay for the rest. A file that turns out not to be
    well formed has the tags before the error (the loader has refused such files already).
    """

    _CHUNK = 64 * 1024  # [bytes] parsed at a time

    def __init__(self, file: str, data: bytes):
        self.file, self.data = file, data
        self._starts: list[tuple[int, int, str]] = []  # (offset of '<', line, name) in order
        self._ends: dict[int, int] = {}  # tag index -> offset where its end tag (or what
        # follows it) is
        self._lines: dict[int, list[int]] = {}  # line -> indexes of the tags starting on it
        self._read: dict[int, _Tag] = {}
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
            chunk = self.data[self._fed:self._fed + self._CHUNK]
            self._fed += len(chunk)
            final = self._fed >= len(self.data)
            try:
                self._parser.Parse(chunk, final)
            except (expat.ExpatError, ValueError, LookupError):
                self._well_formed, final = False, True
            if final:
                self._parser = None
        return self._well_formed

    def tag(self, index: int) -> _Tag | None:
        """The ``index``-th start tag of the file, its attributes and end tag read; None when
        the file has fewer."""
        if index not in self._read:
            self.parse_until(lambda: index in self._ends)
            if index >= len(self._starts):
                return None
            start, line, name = self._starts[index]
            tag = _read_tag(self.data, start, line)
            at = self._ends.get(index)
            if not tag.self_closing and at is not None and self.data[at:at + 2] == b"</":
                tag.close_name = (at + 2, at + 2 + len(name.encode("utf-8")))
            self._read[index] = tag
        return self._read[index]

    def on_line(self, line: int) -> list[_Tag]:
        """The start tags whose ``<`` is on ``line``."""
        self.parse_until(lambda: bool(self._starts) and self._starts[-1][1] > line)
        return [self.tag(index) for index in self._lines.get(line, ())]

    def position(self, offset: int) -> tuple[int, int]:
        return _position(self.data, offset)

    @property
    def newline(self) -> str:
        """The file's line ending (CRLF when it has any)."""
        return "\r\n" if b"\r\n" in self.data else "\n"

    def edit(self, start: int, end: int, text: str) -> Edit:
        return edit_of(self.file, self.data, start, end, text)


def _position(data: bytes, offset: int) -> tuple[int, int]:
    """1-based line and 0-based column (in characters) of a byte offset."""
    line_start = data.rfind(b"\n", 0, offset) + 1
    column = len(data[line_start:offset].decode("utf-8", errors="replace"))
    return data.count(b"\n", 0, offset) + 1, column


def edit_of(file: str, data: bytes, start: int, end: int, text: str) -> Edit:
    """An edit replacing bytes [start, end) of ``data`` (the contents of ``file``)."""
    old = data[start:end].decode("utf-8", errors="replace")
    return Edit(file, start, end, text, old, *_position(data, start), *_position(data, end))


def parse_source(file: str, data: bytes) -> Source | None:
    """Where the start tags of ``data`` are (found as they are asked for); None when it does
    not begin as well-formed XML."""
    source = Source(file, data)
    return source if source.parse_until(lambda: len(source._starts) > 0) else None


def _read_tag(data: bytes, start: int, line: int) -> _Tag:
    name = _NAME.match(data, start)
    tag = _Tag(start, start, line, name.group(1).decode("utf-8"), name.span(1))
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
        return parse_source(file, data) if data is not None else None
    return robot.memo(("fixes.source", file), read)


def _local(name: str) -> str:
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


def source_tag(robot, element) -> tuple[Source, _Tag] | Unfixable:
    """The start tag where ``element`` of the robot was written."""
    location = robot.locations.get(element)
    if location is None or location.line is None:
        return Unfixable("urdftool does not know where this element was written")
    found = source(robot, location.file)
    if found is None:
        return Unfixable(f"{location.file} was not read as XML")
    if not robot.from_xacro:  # one file, parsed as loaded: elements and tags in the same order
        index = robot.memo(_DocumentOrder, lambda: _DocumentOrder(robot.root)).index(element)
        tag = found.tag(index) if index is not None else None
        if tag is not None and _local(tag.name) == _local(element.tag):
            return found, tag
        return Unfixable("its start tag was not found")
    candidates = [t for t in found.on_line(location.line) if _local(t.name) == _local(element.tag)]
    if len(candidates) > 1:  # several on one line: the one whose literals match
        candidates = [t for t in candidates if all(
            element.get(name) == raw for name, (_, _, raw) in t.attributes.items()
            if not EXPRESSION.search(raw) and not name.startswith(("xmlns", "xacro:")))]
    if len(candidates) != 1:
        return Unfixable(f"its start tag at {location} is not the only <{_local(element.tag)}> "
                         "there")
    return found, candidates[0]


def _escape(value: str) -> str:
    return value.replace("&", "&amp;").replace("<", "&lt;").replace('"', "&quot;")


def set_attribute(robot, element, name: str, value: str) -> list[Edit] | Unfixable:
    """Edits giving ``element``'s attribute ``name`` the value ``value``: the literal replaced,
    or the attribute added after the last one; Unfixable when the value came from an
    expression."""
    found = source_tag(robot, element)
    if isinstance(found, Unfixable):
        return found
    text, tag = found
    if name in tag.attributes:
        _, (start, end), raw = tag.attributes[name]
        if EXPRESSION.search(raw):
            line, _ = text.position(start)
            return Unfixable(_origin(robot, element, name, raw, f"{text.file}:{line}"))
        quote = text.data[start - 1:start]
        escaped = _escape(value) if quote == b'"' else _escape(value).replace("'", "&apos;")
        return [text.edit(start, end, escaped)]
    if element.get(name) is not None:
        return Unfixable(f"{name} is not written at {text.file}:{tag.line} (set by xacro)")
    closing = text.data.rfind(b"/>" if tag.self_closing else b">", tag.start, tag.end)
    at = closing
    while at > tag.start and text.data[at - 1:at].isspace():
        at -= 1
    return [text.edit(at, at, f' {name}="{_escape(value)}"')]


_ARGUMENT = re.compile(r"\$\{\s*([A-Za-z_]\w*)\s*\}")


def _origin(robot, element, name: str, raw: str, where: str) -> str:
    """Where an attribute value written as an expression came from: the macro argument of the
    call that produced the element when the expression is one (``${axis}``), else the
    expression itself."""
    argument = _ARGUMENT.fullmatch(raw.strip())
    location = robot.locations.get(element)
    if argument and location is not None:
        for site in location.via:
            text = source(robot, site.file)
            calls = [t for t in (text.on_line(site.line) if text else ())
                     if t.name.startswith("xacro:") and argument.group(1) in t.attributes]
            if len(calls) == 1:
                value = calls[0].attributes[argument.group(1)][2]
                return (f"{name} is the macro argument {argument.group(1)}=\"{value}\" of the "
                        f"call at {site}; change it there")
    return (f"{name} comes from the expression \"{raw}\" at {where}; change it there or where "
            "its parts are defined")


def swap_attributes(robot, element, first: str, second: str,
                    default: str | None = None) -> list[Edit] | Unfixable:
    """Edits exchanging the values of two attributes of ``element`` (``default``: the value an
    absent one stands for)."""
    values = [element.get(name, default) for name in (first, second)]
    if None in values:
        return Unfixable(f"{first} or {second} is missing")
    edits = []
    for name, value in ((first, values[1]), (second, values[0])):
        found = set_attribute(robot, element, name, value)
        if isinstance(found, Unfixable):
            return found
        edits.extend(found)
    return edits


def insert_before(robot, element, *xml: str) -> list[Edit] | Unfixable:
    """An edit writing the elements ``xml`` just before ``element``'s start tag, each on a line
    of its own with the same indentation when ``element`` starts its line."""
    found = source_tag(robot, element)
    if isinstance(found, Unfixable):
        return found
    text, tag = found
    line_start = text.data.rfind(b"\n", 0, tag.start) + 1
    indent = text.data[line_start:tag.start]
    separator = text.newline + indent.decode("utf-8") if not indent.strip() else " "
    return [text.edit(tag.start, tag.start, "".join(part + separator for part in xml))]


def append_child(robot, element, xml: str) -> list[Edit] | Unfixable:
    """An edit writing ``xml`` (lines of an element) as the last child of ``element``, indented
    one step (two spaces) deeper than ``element`` when its end tag starts a line."""
    found = source_tag(robot, element)
    if isinstance(found, Unfixable):
        return found
    text, tag = found
    if tag.close_name is None:
        return Unfixable(f"<{tag.name}> at {text.file}:{tag.line} is empty-element tag")
    close = tag.close_name[0] - 2
    line_start = text.data.rfind(b"\n", 0, close) + 1
    before = text.data[line_start:close]
    if before.strip():
        return [text.edit(close, close, xml)]
    indent = before.decode("utf-8") + "  "
    lines = "".join(indent + line + text.newline for line in xml.splitlines())
    return [text.edit(line_start, line_start, lines)]


def rename_attribute(robot, element, old: str, new: str) -> list[Edit] | Unfixable:
    """Edits renaming attribute ``old`` of ``element`` to ``new`` where it was written."""
    found = source_tag(robot, element)
    if isinstance(found, Unfixable):
        return found
    text, tag = found
    if old not in tag.attributes:
        return Unfixable(f"attribute {old} is not written at {text.file}:{tag.line}")
    start, end = tag.attributes[old][0]
    return [text.edit(start, end, new)]


def rename_element(robot, element, new: str) -> list[Edit] | Unfixable:
    """Edits renaming ``element`` to ``new`` in its start tag and its end tag."""
    found = source_tag(robot, element)
    if isinstance(found, Unfixable):
        return found
    text, tag = found
    if ":" in tag.name:
        return Unfixable(f"<{tag.name}> at {text.file}:{tag.line} is not a plain element")
    edits = [text.edit(*tag.name_span, new)]
    if tag.close_name is not None:
        edits.append(text.edit(*tag.close_name, new))
    return edits


def _plain_text(robot, element):
    """(source, tag, text, offset of the text) of an element holding plain literal text;
    Unfixable when its text is absent, holds elements or an expression."""
    found = source_tag(robot, element)
    if isinstance(found, Unfixable):
        return found
    text, tag = found
    value = text.data[tag.end:tag.close_name[0] - 2] if tag.close_name is not None else b""
    decoded = value.decode("utf-8", errors="replace")
    if not decoded.strip() or "<" in decoded or EXPRESSION.search(decoded):
        return Unfixable(f"the text of <{tag.name}> at {text.file}:{tag.line} is not a plain "
                         "literal")
    return text, tag, decoded, tag.end + len(value) - len(value.lstrip())


def element_to_attribute(robot, element) -> list[Edit] | Unfixable:
    """Edits turning ``<parent><name>text</name></parent>`` into ``<parent name="text">``: the
    attribute set on the parent, the element deleted."""
    found = _plain_text(robot, element)
    if isinstance(found, Unfixable):
        return found
    text, tag, value, _ = found
    end = text.data.find(b">", tag.close_name[1]) + 1
    attribute = set_attribute(robot, element.getparent(), _local(element.tag), value.strip())
    if isinstance(attribute, Unfixable):
        return attribute
    parent = source_tag(robot, element.getparent())
    if not isinstance(parent, Unfixable) and parent[0] is text and parent[1].close_name:
        holder = parent[1]
        close_end = text.data.find(b">", holder.close_name[1]) + 1
        rest = text.data[holder.end:tag.start] + text.data[end:holder.close_name[0] - 2]
        if not rest.strip():  # nothing else inside: the parent becomes an empty-element tag
            return attribute + [text.edit(holder.end - 1, close_end, "/>")]
    return attribute + [text.edit(tag.start, end, "")]


def prefix_text(robot, element, prefix: str) -> list[Edit] | Unfixable:
    """An edit writing ``prefix`` before the text of ``element`` (after leading blanks)."""
    found = _plain_text(robot, element)
    if isinstance(found, Unfixable):
        return found
    text, _, _, at = found
    return [text.edit(at, at, prefix)]


def inertial_edits(robot, link, body) -> list[Edit] | Unfixable:
    """Edits making ``link``'s ``<inertial>`` say ``body`` (mass [kg], com [m] and inertia
    [kg m^2] about the com in link axes): mass, origin (at the com, rpy zero) and the six
    terms; a whole block written when the link has none."""
    from urdftool.physics.inertia_compare import inertial_numbers

    mass, com, terms = inertial_numbers(body)
    inertial = link.find("inertial")
    if inertial is None:
        return _new_inertial(robot, link, mass, com, terms)
    edits = []
    if inertial.find("mass") is not None and inertial.find("mass").get("value") is not None:
        declared = float(inertial.find("mass").get("value", "nan") or "nan")
        if not abs(declared - float(body.mass)) <= 1e-9 * max(abs(declared), 1.0):
            edits.append(set_attribute(robot, inertial.find("mass"), "value", mass))
    origin = inertial.find("origin")
    if origin is not None:
        edits.append(set_attribute(robot, origin, "xyz", com))
        if origin.get("rpy") is not None:
            edits.append(set_attribute(robot, origin, "rpy", "0 0 0"))
    elif com != "0 0 0":  # as written: round-off is 0
        first = next((c for c in inertial if isinstance(c.tag, str)), None)
        if first is None:
            return Unfixable("its <inertial> is empty")
        edits.append(insert_before(robot, first, f'<origin xyz="{com}" rpy="0 0 0"/>'))
    if inertial.find("inertia") is None:
        return Unfixable("its <inertial> has no <inertia>")
    for name, value in terms.items():
        edits.append(set_attribute(robot, inertial.find("inertia"), name, value))
    unfixable = next((e for e in edits if isinstance(e, Unfixable)), None)
    return unfixable or [edit for group in edits for edit in group]


def _new_inertial(robot, link, mass: str, com: str, terms: dict) -> list[Edit] | Unfixable:
    """An edit writing a whole ``<inertial>`` as the link's first child."""
    block = (f'<inertial><origin xyz="{com}" rpy="0 0 0"/><mass value="{mass}"/><inertia '
             + " ".join(f'{name}="{value}"' for name, value in terms.items()) + "/></inertial>")
    first = next((c for c in link if isinstance(c.tag, str)), None)
    if first is not None:
        return insert_before(robot, first, block)
    found = source_tag(robot, link)
    if isinstance(found, Unfixable):
        return found
    text, tag = found
    if not tag.self_closing:
        return Unfixable(f"<link> at {text.file}:{tag.line} holds no element to write it before")
    closing = text.data.rfind(b"/>", tag.start, tag.end)
    return [text.edit(closing, tag.end, f"><{block[1:]}</link>")]


def offer(where, message: str, description: str, edits, safe: bool = True, creates=()):
    """What a rule yields for a finding with a possible fix: ``(where, message, fix)``; when
    ``edits`` is :class:`Unfixable`, the message with why there is no fix; None: no fix.
    creates: the :class:`~urdftool.diagnostics.Derived` files the fix writes too."""
    if edits is None:
        return where, message, None
    if isinstance(edits, Unfixable):
        return where, f"{message} (no automatic fix: {edits.reason})", None
    return where, message, Fix(description, tuple(edits), safe, tuple(creates))


def converted_mesh(robot, mesh, source, suffix: str):
    """(edits, creates) pointing ``mesh``'s filename at ``source`` converted to ``suffix``
    (``.obj``, ``.stl``), beside it: the file is written when the fix is applied, unless it is
    there already. Unfixable when the filename comes from an expression or has no
    extension to replace."""
    from pathlib import Path

    from urdftool.diagnostics import Derived, display_path

    filename = mesh.get("filename") or ""
    old_suffix = Path(filename.split("?")[0]).suffix
    if not old_suffix or not filename.endswith(old_suffix):
        return Unfixable(f"mesh '{filename}' has no extension to replace"), ()
    edits = set_attribute(robot, mesh, "filename", filename[:-len(old_suffix)] + suffix)
    target = Path(source).with_suffix(suffix)
    if isinstance(edits, Unfixable) or kind_of(target):
        return edits, ()
    return edits, (Derived(display_path(target), display_path(source), suffix[1:]),)


# --- applying ---------------------------------------------------------------------------------


@dataclass
class Plan:
    """What applying the fixes would do.

    changed: file (as findings name it) -> (bytes now, bytes after)
    applied: the fixes taken; skipped: (fix, why) of those left out
    """

    changed: dict[str, tuple[bytes, bytes]] = field(default_factory=dict)
    applied: list[Fix] = field(default_factory=list)
    skipped: list[tuple[Fix, str]] = field(default_factory=list)


def plan(results, unsafe: bool = False, read=None) -> Plan:
    """The fixes of ``results`` (FileResults) that apply: safe ones, unsafe ones too with
    ``unsafe``. A fix is taken whole or not at all; it is left out when one of its edits is
    outside the checked robot's containment root, when the file no longer holds the text
    the edit replaces, or when it overlaps an edit already taken."""
    from urdftool.description.files import read_regular
    from urdftool.description.packages import containment_root

    candidates = []
    for checked in results:
        if checked is None or checked.path == "-":
            continue
        root = containment_root(os.path.dirname(os.path.abspath(checked.path)))
        candidates.extend((finding.fix, root) for finding in checked.findings
                          if finding.fix is not None and (finding.fix.safe or unsafe))
    return _take(candidates, read or read_regular)


def _take(candidates, read) -> Plan:
    """The plan of ``candidates``: (fix, containment root) pairs, in order."""
    from urdftool.description.files import inside

    result = Plan()
    current: dict[str, bytes] = {}
    taken: dict[str, list[Edit]] = {}
    disputed = _disputed([fix for fix, _ in candidates])
    created: dict[str, bytes] = {}
    for fix, root in candidates:
        if fix in result.applied or any(fix is other for other, _ in result.skipped):
            continue
        why = disputed.get(id(fix)) or _refusal(fix, root, current, taken, read, inside) \
            or _creation_refusal(fix, root, created, inside)
        if why == "":
            continue  # the same edits, already taken for another finding
        if why:
            result.skipped.append((fix, why))
            continue
        for edit in fix.edits:
            if edit not in taken.get(edit.file, ()):
                taken.setdefault(edit.file, []).append(edit)
        result.applied.append(fix)
    for file, edits in taken.items():
        data = current[file]
        after = data
        # from the end, so offsets stay true; of insertions at one point, the first taken
        # ends up first
        order = sorted(range(len(edits)), key=lambda i: (edits[i].start, edits[i].end, i))
        for edit in (edits[i] for i in reversed(order)):
            after = after[:edit.start] + edit.text.encode("utf-8") + after[edit.end:]
        result.changed[file] = (data, after)
    for file, data in created.items():
        result.changed[file] = (b"", data)
    return result


def _creation_refusal(fix: Fix, root, created: dict, inside) -> str | None:
    """Why the files ``fix`` creates cannot be made (outside the root, there already, the source
    does not convert); None: they are made, into ``created`` (file -> bytes)."""
    for derived in fix.creates:
        if derived.file in created:
            continue
        if not inside(derived.file, root) or not inside(derived.source, root):
            return f"{derived.file} is outside the repository ({root})"
        if kind_of(derived.file, follow=False):
            return f"{derived.file} exists already"
        from urdftool.description.meshes import converted
        from urdftool.errors import MeshProblem

        try:
            created[derived.file] = converted(derived.source, derived.how)
        except MeshProblem as problem:
            return str(problem)
    return None


def inertia_rewrite(robot, results) -> tuple[Plan, list[tuple[str, str]]]:
    """``urdftool inertia --write``: the edits giving each link of ``results`` (LinkInertia
    with a computed inertial) that inertial, in the files the robot was written in; and (link,
    why) for the links whose inertial cannot be edited (values from expressions)."""
    from urdftool.description.files import read_regular
    from urdftool.description.packages import containment_root

    root = containment_root(robot.base_dir)
    candidates, unfixable = [], []
    for result in results:
        edits = inertial_edits(robot, robot.links[result.link], result.computed)
        if isinstance(edits, Unfixable):
            unfixable.append((result.link, edits.reason))
        else:
            fix = Fix(f"link '{result.link}' inertial from its geometry", tuple(edits), False)
            candidates.append((fix, root))
    changes = _take(candidates, read_regular)
    unfixable.extend((fix.description, why) for fix, why in changes.skipped)
    return changes, unfixable


def _overlap(one: Edit, other: Edit) -> bool:
    """Whether two different edits touch the same text. Insertions at one point do not: they
    are written one after the other."""
    if one == other:
        return False
    if one.start == one.end and other.start == other.end:
        return False
    if one.start == one.end:
        return other.start < one.start < other.end
    if other.start == other.end:
        return one.start < other.start < one.end
    return one.start < other.end and other.start < one.end


def _disputed(candidates: list[Fix]) -> dict[int, str]:
    """Fixes (by id) whose edits overlap a different edit of another fix: a literal in a macro
    that serves several elements needing different values. None of them is taken."""
    spans: dict[str, list[tuple[Edit, int]]] = {}
    for fix in candidates:
        for edit in fix.edits:
            spans.setdefault(edit.file, []).append((edit, id(fix)))
    disputed: dict[int, str] = {}
    for edits in spans.values():
        edits.sort(key=lambda pair: (pair[0].start, pair[0].end))
        for index, (edit, owner) in enumerate(edits):
            for other, second in edits[index + 1:]:
                if other.start > edit.end:
                    break
                if owner != second and _overlap(edit, other):
                    why = (f"the text at {edit.file}:{edit.line} would need different values "
                           "for different elements (a macro used more than once?)")
                    disputed[owner] = disputed[second] = why
    return disputed


def _refusal(fix: Fix, root, current, taken, read, inside) -> str | None:
    """Why ``fix`` cannot be taken; "" when all its edits are taken already; None: take it."""
    if all(edit in taken.get(edit.file, ()) for edit in fix.edits):
        return ""
    for edit in fix.edits:
        if not inside(edit.file, root):
            return f"{edit.file} is outside the repository ({root})"
        if edit.file not in current:
            try:
                current[edit.file] = read(edit.file)
            except OSError as error:
                return f"{edit.file} cannot be read: {error.strerror}"
        data = current[edit.file]
        if data[edit.start:edit.end].decode("utf-8", errors="replace") != edit.old:
            return f"{edit.file} changed since it was checked"
        if any(_overlap(edit, other) for other in taken.get(edit.file, ())):
            return f"it overlaps another fix in {edit.file}"
    return None


MAX_PASSES = 10  # a fix can make another finding (an unused suppression) and its fix appear


def apply(results, recheck, unsafe: bool = False):
    """Apply fixes and check again until nothing more is fixed (at most MAX_PASSES times).

    recheck: ``() -> results`` checks the same targets again
    Returns (the results of the last check, fixes applied, files changed, skipped fixes).
    """
    applied, changed, skipped = 0, set(), []
    for _ in range(MAX_PASSES):
        changes = plan(results, unsafe=unsafe)
        skipped = changes.skipped
        if not changes.changed:
            break
        write(changes)
        applied += len(changes.applied)
        changed.update(changes.changed)
        results = recheck()
    return results, applied, changed, skipped


def write(changes: Plan) -> None:
    """Write the changed files, each atomically (a temporary file replaces it)."""
    from urdftool.description.files import write_file

    for file, (_, after) in changes.changed.items():
        write_file(file, after)
