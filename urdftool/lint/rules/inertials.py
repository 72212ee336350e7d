"""U3xx: inertials (what urdfdom refuses, and what makes simulators drop or reject a body).

Thresholds, chosen so that real robots' dummy links do not trip them:

- A link with zero mass and zero inertia is a massless frame (tool flange, sensor mount,
  ``base_footprint``): fine wherever it is fixed to a body that has mass. Only a *moving* body
  (a link on a non-fixed joint plus every link fixed to it) must have mass.
- Links lighter than 1e-4 kg (0.1 g) are placeholders for frames: their tensor is not judged
  (tools write ``1e-6`` into every field, products included, for such links).
- Moments below ``1e-12 kg m^2`` count as zero (a 1 g, 1 mm part already has ~4e-10).
- Principal moments count as negative below ``-1e-9`` times the largest and below
  ``-1e-12 kg m^2`` (rounding in printed values), and the triangle inequality allows a relative slack of 1e-3 (CAD tools print few
  digits, and thin plates sit exactly on the bound).
"""

from __future__ import annotations

import math

from urdftool.lint.catalogue import Severity, rule
from urdftool.numbers import MILLIMETRE, number, numbers
from urdftool.lint.fixes import Unfixable, inertial_edits, insert_before, offer
from urdftool.description.urdf import VARIABLE
from urdftool.description.xml import first_child
from urdftool.description.values import number_tuple
from urdftool.physics import mat3
from urdftool.physics.mass import INERTIA_ATTRIBUTES, declared, relative_difference, triangle_violation
from urdftool.physics import solids

NEGATIVE_TOLERANCE = 1e-9
NEGATIVE_FLOOR = 1e-12  # [kg m^2]: rounding noise in products of inertia of massless links
ZERO_INERTIA = 1e-12  # [kg m^2]: below this a moment counts as zero
PLACEHOLDER_MASS = 1e-4  # [kg]: lighter links are frames whose tensor is not judged
TRIANGLE_TOLERANCE = 1e-3
COM_MARGIN_FRACTION = 1.0
COM_MARGIN_MIN = 0.05  # [m]
UNIT_FACTORS = (3, 6)  # powers of ten: grams vs kilograms, millimetres vs metres squared
UNIT_POWER_SLACK = 0.15  # the ratio must be within a factor 1.4 of 1e3 or 1e6
UNIT_SHAPE_SLACK = 0.3  # and, rescaled, match the geometry's tensor within 30 %


def _name(link) -> str:
    return link.get("name") or "?"


def _inertial_part(link, tag: str):
    """The ``tag`` child (mass or inertia) of the link's ``<inertial>``, which it has."""
    return first_child(first_child(link, "inertial"), tag)


def _joints_by_child(robot) -> dict:
    found = {}
    for joint, ends in robot.ends().items():
        child = ends["child"][1]
        if ends["child"][0] is not None and child not in found:
            found[child] = joint
    return found


def _fixed_children(robot) -> dict[str, list[str]]:
    children: dict[str, list[str]] = {}
    for joint, ends in robot.ends().items():
        (parent, parent_link), (child, child_link) = ends["parent"], ends["child"]
        if joint.get("type") == "fixed" and parent is not None and child is not None:
            children.setdefault(parent_link, []).append(child_link)
    return children


def _valid(robot) -> list:
    """(link, MassProperties) of every link whose inertial fully parses; computed once per robot
    (every inertia rule asks)."""
    return robot.memo(_valid, lambda: [
        (link, properties) for link in robot.children("link")
        if (properties := declared(link)) is not None and math.isfinite(properties.mass)
        and _finite_tensor(properties.inertia)])


def _finite_tensor(m) -> bool:
    (a, b, c), (d, e, f), (g, h, i) = m
    if math.isfinite(a + b + c + d + e + f + g + h + i):  # else: overflow, or one is not
        return True
    return all(math.isfinite(v) for row in m for v in row)


