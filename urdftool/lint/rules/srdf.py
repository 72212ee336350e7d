"""U80x: the SRDF (MoveIt semantic description) against the URDF.

MoveIt reads the SRDF with the robot a launch file builds: when the robot's launch files give
MoveIt this SRDF only with the robot built otherwise (other xacro arguments: a gripper, a
prefix; or environment variables the robot reads), a mismatch with the robot as checked is a
note naming them (docs/certainty.md): the MoveIt configuration is another build's. When they
give it both only with the defaults of the launch arguments naming the robot's or the SRDF's
package (``FindPackageShare(LaunchConfiguration("description_package"))``), a warning saying
so.
"""

from __future__ import annotations

import functools

from urdftool.description.companions import companions
from urdftool.description.runtime import moveit_with
from urdftool.lint.catalogue import Conditional, Severity, rule
from urdftool.numbers import number
from urdftool.errors import available, listed
from urdftool.description.urdf import LIMITED
from urdftool.description.values import limit_range, parse_numbers
from urdftool.description.xml import attribute
from urdftool.diagnostics import line_end, line_start

LIMIT_TOLERANCE = 1e-6


def as_moveit_runs(check):
    """A rule on MoveIt's files whose findings are :class:`Conditional` when the robot's launch
    files give MoveIt its SRDF only with the robot built from other xacro arguments."""
    @functools.wraps(check)
    def judged(robot):
        srdf = companions(robot).srdf
        state, why = moveit_with(robot, srdf.path) if srdf is not None else ("unknown", "")
        for where, message, *fix in check(robot):
            # (a finding the rule itself lowers keeps its severity, said with the condition)
            kept = message.severity if isinstance(message, Conditional) else None
            # (+, not an f-string: a Said message's repeated parts come along)
            if state == "conditional":  # the MoveIt configuration of another build: a note
                message = Conditional(f"if MoveIt runs with the robot as checked ({why}): "
                                      + message, Severity.INFO)
            elif state == "certain":
                message = f"{why}: " + message if kept is None else \
                    Conditional(f"{why}: " + message, kept)
            elif state == "by default":  # MoveIt's for the defaults of the launch arguments
                message = Conditional(f"{why}: " + message, kept or Severity.WARNING)
            yield (where, message, *fix)
    return judged


def _srdf(robot):
    srdf = companions(robot).srdf
    return srdf if srdf is not None and srdf.root is not None else None


def _elements(srdf, *paths):
    for path in paths:
        yield from srdf.root.iterfind(path)


def _references(srdf, attributes):
    """(element, attribute, name) for each ``(path, attribute)`` the SRDF sets."""
    for path, attribute in attributes:
        for element in srdf.root.iterfind(path):
            name = element.get(attribute)
            if name is not None:
                yield element, attribute, name


@rule("U801", "malformed-srdf", Severity.ERROR)
def malformed_srdf(robot):
    """The SRDF is not well-formed XML, has no ``<robot>`` root, or cannot be read.

    MoveIt refuses to start with it.

    A **warning** when srdfdom reads it all the same: a ``--`` inside a comment
    (``<!-- ------ -->``), which the XML standard forbids, but srdfdom's TinyXML2 ends the
    comment at the first ``-->``. MoveIt then reads it when its launch file loads the SRDF as
    text (ROS 1's ``textfile=``), not through xacro (MoveItConfigsBuilder's way), which
    refuses it. And an entity the SRDF declares and uses (``<!ENTITY g "arm">``, ``<group
    name="&g;">``): TinyXML2 expands none, so MoveIt reads ``&g;`` as those characters when the
    SRDF is loaded as text, the entity's text through xacro. The SRDF is checked as srdfdom
    reads it.

    Bad: ``<group name="arm"> <chain base_link="a" tip_link="b">`` (unclosed)
    Good: ``<chain base_link="a" tip_link="b"/>``
    """
    srdf = companions(robot).srdf
    if srdf is not None and srdf.problem:
        yield srdf.at(srdf.line), srdf.problem
    elif srdf is not None and srdf.caution:
        yield srdf.at(srdf.line), Conditional(srdf.caution)


