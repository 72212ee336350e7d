"""``urdftool server``: a language server (LSP over stdio) for editors, built on pygls.

- **Diagnostics** for ``.urdf`` and ``.xacro`` documents on open, on change (the unsaved buffer,
  debounced by :data:`DEBOUNCE`: the newest version wins, a result for an older version is never
  published) and on save. Each is checked by :func:`urdftool.check_file`, in this process, with
  the settings file above it (``urdftool.toml`` or ``[tool.urdftool]``), as ``urdftool check``
  would check it.
- A macro library (a ``.xacro`` that only defines macros) is checked through the robots that
  include it, and a companion file (controllers ``.yaml``, ``.srdf``) through the robots
  ``urdftool check`` would check with it; both on open, on change and on save. A check reads
  every open document from its buffer, the robot's and every file its expansion and discovery
  read (:func:`urdftool.description.files.unsaved`, where every read goes): an edit to an
  included macro file re-checks, debounced, the robots that read it, with its findings at the
  buffer's lines; a result is dropped when any buffer it read has changed since, and closing an
  unsaved buffer re-checks those robots from the disk.
- Which robots a file saved, created, changed or removed concerns is asked of each robot's
  record (:mod:`urdftool.description.record`): the record of its last check, made by the
  loader and discovery as they read, names every file read, folder searched (found empty too),
  path probed and link followed. A saved include, companion, mesh or settings file, and a new
  file in a folder discovery searched (a ``config/controllers.yaml`` made beside a robot that
  had none) re-check the robots concerned. Changes made outside the editor arrive as
  ``workspace/didChangeWatchedFiles``, for which the server asks the client to watch every file
  of the workspace when the client can.
- A finding is published on the file it is located in, whichever document was checked: one in an
  included macro file appears on that file, and at each macro call site (with related
  information pointing at the other). Each robot's diagnostics are kept per file, so a re-check
  that no longer finds something clears it on every file it was shown on.
- **Hover** on a rule code (``U204``, or a rule name in an ``urdftool:`` comment) shows the
  rule's documentation; **code actions** offer the ``<!-- urdftool: ignore CODE -->``
  suppressions (:data:`ACTION_PROVIDERS`: a provider maps a finding to code actions).

Each robot is checked in a forked worker within the same time and memory budget as ``urdftool
check`` (:func:`urdftool.lint.pool.run_budgeted`; ``urdftool server --timeout/--max-memory``,
the settings' ``max-memory``): a robot that takes too long or too much ends with its U015 or
U018 diagnostic, located where the work was, and its worker is killed. Up to :data:`JOBS`
documents are checked at once, each job waiting in a thread of its own, so one slow document
never holds the others' diagnostics; a newer version of a document (or its closing) stops the
check of the older one at once (its worker is killed, its result dropped), so a flood of
changes keeps at most one check per document. The server answers hovers and code actions all
the while. A check that raises is logged (``window/logMessage``) and shown once
(``window/showMessage``); nothing new is published for it and the server goes on.
"""

from __future__ import annotations

import asyncio
import io
import itertools
import logging
import os
import re
import sys
import threading
import time
import traceback
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from urllib.parse import unquote

from lsprotocol import types
from pygls.lsp.server import LanguageServer
from pygls.uris import from_fs_path, to_fs_path
from pygls.workspace import TextDocument

from urdftool.budget import DEFAULT_TIMEOUT, Budget
from urdftool.diagnostics import Finding, Location, Severity, display_path, lines_of
from urdftool.description.companions import COMPANION_SUFFIXES
from urdftool.description.urdf import ROBOT_SUFFIXES, is_robot_name

DEBOUNCE = 0.3  # [s] quiet time after the last change before the buffer is checked
JOBS = 2  # documents checked at once (each in a worker process; at least 2: a slow one and the
# one being typed in), more on machines with more cores: see _jobs()
SOURCE = "urdftool"

_SEVERITIES = {Severity.ERROR: types.DiagnosticSeverity.Error,
               Severity.WARNING: types.DiagnosticSeverity.Warning,
               Severity.INFO: types.DiagnosticSeverity.Information}
# (the word before the position from its first character: from each, quadratic in a long word)
_WORD = re.compile(r"(?<![A-Za-z0-9_-])[A-Za-z0-9_-]*$"), re.compile(r"^[A-Za-z0-9_-]*")
_CODE = re.compile(r"[Uu]\d{3}")
_PLAIN_NAME = re.compile(r"(?!\.\.?$)[A-Za-z0-9._-]+")  # (UrdftoolServer.paths_of)
_PLAIN_FOLDER_URI = re.compile(r"file://[^;?#\x00-\x20\x7f]*")
_IGNORE_LINE = re.compile(r"^(\s*)<!--\s*urdftool:\s*ignore\s++(.*)-->\s*$")  # group 2 stripped where read

logger = logging.getLogger(__name__)


def kind_of(path: str) -> str | None:
    """'robot', 'companion', or None for a file the server shows no diagnostics of its own
    for (a settings file, a mesh: saving one re-checks the robots whose record names it)."""
    name = os.path.basename(path)
    if is_robot_name(name):
        return "robot"
    return "companion" if name.endswith(COMPANION_SUFFIXES) else None


# ---- in the worker thread: checking, and findings -> diagnostics ------------------------------

@dataclass(frozen=True)
class Buffer:
    """An open document as it was when a check started."""

    uri: str
    text: str
    version: int | None


Shown = tuple[types.Diagnostic, Finding]  # a diagnostic and the finding it shows


@dataclass
class Outcome:
    """One robot checked.

    version: of its open document whose text was checked; None when read from disk
    versions: of every open document the check read (the robot, an included file, a
        companion), by path: the buffers it was served
    by_path: diagnostics per file (absolute path); the robot's own file always has an entry
    record: what the check read, searched, probed and followed
        (:class:`~urdftool.description.record.Record`), None when it raised
    error: why the check raised, instead of findings: a UrdftoolError's message (a settings
        file in error: ``user_error``) or a traceback (a bug)
    notes: what the check said beside its findings (:attr:`urdftool.lint.options.FileResult.
        notes`: the settings files above it not read, another user's in no repository,
        :func:`urdftool.lint.settings.foreign`), in words: shown once each, as ``urdftool
        check`` says them
    """

    robot: str
    version: int | None
    by_path: dict[str, list[Shown]] = field(default_factory=dict)
    versions: dict[str, int | None] = field(default_factory=dict)
    record: object | None = None
    error: str | None = None
    user_error: bool = False
    seconds: float = 0.0
    notes: tuple = ()


