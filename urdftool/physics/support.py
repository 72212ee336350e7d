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

import functools
import math
import weakref
from dataclasses import dataclass, field

from urdftool.physics import mat3
from urdftool.physics.frames import Frame
from urdftool.physics.solids import GROUP_DIRECT, _bodies, body_points, _fixed_neighbours, \
    _link_shapes, mesh_reader, rigid_group, _rigid_frames
from urdftool.numbers import power

TAGS = ("visual", "collision")


@dataclass(slots=True)
class Piece:
    """One shape placed in the frame of a :class:`Reach`: ``kind`` box, cylinder, sphere or
    mesh; ``centre`` [m]; ``rotation`` (its axes as columns); ``size``: half sizes of a box,
    (radius, half length) of a cylinder, (radius,) of a sphere; ``vertices``: a mesh's
    vertices placed, numpy [k, 3] (placed when first asked, from ``mesh``, its
    ``MeshFacts``); ``inner``: a few points of the mesh placed (``MeshFacts.inner_points``:
    points of its hull; :meth:`inner_placed`); ``link``: the link it belongs to."""

    kind: str
    centre: mat3.Vector
    rotation: mat3.Matrix
    size: tuple = ()
    vertices: object = None
    link: str = ""
    inner: object = None
    mesh: object = field(default=None, repr=False, compare=False)

    def inner_placed(self):
        """A mesh's ``inner`` points, placed when first asked (most pieces never are: only a
        reach whose star is made asks). Nothing overflows here (else :func:`_piece` placed them
        at once, within numpy's error state): no error state need be set."""
        if self.inner is None:
            import numpy as np

            self.inner = self.mesh.inner_points @ np.asarray(self.rotation).T + \
                np.asarray(self.centre)
        return self.inner

    def placed(self):
        """A mesh's vertices placed (every vertex: the support and the farthest point are
        reached at one), placed once."""
        if self.vertices is None:
            self.vertices = _placed(self.mesh.vertices, self.rotation, self.centre)
        return self.vertices

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
        return float((self.placed() @ (dx, dy, dz)).max())

    def farthest(self, p) -> float:
        """The largest distance [m] from ``p`` to a point of the piece."""
        offset = tuple(a - b for a, b in zip(p, self.centre))
        r = self.rotation
        if self.kind == "box":
            local = [abs(r[0][i] * offset[0] + r[1][i] * offset[1] + r[2][i] * offset[2])
                     for i in range(3)]
            return math.sqrt(sum(power(v + half, 2) for v, half in zip(local, self.size)))
        if self.kind == "cylinder":
            radius, half = self.size
            along = r[0][2] * offset[0] + r[1][2] * offset[1] + r[2][2] * offset[2]
            across = math.sqrt(max(mat3.dot(offset, offset) - along * along, 0.0))
            return math.hypot(abs(along) + half, across + radius)
        if self.kind == "sphere":
            return math.sqrt(mat3.dot(offset, offset)) + self.size[0]
        import numpy as np

        return float(np.sqrt((power(self.placed() - np.asarray(p), 2)).sum(axis=1)).max())

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
    _table: object = field(default=None, repr=False, compare=False)  # see outside
    _shapes: object = field(default=None, repr=False, compare=False)  # see _answers

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

    def outside(self, p, beyond=None) -> float:
        """How far ``p`` lies outside the convex hull of the pieces, at least [m]: the largest
        ``d . p - h(d)`` over :data:`DIRECTIONS` and the direction from the centre of the
        pieces' box to ``p`` (each a true lower bound of the distance; 0 or less: inside, or
        too near to tell). 0 when ``p`` is inside a primitive piece. With a mesh among the
        pieces (numpy is loaded), every direction is asked at once (:class:`_Table`), and 0
        when ``p`` is found inside the hull of a few points of the pieces (:class:`_Inside`),
        or, given ``beyond`` (largest extent [m] -> the distance [m] that matters for
        geometry that large, never smaller for a larger one), found within that distance of
        it (:meth:`_Inside.near`): then no vertex of a mesh is placed (nor a mesh merged)."""
        if not self.pieces:
            return 0.0
        if any(piece.kind == "mesh" for piece in self.pieces):
            answers, asked = self._answers(), (tuple(p), beyond)
            found = answers.get(asked)
            if found is None:
                if self._table is None:
                    self._table = _Table(self.pieces)
                found = answers[asked] = self._table.outside(p, beyond=beyond)
            return found
        if any(piece.holds(p) for piece in self.pieces):
            return 0.0
        centre = tuple((self.support(axis) - self.support(tuple(-a for a in axis))) / 2
                       for axis in _AXES)
        towards = tuple(a - b for a, b in zip(p, centre))
        norm = math.sqrt(mat3.dot(towards, towards))
        directions = DIRECTIONS + ((tuple(v / norm for v in towards),) if norm > 0 else ())
        return max(mat3.dot(d, p) - self.support(d) for d in directions)


    def _answers(self) -> dict:
        """(point, beyond) -> :meth:`outside`'s answer, kept once per run for every reach of
        the same shapes (each piece's kind, place, turn, size and mesh measures: the robot
        described again in another package, another file of the same robot; on the corpus
        291 of 578 questions), with the first mesh's measures (:data:`_ANSWERS`; a mesh's
        measures named by a weak reference: the run's cache may let them go). Shapes at a
        zero of the other sign share answers: they differ at most in a zero's sign."""
        if self._shapes is None:
            self._shapes = tuple((piece.kind, piece.centre, piece.rotation, piece.size,
                                  None if piece.mesh is None else weakref.ref(piece.mesh))
                                 for piece in self.pieces)
        first = next(piece.mesh for piece in self.pieces if piece.kind == "mesh")
        kept = _ANSWERS.get(first)
        if kept is None:
            kept = _ANSWERS[first] = {}
        return kept.setdefault(self._shapes, {})


