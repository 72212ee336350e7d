"""Self-collision at one configuration: colliding pairs with depth, and the closest others."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from urdftool.collision.matrix import MAX_PAIRS


@dataclass
class Contact:
    """A link pair at the pose: colliding with ``depth`` [m], or ``distance`` [m] apart.

    depth_at_most: a bound on the depth [m] (the depth when it is known; for a non-convex mesh
    in contact the depth of the convex hulls, and ``depth`` None); None when not even that is
    known (a flat mesh)
    allowed: why the pair may touch ('Adjacent', an SRDF reason, 'Welded': held together by
    fixed joints alone, so in contact in every configuration, 'Closing': joined by a joint
    written in a ``<gazebo>`` block, closing a loop), or '' when it must not
    """

    link1: str
    link2: str
    colliding: bool
    distance: float
    depth: float | None
    allowed: str = ""
    depth_at_most: float | None = math.nan  # nan: the depth, when not given

    def __post_init__(self):
        if self.depth_at_most is not None and math.isnan(self.depth_at_most):
            self.depth_at_most = self.depth

    @property
    def touching(self) -> bool:
        """In contact no deeper than :data:`~urdftool.collision.pairs.TOUCHING`: surfaces that
        meet (FCL reports exactly touching shapes as a contact of depth 0), not a collision.
        Non-convex meshes touch when their convex hulls do; whose hulls overlap deeper collide
        (FCL sees their surfaces cross, and how deep is not known)."""
        from urdftool.collision.pairs import TOUCHING

        return self.colliding and self.depth_at_most is not None and \
            self.depth_at_most <= TOUCHING


@dataclass
class PoseReport:
    """What was found at one configuration. problems: collision elements left out (a mesh
    that does not resolve or load, an unusable shape): with any, "no self-collision" is not
    established."""

    q: dict[str, float]
    colliding: list[Contact]
    closest: list[Contact]
    visual_only: list[str] = field(default_factory=list)
    problems: list = field(default_factory=list)
    srdf: str | None = None
    warnings: list[str] = field(default_factory=list)
    joints: int | None = None  # the joints ``q`` sets (a planar joint's 3 coordinates: one)

    @property
    def forbidden(self) -> list[Contact]:
        return [contact for contact in self.colliding if not contact.allowed and
                not contact.touching]


def check_pose(robot, values: dict[str, str], degrees: bool = False,
               srdf: Path | None = None, max_pairs: int | None = MAX_PAIRS) -> PoseReport:
    """Self-collision of ``robot`` at one configuration: ``values`` ({joint: text}) over the
    default (0, or mid-range when 0 is outside the limits), pairs allowed by adjacency or by
    the SRDF's disable_collisions. The SRDF is ``srdf``, else the one found beside the robot
    (urdftool.description.companions.find_srdf), else none.

    Raises ConfigError for a bad joint name or value, SrdfError for an SRDF that cannot be read.
    """
    from urdftool.collision import srdf as srdf_module
    from urdftool.collision.matrix import Scene
    from urdftool.description.companions import find_srdf
    from urdftool.diagnostics import display_path

    scene = Scene(robot, 0.0, max_pairs)
    chosen = configuration(scene, values, degrees)
    srdf = srdf or find_srdf(robot)
    allowed = srdf_module.allowed_pairs(srdf_module.read(srdf)[0]) if srdf else {}
    report = check(scene, chosen.values[0], allowed, srdf=display_path(srdf) if srdf else None)
    report.warnings = chosen.warnings + scene.geometry.assumed
    return report


def configuration(scene, values: dict[str, str], degrees: bool = False):
    """Configurations (one row) from ``{joint: text}`` over the default configuration (0, or
    mid-range when 0 is outside the limits), with out-of-limit warnings; bad input raises
    ConfigError naming the valid joints."""
    from urdftool.kinematics import configuration as config

    return config.from_words(scene.variables, values, degrees, scene.kinematics.mimics)


def check(scene, q: np.ndarray, allowed: dict[tuple[str, str], str], closest: int = 5,
          srdf: str | None = None) -> PoseReport:
    """Every pair of links with geometry at configuration ``q``."""
    from urdftool.kinematics.tree import closing_pairs, welded_pairs

    poses = scene.at(q)
    welded = welded_pairs(scene.robot, set(scene.links))
    closing = closing_pairs(scene.robot, set(scene.links))
    # Parts placed once, not once per pair (that was n^3 at 1,500 links)
    scene.checker.place(parts := scene.checker.part_poses(poses))
    contacts = []
    for index, pair in enumerate(scene.pairs):
        hit, distance, depth, bound = scene.checker.exact(poses, index, contacts=True,
                                                          part_poses=parts, placed=True)
        reason = "Adjacent" if pair in scene.adjacent else allowed.get(pair, "") or \
            ("Welded" if pair in welded else "Closing" if pair in closing else "")
        contacts.append(Contact(*pair, hit, distance, depth, reason, depth_at_most=bound))
    # deepest first (a bound counts as its depth), a contact of no known bound before all
    colliding = sorted((c for c in contacts if c.colliding),
                       key=lambda c: -math.inf if c.depth_at_most is None else -c.depth_at_most)
    apart = sorted((c for c in contacts if not c.colliding and c.allowed != "Adjacent"),
                   key=lambda c: c.distance)
    values = {v.name: float(x) for v, x in zip(scene.variables, q)}
    return PoseReport(values, colliding, apart[:closest], scene.geometry.visual_only,
                      scene.geometry.problems, srdf,
                      joints=len({variable.joint for variable in scene.variables}))
