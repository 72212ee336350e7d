"""How far a link's geometry reaches: support functions of its shapes, placed in one frame.

The support function of a set ``S`` is ``h(d) = max over x in S of d . x``: for a box, a
cylinder and a sphere it has a closed form, for a mesh it is the largest over its vertices
(exact: the farthest point of a mesh along any direction is a vertex). From it come, exactly:
the lowest point of a wheel (``-h(-z)``), the farthest point from a centre of mass (a physical
bound on the inertia), and a lower bound of how far a point lies outside the convex hull of the
geometry (``max over unit d of d . p - h(d)`` is that distance; over a finite set of directions
it is a lower bound, so "outside by at least" is always true).

A :class:`Reach` says whether it is ``complete``: every ``<visual>``/``<collision>`` it was
asked for made a shape that could be measured. A mesh that does not resolve, load or stay
within the limits, or a geometry element urdfdom would drop, leaves it incomplete and says
what is missing (``missing``): a check that needs the whole body skips it then.

Pure Python for primitives (``urdftool check`` starts fast); numpy for mesh vertices only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from urdftool.physics import mat3
from urdftool.physics.frames import Frame
from urdftool.physics.solids import _link_shapes, rigid_group, _rigid_frames

TAGS = ("visual", "collision")


@dataclass(slots=True)
class Piece:
    """One shape placed in the frame of a :class:`Reach`: ``kind`` box, cylinder, sphere or
    mesh; ``centre`` [m]; ``rotation`` (its axes as columns); ``size``: half sizes of a box,
    (radius, half length) of a cylinder, (radius,) of a sphere; ``vertices``: a mesh's
    vertices placed, numpy [k, 3]; ``link``: the link it belongs to."""

    kind: str
    centre: mat3.Vector
    rotation: mat3.Matrix
    size: tuple = ()
    vertices: object = None
    link: str = ""

    def support(self, d) -> float:
        """max over the piece of d . x [m] (``d`` need not be a unit vector)."""
        (cx, cy, cz), (dx, dy, dz) = self.centre, d
        base = cx * dx + cy * dy + cz * dz
        r = self.rotation
        if self.kind == "box":
            return base + sum(half * abs(r[0][i] * dx + r[1][i] * dy + r[2][i] * dz)
                              for i, half in enumerate(self.size))
        if self.kind == "cylinder":
            radius, half = self.size
            along = r[0][2] * dx + r[1][2] * dy + r[2][2] * dz
            across = max(dx * dx + dy * dy + dz * dz - along * along, 0.0)
            return base + half * abs(along) + radius * math.sqrt(across)
        if self.kind == "sphere":
            return base + self.size[0] * math.sqrt(dx * dx + dy * dy + dz * dz)
        return float((self.vertices @ (dx, dy, dz)).max())

    def farthest(self, p) -> float:
        """The largest distance [m] from ``p`` to a point of the piece."""
        offset = tuple(a - b for a, b in zip(p, self.centre))
        r = self.rotation
        if self.kind == "box":
            local = [abs(r[0][i] * offset[0] + r[1][i] * offset[1] + r[2][i] * offset[2])
                     for i in range(3)]
            return math.sqrt(sum((v + half) ** 2 for v, half in zip(local, self.size)))
        if self.kind == "cylinder":
            radius, half = self.size
            along = r[0][2] * offset[0] + r[1][2] * offset[1] + r[2][2] * offset[2]
            across = math.sqrt(max(mat3.dot(offset, offset) - along * along, 0.0))
            return math.hypot(abs(along) + half, across + radius)
        if self.kind == "sphere":
            return math.sqrt(mat3.dot(offset, offset)) + self.size[0]
        import numpy as np

        return float(np.sqrt(((self.vertices - np.asarray(p)) ** 2).sum(axis=1)).max())

    def holds(self, p) -> bool:
        """Whether ``p`` is inside the piece's solid (a mesh: never claimed)."""
        offset = tuple(a - b for a, b in zip(p, self.centre))
        r = self.rotation
        local = [r[0][i] * offset[0] + r[1][i] * offset[1] + r[2][i] * offset[2]
                 for i in range(3)]
        if self.kind == "box":
            return all(abs(v) <= half for v, half in zip(local, self.size))
        if self.kind == "cylinder":
            radius, half = self.size
            return abs(local[2]) <= half and math.hypot(local[0], local[1]) <= radius
        if self.kind == "sphere":
            return math.sqrt(mat3.dot(offset, offset)) <= self.size[0]
        return False


