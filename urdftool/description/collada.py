"""COLLADA (.dae) geometry read with lxml and numpy: no trimesh, no pycollada.

:func:`read_collada` returns the triangles trimesh makes of a COLLADA file
(``trimesh.load(path, force="mesh")``), in the frame of the file's scene and in the file's own
length unit, so that a check that needs a size, a bounding box, a volume or a triangle count
need not import trimesh (0.5-1 s with scipy and networkx) to get them:

- the scene is the ``<visual_scene>`` that ``<scene><instance_visual_scene>`` names, else the
  first one; every ``<instance_geometry>`` reached from its ``<node>``\\ s, through nested
  nodes and ``<instance_node>``, is placed by the transforms of the nodes above it;
- a node's ``<matrix>``, ``<translate>``, ``<rotate>`` and ``<scale>`` compose in document
  order; ``<lookat>`` as the COLLADA specification and assimp (RViz, Gazebo) read it;
  ``<skew>`` is ignored, as pycollada and assimp ignore it;
- ``<triangles>``, ``<polylist>`` and ``<polygons>`` (fan-triangulated from each polygon's
  first corner, as pycollada does; holes, ``<ph>``, are ignored as pycollada ignores them) give
  triangles; lines, strips, fans and skin controllers give none, as in trimesh;
- numbers are rounded to float32 as pycollada reads them, and a node's transforms are
  composed in float32 as pycollada composes them, so the result equals trimesh's;
- a placement within 1e-8 of the identity is the identity, and one within 1e-5 of a rotation
  is made that rotation (by SVD), as trimesh's scene graph makes them;
- a transform that mirrors reverses the corners of its triangles, as trimesh does.

The ``<unit meter>`` is not applied: :func:`urdftool.description.meshes.collada_unit` owns that
rule and its caller scales the result, as it scales trimesh's.

The input is untrusted: anything malformed (a reference to nothing, an index out of range, a
count that does not match, a number that is not finite) raises :class:`ColladaProblem`, and
the triangle limit is checked before the triangles are built, so memory stays bounded by the
size of the file plus the limit.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

_PRIMITIVES = ("triangles", "polylist", "polygons")
_TRANSFORMS = ("matrix", "translate", "rotate", "scale", "lookat")
MAX_NODE_VISITS = 100_000  # node instances walked in one scene: a crafted file may nest many
MAX_NODE_DEPTH = 256  # <instance_node> nesting, as deep as libxml2 nests elements


@dataclass
class ColladaProblem(Exception):
    """Why a COLLADA document gives no triangles: ``kind`` is 'corrupt' or 'too-large' (the
    kinds of :class:`urdftool.errors.MeshProblem`); ``message`` says what is wrong;
    ``not_well_formed`` when the XML itself is broken (a caller may read what libxml2's
    recover mode makes of it, as viewers do); ``not_finite`` when a number the geometry uses is
    not finite (a caller may let trimesh read the file, and say so)."""

    kind: str
    message: str
    not_well_formed: bool = False
    not_finite: bool = False

    def __str__(self) -> str:
        return self.message


def _corrupt(message: str) -> ColladaProblem:
    return ColladaProblem("corrupt", message)


def parser(recover: bool = False):
    """The lxml parser for COLLADA: no entities expanded, no DTD, no network. Text nodes over
    10 MB are read, as pycollada reads them (a float array of a large mesh is one): the
    caller bounds the document's size. ``recover``: libxml2's recover mode, which reads what
    it can of XML that is not well-formed."""
    from lxml import etree

    return etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False,
                           huge_tree=True, recover=recover)


def tag(element) -> str:
    """An element's tag without its namespace; "" for comments and processing instructions."""
    return element.tag.rpartition("}")[2] if isinstance(element.tag, str) else ""


def _children(element, name: str) -> list:
    """The child elements named ``name`` in any namespace or none (lxml's "{*}" filter, in C:
    each ``.tag`` read in Python builds a string)."""
    return list(element.iterchildren("{*}" + name))


def _child(element, name: str):
    return next(element.iterchildren("{*}" + name), None)


