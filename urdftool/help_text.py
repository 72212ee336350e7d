"""The help texts Typer prints, kept in ``urdftool/data/help.txt`` for ``urdftool/__main__.py``
to print before Typer is imported (see ``urdftool/__main__.py``).

``python -m urdftool.help_text`` writes the file from the Typer app itself: never edit it by
hand. tests/cli/test_help_text.py fails when it is stale, and the program never prints a stale
text: the file carries a digest of the command modules (``urdftool/cli/*.py``) it was made from,
and any other digest sends the words to Typer.
"""

from __future__ import annotations

import contextlib
import io
import os
import sys
from pathlib import Path

from urdftool import __main__ as startup

HEADER = ("# The help texts of urdftool, made by `python -m urdftool.help_text` from the Typer "
          "app; do not edit.\n")


def typer_help(words: list[str]) -> tuple[str, str, int]:
    """(standard output, standard error, exit code) of ``urdftool WORDS`` as Typer answers,
    on a terminal of :data:`urdftool.__main__.HELP_COLUMNS` columns or more."""
    from urdftool.cli import app

    out, err = io.StringIO(), io.StringIO()
    columns = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = str(startup.HELP_COLUMNS)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                app(words, prog_name="urdftool")
                code = 0
            except SystemExit as done:
                code = done.code or 0
    finally:
        if columns is None:
            del os.environ["COLUMNS"]
        else:
            os.environ["COLUMNS"] = columns
    return out.getvalue(), err.getvalue(), code


def texts() -> dict[str, str]:
    """``""`` (the program's help) and each command's name -> the help Typer prints."""
    from urdftool.cli import COMMANDS

    found = {"": typer_help(["--help"])[0]}
    for name in sorted(COMMANDS):
        found[name] = typer_help([name, "--help"])[0]
    return found


def render() -> str:
    """The content of ``urdftool/data/help.txt`` for the command modules as they are now."""
    parts = [HEADER, f"{startup.HELP_MARK}digest {startup.commands_digest()}\n"]
    for name, text in texts().items():
        parts.append(f"{startup.HELP_MARK}help {name}\n{text}")
    return "".join(parts)


def main() -> None:
    from urdftool.description.files import write_file

    path = Path(startup.HELP_FILE)
    write_file(path, render())
    print(f"wrote {path}", file=sys.stderr)


if __name__ == "__main__":
    main()
