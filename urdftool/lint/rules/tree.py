"""U1xx: the kinematic tree (names, parents, children, roots, cycles)."""

from __future__ import annotations

from collections import Counter

from urdftool.lint.catalogue import NOT_LOADED, Conditional, Severity, Taken, UrdfdomAlone, rule
from urdftool.errors import available, listed
from urdftool.lint.parts import part
from urdftool.description.xacro_text import dropped_under


def _duplicates(robot, tag: str):
    elements, named = robot.children(tag), robot.names()  # (each name read once per robot)
    names = [named[element] for element in elements]
    counts = Counter(name for name in names if name is not None)  # (two name="" clash too)
    seen: set[str] = set()
    for element, name in zip(elements, names):
        if name is None:
            continue  # a missing name is U103's finding
        if name in seen:
            first = robot.locate(robot.links[name] if tag == "link" else robot.joints[name])
            yield element, _unless_given(robot, tag, name, f"{tag} '{name}' is defined "
                                                           f"{counts[name]} times (first at {first})")
        seen.add(name)


def _unless_given(robot, tag: str, name: str, message: str) -> str:
    """``message`` of a clash of ``name`` (a link's or a joint's), a warning saying so when
    only placeholder xacro arguments make it (:func:`~urdftool.description.runtime.
    placeholder_clashes`: both arms of a dual arm named from ``prefix_1`` and ``prefix_2``,
    each ``default=""``): it holds for a plain ``xacro FILE``, not for a build giving them."""
    from urdftool.description.runtime import placeholder_clashes

    clash = placeholder_clashes(robot)
    if clash is None or name not in (clash.links if tag == "link" else clash.joints):
        return message
    args = clash.args
    listed = f"argument {args[0]} keeps its empty default" if len(args) == 1 else \
        f"arguments {', '.join(args[:-1])} and {args[-1]} keep their empty defaults"
    return Conditional(message + f", only while the xacro {listed}: a build giving "
                       f"{'it a value' if len(args) == 1 else 'each a value of its own'} "
                       f"({' '.join(f'{arg}:=...' for arg in args)}) names them apart")


@rule("U101", "duplicate-link", Severity.ERROR)
def duplicate_link(robot):
    """Two links have the same name.

    urdfdom refuses the file; tools that tolerate it keep one of the two at random.

    A **warning** naming the arguments when only xacro arguments declared with an empty
    default make the clash (a dual arm whose arms are named from ``prefix_1`` and
    ``prefix_2``, both ``default=""``): the robot built again with each given a value of its
    own names them apart, and the launch file that gives them (abb_ros2_control's, from a YAML
    file read at launch) builds that. An error when a launch file here builds it as checked.

    Bad: ``<link name="arm"/> ... <link name="arm"/>``
    Good: ``<link name="upper_arm"/> ... <link name="forearm"/>``
    """
    yield from _duplicates(robot, "link")


@rule("U102", "duplicate-joint", Severity.ERROR)
def duplicate_joint(robot):
    """Two joints have the same name.

    Joint names key /joint_states, controllers and transmissions: a duplicate makes them ambiguous.
    A warning when only xacro arguments with empty defaults make the clash (as U101).

    Bad: two ``<joint name="wheel_joint">`` elements
    Good: ``left_wheel_joint`` and ``right_wheel_joint``
    """
    yield from _duplicates(robot, "joint")


@rule("U103", "missing-name", Severity.ERROR)
def missing_name(robot):
    """A link or joint has no ``name`` attribute (or an empty one).

    No joint, controller or transmission can name it. What urdfdom (check_urdf,
    robot_state_publisher) makes of it depends on the shape, and the commands that pose a robot
    refuse it only where urdfdom does: it refuses a joint without the attribute and takes a
    joint's ``name=""`` (two of them clash: "joint '' is not unique"); it reads a link without
    the attribute as one named ``""``, which no joint can attach to (a joint's ``link=""`` is
    "missing a parent and/or child link specification"): the only link of a robot, it is the
    root, and urdfdom takes it; beside other links it is a second root, refused.

    Bad: ``<link><visual>...</visual></link>``, ``<joint name="" ...>``
    Good: ``<link name="base_link">...</link>``
    """
    names = robot.names()
    links = robot.children("link")
    joints = robot.children("joint")
    empty_joints = sum(1 for joint in joints if names[joint] == "")  # (names read once)
    for tag, elements in (("link", links), ("joint", joints)):
        for element in elements:
            if names[element]:
                continue
            missing = names[element] is None
            message = f"<{tag}> has no name attribute" if missing else \
                f"<{tag}> has an empty name (name=\"\")"
            taken = len(links) == 1 if tag == "link" else not missing and empty_joints == 1
            yield element, Taken(message) if taken else message