def robots_for(path: str, kind: str | None) -> list[str]:
    """The robots to check for ``path`` (absolute) opened or saved, as ``urdftool check PATH``
    finds them (:func:`urdftool.lint.targets.expand`): the robot itself, the robots including
    a macro library, the robots checked with a companion file."""
    from urdftool.description.files import kind_of as found_at
    from urdftool.errors import UrdftoolError
    from urdftool.lint.settings import CheckRequest
    from urdftool.lint.targets import expand

    if kind not in ("robot", "companion"):
        return []
    if found_at(path) != "file":
        return [path] if kind == "robot" else []  # not saved yet: a robot's buffer alone
    try:
        return [os.path.abspath(file) for file in expand([path], CheckRequest()).files]
    except UrdftoolError:  # a settings file in error: checking the robot says so
        return [path] if kind == "robot" else []


def check_robot(robot: str, buffers: dict[str, Buffer], codec) -> Outcome:
    """Check ``robot`` and turn its findings into diagnostics per file; an exception becomes
    ``Outcome.error``. Every file the check reads (the robot, its includes, its companions) is
    read from its open buffer when it has one (:func:`urdftool.description.files.unsaved`)."""
    from urdftool.description.files import unsaved
    from urdftool.description.record import recording
    from urdftool.errors import UrdftoolError
    from urdftool.lint.runner import check_file

    buffer = buffers.get(robot)
    outcome = Outcome(robot, buffer.version if buffer else None)
    started = time.monotonic()
    served: set[str] = set()
    try:
        with recording() as outcome.record, \
                unsaved({path: open_.text for path, open_ in buffers.items()}) as served:
            result = check_file(robot)  # the record is kept when the check raises: fixing a
    except UrdftoolError as error:  # settings file it read re-checks it
        outcome.error, outcome.user_error = str(error), True
        return outcome
    except MemoryError:  # over the budget's memory: the pool makes it U018 on the robot
        raise
    except Exception:
        outcome.error = traceback.format_exc()
        return outcome
    finally:
        outcome.seconds = time.monotonic() - started
        outcome.versions = {path: buffers[path].version for path in served}
    outcome.notes = tuple(result.notes)
    sources = {}
    if result.robot is not None:
        sources = {os.path.abspath(name): data.decode("utf-8", "replace")
                   for name, data in result.robot.sources.items()}
    texts = _Texts(sources, buffers)
    outcome.by_path = diagnostics_by_path(result.findings, texts, codec, uri_of=texts.uri)
    outcome.by_path.setdefault(robot, [])
    return outcome


class _Texts:
    """The text of each file findings are located in: as the check read it (the robot's
    sources), else as open in the editor, else from disk."""

    def __init__(self, sources: dict[str, str], buffers: dict[str, Buffer]):
        self.sources, self.buffers = sources, buffers

    def __call__(self, path: str) -> str:
        if path in self.sources:
            return self.sources[path]
        if path in self.buffers:
            return self.buffers[path].text
        from urdftool.description.files import read_regular

        try:
            text = read_regular(path, 16 * 1024 * 1024).decode("utf-8", "replace")
        except (OSError, ValueError):
            text = ""
        self.sources[path] = text
        return text

    def uri(self, path: str) -> str:
        return self.buffers[path].uri if path in self.buffers else uri_of_path(path)


def uri_of_path(path: str) -> str:
    """The ``file:`` URI of ``path``: pygls's, and for a name holding bytes that are not UTF-8
    (which Python reads as lone surrogates, ``os.fsdecode``) those bytes percent-encoded, as RFC
    8089 writes any byte. pygls's ``from_fs_path`` raised UnicodeEncodeError on such a name: a
    robot whose controllers YAML or launch file was so named lost its whole check to U900."""
    try:
        return from_fs_path(path) or path
    except UnicodeError:
        from urllib.parse import quote

        return "file://" + quote(os.fsencode(path), safe="/")


def path_of_uri(uri: str) -> str | None:
    """The path a ``file:`` URI names (pygls's ``to_fs_path``), the name's own bytes where its
    percent-escapes are not UTF-8 (pygls made each such byte U+FFFD, a file that is not
    there): :func:`uri_of_path` read back. A URI no file can have (a NUL byte, ``%00``) names no
    path: every check reads every open buffer, so one such document broke them all."""
    path = to_fs_path(uri)
    if path and "\x00" in path:
        return None
    if path and "\ufffd" in path and "%" in uri:
        from urllib.parse import unquote_to_bytes, urlparse

        parsed = urlparse(uri)
        raw = unquote_to_bytes(parsed.path)
        if parsed.scheme == "file" and not parsed.netloc:
            try:
                raw.decode("utf-8")
            except UnicodeDecodeError:
                return os.fsdecode(raw)
    return path


def diagnostics_by_path(findings: list[Finding], text_of, codec, uri_of=None
                        ) -> dict[str, list[Shown]]:
    """Each finding as a diagnostic on the file it is located in and one at each macro call site
    that produced it (in the robot, or an intermediate macro), keyed by absolute path; each
    points at the others as related information. Findings about standard input are left out."""
    from urdftool.origin import rule_url

    uri_of = uri_of or uri_of_path
    by_path: dict[str, list[Shown]] = {}
    measured: dict[str, _Measured] = {}  # (each file's lines split and measured once)

    def measure(path: str) -> _Measured:
        if path not in measured:
            measured[path] = _Measured(text_of(path), codec)
        return measured[path]

    for finding in findings:
        places = [place for place in (finding.location, *finding.location.via)
                  if not place.file.startswith("<")]
        ranges = [_range(place, measure(os.path.abspath(place.file)), codec) for place in places]
        where = [types.Location(uri=uri_of(os.path.abspath(place.file)), range=span)
                 for place, span in zip(places, ranges)]
        seen = set()
        for index, (place, span) in enumerate(zip(places, ranges)):
            path = os.path.abspath(place.file)
            if (path, span.start.line) in seen:
                continue
            seen.add((path, span.start.line))
            message = finding.message if index == 0 else \
                f"{finding.message} (at {finding.location}, from this macro call)"
            related = [types.DiagnosticRelatedInformation(
                location=other, message="written here" if other_index == 0 else "macro call")
                for other_index, other in enumerate(where) if other_index != index]
            diagnostic = types.Diagnostic(
                range=span, message=message, severity=_SEVERITIES[finding.severity],
                code=finding.code, source=SOURCE,
                code_description=_code_description(rule_url(finding.code)),
                related_information=related or None)
            by_path.setdefault(path, []).append((diagnostic, finding))
    return by_path


def _range(place: Location, text: "str | _Measured", codec) -> types.Range:
    """The element's start on ``place.line`` (its column when known, else the first non-blank
    character) to the end of that line, in the client's position units. ``text``: the file's
    text, or its :class:`_Measured` (every finding of a file: the lines split once)."""
    measured = text if isinstance(text, _Measured) else _Measured(text, codec)
    lines = measured.lines
    number = min(max((place.line or 1) - 1, 0), len(lines) - 1)
    line = lines[number]
    if place.column is not None:
        start = min(place.column - 1, len(line))
    else:
        start = len(line) - len(line.lstrip())
    end, narrow = measured.length(number)
    start = start if narrow else measured.units(line[:start])
    return types.Range(start=types.Position(number, start if start < end else 0),
                       end=types.Position(number, end))


