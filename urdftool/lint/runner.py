"""The linter's entry points: check paths as ``urdftool check`` does, many files in worker
processes, one file as an editor has it.

``check_paths`` is ``urdftool check`` (settings per target, folders walked, budgets, the result
cache, an exit code) and ``check_file`` one file in this process, with the settings above it
(both are the public API: ``urdftool.check_paths``, ``urdftool.check_file``); ``check_files``
checks files already resolved to their options in the budgeted workers of
:mod:`urdftool.lint.pool`. Each file is loaded and checked by ``engine.load_and_check``. The rules
are imported before the workers that check files are forked, so that each inherits them rather
than importing them again.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Iterable, Mapping

from urdftool.budget import DEFAULT_TIMEOUT, Budget
from urdftool.description.crashes import guarded
from urdftool.description.run_memo import one_run
from urdftool.diagnostics import Finding
from urdftool.description.inputs import held
from urdftool.errors import OptionError, SettingsError, TargetError, available
from urdftool.lint.options import CheckOptions, FileResult
from urdftool.lint.pool import Stop, auto_jobs, run_budgeted
from urdftool.lint.settings import CheckRequest, Companions, check_companions, for_file
from urdftool.records import NEW, Record


def check_files(files: list[str], options_for, jobs: int | None = None,
                timeout: float | None = DEFAULT_TIMEOUT,
                memory: int | None = None, stdin_as: str | None = None,
                cache=None, finished=None) -> list[FileResult]:
    """Check ``files`` (``options_for(path) -> CheckOptions``) and return results in order.

    jobs: worker processes [default: :func:`auto_jobs`]; timeout: budget per file in [s],
    memory: address space per worker in [bytes]; None or 0 for no limit. Without a budget and
    with one job, files are checked in this process. Standard input ('-') is read here.
    stdin_as: the path standard input is checked as (its includes and packages are found from
        there, its findings name it), as an editor sends an unsaved buffer
    cache: a :class:`~urdftool.lint.cache.Cache`: files whose result it holds are not checked
        again (looked up here, before any worker starts), the others' results are kept in it;
        standard input is never cached
    finished: called with how many of ``files`` are done (found in the cache or checked), as
        each is (progress)
    """
    with one_run():  # one view of the file system for the files (the workers inherit it)
        return _check_files(files, options_for, jobs, timeout, memory, stdin_as, cache,
                            finished or (lambda done: None))


# how the rules are imported before files are checked: the door (urdftool.__main__) imports
# them with the collector off and freezes them; None: as any import
import_rules = None


def _check_files(files, options_for, jobs, timeout, memory, stdin_as, cache,
                 finished) -> list[FileResult]:
    budget = Budget(timeout or None, memory or None)
    stdin = {}
    if "-" in files:
        stdin["-"] = sys.stdin.buffer.read(options_for("-").max_file_size + 1)
    named = [stdin_as if path == "-" and stdin_as else path for path in files]
    kept = [cache.get(path, options_for(path)) if cache and path != "-" else None
            for path in files]
    todo = [index for index, found in enumerate(kept) if found is None]
    finished(len(files) - len(todo))
    jobs = max(1, jobs or auto_jobs(len(todo)))

    if todo:  # the rules, before the workers fork (they inherit them); not for a run the
        # result cache serves
        if import_rules is not None:
            import_rules()
        from urdftool.lint import engine  # noqa: F401
    work = _Checking([files[i] for i in todo], [named[i] for i in todo],
                     [options_for(files[i]) for i in todo], stdin, cache)

    def stopped(index: int, stop: Stop) -> tuple[list[Finding], list[str], tuple, None, None]:
        from urdftool.lint.engine import stop_finding

        return [stop_finding(named[todo[index]], stop, "checking")], [], (), None, None

    lines: list[list[str]] = [[] for _ in files]
    # (a file the cache holds: what its check read, as a worker says it)
    read: list[tuple] = [cache.reads(path, options_for(path)) if found is not None else ()
                         for path, found in zip(files, kept)]
    arguments: list = [cache.arguments(path, options_for(path)) if found is not None else None
                       for path, found in zip(files, kept)]
    checked = run_budgeted(len(todo), work, budget, stopped, jobs,
                           lambda done: finished(len(files) - len(todo) + done))
    for index, (found, companions, paths, unkept, named_args) in zip(todo, checked):
        kept[index], lines[index], read[index], arguments[index] = \
            found, companions, paths, named_args
        if unkept:
            cache.failed(unkept)
    return [FileResult(path, found, companions=companions, read=paths, arguments=args)
            for path, found, companions, paths, args in zip(named, kept, lines, read, arguments)]


class _Checking(Record):
    """Checking ``paths[i]`` as ``named[i]`` with ``options[i]``, a worker's piece ``i``.
    stdin: the bytes read for '-'; cache: where results are kept, or None."""

    paths: list[str]
    named: list[str]
    options: list[CheckOptions]
    stdin: dict[str, bytes]
    cache: object

    __slots__ = ("paths", "named", "options", "stdin", "cache")

    def __init__(self, paths: list[str], named: list[str], options: list[CheckOptions],
                 stdin: dict[str, bytes], cache: object = None) -> None:
        self.paths = paths
        self.named = named
        self.options = options
        self.stdin = stdin
        self.cache = cache

    def __call__(self, index: int
                 ) -> tuple[list[Finding], list[str], tuple[str, ...], str | None, list | None]:
        path, options = self.paths[index], self.options[index]
        from urdftool.lint import engine  # every rule: imported only when a file is checked

        result = engine.load_and_check(self.named[index], options, data=self.stdin.get(path))
        if self.cache and path != "-":
            self.cache.put(path, options, result)  # with the record of what its check read
        read = tuple(found.real for found in result.record.reads().values()
                     if found.failure is None)  # (an output must not replace them)
        # why the result could not be kept, for the run to say once (a worker's cache is a copy)
        return (result.findings, result.companions, read, self.cache and self.cache.failure,
                result.arguments)


class Run(Record):
    """What checking some paths found.

    results: one per file checked, in order
    skipped: files found in folders and not checked -> why
    notes: "PATH: what happened" for files named that were checked through others or not at all
    strict: per result, whether a warning in it fails the run (its settings or the request)
    depends: for a run the result cache keeps whole, the stamps of what it was built from
        (see :mod:`urdftool.lint.cache`); None for any other
    errors: why files were not checked: the settings file that applies to them is broken
        (each message names it); the other files were checked
    unbuilt: the launch files named that build no robot (their reasons in ``skipped``)
    """

    results: list[FileResult]
    skipped: dict[str, str]
    notes: list[str]
    strict: list[bool]
    depends: list | None
    errors: list[str]
    unbuilt: list[str]

    __slots__ = ("results", "skipped", "notes", "strict", "depends", "errors", "unbuilt")
    _shown = ("results", "skipped", "notes", "strict", "errors", "unbuilt")

    def __init__(self, results: list[FileResult], skipped: dict[str, str] = NEW,
                 notes: list[str] = NEW, strict: list[bool] = NEW, depends: list | None = None,
                 errors: list[str] = NEW, unbuilt: list[str] = NEW) -> None:
        self.results = results
        self.skipped = {} if skipped is NEW else skipped
        self.notes = [] if notes is NEW else notes
        self.strict = [] if strict is NEW else strict
        self.depends = depends
        self.errors = [] if errors is NEW else errors
        self.unbuilt = [] if unbuilt is NEW else unbuilt
        self.__post_init__()

    def __post_init__(self):
        for result, strict in zip(self.results, self.strict):
            result.strict = strict
        self.strict = [result.strict for result in self.results]

    @property
    def unexpanded(self) -> list[str]:
        """The files not checked for a package this machine lacks
        (:attr:`FileResult.unexpanded`): nothing in them is known wrong, and a run that could
        not check them is no pass."""
        return [result.path for result in self.results if result.unexpanded]

    @property
    def exit_code(self) -> int:
        """0 clean, 1 when a file has an error, or a warning and is checked strictly; 2 when
        files were not checked: for their broken settings (:attr:`errors`) or for a
        package not installed (:attr:`unexpanded`)."""
        if self.errors or self.unexpanded:
            return 2
        return 1 if any(result.failures for result in self.results) else 0


def check_paths(paths, request: CheckRequest | None = None, /, *, progress=None,
                **options) -> Run:
    """Check files and folders as ``urdftool check PATH...`` does: the settings file above each
    target applies to it, folders are walked for top-level robots, a macro library named is
    replaced by the robots including it, and files are checked in worker processes within the
    time and memory budgets.

    paths: files, folders or ``-`` (standard input); one path alone works too
    request: a :class:`~urdftool.lint.settings.CheckRequest`, or its fields as keywords
        (``select``, ``ignore``, ``strict``, ``xacro_args``, ``packages``, ``companions``,
        ``allow_env``, ``max_file_size``, ``max_triangles``, ``max_memory``, ``timeout`` [s],
        ``jobs``, ``use_settings``, ``cache_dir``); defaults as the command line's, except
        that results are kept between runs only with ``cache_dir``
    progress: called with (files done, files to check) as the files are checked
    The results' records (:mod:`urdftool.description.record`) note the digests of the files
    read only with ``cache_dir``, the one reader that compares them with the disk.
    Raises TargetError (an UrdftoolError) before anything is checked (also when nothing is to
    be checked while a path named asked for a robot: ``Targets.unchecked``, or no path is given),
    and SettingsError when the settings of every file to check are broken; broken settings that
    apply to some files only are the run's ``errors``, and the other files are checked.
    """
    if request is None:
        request = _request(options)
    elif options:
        raise TypeError("check_paths takes a CheckRequest or keyword options, not both")
    elif not isinstance(request, CheckRequest):
        raise OptionError("request", f"request must be a CheckRequest, not "
                                     f"{type(request).__name__} (its fields as keywords: "
                                     "check_paths(paths, strict=True))")
    progress = held("progress", progress, "call", none=True)
    check_companions(request.companions)
    paths = [_path(paths)] if isinstance(paths, (str, bytes, os.PathLike)) or \
        not isinstance(paths, Iterable) else [_path(path) for path in paths]  # one path, not its
    # characters (nor its bytes' numbers)
    if not paths:  # (a glob that matched nothing: the command line's "no PATH given", never a
        raise TargetError("nothing checked: no path given")  # pass)
    from urdftool.description.record import digesting

    # one view of the file system (roots and settings looked up once); the files' digests only
    # for the cache, the one reader that compares a record with the disk by content
    with one_run(), digesting(request.cache_dir is not None):
        return _check_paths(list(paths), request, progress or (lambda done, planned: None))


def _check_paths(paths: list, request: CheckRequest, progress) -> Run:
    cache = None
    if request.cache_dir is not None:
        from urdftool.lint.cache import Cache

        cache = Cache(request.cache_dir)
        kept = cache.get_run(paths, request)
        if kept is not None:
            return Run(kept[0], strict=kept[1], depends=kept[2])
    if import_rules is not None and cache is None:  # every file is checked: the rules now,
        import_rules()  # before the targets' imports, which they make with the collector off
    from urdftool.description.record import recording
    from urdftool.lint.targets import expand  # not on a re-run served whole from the cache

    with recording() as surroundings:  # what finding targets and settings read: a run kept
        targets = expand(paths, request)  # whole depends on it
        if not targets.files and targets.unchecked:  # a check that checks nothing is no pass
            raise TargetError(f"nothing checked: {'; '.join(targets.unchecked)}")
        by_path, errors = {}, []
        for path in targets.files:  # broken settings stop the files they apply to, no others
            try:  # (its settings reader's crash: U900 at the file, not checked)
                plan = guarded("the settings reader", path, lambda: for_file(
                    request.stdin_filename if path == "-" and request.stdin_filename else path,
                    request))
            except SettingsError as error:
                errors.append(str(error))
            else:
                if plan is not None:
                    by_path[path] = plan
    crashed = discovery_crashes()
    errors = list(dict.fromkeys(errors))
    if errors and not by_path:
        raise SettingsError(errors[0])
    files = [path for path in targets.files if path in by_path]
    plans = [by_path[path] for path in files]
    results: list[FileResult | None] = [None] * len(files)
    before = 0  # files of the pools already run
    for memory, timeout in dict.fromkeys((plan.memory, plan.timeout) for plan in plans):
        indexes = [i for i, plan in enumerate(plans)  # one pool per budget
                   if (plan.memory, plan.timeout) == (memory, timeout)]
        found = check_files([files[i] for i in indexes], lambda p: by_path[p].options,
                            jobs=request.jobs, timeout=timeout, memory=memory,
                            stdin_as=request.stdin_filename, cache=cache,
                            finished=lambda done: progress(before + done, len(files)))
        before += len(indexes)
        for index, result in zip(indexes, found):
            result.notes = plans[index].skipped
            results[index] = result
    unread = dict.fromkeys(why for result in results for why in result.notes)  # (said once; a
    # run with notes is never kept whole: said again on every run)
    results += crashed  # (after the pools: a file checked keeps its place and strictness)
    run = Run(results, targets.skipped, [*targets.notes, *unread], [plan.strict for plan in plans],
              errors=errors, unbuilt=targets.unbuilt)
    if cache is not None and not errors and not crashed:  # (a crash is worth trying again)
        run.depends = cache.put_run(paths, request, run, lambda path: by_path[path].options,
                                    surroundings)
    if cache is not None and cache.unkept():  # said once a run; the check went on
        run.notes.append(cache.unkept())
    return run


def discovery_crashes() -> list[FileResult]:
    """The crashes of readers while finding targets (a launch file read to know the robots it
    builds), each a result of its own at the file being read: U900, as a rule's crash. The
    engine (and with it the rules) is imported only when one crashed."""
    from urdftool.description.crashes import any_kept

    if not any_kept():
        return []
    from urdftool.lint.engine import reader_crashes

    by_file: dict[str, list[Finding]] = {}
    for finding in reader_crashes():
        by_file.setdefault(finding.location.file, []).append(finding)
    return [FileResult(path, found) for path, found in by_file.items()]


def check_file(path, *, data: bytes | str | None = None, **options) -> FileResult:
    """Check one file in this process, with no time budget, as an editor has it.

    data: the file's content when it is not to be read from ``path`` (an unsaved buffer);
        suppression comments are read from it too. It is read as any unsaved buffer
        (:func:`urdftool.description.files.unsaved`, which also gives the check the buffers
        of other files: included macro files, companions): recorded by its digest, and
        refused where the file would be (a link leading out of the repository)
    options: as :func:`check_paths` (the settings file above ``path`` applies, per-file ignores
        too, unless ``use_settings=False``); the result keeps the loaded ``robot`` and the
        ``record`` of what the check read, searched and followed, the settings looked for
        included (:mod:`urdftool.description.record`), and its ``notes`` (the settings files
        not read), as a run's
    """
    path = _path(path)
    if not isinstance(data, (str, bytes, type(None))):
        raise TypeError(f"data must be the file's text (str or bytes), not "
                        f"{type(data).__name__}")
    request = _request(options)
    buffers = {}
    if data is not None and path != "-":
        buffers[path], data = data, None
    if isinstance(data, str):
        data = data.encode("utf-8")
    from urdftool.description.files import unsaved
    from urdftool.description.record import recording
    from urdftool.lint import engine

    with recording() as record, unsaved(buffers):  # the settings found, and the check's own
        check_companions(request.companions)  # record
        settings = for_file(path, request)
        result = engine.load_and_check(path, settings.options, data=data)
    result.record, result.notes = record, settings.skipped
    return result


def _path(path) -> str:
    """A path the API was given (str, bytes or os.PathLike, as ``os`` takes them) as the str
    every reader takes (bytes that are not UTF-8 as ``os.fsdecode`` reads a folder's names);
    TypeError naming anything else (``check_paths(b"robots")`` checked the paths 114, 111, ...,
    ``check_paths(5)`` said "'int' object is not iterable")."""
    if not isinstance(path, (str, bytes, os.PathLike)):
        raise TypeError(f"a path must be str, bytes or os.PathLike, not {type(path).__name__}")
    return os.fsdecode(path)


def _request(options: dict) -> CheckRequest:
    """The request of an API call's keywords, each held by the one guard of a caller's options
    (``CheckRequest``'s): a keyword no field has, or a companion no map has, an OptionError
    naming the ones there are (not Python's "unexpected keyword argument" from inside)."""
    for given, fields in ((options, CheckRequest.__slots__),
                          (options.get("companions"), Companions.__slots__)):
        for name in (given if isinstance(given, Mapping) else ()):
            if name not in fields:
                raise OptionError(str(name), f"no option {name!r}; "
                                             + available("options", str(name), fields))
    companions = options.get("companions")
    if isinstance(companions, Mapping):
        options = {**options, "companions": Companions(**companions)}
    return CheckRequest(**options)

__all__ = ["CheckOptions", "CheckRequest", "FileResult", "Run", "check_file", "check_files",
           "check_paths"]
