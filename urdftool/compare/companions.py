"""What changed in the files beside two robots: the SRDF's groups and disabled collision pairs,
and the controller YAML, key by key.

Each side's companions are the ones ``check`` finds (or is told about) for that robot
(:mod:`urdftool.description.companions`); for ``diff --rev`` the old side's come from the same
revision. Link and joint names of the old side are read through the renames found in the
URDF, so renaming a link is not also a change of every group and pair naming it.

A file of the same place that one side cannot read or parse (a FIFO, a folder, a link leading
out, invalid UTF-8, not YAML or XML) is not compared, and said so (:class:`NotCompared`), unless
both sides hold the same bytes: neither equal nor changed can be claimed of what was not read.
"""

from __future__ import annotations

import os
from pathlib import Path

from urdftool.compare.structure import Change, NotCompared, Renames, same_value


def _old_name(renames: Renames, name):
    """An old link or joint name as the new description calls it."""
    return renames.links.get(name, renames.joints.get(name, name))


def _groups(srdf, rename) -> dict[str, tuple]:
    """Group name -> its members, sorted: 'joint NAME', 'link NAME', 'chain BASE -> TIP',
    'group NAME'."""
    found = {}
    for group in srdf.iter("group"):
        members = []
        for child in group:
            if child.tag in ("joint", "link"):
                members.append(f"{child.tag} {rename(child.get('name'))}")
            elif child.tag == "chain":
                members.append(f"chain {rename(child.get('base_link'))} -> "
                               f"{rename(child.get('tip_link'))}")
            elif child.tag == "group":
                members.append(f"group {child.get('name')}")
        found.setdefault(group.get("name"), tuple(sorted(members)))
    return found


def _disabled(srdf, rename) -> dict[str, str]:
    """'link1/link2' (sorted) -> reason, for every ``disable_collisions``."""
    found = {}
    for entry in srdf.iter("disable_collisions"):
        pair = sorted((rename(entry.get("link1")) or "", rename(entry.get("link2")) or ""))
        found.setdefault("/".join(pair), entry.get("reason") or "")
    return found


def _flat(data, rename, prefix: str = "", out=None, depth: int = 0) -> dict:
    """A YAML document as {dotted key: value}; a list of scalars is one value."""
    out = {} if out is None else out
    if depth > 64:  # the YAML reader bounds depth too; this only keeps the walk finite
        return out
    if isinstance(data, dict):  # keys may be joint names too (tolerances per joint)
        for key, value in data.items():
            key = rename(key) if isinstance(key, str) else key
            _flat(value, rename, f"{prefix}.{key}" if prefix else str(key), out, depth + 1)
    elif isinstance(data, list) and any(isinstance(item, (dict, list)) for item in data):
        for index, value in enumerate(data):
            _flat(value, rename, f"{prefix}[{index}]", out, depth + 1)
    elif isinstance(data, list):
        out[prefix] = tuple(rename(item) if isinstance(item, str) else _plain(item)
                            for item in data)
    else:
        out[prefix] = rename(data) if isinstance(data, str) else _plain(data)
    return out


def _plain(value):
    """A YAML value as the diff compares and writes it, exact: JSON's scalars as they are, a
    set as its items in order, an ordered map's pairs as pairs, bytes as text, a date or a
    timestamp as its text (a set or a date was a traceback of ``diff -f json``: no JSON
    value; and the text report wrote its repr, unquoted)."""
    if value is None or isinstance(value, (str, int, float)):
        return value
    if isinstance(value, (set, frozenset, tuple, list)):
        items = tuple(_plain(item) for item in value)
        return items if isinstance(value, (tuple, list)) else tuple(sorted(items, key=repr))
    if isinstance(value, bytes):
        return value.decode("utf-8", "backslashreplace")
    return str(value)


def _by_place(files, base) -> dict:
    """Files by their path relative to the robot's folder (how the two sides pair)."""
    return {os.path.relpath(f.path, base): f for f in files}


def _unread_by_place(found, base) -> dict:
    """The files named as companions are where none could be read (a folder, a FIFO, a link
    to another folder), by place, each as a companion file holding why as its problem."""
    from urdftool.description.documents import CompanionFile
    from urdftool.diagnostics import display_path

    return {os.path.relpath(path, base): CompanionFile(path, display_path(path), problem=why)
            for path, why in found.unread.items()}


