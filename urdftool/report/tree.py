"""``urdftool tree``: the kinematic tree listed the way urdfdom's check_urdf lists it."""

from __future__ import annotations

from urdftool.kinematics.tree import children_by_link, root_link
from urdftool.report.escape import text


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
        lines.append("    " * depth + f"child({index}):  {text(link)}")
        if link in seen:
            continue  # a cycle below the root: listed once, not followed
        seen.add(link)
        stack.extend((child, number, depth + 1) for number, (_, child) in reversed(
            list(enumerate(children.get(link, []), start=1))))
    return "\n".join(lines) + "\n"
