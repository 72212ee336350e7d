"""Link poses for many configurations at once: forward kinematics vectorised over samples.

Revolute, continuous and prismatic joints move; fixed joints do not; floating and planar joints
are held at their origin (a self-collision matrix does not depend on where the base is). Mimic
joints follow their source joint.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..rules._values import parse_numbers
from .geometry import origin_matrix

MOVING = ("revolute", "continuous", "prismatic")


@dataclass
class Chain:
    """The kinematic tree in an order where each parent comes before its children.

    links: link names, root first; parents[i]: index of link i's parent link (-1 for the root)
    origins: (L, 4, 4) joint origin of the joint into link i
    axes: (L, 3) unit joint axes; kinds: joint type into link i ('' for the root)
    source, multiplier, offset: the joint value of link i's joint is
        multiplier * q[source] + offset (source -1: the joint does not move)
    joints: actuated joint names, with lower and upper bounds in [rad] or [m]
    """

    links: list[str]
    parents: np.ndarray
    origins: np.ndarray
    axes: np.ndarray
    kinds: list[str]
    source: np.ndarray
    multiplier: np.ndarray
    offset: np.ndarray
    joints: list[str]
    lower: np.ndarray
    upper: np.ndarray
    joint_of_link: dict

    def default(self) -> np.ndarray:
        """MoveIt's default state: 0 where the limits allow it, else the middle of the range."""
        inside = (self.lower <= 0) & (self.upper >= 0)
        return np.where(inside, 0.0, (self.lower + self.upper) / 2)

    def sample(self, rng, count: int) -> np.ndarray:
        """``count`` configurations drawn uniformly within the joint limits, (count, J)."""
        return rng.uniform(self.lower, self.upper, size=(count, len(self.joints)))

    def poses(self, q: np.ndarray) -> np.ndarray:
        """World pose of every link for each configuration: (N, J) -> (N, L, 4, 4)."""
        q = np.atleast_2d(np.asarray(q, dtype=float))
        count = len(q)
        poses = np.empty((count, len(self.links), 4, 4))
        poses[:, 0] = np.eye(4)
        for index in range(1, len(self.links)):
            local = np.broadcast_to(self.origins[index], (count, 4, 4))
            if self.source[index] >= 0:
                value = self.multiplier[index] * q[:, self.source[index]] + self.offset[index]
                local = local @ _motion(self.kinds[index], self.axes[index], value)
            poses[:, index] = poses[:, self.parents[index]] @ local
        return poses


def _motion(kind: str, axis: np.ndarray, value: np.ndarray) -> np.ndarray:
    motion = np.zeros((len(value), 4, 4))
    motion[:, 3, 3] = 1.0
    if kind == "prismatic":
        motion[:, :3, :3] = np.eye(3)
        motion[:, :3, 3] = value[:, None] * axis
        return motion
    cross = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    sin, cos = np.sin(value)[:, None, None], np.cos(value)[:, None, None]
    motion[:, :3, :3] = np.eye(3) + sin * cross + (1 - cos) * (cross @ cross)
    return motion


class ChainError(Exception):
    """The tree cannot be walked (no single root, a cycle); check reports why."""


def build(robot) -> Chain:
    joints = {}
    for joint in robot.children("joint"):
        parent, child = joint.find("parent"), joint.find("child")
        if parent is None or child is None or child.get("link") in joints:
            continue
        joints[child.get("link")] = joint
    roots = [name for name in robot.links if name not in joints]
    if len(roots) != 1:
        raise ChainError(f"the tree has {len(roots)} root links ({', '.join(roots) or 'none'});"
                         " run `urdftool check` for the cause")
    children: dict[str, list[str]] = {}
    for child, joint in joints.items():
        children.setdefault(joint.find("parent").get("link"), []).append(child)
    order, stack = [], [roots[0]]
    while stack:
        link = stack.pop()
        order.append(link)
        stack.extend(reversed(children.get(link, [])))
    order = [name for name in order if name in robot.links]
    index = {name: i for i, name in enumerate(order)}
    actuated = [joints[name] for name in order[1:]
                if joints[name].get("type") in MOVING and joints[name].find("mimic") is None]
    names = [joint.get("name") for joint in actuated]
    lower, upper = zip(*(_bounds(joint) for joint in actuated)) if actuated else ((), ())
    count = len(order)
    chain = Chain(order, np.full(count, -1), np.tile(np.eye(4), (count, 1, 1)),
                  np.zeros((count, 3)), [""] * count, np.full(count, -1), np.ones(count),
                  np.zeros(count), names, np.array(lower, dtype=float),
                  np.array(upper, dtype=float), {})
    by_name = {joint.get("name"): joint for joint in joints.values()}
    for i, link in enumerate(order[1:], start=1):
        joint = joints[link]
        chain.joint_of_link[link] = joint.get("name")
        chain.parents[i] = index[joint.find("parent").get("link")]
        chain.origins[i] = origin_matrix(joint)
        chain.kinds[i] = joint.get("type", "")
        if chain.kinds[i] not in MOVING:
            continue
        axis = joint.find("axis")
        values, _ = parse_numbers(axis.get("xyz") if axis is not None else "1 0 0", 3)
        norm = np.linalg.norm(values) if values else 0.0
        if not norm or not np.isfinite(norm):
            continue
        chain.axes[i] = np.array(values) / norm
        source, multiplier, offset = _source(joint, by_name, names)
        chain.source[i], chain.multiplier[i], chain.offset[i] = source, multiplier, offset
    return chain


def _bounds(joint) -> tuple[float, float]:
    limit = joint.find("limit")
    if joint.get("type") == "continuous" or limit is None:
        return -np.pi, np.pi
    lower, _ = parse_numbers(limit.get("lower", "0"), 1)
    upper, _ = parse_numbers(limit.get("upper", "0"), 1)
    if not lower or not upper or not np.isfinite(lower[0] + upper[0]) or lower[0] > upper[0]:
        return 0.0, 0.0
    return lower[0], upper[0]


def _source(joint, by_name, names) -> tuple[int, float, float]:
    """(index of the actuated joint driving ``joint``, multiplier, offset), following mimics."""
    multiplier, offset, seen = 1.0, 0.0, set()
    while joint is not None and joint.find("mimic") is not None:
        if joint.get("name") in seen:
            return -1, 1.0, 0.0
        seen.add(joint.get("name"))
        mimic = joint.find("mimic")
        factor, _ = parse_numbers(mimic.get("multiplier", "1"), 1)
        shift, _ = parse_numbers(mimic.get("offset", "0"), 1)
        factor, shift = (factor or [1.0])[0], (shift or [0.0])[0]
        multiplier, offset = multiplier * factor, offset + multiplier * shift
        joint = by_name.get(mimic.get("joint"))
    if joint is None or joint.get("name") not in names:
        return -1, 1.0, 0.0
    return names.index(joint.get("name")), multiplier, offset
