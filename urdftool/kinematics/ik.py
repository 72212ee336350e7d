"""Inverse kinematics of a limb (kinematics.chain.Chain): numeric, and closed form where exact.

Numeric: damped least squares (Gauss-Newton with Levenberg's damping) on Pinocchio's frame
Jacobian. With an orientation the error is ``log6(pose^-1 target)`` in the tip frame and the
Jacobian is the LOCAL frame Jacobian through ``Jlog6`` (Pinocchio's CLIK example); position only,
the error is the tip's position in the base frame and the Jacobian its LOCAL_WORLD_ALIGNED rows.
Each step is bounded (to a length of 1 rad or m: near a singularity the raw step is
huge), then joints are clamped into their limits and continuous joints wrapped to (-pi, pi].
Several seeds: the given configuration first, then random in-limit ones; a seed that stops
making progress is left for the next.

Closed form: a limb of two or three revolute joints with parallel axes (a planar limb: hip
pitch, knee, ankle pitch) is solved in the plane of motion (law of cosines, both elbow branches);
a six-joint arm whose first two axes meet and whose last three meet in one point (a spherical
wrist, PUMA-like) by Paden-Kahan subproblems on the product of exponentials (up to eight
branches). The branch within limits that reaches the target nearest the seed is taken; where no
closed form applies or none lands within the limits the numeric solver runs.

Units: positions [m], angles [rad]; residuals are the position distance [m] and the rotation
angle [rad] between the pose reached and the target.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass, field

import numpy as np

from urdftool.numbers import SQUARABLE, length, number, power
from urdftool.errors import ConfigError, available
from urdftool.kinematics.chain import Chain, frame_jacobian, refuse_far

TOLERANCE = 1e-6  # [m] and [rad]
MAX_ITERATIONS = 100  # per seed
SEEDS = 16  # starting points: the given one and 15 random ones
_DAMPING = 1e-12  # as Pinocchio's CLIK example: the step bound does the rest
_MAX_STEP = 1.0  # [rad or m]: the longest step (its 2-norm)
_STALL = 15  # iterations without progress before the next seed
_AT_LIMIT = 1e-9  # [rad or m]
MAX_TARGET = SQUARABLE  # [m] the farthest coordinate of a target: the solver squares distances
# (a target at 1e308 overflowed to "inf m" after numpy's overflow warnings)


@dataclass
class Target:
    """A pose of the tip in the base frame: ``position`` [m], ``rotation`` (3x3) or None for
    position only; ``name`` labels a target read from a file."""

    position: np.ndarray
    rotation: np.ndarray | None = None
    name: str = ""

    def __post_init__(self):
        """ConfigError for a position the solver cannot square (:data:`MAX_TARGET`): every
        target, from words, a file or a frame's pose, is made here."""
        refuse_far("target position", self.position, "the solver", "xyz")

    def se3(self):
        import pinocchio as pin

        return pin.SE3(np.eye(3) if self.rotation is None else self.rotation,
                       np.asarray(self.position, dtype=float))


@dataclass
class Solution:
    """What the solver reached for one target.

    x: the limb's values (Chain.variables order); row: the full variable row
    pose: base^-1 tip reached (4x4); position_error [m], rotation_error [rad] (0 position only)
    iterations: summed over the seeds tried; seeds: how many were tried
    at_limits: (variable, "lower"|"upper") of the limb's joints that end at a limit
    method: "numeric" or "closed form"; reason: why it is not solved (None when solved)
    """

    target: Target
    solved: bool
    x: np.ndarray
    row: np.ndarray
    pose: np.ndarray
    position_error: float
    rotation_error: float
    iterations: int
    seeds: int
    method: str
    at_limits: list = field(default_factory=list)
    reason: str | None = None


SHORTEST_QUATERNION = 1e-12  # a quaternion no longer is no rotation
_POSITION = ("x", "y", "z")
_RPY = ("roll", "pitch", "yaw")
_QUATERNION = ("qx", "qy", "qz", "qw")


def target(xyz, rpy=None, quaternion=None, degrees: bool = False, name: str = "") -> Target:
    """A Target from a position [m] and an optional orientation as roll, pitch, yaw (fixed
    axes X, Y, Z as in URDF; [rad], or degrees) or a quaternion x, y, z, w (normalised)."""
    from urdftool.kinematics import transforms

    rotation = None
    if rpy is not None:
        angles = np.radians(rpy) if degrees else np.asarray(rpy, dtype=float)
        rotation = transforms.rotation_from_rpy(np.asarray(angles, dtype=float)[None])[0]
    elif quaternion is not None:
        import pinocchio as pin

        x, y, z, w = (float(v) for v in quaternion)
        norm = length((x, y, z, w))
        if norm < SHORTEST_QUATERNION:
            raise ConfigError("a quaternion of length 0 is no rotation")
        rotation = pin.Quaternion(w / norm, x / norm, y / norm, z / norm).matrix()
    return Target(np.asarray(xyz, dtype=float), rotation, name)


