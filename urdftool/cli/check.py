"""``urdftool check``: the linter and CI step."""

from __future__ import annotations

import sys
from pathlib import Path

import typer

from urdftool.errors import UsageError
from urdftool.cli._common import (PackageOption, XacroArgOption, document, fail_usage,
                                  max_memory_option, refuse_bad_outputs, robot_inputs, say, show,
                                  timeout_option, write_output)
from urdftool.report import FORMATS as REPORT_FORMATS

FORMATS = (*REPORT_FORMATS, "auto")  # auto: github under GitHub Actions, else text


def register(app: typer.Typer) -> None:
    app.command(
        "check",
        help="Check robot descriptions (files or folders) and report problems. "
             "Exit code: 0 clean, 1 errors (or warnings with --strict), 2 usage error.",
    )(check)


def check(
    words: list[str] = typer.Argument(..., metavar="PATH... [NAME:=VALUE...]",
                                      help="URDF/xacro files or folders; '-' reads stdin."),
    arg: list[str] = XacroArgOption,
    package: list[str] = PackageOption,
    format: str = typer.Option("auto", "--format", "-f",
                               help="text, concise, json, json-lines, sarif, junit, github, "
                                    "gitlab, rdjson, or auto (github under GitHub Actions, "
                                    "else text)."),
    output: Path = typer.Option(None, "--output", "-o", help="Write the report to this file."),
    select: list[str] = typer.Option([], "--select", metavar="CODES",
                                     help="Only these codes, prefixes or names "
                                          "(comma-separated, repeatable)."),
    ignore: list[str] = typer.Option([], "--ignore", metavar="CODES",
                                     help="Skip these codes, prefixes or names."),
    target: list[str] = typer.Option([], "--target", "-t", metavar="NAME",
                                     help="Also check what this simulator refuses or changes "
                                          "(repeatable): gazebo, gz, mujoco, drake, pybullet, "
                                          "isaac, pinocchio; NAME@VERSION for an older one. "
                                          "See docs/targets.md."),
    strict: bool = typer.Option(False, "--strict", help="Exit 1 on warnings too."),
    verbose: bool = typer.Option(False, "--verbose", "-v", help="Say which files were skipped, "
                                 "and which companion files each robot was checked with."),
    quiet: bool = typer.Option(False, "--quiet", "-q",
                               help="Text format: print the findings only, no summary line."),
    notes: bool = typer.Option(None, "--notes/--no-notes", show_default=False,
                               help="Text format: show the notes (severity info: what a check "
                                    "assumed or could not do, not problems); the other formats "
                                    "always include them [default: --no-notes, or notes in "
                                    "the settings]."),
    exit_zero: bool = typer.Option(False, "--exit-zero",
                                   help="Exit 0 even when problems are found (usage errors "
                                        "still exit 2)."),
    statistics: bool = typer.Option(False, "--statistics",
                                    help="Print how many times each rule fired, most first, "
                                         "instead of the findings."),
    config: Path = typer.Option(None, "--config", metavar="FILE",
                                help="Use this settings file for every path instead of the "
                                     "one found above each."),
    isolated: bool = typer.Option(False, "--isolated",
                                  help="Ignore every settings file."),
    stdin_filename: str = typer.Option(None, "--stdin-filename", metavar="PATH",
                                       help="The path standard input is checked as: its "
                                            "includes, packages and settings are found from "
                                            "there, and findings name it."),
    allow_env: bool = typer.Option(
        None, "--allow-env/--no-env", show_default=False,
        help="--no-env, the safe mode for untrusted input: the environment is never read "
             "($(env) is an error, $(optenv NAME DEFAULT) its default) and xacro reads no "
             "file outside the repository and its packages. --allow-env: "
             "both allowed. [default: --no-env when CI is set, as CI services do; else "
             "--allow-env]"),
    max_file_size: int = typer.Option(None, "--max-file-size", metavar="BYTES",
                                      help="Refuse input files larger than this [default: 16 MiB]."),
    controllers: list[Path] = typer.Option([], "--controllers", metavar="FILE",
                                           help="Controller configuration YAML (repeatable) "
                                                "[default: config/*.yaml beside the robot]."),
    srdf: Path = typer.Option(None, "--srdf", metavar="FILE",
                              help="MoveIt SRDF [default: the *.srdf beside the robot]."),
    spec: Path = typer.Option(None, "--spec", metavar="FILE",
                              help="Joint spec table [default: joint_limits.yaml beside the "
                                   "robot, when it is a urdftool spec]."),
    max_triangles: int = typer.Option(None, "--max-triangles", metavar="N", min=1,
                                      help="Refuse meshes with more triangles than this "
                                           "[default: 2,000,000, or max-triangles in the "
                                           "settings]."),
    timeout: float = timeout_option("each file", "the file is stopped and reported as U015, "
                                                 "exit 1", default=None,
                                    note=" [default: 60, or timeout in the settings]"),
    max_memory: str = max_memory_option("each worker", "its file is stopped and reported as "
                                        "U018, exit 1", default=None,
                                        note=" [default: 2G, or max-memory in the settings]"),
    jobs: int = typer.Option(0, "--jobs", "-j", metavar="N",
                             help="Check files in N worker processes [default: one per idle core, "
                                  "at most one per 4 files]."),
    fix: bool = typer.Option(False, "--fix", help="Apply the safe fixes ([*] in the report) to "
                             "the files (inside the repository), then report what remains."),
    unsafe_fixes: bool = typer.Option(False, "--unsafe-fixes",
                                      help="With --fix or --diff: the unsafe fixes ([~]) too."),
    diff: bool = typer.Option(False, "--diff", help="Print the fixes as a unified diff and "
                              "write nothing; exit 1 when there is something to fix."),
    no_cache: bool = typer.Option(False, "--no-cache", help="Neither read nor keep results."),
    cache_dir: Path = typer.Option(None, "--cache-dir", metavar="DIR",
                                   help="Keep results here between runs [default: "
                                        ".urdftool_cache; none when CI is set]."),
) -> None:
    from urdftool.budget import Budget, one_blas_thread
    from urdftool.errors import SettingsError, TargetError, UnknownName
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
        refuse_bad_outputs(output)
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
            run = _apply_fixes(run, diff, unsafe_fixes, lambda: check_paths(paths, request))
    except (UsageError, SettingsError, TargetError, UnknownName) as error:
        fail_usage(error)
    messages = [f"urdftool: {note}" for note in run.notes]
    if verbose:
        messages += [f"skipped {path}: {reason}" for path, reason in run.skipped.items()]
        messages += [f"companion of {result.path}: {line}" for result in run.results
                     for line in result.companions]
    messages = [text(message) for message in messages]  # a file name can hold a line break
    for message in messages:
        say(message, err=True)
    if statistics:
        from urdftool.report.statistics import render as render_statistics

        report = render_statistics
    else:
        def report(results, stream):
            render(format, results, stream, quiet=quiet,
                   notes=lambda result: notes_shown(result.path, notes, request))
    code = 2 if run.errors else 0 if exit_zero else run.exit_code
    keep = output is None and not (fix or diff) and _keeps_output(request, run)
    if output or keep:
        import io

        text = io.StringIO()
        report(run.results, text)
        if output:
            write_output(output, text.getvalue())
        else:
            document(text.getvalue())
            _keep_output(request, run, text.getvalue(), "".join(m + "\n" for m in messages),
                         code)
    else:
        report(run.results, sys.stdout)
    for error in run.errors:  # settings broken for some files; the others were checked
        say(f"urdftool: error: {error}", err=True)
    raise typer.Exit(code)


