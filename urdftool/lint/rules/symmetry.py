"""U218-U223: left/right symmetry of limbs and wheels named as mirror pairs.

Pairs are found by name (:mod:`urdftool.physics.mirror`: ``l_``/``r_``, ``left``/``right``,
``_l``/``_r``, DARwIn's and Romeo's capital ``L``/``R``, the legs' ``LF``/``RF``...), and the
mirror plane from the pairs themselves at the zero pose. A difference between the two sides is
a finding that names both and says what differs: robots are built symmetric, and a number
changed on one side only (an axis sign, a limit, a mass copied from another part) is the most
common slip in a mirrored limb. An asymmetry that is meant (a sensor on one arm, a heavier
gripper) is declared with a suppression comment before either element of the pair, or before
the macro call that makes it: ``<!-- urdftool: ignore U221 -->``; a whole robot that is not
symmetric by design with ``ignore = ["U218"...]`` in the settings.

A place (U218) that differs, or an axis tilted less than 45 degrees from its mirror image
(U219), is a note: in the real sweep none of 33 rows was a slip anyone could name from the files
(vendors' left and right hand models, asymmetric mountings, sensors placed by design), where
limits (U220) and inertials (U221) that differ were slips in a third of their rows (one side
not updated, a decimal point), and an axis along another direction was one (MuR620's lifts).
Of the inertials, every slip was 1.5 times apart or more; under that (two sides' CAD parts of
one design, 5 to 40 % apart) U221 is a note.

Nothing is said when fewer than two pairs agree with the plane they give (a robot whose sides
are not mirror images by design: two identical arms turned 180 degrees apart, say), and each
difference is reported once, at the first pair down the tree where it appears.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from urdftool.description.urdf import VARIABLE
from urdftool.description.values import finite, limit_range, number as attribute_number
from urdftool.description.xml import first_child
from urdftool.lint.catalogue import Severity, rule
from urdftool.numbers import decimal_slip, number, numbers
from urdftool.physics import mat3
from urdftool.physics.frames import child_joints, joint_frames, link_frames, parent_joints, world_axis
from urdftool.physics.mass import declared_of, moments_of
from urdftool.physics.mirror import joint_pairs, link_pairs, plane
from urdftool.physics.wheels import driven_joints

POSITION_TOLERANCE = 0.002  # [m]: CAD exports round to 0.1 mm; a slip is a centimetre
RELATIVE_POSITION = 0.01  # and 1 % of the distance from the plane (big robots round coarser)
AXIS_TOLERANCE = math.radians(2.0)
TURNED = math.radians(45.0)  # an axis this far from its mirror image is another axis (U219)
LIMIT_TOLERANCE = 1e-3  # [rad or m] absolute, and 1 % of the range
STOPS_APART = 0.10  # of the range: the stops of two sides of one design differ by up to 6 % of
# it (Nao's ankle and hip rolls, Spot's hips, Poppy's shoulders, the Pi+'s thighs); every range
# judged a slip in the sweep was 16 % or more from the mirror image's (a negated or copied range)
MASS_TOLERANCE = 0.05  # relative: left and right parts differ by cables and screws, not 5 %
INERTIA_TOLERANCE = 0.10  # relative, on the principal moments (a tensor is rounded harder)
ZERO_SIDE = 1e-6  # a side whose largest moment is this small against the other's has none
SLIP_RATIO = 1.5  # one side's mass or a principal moment half as large again as the other's:
# every inertial slip judged in the sweep was (a value from another part, a decimal point, a
# placeholder tensor: 1.57 to 200 times); the CAD parts of two sides of one design differ by up
# to 1.4 times (Nao's pelvis, iCub's shoulders, HSR's fingers), a note naming the condition
AGREEING = 2  # pairs that must agree with the plane before any position is judged
# what the user knows and the file does not say (U220, U221: a slip in a third of the sweep's rows)
_CONDITION = ", if the two sides are built as mirror images"


def _near(a: float, b: float, absolute: float, relative: float = 0.0, scale=None) -> bool:
    """|a - b| within ``absolute`` plus ``relative`` times ``scale`` (default: the larger of
    |a| and |b|)."""
    scale = max(abs(a), abs(b)) if scale is None else abs(scale)
    return abs(a - b) <= absolute + relative * scale


def _located(robot, left, right):
    """The element to report on: the later of the two in the document (a fix usually goes to
    the side written second, a copy of the first)."""
    return right if _place(robot, right) >= _place(robot, left) else left


def _place(robot, element) -> int:
    """The index of the element's ``<robot>`` child (itself, or the link or joint holding it)."""
    while element is not None and element.getparent() is not None \
            and element.getparent() is not robot.root:
        element = element.getparent()
    return robot.root.index(element) if element is not None and \
        element.getparent() is robot.root else -1


