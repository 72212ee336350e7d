"""Options and argument parsing shared by commands that load a robot."""

from __future__ import annotations

import functools
import inspect
import sys
import typing
from pathlib import Path

import typer

from urdftool.budget import DEFAULT_TIMEOUT
from urdftool.errors import UsageError
from urdftool.terminal import Terminal, pairs, robot_inputs, split_words  # noqa: F401

# how the commands print and exit: click's echo, Typer's Exit (urdftool.terminal: the only ways
# a command prints)
TYPER = Terminal(typer.echo, typer.Exit)
say, show, document, fail_usage = TYPER.say, TYPER.show, TYPER.document, TYPER.fail_usage
refuse_bad_outputs, write_output = TYPER.refuse_bad_outputs, TYPER.write_output

ARG_HELP = "xacro argument NAME=VALUE (repeatable); NAME:=VALUE words after the file work too."
PACKAGE_HELP = "Where a ROS package is: NAME=PATH (repeatable)."

XacroArgOption = typer.Option([], "--arg", metavar="NAME=VALUE", help=ARG_HELP)
PackageOption = typer.Option([], "--package", "-p", metavar="NAME=PATH", help=PACKAGE_HELP)


def timeout_option(what: str, over: str, default: float | None = DEFAULT_TIMEOUT,
                   note: str = ""):
    """``--timeout``, its help saying what the budget covers (``what``: "each file", "the
    command") and what happens over it (``over``)."""
    return typer.Option(default, "--timeout", metavar="SECONDS",
                        help=f"Seconds {what} may take; 0 for none. Over it: {over}.{note}")


def max_memory_option(what: str, over: str, default: str | None = "2G", note: str = ""):
    """``--max-memory``, its help saying whose memory it bounds (``what``)."""
    return typer.Option(default, "--max-memory", metavar="SIZE",
                        help=f"Memory (address space) {what} may use, e.g. 2G, 512M; 0 for "
                             f"none. Over it: {over}.{note}")


# the commands that analyse one robot (``budgeted``): the budget is the whole command's
TimeoutOption = timeout_option("the command", "it stops and reports U015, exit 1")
MaxMemoryOption = max_memory_option("the command", "it stops and reports U018, exit 1")
MAX_SCENE_TRIANGLES = 8_000_000  # urdftool.kinematics.scene's (not imported: start-up time)
MaxSceneTrianglesOption = typer.Option(
    MAX_SCENE_TRIANGLES, "--max-scene-triangles", min=0, metavar="N",
    help="Refuse, before any work, to draw a robot whose geometry holds more triangles (every "
         "instance of a mesh counted; memory and time grow with them); 0 for no limit.")


def fail_over_limit(error, option: str) -> None:
    """Exit 2 for a size limit (``errors.OverLimit``) checked before the work, naming the option
    that raises it."""
    fail_usage(UsageError(f"{error} (raise it with {option})"))


def fail_config(error, option: str) -> None:
    """Exit 2 for a ConfigError about ``option``'s values, the option named first; an error about
    a file (its ``where``) already says where it is."""
    fail_usage(UsageError(str(error) if error.where else f"{option}: {error}"))


def given(*names: str) -> list[str]:
    """The options among ``names`` (their parameters' names: ``"min_fraction"``) that the
    command line wrote, as its help names them (``--min-fraction``), in the command's order. One
    left at its default was not given, whatever its value."""
    from typer._click.core import ParameterSource  # typer's own click, not the package's
    from typer._click.globals import get_current_context

    context = get_current_context(silent=True)
    if context is None:
        return []
    return [next((o for o in parameter.opts if o.startswith("--")), parameter.opts[0])
            for parameter in context.command.params
            if parameter.name in names and context.get_parameter_source(parameter.name)
            in (ParameterSource.COMMANDLINE, ParameterSource.ENVIRONMENT)]


