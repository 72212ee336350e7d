"""Collision geometry: one FCL object per ``<collision>`` element, with its bounding box.

Boxes, cylinders and spheres become FCL primitives; meshes become BVH models, scaled. Each part
also carries an oriented bounding box (frame in the link, half extents) and a bounding sphere, the
cheap tests the matrix runs across thousands of samples before asking FCL.

Meshes are loaded through :mod:`urdftool.description.meshes`, with its safety limits and per-robot cache.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field

import fcl
import numpy as np

from urdftool.diagnostics import Location
from urdftool.kinematics import transforms
from urdftool.description.urdf import ROUND
from urdftool.description.values import origin as read_origin, parse_numbers


@dataclass
class Part:
    """One ``<collision>`` of a link.

    origin: pose of the geometry in the link frame, 4x4
    box: pose of the oriented bounding box in the link frame, 4x4 (box centre and axes)
    half: half extents of that box in [m]
    radius: radius of the bounding sphere around the box centre in [m]
    shape: what the geometry is, comparable across robots: a primitive's sizes, a mesh's
    digest of its vertices and faces as FCL holds them (two parts with equal ``kind``,
    ``shape`` and ``origin`` collide alike wherever their links are)
    mesh: a mesh's (vertices [m], triangles) in the geometry frame, for the convex hull that
    gives a contact its depth (FCL's contacts between triangles have none); None for a primitive
    """

    link: str
    kind: str
    geometry: object
    origin: np.ndarray
    box: np.ndarray
    half: np.ndarray
    shape: object
    mesh: tuple | None = None

    @property
    def radius(self) -> float:
        return float(np.linalg.norm(self.half))


@dataclass
class Problem:
    """A collision element that could not be used, and why; it is left out of every check."""

    location: Location
    message: str


@dataclass
class Geometry:
    """Collision parts by link, in link document order, and what was left out."""

    parts: dict[str, list[Part]] = field(default_factory=dict)
    visual_only: list[str] = field(default_factory=list)
    problems: list[Problem] = field(default_factory=list)
    # meshes checked as read under an assumption (description.meshes.read_as_assumed): kept,
    # and said as warnings, each once
    assumed: list[str] = field(default_factory=list)

    @property
    def links(self) -> list[str]:
        return list(self.parts)


def build(robot) -> Geometry:
    """Collision parts of every link of ``robot`` that urdfdom's model holds; unusable ones
    become problems. A link beside the tree (:func:`~urdftool.kinematics.tree.
    beside_the_tree`) is not posed (its parts were, as a KeyError), and an only link without a
    name is the link ``''`` with nothing in it (Robot.links), as urdfdom reads them."""
    from urdftool.kinematics.tree import beside_the_tree

    result = Geometry()
    meshes: dict = {}
    dropped, names = set(beside_the_tree(robot)), robot.names()
    for name, link in robot.links.items():
        if name in dropped or names[link] is None:
            continue
        collisions = link.findall("collision")
        parts = []
        for collision in collisions:
            part = _part(robot, name, collision, meshes, result.problems, result.assumed)
            if part is not None:
                parts.append(part)
        if parts:
            result.parts[name] = parts
        elif not collisions and link.find("visual") is not None:
            result.visual_only.append(name)
    return result


def _part(robot, link: str, collision, meshes, problems, assumed) -> Part | None:
    where = robot.locate(collision)
    shape = collision.find("geometry")
    # the first element: a comment before it (youBot's base, its box left commented out
    # above the mesh) made the collision "no geometry", left out
    shape = next((child for child in shape if isinstance(child.tag, str)), None) \
        if shape is not None else None
    if shape is None:
        problems.append(Problem(where, f"link '{link}': <collision> has no geometry; ignored"))
        return None
    kind, mesh = shape.tag, None
    if kind == "box":
        size, problem = parse_numbers(shape.get("size"), 3)
        if size is None or min(size) <= 0 or not np.all(np.isfinite(size)):
            return _refuse(problems, robot, shape, link, f"box size {problem or shape.get('size')}")
        geometry, center, half = fcl.Box(*size), np.zeros(3), np.array(size) / 2
        identity = tuple(size)
    elif kind in ROUND:
        radius, length = _positive(shape, "radius"), _positive(shape, "length")
        if radius is None or (kind == "cylinder" and length is None):
            return _refuse(problems, robot, shape, link, f"{kind} needs positive finite "
                           "radius" + (" and length" if kind == "cylinder" else ""))
        if kind == "sphere":
            geometry, half = fcl.Sphere(radius), np.full(3, radius)
        else:
            geometry, half = fcl.Cylinder(radius, length), np.array([radius, radius, length / 2])
        center, identity = np.zeros(3), (radius, length)
    elif kind == "mesh":
        loaded = _load_mesh(robot, shape, meshes)
        if isinstance(loaded, str):
            return _refuse(problems, robot, shape, link, loaded)
        geometry, center, half, identity, mesh, said = loaded
        for why in said:
            note = f"link '{link}': mesh '{shape.get('filename')}'{why}"
            if note not in assumed:  # (a link's mesh named twice is said once)
                assumed.append(note)
    else:
        return _refuse(problems, robot, shape, link, f"geometry <{kind}> is not supported")
    origin = transforms.from_origin(read_origin(collision))  # a malformed part counts as 0
    far = transforms.too_far(origin, center - half, center + half)
    if far:
        return _refuse(problems, robot, shape, link, f"its {kind} {far}")
    box = origin.copy()
    box[:3, 3] = origin[:3, :3] @ center + origin[:3, 3]
    return Part(link, kind, geometry, origin, box, np.maximum(half, 1e-9), identity,
                mesh)


def _positive(element, attribute: str) -> float | None:
    values, _ = parse_numbers(element.get(attribute), 1)
    if values is None or not np.isfinite(values[0]) or values[0] <= 0:
        return None
    return values[0]


def _refuse(problems, robot, shape, link: str, why: str) -> None:
    problems.append(Problem(robot.locate(shape), f"link '{link}': {why}; this collision is "
                                                 "left out of every check"))
    return None


def _load_mesh(robot, shape, cache):
    """(BVH model, bounding box centre, half extents, digest, (vertices, triangles), what it
    was read assuming) or a message saying why not.

    The mesh itself comes from :mod:`urdftool.description.meshes` (containment, extension whitelist, size
    and triangle limits, COLLADA units, the per-robot cache); only the FCL model is built here,
    once per (file, scale).
    """
    from urdftool.description.meshes import MeshProblem, load_mesh, read_as_assumed

    uri = shape.get("filename")
    if not uri:
        return "mesh has no filename"
    scale = (1.0, 1.0, 1.0)
    if shape.get("scale") is not None:
        values, problem = parse_numbers(shape.get("scale"), 3)
        if values is None or not np.all(np.isfinite(values)) or 0 in values:
            return f"mesh scale {problem or shape.get('scale')} is unusable"
        scale = tuple(values)
    key = (uri, scale)
    if key not in cache:
        try:
            mesh = load_mesh(robot, uri, scale)
            cache[key] = (*_bvh(mesh), read_as_assumed(mesh.metadata))
        except MeshProblem as problem:
            cache[key] = str(problem)
    return cache[key]


def _bvh(mesh):
    vertices = np.asarray(mesh.vertices, dtype=float).reshape(-1, 3)
    faces = np.asarray(mesh.faces, dtype=np.int64).reshape(-1, 3)
    model = fcl.BVHModel()
    model.beginModel(len(vertices), len(faces))
    model.addSubModel(vertices, faces)
    model.endModel()
    low, high = vertices.min(axis=0), vertices.max(axis=0)
    digest = hashlib.blake2b(vertices.tobytes(), digest_size=16)
    digest.update(faces.tobytes())
    return model, (low + high) / 2, (high - low) / 2, digest.digest(), (vertices, faces)
