"""The package is layered one way, without cycles (docs/architecture.md).

Imports are read with ast, not by importing: every `import`/`from ... import` at any depth
(inside functions too) and every `importlib.import_module("urdftool....")`. A dynamic
`import_module(f"...")` is itself a failure: registries list their modules explicitly.
"""

from __future__ import annotations

import ast
import re
from collections import defaultdict
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "urdftool"  # tests/test_layers.py

# Lowest first. A module may import modules of its own layer or of a lower one.
LAYERS = [
    ("base", ("urdftool.diagnostics", "urdftool.errors", "urdftool.budget", "urdftool.numbers",
              "urdftool.simulators", "urdftool.origin")),
    ("description", ("urdftool.description",)),
    ("kinematics", ("urdftool.kinematics",)),
    ("physics", ("urdftool.physics",)),
    ("collision", ("urdftool.collision",)),
    ("compare", ("urdftool.compare",)),
    ("lint", ("urdftool.lint",)),
    ("crosscheck", ("urdftool.crosscheck",)),
    ("report", ("urdftool.report",)),
    ("cli", ("urdftool.cli", "urdftool.__main__", "urdftool.docs", "urdftool.help_text",
             "urdftool.pytest_plugin",
             "urdftool.server")),
    ("api", ("urdftool",)),
]
# Inside lint, lowest first (the same rule applies).
LINT = ["urdftool.lint.pool", "urdftool.lint.catalogue", "urdftool.lint.rules", "urdftool.lint.suppressions",
        "urdftool.lint.engine", "urdftool.lint.settings", "urdftool.lint.targets",
        "urdftool.lint.cache", "urdftool.lint.runner"]
ONLY_IN = {"rich": "urdftool.report", "typer": "urdftool.cli", "click": "urdftool.cli"}
# Temporary exceptions while the migration runs: "importer -> imported". Each must still exist
# (the test fails on a stale entry), so this list can only shrink. Empty at the end.
ALLOWED: set[str] = set()


def _modules() -> dict[str, Path]:
    found = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        found[".".join(parts)] = path
    return found


MODULES = _modules()


def _existing(name: str) -> str:
    while name and name not in MODULES:
        name = name.rpartition(".")[0]
    return name


