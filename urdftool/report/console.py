"""Terminal output shared by the command renderers: rich consoles and fixed-point numbers."""

from __future__ import annotations

import sys


def wide_console():
    """A rich console at least 150 columns wide: tables of poses are wide; do not squeeze them."""
    from rich.console import Console

    console = Console(highlight=False)
    console.width = max(console.width, 150)
    return console


def plain_console(stream=None):
    """A rich console on ``stream`` (default: standard output) that never wraps lines."""
    from rich.console import Console

    return Console(file=stream or sys.stdout, highlight=False, soft_wrap=True)


def fixed(value: float, places: int = 6) -> str:
    """``value`` with ``places`` decimals, without the '-0.000000' that round-off leaves."""
    text = f"{value:.{places}f}"
    return text[1:] if text.startswith("-") and not text.strip("-0.") else text
