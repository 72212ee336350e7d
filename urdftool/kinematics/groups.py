"""MoveIt planning groups: the joints an SRDF ``<group>`` stands for, and whether a chain solver
such as KDL can take the group as one serial chain.

The joints of a group are those MoveIt's ``RobotModel::addJointModelGroup`` collects:

- ``<joint name>``: that joint;
- ``<link name>``: the link's parent joint (for the root link, the SRDF's virtual joint, or the
  fixed joint MoveIt adds when there is none);
- ``<chain base_link tip_link>``: the joints from the tip up to the base. When the base is not
  above the tip, MoveIt walks up from both ends and joins the two paths where they meet, taking
  the parent joint of the meeting link too: a chain written backwards (base below tip) or across
  two branches still makes a group, but not the serial chain its author meant;
- ``<group name>``: every joint of that group.

A group's links are its joints' child links (``JointModelGroup``), so a chain's base link is
not one of them. A chain solver (``JointModelGroup::isChain`` and the KDL plugin) needs the
joints to form one path down the tree: a single top joint, no branch, no moving joint of the
path left out, and only one-variable joints.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from urdftool.description.urdf import MOVING

ASSUMED_ROOT = "ASSUMED_FIXED_ROOT_JOINT"  # MoveIt's fixed root joint when the SRDF has none


@dataclass
class Joint:
    """A joint of a planning group's chain."""

    name: str
    parent: str | None  # None for the root joint, whose parent is the world
    child: str
    type: str


@dataclass
class Shape:
    """Why a group is not one serial chain: ``kind`` (reversed, cross-branch, empty, tree,
    gap, multi-dof), the SRDF ``element`` to point at and the message."""

    kind: str
    element: object
    message: str


@dataclass
class Group:
    """``complete`` is False when some name in it (or in a subgroup) is unknown: its joints are
    then only those that could be found."""

    name: str
    element: object
    joints: set = field(default_factory=set)
    complete: bool = True


class Tree:
    """The robot's joints as MoveIt sees them: the URDF's, plus the root joint."""

    def __init__(self, robot, srdf_root=None):
        self.joints: dict[str, Joint] = {}
        self.parent_joint: dict[str, str] = {}
        for name, element in robot.joints.items():
            parent, child = element.find("parent"), element.find("child")
            if parent is None or child is None or not name:
                continue
            joint = Joint(name, parent.get("link"), child.get("link"), element.get("type", ""))
            self.joints[name] = joint
            self.parent_joint.setdefault(joint.child, name)
        roots = [link for link in robot.links if link not in self.parent_joint]
        virtual = {v.get("child_link"): v for v in
                   (srdf_root.iterfind("virtual_joint") if srdf_root is not None else ())}
        for link in roots[:1]:
            element = virtual.get(link)
            name = element.get("name") if element is not None else ASSUMED_ROOT
            kind = element.get("type", "fixed") if element is not None else "fixed"
            self.joints[name] = Joint(name, None, link, kind)
            self.parent_joint[link] = name

    def up(self, joint: str) -> list[str]:
        """The joints above ``joint``, nearest first (cycles cut)."""
        found, seen = [], {joint}
        current = self.joints[joint].parent
        while current is not None and current in self.parent_joint:
            above = self.parent_joint[current]
            if above in seen:
                break
            seen.add(above)
            found.append(above)
            current = self.joints[above].parent
        return found

    def links_up(self, link: str) -> list[str]:
        """``link`` and the links above it, nearest first."""
        joint = self.parent_joint.get(link)
        if joint is None:
            return [link]
        return [link] + [self.joints[j].parent for j in [joint, *self.up(joint)]
                         if self.joints[j].parent is not None]

    def meeting_link(self, one: str, two: str) -> str | None:
        """The lowest link that has both links at or below it."""
        above_one = self.links_up(one)
        return next((link for link in self.links_up(two) if link in above_one), None)

    def chain(self, base: str, tip: str) -> tuple[set[str], str]:
        """The joints MoveIt puts in ``<chain base_link tip_link>``, and how the chain runs:
        'down' (tip below base), 'reversed' (base below tip), 'cross' (different branches) or
        'same' (base is tip)."""
        if base == tip:
            return set(), "same"
        from_tip = []
        link = tip
        while link != base and link in self.parent_joint:
            joint = self.parent_joint[link]
            if joint in from_tip:
                break
            from_tip.append(joint)
            link = self.joints[joint].parent
        if link == base:
            return set(from_tip), "down"
        from_base, link, index = [], base, 0
        while link in self.parent_joint:
            joint = self.parent_joint[link]
            if joint in from_tip:
                index = from_tip.index(joint) + 1
                break
            if joint in from_base:
                break
            from_base.append(joint)
            link = self.joints[joint].parent
        kind = "reversed" if tip in self.links_up(base) else "cross"
        return (set(from_tip[:index]) | set(from_base) if index else set()), kind


def groups(robot, srdf_root) -> dict[str, Group]:
    """Every SRDF group by name (the first of a repeated name, as MoveIt keeps), with its joints."""
    return robot.memo(groups, lambda: _build(robot, srdf_root))


