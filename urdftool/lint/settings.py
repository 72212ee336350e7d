"""Project settings: ``[tool.urdftool]`` in a pyproject.toml, or an ``urdftool.toml``, found above
the input.

Keys: ``select``, ``ignore`` (lists of codes, prefixes or names), ``per-file-ignores`` (a table of
glob -> list), ``packages`` (a table of package name -> folder, relative to the settings file),
``spec``, ``controllers``, ``srdf`` (companion files, relative to the settings file), ``strict``,
``max-file-size`` (bytes), ``max-memory`` (per worker, as ``--max-memory``: ``"2G"``, ``0``).
Command-line options win over the file.

The settings file comes with the repository, so it is as untrusted as the robot files: it is
looked for up to the repository root (the nearest folder holding ``.git``) and no further, read
only when it is a regular file of at most 1 MiB, and a path it names (``packages``, ``spec``,
``srdf``, ``controllers``) that leads outside the repository, through ``..``, an absolute path or
a symbolic link, is a usage error: nothing there is read.
"""

from __future__ import annotations

import fnmatch
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from urdftool.errors import UsageError
from urdftool.description.files import inside, read_regular

MAX_SETTINGS_SIZE = 1024 * 1024  # [bytes]
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
    """The nearest settings file above ``start`` (a file or folder), up to the repository root;
    empty Config when none."""
    from urdftool.description.packages import repository_root

    folder = start.absolute()
    if not folder.is_dir():
        folder = folder.parent
    chain = [folder, *folder.parents]
    root = repository_root(folder)
    if root is not None:
        chain = chain[:chain.index(root) + 1]
    for candidate in chain:
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
    _refuse_outside(path, path, "the settings file itself")
    try:
        return tomllib.loads(read_regular(path, MAX_SETTINGS_SIZE).decode("utf-8"))
    except OSError as error:
        raise UsageError(f"cannot read settings in {path}: {error.strerror}") from None
    except (UnicodeDecodeError, tomllib.TOMLDecodeError) as error:
        raise UsageError(f"cannot read settings in {path}: {error}") from None


def _refuse_outside(settings: Path, path: Path, what: str) -> None:
    """UsageError when ``path``, named by ``settings``, leads outside the settings file's
    repository (nearest ``.git`` above it, else its own folder)."""
    from urdftool.description.packages import repository_root

    root = repository_root(settings.parent) or settings.parent
    if not inside(path, root):
        raise UsageError(f"{settings}: {what} '{path}' leads outside the repository ({root}); "
                         "settings may name only files inside it (give outside paths on the "
                         "command line)")


def _parse(path: Path, table: dict) -> Config:
    unknown = sorted(set(table) - KEYS)
    if unknown:
        raise UsageError(f"{path}: unknown urdftool setting(s) {', '.join(unknown)}; "
                         f"valid: {', '.join(sorted(KEYS))}")
    config = Config(path=path)
    config.select = _strings(path, table, "select")
    config.ignore = _strings(path, table, "ignore")
    for pattern, codes in table.get("per-file-ignores", {}).items():
        config.per_file_ignores[pattern] = codes if isinstance(codes, list) else [codes]
    config.packages = {name: _inside_path(path, f"package {name}", folder)
                       for name, folder in table.get("packages", {}).items()}
    config.companions = {key: _inside_path(path, key, table[key]) for key in ("spec", "srdf")
                         if key in table}
    if "controllers" in table:
        listed = table["controllers"]
        config.companions["controllers"] = [_inside_path(path, "controllers", p) for p in
                                            (listed if isinstance(listed, list) else [listed])]
    config.strict = bool(table.get("strict", False))
    if "max-file-size" in table:
        config.max_file_size = checked_file_size(table["max-file-size"], f"{path}: 'max-file-size'")
    if "max-memory" in table:
        config.max_memory = _memory(path, table["max-memory"])
    return config


def _inside_path(settings: Path, what: str, value) -> Path:
    """A path setting, relative to the settings file; UsageError when it is not a string or
    leads outside the repository."""
    if not isinstance(value, str) or "\0" in value:
        raise UsageError(f"{settings}: {what} must be a path (a string), got {value!r}")
    path = settings.parent / value
    _refuse_outside(settings, path, what)
    return path


MAX_FILE_SIZE = 2 ** 40  # [bytes] the largest size limit that can be set (1 TiB)


def checked_file_size(value, what: str) -> int:
    """``value`` as a file size limit in [bytes]; UsageError naming ``what`` unless it is a whole
    number from 1 to MAX_FILE_SIZE."""
    if isinstance(value, bool) or not isinstance(value, int) or not 0 < value <= MAX_FILE_SIZE:
        raise UsageError(f"{what} must be a whole number of bytes from 1 to {MAX_FILE_SIZE}, "
                         f"not {value!r}")
    return value


def _memory(path: Path, value) -> str:
    from urdftool.budget import parse_memory

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
