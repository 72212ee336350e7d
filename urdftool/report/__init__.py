"""Reporters: every output format is fed from the same list of per-file results.

A reporter is a function ``(results, stream) -> None``; ``results`` is a list of
:class:`urdftool.lint.engine.FileResult` in a stable order. The format modules import what they
share from :mod:`urdftool.report.summary`, never this package.
"""

from __future__ import annotations

import importlib
import os

from urdftool.report.escape import printable
from urdftool.report.summary import STYLES, Summary, all_findings

__all__ = ["FORMATS", "STYLES", "Summary", "all_findings", "printable", "render",
           "resolve_format", "write_json"]

# format -> its module, imported when used (junit's needs lxml)
_MODULES = {"text": "text_format", "json": "json_format", "sarif": "sarif_format",
            "junit": "junit_format", "github": "github_format", "gitlab": "gitlab_format",
            "rdjson": "rdjson_format", "concise": "concise_format",
            "json-lines": "json_lines_format"}
FORMATS = tuple(_MODULES)


def __getattr__(name: str):
    """``write_json``, imported when asked (a text report never is)."""
    if name == "write_json":
        from urdftool.report.json_output import write_json

        return write_json
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def resolve_format(name: str) -> str:
    """``auto`` is github annotations under GitHub Actions and text elsewhere."""
    if name == "auto":
        return "github" if os.environ.get("GITHUB_ACTIONS") == "true" else "text"
    if name not in FORMATS:
        raise ValueError(name)
    return name


def render(format_name: str, results, stream, quiet: bool = False, notes=True) -> None:
    """Write ``results`` in a format; ``quiet``: the text format leaves out its summary line;
    ``notes``: whether the text format shows notes (True, False, or a function of a result);
    the other formats, read by programs, always write every finding."""
    name = resolve_format(format_name)
    module = importlib.import_module(f"urdftool.report.{_MODULES[name]}")
    if name == "text":
        module.render(results, stream, quiet=quiet, notes=notes)
    else:
        module.render(results, stream)