@dataclass
class _Pair:
    """What the zero pose says of a joint pair: ``kind`` "mirror" (the right joint is at the
    left one's mirror image), "copy" (it is where the left one is carried by the transform
    between the pair above them: an identical part, such as the same gripper on both arms,
    is a copy, not a mirror image), "off" (neither) or "local" (a pair mirrored about a plane
    of its own, such as a stereo camera's two lenses or a gripper's two fingers, which hang
    from one link off the robot's plane: not judged); ``residual`` [m]: the distance to the
    mirror image; ``turn``: the rotation carrying the left side onto the right (copies)."""

    kind: str
    residual: float
    turn: mat3.Matrix = mat3.IDENTITY
    copy_turn: mat3.Matrix | None = None  # a copy's turn, when the pair above is turned


def _analysis(robot):
    """(mirror plane, {(left, right): _Pair}, whether positions can be judged: at least two
    pairs, and most of those judged, are mirror images or copies), None without a plane. Once
    per robot."""
    return robot.memo(_analysis, lambda: _analyse(robot))


def _analyse(robot):
    found = plane(robot)
    if found is None:
        return None
    frames = joint_frames(robot)
    known = [(l, r) for l, r in joint_pairs(robot) if l in frames and r in frames
             and not _in_line(robot, robot.joints[l], robot.joints[r])]
    sagittal = [pair for pair in known if _meets_on_plane(robot, pair, found)]
    if len(sagittal) < sum(1 for l, r in joint_pairs(robot) if l in frames and r in frames):
        # refitted only on fewer pairs: on all of them (27 of the corpus's 28 robots with a
        # plane) the fit is the one `plane` made, of the same points in the same order
        found = _refit(frames, sagittal) or found
    pairs: dict = {}
    kept: dict = {}  # left rotation -> whether it is its own mirror image (_translated_copy)
    on_plane = set(sagittal)
    for left, right in known:
        if (left, right) not in on_plane:
            pairs[(left, right)] = _Pair("local", 0.0)
            continue
        residual = math.dist(found.reflect(frames[left][0]), frames[right][0])
        tolerance = _position_tolerance(found, frames[left][0])
        above = _upstream_pair(robot, left, right)
        copied = above is not None and pairs.get(above) is not None and \
            pairs[above].kind == "copy"
        turn = _carry(frames, above) if above is not None else None
        if residual <= tolerance and not _siblings(robot, left, right) and \
                _translated_copy(found, frames[left][1], frames[right][1], kept):
            # the right frame is the left one's, turned as no mirror image is (a hand mounted
            # at 45 degrees on both arms): one product carried across, not mirrored. Two
            # joints of one link (a gripper's fingers) share its frame whatever it is turned
            # to: at mirror-image places they are each other's mirror image
            pairs[(left, right)] = _Pair("copy", residual, _carry(frames, (left, right)))
        elif residual <= tolerance and not copied:
            pairs[(left, right)] = _Pair("mirror", residual)
        elif turn is not None and math.dist(_carried(frames, above, turn, frames[left][0]),
                                            frames[right][0]) <= tolerance:
            pairs[(left, right)] = _Pair("copy", residual, turn)
        elif residual <= tolerance:
            pairs[(left, right)] = _Pair("mirror", residual)
        elif _other_partner(frames, found, left, right, above, turn, tolerance):
            # a copied part keeps its own labels: the right gripper's finger 1 is the copy of
            # the left's finger 1, though the names mirror finger 1 to finger 2
            pairs[(left, right)] = _Pair("copy", residual, turn or mat3.IDENTITY)
        else:
            pairs[(left, right)] = _Pair("off", residual)
        if turn is not None and _turned(turn):
            # identical parts mounted turned (the same arm on both sides of a torso): their
            # axes and limits may be a copy's rather than a mirror's
            pairs[(left, right)].copy_turn = turn
    _copied_limbs(robot, frames, pairs)
    judged = [pair for pair in pairs.values() if pair.kind != "local"]
    agreeing = sum(1 for pair in judged if pair.kind != "off")
    return found, pairs, agreeing >= AGREEING and agreeing * 2 >= len(judged)


