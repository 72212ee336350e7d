"""What loading a robot takes besides its file: the companion files the user named and the
limits on its meshes. Kept apart from the loader so that the settings, the runner and the
result cache handle them without importing it (a re-run served from the cache never does).

And the one guard of the options a caller gives (:func:`held`): ``urdftool.load`` and
``CheckRequest`` (``check_paths``, ``check_file``, the pytest fixture) hold each option to the
kind the command line and the settings take, an :class:`~urdftool.errors.OptionError` naming
it (``load(packages="x")`` was Python's AttributeError from inside, ``allow_env="no"`` true)."""

from __future__ import annotations

import datetime
import json
import math
import os
import re
from collections.abc import Iterable, Mapping
from pathlib import Path

from urdftool.errors import OptionError, SettingsError
from urdftool.records import Frozen

MAX_TRIANGLES = 2_000_000
MAX_MESH_BYTES = 128 * 1024 * 1024
MAX_FILE_SIZE = 2 ** 40  # [bytes] the largest size limit an option can set (1 TiB)


class SettingValue(str):
    """A xacro argument's value that a repository's settings file gave (``per-file-args``):
    data for the expansion, never a folder included files may come from (a value given on the
    command line is one, see :func:`urdftool.description.load.load`)."""

    __slots__ = ()


class MeshLimits(Frozen):
    """How many triangles and bytes a mesh may have to be read."""

    max_triangles: int
    max_bytes: int

    __slots__ = ("max_triangles", "max_bytes")

    def __init__(self, max_triangles: int = MAX_TRIANGLES,
                 max_bytes: int = MAX_MESH_BYTES) -> None:
        set_field = object.__setattr__
        set_field(self, "max_triangles", max_triangles)
        set_field(self, "max_bytes", max_bytes)


class CompanionPaths(Frozen):
    """Companion files named by the user (``check --controllers/--srdf/--spec`` or the settings
    file); what is not named is discovered beside the robot (:mod:`.companions`)."""

    controllers: tuple[Path, ...]
    srdf: Path | None
    spec: Path | None

    __slots__ = ("controllers", "srdf", "spec")

    def __init__(self, controllers: tuple[Path, ...] = (), srdf: Path | None = None,
                 spec: Path | None = None) -> None:
        set_field = object.__setattr__
        set_field(self, "controllers", controllers)
        set_field(self, "srdf", srdf)
        set_field(self, "spec", spec)
        self.__post_init__()

    def __post_init__(self):
        object.__setattr__(self, "controllers", tuple(Path(p) for p in self.controllers or ()))
        for kind in ("srdf", "spec"):
            if getattr(self, kind) is not None:
                object.__setattr__(self, kind, Path(getattr(self, kind)))

    def named(self) -> list[Path]:
        """Every file named."""
        return [*self.controllers, *(p for p in (self.srdf, self.spec) if p is not None)]

    def overridden_by(self, other: "CompanionPaths") -> "CompanionPaths":
        """These paths with every one ``other`` names replaced (the command line wins)."""
        return CompanionPaths(other.controllers or self.controllers, other.srdf or self.srdf,
                              other.spec or self.spec)


# The kinds of option a caller gives, what each takes (said in the message) and its test.
# words: str or an iterable of str (one word alone is a tuple of it); names: a mapping of str
# to str (xacro arguments) or to paths (packages); paths: the same, its values as Path; flag:
# True or False (not "no", not 0); path: str or os.PathLike; seconds: a finite number, 0 or
# more; count: a whole number, 0 or more; call: a callable. A size limit is
# :func:`checked_file_size`'s (a SettingsError, as the settings files' and
# ``--max-file-size``'s).
_KINDS = {
    "words": "be words (str)", "names": "map names (str) to values (str)",
    "flag": "be True or False", "path": "be a path", "seconds": "be a finite number of "
    "seconds, 0 for none", "count": "be a whole number, 0 or more", "call": "be callable",
}


