"""What the engine takes and gives: the options a file is checked with and its result, apart
from the rules themselves, so that settings, the result cache and the runner can handle them
without importing every rule (a re-run served from the cache never does)."""

from __future__ import annotations

import functools
from collections.abc import Callable
from pathlib import Path

from urdftool.description.files import DEFAULT_MAX_FILE_SIZE
from urdftool.description.inputs import CompanionPaths, MeshLimits
from urdftool.diagnostics import Finding, Severity
from urdftool.records import Frozen, NEW, Record


class Selection(Frozen):
    """Which rules run: codes, code prefixes (``U2``) or names (``inverted-limits``).

    targets: the simulators asked for (``check --target``, ``targets`` in the settings), as
        ``NAME`` or ``NAME@VERSION``: a portability rule (U92x-U98x) runs only for its own
        target, and ``select``/``ignore`` narrow them as any other rule
    """

    select: tuple[str, ...]
    ignore: tuple[str, ...]
    targets: tuple[str, ...]

    __slots__ = ("select", "ignore", "targets")

    def __init__(self, select: tuple[str, ...] = (), ignore: tuple[str, ...] = (),
                 targets: tuple[str, ...] = ()) -> None:
        set_field = object.__setattr__
        set_field(self, "select", select)
        set_field(self, "ignore", ignore)
        set_field(self, "targets", targets)

    def allows(self, code: str) -> bool:
        target = _target_of(code)
        if target is not None and target not in {t.partition("@")[0] for t in self.targets}:
            return False
        if not self.select and not self.ignore:
            return True
        return _selected(self, code)

    def allowing(self) -> Callable[[str], bool]:
        """:meth:`allows` as a function that answers each code once for this selection (and
        any equal to it): a check asks it of every rule for every robot, and with ``select`` or
        ``ignore`` each answer hashed and compared the selection, made anew for each file
        (``--ignore U103`` cost a check of the corpus 54 M instructions more than no option)."""
        return _allowing(self).__getitem__

    def runs_nothing(self) -> bool:
        """Whether no rule at all is allowed: every one ignored, or selected only among the
        portability rules of targets not asked for."""
        return bool(self.select or self.ignore) and _runs_nothing(self)


class _Answers(dict):
    """Whether a selection allows each code asked so far, by code."""

    __slots__ = ("selection",)

    def __init__(self, selection: Selection) -> None:
        super().__init__()
        self.selection = selection

    def __missing__(self, code: str) -> bool:
        answer = self[code] = self.selection.allows(code)
        return answer


@functools.lru_cache(maxsize=64)
def _allowing(selection: Selection) -> _Answers:
    return _Answers(selection)


def _selected(selection: Selection, code: str) -> bool:
    """Whether the ``select`` and ``ignore`` lists of ``selection`` let ``code`` run. Not
    remembered here: the engine asks through :meth:`Selection.allowing`, whose table answers
    each code once per selection (a cache of these answers as well saved a check of the corpus
    nothing: 0.7 to 4.3 M instructions more with no option, ``--ignore U3``, ``--select U0,U1``
    and a settings file's ``ignore``, session 26)."""
    from urdftool.lint.rules import CATALOGUE

    if selection.select and not any(CATALOGUE.matches(code, s) for s in selection.select):
        return False
    return not any(CATALOGUE.matches(code, s) for s in selection.ignore)


@functools.lru_cache(maxsize=64)
def _runs_nothing(selection: Selection) -> bool:
    """Asked of the rules a check with the selection's targets may run: without a target, no
    rule of a target's family is allowed, and their family stays unimported."""
    from urdftool.lint.rules import CATALOGUE

    return not any(selection.allows(rule.code)
                   for rule in CATALOGUE.running(bool(selection.targets)))


def _target_of(code: str) -> str | None:
    """The simulator a portability rule's code belongs to, or None. The catalogue is imported
    when first asked (a run served from the cache never asks), then kept: every rule asks for
    every robot."""
    decades = _DECADES[0]
    if decades is None:
        from urdftool.lint.catalogue import TARGET_DECADES

        decades = _DECADES[0] = TARGET_DECADES
    return decades.get(code[:3])


