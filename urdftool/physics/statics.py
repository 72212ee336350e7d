"""Statics of a robot standing on support links (feet, wheels): what each joint holds when the
ground, not a fixed torso, carries the robot.

The robot gets a free-flyer root (Pinocchio) placed so that the first support link is level
(its frame's axes are the ground frame's: z up, against gravity) and the lowest point of the
supports' geometry is on the ground (z = 0). Gravity ``g(q)`` is then balanced by the ground's
wrenches ``f`` on the supports and by the joints:

    g(q) = S^T tau + sum_i J_i(q)^T f_i

The six rows of the floating base fix the wrenches (``J_b^T f = g_b``) and the joint rows give
the torques (``tau = g_j - J_j^T f``). For one support this is exact (it equals a model rooted at
the support and fixed there). Several supports share the load in ways statics cannot decide:
the wrenches taken are those of least norm that balance the robot (an equal share between
symmetric feet), and the result says so.

The support polygon is the convex hull, projected on the ground, of the support geometry's
points within 1 mm of the ground; the centre of mass margin is its distance to the nearest edge
(negative when outside: the robot tips over). Units: [m], [kg], [N], [N m].
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from urdftool.numbers import number
from urdftool.errors import DynamicsError, UnknownLink
from urdftool.physics.dynamics import JointLoad, Model, gravity_loads, judged_effort
from urdftool.kinematics.chain import frame_jacobian

CONTACT = 1e-3  # [m]: support points this close to the ground touch it
SHARED_LOAD = ("several supports: the load split is statically indeterminate; the wrenches "
               "are the least-norm ones that balance the robot")


@dataclass
class Standing:
    """A floating-base model with its supports: ``points`` [k, 3] per support, in its frame."""

    model: Model
    supports: list[str]
    frames: list[int]
    points: list[np.ndarray]
    fixed: Model  # the same robot with its root fixed, for comparison


@dataclass
class Stance:
    """The robot standing at one configuration.

    torques: per joint (``joints`` order) [N m or N], standing; fixed_base: G(q) with the root
    fixed, as ``dynamics`` gives without --support
    wrenches: support -> the ground's (force, torque) on it at its frame origin, ground axes
    com: centre of mass in the ground frame; polygon: [k, 2] hull corners, counter-clockwise
    margin: the COM's distance to the polygon's nearest edge [m], negative outside
    lifted: support -> height [m] of its lowest point above the ground (0 when it touches)
    pose: link -> its 4x4 pose in the ground frame (the supports' and the root's)
    """

    supports: list[str]
    joints: list[str]
    q: dict
    mass: float
    torques: np.ndarray
    fixed_base: np.ndarray
    wrenches: dict
    com: np.ndarray
    polygon: np.ndarray
    margin: float
    lifted: dict
    contacts: np.ndarray
    efforts: np.ndarray
    assumption: str | None = None
    warnings: list[str] = field(default_factory=list)

    @property
    def stands(self) -> bool:
        """The centre of mass is inside the support polygon."""
        return self.margin > 0

    @property
    def holds(self) -> bool:
        """Every joint's standing torque is within its effort limit, where it has one to judge
        against (:func:`urdftool.physics.dynamics.judged_effort`: not inf, not 0)."""
        return not any(self.beyond)

    @property
    def beyond(self) -> list[bool]:
        """Per joint, whether its standing torque is over a judged effort limit."""
        return [judged_effort(float(effort)) and abs(float(torque)) > effort
                for torque, effort in zip(self.torques, self.efforts)]

    def as_dict(self) -> dict:
        return {"supports": self.supports, "joints": self.joints, "q": self.q,
                "total_mass": self.mass, "com": self.com.tolist(),
                "torques": self.torques.tolist(), "fixed_base_torques": self.fixed_base.tolist(),
                "wrenches": {name: wrench.tolist() for name, wrench in self.wrenches.items()},
                "support_polygon": self.polygon.tolist(), "com_margin": self.margin,
                "stands": self.stands, "efforts": self.efforts.tolist(), "holds": self.holds,
                "lifted": self.lifted, "assumption": self.assumption}


def build_standing(robot, supports: list[str]) -> Standing:
    """The robot with a free-flyer root and its support links' contact points; DynamicsError
    for an unknown support or one without geometry."""
    import pinocchio as pin

    from urdftool.kinematics.tree import beside_the_tree, posed_links
    from urdftool.physics.dynamics import build
    from urdftool.physics.solids import surface_points

    fixed = build(robot)
    # the free root as dynamics --floating builds it (its rows are the wrenches' here, so the
    # joints are the fixed model's); the fixed model's build has refused what urdfdom refuses
    free = build(robot, floating=True)
    floating = free.model
    model = Model(floating, free.data, fixed.joints, fixed.variables, fixed.mimics,
                  multiple=fixed.multiple)
    frames, points = [], []
    # (a usage error in every command; a link beside the tree is in no model: its frame was
    # an IndexError)
    UnknownLink.unless_among(supports, posed_links(robot), beside_the_tree(robot))
    for name in supports:
        link_points, problems = surface_points(robot, robot.links[name])
        if not len(link_points):
            detail = f" ({problems[0][1]})" if problems else ""
            raise DynamicsError(f"support link '{name}' has no collision or visual geometry to "
                                f"stand on{detail}", robot.links[name])
        frames.append(floating.getFrameId(name, pin.FrameType.BODY))
        points.append(link_points)
    return Standing(model, list(supports), frames, points, fixed)


def _placed(standing: Standing, q_values: dict) -> tuple[np.ndarray, list[np.ndarray]]:
    """Pinocchio's q with the root placed (first support level, lowest support point at z = 0)
    and each support's points in the ground frame."""
    import pinocchio as pin

    m, d = standing.model.model, standing.model.data
    q = standing.model.configuration(q_values)  # the root at the identity
    pin.framesForwardKinematics(m, d, q)
    root = d.oMf[standing.frames[0]].inverse()  # makes the first support the identity
    placed = [root * d.oMf[frame] for frame in standing.frames]
    world = [points @ pose.rotation.T + pose.translation
             for points, pose in zip(standing.points, placed)]
    ground = min(float(p[:, 2].min()) for p in world)
    root.translation = root.translation - np.array([0.0, 0.0, ground])
    q[:7] = pin.SE3ToXYZQUAT(root)
    for p in world:
        p[:, 2] -= ground
    return q, world


