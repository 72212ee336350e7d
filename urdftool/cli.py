"""The ``urdftool`` command line: thin commands over core modules.

Each command lives in ``urdftool/commands/<name>.py`` with a ``register(app)`` function; heavy
libraries are imported inside the command that needs them, so ``urdftool --help`` stays fast.
"""

from __future__ import annotations

import importlib
import pkgutil

import typer

from urdftool import commands

app = typer.Typer(
    name="urdftool",
    help="Validate and analyse URDF and xacro robot descriptions, without ROS.",
    no_args_is_help=True,
    add_completion=False,
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
def _root(version: bool = typer.Option(False, "--version", callback=_version, is_eager=True,
                                       help="Show the version and exit.")):
    """Validate and analyse URDF and xacro robot descriptions, without ROS."""


for _module in sorted(m.name for m in pkgutil.iter_modules(commands.__path__)
                      if not m.name.startswith("_")):
    importlib.import_module(f"{commands.__name__}.{_module}").register(app)


def main() -> None:
    app()


if __name__ == "__main__":
    main()