@rule("U802", "srdf-robot-name", Severity.WARNING)
@as_moveit_runs
def srdf_robot_name(robot):
    """The SRDF's robot name differs from the URDF's.

    MoveIt warns "Semantic description is not specified for the same robot as the URDF" and
    the SRDF may belong to another robot.

    Bad: ``<robot name="ur5">`` against a URDF named ``ur5e``
    Good: the same name in both
    """
    srdf = _srdf(robot)
    if srdf is not None and srdf.root.get("name") != robot.name:
        yield srdf.at(srdf.root.sourceline), (f"SRDF robot name '{srdf.root.get('name')}' differs "
                                              f"from the URDF robot name '{robot.name}'")


def _virtual_joints(srdf) -> set:
    """SRDF virtual joints, and Pinocchio's ``root_joint`` (its free-flyer joint's name)."""
    return {v.get("name") for v in srdf.root.iterfind("virtual_joint")} | {"root_joint"}


@rule("U803", "srdf-unknown-joint", Severity.ERROR)
@as_moveit_runs
def srdf_unknown_joint(robot):
    """An SRDF group, group state or passive joint names a joint the URDF lacks.

    MoveIt fails to build the group ("Joint 'X' not found in model").

    Virtual joints and ``root_joint`` (Pinocchio's free-flyer) are accepted.

    Bad: ``<group name="arm"> <joint name="elbw"/>``
    Good: ``<joint name="elbow"/>``
    """
    srdf = _srdf(robot)
    if srdf is None:
        return
    known = set(robot.joints) | _virtual_joints(srdf)
    # offered: the joints MoveIt has (the URDF's, the SRDF's virtual ones), not Pinocchio's name
    offered = set(robot.joints) | {v.get("name") for v in srdf.root.iterfind("virtual_joint")}
    for element in _elements(srdf, "group/joint", "group_state/joint", "passive_joint"):
        name = element.get("name")
        if name not in known:
            yield srdf.at(element.sourceline), (
                f"SRDF <{element.getparent().tag if element.tag == 'joint' else element.tag}> names "
                f"joint '{name}', which is not in the URDF; " + available('joints', name or '', offered))


@rule("U804", "srdf-unknown-link", Severity.ERROR)
@as_moveit_runs
def srdf_unknown_link(robot):
    """An SRDF group, chain, end effector, virtual joint or collision pair names a link the URDF lacks.

    MoveIt (srdfdom) drops what names it: the link from its group, the chain, the end
    effector, the virtual joint (an error: the group or the robot's attachment MoveIt plans
    with is not what the SRDF says). A collision pair (``disable_collisions``,
    ``enable_collisions``) naming an unknown link is dropped with a warning ("Link 'x' is not
    known to URDF. Cannot disable/enable collisions."): it has no effect, and whether the pair
    meant is then checked for collisions depends on the links' geometry: a **warning** (an
    SRDF shared by several variants of a robot lists the pairs of each).

    Bad: ``<group name="arm"><chain base_link="base" tip_link="tool0"/></group>`` when the link is
    ``base_link``
    Good: ``base_link="base_link"``
    """
    srdf = _srdf(robot)
    if srdf is None:
        return
    attributes = (("group/link", "name"), ("group/chain", "base_link"), ("group/chain", "tip_link"),
                  ("end_effector", "parent_link"), ("virtual_joint", "child_link"),
                  ("disable_collisions", "link1"), ("disable_collisions", "link2"),
                  ("enable_collisions", "link1"), ("enable_collisions", "link2"),
                  ("link_sphere_approximation", "link"))
    for element, attribute, name in _references(srdf, attributes):
        if name not in robot.links:
            message = (f"SRDF <{element.tag} {attribute}='{name}'> is not a link of the URDF; "
                       + available('links', name, robot.links))
            if element.tag in ("disable_collisions", "enable_collisions"):
                message = Conditional(
                    f"SRDF <{element.tag} {attribute}='{name}'> is not a link of the URDF: MoveIt "
                    "drops the pair (it has no effect); " + available('links', name, robot.links))
            yield srdf.at(element.sourceline), message


