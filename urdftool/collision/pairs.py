"""Collision and distance between link pairs for many configurations.

For a block of sampled configurations, every part pair first goes through a vectorised
separating-axis test of the parts' oriented bounding boxes, each grown by half the margin (after an
even cheaper bounding-sphere test): a pair that passes them is certainly farther apart than the
margin, and FCL is never asked about it. The
few (sample, pair) candidates left are checked by FCL, one relative transform each (the first part
stays at the identity, the second moves), with a distance query when they do not collide.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import fcl
import numpy as np

CHUNK = 1 << 19  # (sample, part pair) cells worked on at once: ~12 MB a float array of centres


@dataclass
class Tally:
    """What a block of samples showed, per link pair.

    samples: how many configurations; collisions: in how many of them the pair collided
    min_distance: smallest exact distance seen in [m] (0 once collided; inf if FCL never asked)
    bound: smallest bounding-sphere gap seen in [m] (a lower bound on the distance), and
    bound_sample: the global index of the sample where it was seen
    """

    samples: int
    collisions: np.ndarray
    min_distance: np.ndarray
    bound: np.ndarray
    bound_sample: np.ndarray

    @classmethod
    def empty(cls, pairs: int) -> "Tally":
        return cls(0, np.zeros(pairs, dtype=np.int64), np.full(pairs, np.inf),
                   np.full(pairs, np.inf), np.full(pairs, -1, dtype=np.int64))

    def merge(self, other: "Tally") -> "Tally":
        """Both tallies together; associative and independent of which worker did what."""
        take = (other.bound < self.bound) | ((other.bound == self.bound)
                                             & (other.bound_sample < self.bound_sample))
        return Tally(self.samples + other.samples, self.collisions + other.collisions,
                     np.minimum(self.min_distance, other.min_distance),
                     np.where(take, other.bound, self.bound),
                     np.where(take, other.bound_sample, self.bound_sample))


# [m] the one tolerance of contact: shapes whose penetration depth is at most this touch (a lift
# on its base, parts exported to share a face, FCL's contact of exactly touching boxes, depth 0)
# and do not collide: `collisions` at a pose, and the SRDF overlaps check's rules report
TOUCHING = 0.001


class PairChecker:
    """FCL objects and bounding boxes for a fixed list of link pairs."""

    def __init__(self, geometry, links: list[str], link_pairs: list[tuple[str, str]],
                 margin: float):
        """links: the links of the pose arrays given to the checks, in their order."""
        self.link_pairs = link_pairs
        self.margin = margin
        link_index = {name: i for i, name in enumerate(links)}
        parts = [part for name in geometry.links for part in geometry.parts[name]]
        first = {}
        for k, part in enumerate(parts):
            first.setdefault(part.link, []).append(k)
        self.part_link = np.array([link_index[part.link] for part in parts], dtype=np.int64)
        self.origins = np.array([part.origin for part in parts]).reshape(-1, 4, 4)
        self.boxes = np.array([part.box for part in parts]).reshape(-1, 4, 4)
        self.half = np.array([part.half for part in parts]).reshape(-1, 3)
        self.radius = np.linalg.norm(self.half, axis=1)
        self.is_box = np.array([part.kind == "box" for part in parts], dtype=bool)
        self.is_mesh = np.array([part.kind == "mesh" for part in parts], dtype=bool)
        self.meshes = [part.mesh for part in parts]
        self.geometries = [part.geometry for part in parts]
        self._hulls: dict[int, tuple | None] = {}
        self.fixed = [fcl.CollisionObject(part.geometry, fcl.Transform()) for part in parts]
        self.moving = [fcl.CollisionObject(part.geometry, fcl.Transform()) for part in parts]
        rows = [(a, b, index) for index, (one, two) in enumerate(link_pairs)
                for a in first[one] for b in first[two]]
        self.pa, self.pb, self.pair_of = (np.array(column, dtype=np.int64)
                                          for column in zip(*rows)) if rows else \
            (np.zeros(0, dtype=np.int64),) * 3
        self._request = fcl.CollisionRequest()
        self._distance_request = fcl.DistanceRequest()

    def tally(self, link_poses: np.ndarray, first_sample: int = 0,
              distances: bool = True) -> Tally:
        """Collision counts and distances over a block of configurations' link poses.

        distances: ask FCL for the distance of the candidates that do not collide (about half
        of the work on meshes); without it ``min_distance`` stays inf, for callers that only
        count collisions.

        The part pairs are taken in slices of whole link pairs, each at most ``CHUNK`` (sample,
        part pair) cells, so the working arrays stay the same size however many links the robot
        has (a 1,500-link robot has 1.1 million pairs: 250 samples of them at once were 2 GB a
        array)."""
        count, pairs = len(link_poses), len(self.link_pairs)
        result = Tally.empty(pairs)
        result.samples = count
        if not len(self.pa) or not count:
            return result
        boxes = link_poses[:, self.part_link] @ self.boxes
        step = max(1, CHUNK // count)
        row = 0
        while row < len(self.pa):
            first_pair = self.pair_of[row]
            # end on a link-pair boundary: the rows of one pair are contiguous
            last_pair = self.pair_of[min(row + step, len(self.pa)) - 1] + 1
            end = int(np.searchsorted(self.pair_of, last_pair))
            self._tally_rows(link_poses, boxes, slice(row, end),
                             slice(int(first_pair), int(last_pair)), first_sample, result,
                             distances)
            row = end
        result.min_distance[result.collisions > 0] = 0.0
        return result

    def _tally_rows(self, link_poses, boxes, rows_slice: slice, pairs_slice: slice,
                    first_sample: int, result: Tally, distances: bool) -> None:
        """:meth:`tally` for the part pairs ``rows_slice``, which make the link pairs
        ``pairs_slice``; writes into ``result``'s entries of those pairs."""
        count = len(link_poses)
        pa, pb = self.pa[rows_slice], self.pb[rows_slice]
        pair_of = self.pair_of[rows_slice] - pairs_slice.start
        pairs = pairs_slice.stop - pairs_slice.start
        centers = boxes[..., :3, 3]
        gap = (np.linalg.norm(centers[:, pa] - centers[:, pb], axis=-1)
               - self.radius[pa] - self.radius[pb])
        self._bounds(result, gap, pair_of, pairs_slice, first_sample)
        samples, rows = np.nonzero(gap < self.margin)
        del gap
        grow = self.margin / 2
        near = ~separated(boxes[samples, pa[rows]], self.half[pa[rows]] + grow,
                          boxes[samples, pb[rows]], self.half[pb[rows]] + grow)
        samples, rows = samples[near], rows[near]
        collided = np.zeros((count, pairs), dtype=bool)
        # For two boxes the separating-axis test is exact: no FCL call needed to know they touch.
        boxed = self.is_box[pa[rows]] & self.is_box[pb[rows]]
        touching = np.zeros(len(rows), dtype=bool)
        touching[boxed] = ~separated(
            boxes[samples[boxed], pa[rows[boxed]]], self.half[pa[rows[boxed]]],
            boxes[samples[boxed], pb[rows[boxed]]], self.half[pb[rows[boxed]]])
        collided[samples[touching], pair_of[rows[touching]]] = True
        samples, rows, boxed = samples[~touching], rows[~touching], boxed[~touching]
        distance = result.min_distance[pairs_slice]  # a view: _narrow writes through it
        if len(samples):
            ends = np.stack([pa[rows], pb[rows]], axis=1)
            parts = link_poses[samples[:, None], self.part_link[ends]] @ self.origins[ends]
            rotation = np.swapaxes(parts[:, 0, :3, :3], 1, 2) @ parts[:, 1, :3, :3]
            translation = np.einsum("nji,nj->ni", parts[:, 0, :3, :3],
                                    parts[:, 1, :3, 3] - parts[:, 0, :3, 3])
            self._narrow(samples, rows, rotation, translation, ~boxed, collided,
                         distance if distances else None, pa, pb, pair_of)
        result.collisions[pairs_slice] = collided.sum(axis=0)

    def _bounds(self, result: Tally, gap: np.ndarray, pair_of: np.ndarray,
                pairs_slice: slice, first_sample: int) -> None:
        pairs = pairs_slice.stop - pairs_slice.start
        if len(pair_of) == pairs:  # one part per link: rows are pairs
            per_pair = gap
        else:
            per_pair = np.full((len(gap), pairs), np.inf)
            np.minimum.at(per_pair, (slice(None), pair_of), gap)
        best = np.argmin(per_pair, axis=0)
        result.bound[pairs_slice] = per_pair[best, np.arange(pairs)]
        result.bound_sample[pairs_slice] = best + first_sample

    def _narrow(self, samples, rows, rotation, translation, ask, collided, distance,
                pa, pb, pair_of) -> None:
        """Collision for the candidates where ``ask`` (the others are known apart), then distance
        only for candidates of pairs that never collided in this block (a pair that collided is
        at distance 0 whatever else happens); ``distance`` None: collisions only."""
        fixed, moving = self.fixed, self.moving
        apart = []
        for n in range(len(samples)):
            sample, row = samples[n], rows[n]
            if collided[sample, pair_of[row]]:
                continue
            if not ask[n]:
                apart.append(n)
                continue
            mover = moving[pb[row]]
            mover.setTransform(fcl.Transform(rotation[n], translation[n]))
            if fcl.collide(fixed[pa[row]], mover, self._request, fcl.CollisionResult()):
                collided[sample, pair_of[row]] = True
            else:
                apart.append(n)
        if distance is None:
            return
        hit = collided.any(axis=0)
        for n in apart:
            row = rows[n]
            pair = pair_of[row]
            if hit[pair]:
                continue
            mover = moving[pb[row]]
            mover.setTransform(fcl.Transform(rotation[n], translation[n]))
            gap = _gap(fcl.distance(fixed[pa[row]], mover, self._distance_request,
                                    fcl.DistanceResult()))
            if gap < distance[pair]:
                distance[pair] = gap

    def exact(self, link_poses: np.ndarray, pair: int, contacts: bool = False,
              part_poses: np.ndarray | None = None, placed: bool = False,
              touching_first: bool = False):
        """(colliding, distance [m], depth [m] or None, depth bound [m] or None) of one link
        pair at one pose; the depths only with ``contacts`` (else 0).

        The depth is FCL's between primitives. Where a mesh is in contact it is the depth of
        the convex hulls (:meth:`_hull_depth`; FCL's contacts between triangles carry the depth
        of one triangle through the other's plane, 0 to a triangle's size whatever the
        overlap): exact when each mesh is convex, else None with the hulls' depth as the bound
        (the meshes overlap no deeper than their hulls). The bound is the depth when that is
        known, and None when not even the hulls give one (a flat mesh).

        part_poses: :meth:`part_poses` of ``link_poses`` when the caller asks about many pairs
        at the same pose (then ``link_poses`` is not read); placed: :meth:`place` has put
        every part there already (each part is then not placed again for each pair);
        touching_first: a mesh's contact that only touches (:data:`TOUCHING`) is told without
        its hull (:meth:`_hull_depth`), its depth then None, bounded (for a caller that wants
        only the contacts deeper than that: check's SRDF overlaps)."""
        depth, bound, nearest, hit = 0.0, 0.0, np.inf, False
        request = fcl.CollisionRequest(num_max_contacts=16, enable_contact=True) if contacts \
            else self._request
        if part_poses is None:
            part_poses = self.part_poses(link_poses)
        for row in range(self._first_row[pair], self._first_row[pair + 1]):
            a, b = self.pa[row], self.pb[row]
            if placed:
                one, two = self.moving[a], self.moving[b]
            else:
                one, two = self._place(part_poses, a), self._place(part_poses, b)
            result = fcl.CollisionResult()
            if not fcl.collide(one, two, request, result):
                nearest = min(nearest, _gap(fcl.distance(one, two, self._distance_request,
                                                         fcl.DistanceResult())))
                continue
            hit = True
            if not contacts:
                continue
            if self.is_mesh[a] or self.is_mesh[b]:
                here, at_most = self._hull_depth(a, b, part_poses, touching_first)
            else:
                here = at_most = min(max(c.penetration_depth for c in result.contacts),
                                     self._overlap(a, b, part_poses, result.contacts))
            depth = None if depth is None or here is None else max(depth, here)
            bound = None if bound is None or at_most is None else max(bound, at_most)
        return hit, (0.0 if hit else nearest), depth, bound

    def _hull_depth(self, a: int, b: int, part_poses,
                    touching_first: bool = False) -> tuple[float | None, float | None]:
        """(depth, bound) [m] of parts ``a`` and ``b`` in contact, a mesh among them: FCL's
        penetration depth (GJK/EPA) between their convex hulls (a primitive is its own hull),
        exact when each mesh is convex (its volume is its hull's), else only a bound. With
        ``touching_first``, surfaces that only touch (parts exported to share a face) are told
        first, by the least overlap along the axes and the centres' line from the meshes' own
        vertices: their depth is at most that bound (None, the bound), and no hull is built
        (qhull, and the imports of scipy and trimesh it needs)."""
        if touching_first:
            least = self._overlap(a, b, part_poses, ())
            if least <= TOUCHING:
                return None, least
        shapes, exact = [], True
        for part in (a, b):
            if self.is_mesh[part]:
                hull = self._hull(part)
                if hull is None:
                    return None, None
                shapes.append(hull[0])
                exact &= hull[1]
            else:
                shapes.append(self.geometries[part])
        one, two = (fcl.CollisionObject(shape, fcl.Transform(part_poses[part][:3, :3],
                                                            part_poses[part][:3, 3]))
                    for shape, part in zip(shapes, (a, b)))
        result = fcl.CollisionResult()
        # the meshes' surfaces cross, so their hulls overlap: FCL says so with a depth of 0
        # at least (touching hulls), and a hull query that finds no contact is a depth of 0
        fcl.collide(one, two, fcl.CollisionRequest(num_max_contacts=1, enable_contact=True),
                    result)
        deepest = max([0.0, *(c.penetration_depth for c in result.contacts)])
        deepest = min(deepest, self._overlap(a, b, part_poses, result.contacts))
        return (deepest if exact else None), deepest

    def _overlap(self, a: int, b: int, part_poses, contacts) -> float:
        """The least overlap [m] of parts ``a`` and ``b`` (their hulls) along a few directions:
        the contacts' normals, the world's axes, each part's axes and the line between their
        centres. Moving one part by it along that direction separates them, so it bounds the
        penetration depth from above. libccd's EPA, which FCL asks for every pair but two boxes,
        overshoots when the shapes are centred on each other (two crossing cylinders 37 mm into
        each other: 62 mm; coincident cubes of 10 cm: 141 mm), as parts placed at one origin
        in CAD often are; the least of the two is kept."""
        pa, pb = part_poses[a], part_poses[b]
        directions = [np.asarray(c.normal, dtype=float) for c in contacts]
        directions += [*np.eye(3), *pa[:3, :3].T, *pb[:3, :3].T, pb[:3, 3] - pa[:3, 3]]
        least = np.inf
        for d in directions:
            length = np.linalg.norm(d)
            if not length > 1e-12:
                continue
            d = d / length
            high_a, high_b = self._support(a, pa, d), self._support(b, pb, d)
            low_a, low_b = -self._support(a, pa, -d), -self._support(b, pb, -d)
            least = min(least, max(0.0, min(high_a - low_b, high_b - low_a)))
        return least

    def _support(self, part: int, pose: np.ndarray, d: np.ndarray) -> float:
        """max of d . x over part ``part`` (its hull for a mesh) at ``pose`` [m]."""
        local = pose[:3, :3].T @ d
        centre = float(d @ pose[:3, 3])
        shape = self.geometries[part]
        if self.is_mesh[part]:  # its vertices' (the hull's points' maximum is theirs)
            return centre + float(np.max(self.meshes[part][0] @ local))
        if isinstance(shape, fcl.Box):
            return centre + float(np.abs(local) @ (np.asarray(shape.side) / 2))
        if isinstance(shape, fcl.Cylinder):
            return centre + shape.radius * float(np.hypot(local[0], local[1])) + \
                shape.lz / 2 * abs(float(local[2]))
        return centre + shape.radius  # a sphere

    def _hull(self, part: int):
        """(FCL convex hull, whether the mesh is convex) of mesh part ``part``, built once;
        None for a mesh without volume (flat), which has no hull."""
        if part not in self._hulls:
            self._hulls[part] = _convex(*self.meshes[part])
        return self._hulls[part]

    def part_poses(self, link_poses: np.ndarray) -> np.ndarray:
        """World poses ``[..., parts, 4, 4]`` of every part for link poses ``[..., links, 4, 4]``."""
        return link_poses[..., self.part_link, :, :] @ self.origins

    @cached_property
    def _first_row(self) -> list[int]:
        """Row where each pair's part pairs begin (they are contiguous), and the row count."""
        return np.searchsorted(self.pair_of, np.arange(len(self.link_pairs) + 1)).tolist()

    def place(self, part_poses: np.ndarray) -> None:
        """Put every part at its pose in ``part_poses``, for :meth:`exact` with ``placed``."""
        for part in range(len(self.moving)):
            self._place(part_poses, part)

    def _place(self, part_poses, part: int):
        pose = part_poses[part]
        self.moving[part].setTransform(fcl.Transform(pose[:3, :3], pose[:3, 3]))
        return self.moving[part]


