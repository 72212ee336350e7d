"""The repository itself: nothing a merge left behind."""

from __future__ import annotations

import re
from pathlib import Path

from conftest import walked

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


def test_no_two_test_modules_share_a_name():
    """pytest imports a test module by its file's name (the folders hold no __init__.py): a
    second tests/*/test_tree.py is an error at collection of the whole suite, which a run of
    its own folder never shows (commands24's tests/kinematics/test_tree.py beside
    tests/report/test_tree.py, found by the merged suite)."""
    seen: dict[str, list[str]] = {}
    for path in _files():
        relative = path.relative_to(ROOT).as_posix()
        if relative.startswith(("tests/cases/", "tests/fuzz/corpus")) or path.suffix != ".py":
            continue
        if relative.startswith("tests/") and path.name.startswith("test_"):
            seen.setdefault(path.name, []).append(relative)
    assert {name: where for name, where in seen.items() if len(where) > 1} == {}


def test_no_code_searches_a_list_among_the_items_before_each():
    """``name in names[:index]`` in a loop is quadratic in what an input counts (a q-file's
    100,000 columns took fk's 60 s; a controller's 40,000 joints 13 s of a check): a set of
    those seen is one pass."""
    import ast

    import urdftool

    found = []
    for path in Path(urdftool.__file__).parent.rglob("*.py"):
        for loop in walked(path.read_text(encoding="utf-8")):
            targets = [loop.target] if isinstance(loop, ast.For) else \
                [g.target for g in getattr(loop, "generators", ())]
            counters = {n.id for t in targets for n in ast.walk(t) if isinstance(n, ast.Name)}
            for node in ast.walk(loop) if counters else ():
                if not (isinstance(node, ast.Compare)
                        and any(isinstance(op, (ast.In, ast.NotIn)) for op in node.ops)):
                    continue
                for right in node.comparators:  # x in xs[:i], i the loop's own counter
                    if isinstance(right, ast.Subscript) and isinstance(right.slice, ast.Slice) \
                            and isinstance(right.slice.upper, ast.Name) \
                            and right.slice.upper.id in counters:
                        found.append(f"{path.name}:{node.lineno}")
    assert not found, found


def test_no_message_puts_an_article_before_a_word_it_computes():
    """``f"is a {severity} rule"`` said "is a error rule": whether a word takes "a" or "an" is
    known only once it is computed. A message names the word without an article before it
    (``f"{code}'s severity is {severity}"``) or writes the article with the word."""
    import ast

    import urdftool

    before = re.compile(r"(^|\W)(a|an) ['\"(<]?$", re.I)
    found = []
    for path in Path(urdftool.__file__).parent.rglob("*.py"):
        for node in walked(path.read_text(encoding="utf-8")):
            parts = node.values if isinstance(node, ast.JoinedStr) else \
                [node.left, node.right] if isinstance(node, ast.BinOp) and \
                isinstance(node.op, ast.Add) else []
            for part, after in zip(parts, parts[1:]):
                if isinstance(part, ast.Constant) and isinstance(part.value, str) and \
                        before.search(part.value) and not isinstance(after, ast.Constant):
                    found.append(f"{path.name}:{node.lineno}")
    assert not found, found