class _Measured:
    """A file's lines, split once, and each line's length in the client's position units,
    measured once, by the codec's own encoding (C's speed: pygls's counters look at each
    character in Python). Each finding's range split the whole file again and counted its line
    twice character by character: a one-line robot of 1,000 findings took 8.5 s to publish
    (0.5 s to check), a 5,000-line one of 5,000 findings 5.5 s."""

    def __init__(self, text: str, codec):
        self.lines = lines_of(text) or [""]
        encoding = getattr(codec, "encoding", None)
        encoding = str(getattr(encoding, "value", encoding) or "").lower()
        # (pygls counts an encoding it does not know as UTF-16)
        self.width = 1 if encoding == "utf-32" else 0 if encoding == "utf-8" else 2
        self._lengths: dict[int, tuple[int, bool]] = {}

    def units(self, text: str) -> int:
        """``text``'s length in the client's units (a lone surrogate one UTF-16 unit, three
        UTF-8 bytes, as pygls counts it)."""
        if self.width == 1:
            return len(text)
        size = len(text.encode("utf-8" if self.width == 0 else "utf-16-le", "surrogatepass"))
        return size if self.width == 0 else size // 2

    def length(self, number: int) -> tuple[int, bool]:
        """(line ``number``'s length in units, whether each of its characters is one unit)."""
        if number not in self._lengths:
            line = self.lines[number]
            units = self.units(line)
            self._lengths[number] = units, units == len(line)
        return self._lengths[number]


def _work(path: str, kind: str, targets: list[str] | None, also: list[str],
          buffers: dict[str, Buffer], codec, limits: "Limits",
          cancel: threading.Event) -> tuple[list[str], list[Outcome]]:
    """What a job does in its thread: which robots (``targets`` when known), then each robot,
    every step in a budgeted worker that ``cancel`` stops (then the robots not checked are
    left out: the job's result is dropped anyway)."""
    from urdftool.lint import engine  # noqa: F401  (the rules, imported once here: every
    # worker forked from this process starts with them)

    if targets is None:
        found = _budgeted(lambda: robots_for(path, kind), limits.budget, cancel)
        if isinstance(found, _Stopped):
            if found.stop.kind == "cancelled":
                return [], []
            found = [path] if kind == "robot" else []  # its check says what took so long
        targets = found
    outcomes = []
    for robot in dict.fromkeys([*targets, *also]):
        outcome = checked(robot, buffers, codec, limits, cancel)
        if outcome is None:
            break
        outcomes.append(outcome)
    return targets, outcomes


@dataclass(frozen=True)
class Limits:
    """The server's budget per robot, as ``urdftool check``'s: ``timeout`` [s] (None: none) and
    ``max_memory`` as --max-memory takes it (None: the settings' ``max-memory`` or 2G)."""

    timeout: float | None = DEFAULT_TIMEOUT
    max_memory: str | None = None

    @property
    def budget(self) -> Budget:
        """The budget of work that is not a robot's check (finding the robots to check)."""
        return Budget.of(self.timeout or 0, self.max_memory)

    def of(self, robot: str) -> Budget:
        """The budget checking ``robot`` gets: the memory its settings file allows, as
        ``urdftool check`` gives it (the settings' error is the check's to report)."""
        from urdftool.errors import UrdftoolError
        from urdftool.lint.settings import CheckRequest, for_file

        try:
            memory = for_file(robot, CheckRequest(max_memory=self.max_memory)).memory
        except UrdftoolError:
            return self.budget
        return Budget(self.timeout, memory)


@dataclass
class _Stopped:
    """Work the pool stopped, with its Stop."""

    stop: object  # urdftool.lint.pool.Stop


def _budgeted(work, budget: Budget, cancel: threading.Event):
    """``work()`` in a worker within ``budget``; a :class:`_Stopped` when it ended without a
    result (over the budget, cancelled, crashed)."""
    from urdftool.lint.pool import run_budgeted

    [result] = run_budgeted(1, lambda _: work(), budget, lambda _, stop: _Stopped(stop),
                            cancel=cancel)
    return result


def checked(robot: str, buffers: dict[str, Buffer], codec, limits: Limits,
            cancel: threading.Event) -> Outcome | None:
    """:func:`check_robot` in a worker within the robot's budget: over it, an Outcome with the
    U015 or U018 finding, located where the work was; None when ``cancel`` stopped it."""
    result = _budgeted(lambda: check_robot(robot, buffers, codec), limits.of(robot), cancel)
    if not isinstance(result, _Stopped):
        return result
    if result.stop.kind == "cancelled":
        return None
    from urdftool.lint.engine import stop_finding

    buffer = buffers.get(robot)
    outcome = Outcome(robot, buffer.version if buffer else None)
    texts = _Texts({}, buffers)
    finding = stop_finding(robot, result.stop, "checking")
    outcome.by_path = diagnostics_by_path([finding], texts, codec, uri_of=texts.uri)
    outcome.by_path.setdefault(robot, [])
    return outcome


# ---- on the event loop: documents, jobs, publishing -------------------------------------------

@dataclass
class _Published:
    """A robot's last published check: its ticket (later checks have larger ones) and its
    diagnostics per file."""

    ticket: int
    by_path: dict[str, list[Shown]]
    versions: dict[str, int | None] = field(default_factory=dict)  # of the buffers it read


