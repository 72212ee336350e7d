"""Declared inertials against those their geometry implies (``urdftool inertia``).

Returns data only; :mod:`urdftool.cli.inertia` renders it.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from urdftool.physics.inertia import MassProperties, declared, relative_difference, triangle_violation
from urdftool.description.urdf import VARIABLE
from urdftool.physics.solids import _bodies, computed, link_solid, rigid_group
from urdftool.errors import UnknownLink  # noqa: F401 - raised here, re-exported

AGREE_TOLERANCE = 0.1  # relative difference of tensor and com offset (vs link size) that agrees
VERDICTS = ("agrees", "differs", "invalid", "missing", "unknown")


@dataclass
class LinkInertia:
    """One link: declared and computed mass properties, their differences and a verdict.

    source: which geometry the computed values come from (collision, visual, none)
    verdict: agrees, differs, invalid (the declared values are physically impossible or
    malformed), missing (no ``<inertial>``: nothing declared to compare), unknown (no
    geometry to compare with)
    fails: the link makes the robot wrong to simulate (invalid values, or a moving body that
    has no mass at all)
    """

    link: str
    declared: MassProperties | None
    computed: MassProperties | None
    source: str
    verdict: str
    differences: dict = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    element: object = None
    fails: bool = False

    def as_dict(self) -> dict:
        return {"link": self.link,
                "declared": self.declared.as_dict() if self.declared else None,
                "computed": self.computed.as_dict() if self.computed else None,
                "source": self.source, "verdict": self.verdict,
                "differences": self.differences, "notes": self.notes, "fails": self.fails}


def _invalid(properties: MassProperties) -> str | None:
    if not np.isfinite(properties.mass) or not np.all(np.isfinite(properties.inertia)):
        return "not finite"
    if properties.mass < 0:
        return "negative mass"
    moments = properties.principal_moments()
    if properties.mass > 0 and moments[0] < -1e-9 * max(abs(moments).max(), 1e-12):
        return "not positive definite"
    violation = triangle_violation(moments, 1e-3) if properties.mass > 0 and moments[-1] > 0 \
        else None
    return f"violates the triangle inequality ({violation})" if violation else None


def compare_link(robot, link, density: float | None = None) -> LinkInertia:
    """Declared vs computed for one link; mass kept as declared unless ``density`` is given."""
    name = link.get("name", "")  # (urdfdom's name of a link without one: Robot.links)
    mine = declared(link)
    solid = link_solid(robot, link)
    notes = [message for _, message in solid.problems] + solid.assumed
    if solid.source == "visual":
        notes.append("no collision geometry: computed from the visual geometry")
    from urdftool.physics.mass import problem

    beyond = problem(link) if mine is None else None  # (a mass of 1e308, a com at 1e200)
    keep = mine.mass if mine is not None and density is None and mine.mass > 0 else None
    if keep is None and density is None and solid.parts and not beyond:
        notes.append("no declared mass: computed with 1000 kg/m^3 (pass --density)")
    # a declared mass past the bounds is kept by no proposal: none is made without --density
    body = computed(solid, mass=keep, density=density) if not beyond or density else None
    result = MassProperties.of(body) if body is not None else None
    if result is not None and _invalid(result) == "not finite":  # (a mass of 1e308 over its
        # geometry's volume: no inertial to propose, and `--write` wrote ixx="inf" ixy="nan")
        notes.append("computed inertia is past what a float holds: nothing to compare or write")
        result = None
    if link.find("inertial") is None and result is not None:
        verdict = "missing"
        notes.append("no <inertial>: nothing declared to compare with; computed is what its "
                     "geometry implies")
    elif link.find("inertial") is not None and mine is None:
        verdict, notes = "invalid", notes + [f"<inertial>{beyond or ' is malformed'}"]
    elif mine is not None and (invalid := _invalid(mine)):
        verdict, notes = "invalid", notes + [f"declared inertia {invalid}"]
    elif result is None:
        verdict = "unknown"
    else:
        verdict = "agrees"
    differences = {}
    if mine is not None and result is not None:
        low, high = solid.bounds
        size = max(max(h - l for l, h in zip(low, high)), 1e-9)
        differences = {"mass": relative_difference(mine.mass, result.mass),
                       "com": float(np.linalg.norm(mine.com - result.com)) / size,
                       "inertia": relative_difference(mine.inertia, result.inertia)}
        if verdict == "agrees" and max(differences.values()) > AGREE_TOLERANCE:
            verdict = "differs"
    mover = _massless_moving_body(robot, name) if link.find("inertial") is None else None
    if mover is not None:
        notes.append(f"moved by joint '{mover}', and neither it nor a link fixed to it has "
                     "mass: Gazebo drops it, Pinocchio and MuJoCo refuse or go singular")
    return LinkInertia(name, mine, result, solid.source, verdict, differences, notes,
                       link.find("inertial"), fails=verdict == "invalid" or mover is not None)


def _massless_moving_body(robot, name: str) -> str | None:
    """The joint moving link ``name`` when no link of its rigid body declares a positive
    mass; None when it is not moved or carries mass, or when the robot declares no
    ``<inertial>`` at all (a kinematic model, not meant to be simulated). What it reads of the
    whole robot is read once per robot (asked of every link without an inertial)."""
    if not robot.memo(_massless_moving_body, lambda: any(
            link.find("inertial") is not None for link in robot.children("link"))):
        return None
    mover = _movers(robot).get(name)
    if mover is None:
        return None
    return None if _body_has_mass(robot, name) else mover.get("name", "?")


def _body_has_mass(robot, name: str) -> bool:
    """Whether a link of link ``name``'s rigid body declares a positive mass; once per body."""
    bodies = _bodies(robot)
    root = bodies[name][0] if name in bodies else name
    return robot.memo_for(_body_has_mass, root, lambda: any(
        (properties := declared(robot.links[member])) is not None and properties.mass > 0
        for member in rigid_group(robot, name)))


