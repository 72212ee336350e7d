"""A robot's geometry posed at a configuration, as triangles: what a picture is drawn from.

The scene is yourdfpy's scene graph (a trimesh scene with one node per link, joints as edges,
``update_cfg`` for the forward kinematics). yourdfpy gets the already expanded URDF text and
never opens a file itself: it is built with ``load_meshes=False`` (it makes the boxes, cylinders
and spheres), and every mesh is loaded by :func:`urdftool.description.meshes.load_mesh` (the
containment, size and triangle limits, no textures) and added to the link's node here. Its
``filename_handler`` is urdftool's resolver too, so nothing yourdfpy might still ask for
leads outside the robot's repository or packages.

Joint values are urdftool's variables (:mod:`urdftool.kinematics.configuration`): revolute,
continuous and prismatic joints, mimic joints following theirs, and the coordinates of floating
and planar joints (``NAME.x``, ...), which urdftool places itself (``fk.coordinates_motion``):
yourdfpy counts a planar joint as 2 values and a floating one as 3 or 6, and drew both at their
origin whatever ``--q`` said.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field

from urdftool.errors import MeshProblem, SceneError, described
from urdftool.description.urdf import MOVING
from urdftool.numbers import power, unit

# the scene's metadata: the parts of links left out of it, as notes (transforms.too_far)
LEFT_OUT = "urdftool_left_out"
DEFAULT_COLOUR = (0.62, 0.64, 0.68)  # [0, 1] rgb of geometry without a material colour
# Triangles a posed scene may hold, checked before any is placed: the per-mesh limit is 2 million
# (check --max-triangles), and one such mesh on many links is that many copies (72 bytes each).
MAX_SCENE_TRIANGLES = 8_000_000


@dataclass
class PosedScene:
    """Triangles of a robot's geometry in its root frame at one configuration.

    links: names of the links that have geometry; ``owners`` index into it
    triangles: ``[n, 3, 3]`` corner positions in [m]
    owners: ``[n]`` the link each triangle belongs to
    colours: ``[n, 3]`` rgb in [0, 1] (the URDF material, else a neutral grey)
    facing: ``[n]`` +1 where the corners' order (right hand) gives the outward normal of a
        closed surface, -1 where it gives the inward one, 0 for an open surface (unknown)
    frames: every link's pose (4x4) in the root frame
    axes: (joint, point [m], unit direction) of each moving joint, in the root frame
    q: the joint values drawn, by variable name, in [rad] or [m]
    problems: geometry left out, and why (a mesh that may not or cannot be loaded)
    """

    links: list[str]
    triangles: np.ndarray
    owners: np.ndarray
    colours: np.ndarray
    frames: dict[str, np.ndarray]
    axes: list[tuple[str, np.ndarray, np.ndarray]]
    facing: np.ndarray | None = None
    q: dict[str, float] = field(default_factory=dict)
    problems: list[str] = field(default_factory=list)


class SceneModel:
    """A robot's visual (or collision) geometry in yourdfpy's scene graph, posed on demand."""

    def __init__(self, robot, collision: bool = False):
        from urdftool.kinematics.configuration import (FLOATING_COORDINATES, PLANAR_COORDINATES,
                                                       mimics_of, variables_of)

        self.robot = robot
        self.collision = collision
        self.urdf = _yourdfpy(robot, collision)
        self.scene = self.urdf.collision_scene if collision else self.urdf.scene
        self.problems: list[str] = list(self.scene.metadata.get(LEFT_OUT, ()))
        self._colours: dict[str, tuple] = {}
        self._add_meshes()
        self.variables = [v for v in variables_of(robot)
                          if v.kind in MOVING]
        self.all_variables = variables_of(robot)
        self.mimics = mimics_of(robot)
        # the joints of several variables (yourdfpy's joints, with their coordinates' names)
        self._multiple = [(joint, FLOATING_COORDINATES if joint.type == "floating"
                           else PLANAR_COORDINATES) for joint in self.urdf.robot.joints
                          if joint.type in ("floating", "planar") and joint.mimic is None]
        self._nodes = [(node, self.scene.graph.transforms.parents[node])
                       for node in self.scene.graph.nodes_geometry]
        self.links = list(dict.fromkeys(link for _, link in self._nodes))
        # closed, consistently wound surfaces: their faces turned away can be left undrawn; a
        # primitive (box, sphere, cylinder) is closed by construction (asking trimesh took 15
        # of 68 s on 2,000 spheres: each one's edges grouped)
        from trimesh.primitives import Primitive

        self._closed = {node: isinstance(self._geometry(node), Primitive) or bool(
            self._geometry(node).is_watertight and self._geometry(node).is_winding_consistent)
            for node, _ in self._nodes}

    @property
    def triangle_count(self) -> int:
        return sum(len(self._geometry(node).faces) for node, _ in self._nodes)

    def _geometry(self, node: str):
        # the node's own data: graph[node] would walk its path from the base (_placements)
        return self.scene.geometry[self.scene.graph.transforms.node_data[node]["geometry"]]

    def _add_meshes(self) -> None:
        """Every ``<mesh>`` of every link, loaded safely and hung from its link's node."""
        import numpy as np

        from urdftool.description.meshes import load_mesh, read_as_assumed
        from urdftool.kinematics import transforms

        for link in self.urdf.robot.links:
            for element in (link.collisions if self.collision else link.visuals):
                mesh = element.geometry.mesh if element.geometry is not None else None
                if mesh is None:
                    continue
                scale = mesh.scale if mesh.scale is not None else 1.0
                scale = np.broadcast_to(np.asarray(scale, dtype=float), (3,))
                try:
                    loaded = load_mesh(self.robot, mesh.filename or "", tuple(scale))
                except MeshProblem as problem:
                    self.problems.append(f"link '{link.name}': {problem}; not drawn")
                    continue
                self.problems += [f"link '{link.name}': mesh '{mesh.filename}'{said}"
                                  for said in read_as_assumed(loaded.metadata)]
                origin = element.origin if element.origin is not None else np.eye(4)
                far = transforms.too_far(origin, *loaded.bounds)
                if far:
                    self.problems.append(f"link '{link.name}': its mesh {far}; not drawn")
                    continue
                node = self.scene.add_geometry(loaded, parent_node_name=link.name,
                                               transform=origin)
                self._colours[node] = self._material_colour(element)

    def _material_colour(self, element) -> tuple | None:
        """The rgb of a ``<visual>``'s material, looked up as yourdfpy does; None when none."""
        material = getattr(element, "material", None)
        if material is None:
            return None
        colour = material.color
        if colour is None and material.name in self.urdf._material_map:
            colour = self.urdf._material_map[material.name].color
        return tuple(float(c) for c in colour.rgba[:3]) if colour is not None else None

    def _colour(self, node: str, geometry) -> tuple:
        if node in self._colours:
            return self._colours[node] or DEFAULT_COLOUR
        visual = getattr(geometry, "visual", None)
        if self.collision or getattr(visual, "kind", None) != "face":
            return DEFAULT_COLOUR
        return tuple(float(c) / 255 for c in visual.face_colors[0][:3])

    def pose(self, q: dict[str, float] | None = None,
             max_triangles: int | None = MAX_SCENE_TRIANGLES) -> PosedScene:
        """The triangles at joint values ``q`` ({variable: value} in [rad] or [m]; others 0,
        or mid-range when 0 is outside the limits). OverLimit, before any is placed, when the
        scene holds more than ``max_triangles`` (None: no limit; every instance of a mesh
        counted: one mesh within the per-mesh limit, used by many links, is that many copies
        here)."""
        import numpy as np

        from urdftool.errors import OverLimit
        from urdftool.kinematics.fk import coordinates_motion

        if max_triangles is not None and self.triangle_count > max_triangles:
            raise OverLimit("the robot's geometry, every instance of a mesh counted",
                            self.triangle_count, max_triangles, "triangles")

        values = {v.name: v.default for v in self.variables}
        values.update({name: float(value) for name, value in (q or {}).items()
                       if name in values})
        if values:
            self.urdf.update_cfg(values)
        graph = self.scene.graph
        for joint, coordinates in self._multiple:  # placed here, not by yourdfpy
            pose = [float((q or {}).get(f"{joint.name}.{c}", 0.0)) for c in coordinates]
            values.update({f"{joint.name}.{c}": x for c, x in zip(coordinates, pose)})
            origin = joint.origin if joint.origin is not None else np.eye(4)
            graph.update(frame_from=joint.parent, frame_to=joint.child,
                         matrix=origin @ coordinates_motion(joint.type, [pose])[0])
        placed = _placements(graph)
        frames = {link.name: placed(link.name) for link in self.urdf.robot.links
                  if link.name in graph.nodes}
        index = {link: i for i, link in enumerate(self.links)}
        triangles, owners, colours, facing = [], [], [], []
        for node, link in self._nodes:
            transform, geometry = placed(node), self._geometry(node)
            vertices = np.asarray(geometry.vertices, dtype=float) @ transform[:3, :3].T \
                + transform[:3, 3]
            faces = np.asarray(geometry.faces, dtype=np.int64)
            posed = vertices[faces]
            triangles.append(posed)
            owners.append(np.full(len(faces), index[link]))
            colours.append(np.tile(self._colour(node, geometry), (len(faces), 1)))
            facing.append(np.full(len(faces), _orientation(posed) if self._closed[node] else 0,
                                  dtype=np.int8))
        axes = []
        for joint in self.urdf.robot.joints:
            if joint.type in MOVING and joint.parent in frames:
                origin = joint.origin if joint.origin is not None else np.eye(4)
                placed = frames[joint.parent] @ origin
                direction = unit(placed[:3, :3] @ joint.axis)  # (a unit axis: _unit_axes)
                if direction is not None:
                    axes.append((joint.name, placed[:3, 3].copy(), np.asarray(direction)))
        empty = np.zeros((0, 3))
        return PosedScene(
            list(self.links),
            np.concatenate(triangles) if triangles else np.zeros((0, 3, 3)),
            np.concatenate(owners) if owners else np.zeros(0, dtype=np.int64),
            np.concatenate(colours) if colours else empty,
            frames, axes, np.concatenate(facing) if facing else np.zeros(0, dtype=np.int8),
            values, list(self.problems))