def read_targets(path: str, degrees: bool = False) -> Targets:
    """Targets from a CSV (header x, y, z and optionally roll, pitch, yaw or qx, qy, qz, qw) or
    JSON file (a list of such objects); ConfigError, located, for anything else, before any
    target is used."""
    from urdftool.kinematics.configuration import read_table

    known = _POSITION + _RPY + _QUATERNION

    def check(names):
        for name in names:
            if name not in known:
                raise ConfigError(f"unknown column '{name}'; " + available("columns", name, known),
                                  f"{path}: header")
        given = set(names)
        for group in (_POSITION, _RPY, _QUATERNION):
            if given & set(group) and not set(group) <= given:
                raise ConfigError(f"give all of {', '.join(group)} or none", f"{path}: header")
        if not set(_POSITION) <= given:
            raise ConfigError("the header must name x, y and z", f"{path}: header")
        if set(_RPY) <= given and set(_QUATERNION) <= given:
            raise ConfigError("give roll, pitch, yaw or qx, qy, qz, qw, not both", f"{path}: header")

    names, table = read_table(path, "target file", "column", check)
    index = {name: k for k, name in enumerate(names)}
    targets = Targets(path, table, [[index[name] for name in group] if group[0] in index else None
                                    for group in (_POSITION, _RPY, _QUATERNION)], degrees)
    targets.refused()
    return targets


class Targets:
    """The targets of a file (:func:`read_targets`), each made (:func:`target`) as it is
    reached: its table of numbers held, not a Target (a position, a 3x3 rotation, a name) for
    every row at once (150,000 targets of a 13.7 MB file were 97 MB and 5 s before the first
    was solved). ``columns``: the table's columns of the position, roll-pitch-yaw and
    quaternion (None: not given)."""

    def __init__(self, path: str, table: np.ndarray, columns: list, degrees: bool) -> None:
        self.path, self.table, self.columns, self.degrees = path, table, columns, degrees

    def __len__(self) -> int:
        return len(self.table)

    def __iter__(self) -> Iterator[Target]:
        return (self.made(number) for number in range(1, len(self.table) + 1))

    def made(self, number: int) -> Target:
        """The target of row ``number`` (from 1); ConfigError located at it when refused."""
        row = self.table[number - 1]
        try:
            return target(*(None if group is None else row[group] for group in self.columns),
                          self.degrees, f"target {number}")
        except ConfigError as error:
            raise ConfigError(str(error), f"{self.path}: row {number}") from None

    def refused(self) -> None:
        """ConfigError at the first row :func:`target` refuses, if any: made of the rows it
        may refuse (a coordinate past :data:`MAX_TARGET`, a quaternion near
        :data:`SHORTEST_QUATERNION` or not finite), found at once for the whole table."""
        doubtful = ~np.all(np.abs(self.table[:, self.columns[0]]) <= MAX_TARGET, axis=1)
        if self.columns[2] is not None:
            quaternions = self.table[:, self.columns[2]]
            with np.errstate(all="ignore"):  # (an underflow is doubtful: target decides)
                doubtful |= ~(np.sqrt((quaternions * quaternions).sum(axis=1))
                              >= 10 * SHORTEST_QUATERNION)
        for number in np.flatnonzero(doubtful):
            self.made(int(number) + 1)


def residuals(chain: Chain, x: np.ndarray, target: Target) -> tuple[np.ndarray, float, float]:
    """(pose reached as 4x4, position error [m], rotation error [rad]) of ``x`` for ``target``."""
    import pinocchio as pin

    pose = chain.pose(x)
    position = float(np.linalg.norm(pose.translation - target.position))
    rotation = 0.0 if target.rotation is None else float(
        np.linalg.norm(pin.log3(pose.rotation.T @ target.rotation)))
    return pose.homogeneous, position, rotation


def _wrap(chain: Chain, x: np.ndarray, continuous: np.ndarray | None) -> np.ndarray:
    """``x`` clamped into the limits and, where ``continuous`` (None: no such joint), wrapped."""
    x = np.minimum(np.maximum(x, chain.lower), chain.upper)
    if continuous is not None:
        x[continuous] = np.mod(x[continuous] + math.pi, 2 * math.pi) - math.pi
    return x