class UrdftoolServer(LanguageServer):
    """The document state, the debounced jobs and what each robot published."""

    def __init__(self, debounce: float = DEBOUNCE, limits: Limits = Limits(),
                 jobs: int | None = None):
        from urdftool import __version__

        super().__init__("urdftool", __version__)
        self.debounce, self.limits = debounce, limits
        self.checks = ThreadPoolExecutor(max_workers=jobs or _jobs(),
                                         thread_name_prefix="urdftool-check")
        self.running: set[threading.Event] = set()  # the cancel switch of each job running
        self.open: dict[str, str] = {}  # path -> the URI whose buffer a check reads
        # path -> every URI open naming it, in order (one file, several URIs: `..`, `.`, `//`)
        self.aliases: dict[str, dict[str, None]] = {}
        self.targets: dict[str, list[str]] = {}  # document path -> the robots it means
        self.published: dict[str, _Published] = {}  # robot path -> its diagnostics
        self.records: dict = {}  # robot path -> the record of its last check
        self.pending: dict[str, asyncio.Task] = {}
        self.tickets = itertools.count(1)
        self.errors_shown: set[str] = set()
        self.notes_shown: set[str] = set()  # the checks' notes (settings files not read), said

    # -- documents

    def path_of(self, uri: str) -> str | None:
        path = path_of_uri(uri)
        return os.path.abspath(path) if path else None

    def paths_of(self, uris):
        """:meth:`path_of` of each of ``uris``, in order, each folder's URI parsed once: a URI
        whose last part is a plain name (letters, digits, ``.``, ``_``, ``-``; not ``.`` or
        ``..``) after a folder's URI without a query, fragment, parameters or white space is
        that folder's path and the name, as :meth:`path_of` would say (parsing 300,000 URIs
        one by one cost the server's loop seconds)."""
        folders = {}
        for uri in uris:
            head, _, name = uri.rpartition("/")
            if not (_PLAIN_NAME.fullmatch(name) and _PLAIN_FOLDER_URI.fullmatch(head)):
                yield self.path_of(uri)
                continue
            folder = folders.get(head, False)
            if folder is False:
                folder = folders[head] = self.path_of(head + "/")
            yield os.path.join(folder, name) if folder else None

    def uri_of(self, path: str) -> str:
        return self.open.get(path) or uri_of_path(path)

    def opened(self, uri: str) -> None:
        adopt(self.workspace, uri)
        path = self.path_of(uri)
        if path and kind_of(path) in ("robot", "companion"):
            self.aliases.setdefault(path, {})[uri] = None
            self.open[path] = uri
            self.schedule(path, 0.0, retarget=True)

    def changed(self, uri: str) -> None:
        """An edit, not saved: what the document means (a robot, the robots including a macro
        file or checked with a companion) and the robots whose last check read it are checked
        again, each reading every open document from its buffer."""
        path = self.path_of(uri)
        if path in self.open:
            if uri in self.aliases.get(path, ()):
                self.open[path] = uri  # the buffer edited last is the file's, to a check
            self.schedule(path, self.debounce)

    def saved(self, uri: str) -> None:
        """A document saved: a robot or companion open is checked again, what it means found
        again; any other file (a settings file) as a file changed outside the editor, for the
        robots it concerns, one job each: saves of robot files never opened each queued a
        check, and the documents open waited behind any number of them."""
        path = self.path_of(uri)
        if path in self.open:
            self.schedule(path, 0.0, retarget=True)
        else:
            self.watched([uri])

    def watched(self, uris: list[str]) -> None:
        """Files created, changed or removed outside the editor: the robots whose record they
        concern are checked again (a document open in the editor is left to its own events).
        Each robot concerned is one job, keyed by the robot: a checkout that changes 300,000
        files queued a check of the same robots for each of them, and the server answered
        nothing for minutes."""
        robots, checked = {}, sum(record is not None for record in self.records.values())
        for path in self.paths_of(dict.fromkeys(uris)):
            if len(robots) == checked:
                break  # every robot checked is concerned already: the rest can add none
            if path and path not in self.open:
                robots.update(dict.fromkeys(self.concerned(path)))
        for robot in robots:
            if not (robot in self.open and robot in self.pending):  # its own job reads it
                self.schedule(robot, self.debounce, concerned_only=True)

    def concerned(self, path: str) -> list[str]:
        """The robots checked so far whose last check a change at ``path`` may change: their
        record says the check read, searched, probed or followed it (see
        :meth:`~urdftool.description.record.Record.concerns`)."""
        def file() -> bool:  # (asked only where it matters: Record.concerns)
            from urdftool.description.files import kind_of as found_at

            return found_at(path, follow=False) == "file"

        return [robot for robot, record in self.records.items()
                if record is not None and record.concerns(path, file)]

    def closed(self, uri: str) -> None:
        """Forget the document; what its robot check published is cleared. The robots whose
        last check read its buffer are checked again: closed unsaved, it is the disk's again."""
        path = self.path_of(uri)
        if not path:
            return
        uris = self.aliases.get(path, {})
        for alias in [alias for alias in uris if unquote(alias) == unquote(uri)]:
            del uris[alias]  # (pygls keeps one document for the URIs that unquote alike)
            if alias != uri or path not in self.open:
                continue
            self.text_document_publish_diagnostics(types.PublishDiagnosticsParams(
                uri=alias, diagnostics=[]))
        if uris and path in self.open:  # still open by another URI: its buffer is checked
            self.open[path] = next(reversed(uris))
            self.schedule(path, 0.0, retarget=True)
            return
        self.aliases.pop(path, None)
        self.open.pop(path, None)
        task = self.pending.pop(path, None)
        if task:
            task.cancel()
        self.targets.pop(path, None)
        self.records.pop(path, None)
        previous = self.published.pop(path, None)
        for shown in previous.by_path if previous else ():
            self._send(shown)
        if any(path in published.versions for published in self.published.values()):
            self.schedule(path, 0.0, concerned_only=True)

    def watch_files(self) -> None:
        """Ask the client to report every file of the workspace created, changed or removed
        (``workspace/didChangeWatchedFiles``), when it can register that dynamically: a
        record names meshes, package manifests and settings files as well as robots."""
        capabilities = self.client_capabilities.workspace
        watched = capabilities.did_change_watched_files if capabilities else None
        if not (watched and watched.dynamic_registration):
            return
        self.client_register_capability(types.RegistrationParams(registrations=[
            types.Registration(
                id="urdftool-watch", method=types.WORKSPACE_DID_CHANGE_WATCHED_FILES,
                register_options=types.DidChangeWatchedFilesRegistrationOptions(
                    watchers=[types.FileSystemWatcher(glob_pattern="**/*")]))]))

    def _buffers(self) -> dict[str, Buffer]:
        buffers = {}
        for path, uri in self.open.items():
            document = self.workspace.get_text_document(uri)
            buffers[path] = Buffer(uri, document.source, document.version)
        return buffers

    # -- jobs

    def schedule(self, path: str, delay: float, retarget: bool = False,
                 concerned_only: bool = False) -> None:
        """Check what ``path`` means (unless ``concerned_only``), and the robots it concerns,
        after ``delay`` [s]; a job already waiting or running for it is cancelled (its result,
        if it comes, is dropped)."""
        kind = None if concerned_only else kind_of(path)
        task = self.pending.pop(path, None)
        if task:
            task.cancel()
        self.pending[path] = asyncio.ensure_future(self._job(path, kind, delay, retarget))

    async def _job(self, path: str, kind: str | None, delay: float, retarget: bool) -> None:
        try:
            await asyncio.sleep(delay)
            ticket = next(self.tickets)
            buffers = self._buffers()
            targets = None if retarget or kind is None else self.targets.get(path)
            also = self.concerned(path)
            if kind is None and not also:
                return  # a file no robot checked so far read, searched or followed
            cancel = threading.Event()
            self.running.add(cancel)
            try:
                targets, outcomes = await asyncio.get_running_loop().run_in_executor(
                    self.checks, _work, path, kind, targets, also, buffers,
                    self.workspace.position_codec, self.limits, cancel)
            except asyncio.CancelledError:  # a newer version, or closed: its worker is killed
                cancel.set()
                raise
            finally:
                self.running.discard(cancel)
            if kind is not None:
                self.targets[path] = targets
            for outcome in outcomes:
                self._publish(outcome, ticket)
        except Exception:  # a bug here: logged, and the server goes on
            self._log(types.MessageType.Error,
                      f"checking {display_path(path)} failed:\n{traceback.format_exc()}")
        finally:
            if self.pending.get(path) is asyncio.current_task():
                del self.pending[path]

    # -- publishing

    def _publish(self, outcome: Outcome, ticket: int) -> None:
        robot = outcome.robot
        shown = display_path(robot)
        if outcome.user_error and outcome.record is not None:
            self.records[robot] = outcome.record  # what it read before it stopped
        if outcome.error is not None:
            what = "cannot check" if outcome.user_error else "internal error checking"
            self._log(types.MessageType.Error, f"{what} {shown}: {outcome.error}")
            headline = outcome.error.strip().splitlines()[-1] if outcome.error.strip() else ""
            if headline not in self.errors_shown:
                from urdftool.report.escape import notification

                self.errors_shown.add(headline)
                self.window_show_message(types.ShowMessageParams(
                    type=types.MessageType.Error,
                    message=notification(f"urdftool: {what} {shown}: {headline}")))
            return
        for why in outcome.notes:  # once each, as the check says it on every run
            if why not in self.notes_shown:
                self.notes_shown.add(why)
                self._log(types.MessageType.Warning, f"urdftool: {why}")
                from urdftool.report.escape import notification

                self.window_show_message(types.ShowMessageParams(  # (a path in it: escaped
                    # as every pop-up is, its links never live)
                    type=types.MessageType.Warning, message=notification(f"urdftool: {why}")))
        stale = self._stale(outcome)
        if stale:  # it read an older version: the newer one's job publishes; a buffer closed
            if robot not in stale and any(path not in self.open for path in stale):
                self.schedule(robot, 0.0)  # since: the robot is checked again from the disk
            return
        previous = self.published.get(robot)
        if previous is not None and previous.ticket > ticket:
            return
        self.published[robot] = _Published(ticket, outcome.by_path, outcome.versions)
        self.records[robot] = outcome.record
        for path in {*outcome.by_path, *(previous.by_path if previous else ())}:
            self._send(path)
        count = sum(len(v) for v in outcome.by_path.values())
        version = "" if outcome.version is None else f" (version {outcome.version})"
        self._log(types.MessageType.Log, f"checked {shown}{version}: {count} diagnostic(s) "
                                         f"in {outcome.seconds:.2f} s")  # after: it is done

    def _stale(self, outcome: Outcome) -> list[str]:
        """The open documents ``outcome``'s check read whose buffer has changed since, or
        closed (then the disk holds what a check reads); the robot's own document when it
        was opened or closed since."""
        buffers = self._buffers()
        read = dict(outcome.versions)
        if outcome.robot in self.open or outcome.version is not None:
            read[outcome.robot] = outcome.version
        return [path for path, version in read.items()
                if path not in buffers or buffers[path].version != version]

    def _send(self, path: str) -> None:
        """Publish on ``path`` what every robot's last check found there, with the version of
        its buffer when every diagnostic there came from that version."""
        seen, diagnostics, versions = set(), [], set()
        for published in self.published.values():
            shown = published.by_path.get(path, ())
            if shown:
                versions.add(published.versions.get(path))
            for diagnostic, _ in shown:
                key = (diagnostic.range.start.line, diagnostic.range.start.character,
                       diagnostic.code, diagnostic.message)
                if key not in seen:
                    seen.add(key)
                    diagnostics.append(diagnostic)
        buffer = self._buffers().get(path) if path in self.open else None
        version = buffer.version if buffer is not None and versions == {buffer.version} \
            else None
        read = self.uri_of(path)
        for uri in self.aliases.get(path) or (read,):  # every URI the file is open by
            self.text_document_publish_diagnostics(types.PublishDiagnosticsParams(
                uri=uri, diagnostics=diagnostics, version=version if uri == read else None))

    def shutdown(self) -> None:
        """Stop every check (its worker is killed, its thread returns), then the server."""
        for cancel in list(self.running):
            cancel.set()
        self.checks.shutdown(wait=False, cancel_futures=True)
        super().shutdown()

    def _log(self, kind: types.MessageType, message: str) -> None:
        from urdftool.report.escape import lines

        # the log file (and standard error, without one) is terminal text; the client's copy
        # is JSON and stays exact
        logger.log(logging.ERROR if kind == types.MessageType.Error else logging.INFO,
                   lines(message))
        self.window_log_message(types.LogMessageParams(type=kind, message=message))

    def finding_for(self, path: str, diagnostic: types.Diagnostic) -> Finding | None:
        """The finding a diagnostic the editor sends back (code actions) shows."""
        for published in self.published.values():
            for shown, finding in published.by_path.get(path, ()):
                if (shown.range.start.line, shown.code, shown.message) == \
                        (diagnostic.range.start.line, diagnostic.code, diagnostic.message):
                    return finding
        return None

    # -- hover and code actions

    def document(self, uri: str) -> TextDocument | None:
        """The document open at ``uri``, None when the client has not opened it (pygls would
        read it from disk, or fail to: its FileNotFoundError was the client's internal error)."""
        held = {unquote(alias) for alias in self.aliases.get(self.path_of(uri) or "", ())}
        return self.workspace.get_text_document(uri) if unquote(uri) in held else None

    def hover(self, params: types.HoverParams) -> types.Hover | None:
        document = self.document(params.text_document.uri)
        if document is None:
            return None
        word = document.word_at_position(params.position, *_WORD)
        line = document.lines[params.position.line] if params.position.line < len(
            document.lines) else ""
        found = rule_named(word, in_comment="urdftool:" in line)
        if found is None:
            return None
        return types.Hover(contents=types.MarkupContent(kind=types.MarkupKind.Markdown,
                                                        value=rule_markdown(found)))

    def code_actions(self, params: types.CodeActionParams) -> list[types.CodeAction] | None:
        path = self.path_of(params.text_document.uri)
        document = self.document(params.text_document.uri)
        if document is None or kind_of(path) != "robot":
            return None
        lines = list(document.lines)
        actions = []
        for diagnostic in params.context.diagnostics:
            if diagnostic.source != SOURCE or not isinstance(diagnostic.code, str):
                continue
            finding = self.finding_for(path, diagnostic)
            if finding is None:  # not one this server published: its code is no rule's (any
                continue  # extension may name its diagnostics "urdftool": a code of
                # "U204 --><script/>" was written into the robot as a suppression comment)
            for provider in ACTION_PROVIDERS:
                actions.extend(provider(params.text_document.uri, lines, diagnostic, finding,
                                        self.workspace.position_codec))
        if actions:
            inside = starts_inside_markup(lines)
            actions = [action for action in actions if not any(
                edit.range.start.character == 0 and edit.range.start.line in inside
                for edits in action.edit.changes.values() for edit in edits)]
        return actions or None