def _orientation(triangles) -> int:
    """+1 when a closed surface's triangles wind outward (positive enclosed volume, the sum of
    the corners' triple products), -1 inward (a mirroring scale turns them), 0 when flat."""
    import numpy as np

    volume = np.einsum("ij,ij->", triangles[:, 0], np.cross(triangles[:, 1], triangles[:, 2]))
    extent = np.ptp(triangles.reshape(-1, 3), axis=0).max() if len(triangles) else 0.0
    if abs(volume) <= 1e-12 * power(max(extent, 1e-12), 3):
        return 0
    return 1 if volume > 0 else -1


def _as_urdfdom_reads(robot, root) -> None:
    """``root`` (the robot's URDF as yourdfpy will read it) made what urdfdom's model holds:
    an only ``<link>`` without a name is the link ``''`` with nothing in it (Robot.links:
    yourdfpy refused it, "an element lacks its 'name' attribute"), and the links beside the
    tree and their joints are dropped (their loop sent trimesh's scene graph round it:
    "Iteration limit exceeded!")."""
    from urdftool.kinematics.tree import beside_the_tree

    dropped = set(beside_the_tree(robot))
    for link in list(root.iterchildren("link")):
        if link.get("name") is None:
            link.clear()
            link.set("name", "")
        elif link.get("name") in dropped:
            root.remove(link)
    for joint in list(root.iterchildren("joint")) if dropped else ():
        ends = [joint.find(side) for side in ("parent", "child")]
        if any(end is not None and end.get("link") in dropped for end in ends):
            root.remove(joint)


