"""``urdftool server``: the language server for editors (:mod:`urdftool.server`)."""

from __future__ import annotations

from pathlib import Path

import typer

from urdftool.budget import DEFAULT_TIMEOUT
from urdftool.cli._common import MaxMemoryOption


def register(app: typer.Typer) -> None:
    app.command("server", help="Run the language server (LSP) on standard input and output, "
                               "for editors: diagnostics as you type, rule documentation on "
                               "hover, quick fixes. Needs the lsp extra.")(server)


def server(log_file: Path = typer.Option(None, "--log-file", metavar="FILE",
                                         help="Write the server's log (every message) here."),
           stdio: bool = typer.Option(False, "--stdio", hidden=True,
                                      help="Accepted for clients that pass it; stdio is the "
                                           "only transport."),
           timeout: float = typer.Option(DEFAULT_TIMEOUT, "--timeout", metavar="SECONDS",
                                         help="Time budget per robot checked; 0 for none. "
                                              "Over it: U015 on the robot."),
           max_memory: str = typer.Option(None, "--max-memory", metavar="SIZE",
                                          help=f"{MaxMemoryOption.help} Per robot [default: 2G, "
                                               "or max-memory in the settings].")) -> None:
    try:
        import lsprotocol  # noqa: F401
        import pygls  # noqa: F401
    except ImportError:
        from urdftool.cli._common import say

        say("urdftool: error: the language server needs pygls: pip install 'urdftool[lsp]'",
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
    serve(str(log_file) if log_file else None, Limits(timeout or None, max_memory))