def only_with(names: tuple[str, ...], needed: bool, what: str) -> tuple[bool, str]:
    """A ``problems`` pair of :func:`single_robot`: the options among ``names`` given without
    what they act on (``needed`` false; ``what``: "--matrix"). A command read them and did
    nothing with them before (``collisions --samples 500`` at one pose, ``inertia --all``
    without ``--write``, ``fk --seed 3`` with ``--q``), exit 0, as if they had counted."""
    options = [] if needed else given(*names)
    listed = ", ".join(options[:-1]) + f" and {options[-1]}" if len(options) > 1 else \
        "".join(options)
    return (bool(options), f"{listed} {'needs' if len(options) == 1 else 'need'} {what} "
                           f"(without it, {'it does' if len(options) == 1 else 'they do'} "
                           "nothing)")


def joint_words(values: list[str], option: str) -> dict[str, str]:
    """``{joint: text}`` from an option's ``NAME=VALUE`` values, split at the last '=' (a
    joint name may hold '=', a value does not); exit 2 when one is malformed."""
    try:
        return pairs(values, option, strip=True, last=True)
    except UsageError as error:
        fail_usage(error)


def warn(warnings) -> None:
    for warning in warnings:
        say(f"urdftool: warning: {warning}", err=True)


def error_format() -> str | None:
    """The ``--format`` of the command now running, as its command line gave it (click's
    context, read where an error is reported): the one owner of "errors as JSON". With json, an
    error about the robot (exit 1) is also a JSON document on standard output
    (report.json_format's error_document), so that a script reading it gets one. None outside a
    command, or for one without ``--format``. (Each command set a module-level value before, by
    ``budgeted``, ``single_robot`` or itself: one that forgot, or a value left by the command
    before it in the same process, gave the wrong format. The door's plain ``check``, which
    runs without click, writes its errors in its own report: urdftool.checking.)"""
    from typer._click.globals import get_current_context  # typer's own click

    context = get_current_context(silent=True)
    if context is None:
        return None
    return next((context.params.get(parameter.name) for parameter in context.command.params
                 if "--format" in parameter.opts), None)


def _error_document(results=(), message=None, location=None) -> None:
    if error_format() == "json":
        from urdftool.report.json_format import error_document
        from urdftool.report.json_output import dumps

        show(dumps(error_document(results, message, location)))


def fail_at(robot, error: Exception, option: str | None = None) -> None:
    """End the command on ``error`` by whose it is (its ``asked``: the one place every command
    decides it, :class:`~urdftool.errors.UrdftoolError`). The question's (a name the robot
    does not have, a tip not below its base, a limb or chain no joint moves or that runs
    through a joint the computation does not take, a D-H table that cannot be read or does not
    fit the robot) is a usage error in every command: one line, exit 2, the place first when
    there is one (the table's file and row; the joint of the robot it is about). The robot's is printed where it is (its ``where``, else its
    ``element`` in ``robot``, else the robot's file), exit 1. (dh, ik and workspace exited 1
    for "swap --base and --tip" and "no joint moves 'a'", 2 for a link that does not exist.)
    ``option``: the option that asked (``--chain``), named first in a usage error."""
    if getattr(error, "asked", False):
        text, element = str(error), getattr(error, "element", None)
        where = getattr(error, "where", None) or (robot.locate(element) if element is not None
                                                  else None)
        text = f"{where}: {text}" if where and not text.startswith(f"{where}:") else text
        fail_usage(UsageError(f"{option}: {text}" if option else text))
    where = getattr(error, "where", None) or robot.locate(getattr(error, "element", None))
    say(f"{where}: error: {error}", err=True)
    _error_document(message=str(error), location=where)
    raise typer.Exit(1)


def missing_extra_exit(command: str, error: ImportError) -> int:
    """Say which extra to install when a command needs an analysis library that a lint-only
    install leaves out, and return the exit code, 2; any other ImportError is a bug: raised."""
    from urdftool.errors import missing_extra

    advice = missing_extra(error)
    if advice is None:
        raise error
    say(f"urdftool: error: urdftool {command} {advice}", err=True)
    return 2