def _yourdfpy(robot, collision: bool):
    """yourdfpy's model of ``robot`` from its expanded URDF text, meshes not loaded; SceneError
    (with the element when known) for what yourdfpy cannot read."""
    import yourdfpy
    from lxml import etree

    from urdftool.errors import FKError
    from urdftool.kinematics.fk import placed_within

    try:  # (a joint at 1e200: numpy's warnings, the picture NaN)
        placed_within(robot)
    except FKError as error:
        raise SceneError(str(error), error.element) from None
    logging.getLogger("yourdfpy").setLevel(logging.CRITICAL)  # its warnings are rule findings
    parser = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                             remove_comments=True, remove_blank_text=True)
    root = etree.fromstring(robot.urdf.encode("utf-8"), parser)
    _follow_variables(robot, root)
    _as_urdfdom_reads(robot, root)
    try:
        model = yourdfpy.URDF._parse_robot(root)
        _unit_axes(robot, model)
        urdf = yourdfpy.URDF(model, build_scene_graph=False, build_collision_scene_graph=False,
                             load_meshes=False, load_collision_meshes=False,
                             filename_handler=lambda fname: _contained(robot, fname))
        urdf._base_link = urdf._determine_base_link()
        if collision:
            urdf._scene_collision = _scene_graph(urdf, collision)
        else:
            urdf._scene = _scene_graph(urdf, collision)
        return urdf
    except SceneError:
        raise
    except KeyError as error:  # yourdfpy reads required attributes as attrib[name]
        raise SceneError(f"yourdfpy cannot build the scene: an element lacks its "
                         f"'{error.args[0]}' attribute; run 'urdftool check' for where") from None
    except Exception as error:  # yourdfpy raises what its parsing meets (ValueError, ...)
        raise SceneError(f"yourdfpy cannot build the scene ({described(error)}); "
                         "run 'urdftool check' for the cause") from None


