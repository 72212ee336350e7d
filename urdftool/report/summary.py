"""What every report format shares: the counts, the severity styles, and safe text."""

from __future__ import annotations

import re
from dataclasses import dataclass

from urdftool.diagnostics import Finding, Severity

STYLES = {"error": "bold red", "warning": "yellow", "info": "cyan"}  # rich style per severity


@dataclass(frozen=True)
class Summary:
    files: int
    errors: int
    warnings: int
    infos: int

    @classmethod
    def of(cls, results) -> "Summary":
        findings = all_findings(results)
        count = lambda level: sum(1 for f in findings if f.severity is level)  # noqa: E731
        return cls(len(results), count(Severity.ERROR), count(Severity.WARNING),
                   count(Severity.INFO))


# Characters that move the cursor, end a line, change the terminal's state or reorder text
# (Unicode categories Cc, Cf, Cs, Zl, Zp): a name in a robot file that holds one could forge
# report lines ("::error ...", "no problems found"), hide text, or make a report unwritable.
_UNPRINTABLE = re.compile(
    "[\x00-\x1f\x7f-\x9f\xad\u0600-\u0605\u061c\u06dd\u070f\u0890\u0891\u08e2\u180e"
    "\u200b-\u200f\u2028-\u202e\u2060-\u2064\u2066-\u206f\ud800-\udfff\ufeff"
    "\ufff9-\ufffb\U000110bd\U000110cd\U00013430-\U0001343f\U0001bca0-\U0001bca3"
    "\U0001d173-\U0001d17a\U000e0001\U000e0020-\U000e007f]")
_SHORT = {"\n": "\\n", "\r": "\\r", "\t": "\\t"}


def _escaped(match) -> str:
    char = match.group()
    code = ord(char)
    return _SHORT.get(char) or (f"\\x{code:02x}" if code < 0x100 else
                                f"\\u{code:04x}" if code < 0x10000 else f"\\U{code:08x}")


def printable(text: str, keep: str = "") -> str:
    """``text`` with every control, format, separator or lone surrogate character written as
    a Python escape (``\\n``, ``\\x1b``, ``\\u202e``), except those in ``keep``."""
    if text.isascii() and text.isprintable():  # the characters escaped in ASCII are C0 and DEL,
        return text  # exactly what isprintable refuses there: most text, at C speed
    return _UNPRINTABLE.sub(lambda m: m.group() if m.group() in keep else _escaped(m), text)


def via_text(location) -> list[str]:
    """The macro call chain of a location as lines, innermost call first."""
    return [f"expanded from macro call at {site}" for site in location.via]


def location_dict(location) -> dict:
    """A location as the JSON formats write it: file, line, column (null when unknown) and the
    macro call sites it was expanded from (``via``, innermost first)."""
    return {"file": location.file, "line": location.line, "column": location.column,
            "via": [{"file": site.file, "line": site.line, "column": site.column}
                    for site in location.via]}


def counted(number: int, noun: str) -> str:
    """``1 error``, ``2 errors``."""
    return f"{number} {noun}" if number == 1 else f"{number} {noun}s"


def all_findings(results) -> list[Finding]:
    return [finding for result in results for finding in result.findings]


