"""The repository itself: nothing a merge left behind."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
# where conflict markers are the data: U001's case files, the fuzz regressions, and the rule
# pages generated from the case files
FIXTURES = ("tests/cases/", "tests/fuzz/", "docs/rules/")
SKIPPED = {".git", ".venv", "node_modules", "__pycache__", ".pytest_cache", "build", "dist"}
MARKER = re.compile(rb"^(<{7} |>{7} |\|{7} )", re.M)


def _files():
    for path in sorted(ROOT.rglob("*")):
        parts = path.relative_to(ROOT).parts
        if any(part in SKIPPED or part.endswith(".egg-info") for part in parts):
            continue
        if path.is_file() and not path.is_symlink():
            yield path


def test_no_file_holds_a_merge_conflict_left_unresolved():
    left = []
    for path in _files():
        relative = path.relative_to(ROOT).as_posix()
        if relative.startswith(FIXTURES) or path.stat().st_size > 4 * 1024 * 1024:
            continue
        if MARKER.search(path.read_bytes()):
            left.append(relative)
    assert left == []