def rule_named(word: str, in_comment: bool = False):
    """The rule a word names: a code anywhere, a rule name in an ``urdftool:`` comment."""
    from urdftool.lint.rules import CATALOGUE

    if _CODE.fullmatch(word) and word.upper() in CATALOGUE:
        return CATALOGUE.get(word.upper())
    if in_comment and "-" in word:
        return next((rule for rule in CATALOGUE if rule.name == word), None)
    return None


def _code_description(url: str | None):
    """The link to a rule's page (urdftool.origin), None when nothing says where it is."""
    return None if url is None else types.CodeDescription(href=url)


def rule_markdown(rule) -> str:
    from urdftool.origin import rule_url

    url = rule_url(rule.code)
    link = f"\n\n[{rule.code} in the documentation]({url})" if url else ""
    return (f"**{rule.code} {rule.name}** ({rule.severity.value}, {rule.family})\n\n"
            f"{rule.doc or rule.summary}{link}")


# ---- code actions: a provider maps (document, diagnostic, finding) to code actions ------------

def _line_ending(lines: list[str]) -> str:
    return "\r\n" if lines and lines[0].endswith("\r\n") else "\n"


def _title(diagnostic: types.Diagnostic, finding: Finding | None) -> str:
    return f"{diagnostic.code} ({finding.name})" if finding else str(diagnostic.code)


