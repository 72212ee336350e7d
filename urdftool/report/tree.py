"""``urdftool tree``: the kinematic tree listed the way urdfdom's check_urdf lists it."""

from __future__ import annotations

from urdftool.kinematics.tree import children_by_link, root_link


def tree_text(robot) -> str:
    """check_urdf's tree listing; TreeError (urdftool.kinematics.tree) when there is no tree."""
    root = root_link(robot)
    children = children_by_link(robot)
    lines = [f"robot name is: {robot.name}",
             "---------- Successfully Parsed XML ---------------",
             f"root Link: {root} has {len(children.get(root, []))} child(ren)"]

    def walk(link: str, depth: int):
        for index, (_, child) in enumerate(children.get(link, []), start=1):
            lines.append("    " * depth + f"child({index}):  {child}")
            walk(child, depth + 1)

    walk(root, 1)
    return "\n".join(lines) + "\n"
