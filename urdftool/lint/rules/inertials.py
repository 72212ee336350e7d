"""U3xx: inertials (what urdfdom refuses, and what makes simulators drop or reject a body).

Thresholds, chosen so that real robots' dummy links do not trip them:

- A link with zero mass and zero inertia is a massless frame (tool flange, sensor mount,
  ``base_footprint``): fine wherever it is fixed to a body that has mass. Only a *moving* body
  (a link on a non-fixed joint plus every link fixed to it) must have mass.
- No mass switches the validity of a tensor off (U304, U305, U306): a 1e-6 kg placeholder
  whose six fields are all ``1e-6`` has principal moments (0, 0, 3e-6), which MuJoCo, Drake
  and sdformat refuse like any other. What counts as zero scales with the mass: moments
  below ``1e-12 kg m^2`` times the mass in kg (up to 1 kg), a radius of gyration under a
  micrometre (a 1 g, 1 mm part already has ~4e-10 kg m^2).
- Principal moments count as negative below ``-1e-9`` times the largest and below
  ``-1e-12 kg m^2`` times the mass (up to 1 kg: rounding in printed values), and the
  triangle inequality allows a relative slack of 1e-3 (CAD tools print few digits, and thin
  plates sit exactly on the bound).
- The comparisons with geometry (U309, U310, U311) leave out links of 0.1 g or less: a
  placeholder frame's tensor has no weight in the dynamics, and its geometry is a marker. The
  physical bound of U316 judges them too: no mass makes a tensor beyond it possible.
"""

from __future__ import annotations

import math

from urdftool.lint.catalogue import Conditional, ReadersTake, Severity, rule
from urdftool.numbers import MILLIMETRE, number, numbers, power
from urdftool.description.urdf import VARIABLE
from urdftool.description.xml import attribute, first_child
from urdftool.description.values import number_tuple, origin_pose
from urdftool.description.values import origin as origin_of
from urdftool.physics import mat3
from urdftool.physics.mass import INERTIA_ATTRIBUTES, Body, declared_of, moments_of, \
    problem_at, relative_difference, triangle_violation
from urdftool.physics import solids
from urdftool.physics.frames import parent_joints
from urdftool.physics.support import inside_own, link_reach
from urdftool.lint.rules.joints import origin_xyz

NEGATIVE_TOLERANCE = 1e-9
NEGATIVE_FLOOR = 1e-12  # [kg m^2]: rounding noise in products of inertia of massless links
ZERO_INERTIA = 1e-12  # [kg m^2]: below this a moment counts as zero
PLACEHOLDER_MASS = 1e-4  # [kg]: lighter links' tensors are not compared with their geometry
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
    return {parent: [child for _, child in below]
            for parent, below in _fixed_joints_below(robot).items()}


def _valid(robot) -> list:
    """(link, MassProperties) of every link whose inertial fully parses; computed once per robot
    (every inertia rule asks)."""
    return robot.memo(_valid, lambda: [
        (link, properties) for link in robot.children("link")
        if (properties := declared_of(robot, link)) is not None and math.isfinite(properties.mass)
        and _finite_tensor(properties.inertia)])


def _finite_tensor(m) -> bool:
    (a, b, c), (d, e, f), (g, h, i) = m
    if math.isfinite(a + b + c + d + e + f + g + h + i):  # else: overflow, or one is not
        return True
    return all(math.isfinite(v) for row in m for v in row)


def _scaled(floor: float, mass: float) -> float:
    """A floor [kg m^2] for a link of ``mass`` [kg]: ``floor`` up to 1 kg, ``floor`` times the
    mass below (so that no mass, however small, makes every moment count as zero)."""
    return floor if mass >= 1.0 else floor * mass


def _zero_tensor(m, zero: float = ZERO_INERTIA) -> bool:
    """Whether every entry of a tensor is zero (below ``zero``)."""
    (a, b, c), (d, e, f), (g, h, i) = m  # written out (10,000 links, twice): in row order
    return abs(a) < zero and abs(b) < zero and abs(c) < zero \
        and abs(d) < zero and abs(e) < zero and abs(f) < zero \
        and abs(g) < zero and abs(h) < zero and abs(i) < zero


def _judged(robot):
    """(link, MassProperties) of links with mass: the validity of a tensor does not depend on
    how light the link is."""
    for link, properties in _valid(robot):
        if properties.mass > 0:
            yield link, properties


def _from_geometry(robot, link, mass: float):
    """Edits replacing a link's inertial with the one its geometry gives at the declared
    ``mass``; None without usable geometry, Unfixable when a value comes from an expression."""
    solid = _solid(robot, link)
    if not solid.sound or not solid.parts:
        return None  # nothing to compute it from (a missing mesh is reported on its own)
    body = solids.computed(solid, mass=mass)
    from urdftool.lint.fixes import inertial_edits  # (only for a finding)
    return inertial_edits(robot, link, body) if body is not None else None


def _solid(robot, link, tag: str | None = None):
    """The link's solids (physics.solids.link_solid, of ``tag`` only when given), built once
    per robot, link and tag: several rules ask."""
    return robot.memo_for((_solid, tag), link, lambda: solids.link_solid(robot, link, tag=tag))


def _recomputed(robot, link, properties, message: str):
    """The finding on ``link``'s <inertia>, with the inertia from geometry as its unsafe fix."""
    from urdftool.lint.fixes import offer  # (only for a finding)
    return offer(_inertial_part(link, "inertia"), message,
                 f"replace link '{_name(link)}' inertia with its {_solid_source(robot, link)} "
                 "geometry's", _from_geometry(robot, link, properties.mass), safe=False)


def _solid_source(robot, link) -> str:
    return _solid(robot, link).source


def _moving(robot) -> dict:
    """Link name -> the joint that moves it, for links a non-fixed joint moves; once per robot
    (U303 and U304 ask)."""
    kinds = robot.kinds()
    return robot.memo(_moving, lambda: {name: joint for name, joint in
                                        _joints_by_child(robot).items()
                                        if kinds[joint] in VARIABLE})


def _prefix(link) -> str:
    return f"link '{_name(link)}': <inertial>"


@rule("U301", "malformed-inertial", Severity.ERROR)
def malformed_inertial(robot):
    """An ``<inertial>`` lacks its mass or one of the six inertia terms, or one is not a number.

    urdfdom needs ``<mass value>`` and ``<inertia>`` with all of ixx, ixy, ixz, iyy, iyz, izz,
    each a finite number. urdfdom refuses the inertial (and older versions the whole robot); Gazebo then drops the link.
    A mass past 1e30 kg, a moment past 2.1e51 kg m^2 or a centre of mass past 4.6e10 m is
    found here too: urdfdom reads it, but what any simulator derives from it (m g z, the
    parallel-axis m d^2, sums over the links) overflows, and urdftool computes nothing from it.

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
            if inertial is inertials[0] and (beyond := problem_at(link)):
                part = first_child(inertial, beyond[0])
                yield (part if part is not None else inertial), f"{_prefix(link)}{beyond[1]}"


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

    What each consumer does with a moving body of no mass (the link and the links fixed to
    it, which every simulator lumps or fuses into one body):

    - **Gazebo** (gazebosim/sdformat ``src/parser_urdf.cc``, ``CreateSDF``, after lumping
      the fixed joints): a link with no ``<inertial>`` or a mass of 0 or less "is not modeled
      in sdf": it, its joint and every link and joint below it are dropped, with a warning in
      the log (Gazebo Classic's older sdformat: a mass within 1e-6 kg of 0).
    - **MuJoCo** (google-deepmind/mujoco ``src/xml/xml_urdf.cc``, fixed links fused,
      ``fusestatic``): a link without ``<inertial>`` takes its mass from its collision
      geometry; a moving body whose mass or a principal moment is below ``mjMINVAL`` (1e-15),
      its fused links counted, is refused: "mass and inertia of moving bodies must be larger
      than mjMINVAL" (``src/user/user_model.cc``, ``CheckBodyMassInertia``).
    - **PyBullet** (bulletphysics/bullet3
      ``examples/Importers/ImportURDFDemo/UrdfParser.cpp``): a link without ``<inertial>``
      is given 1 kg and unit moments ("No inertial data for link, using mass=1"): it loads,
      with dynamics of its own making.
    - **Drake** (RobotLocomotion/drake ``multibody/parsing/detail_urdf_parser.cc``: no
      ``<inertial>`` is zero mass): its articulated-body solver refuses a joint whose child,
      with everything outboard of it, has no mass or moment ("An internal mass matrix
      associated with the joint ... is not positive-definite", ``multibody/tree/
      body_node.cc``); a massless link with a body of mass below it (Drake's planar base
      emulated by x, y and yaw joints) is fine.
    - **Pinocchio** reads it, and its mass matrix is singular (forward dynamics divides by
      zero).
    - A web page's viewer (three.js urdf-loader) reads no mass at all.
    - **Genesis** (its assets, read by ``genesis/utils/urdf.py``) weighs a link without
      ``<inertial>`` as its mesh's volume times the material's density, 1 kg without a mesh.

    So the finding is an error where a simulator may load the file (ROS's, or one nobody is
    known to read), and a warning naming the condition where the readers known take it
    (:mod:`urdftool.description.readers`): "if Gazebo or MuJoCo loads it" in a file only
    Drake reads, when a link below carries mass (a terminal massless body Drake refuses too:
    an error there), or in Genesis's assets when the link has no ``<inertial>``; "if a
    simulator loads it" in a web application's copy.
    A massless frame fixed to a body with mass is fine.

    Only checked when the robot declares at least one ``<inertial>``: a description without any
    is a kinematic model (for visualisation or planning) and is not meant to be simulated.

    Bad: ``<joint type="revolute">`` whose child link has no ``<inertial>``
    Good: the child link has ``<inertial>`` with its real mass, or a link fixed to it has
    """
    if not any(first_child(link, "inertial") is not None for link in robot.children("link")):
        return
    moving = _moving(robot)
    names = robot.names()
    masses = {names[link]: p.mass for link, p in _valid(robot)}
    fixed = _fixed_children(robot)
    for name in sorted(moving.keys() & robot.links.keys()):
        if name not in fixed:  # nothing fixed below it (most links): the walk's one step
            body, total = (name,), 0.0 + max(masses.get(name, 0.0), 0.0)
        else:
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
            takers = {"browser": "a simulator"}  # (a web page's viewer reads no mass)
            if what == "no <inertial>":  # Genesis weighs the link's mesh (1 kg without one)
                takers["genesis"] = "Gazebo or MuJoCo"
            if name in _carried(robot):  # Drake's solver takes it: mass outboard
                takers["drake"] = "Gazebo or MuJoCo"
            yield link, ReadersTake(f"link '{name}' is moved by joint "
                                    f"'{moving[name].get('name')}' but has {what} (nor "
                                    "does any link fixed to it); give it its real mass and "
                                    "inertia", takers)


