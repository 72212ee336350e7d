"""The package is layered one way, without cycles (docs/architecture.md).

The contracts are import-linter's, in pyproject.toml (``[tool.importlinter]``): the layers
(every top-level module in one), the order inside lint, rich only in report, typer and click
only in cli, no cycle between siblings. ``lint-imports`` reads every import statement, inside
functions too; this file runs it, shows that each contract can fail, and keeps the two checks
import-linter cannot make: a module imported by a computed name (which it does not see) and a
rule code named below lint.
"""

from __future__ import annotations

import ast
import re
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from conftest import walked

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "urdftool"
CONTRACTS = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["importlinter"]
LAYERS = next(c for c in CONTRACTS["contracts"] if c["id"] == "layers")["layers"]  # highest first


def _lint_imports(root: Path) -> subprocess.CompletedProcess:
    """``lint-imports`` on the package under ``root`` with the contracts of its pyproject.toml,
    every dependency of a broken acyclic contract listed (import-linter lists the first five by
    name: which those are depends on the package's other imports, not on the one broken)."""
    return subprocess.run([sys.executable, "-c", "import sys; from importlinter.cli import "
                           "lint_imports_command; from importlinter.contracts import "
                           "acyclic_siblings; acyclic_siblings.MAX_DEPENDENCIES_TO_RENDER = "
                           "10 ** 6; sys.exit(lint_imports_command())",
                           "--no-cache"], cwd=root, env={"PYTHONPATH": str(root)},
                          capture_output=True, text=True)


def test_the_import_contracts_are_kept():
    done = _lint_imports(ROOT)
    assert done.returncode == 0, done.stdout + done.stderr


def test_each_contract_can_fail(tmp_path):
    """On a copy of the package with one violation of each kind, each contract is broken."""
    shutil.copytree(PACKAGE, tmp_path / "urdftool", ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path)

    def add(module: str, line: str) -> None:
        path = tmp_path / "urdftool" / module
        path.write_text(path.read_text() + f"\n\ndef _late():\n    {line}\n")

    add("description/values.py", "from urdftool.lint import settings")  # upward, in a function
    add("lint/pool.py", "from urdftool.lint import engine")  # the pool knowing rules
    add("kinematics/fk.py", "import rich")
    add("report/json_output.py", "import typer")
    add("description/xml.py", "from urdftool.description import load")  # load imports xml
    (tmp_path / "urdftool" / "stray.py").write_text('"""A module in no layer."""\n')
    done = _lint_imports(tmp_path)
    assert done.returncode == 1
    report = done.stdout.split("Broken contracts")[1]
    for expected in ("urdftool.description.values -> urdftool.lint.settings",
                     "urdftool.lint.pool -> urdftool.lint.engine",
                     "urdftool.stray",  # exhaustive: every top-level module has a layer
                     "urdftool.kinematics.fk -> rich", "urdftool.report.json_output -> typer",
                     "No cycles are allowed in urdftool.description.\nIt could be made acyclic "
                     "by removing"):
        assert expected in report, expected
    cycles = report.split("No cycles are allowed in urdftool.description.")[1].split("\n\n\n")[0]
    assert "- .xml -> .load" in cycles.split("No cycles are allowed in")[0], cycles
    assert done.stdout.count(" BROKEN") == len(CONTRACTS["contracts"])


def _modules() -> dict[str, Path]:
    found = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = list(path.relative_to(ROOT).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        found[".".join(parts)] = path
    return found


MODULES = _modules()


def _computed_imports(name: str, path: Path):
    """(line, name imported) of every ``import_module`` call not naming its module whole."""
    own = name if path.name == "__init__.py" else name.rpartition(".")[0]
    for node in walked(path.read_text(encoding="utf-8")):
        if isinstance(node, ast.Call) and getattr(node.func, "attr",
                                                  getattr(node.func, "id", "")) == "import_module":
            argument = node.args[0] if node.args else None
            if isinstance(argument, ast.Constant) and isinstance(argument.value, str):
                yield node.lineno, argument.value
            elif isinstance(argument, ast.JoinedStr) and argument.values and \
                    isinstance(argument.values[0], ast.Constant) and \
                    argument.values[0].value == own + ".":
                continue  # f"urdftool.cli.{name}" in urdftool.cli: a module of its own package
            else:
                yield node.lineno, "<computed>"


def test_no_module_is_imported_where_the_contracts_cannot_see_it():
    """import-linter reads import statements: ``import_module`` may only compute the name of a
    module of the caller's own package (a registry listing its modules, as cli/__init__.py and
    report/__init__.py do); a module of urdftool named whole is imported with ``import``."""
    found = [f"{path.relative_to(ROOT)}:{line}: import_module({target})"
             for name, path in MODULES.items()
             for line, target in _computed_imports(name, path)
             if target == "<computed>" or target.split(".")[0] == "urdftool"]
    assert not found, found


def _below_lint() -> list[str]:
    """The packages and modules of the layers below lint."""
    lower = LAYERS[LAYERS.index("lint") + 1:]
    return [f"urdftool.{tail.strip()}" for layer in lower for tail in re.split(r"[:|]", layer)]


def test_only_the_linter_knows_rule_codes():
    below = tuple(_below_lint())
    assert "urdftool.description" in below and "urdftool.compare" in below
    found = [f"{path.relative_to(ROOT)}:{number}" for name, path in MODULES.items()
             if name.startswith(tuple(f"{b}." for b in below)) or name in below
             for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
             if re.search(r"\bU\d{3}\b", line)]
    assert not found, found


@pytest.mark.parametrize("source, expected", [
    ('import importlib\nimportlib.import_module("urdftool.lint.engine")\n',
     [(2, "urdftool.lint.engine")]),
    ('from importlib import import_module\nimport_module(NAMES[0])\n', [(2, "<computed>")]),
    ('import importlib\nimportlib.import_module(f"urdftool.lint.{x}")\n', [(2, "<computed>")]),
    ('import importlib\nimportlib.import_module(f"urdftool.description.{x}")\n', []),
])
def test_the_computed_import_check_sees_what_it_must(tmp_path, source, expected):
    (tmp_path / "__init__.py").write_text(source)
    assert list(_computed_imports("urdftool.description", tmp_path / "__init__.py")) == expected
