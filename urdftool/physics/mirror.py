"""Left/right mirror pairs of a robot: which joints and links are named as each other's mirror
image, and the plane they mirror about.

Names: the side words are swapped all at once (``l_gripper_r_finger_joint`` mirrors to
``r_gripper_l_finger_joint``: the mirror image of the left gripper's right finger is the right
gripper's left finger), else the first alone (``RLEG_HIP_R``, whose last ``R`` is a roll, pairs
with ``LLEG_HIP_R``); a later word alone names a part within one side (two fingers of a hand),
not the robot's left and right. Side words: ``l``/``r``, ``left``/``right`` in any case, a capital
``L``/``R`` starting a capitalised word (``LShoulderPitch``, ``LLEG``), and the two-letter leg
codes (``lf``/``rf``, ``fl``/``fr``, ``lh``/``rh``, ``hl``/``hr``, ``bl``/``br``). A pair
counts only when both names exist.

The plane: from the pairs themselves (not assumed to be y = 0): each pair of joint positions at
the zero pose (root frame) gives a candidate, the plane halfway between them; the plane is the
candidate most pairs agree with (a consensus: one limb of another length does not tilt it).
Its normal points to the left side. Pure Python (:mod:`urdftool.physics.mat3`).
"""

from __future__ import annotations

import functools
import math
import re
from dataclasses import dataclass

from urdftool.physics import mat3
from urdftool.physics.frames import joint_frames

# (pattern of one word, its mirror) by the word's exact spelling
_SWAPS = {"l": "r", "r": "l", "left": "right", "right": "left", "L": "R", "R": "L",
          "Left": "Right", "Right": "Left", "LEFT": "RIGHT", "RIGHT": "LEFT",
          "lf": "rf", "rf": "lf", "lh": "rh", "rh": "lh", "fl": "fr", "fr": "fl",
          "hl": "hr", "hr": "hl", "bl": "br", "br": "bl", "rl": "rr", "rr": "rl",
          "LF": "RF", "RF": "LF", "LH": "RH", "RH": "LH", "FL": "FR", "FR": "FL",
          "HL": "HR", "HR": "HL", "BL": "BR", "BR": "BL"}
# A word: letters between separators (_ - / . digits), or a capitalised part of camel case; a
# single capital L or R starting a capitalised word (LShoulder, LLEG) is a word of its own.
_SIDE_LETTERS = frozenset("lrLR")  # one of these is in every side word (_SWAPS)
_WORD = re.compile(r"(?<![A-Za-z])[LR](?=[A-Z])|[A-Z]?[a-z]+|[A-Z]+(?![a-z])")


def _side_words(name: str, strong: bool = False) -> list[tuple[int, int, str]]:
    """(start, end, mirror) of each side word in ``name``; ``strong``: not a capital L or R
    that starts a word in capitals (``LLEG`` is a left leg, but ``LOW`` is not a right 'OW')."""
    words, weak = _marked_side_words(name)
    return [word for word in words if word not in weak] if strong and weak else words


@functools.lru_cache(maxsize=4096)
def _marked_side_words(name: str) -> tuple[list[tuple[int, int, str]], list]:
    """(every side word of ``name`` as :func:`_side_words` gives them, the weak ones among
    them): one pass of the pattern for both lists; once per name (the pairs of a robot ask
    each name two or three times, the variants of one robot in a run the same names again).
    The lists are shared: read them, never change them."""
    found, weak = [], []
    if _SIDE_LETTERS.isdisjoint(name):  # (every side word holds one: most joint names none)
        return found, weak
    for match in _WORD.finditer(name):
        word = match.group(0)
        if word in _SWAPS:
            end = match.end()
            found.append((match.start(), end, _SWAPS[word]))
            if len(word) == 1 and word in "LR":
                after = name[end:end + 2]
                if after[:1].isupper() and not after[1:2].islower():
                    weak.append(found[-1])
    return found, weak


def _replaced(name: str, words) -> str:
    out, last = [], 0
    for start, end, mirror in words:
        out.append(name[last:start])
        out.append(mirror)
        last = end
    out.append(name[last:])
    return "".join(out)


def mirror_names(name: str) -> list[str]:
    """The names ``name`` may mirror to: every side word swapped, then each one alone."""
    words = _side_words(name)
    if not words:
        return []
    candidates = [_replaced(name, words)]
    if len(words) > 1:
        candidates.extend(_replaced(name, [word]) for word in words)
    return [c for c in candidates if c != name]


def partner_names(name: str) -> list[str]:
    """The names ``name`` is paired with: every side word swapped, else the first one alone
    (the side of the robot; a later word alone names a part within one side, such as a
    finger of one hand, or is a label such as the SVH hand's little and ring fingers'); the
    same again without the capital L or R starting a word in capitals (``MP_ARM_LOW_L``)."""
    words, weak = _marked_side_words(name)
    if not words:
        return []
    strong = [word for word in words if word not in weak] if weak else words
    candidates, tried = [], []
    for chosen in (words, strong, words[:1], strong[:1]):
        if chosen and chosen not in tried:  # (the same words give the same candidate)
            tried.append(chosen)
            candidate = _replaced(name, chosen)
            if candidate != name and candidate not in candidates:
                candidates.append(candidate)
    return candidates