def _zero_tensor(m) -> bool:
    """Whether every entry of a tensor is zero (below :data:`ZERO_INERTIA`)."""
    (a, b, c), (d, e, f), (g, h, i) = m  # written out (10,000 links, twice): in row order
    return abs(a) < ZERO_INERTIA and abs(b) < ZERO_INERTIA and abs(c) < ZERO_INERTIA \
        and abs(d) < ZERO_INERTIA and abs(e) < ZERO_INERTIA and abs(f) < ZERO_INERTIA \
        and abs(g) < ZERO_INERTIA and abs(h) < ZERO_INERTIA and abs(i) < ZERO_INERTIA


def _judged(robot):
    """(link, MassProperties) of links heavy enough for their tensor to matter."""
    for link, properties in _valid(robot):
        if properties.mass >= PLACEHOLDER_MASS:
            yield link, properties


def _from_geometry(robot, link, mass: float):
    """Edits replacing a link's inertial with the one its geometry gives at the declared
    ``mass``; None without usable geometry, Unfixable when a value comes from an expression."""
    solid = _solid(robot, link)
    if not solid.sound or not solid.parts:
        return None  # nothing to compute it from (a missing mesh is reported on its own)
    return inertial_edits(robot, link, solids.computed(solid, mass=mass))


def _solid(robot, link, tag: str | None = None):
    """The link's solids (physics.solids.link_solid, of ``tag`` only when given), built once
    per robot, link and tag: several rules ask."""
    return robot.memo_for((_solid, tag), link, lambda: solids.link_solid(robot, link, tag=tag))


def _recomputed(robot, link, properties, message: str):
    """The finding on ``link``'s <inertia>, with the inertia from geometry as its unsafe fix."""
    return offer(_inertial_part(link, "inertia"), message,
                 f"replace link '{_name(link)}' inertia with its {_solid_source(robot, link)} "
                 "geometry's", _from_geometry(robot, link, properties.mass), safe=False)


def _solid_source(robot, link) -> str:
    return _solid(robot, link).source


def _moving(robot) -> dict:
    """Link name -> the joint that moves it, for links a non-fixed joint moves; once per robot
    (U303 and U304 ask)."""
    return robot.memo(_moving, lambda: {name: joint for name, joint in
                                        _joints_by_child(robot).items()
                                        if joint.get("type") in VARIABLE})


def _prefix(link) -> str:
    return f"link '{_name(link)}': <inertial>"


@rule("U301", "malformed-inertial", Severity.ERROR)
def malformed_inertial(robot):
    """An ``<inertial>`` lacks its mass or one of the six inertia terms, or one is not a number.

    urdfdom needs ``<mass value>`` and ``<inertia>`` with all of ixx, ixy, ixz, iyy, iyz, izz,
    each a finite number. urdfdom refuses the inertial (and older versions the whole robot); Gazebo then drops the link.

    Bad: ``<inertia ixx="0.01" iyy="0.01" izz="0.01"/>``
    Good: ``<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>``
    """
    # a link's first <inertial> whose mass and six terms parse as finite numbers (_valid: its
    # tensor in link axes is finite, which no inf or nan among them leaves) has nothing to say
    sound = {link for link, _ in _valid(robot)}
    for link in robot.children("link"):
        inertials = robot.grouped(link).get("inertial", ())
        for inertial in inertials[1:] if link in sound else inertials:
            mass = first_child(inertial, "mass")
            if mass is None:
                yield inertial, f"{_prefix(link)} has no <mass value=...>"
            elif mass.get("value") is None:
                yield mass, f"{_prefix(link)} <mass> has no value attribute"
            else:
                values, problem = number_tuple(mass.get("value"), 1)
                if problem or not math.isfinite(values[0]):
                    yield mass, f"{_prefix(link)} mass '{mass.get('value')}' is not a finite number"
            inertia = first_child(inertial, "inertia")
            if inertia is None:
                yield inertial, (f"{_prefix(link)} has no <inertia>; give all six of "
                                 f"{', '.join(INERTIA_ATTRIBUTES)}")
                continue
            texts = [inertia.get(a) for a in INERTIA_ATTRIBUTES]
            if None in texts:
                missing = [a for a, text in zip(INERTIA_ATTRIBUTES, texts) if text is None]
                yield inertia, (f"{_prefix(link)} <inertia> lacks {', '.join(missing)} "
                                "(urdfdom needs all six; write 0 for products of inertia that "
                                "vanish)")
            for attribute, text in zip(INERTIA_ATTRIBUTES, texts):
                if text is None:
                    continue
                values, problem = number_tuple(text, 1)
                if problem or not math.isfinite(values[0]):
                    yield inertia, f"{_prefix(link)} {attribute}='{text}' is not a finite number"