def _action(title: str, uri: str, diagnostic: types.Diagnostic, edit: types.TextEdit,
            preferred: bool = False) -> types.CodeAction:
    return types.CodeAction(title=title, kind=types.CodeActionKind.QuickFix,
                            diagnostics=[diagnostic], is_preferred=preferred or None,
                            edit=types.WorkspaceEdit(changes={uri: [edit]}))


def suppress_on_line(uri: str, lines: list[str], diagnostic: types.Diagnostic,
                     finding: Finding | None, codec) -> list[types.CodeAction]:
    """``<!-- urdftool: ignore CODE -->`` on the line above the element, indented as it is; the
    code added to such a comment when the line above already is one."""
    code, number = str(diagnostic.code), diagnostic.range.start.line
    line = lines[number] if number < len(lines) else ""
    title = f"Ignore {_title(diagnostic, finding)} here"
    above = _IGNORE_LINE.match(lines[number - 1].rstrip("\r\n")) if 0 < number <= len(lines) \
        else None
    if above:
        codes = above.group(2).rstrip()
        if code in re.split(r"[\s,]+", codes):
            return []
        previous = lines[number - 1].rstrip("\r\n")
        edit = types.TextEdit(
            range=types.Range(start=types.Position(number - 1, 0),
                              end=types.Position(number - 1, codec.client_num_units(previous))),
            new_text=f"{above.group(1)}<!-- urdftool: ignore {codes}, {code} -->")
        return [_action(title, uri, diagnostic, edit)]
    indent = line[:len(line) - len(line.lstrip())]
    edit = types.TextEdit(range=types.Range(start=types.Position(number, 0),
                                            end=types.Position(number, 0)),
                          new_text=f"{indent}<!-- urdftool: ignore {code} -->{_line_ending(lines)}")
    return [_action(title, uri, diagnostic, edit, preferred=True)]


def suppress_in_file(uri: str, lines: list[str], diagnostic: types.Diagnostic,
                     finding: Finding | None, codec) -> list[types.CodeAction]:
    """``<!-- urdftool: ignore-file CODE -->`` at the top (after the XML declaration)."""
    number = 1 if lines and lines[0].lstrip().startswith("<?xml") else 0
    edit = types.TextEdit(range=types.Range(start=types.Position(number, 0),
                                            end=types.Position(number, 0)),
                          new_text=f"<!-- urdftool: ignore-file {diagnostic.code} -->"
                                   f"{_line_ending(lines)}")
    return [_action(f"Ignore {_title(diagnostic, finding)} in this file", uri, diagnostic, edit)]


# Each provider: (uri, document lines, diagnostic, finding or None, position codec) -> actions.
# An action whose edit writes at the start of a line that starts inside markup is dropped
# (:func:`starts_inside_markup`, in UrdftoolServer.code_actions: the one guard of every edit).
ACTION_PROVIDERS = (suppress_on_line, suppress_in_file)

# What a comment cannot be written inside: a tag (its quoted values may hold '>'), a comment, a
# CDATA section, a processing instruction or declaration, a document type declaration
_MARKUP = re.compile(r"""<!--.*?(?:-->|\Z)|<!\[CDATA\[.*?(?:\]\]>|\Z)|<\?.*?(?:\?>|\Z)"""
                     r"""|<!?(?:"[^"]*(?:"|\Z)|'[^']*(?:'|\Z)|[^>"'])*+(?:>|\Z)""", re.S)


def starts_inside_markup(lines: list[str]) -> set[int]:
    """The numbers of the document's lines (its lines as the server keeps them, ends kept)
    that start inside a tag, comment, CDATA section or processing instruction: a comment
    written at such a line's start breaks the document (an element whose start tag begins on
    the line an attribute value of the tag before it ends on; a tag written across lines)."""
    text = "".join(lines)
    starts, at = [], 0
    for line in lines:
        starts.append(at)
        at += len(line)
    inside: set[int] = set()
    import bisect

    for match in _MARKUP.finditer(text):
        first = bisect.bisect_right(starts, match.start())  # the first line starting after '<'
        last = bisect.bisect_left(starts, match.end())  # lines starting at or past the end
        inside.update(range(first, last))
    return inside


# ---- the server -------------------------------------------------------------------------------

