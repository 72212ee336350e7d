"""Project settings: ``[tool.urdftool]`` in a pyproject.toml, or an ``urdftool.toml``, found above
each input, and their merge with what was asked for (:class:`CheckRequest`, the command line).

Settings are resolved per target file (:func:`for_file`): checking ``a/`` and ``b/`` together
applies ``a``'s settings to the files in ``a`` and ``b``'s to those in ``b``, in either order.

Keys (:data:`KEYS`): ``select``, ``ignore`` (lists of codes, prefixes or names),
``per-file-ignores`` (a table of glob -> list), ``per-file-args`` (a table of glob -> xacro
arguments), ``packages`` (a table of package name -> folder, relative to the settings file),
``spec``, ``controllers``, ``srdf`` (companion files, relative to the settings file),
``strict``, ``max-file-size`` (bytes), ``max-memory`` (per worker, as ``--max-memory``:
``"1G"``), ``timeout`` (per file, in seconds, as ``--timeout``), ``max-triangles`` (per mesh,
as ``--max-triangles``), ``targets`` (simulators to check portability to, as ``--target``:
``["mujoco", "gz"]``), ``notes`` (whether the text report shows notes, as ``--notes``; false
by default). Command-line options win over the file.

The settings file comes with the repository, so it is as untrusted as the robot files. It is
looked for up to the repository root (the nearest folder holding ``.git``) and no further (in
no repository, up to ``/``, where a file another user owns is not read, and said:
:func:`foreign`), read only when it is a regular file of at most 1 MiB nesting at most
:data:`MAX_DEPTH` levels, and every key goes through :func:`_validated`, so that a key added
later cannot skip it:

- no string anywhere in it (a key, a glob, a xacro argument's value, a package folder, a
  companion) names a path outside the repository: absolute, ``~``, a drive, a ``file:`` URI,
  or ``..`` climbing out of the repository from the settings file's folder; the path keys
  (``packages``, ``spec``, ``srdf``, ``controllers``) may not lead out through a symbolic link
  either. A xacro argument from the settings is never a folder includes may come from
  (:class:`~urdftool.description.inputs.SettingValue`);
- a limit (:data:`LIMITS`: every budget the command line of ``check`` has: ``max-file-size``,
  ``max-memory``, ``timeout``, ``max-triangles``) may be lowered, never raised above the
  built-in default nor turned off: raising it takes the command line;
- anything else is a :class:`~urdftool.errors.SettingsError` naming the file and key. It stops
  only the files those settings apply to (see :mod:`urdftool.lint.runner`).
"""

from __future__ import annotations

import fnmatch
import functools
import math
import os
import re
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path

from urdftool.budget import DEFAULT_MEMORY, DEFAULT_TIMEOUT, format_memory, parse_memory
from urdftool.diagnostics import line_at
from urdftool.errors import OptionError, SettingsError, UnknownRule, UsageError
from urdftool.description.files import DEFAULT_MAX_FILE_SIZE, env_allowed, identity_or_why, \
    inside, kind_of, read_regular, unreachable
from urdftool.description.inputs import MAX_TRIANGLES, CompanionPaths, MeshLimits, SettingValue, \
    checked_file_size, held, shown
from urdftool.description.record import remembered
from urdftool.description.run_memo import per_run
from urdftool.lint.options import CheckOptions, Selection
from urdftool.numbers import too_long
from urdftool.records import Frozen, NEW, Record, replace

MAX_SETTINGS_SIZE = 1024 * 1024  # [bytes]
# [bytes] a pyproject.toml read to tell whether it holds settings at all (another tool's may
# be larger than settings are; may_hold's scan is linear)
MAX_OTHERS_SIZE = 16 * 1024 * 1024
MAX_DEPTH = 32  # nesting of arrays, tables and dotted keys in a settings file


