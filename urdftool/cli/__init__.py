"""The ``urdftool`` command line: thin commands over core modules.

Each command lives in ``urdftool/cli/<name>.py`` with a ``register(app)`` function, listed in
``COMMANDS``; heavy libraries are imported inside the command that needs them, so
``urdftool --help`` stays fast.
"""

from __future__ import annotations

import typer

from urdftool.cli import (check, collisions, dh, diff, dynamics, fk, graph, ik, inertia, render,
                          rules, server, tree, workspace, xacro)

COMMANDS = (check, collisions, dh, diff, dynamics, fk, graph, ik, inertia, render, rules, server,
            tree, workspace, xacro)

app = typer.Typer(
    name="urdftool",
    help="Validate and analyse URDF and xacro robot descriptions, without ROS.",
    no_args_is_help=True,
    add_completion=True,  # --install-completion / --show-completion for bash, zsh, fish
    pretty_exceptions_enable=False,
    rich_markup_mode=None,  # plain click help: rich formatting costs ~0.4 s of imports
    context_settings={"help_option_names": ["-h", "--help"]},
)


def _version(value: bool):
    if value:
        from urdftool import __version__

        typer.echo(f"urdftool {__version__}")
        raise typer.Exit()


@app.callback()
def _root(version: bool = typer.Option(False, "--version", "-V", callback=_version,
                                       is_eager=True, help="Show the version and exit.")):
    """Validate and analyse URDF and xacro robot descriptions, without ROS."""


for _command in COMMANDS:
    _command.register(app)


def main() -> None:
    app()


if __name__ == "__main__":
    main()