_ANSWERS = weakref.WeakKeyDictionary()  # MeshFacts -> shapes -> answers: once per run


class _Body:
    """The reach of a rigid body of more than :data:`~urdftool.physics.solids.GROUP_DIRECT`
    links seen from one member's frame: the body's pieces are placed once, in its root's
    frame (``reach``, its :class:`_Table` reduced to its hull's vertices), and each question
    is turned into that frame (``rotation``, ``xyz``: p_root = xyz + rotation p_member)."""

    __slots__ = ("reach", "rotation", "xyz", "_links")

    def __init__(self, reach: Reach, frame, links):
        self.reach, (self.rotation, self.xyz), self._links = reach, frame, links

    @property
    def pieces(self) -> list[Piece]:
        return self.reach.pieces  # in the root's frame: whether there are any

    @property
    def missing(self) -> list:
        return self.reach.missing

    @property
    def complete(self) -> bool:
        return not self.reach.missing

    @property
    def links(self) -> list[str]:
        if callable(self._links):
            self._links = self._links()
        return self._links

    def _table(self):
        if self.reach._table is None:
            self.reach._table = _Table(self.reach.pieces, reduce=len(self.reach.links))
        return self.reach._table

    def support(self, d) -> float:
        import numpy as np

        if not self.reach.pieces:
            return -math.inf
        return float(self._table().support(np.asarray(d, dtype=float).reshape(3, 1),
                                           (self.rotation, self.xyz))[0])

    def lowest(self) -> float:
        return -self.support((0.0, 0.0, -1.0))

    def farthest(self, p) -> float:
        if not self.reach.pieces:
            return 0.0
        return self._table().farthest(p, (self.rotation, self.xyz))

    def outside(self, p, beyond=None) -> float:
        """:meth:`Reach.outside` (``beyond`` is not asked: the body's few points are in its
        root's frame)."""
        if not self.reach.pieces:
            return 0.0
        return self._table().outside(p, (self.rotation, self.xyz))