@rule("U805", "srdf-unknown-group", Severity.ERROR)
@as_moveit_runs
def srdf_unknown_group(robot):
    """An SRDF subgroup, group state or end effector names a group that is not defined.

    Bad: ``<group_state name="home" group="arms">`` when the group is ``arm``
    Good: ``group="arm"``
    """
    srdf = _srdf(robot)
    if srdf is None:
        return
    groups = {g.get("name") for g in srdf.root.iterfind("group")}
    attributes = (("group/group", "name"), ("group_state", "group"), ("end_effector", "group"),
                  ("end_effector", "parent_group"))
    for element, attribute, name in _references(srdf, attributes):
        if name not in groups:
            yield srdf.at(element.sourceline), (
                f"SRDF <{element.tag} {attribute}='{name}'> names no group; "
                + available('groups', name, groups))


@rule("U806", "srdf-state-outside-limits", Severity.ERROR)
@as_moveit_runs
def srdf_state_outside_limits(robot):
    """An SRDF group state puts a joint outside its URDF limits.

    MoveIt rejects the named pose as invalid, so "home" cannot be planned to.

    Bad: ``<joint name="knee" value="2.5"/>`` with ``<limit lower="0" upper="2.27" .../>``
    Good: a value between lower and upper
    """
    srdf = _srdf(robot)
    if srdf is None:
        return
    for element in srdf.root.iterfind("group_state/joint"):
        joint = robot.joints.get(element.get("name"))
        limit = joint.find("limit") if joint is not None else None
        if limit is None or joint.get("type") not in LIMITED:
            continue
        values, problem = parse_numbers(element.get("value"), 1)
        bounds = limit_range(joint.get("type"), limit)
        state = element.getparent().get("name")
        if problem:
            yield srdf.at(element.sourceline), f"SRDF group state '{state}': joint value {problem}"
        elif bounds and not (bounds[0] - LIMIT_TOLERANCE <= values[0] <= bounds[1] + LIMIT_TOLERANCE):
            yield srdf.at(element.sourceline), (
                f"SRDF group state '{state}' sets joint '{element.get('name')}' to {values[0]:g}, "
                f"outside its URDF limits [{bounds[0]:g}, {bounds[1]:g}]")


@rule("U807", "srdf-duplicate-group", Severity.ERROR)
@as_moveit_runs
def srdf_duplicate_group(robot):
    """Two SRDF groups have the same name.

    MoveIt keeps the first and drops the other ("A group named 'arm' already exists"), so the
    joints of the second definition are never planned for.

    Bad: ``<group name="arm"><chain .../></group> <group name="arm"><joint .../></group>``
    Good: one ``<group name="arm">`` holding both, or two names
    """
    srdf = _srdf(robot)
    if srdf is None:
        return
    first: dict[str, int] = {}
    for element in srdf.root.iterfind("group"):
        name = element.get("name")
        if name in first:
            yield srdf.at(element.sourceline), (
                f"SRDF group '{name}' is defined again (first at line {first[name]}); MoveIt "
                "keeps the first definition and drops this one")
        else:
            first[name] = element.sourceline


def _groups(robot, srdf):
    from urdftool.kinematics.groups import groups, tree

    return tree(robot, srdf.root), groups(robot, srdf.root)


