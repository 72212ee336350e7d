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


def single_robot_input(command: str, words: list[str], arg_options: list[str],
                       package_options: list[str]):
    """(path, xacro args, packages) for commands that take exactly one robot; exit 2 otherwise."""
    try:
        paths, args, packages = robot_inputs(words, arg_options, package_options)
        if len(paths) != 1:
            raise UsageError(f"{command} takes exactly one FILE")
    except UsageError as error:
        fail_usage(error)
    return paths[0], args, packages


def fail_usage(error: UsageError) -> None:
    typer.echo(f"urdftool: error: {error}", err=True)
    raise typer.Exit(2)


def load_one(path: str, args, packages, **kwargs):
    """Load one robot for an analysis command; load failures print as diagnostics, exit 1."""
    from ..errors import LoadError
    from ..loader import load

    try:
        return load(path, xacro_args=args, packages=packages, **kwargs)
    except LoadError as error:
        from ..engine import FileResult
        from ..report import render

        render("text", [FileResult(path, error.findings)], sys.stderr)
        raise typer.Exit(1)