class Settings(Record):
    """One settings file as read (``path`` None: no settings file). Shared between the files
    it applies to: do not change it."""

    path: Path | None
    select: list[str]
    ignore: list[str]
    per_file_ignores: dict[str, list[str]]
    per_file_args: dict[str, dict[str, str]]
    packages: dict[str, Path]
    companions: dict[str, Path]
    strict: bool
    max_file_size: int | None
    max_memory: str | None  # as --max-memory takes it
    timeout: float | None  # [s] per file
    max_triangles: int | None  # per mesh
    targets: list[str]  # as --target takes them
    notes: bool  # the text report shows notes (severity info)
    # each per-file table's globs compiled once (fnmatch's cache holds 32,768: a table of more
    # was compiled again for every file, seconds each)
    _globs: dict
    # the settings files found and not read on the way (another user's, in no repository:
    # :func:`foreign`), each said in words
    skipped: tuple

    __slots__ = ("path", "select", "ignore", "per_file_ignores", "per_file_args", "packages",
                 "companions", "strict", "max_file_size", "max_memory", "timeout", "max_triangles",
                 "targets", "notes", "_globs", "skipped")
    _compared = ("path", "select", "ignore", "per_file_ignores", "per_file_args", "packages",
                 "companions", "strict", "max_file_size", "max_memory", "timeout", "max_triangles",
                 "targets", "notes")
    _shown = ("path", "select", "ignore", "per_file_ignores", "per_file_args", "packages",
              "companions", "strict", "max_file_size", "max_memory", "timeout", "max_triangles",
              "targets", "notes")

    def __init__(self, path: Path | None = None, select: list[str] = NEW, ignore: list[str] = NEW,
                 per_file_ignores: dict[str, list[str]] = NEW,
                 per_file_args: dict[str, dict[str, str]] = NEW, packages: dict[str, Path] = NEW,
                 companions: dict[str, Path] = NEW, strict: bool = False,
                 max_file_size: int | None = None, max_memory: str | None = None,
                 timeout: float | None = None, max_triangles: int | None = None,
                 targets: list[str] = NEW, notes: bool = False, _globs: dict = NEW,
                 skipped: tuple = ()) -> None:
        self.path = path
        self.select = [] if select is NEW else select
        self.ignore = [] if ignore is NEW else ignore
        self.per_file_ignores = {} if per_file_ignores is NEW else per_file_ignores
        self.per_file_args = {} if per_file_args is NEW else per_file_args
        self.packages = {} if packages is NEW else packages
        self.companions = {} if companions is NEW else companions
        self.strict = strict
        self.max_file_size = max_file_size
        self.max_memory = max_memory
        self.timeout = timeout
        self.max_triangles = max_triangles
        self.targets = [] if targets is NEW else targets
        self.notes = notes
        self._globs = {} if _globs is NEW else _globs
        self.skipped = skipped

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
        globs = self._globs.get(id(table))
        if globs is None:
            globs = self._globs[id(table)] = [(re.compile(fnmatch.translate(pattern)).match, value)
                                              for pattern, value in table.items()]
        name = target.name
        return [value for match, value in globs if match(relative) or match(name)]


def settings_for(path: str | os.PathLike) -> Settings:
    """The settings that apply to ``path`` (a file or folder; ``-``, standard input: the working
    folder): the nearest settings file above it, up to the repository root; empty Settings when
    none. Each settings file is read once per version."""
    folder = Path.cwd() if os.fspath(path) == "-" else Path(path).absolute()
    if kind_of(folder) != "folder":
        folder = folder.parent
    return _settings_in(folder)


@per_run
def _settings_in(folder: Path) -> Settings:
    from urdftool.description.packages import repository_root

    chain = [folder, *folder.parents]
    root = repository_root(folder)
    if root is not None:
        chain = chain[:chain.index(root) + 1]
    skipped = []
    for candidate in chain:
        for name in ("urdftool.toml", "pyproject.toml"):
            file = candidate / name
            known = identity_or_why(file)
            if isinstance(known, tuple):
                why = None if root is not None else foreign(file)
                if why is not None:
                    skipped.append(why)
                    continue
                found = _settings_file(file, known)
                if found is not None:
                    return replace(found, skipped=tuple(skipped)) if skipped else found
            elif known:  # a name for settings that holds none: the settings meant are not
                # known, and a check with the defaults in their place would pass in silence
                raise SettingsError(f"settings file '{file}' {_what_is_there(known)}: the "
                                    "settings it names cannot be read; make it a file, or "
                                    "remove it")
    return Settings(skipped=tuple(skipped))


def foreign(file: Path) -> str | None:
    """Why the settings file ``file``, found above a folder that is in no repository, is not
    read: it belongs to another user (not this process's, nor root's), as git reads no
    repository another user owns (``safe.directory``): a ``pyproject.toml`` another local user
    leaves in ``/tmp`` would select and ignore the rules of a check of an archive unpacked
    below it. None for a file that may be read. The one decision, which the check, the
    language server and the pytest plugin each say (:attr:`Settings.skipped`)."""
    from urdftool.description.files import owner as owner_of

    uid = getattr(os, "geteuid", None)
    if uid is None:  # (no owners to compare)
        return None
    owner = owner_of(file)
    if owner is None or owner in (uid(), 0):
        return None
    return (f"settings file '{file}' not read: it belongs to another user (uid {owner}) and "
            "lies in no repository (as git reads no repository another user owns); give it "
            "with --config to use it")


def _what_is_there(why: str) -> str:
    return why if why.startswith("cannot") else f"is {why}"


def settings_file(path: str | os.PathLike) -> Settings:
    """The settings in one named file (``--config``): an ``urdftool.toml``, or any other TOML
    file holding them at top level or under ``[tool.urdftool]``. Its content is held to the
    same rules as a settings file found in a repository (it may well be one: naming it does
    not make what a stranger wrote in it the user's)."""
    path = Path(path).absolute()
    kind = kind_of(path)
    if kind != "file":
        raise SettingsError(f"settings file '{path}' " + (
            unreachable(path) if not kind else "is not a file"))
    table = _read(path)
    if path.name != "urdftool.toml" and "tool" in table:
        table = table["tool"].get("urdftool", {}) if isinstance(table["tool"], dict) else {}
    return _parse(path, table)


_READ_SETTINGS: dict = {}  # (file, its identity) -> (settings, what reading them recorded)