def _copied_limbs(robot, frames, pairs) -> None:
    """A limb (pairs joined to the pair above them) holding a pair that is a copy and not a
    mirror image is a copy of one product on both sides (two identical arms): each of its
    pairs may then be read as a copy, its right joint's frame carried from the left one's."""
    limb: dict = {}

    def root(pair):
        while limb.get(pair, pair) != pair:
            pair = limb[pair]
        return pair

    for pair in pairs:
        above = _upstream_pair(robot, *pair)
        if above in pairs:
            limb[root(pair)] = root(above)
    copied = {root(pair) for pair, found in pairs.items() if found.kind == "copy"}
    for pair, found in pairs.items():
        if found.kind in ("mirror", "off") and root(pair) in copied and found.copy_turn is None:
            left, right = pair
            found.copy_turn = mat3.multiply(frames[right][1], mat3.transpose(frames[left][1]))


def _siblings(robot, left: str, right: str) -> bool:
    """Whether joints ``left`` and ``right`` hang from one link."""
    ends = robot.ends()
    parents = {ends[robot.joints[name]]["parent"][1] for name in (left, right)}
    return len(parents) == 1 and None not in parents


def _in_line(robot, a, b) -> bool:
    """Whether joint ``b`` is above or below joint ``a`` (a serial arm's joint_l and joint_r:
    Motoman's L and R axes, not a left and a right)."""
    names = robot.names()  # (each joint's name as loaded: no lxml attribute read per pair)
    a, b = names[a], names[b]
    return b in _joints_above(robot, a) or a in _joints_above(robot, b)


COPY_TURN = math.radians(10.0)
_SIGNS = [(a, b, c) for a in (1, -1) for b in (1, -1) for c in (1, -1)]


def _translated_copy(found, left, right, kept: dict, tolerance: float = 1e-6) -> bool:
    """Whether two frames have one orientation that their mirror image does not keep (up to
    the sign of each axis): the mark of a part carried across, not mirrored. ``kept``: the
    answer of each left rotation already asked about this plane (most pairs of a robot share
    a few rotations: the identity, a quarter turn)."""
    if any(abs(a - b) > tolerance for row_a, row_b in zip(left, right)
           for a, b in zip(row_a, row_b)):
        return False
    own = kept.get(left)
    if own is None:
        own = kept[left] = _own_mirror_image(found.normal, left, tolerance)
    return not own


def _own_mirror_image(n, left, tolerance: float) -> bool:
    """Whether a rotation is its own mirror image about a plane of normal ``n``, up to the
    sign of each axis."""
    reflection = tuple(tuple((1.0 if i == j else 0.0) - 2 * n[i] * n[j] for j in range(3))
                       for i in range(3))
    mirrored = mat3.multiply(mat3.multiply(reflection, left), reflection)
    for signs in _SIGNS:
        flipped = tuple(tuple(left[i][j] * signs[j] for j in range(3)) for i in range(3))
        if all(abs(a - b) <= tolerance for row_a, row_b in zip(mirrored, flipped)
               for a, b in zip(row_a, row_b)):
            return True  # the frame is its own mirror image, up to its axes' signs
    return False


def _turned(turn) -> bool:
    """Whether a rotation turns by more than 10 degrees (a translated copy of a limb is not
    how a robot carries one part on both sides: its limbs are mirror images)."""
    return math.acos(max(-1.0, min(1.0, (mat3.trace(turn) - 1) / 2))) > COPY_TURN


def _other_partner(frames, found, left, right, above, turn, tolerance) -> bool:
    """Whether another name ``left`` may mirror to is at its mirror image, or its copy."""
    from urdftool.physics.mirror import mirror_names

    for other in mirror_names(left):
        if other == right or other not in frames:
            continue
        if math.dist(found.reflect(frames[left][0]), frames[other][0]) <= tolerance:
            return True
        if turn is not None and math.dist(_carried(frames, above, turn, frames[left][0]),
                                          frames[other][0]) <= tolerance:
            return True
    return False


def _meets_on_plane(robot, pair, found) -> bool:
    """Whether the two joints' chains meet at a link whose frame lies on the plane (a limb
    pair hangs from the torso; a stereo camera's lenses from one camera off the plane)."""
    parents = parent_joints(robot)
    left, right = (robot.joints[name] for name in pair)
    chain = _links_above(robot, left, parents)
    others = set(_links_above(robot, right, parents))
    common = next((link for link in chain if link in others), None)
    frames = link_frames(robot)
    if common is None or common not in frames:
        return False
    return abs(mat3.dot(found.normal, frames[common][0]) - found.offset) <= POSITION_TOLERANCE


