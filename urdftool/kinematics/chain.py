"""A limb: the joints between a base link and a tip link, as a small Pinocchio model.

Every joint off the path from ``base`` to ``tip`` is folded into the model at its current value
(``pinocchio.buildReducedModel``), fixed joints are already merged by Pinocchio's URDF parser, and
what is left is the limb. Its coordinates ``x`` are the robot's *variables* that move the limb
(configuration.Variable): a mimic joint on the path follows its variable, a continuous joint takes
one angle (Pinocchio's (cos, sin) pair is built from it). Poses and Jacobians come from Pinocchio
(``computeFrameJacobian``); nothing here differentiates by hand.

The tip may hang off another branch than the base (a foot relative to a hand): the pose is then
``base^-1 tip`` and its Jacobian the difference of the two frames' Jacobians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from urdftool.errors import IKError, UnknownLink
from urdftool.kinematics.configuration import Variable
from urdftool.kinematics.fk import KinematicModel
from urdftool.kinematics.model import oversized_data


@dataclass
class Chain:
    """The limb from ``base`` to ``tip`` of ``robot`` with the other variables at ``row``.

    variables: the limb's variables (columns of ``x``), in the robot's variable order
    columns: their indices in the robot's full variable row
    joints: the limb's joint names, base side first
    lower, upper: limits [rad or m] of ``x``, inf for continuous joints
    """

    kinematics: KinematicModel
    base: str
    tip: str
    row: np.ndarray
    variables: list[Variable]
    columns: list[int]
    joints: list[str]
    lower: np.ndarray
    upper: np.ndarray
    model: object
    data: object
    base_frame: int
    tip_frame: int
    base_moves: bool
    _slots: list  # per reduced joint: (idx_q, idx_v, x column, multiplier, offset, unbounded)
    _selection: np.ndarray | None  # [nv, len(x)]: d(v)/d(x); None when q = v = x
    _base_placement: object = None  # the base's pose when no limb joint moves it

    @property
    def continuous(self) -> np.ndarray:
        """Which of ``x`` are continuous joints (wrapped to (-pi, pi])."""
        return np.array([v.kind == "continuous" for v in self.variables], dtype=bool)

    @property
    def held(self) -> list[str]:
        """The limb's variables of no range (``lower = upper``: double_pendulum_simple's
        ``<limit lower="0" upper="0">``): they stay at that value in every pose."""
        return [v.name for v in self.variables if not v.upper - v.lower > 0]

    def x_of(self, row: np.ndarray) -> np.ndarray:
        """The limb's coordinates in a full variable row."""
        return np.asarray(row, dtype=float)[self.columns].copy()

    def row_of(self, x: np.ndarray) -> np.ndarray:
        """The full variable row with the limb at ``x`` and the rest as given."""
        row = self.row.copy()
        row[self.columns] = x
        return row

    def q(self, x: np.ndarray) -> np.ndarray:
        """Pinocchio's configuration of the reduced model for ``x``."""
        if self._selection is None:
            return x
        q = np.empty(self.model.nq)
        for idx_q, _, column, multiplier, offset, unbounded in self._slots:
            value = multiplier * x[column] + offset
            if unbounded:
                q[idx_q], q[idx_q + 1] = np.cos(value), np.sin(value)
            else:
                q[idx_q] = value
        return q

    def pose(self, x: np.ndarray):
        """``base^-1 tip`` at ``x`` as a pinocchio.SE3."""
        import pinocchio as pin

        pin.framesForwardKinematics(self.model, self.data, self.q(x))
        return self.data.oMf[self.base_frame].actInv(self.data.oMf[self.tip_frame])

    def pose_and_jacobian(self, x: np.ndarray, local: bool = True):
        """(``base^-1 tip`` as SE3, its Jacobian ``[6, len(x)]`` with respect to ``x``): the tip's
        body velocity relative to the base, in the tip frame (``local``) or in the base frame."""
        import pinocchio as pin

        m, d = self.model, self.data
        q = self.q(x)
        pin.computeJointJacobians(m, d, q)  # and the joint placements
        jacobian = frame_jacobian(m, d, self.tip_frame, pin.LOCAL)
        tip = pin.updateFramePlacement(m, d, self.tip_frame)
        if self._base_placement is not None:
            relative = self._base_placement.actInv(tip)
        else:
            relative = pin.updateFramePlacement(m, d, self.base_frame).actInv(tip)
            base_jacobian = frame_jacobian(m, d, self.base_frame, pin.LOCAL)
            jacobian = jacobian - relative.inverse().action @ base_jacobian
        if self._selection is not None:
            jacobian = jacobian @ self._selection
        if not local:
            rotation = relative.rotation
            jacobian = np.vstack([rotation @ jacobian[:3], rotation @ jacobian[3:]])
        return relative, jacobian