def _linearised(chain: Chain, x: np.ndarray, target: Target, goal):
    """(error e, Jacobian de/dx, squared position error [m^2], squared rotation error) at x:
    position only, e is the tip's offset from the goal in the base frame; else
    ``-log6(pose^-1 goal)`` in the tip frame (Pinocchio's CLIK form, through Jlog6)."""
    import pinocchio as pin

    position_only = target.rotation is None
    pose, jacobian = chain.pose_and_jacobian(x, local=not position_only)
    translation = pose.translation - goal.translation
    if position_only:
        return translation, jacobian[:3], translation @ translation, 0.0
    difference = pose.actInv(goal)
    twist = pin.log6(difference).vector
    rotation = twist[3:]
    return (-twist, pin.Jlog6(difference.inverse()) @ jacobian, translation @ translation,
            rotation @ rotation)


def _solver():
    """numpy's solve without its Python wrapper (errstate, checks: 4x the time of a 6x6
    solve, the cost of an iteration); the public function when the private one moved."""
    try:
        from numpy.linalg import _umath_linalg

        return _umath_linalg.solve1
    except (ImportError, AttributeError):  # pragma: no cover - another numpy
        return np.linalg.solve


_solve = _solver()


def _step(error: np.ndarray, jacobian: np.ndarray, damping: float) -> np.ndarray:
    """The Levenberg-Marquardt step ``-(J^T J + damping I)^-1 J^T e``."""
    hessian = jacobian.T @ jacobian
    hessian.flat[::len(hessian) + 1] += damping
    gradient = jacobian.T @ error
    with np.errstate(all="ignore"):
        step = _solve(hessian, gradient)
        return -(step if np.isfinite(step).all() else _damped_again(hessian, gradient))


def _scaled_damping(hessian: np.ndarray) -> np.ndarray:
    """Levenberg's damping for a descent whose first ``hessian`` (J^T J) is given: ``_DAMPING``
    of its largest diagonal entry, and at least ``_DAMPING`` (Pinocchio's CLIK example's
    absolute damping, which a limb of a metre or so keeps). With a point far off the tip
    (``--point 1e4 0 0``), J^T J is 1e8 and its rounding (1e-8) swamps an absolute 1e-12: the
    matrix is singular to the bit, and what its solve returns (NaN, or a finite step of no
    meaning) depended on the CPU's LAPACK kernels: 1 of 20 reachable targets was solved on one
    machine and 2 on another. Damped relative to its scale, the solve is the same everywhere."""
    scale = float(np.diagonal(hessian).max(initial=0.0))
    return _DAMPING * max(scale, 1.0) * np.eye(len(hessian))


def _damped_again(hessian: np.ndarray, gradient: np.ndarray) -> np.ndarray:
    """The step of a ``hessian`` whose solve was not finite, damped by ``_DAMPING`` of its
    largest diagonal entry; zero (the seed stalls and the next is tried) when that is not
    finite either. ``_DAMPING`` is absolute, as Pinocchio's CLIK example has it: with a point
    100 m off the tip (``--point``), J^T J is 1e4 and the damping vanishes beside it; a limb
    of fewer position rows than joints is then singular to the bit, and the solve was NaN
    (numpy's "invalid value" warning, and a seed spent on steps of NaN)."""
    damped = hessian + _scaled_damping(hessian)  # (its diagonal: squares, and the damping)
    step = _solve(damped, gradient)
    return step if np.isfinite(step).all() else np.zeros_like(gradient)