def _links_above(robot, joint, parents) -> list[str]:
    found, seen, ends = [], set(), robot.ends()
    while joint is not None:
        link = ends[joint]["parent"][1]
        if link is None or link in seen:
            break
        seen.add(link)
        found.append(link)
        joint = parents.get(link)
    return found


def _refit(frames, pairs):
    from urdftool.physics.mirror import fit

    return fit([(frames[l][0], frames[r][0]) for l, r in pairs])


def _carry(frames, above) -> mat3.Matrix:
    """The rotation carrying the left joint of pair ``above`` onto the right one."""
    return mat3.multiply(frames[above[1]][1], mat3.transpose(frames[above[0]][1]))


def _carried(frames, above, turn, point) -> mat3.Vector:
    """``point`` carried as the left joint of ``above`` is carried onto the right one."""
    offset = tuple(a - b for a, b in zip(point, frames[above[0]][0]))
    return mat3.add(frames[above[1]][0], mat3.apply(turn, offset))


def _position_tolerance(found, point) -> float:
    return POSITION_TOLERANCE + RELATIVE_POSITION * abs(mat3.dot(found.normal, point) -
                                                        found.offset)


def _upstream_pair(robot, left: str, right: str) -> tuple[str, str] | None:
    """The nearest pair of joints above ``left`` and ``right`` (one above each), if any; once
    per robot and pair (every symmetry rule asks it of every pair)."""
    return robot.memo_for(_upstream_pair, (left, right),
                          lambda: _find_upstream_pair(robot, left, right) or ()) or None


def _find_upstream_pair(robot, left: str, right: str) -> tuple[str, str] | None:
    pairs = robot.memo(_find_upstream_pair, lambda: dict(joint_pairs(robot)))
    above_right = set(_joints_above(robot, right))
    for joint in _joints_above(robot, left):
        if pairs.get(joint) in above_right:
            return joint, pairs[joint]
    return None


def _joints_above(robot, joint_name: str) -> tuple[str, ...]:
    """The names of the joints above ``joint_name``, nearest first; once per robot and joint."""
    return robot.memo_for(_joints_above, joint_name, lambda: _walk_up(robot, joint_name))


def _walk_up(robot, joint_name: str) -> tuple[str, ...]:
    parents, ends, names = parent_joints(robot), robot.ends(), robot.names()
    found, seen = [], set()
    joint = robot.joints.get(joint_name)
    while joint is not None:
        link = ends[joint]["parent"][1]
        joint = parents.get(link)
        name = names[joint] if joint is not None else None
        if name is None or name in seen:
            break  # the root, a joint without a name (U103), or a cycle (U109)
        seen.add(name)
        found.append(name)
    return tuple(found)


def _text(v) -> str:
    return f"({numbers(v, 4, ', ')})"  # round-off beside the largest component written 0


@rule("U218", "mirror-origin", Severity.INFO)
def mirror_origin(robot):
    """Two joints named as a left/right pair are not at mirror-image places at the zero pose.

    The mirror plane is found from all the pairs (the median of the directions joining them),
    not assumed to be y = 0. A joint more than 2 mm (and 1 % of its distance from the plane)
    off its partner's mirror image was moved on one side only: a limb segment of another
    length, a sign slip in an origin. Reported once, at the first pair down the tree that is
    off (the joints below it move with it). Not judged unless most pairs, and at least two,
    agree with the plane.

    A **note**: nothing that loads a robot needs its sides to be mirror images, and whether
    they are meant to be the file does not say. In the real sweep (363 public repositories)
    none of 22 such findings was a slip anyone could name from the files (NimbRo-OP's hip
    rolls 30 mm apart, Fourier's shoulders 7 mm, Unitree's hands), and none of the fixed parts
    with nothing moving below them (a camera, an IMU, a skin patch, a logo), which the note
    says may be placed so by design (iCub's forearm skins, the Create 3's infrared sensors).

    Bad: ``l_knee`` at ``xyz="0 0 -0.093"`` and ``r_knee`` at ``xyz="0 0 -0.039"``
    Good: both legs from one macro, the side given as ``reflect="1"`` / ``"-1"``
    """
    analysis = _analysis(robot)
    if analysis is None or not analysis[2]:
        return
    mirror, pairs, _ = analysis
    frames = joint_frames(robot)
    for (left, right), pair in pairs.items():
        if pair.kind != "off":
            continue
        above = _upstream_pair(robot, left, right)
        if above is not None and above in pairs and pairs[above].kind == "off":
            continue  # moved with the pair above, reported there
        message = (
            f"joints '{left}' and '{right}' are not mirror images: '{right}' is at "
            f"{_text(frames[right][0])} m, {number(pair.residual * 1000, places=0)} mm from the mirror image "
            f"of '{left}' {_text(mirror.reflect(frames[left][0]))} about the robot's mirror "
            f"plane (normal {_text(mirror.normal)}); one side's origin differs")
        where = _located(robot, robot.joints[left], robot.joints[right])
        if _rigid_end(robot, left) and _rigid_end(robot, right):
            yield where, message + (" (both fixed, nothing moving below them: a sensor or "
                                    "marker may be placed so by design)")
        else:
            yield where, message + " (if the two sides are built as mirror images)"


