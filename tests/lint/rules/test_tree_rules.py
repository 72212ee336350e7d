"""The tree rules' cost: each link's way to the root is walked once (U109), not once per link
below it, and what several rules derive (the parent map) is built once per robot."""

from __future__ import annotations

from conftest import synthetic_robot
from urdftool.description.load import load
from urdftool.lint.rules import tree


class _CountingParents(dict):
    """A parent map that counts how often a link's parents are looked up."""

    lookups = 0

    def __contains__(self, key):
        type(self).lookups += 1
        return super().__contains__(key)

    def __getitem__(self, key):
        type(self).lookups += 1
        return super().__getitem__(key)


def test_kinematic_cycle_walks_each_link_once(tmp_path, monkeypatch):
    robot = load(str(synthetic_robot(tmp_path, 2000)))
    parents = _CountingParents(tree.parent_map(robot))
    monkeypatch.setattr(tree, "parent_map", lambda _: parents)
    _CountingParents.lookups = 0
    assert list(tree.kinematic_cycle(robot)) == []
    # two lookups per link walked and one to stop per start: O(n), where walking every link
    # to the root was n^2 / 2 = 2,000,000
    assert _CountingParents.lookups <= 3 * 2000 + 10


def test_a_cycle_is_still_found_after_the_acyclic_links(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_text('<robot name="r"><link name="base"/><link name="a"/><link name="b"/>'
                    '<link name="c"/><joint name="j0" type="fixed"><parent link="base"/>'
                    '<child link="c"/></joint><joint name="j1" type="fixed"><parent link="a"/>'
                    '<child link="b"/></joint><joint name="j2" type="fixed"><parent link="b"/>'
                    '<child link="a"/></joint></robot>')
    robot = load(str(path))
    [(joint, message)] = tree.kinematic_cycle(robot)
    assert message == "joints form a cycle through links b -> a -> b"


def test_the_parent_map_is_built_once_per_robot(tmp_path, monkeypatch):
    robot = load(str(synthetic_robot(tmp_path, 10)))
    built = []
    original = tree._parent_map
    monkeypatch.setattr(tree, "_parent_map", lambda r: built.append(r) or original(r))
    for check in (tree.multiple_parents, tree.multiple_roots, tree.kinematic_cycle):
        list(check(robot))
    assert len(built) == 1


def test_multiple_roots_name_a_dozen_roots_not_all_at_each(tmp_path):
    """U108 is said at each root but the first, and each message named every root: 2,500
    roots made 54 MB of JSON (10,000: 40 s to write), the output growing as the square of the
    robot. Each names twelve and how many (errors.listed, as ``available`` lists names)."""
    path = tmp_path / "r.urdf"
    path.write_text('<robot name="r">' + "".join(f'<link name="l{i}"/>' for i in range(3000))
                    + "</robot>")
    messages = [message for _, message in tree.multiple_roots(load(str(path)))]
    assert len(messages) == 2999 and max(map(len, messages)) < 400
    assert "('l0', 'l1', 'l2', 'l3', 'l4', 'l5', 'l6', 'l7', 'l8', 'l9', 'l10', 'l11', ... " \
        "(3000 in all))" in messages[0]
    path.write_text('<robot name="r"><link name="a"/><link name="b"/></robot>')
    [(_, message)] = tree.multiple_roots(load(str(path)))
    assert message == "link 'b' has no parent joint: the robot has 2 roots ('a', 'b'), and " \
        "urdfdom refuses a robot of more than one: robot_state_publisher, RViz, MoveIt and " \
        "Gazebo (sdformat) do not load it; connect them with joints"


def _chain_with_loop(tmp_path, links: int, back_to: int):
    """``r -> l0 -> ... -> l{links-1}``, and a joint from the last link back to ``l{back_to}``:
    a loop below the root, closed by a second parent joint of ``l{back_to}``."""
    names = ["r", *(f"l{i}" for i in range(links))]
    joints = [(f"j{i}", names[i], names[i + 1]) for i in range(links)]
    joints.append(("back", names[-1], f"l{back_to}"))
    path = tmp_path / "r.urdf"
    path.write_text('<robot name="r">' + "".join(f'<link name="{n}"/>' for n in names)
                    + "".join(f'<joint name="{j}" type="fixed"><parent link="{p}"/>'
                              f'<child link="{c}"/></joint>' for j, p, c in joints)
                    + "</robot>")
    return load(str(path))


def test_a_loop_below_the_root_is_a_cycle(tmp_path):
    """The walk up each link's first parent joint missed a loop closed by a second parent
    joint (``r -> a -> b -> a``): U107 alone, while urdfdom's check_urdf never returns on it.
    Loops of one link (a self-joint below the root), two, three and eight."""
    for links, back_to, loop in ((1, 0, "l0 -> l0"), (2, 0, "l0 -> l1 -> l0"),
                                 (3, 0, "l0 -> l1 -> l2 -> l0"), (3, 1, "l1 -> l2 -> l1"),
                                 (8, 0, " -> ".join(f"l{i}" for i in (*range(8), 0)))):
        robot = _chain_with_loop(tmp_path, links, back_to)
        [(joint, message)] = tree.kinematic_cycle(robot)
        assert message == f"joints form a cycle through links {loop}"
        assert joint.get("name") == "back"


def test_a_second_parent_without_a_loop_is_no_cycle(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_text('<robot name="r"><link name="r"/><link name="a"/><link name="b"/>'
                    + "".join(f'<joint name="{j}" type="fixed"><parent link="{p}"/>'
                              f'<child link="{c}"/></joint>'
                              for j, p, c in (("j0", "r", "a"), ("j1", "r", "b"),
                                              ("j2", "a", "b")))
                    + "</robot>")
    assert list(tree.kinematic_cycle(load(str(path)))) == []


def test_a_loop_at_the_end_of_a_long_chain_is_found_without_recursion(tmp_path):
    robot = _chain_with_loop(tmp_path, 5000, 10)
    [(joint, message)] = tree.kinematic_cycle(robot)
    assert message.startswith("joints form a cycle through links l10 -> l11 -> ")
    assert message.endswith("-> l4999 -> l10")


def test_an_empty_name_is_said_as_empty_not_as_missing(tmp_path):
    """``name=""`` and ``link=""`` were said as attributes missing; urdfdom reads an absent name
    and an empty one differently (it refuses the first, takes the second for a joint)."""
    path = tmp_path / "r.urdf"
    path.write_text('<robot name="r"><link name="r"/><link name=""/><link/>'
                    '<joint name="" type="fixed"><parent link="r"/><child link=""/></joint>'
                    '<joint name="j" type="fixed"><parent link="r"/><child/></joint></robot>')
    robot = load(str(path))
    assert [message for _, message in tree.missing_name(robot)] == [
        '<link> has an empty name (name="")', "<link> has no name attribute",
        '<joint> has an empty name (name="")']
    assert [message for _, message in tree.joint_missing_endpoint(robot)] == [
        """joint '': <child> names no link (link="")""", "joint 'j': <child> has no link attribute"]


def _robot(tmp_path, body: str):
    path = tmp_path / "r.urdf"
    path.write_text(f'<robot name="r">{body}</robot>')
    return load(str(path))


def _taken(rule, robot) -> list[tuple[str, bool]]:
    """Each finding's message and whether its rule says urdfdom takes it."""
    from urdftool.lint.catalogue import Taken

    return [(str(message), isinstance(message, Taken)) for _, message in rule(robot)]


def test_a_joint_s_empty_name_is_taken_by_urdfdom_and_a_missing_one_is_not(tmp_path):
    """check_urdf takes a joint's name="" ("child(1): a") and refuses a joint without the
    attribute ("unnamed joint found"), in one robot too: the fact is per finding."""
    robot = _robot(tmp_path, '<link name="r"/><link name="a"/><link name="b"/>'
                   '<joint name="" type="fixed"><parent link="r"/><child link="a"/></joint>'
                   '<joint type="fixed"><parent link="r"/><child link="b"/></joint>')
    assert _taken(tree.missing_name, robot) == [('<joint> has an empty name (name="")', True),
                                                ("<joint> has no name attribute", False)]


def test_two_joints_named_empty_are_not_taken(tmp_path):
    """check_urdf: "joint '' is not unique"; U102 counts them (it said "defined 0 times")."""
    robot = _robot(tmp_path, '<link name="r"/><link name="a"/><link name="b"/>'
                   '<joint name="" type="fixed"><parent link="r"/><child link="a"/></joint>'
                   '<joint name="" type="fixed"><parent link="r"/><child link="b"/></joint>')
    assert [taken for _, taken in _taken(tree.missing_name, robot)] == [False, False]
    assert [message for _, message in tree.duplicate_joint(robot)] == [
        f"joint '' is defined 2 times (first at {robot.path}:1)"]


def test_an_only_link_without_a_name_is_taken_and_one_beside_others_is_not(tmp_path):
    """urdfdom reads a link without the attribute as one named '' (check_urdf logs "No name
    given for the link." and parses it): the only link is its root; beside another it is a
    second root ("Two root links found: [] and [r]")."""
    for body in ('<link name=""/>', "<link/>"):
        assert [taken for _, taken in _taken(tree.missing_name, _robot(tmp_path, body))] == [True]
        assert [taken for _, taken in _taken(tree.missing_name, _robot(
            tmp_path, '<link name="r"/>' + body))] == [False]


def _fixed(name: str, parent: str, child: str) -> str:
    return f'<joint name="{name}" type="fixed"><parent link="{parent}"/><child link="{child}"/></joint>'


def test_a_loop_beside_the_tree_is_taken_and_one_below_or_through_the_root_is_not(tmp_path):
    """check_urdf takes a loop no link of which hangs below the root (it drops its links),
    hangs on one below the root and refuses one through every root ("No root link found")."""
    beside = _robot(tmp_path, '<link name="r"/><link name="x"/><link name="a"/><link name="b"/>'
                    + _fixed("j0", "r", "x") + _fixed("j1", "a", "b") + _fixed("j2", "b", "a"))
    assert _taken(tree.kinematic_cycle, beside) == [
        ("joints form a cycle through links b -> a -> b", True)]
    below = _robot(tmp_path, '<link name="r"/><link name="a"/><link name="b"/>'
                   + _fixed("j0", "r", "a") + _fixed("j1", "a", "b") + _fixed("j2", "b", "a"))
    assert [taken for _, taken in _taken(tree.kinematic_cycle, below)] == [False]
    through = _robot(tmp_path, '<link name="r"/><link name="a"/>'
                     + _fixed("j0", "r", "a") + _fixed("j1", "a", "r"))
    assert [taken for _, taken in _taken(tree.kinematic_cycle, through)] == [False]


def test_a_link_with_two_parents_says_what_becomes_of_it(tmp_path):
    """U107 said only "link 'c' has 2 parent joints", where its siblings (U108, U109) say what
    follows: urdfdom takes the robot, keeping as the link's parent the joint whose name sorts
    last (its joints are a map by name), and the commands that pose a robot refuse it
    (engine.POSING_REFUSES: no one pose of the link)."""
    path = tmp_path / "r.urdf"
    path.write_text('<robot name="r"><link name="r"/><link name="a"/><link name="b"/>' + "".join(
        f'<joint name="{j}" type="fixed"><parent link="{p}"/><child link="{c}"/></joint>'
        for j, p, c in (("j0", "r", "a"), ("z1", "r", "b"), ("a2", "a", "b"))) + "</robot>")
    [(_, message)] = tree.multiple_parents(load(str(path)))
    assert message.startswith("link 'b' has 2 parent joints ('z1', 'a2')")
    assert "urdfdom keeps 'z1' as its parent joint (the name that sorts last)" in message
    assert "the commands that pose a robot (fk, render...) refuse it" in message
