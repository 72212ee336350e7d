"""U4xx: geometry, materials and meshes of links (what urdfdom refuses, and what it misses).

Mesh files are resolved, bounded and loaded by :mod:`urdftool.description.meshes` (once per run).
"""

from __future__ import annotations

import math

from urdftool.lint.catalogue import (NOT_LOADED, Conditional, Severity, Taken, UrdfdomDrops,
                                     rule, weighed)
from urdftool.numbers import number
from urdftool.description.urdf import SHAPE_ATTRIBUTES, SHAPES, version_problem
from urdftool.description.xml import child_list, children_named, first_child
from urdftool.description.xacro_text import dropped_under
from urdftool.description.values import finite, number_tuple, origin_pose, parse_numbers
from urdftool.description.values import number as attribute_number

ORIGIN_FIELDS = (("origin", "xyz"), ("origin", "rpy"))


def _link_name(element) -> str:
    while element is not None and element.tag != "link":
        element = element.getparent()
    return element.get("name", "?") if element is not None else "?"


def _parts(robot) -> list:
    """(link, holder, tag, origins, shape, kind) of each ``<visual>``, ``<collision>`` and
    ``<inertial>`` of every link, in document order, walked once per robot: most rules of this
    family read them, and each walk over lxml elements makes a proxy object for each child
    visited.

    tag: the holder's tag; origins: its ``<origin>`` children; shape: the first element inside
    its first ``<geometry>`` (None for an inertial, when there is no geometry or it is empty);
    kind: the shape's tag (None without a shape), read once: six rules ask (each read of an
    lxml tag makes a string: 140,000 on a 10,000-link robot).
    """
    return robot.memo(_parts, lambda: _walk_parts(robot))


def _walk_parts(robot) -> list:
    found = []  # appended to, not yielded: 30,000 parts on a 10,000-link robot
    for link in robot.children("link"):
        for holder in child_list(link):
            tag = holder.tag
            if tag != "visual" and tag != "collision" and tag != "inertial":
                continue
            children = robot.grouped(holder)  # one pass over its children, kept for U405/U406
            if tag == "inertial":
                found.append((link, holder, tag, children.get("origin", ()), None, None))
                continue
            geometry = children.get("geometry")
            shape = _first_element(geometry[0]) if geometry else None
            found.append((link, holder, tag, children.get("origin", ()), shape,
                          None if shape is None else shape.tag))
    return found


def _holders(robot, tags=("visual", "collision")):
    for link, holder, tag, _, _, _ in _parts(robot):
        if tag in tags:
            yield link, holder


def _first_element(geometry):
    """The shape inside a ``<geometry>``: its first child that is an element (not a comment).
    Steps over siblings (``getnext``), as :func:`~urdftool.description.xml.first_child` does:
    a generator over the children costs twice as much for the one step it usually takes."""
    if geometry is None or not len(geometry):
        return None
    child = geometry[0]
    while child is not None and not isinstance(child.tag, str):
        child = child.getnext()
    return child


def _capsule(robot) -> str:
    version = robot.root.get("version", "1.0").strip()
    if version_problem(version) is None and tuple(map(int, version.split("."))) >= (1, 1):
        return ("a URDF 1.1 shape: urdfdom 4 (ROS 2 Jazzy on) reads it, urdfdom 3 (ROS 2 "
                "Humble, Noetic) drops the element")
    return ("which urdfdom reads only in a robot of version=\"1.1\" (urdfdom 4, ROS 2 Jazzy "
            "on): here it drops the element, and ROS tools see no shape there; PyBullet, "
            "Isaac Gym and Drake read it")


# Shapes urdfdom does not read in every version but other URDF readers do -> why (robot).
_OTHER_READERS_SHAPES = {
    "capsule": _capsule,
    "plane": lambda robot: ("PyBullet's infinite ground: PyBullet reads it, urdfdom drops the "
                            "element and ROS tools see no shape there"),
}


