"""Exceptions. One base class; narrow subclasses carry the data a reporter needs."""

from __future__ import annotations


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
