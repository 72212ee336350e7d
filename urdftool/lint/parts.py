"""Whether a checked robot is a part of a robot defined elsewhere: decided once per robot, for
every rule, whether the folder walk found the file or the user named it.

The folder walk skips a file whose text shows it is a part (:mod:`urdftool.lint.targets`: an
``X.gazebo.xacro`` holding only ``<gazebo>`` blocks, a ``.urdf`` whose joints hang on links it
does not write). When only the expansion shows it (a top-level macro call builds the part), the
file is checked, and what it cannot be right about alone (a name it does not write, its own
name, links of its own) is a note stating the condition:

- **hangs**: links of its own, each a joint's child, and joints hanging on links it does not
  write (Gazebo's ``world`` aside: a robot fixed to the world is a robot): Baxter's example end
  effector, mounted on the arm's ``left_hand``. U105 says so on the joints' ``<parent>``
  (:func:`~urdftool.lint.rules.tree.unknown_link`), and a name of its own is not needed.
- **joints**: no link at all, only joints between links it does not write (a mount file
  joining the robot's ``front_mount`` to a sensor another file writes: jackal's
  ``custom_example.urdf``); judged as an **extensions** part is, and U105 notes both ends.
- **extensions**: no link and no joint at all, only :data:`EXTENSIONS` blocks (and materials):
  Care-O-bot's ``raw_mini`` base, whose ``base.urdf.xacro`` calls only the macro writing its
  Gazebo plugins; or only ``<material>`` definitions, a library of colours named ``.urdf``
  (TurtleBot3's ``common_properties.urdf``, whose xacro include is commented out). Every rule
  of :data:`ABOUT_THE_ROBOT` (a name compared with links and joints it does not write, links
  or a simulator plugin it lacks) is a note.

Whether a robot has a root link of its own is decided once (:func:`rootless`), for the
expansion here and for a file's text in the folder walk.

A robot with nothing at all in it (a macro call that wrote nothing) is not a part: U106 stays
an error (docs/certainty.md); nor is one a launch file of its repository runs as the robot,
unconditionally and as checked: whatever it lacks, it lacks where it runs.
"""

from __future__ import annotations


from urdftool.diagnostics import Finding, Severity
from urdftool.description.xacro_text import PART_BLOCKS
from urdftool.records import Frozen, replace

# What a fragment of a robot defined elsewhere holds besides definitions (X.gazebo.xacro)
EXTENSIONS = PART_BLOCKS
# Top-level elements an expanded part may hold besides EXTENSIONS
_DEFINITIONS = frozenset({"material"})
# The rules whose findings on a part with no link and no joint of its own hold only for the robot
# alone, not inside the robot that includes it: the robot's name, its links, and every name of a
# link or joint (or the Gazebo plugin loading its hardware) that the includer writes.
# tests/lint/test_parts.py holds every rule that compares a name with the robot's links or
# joints to this set.
ABOUT_THE_ROBOT = frozenset({
    "U011",  # robot-name-missing: the includer's <robot> has the name
    "U106",  # no-links
    "U501", "U511",  # a transmission's or a ros2_control block's joint
    "U519",  # ros2_control hardware of a simulator and no Gazebo plugin loading it
    "U602", "U603", "U604",  # a controller's joints
    "U611", "U612", "U615", "U616",  # Gazebo references, diff drive joints and frames, sensors
    "U702",  # the joint spec table's joints
    "U802", "U803", "U804", "U809", "U815",  # MoveIt's robot name, joints and links
})
# A name of its own is the includer's, for either kind
_HANGS = frozenset({"U011"})


class Part(Frozen):
    """A robot checked alone that is a part of one defined elsewhere.

    kind: 'hangs', 'joints' or 'extensions' (see the module)
    mounts: the links its joints hang on, which it does not write (empty for 'extensions')
    condition: what makes it a part, as a finding's message says it
    attaches: the links its joints attach to the mounts, which it does not write either
        ('joints'; empty otherwise)
    """

    kind: str
    mounts: frozenset[str]
    condition: str
    attaches: frozenset[str]

    __slots__ = ("kind", "mounts", "condition", "attaches")

    def __init__(self, kind: str, mounts: frozenset[str], condition: str,
                 attaches: frozenset[str] = frozenset()) -> None:
        set_field = object.__setattr__
        set_field(self, "kind", kind)
        set_field(self, "mounts", mounts)
        set_field(self, "condition", condition)
        set_field(self, "attaches", attaches)

    def covers(self, code: str) -> bool:
        """Whether a finding of rule ``code`` on this part is right only inside the robot that
        includes it (U105's joints are judged by the rule itself, one side at a time)."""
        return code in (_HANGS if self.kind == "hangs" else ABOUT_THE_ROBOT)

    def noted(self, finding: Finding) -> Finding:
        """``finding`` as the note it is on this part: its message after the condition."""
        return replace(finding, severity=Severity.INFO,
                       message=f"{self.condition}, right only inside the robot that includes it: "
                               f"{finding.message}")


