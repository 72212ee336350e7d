"""The standard streams: the one owner of how urdftool writes its output and ends.

Every way urdftool runs (``urdftool`` and ``python -m urdftool``: the door in
``__main__.py``, Typer's commands, its help and usage errors; ``python -m urdftool.docs``; a
budgeted command's forked worker; the language server's messages) runs inside :func:`run`,
which ends the program as follows (``docs/output.md``):

- the reader of standard output left (EPIPE: ``urdftool check ... | head -1``): the command
  stops, nothing is said, exit :data:`READER_LEFT` (1, as click and hence every Typer program
  ends; a shell reports 141 for a program SIGPIPE killed, which Python never is: both fail a
  ``set -o pipefail`` pipeline);
- standard output cannot be written otherwise (ENOSPC ``> /dev/full``, EIO, EBADF: a closed
  ``>&-``): one line on standard error naming the stream and the reason, exit
  :data:`LOST` (2, an error of the run): never a traceback, never 0 after output was lost;
- standard error closed or failing: what is said there is lost, nothing else changes (the
  output, the exit status);
- nothing is left in a buffer for Python's shutdown to fail on ("Exception ignored ...").

How: :func:`guard` gives ``sys.stdout`` and ``sys.stderr`` text streams over a raw stream of
this module (:class:`_Stream`), which writes the file descriptor and keeps its first failure,
whoever caught the exception it raised (click catches EPIPE, rich turns it into SystemExit, a
library may log and go on). :func:`end` asks them, not the exception: the decision holds
whatever path the output took. A standard file descriptor closed when the program starts is
opened on the null device first (standard output read-only, so that writing it fails as a
closed one does), so that no file urdftool opens takes its number and receives its output.
"""

from __future__ import annotations

import io
import os
import sys

READER_LEFT = 1  # exit status when the reader of standard output left (EPIPE)
LOST = 2  # exit status when standard output could not be written otherwise
_EPIPE = 32  # errno.EPIPE (POSIX; errno is not imported on the start-up path)


class _Stream(io.RawIOBase):
    """A standard stream's file descriptor, written with ``os.write``, which keeps the errno
    of its first failed write (:attr:`failed`). ``output``: a failed write raises (the command
    stops: its output is lost); else (standard error) the bytes are dropped and it goes on."""

    def __init__(self, fd: int, name: str, output: bool, lost: bool = False):
        super().__init__()
        self.fd, self.name, self.output, self.lost = fd, name, output, lost
        self.failed: int | None = None
        self.said = False
        self._tty: bool | None = None

    def writable(self) -> bool:
        return True

    def fileno(self) -> int:
        return self.fd

    def isatty(self) -> bool:
        if self._tty is None:
            self._tty = os.isatty(self.fd)
        return self._tty

    def write(self, data) -> int | None:
        try:
            return os.write(self.fd, data)
        except BlockingIOError:  # a non-blocking descriptor, full for now: as FileIO says it
            return None
        except OSError as error:
            if self.failed is None:
                self.failed = error.errno
            if self.lost:
                raise BrokenPipeError(error.errno, error.strerror) from None
            if self.output:
                raise
            return len(data)


_WATCHED: list[_Stream] = []  # the output streams whose failure ends the program
_ERR: list[_Stream] = []  # standard error's (guard() made the streams: it is done)


def guard() -> None:
    """Put the standard streams in this module's hands (once): closed descriptors opened on
    the null device, ``sys.stdout`` and ``sys.stderr`` written through :class:`_Stream`."""
    if _WATCHED or _ERR:
        return
    for fd, name, flags in ((0, "stdin", os.O_RDONLY), (1, "stdout", os.O_RDONLY),
                            (2, "stderr", os.O_WRONLY)):
        if getattr(sys, name) is None:
            _reopen(fd, flags)
            if fd == 0:
                sys.stdin = io.TextIOWrapper(io.BufferedReader(io.FileIO(0, closefd=False)),
                                             encoding="utf-8")  # (empty: the null device)
    sys.stdout = _text(sys.stdout, 1, "standard output", True)
    sys.stderr = _text(sys.stderr, 2, "standard error", False)
    import warnings  # (imported by Python at start: no cost)

    warnings.showwarning = _warning_line


def _warning_line(message, category, filename, lineno, file=None, line=None) -> None:
    """A Python warning (numpy's ``RuntimeWarning`` on a mesh of NaN and 1e38, a library's
    ``UserWarning`` that may quote a file's text) as one line of standard error through the
    terminal-text escaper, as every message there: Python printed the warning's source line
    and whatever text it held, raw, beside urdftool's own lines."""
    from urdftool.report.escape import text

    where = f"{os.path.basename(str(filename))}:{lineno}"
    say(text(f"urdftool: warning: {category.__name__}: {message} ({where})"))