class _Table:
    """Pieces as arrays, for questions asked in many directions at once: points (a mesh's
    vertices, a box's corners: a box's support and farthest point are reached at a corner),
    cylinders and spheres by their closed forms, and for :meth:`holds` every primitive. The
    points are gathered when first asked (:meth:`outside` may not need them, see
    :class:`_Inside`); with ``reduce`` (the members of a body asking), cut to the vertices
    of their convex hull (the same extremes) when many (:func:`~urdftool.physics.solids.
    body_points`). A ``frame`` (rotation, xyz) takes the asker's coordinates into the table's."""

    __slots__ = ("_pieces", "_points", "_reduce", "_inside", "_corners", "cylinders",
                 "spheres", "boxes")

    def __init__(self, pieces, reduce: int = 0):
        import numpy as np

        corners, cylinders, spheres, boxes = [], [], [], []
        for piece in pieces:
            if piece.kind == "box":
                rotation = np.asarray(piece.rotation, dtype=float)
                corners.append((_columns()[2] * piece.size) @ rotation.T + piece.centre)
                boxes.append((piece.centre, rotation, piece.size))
            elif piece.kind == "cylinder":
                cylinders.append((piece.centre, np.asarray(piece.rotation, dtype=float),
                                  piece.size))
            elif piece.kind == "sphere":
                spheres.append((*piece.centre, piece.size[0]))
        self._pieces, self._reduce, self._corners = pieces, reduce, corners
        self._points = self._inside = None
        self.boxes = _primitives(boxes)
        self.cylinders = _primitives(cylinders)
        self.spheres = np.array(spheres, dtype=float).reshape(-1, 4)

    @property
    def points(self):
        """Every mesh vertex and box corner, placed (numpy [k, 3]), in the pieces' order."""
        if self._points is None:
            import numpy as np

            found, corners = [], iter(self._corners)
            for piece in self._pieces:
                if piece.kind == "mesh":
                    found.append(piece.placed())
                elif piece.kind == "box":
                    found.append(next(corners))
            points = np.vstack(found) if found else np.zeros((0, 3))
            if self._reduce and len(points):
                points = body_points(points, self._reduce)
            self._points = points
        return self._points

    def within(self, p) -> bool:
        """Whether ``p`` (the table's frame) is found inside the convex hull of the pieces
        from a few of their points (:class:`_Inside`): no mesh vertex is placed for it."""
        if self._inside is None:
            self._inside = _Inside(self._pieces, self._corners, self.cylinders, self.spheres)
        return self._inside.holds(p)

    def support(self, directions, frame=None):
        """h(d) [m] for each column d of ``directions`` (3, k), in the asker's frame."""
        import numpy as np

        if frame is not None:
            rotation, xyz = np.asarray(frame[0], dtype=float), np.asarray(frame[1], dtype=float)
            turned = rotation @ directions
            return self.support(turned) - xyz @ turned
        heights = np.full(directions.shape[1], -np.inf)
        if len(self.points):
            with np.errstate(all="ignore"):
                heights = np.maximum(heights, highest(self.points, directions))
        return self._round_heights(directions, heights)

    def _round_heights(self, directions, heights):
        """``heights`` (the points' h(d), or -inf) raised to the cylinders' and spheres'."""
        import numpy as np

        with np.errstate(all="ignore"):
            if self.cylinders is not None:
                centres, rotations, (radii, halves) = self.cylinders
                along = rotations[:, :, 2] @ directions  # (c, k): the axis is the third column
                across = np.sqrt(np.maximum((directions * directions).sum(axis=0) -
                                            along * along, 0.0))
                heights = np.maximum(heights, (centres @ directions + halves[:, None] *
                                               np.abs(along) + radii[:, None] * across)
                                     .max(axis=0))
            if len(self.spheres):
                lengths = np.sqrt((directions * directions).sum(axis=0))
                heights = np.maximum(heights, (self.spheres[:, :3] @ directions +
                                               self.spheres[:, 3:] * lengths).max(axis=0))
        return heights

    def _in_table_frame(self, p, frame):
        import numpy as np

        p = np.asarray(p, dtype=float)
        if frame is None:
            return p
        return np.asarray(frame[1], dtype=float) + np.asarray(frame[0], dtype=float) @ p

    def holds(self, p) -> bool:
        """Whether ``p`` (the table's frame) is inside a box, cylinder or sphere."""
        import numpy as np

        for found, inside in ((self.boxes, _in_boxes), (self.cylinders, _in_cylinders)):
            if found is not None and inside(found, p):
                return True
        if len(self.spheres):
            offsets = p - self.spheres[:, :3]
            return bool((np.sqrt((offsets * offsets).sum(axis=1)) <= self.spheres[:, 3]).any())
        return False

    def farthest(self, p, frame=None) -> float:
        """The largest distance [m] from ``p`` to the pieces."""
        import numpy as np

        p = self._in_table_frame(p, frame)
        found = 0.0
        if len(self.points):
            offsets = self.points - p
            found = max(found, float(np.sqrt((offsets * offsets).sum(axis=1)).max()))
        if self.cylinders is not None:
            centres, rotations, (radii, halves) = self.cylinders
            offsets = p - centres
            along = (offsets * rotations[:, :, 2]).sum(axis=1)
            across = np.sqrt(np.maximum((offsets * offsets).sum(axis=1) - along * along, 0.0))
            found = max(found, float(np.hypot(np.abs(along) + halves, across + radii).max()))
        if len(self.spheres):
            offsets = p - self.spheres[:, :3]
            found = max(found, float((np.sqrt((offsets * offsets).sum(axis=1)) +
                                      self.spheres[:, 3]).max()))
        return found

    def outside(self, p, frame=None, beyond=None) -> float:
        """:meth:`Reach.outside` of ``p`` (the asker's frame; ``beyond`` asked without a
        ``frame`` only)."""
        import numpy as np

        inside = self._in_table_frame(p, frame)
        if self.holds(inside) or self.within(inside):
            return 0.0
        if beyond is not None and frame is None and self._inside.near(inside, beyond):
            return 0.0  # within what matters: a lower bound of how far out, as 0 is
        p = np.asarray(p, dtype=float)
        every, six, _ = _columns()
        heights = self.support(six, frame)
        centre = (heights[:3] - heights[3:]) / 2
        towards = p - centre
        norm = math.sqrt(float(towards @ towards))
        directions = every if not norm > 0 else \
            np.hstack([every, (towards / norm).reshape(3, 1)])
        if frame is None:
            found = self._pruned(p, directions)
            if found is not None:
                return found
        return float((p @ directions - self.support(directions, frame)).max())

    def _pruned(self, p, directions) -> float | None:
        """``(p @ directions - self.support(directions)).max()``, the same number, with the
        points' heights asked in the few directions that can give the largest: a question
        the stars and the walk could not settle (on the corpus 33 of 613, most of them
        findings, whose message gives the distance) otherwise asks every point (52,822
        placed vertices) in all 136 directions. The stars' points (:class:`_Inside`) lie in
        the pieces' hull (a mesh's within its ``inner_slack``), so their heights, less that
        and room for rounding, are below the points' h(d): a direction whose ``d . p``
        less that bound is below a largest found is not the largest. The heights asked are
        the same products (a column of the directions, each row of points: the same
        numbers), at least two columns at a time (numpy takes one column to another BLAS
        routine). None (every direction asked) when something is not finite."""
        import numpy as np

        few = self._inside._points if self._inside is not None else None
        points = self.points
        if few is None or not len(few) or len(points) <= _PRUNED_BELOW:
            return None
        lifted = p @ directions
        rounded = self._round_heights(directions, np.full(directions.shape[1], -np.inf))
        if not (np.isfinite(few).all() and np.isfinite(lifted).all() and
                np.isfinite(points).all() and not np.isnan(rounded).any()):
            return None
        slack = max((piece.mesh.inner_slack for piece in self._inside.pieces), default=0.0)
        size = float(np.abs(few).max()) + float(np.abs(p).max())
        below = (few @ directions).max(axis=0) - (slack + _NEAR_ROOM + 1e-9 * size)
        bound = lifted - np.maximum(below, rounded)  # at least d . p - h(d)
        order = np.argsort(-bound, kind="stable")
        asked = order[:_PRUNED_FIRST]
        found = self._lifted_less(lifted, rounded, directions, asked, points)
        rest = order[_PRUNED_FIRST:]
        rest = rest[bound[rest] >= found]
        if len(rest):
            if len(rest) == 1:  # (two columns: see above)
                rest = order[_PRUNED_FIRST - 1:_PRUNED_FIRST + 1]
            found = max(found, self._lifted_less(lifted, rounded, directions, rest, points))
        return found

    @staticmethod
    def _lifted_less(lifted, rounded, directions, asked, points) -> float:
        """The largest ``d . p - h(d)`` of the directions ``asked`` (indices, two or more),
        as :meth:`support` finds each."""
        import numpy as np

        with np.errstate(all="ignore"):
            heights = np.maximum(np.full(len(asked), -np.inf),
                                 highest(points, np.ascontiguousarray(directions[:, asked])))
        return float((lifted[asked] - np.maximum(heights, rounded[asked])).max())