def _settings_file(file: Path, known: tuple) -> Settings | None:
    """The settings in ``file`` (whose :func:`~urdftool.description.files.identity` is
    ``known``), read once per version of it, what reading it recorded replayed each time."""
    if len(_READ_SETTINGS) > 64:
        _READ_SETTINGS.clear()
    return remembered(_READ_SETTINGS, (file, known), lambda: _settings_in_file(file))


def _settings_in_file(file: Path) -> Settings | None:
    """The settings in ``file``; None for a pyproject.toml without ``[tool.urdftool]``."""
    if file.name == "urdftool.toml":
        return _parse(file, _read(file))
    tool = _read(file, holding="urdftool").get("tool", {})
    table = tool.get("urdftool") if isinstance(tool, dict) else None
    return None if table is None else _parse(file, table)


def _read(path: Path, holding: str | None = None) -> dict:
    """The TOML table in ``path``. With ``holding``, a file whose text cannot hold a key of
    that name in its table ``tool`` (:func:`may_hold`) is no settings file and reads as
    empty, unparsed. Another project's pyproject.toml is then neither parsed nor held to our
    rules: a defect in it is not the user's settings."""
    _refuse_outside(path, path, "the settings file itself")
    try:  # another tool's file may be larger than settings are, or not UTF-8: its size and
        # encoding are not ours to judge until it may hold our settings
        data = read_regular(path, MAX_SETTINGS_SIZE if holding is None else MAX_OTHERS_SIZE,
                            as_="settings")
    except OSError as error:
        raise SettingsError(f"cannot read settings in {path}: {error.strerror}") from None
    if holding is not None and not may_hold(data.decode("utf-8", "surrogateescape"), "tool",
                                            holding):
        return {}
    if len(data) > MAX_SETTINGS_SIZE:  # (a pyproject.toml that may hold the settings)
        raise SettingsError(f"cannot read settings in {path}: file is {len(data)} bytes, over "
                            f"the limit of {MAX_SETTINGS_SIZE}")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise SettingsError(f"cannot read settings in {path}: {error}") from None
    import tomllib  # only where a settings file is

    deep = too_deep(text)
    if deep is not None:
        raise SettingsError(f"{path}:{deep}: settings nest deeper than {MAX_DEPTH} levels "
                            "(arrays, tables or dotted keys); not read")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise SettingsError(f"cannot read settings in {path}: {error}") from None
    except ValueError:  # tomllib's int() of a number past Python's 4,300 digits
        found = _long_number(text)
        where = f"{path}:{line_at(text, found.start())}" if found else f"{path}"
        raise SettingsError(f"cannot read settings in {where}: " + (
            str(too_long(len(found.group()))) if found else "a number too long for any "
            "setting")) from None
    except RecursionError:  # what too_deep() missed
        raise SettingsError(f"{path}: settings nest too deeply; not read") from None


def _long_number(text: str):
    """Where tomllib's ValueError is: the first run of digits longer than Python converts
    that is not inside a string on its line (an even number of quotes of each kind before it
    there), or None."""
    from urdftool.diagnostics import lines_of
    from urdftool.numbers import long_integers

    lines = None
    for found in long_integers(text):
        lines = lines or lines_of(text)
        line = lines[line_at(text, found.start()) - 1]
        before = line[:line.find(found.group()[:40])]
        if before.count('"') % 2 == 0 and before.count("'") % 2 == 0:
            return found
    return None


def may_hold(text: str, table: str, key: str) -> bool:
    """Whether the TOML ``text`` may give its top-level table ``table`` the key ``key``
    (``[tool.urdftool]``, ``[[tool.urdftool]]``, ``[tool]`` then ``urdftool = ...`` or
    ``urdftool.x = ...``, ``tool.urdftool.x = ...`` or ``tool = {urdftool = ...}`` at the top,
    each part bare or quoted, spaced or not). False only when it cannot: ``key`` is not in the
    text, or the text is made of plain lines (:func:`_plain_line`) of which none can. A key
    is written bare (the name as it is) or quoted, where only an escape (a backslash) could
    spell it otherwise; a text the parser alone can tell (an escape, a multi-line string, a
    line that is not plain) may: pyproject.toml files of Python packages name their package
    in other tables (``[project.scripts]``), which is no settings table of ours."""
    if "\\" in text or '"""' in text or "'''" in text:
        return True
    if key not in text:
        return False
    plain, at, end, header = _plain_line(), 0, len(text), ""
    while at < end:
        found = plain.match(text, at)
        if found is None:
            return True  # not plain: the parser decides
        at = found.end()
        heading, keyed = found.group(1, 2)
        if heading is not None:
            header = heading
            if key in heading and _key_path(heading)[:2] == (table, key):
                return True
        elif keyed is not None and key in found.group():
            path = _key_path(header) + _key_path(keyed)
            if path[:2] == (table, key) or path == (table,):  # (tool = {urdftool = ...})
                return True
    return False


_KEY_PART = re.compile(r"""[A-Za-z0-9_-]+|"[^"]*"|'[^']*'""")


def _key_path(dotted: str) -> tuple[str, ...]:
    """The parts of a dotted key as :func:`_plain_line` matched it, unquoted."""
    return tuple(part[1:-1] if part[0] in "\"'" else part for part in _KEY_PART.findall(dotted))