def _carried(robot) -> set[str]:
    """The names of the links below which (through any joint, moving or fixed) a link has
    mass: walked up from each such link, once per robot."""
    def build():
        parents, ends, found = parent_joints(robot), robot.ends(), set()
        for link, properties in _valid(robot):
            current = _name(link)
            while properties.mass > 0 and current in parents:
                above = ends[parents[current]]["parent"][1]
                if above is None or above in found:
                    break
                found.add(above)
                current = above
        return found
    return robot.memo(_carried, build)


def _rigid_body_has_no_inertia(robot, name: str) -> bool:
    """Whether the rigid body of link ``name`` (it and every link fixed to it, placed by the
    fixed joints' origins) has zero inertia about its centre of mass. Gazebo and gz sim lump
    fixed joints, MuJoCo fuses them (``fusestatic``, its URDF default), Pinocchio merges them:
    a link's zero tensor is no defect when the body they move has inertia."""
    from urdftool.physics.mass import combine, transformed

    fixed = _fixed_joints_below(robot)
    if name not in fixed:  # nothing fixed below it (most links): the link alone
        return True
    parts, stack = [], [(name, (0.0, 0.0, 0.0), mat3.rpy_matrix((0.0, 0.0, 0.0)))]
    seen = set()
    while stack:
        current, xyz, rotation = stack.pop()
        if current in seen:
            continue
        seen.add(current)
        link = robot.links.get(current)
        body = declared_of(robot, link) if link is not None else None
        if body is not None and math.isfinite(body.mass) and body.mass > 0 \
                and _finite_tensor(body.inertia):
            parts.append(transformed(body, xyz, rotation))
        for joint, child in fixed.get(current, ()):
            offset, rpy = origin_pose(joint)
            stack.append((child, mat3.add(mat3.vector(xyz), mat3.apply(rotation, offset)),
                          mat3.multiply(rotation, mat3.rpy_matrix(rpy))))
    whole = combine(parts)
    return _zero_tensor(whole.inertia, _scaled(ZERO_INERTIA, whole.mass))


def _fixed_joints_below(robot) -> dict[str, list]:
    """Link name -> (fixed joint, child link name) of the fixed joints hanging from it."""
    def build():
        below: dict[str, list] = {}
        kinds = robot.kinds()
        for joint, ends in robot.ends().items():
            (parent, parent_link), (child, child_link) = ends["parent"], ends["child"]
            if kinds[joint] == "fixed" and parent is not None and child is not None:
                below.setdefault(parent_link, []).append((joint, child_link))
        return below
    return robot.memo(_fixed_joints_below, build)


def _principal(robot, link, properties):
    """(principal moments, the largest magnitude) of a link's declared inertial (from
    :func:`_valid`), once per robot and link (U305, U306, U314 and U316 ask, of every link:
    looked up in the robot's one dict of them, no function made per asking)."""
    known = _principals(robot)
    found = known.get(link)
    if found is None:  # (properties is the link's declared_of)
        found = known[link] = _moments_and_largest(moments_of(robot, link))
    return found


def _moments_and_largest(moments) -> tuple:
    a, b, c = moments  # (the largest of the three as of a generator over them: the same one)
    return moments, max(max(abs(a), abs(b), abs(c)), 1e-300)


def _principals(robot) -> dict:
    """Link -> :func:`_principal`, once per robot; on a robot of
    :data:`~urdftool.physics.solids.BULK_LINKS` links or more, made at once for every link
    with mass whose tensor has no products of inertia (the moments
    :func:`~urdftool.physics.mat3.eigvalsh` gives such a one: its diagonal sorted), in one
    loop over :func:`_valid` rather than a chain of per-link memos for each; the others are
    added as asked."""
    def build():
        found = {}
        if len(robot.links) < solids.BULK_LINKS:
            return found
        for link, properties in _valid(robot):
            if properties.mass > 0:
                (xx, _, _), (yx, yy, _), (zx, zy, zz) = properties.inertia
                if yx == 0 and zx == 0 and zy == 0:  # (eigvalsh reads the lower triangle)
                    found[link] = _moments_and_largest(tuple(sorted((xx, yy, zz))))
        return found

    return robot.memo(_principals, build)


def _diagonal(properties) -> list[float]:
    return [properties.inertia[i][i] for i in range(3)]


def _negative_moment(properties) -> bool:
    """Whether a diagonal moment is negative (below the negative floor for its mass); written
    out: U304 and U305 ask for every link."""
    (xx, _, _), (_, yy, _), (_, _, zz) = properties.inertia
    floor = -_scaled(NEGATIVE_FLOOR, properties.mass)
    return xx < floor or yy < floor or zz < floor


@rule("U304", "inertia-not-positive-definite", Severity.ERROR)
def inertia_not_positive_definite(robot):
    """A diagonal moment of inertia is negative, or a moving link with mass has zero inertia.

    A body with mass but no rotational inertia cannot be simulated: MuJoCo refuses it, and
    Gazebo/ODE produce an explosion. Zero mass with zero inertia (a massless frame) is fine.
    The body judged is the one simulators move: the link and every link fixed to it (Gazebo
    lumps them, MuJoCo fuses them, Pinocchio merges them), so a zero tensor on a link whose
    fixed foot or hand carries the inertia is no finding.

    Fix (unsafe): the inertia (and inertial origin) computed from the link's geometry at its
    declared mass; a person should confirm the geometry stands for the body.

    Bad: ``<mass value="0.5"/><inertia ixx="0" ... iyy="0" ... izz="0"/>`` on a revolute link
    Good: the inertia of the link's shape, e.g. ``urdftool inertia ROBOT``
    """
    moving, named = _moving(robot), robot.names()
    for link, properties in _judged(robot):
        if _negative_moment(properties):
            names = [a for a, v in zip(("ixx", "iyy", "izz"), _diagonal(properties))
                     if v < -_scaled(NEGATIVE_FLOOR, properties.mass)]
            yield _recomputed(robot, link, properties, (
                f"link '{_name(link)}': {', '.join(names)} negative; moments of inertia are "
                "positive"))
        elif (named[link] or "?") in moving and _zero_tensor(
                properties.inertia, _scaled(ZERO_INERTIA, properties.mass)) \
                and _rigid_body_has_no_inertia(robot, named[link] or "?"):
            yield _recomputed(robot, link, properties, (
                f"link '{_name(link)}' has mass {properties.mass:g} kg but zero inertia and is "
                "moved by a joint; give the inertia of its shape"))


@rule("U305", "inertia-indefinite", Severity.ERROR)
def inertia_indefinite(robot):
    """The products of inertia (ixy, ixz, iyz) make the inertia tensor indefinite.

    A principal moment is negative although every diagonal moment is positive. No rigid body has such a tensor; a sign or transcription error is likely (e.g. a CAD tool
    reporting products of inertia with the opposite sign convention). A product larger than
    its two moments allow (``|ixz| <= sqrt(ixx izz)`` for any body) no sign mends: the message
    says so, and that the moments or products are placeholders or another part's.

    Fix (unsafe): the inertia computed from the link's geometry at its declared mass.

    Bad: ``ixx="1" iyy="1" izz="1" ixy="2"`` (principal moments -1, 1, 3)
    Good: ``ixx="1" iyy="1" izz="1" ixy="0.2"``
    """
    for link, properties in _judged(robot):
        if _negative_moment(properties):
            continue
        moments, largest = _principal(robot, link, properties)
        if moments[0] < -max(NEGATIVE_TOLERANCE * largest,
                             _scaled(NEGATIVE_FLOOR, properties.mass)):
            yield _recomputed(robot, link, properties, (
                f"link '{_name(link)}': principal moments "
                f"{', '.join(number(m) for m in moments)} include a negative one; "
                + _indefinite_why(properties.inertia)))