@dataclass(slots=True)
class Reach:
    """The pieces of one or more links' geometry in one frame; ``missing``: (element,
    what) for geometry that could not be measured (then ``complete`` is False)."""

    pieces: list[Piece] = field(default_factory=list)
    missing: list = field(default_factory=list)
    links: list[str] = field(default_factory=list)

    @property
    def complete(self) -> bool:
        return not self.missing

    def support(self, d) -> float:
        """max over every piece of d . x; -inf without pieces."""
        return max((piece.support(d) for piece in self.pieces), default=-math.inf)

    def lowest(self) -> float:
        """The least z [m] of the geometry (-support of -z)."""
        return -self.support((0.0, 0.0, -1.0))

    def farthest(self, p) -> float:
        """The largest distance [m] from ``p`` to the geometry; 0 without pieces."""
        return max((piece.farthest(p) for piece in self.pieces), default=0.0)

    def outside(self, p) -> float:
        """How far ``p`` lies outside the convex hull of the pieces, at least [m]: the largest
        ``d . p - h(d)`` over :data:`DIRECTIONS` and the direction from the centre of the
        pieces' box to ``p`` (each a true lower bound of the distance; 0 or less: inside, or
        too near to tell). 0 when ``p`` is inside a primitive piece."""
        if not self.pieces or any(piece.holds(p) for piece in self.pieces):
            return 0.0
        centre = tuple((self.support(axis) - self.support(tuple(-a for a in axis))) / 2
                       for axis in _AXES)
        towards = tuple(a - b for a, b in zip(p, centre))
        norm = math.sqrt(mat3.dot(towards, towards))
        directions = DIRECTIONS + ((tuple(v / norm for v in towards),) if norm > 0 else ())
        meshes = [piece for piece in self.pieces if piece.kind == "mesh"]
        heights = _mesh_heights(meshes, directions) if meshes else None
        best = -math.inf
        for index, d in enumerate(directions):
            h = max((piece.support(d) for piece in self.pieces if piece.kind != "mesh"),
                    default=-math.inf)
            if heights is not None:
                h = max(h, heights[index])
            best = max(best, mat3.dot(d, p) - h)
        return best


_AXES = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


def _fibonacci(count: int) -> tuple:
    """``count`` unit vectors spread evenly over the sphere (a Fibonacci lattice), then the six
    axis directions."""
    golden = math.pi * (3.0 - math.sqrt(5.0))
    found = []
    for k in range(count):
        z = 1.0 - 2.0 * (k + 0.5) / count
        ring = math.sqrt(1.0 - z * z)
        found.append((ring * math.cos(golden * k), ring * math.sin(golden * k), z))
    return tuple(found) + _AXES + tuple(tuple(-a for a in axis) for axis in _AXES)


DIRECTIONS = _fibonacci(128)  # neighbours ~18 deg apart: a bound within 2 % of the distance


def _mesh_heights(meshes, directions) -> list[float]:
    import numpy as np

    d = np.asarray(directions).T
    return np.max([(piece.vertices @ d).max(axis=0) for piece in meshes], axis=0).tolist()


