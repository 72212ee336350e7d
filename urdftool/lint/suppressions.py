"""Inline suppressions: ``<!-- urdftool: ignore U203 -->`` comments in the files a user wrote.

``<!-- urdftool: ignore CODES -->`` silences those codes for findings located on the line of the
element that follows the comment (or on the comment's own line, when the comment trails an
element). ``<!-- urdftool: ignore-file CODES -->`` silences them for every finding located in
that file. CODES are rule codes, code prefixes (``U3``) or names, separated by commas or spaces.

For xacro, a finding is located where its element was written (often a macro in an included
file) and at each macro call site that produced it: a comment before either one silences it, so
a comment before ``<xacro:wheel .../>`` silences one wheel and a comment in the macro all of them.

A suppression that silences nothing is reported as U901, unless one of its codes did not run
(``--select``/``--ignore``): then it cannot be known to be unused.
"""

from __future__ import annotations

import re
from collections.abc import Mapping

from urdftool.diagnostics import Finding, Fix, LineNumbers, Location, line_end, line_start, lines_of
from urdftool.description.files import read_regular
from urdftool.lint.catalogue import FAMILIES, Catalogue
from urdftool.records import Frozen

_COMMENT = re.compile(r"<!--\s*urdftool:\s*(ignore-file|ignore)\b((?:(?!<!--).)*?)-->", re.S)
_ONLY_COMMENT = re.compile(r"^\s*<!--.*-->\s*$")


class Suppression(Frozen):
    """One comment: where it is, the line it covers (None: the whole file), and its codes."""

    file: str
    line: int
    target: int | None
    selectors: tuple[str, ...]
    span: tuple[int, int]  # [characters] of the comment in the file's text

    __slots__ = ("file", "line", "target", "selectors", "span")

    def __init__(self, file: str, line: int, target: int | None, selectors: tuple[str, ...],
                 span: tuple[int, int] = (0, 0)) -> None:
        set_field = object.__setattr__
        set_field(self, "file", file)
        set_field(self, "line", line)
        set_field(self, "target", target)
        set_field(self, "selectors", selectors)
        set_field(self, "span", span)

    def covers(self, finding: Finding, location: Location, catalogue: Catalogue) -> bool:
        if self.target is not None and location.line != self.target:
            return False
        return any(catalogue.matches(finding.code, selector) for selector in self.selectors)


def _known(selector: str, catalogue: Catalogue) -> bool:
    family = selector.upper()
    return family in FAMILIES or family == "U" or \
        any(catalogue.matches(r.code, selector) for r in catalogue)


def parse(text: str, file: str) -> list[Suppression]:
    """Every suppression comment in ``text`` (the contents of ``file``), its lines numbered
    as findings' are (:func:`~urdftool.diagnostics.lines_of`: a LINE SEPARATOR in a comment
    above made a suppression cover a later line than the one below it, a file ending its lines
    with CR made every one line 1)."""
    lines = lines_of(text)
    line_of = LineNumbers(text)  # (line_at of each comment counted the lines before it again)
    found = []
    for match in _COMMENT.finditer(text):
        start = line_of(match.start())
        end = line_of(match.end())
        selectors = tuple(part for part in re.split(r"[\s,]+", match.group(2)) if part)
        if match.group(1) == "ignore-file":
            target = None
        elif _before_comment(text, match.start()):
            target = start
        else:
            target = _next_content_line(lines, end)
        found.append(Suppression(file, start, target, selectors, match.span()))
    return found


def _before_comment(text: str, offset: int) -> bool:
    """Whether an element is written before the comment on its line (a trailing comment)."""
    return bool(text[line_start(text, offset):offset].strip())


def _next_content_line(lines: list[str], after: int) -> int:
    """The first line after line ``after`` that is neither blank nor only a comment."""
    for number in range(after + 1, len(lines) + 1):
        line = lines[number - 1]
        if line.strip() and not _ONLY_COMMENT.match(line):
            return number
    return after + 1


def _in_file(shown: str, sources: Mapping[str, bytes]) -> list[Suppression]:
    """The suppressions in a file as findings name it: from the bytes loaded when the loader
    read it, else (a companion YAML or SRDF a rule read) from disk."""
    data = sources.get(shown)
    if data is None:
        if shown.startswith("<") or shown == "-":
            return []
        try:
            data = read_regular(shown)
        except OSError:
            return []
    if b"urdftool:" not in data:  # (as in its text: no byte of an ASCII word is ever part of
        return []  # what decoding replaces; a 10,000-link robot's 5 MB are not decoded for none)
    return parse(data.decode("utf-8", errors="replace"), shown)


