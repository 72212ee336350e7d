"""A link's ``<collision>``/``<visual>`` geometry as solids: mass properties and bounds.

The inertia rules and ``urdftool inertia`` read geometry through here, and meshes through
:mod:`urdftool.description.meshes` (their measures, once per run: ``mesh_facts``), so both see
the same shapes, scales and origins. Pure Python (:mod:`urdftool.physics.mat3` tuples): numpy is
imported only when a mesh is measured, trimesh only for formats other than STL.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from urdftool.physics import mass as mp
from urdftool.physics import mat3
from urdftool.description.urdf import SHAPES
from urdftool.description.values import finite, origin, parse_numbers


HULL_USED = "its convex hull was used"  # the problem of an open mesh that still counts


@dataclass
class Shape:
    """One geometry: ``kind`` in SHAPES, ``params`` (size / radius, length / filename, scale),
    placed by ``xyz`` and ``rotation`` in the link frame; ``element`` is the geometry child."""

    kind: str
    params: dict
    xyz: mat3.Vector
    rotation: mat3.Matrix
    element: object


@dataclass
class LinkSolid:
    """What a link's geometry implies: ``source`` is collision, visual or none.

    parts: unit-density solids in the link frame; problems: (element, message) for geometry
    that could not count (missing mesh, open mesh replaced by its hull...)
    """

    source: str
    parts: list = field(default_factory=list)
    problems: list = field(default_factory=list)
    bounds: tuple[mat3.Vector, mat3.Vector] | None = None  # min and max corner, link frame


def _positive(values) -> bool:
    return values is not None and finite(values) and all(v > 0 for v in values)


def shape_of(holder) -> Shape | None:
    """The shape of a ``<visual>``/``<collision>``, or None when malformed (rules say why)."""
    geometry = holder.find("geometry")
    if geometry is None:
        return None
    children = [c for c in geometry if isinstance(c.tag, str)]
    if not children or children[0].tag not in SHAPES:
        return None
    element = children[0]
    xyz, rotation = mat3.placement(origin(holder))  # a malformed part counts as 0
    if element.tag == "box":
        size = parse_numbers(element.get("size"), 3)[0]
        params = {"size": size} if _positive(size) else None
    elif element.tag == "cylinder":
        radius = parse_numbers(element.get("radius"), 1)[0]
        length = parse_numbers(element.get("length"), 1)[0]
        params = {"radius": radius[0], "length": length[0]} \
            if _positive(radius) and _positive(length) else None
    elif element.tag == "sphere":
        radius = parse_numbers(element.get("radius"), 1)[0]
        params = {"radius": radius[0]} if _positive(radius) else None
    else:
        scale = parse_numbers(element.get("scale", "1 1 1"), 3)[0]
        params = {"filename": element.get("filename"), "scale": tuple(scale)} \
            if element.get("filename") and scale and finite(scale) else None
    if params is None:
        return None
    return Shape(element.tag, params, xyz, rotation, element)


def shapes(link, tag: str) -> list[Shape]:
    return [s for s in (shape_of(h) for h in link.findall(tag)) if s is not None]


def _mesh_solid(robot, shape: Shape, problems: list):
    """(unit-density solid, local bounds) of a mesh shape, or (None, None) with a problem.

    trimesh's numpy warnings on degenerate or absurdly scaled meshes are silenced: the
    implausible-size rule and the problems below say what is wrong with the mesh.
    """
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return _mesh_solid_unchecked(robot, shape, problems)


def _mesh_solid_unchecked(robot, shape: Shape, problems: list):
    from urdftool.description.meshes import MeshProblem, mesh_facts  # only robots with meshes

    try:
        mesh = mesh_facts(robot, shape.params["filename"], shape.params["scale"])
    except MeshProblem as problem:
        problems.append((shape.element, str(problem)))
        return None, None
    body = mesh
    bounds = tuple(mat3.vector(corner) for corner in mesh.bounds)
    if not mesh.is_watertight:
        try:
            body = mesh.convex_hull
        except RuntimeError:  # qhull: the vertices are one point, a line or (unjoggled) a plane
            problems.append((shape.element, f"mesh '{shape.params['filename']}' is flat or a "
                                            "single point: it encloses no volume"))
            return None, bounds
        problems.append((shape.element, f"mesh '{shape.params['filename']}' is not closed "
                                        f"(watertight); {HULL_USED}"))
    from urdftool.physics.inertia import mesh_solid

    solid = mesh_solid(body).body()
    if not solid.mass > 0:  # also NaN from a zero-volume mesh
        problems.append((shape.element, f"mesh '{shape.params['filename']}' encloses no volume"))
        return None, bounds
    return solid, bounds


def _local(shape: Shape):
    p = shape.params
    if shape.kind == "box":
        half = tuple(v / 2 for v in p["size"])
        return mp.box(p["size"]), (tuple(-v for v in half), half)
    if shape.kind == "cylinder":
        r, h = p["radius"], p["length"] / 2
        return mp.cylinder(p["radius"], p["length"]), ((-r, -r, -h), (r, r, h))
    r = p["radius"]
    return mp.sphere(r), ((-r,) * 3, (r,) * 3)


def _corners(bounds) -> list[mat3.Vector]:
    return [(bounds[i][0], bounds[j][1], bounds[k][2])
            for i in (0, 1) for j in (0, 1) for k in (0, 1)]


def link_solid(robot, link, load_meshes: bool = True, tag: str | None = None) -> LinkSolid:
    """The solids of a link's collision geometry, or its visual geometry when it has none;
    ``tag`` ("collision" or "visual") takes that geometry only."""
    collision = shapes(link, "collision") if tag in (None, "collision") else []
    chosen, source = (collision, "collision") if collision or tag == "collision" else \
        (shapes(link, "visual"), "visual")
    if not chosen:
        return LinkSolid("none")
    result = LinkSolid(source)
    corners = []
    for shape in chosen:
        if shape.kind == "mesh":
            if not load_meshes:
                continue
            solid, local_bounds = _mesh_solid(robot, shape, result.problems)
        else:
            solid, local_bounds = _local(shape)
        if local_bounds is not None:
            corners.extend(mat3.add(shape.xyz, mat3.apply(shape.rotation, c))
                           for c in _corners(local_bounds))
        if solid is not None:
            result.parts.append(mp.transformed(solid, shape.xyz, shape.rotation))
    if corners:
        result.bounds = (tuple(min(c[i] for c in corners) for i in range(3)),
                         tuple(max(c[i] for c in corners) for i in range(3)))
    return result


@dataclass
class RigidBounds:
    """The bounding box [m] of everything rigidly one with a link, in the link frame.

    links: the link and those fixed to it (through fixed joints, either way), in the order
    reached; complete: False when some of their geometry could not be measured (a mesh that
    does not resolve or load), so the box may be too small; bounds: None without geometry.
    """

    links: list[str]
    complete: bool = True
    bounds: tuple[mat3.Vector, mat3.Vector] | None = None


def rigid_bounds(robot, link) -> RigidBounds:
    """The box of a link's visual and collision geometry and of the links fixed to it."""
    frames = _rigid_frames(robot, link.get("name"))
    result, corners = RigidBounds(list(frames)), []
    for name, (rotation, xyz) in frames.items():
        local, complete = _placed_corners(robot, robot.links.get(name))
        corners.extend(mat3.add(xyz, mat3.apply(rotation, c)) for c in local)
        result.complete = result.complete and complete
    if corners:
        result.bounds = (tuple(min(c[i] for c in corners) for i in range(3)),
                         tuple(max(c[i] for c in corners) for i in range(3)))
    return result


