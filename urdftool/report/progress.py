"""A progress bar on standard error for long sampling runs; silent when it is not a terminal."""

from __future__ import annotations

import contextlib
from typing import Callable, Iterator


@contextlib.contextmanager
def sampling_progress(total: int) -> Iterator[Callable[[int, int], None]]:
    """A context whose value is the callback ``(done, planned)`` that moves the bar."""
    from rich.console import Console
    from rich.progress import (BarColumn, MofNCompleteColumn, Progress, TextColumn,
                               TimeElapsedColumn)

    err = Console(stderr=True, emoji=False)
    progress = Progress(TextColumn("sampling"), BarColumn(), MofNCompleteColumn(),
                        TextColumn("configurations"), TimeElapsedColumn(), console=err,
                        transient=True, disable=not err.is_terminal)
    with progress:
        task = progress.add_task("sampling", total=total)

        def update(done: int, planned: int) -> None:
            progress.update(task, completed=done, total=planned)

        yield update