@rule("U808", "srdf-state-foreign-joint", Severity.ERROR)
@as_moveit_runs
def srdf_state_foreign_joint(robot):
    """An SRDF group state sets a joint that is not in its group.

    MoveIt drops the value ("Group state 'home' specifies value for joint 'x', but that joint
    is not part of group 'arm'"): the named pose is not the one written. A group's joints are
    its ``<joint>`` elements, the parent joints of its ``<link>`` elements, the joints along its
    ``<chain>`` (not the base link's parent joint) and its subgroups' joints. Pinocchio's
    ``root_joint`` (not a URDF joint) is accepted: Pinocchio reads group states without groups.
    A group with an unknown member is left to U803-U805.

    Bad: ``<group_state name="home" group="left_arm"> <joint name="r_elbow" value="0"/>``
    Good: the joint in the group, or the value in a state of the group that has it
    """
    srdf = _srdf(robot)
    if srdf is None:
        return
    model, groups = _groups(robot, srdf)
    for state in srdf.root.iterfind("group_state"):
        group = groups.get(state.get("group"))
        if group is None or not group.complete:
            continue  # an unknown group or member is U803-U805's
        for element in state.iterfind("joint"):
            name = element.get("name")
            if name in group.joints or name not in model.joints:
                continue  # an unknown joint is U803's
            yield srdf.at(element.sourceline), (
                f"SRDF group state '{state.get('name')}' sets joint '{name}', which is not part "
                f"of group '{group.name}' (its joints: {listed(sorted(group.joints), False) or 'none'}); "
                "MoveIt ignores the value")


@rule("U809", "srdf-end-effector-parent", Severity.ERROR)
@as_moveit_runs
def srdf_end_effector_parent(robot):
    """An SRDF end effector's ``parent_link`` is not a link of its ``parent_group``.

    MoveIt refuses the parent group ("Group 'arm' was specified as parent group for
    end-effector 'hand' but it does not include the parent link 'x'"), so the end effector is
    not attached to the arm that carries it. A group's links are the child links of its joints:
    a chain's base link is not one of them.

    Bad: ``<end_effector name="hand" parent_link="base_link" parent_group="arm" group="gripper"/>``
    Good: ``parent_link="wrist_link"``, the arm's last link
    """
    srdf = _srdf(robot)
    if srdf is None:
        return
    from urdftool.kinematics.groups import links_of

    model, groups = _groups(robot, srdf)
    for element in srdf.root.iterfind("end_effector"):
        link, group = element.get("parent_link"), groups.get(element.get("parent_group"))
        if group is None or not group.complete or link not in robot.links:
            continue  # no parent group, or an unknown one (U805) or an unknown link (U804)
        links = links_of(model, group)
        if link not in links:
            yield srdf.at(element.sourceline), (
                f"SRDF end effector '{element.get('name')}' has parent_link '{link}', which is "
                f"not a link of its parent_group '{group.name}'; "
                + available('links of the group', link, links))


def _overlaps(robot, srdf):
    """Pairs in contact at the SRDF's poses (one FCL check per pose), once per robot; None when
    the robot cannot be posed (its tree or geometry is another rule's finding)."""
    def compute():
        from urdftool.collision.srdf import overlaps
        from urdftool.errors import UrdftoolError

        try:
            return overlaps(robot, srdf.root)
        except UrdftoolError:
            return None
    return robot.memo(_overlaps, compute)


def _at_default(overlap) -> bool:
    return any(element is None for _, element in overlap.poses)


def _where(overlap) -> str:
    labels = [label for label, _ in overlap.poses]
    shown = ", ".join(labels[:3]) + (f" and {len(labels) - 3} more" if len(labels) > 3 else "")
    if overlap.depth is not None:
        how = f"penetration depth {number(overlap.depth * 1000, places=1)} mm"
    elif overlap.depth_at_most is not None:
        how = ("their meshes' surfaces cross; the depth of a non-convex mesh is not known, at "
               f"most {number(overlap.depth_at_most * 1000, places=1)} mm by the convex hulls")
    else:
        how = "their meshes' surfaces cross; a flat mesh has no depth"
    return f"collide ({how}) at {shown}"


