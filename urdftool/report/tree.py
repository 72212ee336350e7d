"""``urdftool tree``: the kinematic tree listed the way urdfdom's check_urdf lists it."""

from __future__ import annotations

from urdftool.kinematics.tree import children_by_link, root_link
from urdftool.report.escape import text

DEEPEST = 64  # [levels] indented; a deeper line keeps this indentation and says its depth


def _indented(depth: int, line: str) -> str:
    """``line`` indented as check_urdf indents it at ``depth``, to at most :data:`DEEPEST`
    levels: past them a line says its depth instead (``[depth 3000] child(1):  l2999``), so
    the listing grows with the links, not with their square (a 30,000-link chain: 1.8 GB)."""
    if depth <= DEEPEST:
        return "    " * depth + line
    return "    " * DEEPEST + f"[depth {depth}] " + line


def tree_text(robot) -> str:
    """check_urdf's tree listing; TreeError (urdftool.kinematics.tree) when there is no tree."""
    root = root_link(robot)
    children = children_by_link(robot)
    lines = [f"robot name is: {text(robot.name)}",
             "---------- Successfully Parsed XML ---------------",
             f"root Link: {text(root)} has {len(children.get(root, []))} child(ren)"]

    # depth first with a stack of our own, not recursion: a 1,500-link chain is 1,500 deep
    stack = [(child, index, 1) for index, (_, child) in reversed(
        list(enumerate(children.get(root, []), start=1)))]
    seen = {root}
    while stack:
        link, index, depth = stack.pop()
        lines.append(_indented(depth, f"child({index}):  {text(link)}"))
        if link in seen:
            continue  # a cycle below the root: listed once, not followed
        seen.add(link)
        stack.extend((child, number, depth + 1) for number, (_, child) in reversed(
            list(enumerate(children.get(link, []), start=1))))
    return "\n".join(lines) + "\n"
