"""Reporters: every output format is fed from the same list of per-file results.

A reporter is a function ``(results, stream) -> None``; ``results`` is a list of
:class:`urdftool.lint.engine.FileResult` in a stable order. The format modules import what they
share from :mod:`urdftool.report.summary`, never this package.
"""

from __future__ import annotations

import os

from urdftool.report import (concise_format, github_format, gitlab_format, json_format,
                             json_lines_format, junit_format, rdjson_format, sarif_format,
                             text_format)
from urdftool.report.summary import STYLES, Summary, all_findings, printable, write_json

__all__ = ["FORMATS", "STYLES", "Summary", "all_findings", "printable", "render",
           "resolve_format", "write_json"]

_RENDERERS = {"text": text_format.render, "json": json_format.render,
              "sarif": sarif_format.render, "junit": junit_format.render,
              "github": github_format.render, "gitlab": gitlab_format.render,
              "rdjson": rdjson_format.render, "concise": concise_format.render,
              "json-lines": json_lines_format.render}
FORMATS = tuple(_RENDERERS)


def resolve_format(name: str) -> str:
    """``auto`` is github annotations under GitHub Actions and text elsewhere."""
    if name == "auto":
        return "github" if os.environ.get("GITHUB_ACTIONS") == "true" else "text"
    if name not in FORMATS:
        raise ValueError(name)
    return name


def render(format_name: str, results, stream, quiet: bool = False) -> None:
    """Write ``results`` in a format; ``quiet``: the text format leaves out its summary line."""
    name = resolve_format(format_name)
    if name == "text":
        text_format.render(results, stream, quiet=quiet)
    else:
        _RENDERERS[name](results, stream)