@rule("U401", "missing-geometry", Severity.ERROR)
def missing_geometry(robot):
    """A ``<visual>`` or ``<collision>`` has no ``<geometry>``, an empty one, or an unknown shape.

    urdfdom drops the element with an error; simulators then see a link without collision.
    A shape other URDF readers know is a warning that names them, since the robot may be
    written for them: ``<capsule>``, which urdfdom 4 (ROS 2 Jazzy on) reads in a robot of
    ``version="1.1"`` and urdfdom 3 (Humble, Noetic) never does, and which PyBullet, Isaac Gym
    and Drake read (Fourier's GR1 models for Isaac Gym); PyBullet's ``<plane>`` (its ground,
    ``plane_implicit.urdf``).

    Bad: ``<collision><origin xyz="0 0 0.1"/></collision>``, ``<geometry><cone .../></geometry>``
    Good: ``<collision><geometry><cylinder radius="0.05" length="0.2"/></geometry></collision>``
    """
    for link, holder, tag, _, shape, kind in _parts(robot):
        if tag == "inertial" or kind in SHAPES:
            continue
        where = f"link '{link.get('name')}': <{tag}>"
        if kind in _OTHER_READERS_SHAPES:
            yield shape, Conditional(f"{where} has <{kind}>, "
                                     f"{_OTHER_READERS_SHAPES[kind](robot)}")
        elif shape is not None:
            yield shape, (f"{where} has unknown geometry <{kind}>; valid shapes: "
                          f"{', '.join(SHAPES)}")
        elif (geometry := robot.child(holder, "geometry")) is None:
            dropped = dropped_under(robot, holder, "geometry")
            yield holder, (f"{where} has no <geometry>: {dropped} (--arg NAME=VALUE checks "
                           "another build)" if dropped else
                           f"{where} has no <geometry>; add one (box, cylinder, sphere or mesh)")
        else:
            yield geometry, f"{where} <geometry> is empty; give box, cylinder, sphere or mesh"


def _shapes(robot) -> list:
    """(link, holder, shape element, its tag) of every known shape, found once per robot
    (four rules ask)."""
    return robot.memo(_shapes, lambda: [
        (link, holder, shape, kind) for link, holder, _, _, shape, kind in _parts(robot)
        if kind in SHAPES])


@rule("U402", "geometry-attribute", Severity.ERROR)
def geometry_attribute(robot):
    """A shape lacks a required attribute or its number does not parse.

    urdfdom requires ``box size`` (3 numbers), ``cylinder radius`` and ``length``, ``sphere
    radius`` and ``mesh filename``, all finite; otherwise it drops the whole visual/collision.

    Bad: ``<box size="0.1 0.2"/>``, ``<cylinder radius="0.05"/>``, ``<mesh/>``
    Good: ``<box size="0.1 0.2 0.3"/>``, ``<cylinder radius="0.05" length="0.2"/>``
    """
    sound: set = set()  # (count, text) found to be that many finite numbers (values repeat)
    for link, holder, shape, kind in _shapes(robot):
        for attribute, count in SHAPE_ATTRIBUTES[kind]:
            text = shape.get(attribute)
            if text is None or (count is None and not text.strip()):
                yield shape, f"{_shape_prefix(link, shape)} has no {attribute} attribute"
                continue
            if count is None or (count, text) in sound:
                continue
            values, problem = number_tuple(text, count)
            if problem:
                yield shape, f"{_shape_prefix(link, shape)} {attribute}: {problem}"
            elif not finite(values):
                yield shape, f"{_shape_prefix(link, shape)} {attribute}=\"{text}\" is not finite"
            else:
                sound.add((count, text))


def _shape_prefix(link, shape) -> str:
    """How U402's messages start (made for a finding only: 20,000 shapes on a large robot)."""
    return f"link '{link.get('name')}': <{shape.tag}>"


_DIMENSIONS = {tag: tuple((a, c) for a, c in fields if c is not None)
               for tag, fields in SHAPE_ATTRIBUTES.items()}  # the numbers of each shape


@rule("U403", "non-positive-dimension", Severity.ERROR)
def non_positive_dimension(robot):
    """A box size, radius, length or mesh scale is zero or negative.

    urdfdom accepts it, but collision checkers build a degenerate or inside-out shape and the
    geometry's volume (and so any inertia computed from it) is zero or negative.

    A negative mesh scale mirrors the mesh and is allowed; a zero scale is not. A ``<visual>``
    whose every dimension is zero (``<box size="0 0 0"/>``, ``<sphere radius="0"/>``) is an
    invisible marker of a virtual link, drawn as nothing and never collided with: not reported.
    A ``<collision>`` ``<sphere radius="0"/>`` is a **warning**: a point, which Drake reads as
    a contact point (its ``Sphere(0)`` is a documented special case; Drake's Atlas and Jaco
    models place their feet's and fingers' contacts so), and other checkers as no volume.

    Bad: ``<box size="0.1 0 0.3"/>``, ``<sphere radius="-0.02"/>``, ``scale="1 0 1"``
    Good: ``<box size="0.1 0.01 0.3"/>``, ``<sphere radius="0.02"/>``
    """
    positive: set = set()  # (attribute, count, text) found all positive (values repeat)
    for link, holder, shape, kind in _shapes(robot):
        fields = _DIMENSIONS[kind]
        if kind == "mesh" and shape.get("scale") is not None:
            fields = (("scale", 3),)
        texts = [(attribute, count, shape.get(attribute)) for attribute, count in fields]
        if positive.issuperset(texts):
            continue
        numbers = [number_tuple(text, count)[0] for _, count, text in texts]
        if all(values and all(v > 0 for v in values) for values in numbers):
            positive.update(texts)
            continue  # every number positive, as in most shapes: nothing to report
        if holder.tag == "visual" and kind != "mesh" and all(
                values and all(v == 0 for v in values) for values in numbers):
            continue  # a virtual link's invisible marker
        if kind == "sphere" and holder.tag == "collision" and numbers == [(0.0,)]:
            yield shape, (f"link '{link.get('name')}': <collision> <sphere radius="
                          f"\"{shape.get('radius')}\"> is a point: Drake reads it as a contact "
                          "point (its models' feet and fingertips), but it has no volume, "
                          "and other simulators and collision checkers may touch nothing with "
                          "it; give it a radius if it is not for Drake"), None, Severity.WARNING
            continue
        for (attribute, _), values in zip(fields, numbers):
            mirrored = attribute == "scale" and all(v != 0 for v in values or [0])
            if values and finite(values) and any(v <= 0 for v in values) and not mirrored:
                yield shape, (f"link '{link.get('name')}': <{kind} {attribute}="
                              f"\"{shape.get(attribute)}\"> has a value <= 0; dimensions must "
                              "be positive")


