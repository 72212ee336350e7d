"""Forward kinematics of a URDF, vectorised over configurations, without Pinocchio.

The model is read in one pass down the parsed tree, as Pinocchio's URDF parser reads it (its
joints and link frames in the same order, children by joint name as urdfdom orders them, fixed
joints merged into the frames of the links they carry, the same joint kinds): Pinocchio's own
model build is quadratic in the links (a 2,000-link chain: most of ``fk``'s time; 8,000 links:
seconds), this pass linear. The tests compare both on random trees. Up to
:data:`URDFDOM_VERDICT_UP_TO` links Pinocchio's model is still built, for urdfdom's verdict on
the robot. The poses are then computed
with numpy for all configurations at once: a ``--q-file`` of 10,000 rows costs one batched
matrix product per joint rather than 10,000 Python calls. Mimic joints are expanded here (value =
multiplier * mimicked + offset). Pinocchio's model (:attr:`KinematicModel.model`) is built only
for what needs Pinocchio itself (inverse kinematics); ``pinocchio_q`` gives its configuration
vectors.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Callable

import numpy as np

from urdftool.description.urdf import MOVING
from urdftool.errors import FKError, TreeError, UnknownLink
from urdftool.kinematics import transforms
from urdftool.kinematics.tree import beside_the_tree, children_by_link, root_link
from urdftool.kinematics.configuration import (FLOATING_COORDINATES, PLANAR_COORDINATES, Configurations, MimicError,
                            Variable, mimic_source, mimics_of, variables_of)
from urdftool.numbers import (MAX_COORDINATE, length as vector_length, power,
                              unit as vector_unit)

FLOATING_ROOT = "root_joint"
# [links] up to which Pinocchio's model is built with each KinematicModel, for urdfdom's verdict
# alone (a robot it refuses is refused, as every consumer refuses it: ModelBuildError); the build
# is quadratic in the links (1,000: 64 ms; 2,000: 220 ms, most of fk's time), so above this the
# model read down the tree, which refuses what it cannot pose, is all there is
URDFDOM_VERDICT_UP_TO = 1000


@dataclass
class _Joint:
    """One joint as Pinocchio models it: ``kind`` revolute/prismatic/floating/planar/fixed (the
    universe); ``placement`` in its parent joint's frame (the fixed joints between them folded
    in); ``idx_q`` where its coordinates start in Pinocchio's configuration vector."""

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


# [poses] computed, and held, at a time when the poses of many configurations are written
# (PoseBlocks): 2^14 poses are 2 MB of matrices and some 30 MB of their texts at most (2^16:
# 110 MB more at the peak, no faster); every pose of a --q-file at once was 1.4 KB a pose with
# its texts (12,000 rows of a 300-link chain: 5 GB of text tables, past the 2 GiB budget)
POSES_PER_BLOCK = 1 << 14
# [poses] computed on the way to them at a time (every joint's, 128 bytes each, no text): 32 MB
# (12,000 rows of a 300-joint chain at one frame: 0.41 s of CPU; 0.53 s in one block of 460 MB;
# 2^16 poses a block 0.55 s, 2^14 0.89 s)
POSES_HELD_PER_BLOCK = 1 << 18


@dataclass
class FKResult:
    """Poses ``matrices[rows, frames, 4, 4]`` of ``frames`` relative to ``base``."""

    base: str
    frames: list[str]
    matrices: np.ndarray
    warnings: list[str] = field(default_factory=list)

    @property
    def rows(self) -> int:
        return len(self.matrices)

    def blocks(self):
        """(first row, poses ``[block rows, frames, 4, 4]``) of consecutive blocks of rows, as
        :meth:`PoseBlocks.blocks` gives them (views of :attr:`matrices`)."""
        for start, stop in block_ranges(self.rows, len(self.frames)):
            yield start, self.matrices[start:stop]


