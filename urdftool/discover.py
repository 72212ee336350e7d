"""Which files ``urdftool check DIR`` checks: top-level robots, not the macro libraries they
include."""

from __future__ import annotations

import os
import re
import stat
from pathlib import Path

from .loader.packages import PackageResolver

SUFFIXES = (".urdf", ".xacro")
_CLASSIFY_BYTES = 16 * 1024 * 1024  # read no more of a file to decide whether it is a robot
_SKIP_DIRS = {".git", ".venv", "venv", "node_modules", "__pycache__", "build", "install", "log"}
_INCLUDE = re.compile(rb"<xacro:include\s[^>]*?filename\s*=\s*[\"']([^\"']+)[\"']", re.S)
_FIND = re.compile(r"\$\(find\s+([^)\s]+)\)")
_DIRECT_CONTENT = re.compile(rb"<(link|joint)[\s>/]")
_MACRO_CALL = re.compile(rb"<xacro:(?!(?:include|property|macro|arg|if|unless|insert_block|"
                         rb"element|attribute)\b)[A-Za-z_]")
_MACRO_DEF = re.compile(rb"<xacro:macro[\s>].*?</xacro:macro>", re.S)


def robot_files(folder: Path) -> list[Path]:
    """Every .urdf and .xacro file below ``folder``, sorted, skipping tool folders."""
    found = []
    for current, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if d not in _SKIP_DIRS and not d.startswith("."))
        found.extend(Path(current) / f for f in files if f.endswith(SUFFIXES))
    return sorted(found)


def split_top_level(files: list[Path], resolver_for) -> tuple[list[Path], dict[Path, str]]:
    """(top-level files, {skipped file: reason}) for a set of files found in a folder."""
    included: dict[Path, Path] = {}
    contents = {}
    for path in files:
        contents[path] = _head(path)
    for path, data in contents.items():
        for target in _included_files(path, data, resolver_for(path)):
            included.setdefault(target, path)
    top, skipped = [], {}
    for path in files:
        key = _resolved(path)
        if key in included:
            skipped[path] = f"included by {included[key]}"
        elif path.name.endswith(".xacro") and not _defines_robot(contents[path]):
            skipped[path] = "defines only macros or properties (a macro library)"
        else:
            top.append(path)
    return top, skipped


def _resolved(path: Path) -> Path:
    try:
        return path.resolve()
    except (OSError, ValueError, RuntimeError):  # NUL in a name, a symlink loop
        return path.absolute()


def _head(path: Path) -> bytes:
    """The start of a regular file (enough to classify it); nothing for FIFOs and devices."""
    try:
        if not stat.S_ISREG(path.stat().st_mode):
            return b""
        with open(path, "rb") as handle:
            return handle.read(_CLASSIFY_BYTES)
    except (OSError, ValueError):
        return b""


def _defines_robot(data: bytes) -> bool:
    outside_macros = _MACRO_DEF.sub(b"", data)
    return bool(_DIRECT_CONTENT.search(outside_macros) or _MACRO_CALL.search(outside_macros))


def _included_files(path: Path, data: bytes, resolver: PackageResolver):
    for match in _INCLUDE.finditer(data):
        spec = match.group(1).decode("utf-8", "replace")
        find = _FIND.search(spec)
        if find:
            try:
                spec = spec.replace(find.group(0), str(resolver.find(find.group(1))))
            except Exception:
                continue
        if "$" in spec or "\0" in spec:
            continue
        yield _resolved(path.parent / spec)