def _is_left(name: str, mirror: str) -> bool:
    """Whether ``name`` is the left one of the pair (its first differing side word is left)."""
    for (start, end, _), (other_start, other_end, _) in zip(_side_words(name), _side_words(mirror)):
        word = name[start:end]
        if word != mirror[other_start:other_end]:
            return word.lower().startswith("l") or word.lower() in ("fl", "hl", "bl", "rl")
    return name < mirror


# Every character of a side word or of its mirror: a name and each name it may pair with are
# one text without them (a side word swapped is one run of these replaced by another)
_SIDE_CHARACTERS = str.maketrans("", "", "".join(set("".join(_SWAPS) + "".join(_SWAPS.values()))))


def pairs(names) -> list[tuple[str, str]]:
    """(left, right) name pairs among ``names`` (each name in one pair at most), in the order
    of the left names. Only a name whose text without side characters another name shares is
    asked for its partners (a 10,000-link robot of names ``l0`` ... ``l9999`` asks none)."""
    known = set(names)
    rests = [name.translate(_SIDE_CHARACTERS) for name in names]
    shared: dict[str, bool] = {}
    for rest in rests:
        shared[rest] = rest in shared
    found, used = [], set()
    for name, rest in zip(names, rests):
        if not shared[rest] or name in used:
            continue
        for mirror in partner_names(name):
            if mirror in known and mirror not in used:
                left, right = (name, mirror) if _is_left(name, mirror) else (mirror, name)
                found.append((left, right))
                used.update((name, mirror))
                break
    order = {name: index for index, name in enumerate(names)}
    return sorted(found, key=lambda pair: order[pair[0]])


def joint_pairs(robot) -> list[tuple[str, str]]:
    """(left, right) joint name pairs, once per robot."""
    return robot.memo(joint_pairs, lambda: pairs(list(robot.joints)))


def link_pairs(robot) -> list[tuple[str, str]]:
    """(left, right) link name pairs, once per robot."""
    return robot.memo(link_pairs, lambda: pairs(list(robot.links)))


SEPARATED = 1e-3  # [m]: pairs closer than this say nothing about the plane


@dataclass(frozen=True)
class Plane:
    """The mirror plane: points x with n . x = offset; ``normal`` points to the left side."""

    normal: mat3.Vector
    offset: float

    def reflect(self, p) -> mat3.Vector:
        """The mirror image of a point."""
        distance = mat3.dot(self.normal, p) - self.offset
        return tuple(v - 2 * distance * n for v, n in zip(p, self.normal))

    def reflect_vector(self, v) -> mat3.Vector:
        """The mirror image of a direction (a polar vector)."""
        along = mat3.dot(self.normal, v)
        return tuple(a - 2 * along * n for a, n in zip(v, self.normal))


def plane(robot) -> Plane | None:
    """The plane the joint pairs mirror about at the zero pose, None with no separated pair."""
    return robot.memo(plane, lambda: _fit(robot))


def _fit(robot) -> Plane | None:
    if not joint_pairs(robot):
        return None
    frames = joint_frames(robot)
    return fit([(frames[left][0], frames[right][0]) for left, right in joint_pairs(robot)
                if left in frames and right in frames])


def fit(points, tolerance=(0.002, 0.01)) -> Plane | None:
    """The plane mirroring most left points of ``points`` ((left, right) pairs) onto their
    right ones: of the planes halfway between each pair, the one the most pairs agree with
    (within ``tolerance``: [m] plus a fraction of the distance from the plane), the earliest
    pair's on a tie (pairs nearer the root come first). None when no pair is separated."""
    candidates = []
    for a, b in points:
        step = tuple(x - y for x, y in zip(a, b))
        length = math.sqrt(mat3.dot(step, step))
        if length > SEPARATED:
            normal = tuple(v / length for v in step)
            middle = tuple((x + y) / 2 for x, y in zip(a, b))
            candidates.append(Plane(normal, mat3.dot(normal, middle)))
    best, score = None, -1
    points = [(a, b) for a, b in points]
    near, relative = tolerance
    for candidate in dict.fromkeys(candidates):  # (a plane met again gets the same votes, and
        # the earlier one wins a tie: each counted once; symmetric pairs give the same bits)
        # Plane.reflect inlined (the same operations, the same bits): a pair's vote for each
        # candidate is the inner loop of a robot's symmetry rules
        (nx, ny, nz), offset = candidate.normal, candidate.offset
        agreeing = 0
        for (ax, ay, az), b in points:
            distance = nx * ax + ny * ay + nz * az - offset
            twice = 2 * distance
            if math.dist((ax - twice * nx, ay - twice * ny, az - twice * nz), b) <= \
                    near + relative * abs(distance):
                agreeing += 1
        if agreeing > score:
            best, score = candidate, agreeing
    return best
