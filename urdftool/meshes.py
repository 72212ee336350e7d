"""Mesh files named by a robot: resolve, refuse what is unsafe, load once, measure.

One module serves the mesh rules (U4xx), ``urdftool inertia`` and the collision tools, so every
mesh goes through the same checks before trimesh touches it:

- the URI resolves (``package://`` through the robot's resolver, ``file://``, relative);
- a ``file://`` or relative path may not leave the containment root (the nearest ancestor of
  the robot file holding ``.git``; without one, the robot's package folder, else its folder);
  a ``package://`` path may not leave its package folder;
- only files with a mesh extension are opened (:data:`MESH_EXTENSIONS`);
- the file size and the triangle count are bounded (the count is read from the header where
  the format has one, before the mesh is built), so a crafted file cannot exhaust memory;
- a file that does not parse is a :class:`MeshProblem`, never a traceback.

Meshes are cached per robot, keyed by resolved path and scale. trimesh is imported lazily.
COLLADA files are scaled by the ``<unit meter>`` they declare, as RViz and Gazebo do.
"""

from __future__ import annotations

import logging
import math
import os
import re
import struct
import warnings
from dataclasses import dataclass
from pathlib import Path

from .errors import PackageNotFound
from .loader.packages import package_name, repository_root

MESH_EXTENSIONS = (".stl", ".dae", ".obj", ".ply", ".glb", ".gltf", ".off")
MAX_TRIANGLES = 2_000_000
MAX_MESH_BYTES = 128 * 1024 * 1024
_CACHE_KEY = "_mesh_cache"


@dataclass(frozen=True)
class MeshProblem(Exception):
    """Why a mesh cannot be used.

    kind: ``package`` (unknown package), ``outside`` (escapes the root), ``missing``,
    ``format`` (not a mesh extension), ``too-large`` (bytes or triangles), ``corrupt``
    message: what a user should read, naming the file and the fix
    """

    kind: str
    message: str

    def __str__(self) -> str:
        return self.message


@dataclass(frozen=True)
class MeshLimits:
    max_triangles: int = MAX_TRIANGLES
    max_bytes: int = MAX_MESH_BYTES


def containment_root(robot) -> Path:
    """Where ``file://`` and relative mesh paths must stay: repository, package, or folder."""
    start = robot.base_dir
    root = repository_root(start)
    if root is not None:
        return root
    for folder in [start, *start.parents]:
        if package_name(folder) is not None:
            return folder
    return start


def _inside(path: Path, folder: Path) -> bool:
    try:
        path.relative_to(folder)
        return True
    except ValueError:
        return False


def resolve(robot, uri: str) -> Path:
    """The absolute path of a mesh URI; raises MeshProblem when it may not or cannot be used."""
    if uri.startswith("package://"):
        package = uri[len("package://"):].partition("/")[0]
        try:
            folder = robot.resolver.find(package).resolve()
        except PackageNotFound as error:
            raise MeshProblem("package", f"mesh '{uri}': {error}") from None
        path = robot.resolve_uri(uri).resolve()
        if not _inside(path, folder):
            raise MeshProblem("outside", f"mesh '{uri}' leaves package '{package}' ({folder}); "
                                         "name a file inside the package")
    else:
        if "://" in uri and not uri.startswith("file://"):
            raise MeshProblem("format", f"mesh '{uri}': only package://, file:// and relative "
                                        "paths are supported")
        path = robot.resolve_uri(uri).resolve()
        root = containment_root(robot).resolve()
        if not _inside(path, root):
            raise MeshProblem("outside", (
                f"mesh '{uri}' resolves to {path}, outside {root}; urdftool does not open files "
                "outside the robot's repository: use package://PKG/... for files of another "
                "package"))
    if not path.is_file():
        raise MeshProblem("missing", f"mesh '{uri}' not found (looked at {path})")
    if path.suffix.lower() not in MESH_EXTENSIONS:
        raise MeshProblem("format", (f"mesh '{uri}' has extension '{path.suffix}', not one of "
                                     f"{', '.join(MESH_EXTENSIONS)}; not opened"))
    return path


def triangle_count(path: Path) -> int | None:
    """The triangle count read from the header without building the mesh, or None."""
    suffix = path.suffix.lower()
    try:
        with open(path, "rb") as handle:
            if suffix == ".stl":
                head = handle.read(84)
                if len(head) == 84 and not head.lstrip().lower().startswith(b"solid"):
                    return struct.unpack("<I", head[80:84])[0]
                size = os.path.getsize(path)
                if len(head) == 84:
                    count = struct.unpack("<I", head[80:84])[0]
                    if 84 + 50 * count == size:  # binary STL whose header starts with "solid"
                        return count
                return size // 120  # ASCII STL: a facet takes at least ~120 bytes
            if suffix == ".ply":
                header = handle.read(4096)
                match = re.search(rb"element\s+face\s+(\d+)", header)
                return int(match.group(1)) if match else None
            if suffix == ".off":
                lines = [line for line in handle.read(4096).splitlines()
                         if line.strip() and not line.strip().startswith(b"#")]
                counts = lines[1].split() if len(lines) > 1 and lines[0].strip() == b"OFF" else \
                    lines[0].split()[1:] if lines else []
                return int(counts[1]) if len(counts) > 1 and counts[1].isdigit() else None
            if suffix == ".obj":
                return sum(1 for line in handle if line.startswith(b"f "))
    except (OSError, struct.error, ValueError):
        return None
    return None


