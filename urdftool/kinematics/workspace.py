"""The reach envelope of a limb (kinematics.chain.Chain) from sampled in-limit configurations.

Each sample's tip position [m] is in the base frame, with its manipulability (Yoshikawa's
``sqrt(det(J J^T))`` of the position rows of the Pinocchio frame Jacobian: 0 at a singularity,
larger where the tip moves easily in every direction).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from urdftool.kinematics.chain import Chain


@dataclass
class Workspace:
    """Sampled limb values ``values`` [N, joints], the tip positions ``points`` [N, 3] they give
    and their ``manipulability`` [N]; ``centre`` is the limb's first joint (base frame),
    ``reach`` the largest distance from it [m]."""

    base: str
    tip: str
    joints: list[str]
    samples: int
    seed: int
    values: np.ndarray
    points: np.ndarray
    manipulability: np.ndarray
    centre: np.ndarray

    @property
    def reach(self) -> float:
        return float(np.linalg.norm(self.points - self.centre, axis=1).max())

    @property
    def horizontal_reach(self) -> float:
        """The largest distance from the first joint in the base's x-y plane [m]."""
        return float(np.linalg.norm((self.points - self.centre)[:, :2], axis=1).max())

    @property
    def lower(self) -> np.ndarray:
        return self.points.min(axis=0)

    @property
    def upper(self) -> np.ndarray:
        return self.points.max(axis=0)

    @property
    def mean_manipulability(self) -> float:
        """The mean of :attr:`manipulability`, scaled by its largest where the plain sum
        overflows (2,000 measures of 1e306: "mean inf")."""
        with np.errstate(over="ignore"):
            mean = float(self.manipulability.mean())
        if math.isfinite(mean):
            return mean
        peak = float(self.manipulability.max())
        return peak * float((self.manipulability / peak).mean())

    def as_dict(self) -> dict:
        return {"base": self.base, "tip": self.tip, "joints": self.joints,
                "samples": self.samples, "seed": self.seed, "centre": self.centre.tolist(),
                "reach": self.reach, "horizontal_reach": self.horizontal_reach,
                "lower": self.lower.tolist(), "upper": self.upper.tolist(),
                "vertical_extent": float(self.upper[2] - self.lower[2]),
                "manipulability": {"min": float(self.manipulability.min()),
                                   "mean": self.mean_manipulability,
                                   "max": float(self.manipulability.max())}}


def manipulability(jacobian: np.ndarray) -> float:
    """Yoshikawa's measure of the position rows: ``sqrt(det(J J^T))`` (``J^T J`` for fewer
    than three joints); where that overflows, of the rows scaled first by a power of two near
    their largest entry: a ``--point`` 1e60 m from the tip squared and cubed past the float
    range ("mean inf"), where the measure itself (1e180) is a float. Infinite only when the
    measure is."""
    rows = jacobian[:3]
    with np.errstate(over="ignore", invalid="ignore"):
        measure = _measure(rows)
    if math.isfinite(measure):
        return measure
    largest = float(np.abs(rows).max(initial=0.0))
    if not math.isfinite(largest):
        return math.inf
    exponent = math.frexp(largest)[1]
    scaled = _measure(np.ldexp(rows, -exponent))
    try:
        return math.ldexp(scaled, exponent * min(rows.shape))
    except OverflowError:
        return math.inf


def _measure(rows: np.ndarray) -> float:
    square = rows @ rows.T if rows.shape[1] >= 3 else rows.T @ rows
    return math.sqrt(max(0.0, float(np.linalg.det(square))))


def sample(chain: Chain, samples: int, seed: int = 0, progress=None) -> Workspace:
    """``samples`` random in-limit configurations of the limb (continuous joints over a turn;
    the zero-or-mid-range configuration first) and where they put the tip.

    progress: called with (configurations done, samples) as they are
    """
    from urdftool.kinematics.configuration import random
    from urdftool.kinematics.ik import reach

    values = np.vstack([chain.x_of(chain.row)[None, :],
                        random(chain.variables, samples - 1, seed).values])
    points = np.empty((samples, 3))
    measure = np.empty(samples)
    for row, x in enumerate(values):
        pose, jacobian = chain.pose_and_jacobian(x, local=False)
        points[row] = pose.translation
        measure[row] = manipulability(jacobian)
        if progress is not None:
            progress(row + 1, samples)
    if not np.isfinite(measure).all():
        from urdftool.errors import ConfigError

        error = ConfigError("the manipulability of the point is past what a float holds (it "
                            "grows as the point's distance from the joints to the power of "
                            "their count, at most 3): give a point nearer its link")
        error.argument = "point"
        raise error
    centre, _ = reach(chain)
    return Workspace(chain.base, chain.tip, [v.name for v in chain.variables], samples, seed,
                     values, points, measure, np.asarray(centre, dtype=float))
