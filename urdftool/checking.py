"""``urdftool check``'s work, from its words as parsed to its exit code, without Typer: the
command (``urdftool/cli/check.py``) runs it with the values Typer parsed, and the door
(``urdftool/__main__.py``) with those it parsed itself when they were plain."""

from __future__ import annotations

import sys

from urdftool.errors import UsageError
from urdftool.report import FORMATS as REPORT_FORMATS
from urdftool.terminal import Terminal, robot_inputs

FORMATS = (*REPORT_FORMATS, "auto")  # auto: github under GitHub Actions, else text


def run(terminal: Terminal, /, *, words, arg, package, format, output, select,
        ignore, target, strict, verbose, quiet, notes, exit_zero, statistics, config, isolated,
        stdin_filename, allow_env, max_file_size, controllers, srdf, spec, max_triangles,
        timeout, max_memory, jobs, fix, unsafe_fixes, diff, no_cache, cache_dir) -> int:
    """Check as ``urdftool check`` does and return its exit code; print and exit (on a usage
    error: 2) through ``terminal``. The values are those of the command's parameters (see
    ``urdftool check --help``)."""
    from urdftool.budget import Budget, one_blas_thread
    from urdftool.errors import REFUSALS
    from urdftool.lint.runner import check_paths
    from urdftool.lint.settings import (CheckRequest, Companions, checked_file_size,
                                        notes_shown)
    from urdftool.report import render
    from urdftool.report.escape import text

    try:
        paths, args, packages = robot_inputs(words, arg, package)
        if jobs < 0:
            raise UsageError("--jobs must not be negative")
        if not paths:
            raise UsageError("no PATH given")
        if stdin_filename is not None and "-" not in paths:
            raise UsageError("--stdin-filename names standard input: give '-' as the PATH")
        if config is not None and isolated:
            raise UsageError("--config and --isolated exclude each other")
        if format not in FORMATS:
            raise UsageError(f"unknown format '{format}'; choose from auto, "
                             f"{', '.join(REPORT_FORMATS)}")
        terminal.refuse_bad_outputs(output, inputs=paths)
        if max_file_size is not None:
            checked_file_size(max_file_size, "--max-file-size")
        Budget.of(timeout or 0, max_memory)  # --timeout and --max-memory are well formed
        if unsafe_fixes and not (fix or diff):
            raise UsageError("--unsafe-fixes applies with --fix or --diff")
        request = CheckRequest(
            select=tuple(select), ignore=tuple(ignore), targets=tuple(target), strict=strict,
            xacro_args=args,
            packages=packages, companions=Companions(tuple(controllers), srdf, spec),
            allow_env=allow_env, max_file_size=max_file_size, max_triangles=max_triangles,
            max_memory=max_memory, timeout=timeout, jobs=jobs or None,
            use_settings=not isolated, settings_file=config, stdin_filename=stdin_filename,
            cache_dir=None if no_cache else cache_dir or _default_cache())
        one_blas_thread()  # files checked in this process too (--jobs 1 without budgets)
        from urdftool.report import resolve_format
        from urdftool.report.progress import progress

        machine = not statistics and resolve_format(format) != "text"  # for a program
        with progress("checking", "files", 0, machine=machine) as moved:
            run = check_paths(paths, request, progress=moved)
        if fix or diff:
            run = _apply_fixes(terminal, run, diff, unsafe_fixes,
                               lambda: check_paths(paths, request))
    except REFUSALS as error:
        terminal.fail_usage(error)
    messages = [f"urdftool: {note}" for note in run.notes]
    messages += [f"urdftool: warning: {warning}" for warning in _unnamed_arguments(run, args)]
    if verbose:
        messages += [f"skipped {path}: {reason}" for path, reason in run.skipped.items()]
        messages += [f"companion of {result.path}: {line}" for result in run.results
                     for line in result.companions]
    elif not run.results:  # a launch file named builds nothing: "0 files checked" says not why
        launch = [(path, run.skipped[path]) for path in run.unbuilt]
        messages += [f"skipped {path}: {why}" for path, why in launch[:3]]
        messages += [f"and {len(launch) - 3} more launch files (-v says why)"] * (len(launch) > 3)
    messages = [text(message) for message in messages]  # a file name can hold a line break
    for message in messages:
        terminal.say(message, err=True)
    if statistics:
        from urdftool.report.statistics import render as render_statistics

        report = render_statistics
    else:
        def report(results, stream):
            render(format, results, stream, quiet=quiet,
                   notes=lambda result: notes_shown(result.path, notes, request))
    code = 2 if run.errors or run.unexpanded else 0 if exit_zero else run.exit_code
    if output:
        import io

        from urdftool.description.files import read_elsewhere

        written = io.StringIO()
        report(run.results, written)
        read_elsewhere(path for result in run.results for path in (  # in workers too
            result.read if result.record is None else result.record.reads()))
        terminal.write_output(output, written.getvalue())
    else:
        report(run.results, sys.stdout)
        sys.stdout.flush()  # (the lines below come after the report in a log of both streams)
    for error in run.errors:  # settings broken for some files; the others were checked
        terminal.say(f"urdftool: error: {error}", err=True)
    if run.unexpanded:  # the environment's: said once, after the report that locates each
        from urdftool.report.summary import counted

        # (not "urdftool: error:", which read as urdftool's own failure: it is about the
        # robot's files and this machine, and the run is no pass)
        one = len(run.unexpanded) == 1
        terminal.say(
            f"urdftool: {counted(len(run.unexpanded), 'file')} not checked: a package "
            f"{'it needs' if one else 'they need'} is not installed here, so "
            f"{'its robot was' if one else 'their robots were'} not expanded (U006 in the "
            f"report; nothing in {'it' if one else 'them'} is known to be wrong, and the run "
            "exits 2: not a pass). "
            "Install the dependencies (rosdep install --from-paths . --ignore-src) or pass "
            "--package NAME=PATH" + _undeclared(run), err=True)
    return code


