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
        for line in difflib.unified_diff(
                before.decode("utf-8", errors="replace").splitlines(keepends=True),
                after.decode("utf-8", errors="replace").splitlines(keepends=True),
                *((shown, shown) if shown.startswith("/") else (f"a/{shown}", f"b/{shown}"))):
            out.append(line if line.endswith("\n") else line + "\n\\ No newline at end of file\n")
    return "".join(out)