class Document(TextDocument):
    """An open document whose lines are the protocol's (and XML's, and every Location's): ended
    by CR LF, LF or CR only (:func:`urdftool.diagnostics.lines_of`). pygls splits them with
    :meth:`str.splitlines`, which also ends a line at NEL, LINE SEPARATOR, FF and the like,
    which XML holds raw: an editor's incremental change after one was applied to another line
    (the buffer checked was text the editor did not hold), and hovers and code actions read
    the wrong line.

    It keeps its own text and lines and uses only pygls's public names (the constructor,
    ``apply_change``, ``source``, ``lines``, ``position_codec``; the workspace's
    ``text_documents`` and ``get_text_document``, :func:`adopt`): overriding pygls's private
    ``_apply_incremental_change`` and ``Workspace._create_text_document`` would have stopped
    working without a word when a release renamed them (pygls's own splitting back)."""

    def __init__(self, uri: str, source: str | None = None, **kwargs):
        super().__init__(uri, **kwargs)  # (pygls's copy of the text: none, never read)
        self._text, self._lines, self._joined = source or "", None, True

    @property
    def source(self) -> str:
        if not self._joined:
            self._text, self._joined = "".join(self._lines), True
        return self._text

    @property
    def lines(self):
        return tuple(self._line_list())

    def _line_list(self) -> list[str]:
        if self._lines is None:
            self._lines = lines_of(self.source, keepends=True)
        return self._lines

    def apply_change(self, change) -> None:
        """The client's ``change``: a range's text replaced (:meth:`_change_lines`), or the
        whole document's."""
        if isinstance(change, types.TextDocumentContentChangePartial):
            self._change_lines(change)
        else:
            self._text, self._lines, self._joined = change.text, None, True

    def _change_lines(self, change) -> None:
        """The lines the change spans replaced by the change's text split again (with the line
        before, when it ends with CR: a change starting with LF makes it CR LF): a change costs
        what it spans, not the document's length in Python (pygls rebuilt every line for each
        change of a didChange: 2,000 edits of a 20,000-line robot, a replace-all, held the
        server's loop 5 s). A position past a line's end is its end, past the last line the
        document's end, as the protocol says."""
        lines = self._line_list()
        lines.append("")  # the end of the document: after its last line end
        (first, head), (last, tail) = sorted((self._at(lines, change.range.start),
                                              self._at(lines, change.range.end)))
        text = lines[first][:head] + change.text + lines[last][tail:]
        if first and not lines[first - 1].endswith("\n"):  # CR, or no line end (the end)
            first -= 1
            text = lines[first] + text
        lines[first:last + 1] = lines_of(text, keepends=True)
        if lines and not lines[-1]:
            lines.pop()  # the end's, untouched
        self._joined = False

    def _at(self, lines: list[str], position: types.Position) -> tuple[int, int]:
        """(line, character) of a client's ``position`` in ``lines`` (whose last is the empty
        one after the document's end)."""
        if position.line >= len(lines) - 1:
            return len(lines) - 1, 0
        line = lines[position.line]
        body = line[:-2] if line.endswith("\r\n") else line[:-1] if line.endswith(
            ("\r", "\n")) else line
        if position.character >= self.position_codec.client_num_units(body):
            return position.line, len(body)
        return position.line, self.position_codec.position_from_client_units(
            [body], types.Position(0, position.character)).character


def adopt(workspace, uri: str) -> None:
    """Make the document the client just opened at ``uri`` (put into ``workspace`` by pygls's
    own handler, which runs before ours) a :class:`Document` holding its text, through pygls's
    public names."""
    made = workspace.get_text_document(uri)
    if isinstance(made, Document):
        return
    documents = workspace.text_documents
    for key, held in documents.items():
        if held is made:
            documents[key] = Document(made.uri, made.source, version=made.version,
                                      language_id=made.language_id,
                                      position_codec=made.position_codec)
            return


_DOCUMENT_EVENTS = {types.TEXT_DOCUMENT_DID_OPEN: "opened",
                    types.TEXT_DOCUMENT_DID_CHANGE: "changed",
                    types.TEXT_DOCUMENT_DID_SAVE: "saved",
                    types.TEXT_DOCUMENT_DID_CLOSE: "closed"}


def _on_document(event: str):
    """A notification handler calling ``UrdftoolServer.<event>(uri)``."""

    def handler(ls: UrdftoolServer, params) -> None:
        getattr(ls, event)(params.text_document.uri)

    return handler


def _jobs() -> int:
    from urdftool.lint.pool import default_jobs

    return max(JOBS, min(4, default_jobs()))


def make_server(debounce: float = DEBOUNCE, limits: Limits = Limits()) -> UrdftoolServer:
    server = UrdftoolServer(debounce, limits)
    for method, event in _DOCUMENT_EVENTS.items():
        server.feature(method)(_on_document(event))

    @server.feature(types.INITIALIZED)
    def initialized(ls: UrdftoolServer, params: types.InitializedParams):
        ls.watch_files()

    @server.feature(types.WORKSPACE_DID_CHANGE_WATCHED_FILES)
    def watched(ls: UrdftoolServer, params: types.DidChangeWatchedFilesParams):
        ls.watched([change.uri for change in params.changes])

    @server.feature(types.TEXT_DOCUMENT_HOVER)
    def hover(ls: UrdftoolServer, params: types.HoverParams):
        return ls.hover(params)

    @server.feature(types.TEXT_DOCUMENT_CODE_ACTION,
                    types.CodeActionOptions(code_action_kinds=[types.CodeActionKind.QuickFix]))
    def code_action(ls: UrdftoolServer, params: types.CodeActionParams):
        return ls.code_actions(params)

    return server


MAX_MESSAGE = 128 * 2**20  # [bytes] the largest message read: a 16 MiB robot (the file-size
# limit) with every character escaped as JSON's \uXXXX, and the rest of its didOpen
MAX_HEADER_LINE = 4096  # [bytes] a header line (LSP has two: Content-Length, Content-Type)
MAX_HEADERS = 32  # header lines of one message
_CONTENT_LENGTH = re.compile(rb"Content-Length: ([0-9]+)\r\n")  # pygls.io_'s own pattern
_HEADER = re.compile(rb"[!#-'*+.0-9A-Z^-z|~-]+: [^\r\n]*\r\n")  # RFC 9110's field: a token


class PairedOutput:
    """The stream the server's messages are written to, each through
    :func:`urdftool.report.json_output.paired`: pygls writes them with ``json.dumps``, where a
    name holding a byte that is not UTF-8 (a launch file's, quoted by U620) was an unpaired
    ``\\udcff``, which strict readers refuse (JSON's one function, as every report's)."""

    def __init__(self, stream):
        self.stream = stream

    def write(self, data: bytes):
        from urdftool.report.json_output import paired

        return self.stream.write(paired(data))

    def __getattr__(self, name):
        return getattr(self.stream, name)


class Transport:
    """The protocol's input as pygls reads it (:func:`pygls.io_.run_async`: ``readline`` for
    each header line, ``read(Content-Length)`` for the body after the blank line), held to the
    framing LSP defines before pygls sees a byte: a header line is read only up to
    :data:`MAX_HEADER_LINE` bytes, a body only up to :data:`MAX_MESSAGE`, and a line that is
    not ``Name: value\\r\\n``, a ``Content-Length`` that is not pygls's digits (or repeated,
    zero or over the limit) or a message without one ends the input: pygls would otherwise
    allocate the length it was told (100 GB: ``MemoryError``), read a line of any length, or
    skip a header it cannot read and take the body for headers, answering nothing from then
    on. The framing lost, nothing after it can be trusted to be a message: the input ends
    (pygls returns, the server shuts down), :attr:`broken` says why, once, and the server ends
    with status 1."""

    def __init__(self, stream, limit: int = MAX_MESSAGE):
        self.stream, self.limit = stream, limit
        self.length: int | None = None  # of the message whose headers are being read
        self.headers = 0
        self.broken: str | None = None

    def _break(self, why: str) -> bytes:
        from urdftool.report.escape import text

        if self.broken is None:
            self.broken = text(why)
        return b""

    def readline(self) -> bytes:
        if self.broken:
            return b""
        line = self.stream.readline(MAX_HEADER_LINE + 1)
        if not line:  # the end of the input
            return line
        if line == b"\r\n":
            return line if self.length else self._break("a message without a Content-Length")
        if not _HEADER.fullmatch(line):
            more = " (cut)" if len(line) > MAX_HEADER_LINE else ""
            return self._break(f"not a header line{more}: {line[:80]!r}")
        self.headers += 1
        if self.headers > MAX_HEADERS:
            return self._break(f"more than {MAX_HEADERS} header lines")
        if line.split(b":", 1)[0].lower() == b"content-length":
            match = _CONTENT_LENGTH.fullmatch(line)
            if not match or self.length is not None:
                return self._break(f"a malformed or repeated Content-Length: {line[:80]!r}")
            self.length = int(match.group(1))
            if not 0 < self.length <= self.limit:
                return self._break(f"a message of {self.length} bytes (at most {self.limit})")
        return line

    def read(self, size: int = -1) -> bytes:
        if self.broken or size != self.length:  # pygls reads the length its pattern read
            return self._break(f"a body read of {size} bytes, not {self.length}")
        self.length, self.headers = None, 0
        body = self.stream.read(size)
        if len(body) < size:  # the input ended inside the message: pygls parsed what came
            return self._break(f"a message cut short: {len(body)} of its {size} bytes "
                               "before the input ended")
        return body