def _numbers(element, dtype, what: str, text: str | None = None):
    """The whitespace-separated numbers of ``element``'s text (``text`` when it was read
    already) as a numpy array."""
    import numpy as np

    if text is None:
        text = element.text or ""
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # numpy warns, and stops, at text that is no number
        try:
            return np.fromstring(text, dtype=dtype, sep=" ") if text and not text.isspace() \
                else np.zeros(0, dtype=dtype)
        except (ValueError, DeprecationWarning, RuntimeWarning, OverflowError):
            raise _corrupt(f"{what} (line {element.sourceline}) holds text that is not a "
                           f"list of {'integers' if dtype == 'int64' else 'numbers'}") from None


def _floats32(element, what: str, count: int | None = None):
    """Floats rounded to float32 as pycollada reads them, returned as float64."""
    import numpy as np

    values = _numbers(element, "float64", what)
    if count is not None and len(values) != count:
        raise _corrupt(f"{what} (line {element.sourceline}) holds {len(values)} numbers, "
                       f"expected {count}")
    with np.errstate(over="ignore"):
        return values.astype(np.float32)


def _whole_numbers(element, what: str, stride: int = 1, offset: int = 0):
    """(how many whole numbers ``element``'s text holds, the int64 array of those at
    ``offset``, ``offset + stride``, ...: a ``<p>``'s column of one input), read in bulk when
    the text is long and plain (:mod:`urdftool.description.number_lists`); the column is
    whole only when the count is a multiple of ``stride``."""
    import numpy as np

    from urdftool.description import number_lists

    text = element.text or ""
    if len(text) >= number_lists.BULK:
        found = number_lists.whole_numbers(text, stride, offset)
        if found is not None:
            return found
    numbers = _numbers(element, "int64", what, text)
    return len(numbers), numbers if stride == 1 else np.ascontiguousarray(numbers[offset::stride])


def _joined(indices: list):
    """The index arrays of a primitive's ``<p>`` elements end to end: a new array (the one
    array itself when there is one: each is read for this primitive alone)."""
    import numpy as np

    if len(indices) == 1:
        return indices[0]
    return np.concatenate(indices) if indices else np.zeros(0, dtype=np.int64)


def _int_attribute(element, name: str, default: int | None = None) -> int:
    value = element.get(name)
    if value is None and default is not None:
        return default
    try:
        number = int(value)
    except (TypeError, ValueError):
        raise _corrupt(f"<{tag(element)}> (line {element.sourceline}) has {name}="
                       f"{value!r}, not a whole number") from None
    if number < 0:
        raise _corrupt(f"<{tag(element)}> (line {element.sourceline}) has a negative {name}")
    return number


def _transform(element):
    """The 4x4 float32 matrix of one ``<matrix>``/``<translate>``/... element, as pycollada
    makes it (``<lookat>`` as the specification and assimp make it)."""
    import numpy as np

    kind = tag(element)
    sizes = {"matrix": 16, "translate": 3, "rotate": 4, "scale": 3, "lookat": 9}
    values = _floats32(element, f"<{kind}>", sizes[kind])
    if not np.all(np.isfinite(values)):
        raise ColladaProblem("corrupt", f"<{kind}> (line {element.sourceline}) holds a number "
                             "that is not finite", not_finite=True)
    matrix = np.identity(4, dtype=np.float32)
    if kind == "matrix":
        matrix = values.reshape(4, 4)
    elif kind == "translate":
        matrix[:3, 3] = values
    elif kind == "scale":
        matrix[0, 0], matrix[1, 1], matrix[2, 2] = values
    elif kind == "rotate":  # pycollada's makeRotationMatrix: the axis is taken as it is
        x, y, z, angle = values
        angle = angle * np.pi / 180.0
        c, s = np.cos(angle), np.sin(angle)
        t = 1 - c
        matrix = np.array([[t * x * x + c, t * x * y - s * z, t * x * z + s * y, 0],
                           [t * x * y + s * z, t * y * y + c, t * y * z - s * x, 0],
                           [t * x * z - s * y, t * y * z + s * x, t * z * z + c, 0],
                           [0, 0, 0, 1]], dtype=np.float32)
    else:  # lookat: eye, interest, up; the node looks down its -Z axis at the interest
        eye, interest, up = values[:3].astype(float), values[3:6].astype(float), \
            values[6:].astype(float)
        from urdftool.numbers import unit

        # each direction scaled before it is normalised: 1e308 apart is a direction
        direction, up = unit(interest - eye), unit(up)
        side = unit(np.cross(direction, up)) if direction is not None and up is not None else None
        if side is None:
            raise _corrupt(f"<lookat> (line {element.sourceline}) has no direction: its eye, "
                           "interest and up vector are degenerate")
        direction, side, up = (np.array(v) for v in (direction, side, up))
        matrix[:3, 0], matrix[:3, 1], matrix[:3, 2], matrix[:3, 3] = side, up, -direction, eye
    return matrix


