"""Mesh files named by a robot: resolve, refuse what is unsafe, load once, measure.

One package serves the mesh rules, ``urdftool inertia`` and the collision tools, so every mesh
goes through the same checks before trimesh touches it. One module per concept:

- :mod:`.uris`: where a URI leads and whether it may be opened (containment, extensions);
- :mod:`.counting`: triangle counts read from the file's bytes before anything builds it;
- :mod:`.reading`: the file read within its limits, through trimesh (:func:`load_mesh`);
- :mod:`.run_cache`: what was read and measured, kept between the robots of a process within
  a byte bound;
- :mod:`.measures`: what the checks measure (:func:`mesh_facts`), without trimesh where the
  format allows.

Every file is read through :mod:`urdftool.description.files` (and so recorded).
"""

from urdftool.description.inputs import MeshLimits
from urdftool.description.meshes.counting import triangle_count
from urdftool.description.meshes.measures import MeshFacts, mesh_facts
from urdftool.description.meshes.reading import NODE_TRANSFORM, NOT_FINITE, NOT_WELL_FORMED, \
    collada_unit, converted, load_mesh, read_as_assumed
from urdftool.description.meshes.uris import MESH_EXTENSIONS, resolve
from urdftool.errors import MeshProblem

__all__ = ["MESH_EXTENSIONS", "NODE_TRANSFORM", "NOT_FINITE", "NOT_WELL_FORMED", "MeshFacts", "MeshLimits", "MeshProblem",
           "collada_unit", "converted", "load_mesh", "mesh_facts", "read_as_assumed", "resolve",
           "triangle_count"]