def _descend(chain: Chain, x: np.ndarray, target: Target, goal, tolerance: float,
             iterations: int, continuous: np.ndarray | None):
    """Damped least squares from ``x``: (x, iterations used, solved, squared error).

    Each step is Gauss-Newton's, lightly damped, shortened to a length of ``_MAX_STEP`` (near a
    singularity the raw step is huge and lands anywhere), then clamped into the limits; the
    joints a step pushes against their limit are left out of it. A seed that has not lowered
    its error for ``_STALL`` iterations is given up. Within the tolerance, one more step is
    taken for the last digits. The loop is written out for speed: an iteration costs little
    more than Pinocchio's own calls."""
    import pinocchio as pin

    m, d, tip = chain.model, chain.data, chain.tip_frame
    position_only = target.rotation is None
    direct = chain._selection is None and chain._base_placement is not None
    if direct:  # q is x and the base stands still: work in the model's world frame
        goal = chain._base_placement * goal
    reference = pin.LOCAL_WORLD_ALIGNED if position_only else pin.LOCAL
    log6, jlog6, solve = pin.log6, pin.Jlog6, _solve
    lower, upper = chain.lower, chain.upper
    damping = None  # (made at the first step, relative to the limb's scale: _scaled_damping)
    target_position = goal.translation
    tolerance2 = tolerance * tolerance
    best, best_x, since = math.inf, x, 0
    polished, limited = False, True
    for iteration in range(iterations + 1):
        if direct:
            pin.computeJointJacobians(m, d, x)
            jacobian = frame_jacobian(m, d, tip, reference)
            pose = pin.updateFramePlacement(m, d, tip)
        else:
            pose, jacobian = chain.pose_and_jacobian(x, local=not position_only)
        # the residual, sign flipped: the step is +H^-1 J^T residual
        if position_only:
            residual = target_position - pose.translation
            jacobian = jacobian[:3]
        else:
            difference = pose.actInv(goal)
            residual = log6(difference).vector
            jacobian = jlog6(difference.inverse()) @ jacobian
        squared = float(residual @ residual)
        done = squared <= tolerance2
        if done and polished:
            return x, iteration, True, squared
        if squared < best * 0.999:
            best, best_x, since = squared, x, 0
        else:
            since += 1
        if not done and (iteration == iterations or since > _STALL):
            return best_x, iteration, False, best
        polished = done
        transposed = jacobian.T
        hessian = transposed @ jacobian
        if damping is None:
            damping = _scaled_damping(hessian)
        hessian += damping
        gradient = transposed @ residual
        step = solve(hessian, gradient)
        if limited:  # some joint is at a limit: the others' step without those it pushes
            pushed = ((x <= lower) & (step < 0)) | ((x >= upper) & (step > 0))
            if pushed.any():
                hessian[pushed, :] = 0.0
                hessian[:, pushed] = 0.0
                hessian[pushed, pushed] = 1.0
                gradient[pushed] = 0.0
                step = solve(hessian, gradient)
        length2 = float(step @ step)
        if not math.isfinite(length2):  # (a hessian singular to the bit: see _damped_again)
            step = _damped_again(hessian, gradient)
            length2 = float(step @ step)
        if length2 > _MAX_STEP * _MAX_STEP:
            step *= _MAX_STEP / math.sqrt(length2)
        moved = x + step
        x = np.minimum(np.maximum(moved, lower), upper)
        limited = bool((x != moved).any())
        if continuous is not None:
            x[continuous] = np.mod(x[continuous] + math.pi, 2 * math.pi) - math.pi
    return x, iterations, True, squared


def blocking_limits(chain: Chain, x: np.ndarray, target: Target) -> list[tuple[str, str]]:
    """(variable, "lower"|"upper") of the joints at a limit that the next step would push
    past: the limits that hold the limb back, not those it merely rests on."""
    error, jacobian, _, _ = _linearised(chain, x, target, target.se3())
    step = _step(error, jacobian, _DAMPING)
    scale = 1e-3 * float(np.abs(step).max(initial=0.0))
    blocked = []
    for variable, value, move in zip(chain.variables, x, step):
        if math.isfinite(variable.lower) and value - variable.lower <= _AT_LIMIT \
                and move < -scale:
            blocked.append((variable.name, "lower"))
        elif math.isfinite(variable.upper) and variable.upper - value <= _AT_LIMIT \
                and move > scale:
            blocked.append((variable.name, "upper"))
    return blocked


@dataclass
class LimbSolutions:
    """What :func:`solve_limb` found: the limb (``chain``), a solution per target, in order
    (``count`` of them, each solved as it is iterated, once: a writer holds one, whatever the
    targets of a file), and warnings about the starting configuration (a joint outside its
    limits)."""

    chain: Chain
    solutions: Iterator[Solution]
    warnings: list[str]
    count: int = 1


