"""``urdftool --help`` and ``-V`` answered before Typer is imported, with the texts Typer prints."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

import urdftool.__main__ as door
from conftest import ROOT
from urdftool import help_text

# the program as the urdftool script starts it, saying at exit whether Typer was imported;
# FIRST runs before main() (a patch of the door)
PROGRAM = ("import atexit, sys; import urdftool.__main__ as door; {first}; "
           "atexit.register(lambda: sys.stderr.write('[typer]' * ('typer' in sys.modules))); "
           "sys.argv = ['urdftool', *sys.argv[1:]]; door.main()")


def _program(*words: str, columns: int = 100, first: str = "pass"):
    env = {**os.environ, "COLUMNS": str(columns)}
    return subprocess.run([sys.executable, "-c", PROGRAM.format(first=first), *words],
                          capture_output=True, text=True, cwd=ROOT, env=env, timeout=120)


def test_the_kept_help_texts_are_what_typer_prints():
    kept = door.kept_help()
    assert kept, (f"{door.HELP_FILE} is missing or was made from other command modules: run "
                  "python -m urdftool.help_text")
    assert kept == help_text.texts(), "stale help texts: run python -m urdftool.help_text"


@pytest.mark.parametrize("words", [["--help"], ["-h"], [], ["check", "--help"], ["fk", "-h"],
                                   ["-V"], ["--version"]])
def test_help_and_version_are_answered_as_typer_does_without_importing_it(words):
    done = _program(*words)
    assert (done.stdout, done.stderr.removesuffix("[typer]"), done.returncode) == \
        help_text.typer_help(words)
    assert "[typer]" not in done.stderr


def test_a_narrow_terminal_and_stale_texts_are_left_to_typer():
    narrow = _program("--help", columns=60)
    assert "[typer]" in narrow.stderr and narrow.returncode == 0
    assert max(map(len, narrow.stdout.splitlines())) <= 58  # wrapped to the terminal
    stale = _program("check", "--help", first="door.commands_digest = lambda: 'other'")
    assert "[typer]" in stale.stderr and "Usage: urdftool check" in stale.stdout
    # words that only look like a request for help run the command
    other = _program("check", "--help", "x")
    assert "[typer]" in other.stderr