def _unnamed_arguments(run, args: dict[str, str]) -> list[str]:
    """A warning for each xacro argument given (``--arg``, ``NAME:=VALUE``) that no file any
    robot of the run was built from names: it changes nothing (``check --arg lenght=2`` was
    silent where the robot commands warn). Said once for the run, not per robot: an argument
    one robot of a folder reads and another does not is no mistake. Read from what each check
    kept of its robot's text (``FileResult.arguments``, made where the robot was built, and
    kept by the result cache): nothing is read again (every file each robot read was, from
    disk). Not said when that is not known for a robot (one that did not load, a result
    kept before it was kept): said only when it holds."""
    if not args or not run.results:
        return []  # (before the imports: a check without --arg imports no mesh module here)
    arguments = [result.arguments for result in run.results]
    if any(kept is None for kept in arguments):
        return []
    from urdftool.description.xacro_text import run_argument_warnings
    from urdftool.report.summary import counted

    return run_argument_warnings(arguments, args, f"the {counted(len(run.results), 'robot')} "
                                 "checked")


def _undeclared(run) -> str:
    """What the closing line adds when a package a file was not checked for is declared by no
    package.xml (its U006 a warning, not a note): rosdep installs nothing for it, and it may
    be a misspelt name (doosan-robot2's 23 files naming dsr_description, its package
    dsr_description2)."""
    from urdftool.diagnostics import Severity

    if all(finding.severity is Severity.INFO for result in run.results
           for finding in result.not_checked_by):
        return ""
    return ("; rosdep installs only what a package.xml declares: U006 says where none does "
            "(and a name the package may be misspelt for)")


def _default_cache():
    from urdftool.lint.cache import default_folder  # not imported by a run without the cache

    return default_folder()


def _apply_fixes(terminal, run, diff: bool, unsafe: bool, recheck):
    """--diff: print the fixes as a diff and exit; --fix: write them and check again."""
    from urdftool.lint import fixes

    if diff:
        from urdftool.report.unified import unified

        changes = fixes.plan(run.results, unsafe=unsafe)
        _skipped(terminal, changes.skipped)
        # the files' own lines, as terminal text (their tabs kept)
        terminal.show(unified(changes.changed, changes.spans), nl=False, keep="\t\r")  # (a CR LF file's)
        terminal.say(f"urdftool: {_fixes(len(changes.applied))} in {len(changes.changed)} "
                     "file(s) would be applied", err=True)
        raise terminal.exit(1 if changes.changed else 0)
    rerun = []

    def again():
        rerun.append(recheck())
        return rerun[-1].results

    _, applied, changed, skipped = fixes.apply(run.results, again, unsafe=unsafe)
    _skipped(terminal, skipped)
    if applied:
        terminal.say(f"urdftool: applied {_fixes(applied)} in {len(changed)} file(s)", err=True)
    return rerun[-1] if rerun else run


def _skipped(terminal, skipped) -> None:
    for fix, why in skipped:
        terminal.say(f"urdftool: not fixed ({fix.description}): {why}", err=True)


def _fixes(count: int) -> str:
    return f"{count} fix" if count == 1 else f"{count} fixes"
