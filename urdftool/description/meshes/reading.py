"""Reading a mesh file within its limits, through trimesh.

- the file size and the triangle count (:mod:`.counting`) are bounded before trimesh reads a
  byte; a zipped COLLADA file (ZAE, which pycollada would inflate whole) is refused;
- beside the mesh, trimesh may read only glTF buffers in the mesh's folder, under the size
  limit: no textures or material files;
- a file that does not parse is a :class:`MeshProblem`, never a traceback;
- a COLLADA file that is not well-formed XML is read as libxml2's recover mode reads it (assimp,
  which RViz, Gazebo and MoveIt load meshes with, is as lenient); the loaded mesh says so in
  ``metadata[NOT_WELL_FORMED]``; it is scaled by the ``<unit meter>`` it declares, as RViz and
  Gazebo do;
- triangles whose vertices are not finite numbers are left out, as trimesh leaves them out:
  none kept is "holds no triangles" saying why, some kept is said in ``metadata[NOT_FINITE]``;
- a glTF node's transform is applied as trimesh applies it (translation, rotation and scale,
  a mirror, as every loader does); one that is no such transform (a shear, a bottom row that is
  not 0 0 0 1, a scale of 0, a rotation that is no unit quaternion) is said in
  ``metadata[NODE_TRANSFORM]`` with what trimesh and assimp (Gazebo, RViz) make of it.

Meshes are read once per run (:mod:`.run_cache`) and kept per robot by scale
(:func:`load_mesh`). trimesh is imported lazily.
"""

from __future__ import annotations

import io
import math
import os
import re
import warnings
from pathlib import Path

from urdftool.description.collada import parser
from urdftool.description.xml import entity_uses
from urdftool.description.files import TooLarge, inside, read_regular
from urdftool.description.inputs import MeshLimits
from urdftool.description.meshes.counting import triangle_count
from urdftool.description.meshes.run_cache import limits_key, once, stamp_of
from urdftool.description.meshes.uris import resolve
from urdftool.errors import MeshProblem, described
from urdftool.numbers import MAX_COORDINATE

NOT_WELL_FORMED = "urdftool_not_well_formed"  # mesh metadata: why its XML was recovered
# mesh metadata: which of its triangles use vertices that are not finite numbers (trimesh
# leaves them out), when some are kept
NOT_FINITE = "urdftool_not_finite"
# mesh metadata: a glTF node's transform that is no translation, rotation and scale
NODE_TRANSFORM = "urdftool_node_transform"
# what a text mesh holding a number that is not finite holds (nan, inf, an exponent of three
# digits: 1e400), each a word of its own (not "info", "nanometer" or a COLLADA id "ID3e600"):
# only a sign, which :func:`_non_finite` counts exactly (a false one costs a second reading)
_NOT_FINITE_SIGN = re.compile(rb"(?i)(?<![a-z0-9_#.])[-+]?(?:(?:nan|inf(?:inity)?)(?![a-z0-9_])|"
                              rb"(?:[0-9]*+\.)?[0-9]++e\+?0*[1-9][0-9]{2}(?![0-9a-z_]))")
# The first line of a Git LFS pointer: what a clone without git-lfs holds instead of the file
LFS_POINTER = b"version https://git-lfs.github.com/spec/"


def recovered_collada(data: bytes) -> tuple[bytes, str] | None:
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


def mesh_bytes(path: Path, uri: str, limits: MeshLimits) -> bytes:
    """The mesh file's bytes, read once (recorded as a mesh): MeshProblem when it is over the
    size limit (not opened) or cannot be read."""
    try:
        return read_regular(path, limits.max_bytes, as_="mesh")
    except TooLarge as error:
        raise MeshProblem("too-large", f"mesh '{uri}' is {error.size} bytes, over the limit "
                                       f"of {limits.max_bytes}; not opened") from None
    except OSError as error:
        raise MeshProblem("corrupt", f"mesh '{uri}' cannot be read: {error.strerror}") from None


