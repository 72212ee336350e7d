"""``pytest --urdftool``: robot descriptions as test items (a ``pytest11`` plugin).

With ``--urdftool``, every top-level robot below the paths pytest collects (``.urdf`` and
``.xacro`` files that are robots of their own, as ``urdftool check FOLDER`` finds them; macro
libraries and included fragments are left out) becomes a test item that fails with its located
findings when ``urdftool check`` would exit 1 on it, honouring the settings file above it. The
session's robot items are checked together, at the first one, as ``urdftool check FILE...``
checks them (one run: repositories, packages, launch files and settings looked up once; the
files in worker processes, each within the usual time budget); under pytest-xdist, whose
workers each run a share unknown in advance, each item checks its own file. A reader's crash
while the robots are found (U900, urdftool's internal error) is an item of its own at the file
it was reading, failing as ``urdftool check`` says it.

For tests of your own, the ``urdftool_check`` fixture checks paths and fails the test with the
findings; ``urdftool.check_paths`` returns them for any other use. Without ``--urdftool`` the
plugin only adds that fixture: it imports nothing of urdftool's until it is used, so it costs a
pytest run in the same environment nothing.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest


def pytest_addoption(parser):
    group = parser.getgroup("urdftool")
    group.addoption("--urdftool", action="store_true", default=False,
                    help="check robot descriptions (.urdf, .xacro) with urdftool as test items")


def pytest_collect_file(file_path: Path, parent):
    if not parent.config.getoption("urdftool"):
        return None
    from urdftool.description.urdf import is_robot_name

    if not is_robot_name(file_path.name):
        return None
    from urdftool.description.files import real_path

    if Path(real_path(file_path)) not in _top_level(parent.config, file_path.parent):
        return None  # a macro library or a fragment another file includes: checked through it
    return RobotFile.from_parent(parent, path=file_path, nodeid=_node_id(parent, file_path))


@pytest.hookimpl(wrapper=True)
def pytest_collect_directory(path: Path, parent):
    """The folder's collector (pytest's, or a package's), collecting also the robot files
    ``urdftool check FOLDER`` finds there that pytest's walk passes over: those that are no
    regular file (a named pipe, a link to a device or out of the repository, a link loop),
    which check reports as errors (U001, U017) and pytest never hands to
    :func:`pytest_collect_file`: ``pytest --urdftool`` passed where check failed."""
    collector = yield
    if collector is None or not parent.config.getoption("urdftool"):
        return collector
    passed_over = _not_regular(parent.config, path)
    if passed_over:
        collect = collector.collect

        def with_robots():
            yield from collect()
            for file in passed_over:
                yield RobotFile.from_parent(collector, path=file,
                                            nodeid=_node_id(collector, file))

        collector.collect = with_robots
    return collector


def _not_regular(config, folder: Path) -> list[Path]:
    """The robot files ``urdftool check`` finds directly in ``folder`` that are no regular
    file (by their own names, links not followed out)."""
    from urdftool.description.files import kind_of

    _top_level(config, folder)
    return [file for file in config.stash[_CACHE][("named", folder)]
            if kind_of(file) != "file"]


def _node_id(parent, file_path: Path) -> str:
    """The node ID pytest would give ``file_path`` (relative to the root folder, ``/``
    between folders), through the terminal-text escaper (see :class:`RobotFile`), with no
    ``::`` left in it: pytest reads what follows one as names and a ``[`` after it as the
    parameters, so a robot file named ``a::b[1].urdf`` was the path ``a``, and its item's ID
    a ValueError that interrupted the whole session's collection. A colon before another is
    written ``\\x3a``, as the escaper writes one that starts a line."""
    from urdftool.report.escape import text

    try:
        relative = file_path.relative_to(parent.config.rootpath).as_posix()
    except ValueError:
        relative = file_path.as_posix()
    return _COLON_BEFORE_COLON.sub(r"\\x3a", text(relative))


_COLON_BEFORE_COLON = re.compile(":(?=:)")


def _top_level(config, folder: Path) -> set[Path]:
    """The top-level robot files directly in ``folder`` (cached per folder and session)."""
    cache = config.stash.setdefault(_CACHE, {})
    if folder not in cache:
        from urdftool.description.files import real_path
        from urdftool.description.run_memo import one_run
        from urdftool.lint.settings import CheckRequest
        from urdftool.lint.targets import expand

        try:
            with one_run(config.stash.setdefault(_RUN, {})):
                targets = expand([str(folder)], CheckRequest())
            files = targets.files
            cache[("unchecked", folder)] = targets.unchecked
        except Exception:  # noqa: BLE001 - no robots here, or unreadable: nothing to collect
            files = []
        _keep_crashes(config)
        real = [Path(real_path(file)) for file in files]
        cache[folder] = {file for file in real if file.parent == Path(real_path(folder))}
        cache[("named", folder)] = [Path(file) for file in files
                                    if Path(file).absolute().parent == folder.absolute()]
    return cache[folder]


def _keep_crashes(config) -> None:
    """The readers' crashes while finding the robots (:mod:`urdftool.description.crashes`),
    kept for items of their own (:class:`CrashItem`): left in the record, the first robot
    item's check said them as its own."""
    from urdftool.description.crashes import any_kept

    if not any_kept():
        return
    from urdftool.lint.runner import discovery_crashes

    kept = config.stash.setdefault(_CRASHES, {})
    for result in discovery_crashes():
        findings = kept.setdefault(result.path, [])
        findings.extend(f for f in result.findings if f not in findings)


_CRASHES = pytest.StashKey[dict]()


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(session, config, items):
    """No robot item: :func:`_nothing_checked`; then an item for each file whose reader crashed
    while the robots were found (:class:`CrashItem`). Before ``-k`` deselects (tryfirst): the
    items pytest collected."""
    if not config.getoption("urdftool"):
        return
    if not any(isinstance(i, RobotItem) for i in items):
        _nothing_checked(config)
    for path, findings in config.stash.get(_CRASHES, {}).items():
        file = Path(path).absolute()
        items.append(CrashItem.from_parent(session, name="urdftool", path=file,
                                           nodeid=f"{_node_id(session, file)}::urdftool",
                                           findings=findings))


def _nothing_checked(config) -> None:
    """A check that checks nothing is no pass, as ``urdftool check`` says (exit 2): robot
    files were found (a robot whose root link was deleted, parts no robot includes, macro
    libraries only) and none is a robot of its own, so no item would fail: a usage error."""
    cache = config.stash.get(_CACHE, {})
    reasons = sorted({why for key, found in cache.items()
                      if isinstance(key, tuple) and key[0] == "unchecked" for why in found},
                     key=len)
    if reasons:
        from urdftool.report.escape import text

        more = f" (and {len(reasons) - 1} more)" if len(reasons) > 1 else ""
        raise pytest.UsageError(text(f"urdftool: nothing checked: {reasons[0]}{more}"))


_CACHE = pytest.StashKey[dict]()
_RUN = pytest.StashKey[dict]()  # the per-run memory of the collection and the check together


class RobotFile(pytest.File):
    """A robot file as a pytest collector. Its name and node ID are a stranger's file name,
    which pytest prints at the start of a line (``-v``, ``--collect-only``, the short summary)
    and writes into ``--junitxml``: both go through the terminal-text escaper, so a file named
    ``::error::x.urdf`` or holding a line break, an escape sequence or an undecodable byte
    prints no workflow command, moves no cursor and does not end pytest's JUnit writer with
    a traceback."""

    def __init__(self, *args, **kwargs):
        from urdftool.report.escape import text

        super().__init__(*args, **kwargs)
        self.name = text(self.name)

    def collect(self):
        yield RobotItem.from_parent(self, name="urdftool")


class _FindingsFailure(Exception):
    """``urdftool check`` fails on a robot; the text is its located findings."""


class _FindingsItem(pytest.Item):
    """An item failing with located findings (:class:`_FindingsFailure`), as ``urdftool check``
    prints them."""

    # Plugins that wrap every test call may read ``funcargs`` (pytest-lsp 1.0 stops the run
    # with "did not yield" on an item without it); a robot takes no fixtures.
    funcargs: dict = {}

    def repr_failure(self, excinfo, style=None):
        if isinstance(excinfo.value, _FindingsFailure):
            return str(excinfo.value)
        return super().repr_failure(excinfo, style)


class RobotItem(_FindingsItem):
    def runtest(self):
        from urdftool.errors import REFUSALS
        from urdftool.report.escape import text

        try:
            run = _checked_with_the_session(self)
        except REFUSALS as error:  # as the command line says it, in one line: no traceback
            raise _FindingsFailure(text(f"urdftool: error: {error}")) from None
        if run.exit_code:
            raise _FindingsFailure(_text(run))

    def reportinfo(self):
        from urdftool.report.escape import text

        return self.path, None, text(f"urdftool check {self.path.name}")


class CrashItem(_FindingsItem):
    """A reader's crash while the robots were found (U900, urdftool's internal error), at the
    file it was reading, failing as ``urdftool check`` says it, as an item of its own (the
    robots' items fail on their own findings only)."""

    def __init__(self, *args, findings, **kwargs):
        super().__init__(*args, **kwargs)
        self.findings = findings

    def runtest(self):
        from urdftool.lint.runner import FileResult, Run

        crash = FileResult(str(self.path), self.findings)
        raise _FindingsFailure(_text(Run([crash], strict=[False])))

    def reportinfo(self):
        from urdftool.report.escape import text

        return self.path, None, text(f"urdftool: crashed reading {self.path.name}")


_TOGETHER = pytest.StashKey[dict]()


def _checked_with_the_session(item):
    """The :class:`~urdftool.Run` of ``item``'s file alone, taken from one check of every robot
    item of the session made at the first; its own check when that check has no result for it
    (its settings file is broken: its own run says so) or under pytest-xdist."""
    from urdftool.description.files import real_path
    from urdftool.description.run_memo import one_run
    from urdftool.lint.runner import Run

    config = item.config
    if hasattr(config, "workerinput"):
        return _said(_check([str(item.path)]))
    results = config.stash.get(_TOGETHER, None)
    if results is None:
        paths = [str(other.path) for other in item.session.items if isinstance(other, RobotItem)]
        with one_run(config.stash.setdefault(_RUN, {})):
            together = _said(_check(paths, jobs=None))  # worker processes as urdftool check
        results = {real_path(result.path): result for result in together.results}  # chooses
        config.stash[_TOGETHER] = results
    result = results.get(real_path(item.path))
    if result is None:
        return _said(_check([str(item.path)]))
    return Run([result], strict=[result.strict])


class UrdftoolWarning(UserWarning):
    """What ``urdftool check`` says on standard error of a run that checked (a settings file
    another user owns, not read: :func:`urdftool.lint.settings.foreign`), said as a warning of
    the test that ran the check (pytest's warnings summary; ``-W error`` fails on it)."""


def _said(run):
    """``run``, its notes said (:class:`UrdftoolWarning`), as the command line prints them."""
    import warnings

    from urdftool.report.escape import text

    for note in run.notes:
        warnings.warn(UrdftoolWarning(text(f"urdftool: {note}")), stacklevel=2)
    return run


def _check(paths, **options):
    from urdftool.lint.runner import check_paths

    return check_paths(paths, **{"jobs": 1, **options})


def _text(run) -> str:
    """The findings that fail the check, one located line each (with the macro call chain), so
    that pytest's short summary shows the first."""
    from urdftool.report.escape import text
    from urdftool.report.summary import via_text

    lines = [text(f"urdftool: error: {error}") for error in run.errors]  # settings
    for result in run.results:
        for finding in result.failures:
            lines.append(text(f"{finding.location}: {finding.severity.value} {finding.code} "
                              f"{finding.message} ({finding.name})"))
            lines.extend(f"    {text(line)}" for line in via_text(finding.location))
    return "\n".join(lines)


@pytest.fixture
def urdftool_check():
    """``urdftool_check(*paths, **options)``: check paths as ``urdftool check`` does (options as
    :func:`urdftool.check_paths` takes them) and fail the test with the located findings when it
    would not exit 0; returns the :class:`urdftool.Run` otherwise."""

    def check(*paths, **options):
        from urdftool.errors import REFUSALS
        from urdftool.report.escape import text

        try:
            run = _said(_check(list(paths), **options))  # (str() made b"urdf" the path "b'urdf'")
        except REFUSALS as error:  # in one line, as an item says it: no traceback of urdftool's
            refused = text(f"urdftool: error: {error}")
        else:
            refused = None
        if refused is not None:  # (failed outside the except: no chained exception shown)
            pytest.fail(refused, pytrace=False)
        if run.exit_code:
            pytest.fail(_text(run), pytrace=False)
        return run

    return check