def fail_unbuildable(error) -> int:
    """Report why Pinocchio could not build the robot's model: the linter's errors, each at its
    line (what urdfdom refused, in urdftool's words), else urdfdom's own reasons; returns 1."""
    from urdftool.diagnostics import Severity
    from urdftool.lint.engine import check_robot

    robot = error.robot
    errors = [f for f in check_robot(robot) if f.severity is Severity.ERROR]
    if errors:
        report_findings(robot.path, errors)
    else:
        say(f"{robot.locate(error.element)}: error: {error}", err=True)
        _error_document(message=str(error), location=robot.locate(error.element))
    return 1


def single_robot(command: str, words: list[str], arg_options: list[str],
                 package_options: list[str], choices: dict[str, tuple] | None = None,
                 problems=(), **load_options):
    """The one robot a command analyses, loaded.

    Usage errors exit 2 before anything is loaded: not exactly one FILE, an option value not
    among its choices, or the first of ``problems`` that is true. A robot that does not load
    prints as located diagnostics and exits 1, and so does one without a link (but for
    ``xacro``: a macro library's expansion has none).

    choices: {option: (value, allowed values)}, e.g. {"--format": (fmt, ("text", "json"))}
    problems: (is wrong, message) pairs for the command's own option checks
    load_options: passed to ``urdftool.description.load.load`` (``allow_env``: None, the
        default, is the safe mode when ``CI`` is set, see description.files.env_allowed)
    """
    try:
        paths, args, packages = robot_inputs(words, arg_options, package_options)
        if len(paths) != 1:
            raise UsageError(f"{command} takes exactly one FILE")
        for option, (value, allowed) in (choices or {}).items():
            if value not in allowed:
                raise UsageError(f"{option} must be one of {', '.join(allowed)}, not '{value}'")
        for wrong, message in problems:
            if wrong:
                raise UsageError(message)
    except UsageError as error:
        fail_usage(error)
    robot = load_robot(paths[0], args, packages, **load_options)
    warn_unnamed_arguments(robot, args)
    if not robot.links and command != "xacro":  # a macro library expands to no link: xacro's
        _refuse_linkless(robot)
    if command in POSING:
        refuse_refused(robot, posing=True)
    if command != "xacro":
        _warn_unread_link(robot)
        _warn_beside_the_tree(robot, command)
    return robot


def _warn_beside_the_tree(robot, command: str) -> None:
    """A warning naming the links beside the tree (a loop of joints no root reaches), which
    urdfdom drops and so does every command (``check`` says why: the loop's finding)."""
    from urdftool.errors import listed
    from urdftool.kinematics.tree import beside_the_tree

    dropped = beside_the_tree(robot)
    if dropped:
        them = "them" if len(dropped) > 1 else "it"
        done = f"drawn dashed, apart from the tree, as urdfdom leaves {them} out of its model" \
            if command == "graph" else f"left out as urdfdom leaves {them} out of its model"
        warn([f"{len(dropped)} link{'s' * (len(dropped) > 1)} beside the tree, which no joint "
              f"from the root reaches, {done}: {listed(dropped)} ('urdftool check' says why)"])


def _warn_unread_link(robot) -> None:
    """A warning for a link without a ``name`` that holds anything, on a robot urdfdom takes
    (the only link: U103's shape urdfdom takes, the link ``''``): urdfdom's parseLink stops at
    the missing name, so its model (check_urdf's, robot_state_publisher's, Pinocchio's, which
    ``fk``, ``ik`` and ``dynamics`` compute with) has the link and nothing in it, and so do
    ``collisions`` and ``render`` (``inertia`` compares what the file declares)."""
    names = robot.names()
    for link in robot.children("link"):
        held = sorted({child.tag for child in link if isinstance(child.tag, str)})
        if names[link] is None and held:
            warn([f"{robot.locate(link)}: <link> has no name attribute: urdfdom reads it as "
                  f"the link '' and stops there, so its {', '.join(f'<{t}>' for t in held)} "
                  "are in no model urdfdom or Pinocchio builds, nor in the commands that pose "
                  "the robot (dynamics: no mass; collisions, render: no shape); give it a "
                  "name"])