@rule("U302", "negative-mass", Severity.ERROR)
def negative_mass(robot):
    """A link's mass is negative.

    Bad: ``<mass value="-1.2"/>``
    Good: ``<mass value="1.2"/>``
    """
    for link, properties in _valid(robot):
        if properties.mass < 0:
            yield _inertial_part(link, "mass"), (
                f"link '{_name(link)}' has negative mass {properties.mass:g} kg")


@rule("U303", "moving-link-without-mass", Severity.ERROR)
def moving_link_without_mass(robot):
    """A link moved by a joint has no mass, counting every link fixed to it.

    Gazebo silently drops massless links (and what hangs below them); Pinocchio and MuJoCo
    refuse or produce a singular mass matrix. A massless frame fixed to a body with mass is fine.

    Only checked when the robot declares at least one ``<inertial>``: a description without any
    is a kinematic model (for visualisation or planning) and is not meant to be simulated.

    Bad: ``<joint type="revolute">`` whose child link has no ``<inertial>``
    Good: the child link has ``<inertial>`` with its real mass, or a link fixed to it has
    """
    if not any(first_child(link, "inertial") is not None for link in robot.children("link")):
        return
    moving = _moving(robot)
    masses = {link.get("name"): p.mass for link, p in _valid(robot)}
    fixed = _fixed_children(robot)
    for name in sorted(moving.keys() & robot.links.keys()):
        body, stack, total = set(), [name], 0.0
        while stack:
            current = stack.pop()
            if current in body:
                continue
            body.add(current)
            total += max(masses.get(current, 0.0), 0.0)
            stack.extend(fixed.get(current, []))
        link = robot.links[name]
        if total <= 0 and not any(first_child(l, "inertial") is not None
                                  and _name(l) not in masses
                                  for l in (robot.links.get(b) for b in body) if l is not None):
            what = "no <inertial>" if first_child(link, "inertial") is None else "zero mass"
            yield link, (f"link '{name}' is moved by joint "
                         f"'{moving[name].get('name')}' but has {what} (nor "
                         "does any link fixed to it); give it its real mass and inertia")


def _principal(robot, link, properties):
    """(principal moments, the largest magnitude) of a link's declared inertial (from
    :func:`_valid`), once per robot and link (U305 and U306 ask)."""
    def compute():
        moments = properties.principal_moments()
        return moments, max(max(abs(m) for m in moments), 1e-300)

    return robot.memo_for(_principal, link, compute)


def _diagonal(properties) -> list[float]:
    return [properties.inertia[i][i] for i in range(3)]


def _negative_moment(properties) -> bool:
    """Whether a diagonal moment is negative (below -NEGATIVE_FLOOR); written out: U304 and
    U305 ask for every link."""
    (xx, _, _), (_, yy, _), (_, _, zz) = properties.inertia
    return xx < -NEGATIVE_FLOOR or yy < -NEGATIVE_FLOOR or zz < -NEGATIVE_FLOOR