# _Table._pruned: the directions asked of every point first, and the points below which
# every direction is asked at once
_PRUNED_FIRST, _PRUNED_BELOW = 4, 64

# Rows of points asked at once by highest(): their products with a few hundred directions
# stay in the processor's cache (~1 MB)
HIGHEST_ROWS = 1024


def highest(points, directions):
    """``(points @ directions).max(axis=0)``: the largest product of the points (k, 3) with
    each column of ``directions`` (3, m), the same numbers (each product is the same row
    times the same column; the largest of the largest of each block is the largest, NaN
    as ``max`` carries it), asked :data:`HIGHEST_ROWS` points at a time: the whole (k, m)
    product of a mesh's vertices (8,619 x 135: 9 MB) cost three to six times as much."""
    import numpy as np

    if len(points) <= HIGHEST_ROWS:
        return (points @ directions).max(axis=0)
    found = (points[:HIGHEST_ROWS] @ directions).max(axis=0)
    for start in range(HIGHEST_ROWS, len(points), HIGHEST_ROWS):
        np.maximum(found, (points[start:start + HIGHEST_ROWS] @ directions).max(axis=0),
                   out=found)
    return found


# Meshes of a reach whose own stars are asked before the reach's star is made (see _Inside)
OWN_STARS_FIRST = 4
# _Inside.near: steps of the walk, room for rounding [m], and the coordinates [m] it judges
_NEAR_STEPS, _NEAR_ROOM, _NEAR_RANGE = 48, 1e-6, 1e6