def warn_unnamed_arguments(robot, args: dict[str, str]) -> None:
    """A warning for each xacro argument given (``--arg NAME=VALUE``, ``NAME:=VALUE``) that
    no file of the robot names: xacro takes it and it changes nothing (a misspelt name
    computed the defaults without a word)."""
    from urdftool.description.xacro_text import argument_warnings
    from urdftool.errors import listed

    if not args:
        return
    if not robot.from_xacro:
        warn([f"xacro argument{'s' * (len(args) > 1)} {listed(args)} given, but "
              f"{robot.display} is read as URDF, not expanded by xacro: "
              f"{'they change' if len(args) > 1 else 'it changes'} nothing"])
        return
    warn(argument_warnings(robot.sources, args, "the robot"))


# the commands that pose the robot (a model of its joints and links: Pinocchio's, yourdfpy's,
# urdftool's own): a robot in error they cannot pose is refused before any model is built
POSING = frozenset({"fk", "dh", "ik", "dynamics", "collisions", "render", "workspace"})


def refuse_refused(robot, posing: bool = False) -> None:
    """A robot urdfdom refuses (check_urdf, robot_state_publisher, Pinocchio: every consumer),
    and with ``posing`` one whose links no model of its joints poses (a link with two parents):
    the linter's errors at their lines as ``check`` gives them, exit 1; the one owner of "this
    robot cannot be loaded, because". Each model found its own words for it before, when it
    found any: fk's 'no root link (a cycle?)' for U109 and 'reached twice (a cycle?)' for two
    parents, render's 'yourdfpy cannot build the scene' (U207, U107) or a traceback (U105,
    U109), dynamics none (U107: the link under one of its parents). A part of a robot defined
    elsewhere (lint.parts: ridgeback_iiwa's arm, hung on the base's ``mid_mount``), whose
    refusals are notes, is said as that part: fk and tree said 'no root link (a cycle?)',
    render that an element lacks its 'name'."""
    from urdftool.lint.engine import POSING_REFUSES, URDFDOM_REFUSES, urdfdom_refusals
    from urdftool.lint.parts import part

    refusals = urdfdom_refusals(robot, POSING_REFUSES if posing else URDFDOM_REFUSES)
    if refusals:
        report_findings(robot.path, refusals)
        raise typer.Exit(1)
    found = part(robot)  # (its refusals are notes: right inside the robot that includes it)
    if found is not None:
        where, message = robot.locate(robot.root), (
            f"{found.condition}: it cannot be loaded alone (urdfdom refuses it too); give the "
            "robot that includes it")
        say(f"{where}: error: {message}", err=True)
        _error_document(message=message, location=where)
        raise typer.Exit(1)


def _refuse_linkless(robot) -> None:
    """A robot without a link has nothing to compute or draw: urdfdom's refusal (U106) at its
    line, exit 1, as ``tree`` gives it. Each command found its own words for it before: 'no
    root link (a cycle?)', an empty graph, '(0 links)', a picture of 0 triangles. (An only
    ``<link/>`` is a link: the link ``''``, as urdfdom reads it; Robot.links.)"""
    from urdftool.lint.engine import urdfdom_refusals

    refusals = urdfdom_refusals(robot)
    if refusals:
        report_findings(robot.path, refusals)
    else:
        say(f"{robot.locate(robot.root)}: error: robot has no <link> elements", err=True)
        _error_document(message="robot has no <link> elements", location=robot.locate(robot.root))
    raise typer.Exit(1)


def load_robot(path: str, args: dict[str, str], packages, **load_options):
    """The robot at ``path`` loaded; one that does not load prints as located diagnostics
    and exits 1, or 2 as ``check`` does when a package it needs is not installed (U006: the
    machine's, not the robot's; nothing was computed)."""
    from urdftool.errors import LoadError
    from urdftool.description.load import load

    try:  # (allow_env None: load's, check's, safe mode under CI)
        return load(path, xacro_args=args, packages=packages, **load_options)
    except LoadError as error:
        refuse_unloaded(path, error)