@rule("U304", "inertia-not-positive-definite", Severity.ERROR)
def inertia_not_positive_definite(robot):
    """A diagonal moment of inertia is negative, or a moving link with mass has zero inertia.

    A body with mass but no rotational inertia cannot be simulated: MuJoCo refuses it, and
    Gazebo/ODE produce an explosion. Zero mass with zero inertia (a massless frame) is fine.

    Fix (unsafe): the inertia (and inertial origin) computed from the link's geometry at its
    declared mass; a person should confirm the geometry stands for the body.

    Bad: ``<mass value="0.5"/><inertia ixx="0" ... iyy="0" ... izz="0"/>`` on a revolute link
    Good: the inertia of the link's shape, e.g. ``urdftool inertia ROBOT``
    """
    moving = _moving(robot)
    for link, properties in _judged(robot):
        if _negative_moment(properties):
            names = [a for a, v in zip(("ixx", "iyy", "izz"), _diagonal(properties))
                     if v < -NEGATIVE_FLOOR]
            yield _recomputed(robot, link, properties, (
                f"link '{_name(link)}': {', '.join(names)} negative; moments of inertia are "
                "positive"))
        elif _name(link) in moving and _zero_tensor(properties.inertia):
            yield _recomputed(robot, link, properties, (
                f"link '{_name(link)}' has mass {properties.mass:g} kg but zero inertia and is "
                "moved by a joint; give the inertia of its shape"))


@rule("U305", "inertia-indefinite", Severity.ERROR)
def inertia_indefinite(robot):
    """The products of inertia (ixy, ixz, iyz) make the inertia tensor indefinite.

    A principal moment is negative although every diagonal moment is positive. No rigid body has such a tensor; a sign or transcription error is likely (e.g. a CAD tool
    reporting products of inertia with the opposite sign convention).

    Fix (unsafe): the inertia computed from the link's geometry at its declared mass.

    Bad: ``ixx="1" iyy="1" izz="1" ixy="2"`` (principal moments -1, 1, 3)
    Good: ``ixx="1" iyy="1" izz="1" ixy="0.2"``
    """
    for link, properties in _judged(robot):
        if _negative_moment(properties):
            continue
        moments, largest = _principal(robot, link, properties)
        if moments[0] < -max(NEGATIVE_TOLERANCE * largest, NEGATIVE_FLOOR):
            yield _recomputed(robot, link, properties, (
                f"link '{_name(link)}': principal moments "
                f"{', '.join(number(m) for m in moments)} include a negative one; check the "
                "signs of ixy, ixz, iyz"))


@rule("U306", "inertia-triangle-inequality", Severity.ERROR)
def inertia_triangle_inequality(robot):
    """The principal moments violate the triangle inequality (A + B >= C): no body has them.

    MuJoCo refuses the model; Gazebo and PyBullet simulate physically impossible motion.
    Allows a relative slack of 1e-3 for printed rounding.

    Fix (unsafe): the inertia computed from the link's geometry at its declared mass.

    Bad: ``ixx="0.1" iyy="0.1" izz="0.5"`` (0.1 + 0.1 < 0.5)
    Good: ``ixx="0.3" iyy="0.3" izz="0.5"``
    """
    for link, properties in _judged(robot):
        moments, largest = _principal(robot, link, properties)
        if moments[0] < -max(NEGATIVE_TOLERANCE * largest, NEGATIVE_FLOOR) \
                or moments[-1] < ZERO_INERTIA:
            continue
        broken = triangle_violation(moments, TRIANGLE_TOLERANCE)
        if broken:
            yield _recomputed(robot, link, properties, (
                f"link '{_name(link)}': principal moments violate the triangle inequality "
                f"({broken}); recompute with `urdftool inertia`"))


def _link_solids(robot):
    """(link, declared, LinkSolid) for links with mass and geometry, computed once per robot."""
    return robot.memo(_link_solids, lambda: [(link, properties, _solid(robot, link))
                                             for link, properties in _valid(robot)
                                             if properties.mass > 0])


