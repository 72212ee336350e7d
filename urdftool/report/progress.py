"""Progress bars on standard error for long runs: files checked, configurations sampled.

A bar is shown only where a person watches it: standard error is a terminal (not a pipe, a
file or a CI log, whatever FORCE_COLOR says), TERM is not ``dumb``, and the report is not a
machine format. It appears only once the run has taken ``delay`` seconds, so a quick run
prints nothing, and it is erased when the run ends (transient). rich is imported only then.
"""

from __future__ import annotations

import contextlib
import os
import sys
import time
from collections.abc import Callable, Iterator  # (not typing's: a check does not import it)

Update = Callable[[int, int], None]  # (done, planned)
DELAY = 0.5  # [s] before a bar appears
_INTERVAL = 0.1  # [s] between two redraws


def shown(stream=None, machine: bool = False) -> bool:
    """Whether a bar may be drawn on ``stream`` (default: standard error)."""
    stream = sys.stderr if stream is None else stream
    if machine or os.environ.get("TERM") == "dumb":
        return False
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):  # no isatty, or a closed stream
        return False


@contextlib.contextmanager
def progress(label: str, unit: str, total: int, machine: bool = False, stream=None,
             delay: float = DELAY) -> Iterator[Update]:
    """A context whose value is the callback ``(done, planned)`` that moves a bar
    ``label [====   ] done/planned unit elapsed`` on ``stream`` (default: standard error);
    a callback that does nothing where no bar may be drawn (:func:`shown`)."""
    if not shown(stream, machine):
        yield lambda done, planned: None
        return
    stream = sys.stderr if stream is None else stream
    start = time.monotonic()
    state: dict = {"bar": None, "task": None, "drawn": 0.0}

    def update(done: int, planned: int) -> None:
        now = time.monotonic()
        if state["bar"] is None:
            if now - start < delay or done >= planned:
                return
            state["bar"], state["task"] = _start(label, unit, total, stream)
        if done < planned and now - state["drawn"] < _INTERVAL:
            return
        state["drawn"] = now
        state["bar"].update(state["task"], completed=done, total=planned)

    try:
        yield update
    finally:
        if state["bar"] is not None:
            state["bar"].stop()


def _start(label: str, unit: str, total: int, stream):
    from rich.console import Console
    from rich.progress import (BarColumn, MofNCompleteColumn, Progress, TextColumn,
                               TimeElapsedColumn)

    console = Console(file=stream, force_terminal=True, highlight=False, emoji=False)
    bar = Progress(TextColumn(label, markup=False), BarColumn(), MofNCompleteColumn(),
                   TextColumn(unit, markup=False), TimeElapsedColumn(), console=console,
                   transient=True)
    bar.start()
    return bar, bar.add_task(label, total=total)


@contextlib.contextmanager
def sampling_progress(total: int, machine: bool = False) -> Iterator[Update]:
    """The bar of a sampling run: ``sampling [====  ] 2000/10000 configurations``."""
    with progress("sampling", "configurations", total, machine) as update:
        yield update