def _placed_corners(robot, member) -> tuple[list[mat3.Vector], bool]:
    """(the corners of the boxes of a link's visual and collision shapes, in the link frame;
    whether every shape was measured), once per robot and link: every link fixed to it asks."""
    def build():
        corners, complete = [], True
        for shape in shapes(member, "visual") + shapes(member, "collision"):
            local = _local_bounds(robot, shape)
            if local is None:
                complete = False
                continue
            corners.extend(mat3.add(shape.xyz, mat3.apply(shape.rotation, c))
                           for c in _corners(local))
        complete = complete and len(shapes(member, "visual")) == len(
            member.findall("visual")) and len(shapes(member, "collision")) == len(
            member.findall("collision"))
        return corners, complete

    return robot.memo((_placed_corners, member), build)


def _local_bounds(robot, shape: Shape):
    """A shape's box in its own frame, or None for a mesh that does not resolve or load."""
    if shape.kind != "mesh":
        return _local(shape)[1]
    from urdftool.description.meshes import MeshProblem, mesh_facts

    try:
        mesh = mesh_facts(robot, shape.params["filename"], shape.params["scale"])
    except MeshProblem:
        return None
    return tuple(mat3.vector(corner) for corner in mesh.bounds)


def _fixed_neighbours(robot) -> dict[str, list[tuple[str, mat3.Matrix, mat3.Vector]]]:
    """Link -> (link fixed to it, R, t taking points of that link's frame into this one's)."""
    def build():
        neighbours = {}
        for joint in robot.children("joint"):
            parent, child = joint.find("parent"), joint.find("child")
            if joint.get("type") != "fixed" or parent is None or child is None:
                continue
            parent, child = parent.get("link"), child.get("link")
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
    """Link ``name`` and every link joined to it by fixed joints (either way): one body."""
    return list(_rigid_frames(robot, name))


def _rigid_frames(robot, name: str) -> dict[str, tuple[mat3.Matrix, mat3.Vector]]:
    """Link ``name`` and every link joined to it by fixed joints -> (R, t) taking points of
    that link's frame into ``name``'s frame."""
    neighbours = _fixed_neighbours(robot)
    frames = {name: (mat3.IDENTITY, (0.0, 0.0, 0.0))}
    pending = [name]
    while pending:
        current = pending.pop(0)
        r, t = frames[current]
        for other, rotation, xyz in neighbours.get(current, ()):
            if other not in frames:
                frames[other] = (mat3.multiply(r, rotation), mat3.add(t, mat3.apply(r, xyz)))
                pending.append(other)
    return frames


def volume(solid: LinkSolid) -> float:
    """The summed volume of a solid's parts [m^3] (overlaps count twice; 0 without parts)."""
    return sum(part.mass for part in solid.parts)  # the parts have unit density


def computed(solid: LinkSolid, mass: float | None = None, density: float | None = None):
    """A :class:`~urdftool.physics.mass.Body` of the solids: with ``mass`` [kg] kept, or
    from ``density`` [kg/m^3]."""
    if not solid.parts:
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

    collision = shapes(link, "collision")
    chosen = collision or shapes(link, "visual")
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
            local = np.array(_corners(_local(shape)[1]))
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