def _movers(robot) -> dict:
    """Link name -> the first joint (in document order) of a moving type whose child it is."""
    def build():
        found = {}
        for joint in robot.children("joint"):
            child = joint.find("child")
            if joint.get("type") in VARIABLE and child is not None:
                found.setdefault(child.get("link"), joint)
        return found

    return robot.memo(_movers, build)


def compare(robot, density: float | None = None, links: list[str] | None = None):
    """Every link of the robot's tree (or the named ones), in document order: the links the
    commands that pose it pose, those beside the tree left out as urdfdom drops them
    (:func:`~urdftool.kinematics.tree.posed_links`); UnknownLink when one of ``links``
    is not among them."""
    from urdftool.kinematics.tree import beside_the_tree, posed_links

    tree = posed_links(robot)
    UnknownLink.unless_among(links or (), tree, beside_the_tree(robot))
    chosen = [link for name, link in tree.items() if not links or name in links]
    return [compare_link(robot, link, density) for link in chosen]


INERTIA_TERMS = (("ixx", 0, 0), ("ixy", 0, 1), ("ixz", 0, 2), ("iyy", 1, 1), ("iyz", 1, 2),
                 ("izz", 2, 2))


def inertial_numbers(properties) -> tuple[str, str, dict[str, str]]:
    """Mass, centre of mass (``x y z``) and the six inertia terms (ixx, ixy, ixz, iyy, iyz,
    izz) as written into a file: 6 significant digits, each term counted from the size that
    bounds it (:func:`~urdftool.numbers.symmetric_texts`) and the com from its largest component
    (at least a millimetre), so that round-off is written 0 (never ``-9e-21``) and a thin rod's
    small moment is not."""
    from urdftool.numbers import MILLIMETRE, number, numbers, symmetric_texts

    texts = symmetric_texts(properties.inertia, 6)
    terms = {name: texts[row][column] for name, row, column in INERTIA_TERMS}
    return (number(float(properties.mass), 6), numbers(properties.com, 6, floor=MILLIMETRE),
            terms)


def inertial_xml(properties: MassProperties, indent: str = "  ") -> str:
    """An ``<inertial>`` block for mass properties: origin at the com, link axes."""
    mass, com, terms = inertial_numbers(properties)
    ixx, ixy, ixz, iyy, iyz, izz = terms.values()
    return (f"{indent}<inertial>\n"
            f"{indent}  <origin xyz=\"{com}\" rpy=\"0 0 0\"/>\n"
            f"{indent}  <mass value=\"{mass}\"/>\n"
            f"{indent}  <inertia ixx=\"{ixx}\" ixy=\"{ixy}\" ixz=\"{ixz}\" iyy=\"{iyy}\" "
            f"iyz=\"{iyz}\" izz=\"{izz}\"/>\n"
            f"{indent}</inertial>")