def is_lfs_pointer(data: bytes) -> bool:
    """Whether ``data`` is a Git LFS pointer as its specification writes one: under 1024 bytes
    of ``key value`` lines (printable ASCII), the version line first, an ``oid`` line; not a
    mesh that starts with those words (a binary STL's 80-byte header is free text)."""
    return (len(data) < 1024 and data.startswith(LFS_POINTER) and b"\noid " in data
            and _POINTER_LINES.fullmatch(data) is not None)


_POINTER_LINES = re.compile(rb"(?:[a-z0-9.-]+ [\x20-\x7e]*\r?\n)+")  # (CRLF: autocrlf)


def check_size(path: Path, uri: str, limits: MeshLimits, data: bytes,
                count: bool = True) -> None:
    """Every limit, checked in the file's bytes before trimesh reads them: size, archive,
    triangles (unless ``count`` is false: the reader counts them before it builds them). A Git
    LFS pointer is said to be one: read as the mesh, its text is a binary STL of a billion
    triangles, a COLLADA file that is not XML or an OBJ with no triangles."""
    if is_lfs_pointer(data):
        raise MeshProblem("corrupt", f"mesh '{uri}' is a Git LFS pointer, not the mesh: its "
                                     "content was never fetched (`git lfs pull`), so no "
                                     "viewer or simulator can load it")
    size = len(data)
    if size > limits.max_bytes:
        raise MeshProblem("too-large", f"mesh '{uri}' is {size} bytes, over the limit of "
                                       f"{limits.max_bytes}; not opened")
    if path.suffix.lower() == ".dae" and _zipped(data):
        # pycollada inflates a zipped .dae (ZAE) whole, whatever its name says
        raise MeshProblem("format", f"mesh '{uri}' is a zip archive (ZAE), not a COLLADA "
                                    "document; urdftool does not inflate archives: store "
                                    "the .dae uncompressed")
    used = _entity_in_data(data) if path.suffix.lower() == ".dae" else None
    if used:  # (pycollada's libxml2 expands it, up to its amplification limit)
        raise MeshProblem("corrupt", f"mesh '{uri}' uses the XML entity '{used}' it declares: "
                                     "pycollada expands it, Assimp (RViz) and Gazebo expand no "
                                     "entity and read those characters where numbers or "
                                     "names should be; write the text in place")
    from urdftool.description.meshes.counting import scene_problem

    scene = scene_problem(path, data)
    if scene:
        raise MeshProblem("too-large", f"mesh '{uri}': {scene}; not opened")
    triangles = triangle_count(path, data) if count else None
    if triangles is not None:
        refuse_too_many(uri, triangles, limits)


def _entity_in_data(data: bytes) -> str | None:
    """The first use of an entity a COLLADA document declares, outside the elements of its
    ``<asset>`` that only say who made it (a use there changes no geometry)."""
    for written, offset in entity_uses(data):
        start = data.rfind(b"<", 0, offset) + 1
        name = _TAG_NAME.match(data, start)
        if name is None or name.group(1).rpartition(b":")[2] not in _ASSET_TEXT:
            return written.decode("utf-8", "replace")
    return None


_TAG_NAME = re.compile(rb"([^\s/>]+)")
_ASSET_TEXT = frozenset({b"author", b"authoring_tool", b"comments", b"copyright", b"source_data",
                         b"title", b"subject", b"keywords", b"revision", b"created",
                         b"modified", b"author_email", b"author_website"})


def refuse_too_many(uri: str, triangles: int, limits: MeshLimits) -> None:
    if triangles > limits.max_triangles:
        raise MeshProblem("too-large", f"mesh '{uri}' has {triangles} triangles, over the "
                                       f"limit of {limits.max_triangles}; decimate it")


# [the mesh's own unit] beyond numbers.MAX_COORDINATE, a mesh is not measured: its vertices
# merge at 1e-8 as 64-bit integers (mesh_arrays.KEY_RANGE, 4.6e10); its volume and inertia take
# the third and fifth powers of what fits