# a product of inertia and the two moments that bound it: (name, row, column)
_PRODUCTS = (("ixy", 0, 1), ("ixz", 0, 2), ("iyz", 1, 2))


def _indefinite_why(inertia) -> str:
    """What to look at in an indefinite tensor: a product larger than its two moments allow
    (|ixz| <= sqrt(ixx izz) for any body), which no sign mends (LimX's contact links: 1e-12 on
    the diagonal beside ixz 4e-06), else the signs of the products."""
    names = ("ixx", "iyy", "izz")
    for name, row, column in _PRODUCTS:
        product, bound = inertia[row][column], inertia[row][row] * inertia[column][column]
        if product * product > bound * (1 + 1e-6) and bound >= 0:
            return (f"{name} {number(product)} is beyond sqrt({names[row]} {names[column]}) = "
                    f"{number(math.sqrt(bound))}, which no sign of it mends: the moments or the "
                    "products are placeholders, another part's or in other units")
    return "check the signs of ixy, ixz, iyz"


@rule("U306", "inertia-triangle-inequality", Severity.ERROR)
def inertia_triangle_inequality(robot):
    """The principal moments violate the triangle inequality (A + B >= C): no body has them.

    MuJoCo, Drake and sdformat refuse the model; Gazebo and PyBullet simulate physically
    impossible motion. Allows a relative slack of 1e-3 for printed rounding. Judged whatever
    the mass: a placeholder with every field ``1e-6``, products included, has principal
    moments (0, 0, 3e-6), a tensor of rank 1.

    Fix (unsafe): the inertia computed from the link's geometry at its declared mass.

    Bad: ``ixx="0.1" iyy="0.1" izz="0.5"`` (0.1 + 0.1 < 0.5); ``<mass value="1e-6"/>`` with
    ``ixx="1e-6" ixy="1e-6" ixz="1e-6" iyy="1e-6" iyz="1e-6" izz="1e-6"``
    Good: ``ixx="0.3" iyy="0.3" izz="0.5"``; a placeholder's products of inertia 0
    """
    for link, properties in _judged(robot):
        moments, largest = _principal(robot, link, properties)
        if moments[0] < -max(NEGATIVE_TOLERANCE * largest,
                             _scaled(NEGATIVE_FLOOR, properties.mass)) \
                or moments[-1] < _scaled(ZERO_INERTIA, properties.mass):
            continue
        broken = triangle_violation(moments, TRIANGLE_TOLERANCE)
        if broken:
            hint = ("every field is the same, products included: a tensor of rank 1; give a "
                    "placeholder zero products of inertia, or" if _all_equal(properties) else "")
            yield _recomputed(robot, link, properties, (
                f"link '{_name(link)}': principal moments violate the triangle inequality "
                f"({broken}); {hint} recompute with `urdftool inertia`".replace(";  ", "; ")))


def _all_equal(properties) -> bool:
    """Whether the six fields of a declared tensor are one value (a placeholder's)."""
    (xx, xy, xz), (_, yy, yz), (_, _, zz) = properties.inertia
    return xx != 0 and xx == xy == xz == yy == yz == zz


def _link_solids(robot):
    """(link, declared, solid) for links with mass, computed once per robot: the link's
    :class:`~urdftool.physics.solids.PlainSolid` when it is one of a large robot's plain links
    (measured with the others at once: what the rules read of its LinkSolid, the same
    numbers), else its :class:`~urdftool.physics.solids.LinkSolid`, built in order."""
    def build():
        read = solids.plain_links(robot), robot.names()  # (once, not once per link)
        return [(link, properties, solids.plain_solid(robot, link, read) or _solid(robot, link))
                for link, properties in _valid(robot) if properties.mass > 0]

    return robot.memo(_link_solids, build)


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
    decided = _plain_decided(robot)[0]  # (read once, not once per link)
    for link, properties in _valid(robot):
        far = _far_outside_box(robot, link, properties, decided)
        if far is None:
            continue
        distance, rigid = far
        low, high = rigid.bounds
        com = numbers(properties.com, floor=MILLIMETRE)
        fixed = f" and of {', '.join(repr(n) for n in rigid.links[1:])} fixed to it" \
            if len(rigid.links) > 1 else ""
        yield first_child(link, "inertial"), (
            f"link '{_name(link)}': centre of mass ({com}) is {number(distance, 3)} m outside "
            f"its visual and collision geometry{fixed} (box {_rounded(low)} to "
            f"{_rounded(high)}); check the inertial origin's frame")


def _far_outside_box(robot, link, properties, decided: set | None = None):
    """(distance [m], RigidBounds) when the centre of mass is farther outside the box of the
    link's rigid body than U307 allows, else None. ``decided``: the first set of
    :func:`_plain_decided`, for a caller asking of every link."""
    if decided is None:
        decided = _plain_decided(robot)[0]
    if not properties.mass > 0 or link in decided:
        return None
    # the link's own box first: the body's holds it, so a centre of mass near the own box is
    # near the body's (no farther out, the margin no smaller), found without gathering it
    held = solids.held_box(robot, link)
    if held is not None and _far_beyond(held, properties.com) is None:
        return None
    rigid = solids.rigid_bounds(robot, link)
    if rigid.bounds is None or not rigid.complete:
        return None
    distance = _far_beyond(rigid.bounds, properties.com)
    return None if distance is None else (distance, rigid)


def _far_beyond(bounds, com) -> float | None:
    """How far [m] ``com`` lies outside the box ``bounds`` when farther than U307 allows (its
    largest side, at least :data:`COM_MARGIN_MIN`), else None. Each step is monotonic (a
    larger box: no larger distance, no smaller margin), to the bit."""
    (lx, ly, lz), (hx, hy, hz), (cx, cy, cz) = *bounds, com
    # per axis, written out (10,000 links): the same maxima and the same sum
    ox, oy, oz = max(lx - cx, cx - hx, 0.0), max(ly - cy, cy - hy, 0.0), \
        max(lz - cz, cz - hz, 0.0)
    distance = math.sqrt(sum((ox * ox, oy * oy, oz * oz)))
    extent = max(hx - lx, hy - ly, hz - lz)
    if distance > max(COM_MARGIN_FRACTION * extent, COM_MARGIN_MIN):
        return distance
    return None


def _within_half(trace: float, mass: float, bounds) -> bool:
    """Whether ``trace`` [kg m^2] is within U316's bound for ``mass`` [kg] > 0 whatever the
    farthest point of a body in the box ``bounds`` is (it is at least half the box's largest
    side away); monotonic in the box, to the bit: a larger box is within when this one is."""
    (lx, ly, lz), (hx, hy, hz) = bounds
    half = max(hx - lx, hy - ly, hz - lz) / 2  # no point is this close to all of the body
    return trace <= FAR_BEYOND * 2 * mass * half * half


