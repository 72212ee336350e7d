"""Reporters: every output format is fed from the same list of per-file results.

A reporter is a function ``(results, stream) -> None``; ``results`` is a list of
:class:`urdftool.engine.FileResult` in a stable order.
"""

from __future__ import annotations

import importlib
import json
import os
from dataclasses import dataclass

from ..diagnostics import Finding, Severity

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