def refuse_too_far(uri: str, vertices, cause: str | None = None) -> None:
    """MeshProblem (too-large) for a mesh with a coordinate past :data:`MAX_COORDINATE`, read
    by either reader (urdftool's arrays, trimesh's: give its ``bounds``, of the vertices its
    faces use): 1e200 merged its vertices by integers numpy could not make ("invalid value
    encountered in cast"), overflowed its measures and was "encloses no volume" to
    inertia. ``cause``: what made the coordinates (a glTF node's transform), said with them."""
    if len(vertices):
        far = max(float(vertices.max()), -float(vertices.min()))
        if not far < MAX_COORDINATE:
            from urdftool.numbers import number

            what = f"of {number(far)}, past" if math.isfinite(far) else "that is not finite, " \
                "not within"
            raise MeshProblem("too-large", f"mesh '{uri}' has a coordinate {what} the "
                                           f"{number(MAX_COORDINATE)} (in its own unit) urdftool "
                                           "measures meshes within"
                                           + (f" ({cause})" if cause else ""))


_DAE_UNIT = re.compile(rb"<unit\b[^<>]*\bmeter\s*=\s*[\"']([0-9.eE+-]+)[\"']")


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
    """``zipfile.is_zipfile`` of ``data``; a file without the end-of-central-directory
    signature in its last 64 kB + 22 bytes (where zipfile looks for it: a COLLADA file is XML
    text) is none, without importing zipfile (and shutil, bz2 and lzma with it: 20 M
    instructions)."""
    if data.find(_END_OF_ZIP, max(len(data) - _ZIP_TAIL, 0)) < 0:
        return False
    import zipfile

    return zipfile.is_zipfile(io.BytesIO(data))


_END_OF_ZIP = b"PK\005\006"  # zipfile.stringEndArchive
_ZIP_TAIL = (1 << 16) + 22  # [bytes]: the longest comment and the record (zipfile._EndRecData)


def _binary_stl_mismatch(data: bytes) -> str:
    """Why trimesh found no triangles in an STL that is binary by its header: the count the
    header gives does not match the file's size (trimesh then reads it as ASCII and finds
    none; "holds no triangles" was all it said of a file holding 12 whose header says 10)."""
    if len(data) < 84 or data[:84].lstrip().lower().startswith(b"solid") or \
            b"facet" in data[:1024]:
        return ""
    count = int.from_bytes(data[80:84], "little")
    if 84 + 50 * count == len(data):
        return ""
    return (f": its binary STL header says {count} triangles ({84 + 50 * count} bytes), the "
            f"file has {len(data)} bytes")


def _why_no_triangles(data: bytes, suffix: str, path: Path, limits: MeshLimits) -> str:
    """Why trimesh kept no triangles of a file, when it can be said: an STL's header that does
    not match its size, or faces whose vertices are not finite numbers (``nan``, ``inf``,
    ``1e400``: trimesh drops such faces as it processes the mesh; "holds no triangles" was all
    the finding said of a file holding one). The file is read again, unprocessed: only on this
    way out."""
    mismatch = _binary_stl_mismatch(data) if suffix == ".stl" else ""
    if mismatch:
        return mismatch
    bad = _non_finite(data, suffix, path, limits)[0]
    if not bad:
        return ""
    return (f": its {bad} triangle{'s use' if bad > 1 else ' uses'} vertices that are not "
            f"finite numbers (nan, inf or past the float range), which trimesh drops")


def _non_finite(data: bytes, suffix: str, path: Path, limits: MeshLimits) -> tuple[int, int]:
    """(the triangles of the file whose vertices are not all finite numbers, its triangles),
    the file read again by trimesh unprocessed; (0, 0) when it cannot be."""
    import numpy

    try:
        raw = _trimesh_load(data, suffix[1:], False, path, limits)
        faces, vertices = numpy.asarray(raw.faces), numpy.asarray(raw.vertices, dtype=float)
        if not len(faces):
            return 0, 0
        return int((~numpy.isfinite(vertices[faces]).all(axis=(1, 2))).sum()), len(faces)
    except Exception:  # the reason is a courtesy: the file holds no triangles either way
        return 0, 0