def solve_limb(robot, tip: str, base: str | None = None, point=None,
               q: dict[str, str] | None = None, *, xyz=None, rpy=None, quaternion=None,
               frame: str | None = None, frame_q: dict[str, str] | None = None,
               targets_file: str | None = None, name: str = "", degrees: bool = False,
               seeds_count: int = SEEDS, seed: int = 0, tolerance: float = TOLERANCE, iterations: int = MAX_ITERATIONS,
               method: str = "auto") -> LimbSolutions:
    """Joint values that put ``point`` [m] of ``tip`` (default: its origin) at each target,
    relative to ``base`` (default: the root link).

    q: ``{joint: text}``, the first seed and where the joints off the limb stay; the target is
        one of: ``xyz`` [m] with ``rpy`` or ``quaternion`` (position only without them), where
        ``frame`` is at the configuration ``frame_q`` (the same ``point`` on it), or the targets
        of ``targets_file`` (:func:`read_targets`); name: the label of the one target of ``xyz``
        or ``frame``; degrees: angles in degrees; then
        ``seeds_count`` starting points (:func:`seeds`) for :func:`solve`.
    Raises ConfigError whose ``argument`` names the input it is about ('q', 'orientation',
    'frame_q', 'targets'), FKError, IKError, and UnknownLink for an unknown ``frame``,
    ``base`` or ``tip``.
    """
    from urdftool.kinematics import configuration as config
    from urdftool.kinematics.chain import build_chain
    from urdftool.kinematics.fk import KinematicModel, forward_kinematics

    argument = "q"
    try:
        kinematics = KinematicModel(robot)
        start = config.from_words(kinematics.variables, q or {}, degrees, kinematics.mimics)
        chain = build_chain(robot, base, tip, start.values[0], kinematics, point)
        if xyz is not None:
            argument = "orientation"
            wanted = [target(xyz, rpy, quaternion, degrees, name)]
        elif frame is not None:
            argument = "frame_q"
            other = config.from_words(kinematics.variables, frame_q or {}, degrees,
                                      kinematics.mimics)
            pose = forward_kinematics(kinematics, other, [frame], chain.base).matrices[0, 0]
            if point is not None:  # the same point on the target frame
                pose[:3, 3] += pose[:3, :3] @ point
            wanted = [Target(pose[:3, 3], pose[:3, :3], name)]
        else:
            argument = "targets"
            wanted = read_targets(targets_file, degrees)
    except ConfigError as error:
        error.argument = error.argument if error.argument == "point" else \
            "xyz" if error.argument == "xyz" and argument == "orientation" else argument
        raise
    starts = seeds(chain, seeds_count, seed)
    return LimbSolutions(chain, (solve(chain, goal, starts, tolerance, iterations, method)
                                 for goal in wanted), start.warnings, len(wanted))


def seeds(chain: Chain, count: int, seed: int, first: np.ndarray | None = None) -> np.ndarray:
    """``count`` starting points ``[count, len(x)]``: ``first`` (default: the limb's values in
    the chain's row), then random ones within the limits (continuous joints over a turn)."""
    first = chain.x_of(chain.row) if first is None else np.asarray(first, dtype=float)
    first = _wrap(chain, first, chain.continuous)
    if count <= 1:
        return first[None, :]
    from urdftool.kinematics.configuration import random_stream, within

    lower = np.where(np.isfinite(chain.lower), chain.lower, -math.pi)
    upper = np.where(np.isfinite(chain.upper), chain.upper, math.pi)
    return np.vstack([first, within(random_stream(seed), lower, upper, (count - 1, len(first)))])


def solve(chain: Chain, target: Target, starts: np.ndarray | None = None,
          tolerance: float = TOLERANCE, iterations: int = MAX_ITERATIONS,
          method: str = "auto") -> Solution:
    """Joint values that put ``chain.tip`` at ``target`` (in the base frame).

    starts: seeds ``[k, len(x)]`` tried in order until one converges (default: ``seeds(chain,
    SEEDS, 0)``); method: "auto" (closed form where it applies, else numeric), "numeric" or
    "closed form" (numeric when the closed form does not apply)
    """
    starts = seeds(chain, SEEDS, 0) if starts is None else np.atleast_2d(starts)
    if method != "numeric":
        closed = closed_form(chain, target, starts[0], tolerance)
        if closed is not None and closed.solved:
            return closed
    goal = target.se3()
    continuous = chain.continuous if chain.continuous.any() else None
    used, best = 0, None
    for number, start in enumerate(starts, start=1):
        with np.errstate(all="ignore"):  # (a solve that is not finite is damped again)
            x, count, done, squared = _descend(
                chain, _wrap(chain, np.array(start, dtype=float), continuous), target, goal,
                tolerance, iterations, continuous)
        used += count
        if best is None or squared < best[1]:
            best = (x, squared)
        if done:
            break
    return _solution(chain, target, best[0], used, number, "numeric", tolerance)


def _solution(chain, target, x, iterations, tried, method, tolerance) -> Solution:
    pose, position, rotation = residuals(chain, x, target)
    solved = position <= tolerance and rotation <= tolerance
    # a joint of no range (HSR's wrist_ft_sensor_frame_joint, limits 0 and 0) is held, not
    # stopped: it was "at a limit: ... (lower), ... (upper)" on every solution
    at_limits = [(v.name, side) for v, value in zip(chain.variables, x)
                 if not v.upper - v.lower <= _AT_LIMIT
                 for side, limit in (("lower", v.lower), ("upper", v.upper))
                 if math.isfinite(limit) and abs(value - limit) <= _AT_LIMIT]
    result = Solution(target, solved, x, chain.row_of(x), pose, position, rotation, iterations,
                      tried, method, at_limits)
    if not solved:
        result.reason = why_unreachable(chain, target, result)
    return result


