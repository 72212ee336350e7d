"""Mesh files named by a robot: resolve, refuse what is unsafe, load once, measure.

One module serves the mesh rules (U4xx), ``urdftool inertia`` and the collision tools, so every
mesh goes through the same checks before trimesh touches it:

- the URI resolves (``package://`` through the robot's resolver, ``file://``, relative);
- a ``file://`` or relative path may not leave the containment root (the nearest ancestor of
  the robot file holding ``.git``; without one, the robot's package folder, else its folder);
  a ``package://`` path may not leave its package folder;
- only files with a mesh extension are opened (:data:`MESH_EXTENSIONS`);
- the file size and the triangle count are bounded before trimesh reads a byte (the count is
  read from the header where the format has one, else counted over the file in chunks: an
  OBJ or PLY face of k corners is k - 2 triangles; a COLLADA or glTF mesh counts once per instance
  in its scene), so a crafted file cannot exhaust memory;
- a zipped COLLADA file (ZAE, which pycollada would inflate whole) is refused;
- beside the mesh, trimesh may read only glTF buffers in the mesh's folder, under the size
  limit: no textures or material files;
- a file that does not parse is a :class:`MeshProblem`, never a traceback;
- a COLLADA file that is not well-formed XML is read as libxml2's recover mode reads it (assimp,
  which RViz, Gazebo and MoveIt load meshes with, is as lenient); the loaded mesh says so in
  ``metadata[NOT_WELL_FORMED]``.

A URI is resolved and checked once per robot. Meshes are read once per run (process), keyed by
resolved path, file identity and modification and the limits, and cached per robot by scale.
What the checks measure (:func:`mesh_facts`: bounds, triangle count, watertightness, volume,
centre of mass, inertia, the convex hull's) is measured once per file and scale per run, on
the mesh's corners merged by position (a seam of normals or texture coordinates is no hole),
merged only when something beyond the bounds and triangle count is asked;
STL, COLLADA and plain OBJ files are read and measured without trimesh or pycollada
(:mod:`.mesh_arrays`, COLLADA through :mod:`.collada`), other formats through trimesh.
trimesh is imported lazily.
COLLADA files are scaled by the ``<unit meter>`` they declare, as RViz and Gazebo do.
"""

from __future__ import annotations

import io
import math
import os
import re
import struct
import warnings
from dataclasses import dataclass
from pathlib import Path

from urdftool.errors import MeshProblem, PackageNotFound
from urdftool.description import mesh_arrays
from urdftool.description.collada import ColladaProblem, parser, tag
from urdftool.description.files import TooLarge, identity, inside, kind_of, read_regular, \
    real_path, resolved
from urdftool.description.inputs import MAX_MESH_BYTES, MeshLimits
from urdftool.description.packages import containment_root, package_uri_parts
from urdftool.description.record import captured, replay
from urdftool.description.run_memo import per_run

MESH_EXTENSIONS = (".stl", ".dae", ".obj", ".ply", ".glb", ".gltf", ".off")

def resolve(robot, uri: str) -> Path:
    """The absolute path of a mesh URI; raises MeshProblem when it may not or cannot be used.

    Resolved and checked once per robot and URI (every rule, link and solid asks again)."""
    found = robot.memo((resolve, uri), lambda: _resolved(robot, uri))
    if isinstance(found, MeshProblem):
        raise found
    return found


def _resolved(robot, uri: str) -> Path | MeshProblem:
    try:
        found = _resolve(robot, uri)
    except MeshProblem as problem:
        resolved(f"mesh {uri}", f"{problem.kind}: {problem}")
        return problem
    resolved(f"mesh {uri}", found)
    return found