def _rigid_end(robot, name: str) -> bool:
    """Whether joint ``name`` is fixed and every joint below its child link is fixed too: a
    part rigidly attached at the end of the tree (a sensor with its optical frames)."""
    joint, below, kinds, ends = robot.joints[name], child_joints(robot), robot.kinds(), \
        robot.ends()
    if kinds[joint] != "fixed":
        return False
    links, seen = [ends[joint]["child"][1]], set()
    while links:
        link = links.pop()
        if link in seen:
            continue
        seen.add(link)
        for child in below.get(link, ()):
            if kinds[child] != "fixed":
                return False
            links.append(ends[child]["child"][1])
    return True


def _limits(joint) -> tuple[float, float] | None:
    """The joint's finite range (:func:`~urdftool.description.values.limit_range`), or None."""
    bounds = limit_range(joint.get("type"), first_child(joint, "limit"))  # (not lxml's find,
    return bounds if bounds is not None and finite(bounds) else None  # which parses a path)


def _expected_axis(robot, left, found, pair) -> mat3.Vector | None:
    """The right joint's axis that moves it as the mirror image of the left one (or, for a
    copy, as the left one carried over) for the same value."""
    a_left = _world_axis(robot, left)
    if a_left is None:
        return None
    if pair is not None and pair.kind == "copy":
        return mat3.apply(pair.turn, a_left)
    reflected = found.reflect_vector(a_left)
    # a rotation's axis is an axial vector: its mirror image turns the other way
    return reflected if left.get("type") == "prismatic" else tuple(-v for v in reflected)


def _world_axis(robot, joint) -> mat3.Vector | None:
    """:func:`~urdftool.physics.frames.world_axis`, once per robot and joint (U219 and U220
    ask each joint of a pair for it under every reading of the pair)."""
    known = robot.memo(_world_axis, dict)
    if joint not in known:
        known[joint] = world_axis(robot, joint)
    return known[joint]


def _relations(robot, left, right, found, pair) -> list[tuple[str, float]]:
    """:func:`_axis_relation` under each reading the pair allows: a mirror image, and a copy
    when it is one or may be one (``copy_turn``); once per robot and pair (U219 and U220 both
    ask, of the plane and the pair the one analysis gives). The list is shared: read it."""
    known = robot.memo(_relations, dict)
    if (left, right) not in known:
        known[(left, right)] = _find_relations(robot, left, right, found, pair)
    return known[(left, right)]


def _find_relations(robot, left, right, found, pair) -> list[tuple[str, float]]:
    readings = [pair]
    if pair is not None and pair.kind != "copy" and pair.copy_turn is not None:
        readings.append(_Pair("copy", pair.residual, pair.copy_turn))
    found_relations = [_axis_relation(robot, left, right, found, reading) for reading in readings]
    return [relation for relation in found_relations if relation is not None]


def _axis_relation(robot, left, right, found, pair=None) -> tuple[str, float] | None:
    """("same", angle) when the right axis moves the right joint as the mirror image of the
    left one (or its copy) for the same value, ("negated", angle) when for the opposite value,
    and the angle to the nearer of the two [rad]; None when an axis cannot be read."""
    mirrored, a_right = _expected_axis(robot, left, found, pair), _world_axis(robot, right)
    if mirrored is None or a_right is None:
        return None
    cosine = max(-1.0, min(1.0, mat3.dot(mirrored, a_right)))
    angle = math.acos(abs(cosine))
    return ("same" if cosine >= 0 else "negated"), angle


def _typed_pairs(robot):
    """(left joint, right joint, plane, _Pair) for the pairs of the same moving type that are
    not mirrored about a plane of their own."""
    analysis = _analysis(robot)
    if analysis is None:
        return
    found, pairs, _ = analysis
    driven = driven_joints(robot)  # a diff drive's wheels: U617 judges their axes
    for (left, right), pair in pairs.items():
        a, b = robot.joints[left], robot.joints[right]
        if pair.kind != "local" and a.get("type") == b.get("type") and \
                a.get("type") in VARIABLE and not (left in driven and right in driven):
            yield a, b, found, pair