def _plain_decided(robot) -> tuple[set, set, set]:
    """What the links of :func:`~urdftool.physics.solids.plain_links` with mass and a finite
    centre of mass settle at once (numpy, the per-link path's operations in its order, to the
    bit): (links whose centre of mass is not far outside their box (U307), links whose trace
    is within the half-size bound (U316), links whose centre of mass is inside one of their
    own primitives (U312: outside by 0)). Empty below
    :data:`~urdftool.physics.solids.BULK_LINKS` links; once per robot."""
    def build():
        table = solids.plain_links(robot)
        if table is None:
            return set(), set(), set()
        import numpy as np

        links, names, found = [], [], []
        rows, isfinite, named = table.rows, math.isfinite, robot.names()
        for link, properties in _valid(robot):
            name = named[link]
            if name in rows and properties.mass > 0:
                mass, (cx, cy, cz), ((xx, _, _), (_, yy, _), (_, _, zz)) = properties
                if isfinite(cx + cy + cz):  # (overflow too: not asked)
                    links.append(link)
                    names.append(name)
                    found += (cx, cy, cz, mass, xx, yy, zz)
        if not links:
            return set(), set(), set()
        values = np.array(found, dtype=float).reshape(-1, 7)
        com, mass = values[:, :3], values[:, 3]
        trace = values[:, 4] + values[:, 5] + values[:, 6]  # mat3.trace's order
        at = np.fromiter((rows[name] for name in names), dtype=np.intp, count=len(names))
        low, high = table.low[at], table.high[at]
        with np.errstate(all="ignore"):
            # _far_outside_box: per axis max(l - c, c - h, 0), their squares' sum, its root
            outside = np.maximum(np.maximum(low - com, com - high), 0.0)
            distance = np.sqrt(outside[:, 0] * outside[:, 0] + outside[:, 1] * outside[:, 1] +
                               outside[:, 2] * outside[:, 2])
            sides = high - low
            extent = np.maximum(np.maximum(sides[:, 0], sides[:, 1]), sides[:, 2])
            far = distance > np.maximum(COM_MARGIN_FRACTION * extent, COM_MARGIN_MIN)
            # inertia_beyond_geometry: trace <= FAR_BEYOND * 2 * m * half * half, left to right
            half = extent / 2
            within = trace <= FAR_BEYOND * 2 * mass * half * half
        inside = table.inside(names, com)
        return ({link for link, f in zip(links, far.tolist()) if not f},
                {link for link, w in zip(links, within.tolist()) if w},
                {link for link, i in zip(links, inside.tolist()) if i})

    return robot.memo(_plain_decided, build)


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
    children = robot.hanging()
    roots = [name for name in robot.links if name not in children]
    if len(roots) != 1:
        return
    mass, names = 0, robot.names()  # the root's: the last link of its name with an inertial
    for link, properties in _valid(robot):
        if (names[link] or "?") == roots[0]:
            mass = properties.mass
    if mass > 0:
        root = robot.links[roots[0]]
        name = next(n for n in ("base_footprint", f"{roots[0]}_root", f"{roots[0]}_massless_root")
                    if n not in robot.links and f"{n}_joint" not in robot.joints)
        location = robot.locations.get(root)
        from urdftool.lint.fixes import Unfixable, insert_before, offer  # (only for a finding)
        edits = Unfixable(f"'{roots[0]}' is written in a macro (called at {location.via[0]}); "
                          "add the link beside the call") if location and location.via else \
            insert_before(robot, root, f'<link name="{attribute(name)}"/>',
                          f'<joint name="{attribute(name)}_joint" type="fixed"><parent '
                          f'link="{attribute(name)}"/><child link="{attribute(roots[0])}"/>'
                          '</joint>')
        yield offer(first_child(root, "inertial"), (
            f"root link '{roots[0]}' has mass {mass:g} kg, which KDL ignores; add a "
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
            if expected is None or mat3.trace(expected.inertia) == 0:  # no ratio to judge
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


def _largest_trace(properties, solid, bounds=None) -> float:
    """The largest trace any mass distribution inside the geometry's bounding box (``bounds``
    when given) can have about the declared centre of mass: 2 m R^2, R the box corner farthest
    from it [kg m^2]."""
    low, high = bounds or solid.bounds
    reach = sum(power(max(abs(l - c), abs(h - c)), 2) for l, c, h in zip(low, properties.com, high))
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
    not (see U414). Unit slips of 10^3 and 10^6 are U309, a tensor no body has (indefinite, or
    breaking the triangle inequality) U305's or U306's alone.

    A **note** naming the condition when the tensor is beyond the collision geometry's bound
    but within that of the link's visual and collision geometry: a collision shape simplified
    smaller than the part (a box inside an arm's mesh) bounds nothing of the real part, and the
    tensor is wrong only if it is the body's shape. The message says what the visual geometry
    adds: nothing (no larger: youbot's wheels; a link drawn only with a visual is judged from
    it), or that not all of it could be measured (a mesh missing), when it could not tell.

    A **note** too when the link is welded by fixed joints to other links, weighs under 1 % of
    that rigid body, and its geometry's tensor in place of the declared one would change the
    body's inertia by under 1 % of its least principal moment, about any axis: every simulator moves welded links as one body (Gazebo and MuJoCo
    lump them, Pinocchio merges them into the parent, Bullet and Drake sum them), so the error
    is lost in the body's (Unitree G1's 1 g contour and support links, fixed to a 4 kg pelvis
    and a torso; Go2's head, cameras and mounts on bases: in the real sweep 79 rows became
    notes and 8 lost lines, 72 of those rows judged TRUE as placeholders, 7 DEBATABLE).

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
        if _impossible(robot, link, properties):
            continue  # U305 or U306 refuses it: no geometry holds it, one defect told once
        beyond = (f", more than any distribution of that mass inside it can have "
                  f"({number(_largest_trace(properties, solid), 3)})") if larger else (
            ", so that nearly all the mass would lie within a third of its size around the "
            "centre of mass: a placeholder, another part's tensor, or a collision shape larger "
            "than the part")
        drawn = _drawn_bound(robot, link, properties, solid) if larger else None
        held = drawn is not None and trace <= drawn
        if held:  # the collision geometry is smaller than what the visual draws
            beyond += f", though its visual geometry could hold it (up to {number(drawn, 3)})"
        elif drawn is not None and drawn > _largest_trace(properties, solid) * (1 + 1e-9):
            beyond += f", nor inside its visual geometry ({number(drawn, 3)})"
        elif drawn is not None and robot.grouped(link).get("visual"):
            beyond += ", nor inside its visual geometry, which is no larger"
        elif larger and solid.source == "collision":  # what the visual draws is not known
            beyond += ", its visual geometry not all measured"
        message = (
            f"link '{_name(link)}': declared inertia (trace {number(trace, 3)} kg m^2) is "
            f"{number(ratio, 3)} times that of its {solid.source} geometry as a uniform solid of "
            f"the declared {properties.mass:g} kg (trace "
            f"{number(mat3.trace(expected.inertia), 3)}){beyond}; "
            f"{_computed_by(link)}")
        if held:
            message = Conditional("if the collision geometry is the body's shape, not a "
                                  "simplification smaller than it: " + message, Severity.INFO)
        lumped = _negligible_where_fixed(robot, link, properties, expected)
        if lumped is not None:  # welded to a heavier body: its error is lost in the body's
            yield _inertial_part(link, "inertia"), message + "; " + lumped, None, Severity.INFO
            continue
        yield _inertial_part(link, "inertia"), message


FIXED_SHARE = 0.01  # of a rigid body's inertia: a link's tensor error below it changes nothing
_POINT_MASS = Body(0.0, (0.0, 0.0, 0.0), ((0.0, 0.0, 0.0),) * 3)  # no tensor: the error is all of it


def _negligible_where_fixed(robot, link, properties, expected) -> str | None:
    """What to say when ``link`` is welded by fixed joints to other links and replacing its
    declared tensor by its geometry's (``expected``) changes the whole rigid body's inertia by
    under FIXED_SHARE of its least principal moment, about any axis, that moment read both
    from the declared tensors and with every measured link's tensor its geometry's (a parent's
    placeholder ``ixx="300"`` would hide anything) (a 1 g placeholder on a contour mesh fixed
    to a 4 kg pelvis: Unitree's G1); else None. Every simulator moves welded links as one body (Gazebo and
    MuJoCo lump them, Pinocchio merges them into the parent, Bullet and Drake sum them in the
    composite), so only the body's tensor matters, and this link's error is lost in it."""
    name = _name(link)
    members, body, measured, by_mass = robot.memo_for(
        _negligible_where_fixed, solids.rigid_root(robot, name),
        lambda: _welded_body(robot, solids.rigid_root(robot, name)))
    if len(members) < 2 or body is None:
        return None
    # the most the tensor's error turns the body's inertia about any axis, against the
    # body's least moment either way: under FIXED_SHARE of it about every axis
    error = tuple(tuple(e - d for e, d in zip(row, declared))
                  for row, declared in zip(expected.inertia, properties.inertia))
    least = min(mat3.eigvalsh(b.inertia)[0] for b in (body, measured or body))
    whole = mat3.trace(body.inertia)
    if not least > 0 or max(abs(v) for v in mat3.eigvalsh(error)) >= FIXED_SHARE * least \
            or properties.mass >= FIXED_SHARE * body.mass:
        return None  # (a link of a hundredth of the body's mass or more: its own part)
    heaviest = next(member for member in by_mass if member != name)
    others = f" and {len(members) - 2} more" if len(members) > 2 else ""
    return (f"negligible where it is: fixed joints make '{name}' one body with '{heaviest}'"
            f"{others} ({number(body.mass, 3)} kg, of which it is under "
            f"{number(FIXED_SHARE * 100, places=0)} %), whose inertia (trace "
            f"{number(whole, 3)} kg m^2) this tensor changes by under "
            f"{number(FIXED_SHARE * 100, places=0)} % about any axis, and simulators move that "
            "body as one")


def _welded_body(robot, root: str) -> tuple:
    """Link ``root``'s rigid body, once for all its links (a 5,000-link body asked it of each
    link: quadratic): its members; its declared inertials as one body; the same with every
    measured link's tensor its geometry's (a body whose declared tensors are too large, a
    parent's placeholder or the welded links' own, hides nothing); its members heaviest first
    (ties in the walk's order). In the root's frame: only what no rigid motion changes is read
    from them (masses, traces and principal moments about the centre of mass)."""
    def mass(member: str) -> float:
        declared = declared_of(robot, robot.links[member]) if member in robot.links else None
        return declared.mass if declared is not None and math.isfinite(declared.mass) else 0.0

    members = solids.rigid_group(robot, root)
    if len(members) < 2:
        return members, None, None, members
    measured = {_name(other): computed.inertia
                for other, _, _, computed, _ in _inertia_ratios(robot)}
    return (members, solids.rigid_declared(robot, root),
            solids.rigid_declared(robot, root, measured),
            sorted(members, key=mass, reverse=True))


def _drawn_bound(robot, link, properties, solid) -> float | None:
    """The largest trace inside the box of the link's own visual and collision geometry
    [kg m^2], when the tensor is judged from its collision geometry and all of that geometry
    is measured; else None. A collision shape simplified smaller than the part (a wheel's thin
    cylinder, a box inside an arm's mesh) bounds nothing of the real part: what is drawn does."""
    if solid.source != "collision":
        return None
    box, complete = solids.link_bounds(robot, link)
    if box is None or not complete:
        return None
    return _largest_trace(properties, solid, box)


def _shell_word(name: str) -> str:
    """``name`` as one shell word in single quotes, as the other names of a message are
    quoted (so that the report's groups read it as a name: one line for a robot's four
    suction cups, not four)."""
    return "'" + name.replace("'", "'\"'\"'") + "'"


def _told_by_ratio(robot) -> set[str]:
    """The links whose tensor U309 or U310 reports (a unit slip, or far from the geometry)."""
    told = set()
    for link, properties, solid, expected, ratio in _inertia_ratios(robot):
        if _unit_factor(properties, expected, ratio) is not None:
            told.add(_name(link))
        elif properties.mass > PLACEHOLDER_MASS and _body_sized(solid) and (
                ratio < 1 / FAR_RATIO or ratio > FAR_RATIO and
                mat3.trace(properties.inertia) > _largest_trace(properties, solid)):
            told.add(_name(link))
    return told


DENSEST = 22_590.0  # [kg/m^3]: osmium, the densest element (CRC Handbook of Chemistry and Physics)
LIGHTEST = 0.16  # [kg/m^3]: graphene aerogel, the lightest solid made (Sun et al., Adv. Mater. 2013)


def _volume_bounds(robot, link, solid, mass: float) -> tuple[float, float | None] | None:
    """(smallest, largest) volume the link's drawn body can have [m^3], or None when some
    geometry did not load (its collision or its visual: never judged from part of it). The largest takes the bigger of its collision and visual
    geometry with open meshes as their convex hulls (a hull holds the part): dividing the mass
    by it gives the least density the link can have. The smallest counts only when the
    geometry is trustworthy (no hull); a hollow shell's envelope makes it too large, so it
    only bounds the density from below loosely.

    The largest is None when it cannot matter: when ``mass`` [kg] in a lower bound of the
    solid's own volume (exact without open meshes, which count as their convex hulls) is no
    denser than osmium, no larger volume makes it denser, and no other geometry is built."""
    def light_enough(floor: float) -> bool:
        return floor > 0 and mass / floor <= DENSEST

    if light_enough(solid.volume_floor(enough=light_enough)):
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
        if not loaded(second):
            return None  # the body may be the other geometry, which is not all known: the
            # least density cannot be judged from part of the link's geometry
        volumes.append(solids.volume(second))
    return (own if _trustworthy(solid) else 0.0), max(volumes)


def _plain_volumes(robot) -> dict:
    """link -> (whether :func:`_body_sized`, the source, the volume [m^3], the volume of its
    <visual> shapes [m^3] or None without) of the links of
    :func:`~urdftool.physics.solids.plain_links` with mass (the volume of the geometry
    :func:`~urdftool.physics.solids.link_solid` takes, as :func:`~urdftool.physics.solids.
    volume` sums it), measured without their solids; every other link with mass has its
    solid built here, in order, as :func:`_link_solids` builds them (an error is raised where
    it raises). Once per robot (U311 asks)."""
    def build():
        table = solids.plain_links(robot)
        rows = table.rows if table is not None else {}
        if table is not None:  # the volumes as the shapes' unit_volume sums them, at once
            units = table.units
            extents, volumes = table.extents.tolist(), units["mass"].tolist()
            visual = [v if n else None for v, n in zip(units["visual"].tolist(),
                                                         units["visuals"].tolist())]
            sources = ["collision" if c else "visual" for c in units["collision"].tolist()]
        found, marker, names = {}, MARKER_EXTENT * 1.01, robot.names()
        for link, properties in _valid(robot):
            if not properties.mass > 0:
                continue
            name = names[link]
            row = rows.get(name)
            if row is None or robot.links.get(name) is not link:
                _solid(robot, link)
                continue
            found[link] = (marker < extents[row] <= 5.0, sources[row], volumes[row], visual[row])
        return found

    return robot.memo(_plain_volumes, build)


def _plain_volume_bounds(robot, link, found, mass: float) -> tuple[float, float | None]:
    """:func:`_volume_bounds` of a link of :func:`_plain_volumes` of a plain size (its
    geometry is trustworthy, and all of it loaded)."""
    _, source, own, visual = found
    if own > 0 and mass / own <= DENSEST:
        return own, None
    volumes = [own]
    if source == "collision" and visual is not None:  # (a plain link's visuals all count)
        volumes.append(visual)
    return own, max(volumes)


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
    plain = _plain_volumes(robot)
    osmium = number(DENSEST, places=0, grouped=True)  # (in every message)
    denser: dict = {}  # (mass, volume) -> what is said of them (copies of a link repeat them)
    names = robot.names()
    for link, properties in _valid(robot):
        if not properties.mass > 0:
            continue
        found = plain.get(link)
        if found is None:  # the per-link path: the link's solids
            solid = _solid(robot, link)
            if properties.mass <= PLACEHOLDER_MASS or not _body_sized(solid):
                continue
            bounds = _volume_bounds(robot, link, solid, properties.mass)
            source = solid.source
        else:
            if properties.mass <= PLACEHOLDER_MASS or not found[0]:
                continue
            bounds, source = _plain_volume_bounds(robot, link, found, properties.mass), found[1]
        if bounds is None or bounds[1] is not None and bounds[1] <= 0:
            continue
        least = properties.mass / bounds[1] if bounds[1] is not None else 0.0
        if least > DENSEST:  # (mass and volume positive: equal keys, the same numbers)
            said = denser.get((properties.mass, bounds[1]))
            if said is None:  # (a mass of 1e308 over a litre: more than a float holds)
                density = f"at least {number(least, places=0, grouped=True)}" \
                    if math.isfinite(least) else "more than 1e+308"
                said = denser[properties.mass, bounds[1]] = (
                    f"{properties.mass:g} kg in at most {number(bounds[1], 3)} m^3 of geometry "
                    f"is {density} kg/m^3, denser than "
                    f"osmium ({osmium}); a wrong mass or geometry scale")
            yield _inertial_part(link, "mass"), f"link '{names[link] or '?'}': {said}"
        elif bounds[0] > 0 and properties.mass / bounds[0] < LIGHTEST:
            yield _inertial_part(link, "mass"), (
                f"link '{_name(link)}': {properties.mass:g} kg in {number(bounds[0], 3)} m^3 of "
                f"{source} geometry is {number(properties.mass / bounds[0], 3)} kg/m^3, "
                "lighter "
                f"than any solid ({LIGHTEST:g}, aerogel); a wrong mass or geometry scale")


COM_HULL_FRACTION = 0.2  # of the geometry's largest extent: collision shapes are simplified
COM_HULL_MIN = 0.01  # [m]


def _largest_extent(reach) -> float:
    """The largest side of the box of a reach's pieces [m]."""
    return max(reach.support(axis) + reach.support(tuple(-a for a in axis))
               for axis in ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)))