def _resolve(robot, uri: str) -> Path:
    if uri.startswith("package://"):
        package, _ = package_uri_parts(uri)
        try:
            folder = robot.resolver.find(package)
        except PackageNotFound as error:
            raise MeshProblem("package", f"mesh '{uri}': {error}") from None
        found = _checked(uri, os.fspath(robot.resolve_uri(uri)), os.fspath(folder), package)
    else:
        if "://" in uri and not uri.startswith("file://"):
            raise MeshProblem("format", f"mesh '{uri}': only package://, file:// and relative "
                                        "paths are supported")
        found = _checked(uri, os.fspath(robot.resolve_uri(uri)), os.fspath(robot.base_dir),
                         None)
    if isinstance(found, MeshProblem):
        raise MeshProblem(found.kind, found.message)  # a new one: raised once per robot
    return found


@per_run
def _checked(uri: str, named: str, base: str, package: str | None) -> Path | MeshProblem:
    """The path ``named`` for mesh ``uri`` with its links followed, when it stays in package
    ``package``'s folder ``base`` (or, for ``package`` None, in the containment root of the
    robot's folder ``base``) and is a file with a mesh extension; else the MeshProblem.
    Once per run: robots of one package name the same meshes."""
    path = _real(Path(named))
    if package is not None:
        folder = _real(Path(base))
        if not inside(path, folder):
            return MeshProblem("outside", f"mesh '{uri}' leaves package '{package}' "
                                          f"({folder}); name a file inside the package")
    else:
        # file:// and relative paths stay where the loader's files stay
        root = _real(containment_root(Path(base)))
        if not inside(path, root):
            # as written, never where links lead: that would name what exists outside
            written = os.path.normpath(os.path.join(base, named))
            how = (f"is a symbolic link (or lies in one) leading outside {root}"
                   if written.startswith(str(containment_root(Path(base))) + os.sep)
                   else f"resolves to {written}, outside {root}")
            return MeshProblem("outside", (
                f"mesh '{uri}' {how}; urdftool does not open files outside the robot's "
                "repository: use package://PKG/... for files of another package"))
    if kind_of(path) != "file":
        return MeshProblem("missing", f"mesh '{uri}' not found (looked at {path})")
    if path.suffix.lower() not in MESH_EXTENSIONS:
        return MeshProblem("format", (f"mesh '{uri}' has extension '{path.suffix}', not one of "
                                      f"{', '.join(MESH_EXTENSIONS)}; not opened"))
    return path


def _real(path: Path) -> Path:
    """``path`` with every symbolic link followed (once per run; a loop is left as it is, and
    is then no file)."""
    return Path(real_path(os.fspath(path)))


_CHUNK = 1 << 20
# OBJ face corners are counted over bytes, so that no text decoding trimesh may choose finds
# more: a run of printable ASCII is at most one corner, any other byte that is not ASCII
# white space at most one more (a separator in some encoding, or a corner of its own)
_CORNER_CLASSES = bytes.maketrans(bytes(range(256)), bytes(
    10 if b == 10 else 32 if b in b" \t\r\x0b\x0c" else 112 if 0x21 <= b <= 0x7E else 111
    for b in range(256)))  # newline stays, white space -> " ", printable -> "p", other -> "o"
_FACE_LINE = re.compile(rb"^[ \t]*f([^\n]*)", re.MULTILINE)


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
    offsets = [int(c.get("offset", "0")) for c in primitive
               if tag(c) == "input" and c.get("offset", "0").isdigit()]
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


NOT_WELL_FORMED = "urdftool_not_well_formed"  # mesh metadata: why its XML was recovered


def _recovered_collada(data: bytes) -> tuple[bytes, str] | None:
    """(the document libxml2's recover mode makes of a COLLADA file that is not well-formed
    XML, the first error with its line), or None when it makes none."""
    from lxml import etree

    lenient = parser(recover=True)
    try:
        root = etree.fromstring(data, lenient)
    except (etree.LxmlError, ValueError):
        return None
    if root is None:
        return None
    errors = [e for e in lenient.error_log if e.level >= etree.ErrorLevels.ERROR]
    first = f"line {errors[0].line}: {errors[0].message}" if errors else "not well-formed"
    return etree.tostring(root), first


def _gltf_header(path: Path, data: bytes) -> dict | None:
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


