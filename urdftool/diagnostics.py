"""Findings: what a rule found, where, and how bad it is."""

from __future__ import annotations

import bisect
import enum
import os
import re

from urdftool.records import Frozen


class Severity(str, enum.Enum):
    ERROR = "error"
    WARNING = "warning"
    INFO = "info"


class Location(Frozen):
    """A place in a file the user wrote.

    file: path as shown to the user (relative to the working directory when inside it)
    line: 1-based line of the element's opening ``<``, or None when unknown
    via: for elements a xacro macro produced, the call sites, innermost first
    column: 1-based column of the element's ``<`` (in characters), or None when unknown
    """

    file: str
    line: int | None
    via: tuple["Location", ...]
    column: int | None

    __slots__ = ("file", "line", "via", "column")

    def __init__(self, file: str, line: int | None = None, via: tuple["Location", ...] = (),
                 column: int | None = None) -> None:
        set_file, set_line, set_via, set_column = self._setters  # (one made per finding)
        set_file(self, file)
        set_line(self, line)
        set_via(self, via)
        set_column(self, column)

    def __str__(self) -> str:
        return self.file if self.line is None else f"{self.file}:{self.line}"


class Edit(Frozen):
    """Replace bytes ``start``..``end`` of a file the user wrote with ``text``.

    file: path as findings name it (see :class:`Location`)
    start, end: byte offsets [start, end) in the file as it was read; ``old`` is what they hold
    line, column: where ``start`` is: 1-based line, 0-based column in characters
    end_line, end_column: where ``end`` is, the same way (an editor's range is line/column)
    """

    file: str
    start: int
    end: int
    text: str
    old: str
    line: int
    column: int
    end_line: int
    end_column: int

    __slots__ = ("file", "start", "end", "text", "old", "line", "column", "end_line", "end_column")

    def __init__(self, file: str, start: int, end: int, text: str, old: str, line: int,
                 column: int, end_line: int = 0, end_column: int = 0) -> None:
        set_field = object.__setattr__
        set_field(self, "file", file)
        set_field(self, "start", start)
        set_field(self, "end", end)
        set_field(self, "text", text)
        set_field(self, "old", old)
        set_field(self, "line", line)
        set_field(self, "column", column)
        set_field(self, "end_line", end_line)
        set_field(self, "end_column", end_column)


class Derived(Frozen):
    """A new file a fix writes, made from another when the fix is applied (not before: a
    converted mesh can be megabytes).

    file: the new file's path as findings name files; source: the file it is made from
    how: ``obj`` (the mesh converted to Wavefront OBJ), ``stl`` (to binary STL)
    """

    file: str
    source: str
    how: str

    __slots__ = ("file", "source", "how")

    def __init__(self, file: str, source: str, how: str) -> None:
        set_field = object.__setattr__
        set_field(self, "file", file)
        set_field(self, "source", source)
        set_field(self, "how", how)


class Fix(Frozen):
    """What would make a finding go away, as edits of the files the user wrote.

    safe: whether applying it keeps what the description means apart from the defect (``check
        --fix``); an unsafe fix changes a value a person should look at (``--unsafe-fixes``)
    creates: new files the fix writes besides its edits (a mesh converted to another format)
    """

    description: str
    edits: tuple[Edit, ...]
    safe: bool
    creates: tuple[Derived, ...]

    __slots__ = ("description", "edits", "safe", "creates")

    def __init__(self, description: str, edits: tuple[Edit, ...], safe: bool = True,
                 creates: tuple[Derived, ...] = ()) -> None:
        set_field = object.__setattr__
        set_field(self, "description", description)
        set_field(self, "edits", edits)
        set_field(self, "safe", safe)
        set_field(self, "creates", creates)