def frame_jacobian(model, data, frame: int, reference) -> np.ndarray:
    """``pinocchio.getFrameJacobian`` (after ``computeJointJacobians``) as a ``[6, nv]`` array,
    always two-dimensional: for a model of one velocity (a limb of one joint) Pinocchio hands
    back a vector of 6, and every product with it took the wrong shape (ik raised
    ValueError). The only caller of getFrameJacobian (a test holds it so)."""
    import pinocchio as pin

    return np.asarray(pin.getFrameJacobian(model, data, frame, reference)).reshape(6, model.nv)


def reduced_model(full, locked: list[int], reference: np.ndarray):
    """``pinocchio.buildReducedModel(full, locked, reference)`` for any URDF: Pinocchio looks
    frames up by name alone and raises "Several frames match the filter" when a link has a
    joint's name (ANYmal's LF_HAA is both, and Baxter's fixed joint left_hand is its link's
    name, as URDF allows). Such joints' frames are renamed in a copy while it reduces, and
    named back after."""
    import pinocchio as pin
    from collections import Counter

    count = Counter(frame.name for frame in full.frames)
    clashes = {name for name, times in count.items() if times > 1}
    if not clashes:
        return pin.buildReducedModel(full, locked, reference)
    model = full.copy()
    renamed = {}
    for frame in model.frames:
        if frame.name in clashes and frame.type in (pin.FrameType.JOINT,
                                                    pin.FrameType.FIXED_JOINT):
            new = f"{frame.name}\x1f{int(frame.type)}"
            renamed[new] = frame.name
            frame.name = new
    for joint, name in enumerate(model.names):
        if joint and name in clashes:
            model.names[joint] = f"{name}\x1f{int(pin.FrameType.JOINT)}"
    reduced = pin.buildReducedModel(model, locked, reference)
    for frame in reduced.frames:
        frame.name = renamed.get(frame.name, frame.name)
    for joint, name in enumerate(reduced.names):
        reduced.names[joint] = renamed.get(name, name)
    return reduced


def refuse_far(what: str, position, computes: str, argument: str) -> None:
    """ConfigError (its ``argument`` given) for a position with a coordinate past
    :data:`~urdftool.numbers.SQUARABLE` [m]: ik's targets and the point on the tip (the
    solver squares distances, the workspace its reach and manipulability)."""
    from urdftool.errors import ConfigError
    from urdftool.numbers import SQUARABLE, number

    far = [f"{axis} {number(value)}" for axis, value in zip("xyz", position)
           if not abs(value) <= SQUARABLE]
    if far:
        error = ConfigError(f"{what} {', '.join(far)} m is past what {computes} computes with "
                            f"(at most {number(SQUARABLE)} m each)")
        error.argument = argument
        raise error