def _unit_axes(robot, model) -> None:
    """Each moving joint's axis in yourdfpy's ``model`` as
    :func:`urdftool.kinematics.fk.unit_axis` reads it (the one reading of an axis): yourdfpy
    rotated about the axis as written, so a child on ``0 0 0`` or ``1e-320 0 0`` was posed at
    NaN (drawn nowhere, numpy's warnings) and one on ``1e308 1e308 1e308`` overflowed.
    SceneError at the joint for an axis with no direction."""
    from urdftool.errors import FKError
    from urdftool.kinematics.fk import unit_axis

    for joint in model.joints:
        element = robot.joints.get(joint.name)
        if joint.type in MOVING and element is not None:
            try:
                joint.axis = unit_axis(element)
            except FKError as error:
                raise SceneError(str(error), error.element) from None


def _scene_graph(urdf, collision: bool):
    """The trimesh scene yourdfpy's ``_create_scene`` makes (a node per link, joints as edges,
    each link's boxes, cylinders and spheres hung from it; for collision geometry, each link's
    concatenated into one), built in time linear in the links: yourdfpy asks the scene's
    ``graph.nodes`` once per link, which trimesh computes again after every update from a hash
    of the whole graph (86 of 93 s on 2,000 links of two primitives each; 44 s for 4,000 links
    where 1,000 took 2), and names each geometry by trying ``name_0``, ``name_1``... past those
    taken (robots name every visual alike)."""
    import numpy as np
    import trimesh
    from yourdfpy.urdf import Visual, apply_visual_color

    scene = trimesh.scene.Scene(base_frame=urdf._base_link)
    nodes = {urdf._base_link}
    for joint in urdf.robot.joints:
        matrix, _ = urdf._forward_kinematics_joint(joint)
        scene.graph.update(frame_from=joint.parent, frame_to=joint.child, matrix=matrix)
        nodes.update((joint.parent, joint.child))
    for link in urdf.robot.links:  # not joined: hung from the base, as yourdfpy does
        if link.name not in nodes:
            scene.graph.update(frame_from=urdf._base_link, frame_to=link.name)
            nodes.add(link.name)
    counts: dict = {}

    def unique(name: str, taken) -> str:
        found = name
        while found in taken:
            counts[name] = counts.get(name, 0) + 1
            found = f"{name}_{counts[name]}"
        return found

    left_out = scene.metadata[LEFT_OUT] = []
    for link in urdf.robot.links:
        parts = []
        for shape in (link.collisions if collision else link.visuals):
            if shape.geometry is None:
                continue
            far = _too_far(shape)
            if far:  # (trimesh's primitive of it: numpy's overflow, NaN corners)
                left_out.append(f"link '{link.name}': its {far}; not drawn")
                continue
            made = urdf._geometry2trimeshscene(geometry=shape.geometry, load_file=False,
                                               force_mesh=collision, skip_materials=collision)
            if made is None:
                continue
            origin = shape.origin if shape.origin is not None else np.eye(4)
            for node in made.graph.nodes_geometry:
                transform, name = made.graph.get(node)
                geometry = made.geometry[name]
                if isinstance(shape, Visual):
                    apply_visual_color(geometry, shape, urdf._material_map)
                parts.append((shape.name, geometry, origin @ transform))
        if collision and parts:  # one geometry per link, as yourdfpy's force_mesh
            single = trimesh.Scene(base_frame=link.name)
            for name, geometry, transform in parts:
                single.add_geometry(geometry=geometry, geom_name=name,
                                    parent_node_name=link.name, transform=transform)
            parts = [(parts[0][0], single.dump(concatenate=True), np.eye(4))]
        for name, geometry, transform in parts:
            key = unique(name or f"geometry_{len(scene.geometry)}", scene.geometry)
            node = unique(key, nodes)
            nodes.add(node)
            scene.add_geometry(geometry=geometry, geom_name=key, node_name=node,
                               parent_node_name=link.name, transform=transform)
    return scene


