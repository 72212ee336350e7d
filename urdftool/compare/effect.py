"""What a change does to the robot: frames that moved, mass and centre of mass, reach,
collisions, computed on both descriptions at the same joint values.

The configurations are the zero one (0, or mid-range where 0 is outside the limits) and
``samples`` drawn within the limits common to both (the intersection of each joint's ranges),
over the joints both have (renamed ones matched); a joint only one side has stays at its
default there. Frames are compared in each side's root frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from urdftool.compare.structure import Renames


@dataclass
class FrameEffect:
    """How far a link's frame moved: at the zero configuration and at most over the samples
    (position in [m], rotation in [rad]) and where (joint values by new name); ``joints``:
    the variables that move the frame (the joints from the root to it, root first), the only
    values of ``at`` that change how far it moved."""

    link: str
    zero_position: float
    zero_rotation: float
    max_position: float
    max_rotation: float
    at: dict[str, float]
    joints: list[str] = field(default_factory=list)


@dataclass
class ChainEffect:
    """The reach of a chain (the largest distance from ``base`` to ``tip`` over the
    configurations, and at zero) in [m], old and new."""

    base: str
    tip: str
    old_reach: float
    new_reach: float
    old_zero: float
    new_zero: float


@dataclass
class CollisionEffect:
    """A link pair (new names) and in how many of the sampled configurations it collides."""

    link1: str
    link2: str
    old_count: int
    new_count: int


@dataclass
class Effects:
    """What a change does: frames moved, mass and centre of mass, reach, over ``samples``."""

    samples: int
    frames: list[FrameEffect] = field(default_factory=list)
    old_mass: float = 0.0
    new_mass: float = 0.0
    old_com: tuple = (0.0, 0.0, 0.0)
    new_com: tuple = (0.0, 0.0, 0.0)
    mass_unknown: str | None = None  # why the masses are not compared (an inertial unusable)
    chains: list[ChainEffect] = field(default_factory=list)
    collisions: list[CollisionEffect] = field(default_factory=list)
    worst: dict[str, float] = field(default_factory=dict)
    worst_old: dict[str, float] = field(default_factory=dict)  # the same row, the old names
    warnings: list[str] = field(default_factory=list)

    @property
    def moving(self) -> list[str]:
        """The variables that move the frames that moved, in the order the frames name them
        (the values of ``worst`` that matter)."""
        return list(dict.fromkeys(j for frame in self.frames for j in frame.joints))


@dataclass
class _Side:
    """One side of a comparison: its model and its joint values."""

    model: object
    values: object  # [rows, variables]


def _rows(old_model, new_model, renames: Renames, samples: int, seed: int):
    """Configurations of both sides for the same joint values: (old, new) arrays and the
    new side's values by name per row."""
    import numpy as np

    from urdftool.kinematics import configuration as config

    old_by_name = {renames.joint(v.joint) + v.name[len(v.joint):]: i
                   for i, v in enumerate(old_model.variables)}
    common = []
    for i, variable in enumerate(new_model.variables):
        j = old_by_name.get(variable.name)
        if j is None:
            continue
        other = old_model.variables[j]
        lower, upper = max(variable.lower, other.lower), min(variable.upper, other.upper)
        if lower <= upper:
            common.append((i, j, config.Variable(variable.name, variable.joint, variable.kind,
                                                 lower, upper)))
    drawn = config.random([v for _, _, v in common], samples, seed).values
    zero = config.defaults([v for _, _, v in common])[None]
    shared = np.concatenate([zero, drawn])
    new = np.tile(config.defaults(new_model.variables), (len(shared), 1))
    old = np.tile(config.defaults(old_model.variables), (len(shared), 1))
    for column, (i, j, _) in enumerate(common):
        new[:, i] = shared[:, column]
        old[:, j] = shared[:, column]
    return old, new


def _angle(old_rotations, new_rotations):
    """The angle [rad] of the rotation between each pair, accurate near 0 (atan2 of the sine
    and cosine parts, where arccos of the trace alone loses half the digits)."""
    import numpy as np

    relative = np.einsum("...ji,...jk->...ik", old_rotations, new_rotations)
    cosine = np.trace(relative, axis1=-2, axis2=-1) - 1
    sine = np.linalg.norm(np.stack([relative[..., 2, 1] - relative[..., 1, 2],
                                    relative[..., 0, 2] - relative[..., 2, 0],
                                    relative[..., 1, 0] - relative[..., 0, 1]], -1), axis=-1)
    return np.arctan2(sine, cosine)


