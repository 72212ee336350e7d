"""The command group (urdftool/cli/__init__.py): commands are imported only when they run, and
``urdftool --help`` lists them exactly as the eagerly built group would."""

from __future__ import annotations

import re
import subprocess
import sys

import typer
from typer.testing import CliRunner

from urdftool import cli

ENV = {"COLUMNS": "100", "NO_COLOR": "1", "TERM": "dumb"}


def _eager() -> typer.Typer:
    """The group as it was built before it was lazy: every module registered on the app."""
    app = typer.Typer(name="urdftool", help=cli.app.info.help, no_args_is_help=True,
                      pretty_exceptions_enable=False, rich_markup_mode=None,
                      context_settings={"help_option_names": ["-h", "--help"]})
    app.callback()(cli._root)
    for name in cli.COMMANDS:
        __import__(f"urdftool.cli.{name}", fromlist=["register"]).register(app)
    return app


def test_help_lists_the_commands_as_the_eager_group_does():
    for columns in ("60", "100", "200"):
        env = {**ENV, "COLUMNS": columns}
        lazy = CliRunner().invoke(cli.app, ["--help"], env=env).stdout
        eager = CliRunner().invoke(_eager(), ["--help"], env=env).stdout
        assert lazy == eager
        assert "check" in lazy and "xacro" in lazy


def test_each_summary_is_the_first_sentence_of_its_command_help():
    for name, summary in cli.COMMANDS.items():
        first = re.split(r"(?<=\.)\s", cli.command(name).help, maxsplit=1)[0]
        assert first == summary, name


def test_a_command_imports_no_other_command_module():
    code = ("import sys\nsys.argv = ['urdftool', 'rules', 'U204']\nfrom urdftool.cli import main\n"
            "try:\n    main()\nexcept SystemExit:\n    pass\n"
            "print(sorted(m for m in sys.modules if m.startswith('urdftool.cli.')), file=sys.stderr)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert "inverted-limits" in done.stdout
    assert done.stderr.strip().splitlines()[-1] == "['urdftool.cli._common', 'urdftool.cli.rules']"


def test_an_unknown_command_is_a_usage_error():
    result = CliRunner().invoke(cli.app, ["chek"], env=ENV)
    assert result.exit_code == 2
    assert "No such command 'chek'" in result.output
