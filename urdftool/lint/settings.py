"""Project settings: ``[tool.urdftool]`` in a pyproject.toml, or an ``urdftool.toml``, found above
each input, and their merge with what was asked for (:class:`CheckRequest`, the command line).

Settings are resolved per target file (:func:`for_file`): checking ``a/`` and ``b/`` together
applies ``a``'s settings to the files in ``a`` and ``b``'s to those in ``b``, in either order.

Keys: ``select``, ``ignore`` (lists of codes, prefixes or names), ``per-file-ignores`` (a table of
glob -> list), ``per-file-args`` (a table of glob -> xacro arguments), ``packages`` (a table of package name -> folder, relative to the settings file),
``spec``, ``controllers``, ``srdf`` (companion files, relative to the settings file), ``strict``,
``max-file-size`` (bytes), ``max-memory`` (per worker, as ``--max-memory``: ``"2G"``, ``0``),
``targets`` (simulators to check portability to, as ``--target``: ``["mujoco", "gz"]``).
Command-line options win over the file.

The settings file comes with the repository, so it is as untrusted as the robot files: it is
looked for up to the repository root (the nearest folder holding ``.git``) and no further, read
only when it is a regular file of at most 1 MiB, and a path it names (``packages``, ``spec``,
``srdf``, ``controllers``) that leads outside the repository, through ``..``, an absolute path or
a symbolic link, is a :class:`~urdftool.errors.SettingsError`: nothing there is read.
"""

from __future__ import annotations

import fnmatch
import os
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

from urdftool.budget import DEFAULT_MEMORY, DEFAULT_TIMEOUT, parse_memory
from urdftool.errors import SettingsError, UnknownRule, UsageError
from urdftool.description.files import inside, read_regular
from urdftool.description.inputs import CompanionPaths, MeshLimits
from urdftool.description.run_memo import per_run
from urdftool.lint.options import CheckOptions, Selection

MAX_SETTINGS_SIZE = 1024 * 1024  # [bytes]
KEYS = {"select", "ignore", "per-file-ignores", "per-file-args", "packages", "spec",
        "controllers", "srdf", "strict", "max-file-size", "max-memory", "targets"}


@dataclass
class Settings:
    """One settings file as read (``path`` None: no settings file). Shared between the files
    it applies to: do not change it."""

    path: Path | None = None
    select: list[str] = field(default_factory=list)
    ignore: list[str] = field(default_factory=list)
    per_file_ignores: dict[str, list[str]] = field(default_factory=dict)
    per_file_args: dict[str, dict[str, str]] = field(default_factory=dict)
    packages: dict[str, Path] = field(default_factory=dict)
    companions: dict[str, Path] = field(default_factory=dict)
    strict: bool = False
    max_file_size: int | None = None
    max_memory: str | None = None  # as --max-memory takes it
    targets: list[str] = field(default_factory=list)  # as --target takes them

    def ignores_for(self, file: str) -> list[str]:
        """Codes ignored for one file by ``per-file-ignores`` globs (relative to the config)."""
        return [code for codes in self._matching(self.per_file_ignores, file) for code in codes]

    def args_for(self, file: str) -> dict[str, str]:
        """xacro arguments for one file by ``per-file-args`` globs, later globs winning."""
        found: dict[str, str] = {}
        for args in self._matching(self.per_file_args, file):
            found.update(args)
        return found

    def _matching(self, table: dict, file: str) -> list:
        """The values of ``table`` whose glob matches ``file``, relative to the settings file's
        folder, or its name alone."""
        if not table:
            return []
        target = Path(file).absolute()
        base = self.path.parent if self.path else Path.cwd()
        try:
            relative = target.relative_to(base).as_posix()
        except ValueError:
            relative = target.as_posix()
        return [value for pattern, value in table.items()
                if fnmatch.fnmatch(relative, pattern) or fnmatch.fnmatch(target.name, pattern)]


def settings_for(path: str | os.PathLike) -> Settings:
    """The settings that apply to ``path`` (a file or folder; ``-``, standard input: the working
    folder): the nearest settings file above it, up to the repository root; empty Settings when
    none. Each settings file is read once per version."""
    folder = Path.cwd() if os.fspath(path) == "-" else Path(path).absolute()
    if not folder.is_dir():
        folder = folder.parent
    return _settings_in(folder)


@per_run
def _settings_in(folder: Path) -> Settings:
    from urdftool.description.packages import repository_root

    chain = [folder, *folder.parents]
    root = repository_root(folder)
    if root is not None:
        chain = chain[:chain.index(root) + 1]
    for candidate in chain:
        for name in ("urdftool.toml", "pyproject.toml"):
            file = candidate / name
            if file.is_file():
                status = file.stat()
                found = _settings_file(file, status.st_mtime_ns, status.st_size)
                if found is not None:
                    return found
    return Settings()