def _hull_margin(reach) -> float:
    """How far outside a geometry's hull a centre of mass may be [m]: a fifth of its largest
    extent, at least 1 cm (:func:`_margin`)."""
    return _margin(_largest_extent(reach))


def _margin(extent: float) -> float:
    """How far outside the hull of geometry whose largest extent is ``extent`` [m] a centre
    of mass may be [m]: a fifth of it, at least 1 cm (never smaller for larger geometry: a
    reach finding the point within it from a few points of its pieces says 0)."""
    return max(COM_HULL_FRACTION * extent, COM_HULL_MIN)


def _copied_joint_origin(robot, link, properties, read: tuple | None = None) -> object | None:
    """The joint whose child ``link`` is, when the inertial origin repeats that joint's origin
    (its xyz, over 1 cm from the link frame), else None. ``read``: (:func:`~urdftool.physics.
    frames.parent_joints`, :meth:`~urdftool.description.robot.Robot.names`) of the robot, for a
    caller asking of every link (not looked up again 10,000 times)."""
    parents, names = (parent_joints(robot), robot.names()) if read is None else read
    joint = parents.get(names[link] or "?")  # (_name, as read once)
    if joint is None:
        return None
    xyz = origin_xyz(robot, joint)  # origin_of(joint).xyz, from the joints' texts
    (cx, cy, cz), (x, y, z) = properties.com, xyz
    # the centre of mass first (most links: not the joint's; written out, 10,000 links),
    # then the joint's distance, then the written origin
    if not (abs(cx - x) <= 1e-9 + 1e-6 * abs(cx) and abs(cy - y) <= 1e-9 + 1e-6 * abs(cy)
            and abs(cz - z) <= 1e-9 + 1e-6 * abs(cz)):
        return None
    if math.sqrt(mat3.dot(xyz, xyz)) <= COM_HULL_MIN:
        return None
    written = origin_of(first_child(link, "inertial")).xyz
    if all(abs(a - b) <= 1e-9 + 1e-6 * abs(a) for a, b in zip(written, xyz)):
        return joint
    return None