def apply(findings: list[Finding], sources: Mapping[str, bytes], ran,
          catalogue: Catalogue) -> list[Finding]:
    """``findings`` without the suppressed ones, plus U901 for suppressions that silenced nothing.

    sources: every file the robot was built from, with the bytes loaded (``Robot.sources``);
        suppressions in them can be unused. Other files findings name are read from disk.
    ran: ``ran(code) -> bool``, whether a code's rule ran in this check
    catalogue: the rules, to tell unknown codes from known ones
    """
    shown_files = list(dict.fromkeys([*sources, *(f.file for f in findings)]))
    suppressions = [s for shown in shown_files for s in _in_file(shown, sources)]
    if not suppressions:
        return findings
    # file -> line -> the suppressions covering it (None: the whole file): a finding is held
    # against those of its lines, not every suppression of its file (a robot with a comment
    # above each of its 8,000 joints compared 64 million pairs)
    by_line: dict[str, dict[int | None, list[Suppression]]] = {}
    for suppression in suppressions:
        by_line.setdefault(suppression.file, {}).setdefault(suppression.target, []).append(
            suppression)
    used: set[Suppression] = set()
    kept = []
    for finding in findings:
        silenced_by = [s for location in (finding.location, *finding.location.via)
                       for line in ((location.line, None) if location.line is not None else (None,))
                       for s in by_line.get(location.file, {}).get(line, ())
                       if s.covers(finding, location, catalogue)]
        used.update(silenced_by)
        if not silenced_by:
            kept.append(finding)
    if ran("U901"):
        checkable: dict[tuple[str, ...], bool] = {}  # (each set of codes asked once)
        texts: dict[str, str] = {}  # (each file decoded once for all its removals)
        for s in suppressions:
            if s in used:
                continue
            if s.selectors not in checkable:
                checkable[s.selectors] = _checkable(s, ran, catalogue)
            if checkable[s.selectors]:
                kept.append(_unused(s, catalogue, sources, texts))
    return kept


def _checkable(suppression: Suppression, ran, catalogue: Catalogue) -> bool:
    """Whether every code a suppression names ran, so that it can be known to be unused."""
    for selector in suppression.selectors:
        codes = [r.code for r in catalogue if catalogue.matches(r.code, selector)]
        if codes and not all(ran(code) for code in codes):
            return False
    return True


def _removal(suppression: Suppression, sources: Mapping[str, bytes],
             texts: dict[str, str]) -> Fix | None:
    """The edit deleting an unused suppression: its line when the comment is alone on it,
    else the comment and the blanks before it. ``texts``: each file's text, decoded once."""
    data = sources.get(suppression.file)
    if data is None:
        try:
            data = read_regular(suppression.file)
        except OSError:
            return None
    if suppression.file not in texts:
        texts[suppression.file] = data.decode("utf-8", errors="replace")
    text = texts[suppression.file]
    start, end = suppression.span
    first, last = line_start(text, start), line_end(text, end)
    if not text[first:start].strip() and not text[end:last].strip():
        start, end = first, last
    elif not text[first:start].strip():  # other content follows on the line
        while end < last and text[end] in " \t":
            end += 1
    else:
        while start > first and text[start - 1] in " \t":
            start -= 1
    offset = len(text[:start].encode("utf-8"))
    from urdftool.lint.fixes import edit_of  # (only for a finding)
    return Fix("delete the unused suppression", (edit_of(
        suppression.file, data, offset, offset + len(text[start:end].encode("utf-8")), ""),))


def _unused(suppression: Suppression, catalogue: Catalogue,
            sources: Mapping[str, bytes], texts: dict[str, str]) -> Finding:
    unknown = [s for s in suppression.selectors if not _known(s, catalogue)]
    if not suppression.selectors:
        message = "suppression names no rule; write e.g. <!-- urdftool: ignore U203 -->"
    elif unknown:
        message = (f"suppression names unknown rule(s) {', '.join(unknown)}; "
                   "`urdftool rules` lists the valid codes and names")
    elif suppression.target is None:
        message = (f"file-level suppression of {', '.join(suppression.selectors)} silences "
                   "nothing in this file; delete it")
    else:
        message = (f"suppression of {', '.join(suppression.selectors)} silences nothing on "
                   f"line {suppression.target}; delete it or move it just above the element "
                   "the finding points at")
    fix = _removal(suppression, sources, texts) if suppression.selectors and not unknown else None
    return catalogue.get("U901").finding(message, Location(suppression.file, suppression.line),
                                         fix)