@rule("U219", "mirror-axis", Severity.WARNING)
def mirror_axis(robot):
    """Two joints named as a left/right pair turn about axes that are not mirror images.

    The right joint's axis must be the mirror image of the left one's (about the plane the
    pairs give), up to its sign: robots choose per joint whether the same value moves both
    sides as mirror images (pitch axes both along y) or the same way (roll axes both along x,
    limits negated); U220 checks that the limits agree with that choice. An axis along
    another direction (45 degrees off or more) turns that limb in another plane: a warning
    (MuR620's lift joints about y on the left and z on the right). An axis tilted from it (more
    than 2 degrees, less than 45) is a **note** saying "if the two sides are built as mirror
    images": in the real sweep none of these was a slip anyone could name from the files
    (Unitree's and iCub's left and right hand models 7 and 10 degrees apart, a SolidWorks
    export's thrusters 2 degrees apart).

    Bad: ``l_hip_roll`` about ``1 0 0`` and ``r_hip_roll`` about ``0 1 0``
    Good: both about ``1 0 0``, or ``1 0 0`` and ``-1 0 0``
    """
    for left, right, found, pair in _typed_pairs(robot):
        relations = _relations(robot, left, right, found, pair)
        if not relations or any(angle <= AXIS_TOLERANCE for _, angle in relations):
            continue
        relation = relations[0]
        a_right = world_axis(robot, right)
        what = "carried over from" if pair.kind == "copy" else "the mirror image of"
        yield _located(robot, left, right), (
            f"joints '{left.get('name')}' and '{right.get('name')}' turn about axes that are not "
            f"mirror images: {_text(world_axis(robot, left))} and {_text(a_right)} at the zero "
            f"pose ({what} the first is {_text(_expected_axis(robot, left, found, pair))}, up "
            f"to sign), {number(math.degrees(relation[1]), places=0)} degrees apart, if the two "
            "sides are built as mirror images"), None, \
            Severity.WARNING if relation[1] >= TURNED else Severity.INFO


def _mirrored_limits(lower, upper):
    return -upper, -lower


@rule("U220", "mirror-limits", Severity.WARNING)
def mirror_limits(robot):
    """Two joints named as a left/right pair have limits that are not mirror images.

    Mirrored joints may have equal limits or negated and swapped ones (``[a, b]`` and
    ``[-b, -a]``); which one follows from their axes (U219): when the same value moves both
    sides as mirror images the limits are equal, when it moves them the same way they are
    negated. Limits of the other form mean an axis or a limit whose sign was flipped on one
    side only; limits of neither form, or a different effort or velocity, a number changed on
    one side. Within 1e-3 (and 1 % of the range). Mimic joints are not judged: a mimic joint
    goes where its source and multiplier take it (U216 checks that against its limits).

    A range whose stops are less than 10 % of it from the mirror image's, with effort and
    velocity agreeing, is a **note** saying "if the two sides are built as mirror images":
    the stops of two sides of one design differ that much (Nao's documented ankle and hip
    rolls, about a degree; Spot's hips, 0.05 rad), where every range judged a slip in the real
    sweep was 16 % of it or more away (a range negated once too often, one copied from
    another joint).

    Bad: ``l_sho_roll`` ``[-0.5, 1.7]`` and ``r_sho_roll`` ``[-0.5, 1.7]`` about the same
    axis (the right arm can only swing inwards)
    Good: ``r_sho_roll`` ``[-1.7, 0.5]``
    """
    for left, right, found, pair in _typed_pairs(robot):
        yield from _limit_findings(robot, left, right, found, pair)