class Finding(Frozen):
    """What a rule found, where, how bad, and how to fix it.

    target: for a finding about one simulator or loader (``check --target``), its name
        (``mujoco``, ``gz``...); None for the others
    not_checked: True for a finding saying its file's robot was not expanded, so not checked,
        for a package this machine lacks: nothing in it is known to be wrong, and the run says
        so and exits 2 (a file that only defines macros, which expanded would make no robot,
        loses nothing and says False)
    repeated: the parts of the message that other findings of one report say word for word,
        ``(kind, text, detail)`` each, ``text`` as it stands in the message: the evidence a
        rule gives for what it assumed (``why``: a Gazebo plugin's "the robot is ROS 2 (its
        package builds with ament_cmake ...)"), where a package not found was looked for
        (``searched``, detail: its name), the names there are where a name is not known
        (``available``, detail: how many and what they are, ``31 links``:
        urdftool.errors.available's "available links: a, b, ..."). A report for people writes each once per file and
        refers to it after (urdftool.report.text_format); the machine formats keep every
        message whole
    urdfdom_takes: True for a finding of a code urdfdom refuses for
        (:data:`~urdftool.lint.engine.URDFDOM_REFUSES`) on a shape urdfdom parses all the same,
        as its rule knows (a joint's ``name=""``, where a joint without the attribute is refused):
        the commands that pose a robot do not refuse it as urdfdom's refusal
    urdfdom_refuses: True for a finding below an error that is urdfdom's refusal all the same:
        a shape urdfdom refuses in a file read by another reader that takes it (Drake, a web
        page), a warning naming the condition (lint.catalogue.Refused): the commands that pose
        a robot refuse it as urdfdom does
    """

    code: str
    name: str
    severity: Severity
    message: str
    location: Location
    fix: Fix | None
    target: str | None
    not_checked: bool
    repeated: tuple[tuple[str, str, str], ...]
    urdfdom_takes: bool
    urdfdom_refuses: bool

    __slots__ = ("code", "name", "severity", "message", "location", "fix", "target",
                 "not_checked", "repeated", "urdfdom_takes", "urdfdom_refuses")

    def __init__(self, code: str, name: str, severity: Severity, message: str, location: Location,
                 fix: Fix | None = None, target: str | None = None,
                 not_checked: bool = False, repeated: tuple = (),
                 urdfdom_takes: bool = False, urdfdom_refuses: bool = False) -> None:
        set_code, set_name, set_severity, set_message, set_location, set_fix, set_target, \
            set_not_checked, set_repeated, set_takes, set_refuses = self._setters  # (10,000 findings)
        set_code(self, code)
        set_name(self, name)
        set_severity(self, severity)
        set_message(self, message)
        set_location(self, location)
        set_fix(self, fix)
        set_target(self, target)
        set_not_checked(self, not_checked)
        set_repeated(self, repeated)
        set_takes(self, urdfdom_takes)
        set_refuses(self, urdfdom_refuses)

    @property
    def file(self) -> str:
        return self.location.file

    @property
    def line(self) -> int | None:
        return self.location.line

    @property
    def column(self) -> int | None:
        return self.location.column

    def sort_key(self):
        """Line order, then a total order: findings that differ only in their column or macro
        call sites come out the same way in every run."""
        location = self.location  # (read once, not through the properties: 10,000 findings)
        via = location.via
        return (location.file, location.line or 0, self.code, self.message,
                location.column or 0,
                [(site.file, site.line or 0, site.column or 0) for site in via] if via else [])


def distinct_sorted(findings: list[Finding]) -> list[Finding]:
    """``sorted(set(findings), key=Finding.sort_key)`` without hashing each finding: sorted
    (stably), then each finding equal to one before it with the same key left out (equal
    findings have equal keys; a robot of 10,000 links has 10,000 findings). Findings of one
    key that differ keep the order they were given in."""
    keys = [finding.sort_key() for finding in findings]
    kept, last, same = [], None, []
    for index in sorted(range(len(findings)), key=keys.__getitem__):
        finding, key = findings[index], keys[index]
        if key != last:
            last, same = key, [finding]
        elif finding in same:
            continue
        else:
            same.append(finding)
        kept.append(finding)
    return kept


# A line ends at CR LF, LF or CR: where XML numbers its lines (it reads each as one LF: the
# lines of every Location) and where the language server protocol does. Python's str.splitlines
# also ends a line at VT, FF, FS, GS, RS, NEL, LINE SEPARATOR and PARAGRAPH SEPARATOR, which
# XML holds raw in a comment or a value: every line after one was another line.
_LINE_END = re.compile("\r\n|\n|\r")
_LINE_END_BYTES = re.compile(b"\r\n|\n|\r")

# Where a line starts, for a pattern that matches at the start of any line of a file (in place
# of ``^`` under re.MULTILINE, which starts a line after LF only: a file whose lines end with CR
# alone is one line to it): the text's start, after LF, or after a CR that no LF follows.
AT_LINE_START = r"(?:\A|(?<=\n)|(?<=\r)(?!\n))"
AT_LINE_START_BYTES = AT_LINE_START.encode()
_LF = re.compile("\n")  # the line ends of a stretch without CR (sre finds a literal at C speed)
_LF_BYTES = re.compile(b"\n")


def _count_ends(text: str | bytes, start: int, end: int | None) -> int:
    """How many line ends :data:`_LINE_END` finds in ``text`` from ``start`` to ``end`` (read
    as if the text stopped there)."""
    if isinstance(text, bytes):
        if text.find(b"\r", start, end) < 0:
            return text.count(b"\n", start, end)
        return len(_LINE_END_BYTES.findall(text, start, len(text) if end is None else end))
    if text.find("\r", start, end) < 0:
        return text.count("\n", start, end)
    return len(_LINE_END.findall(text, start, len(text) if end is None else end))


def _ends_pattern(text: str | bytes, feeds_only: bool = False):
    """The pattern of the line ends of ``text``: LF alone when it holds no CR (the same ends,
    found at memchr's speed, where the alternation is tried at each character), or when
    ``feeds_only`` (a patch's lines: :func:`lines_of`)."""
    if isinstance(text, bytes):
        return _LF_BYTES if feeds_only or b"\r" not in text else _LINE_END_BYTES
    return _LF if feeds_only or "\r" not in text else _LINE_END


