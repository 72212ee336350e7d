"""`make bench`'s modules name only what exists: a name one benchmark imports from another (or
from timing.py), at the top or inside a function, is there. The benchmarks run by `make bench`,
not by `make test`; a name removed from one module failed another only there (bench_render and
bench_xacro imported bench_fk's ``_best_of`` after it went)."""

from __future__ import annotations

import ast
import importlib
from pathlib import Path

import pytest

BENCHMARKS = Path(__file__).resolve().parent.parent / "benchmarks"
SIBLINGS = {path.stem for path in BENCHMARKS.glob("*.py")}


def _imported_names() -> list[tuple[str, str, str]]:
    """(file, module, name) of every ``from MODULE import NAME`` of benchmarks/ naming a
    benchmarks module."""
    found = []
    for path in sorted(BENCHMARKS.glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if not isinstance(node, ast.ImportFrom) or node.module is None:
                continue
            module = node.module.removeprefix("benchmarks.")
            if module in SIBLINGS:
                found += [(path.name, module, alias.name) for alias in node.names]
    return found


@pytest.mark.parametrize("file,module,name", _imported_names())
def test_what_a_benchmark_imports_from_another_exists(file, module, name, monkeypatch):
    monkeypatch.syspath_prepend(str(BENCHMARKS.parent))
    imported = importlib.import_module(f"benchmarks.{module}")
    assert hasattr(imported, name), f"{file} imports {name} from {module}, which has none"


def test_the_imports_are_found():  # (the list above is not empty by accident)
    assert ("bench_render.py", "timing", "best_of") in _imported_names()