def _gltf_triangles(path: Path, data: bytes) -> int | None:
    """Triangles of a glTF scene as trimesh builds it: every node the scene reaches adds its
    mesh's triangles (accessor counts), so a file naming one mesh from a million nodes is
    counted before it is built."""
    header = _gltf_header(path, data)
    if header is None:
        return None

    def listed(value) -> list:
        return value if isinstance(value, list) else []

    def entry(items, index) -> dict:
        ok = isinstance(index, int) and 0 <= index < len(listed(items))
        return items[index] if ok and isinstance(items[index], dict) else {}

    def count(index) -> int:
        value = entry(header.get("accessors"), index).get("count")
        return value if isinstance(value, int) and value > 0 else 0

    def mesh_triangles(mesh: dict) -> int:
        total = 0
        for primitive in listed(mesh.get("primitives")):
            if not isinstance(primitive, dict):
                continue
            mode = primitive.get("mode", 4)
            attributes = primitive.get("attributes")
            corners = count(primitive["indices"]) if "indices" in primitive else \
                count(attributes.get("POSITION")) if isinstance(attributes, dict) else 0
            total += corners // 3 if mode == 4 else max(corners - 2, 0) if mode == 5 else 0
        return total

    nodes = listed(header.get("nodes"))
    scene = entry(header.get("scenes"), header.get("scene", 0))
    seen, queue, total = set(), list(listed(scene.get("nodes"))), 0
    while queue:
        index = queue.pop()
        if not isinstance(index, int) or index in seen or not 0 <= index < len(nodes):
            continue
        seen.add(index)
        node = entry(nodes, index)
        if "mesh" in node:
            total += mesh_triangles(entry(header.get("meshes"), node["mesh"]))
        queue.extend(listed(node.get("children")))
    return total


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
                head = handle.read(84)
                if len(head) == 84 and not head.lstrip().lower().startswith(b"solid"):
                    return struct.unpack("<I", head[80:84])[0]
                size = len(data)
                if len(head) == 84:
                    count = struct.unpack("<I", head[80:84])[0]
                    if 84 + 50 * count == size:  # binary STL whose header starts with "solid"
                        return count
                handle.seek(0)
                return _stl_ascii_triangles(handle)
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


def _mesh_bytes(path: Path, uri: str, limits: MeshLimits) -> bytes:
    """The mesh file's bytes, read once (recorded as a mesh): MeshProblem when it is over the
    size limit (not opened) or cannot be read."""
    try:
        return read_regular(path, limits.max_bytes, as_="mesh")
    except TooLarge as error:
        raise MeshProblem("too-large", f"mesh '{uri}' is {error.size} bytes, over the limit "
                                       f"of {limits.max_bytes}; not opened") from None
    except OSError as error:
        raise MeshProblem("corrupt", f"mesh '{uri}' cannot be read: {error.strerror}") from None


def _check_size(path: Path, uri: str, limits: MeshLimits, data: bytes,
                count: bool = True) -> None:
    """Every limit, checked in the file's bytes before trimesh reads them: size, archive,
    triangles (unless ``count`` is false: the reader counts them before it builds them)."""
    size = len(data)
    if size > limits.max_bytes:
        raise MeshProblem("too-large", f"mesh '{uri}' is {size} bytes, over the limit of "
                                       f"{limits.max_bytes}; not opened")
    if path.suffix.lower() == ".dae" and _zipped(data):
        # pycollada inflates a zipped .dae (ZAE) whole, whatever its name says
        raise MeshProblem("format", f"mesh '{uri}' is a zip archive (ZAE), not a COLLADA "
                                    "document; urdftool does not inflate archives: store "
                                    "the .dae uncompressed")
    triangles = triangle_count(path, data) if count else None
    if triangles is not None:
        _refuse_too_many(uri, triangles, limits)


def _refuse_too_many(uri: str, triangles: int, limits: MeshLimits) -> None:
    if triangles > limits.max_triangles:
        raise MeshProblem("too-large", f"mesh '{uri}' has {triangles} triangles, over the "
                                       f"limit of {limits.max_triangles}; decimate it")