def settings_file(path: str | os.PathLike) -> Settings:
    """The settings in one named file (``--config``): an ``urdftool.toml``, or any other TOML
    file holding them at top level or under ``[tool.urdftool]``. It was named by whoever runs
    the check, so the paths it names may lead anywhere its own folder's repository allows."""
    path = Path(path).absolute()
    if not path.is_file():
        raise SettingsError(f"settings file '{path}' does not exist or is not a file")
    table = _read(path)
    if path.name != "urdftool.toml" and "tool" in table:
        table = table["tool"].get("urdftool", {}) if isinstance(table["tool"], dict) else {}
    return _parse(path, table)


@lru_cache(maxsize=64)
def _settings_file(file: Path, mtime: int, size: int) -> Settings | None:
    """The settings in ``file``; None for a pyproject.toml without ``[tool.urdftool]``."""
    if file.name == "urdftool.toml":
        return _parse(file, _read(file))
    table = _read(file).get("tool", {}).get("urdftool")
    return None if table is None else _parse(file, table)


def _read(path: Path) -> dict:
    import tomllib  # only where a settings file is

    _refuse_outside(path, path, "the settings file itself")
    try:
        return tomllib.loads(read_regular(path, MAX_SETTINGS_SIZE).decode("utf-8"))
    except OSError as error:
        raise SettingsError(f"cannot read settings in {path}: {error.strerror}") from None
    except (UnicodeDecodeError, tomllib.TOMLDecodeError) as error:
        raise SettingsError(f"cannot read settings in {path}: {error}") from None


def _refuse_outside(settings: Path, path: Path, what: str) -> None:
    """SettingsError when ``path``, named by ``settings``, leads outside the settings file's
    repository (nearest ``.git`` above it, else its own folder)."""
    from urdftool.description.packages import repository_root

    root = repository_root(settings.parent) or settings.parent
    if not inside(path, root):
        raise SettingsError(f"{settings}: {what} '{path}' leads outside the repository ({root}); "
                         "settings may name only files inside it (give outside paths on the "
                         "command line)")


def _parse(path: Path, table: dict) -> Settings:
    unknown = sorted(set(table) - KEYS)
    if unknown:
        raise SettingsError(f"{path}: unknown urdftool setting(s) {', '.join(unknown)}; "
                         f"valid: {', '.join(sorted(KEYS))}")
    config = Settings(path=path)
    config.select = _selectors(path, table, "select")
    config.ignore = _selectors(path, table, "ignore")
    for pattern in _table(path, table, "per-file-ignores"):
        config.per_file_ignores[pattern] = _selectors(path, table["per-file-ignores"], pattern,
                                                      f"per-file-ignores.{pattern}")
    for pattern, args in _table(path, table, "per-file-args").items():
        config.per_file_args[pattern] = _xacro_args(path, pattern, args)
    config.packages = {name: _inside_path(path, f"package {name}", folder)
                       for name, folder in _table(path, table, "packages").items()}
    config.companions = {key: _inside_path(path, key, table[key]) for key in ("spec", "srdf")
                         if key in table}
    if "controllers" in table:
        listed = table["controllers"]
        config.companions["controllers"] = [_inside_path(path, "controllers", p) for p in
                                            (listed if isinstance(listed, list) else [listed])]
    config.strict = table.get("strict", False)
    if not isinstance(config.strict, bool):
        raise SettingsError(f"{path}: 'strict' must be true or false (a TOML boolean, "
                            f"unquoted), not {config.strict!r}")
    if "max-file-size" in table:
        config.max_file_size = checked_file_size(table["max-file-size"], f"{path}: 'max-file-size'")
    if "max-memory" in table:
        config.max_memory = _memory(path, table["max-memory"])
    if "targets" in table:
        config.targets = _targets(path, table["targets"])
    return config


def _targets(path: Path, value) -> list[str]:
    """``targets``: a list of simulator names (``NAME`` or ``NAME@VERSION``)."""
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not all(isinstance(item, str) for item in value):
        raise SettingsError(f"{path}: 'targets' must be a list of simulator names, such as "
                            f"[\"mujoco\", \"gz\"], not {value!r}")
    try:
        checked_targets(value)
    except UsageError as error:
        raise SettingsError(f"{path}: 'targets': {error}") from None
    return value


