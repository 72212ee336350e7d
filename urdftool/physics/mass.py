"""Rigid-body mass properties in pure Python: URDF inertials, primitive solids, combination.

Conventions: every tensor is about the body's centre of mass, in [kg m^2]; ``com`` is in [m] and,
unless said otherwise, expressed in the link frame with axes parallel to the link frame. A URDF
``<inertial>`` gives its tensor in the frame of its ``<origin>`` (rotated by ``rpy``), so
:func:`declared` rotates it into the link axes: ``I_link = R I R^T``.

This is the one implementation of these formulas. The inertia rules use it directly (no numpy,
so ``urdftool check`` starts fast); :mod:`urdftool.physics.inertia` wraps it in numpy arrays for
``urdftool inertia`` and adds meshes.
"""

from __future__ import annotations

import math
from collections import namedtuple

from urdftool.physics import mat3
from urdftool.description.values import number_tuple
from urdftool.description.xml import first_child
from urdftool.numbers import MAX_COORDINATE, length as vector_length, power

INERTIA_ATTRIBUTES = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")

# The bounds of a declared inertial urdftool computes with (judged in one place, _past: every
# command and rule reads a link's inertial through _body, and why it gives none through
# problem_at). A centre of mass past numbers.MAX_COORDINATE, a mass past MAX_MASS or a moment
# past MAX_MOMENT is no body: what is derived from it (the parallel-axis m d^2, a sum of
# masses, m g z, a distance squared) overflowed to inf or NaN in the com-outside-geometry
# rule's message, `inertia`'s "com inf%", `dynamics`' "P = inf J".
# Within them, m d^2 between two centres of mass is at most 1e30 (2 x 4.6e10)^2 = 8.5e51, and a
# million links' sums stay finite.
MAX_MASS = 1e30  # [kg] half the Sun's
MAX_MOMENT = MAX_MASS * MAX_COORDINATE * MAX_COORDINATE  # [kg m^2] (2.1e51) that mass at the
# farthest place


class Body(namedtuple("Body", ("mass", "com", "inertia"))):
    """mass [kg], com [m] (3-tuple), inertia [kg m^2] (3x3 tuples) about the com, link axes.

    A named tuple, immutable: a half of a frozen dataclass's cost to make (the inertia rules
    make 60,000 on a 10,000-link robot). collections' (typing's NamedTuple would import typing
    into every check)."""

    __slots__ = ()

    def principal_moments(self) -> mat3.Vector:
        """Eigenvalues of the tensor, ascending."""
        return mat3.eigvalsh(self.inertia)

    def scaled_to(self, mass: float) -> "Body":
        """The same shape with another mass: inertia scales linearly with mass."""
        factor = mass / self.mass if self.mass else 0.0
        return Body(mass, self.com, mat3.scaled(self.inertia, factor))


def declared(link) -> Body | None:
    """A link's ``<inertial>`` in link axes, or None when absent or not fully numeric."""
    inertial = first_child(link, "inertial")
    if inertial is None:
        return None
    return _declared(inertial, first_child(inertial, "mass"), first_child(inertial, "inertia"),
                     first_child(inertial, "origin"))


def _declared(inertial, mass_el, inertia_el, origin_el, known: dict | None = None
              ) -> Body | None:
    """:func:`declared` of an ``<inertial>`` whose first ``<mass>``, ``<inertia>`` and
    ``<origin>`` (each None when it has none) are found; ``known``: the bodies of the texts
    read before (a robot's: robots repeat their inertials), which it adds to."""
    texts = _texts(mass_el, inertia_el, origin_el)
    if texts is None:
        return None
    if known is None:
        return _body(texts)
    body = known.get(texts, _NONE)
    if body is _NONE:
        body = known[texts] = _body(texts)
    return body


def _texts(mass_el, inertia_el, origin_el) -> tuple | None:
    """The texts an ``<inertial>`` is read from, given its first ``<mass>``, ``<inertia>`` and
    ``<origin>`` (each None when it has none): the six inertia terms, the mass, and the
    origin's xyz and rpy when it has one; None without a mass or an inertia."""
    if mass_el is None or inertia_el is None:
        return None
    get = inertia_el.get  # the texts it is made of, each read once (a 10,000-link robot)
    texts = (get("ixx"), get("ixy"), get("ixz"), get("iyy"), get("iyz"), get("izz"),
             mass_el.get("value"))
    if origin_el is not None:
        texts += (origin_el.get("xyz", "0 0 0"), origin_el.get("rpy", "0 0 0"))
    return texts


