"""``urdftool`` and ``python -m urdftool``: the command line.

``urdftool check`` run again with the same words, in the same folder and environment, while
none of the files its findings came from changed, prints what it printed before from the result
cache (:meth:`urdftool.lint.cache.Cache.get_output`) without importing Typer, a third of the
run: the case of pre-commit hooks and editors checking on save. On any doubt the command runs.

Otherwise ``check`` forks a spare worker first (:func:`urdftool.lint.runner.fork_spare`), and
ends without tearing the interpreter down (:func:`_end`).
"""

from __future__ import annotations

import sys


def main() -> None:
    words = sys.argv[1:]
    check = words[:1] == ["check"]
    if check:
        _replay(words)
        from urdftool.lint.runner import fork_spare

        fork_spare()  # the rules are imported on another core while Typer is imported here
    from urdftool.cli import main as run

    try:
        run()
    except SystemExit as done:
        if check:
            _end(done.code)
        raise


def _end(code) -> None:
    """End a check as ``SystemExit(code)`` ends Python, but without tearing the interpreter
    down: the message of a text ``code``, the exit functions, the standard streams flushed,
    then the process ends, not freeing the rules', the robot's and the libraries' objects one
    by one (a noticeable part of a short check; the system frees the memory at once). Files are
    closed by then (the cache and ``--output`` write within ``with``). Returns, for Python's
    own ending, while another thread runs (Python waits for it first)."""
    import atexit
    import os
    import threading

    if threading.active_count() > 1:
        return
    if code is None or isinstance(code, int):
        status = code or 0
    else:
        print(code, file=sys.stderr)
        status = 1
    atexit._run_exitfuncs()  # as Python's ending runs them, last registered first, once
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):
            status = status or 120  # what Python's ending gives when flushing fails
    os._exit(status)


def _replay(words: list[str]) -> None:
    """Exit with the output kept for ``words``, when there is one; else return.

    The cache folder is read off the words without parsing them as the command does: where
    that reading is wrong, it looks in a folder the command never kept these words in (each
    entry is keyed by the words), and the command runs."""
    if "--no-cache" in words:
        return
    from urdftool.lint.cache import Cache, default_folder

    folder = default_folder()
    for word, after in zip(words, [*words[1:], None]):
        if word == "--cache-dir" and after is not None:
            folder = after
        elif word.startswith("--cache-dir="):
            folder = word.partition("=")[2]
    if folder is None or (kept := Cache(folder).get_output(words)) is None:
        return
    stdout, stderr, code = kept
    try:
        sys.stderr.write(stderr)
        sys.stdout.write(stdout)
        sys.stdout.flush()
    except BrokenPipeError:  # the reader left (``| head``): stop quietly, as click does
        import os

        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        code = 1
    raise SystemExit(code)


if __name__ == "__main__":
    main()