def _origin_fields(robot, sound: set):
    """(link, holder, element, attribute, its text) of every origin ``xyz``/``rpy`` and mesh
    ``scale`` written in a visual, collision or inertial, but those whose text is in ``sound``
    as each is read (texts found sound already, which the caller adds to: values repeat, and
    a large robot's 60,000 need not each be handed over)."""
    for link, holder, _, origins, shape, kind in _parts(robot):
        for origin in origins:
            for attribute in ("xyz", "rpy"):
                text = origin.get(attribute)
                if text is not None and text not in sound:
                    yield link, holder, origin, attribute, text
        if kind == "mesh" and (text := shape.get("scale")) is not None and text not in sound:
            yield link, holder, shape, "scale", text


@rule("U404", "malformed-link-number", Severity.ERROR)
def malformed_link_number(robot):
    """An ``<origin>`` of a visual, collision or inertial, or a mesh ``scale``, does not parse.

    urdfdom needs exactly three finite numbers and drops the whole element otherwise.

    Bad: ``<origin xyz="0 0.1"/>``, ``<mesh filename="a.stl" scale="0.001"/>``
    Good: ``<origin xyz="0 0.1 0"/>``, ``<mesh filename="a.stl" scale="0.001 0.001 0.001"/>``
    """
    sound: set = set()  # texts found to be three finite numbers (values repeat)
    for link, holder, element, attribute, text in _origin_fields(robot, sound):
        values, problem = number_tuple(text, 3)
        if problem is None and not finite(values):
            problem = f"'{text}' is not finite"
        if not problem:
            sound.add(text)
        else:
            yield element, (f"link '{link.get('name')}': <{holder.tag}> <{element.tag} "
                            f"{attribute}>: {problem}")


def _rgba_problem(color) -> str | None:
    values, problem = parse_numbers(color.get("rgba"), 4)
    if problem:
        return f"<color rgba>: {problem}"
    if not finite(values) or any(v < 0 or v > 1 for v in values):
        return f"<color rgba=\"{color.get('rgba')}\">: each component must be between 0 and 1"
    return None


def _defines(material) -> bool:
    return first_child(material, "color") is not None \
        or first_child(material, "texture") is not None


