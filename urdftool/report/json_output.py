"""The JSON documents that analysis commands (collisions, dh, dynamics, fk, inertia) print."""

from __future__ import annotations

import json
import math
import sys


def write_json(data, stream=None, finite: bool = False) -> None:
    """``data`` as indented JSON and a newline on ``stream`` (default: standard output).

    finite: write infinite or NaN floats as null, which JSON can carry (else they are refused)
    """
    if finite:
        data = _finite(data)
    (stream or sys.stdout).write(json.dumps(data, indent=2, allow_nan=not finite) + "\n")


def _finite(value):
    if isinstance(value, dict):
        return {key: _finite(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(item) for item in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value