def _may_hold_non_finite(data: bytes, suffix: str) -> bool:
    """Whether a mesh trimesh read may have had triangles left out for vertices that are not
    finite, the one decision of which bytes to look at: a binary STL's numbers (numpy over the
    records); a binary PLY's, a GLB's or a glTF's (its buffers binary, or base64, or files of
    their own) always, as they have no cheap sign (read again to count them); any other file's
    bytes searched for :data:`_NOT_FINITE_SIGN`, NUL or not (a NUL in a comment left an OBJ's
    ``nan`` unlooked at; a false sign costs a second reading)."""
    if suffix == ".stl":
        from urdftool.description.mesh_arrays import _stl_binary

        raw = _stl_binary(data)
        if raw is not None:
            import numpy

            return not numpy.isfinite(raw).all()
    if suffix in (".glb", ".gltf") or (
            suffix == ".ply" and b"format binary" in data[:data.find(b"end_header") + 1]):
        return True
    return _NOT_FINITE_SIGN.search(data) is not None


def read_as_assumed(metadata: dict) -> list[str]:
    """What a mesh was read assuming, each said after the mesh's name (``mesh 'm.glb'`` + it):
    XML repaired (:data:`NOT_WELL_FORMED`), triangles left out for vertices that are not finite
    (:data:`NOT_FINITE`), a glTF node's transform glTF does not allow (:data:`NODE_TRANSFORM`).
    The one wording, for ``check`` and for every command that computes with the mesh (render,
    collisions, inertia), so that none uses such a mesh in silence."""
    said = []
    why = metadata.get(NOT_WELL_FORMED)
    if why:
        said.append(f" is not well-formed XML ({why}); read as repaired, as assimp reads it, "
                    "but XML-strict readers (pycollada, trimesh) refuse it")
    if metadata.get(NOT_FINITE):
        said.append(f": {metadata[NOT_FINITE]}; checked as trimesh reads it (without them), "
                    "while renderers and physics engines read them as they are")
    if metadata.get(NODE_TRANSFORM):
        said.append(f": {metadata[NODE_TRANSFORM]}")
    return said


def _trimesh_load(data: bytes, file_type: str, process: bool, path: Path, limits: MeshLimits):
    """trimesh's mesh of ``data``, every read of a mesh by trimesh: numpy's warnings on
    vertices not finite or too far (merging them in integers), or on a glTF node's matrix of
    1e308 (trimesh's test of it overflows), are left unsaid here: what matters of each is said
    where it is found (NOT_FINITE, refuse_too_far); the second reading that counts them printed
    them (a GLB, always read again)."""
    import trimesh

    if file_type == "obj":
        data = _without_materials(data)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return trimesh.load(io.BytesIO(data), file_type=file_type, force="mesh", process=process,
                            resolver=_geometry_resolver(path, limits))


# a material an OBJ uses, as trimesh splits the faces at it: "usemtl NAME" anywhere in a line
_OBJ_MATERIAL = re.compile(r"usemtl [^\n]*")


def _without_materials(data: bytes) -> bytes:
    """An OBJ's text as trimesh decodes it (``util.decode_text``: UTF-8, else the encoding it
    detects), its ``usemtl`` statements left out, in UTF-8. trimesh makes a mesh of each
    material's faces and joins them: in ``exchange/obj.py``'s ``load_obj`` each piece is named
    by ``util.unique_name`` without the memo of counts its glTF and COLLADA readers give it
    (the k-th piece named alike, as every piece is when no material file is read, tries k
    names: 10,000 materials were 50 million ``str.format`` calls, 13 s a load) and masks the
    file's whole vertex array (``mask_v``, ``inverse``: pieces times vertices, 999 materials
    over 4 million vertices took 18 s a check). urdftool reads no material file (geometry
    only), so the pieces are one mesh's faces grouped by a name nothing reads: read as one, in
    the file's order, the same triangles."""
    if b"usemtl" not in data and b"\0" not in data:
        return data  # (UTF-16 and UTF-32 hold NULs between the letters)
    from trimesh.util import decode_text

    text = decode_text(data)
    return _OBJ_MATERIAL.sub("", text).encode("utf-8") if "usemtl " in text else data


