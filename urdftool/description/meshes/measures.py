"""What the checks measure of a mesh (:func:`mesh_facts`): bounds, triangle count,
watertightness, volume, centre of mass, inertia, the convex hull's.

Measured once per file and scale per run, on the mesh's corners merged by position (a seam of
normals or texture coordinates is no hole), merged only when something beyond the bounds and
triangle count is asked. STL, COLLADA and plain OBJ files are read and measured without trimesh
or pycollada (:mod:`urdftool.description.mesh_arrays`, COLLADA through
:mod:`urdftool.description.collada`), other formats through trimesh (:mod:`.reading`).
"""

from __future__ import annotations

from pathlib import Path

from urdftool.description import mesh_arrays
from urdftool.description.collada import ColladaProblem
from urdftool.description.inputs import MeshLimits
from urdftool.description.meshes.reading import NOT_FINITE, NOT_WELL_FORMED, beyond_range, \
    check_size, collada_unit, finite_scale, mesh_bytes, read_once, recovered_collada, \
    refuse_too_far, refuse_too_many
from urdftool.description.meshes.run_cache import limits_key, once, stamp_of
from urdftool.description.meshes.uris import resolve
from urdftool.errors import MeshProblem

def _arrays_once(path: Path, uri: str, limits: MeshLimits, stamp):
    """The mesh's :class:`_Arrays`, once per run: read by :mod:`.mesh_arrays` where the format
    allows (STL, COLLADA, plain OBJ), else by trimesh (:func:`read_once`)."""
    def compute():
        arrays, metadata, unit = None, {}, 1.0
        suffix = path.suffix.lower()
        if suffix in (".stl", ".dae", ".obj"):
            data = mesh_bytes(path, uri, limits)  # read once: the limits are checked in it
            # a COLLADA file's triangles are counted as they are read, before they are built;
            # an OBJ's only when its "f " may make too many (a plain one has one a row;
            # the arrays read are counted below, any other is counted before trimesh reads it)
            check_size(path, uri, limits, data, count=suffix == ".stl" or (
                suffix == ".obj" and data.count(b"f ") > limits.max_triangles))
            if suffix == ".dae":
                arrays, metadata = _collada_arrays(path, uri, data, limits)
                unit = collada_unit(data)
            else:
                arrays = mesh_arrays.read_unmerged(path, data)
        if arrays is None:
            loaded = read_once(path, uri, limits)
            if isinstance(loaded, MeshProblem):
                raise loaded
            import numpy as np

            arrays = mesh_arrays.merged(np.asarray(loaded.vertices, dtype=np.float64),
                                        np.asarray(loaded.faces, dtype=np.int64))
            found = _Arrays(*arrays, {**metadata, **loaded.metadata}, merged=True)
        else:
            found = _Arrays(*arrays, metadata, unit=unit)
        refuse_too_many(uri, found.triangles, limits)
        return found, found.nbytes

    return once((str(path), stamp, limits_key(limits), "arrays"), uri, compute)


def _collada_arrays(path: Path, uri: str, data: bytes, limits: MeshLimits):
    """(arrays or None, metadata) of a COLLADA file read by :mod:`.mesh_arrays`, unmerged, in
    its own unit (:class:`_Arrays` applies it as :func:`_read_mesh` does); XML that is not well-formed is read as recovered
    (metadata :data:`NOT_WELL_FORMED`), as :func:`_read_mesh` reads it. None for a document
    trimesh should judge (no triangles, or malformed: it says what is wrong)."""
    metadata = {}
    try:
        try:
            arrays = mesh_arrays.read_unmerged(path, data, limits.max_triangles)
        except ColladaProblem as problem:
            recovered = recovered_collada(data) if problem.not_well_formed else None
            if recovered is None:
                raise
            arrays = mesh_arrays.read_unmerged(path, recovered[0], limits.max_triangles)
            metadata = {NOT_WELL_FORMED: recovered[1]}
    except ColladaProblem as problem:
        if problem.kind == "too-large":
            raise MeshProblem("too-large", f"mesh '{uri}': {problem}; not loaded") from None
        # trimesh reads it (pycollada: a position that is not finite made another one)
        return None, ({NOT_FINITE: str(problem)} if problem.not_finite else {})
    return arrays, metadata


