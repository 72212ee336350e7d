"""Forward kinematics of a URDF through a Pinocchio model, vectorised over configurations.

Pinocchio parses the URDF (joint placements, axes, which links hang off which joint, fixed joints
merged into frames). The poses are then computed with numpy for all configurations at once: a
``--q-file`` of 10,000 rows costs one batched matrix product per joint rather than 10,000 Python
calls. Mimic joints are expanded here (value = multiplier * mimicked + offset); Pinocchio only sees
ordinary joints. ``pinocchio_q`` gives Pinocchio's own configuration vectors for cross-checks.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from urdftool.errors import FKError, UnknownLink
from urdftool.kinematics import transforms
from urdftool.kinematics.configuration import (FLOATING_COORDINATES, PLANAR_COORDINATES, Configurations, MimicError,
                            Variable, mimic_source, mimics_of, variables_of)

FLOATING_ROOT = "root_joint"


@dataclass
class _Joint:
    """One Pinocchio joint: ``kind`` revolute/prismatic/floating/planar/fixed (the universe)."""

    name: str
    kind: str
    parent: int
    placement: np.ndarray
    axis: np.ndarray | None = None
    # revolute/prismatic: (column, multiplier, offset); floating/planar: coordinate columns
    source: tuple = ()
    idx_q: int = -1
    unbounded: bool = False

    def value(self, values: np.ndarray) -> np.ndarray:
        """A one-variable joint's value [rad or m] in each row of ``values`` (mimics expanded)."""
        column, multiplier, offset = self.source
        return multiplier * values[:, column] + offset

    @cached_property
    def terms(self) -> tuple[np.ndarray, np.ndarray]:
        """For revolute joints (P K, P K^2) with K the axis' cross-product matrix, as 4x4 blocks;
        for prismatic joints (P u in the translation column, zeros)."""
        first, second = np.zeros((4, 4)), np.zeros((4, 4))
        rotation = self.placement[:3, :3]
        x, y, z = self.axis
        if self.kind == "prismatic":
            first[:3, 3] = rotation @ self.axis
        else:
            cross = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
            first[:3, :3] = rotation @ cross
            second[:3, :3] = rotation @ cross @ cross
        return first, second

    @cached_property
    def stacked(self) -> np.ndarray:
        """``[3, 16]``: the placement and the two terms, flattened, for one BLAS product."""
        return np.stack([self.placement, *self.terms]).reshape(3, 16)


@dataclass
class FKResult:
    """Poses ``matrices[rows, frames, 4, 4]`` of ``frames`` relative to ``base``."""

    base: str
    frames: list[str]
    matrices: np.ndarray
    warnings: list[str] = field(default_factory=list)