def _numbers(texts: tuple):
    """(mass, the six inertia terms, xyz, rpy) of an inertial's texts (:func:`_texts`), xyz
    and rpy each None when malformed; None when the mass or a term is no number."""
    # The parsed tuples as they are, no list copies nor dict (a 10,000-link robot asks 70,000
    # times); floats, which mat3.matrix keeps as they are
    xx, xy, xz = number_tuple(texts[0], 1)[0], number_tuple(texts[1], 1)[0], \
        number_tuple(texts[2], 1)[0]
    yy, yz, zz = number_tuple(texts[3], 1)[0], number_tuple(texts[4], 1)[0], \
        number_tuple(texts[5], 1)[0]
    if xx is None or xy is None or xz is None or yy is None or yz is None or zz is None:
        return None
    mass = number_tuple(texts[6], 1)[0]
    if mass is None:
        return None
    if len(texts) == 7:  # no <origin>: its defaults
        xyz = rpy = _ZEROS
    else:
        xyz, rpy = number_tuple(texts[7], 3)[0], number_tuple(texts[8], 3)[0]
    return mass[0], (xx[0], xy[0], xz[0], yy[0], yz[0], zz[0]), xyz, rpy


_ZEROS = (0.0, 0.0, 0.0)


def _body(texts: tuple) -> Body | None:
    """The :class:`Body` of an inertial's texts (:func:`_texts`), or None when a number does
    not parse, is not finite, or is past the bounds urdftool computes with (:func:`_past`
    says which)."""
    read = _numbers(texts)
    if read is None:
        return None
    mass, (xx, xy, xz, yy, yz, zz), xyz, rpy = read
    xyz, rpy = xyz or _ZEROS, rpy or _ZEROS  # a malformed part counts as 0
    if _past(mass, read[1], xyz) is not None or not (
            math.isfinite(rpy[0]) and math.isfinite(rpy[1]) and math.isfinite(rpy[2])):
        return None
    tensor, rotation = ((xx, xy, xz), (xy, yy, yz), (xz, yz, zz)), mat3.rpy_matrix(rpy)
    if rotation is mat3.NO_TURN and mat3.kept_by_no_turn(tensor):
        return Body(mass, xyz, tensor)  # (floats already: mat3.rotate's matrix() of it)
    return Body(mass, xyz, mat3.rotate(tensor, rotation))


def _past(mass: float, terms: tuple, xyz: tuple) -> tuple[str, str] | None:
    """The one statement of the bounds urdftool computes with: why an inertial's ``mass``,
    six inertia ``terms`` and centre of mass ``xyz`` are past them (:data:`MAX_MASS`,
    :data:`MAX_MOMENT`, ``numbers.MAX_COORDINATE``), as (the tag of the ``<inertial>``'s child
    it is about, the message), the first found; None when within. NaN is past them too (each
    comparison is written so that it fails). The message names that child first (``<mass>
    1e+308 kg is past ...``), to follow ``<inertial>``."""
    if not abs(mass) <= MAX_MASS:
        from urdftool.numbers import number

        return "mass", (f"<mass> {number(mass)} kg is past the {number(MAX_MASS)} kg urdftool "
                        "computes mass properties with")
    for attribute, term in zip(INERTIA_ATTRIBUTES, terms):
        if not abs(term) <= MAX_MOMENT:
            from urdftool.numbers import number

            return "inertia", (f"<inertia {attribute}> {number(term)} kg m^2 is past the "
                               f"{number(MAX_MOMENT)} kg m^2 urdftool computes mass properties "
                               "with")
    x, y, z = xyz
    if not (abs(x) < MAX_COORDINATE and abs(y) < MAX_COORDINATE and abs(z) < MAX_COORDINATE):
        from urdftool.numbers import number

        return "origin", (f"<origin> xyz '{' '.join(map(number, xyz))}' is past the "
                          f"{number(MAX_COORDINATE)} m urdftool places a centre of mass within")
    return None


def problem_at(link) -> tuple[str, str] | None:
    """Why a link's ``<inertial>``, whose mass, inertia and origin all parse as finite numbers,
    gives no :class:`Body`: :func:`_past`'s (tag, message); None otherwise (no inertial, a
    number that does not parse or is not finite: the rules reading those say so)."""
    inertial = first_child(link, "inertial")
    if inertial is None:
        return None
    texts = _texts(first_child(inertial, "mass"), first_child(inertial, "inertia"),
                   first_child(inertial, "origin"))
    read = _numbers(texts) if texts is not None else None
    if read is None:
        return None
    mass, terms, xyz, rpy = read
    if xyz is None or rpy is None or not all(map(math.isfinite, (mass, *terms, *xyz, *rpy))):
        return None
    return _past(mass, terms, xyz)


def problem(link) -> str | None:
    """The message of :func:`problem_at`, or None."""
    found = problem_at(link)
    return found[1] if found else None


_NONE = object()  # (robot.memo_for keeps no None)


def declared_of(robot, link) -> Body | None:
    """:func:`declared`, once per robot and link (the inertia and symmetry rules ask), read
    from the children of the link and its inertial grouped once per robot
    (:meth:`~urdftool.description.robot.Robot.grouped`), which the rules read too."""
    found = robot.memo_for(declared_of, link, lambda: _declared_grouped(robot, link) or _NONE)
    return None if found is _NONE else found


def _declared_grouped(robot, link) -> Body | None:
    inertials = robot.grouped(link).get("inertial")
    if not inertials:
        return None
    groups = robot.grouped(inertials[0])
    masses, inertias, origins = groups.get("mass"), groups.get("inertia"), groups.get("origin")
    return _declared(inertials[0], masses[0] if masses else None,
                     inertias[0] if inertias else None, origins[0] if origins else None,
                     robot.memo(_declared, dict))