def effects(old, new, renames: Renames, samples: int = 200, seed: int = 0,
            chains: list[tuple[str, str]] = (), tolerance: float = 1e-9,
            collisions: bool = True) -> Effects:
    """The effects of going from robot ``old`` to robot ``new``; ``chains`` are (base, tip)
    link names in ``new``. FKError when a side cannot be built into a kinematic model."""
    import numpy as np

    from urdftool.kinematics.fk import KinematicModel

    old_model, new_model = KinematicModel(old), KinematicModel(new)
    old_values, new_values = _rows(old_model, new_model, renames, samples, seed)
    result = Effects(samples)
    back = {new_name: old_name for old_name, new_name in renames.links.items()}
    common = [link for link in new_model.links if back.get(link, link) in old_model.links]
    old_index = [old_model.links.index(back.get(link, link)) for link in common]
    new_index = [new_model.links.index(link) for link in common]
    old_poses = old_model.link_poses(old_values, old_index)
    new_poses = new_model.link_poses(new_values, new_index)
    # rounded to 1 nm and 1 nrad, so that equal effects tie and the first (zero) row wins
    moved = np.round(np.linalg.norm(old_poses[..., :3, 3] - new_poses[..., :3, 3], axis=-1), 9)
    turned = np.round(_angle(old_poses[..., :3, :3], new_poses[..., :3, :3]), 9)
    names = [v.name for v in new_model.variables]
    for column, link in enumerate(common):
        row = int(np.argmax(moved[:, column] + turned[:, column] * 1e-3))
        if moved[:, column].max() > tolerance or turned[:, column].max() > tolerance:
            result.frames.append(FrameEffect(
                link, float(moved[0, column]), float(turned[0, column]),
                float(moved[:, column].max()), float(turned[:, column].max()),
                {name: float(x) for name, x in zip(names, new_values[row])},
                new_model.variables_moving(link)))
    result.frames.sort(key=lambda f: (-f.max_position, -f.max_rotation, f.link))
    if len(common):
        worst = int(np.argmax(moved.max(axis=1) + turned.max(axis=1) * 1e-3))
        result.worst = {name: float(x) for name, x in zip(names, new_values[worst])}
        result.worst_old = {v.name: float(x) for v, x in zip(old_model.variables,
                                                             old_values[worst])}
    for side, robot, model, values in (("old", old, old_model, old_values),
                                       ("new", new, new_model, new_values)):
        mass, com = _mass(robot, model, values[:1])
        setattr(result, f"{side}_mass", mass)
        setattr(result, f"{side}_com", com)
        unusable = _unusable_inertial(robot)
        if unusable and result.mass_unknown is None:
            result.mass_unknown = f"{side}: {unusable}"
    for base, tip in chains:  # their names checked by compare.diff.diff
        reaches = []
        for model, values, (b, t) in ((old_model, old_values, (back.get(base, base),
                                                              back.get(tip, tip))),
                                      (new_model, new_values, (base, tip))):
            poses = model.link_poses(values, [model.links.index(b), model.links.index(t)])
            distance = np.linalg.norm(poses[:, 1, :3, 3] - poses[:, 0, :3, 3], axis=-1)
            reaches.append((float(distance.max()), float(distance[0])))
        result.chains.append(ChainEffect(base, tip, reaches[0][0], reaches[1][0],
                                         reaches[0][1], reaches[1][1]))
    if collisions:
        from urdftool.errors import OverLimit

        try:
            result.collisions, problems = _collisions(old, new, old_values, new_values, back)
        except OverLimit as error:  # the pairs of a side are over the limit: not compared
            result.collisions, problems = [], [f"collisions not compared: {error}"]
        result.warnings += problems
    return result