class KinematicModel:
    """A robot's kinematics: its variables, its links, and poses for many configurations."""

    def __init__(self, robot, floating: bool = False):
        import pinocchio

        from urdftool.kinematics.native import build_model

        root = (pinocchio.JointModelFreeFlyer(), FLOATING_ROOT) if floating else ()
        self.model = build_model(robot, *root)
        self.robot = robot
        self.variables: list[Variable] = variables_of(robot, FLOATING_ROOT if floating else None)
        self.mimics = mimics_of(robot)
        self._columns = {v.name: i for i, v in enumerate(self.variables)}
        self._joints = [self._joint(i) for i in range(self.model.njoints)]
        body = pinocchio.FrameType.BODY
        self._frames = [(f.name, f.parentJoint, f.placement.homogeneous.copy())
                        for f in self.model.frames if f.type == body]
        self.links = [name for name, _, _ in self._frames]
        # what poses are relative to without --base: the root link, or with a free-flyer root
        # joint the fixed world it moves in (the root link itself moves)
        self.root_frame = "world" if floating else self.links[0]
        self._at_joint = [np.array_equal(placement, np.eye(4)) for _, _, placement in self._frames]

    def variables_moving(self, link: str) -> list[str]:
        """The variables whose values move ``link``'s frame relative to the root: those of the
        joints from the root to it, root first (a mimic joint's: the one it follows)."""
        joint = self._frames[self.links.index(link)][1]
        columns: list[int] = []
        while joint > 0:
            source = self._joints[joint].source
            if source:
                columns += list(reversed(source)) if self._joints[joint].kind in (
                    "floating", "planar") else [source[0]]
            joint = self._joints[joint].parent
        return [self.variables[c].name for c in reversed(list(dict.fromkeys(columns)))]

    def _joint(self, index: int) -> _Joint:
        model = self.model
        joint, name = model.joints[index], model.names[index]
        placement = model.jointPlacements[index].homogeneous.copy()
        parent = model.parents[index]
        if index == 0:
            return _Joint(name, "fixed", -1, placement)
        short = joint.shortname()
        if short == "JointModelFreeFlyer":
            return _Joint(name, "floating", parent, placement,
                          source=self._coordinate_columns(name, FLOATING_COORDINATES),
                          idx_q=joint.idx_q)
        if short == "JointModelPlanar":
            return _Joint(name, "planar", parent, placement,
                          source=self._coordinate_columns(name, PLANAR_COORDINATES),
                          idx_q=joint.idx_q)
        kind = "prismatic" if short.startswith(("JointModelP", "JointModelPrismatic")) else (
            "revolute" if short.startswith(("JointModelR", "JointModelRevolute")) else None)
        if kind is None:
            raise FKError(f"joint '{name}': unsupported Pinocchio joint {short}",
                          self.robot.joints.get(name))
        axis = _axis(short, self.robot.joints.get(name))
        return _Joint(name, kind, parent, placement, axis, self._source(name), joint.idx_q,
                      unbounded=joint.nq == 2)

    def _coordinate_columns(self, joint: str, coordinates) -> tuple:
        return tuple(self._columns[f"{joint}.{c}"] for c in coordinates)

    def _source(self, name: str) -> tuple:
        """(column, multiplier, offset): the joint's value as a function of one variable."""
        try:
            variable, multiplier, offset = mimic_source(self.robot, name, self._columns)
        except MimicError as error:
            raise FKError(str(error), error.element) from None
        return self._columns[variable], multiplier, offset

    # -- poses ------------------------------------------------------------------------------

    def joint_values(self, values: np.ndarray, joint: str) -> np.ndarray:
        """The value [rad or m] of a one-variable joint (mimic ones included) in each row."""
        column, multiplier, offset = self._source(joint)
        return multiplier * values[:, column] + offset

    def link_poses(self, values: np.ndarray, links: list[int] | None = None) -> np.ndarray:
        """Poses ``[rows, links, 4, 4]`` of links (indices into ``self.links``, default all)
        relative to the root."""
        return np.moveaxis(self._frame_poses(values, links), 0, 1)

    def _frame_poses(self, values: np.ndarray, links: list[int] | None) -> np.ndarray:
        """Poses ``[links, rows, 4, 4]``: each link's block contiguous, so numpy's batched
        matrix products stay on their fast path (strided or broadcast operands are 5-100x
        slower)."""
        values = np.atleast_2d(np.asarray(values, dtype=float))
        links = range(len(self._frames)) if links is None else links
        placed: list = [None]  # the universe: identity
        for joint in self._joints[1:]:
            local = self._local(joint, values)
            parent = placed[joint.parent]
            placed.append(local if parent is None else np.matmul(parent, local))
        out = np.empty((len(links), len(values), 4, 4))
        for index, link in enumerate(links):
            _, joint, placement = self._frames[link]
            if placed[joint] is None:
                out[index] = placement
            elif self._at_joint[link]:  # a link at its joint: no product
                out[index] = placed[joint]
            else:
                np.matmul(placed[joint], placement, out=out[index])
        return out

    def _local(self, joint: _Joint, values: np.ndarray) -> np.ndarray:
        """Joint placement times joint motion, ``[rows, 4, 4]``."""
        rows = len(values)
        if joint.kind in ("revolute", "prismatic"):
            # Rodrigues folded into the placement: P R(q) = P + sin q (P K) + (1 - cos q) (P K^2);
            # P Trans(q u) = P + q (P u e_w^T). Linear in (1, sin q, 1 - cos q): one BLAS product
            # of [rows, 3] coefficients with the [3, 16] stacked blocks.
            q = joint.value(values)
            coefficients = np.empty((rows, 3))
            coefficients[:, 0] = 1.0
            if joint.kind == "prismatic":
                coefficients[:, 1], coefficients[:, 2] = q, 0.0
            else:
                coefficients[:, 1] = np.sin(q)
                coefficients[:, 2] = 1.0 - np.cos(q)
            return (coefficients @ joint.stacked).reshape(rows, 4, 4)
        motion = np.zeros((rows, 4, 4))
        motion[:, 3, 3] = 1.0
        if joint.kind == "floating":
            coordinates = values[:, list(joint.source)]
            motion[:, :3, :3] = transforms.rotation_from_rpy(coordinates[:, 3:])
            motion[:, :3, 3] = coordinates[:, :3]
        else:  # planar: x, y in the joint frame's xy plane, yaw about its z
            x, y, yaw = (values[:, c] for c in joint.source)
            motion[:, :3, :3] = transforms.rotations_about((0.0, 0.0, 1.0), yaw)
            motion[:, 0, 3], motion[:, 1, 3] = x, y
        return np.matmul(joint.placement, motion)

    def pinocchio_q(self, values: np.ndarray) -> np.ndarray:
        """Pinocchio configuration vectors ``[rows, nq]`` for ``values`` (cos/sin, quaternions)."""
        values = np.atleast_2d(np.asarray(values, dtype=float))
        q = np.zeros((len(values), self.model.nq))
        for joint in self._joints[1:]:
            start = joint.idx_q
            if joint.kind in ("revolute", "prismatic"):
                value = joint.value(values)
                if joint.unbounded:
                    q[:, start], q[:, start + 1] = np.cos(value), np.sin(value)
                else:
                    q[:, start] = value
            elif joint.kind == "floating":
                coordinates = values[:, list(joint.source)]
                q[:, start:start + 3] = coordinates[:, :3]
                rotation = transforms.rotation_from_rpy(coordinates[:, 3:])
                q[:, start + 3:start + 7] = transforms.quaternion_from_rotation(rotation)
            else:
                x, y, yaw = (values[:, c] for c in joint.source)
                q[:, start:start + 4] = np.stack([x, y, np.cos(yaw), np.sin(yaw)], -1)
        return q