def _contact_spheres_only(robot, link, reach) -> bool:
    """Whether the rigid body of ``link`` is drawn by no visual and only collision spheres:
    contact points (a foot at the end of a shank, Stanford Pupper v3's no_visual URDF), not the
    body's extent, so a centre of mass outside them says nothing. Once per rigid body (its
    members' shapes are the body's: asked of each member, a body of n links cost n^2)."""
    return robot.memo_for(_contact_spheres_only, solids.rigid_root(robot, link.get("name")),
                          lambda: _drawn_by_spheres_alone(robot, link, reach))


def _drawn_by_spheres_alone(robot, link, reach) -> bool:
    shapes = [shape for name in reach.links if name in robot.links
              for shape in solids._link_shapes(robot, robot.links[name])["collision"][0]]
    if not shapes or any(shape.kind != "sphere" for shape in shapes):
        return False  # (asked first: the visual reach measures meshes, +1.5 % of the corpus)
    return not link_reach(robot, link, ("visual",), rigid=True).pieces


@rule("U312", "com-outside-hull", Severity.WARNING)
def com_outside_hull(robot):
    """A link's centre of mass lies outside the convex hull of its geometry.

    A body's centre of mass is always inside the convex hull of the body. The hull here is that
    of the link's visual and collision geometry and of the links fixed to it (one rigid body),
    meshes by their vertices (open meshes too). Collision shapes are often simplified, so the
    centre of mass may lie outside by a fifth of the geometry's largest extent (at least 1 cm);
    beyond that, the inertial origin is in another frame, has a sign flipped, or belongs to
    another part; or the mass is right and the drawing is split otherwise (a motor drawn in
    the next link's mesh, KUKA's link_N drawn as its flange), which the message names as the
    other cause (a hull counting the neighbouring links told neither apart on the sweep: it
    held Doosan's CAD-frame centres of mass and myCobot's placeholders as well). Skipped when
    some geometry cannot be measured (a mesh missing, refused or unreadable), for a body
    drawn by collision spheres alone (contact points, no visual: a foot, not the leg), and for a
    frame's placeholder inertial (a link without geometry of its own whose centre of mass is
    its origin: a tool centre point between a gripper's fingers).
    Farther out than the geometry's size is U307's, an origin copied from the joint U313's.
    A centre of mass at the link's own origin (no ``<origin>``, or xyz 0 0 0) is said to be
    one: an inertial left on the joint rather than placed where the parts are (the old
    ur_description's wrists, 6 to 12 cm from the centres of mass UR's own description gives).

    A **note** when the centre of mass lies inside the drawn geometry of a link a joint moves
    against this one (its parent, a child): Gazebo, Bullet, MuJoCo and Pinocchio put the mass
    where the inertial says and never look at the drawing, so the dynamics are right when the
    parts drawn there move with this link (a motor's rotor, a gear on the joint's axis), which
    only the CAD tells: in the real sweep (363 repositories) 20 findings of 84 DEBATABLE rows,
    none of a TRUE one (Fourier's GR1 legs, Romeo's and TIAGo's arms, KUKA's iiwa and iisy).
    Not a note for a centre of mass at the link's origin (a placeholder: the origin is on the
    joint, inside the parent's drawing by construction), nor in a robot where another link's
    centre of mass is far outside its geometry (U307: its inertials are in another frame), nor
    when the centre of mass read in the robot's root frame, or with its axes swapped or a sign
    flipped, falls inside the link's own drawing (Rokae's CAD-frame centres of mass, FZI's
    link4).

    Bad: a palm drawn from z = -0.095 to 0 with ``<inertial><origin xyz="0 0 0.0475"/>``
    Good: ``<origin xyz="0 0 -0.0475"/>``
    """
    inside = _plain_decided(robot)[2]  # (read once, not once per link)
    for link, properties in _valid(robot):
        if not properties.mass > 0:
            continue
        if link in inside:
            continue  # inside one of its primitives: outside by 0
        if solids.fixed_to_others(robot, link.get("name")) and \
                inside_own(robot, link, properties.com):
            continue  # inside its own geometry, so inside its body's hull: the body not gathered
        reach = link_reach(robot, link, ("visual", "collision"), rigid=True)
        if not reach.pieces or not reach.complete or _contact_spheres_only(robot, link, reach):
            continue
        # 0 at once inside a box, cylinder or sphere, or found within the margin
        outside = reach.outside(properties.com, beyond=_margin)
        if outside <= COM_HULL_MIN or outside <= _hull_margin(reach) or \
                _far_outside_box(robot, link, properties) is not None:
            continue
        if properties.com == (0.0, 0.0, 0.0) and \
                not link_reach(robot, link, ("visual", "collision")).pieces:
            continue  # a frame's placeholder (a tool centre point between the fingers)
        if _copied_joint_origin(robot, link, properties) is not None and \
                _own_outside(robot, link, properties) is not None:
            continue  # U313 says why
        fixed = f" and of {', '.join(repr(n) for n in reach.links[1:])} fixed to it" \
            if len(reach.links) > 1 else ""
        neighbour = _drawn_by_neighbour(robot, link, properties, reach)
        if neighbour is not None:
            yield first_child(link, "inertial"), (
                f"link '{_name(link)}': centre of mass ({' '.join(f'{number(v, 4)}' for v in properties.com)}) "
                f"is at least {number(outside * 1000, places=0)} mm outside the convex hull of its visual and "
                f"collision geometry{fixed}, inside that of link '{neighbour}', which a joint moves "
                f"against it: right if parts drawn with '{neighbour}' move with "
                f"'{_name(link)}' (a motor's rotor, a gear), else the inertial is another part's"), \
                None, Severity.INFO
            continue
        if properties.com == (0.0, 0.0, 0.0):  # the link's origin, on its joint: a placeholder
            yield first_child(link, "inertial"), (
                f"link '{_name(link)}': centre of mass (0 0 0), the link's own origin, is at "
                f"least {number(outside * 1000, places=0)} mm outside the convex hull of its "
                f"visual and collision geometry{fixed}, where no body has its centre of mass: "
                "an inertial left at the link's origin (no <origin>, or xyz 0 0 0) rather than "
                "placed where the link's parts are, unless the link's mass holds parts drawn "
                "with a neighbouring link (a motor on the joint's axis)")
            continue
        yield first_child(link, "inertial"), (
            f"link '{_name(link)}': centre of mass ({' '.join(f'{number(v, 4)}' for v in properties.com)}) "
            f"is at least {number(outside * 1000, places=0)} mm outside the convex hull of its visual and "
            f"collision geometry{fixed}, where no body has its centre of mass: the inertial "
            "origin is in another part's frame or has a sign flipped, or the link's mass holds "
            "parts drawn with a neighbouring link (a motor drawn in the next link's mesh); "
            "check which")


def _drawn_by_neighbour(robot, link, properties, reach) -> str | None:
    """The link a moving joint joins to ``link``'s rigid body (its parent's, a child's) whose
    drawn geometry holds ``link``'s centre of mass at the zero pose (within the hull margin),
    when that may be a drawing split otherwise than the masses; None when not, when the centre
    of mass is the link's origin (a placeholder: the origin is on the joint, inside the
    parent's drawing by construction), or when another link of the robot has its centre of mass
    far outside its geometry (U307: the robot's inertials are in another frame)."""
    from urdftool.physics.frames import child_joints, link_frames

    if properties.com == (0.0, 0.0, 0.0) or _frames_astray(robot):
        return None
    frames, parents, below = link_frames(robot), parent_joints(robot), child_joints(robot)
    name = _name(link)
    if name not in frames:
        return None
    p, rotation = frames[name]
    if _explained_inside(reach, properties.com, p, rotation):
        return None
    point = tuple(a + b for a, b in zip(p, mat3.apply(rotation, properties.com)))
    body = set(reach.links) | {name}
    joined = [robot.ends()[joint]["parent"][1] for joint in
              (parents.get(member) for member in body) if joint is not None]
    joined += [robot.ends()[joint]["child"][1] for member in body for joint in below.get(member, ())]
    for other in joined:
        if other is None or other in body or other not in frames or other not in robot.links:
            continue
        drawn = link_reach(robot, robot.links[other], ("visual", "collision"), rigid=True)
        if not drawn.pieces or not drawn.complete or body & set(drawn.links):
            continue
        q, turn = frames[other]
        local = mat3.apply(mat3.transpose(turn), tuple(a - b for a, b in zip(point, q)))
        if drawn.outside(local, beyond=_margin) <= max(_hull_margin(drawn), COM_HULL_MIN):
            return other
    return None