@rule("U405", "malformed-material", Severity.ERROR)
def malformed_material(robot):
    """A material is malformed: no name, no colour, a bad colour, or a name defined twice.

    A top-level material needs a name and a colour or texture; ``rgba`` is four numbers in
    [0, 1]. urdfdom refuses a robot whose top-level materials give one name twice ("material
    'red' is not unique"; two without a name are both '' to it): robot_state_publisher does not
    load it. The rest it logs and takes: a material without a name no visual can name, one
    without a colour colours nothing, a bad ``rgba`` is dropped. A visual's material without
    a name is worse: urdfdom stops reading the link there, and the link has none of its
    visuals from that one on, nor any collision.

    A **warning** naming the condition for a visual's material without a name in a file Drake
    or a web page reads, as its files say and nothing says ROS runs it (``xmlns:drake``; a web
    application's served copy that its source fetches): both read its colour.

    Bad: ``<material><color rgba="1 0 0"/></material>``
    Good: ``<material name="red"><color rgba="1 0 0 1"/></material>``
    """
    seen: set[str] = set()
    for material in robot.children("material"):
        name = material.get("name")
        if (name or "") in seen:  # (urdfdom names a material without the attribute '')
            yield material, ((f"material '{name}' is defined twice" if name is not None else
                              "a second top-level <material> named '' to urdfdom (it has no "
                              "name attribute)") + f" at the top level, so urdfdom refuses the "
                             f"robot (\"material '{name or ''}' is not unique\"): {NOT_LOADED}; "
                             "give each its own name")
        elif name is None:
            yield material, Taken("top-level <material> has no name attribute: no visual can "
                                  "name it")
        seen.add(name or "")
        if not _defines(material):
            yield material, Taken(f"top-level material '{name}' has neither <color rgba=...> "
                                  "nor <texture filename=...>")
    materials = robot.children("material") + [
        m for _, holder in _holders(robot, ("visual",))
        for m in robot.grouped(holder).get("material", ())]
    for material in materials:
        parent = material.getparent()
        if parent.tag == "visual" and material.get("name") is None:
            link = _link_name(parent)
            yield material, UrdfdomDrops(
                f"link '{link}': visual <material> has no name attribute, so urdfdom stops "
                f"reading the link there: '{link}' has none of its visuals from this one on, "
                "nor any collision (RViz draws none of them; MoveIt and Gazebo collide with "
                "nothing of it); name it (<material name=\"...\">)", {"drake", "browser"})
        for color in children_named(material, "color"):
            problem = _rgba_problem(color)
            if problem:
                yield color, Taken(f"material '{material.get('name')}': {problem}")


@rule("U406", "undefined-material", Severity.WARNING)
def undefined_material(robot):
    """A visual names a material that is defined nowhere, so it renders without colour.

    urdfdom warns ``material 'x' undefined``. A name-only reference must match a top-level
    ``<material>`` or an earlier visual's material that has a colour or texture (a later
    visual's definition is named: the order is urdfdom's). An empty name
    (``<material name=""/>``) refers to nothing: urdfdom looks up only names it is given
    (``material_name.length() > 0``, model.cpp), and the visual is drawn in the default colour,
    as without the element.

    Bad: ``<material name="gren"/>`` with only ``green`` defined
    Good: ``<material name="green"/>`` after ``<material name="green"><color .../></material>``
    """
    defined = {m.get("name") for m in robot.children("material") if _defines(m)}
    used = [(link, material) for link, holder in _holders(robot, ("visual",))
            for material in robot.grouped(holder).get("material", ()) if material.get("name")]
    later: dict[str, str] = {}  # a name a visual defines -> the link of its last definition
    for link, material in reversed(used):
        if _defines(material):
            later[material.get("name")] = link.get("name")
    for index, (link, material) in enumerate(used):
        name = material.get("name")
        if _defines(material):
            defined.add(name)
        elif name not in defined:
            from urdftool.errors import available
            definer = next((other.get("name") for other, element in used[index + 1:]
                            if element.get("name") == name and _defines(element)), None) \
                if name in later else None
            if definer is not None:  # (a name defined later, in the order urdfdom reads)
                yield material, (f"link '{link.get('name')}': material '{name}' is used before "
                                 f"it is defined (link '{definer}', later, defines it; urdfdom "
                                 "reads materials in order, so this visual has no colour)")
            else:
                yield material, (f"link '{link.get('name')}': material '{name}' is not "
                                 "defined; " + available('materials', name, defined))


# Meshes ------------------------------------------------------------------------------------

def _mesh_elements(robot):
    for link, holder, shape, kind in _shapes(robot):
        if kind == "mesh" and shape.get("filename"):
            yield link, holder, shape


def _mesh_outcomes(robot):
    """(link, holder, mesh element, MeshFacts or MeshProblem) per mesh element, once per robot."""
    return robot.memo(_mesh_outcomes, lambda: list(_load_meshes(robot)))


def _load_meshes(robot):
    elements = list(_mesh_elements(robot))
    if not elements:
        return  # (a robot of primitives: the mesh readers are not imported)
    from urdftool.description.meshes import MeshProblem, mesh_facts

    for link, holder, shape in elements:
        scale, _ = parse_numbers(shape.get("scale", "1 1 1"), 3)
        if not scale or not finite(scale):
            continue
        try:
            outcome = mesh_facts(robot, shape.get("filename"), scale)
        except MeshProblem as problem:
            outcome = problem
        yield link, holder, shape, outcome


def _problems(robot, kind: str):
    for link, holder, shape, outcome in _mesh_outcomes(robot):
        if getattr(outcome, "kind", None) == kind:
            uri = shape.get("filename")
            said = outcome.quoting(uri, _written_filename(robot, shape, uri))
            # a dependency the package.xml declares, or a file the repository leaves for a
            # tool to put in a folder kept empty: the workspace's, not the file's (a note); a
            # problem that may not hold after the package's build: a warning saying so
            yield shape, weighed(f"link '{link.get('name')}' <{holder.tag}>: {said}",
                                 outcome.certain, outcome.declared or outcome.kept_empty,
                                 outcome.repeated)  # (a package's: where it was looked for)