def part(robot) -> Part | None:
    """The :class:`Part` ``robot`` is, or None for a robot of its own (computed once): what a
    launch file of its repository gives as the robot description, unconditionally and with the
    xacro arguments it was checked with, is a robot of its own, however little it writes (its
    errors are certain where it runs)."""
    return robot.memo(part, lambda: _unless_run_as_checked(robot, _part(robot)))


def _unless_run_as_checked(robot, found: Part | None) -> Part | None:
    """``found``, unless a launch configuration describes the robot as checked (asked of a
    part only: reading the launch files costs more than judging the robot)."""
    if found is None:
        return None
    from urdftool.description.runtime import runtime

    run = any(relation == "as checked" for _, relation in runtime(robot).configurations)
    return None if run else found


def _part(robot) -> Part | None:
    ends = robot.ends()
    if not robot.links and not ends:
        tags = {tag for tag in robot.grouped(robot.root)}
        blocks = sorted(tags & EXTENSIONS)
        if blocks and tags <= EXTENSIONS | _DEFINITIONS:
            said = ", ".join(f"<{tag}>" for tag in blocks[:-1])
            said = f"{said} and <{blocks[-1]}>" if said else f"<{blocks[-1]}>"
            return Part("extensions", frozenset(),
                        f"a part of a robot defined elsewhere (no link of its own, only "
                        f"{said} blocks)")
        if tags == _DEFINITIONS and any(  # a library of colours, named .urdf (TurtleBot3's)
                robot.child(m, "color") is not None or robot.child(m, "texture") is not None
                for m in robot.children("material")):
            return Part("extensions", frozenset(),
                        f"{PART} (no link of its own, only <material> definitions: a library "
                        "of colours for xacro to include)")
        return None
    return rootless(robot.links, [e["parent"][1] for e in ends.values()],
                    [e["child"][1] for e in ends.values()])


def rootless(links, parents, children) -> Part | None:
    """The :class:`Part` a robot is when it has no root link of its own, else None: the one
    decision, whether the links and joints are read from the expansion (:func:`part`) or from
    a file's text (the folder walk's :func:`urdftool.lint.targets._root_elsewhere`).

    links: the names of the links it writes; parents, children: the links its joints name on
    each side (None or "" for a side not given). It has no root of its own when every link it
    writes is a joint's child and some joint names a link it does not write, Gazebo's
    ``world`` aside (a robot fixed to the world is a robot; a misspelt parent leaves the real
    root a root). With no link at all, its joints join links it does not write (a mount
    file's joint between the robot's ``front_mount`` and a sensor another file writes): kind
    'joints', judged as the 'extensions' kind is, since every name it gives is the includer's.
    URDF asks a robot for links and one root link (urdfdom refuses it alone either way)."""
    links = set(links)
    parents, children = {p for p in parents if p}, {c for c in children if c}
    if not (parents | children) - links - {"world"} or not links <= children:
        return None
    if not links:
        return Part("joints", frozenset(parents), (
            f"{PART} (no link of its own, only joints between links it does not write)"),
            frozenset(children))
    return Part("hangs", frozenset(parents - links), ROOT_ELSEWHERE)


PART = "a part of a robot defined elsewhere"  # how every condition of rootless() starts
ROOT_ELSEWHERE = (f"{PART} (its joints hang on links it does not write, and it has no root "
                  "link of its own)")


def judged(robot, findings: list[Finding]) -> list[Finding]:
    """``findings`` of rules on ``robot``, those a part cannot be right about alone as notes."""
    found = part(robot)
    if found is None:
        return findings
    return [found.noted(f) if f.severity != Severity.INFO and found.covers(f.code) else f
            for f in findings]
