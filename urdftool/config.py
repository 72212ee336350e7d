"""Project settings: ``[tool.urdftool]`` in a pyproject.toml, or an ``urdftool.toml``, found above
the input.

Keys: ``select``, ``ignore`` (lists of codes, prefixes or names), ``per-file-ignores`` (a table of
glob -> list), ``packages`` (a table of package name -> folder, relative to the settings file),
``spec``, ``controllers``, ``srdf`` (companion files, relative to the settings file), ``strict``,
``max-file-size`` (bytes), ``max-memory`` (per worker, as ``--max-memory``: ``"2G"``, ``0``).
Command-line options win over the file.
"""

from __future__ import annotations

import fnmatch
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from .errors import UsageError

KEYS = {"select", "ignore", "per-file-ignores", "packages", "spec", "controllers", "srdf",
        "strict", "max-file-size", "max-memory"}


@dataclass
class Config:
    path: Path | None = None
    select: list[str] = field(default_factory=list)
    ignore: list[str] = field(default_factory=list)
    per_file_ignores: dict[str, list[str]] = field(default_factory=dict)
    packages: dict[str, Path] = field(default_factory=dict)
    companions: dict[str, Path] = field(default_factory=dict)
    strict: bool = False
    max_file_size: int | None = None
    max_memory: str | None = None  # as --max-memory takes it

    def ignores_for(self, file: str) -> list[str]:
        """Codes ignored for one file by ``per-file-ignores`` globs (relative to the config)."""
        if not self.per_file_ignores:
            return []
        target = Path(file).absolute()
        base = self.path.parent if self.path else Path.cwd()
        try:
            relative = target.relative_to(base).as_posix()
        except ValueError:
            relative = target.as_posix()
        found = []
        for pattern, codes in self.per_file_ignores.items():
            if fnmatch.fnmatch(relative, pattern) or fnmatch.fnmatch(target.name, pattern):
                found.extend(codes)
        return found


def find_config(start: Path) -> Config:
    """The nearest settings file above ``start`` (a file or folder); empty Config when none."""
    folder = start.absolute()
    if not folder.is_dir():
        folder = folder.parent
    for candidate in [folder, *folder.parents]:
        dedicated = candidate / "urdftool.toml"
        if dedicated.is_file():
            return _parse(dedicated, _read(dedicated))
        pyproject = candidate / "pyproject.toml"
        if pyproject.is_file():
            table = _read(pyproject).get("tool", {}).get("urdftool")
            if table is not None:
                return _parse(pyproject, table)
    return Config()


def _read(path: Path) -> dict:
    try:
        return tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as error:
        raise UsageError(f"cannot read settings in {path}: {error}") from None


def _parse(path: Path, table: dict) -> Config:
    unknown = sorted(set(table) - KEYS)
    if unknown:
        raise UsageError(f"{path}: unknown urdftool setting(s) {', '.join(unknown)}; "
                         f"valid: {', '.join(sorted(KEYS))}")
    base = path.parent
    config = Config(path=path)
    config.select = _strings(path, table, "select")
    config.ignore = _strings(path, table, "ignore")
    for pattern, codes in table.get("per-file-ignores", {}).items():
        config.per_file_ignores[pattern] = codes if isinstance(codes, list) else [codes]
    config.packages = {name: base / folder for name, folder in table.get("packages", {}).items()}
    config.companions = {key: base / table[key] for key in ("spec", "srdf") if key in table}
    if "controllers" in table:
        listed = table["controllers"]
        config.companions["controllers"] = [base / p for p in
                                            (listed if isinstance(listed, list) else [listed])]
    config.strict = bool(table.get("strict", False))
    config.max_file_size = table.get("max-file-size")
    if "max-memory" in table:
        config.max_memory = _memory(path, table["max-memory"])
    return config


def _memory(path: Path, value) -> str:
    from .budget import parse_memory

    try:
        parse_memory(str(value))
    except UsageError:
        raise UsageError(f"{path}: 'max-memory' must be a size such as \"2G\", \"512M\" or 0 "
                         f"(no limit), not {value!r}") from None
    return str(value)


def _strings(path: Path, table: dict, key: str) -> list[str]:
    value = table.get(key, [])
    if isinstance(value, str):
        value = [value]
    if not all(isinstance(item, str) for item in value):
        raise UsageError(f"{path}: '{key}' must be a list of rule codes or names")
    return value