def checked_targets(values: Iterable[str]) -> tuple[str, ...]:
    """The targets as given (comma-separated values split); UsageError for an unknown name."""
    from urdftool.simulators import parse_target

    words = tuple(_codes(values))
    for word in words:
        parse_target(word)
    return words


def _inside_path(settings: Path, what: str, value) -> Path:
    """A path setting, relative to the settings file; SettingsError when it is not a string or
    leads outside the repository."""
    if not isinstance(value, str) or "\0" in value:
        raise SettingsError(f"{settings}: {what} must be a path (a string), got {value!r}")
    path = settings.parent / value
    _refuse_outside(settings, path, what)
    return path


MAX_FILE_SIZE = 2 ** 40  # [bytes] the largest size limit that can be set (1 TiB)


def checked_file_size(value, what: str) -> int:
    """``value`` as a file size limit in [bytes]; SettingsError naming ``what`` unless it is a whole
    number from 1 to MAX_FILE_SIZE."""
    if isinstance(value, bool) or not isinstance(value, int) or not 0 < value <= MAX_FILE_SIZE:
        raise SettingsError(f"{what} must be a whole number of bytes from 1 to {MAX_FILE_SIZE}, "
                         f"not {value!r}")
    return value


def _memory(path: Path, value) -> str:
    from urdftool.budget import parse_memory

    try:
        parse_memory(str(value))
    except UsageError:
        raise SettingsError(f"{path}: 'max-memory' must be a size such as \"2G\", \"512M\" or 0 "
                         f"(no limit), not {value!r}") from None
    return str(value)


def _xacro_args(path: Path, pattern: str, args) -> dict[str, str]:
    """One ``per-file-args`` entry: a table of xacro argument name -> value (a string, number or
    boolean, written as xacro reads it)."""
    if not isinstance(args, dict):
        raise SettingsError(f"{path}: 'per-file-args.{pattern}' must be a table of xacro "
                            f"arguments (name = value), not {args!r}")
    values = {}
    for name, value in args.items():
        if isinstance(value, bool):
            value = "true" if value else "false"
        elif isinstance(value, (int, float)):
            value = repr(value)
        if not isinstance(value, str):
            raise SettingsError(f"{path}: 'per-file-args.{pattern}.{name}' must be a string, "
                                f"number or boolean, not {value!r}")
        values[name] = value
    return values


def _table(path: Path, table: dict, key: str) -> dict:
    value = table.get(key, {})
    if not isinstance(value, dict):
        raise SettingsError(f"{path}: '{key}' must be a table, not {value!r}")
    return value


def _selectors(path: Path, table: dict, key: str, what: str | None = None) -> list[str]:
    """A list of rule codes, prefixes or names; SettingsError when it is not one, or when an
    entry picks no rule (a misspelt code would silently select or ignore nothing)."""
    what = what or key
    value = table.get(key, [])
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not all(isinstance(item, str) for item in value):
        raise SettingsError(f"{path}: '{what}' must be a list of rule codes or names")
    for selector in _codes(value):
        try:
            check_selectors([selector])
        except UnknownRule as error:
            raise SettingsError(f"{path}: '{what}': {error}") from None
    return value


def check_selectors(selectors: Iterable[str]) -> None:
    """:class:`~urdftool.errors.UnknownRule` for the first selector that picks no rule."""
    selectors = list(_codes(selectors))
    if selectors:  # the catalogue imports every rule: only when there is something to check
        from urdftool.lint.rules import CATALOGUE

        for selector in selectors:
            CATALOGUE.check_selector(selector)


# ---- settings merged with a request ---------------------------------------------------------

Companions = CompanionPaths  # the API's name for the companion files a request names


def check_companions(companions: CompanionPaths) -> None:
    """SettingsError when a companion file named does not exist."""
    for path in companions.named():
        if not path.is_file():
            raise SettingsError(f"companion file '{path}' does not exist")


def _settings_companions(settings: Settings) -> CompanionPaths:
    listed = settings.companions.get("controllers")
    return CompanionPaths(tuple(listed if isinstance(listed, list) else [listed]) if listed
                          else (), settings.companions.get("srdf"), settings.companions.get("spec"))