def _limit_findings(robot, left, right, found, pair):
    """One finding per pair: every limit that differs, in one message; a note when only the
    range differs, by stops less than 10 % of it from the mirror image's (:data:`STOPS_APART`)."""
    if robot.child(left, "mimic") is not None or robot.child(right, "mimic") is not None:
        return  # a mimic joint goes where its source and multiplier take it, not its limits
    differences = []
    limit_a, limit_b = robot.child(left, "limit"), robot.child(right, "limit")
    for attribute in ("effort", "velocity"):
        a = attribute_number(limit_a, attribute) if limit_a is not None else None
        b = attribute_number(limit_b, attribute) if limit_b is not None else None
        if a is not None and b is not None and not _near(a, b, 1e-9, 0.01):
            slip = decimal_slip(a, b)
            differences.append(f"{attribute} {a:g} and {b:g}"
                               + (f" ({slip[2:]})" if slip else ""))
    ranged = _range_difference(robot, left, right, found, pair)
    near = ranged is not None and not differences and ranged[1] < STOPS_APART
    if ranged is not None:
        differences.insert(0, ranged[0])
    if differences:
        condition = f"{_CONDITION} (stops {number(100 * ranged[1], places=0)} % of the range " \
            "from the mirror image's, as side-specific stops can be)" if near else _CONDITION
        yield _located(robot, left, right), (
            f"joints '{left.get('name')}' and '{right.get('name')}' have limits that are not "
            f"mirror images: {'; '.join(differences)}{condition}"), None, \
            Severity.INFO if near else Severity.WARNING


def _range_difference(robot, left, right, found, pair) -> tuple[str, float] | None:
    """(what differs, how far): the ranges' difference said, and the farthest stop of the right
    range from the nearest mirror image of the left one the axes allow, over the larger span
    (1 when a range is empty against one that is not); None when they agree."""
    if left.get("type") == "continuous":
        return None
    a, b = _limits(left), _limits(right)
    readings = [relation for relation in _relations(robot, left, right, found, pair)
                if relation[1] <= AXIS_TOLERANCE]
    if a is None or b is None or not readings:
        return None
    span = max(a[1] - a[0], b[1] - b[0])
    equal = all(_near(x, y, LIMIT_TOLERANCE, 0.01, span) for x, y in zip(a, b))
    negated = all(_near(x, y, LIMIT_TOLERANCE, 0.01, span)
                  for x, y in zip(_mirrored_limits(*a), b))
    if any(equal if kind == "same" else negated for kind, _ in readings):
        return None
    apart = min(max(abs(x - y) for x, y in zip(a if kind == "same" else _mirrored_limits(*a), b))
                for kind, _ in readings)
    apart = min(1.0, apart / span) if span > 0 else 1.0
    kind = readings[0][0]
    text = f"range [{number(a[0], 4)}, {number(a[1], 4)}] and [{number(b[0], 4)}, {number(b[1], 4)}]"
    if (kind == "same" and negated or kind == "negated" and equal) and apart >= STOPS_APART:
        how = ("move both sides as mirror images for the same value, so the ranges should be "
               "equal" if kind == "same" else "move both sides the same way for the same "
               "value, so the ranges should be negated and swapped")
        return (f"{text} are {'negated' if negated else 'equal'}, but their axes {how}: an "
                "axis or a range's sign was flipped on one side only"), apart
    expected = a if kind == "same" else _mirrored_limits(*a)
    return (f"{text} (with these axes the right would be [{number(expected[0], 4)}, "
            f"{number(expected[1], 4)}])"), apart