def _rounded(values) -> str:
    """Values rounded to 4 decimals (round half to even), as a list: ``[-0.05, 0.1, 0]``."""
    return "[" + ", ".join(number(round(v, 4), 6) for v in values) + "]"


@rule("U307", "com-outside-geometry", Severity.WARNING)
def com_outside_geometry(robot):
    """A link's centre of mass is far outside the bounding box of its geometry.

    The box holds the link's visual and collision geometry and that of the links fixed to it
    (through fixed joints, either way): a body split into a massless-geometry link and an
    inertial link is one rigid body. "Far" is farther beyond the box than its largest extent
    (and over 5 cm): the inertial origin was probably written in another frame (the joint's,
    or the CAD part's). Skipped when some of that geometry cannot be measured (a mesh that
    does not resolve or load: U407, U408, U412 say why).

    Bad: a 10 cm link with ``<inertial><origin xyz="0.5 0 0"/>``
    Good: the centre of mass inside or near the link's shape
    """
    for link, properties in _valid(robot):
        if not properties.mass > 0:
            continue
        rigid = solids.rigid_bounds(robot, link)
        if rigid.bounds is None or not rigid.complete:
            continue
        low, high = rigid.bounds
        (lx, ly, lz), (hx, hy, hz), (cx, cy, cz) = low, high, properties.com
        # per axis, written out (10,000 links): the same maxima and the same sum
        ox, oy, oz = max(lx - cx, cx - hx, 0.0), max(ly - cy, cy - hy, 0.0), \
            max(lz - cz, cz - hz, 0.0)
        distance = math.sqrt(sum((ox * ox, oy * oy, oz * oz)))
        extent = max(hx - lx, hy - ly, hz - lz)
        if distance > max(COM_MARGIN_FRACTION * extent, COM_MARGIN_MIN):
            com = numbers(properties.com, floor=MILLIMETRE)
            fixed = f" and of {', '.join(repr(n) for n in rigid.links[1:])} fixed to it" \
                if len(rigid.links) > 1 else ""
            yield first_child(link, "inertial"), (
                f"link '{_name(link)}': centre of mass ({com}) is {number(distance, 3)} m outside its "
                f"visual and collision geometry{fixed} (box {_rounded(low)} to "
                f"{_rounded(high)}); check the inertial origin's frame")


@rule("U308", "root-link-inertia", Severity.INFO)
def root_link_inertia(robot):
    """The root link has mass: KDL (robot_state_publisher's dynamics, KDL solvers) ignores it.

    KDL prints "The root link has an inertia specified in the URDF, but KDL does not support a
    root link with an inertia". Add a massless root (e.g. ``base_footprint``) fixed to it.

    Fix (unsafe: the robot's root frame changes name): a massless ``base_footprint`` link
    (another name when taken) and a fixed joint to the old root, written before the old root.

    Bad: ``base_link`` (root) with ``<mass value="5"/>``
    Good: a massless ``base_footprint`` root with ``base_link`` fixed below it

    A note, not a warning: floating-base robots used with Pinocchio or MuJoCo are right to carry
    mass in their root.
    """
    children = {c.get("link") for j in robot.children("joint")
                for c in robot.grouped(j).get("child", ())}
    masses = dict((_name(l), p.mass) for l, p in _valid(robot))
    roots = [name for name in robot.links if name not in children]
    if len(roots) == 1 and masses.get(roots[0], 0) > 0:
        root = robot.links[roots[0]]
        name = next(n for n in ("base_footprint", f"{roots[0]}_root", f"{roots[0]}_massless_root")
                    if n not in robot.links and f"{n}_joint" not in robot.joints)
        location = robot.locations.get(root)
        edits = Unfixable(f"'{roots[0]}' is written in a macro (called at {location.via[0]}); "
                          "add the link beside the call") if location and location.via else \
            insert_before(robot, root, f'<link name="{name}"/>',
                          f'<joint name="{name}_joint" type="fixed"><parent link="{name}"/>'
                          f'<child link="{roots[0]}"/></joint>')
        yield offer(first_child(root, "inertial"), (
            f"root link '{roots[0]}' has mass {masses[roots[0]]:g} kg, which KDL ignores; add a "
            "massless root link fixed to it"), f"add the massless root link '{name}'", edits,
            safe=False)


