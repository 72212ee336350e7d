"""Triangle counts of mesh files, read before anything builds the mesh.

The count is read from the header where the format has one (binary STL, PLY, OFF), else
counted over the file in chunks: an OBJ or PLY face of k corners is k - 2 triangles; a COLLADA
or glTF mesh counts once per instance in its scene. So a crafted file cannot exhaust memory:
the limits are checked on the count (:func:`urdftool.description.meshes.reading`).
"""

from __future__ import annotations

import io
import re
import struct
from pathlib import Path

from urdftool.description.collada import parser, tag
from urdftool.description.files import read_regular
from urdftool.description.inputs import MAX_MESH_BYTES
from urdftool.numbers import is_decimal

_CHUNK = 1 << 20
# OBJ face corners are counted over bytes, so that no text decoding trimesh may choose finds
# more: a run of printable ASCII is at most one corner, any other byte that is not ASCII
# white space at most one more (a separator in some encoding, or a corner of its own)
_CORNER_CLASSES = bytes.maketrans(bytes(range(256)), bytes(
    10 if b == 10 else 32 if b in b" \t\r\x0b\x0c" else 112 if 0x21 <= b <= 0x7E else 111
    for b in range(256)))  # newline stays, white space -> " ", printable -> "p", other -> "o"
_FACE_LINE = re.compile(rb"^[ \t]*f([^\n]*)", re.MULTILINE)  # line ends: trimesh's (LF; CR LF joined)


def _chunks(handle):
    while chunk := handle.read(_CHUNK):
        yield chunk


def _logical_chunks(handle):
    """The file in chunks with trimesh's line joining applied (``\\r\\n`` as ``\\n``, a
    backslash before a newline joins the lines), whatever the chunk boundaries."""
    pending = b""
    for chunk in _chunks(handle):
        data = (pending + chunk).replace(b"\r\n", b"\n").replace(b"\\\n", b"")
        keep = 2 if data.endswith(b"\\\r") else 1 if data.endswith((b"\\", b"\r")) else 0
        data, pending = data[:len(data) - keep], data[len(data) - keep:]
        yield data
    if pending:
        yield pending


def _corners(text: bytes) -> bytes:
    """``text`` (face lines without their ``f``) with one byte per corner; lines kept."""
    classes = text.translate(_CORNER_CLASSES)
    while b"pp" in classes:  # each pass halves the printable runs
        classes = classes.replace(b"pp", b"p")
    return classes.replace(b" ", b"")


def _fan_triangles(faces: list[bytes]) -> int:
    """Sum of max(k - 2, 0) over faces of k corners, in C: a face of one corner or none
    makes no triangle (and must not cancel the triangles of others)."""
    if not faces:
        return 0
    corners = _corners(b"\n".join(faces))
    marked = b"[" + corners.replace(b"\n", b"]\n[") + b"]"
    return (len(corners) - (len(faces) - 1) - 2 * len(faces) + 2 * marked.count(b"[]")
            + marked.count(b"[p]") + marked.count(b"[o]"))


def _obj_triangles(handle) -> int:
    """Triangles that trimesh would make of an OBJ's ``f`` lines, counted without building
    them: a face with k corners is k - 2 triangles (a fan). Every line that starts with ``f``
    counts, whatever separates its corners (spaces, tabs, anything else) and however many
    backslash continuations join it; memory stays near one chunk, time linear in C."""
    triangles = 0
    face, corners, joined = None, 0, False  # the line that runs over a chunk boundary
    for data in _logical_chunks(handle):
        head, newline, rest = data.partition(b"\n")
        middle, _, last = rest.rpartition(b"\n")
        for piece, ends in ((head, bool(newline)), (last, False)):
            if face is None and piece.lstrip(b" \t"):
                piece = piece.lstrip(b" \t")
                face = piece.startswith(b"f")
                piece = piece[1:] if face else piece
            if face and piece:  # a printable run split by the chunk boundary counts once
                classes = piece.translate(_CORNER_CLASSES)
                corners += len(_corners(piece)) - (joined and classes.startswith(b"p"))
                joined = classes.endswith(b"p")
            if ends:
                triangles += max(corners - 2, 0)
                face, corners, joined = None, 0, False
                triangles += _fan_triangles(_FACE_LINE.findall(middle))
            if not last:
                break
    return triangles + max(corners - 2, 0)