def _mesh_named(robot, link, holder, shape) -> str:
    """Where a mesh finding is and which mesh, as every mesh rule's message begins: "link 'L'
    <visual>: mesh 'WRITTEN' (expanded: 'URI')" (:func:`~urdftool.errors.mesh_quoted`)."""
    from urdftool.errors import mesh_quoted

    uri = shape.get("filename")
    return (f"link '{link.get('name')}' <{holder.tag}>: "
            f"{mesh_quoted(uri, _written_filename(robot, shape, uri))}")


def _written_filename(robot, shape, uri: str) -> str:
    """The ``filename`` of mesh element ``shape`` as its file writes it (before xacro expands
    ``$(find pkg)`` or ``${prefix}``), ``uri`` when not known or not read from a xacro."""
    if not robot.from_xacro:
        return uri
    from urdftool.lint.fixes.tags import Unfixable, source_tag

    found = source_tag(robot, shape)
    if isinstance(found, Unfixable) or "filename" not in found[1].attributes:
        return uri
    return found[1].attributes["filename"][2]


@rule("U407", "mesh-package-not-found", Severity.ERROR)
def mesh_package_not_found(robot):
    """A mesh's ``package://`` names a package that cannot be found.

    An error when the name is nearly that of a package found here (a misspelt or stale name)
    or a folder of its name above the robot file lacks the file. Otherwise a package not
    installed here is the environment's (as U006 reads a ``$(find)``), and the mesh is not
    checked: a **note** when the robot's package.xml declares it (installed wherever the
    package is built: install the dependencies; a question of the workspace, not of the
    file), a **warning** when it does not (rosdep would not install it: declare it).

    A warning, too, when the file is there for loaders that do not ask ROS:
    ``PACKAGE/PATH`` beside the robot file (onshape-to-robot's ``package://assets/part.stl``:
    PyBullet and Pinocchio given the robot's folder drop ``package://``), or in a folder of the
    package's name with no package.xml above the robot file in its repository (NASA's
    r2_description: a loader given the folder above as a package path finds it). ROS's
    resource_retriever finds neither.

    Bad: ``package://my_robot_descripton/meshes/base.stl``
    Good: the right package name, or ``--package my_robot_description=PATH``
    """
    yield from _problems(robot, "package")


@rule("U408", "mesh-not-found", Severity.ERROR)
def mesh_not_found(robot):
    """A mesh file does not exist.

    Every viewer and simulator fails or shows nothing for that link.

    ``package://NAME/...`` names the installed ``share/NAME``: a file missing from the source
    folder is looked for where the package's build (CMakeLists.txt ``install()``, setup.py or
    setup.cfg ``data_files``) installs it from. When those install rules cannot be read (a
    variable set in a loop, ``data_files`` built by walking folders), a file not found is a
    warning saying so, not an error (docs/packages.md). A warning too for a path xacro made
    from ``$(cwd)`` (the folder it runs in) when the file is there from a folder between the
    robot file and its repository's root: the message names the folder xacro must run in. A
    **note** for a file missing from a folder that holds only placeholders (``.gitkeep``,
    ``.keep``, ``.gitignore``): a folder kept empty in the repository for files a tool, a
    download or a build step puts there (Stretch's ``meshes/``, filled from a robot's
    calibration batch): the workspace's question, as U407's package a package.xml declares.
    A **warning** for a file the repository's ``.gitignore`` ignores (audibot's meshes, which
    its CMakeLists.txt unpacks from an archive; K-Scale's, which its tools download): no clone
    has it, and the message names the pattern; it is there only where something puts it.
    A **warning**, too, for a relative path with no scheme into a folder that is not beside
    the robot file and holds none of the repository's meshes (UWSim's
    ``robot/GIRONA500/hull.osg``, found on its data path ``~/.uwsim/data``; a YCB object's
    ``ycb/NAME/...``): a loader given a data or search path finds it there. And a **warning**
    for a relative path the robot's ``<mujoco><compiler meshdir=...>`` leads MuJoCo to (below
    that folder, or by its file name alone): MuJoCo finds it, loaders reading the path beside
    the file do not (Inspire's hand, ``meshdir="../collision/"`` and bare file names).

    The message names where the repository has the file: beside it in other capitals, or,
    when the folder it was looked for in holds no mesh at all (the folder is wrong, not the
    file), the one file of its name elsewhere, or of several the one below that folder (never
    another choice among several: another robot's ``base_link.STL`` is no advice).

    Bad: ``<mesh filename="package://robot/meshes/base.STL"/>`` when the file is ``base.stl``
    Good: the exact file name (case matters on Linux)
    """
    yield from _problems(robot, "missing")


