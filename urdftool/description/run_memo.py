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

from urdftool.description.record import captured, replay

_MEMO: ContextVar[dict | None] = ContextVar("urdftool_run_memo", default=None)


@contextmanager
def one_run(shared: dict | None = None):
    """Remember :func:`per_run` answers until the block ends (nested blocks share the outer
    one's memory); ``shared``: the memory of earlier blocks of the same run, kept by a caller
    that makes one run of several steps (the pytest plugin's collection and its check)."""
    if _MEMO.get() is not None:
        yield
        return
    token = _MEMO.set({} if shared is None else shared)
    try:
        yield
    finally:
        _MEMO.reset(token)


def per_run(function):
    """``function`` (of hashable positional arguments) answered once per :func:`one_run`; what
    it recorded (:mod:`.record`) is replayed into the record of each later caller."""

    @functools.wraps(function)
    def answered(*args):
        memo = _MEMO.get()
        if memo is None:
            return function(*args)
        key = (function, *args)
        found = memo.get(key)  # (asked again: the most frequent case, answered here)
        if found is not None:
            value, events = found
            if events is not None:
                replay(events)
            return value
        # (not asked yet: computed here, not by record.remembered, whose lookup would fail
        # again, by an exception)
        memo[key] = (value, _) = captured(lambda: function(*args))
        return value

    return answered


def answering(function):
    """``answer(arg, compute, *values)``: what ``function`` (wrapped with :func:`per_run`, of
    one argument) answers to ``arg`` in this run: its remembered answer, or ``compute(*values)``
    remembered as its answer. For an answer found alongside another one (a folder listed in a
    walk, whose real path is its parent's and its name) and for a function that records
    nothing: what ``compute`` records is the caller's. The run's memory is looked up once,
    here (a walk asks two such questions of each of hundreds of folders)."""
    memo, plain = _MEMO.get(), function.__wrapped__
    if memo is None:
        return lambda arg, compute, *values: compute(*values)

    def answer(arg, compute, *values):
        key = (plain, arg)
        found = memo.get(key)
        if found is not None:
            value, events = found
            if events is not None:
                replay(events)
            return value
        value = compute(*values)
        memo[key] = (value, None)
        return value

    return answer