@rule("U104", "joint-missing-endpoint", Severity.ERROR)
def joint_missing_endpoint(robot):
    """A joint has no ``<parent link=...>`` or ``<child link=...>``.

    Bad: ``<joint name="j" type="fixed"><parent link="a"/></joint>``
    Good: ``<joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>``
    """
    for joint, ends in robot.ends().items():
        for side in ("parent", "child"):
            element, link = ends[side]
            if element is None:
                dropped = dropped_under(robot, joint, side)
                yield joint, (f"joint '{joint.get('name')}' has no <{side} link=\"...\"/>"
                              + (f": {dropped} (--arg NAME=VALUE checks another build)"
                                 if dropped else ""))
            elif not link:
                yield element, (f"joint '{joint.get('name')}': <{side}> has no link attribute"
                                if element.get("link") is None else
                                f"joint '{joint.get('name')}': <{side}> names no link "
                                "(link=\"\")")


# The link Drake's parser reads as its world frame (a joint's parent), which urdfdom refuses
DRAKE_WORLD = "world"


@rule("U105", "unknown-link", Severity.ERROR)
def unknown_link(robot):
    """A joint names a parent or child link that does not exist.

    A robot with no root link of its own (every link it writes is a joint's child, and its
    joints hang on links it does not write, Gazebo's ``world`` aside) is a part of a robot
    defined elsewhere, as a macro may build it (Baxter's example end effector, mounted on the
    arm's ``left_hand``): the links it hangs on are said in a note, right only inside the
    robot that includes it (the folder walk skips such a file when its text shows it). So are
    both ends of the joints of a part with no link at all (a mount file's joint between links
    other files write).

    A **warning** naming the condition for a parent link ``world`` in a file Drake reads, as
    its files say and nothing says ROS runs it (``xmlns:drake``): Drake's world frame
    (RobotLocomotion/models' PR2, written for Drake); still urdfdom's refusal, which the
    commands that pose a robot refuse.

    Bad: ``<parent link="bse_link"/>`` when the link is ``base_link``
    Good: ``<parent link="base_link"/>``
    """
    ends = robot.ends()
    found = part(robot)
    mounts = {"parent": found.mounts, "child": found.attaches} if found is not None else {}
    for joint, ends_of in ends.items():
        for side in ("parent", "child"):
            element, link = ends_of[side]
            if not link or link in robot.links:
                continue
            message = (f"joint '{joint.get('name')}' names {side} link '{link}', which does not "
                       "exist; " + available('links', link, robot.links))
            if link in mounts.get(side, ()):
                verb = "hangs on" if side == "parent" else "attaches"
                message = Conditional(
                    f"joint '{joint.get('name')}' {verb} '{link}', which this robot does not "
                    "write, and it has no root link of its own: a part of a robot defined "
                    "elsewhere, right only inside the robot that includes it (alone, urdfdom "
                    "refuses it)", Severity.INFO)
            elif side == "parent" and link == DRAKE_WORLD:
                message = UrdfdomAlone(message, {"drake"})
            yield element, message


@rule("U106", "no-links", Severity.ERROR)
def no_links(robot):
    """The robot has no ``<link>`` at all.

    A robot with no link and no joint that holds ``<gazebo>``, ``<transmission>``,
    ``<ros2_control>`` or ``<webots>`` blocks (a macro call writing only the Gazebo plugins of a
    base that another file writes: Care-O-bot's ``raw_mini``) is a part of a robot defined
    elsewhere: this and every name its blocks give that the robot does not write are notes,
    right only inside the robot that includes it (:mod:`urdftool.lint.parts`). A robot with
    nothing at all in it (a macro call that wrote nothing) is an error.

    Bad: ``<robot name="r"/>``
    Good: ``<robot name="r"><link name="base_link"/></robot>``
    """
    if not robot.children("link"):
        yield robot.root, "robot has no <link> elements; a robot needs at least one link"