class _Arrays:
    """A mesh file's triangles: as read (every vertex used by a face, in the file's unit)
    until something needs them merged by position (:func:`.mesh_arrays.merged`, then scaled by
    a COLLADA file's ``unit``, as trimesh's are). Bounds need no merging
    (:func:`.mesh_arrays.merged_bounds`): a mesh that only has to fit in a box is not merged.
    ``merged=True``: the arrays given are merged already (and in metres). ``faces`` None: each
    three vertices in order are a triangle (:func:`.mesh_arrays.read_unmerged`)."""

    def __init__(self, vertices, faces, metadata: dict, unit: float = 1.0, merged: bool = False):
        self.metadata = metadata
        self.triangles = len(vertices) // 3 if faces is None else len(faces)
        # merged, they are no larger (faces None: merged, they are the merging's own array)
        self.nbytes = vertices.nbytes + (vertices.nbytes // 3 if faces is None else faces.nbytes)
        self._read = None if merged else (vertices, faces)
        self._unit = unit
        self._merged = (vertices, faces, mesh_arrays.is_watertight(faces)) if merged else None

    def merged(self):
        """(vertices, faces, watertight) merged by position; the arrays read are let go."""
        if self._merged is None:
            vertices, faces = mesh_arrays.merged(*self._read)
            if self._unit != 1.0:
                vertices, faces = mesh_arrays.scaled(vertices, faces, (self._unit,) * 3)
            self._merged, self._read = (vertices, faces, mesh_arrays.is_watertight(faces)), None
        return self._merged

    def corners_read(self, scale: tuple[float, float, float]):
        """The triangles' corners as read (not merged: each within 1e-8 of a merged vertex,
        or one), in metres and scaled by ``scale``; None once merged (the merged vertices
        then stand for them)."""
        if self._read is None:
            return None
        import numpy as np

        moved = self._read[0]
        with np.errstate(all="ignore"):
            for factors in ((self._unit,) * 3, scale):
                if factors != (1.0, 1.0, 1.0):
                    moved, _ = mesh_arrays.scaled(moved, self._read[1], factors)
        return moved

    def corner_slack(self, scale: tuple[float, float, float]) -> float:
        """How far [m] a corner as read (:meth:`corners_read`) may lie from the merged vertex
        it merges into: corners merge when their coordinates round to one multiple of 1e-8
        in the file's unit (less than 1e-8 apart on each axis), and both are then scaled by
        the unit and ``scale``; twice that, for rounding."""
        return 2 * 3 ** 0.5 * 10.0 ** -mesh_arrays.MERGE_DIGITS * abs(self._unit) * \
            max(abs(s) for s in scale)

    def refuse_too_far(self, uri: str) -> None:
        """:func:`.reading.refuse_too_far` of the vertices read, before they are merged (the
        bounds found without merging have every coordinate within range)."""
        if self._read is not None:
            refuse_too_far(uri, self._read[0])

    def bounds(self, scale: tuple[float, float, float]):
        """The bounds (min corner, max corner: tuples of floats) of the merged vertices scaled
        by ``scale``, found without merging them; None when that cannot be decided so (see
        :func:`.mesh_arrays.merged_bounds`)."""
        if self._read is None:
            return None
        import numpy as np

        vertices, faces = self._read
        moved = vertices
        with np.errstate(all="ignore"):  # a vertex beyond range: merged, it is reported
            for factors in ((self._unit,) * 3, scale):
                if factors != (1.0, 1.0, 1.0):
                    moved, _ = mesh_arrays.scaled(moved, faces, factors)
        if not np.isfinite(moved).all():
            return None
        return mesh_arrays.merged_bounds(moved, vertices)


class MeshFacts:
    """What the checks measure of a mesh at a scale, under trimesh's names, so that rules and
    solids read it as they would read the ``trimesh.Trimesh`` that :func:`load_mesh` gives
    (same numbers: :mod:`.mesh_arrays` measures as trimesh does).

    faces: the triangle count; bounds: min and max corner and extents, as tuples of floats
    (trimesh's are arrays: six numbers cost less as Python's, and their readers take both);
    is_watertight;
    metadata: :data:`NOT_WELL_FORMED` for a repaired COLLADA file; vertices (merged by
    position), is_watertight, mass_properties (density 1, of the mesh as it is),
    convex_hull (its measures, as trimesh's hull has them; qhull's RuntimeError for a flat
    mesh) and extreme_points (the hull's vertices, or all: :func:`.mesh_arrays.extreme_points`)
    are computed when first asked, once per run for every robot using the file at that scale:
    the merging too, when bounds were found without it.
    """

    def __init__(self, vertices, faces, metadata: dict, watertight: bool | None = None,
                 properties: dict | None = None):
        low, high = mesh_arrays.bounds(vertices, faces)
        self._start(len(faces), (tuple(low.tolist()), tuple(high.tolist())), metadata,
                    vertices.nbytes + faces.nbytes)
        self._vertices, self._faces, self._watertight = vertices, faces, watertight
        self._properties = properties

    @classmethod
    def unmerged(cls, triangles: int, bounds, metadata: dict, nbytes: int, merge,
                 corners=None, slack: float = 0.0):
        """Facts whose bounds are known and whose arrays ``merge()`` builds when first
        needed: (vertices, faces, watertight), merged and scaled; ``corners()``: the corners
        as read, scaled (or None), for what needs no merging (:attr:`inner_points`), each
        within ``slack`` [m] of a merged vertex (:attr:`inner_slack`)."""
        facts = cls.__new__(cls)
        facts._start(triangles, bounds, metadata, nbytes)
        facts._merge, facts._corners = merge, corners
        facts.inner_slack = slack if corners is not None else 0.0
        return facts

    def _start(self, triangles: int, bounds, metadata: dict, nbytes: int) -> None:
        self.faces, self.bounds, self.metadata, self.nbytes = triangles, bounds, metadata, nbytes
        low, high = bounds
        self.extents = (high[0] - low[0], high[1] - low[1], high[2] - low[2])
        # every coordinate within 1e150 of the origin: turned and moved by what is not
        # larger, none overflows
        self.moderate = all(abs(v) < 1e150 for v in low + high)
        self._vertices = self._faces = self._watertight = self._merge = None
        self._properties, self._hull, self._extreme = None, None, None
        self._inner = self._inner_volume = self._inner_tetrahedron = self._corners = None
        self.inner_slack = 0.0  # [m]: how far an inner point may lie from a merged vertex

    def _arrays(self):
        if self._merge is not None:
            self._vertices, self._faces, watertight = self._merge()
            self._watertight = watertight if self._watertight is None else self._watertight
            self._merge = None
        return self._vertices, self._faces

    @property
    def vertices(self):
        """The (n, 3) vertex array, as trimesh's ``vertices`` (read only: shared by every user)."""
        return self._arrays()[0]

    @property
    def is_watertight(self) -> bool:
        if self._watertight is None:
            faces = self._arrays()[1]
            if self._watertight is None:
                self._watertight = mesh_arrays.is_watertight(faces)
        return self._watertight

    @property
    def mass_properties(self) -> dict:
        if self._properties is None:
            self._properties = mesh_arrays.mass_properties(*self._arrays())
        return self._properties

    @property
    def extreme_points(self):
        """The vertices that the support and the farthest point are reached at (read only)."""
        if self._extreme is None:
            self._extreme = mesh_arrays.extreme_points(self.vertices)
        return self._extreme

    @property
    def inner_points(self):
        """At most 26 points of the mesh, each largest along a direction of a cube's faces,
        edges and corners (:func:`.mesh_arrays.cube_extremes`): points of its hull, found
        without building it (read only). Of the corners as read while the mesh is not merged
        (merging would cost more), each within :attr:`inner_slack` [m] of a merged vertex."""
        if self._inner is None:
            points = self._corners() if self._merge is not None and self._corners else None
            if points is None:
                points = self.vertices
            self._inner = points[mesh_arrays.cube_extremes(points)] if len(points) else points
        return self._inner

    @property
    def inner_volume(self) -> float:
        """A lower bound of the volume of the convex hull (:func:`.mesh_arrays.inner_volume`),
        found without building it [m^3]."""
        if self._inner_volume is None:
            self._inner_volume = mesh_arrays.inner_volume(self.vertices)
        return self._inner_volume

    @property
    def inner_tetrahedron_volume(self) -> float:
        """A lower bound of the volume of the convex hull cheaper than :attr:`inner_volume`
        (:func:`.mesh_arrays.inner_tetrahedron_volume`) [m^3]."""
        if self._inner_tetrahedron is None:
            self._inner_tetrahedron = mesh_arrays.inner_tetrahedron_volume(self.vertices)
        return self._inner_tetrahedron

    @property
    def convex_hull(self):
        if self._hull is None:
            hull = mesh_arrays.convex_hull(self.vertices)
            if hull is None:  # one trimesh repairs
                from trimesh.convex import convex_hull

                self._hull = convex_hull(self.vertices)
            else:
                points, faces, properties = hull
                self._hull = MeshFacts(points, faces, {}, watertight=True, properties=properties)
        return self._hull


def mesh_facts(robot, uri: str, scale=(1.0, 1.0, 1.0),
               limits: MeshLimits | None = None) -> MeshFacts:
    """The :class:`MeshFacts` of the mesh at ``uri`` scaled by ``scale``; raises MeshProblem
    as :func:`load_mesh` does. Each file is read once per run and measured once per scale: STL,
    COLLADA and plain OBJ files without trimesh, other formats through it."""
    limits = limits or robot.mesh_limits
    key = (mesh_facts, uri, tuple(scale), limits_key(limits))
    found = robot.memo(key, lambda: _facts_outcome(robot, uri, scale, limits))
    if isinstance(found, MeshProblem):
        raise found
    return found


def _facts_outcome(robot, uri: str, scale, limits: MeshLimits):
    try:
        path = resolve(robot, uri)
        scale = finite_scale(uri, scale)
    except MeshProblem as problem:
        return problem
    stamp = stamp_of(path)

    def compute():
        arrays = _arrays_once(path, uri, limits, stamp)
        if isinstance(arrays, MeshProblem):
            raise arrays
        bounds = arrays.bounds(scale)
        if bounds is not None:
            facts = MeshFacts.unmerged(arrays.triangles, bounds, arrays.metadata, arrays.nbytes,
                                       lambda: _merged_scaled(arrays, scale),
                                       lambda: arrays.corners_read(scale),
                                       arrays.corner_slack(scale))
        else:  # merged: bounds decided above have every coordinate within the merge's range
            import numpy as np

            arrays.refuse_too_far(uri)
            vertices, faces, watertight = _merged_scaled(arrays, scale)
            if scale != (1.0, 1.0, 1.0) and not np.isfinite(vertices).all():
                raise beyond_range(uri, scale)
            facts = MeshFacts(vertices, faces, arrays.metadata, watertight=watertight)
        return facts, facts.nbytes  # unscaled, the arrays' bytes: counted twice, an upper bound

    return once((str(path), stamp, limits_key(limits), "facts", scale), uri, compute)


def _merged_scaled(arrays: _Arrays, scale):
    """(vertices, faces, watertight) of ``arrays`` merged, then scaled (a scale keeps
    watertightness: a mirror turns every face)."""
    vertices, faces, watertight = arrays.merged()
    if scale != (1.0, 1.0, 1.0):
        import numpy as np

        with np.errstate(all="ignore"):  # overflow is reported by the caller
            vertices, faces = mesh_arrays.scaled(vertices, faces, scale)
    return vertices, faces, watertight
