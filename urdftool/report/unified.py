"""``check --diff``: the edits fixes would make, as a unified diff of each file."""

from __future__ import annotations

import difflib

from urdftool.diagnostics import LineNumbers, display_path, lines_of


def unified(changed: dict[str, tuple[bytes, bytes]], spans=None) -> str:
    """``changed``: file -> (bytes now, bytes after), as :class:`urdftool.lint.fixes.Plan` holds
    them; one unified diff per file, in the order given. ``spans``: file -> (start, end, length
    written) of each edit, in the file's order (the plan's ``spans``): the lines between them
    are the same, and only the lines they touch are compared."""
    out = []
    for file, (before, after) in changed.items():
        shown = display_path(file)
        names = (shown, shown) if shown.startswith("/") else (f"a/{shown}", f"b/{shown}")
        old = lines_of(before.decode("utf-8", errors="replace"), keepends=True, feeds_only=True)
        new = lines_of(after.decode("utf-8", errors="replace"), keepends=True, feeds_only=True)
        opcodes = _opcodes(old, new, before, after, (spans or {}).get(file))
        matcher = difflib.SequenceMatcher(None, old, new) if opcodes is None else _Known(opcodes)
        for line in _unified(old, new, *map(_quoted, names), matcher):
            out.append(line if line.endswith("\n") else line + "\n\\ No newline at end of file\n")
    return "".join(out)


class _Known(difflib.SequenceMatcher):
    """A matcher whose opcodes are known: its groups are difflib's grouping of them."""

    def __init__(self, opcodes):
        super().__init__(None, [], [])
        self.opcodes = opcodes

    def get_opcodes(self):
        return self.opcodes


def _opcodes(old: list[str], new: list[str], before: bytes, after: bytes, spans) -> list | None:
    """difflib's opcodes of ``old`` to ``new`` (the lines of ``before`` and ``after``) from the
    edits' spans, (start, end, length written) in the file's order: the lines between the
    groups of lines the edits touch are the same, and difflib compares each group alone.
    difflib over a whole file is quadratic where lines repeat (it takes a line more common
    than 1 % for junk): a robot of 4,000 joints, each with the same axis fixed, took 84 s to
    diff (1,000: 10 s). None when there are no spans: difflib over the whole file."""
    if not spans:
        return None
    # (a patch's lines, numbered by diagnostics as every line number is: those of old and new)
    numbers_old, numbers_new = LineNumbers(before, True), LineNumbers(after, True)

    def line_at(numbers, data: bytes, offset: int) -> int:
        """The 0-based line holding the byte at ``offset`` of ``data``, or its last line."""
        return numbers(min(offset, len(data) - 1)) - 1

    groups: list[list[int]] = []  # [first line, line after the last, growth in bytes]
    for start, end, length in spans:
        first = min(line_at(numbers_old, before, start), len(old))
        last = min(max(first + 1, line_at(numbers_old, before, max(end - 1, start)) + 1),
                   len(old))
        growth = length - (end - start)
        if groups and first <= groups[-1][1]:  # (touching: one block, as difflib shows it)
            groups[-1][1] = max(groups[-1][1], last)
            groups[-1][2] += growth
        else:
            groups.append([first, last, growth])
    opcodes, at, grown = [], 0, 0
    for first, last, growth in groups:
        begin = numbers_old.start(first + 1) if first < len(old) else len(before)
        stop = numbers_old.start(last + 1) if last < len(old) else len(before)
        j1 = line_at(numbers_new, after, begin + grown) if begin + grown < len(after) else \
            len(new)
        grown += growth
        j2 = line_at(numbers_new, after, stop + grown) if stop + grown < len(after) else len(new)
        if first > at:
            opcodes.append(("equal", at, first, j1 - (first - at), j1))
        for tag, i1, i2, k1, k2 in difflib.SequenceMatcher(
                None, old[first:last], new[j1:j2]).get_opcodes():
            opcodes.append((tag, first + i1, first + i2, j1 + k1, j1 + k2))
        at = last
    j = opcodes[-1][4] if opcodes else 0
    if at < len(old) or j < len(new):
        opcodes.append(("equal", at, len(old), j, len(new)))
    if len(old) - at != len(new) - j or any(old[i1:i2] != new[j1:j2] for tag, i1, i2, j1, j2
                                            in opcodes if tag == "equal"):
        return None  # (spans that are not these files' edits: difflib's answer)
    merged = []  # (difflib gives no two equal runs in a row)
    for code in opcodes:
        if merged and code[0] == "equal" == merged[-1][0]:
            merged[-1] = ("equal", merged[-1][1], code[2], merged[-1][3], code[4])
        elif code[1] != code[2] or code[3] != code[4]:
            merged.append(code)
    return merged


def _unified(old: list[str], new: list[str], from_name: str, to_name: str, matcher):
    """difflib.unified_diff's lines from ``matcher``'s grouped opcodes (3 lines of context):
    its loop, which builds its own matcher over the whole files (no argument takes one, nor
    opcodes), the quadratic cost :func:`_opcodes` avoids (tested to give its very text)."""
    started = False
    for group in matcher.get_grouped_opcodes(3):
        if not started:
            started = True
            yield f"--- {from_name}\n"
            yield f"+++ {to_name}\n"
        first, last = group[0], group[-1]
        yield f"@@ -{_range(first[1], last[2])} +{_range(first[3], last[4])} @@\n"
        for tag, i1, i2, j1, j2 in group:
            if tag == "equal":
                yield from (" " + line for line in old[i1:i2])
                continue
            if tag in ("replace", "delete"):
                yield from ("-" + line for line in old[i1:i2])
            if tag in ("replace", "insert"):
                yield from ("+" + line for line in new[j1:j2])


def _range(start: int, stop: int) -> str:
    """A hunk's range as a unified diff writes it (difflib's ``_format_range_unified``,
    private)."""
    length = stop - start
    if length == 1:
        return f"{start + 1}"
    return f"{start if not length else start + 1},{length}"


def _quoted(name: str) -> str:
    """A file name as git writes it in a patch: as it is, or, when it holds a control
    character, a quote, a backslash or anything not ASCII, in double quotes with C escapes
    (``\\n``, ``\\"``, octal bytes) that ``git apply`` and ``patch`` read back."""
    if name.isascii() and name.isprintable() and '"' not in name and "\\" not in name:
        return name
    short = {0x07: "a", 0x08: "b", 0x09: "t", 0x0a: "n", 0x0b: "v", 0x0c: "f", 0x0d: "r",
             0x22: '"', 0x5c: "\\"}
    return '"' + "".join(f"\\{short[b]}" if b in short else chr(b) if 0x20 <= b < 0x7f
                         else f"\\{b:03o}"
                         for b in name.encode("utf-8", "surrogateescape")) + '"'