def _imports(name: str, path: Path):
    """(imported name, line) for every import in the module; external names are kept whole."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name, node.lineno
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[:len(package.split(".")) - node.level + 1]
                parent = ".".join(base + ([node.module] if node.module else []))
            else:
                parent = node.module or ""
            for alias in node.names:
                yield f"{parent}.{alias.name}" if f"{parent}.{alias.name}" in MODULES else parent, \
                    node.lineno
        elif isinstance(node, ast.Call) and getattr(node.func, "attr",
                                                    getattr(node.func, "id", "")) == "import_module":
            argument = node.args[0] if node.args else None
            if isinstance(argument, ast.Constant) and isinstance(argument.value, str):
                yield argument.value, node.lineno
            elif isinstance(argument, ast.JoinedStr) and _package_prefix(argument):
                yield _package_prefix(argument), node.lineno  # f"urdftool.cli.{name}": in there
            else:
                yield "<dynamic import>", node.lineno


def _package_prefix(text: ast.JoinedStr) -> str | None:
    """``urdftool.cli`` for ``f"urdftool.cli.{name}"``: a module of that package, whichever."""
    head = text.values[0] if text.values else None
    if isinstance(head, ast.Constant) and isinstance(head.value, str) and \
            head.value.endswith(".") and head.value.count(".") >= 2:
        return head.value.rstrip(".")
    return None


EDGES = [(name, target, line) for name, path in MODULES.items()
         for target, line in _imports(name, path)]
INTERNAL = [(a, _existing(b), line) for a, b, line in EDGES
            if b == "urdftool" or b.startswith("urdftool.")]


def _rank(name: str, layers) -> int | None:
    best = None
    for rank, prefixes in enumerate(layers):
        for prefix in prefixes:
            if name == prefix or (prefix != "urdftool" and name.startswith(prefix + ".")):
                if best is None or len(prefix) > best[1]:
                    best = (rank, len(prefix))
    return None if best is None else best[0]


def _violations() -> list[str]:
    found = {}  # dict: ordered, without repeats
    layers = [prefixes for _, prefixes in LAYERS]
    for name in MODULES:
        if _rank(name, layers) is None:
            found.setdefault(f"{name}: module outside every layer")
    for a, b, line in INTERNAL:
        rank_a, rank_b = _rank(a, layers), _rank(b, layers)
        if rank_a is None:
            continue
        if rank_b is not None and rank_b > rank_a and b != "urdftool":
            found.setdefault(f"{a}:{line} -> {b}")
        lint_a, lint_b = _rank(a, [(m,) for m in LINT]), _rank(b, [(m,) for m in LINT])
        if lint_a is not None and lint_b is not None and lint_b > lint_a:
            found.setdefault(f"{a}:{line} -> {b}")
    for a, b, line in EDGES:
        if b == "<dynamic import>":
            found.setdefault(f"{a}:{line} -> <dynamic import>")
        top = b.split(".")[0]
        if top in ONLY_IN and not (a == ONLY_IN[top] or a.startswith(ONLY_IN[top] + ".")):
            found.setdefault(f"{a}:{line} -> {top}")
    return list(found)


def _cycles(granularity) -> list[list[str]]:
    """Strongly connected groups (Tarjan) of the graph with names mapped by ``granularity``."""
    graph = defaultdict(set)
    for a, b, _ in INTERNAL:
        if granularity(a) != granularity(b) and b != "urdftool" and a != "urdftool":
            graph[granularity(a)].add(granularity(b))
    index, low, stack, on, groups = {}, {}, [], set(), []

    def visit(node):
        index[node] = low[node] = len(index)
        stack.append(node)
        on.add(node)
        for child in sorted(graph[node]):
            if child not in index:
                visit(child)
                low[node] = min(low[node], low[child])
            elif child in on:
                low[node] = min(low[node], index[child])
        if low[node] == index[node]:
            group = []
            while True:
                member = stack.pop()
                on.discard(member)
                group.append(member)
                if member == node:
                    break
            if len(group) > 1:
                groups.append(sorted(group))

    for node in sorted(set(graph)):
        if node not in index:
            visit(node)
    return groups


def _key(message: str) -> str:
    return re.sub(r":\d+", "", message)  # "a:12 -> b" is allowed as "a -> b"


def test_no_module_imports_a_layer_above_it():
    violations = [v for v in _violations() if _key(v) not in ALLOWED]
    assert not violations, "upward or forbidden imports:\n" + "\n".join(violations)


def test_allowed_exceptions_are_still_needed():
    current = {_key(v) for v in _violations()}
    stale = sorted(ALLOWED - current)
    assert not stale, f"remove from ALLOWED, they are fixed: {stale}"


@pytest.mark.parametrize("granularity", [lambda m: m, lambda m: ".".join(m.split(".")[:2])],
                         ids=["modules", "packages"])
def test_no_import_cycles(granularity):
    assert _cycles(granularity) == []


def test_only_the_linter_knows_rule_codes():
    below_lint = [p for name, p in MODULES.items() if (_rank(name, [x for _, x in LAYERS]) or 0) < 5]
    found = [f"{p.relative_to(PACKAGE.parent)}:{n}" for p in below_lint
             for n, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1)
             if re.search(r"\bU\d{3}\b", line)]
    assert not found, found


def test_the_checker_sees_what_it_must():
    """The rules above can fail: an upward import and a cycle in a fake tree are found."""
    global MODULES, EDGES, INTERNAL
    saved = MODULES, EDGES, INTERNAL
    try:
        MODULES = {"urdftool.description.load": None, "urdftool.lint.engine": None}
        EDGES = [("urdftool.description.load", "urdftool.lint.engine", 3),
                 ("urdftool.lint.engine", "urdftool.description.load", 5)]
        INTERNAL = EDGES
        assert _violations() == ["urdftool.description.load:3 -> urdftool.lint.engine"]
        assert _cycles(lambda m: m) == [sorted(MODULES)]
    finally:
        MODULES, EDGES, INTERNAL = saved