@functools.cache
def _plain_line():
    """A pattern of one plain line of TOML from where it begins to its end: blank, a comment, a
    header (group 1: its dotted key) or a key (group 2) and its value, and a comment. A key
    part is bare or quoted without an escape; a value is a string on one line without an
    escape, a bare word (a number, a boolean, a date), or an array (over lines, with
    comments) or inline table of such values, nested three deep. Lenient where a value is
    wrong (an array without its commas): what is a header or a key is all it tells.
    Possessive: a line that is not plain is refused in time linear in its length.
    Compiled when first asked (a pyproject.toml naming the key): it is long."""
    key = r"""(?:[A-Za-z0-9_-]++|"[^"\\\n]*+"|'[^'\n]*+')"""
    dotted = rf"{key}(?:[ \t]*+\.[ \t]*+{key})*+"
    blank = r"(?:[ \t\r\n]|#[^\n]*+)*+"
    value = r"""(?:"[^"\\\n]*+"|'[^'\n]*+'|[A-Za-z0-9_:+.\-]++)"""
    for _ in range(3):
        array = rf"\[{blank}(?:{value}{blank}(?:,{blank})?)*+\]"
        table = rf"\{{[ \t]*+(?:{dotted}[ \t]*+=[ \t]*+{value}[ \t]*+(?:,[ \t]*+)?)*+\}}"
        value = rf"""(?:"[^"\\\n]*+"|'[^'\n]*+'|[A-Za-z0-9_:+.\-]++|{array}|{table})"""
    return re.compile(rf"[ \t]*+(?:\[\[?[ \t]*+({dotted})[ \t]*+\]\]?|({dotted})[ \t]*+=[ \t]*+"
                      rf"{value})?[ \t]*+(?:#[^\n]*+)?(?:\r?\n|\Z)")


_TOKENS = re.compile("\"\"\"|'''|\"|'|#|\\[|\\]|\\{|\\}|\\.|\n")
_QUOTES = ('"""', "'''", '"', "'")


def too_deep(text: str) -> int | None:
    """The line where ``text`` (TOML) first nests deeper than MAX_DEPTH, counting open
    brackets and braces and the dots of a key on one line (``a.b.c = 1``: tomllib's cost
    grows with their square), strings and comments skipped; None when it never does. A dot
    between two digits is a number's, not a key's."""
    depth, dots, at = 0, 0, 0
    while (found := _TOKENS.search(text, at)) is not None:
        token, at = found.group(), found.end()
        if token == "\n":  # (TOML's line end: LF, or CR LF)
            dots = 0
        elif token == "#":
            end = text.find("\n", at)
            at = len(text) if end < 0 else end
        elif token in _QUOTES:
            at = _string_end(text, at, token)
        elif token in "[{":
            depth += 1
        elif token in "]}":
            depth = max(0, depth - 1)
        elif not (found.start() > 0 and text[found.start() - 1].isdigit()
                  and text[at:at + 1].isdigit()):
            dots += 1
        if depth + dots > MAX_DEPTH:
            return line_at(text, found.start())
    return None


def _string_end(text: str, at: int, quote: str) -> int:
    """Where the string opened by ``quote`` just before ``at`` ends (after its closing quote);
    the end of the line or text for an unterminated one (tomllib says what is wrong)."""
    escapes = quote.startswith('"')
    while at < len(text):
        char = text[at]
        if escapes and char == "\\":
            at += 2
            continue
        if text.startswith(quote, at):
            return at + len(quote)
        if char == "\n" and len(quote) == 1:
            return at
        at += 1
    return at


def _refuse_outside(settings: Path, path: Path, what: str) -> None:
    """SettingsError when ``path``, named by ``settings``, leads outside the settings file's
    repository (nearest ``.git`` above it, else its own folder), symbolic links followed."""
    root = _root_of(settings)
    if not inside(path, root):
        raise SettingsError(f"{settings}: {what} '{path}' leads outside the repository ({root}); "
                            "settings may name only files inside it (give outside paths on the "
                            "command line)")


def _root_of(settings: Path) -> Path:
    from urdftool.description.packages import repository_root

    return repository_root(settings.parent) or settings.parent


_DRIVE = re.compile(r"^[A-Za-z]:([\\/]|$)")


def _names_outside(settings: Path, text: str) -> bool:
    """Whether ``text``, taken as a path from the settings file's folder, names a place outside
    its repository as written: absolute, from a home folder (``~``), a drive, a ``file:`` URI,
    a UNC path, or climbing out with ``..``. Decided on the text alone: nothing is looked up,
    so the answer tells nothing about what exists outside."""
    if text.startswith(("/", "\\", "~")) or _DRIVE.match(text) or \
            text.lower().startswith("file:"):
        return True
    parts = re.split(r"[\\/]", text)
    if ".." not in parts:
        return False
    root = os.path.normpath(os.path.abspath(_root_of(settings)))
    climbed = os.path.normpath(os.path.join(os.path.abspath(settings.parent), *parts))
    return not (climbed == root or climbed.startswith(root.rstrip(os.sep) + os.sep))