class _Inside:
    """A quick test that a point lies inside the convex hull of a reach's pieces, from a few
    points of them (:class:`_Star`). First the stars of the reach's first
    :data:`OWN_STARS_FIRST` meshes, each in its own frame (made once per run: a centre of mass
    lies inside its own link's mesh far more often than not, on the corpus 349 of 420
    questions, and then the reach makes no star of its own); then the star of the points of
    every piece together (of a mesh its ``inner`` points, of a box its corners, of a cylinder
    eight points of its rims, of a sphere its six poles: a point between pieces), made when
    first asked, one test; then the other meshes' own, one test each (asked before the
    reach's, every mesh's made a rigid body of n meshes cost n tests for each of its n links:
    1,000 links fixed together with meshes 1.5 s -> 5.8 s, 2,000 -> 17.5 s). Either star
    finding the point inside is enough, so the order changes only what is made. Outside is
    then 0 (the rules ask of it only beyond a centimetre); a point none can place is asked of
    every vertex."""

    __slots__ = ("_star", "_parts", "pieces", "_points")

    def __init__(self, pieces, corners, cylinders, spheres):
        self._star, self._parts = None, (pieces, corners, cylinders, spheres)
        self.pieces = [piece for piece in pieces if piece.kind == "mesh"]
        self._points = None  # the star's points, once made

    @property
    def star(self):
        """The star of the points of every piece, made when first asked."""
        if self._star is None:
            import numpy as np

            pieces, corners, cylinders, spheres = self._parts
            found = [piece.inner_placed() for piece in pieces if piece.kind == "mesh"] + \
                list(corners)
            if cylinders is not None:
                centres, rotations, (radii, halves) = cylinders
                signs = _columns()[2]  # (8, 3): a rim point for each corner of the box about it
                found.append((centres[:, None, :] + np.einsum(
                    "kij,knj->kni", rotations, signs[None] * np.stack(
                        [radii, np.zeros_like(radii), halves], axis=1)[:, None, :]))
                    .reshape(-1, 3))
            if len(spheres):
                offsets = np.vstack([np.eye(3), -np.eye(3)])
                found.append((spheres[:, None, :3] + spheres[:, None, 3:] * offsets)
                             .reshape(-1, 3))
            self._points = np.vstack(found) if found else np.zeros((0, 3))
            self._star = _Star(self._points)
        return self._star

    def near(self, p, beyond) -> bool:
        """Whether ``p`` is certainly within ``beyond(extent)`` of the hull of the pieces
        (see :meth:`Reach.outside`), found from the star's points alone: a point of their
        hull that near (Gilbert's walk towards ``p``, each step a point of the hull) against
        ``beyond`` of their box's largest side. Their hull lies in the pieces' (a mesh's
        points within its ``inner_slack`` of it: counted, with room for rounding), and their
        box in the pieces', so what holds of them holds of every vertex: False when that
        does not show it (then every vertex is asked)."""
        import numpy as np

        points = self._points
        if points is None:
            self.star  # (made by holds first; made here when a caller did not ask it)
            points = self._points
        if not len(points) or not np.isfinite(points).all() or \
                not np.isfinite(p).all():
            return False
        slack = max((piece.mesh.inner_slack for piece in self.pieces), default=0.0)
        size = float(np.abs(points).max()) + float(np.abs(p).max())
        if not size < _NEAR_RANGE:
            return False
        extent = float((points.max(axis=0) - points.min(axis=0)).max())
        # far more than every rounding (of the points, their box and the walk's sums)
        room = _NEAR_ROOM + 1e-9 * size + slack
        limit = beyond(max(extent - 2 * slack, 0.0)) - room
        if not limit > 0:
            return False
        offsets = points - p
        x = points[int(np.argmin((offsets * offsets).sum(axis=1)))]  # the nearest point
        for _ in range(_NEAR_STEPS):
            g = x - p
            distance = math.sqrt(float(g @ g))
            if distance <= limit:
                return True
            heights = points @ g
            nearest = int(np.argmin(heights))
            # no point of the hull is nearer than along -g: the hull lies beyond p there
            if (float(heights[nearest]) - float(g @ p)) / distance >= limit:
                return False
            step = x - points[nearest]
            length = float(step @ step)
            t = float(g @ step) / length if length > 0 else 0.0
            if not t > 0:
                return False  # x is the nearest point of the hull
            x = x - min(t, 1.0) * step
        return False

    def holds(self, p) -> bool:
        import numpy as np

        p = np.asarray(p, dtype=float)
        first, rest = self.pieces[:OWN_STARS_FIRST], self.pieces[OWN_STARS_FIRST:]
        if _in_own_star(first, p):  # made once per run: no star of the reach made for it
            return True
        if self.star.holds(p):  # one test for the whole reach before every mesh's own: one
            return True  # each made a body of n meshes cost n tests for each of its links
        return _in_own_star(rest, p)