@rule("U309", "inertia-unit-mistake", Severity.WARNING)
def inertia_unit_mistake(robot):
    """The declared inertia is about 10^3 or 10^6 times off from its geometry's: a unit mistake.

    Compares the declared tensor with the one computed from the link's collision geometry
    (visual if none) with the declared mass: the traces must be within a factor 1.4 of 10^3 or
    10^6 apart and, rescaled by that power, the tensors must agree within 30 % (so placeholder
    values such as ``ixx="1e-3"`` on every link are not mistaken for unit errors). 10^3 points at grams vs
    kilograms (g·m^2), 10^6 at millimetres vs metres (kg·mm^2). Skipped when a mesh is missing
    or has an implausible size (then the mesh is suspect, see U413).

    Fix (unsafe): the inertia computed from the link's geometry at its declared mass.

    Bad: ``<inertia ixx="1200" .../>`` from a CAD tool's kg·mm^2 output
    Good: ``<inertia ixx="0.0012" .../>``
    """
    for link, properties, solid, expected, ratio in _inertia_ratios(robot):
        factor = _unit_factor(properties, expected, ratio)
        if factor is not None:
            direction = "larger" if ratio > 1 else "smaller"
            yield _recomputed(robot, link, properties, (
                f"link '{_name(link)}': declared inertia is {number(ratio, 3)} times the "
                f"{solid.source} geometry's (about 1e{factor} {direction}); a unit mistake? "
                "`urdftool inertia` computes the right values"))


MARKER_EXTENT = 0.01  # [m]: geometry this small marks a frame (a sensor's 1 cm box), not a body


def _trustworthy(solid) -> bool:
    """Geometry that stands for the body: primitives and closed meshes, all loaded, of a
    plausible size (1 mm to 5 m; else the mesh is suspect, see U413)."""
    return solid.sound and solid.counts and 0.001 <= solid.extent <= 5.0


def _body_sized(solid) -> bool:
    """Bigger than a frame marker (over 1 cm) and at most 5 m."""
    return solid.bounds is not None and MARKER_EXTENT * 1.01 < solid.extent <= 5.0


def _inertia_ratios(robot) -> list:
    """(link, declared, solid, computed, ratio of traces) for links whose geometry is
    trustworthy: the computed tensor is ``urdftool inertia``'s, a uniform solid of the
    declared mass. Once per robot (U309 and U310 ask)."""
    def build():
        found = []
        for link, properties, solid in _link_solids(robot):
            if not _trustworthy(solid) or _zero_tensor(properties.inertia):
                continue  # a zero tensor is U304's finding, not a ratio to judge
            expected = solids.computed(solid, mass=properties.mass)
            if mat3.trace(expected.inertia) == 0:  # numpy's inf or nan ratio: no finding
                continue
            ratio = mat3.trace(properties.inertia) / mat3.trace(expected.inertia)
            if ratio > 0:
                found.append((link, properties, solid, expected, ratio))
        return found

    return robot.memo(_inertia_ratios, build)


def _unit_factor(properties, expected, ratio) -> int | None:
    """3 or 6 when the declared tensor is the computed one times 10^+-3 or 10^+-6."""
    power = math.log10(ratio)
    for factor in UNIT_FACTORS:
        if abs(abs(power) - factor) > UNIT_POWER_SLACK:
            continue  # the tensors are compared only at a power near the factor
        divisor = 10.0 ** math.copysign(factor, power)
        rescaled = [[v / divisor for v in row] for row in properties.inertia]
        if relative_difference(rescaled, expected.inertia) <= UNIT_SHAPE_SLACK:
            return factor
    return None