@rule("U810", "srdf-disabled-pair-collides", Severity.WARNING)
@as_moveit_runs
def srdf_disabled_pair_collides(robot):
    """A pair disabled as "Never" (or "User") collides at the default pose or a group state.

    ``<disable_collisions>`` tells MoveIt never to check the pair, so a real collision between
    them is planned through. The reason says why the pair was disabled; they are read so:

    - ``Adjacent`` (joined by a joint), ``Default`` (in contact at the default pose, which is
      why the Setup Assistant disabled it) and ``Always`` (in contact in nearly every sampled
      pose): contact is expected, never reported;
    - ``Never`` (the Setup Assistant saw no contact in any sample), ``User`` (disabled by hand)
      and any other reason: a claim that the links do not touch, reported when they do.

    Each pose is checked once with FCL: the default configuration (0, or mid-range where 0 is
    outside the limits) and each SRDF group state over it. The sampled check is
    ``urdftool collisions --check-srdf``.

    A warning, not an error: parts that overlap by design (nested telescoping segments, a
    gripper's fingers) are disabled on purpose, only under the wrong reason.

    Fix (unsafe): remove the entry, as a fresh collision matrix would not list the pair as
    Never; whether they touch by design (then ``reason="Default"``) only the author knows.

    Bad: ``<disable_collisions link1="l_hand" link2="r_hand" reason="Never"/>`` for hands that
    touch in the "home" state
    Good: no entry (MoveIt then checks the pair), or ``reason="Default"`` if they touch by design
    """
    srdf = _srdf(robot)
    entries = list(srdf.root.iter("disable_collisions")) if srdf is not None else []
    if not entries:
        return
    from urdftool.collision.srdf import MAY_TOUCH  # NumPy and FCL: only for an SRDF's entries

    claims = [e for e in entries if e.get("reason") not in MAY_TOUCH]
    found = _overlaps(robot, srdf) if claims else None
    for element in claims if found else ():
        pair = tuple(sorted((element.get("link1", ""), element.get("link2", "")),
                            key=str.encode))
        overlap = found.get(pair)
        if overlap is not None and not overlap.adjacent:
            from urdftool.lint.fixes import offer  # (only for a finding)
            yield offer(srdf.at(element.sourceline), (
                f"{pair[0]} and {pair[1]} are disabled as '{element.get('reason', '')}' but "
                f"{_where(overlap)}: MoveIt will not see that collision; remove the entry"
                + (", or give the reason Default if they touch by design" if _at_default(overlap)
                   else "")), f"remove the <disable_collisions> of {pair[0]} and {pair[1]}",
                _remove_entry(srdf, element), safe=False)


