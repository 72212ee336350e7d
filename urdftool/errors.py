"""Exceptions. One base class; narrow subclasses carry the data a reporter needs."""

from __future__ import annotations

import difflib
from dataclasses import dataclass


class UrdftoolError(Exception):
    """Base class of every error urdftool raises on purpose."""


class UsageError(UrdftoolError):
    """The command line asked for something impossible (exit code 2)."""


class LoadError(UrdftoolError):
    """A robot description could not be loaded; ``findings`` say where and why."""

    def __init__(self, findings):
        self.findings = list(findings)
        super().__init__("; ".join(f.message for f in self.findings) or "load failed")


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
    names = sorted({name for name in names if name})  # unnamed elements are U103's business
    close = difflib.get_close_matches(wanted, names, n=1, cutoff=0.6)
    hint = f"did you mean '{close[0]}'? " if close else ""
    shown = ", ".join(names[:_LISTED]) + (f", ... ({len(names)} in all)" if len(names) > _LISTED else "")
    return f"{hint}available {kind}: {shown or '(none)'}"


# --- Errors of the analyses (one hierarchy; each is re-exported by the module that raises it,
# so ``except fk.FKError`` keeps working) ---------------------------------------------------


class LocatedError(UrdftoolError):
    """An error about a place in a robot description.

    element: the robot's XML element it is about (``Robot.locate`` gives file and line), or None
    location: a :class:`~urdftool.diagnostics.Location` when known without the robot, or None
    """

    element = None
    location = None

    def __init__(self, message: str, element=None, location=None):
        super().__init__(message)
        self.element = element
        self.location = location


@dataclass(frozen=True)
class MeshProblem(LocatedError):
    """Why a mesh cannot be used.

    kind: ``package`` (unknown package), ``outside`` (escapes the root), ``missing``,
    ``format`` (not a mesh extension), ``too-large`` (bytes or triangles), ``corrupt``
    message: what a user should read, naming the file and the fix
    """

    kind: str
    message: str

    def __str__(self) -> str:
        return self.message


class SrdfError(LocatedError):
    """The SRDF cannot be read; the message says where and why."""


class ConfigError(LocatedError):
    """A configuration that cannot be used; ``where`` is a file (and row) when it came from one."""

    def __init__(self, message: str, where: str | None = None):
        super().__init__(f"{where}: {message}" if where else message)
        self.where = where


class MimicError(LocatedError):
    """A mimic joint whose value cannot be resolved; ``element`` is where."""


class TreeError(LocatedError):
    """The joints do not form one tree (no root, several roots, a cycle); ``element`` is where."""


class FKError(LocatedError):
    """The model cannot be built or asked for what it lacks; ``element`` locates it when known."""


class DHError(LocatedError):
    """A chain that cannot be written in D-H form, or a table that cannot be read; ``where`` is
    the table file (and row) when it came from one."""

    def __init__(self, message: str, element=None, where: str | None = None):
        super().__init__(message, element)
        self.where = where


class DynamicsError(LocatedError):
    """The robot cannot be turned into a dynamic model (Pinocchio's reason, made readable)."""


class DotMissing(UrdftoolError):
    """The ``dot`` program is not installed; the DOT file was written instead (the message is
    its path)."""