def reach(chain: Chain) -> tuple[np.ndarray, float]:
    """(centre [m] in the base frame, radius [m]): every tip position lies within ``radius`` of
    the first moving joint's origin, the sum of the distances between consecutive joint origins
    and to the tip (prismatic travel added at its largest)."""
    import pinocchio as pin

    m, d = chain.model, chain.data
    pin.framesForwardKinematics(m, d, chain.q(chain.x_of(chain.row)))
    base = d.oMf[chain.base_frame]
    points = [d.oMi[j].translation for j in range(1, m.njoints)]
    points.append(d.oMf[chain.tip_frame].translation)
    radius = sum(float(np.linalg.norm(b - a)) for a, b in zip(points, points[1:]))
    for variable in chain.variables:
        if variable.kind == "prismatic":
            radius += max(abs(variable.lower), abs(variable.upper))
    if chain.base_moves:  # the path turns at a common ancestor: measure from the base
        radius += float(np.linalg.norm(points[0] - base.translation))
        return np.zeros(3), radius
    return base.actInv(points[0]), radius


def why_unreachable(chain: Chain, target: Target, result: Solution) -> str:
    """What stops the limb: the reach, the limits it ends against, or the orientation a limb
    with fewer than six joints cannot take."""
    centre, radius = reach(chain)
    distance = float(np.linalg.norm(target.position - centre))
    if distance > radius + 1e-9:
        return (f"out of reach: the target is {number(distance)} m from the limb's first "
                f"joint, beyond its reach of {number(radius)} m")
    reasons = []
    blocked = blocking_limits(chain, result.x, target)
    if blocked:
        reasons.append("held back by the limits of " + ", ".join(
            f"{name} ({side})" for name, side in blocked))
    if target.rotation is not None and len(chain.variables) < 6 and result.rotation_error > 1e-6:
        reasons.append(f"a limb of {len(chain.variables)} joints cannot take every orientation")
    return "; ".join(reasons) or ("no seed found it: the target lies within the reach of the "
                                  "links but likely outside what the limits allow together "
                                  "(more --seeds may find it)")


# -- closed form ------------------------------------------------------------------------------


def planar(chain: Chain):
    """The plane of a 2- or 3-joint revolute limb with parallel axes, or None: (axis a, signs of
    each joint's axis along a, joint origins [k, 3], tip origin, tip rotation at x = 0), all
    in the model's world frame at x = 0."""
    import pinocchio as pin

    n = len(chain.variables)
    kinds = {v.kind for v in chain.variables}
    if n not in (2, 3) or chain.base_moves or not kinds <= {"revolute", "continuous"} \
            or len(chain._slots) != n \
            or any((m, o) != (1.0, 0.0) for _, _, _, m, o, _ in chain._slots):
        return None
    m, d = chain.model, chain.data
    zero = np.zeros(n)
    q = chain.q(zero)
    pin.computeJointJacobians(m, d, q)
    pin.framesForwardKinematics(m, d, q)
    # joints in the reduced model's order: base side first (one branch, as the base is fixed)
    axes = [d.J[3:, idx_v] for _, idx_v, _, _, _, _ in chain._slots]
    axis = axes[0] / np.linalg.norm(axes[0])
    signs = []
    for a in axes:
        if np.linalg.norm(np.cross(a, axis)) > 1e-9:
            return None
        signs.append(1.0 if a @ axis > 0 else -1.0)
    joints = np.array([d.oMi[j].translation for j in range(1, m.njoints)])
    columns = [column for _, _, column, _, _, _ in chain._slots]
    tip = d.oMf[chain.tip_frame]
    return axis, np.array(signs), joints, columns, tip.translation.copy(), tip.rotation.copy()


def _in_plane(vector, u, w) -> complex:
    return complex(vector @ u, vector @ w)


def closed_form(chain: Chain, target: Target, start: np.ndarray,
                tolerance: float = TOLERANCE) -> Solution | None:
    """The closed-form solution of a planar 2- or 3-joint limb (3 joints need an orientation)
    or of a 6-joint arm with a spherical wrist (an orientation needed): of the branches within
    the limits, one that reaches the target, nearest ``start``; None when neither applies."""
    candidates = _planar_branches(chain, target)
    if candidates is None:
        candidates = _spherical_branches(chain, target)
    if candidates is None:
        return None
    inside = [x for x in candidates if np.all(x >= chain.lower - 1e-12)
              and np.all(x <= chain.upper + 1e-12)]
    if not inside:
        return None

    def rank(x):
        _, position, rotation = residuals(chain, x, target)
        return (position > tolerance or rotation > tolerance, float(np.sum(power(x - start, 2))))

    return _solution(chain, target, min(inside, key=rank), 0, 1, "closed form", tolerance)