@dataclass(frozen=True)
class CheckRequest:
    """What a check was asked to do (the command line's options, or the API's arguments);
    the settings file above each target fills in what it leaves open.

    select: codes, prefixes or names (comma-separated values are split); replaces the
        settings' ``select`` when given
    ignore: added to the settings' ``ignore``
    strict: warnings fail the run too (as do the settings' ``strict``)
    allow_env: ``$(env)`` and files outside the repository allowed; None: as :func:`env_allowed`
    max_file_size: [bytes] None: the settings', else 16 MiB
    max_memory: per worker, as ``parse_memory`` reads it ("2G", "0" for none) or in bytes;
        None: the settings', else 2 GiB
    timeout: per file in [s]; None or 0 for none
    jobs: worker processes; None: one per core
    use_settings: whether settings files apply at all
    stdin_filename: the path standard input ('-') is checked as: its settings, includes and
        packages are found from there and its findings name it (an editor's unsaved buffer)
    settings_file: this settings file for every target instead of the one above each
    targets: simulators to check portability to (``NAME`` or ``NAME@VERSION``); replaces the
        settings' ``targets`` when given
    cache_dir: where results are kept between runs (:mod:`urdftool.lint.cache`); None: not kept
        (``urdftool check`` keeps them in ``.urdftool_cache`` unless --no-cache or CI)
    """

    select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()
    strict: bool = False
    xacro_args: Mapping[str, str] = field(default_factory=dict)
    packages: Mapping[str, Path] = field(default_factory=dict)
    companions: CompanionPaths = CompanionPaths()
    allow_env: bool | None = None
    max_file_size: int | None = None
    max_triangles: int = 2_000_000
    max_memory: str | int | None = None
    timeout: float | None = DEFAULT_TIMEOUT
    jobs: int | None = None
    use_settings: bool = True
    stdin_filename: str | None = None
    settings_file: Path | None = None
    cache_dir: Path | None = None
    targets: tuple[str, ...] = ()

    def __post_init__(self):
        for name in ("select", "ignore"):
            value = getattr(self, name)
            object.__setattr__(self, name, (value,) if isinstance(value, str) else tuple(value))
            check_selectors(getattr(self, name))
        object.__setattr__(self, "targets", checked_targets(
            (self.targets,) if isinstance(self.targets, str) else self.targets or ()))
        object.__setattr__(self, "xacro_args", dict(self.xacro_args or {}))
        object.__setattr__(self, "packages", {name: Path(folder) for name, folder
                                              in (self.packages or {}).items()})
        if self.companions is None:
            object.__setattr__(self, "companions", CompanionPaths())
        if self.max_file_size is not None:
            checked_file_size(self.max_file_size, "max_file_size")


@dataclass(frozen=True)
class FileSettings:
    """How one file is checked: its settings file merged with the request.

    strict: whether a warning in it fails the run
    memory: the address space a worker checking it may use in [bytes]; None for no limit
    """

    options: CheckOptions
    strict: bool
    memory: int | None


def for_file(path: str, request: CheckRequest) -> FileSettings:
    """The settings for checking ``path``: the settings file above it (unless the request
    turns them off) under the request. Command-line values win: ``select`` replaces, ``ignore``
    and per-file ignores add, companions and packages win one by one."""
    settings = (Settings() if not request.use_settings else
                settings_file(request.settings_file) if request.settings_file is not None else
                settings_for(path))
    selection = Selection(tuple(_codes(request.select or settings.select)),
                          tuple(_codes([*settings.ignore, *request.ignore,
                                        *settings.ignores_for(path)])),
                          request.targets or tuple(_codes(settings.targets)))
    options = CheckOptions(
        xacro_args={**settings.args_for(path), **request.xacro_args}, packages={**settings.packages, **request.packages},
        selection=selection, allow_env=env_allowed(request.allow_env),
        max_file_size=request.max_file_size or settings.max_file_size
        or CheckOptions.max_file_size,
        companions=_settings_companions(settings).overridden_by(request.companions),
        mesh_limits=MeshLimits(max_triangles=request.max_triangles))
    memory = request.max_memory if request.max_memory is not None else settings.max_memory
    try:
        limit = DEFAULT_MEMORY if memory is None else parse_memory(str(memory))  # or bytes
    except UsageError:
        raise SettingsError(f"max_memory must be a size such as \"2G\", \"512M\" or 0 "
                            f"(no limit), not {memory!r}") from None
    return FileSettings(options, request.strict or settings.strict, limit)


def env_allowed(flag: bool | None) -> bool:
    """``allow_env`` as given; unset, the safe mode when ``CI`` is set.

    A CI job on a pull request checks files a stranger wrote, and its environment holds
    tokens and secrets: ``$(env)`` or an include of a file outside the checkout would print
    them in the job's public log. GitHub Actions, GitLab CI and most other services set
    ``CI=true``; on a developer's machine the files are their own.
    """
    if flag is not None:
        return flag
    return os.environ.get("CI", "").strip().lower() in ("", "0", "false", "no")


def _codes(values: Iterable[str]) -> list[str]:
    """Codes from values that may each hold several, comma-separated."""
    return [part.strip() for value in values for part in value.split(",") if part.strip()]