def lines_of(text: str, keepends: bool = False, feeds_only: bool = False) -> list[str]:
    """The lines of a file's ``text`` as :class:`Location` numbers them (line N is item N - 1):
    split at CR LF, LF and CR only, never where :meth:`str.splitlines` also splits. With
    ``keepends``, each line keeps its line end (joined, they are ``text``). ``feeds_only``: the
    lines of a patch instead (``git apply``, ``patch``, difflib's unified diff of them: split
    at line feeds only, a CR part of its line; a CR-only file is one line), with their ends."""
    if not keepends:
        return (text.split("\n") if "\r" not in text else _LINE_END.split(text)) if text else []
    found, at = [], 0
    for end in _ends_pattern(text, feeds_only).finditer(text):
        found.append(text[at:end.end()])
        at = end.end()
    if at < len(text):
        found.append(text[at:])
    return found


def line_at(text: str | bytes, offset: int) -> int:
    """The 1-based line (as :class:`Location` numbers it: :func:`lines_of`) holding the
    character (or byte, of a file's bytes) at ``offset`` of ``text``: the one count of lines
    before a place in a file, for every message and finding that says a line. An LF ending a
    line with the CR before it is on that line."""
    ends = _count_ends(text, 0, offset)
    if 0 < offset < len(text) and text[offset - 1:offset + 1] in ("\r\n", b"\r\n"):
        ends -= 1  # (the CR alone was counted: the slice ended between CR and LF)
    return ends + 1


def lines_between(text: str | bytes, start: int, end: int) -> int:
    """How many line ends of ``text`` lie in [start, end) (neither between a CR and its LF):
    the lines an ascending walk through a file adds from ``start`` to ``end``, at the cost of
    that stretch only."""
    return _count_ends(text, start, end)


def line_ends(text: str | bytes, feeds_only: bool = False) -> list[int]:
    """The offset of the last character (or byte) of each line end of ``text``: a CR LF's LF
    (:func:`line_at` of an offset is 1 + how many of these come before it). ``feeds_only``:
    a patch's lines (:func:`lines_of`)."""
    return [end.end() - 1 for end in _ends_pattern(text, feeds_only).finditer(text)]


class LineNumbers:
    """:func:`line_at` of many offsets of one ``text`` (str or bytes), each found by bisection
    in its :func:`line_ends`, found once; ``feeds_only``: a patch's lines (:func:`lines_of`)."""

    __slots__ = ("_ends",)

    def __init__(self, text: str | bytes, feeds_only: bool = False):
        self._ends = line_ends(text, feeds_only)

    def __call__(self, offset: int) -> int:
        return bisect.bisect_left(self._ends, offset) + 1

    def start(self, line: int) -> int:
        """Where the 1-based ``line`` starts (after the line end before it)."""
        return self._ends[line - 2] + 1 if line > 1 else 0


def line_start(text: str | bytes, offset: int) -> int:
    """Where the line holding ``offset`` of ``text`` starts (after a CR LF, LF or CR: as
    :func:`lines_of` splits), for a column or an indentation."""
    lf, cr = (b"\n", b"\r") if isinstance(text, bytes) else ("\n", "\r")
    after = text.rfind(lf, 0, offset) + 1  # (a CR is looked for after the LF only: a file
    return max(after, text.rfind(cr, after, offset) + 1)  # without CR is not read back whole)


def line_end(text: str | bytes, offset: int) -> int:
    """Where the line holding ``offset`` of ``text`` ends, after its line end (CR LF, LF or
    CR), or the end of ``text``."""
    lf, cr = (b"\n", b"\r") if isinstance(text, bytes) else ("\n", "\r")
    at = text.find(lf, offset)  # (a CR looked for before that LF only, as line_start does)
    before = text.find(cr, offset, len(text) if at < 0 else at)
    at = before if before >= 0 else at
    if at < 0:
        return len(text)
    return at + 2 if text[at:at + 2] in ("\r\n", b"\r\n") else at + 1


def display_path(path: str | os.PathLike) -> str:
    """The path as a user should read it: relative to the working directory when below it."""
    text = os.fspath(path)
    if text == "-" or text.startswith("<"):
        return text
    absolute = os.path.abspath(text)
    here = os.getcwd()  # (the system's: already normal, as abspath would make it)
    if absolute.startswith("//") or here.startswith("//"):  # (POSIX's other root: relpath's)
        try:
            relative = os.path.relpath(absolute)
        except ValueError:
            return absolute
    elif absolute == here:
        relative = os.curdir
    else:
        # relpath's answer for a path below the working directory, without its Python steps:
        # both are normal, so it is the rest after the directory's name and a separator
        below = here if here.endswith(os.sep) else here + os.sep
        relative = absolute[len(below):] if absolute.startswith(below) else os.pardir
    return absolute if relative.startswith("..") else relative
