"""Shared fixtures: the corpus location, CLI runner settings."""

from __future__ import annotations

import os
import re
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


# ---- case files (tests/cases): one per rule, offending lines marked `expect: CODE` ----------

MARK = re.compile(r"expect:\s*((?:U\d{3}[\s,]*)+)(?:is reported )?(?:at\s+([\w.\-]+):(\d+))?")


def case_robot(case: Path) -> Path:
    if case.is_file():
        return case
    robots = sorted(p for p in case.iterdir() if p.name.endswith((".urdf", ".urdf.xacro")))
    assert len(robots) == 1, f"{case} must hold exactly one .urdf or .urdf.xacro, has {robots}"
    return robots[0]


def expected_marks(case: Path) -> set[tuple[str, int, str]]:
    files = [case] if case.is_file() else sorted(p for p in case.rglob("*") if p.is_file())
    marks = set()
    for path in files:
        for number, line in enumerate(path.read_text(errors="replace").splitlines(), start=1):
            for codes, elsewhere, at_line in MARK.findall(line):
                where = (elsewhere, int(at_line)) if elsewhere else (path.name, number)
                for code in re.findall(r"U\d{3}", codes):
                    marks.add((*where, code))
    return marks


CASE_PATHS = sorted(p for p in CASES.iterdir() if re.match(r"U\d{3}_", p.name))


def pytest_collection_modifyitems(config, items):
    """Everything under tests/integration/ is marked ``integration`` (``make test-fast`` skips it)."""
    for item in items:
        if "integration" in item.path.relative_to(ROOT).parts[:2]:
            item.add_marker(pytest.mark.integration)
