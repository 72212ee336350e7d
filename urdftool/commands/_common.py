"""Options and argument parsing shared by commands that load a robot."""

from __future__ import annotations

import sys
from pathlib import Path

import typer

from ..errors import UsageError

ARG_HELP = "xacro argument NAME=VALUE (repeatable); NAME:=VALUE words after the file work too."
PACKAGE_HELP = "Where a ROS package is: NAME=PATH (repeatable)."

XacroArgOption = typer.Option([], "--arg", metavar="NAME=VALUE", help=ARG_HELP)
PackageOption = typer.Option([], "--package", "-p", metavar="NAME=PATH", help=PACKAGE_HELP)


def split_words(words: list[str]) -> tuple[list[str], dict[str, str]]:
    """Separate ``name:=value`` xacro words from paths."""
    paths, args = [], {}
    for word in words:
        if ":=" in word:
            name, _, value = word.partition(":=")
            args[name] = value
        else:
            paths.append(word)
    return paths, args


def pairs(values: list[str], what: str, separator: str = "=") -> dict[str, str]:
    """``NAME=VALUE`` option values as a dict; a malformed one is a usage error."""
    result = {}
    for value in values:
        name, sep, rest = value.partition(separator)
        if not sep or not name:
            raise UsageError(f"{what} must be NAME{separator}VALUE, got '{value}'")
        result[name] = rest
    return result


def robot_inputs(words: list[str], arg_options: list[str], package_options: list[str]):
    """(paths, xacro args, packages) from a command's words and options; checks paths exist."""
    paths, args = split_words(words)
    args.update(pairs(arg_options, "--arg"))
    packages = {name: Path(path) for name, path in pairs(package_options, "--package").items()}
    for path in paths:
        if path != "-" and not Path(path).exists():
            raise UsageError(f"path '{path}' does not exist")
    return paths, args, packages


def fail_usage(error: UsageError) -> None:
    typer.echo(f"urdftool: error: {error}", err=True)
    raise typer.Exit(2)


def refuse_bad_outputs(*paths) -> None:
    """Exit 2 with one line when an output path given (None: not given) cannot be written: its
    folder is missing or it is a folder. Call it before the work."""
    from ..files import check_output

    try:
        for path in paths:
            if path is not None:
                check_output(path)
    except UsageError as error:
        fail_usage(error)


def write_output(path, data: str | bytes) -> None:
    """Write an output file with :func:`urdftool.files.write_file` (a symbolic link planted at
    ``path`` is replaced, never followed); exit 2 with one line when it cannot be written."""
    from ..files import write_file

    try:
        write_file(path, data)
    except UsageError as error:
        fail_usage(error)


def fail_at(robot, error: Exception) -> None:
    """Print ``error`` where it is (its ``where``, else its ``element`` in ``robot``, else the
    robot's file) and exit 1."""
    where = getattr(error, "where", None) or robot.locate(getattr(error, "element", None))
    typer.echo(f"{where}: error: {error}", err=True)
    raise typer.Exit(1)


def single_robot(command: str, words: list[str], arg_options: list[str],
                 package_options: list[str], choices: dict[str, tuple] | None = None,
                 problems=(), **load_options):
    """The one robot a command analyses, loaded.

    Usage errors exit 2 before anything is loaded: not exactly one FILE, an option value not
    among its choices, or the first of ``problems`` that is true. A robot that does not load
    prints as located diagnostics and exits 1.

    choices: {option: (value, allowed values)}, e.g. {"--format": (fmt, ("text", "json"))}
    problems: (is wrong, message) pairs for the command's own option checks
    load_options: passed to ``urdftool.loader.load`` (e.g. ``allow_env``)
    """
    from ..errors import LoadError
    from ..loader import load

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
    try:
        return load(paths[0], xacro_args=args, packages=packages, **load_options)
    except LoadError as error:
        from ..engine import FileResult
        from ..report import render

        render("text", [FileResult(paths[0], error.findings)], sys.stderr)
        raise typer.Exit(1)


def wide_console():
    """A rich console at least 150 columns wide: tables of poses are wide; do not squeeze them."""
    from rich.console import Console

    console = Console(highlight=False)
    console.width = max(console.width, 150)
    return console


def fixed(value: float, places: int = 6) -> str:
    """``value`` with ``places`` decimals, without the '-0.000000' that round-off leaves."""
    text = f"{value:.{places}f}"
    return text[1:] if text.startswith("-") and not text.strip("-0.") else text