def build_chain(robot, base: str | None, tip: str, row: np.ndarray | None = None,
                kinematics: KinematicModel | None = None, point=None) -> Chain:
    """The limb from ``base`` (default: the root link) to ``tip``; the variables off the limb
    stay at ``row`` (default: each variable's default); ``point`` [m] in the tip's frame is the
    point placed instead of the tip's origin (a hand's palm on a forearm link). UnknownLink for
    an unknown link, IKError for a limb without a moving joint or through a joint of more than
    one variable (each the question's, ``asked``: a usage error in every command), ConfigError (argument ``point``) for a point whose coordinates
    the solver and the workspace's reach and manipulability cannot square
    (:data:`urdftool.numbers.SQUARABLE`, as ik's targets: ``--point 1e308 0 0`` was numpy's
    overflow warnings and a reach of inf m)."""
    import pinocchio as pin

    if point is not None:
        refuse_far("point", point, "the kinematics", "point")

    kinematics = kinematics or KinematicModel(robot)
    full = kinematics.model
    base = base or kinematics.links[0]
    from urdftool.kinematics.tree import beside_the_tree

    UnknownLink.unless_among((base, tip), kinematics.links, beside_the_tree(robot))
    row = np.array([v.default for v in kinematics.variables]) if row is None else \
        np.asarray(row, dtype=float).copy()
    frame = {name: full.getFrameId(name, pin.FrameType.BODY) for name in (base, tip)}
    supports = {name: set(full.supports[full.frames[frame[name]].parentJoint]) - {0}
                for name in (base, tip)}
    path = supports[base] ^ supports[tip]
    if not path:
        raise IKError(f"no joint moves '{tip}' relative to '{base}'", asked=True)
    for joint in sorted(path):
        if full.joints[joint].nv != 1:
            name = full.names[joint]
            raise IKError(f"joint '{name}' between '{base}' and '{tip}' is "
                          f"{robot.joints[name].get('type')}: a limb is made of revolute, "
                          "continuous and prismatic joints (choose a --base below it)",
                          robot.joints.get(name), asked=True)
    locked = [j for j in range(1, full.njoints) if j not in path]
    reference = kinematics.pinocchio_q(row)[0]
    model = reduced_model(full, locked, reference) if locked else full.copy()
    joints = [model.names[j] for j in range(1, model.njoints)]
    sources = {name: kinematics._source(name) for name in joints}
    columns = sorted({column for column, _, _ in sources.values()})
    position = {column: k for k, column in enumerate(columns)}
    selection = np.zeros((model.nv, len(columns)))
    slots = []
    for j, name in zip(range(1, model.njoints), joints):
        joint = model.joints[j]
        column, multiplier, offset = sources[name]
        slots.append((joint.idx_q, joint.idx_v, position[column], multiplier, offset,
                      joint.nq == 2))
        selection[joint.idx_v, position[column]] += multiplier
    variables = [kinematics.variables[c] for c in columns]
    base_id = model.getFrameId(base, pin.FrameType.BODY)
    tip_id = model.getFrameId(tip, pin.FrameType.BODY)
    if point is not None:
        frame = model.frames[tip_id]
        offset = frame.placement * pin.SE3(np.eye(3), np.asarray(point, dtype=float))
        tip_id = model.addFrame(pin.Frame(f"{tip}+point", frame.parentJoint, tip_id, offset,
                                          pin.FrameType.OP_FRAME))
    moving = bool(set(model.supports[model.frames[base_id].parentJoint]) - {0})
    plain = model.nq == model.nv == len(columns) and all(
        (idx_q, idx_v, column, multiplier, offset, unbounded) == (k, k, k, 1.0, 0.0, False)
        for k, (idx_q, idx_v, column, multiplier, offset, unbounded) in enumerate(slots))
    oversized = oversized_data(model.nv, "choose a --base or --tip with fewer joints between "
                                         "them")
    if oversized:  # (the question's, as the size limits of the commands: another limb fits)
        raise IKError(oversized.replace("joint variables", f"joint variables from '{base}' "
                                                          f"to '{tip}'"), robot.root, asked=True)
    data = model.createData()
    placement = None
    if not moving:
        pin.framesForwardKinematics(model, data, pin.neutral(model))
        placement = data.oMf[base_id].copy()
    return Chain(kinematics, base, tip, row, variables, columns, joints,
                 np.array([v.lower for v in variables]), np.array([v.upper for v in variables]),
                 model, data, base_id, tip_id, moving, slots,
                 None if plain else selection, placement)
