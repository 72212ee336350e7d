"""The programs that load a URDF, as ``check --target`` names them and ``crosscheck`` runs them,
and what each does with a URDF, by version: the one owner of these facts.

Each fact was observed with the loader named in :data:`VERIFIED` (loading small robots made for
it, kept as the tests of the rules that use it: ``tests/lint/rules/test_portability.py``), or,
where a version could not be run here, read in the loader's source (the source is named). The
rules of the portability family (``urdftool.lint.rules.portability``) read them from here and
never hold a loader fact of their own.

A target is written ``NAME`` (the newest behaviour known) or ``NAME@VERSION`` (``mujoco@3.6``):
facts that changed between versions are :class:`Since` tables.
"""

from __future__ import annotations


from urdftool.errors import UsageError
from urdftool.records import Frozen


class Simulator(Frozen):
    """One program that loads a URDF.

    name: the target name (``--target NAME``)
    title: how people name it, in messages
    reads_with: the call or command that loads a URDF, as the facts were observed with it
    loader: the crosscheck loader that runs it here, or None (it cannot run in a process of
        ours: Gazebo Classic, Isaac Sim)
    """

    name: str
    title: str
    reads_with: str
    loader: str | None

    __slots__ = ("name", "title", "reads_with", "loader")

    def __init__(self, name: str, title: str, reads_with: str, loader: str | None) -> None:
        set_field = object.__setattr__
        set_field(self, "name", name)
        set_field(self, "title", title)
        set_field(self, "reads_with", reads_with)
        set_field(self, "loader", loader)


SIMULATORS = {s.name: s for s in (
    Simulator("gazebo", "Gazebo Classic", "gz sdf -p (sdformat 9, Gazebo 11)", None),
    Simulator("gz", "Gazebo (gz sim)", "gz sdf -p / ign sdf -p (sdformat 12 and later)",
              "sdformat"),
    Simulator("mujoco", "MuJoCo", "mujoco.MjModel.from_xml_path", "mujoco"),
    Simulator("drake", "Drake", "pydrake Parser(plant).AddModels with "
              "AddMultibodyPlantSceneGraph", "drake"),
    Simulator("pybullet", "PyBullet", "pybullet.loadURDF (default flags)", "pybullet"),
    Simulator("isaac", "Isaac Sim", "the Isaac Sim URDF importer", None),
    Simulator("pinocchio", "Pinocchio", "pinocchio.buildModelFromUrdf", "pinocchio"),
)}
TARGETS = tuple(SIMULATORS)

# The versions each fact below was observed with (or read in, for the sdformat 9 of Gazebo
# Classic and the Isaac importer, which do not run here).
VERIFIED = {
    "mujoco": "4.0.0",
    "pybullet": "3.2.7",
    "drake": "1.51.1",
    "gz": "12.3.0",  # sdformat, through `ign sdf` (Debian's libsdformat12 + ignition-tools)
    "gazebo": "9.10",  # sdformat 9, read in its parser_urdf.cc: the same code as 12 here
    "isaac": None,  # the importer's name rule, read in its source (UrdfParser.cpp)
    "pinocchio": "4.1.0",
}


class Target(Frozen):
    """A target as asked for: a simulator, and the version whose behaviour to predict (None:
    the newest known)."""

    name: str
    version: tuple[int, ...] | None

    __slots__ = ("name", "version")

    def __init__(self, name: str, version: tuple[int, ...] | None = None) -> None:
        set_field = object.__setattr__
        set_field(self, "name", name)
        set_field(self, "version", version)

    @property
    def simulator(self) -> Simulator:
        return SIMULATORS[self.name]

    @property
    def title(self) -> str:
        return self.simulator.title

    def __str__(self) -> str:
        return self.name if self.version is None else \
            f"{self.name}@{'.'.join(map(str, self.version))}"


def parse_target(text: str) -> Target:
    """``NAME`` or ``NAME@VERSION`` as a Target; UsageError naming the valid names otherwise."""
    name, _, version = str(text).strip().partition("@")
    name = name.strip().lower()
    if name not in SIMULATORS:
        from urdftool.errors import available

        raise UsageError(f"unknown target '{text}'; " + available("targets", name, TARGETS))
    if not version:
        return Target(name)
    try:
        numbers = tuple(int(part) for part in version.strip().split("."))
    except ValueError:
        raise UsageError(f"target '{text}': the version must be numbers separated by dots, "
                         f"such as {name}@3.6") from None
    return Target(name, numbers)