def _planar_branches(chain: Chain, target: Target) -> list[np.ndarray] | None:
    """Both elbow branches of a planar 2- or 3-joint limb, or None when it is not one."""
    plane = planar(chain)
    if plane is None:
        return None
    axis, signs, joints, columns, tip, tip_rotation = plane
    n = len(columns)
    if n == 3 and target.rotation is None:
        return None
    base = chain.data.oMf[chain.base_frame]
    goal = base.act(np.asarray(target.position, dtype=float))
    u = np.cross(axis, [1.0, 0.0, 0.0])
    if np.linalg.norm(u) < 0.5:
        u = np.cross(axis, [0.0, 1.0, 0.0])
    u /= np.linalg.norm(u)
    w = np.cross(axis, u)
    wanted = _in_plane(goal - joints[0], u, w)
    links = [_in_plane(b - a, u, w) for a, b in zip(joints, list(joints[1:]) + [tip])]
    total = None
    if n == 3:
        turn = base.rotation @ target.rotation @ tip_rotation.T  # Rot(axis, total), if planar
        total = math.atan2(axis @ np.cross(u, turn @ u), u @ turn @ u)
        wanted -= complex(math.cos(total), math.sin(total)) * links[2]
    first, second = links[0], links[1]
    r1, r2 = abs(first), abs(second)
    if r1 < 1e-12 or r2 < 1e-12:
        return None
    cosine = (power(abs(wanted), 2) - r1 * r1 - r2 * r2) / (2 * r1 * r2)
    beta = math.acos(max(-1.0, min(1.0, cosine)))
    alpha1 = math.atan2(first.imag, first.real)
    alpha2 = math.atan2(second.imag, second.real) - alpha1
    candidates = []
    for branch in (beta, -beta):
        theta2 = branch - alpha2
        inner = r1 + r2 * complex(math.cos(branch), math.sin(branch))
        theta1 = math.atan2(wanted.imag, wanted.real) - alpha1 - math.atan2(inner.imag,
                                                                             inner.real)
        thetas = [theta1, theta2] + ([total - theta1 - theta2] if n == 3 else [])
        x = np.zeros(n)
        for column, sign, theta in zip(columns, signs, thetas):
            x[column] = _within(sign * theta, chain.variables[column])
        candidates.append(x)
    return candidates


# -- a 6-joint arm with a spherical wrist: Paden-Kahan subproblems on the product of exponentials


def _turn(axis, point, angle, p):
    """``p`` turned by ``angle`` about the line through ``point`` along the unit ``axis``."""
    cross = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    rotation = np.eye(3) + math.sin(angle) * cross + (1 - math.cos(angle)) * cross @ cross
    return point + rotation @ (p - point), rotation


def _motion(axis, point, angle) -> np.ndarray:
    """The 4x4 rigid motion of turning about a line."""
    moved, rotation = _turn(axis, point, angle, np.zeros(3))
    motion = np.eye(4)
    motion[:3, :3], motion[:3, 3] = rotation, moved
    return motion


def _flat(axis, vector):
    return vector - axis * (axis @ vector)


def _subproblem1(axis, point, p, q) -> float:
    """The angle about the line that takes ``p`` to ``q`` (Paden-Kahan 1)."""
    u, v = _flat(axis, p - point), _flat(axis, q - point)
    return math.atan2(axis @ np.cross(u, v), u @ v)


def _subproblem2(axis1, axis2, point, p, q) -> list[tuple[float, float]]:
    """(angle1, angle2) with turn(axis1, angle1) turn(axis2, angle2) p = q, both lines through
    ``point`` (Paden-Kahan 2): none, one or two pairs."""
    u, v = p - point, q - point
    c = axis1 @ axis2
    alpha = (c * (axis2 @ u) - axis1 @ v) / (c * c - 1)
    beta = (c * (axis1 @ v) - axis2 @ u) / (c * c - 1)
    normal = np.cross(axis1, axis2)
    gamma2 = (u @ u - power(alpha, 2) - power(beta, 2) - 2 * alpha * beta * c) / (normal @ normal)
    if gamma2 < -1e-12:
        return []
    pairs = []
    for sign in ((1.0, -1.0) if gamma2 > 1e-12 else (1.0,)):
        middle = point + alpha * axis1 + beta * axis2 + sign * math.sqrt(max(gamma2, 0.0)) * normal
        pairs.append((_subproblem1(axis1, point, middle, q), _subproblem1(axis2, point, p, middle)))
    return pairs


