"""Shared fixtures: the corpus location, CLI runner settings."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
ROBOTS = ROOT / "robots"
CASES = Path(__file__).resolve().parent / "cases"
CORPUS = Path(os.environ.get("URDFTOOL_CORPUS", ROOT.parent / "shared" / "corpus"))


def corpus_or_skip() -> Path:
    if not CORPUS.is_dir():
        pytest.skip(f"corpus not found at {CORPUS}")
    return CORPUS


@pytest.fixture
def corpus() -> Path:
    return corpus_or_skip()


@pytest.fixture
def run_cli():
    """Invoke the CLI in-process with a fixed width and no colour; returns the Result."""
    from typer.testing import CliRunner

    from urdftool.cli import app

    runner = CliRunner()

    def run(*args, input=None):
        return runner.invoke(app, [str(a) for a in args], input=input,
                             env={"COLUMNS": "120", "NO_COLOR": "1", "TERM": "dumb",
                                  "GITHUB_ACTIONS": ""})

    return run