def _paired(one: dict, other: dict, other_unread: dict) -> None:
    """Where ``one`` has a file and ``other`` none, but ``other`` has an unreadable one of
    that place, or a folder on its way that is not entered: that one, so that the place is
    not compared rather than removed or added."""
    for place in one:
        if place in other:
            continue
        folders = [str(parent) for parent in Path(place).parents if str(parent) != "."]
        unread = next((other_unread[name] for name in [place, *folders] if name in other_unread),
                      None)
        if unread is not None:
            other[place] = unread


def _same_bytes(old, new) -> bool:
    """Whether two companion files hold the same bytes: each a regular file itself (no link
    is followed here, so nothing is read that discovery did not read), neither over the
    limit. A file neither side can parse is then the same file, unchanged."""
    from urdftool.description.documents import MAX_SIZE
    from urdftool.description.files import kind_of, read_regular

    if kind_of(old.path, follow=False) != "file" or kind_of(new.path, follow=False) != "file":
        return False
    try:
        return read_regular(old.path, MAX_SIZE, "compared") == read_regular(new.path, MAX_SIZE,
                                                                           "compared")
    except OSError:  # (TooLarge too)
        return False


def _unread(element: str, place: str, old, new) -> list[NotCompared]:
    """A file of the same place on both sides, one of which was not read or parsed: not
    compared, with each side's reason; nothing when both hold the same bytes."""
    if (old is None or old.problem is None) and (new is None or new.problem is None):
        return []
    if old is not None and new is not None and _same_bytes(old, new):
        return []
    return [NotCompared(element, place, old.problem if old is not None else None,
                        new.problem if new is not None else None)]


def compare(old_robot, new_robot, renames: Renames) -> tuple[list[Change], list[NotCompared]]:
    """Changes in the SRDF groups and disabled pairs, and in the controller YAML; and the files
    not compared (a side's file unread or not parsed)."""
    from urdftool.description.companions import companions

    old, new = companions(old_robot), companions(new_robot)

    def rename(name):
        return _old_name(renames, name)

    def same(name):
        return name

    changes: list[Change] = []
    unread: list[NotCompared] = []
    old_unread = _unread_by_place(old, old_robot.base_dir)
    new_unread = _unread_by_place(new, new_robot.base_dir)
    old_srdfs = {os.path.relpath(old.srdf.path, old_robot.base_dir): old.srdf} if old.srdf else {}
    new_srdfs = {os.path.relpath(new.srdf.path, new_robot.base_dir): new.srdf} if new.srdf else {}
    _paired(old_srdfs, new_srdfs, new_unread)
    _paired(new_srdfs, old_srdfs, old_unread)
    if old_srdfs or new_srdfs:
        srdfs = (next(iter(old_srdfs.values()), None), next(iter(new_srdfs.values()), None))
        unread += _unread("srdf", next(iter(new_srdfs or old_srdfs)), *srdfs)
        if all(f is None or f.problem is None for f in srdfs):  # (a side without one: its
            for element, read in (("group", _groups), ("disable_collisions", _disabled)):
                before = read(srdfs[0].data, rename) if srdfs[0] is not None else {}
                after = read(srdfs[1].data, same) if srdfs[1] is not None else {}
                changes += _compare_tables(element, before, after)  # groups added or removed)
    old_files = _by_place(old.controllers, old_robot.base_dir)
    new_files = _by_place(new.controllers, new_robot.base_dir)
    _paired(old_files, new_files, new_unread)
    _paired(new_files, old_files, old_unread)
    for place in list(old_files) + [p for p in new_files if p not in old_files]:
        if place not in new_files:
            changes.append(Change("removed", "controllers", place))
        elif place not in old_files:
            changes.append(Change("added", "controllers", place))
        else:
            missed = _unread("controllers", place, old_files[place], new_files[place])
            unread += missed
            if missed or old_files[place].problem is not None:
                continue  # not compared, or the same bytes, parsed by neither side
            before = _flat(old_files[place].data, rename)
            after = _flat(new_files[place].data, same)
            changes += [Change("changed", "controllers", place, key, before.get(key),
                               after.get(key))
                        for key in list(before) + [k for k in after if k not in before]
                        if not same_value(before.get(key), after.get(key))]
    return changes, unread


def _compare_tables(element: str, before: dict, after: dict) -> list[Change]:
    changes = []
    for name in list(before) + [n for n in after if n not in before]:
        if name not in after:
            changes.append(Change("removed", element, name, old=before[name]))
        elif name not in before:
            changes.append(Change("added", element, name, new=after[name]))
        elif before[name] != after[name]:
            field = "members" if element == "group" else "reason"
            changes.append(Change("changed", element, name, field, before[name], after[name]))
    return changes
