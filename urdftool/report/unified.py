"""``check --diff``: the edits fixes would make, as a unified diff of each file."""

from __future__ import annotations

import difflib

from urdftool.diagnostics import display_path


def unified(changed: dict[str, tuple[bytes, bytes]]) -> str:
    """``changed``: file -> (bytes now, bytes after), as :class:`urdftool.lint.fixes.Plan` holds
    them; one unified diff per file, in the order given."""
    out = []
    for file, (before, after) in changed.items():
        shown = display_path(file)
        names = (shown, shown) if shown.startswith("/") else (f"a/{shown}", f"b/{shown}")
        for line in difflib.unified_diff(
                _lines(before.decode("utf-8", errors="replace")),
                _lines(after.decode("utf-8", errors="replace")), *map(_quoted, names)):
            out.append(line if line.endswith("\n") else line + "\n\\ No newline at end of file\n")
    return "".join(out)


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


def _lines(text: str) -> list[str]:
    """The file's lines with their ends, split where a patch splits them: at line feeds only
    (``str.splitlines`` also splits at NEL, LINE SEPARATOR and the like, which a name may hold
    raw in XML)."""
    parts = text.split("\n")
    return [part + "\n" for part in parts[:-1]] + ([parts[-1]] if parts[-1] else [])