def _in_own_star(pieces, p) -> bool:
    """Whether ``p`` (the reach's frame) is inside the star of one of the mesh ``pieces`` in
    its own frame (:func:`_mesh_star`)."""
    import numpy as np

    for piece in pieces:
        star = _mesh_star(piece.mesh)
        # p in the mesh's own frame: rotation^T (p - centre)
        if star.inverses is not None and \
                star.holds((p - piece.centre) @ np.asarray(piece.rotation)):
            return True
    return False


class _Star:
    """Of some points of a solid, the ones largest along the 26 directions of a cube's faces,
    edges and corners span a star of 48 tetrahedra about their mean (one per triangle of
    neighbouring directions, :data:`~urdftool.description.mesh_arrays.CUBE_TRIANGLES`).
    Every tetrahedron lies in the solid's hull, so a point strictly inside one (by 1e-7 in
    barycentric coordinates; flat ones are not asked) is inside it (to within 1e-8 m times a
    mesh's scale: a mesh's points are its corners as read until it is merged). Coordinates
    over 1e6 m are not judged so (rounding beyond a micrometre)."""

    __slots__ = ("centre", "inverses")

    def __init__(self, points):
        import numpy as np

        from urdftool.description.mesh_arrays import cube_extremes

        self.centre = self.inverses = None
        if len(points) < 4 or not (np.abs(points) < 1e6).all():
            return
        extremes = points[cube_extremes(points)]
        centre = extremes.mean(axis=0)
        # (3, 48, 3): the corners a, b, c of each tetrahedron but the centre, from the centre
        corners = (extremes[_triangles()] - centre).transpose(1, 0, 2)
        turned = corners[[1, 2, 0]]  # b, c, a: then b x c, c x a, a x b are the rows of the
        after = corners[[2, 0, 1]]  # inverse of the matrix of columns a, b, c times its det
        normals = turned[..., [1, 2, 0]] * after[..., [2, 0, 1]] - \
            turned[..., [2, 0, 1]] * after[..., [1, 2, 0]]
        volumes = (corners[0] * normals[0]).sum(axis=1)  # a . (b x c)
        sizes = np.sqrt((corners * corners).sum(axis=2)).prod(axis=0)
        solid = np.abs(volumes) > 1e-6 * sizes  # not flat: well conditioned
        if solid.any():
            self.centre = centre
            self.inverses = normals[:, solid] / volumes[solid][:, None]

    def holds(self, p) -> bool:
        if self.inverses is None:
            return False
        # barycentric weights of p in each tetrahedron (for a, b, c; the centre's is the rest)
        weights = self.inverses @ (p - self.centre)
        return bool(((weights > 1e-7).all(axis=0) & (weights.sum(axis=0) < 1 - 1e-7)).any())