def link_reach(robot, link, tags=TAGS, rigid: bool = False) -> Reach:
    """The geometry of ``link`` (its ``tags`` elements) in its own frame; with ``rigid``, that
    of every link fixed to it too (:func:`urdftool.physics.solids.rigid_group`). Once per
    robot, link, tags and rigid."""
    name = link.get("name")
    return robot.memo_for((link_reach, tuple(tags), rigid), name or link,
                          lambda: _build(robot, link, tuple(tags), rigid))


def _build(robot, link, tags, rigid) -> Reach:
    name = link.get("name")
    frames = _rigid_frames(robot, name) if rigid and name in robot.links else \
        {name: (mat3.IDENTITY, (0.0, 0.0, 0.0))}
    reach = Reach(links=list(frames))
    for member, (rotation, xyz) in frames.items():
        element = robot.links.get(member, link)
        found = _link_shapes(robot, element)
        for tag in tags:
            kept, count = found[tag]
            if len(kept) < count:
                reach.missing.append((element, f"{count - len(kept)} <{tag}> of link '{member}' "
                                               "without a shape that can be measured"))
            for shape in kept:
                piece = _piece(robot, shape, (xyz, rotation), member)
                if isinstance(piece, str):
                    reach.missing.append((shape.element, piece))
                else:
                    reach.pieces.append(piece)
    return reach


def _extreme_points(vertices):
    """The vertices of the convex hull of ``vertices`` (qhull), or all of them when qhull
    cannot build one (a flat mesh; scipy absent). Exact for everything a piece answers: the
    support in any direction and the farthest point from any point are both reached at a
    vertex of the hull. A mesh of 100,000 vertices keeps a few thousand: every direction and
    every reach that holds it is that much cheaper (134 directions per link are asked whether
    a centre of mass is outside the hull)."""
    import numpy as np

    vertices = np.asarray(vertices, dtype=float)
    if len(vertices) < 64:
        return vertices
    try:
        from scipy.spatial import ConvexHull

        return vertices[np.sort(ConvexHull(vertices, qhull_options="Qt").vertices)]
    except Exception:  # qhull's error for a flat or degenerate mesh, or no scipy
        return vertices


def _piece(robot, shape, frame: Frame, member: str) -> Piece | str:
    """A shape placed by ``frame`` (position, rotation of its link in the reach's frame), or
    what keeps it from being measured."""
    position, turn = frame
    centre = mat3.add(position, mat3.apply(turn, shape.xyz))
    rotation = mat3.multiply(turn, shape.rotation)
    p = shape.params
    if shape.kind == "box":
        return Piece("box", centre, rotation, tuple(v / 2 for v in p["size"]), link=member)
    if shape.kind == "cylinder":
        return Piece("cylinder", centre, rotation, (p["radius"], p["length"] / 2), link=member)
    if shape.kind == "sphere":
        return Piece("sphere", centre, rotation, (p["radius"],), link=member)
    from urdftool.description.meshes import MeshProblem, mesh_facts

    try:
        mesh = mesh_facts(robot, p["filename"], p["scale"])
        vertices = robot.memo((_extreme_points, p["filename"], tuple(p["scale"])),
                              lambda: _extreme_points(mesh.vertices))
    except MeshProblem as problem:
        return str(problem)
    import numpy as np

    with np.errstate(all="ignore"):
        placed = np.asarray(vertices, dtype=float) @ np.asarray(rotation).T + np.asarray(centre)
    if not len(placed) or not np.isfinite(placed).all():
        return f"mesh '{p['filename']}' has no finite vertices"
    return Piece("mesh", centre, rotation, vertices=placed, link=member)


def frame_of(robot, name: str, base: str) -> Frame | None:
    """(position, rotation) of link ``name``'s frame in link ``base``'s, when both are one rigid
    body (None otherwise)."""
    frames = _rigid_frames(robot, base)
    if name not in frames:
        return None
    rotation, xyz = frames[name]
    return xyz, rotation


__all__ = ["Piece", "Reach", "link_reach", "frame_of", "rigid_group", "DIRECTIONS"]