def _explained_inside(reach, com, p, rotation) -> bool:
    """Whether the centre of mass ``com`` falls inside the link's own drawing (``reach``, the
    link's frame at ``p``, ``rotation`` at the zero pose) once read as a common slip: given in
    the robot's root frame (a CAD export's world frame), or with its axes swapped or signs
    flipped (FZI's link4 drawn along y, its centre of mass written along z)."""
    def inside(point) -> bool:
        return reach.outside(point, beyond=_margin) <= max(_hull_margin(reach), COM_HULL_MIN)

    world = mat3.apply(mat3.transpose(rotation), tuple(a - b for a, b in zip(com, p)))
    x, y, z = com
    slipped = [(c * s[0], d * s[1], e * s[2]) for c, d, e in ((x, y, z), (y, x, z), (z, y, x),
                                                              (x, z, y), (y, z, x), (z, x, y))
               for s in ((1, 1, 1), (-1, 1, 1), (1, -1, 1), (1, 1, -1), (-1, -1, 1),
                         (-1, 1, -1), (1, -1, -1), (-1, -1, -1))][1:]
    return inside(world) or any(inside(point) for point in slipped)


def _frames_astray(robot) -> bool:
    """Whether some link's centre of mass is far outside its rigid body's box (U307's
    finding): the robot's inertials are then likely in another frame. Once per robot."""
    return robot.memo(_frames_astray, lambda: any(
        _far_outside_box(robot, link, properties) is not None for link, properties in _valid(robot)))


def _own_outside(robot, link, properties) -> float | None:
    """How far [m] the centre of mass is outside the hull of the link's own geometry, when
    beyond the margin; None when inside it, or when the geometry cannot all be measured."""
    reach = link_reach(robot, link, ("visual", "collision"))
    if not reach.pieces or not reach.complete:
        return None
    outside = reach.outside(properties.com, beyond=_margin)
    return outside if outside > _hull_margin(reach) else None


@rule("U313", "inertial-origin-is-joint-origin", Severity.WARNING)
def inertial_origin_is_joint_origin(robot):
    """A link's inertial origin repeats the origin of the joint that holds it, outside the link.

    The joint's ``<origin>`` places the link's frame in its parent; the inertial's
    ``<origin>`` places the centre of mass in the link's own frame. Copying one into the other
    puts the centre of mass as far again from the joint, outside the link (a caster 0.4 m
    behind the base gets its mass 0.8 m behind it). Reported when the two xyz are the same
    (over 1 cm from the link frame) and the centre of mass is outside the hull of the link's
    own geometry by a fifth of its size (at least 1 cm).

    Bad: ``<joint name="caster_joint"><origin xyz="-0.4 0 -0.05"/>`` and the caster's
    ``<inertial><origin xyz="-0.4 0 -0.05"/>``
    Good: the caster's ``<inertial><origin xyz="0 0 0"/>`` (its centre)
    """
    read = parent_joints(robot), robot.names()
    for link, properties in _valid(robot):
        if not properties.mass > 0:
            continue
        joint = _copied_joint_origin(robot, link, properties, read)
        if joint is None:
            continue
        outside = _own_outside(robot, link, properties)
        if outside is None:
            continue
        xyz = " ".join(f"{number(v, 4)}" for v in properties.com)
        yield first_child(link, "inertial"), (
            f"link '{_name(link)}': inertial origin xyz=\"{xyz}\" repeats the origin of joint "
            f"'{joint.get('name')}', which places the link itself; in the link's frame it puts "
            f"the centre of mass at least {number(outside * 1000, places=0)} mm outside the link's geometry "
            "(the centre of mass is given from the link's own origin)")


ORDER_RATIO = 4.0  # the geometry's largest moment over its smallest: clearly long or flat
ORDER_SLACK = 2.0  # the declared moments must be reversed by this much: a heavy motor in
# the middle of a long bracket can lower the moments across it, not below half the axial one


@rule("U314", "principal-moments-order", Severity.WARNING)
def principal_moments_order(robot):
    """A link's declared moments of inertia are ordered against its geometry's (two swapped).

    A long or flat body turns hardest about the axes across its length and easiest about its
    long axis, whatever its density: the ordering of its moments follows its shape (for a
    hollow tube as for a solid rod, once it is longer than it is wide). Compared, along the
    principal axes of the link's geometry (collision, else visual; primitives and closed meshes
    only), when the geometry's largest moment is at least 4 times its smallest: reported when
    the declared moment about the geometry's easiest axis is over twice the declared moment
    about its hardest one (mass gathered in the middle of a long part lowers the moments across
    it, not that far). Typical of a tensor written for another axis convention (a
    cylinder along z whose link is a rod along x), or of ixx and izz swapped. Wheels, and the
    hubs and tyres fixed below them, are U421's; a tensor no body has (indefinite, or breaking
    the triangle inequality) is U305's or U306's alone.

    Bad: a 0.4 x 0.05 x 0.05 m box with ``ixx="0.013" iyy="0.013" izz="0.0004"``
    Good: ``ixx="0.0004" iyy="0.013" izz="0.013"``
    """
    from urdftool.physics.wheels import wheel_body, wheels

    skip = {part for wheel in wheels(robot) for part in wheel_body(robot, wheel.link)}
    names = robot.names()
    # the links with trustworthy geometry and a tensor, with the geometry's (U309, U310 ask)
    for link, properties, solid, expected, _ in _inertia_ratios(robot):
        if (names[link] or "?") in skip or properties.mass <= PLACEHOLDER_MASS:
            continue
        easiest, _, hardest = mat3.eigvalsh(expected.inertia)
        if not easiest > 0 or hardest < ORDER_RATIO * easiest:
            continue
        least, _, most = _principal(robot, link, properties)[0]
        if not most > ORDER_SLACK * least:
            continue  # no two axes of the declared tensor are twice apart
        # about the geometry's easiest axis against its hardest; when two of its moments are
        # equal, every axis of their plane is one: the declared tensor's most about the easy
        # ones against its least about the hard ones
        easy, about_easy = _declared_about(properties.inertia, expected.inertia, easiest, max)
        hard, about_hard = _declared_about(properties.inertia, expected.inertia, hardest, min)
        # (U305 or U306 refusing the tensor asked last, where a finding would be: the star's
        # 10,000 links asked it at 13 k instructions each, 1.6 %)
        if about_easy > ORDER_SLACK * about_hard and not _impossible(robot, link, properties):
            yield _recomputed(robot, link, properties, (
                f"link '{_name(link)}': its {solid.source} geometry turns easiest about "
                f"({_axis_text(easy)}) and hardest about ({_axis_text(hard)}) (moments "
                f"{number(easiest, 3)} and {number(hardest, 3)} kg m^2 as a uniform solid), but the declared "
                f"tensor has {number(about_easy, 3)} and {number(about_hard, 3)} about them: moments "
                f"written for other axes{_swapped(easy, hard)}"))


def _swapped(easy, hard) -> str:
    """' (iyy and izz swapped?)': the moments about the link's axes nearest the geometry's
    easiest and hardest axes, when those are two of the link's axes ("" otherwise: the
    geometry's axes lie between them)."""
    nearest = [max(range(3), key=lambda i: abs(axis[i])) for axis in (easy, hard)]
    if nearest[0] == nearest[1] or min(abs(easy[nearest[0]]), abs(hard[nearest[1]])) < 0.9:
        return ""
    first, second = sorted(nearest)
    return f" (i{'xyz'[first] * 2} and i{'xyz'[second] * 2} swapped?)"


def _axis_text(v) -> str:
    return numbers(v, 3, ", ")  # (1, 0, 0), not (1, 4.9e-12, 1.74e-39): counted from the largest


def _declared_about(declared, geometry, value: float, pick) -> tuple[mat3.Vector, float]:
    """(axis, declared moment about it) for the geometry's principal moment ``value``: its
    axis when the moment is simple; when it is repeated, the axis of its plane about which the
    declared tensor's moment is ``pick`` (min or max) of those in the plane."""
    rows = [tuple(geometry[i][j] - (value if i == j else 0.0) for j in range(3)) for i in range(3)]
    crosses = sorted((mat3.cross(rows[0], rows[1]), mat3.cross(rows[0], rows[2]),
                      mat3.cross(rows[1], rows[2])), key=lambda c: mat3.dot(c, c))
    scale = max(abs(v) for row in geometry for v in row) or 1.0
    longest = crosses[-1]
    if mat3.dot(longest, longest) > power(1e-9 * scale * scale, 2):  # a simple eigenvalue
        axis = _unit(longest)
        return axis, mat3.dot(axis, mat3.apply(declared, axis))
    # repeated: the plane is orthogonal to the row of largest norm (rank 1), or everything
    normal = max(rows, key=lambda r: mat3.dot(r, r))
    if not mat3.dot(normal, normal) > 0:
        normal = (0.0, 0.0, 1.0)
    normal = _unit(normal)
    helper = (1.0, 0.0, 0.0) if abs(normal[0]) < 0.9 else (0.0, 1.0, 0.0)
    u = _unit(mat3.cross(normal, helper))
    v = mat3.cross(normal, u)
    uu, vv = mat3.dot(u, mat3.apply(declared, u)), mat3.dot(v, mat3.apply(declared, v))
    uv = mat3.dot(u, mat3.apply(declared, v))
    mean, radius = (uu + vv) / 2, math.hypot((uu - vv) / 2, uv)
    moment = pick(mean - radius, mean + radius)
    angle = 0.5 * math.atan2(2 * uv, uu - vv) + (0.0 if moment == mean + radius else math.pi / 2)
    axis = tuple(math.cos(angle) * a + math.sin(angle) * b for a, b in zip(u, v))
    return axis, moment