_STARS = weakref.WeakKeyDictionary()  # MeshFacts -> its _Star: once per run, as the facts


def _mesh_star(mesh) -> _Star:
    """The :class:`_Star` of a mesh's inner points in its own frame, made once."""
    star = _STARS.get(mesh)
    if star is None:
        star = _STARS[mesh] = _Star(mesh.inner_points)
    return star


@functools.cache
def _triangles():
    """:data:`~urdftool.description.mesh_arrays.CUBE_TRIANGLES` as a numpy array, made once."""
    import numpy as np

    from urdftool.description.mesh_arrays import CUBE_TRIANGLES

    return np.array(CUBE_TRIANGLES)


def _primitives(found):
    """(centres (k, 3), rotations (k, 3, 3), sizes as columns) of boxes or cylinders, or None."""
    import numpy as np

    if not found:
        return None
    centres, rotations, sizes = zip(*found)
    return (np.array(centres, dtype=float), np.array(rotations),
            tuple(np.array(sizes, dtype=float).T))


def _local(found, p):
    """``p`` in each primitive's own axes: rotation^T (p - centre), (k, 3)."""
    import numpy as np

    centres, rotations, _ = found
    return np.einsum("kij,ki->kj", rotations, p - centres)


def _in_boxes(found, p) -> bool:
    import numpy as np

    halves = np.stack(found[2], axis=1)
    return bool((np.abs(_local(found, p)) <= halves).all(axis=1).any())


def _in_cylinders(found, p) -> bool:
    import numpy as np

    local = _local(found, p)
    radii, halves = found[2]
    return bool(((np.abs(local[:, 2]) <= halves) &
                 (np.hypot(local[:, 0], local[:, 1]) <= radii)).any())


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


@functools.cache
def _columns():
    """(DIRECTIONS as columns (3, k), the six axis directions as columns, the signs of a box's
    corners (8, 3)) in numpy, made when first asked: a robot without meshes needs no numpy."""
    import numpy as np

    signs = [(i, j, k) for i in (-1.0, 1.0) for j in (-1.0, 1.0) for k in (-1.0, 1.0)]
    return (np.array(DIRECTIONS, dtype=float).T, np.hstack([np.eye(3), -np.eye(3)]),
            np.array(signs))