_DAE_UNIT = re.compile(rb"<unit\b[^>]*\bmeter\s*=\s*[\"']([0-9.eE+-]+)[\"']")


def collada_unit(data: bytes) -> float:
    """The ``<unit meter=...>`` a COLLADA document declares (1 when none): viewers apply it,
    and trimesh does not, so :func:`load_mesh` does."""
    try:
        match = _DAE_UNIT.search(data, 0, 65536)
        value = float(match.group(1)) if match else 1.0
    except (OSError, ValueError):
        return 1.0
    return value if value > 0 and value == value and value != float("inf") else 1.0


_SIDECARS = (".bin",)  # the files beside a mesh that hold geometry: glTF buffers


def _geometry_resolver(path: Path, limits: MeshLimits):
    """What trimesh may read beside the mesh: glTF buffers in the mesh's folder (or below it),
    regular files under the size limit, read through the one door (recorded). Textures and
    materials are refused (urdftool reads geometry only, and an image can be a decompression
    bomb); trimesh loads the mesh without them."""
    from trimesh.resolvers import Resolver

    folder = path.parent

    class GeometryResolver(Resolver):
        def __init__(self):
            pass

        def get(self, name: str):
            name = name.strip()
            for candidate in (name, name.lstrip("/"), os.path.split(name)[-1]):
                found = folder / candidate
                if found.suffix.lower() not in _SIDECARS:
                    raise FileNotFoundError(f"{name}: not geometry, not read")
                if not inside(found, folder):
                    continue  # it leaves the mesh's folder
                try:
                    return read_regular(found, limits.max_bytes, as_="mesh buffer")
                except OSError:
                    continue
            raise FileNotFoundError(f"{name}: not a regular file under the size limit in the "
                                    "mesh's folder")

        def write(self, name, data):
            raise NotImplementedError("urdftool writes no mesh files")

        def namespaced(self, namespace):
            raise NotImplementedError("a mesh's buffers are beside it")

        def keys(self):
            return iter(())  # nothing is listed

    return GeometryResolver()


def _zipped(data: bytes) -> bool:
    import zipfile  # only for COLLADA files, not on every check's start-up

    return zipfile.is_zipfile(io.BytesIO(data))


def _read_mesh(path: Path, uri: str, limits: MeshLimits):
    import logging

    import trimesh

    data = _mesh_bytes(path, uri, limits)
    _check_size(path, uri, limits, data)
    # trimesh logs missing textures with tracebacks; a mesh's geometry is all urdftool reads
    logging.getLogger("trimesh").setLevel(logging.CRITICAL)
    malformed = None
    suffix = path.suffix.lower()
    try:
        try:
            loaded = trimesh.load(io.BytesIO(data), file_type=suffix[1:], force="mesh",
                                  process=True, resolver=_geometry_resolver(path, limits))
        except Exception as error:  # pycollada refuses XML that is not well-formed
            recovered = _recovered_collada(data) if suffix == ".dae" and \
                "XML Parsing Error" in str(error) else None
            if recovered is None:
                raise
            data, malformed = recovered
            loaded = trimesh.load(io.BytesIO(data), file_type="dae", force="mesh",
                                  process=True, resolver=_geometry_resolver(path, limits))
    except Exception as error:  # trimesh raises many types for a bad file
        raise MeshProblem("corrupt", f"mesh '{uri}' does not load: {type(error).__name__}: "
                                     f"{error}") from None
    if not isinstance(loaded, trimesh.Trimesh) or len(loaded.faces) == 0:
        raise MeshProblem("corrupt", f"mesh '{uri}' holds no triangles")
    _refuse_too_many(uri, len(loaded.faces), limits)
    unit = collada_unit(data) if suffix == ".dae" else 1.0
    if unit != 1.0:
        loaded.apply_scale(unit)
    if malformed:
        loaded.metadata[NOT_WELL_FORMED] = malformed
    return loaded


# [bytes] of meshes kept between robots (a worker has 2 GiB of address space in all)
RUN_CACHE_BYTES = 128 * 1024 * 1024