def _reopen(fd: int, flags: int) -> None:
    """The null device opened as ``fd`` when it is closed (as Python found it at start)."""
    try:
        os.fstat(fd)
        return
    except OSError:
        pass
    _reopen_null(fd, flags)


def _text(stream, fd: int, name: str, output: bool):
    """A text stream like ``stream`` (Python's standard one: its encoding, errors, buffering)
    over a :class:`_Stream` of its descriptor (``fd`` when it had none: closed at start);
    ``stream`` itself when it is no file (a test's, an embedding program's)."""
    if stream is None:
        encoding, errors, line_buffering, write_through = "utf-8", "backslashreplace", True, False
    elif isinstance(stream, io.TextIOWrapper):
        try:
            fd = stream.fileno()
            stream.flush()
        except (OSError, ValueError):
            return stream
        encoding, errors = stream.encoding, _errors(stream.encoding, stream.errors)
        line_buffering, write_through = stream.line_buffering, stream.write_through
    else:
        return stream
    raw = _Stream(fd, name, output)
    (_WATCHED if output else _ERR).append(raw)
    text = io.TextIOWrapper(io.BufferedWriter(raw), encoding=encoding, errors=errors,
                            newline="\n", line_buffering=line_buffering,
                            write_through=write_through)
    text.mode = "w"
    return text


def _errors(encoding: str, errors: str) -> str:
    """How a standard stream of ``encoding`` writes a character it cannot: as Python set it
    for UTF-8, else (an ASCII or Latin-1 locale, ``PYTHONIOENCODING=cp1252``) a backslash
    escape, as the terminal-text escaper writes what may not be printed: a robot name with a
    character outside the encoding was a UnicodeEncodeError traceback in place of the report
    ('strict', and 'surrogateescape' only takes surrogates)."""
    import codecs

    try:
        utf8 = codecs.lookup(encoding).name == "utf-8"
    except LookupError:
        utf8 = False
    return errors if utf8 or errors not in ("strict", "surrogateescape") else "backslashreplace"


def binary_output(fd: int):
    """A binary stream writing ``fd`` (a copy of standard output: the language server's
    messages) whose failure ends the program as standard output's does. Any failure is
    raised as BrokenPipeError, the one a protocol library (pygls) takes for a connection
    lost, and stops on; its own errno is kept for :func:`end`."""
    raw = _Stream(fd, "standard output", True, lost=True)
    _WATCHED.append(raw)
    return io.BufferedWriter(raw)


def failed() -> bool:
    """Whether an output stream of this process failed."""
    return any(stream.failed is not None for stream in _WATCHED)


def run(main) -> None:
    """Run ``main()`` (the program; it returns or raises its exit status) with the streams
    guarded, and end: ``SystemExit`` with the status :func:`end` decides. An exception that
    is not the output's failing stays a traceback (a bug), the output flushed first."""
    guard()
    try:
        code = main()
    except SystemExit as ended:
        code = ended.code
    except BaseException:
        end(1)
        if not failed():
            raise
        code = 1
    raise SystemExit(end(code))


def end(code):
    """The exit status of a program (or a forked worker) that would exit with ``code``, its
    output flushed: :data:`READER_LEFT` when the reader of an output left, :data:`LOST` (said
    once on standard error) when it could not be written otherwise, else ``code``. A failed
    output's descriptor is then the null device: nothing remains to fail at exit."""
    for stream in {id(s): s for s in (sys.stdout, sys.__stdout__) if s is not None}.values():
        try:
            stream.flush()
        except (OSError, ValueError):  # kept by its _Stream; a stream closed by its owner
            pass
    for stream in _WATCHED:
        if stream.failed is None:
            continue
        _reopen_null(stream.fd)
        if stream.failed == _EPIPE:
            code = LOST if code == LOST else READER_LEFT
        else:
            code = LOST
            if not stream.said:
                stream.said = True
                say(f"urdftool: error: cannot write {stream.name}: "
                    f"{os.strerror(stream.failed)}")
    try:
        sys.stderr.flush()
    except (AttributeError, OSError, ValueError):
        pass
    return code


def say(line: str) -> None:
    """One line on standard error, whatever state it is in."""
    try:
        sys.stderr.write(line + "\n")
        sys.stderr.flush()
    except (AttributeError, OSError, ValueError):
        pass


def _reopen_null(fd: int, flags: int = os.O_WRONLY) -> None:
    """``fd`` on the null device, opened with ``flags`` (written to nowhere from now on)."""
    try:
        null = os.open(os.devnull, flags)
    except OSError:
        return
    if null == fd:  # (fd was closed: the lowest free number)
        return
    try:
        os.dup2(null, fd)
    except OSError:
        pass
    finally:
        os.close(null)