def _refuse_outside_text(settings: Path, key: str, value) -> None:
    """SettingsError for the first string in ``value`` (keys of tables too) that
    :func:`_names_outside`: every key's value goes through this walk."""
    if isinstance(value, str):
        if _names_outside(settings, value):
            raise SettingsError(f"{settings}: {key}: '{value}' leads outside the "
                                f"repository ({_root_of(settings)}); settings may name only "
                                "paths inside it (give outside paths on the command line)")
    elif isinstance(value, dict):
        for name, item in value.items():
            _refuse_outside_text(settings, key, name)
            _refuse_outside_text(settings, f"{key}.{name}", item)
    elif isinstance(value, list):
        for item in value:
            _refuse_outside_text(settings, key, item)


# ---- one validation for every key -----------------------------------------------------------

class _Key(Frozen):
    """A settings key: ``read(settings file, value, key)`` checks its value and returns what
    :class:`Settings` keeps under ``attribute`` (None: in ``companions``, under the key)."""

    read: Callable
    attribute: str | None

    __slots__ = ("read", "attribute")

    def __init__(self, read: Callable, attribute: str | None) -> None:
        set_field = object.__setattr__
        set_field(self, "read", read)
        set_field(self, "attribute", attribute)


def _validated(path: Path, key: str, value):
    """The one gate of a settings key: known, no path outside the repository anywhere in its
    value, then its own check (a limit no higher than the built-in one). SettingsError
    naming the file and the key otherwise."""
    if key not in KEYS:
        raise SettingsError(f"{path}: unknown urdftool setting(s) {key}; "
                            f"valid: {', '.join(sorted(KEYS))}")
    _refuse_outside_text(path, f"'{key}'", value)
    return KEYS[key].read(path, value, key)


def _parse(path: Path, table: dict) -> Settings:
    if not isinstance(table, dict):  # `urdftool = 5` under [tool]: TypeError; a string was
        # read as its characters, each an unknown setting
        where = "the file" if path.name == "urdftool.toml" else "[tool.urdftool]"
        raise SettingsError(f"{path}: {where} must be a table of settings, not "
                            f"{type(table).__name__} {shown(table)}")
    unknown = sorted(set(table) - set(KEYS))
    if unknown:
        raise SettingsError(f"{path}: unknown urdftool setting(s) {', '.join(unknown)}; "
                            f"valid: {', '.join(sorted(KEYS))}")
    config = Settings(path=path)
    for key, value in table.items():
        read = _validated(path, key, value)
        if KEYS[key].attribute is None:
            config.companions[key] = read
        else:
            setattr(config, KEYS[key].attribute, read)
    return config


def _targets(path: Path, value, key: str = "targets") -> list[str]:
    """``targets``: a list of simulator names (``NAME`` or ``NAME@VERSION``)."""
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not all(isinstance(item, str) for item in value):
        raise SettingsError(f"{path}: 'targets' must be a list of simulator names, such as "
                            f"[\"mujoco\", \"gz\"], not {shown(value)}")
    try:
        return list(checked_targets(value))
    except UsageError as error:
        raise SettingsError(f"{path}: 'targets': {error}") from None


def checked_targets(values: Iterable[str]) -> tuple[str, ...]:
    """The targets as given (comma-separated values split), each as :func:`parse_target`
    reads it (``MUJOCO``, `` Gz @ 8 `` are ``mujoco``, ``gz@8``), each once; UsageError for an
    unknown name. The one spelling every consumer matches: ``MUJOCO`` was taken as mujoco
    here and then matched no rule's target (``Selection.allows``), so the mujoco rules did
    not run, without a word."""
    from urdftool.simulators import parse_target

    return tuple(dict.fromkeys(str(parse_target(word)) for word in _codes(values)))


def _inside_path(settings: Path, value, what: str) -> Path:
    """A path setting, relative to the settings file; SettingsError when it is not a string or
    leads outside the repository."""
    if not isinstance(value, str) or "\0" in value:
        raise SettingsError(f"{settings}: {what} must be a path (a string), got {shown(value)}")
    path = settings.parent / value
    _refuse_outside(settings, path, what)
    return path


def _packages(settings: Path, value, key: str) -> dict[str, Path]:
    return {name: _inside_path(settings, folder, f"package {name}")
            for name, folder in _table(settings, value, key).items()}


def _controllers(settings: Path, value, key: str) -> list[Path]:
    return [_inside_path(settings, item, key)
            for item in (value if isinstance(value, list) else [value])]


def _strict(settings: Path, value, key: str) -> bool:
    """A true-or-false key (``strict``, ``notes``)."""
    if not isinstance(value, bool):
        raise SettingsError(f"{settings}: '{key}' must be true or false (a TOML boolean, "
                            f"unquoted), not {shown(value)}")
    return value


def _per_file_ignores(settings: Path, value, key: str) -> dict[str, list[str]]:
    table = _table(settings, value, key)
    return {pattern: _selectors(settings, table[pattern], f"{key}.{pattern}")
            for pattern in table}


