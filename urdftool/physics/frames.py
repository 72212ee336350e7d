"""Where every link and joint is at the zero pose, in pure Python (:mod:`urdftool.physics.mat3`).

The rules that judge conventions (a camera's optical frame, ``base_footprint`` on the ground,
wheels touching it) and left/right symmetry read link frames at the zero pose; ``urdftool
check`` must start fast, so this is tuples, not numpy or Pinocchio. Every joint is at 0 (mimic
joints too: their offset is a runtime choice of the driver). Frames are in the frame of the
root of the tree they belong to (a robot with several roots has several trees, each rooted at
the identity); a joint that names a missing link, or a link in a cycle, has no frame.
"""

from __future__ import annotations

from urdftool.description.values import axis_xyz, origin
from urdftool.numbers import unit
from urdftool.physics import mat3

Frame = tuple[mat3.Vector, mat3.Matrix]  # position [m], rotation, in the root frame
_ROOT: Frame = ((0.0, 0.0, 0.0), mat3.IDENTITY)


def link_frames(robot) -> dict[str, Frame]:
    """Link name -> (position, rotation) of its frame at the zero pose, once per robot."""
    return robot.memo(_walk, lambda: _walk(robot))[0]


def joint_frames(robot) -> dict[str, Frame]:
    """Joint name -> (position, rotation) of its frame (its child link's) at the zero pose."""
    return robot.memo(_walk, lambda: _walk(robot))[1]


def parent_joints(robot) -> dict[str, object]:
    """Child link name -> the joint element whose child it is (the first, when several)."""
    def build():
        found = {}
        for joint, ends in robot.ends().items():
            child = ends["child"][1]
            if child is not None and child not in found:
                found[child] = joint
        return found

    return robot.memo(parent_joints, build)


def child_joints(robot) -> dict[str, list]:
    """Parent link name -> the joint elements that hang from it, in document order."""
    def build():
        found: dict[str, list] = {}
        for joint, ends in robot.ends().items():
            parent = ends["parent"][1]
            if parent is not None:
                found.setdefault(parent, []).append(joint)
        return found

    return robot.memo(child_joints, build)


def _walk(robot) -> tuple[dict[str, Frame], dict[str, Frame]]:
    parents = parent_joints(robot)
    children = child_joints(robot)
    links: dict[str, Frame] = {}
    joints: dict[str, Frame] = {}
    roots = [name for name in robot.links if name not in parents]
    pending = [(name, _ROOT) for name in roots]
    while pending:
        name, frame = pending.pop()
        if name in links:
            continue
        links[name] = frame
        position, rotation = frame
        for joint in children.get(name, ()):
            child = robot.ends()[joint]["child"][1]
            if child is None or child in links or parents.get(child) is not joint:
                continue
            xyz, turn = mat3.placement(origin(joint))  # a malformed part counts as 0
            placed = (mat3.add(position, mat3.apply(rotation, xyz)), mat3.multiply(rotation, turn))
            joints.setdefault(joint.get("name"), placed)
            pending.append((child, placed))
    return links, joints


def axis(joint) -> mat3.Vector | None:
    """A joint's unit axis in its own frame (:func:`~urdftool.description.values.axis_xyz`:
    ``1 0 0`` when absent), None when zero or malformed."""
    values = axis_xyz(joint)
    return unit(values) if values else None  # scaled first: 1e308 1e308 1e308 has a direction


def world_axis(robot, joint) -> mat3.Vector | None:
    """A joint's unit axis in the root frame at the zero pose, or None."""
    local = axis(joint)
    frame = joint_frames(robot).get(joint.get("name"))
    if local is None or frame is None:
        return None
    return mat3.apply(frame[1], local)


def placed(frame: Frame, point) -> mat3.Vector:
    """A point of a link's frame in the root frame."""
    return mat3.add(frame[0], mat3.apply(frame[1], point))


def relative(base: Frame, frame: Frame) -> Frame:
    """``frame`` expressed in ``base``: (position, rotation) of base^-1 * frame."""
    back = mat3.transpose(base[1])
    offset = tuple(a - b for a, b in zip(frame[0], base[0]))
    return mat3.apply(back, offset), mat3.multiply(back, frame[1])
