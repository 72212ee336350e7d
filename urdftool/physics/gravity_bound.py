"""The worst gravity torque of each joint over its robot's joint ranges, not over a sample.

``dynamics --samples N`` draws N poses; the largest |G_i(q)| among them reads a few per cent
below the true largest over the ranges, so an effort limit in that gap passes. This module
climbs from the worst samples to a maximum, one variable at a time, and the step along one
variable is exact:

- for a revolute or continuous joint's angle t, with every other variable held, G_i is
  ``A cos t + B sin t + C``: the torque is a triple product of vectors that the joint's
  rotation turns (those below it, or gravity seen from those above it), linear in its
  rotation matrix. Three evaluations give A, B, C; the maximum over [lower, upper] is at an end
  or at ``atan2(B, A)``;
- for a prismatic joint G_i is affine in its travel: the maximum is at an end;
- a variable that drives mimic joints turns several rotations at once: its maximum is found
  on a grid of 64 points refined by golden-section search (no longer exact: the result is
  still a torque the robot reaches, so a lower bound of the maximum).

Each sweep cannot lower the value, and the climb stops when a sweep gains less than 1e-12
(relative). The result is a torque the robot reaches within its ranges (the pose is given), at
least the sampled worst; starting from several of the worst samples, for the largest positive
and the largest negative torque, it finds the maximum over the ranges unless that lies at a
local maximum none of them climbs to (``tests/physics/test_gravity_bound.py`` checks it
against brute-force grids). Units: [N m] or [N].
"""

from __future__ import annotations

import math

import numpy as np

from urdftool.physics.dynamics import (_ROUND_OFF, JointLoad, Model, gravity_variables,
                                       held_coordinates, sampled_loads)

STARTS = 2  # the worst samples climbed from, for each sign of the torque
SWEEPS = 100
GAIN = 1e-12  # relative: a sweep that gains less than this ends the climb
_GRID = 64
_GOLDEN = (math.sqrt(5) - 1) / 2


class _Torque:
    """G_i(q) of one joint as a function of the variables' values (a vector in
    ``model.variables`` order): Pinocchio's q is written in place, each variable to the joints
    it drives (itself and the mimic joints that follow it)."""

    def __init__(self, model: Model, joint: str, followers: dict | None = None):
        import pinocchio as pin

        self.model, self.gravity = model, pin.computeGeneralizedGravity
        m = model.model
        # the joint's actuator's torque: its own G, plus each mimic joint's it drives times
        # that one's multiplier (urdftool.physics.dynamics.actuated)
        self.rows = [(model.row(name), weight) for name, weight in
                     [(joint, 1.0), *(followers or {}).items()]]
        index = {variable.name: k for k, variable in enumerate(model.variables)}
        self.writes: list[list[tuple[int, int, float, float]]] = [[] for _ in index]
        # a coordinate of a joint of several variables (planar, floating): variable -> (its
        # joint's first index in q, the joint's coordinate values, which one it is)
        self.coordinates: dict[int, tuple[int, list, int]] = {}
        blocks: dict[str, tuple[int, list]] = {}
        for name in model.joints:
            found = model.coordinate(name)
            if found is not None:
                owner, which = found
                if owner not in blocks:
                    blocks[owner] = (m.joints[m.getJointId(owner)].idx_q,
                                     [0.0] * len(model.multiple[owner]))
                if name in index:
                    self.coordinates[index[name]] = (*blocks[owner], which)
                continue
            variable, multiplier, offset = model.mimics.get(name, (name, 1.0, 0.0))
            if variable in index:
                found = m.joints[m.getJointId(name)]
                self.writes[index[variable]].append((found.idx_q, found.nq, multiplier, offset))
        self.q = pin.neutral(m)
        self.evaluations = 0

    def set(self, k: int, value: float) -> None:
        """Variable ``k`` to ``value`` (and the mimic joints it drives)."""
        q = self.q
        if k in self.coordinates:  # its joint's whole block, from all its coordinates
            from urdftool.physics.dynamics import coordinates_q

            start, pose, which = self.coordinates[k]
            pose[which] = value
            block = coordinates_q(pose)
            q[start:start + len(block)] = block
            return
        for start, nq, multiplier, offset in self.writes[k]:
            angle = multiplier * value + offset
            if nq == 2:  # continuous: (cos, sin)
                q[start], q[start + 1] = math.cos(angle), math.sin(angle)
            else:
                q[start] = angle

    def load(self, values: np.ndarray) -> None:
        for k, value in enumerate(values):
            self.set(k, float(value))

    def __call__(self, values: np.ndarray | None = None) -> float:
        """The torque at the values set (``values``: set them all first)."""
        if values is not None:
            self.load(values)
        self.evaluations += 1
        gravity = self.gravity(self.model.model, self.model.data, self.q)
        return float(sum(weight * gravity[row] for row, weight in self.rows))


def worst_loads(model: Model, samples: int, seed: int = 0, progress=None) -> list[JointLoad]:
    """Per joint, the worst |G(q)| over the joint ranges: the zero pose and ``samples`` random
    poses (:func:`urdftool.physics.dynamics.gravity_loads`), then climbed from the worst.
    ``progress``: called with (poses done, poses) as the samples are."""
    loads, poses, torques = sampled_loads(model, samples, seed, progress=progress)
    refine(model, loads, poses, torques)
    return loads