@rule("U409", "mesh-outside-root", Severity.ERROR)
def mesh_outside_root(robot):
    """A ``file://`` or relative mesh path leaves the robot's repository (or package).

    urdftool does not open files outside the repository holding the robot (the nearest folder
    with ``.git``; without one, the robot's package or folder), nor outside a package for
    ``package://``: a description should not reach into the rest of a machine, and an absolute
    path works on one computer only. A **warning** for a file of a ROS distribution's install
    (``/opt/ros/DISTRO/share/PACKAGE/...``, as a generator writes it): it is there wherever
    that distribution and package are installed; ``package://PACKAGE/...`` says so anywhere.
    A ``file://`` path xacro made with ``$(find PACKAGE)`` names where that package is on the
    machine xacro runs on, on every machine, as ``package://PACKAGE/...`` does: it is read
    as that package's file (found by ``--package`` or the package path, outside the
    repository too), and is U409 only when it leaves the package. So is a relative path, or a
    ``package://`` path, that leads by ``..`` into a package found right there
    (``../../other_pkg/meshes/x.stl`` where other_pkg is found beside the robot's package):
    ``package://other_pkg/meshes/x.stl`` where the two packages are side by side.

    Bad: ``<mesh filename="file:///home/me/meshes/base.stl"/>``, ``filename="../../../x.stl"``
    Good: ``<mesh filename="package://my_robot/meshes/base.stl"/>``
    """
    yield from _problems(robot, "outside")


@rule("U410", "mesh-unsupported-format", Severity.WARNING)
def mesh_unsupported_format(robot):
    """A mesh file is not in a format urdftool opens (STL, DAE, OBJ, PLY, GLB, glTF, OFF).

    Such files (Ogre ``.mesh``, ``.blend``...) are not opened, so nothing about them is checked;
    most URDF consumers cannot read them either.

    Bad: ``<mesh filename="package://robot/meshes/base.mesh"/>``
    Good: ``<mesh filename="package://robot/meshes/base.stl"/>``
    """
    yield from _problems(robot, "format")


@rule("U411", "mesh-too-large", Severity.WARNING)
def mesh_too_large(robot):
    """A mesh file is over the size or triangle limit (128 MiB, 2,000,000 triangles); not opened.

    A mesh with a coordinate past 4.6e10 (in its own unit: urdftool merges vertices in 64-bit
    integers of 1e-8) is not measured either.

    Collision checking and inertia computation with such meshes is slow, and a crafted file could
    exhaust memory. Use a decimated collision mesh.

    Bad: a 5,000,000-triangle scan as collision geometry
    Good: a convex or decimated collision mesh of a few thousand triangles
    """
    yield from _problems(robot, "too-large")


@rule("U412", "mesh-unreadable", Severity.ERROR)
def mesh_unreadable(robot):
    """A mesh file exists but does not load (corrupt, truncated or empty).

    Also a COLLADA file that uses an XML entity it declares where geometry or names are
    written: pycollada (libxml2) expands it, Assimp (RViz) and Gazebo expand none.

    Bad: an STL file truncated by a failed download
    Good: a mesh that opens in a mesh viewer
    """
    yield from _problems(robot, "corrupt")


def _extent(mesh) -> float:
    return float(max(mesh.extents))


def _half_size(shape) -> float:
    """How far a primitive reaches from its origin [m]: half a box's largest side, a sphere's
    radius, a cylinder's half diagonal (0 when malformed or for a mesh)."""
    if shape.tag == "box":
        sides, _ = number_tuple(shape.get("size"), 3)
        return max(map(abs, sides)) / 2 if sides else 0.0
    radius = abs(attribute_number(shape, "radius", 0.0) or 0.0)
    if shape.tag == "cylinder":
        return math.hypot(radius, (attribute_number(shape, "length", 0.0) or 0.0) / 2)
    return radius if shape.tag == "sphere" else 0.0  # a mesh: its size is the question