def refuse_unloaded(path: str, error) -> None:
    """Report the :class:`~urdftool.errors.LoadError` of the robot at ``path`` as ``check``
    does, located, and exit as it does: 2 when a package it needs is not installed (U006), else
    1."""
    from urdftool.lint.engine import FileResult, load_error_findings

    result = FileResult(path, load_error_findings(error))
    report_findings(path, result.findings)
    raise typer.Exit(2 if result.unexpanded else 1)


def budgeted(command):
    """``command`` with ``--timeout`` and ``--max-memory`` options, run within that budget in a
    forked process (see urdftool.lint.pool): over it, a finding located where the work was (U015,
    U018) and exit 1. The command's first word is the robot it is about."""
    signature = inspect.signature(command, eval_str=True)
    options = {"timeout": (float, TimeoutOption), "max_memory": (str, MaxMemoryOption)}

    @functools.wraps(command)
    def run(**kwargs):
        from urdftool.budget import Budget
        from urdftool.lint.pool import Stop, run_budgeted

        try:
            budget = Budget.of(kwargs.pop("timeout"), kwargs.pop("max_memory"))
        except UsageError as error:
            fail_usage(error)
        path = next(iter(split_words(kwargs.get("words") or [])[0]), "-")
        stdin = None
        if path == "-" and not budget.unlimited:  # only this process can read it
            from urdftool.description.load import DEFAULT_MAX_FILE_SIZE

            stdin = sys.stdin.buffer.read(DEFAULT_MAX_FILE_SIZE + 1)

        def work(_):
            """The command in the worker, its exit status as its output decides (a reader
            that left, a full disk: :func:`urdftool.streams.end`)."""
            from urdftool import streams

            try:
                return streams.end(worked())
            except BaseException:
                if not streams.failed():
                    raise
                return streams.end(1)

        def worked():
            from urdftool.errors import ModelBuildError, OverLimit

            if stdin is not None:
                sys.stdin = _bytes_stdin(stdin)
            try:
                command(**kwargs)
            except typer.Exit as exit:
                return exit.exit_code
            except ModelBuildError as error:
                return fail_unbuildable(error)
            except (OverLimit, UsageError) as error:  # a size limit checked before the work,
                # an output file the system refuses: a usage error
                say(f"urdftool: error: {error}", err=True)
                return 2
            except ImportError as error:
                return missing_extra_exit(command.__name__, error)
            return 0

        [result] = run_budgeted(1, work, budget, lambda _, stop: stop)
        if isinstance(result, Stop):
            if result.kind == "crash":  # a traceback: its lines quote the robot's names
                show(result.detail, err=True, nl=False)
            else:
                from urdftool.lint.engine import stop_finding

                report_findings(path, [stop_finding(path, result, f"urdftool {command.__name__}")])
            raise typer.Exit(1)
        raise typer.Exit(result)

    run.__signature__ = signature.replace(parameters=[
        *signature.parameters.values(),
        *(inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=default,
                            annotation=kind) for name, (kind, default) in options.items())])
    run.__annotations__ = {**typing.get_type_hints(command),
                           **{name: kind for name, (kind, _) in options.items()}}
    return run


def _bytes_stdin(data: bytes):
    import io

    return io.TextIOWrapper(io.BytesIO(data), encoding="utf-8")


def report_findings(path: str, findings) -> None:
    """Print findings about the robot at ``path`` to stderr as ``check`` would (and with
    ``--format json`` as a JSON document on stdout: :func:`error_format`)."""
    from urdftool.lint.engine import FileResult
    from urdftool.records import replace
    from urdftool.report import render

    # (text as check's, without its "[*] fixable with --fix": this command has no --fix)
    render("text", [FileResult(path, [replace(f, fix=None) for f in findings])], sys.stderr)
    fixable = sum(f.fix is not None and f.fix.safe for f in findings)
    if fixable:
        say(f"[*] {fixable} fixable with `urdftool check --fix`", err=True)
    _error_document([FileResult(path, findings)])