FAR_RATIO = 10.0  # declared vs computed trace: beyond this, no mass distribution explains it


def _largest_trace(properties, solid) -> float:
    """The largest trace any mass distribution inside the geometry's bounding box can have
    about the declared centre of mass: 2 m R^2, R the box corner farthest from it [kg m^2]."""
    low, high = solid.bounds
    reach = sum(max(abs(l - c), abs(h - c)) ** 2 for l, c, h in zip(low, properties.com, high))
    return 2 * properties.mass * reach


@rule("U310", "inertia-far-from-geometry", Severity.WARNING)
def inertia_far_from_geometry(robot):
    """The declared inertia is 10 times off from its geometry's, beyond any mass distribution.

    The computed tensor is what ``urdftool inertia`` reports: the link's collision geometry
    (visual if none) as a solid of uniform density carrying the declared mass. Real links are
    not uniform (motors, hollow shells), and that moves the trace by a factor of 2 or 3, not 10.
    Larger: reported when the trace is over 10 times the computed one *and* over 2 m R^2 (R the
    distance from the declared centre of mass to the farthest corner of the geometry's bounding
    box), which no distribution of the mass inside the geometry reaches, hollow or not.
    Smaller: over 10 times below the uniform solid (most mass within a third of the size around
    the centre of mass). Either way the tensor belongs to another part, another mass or a
    placeholder (``ixx="1e-3"`` copied onto every link). Only judged when the geometry is
    trustworthy: primitives and closed (watertight) meshes, all loaded, over 1 cm (smaller
    boxes mark sensor frames) and up to 5 m in size; a convex hull of an open or hollow mesh is
    not (see U414). Unit slips of 10^3 and 10^6 are U309.

    Bad: a 0.1 kg, 10 x 3 x 3 cm camera with ``ixx="0.0016" iyy="0.0016" izz="0.0016"``
    (24 times its box's)
    Good: ``ixx="1.5e-5" iyy="9.1e-5" izz="9.1e-5"`` (``urdftool inertia`` computes them)
    """
    for link, properties, solid, expected, ratio in _inertia_ratios(robot):
        if properties.mass <= PLACEHOLDER_MASS or not _body_sized(solid):
            continue
        trace = mat3.trace(properties.inertia)
        larger = ratio > FAR_RATIO and trace > _largest_trace(properties, solid)
        if not (larger or ratio < 1 / FAR_RATIO):
            continue
        if _unit_factor(properties, expected, ratio) is not None:
            continue  # U309 says it
        beyond = (f", more than any distribution of that mass inside it can have "
                  f"({number(_largest_trace(properties, solid), 3)})") if larger else ""
        yield _inertial_part(link, "inertia"), (
            f"link '{_name(link)}': declared inertia (trace {number(trace, 3)} kg m^2) is "
            f"{number(ratio, 3)} times that of its {solid.source} geometry as a uniform solid of "
            f"the declared {properties.mass:g} kg (trace "
            f"{number(mat3.trace(expected.inertia), 3)}){beyond}; "
            f"`urdftool inertia --link {_name(link)}` computes it")


DENSEST = 22_590.0  # [kg/m^3]: osmium, the densest element (CRC Handbook of Chemistry and Physics)
LIGHTEST = 0.16  # [kg/m^3]: graphene aerogel, the lightest solid made (Sun et al., Adv. Mater. 2013)


