"""``urdftool server``: the language server for editors (:mod:`urdftool.server`)."""

from __future__ import annotations

from pathlib import Path

import typer

from urdftool.cli._common import max_memory_option, timeout_option


def register(app: typer.Typer) -> None:
    app.command("server", help="Run the language server (LSP) on standard input and output, "
                               "for editors: diagnostics as you type, rule documentation on "
                               "hover, quick fixes. Needs the lsp extra.")(server)


def server(log_file: Path = typer.Option(None, "--log-file", metavar="FILE",
                                         help="Write the server's log (every message) here."),
           stdio: bool = typer.Option(False, "--stdio", hidden=True,
                                      help="Accepted for clients that pass it; stdio is the "
                                           "only transport."),
           timeout: float = timeout_option("each robot checked", "U015 on the robot"),
           max_memory: str = max_memory_option(
               "each robot checked", "U018 on the robot", default=None,
               note=" [default: max-memory in the settings, or 2G]")) -> None:
    try:
        import lsprotocol  # noqa: F401
        import pygls  # noqa: F401
    except ImportError:
        from urdftool.cli._common import say
        from urdftool.origin import install_command

        say(f"urdftool: error: the language server needs pygls: {install_command('lsp')}",
            err=True)
        raise typer.Exit(2)
    from urdftool.budget import Budget
    from urdftool.cli._common import fail_usage
    from urdftool.errors import UsageError
    from urdftool.server import Limits, serve

    try:
        Budget.of(timeout, max_memory)  # well formed
    except UsageError as error:
        fail_usage(error)
    raise typer.Exit(serve(str(log_file) if log_file else None,
                           Limits(timeout or None, max_memory)))
