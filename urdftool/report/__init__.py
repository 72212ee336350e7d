"""Reporters: every output format is fed from the same list of per-file results.

A reporter is a function ``(results, stream) -> None``; ``results`` is a list of
:class:`urdftool.lint.engine.FileResult` in a stable order.
"""

from __future__ import annotations

import importlib
import json
import os
import re
from dataclasses import dataclass

from urdftool.diagnostics import Finding, Severity

FORMATS = ("text", "json", "sarif", "junit", "github")
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
    return _UNPRINTABLE.sub(lambda m: m.group() if m.group() in keep else _escaped(m), text)


def all_findings(results) -> list[Finding]:
    return [finding for result in results for finding in result.findings]


def write_json(document: dict, stream) -> None:
    """A JSON document as the json and sarif formats write it: indented, ending in a newline."""
    json.dump(document, stream, indent=2)
    stream.write("\n")


def resolve_format(name: str) -> str:
    """``auto`` is github annotations under GitHub Actions and text elsewhere."""
    if name == "auto":
        return "github" if os.environ.get("GITHUB_ACTIONS") == "true" else "text"
    if name not in FORMATS:
        raise ValueError(name)
    return name


def render(format_name: str, results, stream) -> None:
    module = importlib.import_module(f"{__name__}.{resolve_format(format_name)}_format")
    module.render(results, stream)
