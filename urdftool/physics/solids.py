"""A link's ``<collision>``/``<visual>`` geometry as solids: mass properties and bounds.

The inertia rules and ``urdftool inertia`` read geometry through here, and meshes through
:mod:`urdftool.description.meshes` (their measures, once per run: ``mesh_facts``), so both see
the same shapes, scales and origins. Pure Python (:mod:`urdftool.physics.mat3` tuples): numpy is
imported only when a mesh is measured, trimesh only for formats other than STL, COLLADA and
plain OBJ, scipy (qhull) only for the convex hull of an open mesh.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

from urdftool.physics import mass as mp
from urdftool.physics import mat3
from urdftool.description.values import finite, number_tuple, origin, origin_pose
from urdftool.description.xml import child_list, first_child


HULL_USED = "its convex hull was used"  # the problem of an open mesh that still counts


@dataclass(slots=True)
class Shape:
    """One geometry: ``kind`` in :data:`~urdftool.description.urdf.SHAPES`, ``params`` (size /
    radius, length / filename, scale), placed by ``xyz`` and ``rotation`` in the link frame;
    ``element`` is the geometry child."""

    kind: str
    params: dict
    xyz: mat3.Vector
    rotation: mat3.Matrix
    element: object
    placed: tuple | None = field(default=None, repr=False)  # see _measured, _shape_corners
    axes: tuple | None = field(default=None, repr=False)  # their coordinates, if unturned
    box: tuple | None = field(default=None, repr=False)  # their min and max corner
    finite: bool = field(default=False, repr=False)  # True: every coordinate of them finite


class LinkSolid:
    """What a link's geometry implies: ``source`` is collision, visual or none.

    parts: unit-density solids in the link frame; problems: (element, message) for geometry
    that could not count (missing mesh, open mesh replaced by its hull...). An open mesh's
    convex hull (and with it scipy) is built only when ``parts``, ``problems`` or
    ``volume_floor`` is first read: ``sound`` answers without it. A primitive is placed in the
    link frame only when ``parts`` is first read: ``counts``, :func:`volume` and
    ``volume_floor`` need only its volume, which placing keeps.
    """

    __slots__ = ("source", "bounds", "_entries", "_built", "_parts", "_extent", "_unread")

    def __init__(self, source: str):
        self.source = source
        self._unread: list = []  # (element, message): geometry that made no shape
        self.bounds: tuple[mat3.Vector, mat3.Vector] | None = None  # min, max corner, link frame
        self._extent: float | None = None
        self._entries: list[_Entry] = []  # one per shape counted, in order
        self._built: tuple[list, list] | None = None  # entries that count, problems
        self._parts: list | None = None

    @property
    def parts(self) -> list:
        if self._parts is None:
            self._parts = [_placed_solid(entry) for entry in self._build()[0]]
        return self._parts

    @property
    def problems(self) -> list:
        return self._build()[1]

    @property
    def assumed(self) -> list[str]:
        """What its meshes were read assuming (:func:`~urdftool.description.meshes.
        read_as_assumed`), each after the mesh's name: not problems (the mesh counts as read),
        said by the commands that compute with them."""
        return [said for entry in self._entries for said in entry.assumed]

    @property
    def extent(self) -> float:
        """The largest side of ``bounds`` [m] (which it has), worked out once: the inertia rules
        ask up to four times a link."""
        if self._extent is None:
            (lx, ly, lz), (hx, hy, hz) = self.bounds
            self._extent = max(hx - lx, hy - ly, hz - lz)
        return self._extent

    @property
    def counts(self) -> bool:
        """Whether ``parts`` is not empty (without placing them)."""
        return bool(self._build()[0])

    @property
    def sound(self) -> bool:
        """No problems: every shape counted as it is (an open mesh always has one, its hull)."""
        for entry in self._entries:
            if entry.open_mesh is not None:
                return False
        return not self.problems

    def volume_floor(self, enough=None) -> float:
        """A lower bound of :func:`volume` [m^3] (exact without open meshes; an open mesh counts
        with its convex hull, shaved for rounding) that places no primitive. With ``enough``
        (a test of a floor), a lower one is returned when it passes: open meshes counted with
        a bound of their hull's volume found without building it (and without qhull), each
        below the hull's, so that their sum is too (``enough`` must hold of every larger floor
        when it holds of a smaller one): first one tetrahedron of each hull's points
        (:func:`_tetrahedron_floor`), then the hull of a few of them (:func:`_inner_floor`)."""
        floor = sum(_unit_volume(entry) for entry in self._entries
                    if entry.solid is not None or entry.local is not None)
        opened = [entry.open_mesh for entry in self._entries if entry.open_mesh is not None]
        if enough is not None and opened:
            for bound in (_tetrahedron_floor, _inner_floor):
                lower = floor
                for mesh in opened:
                    lower += _quietly(bound, mesh)
                if enough(lower):
                    return lower
        for mesh in opened:
            floor += _quietly(_hull_floor, mesh)
        return floor

    def _build(self) -> tuple[list, list]:
        if self._built is None:
            for entry in self._entries:
                if entry.open_mesh is not None:
                    _quietly(_hull_entry, entry)
            self._built = ([entry for entry in self._entries
                            if entry.solid is not None or entry.local is not None],
                           [p for entry in self._entries for p in entry.problems] + self._unread)
        return self._built


@dataclass(slots=True)
class _Entry:
    """One shape of a :class:`LinkSolid`: its solid placed in the link frame (None when it does
    not count, or until a primitive's ``local`` solid is placed), its problems, and the open
    mesh whose hull is to stand for it (until built)."""

    shape: Shape
    solid: object = None
    problems: list = field(default_factory=list)
    open_mesh: object = None
    local: object = None  # a primitive's unit-density solid in its own frame, until placed
    assumed: list = field(default_factory=list)  # what its mesh was read assuming


def _placed_solid(entry: _Entry):
    """An entry's solid in the link frame, a primitive's placed the first time it is asked."""
    if entry.local is not None:
        entry.solid = mp.transformed(entry.local, entry.shape.xyz, entry.shape.rotation)
        entry.local = None
    return entry.solid


def _unit_volume(entry: _Entry) -> float:
    """The volume of an entry that counts [m^3]: its mass at unit density, placed or not
    (:func:`~urdftool.physics.mass.transformed` keeps the mass)."""
    return (entry.solid if entry.solid is not None else entry.local).mass


def _positive(values) -> bool:
    """Every value finite and above 0 (None: not)."""
    if values is None:
        return False
    for v in values:
        if not (v > 0 and math.isfinite(v)):
            return False
    return True


def shape_of(holder, groups: dict | None = None) -> Shape | None:
    """The shape of a ``<visual>``/``<collision>``, or None when malformed (rules say why);
    ``groups``: the holder's children by tag (:meth:`~urdftool.description.robot.Robot.
    grouped`) when read already."""
    read = _shape_read(holder, groups)
    if read is None:
        return None
    kind, params, element, origin_element = read
    xyz, rpy = origin_pose(holder, origin_element)  # a malformed part counts as 0
    return Shape(kind, params, xyz, mat3.rpy_matrix(rpy), element)


def _shape_read(holder, groups: dict | None):
    """(kind, params, shape element, first ``<origin>`` or None) of a ``<visual>``/
    ``<collision>`` whose shape is well formed (what :func:`shape_of` places), else None."""
    if groups is None:
        geometry, origin_element = first_child(holder, "geometry"), first_child(holder, "origin")
    else:
        geometries, origins = groups.get("geometry"), groups.get("origin")
        geometry = geometries[0] if geometries else None
        origin_element = origins[0] if origins else None
    if geometry is None:
        return None
    for element in child_list(geometry):
        kind = element.tag
        if isinstance(kind, str):
            break
    else:
        return None
    # the parsed tuples as they are (number_tuple: no list copy), judged before the placement
    if kind == "box":
        size = number_tuple(element.get("size"), 3)[0]
        if not _positive(size):
            return None
        params = {"size": size}
    elif kind == "cylinder":
        radius = number_tuple(element.get("radius"), 1)[0]
        length = number_tuple(element.get("length"), 1)[0]
        if not (_positive(radius) and _positive(length)):
            return None
        params = {"radius": radius[0], "length": length[0]}
    elif kind == "sphere":
        radius = number_tuple(element.get("radius"), 1)[0]
        if not _positive(radius):
            return None
        params = {"radius": radius[0]}
    elif kind == "mesh":
        scale = number_tuple(element.get("scale", "1 1 1"), 3)[0]
        filename = element.get("filename")
        if not (filename and scale and finite(scale)):
            return None
        params = {"filename": filename, "scale": scale}
    else:
        return None
    return kind, params, element, origin_element


def shapes(robot, link, tag: str) -> list[Shape]:
    """The well-formed shapes of a link's ``tag`` (visual or collision) elements, in order;
    read once per robot, link and tag (the solids, bounds and inertia rules all ask)."""
    return _link_shapes(robot, link)[tag][0]


def _link_shapes(robot, link) -> dict[str, tuple[list[Shape], int]]:
    """tag -> (well-formed shapes, number of elements) for a link's visual and collision."""
    def build():  # from the link's children grouped by tag (each in document order), which
        # the rules group anyway, instead of a second walk of lxml's
        grouped = robot.grouped(link)
        found = {}
        for tag in ("visual", "collision"):
            holders = grouped.get(tag, ())
            kept = []
            for holder in holders:  # (its children grouped once: the geometry rules read them)
                shape = shape_of(holder, robot.grouped(holder))
                if shape is not None:
                    kept.append(shape)
            found[tag] = (kept, len(holders))
        return found

    return robot.memo_for(_link_shapes, link, build)


def _quietly(compute, *args):
    """``compute(*args)`` with trimesh's and numpy's warnings on degenerate or absurdly scaled
    meshes silenced: the implausible-size rule and the problems say what is wrong."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return compute(*args)


@functools.cache
def mesh_reader():
    """(MeshProblem, mesh_facts, read_as_assumed), imported when a mesh is first measured (a robot without
    meshes does not import them), then kept: an import statement in each call (a mesh's box,
    its entry, its piece) ran importlib's Python for each of the corpus's 5,000 asks."""
    from urdftool.description.meshes import MeshProblem, mesh_facts, read_as_assumed

    return MeshProblem, mesh_facts, read_as_assumed


def _mesh_entry(robot, shape: Shape) -> _Entry:
    """A mesh shape's entry: its solid when closed, else the open mesh (its hull is built only
    when asked), or a problem when it does not resolve or load."""
    MeshProblem, mesh_facts, read_as_assumed = mesh_reader()
    entry = _Entry(shape)
    try:
        mesh = mesh_facts(robot, shape.params["filename"], shape.params["scale"])
    except MeshProblem as problem:
        entry.problems.append((shape.element, str(problem)))
        return entry
    entry.assumed = [f"mesh '{shape.params['filename']}'{said}"
                     for said in read_as_assumed(mesh.metadata)]
    if mesh.is_watertight:
        _set_solid(entry, mesh)
    else:
        entry.open_mesh = mesh
    return entry


def _hull_entry(entry: _Entry) -> None:
    """Build the hull standing for an entry's open mesh, and its solid or problem."""
    mesh, entry.open_mesh = entry.open_mesh, None
    filename = entry.shape.params["filename"]
    try:
        body = mesh.convex_hull
    except RuntimeError:  # qhull: the vertices are one point, a line or (unjoggled) a plane
        entry.problems.append((entry.shape.element, f"mesh '{filename}' is flat or a single "
                                                    "point: it encloses no volume"))
        return
    entry.problems.append((entry.shape.element, f"mesh '{filename}' is not closed "
                                                f"(watertight); {HULL_USED}"))
    _set_solid(entry, body)


def _set_solid(entry: _Entry, body) -> None:
    from urdftool.physics.inertia import mesh_solid

    solid = mesh_solid(body).body()
    if not solid.mass > 0:  # also NaN from a zero-volume mesh
        entry.problems.append((entry.shape.element,
                               f"mesh '{entry.shape.params['filename']}' encloses no volume"))
        return
    entry.solid = mp.transformed(solid, entry.shape.xyz, entry.shape.rotation)


def _hull_floor(mesh) -> float:
    """The volume of the convex hull of a mesh's vertices [m^3] (qhull, through the mesh's
    ``convex_hull``: built once, and the same hull stands for the mesh in ``parts``), shaved
    by 1e-6 for rounding; 0 when the vertices are flat or a single point."""
    try:
        hull = mesh.convex_hull
    except RuntimeError:  # qhull: the vertices are one point, a line or (unjoggled) a plane
        return 0.0
    properties = getattr(hull, "mass_properties", None)
    volume = float(properties["volume"]) if isinstance(properties, dict) else float(hull.volume)
    return volume * (1 - 1e-6) if math.isfinite(volume) and volume > 0 else 0.0


def _inner_floor(mesh) -> float:
    """Below :func:`_hull_floor` of the same mesh [m^3]: a lower bound of its hull's volume
    (``inner_volume``, no hull built), shaved by 1e-6 as that one is."""
    volume = getattr(mesh, "inner_volume", 0.0)
    return volume * (1 - 1e-6) if math.isfinite(volume) and volume > 0 else 0.0


def _tetrahedron_floor(mesh) -> float:
    """:func:`_inner_floor` of one tetrahedron of the hull's points (``inner_tetrahedron_
    volume``): a twentieth of its Python, and on the corpus enough for 111 of 115 open
    meshes."""
    volume = getattr(mesh, "inner_tetrahedron_volume", 0.0)
    return volume * (1 - 1e-6) if math.isfinite(volume) and volume > 0 else 0.0


def _local(shape: Shape):
    """The unit-density solid of a primitive in its own frame."""
    return _of_primitive(shape, mp.box, mp.cylinder, mp.sphere)


def unit_volume(shape: Shape) -> float:
    """The volume of a primitive [m^3]: its :func:`_local` solid's mass, without the solid."""
    return _of_primitive(shape, mp.box_volume, mp.cylinder_volume, mp.sphere_volume)


def _of_primitive(shape: Shape, box, cylinder, sphere):
    """``box(size)``, ``cylinder(radius, length)`` or ``sphere(radius)`` of a primitive."""
    p = shape.params
    if shape.kind == "box":
        return box(p["size"])
    if shape.kind == "cylinder":
        return cylinder(p["radius"], p["length"])
    return sphere(p["radius"])


def _local_box(shape: Shape):
    """A primitive's box in its own frame: (min corner, max corner)."""
    p = shape.params
    if shape.kind == "box":
        x, y, z = p["size"]
        x, y, z = x / 2, y / 2, z / 2
        return (-x, -y, -z), (x, y, z)
    if shape.kind == "cylinder":
        r, h = p["radius"], p["length"] / 2
        return (-r, -r, -h), (r, r, h)
    r = p["radius"]
    return (-r,) * 3, (r,) * 3


def _corners(bounds) -> list[mat3.Vector]:
    return [(bounds[i][0], bounds[j][1], bounds[k][2])
            for i in (0, 1) for j in (0, 1) for k in (0, 1)]


def link_solid(robot, link, load_meshes: bool = True, tag: str | None = None) -> LinkSolid:
    """The solids of a link's collision geometry, or its visual geometry when it has none;
    ``tag`` ("collision" or "visual") takes that geometry only."""
    found = _link_shapes(robot, link)
    collision, written = found["collision"] if tag in (None, "collision") else ([], 0)
    # a link whose collision elements are all unreadable is judged by none of its geometry,
    # not by its visual: that would be another body
    chosen, source = (collision, "collision") if collision or written or tag == "collision" \
        else (found["visual"][0], "visual")
    written = found[source][1]
    if not written:
        return LinkSolid("none")
    result = LinkSolid(source)
    if len(chosen) < written:  # an element without a shape that can be measured
        result._unread.append((link, f"{written - len(chosen)} of the link's {written} <{source}> "
                                     "elements have no shape that can be measured"))
    boxes = []
    for shape in chosen:
        if shape.kind == "mesh":
            if not load_meshes:
                continue
            result._entries.append(_quietly(_mesh_entry, robot, shape))
        else:
            result._entries.append(_Entry(shape, local=_local(shape)))
        if _measured(robot, shape):
            boxes.append(shape.box)
    result.bounds = _joined(boxes)
    return result


class RigidBounds:
    """The bounding box [m] of everything rigidly one with a link, in the link frame.

    links: the link and those fixed to it (through fixed joints, either way), in the order
    reached (listed when first read: a message asks, a rule deciding does not); complete:
    False when some of their geometry could not be measured (a mesh that does not resolve or
    load), so the box may be too small; bounds: None without geometry.
    """

    __slots__ = ("_links", "complete", "bounds")

    def __init__(self, links, complete: bool = True,
                 bounds: tuple[mat3.Vector, mat3.Vector] | None = None):
        self._links = links  # a list, or what lists them
        self.complete, self.bounds = complete, bounds

    @property
    def links(self) -> list[str]:
        if callable(self._links):
            self._links = self._links()
        return self._links

    def __eq__(self, other) -> bool:
        return isinstance(other, RigidBounds) and (self.links, self.complete, self.bounds) == \
            (other.links, other.complete, other.bounds)

    def __repr__(self) -> str:
        return f"RigidBounds({self.links!r}, {self.complete!r}, {self.bounds!r})"


# A rigid body of more links than this is measured once in one frame (its root's, see
# _bodies) and seen from each member's frame, not gathered again from each: a robot's cost
# stays linear in its links however many are fixed together. Up to it, each member's box is
# gathered from its own frame (the numbers of the member's own walk, to the bit).
GROUP_DIRECT = 16
# A large body's points (corners, vertices) times its members up to this are all kept: each
# member asks of them in a few directions, which costs less than reducing them to the
# vertices of their hull (qhull, and scipy's import: 0.2 s).
BODY_POINTS = 2 ** 22


def body_points(points, members: int):
    """``points`` of a body of ``members`` links, cut to the vertices of their hull (the same
    extremes) when asking every one of them from every member would cost more."""
    from urdftool.description.mesh_arrays import extreme_points

    return extreme_points(points, all_below=BODY_POINTS // max(members, 1))


def rigid_bounds(robot, link) -> RigidBounds:
    """The box of a link's visual and collision geometry and of the links fixed to it, once
    per robot and link (two inertia rules ask of every link with mass)."""
    return robot.memo_for(rigid_bounds, link, lambda: _rigid_bounds(robot, link))


def held_box(robot, link) -> tuple[mat3.Vector, mat3.Vector] | None:
    """A box [m] in the link frame that :func:`rigid_bounds`' box holds to the bit (its min
    corner's coordinates no larger, its max corner's no smaller), found without gathering
    the link's rigid body: the link's own box, when its body's box is walked from it (a body
    of at most :data:`GROUP_DIRECT` links, or the link alone: the walk starts with the own
    box, and the least and the largest of more coordinates are no larger and no smaller;
    one not a number comes later and is never taken). None without an own box, and for a
    member of a larger body (measured in its root's frame and turned: its box need not hold
    the own box to the bit). A question that the own box settles (a centre of mass inside
    it, a bound that its size already meets) the body's box settles the same way."""
    name = link.get("name")
    if name in _fixed_neighbours(robot) and len(_bodies(robot)[name][1]) > GROUP_DIRECT:
        return None
    return _placed_corners(robot, robot.links.get(name, link))[1]


def _rigid_bounds(robot, link) -> RigidBounds:
    name = link.get("name")
    if name not in _fixed_neighbours(robot):  # nothing fixed to it (most links): its own box
        members, box, complete = _placed_corners(robot, robot.links.get(name, link))
        if box is not None:
            return RigidBounds([name], complete, box)
    else:
        root, frames = _bodies(robot)[name]
        if len(frames) > GROUP_DIRECT:
            found = _body_bounds(robot, name, root, frames)
            if found is not None:
                return found
    frames = _rigid_frames(robot, name)
    result, corners = RigidBounds(list(frames)), []
    for name, (rotation, xyz) in frames.items():
        # a link without a name is in no joint: only the link itself may not be in links
        members, box, complete = _placed_corners(robot, robot.links.get(name, link))
        if rotation is mat3.IDENTITY and box is not None:  # the link itself: its own box
            if len(frames) == 1:  # and nothing else: the box is its own min and max
                result.complete, result.bounds = complete, box
                return result
            corners.extend(box)  # (as min and max of the corners moved by 0 + I c would be)
        else:
            corners.extend(_placed(xyz, rotation, [c for shape in members
                                                   for c in _shape_corners(shape)]))
        result.complete = result.complete and complete
    result.bounds = _box(corners)
    return result


def _body_bounds(robot, name: str, root: str, frames: dict) -> RigidBounds | None:
    """The rigid bounds of member ``name`` of a body of more than :data:`GROUP_DIRECT` links:
    the corners of every member's shapes placed in the root's frame once (numpy; reduced to
    their convex hull's vertices, which have the same extremes in every direction), then
    turned into ``name``'s frame. None when some corner is not finite (then the member's own
    walk decides, as for a small body)."""
    import numpy as np

    found = robot.memo_for(_body_bounds, root, lambda: _body_corners(robot, frames))
    if found is None:
        return None
    points, complete = found
    if points is None:
        return RigidBounds(lambda: rigid_group(robot, name), complete, None)
    rotation, xyz = frames[name]  # p_root = xyz + rotation p_member
    local = (points - np.asarray(xyz)) @ np.asarray(rotation)  # rows: rotation^T (p - xyz)
    low, high = local.min(axis=0) + 0.0, local.max(axis=0) + 0.0  # a zero of either sign: +0
    return RigidBounds(lambda: rigid_group(robot, name), complete,
                       (tuple(low.tolist()), tuple(high.tolist())))


def _body_corners(robot, frames: dict):
    """(the hull vertices of every member's shape corners placed in the root's frame, or None
    without any; whether every shape was measured), or None when a corner is not finite."""
    import numpy as np

    placed, complete = [], True
    for member, (rotation, xyz) in frames.items():
        shapes, _, measured = _placed_corners(robot, robot.links[member])
        complete = complete and measured
        if shapes:
            corners = np.array([c for shape in shapes for c in _shape_corners(shape)])
            with np.errstate(all="ignore"):
                placed.append(corners @ np.asarray(rotation).T + np.asarray(xyz))
    if not placed:
        return None, complete
    points = np.vstack(placed)
    if not np.isfinite(points).all():
        return None
    return body_points(points, len(frames)), complete


def _box(corners) -> tuple[mat3.Vector, mat3.Vector] | None:
    """(min corner, max corner) of points, None without any."""
    if not corners:
        return None
    xs, ys, zs = zip(*corners)
    return (min(xs), min(ys), min(zs)), (max(xs), max(ys), max(zs))


def _joined(boxes) -> tuple[mat3.Vector, mat3.Vector] | None:
    """The box of boxes: what :func:`_box` gives for all their points (the same numbers: the
    least of the least, the first of equals first)."""
    if not boxes:
        return None
    if len(boxes) == 1:
        return boxes[0]
    if len(boxes) == 2:  # a visual and a collision (most links): min and max written out,
        ((ax, ay, az), (bx, by, bz)), ((cx, cy, cz), (dx, dy, dz)) = boxes  # as they choose
        return ((cx if cx < ax else ax, cy if cy < ay else ay, cz if cz < az else az),
                (dx if dx > bx else bx, dy if dy > by else by, dz if dz > bz else bz))
    lows, highs = zip(*boxes)
    (lx, ly, lz), (hx, hy, hz) = zip(*lows), zip(*highs)
    return (min(lx), min(ly), min(lz)), (max(hx), max(hy), max(hz))


def link_bounds(robot, link) -> tuple[tuple | None, bool]:
    """(the box of the link's own visual and collision geometry in its frame, or None; whether
    every shape of it was measured), as :func:`rigid_bounds` reads it of each member."""
    return _placed_corners(robot, link)[1:]


def _placed_corners(robot, member) -> tuple[list[Shape], tuple | None, bool]:
    """(a link's visual and collision shapes whose box corners are placed in the link frame
    (:func:`_shape_corners`); their box as (min corner, max corner) when every coordinate is finite,
    a zero of either sign as +0; whether every shape was measured), once per robot and link:
    every link fixed to it asks."""
    def build():
        found = _link_shapes(robot, member)
        members, finite, elements = [], True, 0
        for tag in ("visual", "collision"):
            kept, count = found[tag]
            elements += count
            for shape in kept:
                if _measured(robot, shape):
                    members.append(shape)
                    finite = finite and shape.finite
        box = None
        if members and finite:
            low, high = _joined([shape.box for shape in members])
            box = ((low[0] + 0.0, low[1] + 0.0, low[2] + 0.0),
                   (high[0] + 0.0, high[1] + 0.0, high[2] + 0.0))
        return members, box, len(members) == elements

    return robot.memo_for(_placed_corners, member, build)


def _measured(robot, shape: Shape) -> bool:
    """Place the corners of a shape's box in the link frame, once per shape (the solids and
    the rigid bounds both ask): their box (``shape.box``) and whether all are finite
    (``shape.finite``); False for a mesh that does not resolve or load. Unturned corners
    (rpy 0 0 0, see :func:`_kept_by_no_turn`) are kept as their coordinates on each axis, and
    made points only when a link fixed to this one asks (:func:`_shape_corners`)."""
    if shape.placed is None and shape.axes is None:
        local = _local_bounds(robot, shape)
        if local is None:
            shape.placed = ()
        elif shape.rotation is mat3.NO_TURN and _kept_by_no_turn(local):
            (lx, ly, lz), (hx, hy, hz) = local
            tx, ty, tz = shape.xyz
            xs, ys, zs = shape.axes = (tx + lx, tx + hx), (ty + ly, ty + hy), (tz + lz, tz + hz)
            (x0, x1), (y0, y1), (z0, z1) = xs, ys, zs  # min and max as the builtins choose
            shape.box = ((x1 if x1 < x0 else x0, y1 if y1 < y0 else y0, z1 if z1 < z0 else z0),
                         (x1 if x1 > x0 else x0, y1 if y1 > y0 else y0, z1 if z1 > z0 else z0))
            # sum(map(sum, corners)) below, the same additions in the same order (corners
            # x0 y0 z0, x0 y0 z1, x0 y1 z0, ...), written out
            total = 0 + (0 + x0 + y0 + z0)
            total += 0 + x0 + y0 + z1
            total += 0 + x0 + y1 + z0
            total += 0 + x0 + y1 + z1
            total += 0 + x1 + y0 + z0
            total += 0 + x1 + y0 + z1
            total += 0 + x1 + y1 + z0
            total += 0 + x1 + y1 + z1
            shape.finite = math.isfinite(total)  # False on overflow too
        else:
            shape.placed = _placed(shape.xyz, shape.rotation, _corners(local))
            shape.box = _box(shape.placed)
            shape.finite = math.isfinite(sum(map(sum, shape.placed)))  # False on overflow too
    return shape.axes is not None or bool(shape.placed)


def _shape_corners(shape: Shape) -> tuple:
    """The corners of a measured shape's box in the link frame, in :func:`_corners`' order."""
    if shape.placed is None:
        xs, ys, zs = shape.axes
        shape.placed = tuple((x, y, z) for x in xs for y in ys for z in zs)
    return shape.placed


def _kept_by_no_turn(bounds) -> bool:
    """Whether :data:`mat3.NO_TURN` (entries 1.0 and zeros of either sign) moves the corners
    of ``bounds`` to themselves to the bit: every coordinate finite (0 * inf is nan) and none
    zero (-0.0 + 0.0 is 0.0); :func:`_placed` then adds only zeros to each."""
    (lx, ly, lz), (hx, hy, hz) = bounds
    return math.isfinite(lx + ly + lz + hx + hy + hz) and \
        0.0 not in (lx, ly, lz, hx, hy, hz)


def _placed(xyz, rotation, points) -> tuple:
    """``mat3.add(xyz, mat3.apply(rotation, p))`` for each point, the same sums in one loop."""
    (a, b, c), (d, e, f), (g, h, i) = rotation
    tx, ty, tz = xyz
    return tuple((tx + (a * x + b * y + c * z), ty + (d * x + e * y + f * z),
                  tz + (g * x + h * y + i * z)) for x, y, z in points)


def _local_bounds(robot, shape: Shape):
    """A shape's box in its own frame, or None for a mesh that does not resolve or load."""
    if shape.kind != "mesh":
        return _local_box(shape)
    MeshProblem, mesh_facts, _ = mesh_reader()
    try:
        mesh = mesh_facts(robot, shape.params["filename"], shape.params["scale"])
    except MeshProblem:
        return None
    return tuple(mat3.vector(corner) for corner in mesh.bounds)


# A robot of this many links or more measures its plain links' boxes all at once (numpy):
# below, numpy's import (50 ms) costs more than the per-link Python it saves.
BULK_LINKS = 256


class PlainLinks:
    """The links of a robot that are a rigid body alone (no fixed joint) and whose every
    ``<visual>`` and ``<collision>`` made a box, cylinder or sphere, measured all at once
    (numpy, the per-link path's operations in its order, so the same numbers to the bit):
    ``rows`` link name -> row of ``low`` and ``high`` (n, 3), the box of the link's shapes as
    :func:`rigid_bounds` gives it (a zero of either sign as +0; only links whose box is all
    finite have a row); ``extents``: the largest side of the box of the geometry
    :func:`link_solid` takes (collision, else visual), its ``extent``; for :meth:`inside`, the
    shapes as :class:`~urdftool.physics.support.Piece` places them (``shape_rows`` the row of
    each shape's link); ``solids``: link name -> its :class:`PlainSolid` (made when first
    asked, see :func:`plain_solid`) from ``units`` (see :func:`_plain_units`)."""

    __slots__ = ("rows", "low", "high", "shape_rows", "kinds", "centres", "rotations",
                 "sizes", "extents", "units", "solids")

    def inside(self, names, points):
        """For link names (each with a row) and points [m] (k, 3) in their frames: whether
        each point is certainly inside one of its link's primitives (what
        :meth:`~urdftool.physics.support.Piece.holds` answers True for; a point on a cylinder's
        round side within rounding is left undecided: False)."""
        import numpy as np

        asked = np.fromiter((self.rows[name] for name in names), dtype=np.intp,
                            count=len(names))
        found = np.zeros(len(asked), dtype=bool)
        # each point against each shape of its link (the rows' shapes are consecutive)
        starts = np.searchsorted(self.shape_rows, asked, "left")
        counts = np.searchsorted(self.shape_rows, asked, "right") - starts
        shape_of = np.repeat(np.arange(len(asked)), counts)  # the point of each pair
        if not len(shape_of):
            return found
        chosen = np.repeat(starts - (np.cumsum(counts) - counts), counts) + \
            np.arange(len(shape_of))  # the shape of each pair
        p = np.asarray(points, dtype=float).reshape(-1, 3)[shape_of]
        kinds, centres, r = self.kinds[chosen], self.centres[chosen], self.rotations[chosen]
        sizes = self.sizes[chosen]
        with np.errstate(all="ignore"):
            o0, o1, o2 = p[:, 0] - centres[:, 0], p[:, 1] - centres[:, 1], p[:, 2] - centres[:, 2]
            # r[0][i] * o0 + r[1][i] * o1 + r[2][i] * o2, in Piece.holds' order
            local = [r[:, 0, i] * o0 + r[:, 1, i] * o1 + r[:, 2, i] * o2 for i in range(3)]
            box = (np.abs(local[0]) <= sizes[:, 0]) & (np.abs(local[1]) <= sizes[:, 1]) & \
                (np.abs(local[2]) <= sizes[:, 2])
            radius, half = sizes[:, 0], sizes[:, 1]
            # math.hypot(x, y) <= radius, certain: its square with room for rounding, in a
            # range where nothing underflows to matter
            across = local[0] * local[0] + local[1] * local[1]
            cylinder = (np.abs(local[2]) <= half) & (across <= radius * radius * (1 - 1e-9)) & \
                (radius >= 1e-100) & (np.abs(local[0]) <= 1e100) & (np.abs(local[1]) <= 1e100)
            sphere = np.sqrt(o0 * o0 + o1 * o1 + o2 * o2) <= sizes[:, 0]
        holds = np.where(kinds == 0, box, np.where(kinds == 1, cylinder, sphere))
        np.logical_or.at(found, shape_of[holds], True)
        return found


def plain_links(robot) -> PlainLinks | None:
    """:class:`PlainLinks` of a robot of :data:`BULK_LINKS` links or more (else None), once
    per robot."""
    return robot.memo(plain_links, lambda: _plain_links(robot) if len(robot.links) >= BULK_LINKS
                      else None)


def _plain_links(robot) -> PlainLinks:
    import numpy as np
    from itertools import chain

    neighbours = _fixed_neighbours(robot)
    names, shape_rows, xyzs, turns, chosen = [], [], [], [], []
    dims, collisions = [], []  # per shape: see _dimensions; whether a <collision>'s
    index, distinct = {}, []  # the distinct rotations (most shapes': NO_TURN), by identity
    for name, link in robot.links.items():
        if name in neighbours:
            continue
        read = _plain_read(robot, link)
        if read is None:
            continue  # incomplete, a mesh, or nothing to measure: the per-link path says so
        shapes, visuals = read
        row, collision = len(names), len(shapes) - visuals
        names.append(name)
        chosen += [not collision] * visuals + [True] * collision
        collisions += [False] * visuals + [True] * collision
        for dimensions, xyz, rotation in shapes:
            shape_rows.append(row)
            dims.append(dimensions)
            xyzs.append(xyz)
            turn = index.get(id(rotation))
            if turn is None:  # (distinct keeps it alive: its id stays its own)
                turn = index[id(rotation)] = len(distinct)
                distinct.append(rotation)
            turns.append(turn)
    table = PlainLinks()
    k = len(shape_rows)
    shape_rows = np.array(shape_rows, dtype=np.intp)
    kinds_dims = np.fromiter(chain.from_iterable(dims), dtype=float, count=4 * k).reshape(-1, 4)
    kinds, dims = kinds_dims[:, 0].astype(np.int8), kinds_dims[:, 1:]
    high = _local_highs(kinds, dims)
    xyz = np.fromiter(chain.from_iterable(xyzs), dtype=float, count=3 * k).reshape(-1, 3)
    turns = np.array(turns, dtype=np.intp)
    rotation = np.array(distinct, dtype=float).reshape(-1, 3, 3)[turns]
    unturned = np.array([r is mat3.NO_TURN for r in distinct], dtype=bool).reshape(-1)[turns]
    low, high_box, finite = _shape_boxes(-high, high, xyz, rotation, unturned)
    shape_low, shape_high = low, high_box  # (each shape's, before the links' are taken)
    count = len(names)
    starts = np.searchsorted(shape_rows, np.arange(count)) if count else shape_rows
    extents = np.zeros(count)
    if count:
        # link_solid's extent: of its chosen shapes' box (finite: the differences are the
        # same whatever the sign of a zero)
        picked = np.array(chosen, dtype=bool)[:, None]
        with np.errstate(all="ignore"):  # (rows not all finite are dropped below)
            sides = np.maximum.reduceat(np.where(picked, high_box, -np.inf), starts) - \
                np.minimum.reduceat(np.where(picked, low, np.inf), starts)
        extents = np.maximum(np.maximum(sides[:, 0], sides[:, 1]), sides[:, 2])
        low = np.minimum.reduceat(low, starts) + 0.0  # a zero of either sign: +0
        high_box = np.maximum.reduceat(high_box, starts) + 0.0
        finite = np.logical_and.reduceat(finite, starts)
    kept = np.flatnonzero(finite) if count else np.zeros(0, dtype=np.intp)
    table.rows = {names[i]: j for j, i in enumerate(kept.tolist())}
    table.low, table.high, table.extents = low[kept], high_box[kept], extents[kept]
    renumbered = np.full(count, -1, dtype=np.intp)
    renumbered[kept] = np.arange(len(kept))
    shapes_kept = renumbered[shape_rows] >= 0 if count else np.zeros(0, dtype=bool)
    table.shape_rows = renumbered[shape_rows][shapes_kept] if count else shape_rows
    table.kinds = kinds[shapes_kept]
    # as support._piece places a shape of a link alone: centre 0 + I xyz, rotation I R
    one = np.asarray(mat3.IDENTITY)
    x, y, z = xyz[:, 0], xyz[:, 1], xyz[:, 2]
    with np.errstate(all="ignore"):
        centres = np.stack([0.0 + (one[i, 0] * x + one[i, 1] * y + one[i, 2] * z)
                            for i in range(3)], axis=1)
        placed = np.empty_like(rotation)
        for i in range(3):
            for j in range(3):
                placed[:, i, j] = one[i, 0] * rotation[:, 0, j] + \
                    one[i, 1] * rotation[:, 1, j] + one[i, 2] * rotation[:, 2, j]
    table.centres, table.rotations = centres[shapes_kept], placed[shapes_kept]
    # Piece sizes: a box's half sizes (size / 2: the local box's high corner), a cylinder's
    # (radius, half length), a sphere's (radius,)
    table.sizes = high[shapes_kept]
    cylinders = table.kinds == 1
    table.sizes[cylinders] = high[shapes_kept][cylinders][:, [0, 2, 2]]
    taken = np.array(chosen, dtype=bool).reshape(-1)[shapes_kept] if count else \
        np.zeros(0, dtype=bool)  # the shapes link_solid takes, of the links kept

    def kept_taken(values):
        return values[shapes_kept][taken] if count else values[:0]

    table.units = _plain_units(
        len(kept), table.shape_rows[taken], table.kinds[taken], kept_taken(dims),
        kept_taken(xyz), kept_taken(rotation), kept_taken(shape_low), kept_taken(shape_high))
    collision = np.zeros(len(kept), dtype=bool)
    visual = np.logical_not(np.array(collisions, dtype=bool).reshape(-1))[shapes_kept] \
        if count else np.zeros(0, dtype=bool)
    if count:  # the links with a <collision> shape: link_solid takes those
        collision[table.shape_rows[np.logical_not(visual)]] = True
    table.units["collision"], table.solids = collision, {}
    # each link's <visual> shapes' volume, summed in order (the larger body the density rule asks of)
    table.units["visual"] = _summed(len(kept), table.shape_rows[visual], _unit_volumes(
        table.kinds[visual], dims[shapes_kept][visual] if count else dims[:0]))
    table.units["visuals"] = np.bincount(table.shape_rows[visual], minlength=len(kept))
    return table


def _unit_volumes(kinds, dims):
    """The volume of each primitive (``kinds`` 0 box, 1 cylinder, 2 sphere; ``dims``
    :func:`_dimensions`) as :func:`unit_volume` gives it (its unit solid's mass)."""
    import numpy as np

    a, b, c = dims[:, 0], dims[:, 1], dims[:, 2]
    with np.errstate(all="ignore"):
        return np.where(kinds == 0, a * b * c, np.where(kinds == 1, math.pi * a * a * b, b))


def _parts_in_order(rows) -> list:
    """For items of links ``rows`` (ascending, each link's items together, in order): for
    k = 0, 1, ..., whether each item is its link's k-th."""
    import numpy as np

    if not len(rows):
        return []
    order = np.arange(len(rows)) - np.searchsorted(rows, rows, "left")
    return [order == k for k in range(int(order.max()) + 1)]


def _summed(count: int, rows, values):
    """Per link of ``count``, the sum of its items' ``values`` (``rows`` as for
    :func:`_parts_in_order`) from 0 in their order, as Python's ``sum`` adds them."""
    import numpy as np

    total = np.zeros(count)
    with np.errstate(all="ignore"):
        for at in _parts_in_order(rows):
            total[rows[at]] = total[rows[at]] + values[at]
    return total


def _plain_read(robot, link):
    """(shapes, how many of them are visual) of a link whose every ``<visual>`` then
    ``<collision>`` is a well-formed box, cylinder or sphere, each shape as
    (:func:`_dimensions`, xyz, rotation) placed as :func:`shape_of` places it; None when one
    is not (malformed, a mesh) or the link has none. What :func:`_plain_links` measures, read
    without a :class:`Shape` each nor kept (a 10,000-link robot's 20,000 shapes): the links
    it leaves read their own for the per-link path."""
    groups = robot.grouped(link)
    visuals, collisions = groups.get("visual", ()), groups.get("collision", ())
    if not (visuals or collisions):
        return None
    shapes = []
    for holders in (visuals, collisions):
        for holder in holders:
            read = _shape_read(holder, robot.grouped(holder))
            if read is None or read[0] == "mesh":
                return None
            kind, params, _, origin_element = read
            xyz, rpy = origin_pose(holder, origin_element)  # a malformed part counts as 0
            shapes.append((_dimensions(kind, params), xyz, mat3.rpy_matrix(rpy)))
    return shapes, len(visuals)


def _dimensions(kind: str, p: dict) -> tuple[float, float, float, float]:
    """What :func:`_plain_links` measures a primitive of ``kind`` and params ``p`` from: its
    kind (0 box, 1 cylinder, 2 sphere) and a box's size, a cylinder's (radius, length, 0), a
    sphere's (radius, volume, 0) (its volume from :func:`~urdftool.physics.mass.sphere_volume`:
    a cube as Python's ``**`` gives it)."""
    if kind == "box":
        a, b, c = p["size"]
        return 0.0, a, b, c
    if kind == "cylinder":
        return 1.0, p["radius"], p["length"], 0.0
    return 2.0, p["radius"], mp.sphere_volume(p["radius"]), 0.0


def _local_highs(kinds, dims):
    """Each primitive's :func:`_local_box` high corner (its low one is its negation): a box's
    half size, a cylinder's (radius, radius, half length), a sphere's radius thrice."""
    import numpy as np

    a, b, c = dims[:, 0], dims[:, 1], dims[:, 2]
    box, cylinder = (kinds == 0)[:, None], (kinds == 1)[:, None]
    with np.errstate(all="ignore"):
        return np.where(box, np.stack([a / 2, b / 2, c / 2], axis=1), np.where(
            cylinder, np.stack([a, a, b / 2], axis=1), np.stack([a, a, a], axis=1)))


def _plain_units(count: int, rows, kinds, dims, xyz, rotation, low, high) -> dict:
    """The unit-density solid of each of ``count`` plain links, from its chosen shapes (those
    :func:`link_solid` takes, in order: ``rows`` the link of each, ``kinds`` 0 box, 1 cylinder,
    2 sphere, ``dims`` :func:`_dimensions`, placed by ``xyz`` and ``rotation``, their boxes
    ``low``, ``high`` as :func:`_measured` finds them): :func:`~urdftool.physics.mass.box`,
    ``cylinder`` or ``sphere``, ``transformed``, then ``combine`` as :func:`computed` takes
    them, every product and sum in their order (numpy's elementwise operations are IEEE's, as
    Python's), so the same numbers to the bit. A dict of arrays: ``mass`` (n,) (the volume,
    summed as :func:`volume` sums it), ``com`` (n, 3), ``inertia`` (n, 3, 3), ``low`` and
    ``high`` (n, 3) (the box of the chosen shapes, a zero of either sign as +0);
    :func:`_plain_links` adds ``collision`` (whether the link has a <collision> shape: its
    solid's source), ``visual`` (the volume of its <visual> shapes, summed in order) and
    ``visuals`` (how many)."""
    import numpy as np

    with np.errstate(all="ignore"):
        a, b, c = dims[:, 0], dims[:, 1], dims[:, 2]
        box, cylinder = kinds == 0, kinds == 1
        # mass.box / cylinder / sphere: the volume and the diagonal, as each writes them
        m = _unit_volumes(kinds, dims)
        side = m * (3 * a * a + b * b) / 12
        moment = 2 / 5 * m * a * a
        diagonal = np.stack([np.where(box, m * (b * b + c * c) / 12, np.where(cylinder, side, moment)),
                             np.where(box, m * (a * a + c * c) / 12, np.where(cylinder, side, moment)),
                             np.where(box, m * (a * a + b * b) / 12,
                                      np.where(cylinder, m * a * a / 2, moment))], axis=1)
        local = np.zeros((len(m), 3, 3))
        for i in range(3):
            local[:, i, i] = diagonal[:, i]
        r = rotation
        # mass.transformed: com xyz + R (0, 0, 0); inertia R T R^T (mat3.multiply's sums)
        com = np.stack([xyz[:, i] + (r[:, i, 0] * 0.0 + r[:, i, 1] * 0.0 + r[:, i, 2] * 0.0)
                        for i in range(3)], axis=1)
        turned = np.empty_like(local)
        for i in range(3):
            for j in range(3):
                turned[:, i, j] = r[:, i, 0] * local[:, 0, j] + r[:, i, 1] * local[:, 1, j] + \
                    r[:, i, 2] * local[:, 2, j]
        inertia = np.empty_like(local)
        for i in range(3):
            for j in range(3):
                inertia[:, i, j] = turned[:, i, 0] * r[:, j, 0] + turned[:, i, 1] * r[:, j, 1] + \
                    turned[:, i, 2] * r[:, j, 2]
        # mass.combine over each link's parts in order: the sums start at 0, part by part
        taken = [(rows[at], m[at], com[at], inertia[at])
                 for at in _parts_in_order(rows)]  # each link's k-th parts
        mass, weighted = _summed(count, rows, m), np.zeros((count, 3))
        for link, mk, ck, _ in taken:
            weighted[link] = weighted[link] + mk[:, None] * ck
        centre = weighted / mass[:, None]
        total = np.zeros((count, 3, 3))
        for link, mk, ck, ik in taken:
            d = ck - centre[link]
            squared = d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1] + d[:, 2] * d[:, 2]
            for i in range(3):
                for j in range(3):
                    shift = squared - d[:, i] * d[:, j] if i == j else 0.0 - d[:, i] * d[:, j]
                    total[link, i, j] = total[link, i, j] + (ik[:, i, j] + mk * shift)
        # the box of the chosen shapes, as _joined gives it (its zeros as +0)
        first = np.full((count, 3), np.inf), np.full((count, 3), -np.inf)
        np.minimum.at(first[0], rows, low)
        np.maximum.at(first[1], rows, high)
    return {"mass": mass, "com": centre, "inertia": total, "low": first[0] + 0.0,
            "high": first[1] + 0.0}


class PlainSolid:
    """What :func:`link_solid` gives for a link of :class:`PlainLinks` that the inertia rules
    read, measured with the others at once: ``source``, ``bounds`` (a zero of either sign as
    +0), ``extent``; ``sound`` and ``counts`` (a plain link's primitives all count);
    :func:`volume` and :func:`computed` of it are the same numbers as of the link's
    :class:`LinkSolid`."""

    __slots__ = ("source", "bounds", "extent", "unit")
    sound = True
    counts = True

    def __init__(self, source: str, bounds, extent: float, unit: mp.Body):
        self.source, self.bounds, self.extent, self.unit = source, bounds, extent, unit


def plain_solid(robot, link, read: tuple | None = None) -> PlainSolid | None:
    """The :class:`PlainSolid` of ``link`` when it is one of :func:`plain_links` (the link of
    its name), else None. ``read``: (:func:`plain_links`, :meth:`~urdftool.description.robot.
    Robot.names`) of the robot, for a caller asking of every link."""
    table, names = (plain_links(robot), robot.names()) if read is None else read
    if table is None:
        return None
    name = names[link] if link in names else link.get("name")
    found = table.solids.get(name)
    if found is None:
        row = table.rows.get(name)
        if row is None or robot.links.get(name) is not link:
            return None
        if not table.solids:  # all at once, the first time: lists, not a numpy row each
            _plain_solids(table)
        found = table.solids[name]
    return found


def _plain_solids(table: PlainLinks) -> None:
    units = table.units
    masses, coms, inertias = units["mass"].tolist(), units["com"].tolist(), \
        units["inertia"].tolist()
    lows, highs, extents = units["low"].tolist(), units["high"].tolist(), \
        table.extents.tolist()
    sources = ["collision" if c else "visual" for c in units["collision"].tolist()]
    for name, row in table.rows.items():
        (a, b, c), (d, e, f), (g, h, i) = inertias[row]
        table.solids[name] = PlainSolid(
            sources[row], (tuple(lows[row]), tuple(highs[row])), extents[row],
            mp.Body(masses[row], tuple(coms[row]), ((a, b, c), (d, e, f), (g, h, i))))


def _shape_boxes(low, high, xyz, rotation, unturned):
    """(min corner, max corner, whether finite) of each shape's box placed in its link's
    frame, as :func:`_measured` finds them: (k, 3), (k, 3), (k,)."""
    import numpy as np

    with np.errstate(all="ignore"):
        (lx, ly, lz), (hx, hy, hz) = low.T, high.T
        # _kept_by_no_turn: the six coordinates' sum finite (in its order) and none zero
        kept = unturned & np.isfinite(lx + ly + lz + hx + hy + hz) & \
            (lx != 0) & (ly != 0) & (lz != 0) & (hx != 0) & (hy != 0) & (hz != 0)
        tx, ty, tz = xyz.T
        # unturned: the corners' coordinates on each axis, t + l and t + h
        axes = [(tx + lx, tx + hx), (ty + ly, ty + hy), (tz + lz, tz + hz)]
        total = np.zeros(len(low))
        for x in axes[0]:
            for y in axes[1]:
                for z in axes[2]:
                    total = total + (x + y + z)
        axes_low = np.stack([np.where(b < a, b, a) for a, b in axes], axis=1)
        axes_high = np.stack([np.where(b > a, b, a) for a, b in axes], axis=1)
        axes_finite = np.isfinite(total)
        # turned: the eight corners (in _corners' order) placed, t + (a x + b y + c z)
        r = rotation
        corners = [(x, y, z) for x in (lx, hx) for y in (ly, hy) for z in (lz, hz)]
        placed = [tuple(t + (r[:, i, 0] * x + r[:, i, 1] * y + r[:, i, 2] * z)
                        for i, t in enumerate((tx, ty, tz))) for x, y, z in corners]
        total = np.zeros(len(low))
        for x, y, z in placed:
            total = total + (x + y + z)
        points = np.array(placed)  # (8, 3, k)
        turned_low, turned_high = points.min(axis=0).T, points.max(axis=0).T
        turned_finite = np.isfinite(total)
    return (np.where(kept[:, None], axes_low, turned_low),
            np.where(kept[:, None], axes_high, turned_high),
            np.where(kept, axes_finite, turned_finite))


def _fixed_neighbours(robot) -> dict[str, list[tuple[str, mat3.Matrix, mat3.Vector]]]:
    """Link -> (link fixed to it, R, t taking points of that link's frame into this one's)."""
    def build():
        neighbours, kinds = {}, robot.kinds()
        for joint, ends in robot.ends().items():
            (parent_element, parent), (child_element, child) = ends["parent"], ends["child"]
            if kinds[joint] != "fixed" or parent_element is None or child_element is None:
                continue
            if parent not in robot.links or child not in robot.links:
                continue
            xyz, rotation = mat3.placement(origin(joint))  # p_parent = xyz + rotation p_child
            back = mat3.transpose(rotation)  # p_child = back p_parent - back xyz
            neighbours.setdefault(parent, []).append((child, rotation, xyz))
            neighbours.setdefault(child, []).append(
                (parent, back, tuple(-v for v in mat3.apply(back, xyz))))
        return neighbours

    return robot.memo(_fixed_neighbours, build)


def rigid_group(robot, name: str) -> list[str]:
    """Link ``name`` and every link joined to it by fixed joints (either way): one body, in the
    order reached from ``name``."""
    neighbours = _fixed_neighbours(robot)
    order, seen = [name], {name}
    for current in order:  # the walk of _rigid_frames, without the frames
        for other, _, _ in neighbours.get(current, ()):
            if other not in seen:
                seen.add(other)
                order.append(other)
    return order


def fixed_to_others(robot, name: str) -> bool:
    """Whether some link is joined to link ``name`` by a fixed joint: its rigid body is more
    than itself."""
    return name in _fixed_neighbours(robot)


def rigid_root(robot, name: str) -> str:
    """The root of link ``name``'s rigid body (:func:`_bodies`: the same link for every member),
    ``name`` itself when no link is fixed to it: a key for what is asked once per body."""
    found = _bodies(robot).get(name)
    return name if found is None else found[0]


def rigid_declared(robot, name: str, tensors: dict | None = None) -> mp.Body | None:
    """The declared inertials of link ``name``'s rigid body (it and every link joined to it by
    fixed joints, either way) as one body in ``name``'s frame, as Gazebo, MuJoCo and Pinocchio
    lump them (and as any simulator moves them: welded links move as one); ``tensors``: link
    name -> a tensor to take in place of the declared one (about the same centre of mass);
    None when none of them has a finite positive mass and a finite tensor."""
    parts = []
    for member, (rotation, xyz) in _rigid_frames(robot, name).items():
        link = robot.links.get(member)
        body = mp.declared_of(robot, link) if link is not None else None
        if body is None or not (math.isfinite(body.mass) and body.mass > 0) or not all(
                math.isfinite(v) for row in body.inertia for v in row) or not all(
                math.isfinite(v) for v in body.com):
            continue
        if tensors and member in tensors:
            body = mp.Body(body.mass, body.com, tensors[member])
        parts.append(mp.transformed(body, xyz, rotation))
    return mp.combine(parts) if parts else None


def _rigid_frames(robot, name: str) -> dict[str, tuple[mat3.Matrix, mat3.Vector]]:
    """Link ``name`` and every link joined to it by fixed joints -> (R, t) taking points of
    that link's frame into ``name``'s frame."""
    neighbours = _fixed_neighbours(robot)
    frames = {name: (mat3.IDENTITY, (0.0, 0.0, 0.0))}
    pending = [name]
    for current in pending:  # breadth first: each link is appended once
        r, t = frames[current]
        for other, rotation, xyz in neighbours.get(current, ()):
            if other not in frames:
                frames[other] = (mat3.multiply(r, rotation), mat3.add(t, mat3.apply(r, xyz)))
                pending.append(other)
    return frames


def _bodies(robot) -> dict[str, tuple[str, dict]]:
    """Link -> (the root of its rigid body, the body's :func:`_rigid_frames` from the root),
    for every link with a link fixed to it; one walk per body, once per robot. The root is
    the body's link met first in the joints' order."""
    def build():
        found = {}
        for name in _fixed_neighbours(robot):
            if name not in found:
                frames = _rigid_frames(robot, name)
                for member in frames:
                    found[member] = (name, frames)
        return found

    return robot.memo(_bodies, build)


def volume(solid: LinkSolid | PlainSolid) -> float:
    """The summed volume of a solid's parts [m^3] (overlaps count twice; 0 without parts)."""
    if isinstance(solid, PlainSolid):
        return solid.unit.mass  # (summed so)
    # the parts' masses (unit density), in their order, without placing them
    return sum(_unit_volume(entry) for entry in solid._build()[0])


def computed(solid: LinkSolid, mass: float | None = None, density: float | None = None):
    """A :class:`~urdftool.physics.mass.Body` of the solids: with ``mass`` [kg] kept, or
    from ``density`` [kg/m^3]. None without parts, or when their volume is no positive
    finite float (sizes of ~1e-108 m underflow to 0, of ~1e103 m overflow to infinity): such a
    solid says nothing of a tensor."""
    if isinstance(solid, PlainSolid):
        unit = solid.unit  # (combined so)
        if not 0 < unit.mass < math.inf:
            return None
    else:
        if not solid.parts:
            return None
        volume = sum(part.mass for part in solid.parts)
        if not 0 < volume < math.inf:
            return None
        unit = mp.combine(solid.parts)  # density 1: mass is volume
    if mass is not None:
        return unit.scaled_to(mass)
    return unit.scaled_to(unit.mass * (density if density is not None else 1000.0))


_ROUND = 48  # points on a cylinder's rim or a sphere's circles


def surface_points(robot, link) -> tuple:
    """(points ``[k, 3]`` [m] in the link frame, problems): points of the link's collision
    geometry (visual when it has none) among which any lowest point lies: a box's corners, a
    cylinder's rims, a sphere's points on a fine grid, a mesh's vertices. numpy, for statics."""
    import numpy as np

    collision = shapes(robot, link, "collision")
    chosen = collision or shapes(robot, link, "visual")
    points, problems = [], []
    for shape in chosen:
        p = shape.params
        if shape.kind == "mesh":
            from urdftool.description.meshes import MeshProblem, load_mesh

            try:
                local = np.asarray(load_mesh(robot, p["filename"], p["scale"]).vertices)
            except MeshProblem as problem:
                problems.append((shape.element, str(problem)))
                continue
        elif shape.kind == "box":
            local = np.array(_corners(_local_box(shape)))
        elif shape.kind == "cylinder":
            angles = np.linspace(0.0, 2 * np.pi, _ROUND, endpoint=False)
            ring = np.stack([p["radius"] * np.cos(angles), p["radius"] * np.sin(angles)], -1)
            half = p["length"] / 2
            local = np.vstack([np.column_stack([ring, np.full(_ROUND, z)]) for z in (-half, half)])
        else:
            polar, azimuth = np.meshgrid(np.linspace(0, np.pi, _ROUND // 2 + 1),
                                         np.linspace(0, 2 * np.pi, _ROUND, endpoint=False))
            local = p["radius"] * np.stack([np.sin(polar) * np.cos(azimuth),
                                            np.sin(polar) * np.sin(azimuth),
                                            np.cos(polar)], -1).reshape(-1, 3)
        points.append(local @ np.array(shape.rotation).T + np.array(shape.xyz))
    return (np.vstack(points) if points else np.zeros((0, 3))), problems