def _subproblem3(axis, point, p, q, distance) -> list[float]:
    """The angles about the line that put ``p`` at ``distance`` from ``q`` (Paden-Kahan 3)."""
    u, v = _flat(axis, p - point), _flat(axis, q - point)
    flat2 = power(distance, 2) - power(axis @ (p - q), 2)
    nu, nv = np.linalg.norm(u), np.linalg.norm(v)
    if nu < 1e-12 or nv < 1e-12:
        return []
    cosine = (power(nu, 2) + power(nv, 2) - flat2) / (2 * nu * nv)
    if abs(cosine) > 1 + 1e-9:
        return []
    base = math.atan2(axis @ np.cross(u, v), u @ v)
    spread = math.acos(max(-1.0, min(1.0, cosine)))
    return [base - spread, base + spread] if spread > 1e-12 else [base]


def _meeting(point1, axis1, point2, axis2) -> np.ndarray | None:
    """Where two lines meet, or None when they are parallel or pass each other."""
    normal = np.cross(axis1, axis2)
    if normal @ normal < 1e-18:
        return None
    between = point2 - point1
    if abs(between @ normal) / math.sqrt(normal @ normal) > 1e-9:
        return None
    t = np.cross(between, axis2) @ normal / (normal @ normal)
    return point1 + t * axis1


def spherical(chain: Chain):
    """The screws of a 6-joint revolute arm whose first two axes meet and whose last three meet
    in one point (the spherical wrist), or None: (axes [6, 3], points [6, 3], shoulder point,
    wrist centre, tip pose at x = 0) in the model's world frame."""
    import pinocchio as pin

    if len(chain.variables) != 6 or chain._selection is not None or chain.base_moves \
            or any(v.kind not in ("revolute", "continuous") for v in chain.variables):
        return None
    m, d = chain.model, chain.data
    zero = np.zeros(6)
    pin.computeJointJacobians(m, d, zero)
    tip = pin.updateFramePlacement(m, d, chain.tip_frame).homogeneous.copy()
    axes = np.array([d.J[3:, k] / np.linalg.norm(d.J[3:, k]) for k in range(6)])
    points = np.array([d.oMi[j].translation for j in range(1, 7)])
    shoulder = _meeting(points[0], axes[0], points[1], axes[1])
    wrist = _meeting(points[3], axes[3], points[4], axes[4])
    if shoulder is None or wrist is None:
        return None
    on_sixth = _flat(axes[5], wrist - points[5])
    if on_sixth @ on_sixth > 1e-18 or abs(axes[3] @ axes[4]) > 1 - 1e-9 \
            or abs(axes[4] @ axes[5]) > 1 - 1e-9:
        return None
    return axes, points, shoulder, wrist, tip


def _spherical_branches(chain: Chain, target: Target) -> list[np.ndarray] | None:
    """The up to eight solutions of a spherical-wrist arm (shoulder, elbow and wrist branches),
    or None when the arm is not one or the target has no orientation."""
    screws = spherical(chain)
    if screws is None or target.rotation is None:
        return None
    axes, points, shoulder, wrist, tip = screws
    goal = (chain._base_placement * target.se3()).homogeneous
    motion = goal @ np.linalg.inv(tip)  # = e1 e2 ... e6
    centre = motion[:3, :3] @ wrist + motion[:3, 3]
    along = wrist + axes[5]  # a point of the sixth axis, off the fourth and fifth
    across = wrist + np.cross(axes[5], axes[4] if abs(axes[4] @ axes[5]) < 0.9 else axes[3])
    branches = []
    for t3 in _subproblem3(axes[2], points[2], wrist, shoulder,
                           float(np.linalg.norm(centre - shoulder))):
        elbow, _ = _turn(axes[2], points[2], t3, wrist)
        for t1, t2 in _subproblem2(axes[0], axes[1], shoulder, elbow, centre):
            arm = (_motion(axes[0], points[0], t1) @ _motion(axes[1], points[1], t2)
                   @ _motion(axes[2], points[2], t3))
            rest = np.linalg.inv(arm) @ motion  # = e4 e5 e6
            seen = rest[:3, :3] @ along + rest[:3, 3]
            for t4, t5 in _subproblem2(axes[3], axes[4], wrist, along, seen):
                wrist_motion = _motion(axes[3], points[3], t4) @ _motion(axes[4], points[4], t5)
                last = np.linalg.inv(wrist_motion) @ rest
                t6 = _subproblem1(axes[5], wrist, across, last[:3, :3] @ across + last[:3, 3])
                x = np.array([t1, t2, t3, t4, t5, t6])
                branches.append(np.array([_within(t, v) for t, v in zip(x, chain.variables)]))
    return branches


def _within(angle: float, variable) -> float:
    """``angle`` or a turn away from it, inside the variable's limits when one is."""
    angle = math.remainder(angle, 2 * math.pi)
    for candidate in (angle, angle + 2 * math.pi, angle - 2 * math.pi):
        if variable.lower - 1e-12 <= candidate <= variable.upper + 1e-12:
            return candidate
    return angle