_TRACEBACK = re.compile(r"(?<![\s|+])[\s|+]*?(?:Exception Group )?Traceback \(most recent call last\):")
_EXCEPTION_LINE = re.compile(r"[A-Za-z_][\w.]*(?::|$)")  # "TypeError: ...", not "File ..."
MAX_LOG_RECORD = 2000  # [characters] of a record's message


class OneLine(logging.Formatter):
    """Every record of the server's log (the log file, standard error) is one line of terminal
    text (:func:`urdftool.report.escape.text`): a traceback (pygls logs one for each message it
    cannot read, with the client's words in it, and formats some into its message) is its last
    line, the exception, and where it was raised; a message is cut at :data:`MAX_LOG_RECORD`
    characters. What a client sends cannot write lines of its own into the log, nor flood it
    with a traceback per malformed message."""

    def format(self, record: logging.LogRecord) -> str:
        from urdftool.errors import described
        from urdftool.report.escape import text

        message = _without_traceback(record.getMessage())
        error = record.exc_info[1] if record.exc_info else None
        if error is not None:
            message += f": {described(error)}{_raised_at(error)}"
        if len(message) > MAX_LOG_RECORD:
            message = f"{message[:MAX_LOG_RECORD]}... ({len(message) - MAX_LOG_RECORD} more)"
        record.message = message
        if self.usesTime():
            record.asctime = self.formatTime(record, self.datefmt)
        return text(self.formatMessage(record))


def _without_traceback(message: str) -> str:
    """``message`` with a traceback formatted into it (pygls's "Unable to deserialize message")
    replaced by its last exception line."""
    at = _TRACEBACK.search(message)
    if not at:
        return message
    last = next((line.lstrip(" |+") for line in reversed(message[at.end():].splitlines())
                 if _EXCEPTION_LINE.match(line.lstrip(" |+"))), "")
    return message[:at.start()] + (f": {last}" if last else "")


def _raised_at(error: BaseException) -> str:
    import traceback

    frames = traceback.extract_tb(error.__traceback__)
    return f" (at {os.path.basename(frames[-1].filename)}:{frames[-1].lineno})" if frames else ""


class _Log(logging.StreamHandler):
    """The log file (:func:`urdftool.description.files.append_stream`: judged as any output
    file, a named pipe without a reader refused): one that stops being written (a full disk)
    says so once, and the server then ends with status 2 (:func:`serve`), not a traceback per
    message."""

    failed = False

    def __init__(self, path: str):
        import io

        from urdftool.description.files import append_stream

        self.baseFilename = path
        super().__init__(io.TextIOWrapper(append_stream(path), encoding="utf-8",
                                          errors="backslashreplace", write_through=True))

    def handleError(self, record) -> None:
        if not self.failed:
            from urdftool.streams import say

            self.failed = True
            say(f"urdftool: error: cannot write '{self.baseFilename}': {sys.exc_info()[1]}")


def _quiet_once_output_failed(failed) -> None:
    """Once the protocol's output failed (``failed()``), pygls's tracebacks of each message
    it could not send (thousands, as it reports its errors by sending them) and the thread
    pool's of its callbacks say nothing more than the one line :func:`urdftool.streams.end`
    says: left out, of the log file too. Without a log file, warnings go to standard error as
    Python's last resort printed them."""
    handlers = logging.getLogger().handlers
    if not handlers:
        handler = logging.StreamHandler()
        handler.setFormatter(OneLine("urdftool server: %(levelname)s: %(message)s"))
        handler.setLevel(logging.WARNING)
        logging.getLogger().addHandler(handler)
        handlers = [handler]
    for handler in handlers:
        handler.addFilter(lambda record: not failed())


def serve(log_file: str | None = None, limits: Limits = Limits()) -> int:
    """Run the server on standard input and output until the editor ends it; ``limits``: the
    budget of each robot's check. Its exit status: 2 when the log file could not be written."""
    if log_file:
        from urdftool.errors import UsageError

        try:
            handler = _Log(log_file)
            handler.setFormatter(OneLine("%(asctime)s %(name)s %(levelname)s %(message)s"))
            logging.getLogger().addHandler(handler)
            logging.getLogger().setLevel(logging.DEBUG)
        except OSError as error:
            raise UsageError(f"cannot write '{log_file}': {error.strerror}") from None
    # The protocol writes to its own copy of standard output; anything else written there (a
    # library's print, C code) goes to standard error instead of corrupting the messages.
    from urdftool import streams

    protocol_out = streams.binary_output(os.dup(sys.stdout.fileno()))  # ends as stdout does
    _quiet_once_output_failed(streams.failed)
    os.dup2(sys.stderr.fileno(), sys.stdout.fileno())
    sys.stdout = sys.stderr
    # A worker (forked by run_budgeted) closes sys.stdin as it starts: not the protocol's, whose
    # lock pygls's reader thread holds while it waits for a message (the worker would wait for
    # it forever). ``protocol_in`` keeps the original open; the server reads no other input.
    protocol_in, sys.stdin = sys.stdin, io.StringIO()
    transport = Transport(protocol_in.buffer)
    server = make_server(limits=limits)
    server.start_io(transport, PairedOutput(protocol_out))
    if any(getattr(h, "failed", False) for h in logging.getLogger().handlers):
        return 2
    if transport.broken:  # in the log (standard error without one), and on standard error
        logger.error("the client's input: %s: the server stopped", transport.broken)
        if log_file:
            streams.say(f"urdftool: error: the client's input: {transport.broken}")
        return 1
    if not server.protocol._shutdown:  # LSP: exit without shutdown is status 1 (pygls's
        # sys.exit(1) in its exit handler was lost in the loop: 0), and so is an input that
        # ended with no shutdown (the editor gone)
        logger.warning("the session ended without a shutdown request")
        return 1
    return 0
