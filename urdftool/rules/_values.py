"""Reading numbers out of URDF attributes the way urdfdom does, with reasons when it cannot."""

from __future__ import annotations

import math


def parse_numbers(text: str | None, count: int | None = None):
    """(values, problem): values is None when ``text`` is not ``count`` finite-or-not numbers."""
    if text is None:
        return None, "missing"
    parts = text.split()
    if count is not None and len(parts) != count:
        return None, f"expected {count} numbers, found {len(parts)} in '{text}'"
    values = []
    for part in parts:
        try:
            values.append(float(part))
        except ValueError:
            return None, f"'{part}' is not a number (in '{text}')"
    return values, None


def finite(values) -> bool:
    return all(math.isfinite(v) for v in values)


def number(element, attribute: str, default: float | None = None):
    """A single numeric attribute as float, ``default`` when absent, None when malformed."""
    text = element.get(attribute)
    if text is None:
        return default
    values, problem = parse_numbers(text, 1)
    return values[0] if values else None