def _unit(v) -> mat3.Vector:
    norm = math.sqrt(mat3.dot(v, v))
    return tuple(x / norm for x in v)


SHELL = 0.25  # [kg/m^2]: the lightest wall a robot part has (0.25 mm of plastic, 0.1 mm of
# aluminium); a closed body of size L weighs at least its surface times this: 6 SHELL / L
# per volume for a cube, more for anything flatter
MATERIALS = {"water": 1000.0, "ABS": 1050.0, "nylon": 1140.0, "polycarbonate": 1200.0,
             "PLA": 1240.0, "PETG": 1270.0, "acetal": 1410.0, "carbon fibre": 1600.0,
             "magnesium": 1740.0, "aluminium": 2700.0, "titanium": 4430.0, "steel": 7850.0,
             "brass": 8500.0, "copper": 8960.0}
# [kg/m^3]: the densities a part's mass is computed from (CRC Handbook; plastics' datasheets)
MATERIAL_MATCH = 0.03  # relative: a density typed with two or three digits


def _material(density: float) -> str | None:
    """The material whose density ``density`` [kg/m^3] is, within 3 %."""
    for name, value in MATERIALS.items():
        if abs(density - value) <= MATERIAL_MATCH * value:
            return name
    return None


def _round_number(value: float) -> bool:
    """Whether a mass is a power of ten (1e-3, 0.01...): a placeholder, not a product."""
    return value > 0 and abs(math.log10(value) - round(math.log10(value))) < 1e-9


@rule("U315", "density-in-grams", Severity.WARNING)
def density_in_grams(robot):
    """A link's mass is 1000 times too small for its geometry: a density in g/cm^3 typed as kg/m^3.

    A mass computed as density times volume with the density in g/cm^3 (aluminium 2.7, steel
    7.85, PLA 1.24) where kg/m^3 was meant (2700, 7850, 1240) comes out 1000 times too small.
    Reported when the implied density (the declared mass over the volume of the link's
    primitives or closed meshes) is lighter than the thinnest plausible shell at that size
    (0.25 kg/m^2 of wall over a cube of the geometry's largest extent: 6 * 0.25 / L
    kg/m^3) and 1000 times it is, within 3 %, the density of a material parts are made of
    (water 1000, ABS 1050, nylon 1140, polycarbonate 1200, PLA 1240, PETG 1270, acetal 1410,
    carbon fibre 1600, magnesium 1740, aluminium 2700, titanium 4430, steel 7850, brass 8500,
    copper 8960 kg/m^3). A mass that is a power of ten (``1e-3``) is a placeholder, not a
    product of a density, and is not judged.
    Envelopes drawn around something mostly empty (a propeller's disc) are large enough to
    stay above that bound; a mass 1000 times too large is U311's (denser than osmium).

    Bad: ``<mass value="${2.7 * 0.1 * 0.05 * 0.02}"/>`` (0.00027 kg) on a 10 x 5 x 2 cm box
    Good: ``<mass value="${2700 * 0.1 * 0.05 * 0.02}"/>`` (0.27 kg)
    """
    for link, properties, solid in _link_solids(robot):
        if properties.mass <= 0 or not _trustworthy(solid):
            continue
        volume = solids.volume(solid)
        if not volume > 0:
            continue
        density = properties.mass / volume
        lightest_shell = 6 * SHELL / solid.extent
        if density >= lightest_shell:
            continue
        material = _material(1000 * density)
        if material is not None and not _round_number(properties.mass):
            yield _inertial_part(link, "mass"), (
                f"link '{_name(link)}': {number(properties.mass, 4)} kg in {number(volume, 3)} m^3 of "
                f"{solid.source} geometry is {number(density, 3)} kg/m^3, lighter than any shell of "
                f"its size ({number(lightest_shell, 3)}), and 1000 times that is {material}'s "
                f"density ({number(MATERIALS[material], places=0, grouped=True)} kg/m^3): was a density in g/cm^3 used as "
                f"kg/m^3? The mass would be {number(1000 * properties.mass, 4)} kg")


FAR_BEYOND = 2.0  # the bound takes the whole rigid body's reach: twice it is beyond doubt


def _computed_by(link) -> str:
    """What computes the tensor a link's geometry implies, as U310 and U316 end with it."""
    return f"`urdftool inertia --link {_shell_word(_name(link))}` computes it"


def _impossible(robot, link, properties) -> bool:
    """Whether U305 or U306 already refuses the tensor (indefinite, or a triangle broken): the
    one defect the comparisons with geometry (U310, U314, U316) then leave to them."""
    moments, largest = _principal(robot, link, properties)
    if moments[0] < -max(NEGATIVE_TOLERANCE * largest, _scaled(NEGATIVE_FLOOR, properties.mass)):
        return True
    return moments[-1] >= _scaled(ZERO_INERTIA, properties.mass) and \
        triangle_violation(moments, TRIANGLE_TOLERANCE) is not None


@rule("U316", "inertia-beyond-geometry", Severity.WARNING)
def inertia_beyond_geometry(robot):
    """A link's inertia is larger than any distribution of its mass inside its geometry allows.

    About its centre of mass a body's inertia tensor has trace 2 * sum(m r^2) <= 2 m d^2, d the
    farthest point of the body from its centre of mass: a physical bound that needs no closed
    mesh, only how far the geometry reaches (every vertex of a mesh, open or not, and the
    primitives exactly). The geometry is the link's visual and collision geometry and that of
    the links fixed to it (the whole rigid body: a generous d), so a trace over twice the
    bound is reported; skipped when some of that geometry cannot be measured, or is 1 cm or
    less (a frame's marker box, not its body). Judged whatever
    the mass (a placeholder's tensor beyond it is as impossible), and when U305, U306, U309
    and U310 have not already said so. Beyond the bound, the tensor belongs to another part or
    another mass, or is in other units.

    A **note**, as U310's, when the link is welded by fixed joints to other links, weighs under
    1 % of that rigid body, and its whole declared tensor is under 1 % of the body's least
    principal moment: what it should be is smaller still, and simulators move the body as one
    (HippoCampus' flange, dome and thruster mounts: 1e-5 kg with 1e-5 kg m^2 placeholders on a
    2.31 kg hull).

    Bad: a 2 kg arm link reaching 0.15 m from its centre of mass with
    ``ixx="0.5" iyy="0.5" izz="0.5"`` (trace 1.5 > 2 * 2 * 0.15^2 = 0.09)
    Good: the tensor ``urdftool inertia`` computes from its geometry
    """
    told = _told_by_ratio(robot)
    within = _plain_decided(robot)[1]  # (read once, not once per link)
    for link, properties in _valid(robot):
        if not properties.mass > 0:
            continue
        if link in within:
            continue  # within the bound, found with the others at once
        trace = mat3.trace(properties.inertia)
        held = solids.held_box(robot, link)  # the body's box holds it: no shorter a side
        if held is not None and _within_half(trace, properties.mass, held):
            continue  # within the bound of the body's box too, found without gathering it
        rigid = solids.rigid_bounds(robot, link)
        if rigid.bounds is None or _within_half(trace, properties.mass, rigid.bounds):
            continue  # within the bound whatever the farthest point is (d >= half)
        if _name(link) in told or _impossible(robot, link, properties):
            continue
        reach = link_reach(robot, link, ("visual", "collision"), rigid=True)
        if not reach.pieces or not reach.complete or _largest_extent(reach) <= MARKER_EXTENT:
            continue  # a frame's marker box is not its body
        farthest = reach.farthest(properties.com)
        bound = 2 * properties.mass * farthest * farthest
        if trace > FAR_BEYOND * bound:
            fixed = f" and the links fixed to it" if len(reach.links) > 1 else ""
            message = (
                f"link '{_name(link)}': declared inertia has trace {number(trace, 3)} kg m^2, over "
                f"twice 2 m d^2, the most its {properties.mass:g} kg can have anywhere inside its "
                f"geometry{fixed}, which reaches d = {number(farthest, 3)} m from its centre of "
                f"mass: a tensor of another part, mass or unit; {_computed_by(link)}")
            # what it should be is smaller than what it is (within the bound): the declared
            # tensor itself is the most the body's inertia can be off by it
            lumped = _negligible_where_fixed(robot, link, properties, _POINT_MASS)
            if lumped is not None:  # welded to a heavier body: lost in the body's, as U310's
                yield _inertial_part(link, "inertia"), message + "; " + lumped, None, Severity.INFO
                continue
            yield _inertial_part(link, "inertia"), message