def parent_map(robot) -> dict[str, list]:
    """Child link name -> joints that name it as child (only links that exist); built once per
    robot (several rules ask)."""
    return robot.memo(parent_map, lambda: _parent_map(robot))


def _parent_map(robot) -> dict[str, list]:
    parents: dict[str, list] = {}
    for joint, ends in robot.ends().items():
        _, child = ends["child"]
        _, parent = ends["parent"]
        if child in robot.links and parent in robot.links:
            parents.setdefault(child, []).append(joint)
    return parents


@rule("U107", "multiple-parents", Severity.ERROR)
def multiple_parents(robot):
    """A link is the child of more than one joint.

    URDF describes a tree: each link has at most one parent joint. urdfdom takes the robot and
    keeps one of them, the joint whose name sorts last (it reads joints by name), as the link's
    parent: the others' pose of it is lost, by the joints' names alone. The commands that pose
    a robot refuse it (Pinocchio hangs the link under that joint or refuses the robot). Closed
    chains need a different format (SDF) or a mimic joint. A warning when the link's name
    clashes only because xacro arguments keep their empty defaults (as U101).

    Bad: joints ``a_to_c`` and ``b_to_c`` both with ``<child link="c"/>``
    Good: one of them attaches a new link instead.
    """
    for child, joints in parent_map(robot).items():
        if len(joints) > 1:
            names = ", ".join(f"'{j.get('name')}'" for j in joints)
            kept = max(j.get("name") or "" for j in joints)  # (urdfdom's map of joints by name)
            for joint in joints[1:]:
                yield robot.ends()[joint]["child"][0], _unless_given(
                    robot, "link", child, f"link '{child}' has {len(joints)} parent joints "
                    f"({names}): urdfdom keeps '{kept}' as its parent joint (the name that sorts "
                    "last) and loses the others' pose of it, and the commands that pose a robot "
                    "(fk, render...) refuse it; give each joint a child link of its own")


def roots(robot) -> list[str]:
    """Links that are nobody's child, in document order."""
    parents = parent_map(robot)
    return [name for name in robot.links if name not in parents]


@rule("U108", "multiple-roots", Severity.ERROR)
def multiple_roots(robot):
    """More than one link has no parent: the robot falls apart into several trees.

    Usually a joint is missing, or a joint's parent or child link is misspelt.

    Bad: links ``base_link`` and ``camera_link`` with no joint between them
    Good: a fixed joint from ``base_link`` to ``camera_link``
    """
    found = roots(robot)
    if len(found) > 1 and _all_joints_wired(robot):
        named, names = listed(found), robot.names()
        for name in found[1:]:
            if names[robot.links[name]] is None:
                continue  # a link without a name (urdfdom's '', a second root): U103 says it
            yield robot.links[name], (f"link '{name}' has no parent joint: the robot has "
                                      f"{len(found)} roots ({named}), and urdfdom refuses a "
                                      f"robot of more than one: {NOT_LOADED}; connect them "
                                      "with joints")


def _all_joints_wired(robot) -> bool:
    """Whether every joint names an existing parent and child (else U104/U105 explain roots)."""
    return all(ends[side][1] in robot.links
               for ends in robot.ends().values() for side in ("parent", "child"))


@rule("U109", "kinematic-cycle", Severity.ERROR)
def kinematic_cycle(robot):
    """The joints form a loop, so the tree has no root or a link is its own ancestor.

    A loop below the root (``r -> a -> b -> a``: ``a`` has a second parent joint, U107, and is
    its own ancestor through it) is one too: urdfdom's check_urdf never returns on it (its tree
    walk loops) and robot_state_publisher never starts.

    A loop beside the tree (no link of it reached from a link without a parent joint, while
    one such link exists) urdfdom takes: it builds the tree from that root and drops the
    loop's links silently (check_urdf lists the tree without them); the commands that pose a
    robot take it too, and pose the tree, naming the links left out (``inertia`` lists the
    links they pose).

    Bad: ``a -> b`` and ``b -> a``
    Good: a tree: each link reached from the root by exactly one path
    """
    for joint, message, cycle in _cycles(robot):
        yield joint, Taken(message) if _beside_the_tree(robot, cycle) else message