# Meshes read in this process, shared by every robot checked in it (a run of robots of one
# package reads each mesh once, not once per robot): key -> (bytes held, outcome, what
# computing it recorded), least recently used first. Outcomes: a trimesh (counted as its file's
# size), a mesh's arrays and their measures (counted as the arrays' bytes), or a MeshProblem.
# A worker process per file has its own; it dies with its file.
class _RunCache(dict):
    """key -> (bytes held, outcome, record), with ``held``: the bytes of all entries (kept as
    entries come and go, not summed again at each insertion)."""

    held = 0

    def __setitem__(self, key, entry) -> None:
        self.held += entry[0] - (self[key][0] if key in self else 0)
        super().__setitem__(key, entry)

    def pop(self, key, *default):
        if key in self:
            self.held -= self[key][0]
        return super().pop(key, *default)

    def clear(self) -> None:
        self.held = 0
        super().clear()


_RUN_CACHE = _RunCache()


def _stamp(path: Path):
    """A file's identity and modification (device, inode, size, mtime in ns), or None."""
    return identity(path)


def _once(key: tuple, uri: str, compute):
    """``compute()`` -> (outcome, bytes held) once per run for ``key`` (which starts with the
    path and its :func:`_stamp`: a changed file is read again); a MeshProblem is kept under the
    URI its message names too. What computing it recorded (the mesh read, :mod:`.record`) is
    replayed into the record of each later caller. Returns the outcome or the MeshProblem."""
    for known in (key, (*key, uri)):
        if known in _RUN_CACHE:
            _RUN_CACHE[known] = entry = _RUN_CACHE.pop(known)  # most recently used last
            replay(entry[2])
            return entry[1]

    def outcome_of():
        try:
            return compute()
        except MeshProblem as problem:
            return problem, 0

    (outcome, size), events = captured(outcome_of)
    if key[1] is not None:
        _RUN_CACHE[(*key, uri) if isinstance(outcome, MeshProblem) else key] = (size, outcome,
                                                                               events)
        while _RUN_CACHE.held > RUN_CACHE_BYTES:
            _RUN_CACHE.pop(next(iter(_RUN_CACHE)))  # the least recently used
    return outcome


def _read_once(path: Path, uri: str, limits: MeshLimits):
    """``_read_mesh`` once per run for a file as it is now (keyed by the resolved path, its
    :func:`_stamp` and the limits). Returns the mesh or the MeshProblem."""
    stamp = _stamp(path)
    return _once((str(path), stamp, limits), uri,
                 lambda: (_read_mesh(path, uri, limits), stamp[2] if stamp else 0))


def _arrays_once(path: Path, uri: str, limits: MeshLimits, stamp):
    """The mesh's :class:`_Arrays`, once per run: read by :mod:`.mesh_arrays` where the format
    allows (STL, COLLADA, plain OBJ), else by trimesh (:func:`_read_once`)."""
    def compute():
        arrays, metadata, unit = None, {}, 1.0
        suffix = path.suffix.lower()
        if suffix in (".stl", ".dae", ".obj"):
            data = _mesh_bytes(path, uri, limits)  # read once: the limits are checked in it
            # a COLLADA file's triangles are counted as they are read, before they are built;
            # an OBJ's only when its "f " may make too many (a plain one has one a row;
            # the arrays read are counted below, any other is counted before trimesh reads it)
            _check_size(path, uri, limits, data, count=suffix == ".stl" or (
                suffix == ".obj" and data.count(b"f ") > limits.max_triangles))
            if suffix == ".dae":
                arrays, metadata = _collada_arrays(path, uri, data, limits)
                unit = collada_unit(data)
            else:
                arrays = mesh_arrays.read_unmerged(path, data)
        if arrays is None:
            loaded = _read_once(path, uri, limits)
            if isinstance(loaded, MeshProblem):
                raise loaded
            import numpy as np

            arrays = mesh_arrays.merged(np.asarray(loaded.vertices, dtype=np.float64),
                                        np.asarray(loaded.faces, dtype=np.int64))
            found = _Arrays(*arrays, dict(loaded.metadata), merged=True)
        else:
            found = _Arrays(*arrays, metadata, unit=unit)
        _refuse_too_many(uri, found.triangles, limits)
        return found, found.nbytes

    return _once((str(path), stamp, limits, "arrays"), uri, compute)


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
            recovered = _recovered_collada(data) if problem.not_well_formed else None
            if recovered is None:
                raise
            arrays = mesh_arrays.read_unmerged(path, recovered[0], limits.max_triangles)
            metadata = {NOT_WELL_FORMED: recovered[1]}
    except ColladaProblem as problem:
        if problem.kind == "too-large":
            raise MeshProblem("too-large", f"mesh '{uri}': {problem}; not loaded") from None
        return None, {}
    return arrays, metadata