def stand(standing: Standing, q_values: dict, polygon: bool = True) -> Stance:
    """The joint torques, support wrenches, centre of mass and support polygon of the robot
    standing on its supports at ``q_values`` (variable values by name; the rest 0)."""
    import pinocchio as pin

    model = standing.model
    m, d = model.model, model.data
    q, world = _placed(standing, q_values)
    gravity = pin.computeGeneralizedGravity(m, d, q).copy()
    pin.computeJointJacobians(m, d, q)
    pin.updateFramePlacements(m, d)
    jacobians = [frame_jacobian(m, d, frame, pin.LOCAL_WORLD_ALIGNED)
                 for frame in standing.frames]
    base = np.hstack([jacobian[:, :6].T for jacobian in jacobians])  # [6, 6 k]
    if len(jacobians) == 1:
        wrench = np.linalg.solve(base, gravity[:6])
    else:
        wrench = np.linalg.lstsq(base, gravity[:6], rcond=None)[0]  # least norm
    wrenches = wrench.reshape(len(jacobians), 6)
    joint_torques = gravity[6:] - sum(jacobian[:, 6:].T @ f
                                      for jacobian, f in zip(jacobians, wrenches))
    index = [model.row(name) - 6 for name in model.joints]
    torques = joint_torques[index]
    com = pin.centerOfMass(m, d, q).copy()
    mass = float(sum(inertia.mass for inertia in m.inertias))
    lifted = {name: float(p[:, 2].min()) for name, p in zip(standing.supports, world)}
    contacts = np.vstack([p[p[:, 2] <= CONTACT] for p in world])
    hull = convex_hull(contacts[:, :2]) if polygon else np.zeros((0, 2))
    stance = Stance(standing.supports, model.joints, dict(q_values), mass, torques,
                    _fixed_base(standing, q_values), dict(zip(standing.supports, wrenches)),
                    com, hull, margin(hull, com[:2]) if polygon else math.nan,
                    {name: height if height > CONTACT else 0.0 for name, height in lifted.items()},
                    contacts, _efforts(model), SHARED_LOAD if len(jacobians) > 1 else None)
    for name, height in lifted.items():
        if height > CONTACT:
            stance.warnings.append(f"support '{name}' is {number(height * 1000, places=1)} mm "
                                   "above the "
                                   "ground: it cannot carry the share it is given")
    return stance


