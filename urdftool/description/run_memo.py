"""One run, one view of the file system: what a folder's repository is, where a link leads and
which settings apply are looked up once per run, not once per file, rule or mesh.

``urdftool check`` over a corpus asks the same questions thousands of times (every mesh URI's
sandbox check follows the same links to the same repository root). Inside :func:`one_run`,
functions wrapped with :func:`per_run` remember their answers; outside it (a long-running
editor server, a library caller) they ask every time, so that a ``.git`` or settings file made
between two checks is seen.
"""

from __future__ import annotations

import functools
from contextlib import contextmanager
from contextvars import ContextVar

_MEMO: ContextVar[dict | None] = ContextVar("urdftool_run_memo", default=None)


@contextmanager
def one_run():
    """Remember :func:`per_run` answers until the block ends (nested blocks share the outer
    one's memory)."""
    if _MEMO.get() is not None:
        yield
        return
    token = _MEMO.set({})
    try:
        yield
    finally:
        _MEMO.reset(token)


def per_run(function):
    """``function`` (of hashable positional arguments) answered once per :func:`one_run`."""

    @functools.wraps(function)
    def remembered(*args):
        memo = _MEMO.get()
        if memo is None:
            return function(*args)
        key = (function, *args)
        try:
            return memo[key]
        except KeyError:
            memo[key] = answer = function(*args)
            return answer

    return remembered
