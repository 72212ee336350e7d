"""Self-collision at one configuration: colliding pairs with depth, and the closest others."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from urdftool.errors import UsageError


@dataclass
class Contact:
    """A link pair at the pose: colliding with ``depth`` [m], or ``distance`` [m] apart.

    allowed: why the pair may touch ('Adjacent', an SRDF reason), or '' when it must not
    """

    link1: str
    link2: str
    colliding: bool
    distance: float
    depth: float
    allowed: str = ""


@dataclass
class PoseReport:
    q: dict[str, float]
    colliding: list[Contact]
    closest: list[Contact]
    visual_only: list[str] = field(default_factory=list)
    problems: list = field(default_factory=list)
    srdf: str | None = None

    @property
    def forbidden(self) -> list[Contact]:
        return [contact for contact in self.colliding if not contact.allowed]


def configuration(scene, values: dict[str, str], degrees: bool = False):
    """Configurations (one row) from ``--q`` values (``{name: value text}``) over the default configuration
    (0, or mid-range when 0 is outside the limits), with out-of-limit warnings; bad input raises
    UsageError naming the valid joints."""
    from urdftool.kinematics import configuration as config

    try:
        return config.from_words(scene.variables, values, degrees, scene.kinematics.mimics)
    except config.ConfigError as error:
        raise UsageError(str(error)) from None


def check(scene, q: np.ndarray, allowed: dict[tuple[str, str], str], closest: int = 5,
          srdf: str | None = None) -> PoseReport:
    """Every pair of links with geometry at configuration ``q``."""
    poses = scene.at(q)
    contacts = []
    for index, pair in enumerate(scene.pairs):
        hit, distance, depth = scene.checker.exact(poses, index, contacts=True)
        reason = "Adjacent" if pair in scene.adjacent else allowed.get(pair, "")
        contacts.append(Contact(*pair, hit, distance, depth, reason))
    colliding = sorted((c for c in contacts if c.colliding), key=lambda c: -c.depth)
    apart = sorted((c for c in contacts if not c.colliding and c.allowed != "Adjacent"),
                   key=lambda c: c.distance)
    values = {v.name: float(x) for v, x in zip(scene.variables, q)}
    return PoseReport(values, colliding, apart[:closest], scene.geometry.visual_only,
                      scene.geometry.problems, srdf)