def _efforts(model: Model) -> np.ndarray:
    """Each joint's effort limit [N m or N], in ``model.joints`` order."""
    return np.array([model.model.effortLimit[model.row(name)] for name in model.joints])


def _fixed_base(standing: Standing, q_values: dict) -> np.ndarray:
    import pinocchio as pin

    fixed = standing.fixed
    return pin.computeGeneralizedGravity(fixed.model, fixed.data,
                                         fixed.configuration(q_values)).copy()


@dataclass
class StandingLoads:
    """Worst standing loads per joint over the poses in which the robot stands (every support
    on the ground, the centre of mass over the support polygon): ``stable`` of the ``poses`` drawn (the zero pose and the
    random ones); ``zero_stands``: whether the zero pose is one of them."""

    loads: list[JointLoad]
    poses: int
    stable: int
    zero_stands: bool


def standing_loads(standing: Standing, samples: int, seed: int = 0,
                   progress=None) -> StandingLoads:
    """Per joint, the largest standing |torque| over the zero pose and ``samples`` random poses
    within the limits (as urdftool.physics.dynamics.gravity_loads) in which the robot stands,
    against its effort limit; the poses in which it tips over or lifts a support are left
    out."""
    stable = []

    def torques(pose):
        stance = stand(standing, pose)
        stable.append(stance.stands and not any(stance.lifted.values()))
        return stance.torques if stable[-1] else None

    loads = gravity_loads(standing.model, samples, seed, torques, progress)
    if not any(stable):
        loads = []
    return StandingLoads(loads, len(stable), sum(stable), bool(stable and stable[0]))


def convex_hull(points: np.ndarray) -> np.ndarray:
    """The convex hull of 2-D points, counter-clockwise, without repeated or collinear corners
    (Andrew's monotone chain); fewer than three corners for a point or a segment."""
    unique = sorted({(round(float(x), 12), round(float(y), 12)) for x, y in points})
    if len(unique) <= 2:
        return np.array(unique, dtype=float).reshape(-1, 2)

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for point in unique:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], point) <= 1e-15:
            lower.pop()
        lower.append(point)
    for point in reversed(unique):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], point) <= 1e-15:
            upper.pop()
        upper.append(point)
    return np.array(lower[:-1] + upper[:-1], dtype=float)


def margin(polygon: np.ndarray, point: np.ndarray) -> float:
    """Distance [m] from ``point`` to the nearest edge of the counter-clockwise ``polygon``:
    positive inside, negative outside (and for a polygon of fewer than three corners, which
    has no inside)."""
    if len(polygon) == 0:
        return -math.inf
    if len(polygon) == 1:
        return -float(np.linalg.norm(point - polygon[0]))
    edges = list(zip(polygon, np.roll(polygon, -1, axis=0)))
    if len(polygon) == 2:
        edges = edges[:1]
    distances = []
    inside = len(polygon) >= 3
    for a, b in edges:
        edge = b - a
        t = min(1.0, max(0.0, float((point - a) @ edge / (edge @ edge))))
        distances.append(float(np.linalg.norm(point - (a + t * edge))))
        if edge[0] * (point[1] - a[1]) - edge[1] * (point[0] - a[0]) < 0:
            inside = False
    nearest = min(distances)
    return nearest if inside else -nearest
