"""What changed in the files beside two robots: the SRDF's groups and disabled collision pairs,
and the controller YAML, key by key.

Each side's companions are the ones ``check`` finds (or is told about) for that robot
(:mod:`urdftool.description.companions`); for ``diff --rev`` the old side's come from the same
revision. Link and joint names of the old side are read through the renames found in the
URDF, so renaming a link is not also a change of every group and pair naming it.
"""

from __future__ import annotations

import os

from urdftool.compare.structure import Change, Renames, same_value


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
        out[prefix] = tuple(rename(item) if isinstance(item, str) else item for item in data)
    else:
        out[prefix] = rename(data) if isinstance(data, str) else data
    return out


def _by_place(files, base) -> dict:
    """Readable files by their path relative to the robot's folder (how the two sides pair)."""
    return {os.path.relpath(f.path, base): f for f in files if f.problem is None}


def compare(old_robot, new_robot, renames: Renames) -> list[Change]:
    """Changes in the SRDF groups and disabled pairs, and in the controller YAML."""
    from urdftool.description.companions import companions

    old, new = companions(old_robot), companions(new_robot)

    def rename(name):
        return _old_name(renames, name)

    def same(name):
        return name

    changes: list[Change] = []
    old_srdf = old.srdf.data if old.srdf is not None and old.srdf.problem is None else None
    new_srdf = new.srdf.data if new.srdf is not None and new.srdf.problem is None else None
    if old_srdf is not None or new_srdf is not None:
        for element, read in (("group", _groups), ("disable_collisions", _disabled)):
            before = read(old_srdf, rename) if old_srdf is not None else {}
            after = read(new_srdf, same) if new_srdf is not None else {}
            changes += _compare_tables(element, before, after)
    old_files = _by_place(old.controllers, old_robot.base_dir)
    new_files = _by_place(new.controllers, new_robot.base_dir)
    for place in list(old_files) + [p for p in new_files if p not in old_files]:
        if place not in new_files:
            changes.append(Change("removed", "controllers", place))
        elif place not in old_files:
            changes.append(Change("added", "controllers", place))
        else:
            before = _flat(old_files[place].data, rename)
            after = _flat(new_files[place].data, same)
            changes += [Change("changed", "controllers", place, key, before.get(key),
                               after.get(key))
                        for key in list(before) + [k for k in after if k not in before]
                        if not same_value(before.get(key), after.get(key))]
    return changes


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
