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
                                  "GITHUB_ACTIONS": "", "CI": ""})  # CI: the full mode

    return run


def corpus_entry_points() -> list[tuple[str, dict[str, str]]]:
    """Every corpus robot: (path relative to the corpus, xacro args) — the plain URDFs and the
    xacro entry points with the args CHECKS.tsv records (``<corpus>`` replaced)."""
    if not CORPUS.is_dir():
        return []
    entries = []
    for line in (CORPUS / "MANIFEST.tsv").read_text().splitlines()[1:]:
        columns = line.split("\t")
        if columns[4] == "urdf":
            entries.append((columns[0], {}))
    for line in (CORPUS / "CHECKS.tsv").read_text().splitlines()[1:]:
        columns = line.split("\t")
        if columns[1] != "xacro":
            continue
        args = {}
        for word in columns[2].split():
            name, _, value = word.partition(":=")
            args[name] = value.replace("<corpus>", str(CORPUS))
        entries.append((columns[0], args))
    return entries


def entry_id(entry) -> str:
    path, args = entry
    return path + ("[" + ",".join(f"{k}={Path(v).name}" for k, v in sorted(args.items())) + "]"
                   if args else "")