def _mass(robot, model, values) -> tuple[float, tuple]:
    """Total declared mass [kg] and the centre of mass [m] in the root frame at ``values``."""
    import numpy as np

    from urdftool.physics.mass import declared

    moment = np.zeros(3)
    indices = {name: i for i, name in enumerate(model.links)}
    bodies = [(indices[name], declared(link)) for name, link in robot.links.items()
              if name in indices]
    bodies = [(i, body) for i, body in bodies if body is not None and math.isfinite(body.mass)]
    if not bodies:
        return 0.0, (0.0, 0.0, 0.0)
    poses = model.link_poses(values, [i for i, _ in bodies])[0]
    for pose, (_, body) in zip(poses, bodies):
        moment += body.mass * (pose[:3, :3] @ np.array(body.com) + pose[:3, 3])
    total = math.fsum(body.mass for _, body in bodies)  # ten links of 0.1 kg weigh 1 kg, exactly
    com = moment / total if total else np.zeros(3)
    return float(total), tuple(float(x) for x in com)


def _unusable_inertial(robot) -> str | None:
    """The first link whose ``<inertial>`` gives no mass to count (malformed, not finite, or
    past :mod:`urdftool.physics.mass`'s bounds), in words; None when every one counts: a mass
    of 1e308 was left out of the total, which read "total mass 3 -> 0 kg (-100 %)"."""
    from urdftool.physics.mass import declared, problem

    for name, link in robot.links.items():
        if link.find("inertial") is not None:
            body = declared(link)
            if body is None or not math.isfinite(body.mass):
                return (f"link '{name}': <inertial>"
                        f"{problem(link) or ' is malformed or not finite'}")
    return None


def _collisions(old, new, old_values, new_values, back: dict):
    """Pairs (new names) whose collision count over the samples went from 0 to some or from
    some to 0; adjacent pairs are left out. Also the collision geometry left out, per side.

    A pair both of whose links keep their collision parts and, at every sample, their pose to
    the bit collides alike on both sides: it cannot change, and FCL is not asked about it (a
    change to one joint asks only about the pairs that joint moves; a change of mass, none)."""
    import numpy as np

    from urdftool.collision.matrix import Scene
    from urdftool.collision.pairs import PairChecker

    scenes = (Scene(old, 0.0), Scene(new, 0.0))
    sides: dict[str, list] = {}  # a problem's message -> (side, location) of each side with it
    for label, scene in zip(("old", "new"), scenes):
        for problem in scene.geometry.problems:
            sides.setdefault(problem.message, []).append((label, problem.location))
    # both sides' (a mesh not found in either version) said once, where the new side has it
    problems = [f"{' and '.join(label for label, _ in found)}: {found[-1][1]}: {message}"
                for message, found in sides.items()]
    poses = (scenes[0].poses(old_values), scenes[1].poses(new_values))
    forward = {old_name: new_name for new_name, old_name in back.items()}
    old_column = {name: i for i, name in enumerate(scenes[0].links)}
    kept = set()  # new names of links whose parts and poses are the old link's, to the bit
    for column, name in enumerate(scenes[1].links):
        before = back.get(name, name)
        if before in old_column and _same_parts(scenes[0].geometry.parts[before],
                                                scenes[1].geometry.parts[name]) \
                and np.array_equal(poses[0][:, old_column[before]], poses[1][:, column]):
            kept.add(name)
    counts = []
    for scene, names, values in zip(scenes, (forward, {}), poses):
        asked = [(a, b) for a, b in scene.pairs
                 if not {names.get(a, a), names.get(b, b)} <= kept]
        tally = PairChecker(scene.geometry, scene.links, asked, 0.0).tally(values,
                                                                          distances=False)
        counts.append(({pair: int(hits) for pair, hits in zip(asked, tally.collisions)},
                       scene.adjacent))
    (old_counts, old_adjacent), (new_counts, new_adjacent) = counts
    renamed = {}
    for (a, b), hits in old_counts.items():
        one, two = sorted((forward.get(a, a), forward.get(b, b)), key=str.encode)
        renamed[(one, two)] = hits
    adjacent = {tuple(sorted((forward.get(a, a), forward.get(b, b)), key=str.encode))
                for a, b in old_adjacent} | new_adjacent
    found = []
    for pair, hits in new_counts.items():
        if pair in adjacent or pair not in renamed:
            continue
        before = renamed[pair]
        if (before == 0) != (hits == 0):
            found.append(CollisionEffect(*pair, before, hits))
    return found, problems


def _same_parts(old_parts, new_parts) -> bool:
    """The two lists of collision parts are the same geometry at the same origins."""
    import numpy as np

    return len(old_parts) == len(new_parts) and all(
        a.kind == b.kind and a.shape == b.shape and np.array_equal(a.origin, b.origin)
        for a, b in zip(old_parts, new_parts))