def _read_mesh(path: Path, uri: str, limits: MeshLimits):
    import logging

    import trimesh

    data = mesh_bytes(path, uri, limits)
    check_size(path, uri, limits, data)
    # trimesh logs missing textures with tracebacks; a mesh's geometry is all urdftool reads
    logging.getLogger("trimesh").setLevel(logging.CRITICAL)
    malformed = None
    suffix = path.suffix.lower()
    try:
        try:
            loaded = _trimesh_load(data, suffix[1:], True, path, limits)
        except Exception as error:  # pycollada refuses XML that is not well-formed
            recovered = recovered_collada(data) if suffix == ".dae" and \
                "XML Parsing Error" in str(error) else None
            if recovered is None:
                raise
            data, malformed = recovered
            loaded = _trimesh_load(data, "dae", True, path, limits)
    except Exception as error:  # trimesh raises many types for a bad file
        raise MeshProblem("corrupt", f"mesh '{uri}' does not load: {described(error)}") from None
    if not isinstance(loaded, trimesh.Trimesh) or len(loaded.faces) == 0:
        raise MeshProblem("corrupt", f"mesh '{uri}' holds no triangles"
                                     f"{_why_no_triangles(data, suffix, path, limits)}")
    refuse_too_many(uri, len(loaded.faces), limits)
    transform = gltf_node_transform(path, data) if suffix in (".glb", ".gltf") else None
    refuse_too_far(uri, loaded.bounds, transform)
    if _may_hold_non_finite(data, suffix):  # (some triangles left out: trimesh says nothing)
        bad, total = _non_finite(data, suffix, path, limits)
        if bad:
            loaded.metadata[NOT_FINITE] = (f"{bad} of its {total} triangles use vertices that "
                                           "are not finite numbers (nan, inf or past the float "
                                           "range)")
    if transform:
        loaded.metadata[NODE_TRANSFORM] = transform
    unit = collada_unit(data) if suffix == ".dae" else 1.0
    if unit != 1.0:
        loaded.apply_scale(unit)
    if malformed:
        loaded.metadata[NOT_WELL_FORMED] = malformed
    return loaded


# How far a glTF node's rotation may be from unit length, and its matrix's columns from
# orthogonal (of their lengths' product), before it is no rotation (the glTF validator's
# tolerance for unit quaternions is 5e-6; a float32 export's round-off is 1e-7)
_NODE_TOLERANCE = 1e-5


def gltf_node_transform(path: Path, data: bytes) -> str | None:
    """What is wrong with the transforms of the nodes a glTF's scene reaches, or None: glTF
    2.0 requires a node's ``matrix`` to be a translation, rotation and scale (TRS) and its
    ``rotation`` a unit quaternion. trimesh applies a matrix's upper 3 rows as they are (a
    shear too) and ignores its bottom row, as assimp (Gazebo, RViz) does; it normalises a
    rotation that is not unit, which assimp does not (its quaternion's matrix then scales and
    shears); a scale of 0 flattens the mesh. The first node said, and how many more."""
    import numpy as np

    from urdftool.description.meshes.counting import gltf_header, gltf_scene_nodes

    header = gltf_header(path, data)
    problems = []
    for index, node, _ in gltf_scene_nodes(header) if header is not None else ():
        problem = _node_problem(node, np)
        if problem:
            name = node.get("name")
            label = f"node '{name}'" if isinstance(name, str) and name else f"node {index}"
            problems.append(f"glTF {label}: {problem}")
    if not problems:
        return None
    more = f" (and {len(problems) - 1} more node(s))" if len(problems) > 1 else ""
    return problems[0] + more