def tree(robot, srdf_root) -> Tree:
    return robot.memo(tree, lambda: Tree(robot, srdf_root))


def _build(robot, srdf_root) -> dict[str, Group]:
    """Every SRDF group by name, its subgroups' joints included. Subgroups are walked with a
    stack, not by recursion: a chain of groups each naming the next, written in reverse order
    (``g1499`` holds ``g1498``...), is as deep as it is long. A subgroup that is being built
    (a cycle) or is not defined counts as unknown."""
    model = tree(robot, srdf_root)
    elements: dict[str, object] = {}
    for element in srdf_root.iterfind("group"):
        elements.setdefault(element.get("name"), element)
    built: dict[str, Group] = {}

    def member(group: Group, item) -> None:
        if item.tag == "joint":
            found = item.get("name") in model.joints
            group.joints |= {item.get("name")} if found else set()
        elif item.tag == "link":
            found = item.get("name") in model.parent_joint
            group.joints |= {model.parent_joint[item.get("name")]} if found else set()
        elif item.tag == "chain":
            found = {item.get("base_link"), item.get("tip_link")} <= set(robot.links)
            group.joints |= model.chain(item.get("base_link"), item.get("tip_link"))[0] if found else set()
        else:
            return
        group.complete = group.complete and found

    def with_subgroup(group: Group, sub: Group | None) -> None:
        group.joints |= sub.joints if sub is not None else set()
        group.complete = group.complete and sub is not None and sub.complete

    def build(name: str) -> None:
        if name in built or elements.get(name) is None:
            return
        stack = [(Group(name, elements[name]), iter(elements[name]))]  # the groups being built
        building = {name}
        while stack:
            group, items = stack[-1]
            for item in items:
                if item.tag != "group":
                    member(group, item)
                    continue
                sub_name = item.get("name")
                if sub_name in built or elements.get(sub_name) is None or sub_name in building:
                    with_subgroup(group, built.get(sub_name))
                    continue
                stack.append((Group(sub_name, elements[sub_name]), iter(elements[sub_name])))
                building.add(sub_name)
                break
            else:  # every member read: the group is built, and joins the one that named it
                stack.pop()
                building.discard(group.name)
                built[group.name] = group
                if stack:
                    with_subgroup(stack[-1][0], group)

    for name in elements:
        build(name)
    return built


def links_of(model: Tree, group: Group) -> set[str]:
    """The group's links as MoveIt's ``JointModelGroup::hasLinkModel`` knows them."""
    return {model.joints[j].child for j in group.joints}


def serial_problems(model: Tree, group: Group, links) -> list[Shape]:
    """Why a chain solver cannot take ``group`` (empty when it can); ``links`` are the URDF's."""
    problems = []
    for item in group.element.iterfind("chain"):
        base, tip = item.get("base_link"), item.get("tip_link")
        if base not in links or tip not in links:
            continue
        kind = model.chain(base, tip)[1]
        if kind == "reversed":
            problems.append(Shape(kind, item, f"its chain runs backwards: base_link '{base}' is "
                                  f"below tip_link '{tip}'; swap them"))
        elif kind == "cross":
            meet = model.meeting_link(base, tip)
            problems.append(Shape(kind, item, f"its chain from '{base}' to '{tip}' crosses branches "
                                  f"at link '{meet}': the tip does not descend from the base"))
    if problems:
        return problems
    joints = group.joints
    if not any(model.joints[j].type in MOVING + ("floating", "planar") for j in joints):
        return [Shape("empty", group.element, "it has no moving joint")]
    multi = sorted(j for j in joints if model.joints[j].type in ("floating", "planar"))
    if multi:
        problems.append(Shape("multi-dof", group.element, "joint(s) " + ", ".join(
            f"'{j}' ({model.joints[j].type})" for j in multi) + " have more than one variable"))
    nearest: dict[str, str | None] = {}
    for joint in sorted(joints):
        above = model.up(joint)
        owner = next((j for j in above if j in joints), None)
        nearest[joint] = owner
        if owner is not None:
            skipped = [j for j in above[:above.index(owner)] if model.joints[j].type in MOVING]
            if skipped:
                problems.append(Shape("gap", group.element, (
                    f"a gap between links '{model.joints[owner].child}' and "
                    f"'{model.joints[joint].parent}': joint(s) {', '.join(repr(j) for j in reversed(skipped))} "
                    "of the path are not in the group")))
    below: dict[str | None, list[str]] = {}
    for joint, owner in nearest.items():
        below.setdefault(owner, []).append(joint)
    for owner, children in sorted(below.items(), key=lambda item: str(item[0])):
        if len(children) < 2:
            continue
        ends = [model.joints[j].child for j in children]
        meet = model.meeting_link(ends[0], ends[1])
        for other in ends[2:]:
            meet = model.meeting_link(meet, other) if meet else None
        problems.append(Shape("tree", group.element, (
            f"a tree: it branches at link '{meet}' into {', '.join(repr(e) for e in ends)}")))
    return problems