_DECADES: list = [None]  # [the catalogue's TARGET_DECADES], once imported


class CheckOptions(Record):
    """How to load and check each file."""

    xacro_args: dict[str, str]
    packages: dict[str, Path]
    selection: Selection
    allow_env: bool
    max_file_size: int
    companions: CompanionPaths
    mesh_limits: MeshLimits

    __slots__ = ("xacro_args", "packages", "selection", "allow_env", "max_file_size", "companions",
                 "mesh_limits")

    def __init__(self, xacro_args: dict[str, str] = NEW, packages: dict[str, Path] = NEW,
                 selection: Selection = Selection(), allow_env: bool = True,
                 max_file_size: int = DEFAULT_MAX_FILE_SIZE,
                 companions: CompanionPaths = CompanionPaths(),
                 mesh_limits: MeshLimits = MeshLimits()) -> None:
        self.xacro_args = {} if xacro_args is NEW else xacro_args
        self.packages = {} if packages is NEW else packages
        self.selection = selection
        self.allow_env = allow_env
        self.max_file_size = max_file_size
        self.companions = companions
        self.mesh_limits = mesh_limits


class FileResult(Record):
    """What checking one file found.

    strict: whether a warning in it fails the check (its settings or the request)
    companions: one line per companion file found for the robot, what it was used as and why,
        or why not (``check -v`` lists them)
    record: what the check read, searched and resolved
        (:class:`~urdftool.description.record.Record`), when it was checked here
    read: the real paths of the files its check read, when a worker checked it
    arguments: of the xacro arguments the check was given, those the files its robot was built
        from name, and the arguments those files declare: ``[named, declared]``, read from
        the robot's text where it was built (:attr:`~urdftool.description.robot.Robot.
        sources`, the one owner of what it read), kept with the result; None when not known
        (no argument given, a robot that did not load)
    notes: what its check says beside its findings, in words, as ``urdftool check`` says it
        on standard error: the settings files above it not read
        (:attr:`~urdftool.lint.settings.FileSettings.skipped`, decided once, by the settings
        that applied to it; the run's :attr:`~urdftool.lint.runner.Run.notes`, the language
        server's pop-ups)
    """

    path: str
    findings: list[Finding]
    robot: object | None
    strict: bool
    companions: list[str]
    record: object | None
    read: tuple
    arguments: list | None
    notes: tuple

    __slots__ = ("path", "findings", "robot", "strict", "companions", "record", "read",
                 "arguments", "notes")
    _shown = ("path", "findings", "robot", "strict", "companions")

    def __init__(self, path: str, findings: list[Finding], robot: object | None = None,
                 strict: bool = False, companions: list[str] = NEW, record: object | None = None,
                 read: tuple = (), arguments: list | None = None, notes: tuple = ()) -> None:
        self.path = path
        self.findings = findings
        self.robot = robot
        self.strict = strict
        self.companions = [] if companions is NEW else companions
        self.record = record
        self.read = read
        self.arguments = arguments
        self.notes = notes

    @property
    def unexpanded(self) -> bool:
        """Whether its robot was not expanded, so not checked, for a package this machine
        lacks (:attr:`not_checked_by`)."""
        return bool(self.not_checked_by)

    @property
    def not_checked_by(self) -> list[Finding]:
        """The findings saying its robot was not expanded, so not checked, for a package this
        machine lacks (U006: the environment's, not the robot's, a warning; a note for a
        dependency its package.xml declares, the workspace's, which a report shows even where
        it leaves notes out: the run exits 2 for it; but not for a library of macros nothing
        here builds, a note too, which would make no robot to check). Each says so itself
        (:attr:`~urdftool.diagnostics.Finding.not_checked`, set where the load error became
        it), never read from its words."""
        return [finding for finding in self.findings if finding.not_checked]

    @property
    def failures(self) -> list[Finding]:
        """The findings that fail the check: errors, and warnings when checked strictly."""
        failing = {Severity.ERROR, Severity.WARNING} if self.strict else {Severity.ERROR}
        return [finding for finding in self.findings if finding.severity in failing]