def _node_problem(node: dict, np) -> str | None:
    try:
        matrix = np.array(node["matrix"], dtype=float).reshape(4, 4).T if "matrix" in node \
            else None
        rotation = np.array(node["rotation"], dtype=float).reshape(4) if "rotation" in node \
            else None
        scale = np.array(node["scale"], dtype=float).reshape(3) if "scale" in node else None
    except (TypeError, ValueError):
        return None  # (trimesh refuses it: the file does not load)
    for what, values in (("matrix", matrix), ("rotation", rotation), ("scale", scale)):
        if values is not None and not np.isfinite(values).all():
            return f"its {what} holds a number that is not finite"
    if matrix is not None:
        if not np.array_equal(matrix[3], [0.0, 0.0, 0.0, 1.0]):
            return (f"its matrix's bottom row is {_row(matrix[3])}, not 0 0 0 1 (a projection, "
                    "no glTF transform): trimesh and assimp (Gazebo, RViz) ignore that row, "
                    "and so does urdftool")
        columns = matrix[:3, :3]
        largest = np.abs(columns).max(axis=0)  # (each column scaled first: a scale of 1e308)
        if not largest.all():
            return "its matrix has a scale of 0: it flattens the mesh, which then has no volume"
        directions = columns / largest
        directions /= np.sqrt((directions * directions).sum(axis=0))
        if not abs(np.linalg.det(directions)) > _NODE_TOLERANCE:
            return ("its matrix flattens the mesh (its columns lie in a plane), which then has "
                    "no volume")
        if np.abs(directions.T @ directions - np.eye(3)).max() > _NODE_TOLERANCE:
            return ("its matrix shears (its columns are not at right angles: no translation, "
                    "rotation and scale, as glTF requires); trimesh and assimp (Gazebo, RViz) "
                    "apply it as it is, and so does urdftool")
    if rotation is not None and abs(float(np.sqrt(rotation @ rotation)) - 1) > _NODE_TOLERANCE:
        return (f"its rotation {_row(rotation)} is no unit quaternion (length "
                f"{_row([np.sqrt(rotation @ rotation)])}): trimesh, and urdftool, normalise "
                "it; assimp (Gazebo, RViz) does not, and its matrix then scales and shears the "
                "mesh")
    if scale is not None and not scale.all():
        return f"its scale {_row(scale)} has a 0: it flattens the mesh, which then has no volume"
    return None


def _row(values) -> str:
    from urdftool.numbers import number

    return " ".join(number(float(v)) for v in values)


def read_once(path: Path, uri: str, limits: MeshLimits):
    """``_read_mesh`` once per run for a file as it is now (keyed by the resolved path, its
    :func:`stamp_of` and the limits). Returns the mesh or the MeshProblem."""
    stamp = stamp_of(path)
    return once((str(path), stamp, limits_key(limits)), uri,
                 lambda: (_read_mesh(path, uri, limits), stamp[2] if stamp else 0))


def finite_scale(uri: str, scale) -> tuple[float, float, float]:
    scale = tuple(float(s) for s in scale)
    if not all(math.isfinite(s) for s in scale):
        raise MeshProblem("corrupt", f"mesh '{uri}' has a non-finite scale {scale}; not loaded")
    return scale


def beyond_range(uri: str, scale) -> MeshProblem:
    return MeshProblem("corrupt", f"mesh '{uri}' scaled by {scale} has coordinates beyond "
                                  "floating point range; not loaded")


def load_mesh(robot, uri: str, scale=(1.0, 1.0, 1.0), limits: MeshLimits | None = None):
    """The mesh at ``uri`` scaled by ``scale`` (a trimesh.Trimesh; do not modify it).

    Loaded once per robot per (path, scale); problems are cached and raised again as
    MeshProblem. The limits are ``robot.mesh_limits`` (``check --max-triangles``) unless
    ``limits`` are given. Checks that need only measures ask :func:`mesh_facts`.
    """
    limits = limits or robot.mesh_limits
    cache = robot.memo(load_mesh, dict)
    path = resolve(robot, uri)
    scale = finite_scale(uri, scale)
    key = (path, scale)
    if key not in cache:
        raw_key = (path, (1.0, 1.0, 1.0))
        if raw_key not in cache:
            cache[raw_key] = read_once(path, uri, limits)
        raw = cache[raw_key]
        if isinstance(raw, MeshProblem) or key == raw_key:
            cache[key] = raw
        else:
            scaled = raw.copy()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)  # overflow is reported below
                scaled.apply_scale(scale)
            finite_vertices = all(math.isfinite(v) for v in scaled.bounds.ravel())
            cache[key] = scaled if finite_vertices else beyond_range(uri, scale)
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
