"""The help texts Typer prints, and the parameters of the commands whose plain words the door
parses itself, kept in ``urdftool/data/help.txt`` for ``urdftool/__main__.py`` to use before
Typer is imported (see ``urdftool/__main__.py``).

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


# the commands whose words the door parses itself when they are plain
PARSED = ("check",)


def words(name: str) -> str:
    """The parameters of the command ``name`` as the door's parser reads them
    (:func:`urdftool.__main__.plain_words`): a line each, of its name, kind, option names,
    negative option names and default, tab-separated. ValueError for a parameter of a kind the
    parser does not know (teach it first)."""
    from urdftool.cli import command

    lines = []
    for param in command(name).params:
        kind = _kind(param)
        default = param.default
        if isinstance(default, bool) or default is None:
            text = repr(default)
        elif isinstance(default, (list, tuple)) and not default:
            text = "[]"
        elif isinstance(default, str) and default.isprintable() and "\t" not in default:
            text = "'" + default
        elif isinstance(default, (int, float)) and kind in ("int", "float"):
            text = repr(default)
        else:
            raise ValueError(f"{name} {param.name}: no way to keep the default {default!r}")
        lines.append("\t".join((param.name, kind, ",".join(param.opts),
                                ",".join(param.secondary_opts), text)))
    return "".join(line + "\n" for line in lines)


def _kind(param) -> str:
    """How the door reads a click parameter's values: 'words' (the arguments), 'flag',
    'switch' (--a/--no-a), 'texts' or 'paths' (repeatable), 'text', 'path', 'int', 'float',
    'int>=N'."""
    kind = param.type.name
    if param.param_type_name == "argument":
        if param.nargs == -1 and kind == "str":
            return "words"
    elif param.is_flag and kind == "boolean" and not param.count:
        return "switch" if param.secondary_opts else "flag"
    elif param.nargs == 1 and not param.secondary_opts and param.envvar is None:
        if param.multiple and kind in ("str", "path"):
            return {"str": "texts", "path": "paths"}[kind]
        if not param.multiple and kind in ("str", "path", "int", "float"):
            return {"str": "text"}.get(kind, kind)
        if not param.multiple and kind == "int range" and param.type.max is None and \
                not param.type.min_open and not param.type.clamp:
            return f"int>={param.type.min}"
    raise ValueError(f"{param.name}: {param.param_type_name} of type {kind}, which the door "
                     "cannot read")


def render() -> str:
    """The content of ``urdftool/data/help.txt`` for the command modules as they are now."""
    parts = [HEADER, f"{startup.HELP_MARK}digest {startup.commands_digest()}\n"]
    for name, text in texts().items():
        parts.append(f"{startup.HELP_MARK}help {name}\n{text}")
    for name in PARSED:
        parts.append(f"{startup.HELP_MARK}words {name}\n{words(name)}")
    return "".join(parts)


def main() -> None:
    from urdftool.description.files import write_file

    path = Path(startup.HELP_FILE)
    write_file(path, render(), rewrites=True)
    print(f"wrote {path}", file=sys.stderr)


if __name__ == "__main__":
    main()