def _too_far(shape) -> str | None:
    """:func:`urdftool.kinematics.transforms.too_far` of a box, cylinder or sphere of
    yourdfpy's (a mesh's is asked when it is loaded: :meth:`SceneModel._add_meshes`), with
    what it is."""
    import numpy as np

    from urdftool.kinematics import transforms

    geometry = shape.geometry
    if geometry.box is not None:
        kind, half = "box", np.asarray(geometry.box.size, dtype=float) / 2
    elif geometry.cylinder is not None:
        kind, half = "cylinder", np.array([geometry.cylinder.radius, geometry.cylinder.radius,
                                           geometry.cylinder.length / 2], dtype=float)
    elif geometry.sphere is not None:
        kind, half = "sphere", np.full(3, float(geometry.sphere.radius))
    else:
        return None
    far = transforms.too_far(shape.origin if shape.origin is not None else np.eye(4), -half,
                             half)
    return f"{kind} {far}" if far else None


def _follow_variables(robot, root) -> None:
    """Point each ``<mimic>`` of ``root`` (the expanded URDF's tree given to yourdfpy) at the
    variable it follows in the end, with the chain's multiplier and offset: yourdfpy follows one
    step only, and posed a mimic of a mimic (28 virtual joints of the qb SoftHand in the sweep)
    at its offset whatever its source's value ("not actuated - will assume 0"). SceneError at
    the joint for a moving one that has no value (a mimic cycle, a mimic of an unknown joint),
    as fk refuses it: yourdfpy drew a cycle at 0 and followed an unknown joint as 0, exit 0."""
    from urdftool.errors import ConfigError, MimicError
    from urdftool.kinematics.configuration import mimic_source, variables_of

    names = {variable.name for variable in variables_of(robot)}
    known: dict = {}
    for joint in root.iterchildren("joint"):
        mimic = joint.find("mimic")
        if mimic is None:
            continue
        try:
            variable, multiplier, offset = mimic_source(robot, joint.get("name"), names,
                                                        known=known)
        except (ConfigError, MimicError) as error:  # a cycle, an unknown joint
            if joint.get("type") == "fixed":  # (its value moves nothing)
                continue
            raise SceneError(str(error), error.element if isinstance(error, MimicError)
                             else robot.joints.get(joint.get("name"))) from None
        mimic.set("joint", variable)
        mimic.set("multiplier", repr(multiplier))
        mimic.set("offset", repr(offset))


def _contained(robot, fname: str) -> str:
    """yourdfpy's filename handler: the path urdftool's resolver allows, else '' (no file)."""
    from urdftool.description.meshes import resolve

    try:
        return str(resolve(robot, fname))
    except MeshProblem:
        return ""


# Triangles trimesh makes of each primitive yourdfpy draws (trimesh 4: a Box's 12, a Sphere's
# icosphere of 3 subdivisions, a Cylinder's 32 sections: sides and caps)
PRIMITIVE_TRIANGLES = {"box": 12, "sphere": 1280, "cylinder": 128}


