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
        if joint.get("name") is None:  # (urdfdom refuses it; diff's effects died sorting it)
            raise TreeError("a <joint> has no name attribute", joint)
        children.setdefault(parent.get("link"), []).append((joint.get("name"), child.get("link")))
    for entries in children.values():
        entries.sort(key=lambda entry: entry[0].encode())
    return children


def roots(robot) -> list[str]:
    """The links no joint names as its child, in document order: one in a tree."""
    child_links = {child.get("link") for child in robot.root.iter("child")
                   if child.getparent() is not None and child.getparent().tag == "joint"}
    return [name for name in robot.links if name not in child_links]


def root_link(robot) -> str:
    """The single root link; raises TreeError when there is none or several."""
    found = roots(robot)
    if len(found) != 1:
        what = "no root link (a cycle?)" if not found else f"{len(found)} root links: {found}"
        raise TreeError(what, robot.root)
    return found[0]


def beside_the_tree(robot) -> list[str]:
    """The links urdfdom's tree leaves out, in document order: those no walk down the joints
    from the root reaches (a loop of joints beside the tree, and what hangs from it), when the
    robot has one root; else none (no tree to be beside). urdfdom builds its tree from the root
    and drops them silently (check_urdf's listing, Pinocchio's model); every command that
    poses the robot, and ``inertia``, leaves them out as it does."""
    def find():
        try:
            root = root_link(robot)
        except TreeError:
            return []
        children: dict[str, list] = {}  # (the joints' ends as read once: Robot.ends)
        for ends in robot.ends().values():
            children.setdefault(ends["parent"][1], []).append(ends["child"][1])
        reached, stack = {root}, [root]
        while stack:
            for child in children.get(stack.pop(), ()):
                if child not in reached:
                    reached.add(child)
                    stack.append(child)
        return [name for name in robot.links if name not in reached]

    return robot.memo(beside_the_tree, find)


def posed_links(robot) -> dict[str, object]:
    """Link elements by name (:attr:`Robot.links`) but those :func:`beside_the_tree`: the
    links every command that poses the robot has, and so the ones an option may name (a
    support, a link to compare, a chain's end)."""
    dropped = set(beside_the_tree(robot))
    return {name: link for name, link in robot.links.items() if name not in dropped} \
        if dropped else robot.links


def own_free_base(robot) -> str | None:
    """The robot's own free base: a ``floating`` joint that is the only joint below a root
    link without an ``<inertial>`` (``world`` -> ``base_link``, as a simulator's description
    writes a free body), or None (also for a robot without one root). Pinocchio reads it as a
    free flyer: a free base of the robot's, to be used as the base that ``--floating`` would
    add above it. (Below a root with a mass, the root stays in the world and a floating joint
    frees only what hangs from it: no free base of the robot.)"""
    try:
        root = root_link(robot)
        below = children_by_link(robot).get(root, [])
    except TreeError:
        return None
    if len(below) != 1 or robot.joints[below[0][0]].get("type") != "floating" or \
            robot.links[root].find("inertial") is not None:
        return None
    return below[0][0]


def pair_key(one: str, two: str) -> tuple[str, str]:
    """A pair of links as MoveIt stores it: the smaller name (byte order) first."""
    return (one, two) if one.encode() <= two.encode() else (two, one)


def adjacent_pairs(robot, with_geometry: set[str]) -> set[tuple[str, str]]:
    """Pairs of the links ``with_geometry`` joined by a joint, looking through links that have
    no geometry (MoveIt's Setup Assistant's "Adjacent")."""
    neighbours: dict[str, set[str]] = {name: set() for name in robot.links}
    for parent, children in children_by_link(robot).items():
        for _, child in children:
            neighbours.setdefault(parent, set()).add(child)
            neighbours.setdefault(child, set()).add(parent)
    result = set()
    for start in with_geometry:
        seen, stack = {start}, [start]
        while stack:
            for other in neighbours.get(stack.pop(), ()):
                if other in seen:
                    continue
                seen.add(other)
                if other in with_geometry:
                    result.add(pair_key(start, other))
                else:
                    stack.append(other)
    return result


def welded_pairs(robot, links: set[str]) -> set[tuple[str, str]]:
    """Pairs of ``links`` held together by fixed joints alone (siblings on one rigid body, a
    bracket on a motor): no configuration moves one against the other."""
    body = {name: name for name in robot.links}

    def find(name: str) -> str:
        while body.setdefault(name, name) != name:
            body[name] = body[body[name]]
            name = body[name]
        return name
    for joint in robot.children("joint"):
        parent, child = joint.find("parent"), joint.find("child")
        if joint.get("type") == "fixed" and parent is not None and child is not None:
            body[find(child.get("link"))] = find(parent.get("link"))
    groups: dict[str, list[str]] = {}
    for name in links:
        groups.setdefault(find(name), []).append(name)
    return {pair_key(a, b) for members in groups.values()
            for i, a in enumerate(members) for b in members[i + 1:]}


def closing_pairs(robot, links: set[str]) -> set[tuple[str, str]]:
    """Pairs of ``links`` joined by a joint written in a ``<gazebo>`` block (an SDF joint, its
    ``<parent>`` and ``<child>`` naming links): how a parallel robot for Gazebo closes its loops
    (a delta's legs on their platform), a joint no URDF reader has in its tree."""
    found = set()
    for block in robot.root.iterchildren("gazebo"):
        for joint in block.iterchildren("joint"):
            ends = [(joint.findtext(end) or "").strip() for end in ("parent", "child")]
            if ends[0] != ends[1] and all(end in links for end in ends):
                found.add(pair_key(*ends))
    return found