def _link_spans(robot) -> dict[str, float]:
    """Each link's span [m]: the longest offset of the joints at it (its parent joint's origin,
    its child joints' origins), of its centre of mass (``<inertial><origin>``, which a CAD
    exporter computes from the part, in metres) and the farthest reach of its own visual and
    collision primitives (origin plus half size), the scale a mesh of that link has; infinite
    for a link with a ``<plane>`` (PyBullet's ground: any size fits it)."""
    def compute():
        spans: dict[str, float] = {}

        def reach(name, length):
            if name is not None and length > spans.get(name, 0.0):
                spans[name] = length

        for joint in robot.children("joint"):
            length = math.hypot(*origin_pose(joint)[0])
            for end in ("parent", "child"):
                element = first_child(joint, end)
                reach(element.get("link") if element is not None else None, length)
        for link in robot.children("link"):
            for holder in child_list(link):
                if holder.tag == "inertial":
                    reach(link.get("name"), math.hypot(*origin_pose(holder)[0]))
                    continue
                geometry = first_child(holder, "geometry") \
                    if holder.tag in ("visual", "collision") else None
                for shape in child_list(geometry) if geometry is not None else ():
                    if not isinstance(shape.tag, str):
                        continue
                    if shape.tag == "plane":  # PyBullet's infinite <plane>: the link is ground
                        reach(link.get("name"), math.inf)
                        continue
                    length = math.hypot(*origin_pose(holder)[0]) + _half_size(shape)
                    if math.isfinite(length):
                        reach(link.get("name"), length)
        return spans
    return robot.memo(_link_spans, compute)


def _static_model(robot) -> bool:
    """Whether Gazebo holds the whole model still: a ``<gazebo>`` without a reference whose
    ``<static>`` is true (SDF's bool: ``true`` or ``1``), as scenery spawned into a world is."""
    def compute():
        for gazebo in robot.children("gazebo"):
            if gazebo.get("reference") is None:
                static = first_child(gazebo, "static")
                if static is not None and (static.text or "").strip().lower() in ("true", "1"):
                    return True
        return False
    return robot.memo(_static_model, compute)


@rule("U413", "mesh-implausible-size", Severity.WARNING)
def mesh_implausible_size(robot):
    """A mesh, after its ``scale``, is over 5 m or under 1 mm across: probably the wrong unit.

    CAD exports are often in millimetres while URDF is in metres; the robot then looks 1000 times
    too big, and any inertia computed from the mesh is 10^6 too big. A size outside that window
    is a unit slip only when the rescaled mesh would fit its link: within 10 times the link's
    span (the longest offset of the joints at the link or of its centre of mass, or the reach of
    its own boxes, cylinders and spheres). A 5 m boat hull whose thrusters sit 2.4 m from its
    origin, or whose collision boxes reach 1.3 m (osrf/vrx's WAM-V), a 0.5 mm marker at a
    fingertip 27 mm from its knuckle (Unitree's BrainCo hand), or a 132 m bridge whose centre
    of mass, as its CAD exporter computed it, lies 14.7 m below its origin (an underwater
    inspection world's pier), is the size it means; a link with none of these is judged by the
    window alone.

    A model Gazebo holds static as a whole (``<gazebo><static>true</static></gazebo>`` without
    a reference) is scenery, not a robot: a building, a terrain or a field is the size it shows,
    so only the lower bound holds there (a 44 m office spawned beside a robot; a dock exported
    in millimetres without its scale goes unsaid).

    Fix (safe): the ``scale`` that brings it to a plausible size (x 0.001 or 0.01 for a mesh
    too large, x 1000 or 100 for one too small), written or multiplied into the one there.

    Bad: ``<mesh filename="base.stl"/>`` for a file in millimetres (extent 350 m)
    Good: ``<mesh filename="base.stl" scale="0.001 0.001 0.001"/>``
    """
    for link, holder, shape, outcome in _mesh_outcomes(robot):
        if not hasattr(outcome, "extents"):
            continue
        extent = _extent(outcome)
        scale, _ = parse_numbers(shape.get("scale", "1 1 1"), 3)
        factor = None
        if extent > 5.0 and _static_model(robot):
            continue
        if extent > 5.0:
            factor = next((f for f in (0.001, 0.01) if extent * f <= 5.0), None)
        elif 0 < extent < 0.001:
            factor = next((f for f in (1000.0, 100.0) if extent * f >= 0.001), None)
        else:
            continue
        span = _link_spans(robot).get(link.get("name"), 0.0)
        if span > 0 and factor and not span / 10 <= extent * factor <= span * 10:
            continue
        where = _mesh_named(robot, link, holder, shape)
        if factor is None:
            yield shape, f"{where} is {number(extent)} m across; check its unit"
            continue
        fixed = " ".join(f"{s * factor:g}" for s in scale)
        from urdftool.lint.fixes import offer, set_attribute  # (only for a finding)
        yield offer(shape, (f"{where} is {number(extent)} m across, which suggests the wrong "
                            f"unit; scale=\"{fixed}\" would make it {number(extent * factor)} m"),
                    f"scale the mesh by {factor:g}", set_attribute(robot, shape, "scale", fixed))