def held(option: str, value, kind: str, *, none: bool = False):
    """``value`` of the option named ``option`` held to ``kind`` (above), as the caller uses it:
    words as a tuple, names as a dict (paths as Path); None passes when ``none``. The one guard
    of a caller's options: OptionError (a UsageError, TypeError and ValueError) naming the
    option and the value otherwise."""
    if value is None and none:
        return None
    if kind == "words":
        words = (value,) if isinstance(value, str) else tuple(value) if isinstance(value, Iterable) \
            else None
        if words is not None and all(isinstance(word, str) for word in words):
            return words
    elif kind == "names" or kind == "paths":
        if isinstance(value, Mapping) and all(
                isinstance(key, str) and isinstance(item, (str, os.PathLike))
                for key, item in value.items()):
            return {key: Path(item) if kind == "paths" else item for key, item in value.items()}
        kind = "names"
    elif kind == "flag":
        if isinstance(value, bool):
            return value
    elif kind == "path":
        if isinstance(value, (str, os.PathLike)):
            return value
    elif kind == "seconds":  # (an int past a double is below inf, and float() of it raised
        # OverflowError where the budget was made)
        if not isinstance(value, bool) and isinstance(value, (int, float)) and \
                0 <= value < math.inf and (isinstance(value, float) or value < 2 ** 1023):
            return value
    elif kind == "count":
        if not isinstance(value, bool) and isinstance(value, int) and value >= 0:
            return value
    elif kind == "call":
        if callable(value):
            return value
    else:
        raise ValueError(f"no kind of option {kind!r}")
    raise OptionError(option, f"{option} must {_KINDS[kind]}, not {shown(value)}")


_SHOWN = 80  # [characters] of a settings value a message quotes, at most


def shown(value) -> str:
    """A settings value as TOML writes it, the one way a settings message quotes one: in the
    words the user wrote (``1979-05-27T07:32:00-08:00``, ``true``, ``nan``, ``"a"`` with TOML's
    escapes, ``[1, 2]``, ``{ a = 1 }``), not Python's (``datetime.datetime(1979, ...)``,
    ``True``), and cut to 80 characters (a 100,000-character string is not repeated whole). A
    value TOML cannot hold (the Python API's) is its ``repr``."""
    pieces, length = [], 0
    for piece in _toml(value):
        pieces.append(piece)
        length += len(piece)
        if length > _SHOWN:
            return "".join(pieces)[:_SHOWN - 3] + "..."
    return "".join(pieces)


def _toml(value):
    """The pieces of ``value`` written as TOML (:func:`shown`), lazily: the text past what a
    message quotes is never made."""
    if isinstance(value, bool):
        yield "true" if value else "false"
    elif isinstance(value, int) and value.bit_length() > 14_000:  # past what str() writes
        yield f"a whole number of {int(value.bit_length() * math.log10(2))} digits or so"
    elif isinstance(value, int) or isinstance(value, float) and math.isfinite(value):
        yield repr(value)  # (an int past a double: math.isfinite raised OverflowError)
    elif isinstance(value, float):
        yield "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    elif isinstance(value, str):
        yield json.dumps(value, ensure_ascii=False)  # TOML's basic string: JSON's escapes
    elif isinstance(value, (datetime.datetime, datetime.date, datetime.time)):
        yield value.isoformat()
    elif isinstance(value, list):
        yield "["
        for index, item in enumerate(value):
            yield ", " if index else ""
            yield from _toml(item)
        yield "]"
    elif isinstance(value, dict):
        yield "{ " if value else "{"
        for index, (key, item) in enumerate(value.items()):
            bare = isinstance(key, str) and _BARE_KEY.fullmatch(key)
            written = key if bare else json.dumps(str(key), ensure_ascii=False)
            yield (", " if index else "") + written + " = "
            yield from _toml(item)
        yield " }" if value else "}"
    else:
        yield repr(value)


_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")


def checked_file_size(value, what: str, most: int = MAX_FILE_SIZE, why: str = "") -> int:
    """``value`` as a file size limit in [bytes]; SettingsError naming ``what`` (and saying
    ``why``) unless it is a whole number from 1 to ``most``."""
    if isinstance(value, bool) or not isinstance(value, int) or not 0 < value <= most:
        raise SettingsError(f"{what} must be a whole number of bytes from 1 to {most}, "
                            f"not {shown(value)}{why}")
    return value