def _check_size(path: Path, uri: str, limits: MeshLimits) -> None:
    size = path.stat().st_size
    if size > limits.max_bytes:
        raise MeshProblem("too-large", f"mesh '{uri}' is {size} bytes, over the limit of "
                                       f"{limits.max_bytes}; not opened")
    count = triangle_count(path)
    if count is not None and count > limits.max_triangles:
        raise MeshProblem("too-large", f"mesh '{uri}' has {count} triangles, over the limit of "
                                       f"{limits.max_triangles}; decimate it")


_DAE_UNIT = re.compile(rb"<unit\b[^>]*\bmeter\s*=\s*[\"']([0-9.eE+-]+)[\"']")


def collada_unit(path: Path) -> float:
    """The ``<unit meter=...>`` a COLLADA file declares (1 when none): viewers apply it, and
    trimesh does not, so :func:`load_mesh` does."""
    try:
        with open(path, "rb") as handle:
            match = _DAE_UNIT.search(handle.read(65536))
        value = float(match.group(1)) if match else 1.0
    except (OSError, ValueError):
        return 1.0
    return value if value > 0 and value == value and value != float("inf") else 1.0


def _read_mesh(path: Path, uri: str, limits: MeshLimits):
    import trimesh

    _check_size(path, uri, limits)
    # trimesh logs missing textures with tracebacks; a mesh's geometry is all urdftool reads
    logging.getLogger("trimesh").setLevel(logging.CRITICAL)
    try:
        loaded = trimesh.load(str(path), force="mesh", process=True)
    except Exception as error:  # trimesh raises many types for a bad file
        raise MeshProblem("corrupt", f"mesh '{uri}' does not load: {type(error).__name__}: "
                                     f"{error}") from None
    if not isinstance(loaded, trimesh.Trimesh) or len(loaded.faces) == 0:
        raise MeshProblem("corrupt", f"mesh '{uri}' holds no triangles")
    if len(loaded.faces) > limits.max_triangles:
        raise MeshProblem("too-large", f"mesh '{uri}' has {len(loaded.faces)} triangles, over "
                                       f"the limit of {limits.max_triangles}; decimate it")
    if path.suffix.lower() == ".dae" and collada_unit(path) != 1.0:
        loaded.apply_scale(collada_unit(path))
    return loaded


def load_mesh(robot, uri: str, scale=(1.0, 1.0, 1.0), limits: MeshLimits | None = None):
    """The mesh at ``uri`` scaled by ``scale`` (a trimesh.Trimesh; do not modify it).

    Loaded once per robot per (path, scale); problems are cached and raised again as
    MeshProblem. The triangle limit is ``robot.options["max_triangles"]`` (``check
    --max-triangles``) unless ``limits`` are given.
    """
    limits = limits or MeshLimits(max_triangles=robot.options.get("max_triangles",
                                                                  MAX_TRIANGLES))
    cache = robot.options.setdefault(_CACHE_KEY, {})
    path = resolve(robot, uri)
    scale = tuple(float(s) for s in scale)
    if not all(math.isfinite(s) for s in scale):
        raise MeshProblem("corrupt", f"mesh '{uri}' has a non-finite scale {scale}; not loaded")
    key = (path, scale)
    if key not in cache:
        raw_key = (path, (1.0, 1.0, 1.0))
        if raw_key not in cache:
            try:
                cache[raw_key] = _read_mesh(path, uri, limits)
            except MeshProblem as problem:
                cache[raw_key] = problem
        raw = cache[raw_key]
        if isinstance(raw, MeshProblem) or key == raw_key:
            cache[key] = raw
        else:
            scaled = raw.copy()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)  # overflow is reported below
                scaled.apply_scale(scale)
            finite_vertices = all(math.isfinite(v) for v in scaled.bounds.ravel())
            cache[key] = scaled if finite_vertices else MeshProblem(
                "corrupt", f"mesh '{uri}' scaled by {scale} has coordinates beyond floating "
                           "point range; not loaded")
    found = cache[key]
    if isinstance(found, MeshProblem):
        raise found
    return found


def unit_hint(extent: float) -> str | None:
    """A sentence naming the scale that would make a mesh of ``extent`` [m] plausible."""
    if extent > 5.0:
        for factor, unit in ((0.001, "millimetres"), (0.01, "centimetres")):
            if extent * factor <= 5.0:
                return (f"extent {extent:.4g} m looks like {unit}: "
                        f"scale=\"{factor:g} {factor:g} {factor:g}\" would fix it")
        return f"extent {extent:.4g} m is over 5 m"
    if 0 < extent < 0.001:
        return (f"extent {extent:.3g} m is under 1 mm; if the file is in metres but the scale "
                f"assumes millimetres, scale=\"1 1 1\" would make it {extent * 1000:.4g} m")
    return None