def moments_of(robot, link) -> mat3.Vector | None:
    """The principal moments of :func:`declared_of`, once per robot and link; None without
    a declared inertial."""
    body = declared_of(robot, link)
    return None if body is None else \
        robot.memo_for(moments_of, link, body.principal_moments)


# Solids: mass properties per unit density, about their own centre, in their own frame.

def box_volume(size) -> float:
    """The volume of a box of edges ``size`` [m^3]: :func:`box`'s mass."""
    a, b, c = size
    return a * b * c


def cylinder_volume(radius: float, length: float) -> float:
    """The volume of a cylinder [m^3]: :func:`cylinder`'s mass."""
    return math.pi * radius * radius * length


def sphere_volume(radius: float) -> float:
    """The volume of a sphere [m^3]: :func:`sphere`'s mass (infinity beyond ~5e102 m)."""
    return 4 / 3 * math.pi * power(radius, 3)


def box(size) -> Body:
    """Solid box of edges ``size`` [m], unit density."""
    a, b, c = size
    m = box_volume(size)
    return Body(m, (0.0, 0.0, 0.0), mat3.diagonal([m * (b * b + c * c) / 12,
                                                   m * (a * a + c * c) / 12,
                                                   m * (a * a + b * b) / 12]))


def cylinder(radius: float, length: float) -> Body:
    """Solid cylinder along z, unit density."""
    m = cylinder_volume(radius, length)
    side = m * (3 * radius * radius + length * length) / 12
    return Body(m, (0.0, 0.0, 0.0), mat3.diagonal([side, side, m * radius * radius / 2]))


def sphere(radius: float) -> Body:
    """Solid sphere, unit density."""
    m = sphere_volume(radius)
    moment = 2 / 5 * m * radius * radius
    return Body(m, (0.0, 0.0, 0.0), mat3.diagonal([moment] * 3))


def transformed(solid: Body, xyz, rotation) -> Body:
    """A solid placed by ``<origin>``: its com moved into the link frame, tensor rotated."""
    return Body(solid.mass, mat3.add(mat3.vector(xyz), mat3.apply(rotation, solid.com)),
                mat3.rotate(solid.inertia, rotation))


def combine(parts: list[Body]) -> Body:
    """Several bodies as one, by the parallel-axis theorem about the common centre of mass."""
    if len(parts) == 1:  # most links: what the sums below give for one part (0 + each term)
        m, (cx, cy, cz) = parts[0].mass, parts[0].com
        mass = 0 + m
        if mass <= 0:
            raise ValueError("bodies without mass cannot be combined")
        com = ((0 + m * cx) / mass, (0 + m * cy) / mass, (0 + m * cz) / mass)
    else:
        mass = sum(p.mass for p in parts)
        if mass <= 0:
            raise ValueError("bodies without mass cannot be combined")
        com = tuple(sum(p.mass * p.com[i] for p in parts) / mass for i in range(3))
    x, y, z = com
    # Written out (20,000 combinations on a 10,000-link robot): the same sums, in the same order
    t00 = t01 = t02 = t10 = t11 = t12 = t20 = t21 = t22 = 0.0
    for part in parts:
        m, (cx, cy, cz) = part.mass, part.com
        dx, dy, dz = cx - x, cy - y, cz - z
        squared = dx * dx + dy * dy + dz * dz
        (o00, o01, o02), (o10, o11, o12), (o20, o21, o22) = part.inertia
        t00 += o00 + m * (squared - dx * dx)
        t01 += o01 + m * (0.0 - dx * dy)
        t02 += o02 + m * (0.0 - dx * dz)
        t10 += o10 + m * (0.0 - dy * dx)
        t11 += o11 + m * (squared - dy * dy)
        t12 += o12 + m * (0.0 - dy * dz)
        t20 += o20 + m * (0.0 - dz * dx)
        t21 += o21 + m * (0.0 - dz * dy)
        t22 += o22 + m * (squared - dz * dz)
    return Body(mass, com, mat3.matrix(((t00, t01, t02), (t10, t11, t12), (t20, t21, t22))))


def triangle_violation(moments, tolerance: float = 0.0) -> str | None:
    """Which triangle inequality principal moments break (a + b >= c), or None."""
    a, b, c = sorted(float(m) for m in moments)
    if a + b < c * (1 - tolerance):
        from urdftool.numbers import number

        return f"{number(a)} + {number(b)} < {number(c)}"
    return None


def _flat(values) -> list[float]:
    if isinstance(values, (int, float)) or not hasattr(values, "__iter__"):
        return [float(values)]
    return [v for item in values for v in _flat(item)]


def relative_difference(declared_value, computed_value) -> float:
    """|declared - computed| / |computed| for scalars, vectors or matrices (Frobenius norm)."""
    d, c = _flat(declared_value), _flat(computed_value)
    scale = vector_length(c)  # scaled: no square overflows
    if scale == 0:
        return math.inf if any(v != 0 for v in d) else 0.0
    return vector_length([a - b for a, b in zip(d, c)]) / scale
