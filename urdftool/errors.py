"""Exceptions. One base class; narrow subclasses carry the data a reporter needs."""

from __future__ import annotations

import difflib


class UrdftoolError(Exception):
    """Base class of every error urdftool raises on purpose."""


class UsageError(UrdftoolError):
    """The command line asked for something impossible (exit code 2)."""


class SettingsError(UrdftoolError):
    """A settings file, or a setting passed to the API, is malformed or names a path it may
    not."""


class TargetError(UrdftoolError):
    """A path to check does not exist or holds no robot description."""


class LoadError(UrdftoolError):
    """A robot description could not be loaded.

    kind: why, one of 'read', 'too-large', 'empty', 'binary', 'syntax', 'entity', 'root',
        'xacro', 'arg' (an undefined xacro argument, named by ``subject``), 'io', 'package'
        (named by ``subject``), 'sandbox', 'outside' or 'link'
    message: what went wrong, for people
    location: the :class:`~urdftool.diagnostics.Location` of the problem
    """

    def __init__(self, kind: str, message: str, location, subject: str | None = None):
        self.kind = kind
        self.message = message
        self.location = location
        self.subject = subject
        super().__init__(message)


class PackageNotFound(UrdftoolError):
    """A ROS package named by ``$(find)`` or ``package://`` is nowhere on the search path."""

    def __init__(self, name: str, searched: list[str]):
        self.name = name
        self.searched = searched
        where = ", ".join(searched) if searched else "nowhere (no search path)"
        super().__init__(
            f"package '{name}' not found; looked in: {where}. "
            f"Pass --package {name}=PATH or set ROS_PACKAGE_PATH"
        )

_LISTED = 12


def available(kind: str, wanted: str, names) -> str:
    """``Did you mean 'x'? Available links: a, b, ...`` for a name that does not exist."""
    names = sorted({name for name in names if name})  # unnamed elements are another rule's business
    close = difflib.get_close_matches(wanted, names, n=1, cutoff=0.6)
    hint = f"did you mean '{close[0]}'? " if close else ""
    shown = ", ".join(names[:_LISTED]) + (f", ... ({len(names)} in all)" if len(names) > _LISTED else "")
    return f"{hint}available {kind}: {shown or '(none)'}"