@dataclass
class PoseBlocks:
    """The poses of ``frames`` relative to ``base`` for ``rows`` configurations, computed a block
    of rows at a time as they are asked for (:meth:`blocks`): what a writer of every pose holds
    is one block's, whatever the rows (:data:`POSES_PER_BLOCK`). ``held``: the poses
    ``compute`` holds for each row, the frames' and those it computes them through (every
    joint's: a block sized by the frames alone held 12,000 rows of a 300-joint chain's poses
    at once for one --frame, 460 MB)."""

    base: str
    frames: list[str]
    rows: int
    warnings: list[str]
    compute: Callable[[int, int], np.ndarray]  # (start, stop) -> [stop - start, frames, 4, 4]
    held: int = 0

    def blocks(self):
        """(first row, poses ``[block rows, frames, 4, 4]``) of consecutive blocks of rows."""
        for start, stop in block_ranges(self.rows, len(self.frames), self.held):
            yield start, self.compute(start, stop)


def block_ranges(rows: int, frames: int, held: int = 0) -> list[tuple[int, int]]:
    """(start, stop) of consecutive blocks of ``rows`` rows of ``frames`` poses each, at most
    :data:`POSES_PER_BLOCK` poses a block, and never a block of one row of several: numpy's
    product of one row (``[1, 3] @ [3, 16]``, :meth:`KinematicModel._local`) is BLAS's gemv,
    of several its gemm, whose last bits differ (a pose's 17th digit, in JSON and CSV); gemm's
    rows are its rows whatever their number, so blocks of two or more give each row the bits
    every row at once gives it. ``held``: the poses computed for a row besides (its joints'),
    at most :data:`POSES_HELD_PER_BLOCK` a block."""
    step = max(2, min(POSES_PER_BLOCK // max(frames, 1), POSES_HELD_PER_BLOCK // max(held, 1)))
    ranges = [(start, min(start + step, rows)) for start in range(0, rows, step)]
    if len(ranges) > 1 and ranges[-1][1] - ranges[-1][0] == 1:  # (its row to the one before)
        ranges[-2:] = [(ranges[-2][0], rows)]
    return ranges


class KinematicModel:
    """A robot's kinematics: its variables, its links, and poses for many configurations."""

    def __init__(self, robot, floating: bool = False):
        """``floating``: a free-flyer root joint ``root_joint`` above the root link, unless the
        robot has its own free base (:func:`urdftool.kinematics.tree.own_free_base`), whose
        coordinates are the free base's then: no second one is added."""
        from urdftool.kinematics.tree import own_free_base

        floating = floating and own_free_base(robot) is None
        self.robot, self.floating = robot, floating
        self.variables: list[Variable] = variables_of(robot, FLOATING_ROOT if floating else None)
        self.mimics = mimics_of(robot)
        self._columns = {v.name: i for i, v in enumerate(self.variables)}
        self._joints, self._frames = self._tree(robot, floating)
        self.links = [name for name, _, _ in self._frames]
        # what poses are relative to without --base: the root link, or with a free-flyer root
        # joint the fixed world it moves in (the root link itself moves)
        self.root_frame = "world" if floating else self.links[0]
        self._at_joint = [np.array_equal(placement, np.eye(4)) for _, _, placement in self._frames]
        if len(robot.links) <= URDFDOM_VERDICT_UP_TO:
            self.model  # noqa: B018  (urdfdom's verdict: ModelBuildError when it refuses)

    @cached_property
    def model(self):
        """Pinocchio's model of the robot (built on first use: quadratic in the links)."""
        import pinocchio

        from urdftool.kinematics.native import build_model

        root = (pinocchio.JointModelFreeFlyer(), FLOATING_ROOT) if self.floating else ()
        return build_model(self.robot, *root)

    def _tree(self, robot, floating: bool) -> tuple[list[_Joint], list[tuple]]:
        """The joints and the link frames (name, joint, placement in the joint's frame) in
        Pinocchio's order: depth first from the root link, each link's children by joint name;
        a fixed joint adds no joint, its child link's frame is placed in the moving joint
        above it."""
        try:
            root, children = root_link(robot), children_by_link(robot)
        except TreeError as error:
            raise FKError(str(error), error.element) from None
        identity = np.eye(4)
        joints = [_Joint("universe", "fixed", -1, identity)]
        top, width = 0, 0  # the joint the root link hangs on; Pinocchio's nq so far
        if floating:
            joints.append(_Joint(FLOATING_ROOT, "floating", 0, identity,
                                 source=self._coordinate_columns(FLOATING_ROOT,
                                                                 FLOATING_COORDINATES),
                                 idx_q=0))
            top, width = 1, NQ["floating"]
        frames = [(root, top, identity)]
        seen = {root}
        stack = [(iter(children.get(root, ())), top, identity)]
        while stack:
            below, parent, above = stack[-1]
            entry = next(below, None)
            if entry is None:
                stack.pop()
                continue
            name, child = entry
            element = robot.joints[name]
            if child in seen or child not in robot.links:
                raise FKError(f"joint '{name}': child link '{child}' "
                              + ("is reached twice (a cycle?)" if child in seen
                                 else "does not exist"), element)
            seen.add(child)
            placement = joint_placement(element)
            if above is not identity or _negative_zero(placement):
                placement = _compose(above, placement)
            kind = element.get("type")
            if kind == "fixed":
                frames.append((child, parent, placement))
                stack.append((iter(children.get(child, ())), parent, placement))
                continue
            joint = self._joint(name, kind, parent, placement, width, element)
            width += NQ["continuous" if kind == "continuous" else joint.kind]
            joints.append(joint)
            frames.append((child, len(joints) - 1, identity))
            stack.append((iter(children.get(child, ())), len(joints) - 1, identity))
        return joints, frames

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

    def _joint(self, name: str, kind: str, parent: int, placement: np.ndarray, idx_q: int,
               element) -> _Joint:
        if kind == "floating":
            return _Joint(name, "floating", parent, placement,
                          source=self._coordinate_columns(name, FLOATING_COORDINATES),
                          idx_q=idx_q)
        if kind == "planar":
            return _Joint(name, "planar", parent, placement,
                          source=self._coordinate_columns(name, PLANAR_COORDINATES),
                          idx_q=idx_q)
        if kind not in MOVING:
            raise FKError(f"joint '{name}': unknown joint type '{kind}'", element)
        return _Joint(name, "prismatic" if kind == "prismatic" else "revolute", parent,
                      placement, unit_axis(element), self._source(name), idx_q,
                      unbounded=kind == "continuous")

    def _coordinate_columns(self, joint: str, coordinates) -> tuple:
        return tuple(self._columns[f"{joint}.{c}"] for c in coordinates)

    def _source(self, name: str) -> tuple:
        """(column, multiplier, offset): the joint's value as a function of one variable."""
        try:
            variable, multiplier, offset = mimic_source(
                self.robot, name, self._columns, known=self.__dict__.setdefault("_sources", {}))
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
        slower). A moving joint's pose is written straight into the block of the link at it
        (every moving joint has one), so no block is copied and memory is touched once."""
        values = np.atleast_2d(np.asarray(values, dtype=float))
        links = range(len(self._frames)) if links is None else links
        rows = len(values)
        out = np.empty((len(links), rows, 4, 4))
        home = {}  # joint -> the block of out its pose is written to
        for index, link in enumerate(links):
            joint = self._frames[link][1]
            if joint and self._at_joint[link]:
                home.setdefault(joint, index)
        scratch = _Scratch(rows)
        placed: list = [None]  # the universe: identity
        for number, joint in enumerate(self._joints[1:], 1):
            target = out[home[number]] if number in home else None
            parent = placed[joint.parent]
            if parent is None:
                placed.append(self._local(joint, values, scratch, target))
            else:
                local = self._local(joint, values, scratch, scratch.local)
                placed.append(np.matmul(parent, local, out=target))
        for index, link in enumerate(links):
            _, joint, placement = self._frames[link]
            if placed[joint] is None:
                out[index] = placement
            elif home.get(joint) == index:  # written above
                continue
            elif self._at_joint[link]:
                out[index] = placed[joint]
            else:
                np.matmul(placed[joint], placement, out=out[index])
        return out

    def _local(self, joint: _Joint, values: np.ndarray, scratch: "_Scratch",
               out: np.ndarray | None = None) -> np.ndarray:
        """Joint placement times joint motion, ``[rows, 4, 4]`` (into ``out`` when given)."""
        rows = len(values)
        if joint.kind in ("revolute", "prismatic"):
            # Rodrigues folded into the placement: P R(q) = P + sin q (P K) + (1 - cos q) (P K^2);
            # P Trans(q u) = P + q (P u e_w^T). Linear in (1, sin q, 1 - cos q): one BLAS product
            # of [rows, 3] coefficients with the [3, 16] stacked blocks.
            q = joint.value(values)
            coefficients = scratch.coefficients
            if joint.kind == "prismatic":
                coefficients[:, 1], coefficients[:, 2] = q, 0.0
            else:
                np.sin(q, out=coefficients[:, 1])
                np.cos(q, out=coefficients[:, 2])
                np.subtract(1.0, coefficients[:, 2], out=coefficients[:, 2])
            if out is None:
                return (coefficients @ joint.stacked).reshape(rows, 4, 4)
            np.matmul(coefficients, joint.stacked, out=out.reshape(rows, 16))
            return out
        motion = coordinates_motion(joint.kind, values[:, list(joint.source)])
        return np.matmul(joint.placement, motion, out=out)

    def pinocchio_q(self, values: np.ndarray) -> np.ndarray:
        """Pinocchio configuration vectors ``[rows, nq]`` for ``values`` (cos/sin, quaternions)."""
        values = np.atleast_2d(np.asarray(values, dtype=float))
        q = np.zeros((len(values), sum(NQ["continuous" if j.unbounded else j.kind]
                                       for j in self._joints[1:])))
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


def coordinates_motion(kind: str, coordinates: np.ndarray) -> np.ndarray:
    """The motions ``[rows, 4, 4]`` of a joint of several variables in its own frame from its
    coordinates ``[rows, n]``: a floating joint's x, y, z [m] and roll, pitch, yaw [rad]
    (fixed axes, as URDF's rpy); a planar joint's x, y [m] in its frame's xy plane and yaw
    [rad] about its z (Pinocchio's ``JointModelPlanar``). The one owner of both motions: fk's
    poses and render's scene."""
    coordinates = np.atleast_2d(np.asarray(coordinates, dtype=float))
    motion = np.zeros((len(coordinates), 4, 4))
    motion[:, 3, 3] = 1.0
    if kind == "floating":
        motion[:, :3, :3] = transforms.rotation_from_rpy(coordinates[:, 3:])
        motion[:, :3, 3] = coordinates[:, :3]
    else:
        motion[:, :3, :3] = transforms.rotations_about((0.0, 0.0, 1.0), coordinates[:, 2])
        motion[:, :2, 3] = coordinates[:, :2]
    return motion


class _Scratch:
    """Arrays reused from joint to joint in one pass: the coefficients (1, sin q, 1 - cos q)
    and one joint's local placement."""

    def __init__(self, rows: int):
        self.coefficients = np.empty((rows, 3))
        self.coefficients[:, 0] = 1.0
        self.local = np.empty((rows, 4, 4))


NQ = {"revolute": 1, "prismatic": 1, "continuous": 2, "floating": 7, "planar": 4}  # Pinocchio's


def placed_within(robot) -> None:
    """FKError for the first joint whose ``<origin>`` is no pose (:func:`joint_placement`): the
    one check of joint origins, which :class:`KinematicModel` makes as it builds (fk, ik,
    workspace, collisions, diff) and the models built otherwise ask (dynamics: Pinocchio from
    the text, which checks the inertials itself; render: yourdfpy); once per robot."""
    def check() -> bool:
        for element in robot.joints.values():
            joint_placement(element)
        return True

    robot.memo(placed_within, check)


def joint_placement(element) -> np.ndarray:
    """The 4x4 transform of a joint's ``<origin>``, its rotation as Pinocchio has it (urdfdom's
    quaternion of the roll-pitch-yaw, then Eigen's matrix of the quaternion: the same numbers
    to the bit, so that an angle at +-pi reads as Pinocchio's did); FKError when a number in it
    is malformed (urdfdom refuses it: there is no pose to give), or places the link past
    :data:`urdftool.numbers.MAX_COORDINATE` (every pose below it rounded or overflowed)."""
    from urdftool.description.values import origin

    found = origin(element)
    problem = found.problem or (None if all(map(math.isfinite, (*found.xyz, *found.rpy))) else
                                f"holds a number that is not finite (xyz {_numbers(found.xyz)}, "
                                f"rpy {_numbers(found.rpy)}): no pose has it")
    if not problem and not max(map(abs, found.xyz)) < MAX_COORDINATE:
        from urdftool.numbers import number

        problem = (f"xyz {_numbers(found.xyz)} is past the {number(MAX_COORDINATE)} m urdftool "
                   "places a link within")
    if problem:  # inf: math.sin raised ValueError; nan: every pose below it nan, silently
        raise FKError(f"joint '{element.get('name')}': <origin> {problem}",
                      found.element if found.element is not None else element)
    mimic = element.find("mimic")
    if mimic is not None:  # multiplier 1e200: its link at 1e200 whatever the joint it follows
        _mimic_within(element, mimic)
    matrix = np.eye(4)
    matrix[:3, 3] = found.xyz
    if found.rpy != (0.0, 0.0, 0.0):  # the identity to the bit, without the products
        matrix[:3, :3] = _rotation(*found.rpy)
    return matrix


def _mimic_within(element, mimic) -> None:
    """FKError for a ``<mimic>`` whose multiplier or offset is past
    :data:`~urdftool.numbers.MAX_COORDINATE`: it moves its link past it whatever the joint it
    follows (values within the bound), a place no pose keeps (a workspace "max reach inf m",
    dynamics "total tau nan", collisions' distances of inf)."""
    from urdftool.description.values import parse_numbers
    from urdftool.numbers import number

    for attribute in ("multiplier", "offset"):
        values, _ = parse_numbers(mimic.get(attribute), 1)
        if values and math.isfinite(values[0]) and not abs(values[0]) < MAX_COORDINATE:
            raise FKError(f"joint '{element.get('name')}': <mimic {attribute}> "
                          f"{number(values[0])} is past the {number(MAX_COORDINATE)} urdftool "
                          "places a link (or turns it, in rad) within", mimic)


def _numbers(values) -> str:
    from urdftool.numbers import number

    return "'" + " ".join(map(number, values)) + "'"


def _compose(first: np.ndarray, second: np.ndarray) -> np.ndarray:
    """``first`` then ``second`` as Pinocchio composes placements (R1 R2, R1 p2 + p1, each sum
    in order), not as a 4x4 product: its zero terms would turn a -0.0 into 0.0, and an angle
    of -pi read off the pose into +pi."""
    r1, p1 = first[:3, :3].tolist(), first[:3, 3].tolist()
    r2, p2 = second[:3, :3].tolist(), second[:3, 3].tolist()
    matrix = np.eye(4)
    matrix[:3, :3] = [[row[0] * r2[0][j] + row[1] * r2[1][j] + row[2] * r2[2][j]
                       for j in range(3)] for row in r1]
    matrix[:3, 3] = [row[0] * p2[0] + row[1] * p2[1] + row[2] * p2[2] + p for row, p in
                     zip(r1, p1)]
    return matrix


def _negative_zero(matrix: np.ndarray) -> bool:
    """Whether ``matrix`` holds a -0.0, which Pinocchio's product with the identity (a joint
    below a link at its joint) makes 0.0; without one that product changes nothing."""
    return bool(np.any(np.signbit(matrix) & (matrix == 0.0)))


def _rotation(roll: float, pitch: float, yaw: float) -> list[list[float]]:
    """urdfdom's ``Rotation::setFromRPY`` (a normalised quaternion) and Eigen's
    ``Quaternion::toRotationMatrix``, operation for operation."""
    phi, the, psi = roll / 2.0, pitch / 2.0, yaw / 2.0
    sphi, cphi, sthe, cthe = math.sin(phi), math.cos(phi), math.sin(the), math.cos(the)
    spsi, cpsi = math.sin(psi), math.cos(psi)
    x = sphi * cthe * cpsi - cphi * sthe * spsi
    y = cphi * sthe * cpsi + sphi * cthe * spsi
    z = cphi * cthe * spsi - sphi * sthe * cpsi
    w = cphi * cthe * cpsi + sphi * sthe * spsi
    norm = math.sqrt(x * x + y * y + z * z + w * w)
    if norm == 0.0:
        x, y, z, w = 0.0, 0.0, 0.0, 1.0
    else:
        x, y, z, w = x / norm, y / norm, z / norm, w / norm
    tx, ty, tz = 2.0 * x, 2.0 * y, 2.0 * z
    twx, twy, twz = tx * w, ty * w, tz * w
    txx, txy, txz = tx * x, ty * x, tz * x
    tyy, tyz, tzz = ty * y, tz * y, tz * z
    return [[1.0 - (tyy + tzz), txy - twz, txz + twy],
            [txy + twz, 1.0 - (txx + tzz), tyz - twx],
            [txz - twy, tyz + twx, 1.0 - (txx + tyy)]]


def unit_axis(element) -> np.ndarray:
    """The joint's unit axis (:func:`~urdftool.description.values.axis_xyz`: x without an
    ``<axis>``); within Eigen's ``isApprox`` of x, y or z, that axis exactly, as Pinocchio
    models the joint. The one reading of a joint's axis as a
    direction (fk, dh, render's scene): scaled before it is squared (``1e308 1e308 1e308`` and
    ``1e-320 0 0`` have one), FKError for an axis with none (``0 0 0``, not finite)."""
    from urdftool.description.values import axis_xyz

    values = axis_xyz(element)  # (urdfdom's: <axis/> without xyz is 0 0 0)
    axis = np.array(values or (1.0, 0.0, 0.0), dtype=float)
    direction = vector_unit(axis)  # scaled first: 1e308 1e308 1e308 has a direction
    if direction is None:  # urdfdom accepts it; every pose would be NaN
        written = element.find("axis").get("xyz")
        said = f"<axis xyz> '{written}'" if written is not None else \
            "<axis> without xyz (urdfdom's 0 0 0)"
        raise FKError(f"joint '{element.get('name')}': {said} has no direction; give a unit "
                      "vector such as '0 0 1'", element)
    length = vector_length(axis)
    for unit in np.eye(3):  # Pinocchio's joint about x, y or z: Eigen's isApprox (1e-12)
        if vector_length(axis - unit) <= 1e-12 * min(length, 1.0):
            return unit
    return np.array(direction)


def forward_kinematics(model: KinematicModel, configurations: Configurations,
                       frames: list[str] | None = None, base: str | None = None) -> FKResult:
    """Poses of ``frames`` (default: every link) relative to ``base`` (default: the root)."""
    found = forward_kinematics_blocks(model, configurations, frames, base)
    return FKResult(found.base, found.frames, found.compute(0, found.rows), found.warnings)


def forward_kinematics_blocks(model: KinematicModel, configurations: Configurations,
                              frames: list[str] | None = None,
                              base: str | None = None) -> PoseBlocks:
    """The poses of :func:`forward_kinematics`, computed a block of rows at a time as a writer
    asks for them (the same numbers: each row's poses are computed alone either way)."""
    index = {name: i for i, name in enumerate(model.links)}
    UnknownLink.unless_among((frames or []) + ([base] if base else []), model.links,
                             beside_the_tree(model.robot))
    chosen = [index[name] for name in frames] if frames else list(range(len(model.links)))
    values = configurations.values

    def compute(start: int, stop: int) -> np.ndarray:
        if base:
            poses = model._frame_poses(values[start:stop], chosen + [index[base]])
            poses = np.matmul(transforms.invert(poses[-1]), poses[:-1])
        else:
            poses = model._frame_poses(values[start:stop], chosen)
        return np.moveaxis(poses, 0, 1)

    return PoseBlocks(base or model.root_frame, [model.links[i] for i in chosen], len(values),
                      list(configurations.warnings), compute,
                      held=len(model._joints) + len(chosen) + bool(base))


def pose_components(matrices: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(positions [..., 3] in [m], rpy [..., 3] in [rad], quaternions [..., 4] as x, y, z, w)."""
    rotations = matrices[..., :3, :3]
    # + 0.0: no -0.0 (atan2's pitch of a level frame), which JSON would otherwise clean again
    return (matrices[..., :3, 3] + 0.0, transforms.rpy_from_rotation(rotations) + 0.0,
            transforms.quaternion_from_rotation(rotations) + 0.0)
