"""``urdftool server``: the language server for editors (:mod:`urdftool.server`)."""

from __future__ import annotations

from pathlib import Path

import typer


def register(app: typer.Typer) -> None:
    app.command("server", help="Run the language server (LSP) on standard input and output, "
                               "for editors: diagnostics as you type, rule documentation on "
                               "hover, quick fixes. Needs the lsp extra.")(server)


def server(log_file: Path = typer.Option(None, "--log-file", metavar="FILE",
                                         help="Write the server's log (every message) here."),
           stdio: bool = typer.Option(False, "--stdio", hidden=True,
                                      help="Accepted for clients that pass it; stdio is the "
                                           "only transport.")) -> None:
    try:
        import lsprotocol  # noqa: F401
        import pygls  # noqa: F401
    except ImportError:
        from urdftool.origin import install_command

        typer.echo(f"urdftool: error: the language server needs pygls: {install_command('lsp')}",
                   err=True)
        raise typer.Exit(2)
    from urdftool.server import serve

    serve(str(log_file) if log_file else None)