def _per_file_args(settings: Path, value, key: str) -> dict[str, dict[str, str]]:
    return {pattern: _xacro_args(settings, pattern, args)
            for pattern, args in _table(settings, value, key).items()}


def _file_size(settings: Path, value, key: str) -> int:
    """A size limit no larger than the built-in one: a repository may lower it, never raise it
    (that takes ``--max-file-size``)."""
    return checked_file_size(value, f"{settings}: '{key}'", LIMITS[key],
                             " (a repository may lower the built-in limit; raise it with "
                             "--max-file-size)")


def _memory(settings: Path, value, key: str) -> str:
    """A memory budget no larger than the built-in one, and not 0 (none): a repository may
    lower it, never raise it (that takes ``--max-memory``)."""
    try:
        size = parse_memory(str(value)) if isinstance(value, (str, int)) else -1
    except UsageError:
        size = -1
    if isinstance(value, bool) or size is None or not 0 < size <= LIMITS[key]:
        raise SettingsError(f"{settings}: '{key}' must be a size such as \"1G\" or \"512M\" up "
                            f"to the built-in {format_memory(LIMITS[key])}, not {shown(value)} (a "
                            "repository may lower the budget; raise it with --max-memory)")
    return str(value)


def _timeout(settings: Path, value, key: str) -> float:
    """A time budget per file in [s] no longer than the built-in one, and not 0 (none): a
    repository may lower it, never raise it (that takes ``--timeout``)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or \
            not 0 < value <= LIMITS[key]:
        raise SettingsError(f"{settings}: '{key}' must be a number of seconds above 0 and up to "
                            f"the built-in {LIMITS[key]:g}, not {shown(value)} (a repository may "
                            "lower the budget; raise it with --timeout)")
    return float(value)


def _triangles(settings: Path, value, key: str) -> int:
    """A triangle limit per mesh no higher than the built-in one: a repository may lower it,
    never raise it (that takes ``--max-triangles``)."""
    if isinstance(value, bool) or not isinstance(value, int) or not 0 < value <= LIMITS[key]:
        raise SettingsError(f"{settings}: '{key}' must be a whole number of triangles from 1 to "
                            f"the built-in {LIMITS[key]}, not {shown(value)} (a repository may lower "
                            "the limit; raise it with --max-triangles)")
    return value


def _selector_key(settings: Path, value, key: str) -> list[str]:
    return _selectors(settings, value, key)


def _companion(settings: Path, value, key: str) -> Path:
    return _inside_path(settings, value, key)


KEYS: dict[str, _Key] = {
    "select": _Key(_selector_key, "select"),
    "ignore": _Key(_selector_key, "ignore"),
    "per-file-ignores": _Key(_per_file_ignores, "per_file_ignores"),
    "per-file-args": _Key(_per_file_args, "per_file_args"),
    "packages": _Key(_packages, "packages"),
    "spec": _Key(_companion, None),
    "srdf": _Key(_companion, None),
    "controllers": _Key(_controllers, None),
    "strict": _Key(_strict, "strict"),
    "notes": _Key(_strict, "notes"),
    "max-file-size": _Key(_file_size, "max_file_size"),
    "max-memory": _Key(_memory, "max_memory"),
    "timeout": _Key(_timeout, "timeout"),
    "max-triangles": _Key(_triangles, "max_triangles"),
    "targets": _Key(_targets, "targets"),
}
# The budgets a settings file may only lower: key -> the built-in value. Every budget of the
# ``check`` command line is one (a test holds them to its options).
LIMITS = {"max-file-size": DEFAULT_MAX_FILE_SIZE, "max-memory": DEFAULT_MEMORY,
          "timeout": DEFAULT_TIMEOUT, "max-triangles": MAX_TRIANGLES}


def _xacro_args(path: Path, pattern: str, args) -> dict[str, str]:
    """One ``per-file-args`` entry: a table of xacro argument name -> value (a string, number or
    boolean, written as xacro reads it), each a :class:`SettingValue`."""
    if not isinstance(args, dict):
        raise SettingsError(f"{path}: 'per-file-args.{pattern}' must be a table of xacro "
                            f"arguments (name = value), not {shown(args)}")
    values = {}
    for name, value in args.items():
        if isinstance(value, bool):
            value = "true" if value else "false"
        elif isinstance(value, (int, float)):
            value = repr(value)
        if not isinstance(value, str):
            raise SettingsError(f"{path}: 'per-file-args.{pattern}.{name}' must be a string, "
                                f"number or boolean, not {shown(value)}")
        values[name] = SettingValue(value)
    return values


def _table(path: Path, value, key: str) -> dict:
    if not isinstance(value, dict):
        raise SettingsError(f"{path}: '{key}' must be a table, not {shown(value)}")
    return value


def _selectors(path: Path, value, what: str) -> list[str]:
    """A list of rule codes, prefixes or names; SettingsError when it is not one, or when an
    entry picks no rule (a misspelt code would silently select or ignore nothing)."""
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not all(isinstance(item, str) for item in value):
        raise SettingsError(f"{path}: '{what}' must be a list of rule codes or names")
    for selector in _codes(value):
        try:
            _known_selector(selector)
        except UnknownRule as error:
            raise SettingsError(f"{path}: '{what}': {error}") from None
    return value


@functools.lru_cache(maxsize=4096)
def _known_selector(selector: str) -> None:
    """:func:`check_selectors` of one selector, each distinct one asked once (50,000
    ``per-file-ignores`` patterns each giving ``["U2"]`` asked it 50,000 times: 5 s)."""
    check_selectors([selector])


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
    """SettingsError when a companion file named does not exist or is not a regular file."""
    for path in companions.named():
        kind = kind_of(path)
        if kind != "file":
            why = (unreachable(path) if not kind else "is a folder" if kind == "folder"
                   else "is not a regular file (a FIFO, a device or a socket)")
            raise SettingsError(f"companion file '{path}' {why}")


def _settings_companions(settings: Settings) -> CompanionPaths:
    listed = settings.companions.get("controllers")
    return CompanionPaths(tuple(listed if isinstance(listed, list) else [listed]) if listed
                          else (), settings.companions.get("srdf"), settings.companions.get("spec"))


class CheckRequest(Frozen):
    """What a check was asked to do (the command line's options, or the API's arguments);
    the settings file above each target fills in what it leaves open.

    select: codes, prefixes or names (comma-separated values are split); replaces the
        settings' ``select`` when given
    ignore: added to the settings' ``ignore``
    strict: warnings fail the run too (as do the settings' ``strict``)
    allow_env: ``$(env)`` and files outside the repository allowed; None: as
        :func:`~urdftool.description.files.env_allowed`
    max_file_size: [bytes] None: the settings', else 16 MiB
    max_memory: per worker, as ``parse_memory`` reads it ("2G", "0" for none) or in bytes;
        None: the settings', else 2 GiB
    max_triangles: per mesh; None: the settings', else 2,000,000
    timeout: per file in [s], 0 for none; None: the settings', else 60
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

    select: tuple[str, ...]
    ignore: tuple[str, ...]
    strict: bool
    xacro_args: Mapping[str, str]
    packages: Mapping[str, Path]
    companions: CompanionPaths
    allow_env: bool | None
    max_file_size: int | None
    max_triangles: int | None
    max_memory: str | int | None
    timeout: float | None
    jobs: int | None
    use_settings: bool
    stdin_filename: str | None
    settings_file: Path | None
    cache_dir: Path | None
    targets: tuple[str, ...]

    __slots__ = ("select", "ignore", "strict", "xacro_args", "packages", "companions", "allow_env",
                 "max_file_size", "max_triangles", "max_memory", "timeout", "jobs", "use_settings",
                 "stdin_filename", "settings_file", "cache_dir", "targets")

    def __init__(self, select: tuple[str, ...] = (), ignore: tuple[str, ...] = (),
                 strict: bool = False, xacro_args: Mapping[str, str] = NEW,
                 packages: Mapping[str, Path] = NEW, companions: CompanionPaths = CompanionPaths(),
                 allow_env: bool | None = None, max_file_size: int | None = None,
                 max_triangles: int | None = None, max_memory: str | int | None = None,
                 timeout: float | None = None, jobs: int | None = None, use_settings: bool = True,
                 stdin_filename: str | None = None, settings_file: Path | None = None,
                 cache_dir: Path | None = None, targets: tuple[str, ...] = ()) -> None:
        set_field = object.__setattr__
        set_field(self, "select", select)
        set_field(self, "ignore", ignore)
        set_field(self, "strict", strict)
        set_field(self, "xacro_args", {} if xacro_args is NEW else xacro_args)
        set_field(self, "packages", {} if packages is NEW else packages)
        set_field(self, "companions", companions)
        set_field(self, "allow_env", allow_env)
        set_field(self, "max_file_size", max_file_size)
        set_field(self, "max_triangles", max_triangles)
        set_field(self, "max_memory", max_memory)
        set_field(self, "timeout", timeout)
        set_field(self, "jobs", jobs)
        set_field(self, "use_settings", use_settings)
        set_field(self, "stdin_filename", stdin_filename)
        set_field(self, "settings_file", settings_file)
        set_field(self, "cache_dir", cache_dir)
        set_field(self, "targets", targets)
        self.__post_init__()

    def __post_init__(self):
        """Every field held to what the command line and the settings take (the API's callers
        gave ``strict="no"``: strict; ``timeout=nan`` and ``max_triangles=nan``: no limit;
        ``jobs=-5``; ``xacro_args="a:=1"``: Python's own error) by the one guard of a caller's
        options (:func:`~urdftool.description.inputs.held`: an OptionError naming it)."""
        set_field = object.__setattr__
        for name in ("select", "ignore", "targets"):
            set_field(self, name, held(name, getattr(self, name) or (), "words"))
        for name in ("select", "ignore"):
            check_selectors(getattr(self, name))
        set_field(self, "targets", checked_targets(self.targets))
        set_field(self, "xacro_args", held("xacro_args", self.xacro_args or {}, "names"))
        set_field(self, "packages", held("packages", self.packages or {}, "paths"))
        if self.companions is None:
            set_field(self, "companions", CompanionPaths())
        elif not isinstance(self.companions, CompanionPaths):
            raise OptionError("companions", "companions must be a Companions or a map of its "
                              f"fields, not {shown(self.companions)}")
        for name in ("strict", "use_settings", "allow_env"):
            held(name, getattr(self, name), "flag", none=name == "allow_env")
        for name in ("stdin_filename", "settings_file", "cache_dir"):
            held(name, getattr(self, name), "path", none=True)
        if self.max_file_size is not None:
            checked_file_size(self.max_file_size, "max_file_size")
        held("timeout", self.timeout, "seconds", none=True)
        for name in ("max_triangles", "jobs"):
            held(name, getattr(self, name), "count", none=True)


class FileSettings(Frozen):
    """How one file is checked: its settings file merged with the request.

    strict: whether a warning in it fails the run
    memory: the address space a worker checking it may use in [bytes]; None for no limit
    timeout: the time checking it may take in [s]; None for no limit
    """

    options: CheckOptions
    strict: bool
    memory: int | None
    timeout: float | None
    skipped: tuple  # the settings files not read on the way (:func:`foreign`), in words

    __slots__ = ("options", "strict", "memory", "timeout", "skipped")

    def __init__(self, options: CheckOptions, strict: bool, memory: int | None,
                 timeout: float | None = DEFAULT_TIMEOUT, skipped: tuple = ()) -> None:
        set_field = object.__setattr__
        set_field(self, "options", options)
        set_field(self, "strict", strict)
        set_field(self, "memory", memory)
        set_field(self, "timeout", timeout)
        set_field(self, "skipped", skipped)


def _applying(path: str, request: CheckRequest) -> Settings:
    """The settings file that applies to ``path`` under the request (none, ``--config``'s, or
    the one above it)."""
    return (Settings() if not request.use_settings else
            settings_file(request.settings_file) if request.settings_file is not None else
            settings_for(path))


def notes_shown(path: str, asked: bool | None, request: CheckRequest) -> bool:
    """Whether the text report shows the notes about ``path``: ``asked`` (``--notes`` or
    ``--no-notes``) when given, else the ``notes`` setting that applies to it, else no (also
    when its settings are broken: the run reports those)."""
    if asked is not None:
        return asked
    if path == "-" and request.stdin_filename:
        path = request.stdin_filename
    try:
        return _applying(path, request).notes
    except SettingsError:
        return False


def for_file(path: str, request: CheckRequest) -> FileSettings:
    """The settings for checking ``path``: the settings file above it (unless the request
    turns them off) under the request. Command-line values win: ``select`` replaces, ``ignore``
    and per-file ignores add, companions and packages win one by one."""
    settings = _applying(path, request)
    selection = Selection(tuple(_codes(request.select or settings.select)),
                          tuple(_codes([*settings.ignore, *request.ignore])),
                          request.targets or tuple(_codes(settings.targets)))
    if selection.runs_nothing():  # every rule ignored (`ignore = ["U"]` in a settings file a
        # pull request edits, `--select U1 --ignore U1`): a check of nothing is no pass. A
        # per-file ignore of every rule is how a repository leaves vendored files out: not here
        where = f" (with {settings.path})" if settings.path else ""
        raise SettingsError(f"select {list(selection.select)}, ignore "
                            f"{list(selection.ignore)} and targets "
                            f"{list(selection.targets)}{where} leave no rule to check "
                            f"{path} with")
    selection = replace(selection, ignore=(
        *selection.ignore, *_codes(settings.ignores_for(path))))
    options = CheckOptions(
        xacro_args={**settings.args_for(path), **request.xacro_args}, packages={**settings.packages, **request.packages},
        selection=selection, allow_env=env_allowed(request.allow_env),
        max_file_size=request.max_file_size or settings.max_file_size
        or DEFAULT_MAX_FILE_SIZE,
        companions=_settings_companions(settings).overridden_by(request.companions),
        mesh_limits=MeshLimits(max_triangles=_given(request.max_triangles,
                                                    settings.max_triangles, MAX_TRIANGLES)))
    memory = request.max_memory if request.max_memory is not None else settings.max_memory
    try:
        limit = DEFAULT_MEMORY if memory is None else parse_memory(str(memory))  # or bytes
    except UsageError:
        raise SettingsError(f"max_memory must be a size such as \"2G\", \"512M\" or 0 "
                            f"(no limit), not {shown(memory)}") from None
    timeout = _given(request.timeout, settings.timeout, DEFAULT_TIMEOUT)
    return FileSettings(options, request.strict or settings.strict, limit, timeout or None,
                        settings.skipped)


def _given(requested, setting, default):
    """The request's value when given (the command line wins), else the settings', else the
    built-in one."""
    return requested if requested is not None else setting if setting is not None else default


def _codes(values: Iterable[str]) -> list[str]:
    """Codes from values that may each hold several, comma-separated, each once (in the order
    first given): a selection of 100,000 codes was matched against every rule, for each rule,
    in settings and in each worker (3.4 s), where the distinct codes and names are a few
    hundred."""
    return list(dict.fromkeys(part.strip() for value in values for part in value.split(",")
                              if part.strip()))