def _stl_ascii_triangles(handle) -> int:
    """Triangles of an ASCII STL as trimesh reads it: every ``vertex`` word, three a triangle."""
    words, tail = 0, b""
    for chunk in _chunks(handle):
        text = tail + chunk.lower()
        words += text.count(b"vertex")
        tail = text[-5:]  # a word split between chunks is counted in the next one
        words -= tail.count(b"vertex")
    return -(-(words + tail.count(b"vertex")) // 3)


_COLLADA_PRIMITIVES = ("triangles", "polylist", "polygons", "trifans", "tristrips")
_COLLADA_DEPTH = 200  # node nesting followed; deeper is refused as if over the limit


def _numbers(text: str | None) -> int:
    """How many numbers a COLLADA list holds, counted without splitting it."""
    return len(_corners(text.encode("utf-8", "replace")).replace(b"\n", b"")) if text else 0


def _primitive_triangles(primitive) -> int:
    """Triangles pycollada and trimesh make of one ``<triangles>``/``<polylist>``/... element:
    every ``<p>`` holds one index per input offset per corner; a polygon of k corners is k - 2."""
    offsets = [int(c.get("offset", "0")) for c in primitive  # (ASCII digits int() takes:
               # '²' is a digit to str.isdigit(), and past 4,300 digits int() refuses)
               if tag(c) == "input" and is_decimal(c.get("offset", "0"))
               and len(c.get("offset", "0")) <= 18]
    stride = max(offsets, default=0) + 1
    corners = [_numbers(c.text) // stride for c in primitive if tag(c) == "p"]
    kind = tag(primitive)
    if kind == "triangles":
        return sum(corners) // 3
    if kind == "polylist":
        polygons = sum(_numbers(c.text) for c in primitive if tag(c) == "vcount")
        return max(sum(corners) - 2 * polygons, 0)
    return sum(max(k - 2, 0) for k in corners)


def _collada_triangles(data: bytes) -> int | None:
    """Triangles of a COLLADA file as trimesh builds them: each geometry's triangles times
    the times the scenes instance it (through nested nodes, ``<instance_node>`` and skin
    controllers), so that a small file naming one mesh a million times is counted before
    it is built; a file that is not well-formed is counted as recovered. None when even
    recovery finds no document (trimesh then says why)."""
    root = _collada_root(data, recover=False)
    if root is None:
        root = _collada_root(data, recover=True)
    if root is None:
        return None
    ids = {element.get("id"): element for element in root.iter() if element.get("id")}
    geometry_triangles = {}

    def geometry(url: str | None) -> int:
        element = ids.get((url or "").lstrip("#"))
        if element is None:
            return 0
        kind = tag(element)
        if kind == "controller":  # a skin or morph deforms a geometry named by its source
            sources = [c.get("source") for c in element.iter("{*}skin", "{*}morph")]
            return sum(geometry(source) for source in sources if source != url)
        if kind != "geometry":
            return 0
        if element not in geometry_triangles:
            geometry_triangles[element] = sum(
                _primitive_triangles(p) for p in element.iter(
                    *(f"{{*}}{name}" for name in _COLLADA_PRIMITIVES)))
        return geometry_triangles[element]

    node_triangles = {}

    def node(element, depth: int) -> int:
        if depth > _COLLADA_DEPTH:
            return MAX_MESH_BYTES  # over any sensible limit
        if element not in node_triangles:
            node_triangles[element] = None  # a cycle counts as over the limit
            total = 0
            for child in element:
                kind = tag(child)
                if kind in ("instance_geometry", "instance_controller"):
                    total += geometry(child.get("url"))
                elif kind == "node":
                    total += node(child, depth + 1)
                elif kind == "instance_node":
                    target = ids.get((child.get("url") or "").lstrip("#"))
                    total += node(target, depth + 1) if target is not None else 0
            node_triangles[element] = total
        found = node_triangles[element]
        return MAX_MESH_BYTES if found is None else found

    try:
        return sum(node(top, 0) for scene in root.iter("{*}visual_scene")
                   for top in scene if tag(top) == "node")
    finally:  # node() and geometry() refer to themselves: free the tree before trimesh reads
        for table in (ids, geometry_triangles, node_triangles):
            table.clear()


def _collada_root(data: bytes, recover: bool):
    """The root element of a COLLADA document, or None when it does not parse (strictly, or
    even in libxml2's recover mode)."""
    from lxml import etree

    try:
        return etree.fromstring(data, parser(recover))
    except (etree.LxmlError, ValueError):
        return None


def gltf_header(path: Path, data: bytes) -> dict | None:
    """The JSON of a ``.gltf``, or of a ``.glb``'s first chunk; None when there is none."""
    import json

    if path.suffix.lower() == ".glb":
        head = data[:20]
        if len(head) < 20 or head[:4] != b"glTF" or head[16:20] != b"JSON":
            return None
        data = data[20:20 + struct.unpack("<I", head[12:16])[0]]
    try:
        header = json.loads(data)
    except (ValueError, RecursionError):
        return None
    return header if isinstance(header, dict) else None


def _listed(value) -> list:
    return value if isinstance(value, list) else []


def _entry(items, index) -> dict:
    ok = isinstance(index, int) and 0 <= index < len(_listed(items))
    return items[index] if ok and isinstance(items[index], dict) else {}


def gltf_scene_nodes(header: dict) -> list[tuple[int, dict, int]]:
    """(index, node, depth) of every node a glTF's scene reaches (its default scene, or the
    first), as trimesh builds the scene from them: each once, whatever names it again; a root
    node is at depth 1."""
    nodes = _listed(header.get("nodes"))
    scene = _entry(header.get("scenes"), header.get("scene", 0))
    seen, found = set(), []
    queue = [(index, 1) for index in _listed(scene.get("nodes"))]
    while queue:
        index, depth = queue.pop()
        if not isinstance(index, int) or index in seen or not 0 <= index < len(nodes):
            continue
        seen.add(index)
        node = _entry(nodes, index)
        found.append((index, node, depth))
        queue.extend((child, depth + 1) for child in _listed(node.get("children")))
    return found


MAX_PIECES = 10_000  # meshes trimesh builds one file from and joins (~0.1 ms each a load)
# an ASCII STL's solids cost more: parsed one by one, about a millisecond each (an OBJ's
# materials, which trimesh made a mesh of each, are read as one mesh: reading._without_materials)
MAX_TEXT_PIECES = 1_000


def scene_problem(path: Path, data: bytes) -> str | None:
    """Why trimesh is not to build a file's scene, or None, the one judge of how many meshes it
    makes of one file: a glTF's primitives, once for each node placing them
    (:data:`MAX_PIECES`); an ASCII STL's solids (:data:`MAX_TEXT_PIECES`: trimesh reads each
    ``solid ... endsolid`` as a mesh of its own: 20,000 took 21 s). An OBJ is one mesh to it:
    its materials are left out before it reads the file
    (:func:`~urdftool.description.meshes.reading._without_materials`). A
    glTF scene is held to a COLLADA scene's bounds too:
    :data:`~urdftool.description.collada.MAX_NODE_VISITS` nodes,
    :data:`~urdftool.description.collada.MAX_NODE_DEPTH` deep (trimesh walks a node's parents
    for each node: a 60 KB GLB of 20,000 nodes each the child of the one before took 4.7 s to
    load, three loads a check; a GLB of 99,000 nodes each placing a triangle took 34 s)."""
    suffix = path.suffix.lower()
    if suffix == ".stl":
        from urdftool.description.mesh_arrays import binary_stl

        if binary_stl(data):
            return None  # one mesh to trimesh, whatever its bytes spell
        solids = data.lower().count(b"endsolid")  # (as trimesh finds them, in any case)
        if solids > MAX_TEXT_PIECES:
            return (f"it holds {solids} solids (endsolid), each a mesh of its own to build and "
                    f"join, over {MAX_TEXT_PIECES}")
        return None
    if suffix not in (".glb", ".gltf"):
        return None
    from urdftool.description.collada import MAX_NODE_DEPTH, MAX_NODE_VISITS

    header = gltf_header(path, data)
    if header is None:
        return None
    found = gltf_scene_nodes(header)
    deepest = max((depth for _, _, depth in found), default=0)
    if len(found) > MAX_NODE_VISITS or deepest > MAX_NODE_DEPTH:
        return (f"its scene has {len(found)} nodes nested {deepest} deep, over "
                f"{MAX_NODE_VISITS} nodes or {MAX_NODE_DEPTH} deep")
    pieces = sum(len(_listed(_entry(header.get("meshes"), node["mesh"]).get("primitives")))
                 for _, node, _ in found if "mesh" in node)
    if pieces > MAX_PIECES:
        return (f"its nodes place {pieces} primitives, each a mesh of its own to build and "
                f"join, over {MAX_PIECES}")
    return None


def _gltf_triangles(path: Path, data: bytes) -> int | None:
    """Triangles of a glTF scene as trimesh builds it: every node the scene reaches adds its
    mesh's triangles (accessor counts), so a file naming one mesh from a million nodes is
    counted before it is built."""
    header = gltf_header(path, data)
    if header is None:
        return None

    def count(index) -> int:
        value = _entry(header.get("accessors"), index).get("count")
        return value if isinstance(value, int) and value > 0 else 0

    def mesh_triangles(mesh: dict) -> int:
        total = 0
        for primitive in _listed(mesh.get("primitives")):
            if not isinstance(primitive, dict):
                continue
            mode = primitive.get("mode", 4)
            attributes = primitive.get("attributes")
            corners = count(primitive["indices"]) if "indices" in primitive else \
                count(attributes.get("POSITION")) if isinstance(attributes, dict) else 0
            total += corners // 3 if mode == 4 else max(corners - 2, 0) if mode == 5 else 0
        return total

    return sum(mesh_triangles(_entry(header.get("meshes"), node["mesh"]))
               for _, node, _ in gltf_scene_nodes(header) if "mesh" in node)


_PLY_SIZES = {"char": 1, "int8": 1, "uchar": 1, "uint8": 1, "short": 2, "int16": 2,
              "ushort": 2, "uint16": 2, "int": 4, "int32": 4, "uint": 4, "uint32": 4,
              "float": 4, "float32": 4, "double": 8, "float64": 8}
_PLY_COUNTS = {1: "B", 2: "H", 4: "I", 8: "Q"}


def _ply_header(handle) -> tuple[str, list, int] | None:
    """(format, [(element, count, properties)], header size) of a PLY file; a property is a
    size, or (count size, item size) for a list."""
    header = handle.read(65536)
    end = header.find(b"end_header")
    if not header.startswith(b"ply") or end < 0:
        return None
    size = header.find(b"\n", end) + 1 or len(header)
    form, elements = "", []
    for line in header[:end].decode("ascii", "replace").splitlines():
        words = line.split()
        if words[:1] == ["format"] and len(words) > 1:
            form = words[1]
        elif words[:1] == ["element"] and len(words) == 3 and words[2].isdigit():
            elements.append((words[1], int(words[2]), []))
        elif words[:1] == ["property"] and elements and len(words) >= 3:
            sizes = [_PLY_SIZES.get(word) for word in words[2:4]]
            elements[-1][2].append(tuple(sizes) if words[1] == "list" else _PLY_SIZES.get(words[1]))
    return form, elements, size


def _tokens(handle) -> int:
    """How many white-space separated words the rest of a file holds, in chunks."""
    total, joined = 0, False
    for chunk in _chunks(handle):
        classes = chunk.translate(_CORNER_CLASSES)
        total += len(_corners(chunk).replace(b"\n", b"")) - (joined and classes.startswith(b"p"))
        joined = classes.endswith(b"p")
    return total


def _ply_triangles(handle) -> int | None:
    """Triangles trimesh makes of a PLY's faces: a face of k corners is k - 2 (a fan), so a
    face list of millions of corners counts as what it is. Binary: each face's corner count
    is read; ASCII: every number after the vertices is taken for a corner (an upper bound,
    exact for faces that hold only their corner list)."""
    parsed = _ply_header(handle)
    if parsed is None:
        return None
    form, elements, start = parsed
    names = [name for name, _, _ in elements]
    if "face" not in names:
        return 0
    before, (_, faces, properties) = elements[:names.index("face")], elements[names.index("face")]
    sizes = [size for _, _, props in elements[:names.index("face") + 1] for prop in props
             for size in (prop if isinstance(prop, tuple) else (prop,))]
    if None in sizes or not properties:
        return None  # an unknown type or a face of nothing: trimesh refuses it too
    handle.seek(start)
    if form == "ascii":
        words = sum(count * len(props) for _, count, props in before)  # lists: a lower bound
        return max(_tokens(handle) - words - 3 * faces, 0)
    if any(isinstance(prop, tuple) for _, _, props in before for prop in props):
        return None  # lists before the faces: where faces start is unknown; trimesh says
    handle.seek(start + sum(count * sum(props) for _, count, props in before))
    data = handle.read()
    if properties == [(properties[0][0], properties[0][1])] and \
            len(data) == faces * (properties[0][0] + 3 * properties[0][1]):
        return faces  # triangles only, nothing after them: the common case, without a walk
    order = "<" if form == "binary_little_endian" else ">"
    offset = total = 0
    for _ in range(faces):  # every face takes at least one byte: bounded by the file
        corners = None
        for prop in properties:
            if isinstance(prop, tuple):
                (count,) = struct.unpack_from(order + _PLY_COUNTS[prop[0]], data, offset)
                offset += prop[0] + count * prop[1]
                corners = count if corners is None else corners
            else:
                offset += prop
        total += max((corners or 0) - 2, 0)
    return total


def triangle_count(path: Path, data: bytes | None = None) -> int | None:
    """The triangle count of the mesh file ``path`` (``data``: its bytes, when read), read
    without building the mesh, or None when unknown: from the header where the format has one
    (binary STL, PLY, OFF), else counted in chunks (OBJ faces, ASCII STL vertices), in memory
    bounded by the chunk size."""
    if data is None:
        try:
            data = read_regular(path, MAX_MESH_BYTES, as_="mesh")
        except OSError:
            return None
    suffix = path.suffix.lower()
    if suffix == ".dae":
        return _collada_triangles(data)
    if suffix in (".gltf", ".glb"):
        try:
            return _gltf_triangles(path, data)
        except struct.error:
            return None
    try:
        with io.BytesIO(data) as handle:
            if suffix == ".stl":
                from urdftool.description.mesh_arrays import binary_stl

                if binary_stl(data):  # (as trimesh reads it, whatever its header spells)
                    return struct.unpack("<I", data[80:84])[0]
                return _stl_ascii_triangles(handle)  # (a binary file cut short too: trimesh
                # reads it as text, and fails)
            if suffix == ".ply":
                return _ply_triangles(handle)
            if suffix == ".off":
                lines = [line for line in handle.read(4096).splitlines()
                         if line.strip() and not line.strip().startswith(b"#")]
                counts = lines[1].split() if len(lines) > 1 and lines[0].strip() == b"OFF" else \
                    lines[0].split()[1:] if lines else []
                if len(counts) < 2 or not (counts[0].isdigit() and counts[1].isdigit()):
                    return None
                # every number after the vertices is a corner (k - 2 triangles per face of k):
                # OFF, the three counts, three coordinates a vertex, a count a face
                handle.seek(0)
                return max(_tokens(handle) - 4 - 3 * int(counts[0]) - 3 * int(counts[1]), 0)
            if suffix == ".obj":
                return _obj_triangles(handle)
    except (OSError, struct.error, ValueError):
        return None
    return None