def _axis(short: str, element) -> np.ndarray:
    """The unit joint axis: Pinocchio's X/Y/Z joints name it; unaligned ones take the URDF's."""
    from urdftool.description.values import parse_numbers

    letter = short[-1]
    if short in ("JointModelR" + letter, "JointModelRUB" + letter, "JointModelP" + letter) \
            and letter in "XYZ":
        return np.eye(3)["XYZ".index(letter)]
    axis_element = element.find("axis") if element is not None else None
    values, _ = parse_numbers(axis_element.get("xyz") if axis_element is not None else "1 0 0", 3)
    axis = np.array(values or (1.0, 0.0, 0.0), dtype=float)
    length = np.linalg.norm(axis)
    if not np.isfinite(length) or length == 0:  # urdfdom accepts it; every pose would be NaN
        raise FKError(f"joint '{element.get('name')}': <axis xyz> '{axis_element.get('xyz')}' has "
                      "no direction; give a unit vector such as '0 0 1'", element)
    return axis / length


def forward_kinematics(model: KinematicModel, configurations: Configurations,
                       frames: list[str] | None = None, base: str | None = None) -> FKResult:
    """Poses of ``frames`` (default: every link) relative to ``base`` (default: the root)."""
    index = {name: i for i, name in enumerate(model.links)}
    for name in (frames or []) + ([base] if base else []):
        if name not in index:
            raise UnknownLink(name, model.links)
    chosen = [index[name] for name in frames] if frames else list(range(len(model.links)))
    if base:
        poses = model._frame_poses(configurations.values, chosen + [index[base]])
        poses = np.matmul(transforms.invert(poses[-1]), poses[:-1])
    else:
        poses = model._frame_poses(configurations.values, chosen)
    matrices = np.moveaxis(poses, 0, 1)
    root = base or model.root_frame
    return FKResult(root, [model.links[i] for i in chosen], matrices,
                    list(configurations.warnings))


def pose_components(matrices: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(positions [..., 3] in [m], rpy [..., 3] in [rad], quaternions [..., 4] as x, y, z, w)."""
    rotations = matrices[..., :3, :3]
    return (matrices[..., :3, 3], transforms.rpy_from_rotation(rotations),
            transforms.quaternion_from_rotation(rotations))