def _node_matrix(node):
    """A node's own transforms composed in document order, in float32 as pycollada does."""
    import numpy as np

    transforms = [_transform(child) for child in node if tag(child) in _TRANSFORMS]
    if not transforms:
        return np.identity(4, dtype=np.float32)
    matrix = transforms[0]
    if len(transforms) > 1:
        matrix = np.identity(4, dtype=np.float32)
        for transform in transforms:
            matrix = np.dot(matrix, transform)
    return matrix


def _placement(matrix):
    """A node's world matrix as trimesh's scene graph places geometry with it: the identity
    when within 1e-8 of it, the nearest rotation when within 1e-5 of being rigid
    (``trimesh.transformations.fix_rigid``), else the matrix itself."""
    import numpy as np

    identity = np.identity(4)
    if np.abs(matrix - identity).max() <= 1e-8:
        return identity
    rotation = matrix[:3, :3]
    deviance = np.abs(np.dot(rotation, rotation.T) - identity[:3, :3]).max()
    if 1e-13 < deviance < 1e-5:
        u, _, v = np.linalg.svd(rotation)
        repaired = np.identity(4)
        repaired[:3, :3] = np.dot(u, v)
        repaired[:3, 3] = matrix[:3, 3]
        return repaired
    return matrix


class _Document:
    """One parsed COLLADA document: its elements by id and its geometries read once."""

    def __init__(self, root, max_triangles: int):
        self.ids = {}
        for element in root.xpath("//*[@id]"):  # elements, in document order: the first wins
            self.ids.setdefault(element.get("id"), element)
        self.max_triangles = max_triangles
        self.geometries = {}
        self.positions = {}

    def target(self, element, kinds: tuple[str, ...]):
        """The element a ``url``/``source`` attribute ("#id") of ``element`` names."""
        url = element.get("url", element.get("source"))
        found = self.ids.get(url[1:]) if url and url.startswith("#") else None
        if found is None or tag(found) not in kinds:
            raise _corrupt(f"<{tag(element)}> (line {element.sourceline}) names {url!r}, "
                           f"which is no <{'> or <'.join(kinds)}> of this file")
        return found

    def geometry(self, element) -> list:
        """[(positions (n, 3), triangles (m, 3))] of one ``<geometry>``, one per primitive,
        each holding only the positions its triangles use."""
        if element not in self.geometries:
            mesh = _child(element, "mesh")
            pieces = []
            if mesh is not None:
                local = {e.get("id"): e for e in mesh if e.get("id") is not None}
                total = 0
                for primitive in mesh:
                    if tag(primitive) in _PRIMITIVES:
                        piece = self._primitive(primitive, local, total)
                        total += len(piece[1])
                        if len(piece[1]):
                            pieces.append(piece)
            self.geometries[element] = pieces
        return self.geometries[element]

    def _source(self, element, local: dict, semantic: str, kind: str):
        url = element.get("source") or ""
        found = local.get(url[1:]) if url.startswith("#") else None
        if found is None or tag(found) != kind:
            raise _corrupt(f"<input semantic=\"{semantic}\"> (line {element.sourceline}) names "
                           f"{url!r}, which is no <{kind}> of its <mesh>")
        return found

    def _positions(self, vertices, local: dict):
        """The (n, 3) float32 positions of a ``<vertices>`` element's POSITION input."""
        position = next((i for i in _children(vertices, "input")
                         if i.get("semantic") == "POSITION"), None)
        if position is None:
            raise _corrupt(f"<vertices> (line {vertices.sourceline}) has no POSITION input")
        source = self._source(position, local, "POSITION", "source")
        array = _child(source, "float_array")
        common = _child(source, "technique_common")
        accessor = None if common is None else _child(common, "accessor")
        if array is None or accessor is None:
            raise _corrupt(f"<source id=\"{source.get('id')}\"> (line {source.sourceline}) "
                           "has no <float_array> or no <accessor>")
        declared = array.get("count")
        values = _floats32(array, "<float_array>", None if declared is None else
                           _int_attribute(array, "count"))
        params = len(_children(accessor, "param"))
        stride = _int_attribute(accessor, "stride", params or 1)
        if params < 3 or stride < 3 or len(values) % stride:
            raise _corrupt(f"<source id=\"{source.get('id')}\"> (line {source.sourceline}) "
                           f"is no list of X Y Z positions: {len(values)} numbers in "
                           f"groups of {stride} with {params} parameters")
        return values.reshape(-1, stride)[:, :3]

    def _primitive(self, primitive, local: dict, before: int):
        import numpy as np

        kind, line = tag(primitive), primitive.sourceline
        inputs = _children(primitive, "input")
        offsets = [_int_attribute(i, "offset") for i in inputs]
        vertex = [(i, o) for i, o in zip(inputs, offsets) if i.get("semantic") == "VERTEX"]
        if not vertex:
            raise _corrupt(f"<{kind}> (line {line}) has no VERTEX input")
        stride = max(offsets) + 1
        vertices = self._source(vertex[0][0], local, "VERTEX", "vertices")
        offset = vertex[0][1]
        blocks = _children(primitive, "p")
        if kind == "polylist":
            blocks = blocks[:1]  # pycollada reads the first; a polylist has one
        # each <p>'s count of indices, and its VERTEX column (the other inputs are not used)
        columns = [_whole_numbers(p, f"<{kind}><p>", stride, offset) for p in blocks]
        for count, _ in columns:
            if count % stride:
                raise _corrupt(f"<{kind}> (line {line}) has {count} indices in <p>, not a "
                               f"multiple of its {stride} inputs")
        held = sum(count for count, _ in columns)  # indices of every input
        corners = _joined([column for _, column in columns])
        if kind == "triangles":
            counts = None
            if held % (3 * stride):
                raise _corrupt(f"<triangles> (line {line}) has {held} indices, not "
                               f"three corners of {stride} inputs each")
        elif kind == "polylist":
            vcount = _child(primitive, "vcount")
            if vcount is None:
                raise _corrupt(f"<polylist> (line {line}) has no <vcount>")
            counts = _whole_numbers(vcount, "<polylist><vcount>")[1]
            if np.any(counts < 0) or np.any(counts > held // stride) or \
                    int(counts.sum()) * stride != held:
                raise _corrupt(f"<polylist> (line {line}): <vcount> counts {int(counts.sum())} "
                               f"corners, <p> holds {held // stride}")
        else:
            counts = np.array([count // stride for count, _ in columns], dtype=np.int64)
        triangles = held // (3 * stride) if counts is None else \
            int(np.maximum(counts - 2, 0).sum())
        declared = primitive.get("count")
        expected = held // (3 * stride) if kind == "triangles" else len(counts)
        if declared is not None and _int_attribute(primitive, "count") != expected:
            raise _corrupt(f"<{kind}> (line {line}) has count=\"{declared}\" but holds "
                           f"{expected} {'triangles' if kind == 'triangles' else 'polygons'}")
        if before + triangles > self.max_triangles:
            raise ColladaProblem("too-large", f"a geometry has over {self.max_triangles} "
                                              "triangles")
        if counts is not None and len(counts) and counts.min() == counts.max() == 3:
            counts = None  # triangles only: each its own fan
        if counts is not None:  # fans: (first, j, j + 1) for each polygon of k >= 3 corners
            fans = np.maximum(counts - 2, 0)
            first = np.repeat(np.cumsum(counts) - counts, fans)
            step = np.arange(triangles) - np.repeat(np.cumsum(fans) - fans, fans) + 1
            corners = np.stack([corners[first], corners[first + step],
                                corners[first + step + 1]], axis=1).ravel()
        if vertices not in self.positions:
            self.positions[vertices] = self._positions(vertices, local)
        positions = self.positions[vertices]
        if len(corners) and (corners.min() < 0 or corners.max() >= len(positions)):
            raise _corrupt(f"<{kind}> (line {line}) has a vertex index out of range: "
                           f"{int(corners.min())}..{int(corners.max())}, but its positions "
                           f"number {len(positions)}")
        used = np.zeros(len(positions), dtype=bool)
        used[corners] = True
        if used.all():  # the common case: no renumbering (corners is this primitive's own)
            kept = positions.astype(np.float64)
        else:
            kept, corners = positions[used].astype(np.float64), (np.cumsum(used) - 1)[corners]
        if not np.all(np.isfinite(kept)):
            raise ColladaProblem("corrupt", f"<{kind}> (line {line}) uses a position that is not "
                                 "finite", not_finite=True)
        return kept, corners.reshape(-1, 3)

    def instances(self, scene) -> list:
        """[(world matrix (4, 4) float64, <geometry>)] of every geometry the scene places."""
        import numpy as np

        placed = []
        visits = [0]
        triangles = [0]

        def walk(node, parent, depth: int, active: tuple) -> None:
            visits[0] += 1
            if visits[0] > MAX_NODE_VISITS or depth > MAX_NODE_DEPTH:
                raise ColladaProblem("too-large", f"the scene instances over {MAX_NODE_VISITS} "
                                                  f"nodes or nests them over {MAX_NODE_DEPTH} "
                                                  "deep")
            with np.errstate(all="ignore"):
                matrix = np.dot(parent, _node_matrix(node))
            if not np.all(np.isfinite(matrix)):
                raise _corrupt(f"<node> (line {node.sourceline}): its transforms compose "
                               "beyond floating point range")
            for child in node:
                kind = tag(child)
                if kind == "instance_geometry":
                    geometry = self.target(child, ("geometry",))
                    triangles[0] += sum(len(faces) for _, faces in self.geometry(geometry))
                    if triangles[0] > self.max_triangles:
                        raise ColladaProblem("too-large", f"the scene has over "
                                                          f"{self.max_triangles} triangles")
                    placed.append((_placement(matrix), geometry))
                elif kind in ("node", "instance_node"):
                    target = child if kind == "node" else self.target(child, ("node",))
                    if target in active:
                        raise _corrupt(f"<instance_node> (line {child.sourceline}) instances a "
                                       "node that contains it")
                    walk(target, matrix, depth + 1, (*active, target))

        identity = np.identity(4)
        for top in _children(scene, "node"):
            walk(top, identity, 0, (top,))
        return placed


def _scene(root, document: _Document):
    """The visual scene the document shows: the one <scene> names, else the first."""
    for scene in _children(root, "scene"):
        for instance in _children(scene, "instance_visual_scene"):
            return document.target(instance, ("visual_scene",))
    for library in _children(root, "library_visual_scenes"):
        for scene in _children(library, "visual_scene"):
            return scene
    raise _corrupt("the file has no <visual_scene>")


def read_collada(data: bytes, *, max_triangles: int):
    """(vertices (n, 3) float64, faces (m, 3) int64) of a COLLADA document, in its scene's
    frame and its own unit (see the module docstring); raises :class:`ColladaProblem` when it
    is malformed or holds over ``max_triangles`` triangles."""
    import numpy as np
    from lxml import etree

    try:
        root = etree.fromstring(data, parser())
    except (etree.LxmlError, ValueError) as error:
        raise ColladaProblem("corrupt", f"not well-formed XML: {error}", True) from None
    if root is None or tag(root) != "COLLADA":
        raise _corrupt(f"the root element is <{tag(root) if root is not None else ''}>, "
                       "not <COLLADA>")
    entity = next(root.iter(etree.Entity), None)
    if entity is not None:
        raise _corrupt(f"entity reference {entity.text} (line {entity.sourceline}): entities "
                       "are not expanded, so the numbers it stands for cannot be read")
    document = _Document(root, max_triangles)
    try:
        placed = document.instances(_scene(root, document))
    except RecursionError:
        raise ColladaProblem("too-large", "the scene nests nodes too deep") from None
    vertices, faces, count = [], [], 0
    identity = np.identity(4)
    for matrix, geometry in placed:
        flips = np.linalg.det(matrix[:3, :3]) < 0
        # placed where it is (the common case): the product below gives each finite
        # coordinate itself, and +0.0 for a zero of either sign, as adding +0.0 does
        kept = np.array_equal(matrix, identity)
        for positions, triangles in document.geometry(geometry):
            with np.errstate(over="ignore", invalid="ignore"):
                moved = positions + 0.0 if kept else \
                    np.dot(positions, matrix[:3, :3].T) + matrix[:3, 3]
            vertices.append(moved)
            faces.append((triangles[:, ::-1] if flips else triangles) + count)
            count += len(positions)
    if not vertices:
        return np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64)
    vertices = np.concatenate(vertices)
    if not np.all(np.isfinite(vertices)):
        raise _corrupt("a transform moves a vertex beyond floating point range")
    return vertices, np.concatenate(faces)
