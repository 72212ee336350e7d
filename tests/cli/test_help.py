"""``--help`` of every command: one default per option, completion options only on
``urdftool`` itself, metavars in one vocabulary, a --timeout that says what it covers, and a
suggestion for a mistyped command."""

from __future__ import annotations

import re
from collections import defaultdict

import pytest
from typer.testing import CliRunner

from urdftool import cli

ENV = {"COLUMNS": "100", "NO_COLOR": "1", "TERM": "dumb"}


def _help(*words: str) -> str:
    result = CliRunner().invoke(cli.app, [*words, "--help"], env=ENV)
    assert result.exit_code == 0, result.output
    return result.stdout


def _options(name: str):
    """(option long name, metavar shown (None for a flag), help text) of each option of
    command ``name``."""
    from typer._click.core import Context
    from typer.core import TyperOption

    built = cli.command(name)
    context = Context(built, info_name=name)
    for param in built.params:
        record = param.get_help_record(context)
        if isinstance(param, TyperOption) and record is not None:
            shown = None if param.is_flag else record[0].split(", ")[-1].partition(" ")[2]
            yield max(param.opts, key=len), shown, record[1]


@pytest.mark.parametrize("name", sorted(cli.COMMANDS))
def test_each_option_says_its_default_once(name):
    for option, _, text in _options(name):
        # "[default: ...]" or "(default; ...)": the option's default, not a value's (xacro's
        # $(optenv NAME DEFAULT))
        assert len(re.findall(r"[\[(]default\b", text.lower())) <= 1, (option, text)


@pytest.mark.parametrize("name", sorted(cli.COMMANDS))
def test_completion_is_offered_by_urdftool_not_by_each_command(name):
    assert "--install-completion" not in _help(name)


def test_urdftool_itself_offers_completion():
    text = _help()
    assert "--install-completion" in text and "--show-completion" in text


def test_metavars_are_words_in_capitals_and_one_per_option_name():
    shown = defaultdict(set)
    for name in cli.COMMANDS:
        for option, metavar, _ in _options(name):
            if metavar is None:
                continue  # a flag
            assert "<" not in metavar and metavar[0].isupper(), (name, option, metavar)
            shown[option].add(metavar.split(".")[0])  # FILE.png|svg is a FILE
    several = {option: metavars for option, metavars in shown.items() if len(metavars) > 1}
    assert not several


def test_timeout_says_what_its_budget_covers():
    helps = {name: text for name in ("check", "crosscheck", "render")
             for option, _, text in _options(name) if option == "--timeout"}
    assert "each file" in helps["check"]
    assert "each loader" in helps["crosscheck"] and "U015" not in helps["crosscheck"]
    assert "the command" in helps["render"] and "per file" not in helps["render"]


def test_a_mistyped_command_gets_a_suggestion():
    result = CliRunner().invoke(cli.app, ["chek", "robot.urdf"], env=ENV)
    assert result.exit_code == 2
    assert "No such command 'chek'; did you mean 'check'?" in result.output
    far = CliRunner().invoke(cli.app, ["zzzz"], env=ENV)
    assert far.exit_code == 2 and "did you mean" not in far.output