@rule("U221", "mirror-inertial", Severity.WARNING)
def mirror_inertial(robot):
    """Two links named as a left/right pair differ in mass or principal moments of inertia.

    A part and its mirror image weigh the same and have the same principal moments, and so do
    two copies of one part (the same gripper on both arms): masses more than 5 % apart or
    principal moments more than 10 % apart (a tensor is rounded harder) point at a value
    copied from another part or typed on one side only. Centres of mass are not compared: a
    copied part's is not at its partner's mirror image, and both are right. A zero tensor on
    one side is U304's finding; links without an inertial on either side are U303's.

    A warning when one side's mass or a principal moment is 1.5 times the other's or more (every
    slip judged in the real sweep was: a value from another part, a decimal point, a placeholder
    tensor); a **note** saying "if the two sides are built as mirror images" below that, where
    the CAD parts of two sides of one design also differ (Nao's pelvis links, iCub's shoulders,
    HSR's fingers: up to 1.4 times, none a slip anyone could name from the files).

    Two masses of the same digits a power of ten apart (0.0070309794 and 0.070309794 kg, as
    ROBOTIS-OP's tibias) are said to be a decimal point slipped.

    Bad: ``l_thigh_link`` 0.119 kg and ``r_thigh_link`` 0.191 kg
    Good: both 0.119 kg
    """
    parents = parent_joints(robot)
    for left, right in link_pairs(robot):
        joints = parents.get(left), parents.get(right)
        if None not in joints and _in_line(robot, *joints):
            continue  # one below the other: a serial arm's L and R axes, not two sides
        a, b = declared_of(robot, robot.links[left]), declared_of(robot, robot.links[right])
        if a is None or b is None or not (a.mass > 0 or b.mass > 0):
            continue
        names = f"links '{left}' and '{right}'"
        moments_a = moments_of(robot, robot.links[left])
        moments_b = moments_of(robot, robot.links[right])
        largest, smallest = sorted((max(moments_a), max(moments_b)))[::-1]
        # a zero tensor on one side is U304's finding: its moments are not compared
        differing = [(x, y) for x, y in zip(moments_a, moments_b)
                     if abs(x - y) > INERTIA_TOLERANCE * largest] \
            if smallest > ZERO_SIDE * largest else []
        moments = (f"principal moments of inertia differ "
                   f"({', '.join(f'{number(m, 3)}' for m in moments_a)} and "
                   f"{', '.join(f'{number(m, 3)}' for m in moments_b)} kg m^2)")
        strong_moments = any(_ratio(x, y) >= SLIP_RATIO for x, y in differing)
        if not _near(a.mass, b.mass, 0.0, MASS_TOLERANCE):
            slip = decimal_slip(a.mass, b.mass)
            strong = bool(slip) or _ratio(a.mass, b.mass) >= SLIP_RATIO or strong_moments
            yield _inertial_place(robot, left, right), (
                f"{names}: masses differ ({a.mass:g} and {b.mass:g} kg, "
                f"{number(100 * abs(a.mass - b.mass) / max(a.mass, b.mass), places=0)} %)"
                + (f", {moments}" if strong_moments and not slip else "")
                + (slip or _condition(strong))), None, _severity(strong)
        elif differing:
            yield _inertial_place(robot, left, right), \
                f"{names}: {moments}{_condition(strong_moments)}", None, _severity(strong_moments)


def _ratio(a: float, b: float) -> float:
    """The larger of two values over the smaller (infinite when the smaller is not positive)."""
    small, large = sorted((a, b))
    return large / small if small > 0 else math.inf


def _condition(strong: bool) -> str:
    """U221's condition: said as it is for a difference of 1.5 times or more, and with the
    CAD's latitude below it (a note)."""
    return _CONDITION if strong else \
        f"{_CONDITION} (under {SLIP_RATIO:g} times apart, as two sides' CAD parts can be)"


def _severity(strong: bool) -> Severity:
    return Severity.WARNING if strong else Severity.INFO


def _inertial_place(robot, left: str, right: str):
    """Where U221 reports a pair: the later of the two links' inertials (looked for only when
    there is a finding: the index of a ``<robot>`` child is a walk over its siblings)."""
    return _located(robot, robot.links[left].find("inertial"), robot.links[right].find("inertial"))


def _servo_ids(robot) -> dict[str, tuple[int, object]]:
    """Joint -> (servo_id, where) from the robot's spec table, if it has one."""
    from urdftool.lint.rules.spec import spec_joints

    found = {}
    for joint, servo, where in spec_joints(robot):
        if isinstance(servo, int) and not isinstance(servo, bool):
            found[joint] = (servo, where)
    return found


@rule("U222", "mirror-servo-ids", Severity.WARNING)
def mirror_servo_ids(robot):
    """A left/right pair's servo IDs in the spec table break the pattern the other pairs follow.

    Servo buses number mirrored joints by a rule (DARwIn-OP: right = left - 1, so left IDs
    are even); a pair whose IDs differ by another amount was given its partner's ID, or the
    sides' IDs were swapped, and the servo on the bus moves the other leg. Judged when at least
    three pairs are in the spec and most of them agree on the difference.

    Bad: ``l_knee: {servo_id: 13}``, ``r_knee: {servo_id: 14}`` where every other pair has
    right = left - 1
    Good: ``l_knee: {servo_id: 14}``, ``r_knee: {servo_id: 13}``
    """
    ids = _servo_ids(robot)
    pairs = [(left, right) for left, right in joint_pairs(robot) if left in ids and right in ids]
    if len(pairs) < 3:
        return
    differences = [ids[left][0] - ids[right][0] for left, right in pairs]
    usual = max(set(differences), key=differences.count)
    if differences.count(usual) * 2 <= len(pairs):
        return
    for (left, right), difference in zip(pairs, differences):
        if difference != usual:
            yield ids[right][1], (
                f"servo IDs of '{left}' ({ids[left][0]}) and '{right}' ({ids[right][0]}) differ "
                f"by {difference}, where {differences.count(usual)} of the {len(pairs)} left/right "
                f"pairs have left - right = {usual}: a swapped or copied ID")