class Since(Frozen):
    """A fact that changed with a version: ``values`` is ((first version, value), ...) in
    version order; a version before the first has ``before``."""

    before: object
    values: tuple

    __slots__ = ("before", "values")

    def __init__(self, before: object, values: tuple) -> None:
        set_field = object.__setattr__
        set_field(self, "before", before)
        set_field(self, "values", values)

    def at(self, version: tuple[int, ...] | None):
        value = self.before
        for first, then in self.values:
            if version is None or version >= first:
                value = then
        return value


# ---- MuJoCo ----------------------------------------------------------------------------------
# Mesh files MuJoCo decodes (src/user/user_mesh.cc and its decoder plugins): STL and OBJ (OBJ
# since 2.1.2), MSH; any other extension: "no decoder found for mesh file" (observed 4.0.0 with
# .dae, .glb, .gltf, .ply), for a <collision> always and for a <visual> when visuals are kept.
MUJOCO_MESH_FORMATS = Since(frozenset({".stl", ".msh"}),
                            (((2, 1, 2), frozenset({".stl", ".msh", ".obj"})),))
# compiler/strippath, which the URDF reader forced to "true" until 3.7.0 (changelog 3.7.0, item
# 13, commit 7ae07d81): a mesh's folders were dropped and its file looked for in meshdir (the
# URDF's folder by default). Since then a filename is a path as written: package://p/m.stl is
# the relative path "package:/p/m.stl" ("Error opening file", observed 4.0.0).
MUJOCO_STRIPS_PATHS = Since(True, (((3, 7, 0), False),))
# compiler/discardvisual is "true" for URDF unless the file's <mujoco><compiler> says otherwise:
# every <visual> is dropped, so a visual mesh that is missing or in an unknown format is never
# opened (observed 4.0.0).
MUJOCO_DISCARDS_VISUALS = True


def mujoco_compiler(root):
    """The ``<mujoco><compiler>`` of a robot's ``<robot>`` element that MuJoCo's URDF importer
    reads (the first ``<mujoco>`` child and its first ``<compiler>``: xml_urdf.cc), or None."""
    block = root.find("mujoco")
    return block.find("compiler") if block is not None else None

# An explicit <inertial> is checked for every body, moving or not (user_objects.cc): principal
# moments must be positive ("inertia must have positive eigenvalues") and satisfy A + B >= C
# ("inertia must satisfy A + B >= C; use 'balanceinertia' to fix"); a moving body needs mass
# and inertia above mjMINVAL ("mass and inertia of moving bodies must be larger than
# mjMINVAL"). A link without <inertial> takes its inertia from its collision geoms at density
# 1000 kg/m^3 (inertiafromgeom="auto").
MUJOCO_MINVAL = 1e-15  # mjMINVAL
# Joint limits (xml_urdf.cc, Joint): the range is dropped when only one of lower/upper is
# written or lower > upper (silently), and when lower == upper (4.0.0 prints "has equal lower
# and upper limits, limit ignored"); a <continuous> joint's lower/upper are read as a range.
# Fixed joints (fusestatic, "true" for URDF): a link with no joint to its parent is fused into
# it, and the root is fused into the world: its name, frame and mass are gone (observed 4.0.0).

# ---- PyBullet --------------------------------------------------------------------------------
# UrdfFindMeshFile.h: the last four characters of a mesh filename must be .dae, .stl, .obj or
# .cdf (any case), else "invalid mesh filename extension" and the load fails. package:// (and
# model://) is cut off, then the rest is tried as given (the working directory), below every
# folder above the URDF file, and below ".", "..", "../.."; not found: the load fails, for a
# <visual> as for a <collision> (observed 3.2.7).
PYBULLET_MESH_EXTENSIONS = frozenset({".dae", ".stl", ".obj", ".cdf"})
# BulletUrdfImporter::loadURDF reads the file with readLine into an 8192-byte buffer and appends
# a line break after each piece: a line longer than 8191 bytes is cut every 8191 bytes, and a
# cut inside a tag breaks the XML ("Cannot load URDF file", observed 3.2.7 with one-line
# robots of 11 kB and more).
PYBULLET_LINE_BUFFER = 8191
# UrdfParser: a link without <inertial> gets mass 1 kg and inertia diag(1, 1, 1), except a
# root link named "world" (mass 0). Without flags=URDF_USE_INERTIA_FROM_FILE every inertia is
# replaced by the collision shapes' (getMassAndInertia2); lower > upper leaves the joint
# without limits; <mimic> is not read (observed 3.2.7).