def _default_cache():
    from urdftool.lint.cache import default_folder  # not imported by a run without the cache

    return default_folder()


def _keeps_output(request, run) -> bool:
    """Whether this run's output is kept for ``urdftool check`` run again with the same words
    (see ``urdftool/__main__.py``): a run the result cache kept whole, started as the program
    (not through the Python API), printing to a file or pipe (a terminal's colours are not
    kept)."""
    from urdftool.cli import COMMAND_LINE

    return COMMAND_LINE is not None and request.cache_dir is not None and \
        run.depends is not None and not sys.stdout.isatty()


def _keep_output(request, run, stdout: str, stderr: str, code: int) -> None:
    from urdftool.cli import COMMAND_LINE
    from urdftool.lint.cache import Cache

    words, environment = COMMAND_LINE  # before check set any variable (one_blas_thread)
    Cache(request.cache_dir).put_output(words, environment, run.depends, stdout, stderr, code)


def _apply_fixes(run, diff: bool, unsafe: bool, recheck):
    """--diff: print the fixes as a diff and exit; --fix: write them and check again."""
    from urdftool.lint import fixes

    if diff:
        from urdftool.report.unified import unified

        changes = fixes.plan(run.results, unsafe=unsafe)
        _skipped(changes.skipped)
        # the files' own lines, as terminal text (their tabs kept)
        show(unified(changes.changed), nl=False, keep="\t")
        say(f"urdftool: {_fixes(len(changes.applied))} in {len(changes.changed)} "
                   "file(s) would be applied", err=True)
        raise typer.Exit(1 if changes.changed else 0)
    rerun = []

    def again():
        rerun.append(recheck())
        return rerun[-1].results

    _, applied, changed, skipped = fixes.apply(run.results, again, unsafe=unsafe)
    _skipped(skipped)
    if applied:
        say(f"urdftool: applied {_fixes(applied)} in {len(changed)} file(s)", err=True)
    return rerun[-1] if rerun else run


def _skipped(skipped) -> None:
    for fix, why in skipped:
        say(f"urdftool: not fixed ({fix.description}): {why}", err=True)


def _fixes(count: int) -> str:
    return f"{count} fix" if count == 1 else f"{count} fixes"