def link_reach(robot, link, tags=TAGS, rigid: bool = False) -> Reach | _Body:
    """The geometry of ``link`` (its ``tags`` elements) in its own frame; with ``rigid``, that
    of every link fixed to it too (:func:`urdftool.physics.solids.rigid_group`): of a body of
    more than :data:`~urdftool.physics.solids.GROUP_DIRECT` links, placed once in the body's
    root's frame and seen from the link's (:class:`_Body`). Once per robot, link, tags and
    rigid."""
    name = link.get("name")
    tags = tuple(tags)
    if rigid and name in _fixed_neighbours(robot):
        root, frames = _bodies(robot)[name]
        if len(frames) > GROUP_DIRECT:
            body = robot.memo_for((link_reach, tags, _Body), root,
                                  lambda: _build(robot, robot.links[root], tags, True))
            return robot.memo_for((link_reach, tags, rigid), name, lambda: _Body(
                body, frames[name], lambda: rigid_group(robot, name)))
        return robot.memo_for((link_reach, tags, rigid), name,
                              lambda: _build(robot, link, tags, rigid))
    # nothing fixed to it (most links): its body is itself, one reach for both
    return robot.memo_for((link_reach, tags), name or link,
                          lambda: _build(robot, link, tags, False))


def inside_own(robot, link, p) -> bool:
    """Whether ``p`` [m] (the link frame) is certainly inside the link's own visual or
    collision geometry (:func:`link_reach` of the link alone): inside one of its primitives
    (:meth:`Piece.holds`) or the star of one of its meshes (:func:`_mesh_star`, in the mesh's
    own frame), every coordinate of ``p`` within 1e6 m (rounding far below a micrometre).
    Then ``p`` is inside the hull of every reach holding those pieces, its rigid body's too,
    whose :meth:`Reach.outside` is 0 to that rounding: asked of a member of a body before the
    body's reach is gathered in the member's frame (each member gathers every member's
    pieces: a body of n links places n^2)."""
    if not all(abs(v) < _NEAR_RANGE for v in p):  # (False for a NaN too)
        return False
    pieces = link_reach(robot, link).pieces
    if any(piece.holds(p) for piece in pieces if piece.kind != "mesh"):
        return True
    meshes = [piece for piece in pieces if piece.kind == "mesh"]
    if not meshes:
        return False
    import numpy as np

    return _in_own_star(meshes, np.asarray(p, dtype=float))


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
    problem_type, mesh_facts, _ = mesh_reader()
    try:
        mesh = mesh_facts(robot, p["filename"], p["scale"])
    except problem_type as problem:
        return str(problem)
    import numpy as np

    # its vertices (merged, once per run for every robot using the file) when first placed
    piece = Piece("mesh", centre, rotation, mesh=mesh, link=member)
    # placed, a vertex within 1e150 of the origin stays finite (a rotation's entries are at
    # most 1) when the centre is too; else each vertex is placed now, as all are asked then
    if not (mesh.faces and all(abs(v) < 1e150 for v in centre) and mesh.moderate):
        placed = piece.placed()
        if not len(placed) or not np.isfinite(placed).all():
            return f"mesh '{p['filename']}' has no finite vertices"
        piece.inner = _placed(mesh.inner_points, rotation, centre)
    # else nothing overflows: its inner points are placed when a star asks (inner_placed)
    return piece


def _placed(points, rotation, centre):
    """``points`` (numpy [k, 3], or rows) turned by ``rotation`` and moved by ``centre``."""
    import numpy as np

    with np.errstate(all="ignore"):
        return np.asarray(points, dtype=float) @ np.asarray(rotation).T + np.asarray(centre)


def frame_of(robot, name: str, base: str) -> Frame | None:
    """(position, rotation) of link ``name``'s frame in link ``base``'s, when both are one rigid
    body (None otherwise)."""
    frames = _rigid_frames(robot, base)
    if name not in frames:
        return None
    rotation, xyz = frames[name]
    return xyz, rotation


__all__ = ["Piece", "Reach", "link_reach", "inside_own", "frame_of", "rigid_group", "DIRECTIONS"]