def described_triangles(robot, collision: bool = False) -> int:
    """The triangles of the robot's visual (or collision) geometry as its description says,
    before any scene is built: each primitive as trimesh makes it, each mesh as its file
    counts them (read without building the mesh; a mesh that cannot be drawn or counted so
    adds none, :meth:`SceneModel.pose` counts it once built). A mesh the scene leaves out adds
    none either: a Git LFS pointer (its text read as a binary STL's header is a billion
    triangles: the Ruiyan hand's 17.9 G refused), one over the per-mesh limits."""
    from urdftool.description.xml import first_child

    counts: dict = {}
    total = 0
    for element in robot.root.iterchildren("link"):
        for shape in element.iterchildren("collision" if collision else "visual"):
            geometry = first_child(shape, "geometry")
            if geometry is None:
                continue
            for child in geometry.iterchildren():
                if child.tag in PRIMITIVE_TRIANGLES:
                    total += PRIMITIVE_TRIANGLES[child.tag]
                elif child.tag == "mesh":
                    uri = child.get("filename") or ""
                    if uri not in counts:
                        counts[uri] = _mesh_triangles(robot, uri)
                    total += counts[uri]
                else:
                    continue
                break  # yourdfpy draws a geometry's first shape
    return total


def _mesh_triangles(robot, uri: str) -> int:
    """The triangles of the mesh at ``uri`` as its file counts them; 0 for one that
    :func:`~urdftool.description.meshes.load_mesh` refuses before reading it (its limits,
    checked in the bytes: a Git LFS pointer, too many bytes or triangles), which the scene
    leaves out, or that cannot be counted so."""
    from urdftool.description.files import read_regular
    from urdftool.description.meshes import resolve, triangle_count
    from urdftool.description.meshes.reading import check_size

    limits = robot.mesh_limits
    try:
        path = resolve(robot, uri)
        data = read_regular(path, limits.max_bytes + 1, as_="mesh")
        check_size(path, uri, limits, data, count=False)
        count = triangle_count(path, data) or 0
    except (MeshProblem, OSError):
        return 0
    return count if count <= limits.max_triangles else 0


def scene_model(robot, collision: bool = False,
                max_triangles: int | None = None) -> SceneModel:
    """The robot's scene model, built once per robot and kind of geometry; OverLimit before
    it is built when its description holds more than ``max_triangles`` (None: no limit):
    building a scene of 20,000 spheres (25 M triangles) took past the time budget."""
    refuse_over(robot, collision, max_triangles)
    return robot.memo((scene_model, collision), lambda: SceneModel(robot, collision))


def refuse_over(robot, collision: bool, max_triangles: int | None) -> None:
    """OverLimit when the robot's description (:func:`described_triangles`) holds more than
    ``max_triangles`` (None: no limit)."""
    if max_triangles is None:
        return
    count = robot.memo((described_triangles, collision),
                       lambda: described_triangles(robot, collision))
    if count > max_triangles:
        from urdftool.errors import OverLimit

        raise OverLimit("the robot's geometry, every instance of a mesh counted",
                        count, max_triangles, "triangles")


def posed(robot, words: dict[str, str] | None = None, degrees: bool = False,
          collision: bool = False, max_triangles: int | None = MAX_SCENE_TRIANGLES):
    """(PosedScene, warnings) of ``robot`` at ``words`` ({joint: text}) over the default
    configuration; ConfigError for a bad joint name or value, OverLimit for a scene over
    ``max_triangles`` (see :meth:`SceneModel.pose`)."""
    from urdftool.kinematics import configuration as config

    model = scene_model(robot, collision, max_triangles)
    chosen = config.from_words(model.all_variables, words or {}, degrees, model.mimics)
    q = {v.name: float(x) for v, x in zip(model.all_variables, chosen.values[0])}
    return model.pose(q, max_triangles), chosen.warnings


def _placements(graph):
    """A node of a trimesh scene graph -> its transform from the base frame, each composed once
    from its parent's: trimesh's ``graph.get`` walks the whole path from the base for every
    node, so a chain of 3,000 links took minutes (quadratic; stopped by the time budget). A
    node whose parents do not lead to the base (a loop, none) is left to ``graph.get``."""
    import numpy as np

    forest = graph.transforms
    placed = {graph.base_frame: np.eye(4)}

    def of(node):
        chain, seen = [], set()
        while node not in placed:
            parent = forest.parents.get(node)
            if parent is None or node in seen:
                return graph.get(chain[0] if chain else node)[0]
            seen.add(node)
            chain.append(node)
            node = parent
        for child in reversed(chain):
            parent = forest.parents[child]
            matrix = forest.edge_data[(parent, child)].get("matrix")
            placed[child] = placed[parent] if matrix is None else placed[parent] @ matrix
        return placed[chain[0] if chain else node]

    return of
