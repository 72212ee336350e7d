"""Helpers for messages that name things: suggestions for misspelt names."""

from __future__ import annotations

import difflib

_LISTED = 12


def available(kind: str, wanted: str, names) -> str:
    """``Did you mean 'x'? Available links: a, b, ...`` for a name that does not exist."""
    names = sorted({name for name in names if name})  # unnamed elements are U103's business
    close = difflib.get_close_matches(wanted, names, n=1, cutoff=0.6)
    hint = f"did you mean '{close[0]}'? " if close else ""
    shown = ", ".join(names[:_LISTED]) + (f", ... ({len(names)} in all)" if len(names) > _LISTED else "")
    return f"{hint}available {kind}: {shown or '(none)'}"