def _beside_the_tree(robot, cycle) -> bool:
    """Whether no link of ``cycle`` is reached, down every joint, from a link without a parent
    joint, and one such link (urdfdom's root) exists."""
    reached = robot.memo(_beside_the_tree, lambda: _reached_from_roots(robot))
    return bool(reached) and reached.isdisjoint(cycle)


def _reached_from_roots(robot) -> set[str]:
    """The links reached down every joint from the links without a parent joint (empty when
    there is none): once per robot, whatever the number of loops asking."""
    parents, children = parent_map(robot), _child_map(robot)
    roots = [link for link in robot.links if link not in parents]
    reached, stack = set(roots), list(roots)
    while stack:
        for _, child in children.get(stack.pop(), ()):
            if child not in reached:
                reached.add(child)
                stack.append(child)
    return reached


def _child_map(robot) -> dict[str, list]:
    """Parent link name -> (joint, child link name) of each joint between links that exist,
    in document order; built once per robot (the two walks down the joints ask)."""
    def build():
        children: dict[str, list] = {}
        for joint, ends in robot.ends().items():
            parent, child = ends["parent"][1], ends["child"][1]
            if parent in robot.links and child in robot.links:
                children.setdefault(parent, []).append((joint, child))
        return children

    return robot.memo(_child_map, build)


def _cycles(robot):
    """(joint, message, links) for each loop of joints."""
    parents, ends = parent_map(robot), robot.ends()
    reported: set[str] = set()
    done: set[str] = set()  # links whose way up is walked: each link is walked once, O(n)
    for start in robot.links:
        path, position, link = [], {}, start
        while link in parents and link not in position and link not in done:
            position[link] = len(path)
            path.append(link)
            link = ends[parents[link][0]]["parent"][1]
        if link in position and link not in reported:
            cycle = path[position[link]:]
            reported.update(cycle)
            joint = parents[link][0]
            yield joint, "joints form a cycle through links " + " -> ".join(
                [*reversed(cycle), cycle[-1]]), cycle
        done.update(path)
    if any(len(joints) > 1 for joints in parents.values()):
        # the walk above goes up through each link's first parent joint only: a loop closed
        # by a second parent joint is found going down every joint
        yield from _loops_through_second_parents(robot, reported)


def _loops_through_second_parents(robot, reported: set[str]):
    """(joint, message, links) for each loop of joints that a walk down every joint finds and that
    shares no link with a loop in ``reported``: depth first, iteratively (10,000-link
    chains), each link entered once; a joint leading back to a link on the way down closes a
    loop, said at that joint as ``a -> b -> a`` (parent to child)."""
    children = _child_map(robot)
    entered: set[str] = set()
    for start in robot.links:
        if start in entered:
            continue
        entered.add(start)
        way, on_way = [start], {start: 0}
        stack = [iter(children.get(start, ()))]
        while stack:
            step = next(stack[-1], None)
            if step is None:
                stack.pop()
                del on_way[way.pop()]
                continue
            joint, child = step
            if child in on_way:
                loop = way[on_way[child]:]
                if reported.isdisjoint(loop):
                    reported.update(loop)
                    yield joint, "joints form a cycle through links " + " -> ".join(
                        [*loop, child]), loop
            elif child not in entered:
                entered.add(child)
                on_way[child] = len(way)
                way.append(child)
                stack.append(iter(children.get(child, ())))


@rule("U110", "self-joint", Severity.ERROR)
def self_joint(robot):
    """A joint has the same link as parent and child.

    Bad: ``<parent link="a"/><child link="a"/>``
    Good: two different links
    """
    for joint, ends in robot.ends().items():
        _, parent = ends["parent"]
        _, child = ends["child"]
        if parent and parent == child:
            yield joint, f"joint '{joint.get('name')}' connects link '{parent}' to itself"