def _gap(distance: float) -> float:
    """FCL's distance of two shapes its collision test found apart [m]: FCL answers -1, its
    "in collision", for shapes that only touch (boxes sharing a face: the collision test says
    apart, the distance's GJK overlapping), which was shown as -1000 mm apart; they are 0 apart."""
    return max(0.0, distance)


# a closed mesh whose volume is within this fraction of its convex hull's is convex: the hulls'
# depth is its own (a faceted sphere or cylinder, a box exported as triangles)
CONVEX = 1e-3


def _convex(vertices: np.ndarray, faces: np.ndarray):
    """(fcl.Convex of the hull of ``vertices``, whether the mesh ``vertices``, ``faces`` is that
    hull: closed, with the hull's volume to :data:`CONVEX`), or None when the points span no
    volume."""
    import trimesh
    from scipy.spatial import ConvexHull, QhullError

    try:
        hull = ConvexHull(vertices)
    except (QhullError, ValueError):  # flat or too few points: no volume
        return None
    mesh = trimesh.Trimesh(vertices, faces, process=True)
    convex = bool(mesh.is_watertight and abs(abs(mesh.volume) - hull.volume) <=
                  CONVEX * hull.volume)
    points = np.ascontiguousarray(hull.points[hull.vertices], dtype=float)
    renumber = np.zeros(len(hull.points), dtype=np.int64)
    renumber[hull.vertices] = np.arange(len(hull.vertices))
    triangles = renumber[hull.simplices]
    counts = np.full((len(triangles), 1), 3, dtype=np.int64)
    return fcl.Convex(points, len(triangles), np.hstack([counts, triangles]).ravel()), convex