@rule("U414", "mesh-not-watertight", Severity.INFO)
def mesh_not_watertight(robot):
    """A mesh that defines a link's inertia is not closed (watertight).

    That is the link's collision mesh, or its visual mesh when it has no collision. An open mesh has no well-defined volume, so ``urdftool inertia`` uses its convex hull; the
    mesh is fine for display and usually for collision. Closed means every edge joins exactly
    two triangles once corners at one position (to 1e-8) are one vertex: a seam, where a
    COLLADA or OBJ file keeps corners apart because their normals or texture coordinates
    differ, is no hole (trimesh alone calls such meshes open).

    Bad: an STL with holes as the only collision geometry of a link
    Good: a closed (watertight) collision mesh
    """
    for link, holder, shape, outcome in _mesh_outcomes(robot):
        feeds = holder.tag == "collision" or first_child(link, "collision") is None
        if feeds and hasattr(outcome, "is_watertight") and not outcome.is_watertight:
            yield shape, (f"{_mesh_named(robot, link, holder, shape)} is not watertight; its "
                          "inertia is taken from its convex hull")


@rule("U415", "empty-package-name", Severity.WARNING)
def empty_package_name(robot):
    """A mesh URI ``package:///NAME/...`` has an empty package name.

    Pinocchio looks the path after ``package://`` up below each of its package directories, so
    this form works there, and urdftool resolves it the same way (``NAME`` as the package). ROS's
    resource_retriever, which RViz, Gazebo and MoveIt load meshes through, takes the empty text
    before the third slash as the package name and fails. A bare file name after the third
    slash (``package:///foot.stl``, as onshape-to-robot writes with no package) names no
    package at all: the message says to put the file in one.

    Bad: ``<mesh filename="package:///talos_data/meshes/arm.stl"/>``
    Good: ``<mesh filename="package://talos_data/meshes/arm.stl"/>``
    """
    from urdftool.description.packages import package_uri_parts

    for link, holder, shape in _mesh_elements(robot):
        uri = shape.get("filename")
        if uri.startswith("package:///"):
            name, tail = package_uri_parts(uri)
            if not tail:  # 'package:///foot.stl': a file name, no folder to take for the package
                yield shape, (f"{_mesh_named(robot, link, holder, shape)} has an "
                              f"empty package name and no folder; Pinocchio looks '{name}' up "
                              "directly in its package directories, ROS's resource_retriever "
                              "(RViz, Gazebo, MoveIt) cannot resolve it: put the file in a "
                              f"package and write 'package://PACKAGE/{name}'")
                continue
            yield shape, (f"{_mesh_named(robot, link, holder, shape)} has an empty "
                          f"package name; Pinocchio (and urdftool) read it as package '{name}', "
                          "ROS's resource_retriever (RViz, Gazebo, MoveIt) cannot resolve it: "
                          f"write 'package://{name}/{tail}'")


@rule("U416", "mesh-not-well-formed", Severity.WARNING)
def mesh_not_well_formed(robot):
    """A mesh is not well-formed XML, has non-finite vertices, or an invalid glTF node transform.

    assimp, through which RViz, Gazebo and MoveIt load meshes, reads such XML anyway, and so
    does urdftool (as libxml2's recover mode repairs it, then checks the mesh); readers that
    need well-formed XML (pycollada, hence trimesh and tools built on them) refuse the file.
    A triangle on a vertex at ``nan``, ``inf`` or past the float range (``1e400``) is left out
    by trimesh, so urdftool checks the rest (its bounds, volume and inertia) without it, while
    what a renderer or a physics engine makes of it differs (a bounding box of ``nan``).

    A glTF node's transform is applied as trimesh and assimp apply it: its translation, rotation
    and scale (a mirror too) as every loader does. glTF requires a node's ``matrix`` to be such
    a transform and its ``rotation`` a unit quaternion; one that shears, has a bottom row other
    than ``0 0 0 1``, a scale of 0 or a rotation of another length is said here, with what
    trimesh (hence urdftool) and assimp (Gazebo, RViz) make of it: they differ on a rotation
    that is not unit (trimesh normalises it, assimp does not).

    Bad: ``<node id="<STL_BINARY>">`` (a ``<`` inside an attribute value); ``v nan 0 0`` in an
    OBJ used by a face; a glTF node ``"matrix": [1, 0, 0, 0, 0.5, 1, ...]`` (a shear)
    Good: ``<node id="STL_BINARY">``, or the file exported again
    """
    outcomes = _mesh_outcomes(robot)
    if not outcomes:
        return  # (no mesh: the mesh readers are not imported)
    from urdftool.description.meshes import read_as_assumed

    for link, holder, shape, outcome in outcomes:
        for said in read_as_assumed(getattr(outcome, "metadata", {})):
            yield shape, f"{_mesh_named(robot, link, holder, shape)}{said}"
