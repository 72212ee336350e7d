"""The kinematic tree as urdfdom builds it: children ordered by joint name."""

from __future__ import annotations

from urdftool.errors import TreeError


def children_by_link(robot) -> dict[str, list[tuple[str, str]]]:
    """Parent link -> [(joint name, child link)], sorted by joint name like urdfdom's std::map."""
    children: dict[str, list[tuple[str, str]]] = {}
    for joint in robot.children("joint"):
        parent, child = joint.find("parent"), joint.find("child")
        if parent is None or child is None:
            raise TreeError(f"joint '{joint.get('name')}' lacks a parent or child", joint)
        children.setdefault(parent.get("link"), []).append((joint.get("name"), child.get("link")))
    for entries in children.values():
        entries.sort(key=lambda entry: entry[0].encode())
    return children


def root_link(robot) -> str:
    """The single root link; raises TreeError when there is none or several."""
    child_links = {child.get("link") for child in robot.root.iter("child")
                   if child.getparent() is not None and child.getparent().tag == "joint"}
    roots = [name for name in robot.links if name not in child_links]
    if len(roots) != 1:
        what = "no root link (a cycle?)" if not roots else f"{len(roots)} root links: {roots}"
        raise TreeError(what, robot.root)
    return roots[0]