def separated(a: np.ndarray, half_a: np.ndarray, b: np.ndarray, half_b: np.ndarray) -> np.ndarray:
    """Separating-axis test of oriented boxes (poses ``a``, ``b`` (..., 4, 4), half extents
    (..., 3)): True where the boxes certainly do not overlap (Gottschalk's 15 axes)."""
    ra, rb = a[..., :3, :3], b[..., :3, :3]
    rotation = np.swapaxes(ra, -1, -2) @ rb
    t = np.einsum("...ji,...j->...i", ra, b[..., :3, 3] - a[..., :3, 3])
    absolute = np.abs(rotation) + 1e-9
    half_a = np.broadcast_to(half_a, t.shape)
    half_b = np.broadcast_to(half_b, t.shape)
    apart = np.any(np.abs(t) > half_a + np.einsum("...ij,...j->...i", absolute, half_b), axis=-1)
    projected = np.einsum("...i,...ij->...j", t, rotation)
    apart |= np.any(np.abs(projected) > np.einsum("...i,...ij->...j", half_a, absolute) + half_b,
                    axis=-1)
    for i in range(3):
        i1, i2 = (i + 1) % 3, (i + 2) % 3
        for j in range(3):
            j1, j2 = (j + 1) % 3, (j + 2) % 3
            lhs = np.abs(t[..., i2] * rotation[..., i1, j] - t[..., i1] * rotation[..., i2, j])
            rhs = (half_a[..., i1] * absolute[..., i2, j]
                   + half_a[..., i2] * absolute[..., i1, j]
                   + half_b[..., j1] * absolute[..., i, j2]
                   + half_b[..., j2] * absolute[..., i, j1])
            apart |= lhs > rhs
    return apart