class _Arrays:
    """A mesh file's triangles: as read (every vertex used by a face, in the file's unit)
    until something needs them merged by position (:func:`.mesh_arrays.merged`, then scaled by
    a COLLADA file's ``unit``, as trimesh's are). Bounds need no merging
    (:func:`.mesh_arrays.merged_bounds`): a mesh that only has to fit in a box is not merged.
    ``merged=True``: the arrays given are merged already (and in metres)."""

    def __init__(self, vertices, faces, metadata: dict, unit: float = 1.0, merged: bool = False):
        self.metadata, self.triangles = metadata, len(faces)
        self.nbytes = vertices.nbytes + faces.nbytes  # merged, they are no larger
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

    def bounds(self, scale: tuple[float, float, float]):
        """The (2, 3) bounds of the merged vertices scaled by ``scale``, found without merging
        them; None when that cannot be decided so (see :func:`.mesh_arrays.merged_bounds`)."""
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
        found = mesh_arrays.merged_bounds(moved, vertices)
        return None if found is None else np.array(found)


def _finite_scale(uri: str, scale) -> tuple[float, float, float]:
    scale = tuple(float(s) for s in scale)
    if not all(math.isfinite(s) for s in scale):
        raise MeshProblem("corrupt", f"mesh '{uri}' has a non-finite scale {scale}; not loaded")
    return scale


def _beyond_range(uri: str, scale) -> MeshProblem:
    return MeshProblem("corrupt", f"mesh '{uri}' scaled by {scale} has coordinates beyond "
                                  "floating point range; not loaded")


class MeshFacts:
    """What the checks measure of a mesh at a scale, under trimesh's names, so that rules and
    solids read it as they would read the ``trimesh.Trimesh`` that :func:`load_mesh` gives
    (same numbers: :mod:`.mesh_arrays` measures as trimesh does).

    faces: the triangle count; bounds: (2, 3) min and max corner; extents; is_watertight;
    metadata: :data:`NOT_WELL_FORMED` for a repaired COLLADA file; vertices (merged by
    position), is_watertight, mass_properties (density 1, of the mesh as it is) and
    convex_hull (its measures, as trimesh's hull has them; qhull's RuntimeError for a flat
    mesh) are computed when first asked: the merging too, when bounds were found without it.
    """

    def __init__(self, vertices, faces, metadata: dict, watertight: bool | None = None,
                 properties: dict | None = None):
        import numpy as np

        self._start(len(faces), np.array(mesh_arrays.bounds(vertices, faces)), metadata,
                    vertices.nbytes + faces.nbytes)
        self._vertices, self._faces, self._watertight = vertices, faces, watertight
        self._properties = properties

    @classmethod
    def unmerged(cls, triangles: int, bounds, metadata: dict, nbytes: int, merge):
        """Facts whose bounds are known and whose arrays ``merge()`` builds when first
        needed: (vertices, faces, watertight), merged and scaled."""
        facts = cls.__new__(cls)
        facts._start(triangles, bounds, metadata, nbytes)
        facts._merge = merge
        return facts

    def _start(self, triangles: int, bounds, metadata: dict, nbytes: int) -> None:
        self.faces, self.bounds, self.metadata, self.nbytes = triangles, bounds, metadata, nbytes
        self.extents = self.bounds[1] - self.bounds[0]
        self._vertices = self._faces = self._watertight = self._merge = None
        self._properties, self._hull = None, None

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
    key = (mesh_facts, uri, tuple(scale), limits)
    found = robot.memo(key, lambda: _facts_outcome(robot, uri, scale, limits))
    if isinstance(found, MeshProblem):
        raise found
    return found