# ---- Drake -----------------------------------------------------------------------------------
# With a SceneGraph (AddMultibodyPlantSceneGraph), a <collision> mesh becomes a convex hull,
# which Drake makes only from .obj, .vtk and .gltf ("MakeConvexHull only applies to .obj, .vtk,
# and .gltf meshes", observed 1.51.1 with .stl, .dae, .glb, .ply). Every mesh and texture file
# must exist ("URI ... which does not exist"), and package:// must name a package of the
# parser's PackageMap ("refers to unknown package"). lower > upper fails a check in Joint()
# (observed 1.51.1: the load stops); a <mimic> on a joint without the leader's degrees of
# freedom is refused ("which has 0 DOF cannot mimic"); a robot with no "world" link gets a
# floating joint (7 positions) on its root.
DRAKE_HULL_FORMATS = frozenset({".obj", ".vtk", ".gltf"})

# sdformat's test for a link without mass, after lumping: ignition::math::equal(mass, 0.0)
# (|mass| <= 1e-6) in 9.9 and 12; mass <= 0 from 9.10 and 13 on.
SDFORMAT_MASSLESS = {"gz": Since(1e-6, (((13, 0, 0), 0.0),)),
                     "gazebo": Since(1e-6, (((9, 10, 0), 0.0),))}
# Before 13 (9.10 for Gazebo Classic) the test applied to a lumped link too: a link on a fixed
# joint without mass (its own <inertial>, with what was lumped into it) was skipped with every
# link below it, though its inertial went to the parent (observed 12.3.0: iCub's r_hip_3 and
# l_hip_3, <mass value="0"/> on fixed joints, take both legs out of the model).
SDFORMAT_DROPS_LUMPED = {"gz": Since(True, (((13, 0, 0), False),)),
                         "gazebo": Since(True, (((9, 10, 0), False),))}

# ---- sdformat (gz, gazebo) -------------------------------------------------------------------
# parser_urdf.cc (the same in 9.10 and 12 to 16 here): fixed joints are lumped: the child's
# inertial, visuals, collisions and <gazebo> blocks move into the parent and its frame is gone,
# unless <gazebo reference="JOINT"><preserveFixedJoint>true</preserveFixedJoint></gazebo>.
# Lumping adds masses with 1 / (m_parent + m_child): a child with an <inertial> of mass 0 into
# a parent of mass 0 gives NaN ("Pose values must be finite": the file is refused, observed
# 12.3.0). After lumping, a link (not named "world") without <inertial> or with mass <= 0 is
# not modelled, with its parent joint and every link below it (silently in 12; a warning from
# 9.10 and 13 on); when that is the root the model has no link ("A model must have at least one
# link": refused). lower > upper is swapped ("switching the two"). The validity check (ign sdf
# -k) refuses a tensor whose principal moments are negative or break the triangle inequality
# ("has invalid inertia", observed 12.3.0).

# ---- Isaac Sim -------------------------------------------------------------------------------
# The importer (isaac-sim/urdf-importer-extension, UrdfParser.cpp) names each link and joint
# prim makeValidUSDIdentifier(name): pxr::TfMakeValidIdentifier (every character but a letter,
# digit or _ becomes _, a leading digit too), then "a" before a leading _ (a warning when the
# name was not a valid identifier).

# ---- Pinocchio -------------------------------------------------------------------------------
# buildModelFromUrdf(path) reads <mimic> only with mimic=True (4.x): by default the follower
# is a free joint of its own (observed 4.1.0).


def version_text(version: tuple[int, ...] | None, name: str) -> str | None:
    """The version facts apply to, as messages say it: the asked one, or the verified one
    (None: facts read in a source that has no version)."""
    return ".".join(map(str, version)) if version is not None else VERIFIED[name]


__all__ = ["SIMULATORS", "TARGETS", "VERIFIED", "Simulator", "Since", "Target", "parse_target",
           "version_text"]