def _volume_bounds(robot, link, solid, mass: float) -> tuple[float, float | None] | None:
    """(smallest, largest) volume the link's drawn body can have [m^3], or None when some
    geometry did not load. The largest takes the bigger of its collision and visual
    geometry with open meshes as their convex hulls (a hull holds the part): dividing the mass
    by it gives the least density the link can have. The smallest counts only when the
    geometry is trustworthy (no hull); a hollow shell's envelope makes it too large, so it
    only bounds the density from below loosely.

    The largest is None when it cannot matter: when ``mass`` [kg] in a lower bound of the
    solid's own volume (found without convex hulls, exact without open meshes) is no denser
    than osmium, no larger volume makes it denser, and no hull or other geometry is built."""
    floor = solid.volume_floor(enough=mass / DENSEST)
    if floor > 0 and mass / floor <= DENSEST:
        return (solids.volume(solid) if _trustworthy(solid) else 0.0), None

    def loaded(s):
        return s.counts and all(solids.HULL_USED in message for _, message in s.problems)

    if not loaded(solid):
        return None
    other = "visual" if solid.source == "collision" else "collision"
    own = solids.volume(solid)
    volumes = [own]
    if robot.grouped(link).get(other):
        second = _solid(robot, link, other)
        if loaded(second):
            volumes.append(solids.volume(second))
    return (own if _trustworthy(solid) else 0.0), max(volumes)


@rule("U311", "implausible-density", Severity.WARNING)
def implausible_density(robot):
    """A link's mass is impossible for the volume of its geometry: a mass or units slip.

    The implied density is the declared mass over the volume of the link's geometry. No
    material is denser than osmium (22,590 kg/m^3; steel is 7,850, aluminium 2,700) and no solid
    lighter than graphene aerogel (0.16 kg/m^3). The volume used for the upper bound is the
    largest the body can have: the bigger of the collision and visual geometry, open meshes
    counting as their convex hulls; so a link heavier than solid osmium filling that volume has
    a wrong mass (a box's mass computed with one dimension missing, grams typed as kilograms)
    or wrong geometry (a mesh scaled twice). Light links are not judged from hulls or
    envelopes: a hollow shell's envelope legitimately holds mostly air (a 2 kg robot torso of
    20 litres is 100 kg/m^3), so only primitives and closed meshes lighter than aerogel count,
    and then as a sign of geometry in millimetres or a mass in tonnes. Links of 0.1 g or less
    (placeholders), geometry of 1 cm or less (a frame's marker box, not its body) and geometry
    that did not load are skipped.

    A warning, not an error: simulation models sometimes mean it (a 1000 kg support anchoring a
    pendulum, 10 g on a hand's virtual link drawn as a 7 mm marker), and only the author knows.

    Bad: ``<mass value="54"/>`` on a 30 x 20 x 1 cm plate (90,000 kg/m^3)
    Good: ``<mass value="1.6"/>`` (aluminium)
    """
    for link, properties, solid in _link_solids(robot):
        if properties.mass <= PLACEHOLDER_MASS or not _body_sized(solid):
            continue
        bounds = _volume_bounds(robot, link, solid, properties.mass)
        if bounds is None or bounds[1] is not None and bounds[1] <= 0:
            continue
        least = properties.mass / bounds[1] if bounds[1] is not None else 0.0
        if least > DENSEST:
            yield _inertial_part(link, "mass"), (
                f"link '{_name(link)}': {properties.mass:g} kg in at most "
                f"{number(bounds[1], 3)} m^3 of geometry is at least "
                f"{number(least, places=0, grouped=True)} kg/m^3, denser than osmium "
                f"({number(DENSEST, places=0, grouped=True)}); a wrong mass or geometry scale")
        elif bounds[0] > 0 and properties.mass / bounds[0] < LIGHTEST:
            yield _inertial_part(link, "mass"), (
                f"link '{_name(link)}': {properties.mass:g} kg in {number(bounds[0], 3)} m^3 of "
                f"{solid.source} geometry is {number(properties.mass / bounds[0], 3)} kg/m^3, "
                "lighter "
                f"than any solid ({LIGHTEST:g}, aerogel); a wrong mass or geometry scale")