def _facts_outcome(robot, uri: str, scale, limits: MeshLimits):
    try:
        path = resolve(robot, uri)
        scale = _finite_scale(uri, scale)
    except MeshProblem as problem:
        return problem
    stamp = _stamp(path)

    def compute():
        arrays = _arrays_once(path, uri, limits, stamp)
        if isinstance(arrays, MeshProblem):
            raise arrays
        bounds = arrays.bounds(scale)
        if bounds is not None:
            facts = MeshFacts.unmerged(arrays.triangles, bounds, arrays.metadata, arrays.nbytes,
                                       lambda: _merged_scaled(arrays, scale))
        else:
            import numpy as np

            vertices, faces, watertight = _merged_scaled(arrays, scale)
            if scale != (1.0, 1.0, 1.0) and not np.isfinite(vertices).all():
                raise _beyond_range(uri, scale)
            facts = MeshFacts(vertices, faces, arrays.metadata, watertight=watertight)
        return facts, facts.nbytes  # unscaled, the arrays' bytes: counted twice, an upper bound

    return _once((str(path), stamp, limits, "facts", scale), uri, compute)


def _merged_scaled(arrays: _Arrays, scale):
    """(vertices, faces, watertight) of ``arrays`` merged, then scaled (a scale keeps
    watertightness: a mirror turns every face)."""
    vertices, faces, watertight = arrays.merged()
    if scale != (1.0, 1.0, 1.0):
        import numpy as np

        with np.errstate(all="ignore"):  # overflow is reported by the caller
            vertices, faces = mesh_arrays.scaled(vertices, faces, scale)
    return vertices, faces, watertight


def load_mesh(robot, uri: str, scale=(1.0, 1.0, 1.0), limits: MeshLimits | None = None):
    """The mesh at ``uri`` scaled by ``scale`` (a trimesh.Trimesh; do not modify it).

    Loaded once per robot per (path, scale); problems are cached and raised again as
    MeshProblem. The limits are ``robot.mesh_limits`` (``check --max-triangles``) unless
    ``limits`` are given. Checks that need only measures ask :func:`mesh_facts`.
    """
    limits = limits or robot.mesh_limits
    cache = robot.memo(load_mesh, dict)
    path = resolve(robot, uri)
    scale = _finite_scale(uri, scale)
    key = (path, scale)
    if key not in cache:
        raw_key = (path, (1.0, 1.0, 1.0))
        if raw_key not in cache:
            cache[raw_key] = _read_once(path, uri, limits)
        raw = cache[raw_key]
        if isinstance(raw, MeshProblem) or key == raw_key:
            cache[key] = raw
        else:
            scaled = raw.copy()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)  # overflow is reported below
                scaled.apply_scale(scale)
            finite_vertices = all(math.isfinite(v) for v in scaled.bounds.ravel())
            cache[key] = scaled if finite_vertices else _beyond_range(uri, scale)
    found = cache[key]
    if isinstance(found, MeshProblem):
        raise found
    return found


def converted(path, how: str, limits: MeshLimits | None = None) -> bytes:
    """The mesh file at ``path`` (read within ``limits``, COLLADA scaled by its unit as the
    loaders read it) written as ``how``: ``obj`` (Wavefront OBJ text) or ``stl`` (binary STL).
    MeshProblem when it does not load. For fixes that point a robot at a format a simulator
    reads."""
    path = Path(path)
    mesh = _read_mesh(path, path.name, limits or MeshLimits())
    if how not in ("obj", "stl"):
        raise MeshProblem("format", f"cannot convert a mesh to '{how}'")
    data = mesh.export(file_type=how)
    return data.encode("utf-8") if isinstance(data, str) else bytes(data)