@rule("U811", "srdf-collision-not-disabled", Severity.WARNING)
@as_moveit_runs
def srdf_collision_not_disabled(robot):
    """Two links overlap at the default pose or a group state, and the SRDF does not disable them.

    The links are not adjacent, and the SRDF has no ``<disable_collisions>`` for them.

    MoveIt finds the robot in collision in that pose ("Start state appears to be in
    collision") and refuses to plan from it: either the geometry or the pose is wrong (e.g.
    both arms mounted on the same side), or the pair touches by design and needs
    ``reason="Default"``. Links joined by a joint (directly or through links without collision
    geometry) are not reported; ``urdftool collisions --check-srdf`` lists missing Adjacent
    entries. Checked only when the robot has an SRDF. Reported at the group state, or at
    ``<robot>`` for the default configuration.

    Fix (unsafe), for a pair in contact at the default pose: add the entry MoveIt's Setup
    Assistant writes for it, ``reason="Default"``, before ``</robot>``; the pair touches by
    design only if the author says so.

    Bad: ``l_hand`` and ``r_hand`` inside each other in the "home" state, with no entry
    Good: a "home" where they are apart
    """
    srdf = _srdf(robot)
    if srdf is None:
        return
    found = _overlaps(robot, srdf)
    listed = {tuple(sorted((e.get("link1", ""), e.get("link2", "")), key=str.encode))
              for e in srdf.root.iter("disable_collisions")}
    for pair, overlap in sorted((found or {}).items()):
        if pair in listed or overlap.adjacent:  # adjacent: U823
            continue
        element = overlap.poses[0][1]
        from urdftool.lint.fixes import offer  # (only for a finding)
        yield offer(
            srdf.at(element.sourceline if element is not None else srdf.root.sourceline), (
                f"{pair[0]} and {pair[1]} {_where(overlap)}, and the SRDF does not disable the "
                "pair: MoveIt reports the robot in collision there; fix the geometry or the pose"
                + (f", or add <disable_collisions link1=\"{pair[0]}\" link2=\"{pair[1]}\" "
                   "reason=\"Default\"/> if they touch by design" if _at_default(overlap)
                   else "")),
            f"disable {pair[0]} and {pair[1]} as Default (in contact at the default pose)",
            _add_default_entry(srdf, pair) if _at_default(overlap) else None, safe=False)


# --- fixes: what a fresh collision matrix says of the pairs checked at the SRDF's poses -------

def _srdf_source(srdf):
    """Where the SRDF's start tags are, parsed once per file (each finding's fix asks)."""
    from urdftool.lint.fixes import parse_source

    if "_source" not in vars(srdf):
        srdf._source = parse_source(srdf.display, srdf.text.encode("utf-8")) if srdf.text else None
    return srdf._source


def _remove_entry(srdf, element):
    """The edit deleting one ``<disable_collisions/>`` (its whole line when it stands alone)."""
    from urdftool.lint.fixes import Unfixable

    source = _srdf_source(srdf)
    tags = [t for t in (source.on_line(element.sourceline) if source else ())
            if t.name == "disable_collisions" and t.self_closing
            and {t.attributes.get(k, (0, 0, None))[2] for k in ("link1", "link2")}
            == {element.get("link1"), element.get("link2")}]
    if len(tags) != 1:
        return Unfixable(f"the entry at {srdf.display}:{element.sourceline} is not one "
                         "<disable_collisions .../> tag on its line")
    data, (start, end) = source.data, (tags[0].start, tags[0].end)
    first, last = line_start(data, start), line_end(data, end)
    if not data[first:start].strip() and not data[end:last].strip():
        start, end = first, last
    return [source.edit(start, end, "")]


def _add_default_entry(srdf, pair):
    return _add_entry(srdf, pair, "Default")


def _add_entry(srdf, pair, reason: str):
    """The edit adding ``<disable_collisions ... reason="REASON"/>`` on a line of its own before
    ``</robot>``, indented as the file's other entries (or by two spaces)."""
    from urdftool.lint.fixes import Unfixable

    source = _srdf_source(srdf)
    root = source.tag(0) if source is not None and len(source) else None
    if root is None or root.close_name is None:
        return Unfixable(f"{srdf.display} holds '--' in a comment, which fixes do not edit"
                         if srdf.caution else f"{srdf.display} has no </robot> to write before")
    data = source.data
    close = root.close_name[0] - 2  # the '<' of '</robot>'
    first = line_start(data, close)
    if data[first:close].strip():
        return Unfixable(f"</robot> in {srdf.display} does not start its line")
    entries = [t for t in (source.tag(i) for i in range(len(source)))
               if t.name == "disable_collisions"]
    if entries:
        indent = data[line_start(data, entries[0].start):entries[0].start].decode(
            "utf-8", "replace")
    else:
        indent = "  "
    line = (f'{indent}<disable_collisions link1="{attribute(pair[0])}" '
            f'link2="{attribute(pair[1])}" reason="{attribute(reason)}"/>{source.newline}')
    return [source.edit(first, first, line)]