def refine(model: Model, loads: list[JointLoad], samples: np.ndarray,
           torques: np.ndarray) -> None:
    """Raise each load's ``worst`` to the largest |G_i| reached climbing from the worst of
    ``samples`` ([poses, variables], in ``model.variables`` order; ``torques`` [poses, joints]
    their G in ``model.joints`` order); ``sampled`` keeps the sample's worst. Loads are changed
    in place."""
    variables = model.variables
    index = {variable.name: k for k, variable in enumerate(variables)}
    for column, load in enumerate(loads):
        load.sampled = load.worst
        held = set(held_coordinates(model))
        free = sorted(index[name] for name in gravity_variables(model, load.joint)
                      if name in index and index[name] not in held)
        if not free or not len(samples):
            continue
        torque = _Torque(model, load.joint, load.followers)
        column_values = torques[:, column]
        for sign in (1.0, -1.0):
            order = np.argsort(-sign * column_values)[:STARTS]
            for start in order:
                values = _within(variables, samples[start])
                values, best = _climb(torque, variables, free, values, sign)
                if abs(best) > load.worst and abs(best) >= _ROUND_OFF:
                    load.worst = abs(best)
                    load.worst_pose = {variables[k].name: float(values[k])
                                       for k in range(len(variables))}
        load.evaluations = torque.evaluations


def _within(variables, values: np.ndarray) -> np.ndarray:
    """A copy of a pose with each variable brought within its range (the zero pose may lie
    outside one)."""
    clipped = np.array(values, dtype=float)
    for k, variable in enumerate(variables):
        lower, upper, _ = _span(variable)
        clipped[k] = min(max(clipped[k], lower), upper)
    return clipped


def _climb(torque: _Torque, variables, free, values: np.ndarray, sign: float):
    """Coordinate ascent of ``sign * torque`` over the ``free`` variables from ``values``:
    (the values reached, the torque there)."""
    current = sign * torque(values)  # sets every variable; each step below sets its own
    for _ in range(SWEEPS):
        before = current
        for k in free:
            values[k], current = _line(torque, variables[k], values, k, sign, current)
        if current - before <= GAIN * max(abs(current), 1e-300):
            break
    return values, sign * current


def _span(variable) -> tuple[float, float, bool]:
    """(lower, upper, whether it wraps: a continuous joint's full turn)."""
    if math.isfinite(variable.lower) and math.isfinite(variable.upper):
        return variable.lower, variable.upper, False
    return -math.pi, math.pi, True


def _line(torque: _Torque, variable, values, k, sign, current):
    """The best value of variable ``k`` with the others held: (value, sign * torque there),
    never worse than ``current``."""
    lower, upper, wraps = _span(variable)
    held = values[k]

    def at(t):
        torque.set(k, t)
        return sign * torque()

    if variable.kind == "prismatic":
        candidates = [(at(lower), lower), (at(upper), upper)]
    elif variable.kind in ("revolute", "continuous") and not _drives_mimics(torque.model, variable):
        candidates = _trigonometric(at, lower, upper, wraps)
    else:
        candidates = _searched(at, lower, upper)
    best_value, best_t = max(candidates)
    if best_value > current:
        values[k] = best_t
        torque.set(k, best_t)
        return best_t, best_value
    values[k] = held
    torque.set(k, held)
    return held, current


def _drives_mimics(model: Model, variable) -> bool:
    return any(source == variable.name for source, _, _ in model.mimics.values())


def _trigonometric(at, lower, upper, wraps):
    """The maximum of ``A cos t + B sin t + C`` over [lower, upper] (the whole circle when it
    wraps), from three evaluations: (value, t) candidates."""
    t0 = 0.0
    f0, f1, f2 = at(t0), at(t0 + 2 * math.pi / 3), at(t0 + 4 * math.pi / 3)
    c = (f0 + f1 + f2) / 3
    a = (2 * f0 - f1 - f2) / 3  # f(t) = a cos t + b sin t + c at t = 0, 2pi/3, 4pi/3
    b = (f1 - f2) / math.sqrt(3)
    peak = math.atan2(b, a)
    candidates = []
    if wraps:
        candidates.append((at(peak), peak))
    else:
        for t in (lower, upper):
            candidates.append((at(t), t))
        for turn in range(-3, 4):
            t = peak + 2 * math.pi * turn
            if lower <= t <= upper:
                candidates.append((at(t), t))
    return candidates


def _searched(at, lower, upper):
    """A grid of 64 points and the ends, the best refined by golden-section search."""
    grid = np.linspace(lower, upper, _GRID)
    values = [at(float(t)) for t in grid]
    best = int(np.argmax(values))
    a, b = float(grid[max(best - 1, 0)]), float(grid[min(best + 1, _GRID - 1)])
    candidates = [(values[best], float(grid[best]))]
    x1, x2 = b - _GOLDEN * (b - a), a + _GOLDEN * (b - a)
    f1, f2 = at(x1), at(x2)
    for _ in range(40):
        if f1 >= f2:
            b, x2, f2 = x2, x1, f1
            x1 = b - _GOLDEN * (b - a)
            f1 = at(x1)
        else:
            a, x1, f1 = x1, x2, f2
            x2 = a + _GOLDEN * (b - a)
            f2 = at(x2)
    candidates += [(f1, x1), (f2, x2)]
    return candidates
