"""U92x-U98x: simulator portability. What each simulator or loader refuses, or silently changes,
in a description that urdfdom accepts; one decade of codes per target.

These rules run only for the targets asked for (``urdftool check --target mujoco``, or
``targets = ["mujoco", "gz"]`` in the settings), and each finding names its target, in its
message and in the ``target`` field of every machine format. A finding is an **error** when
that program refuses the file (its load fails), a **warning** when it loads it and changes what
it means without a word, a **note** for what the program's caller decides.

The loaders' behaviour is data in :mod:`urdftool.simulators`, by version, with the versions it
was observed with; ``--target NAME@VERSION`` predicts an older version where it differs. Each
rule is tested against its real loader (``tests/lint/rules/test_portability.py``: the small
robot of its case file is loaded, and the loader must fail, or change the meaning, as the rule
says; skipped with the reason when that loader is not installed).

=========  ==========================  ========================================================
decade     target                      loader the facts were observed with
=========  ==========================  ========================================================
U92x       ``mujoco``                  MuJoCo 4.0.0 (``MjModel.from_xml_path``)
U93x       ``pybullet``                PyBullet 3.2.7 (``loadURDF``, default flags)
U94x       ``drake``                   Drake 1.51.1 (``Parser.AddModels`` with a SceneGraph)
U95x       ``gz``                      sdformat 12.3.0 (``ign sdf -p``, ``-k``)
U96x       ``gazebo`` (Gazebo Classic)  sdformat 9 (read in its source: the same code paths)
U97x       ``isaac``                   the Isaac Sim URDF importer (read in its source)
U98x       ``pinocchio``               Pinocchio 4.1.0 (``buildModelFromUrdf``)
=========  ==========================  ========================================================
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from urdftool import simulators as facts
from urdftool.description.files import kind_of, no_file_there
from urdftool.numbers import number
from urdftool.description.urdf import DEGREES, LIMITED, VARIABLE
from urdftool.description.values import limit_range, number_tuple, origin_pose
from urdftool.description.xml import attribute, child_list, first_child
from urdftool.lint.catalogue import Severity, rule
from urdftool.physics import mat3

# ---- the robot as the loaders see it ---------------------------------------------------------


@dataclass
class _Tree:
    """The kinematic tree by link name, read once per robot.

    parent: child link -> (joint element, parent link); children: link -> [(joint, child)] in
    joint-name order (urdfdom's std::map, which sdformat's lumping walks); roots: links without
    a parent joint, in document order
    """

    parent: dict = field(default_factory=dict)
    children: dict = field(default_factory=dict)
    roots: list = field(default_factory=list)


def _tree(robot) -> _Tree:
    return robot.memo(_tree, lambda: _read_tree(robot))


def _read_tree(robot) -> _Tree:
    tree = _Tree()
    for joint, ends in robot.ends().items():
        parent, child = ends["parent"][1], ends["child"][1]
        if parent is None or child is None or child in tree.parent:
            continue
        tree.parent[child] = (joint, parent)
        tree.children.setdefault(parent, []).append((joint, child))
    for listed in tree.children.values():
        listed.sort(key=lambda pair: pair[0].get("name") or "")
    tree.roots = [name for name in robot.links if name not in tree.parent]
    return tree


def _type(joint) -> str:
    return joint.get("type") or ""


def _name(element) -> str:
    return element.get("name") or "?"


def _has_world(robot) -> bool:
    return "world" in robot.links


def _version(robot, target: str):
    return robot.targets.get(target)


def _as_of(robot, target: str) -> str:
    """``MuJoCo 4.0.0``: the program and the version a message speaks of."""
    title = facts.SIMULATORS[target].title
    version = facts.version_text(_version(robot, target), target)
    if target in ("gz", "gazebo"):
        return f"{title} (sdformat {version})"
    return f"{title} {version}" if version else title


def _meshes(robot):
    """(link, holder, mesh element, filename) of every mesh, in document order."""
    for link in robot.children("link"):
        for holder in child_list(link):
            if holder.tag not in ("visual", "collision"):
                continue
            geometry = first_child(holder, "geometry")
            mesh = first_child(geometry, "mesh") if geometry is not None else None
            if mesh is not None and mesh.get("filename"):
                yield link, holder, mesh, mesh.get("filename")


def _extension(filename: str) -> str:
    return Path(filename.split("?")[0]).suffix.lower()


def _exists(robot, filename: str) -> Path | None:
    """Where urdftool finds the mesh file, None when it does not exist (or may not be read)."""
    from urdftool.description.meshes import resolve
    from urdftool.errors import MeshProblem

    try:
        return resolve(robot, filename)
    except MeshProblem as problem:
        if problem.kind == "format":  # a file with an extension urdftool does not open
            try:
                found = robot.resolve_uri(filename)
                return found if kind_of(found) == "file" else None
            except Exception:  # noqa: BLE001 - an unknown package: not found
                return None
        return None
    except Exception:  # noqa: BLE001 - an unresolvable URI is not a file
        return None


def _where(link, holder) -> str:
    return f"link '{_name(link)}' <{holder.tag}>"


def _body(link):
    from urdftool.physics.mass import declared

    return declared(link)


def _mass_of(link) -> float | None:
    """The ``<inertial>``'s mass, None without one (or when it is not a number)."""
    inertial = first_child(link, "inertial")
    mass = first_child(inertial, "mass") if inertial is not None else None
    if mass is None:
        return None
    value = number_tuple(mass.get("value"), 1)[0]
    return value[0] if value else None


# ---- frames other files and blocks refer to --------------------------------------------------

# Gazebo plugin parameters that Gazebo looks up as a link of the model (p3d, force, planar
# move): a frame_name/frameName is only written into messages, for TF, which has every link.
PLUGIN_LINK_TAGS = ("bodyName", "body_name", "link_name", "linkName")


def _references(robot, simulator: str) -> list:
    """(frame name, where, what refers to it) for each reference to a link by name that looks
    the link up in ``simulator``'s model: for Gazebo (``gz``, ``gazebo``), its plugins' link
    parameters (a ``<gazebo reference>`` block and its sensors move with a lumped link); for
    MuJoCo, a ``<ros2_control>`` sensor's ``frame_id`` and the SRDF (chains, groups' links, end
    effectors' parent links), read by controllers and planners that run on its model."""
    return robot.memo((_references, simulator),
                      lambda: list(_read_references(robot, simulator)))


def _read_references(robot, simulator: str):
    if simulator in ("gz", "gazebo"):
        for gazebo in robot.children("gazebo"):
            for element in gazebo.iter(*PLUGIN_LINK_TAGS):
                if element.text and element.text.strip():
                    yield (element.text.strip(), element,
                           f"Gazebo plugin parameter <{element.tag}>")
        return
    for control in robot.children("ros2_control"):
        for param in control.iterfind("sensor/param"):
            if param.get("name") == "frame_id" and param.text and param.text.strip():
                yield param.text.strip(), param, "a ros2_control sensor's frame_id"
    from urdftool.description.companions import companions

    try:
        srdf = companions(robot).srdf
    except Exception:  # noqa: BLE001 - the SRDF rules report an SRDF that cannot be read
        srdf = None
    if srdf is None or srdf.root is None:
        return
    for path, attribute, what in (("group/link", "name", "an SRDF group"),
                                  ("group/chain", "base_link", "an SRDF chain"),
                                  ("group/chain", "tip_link", "an SRDF chain tip (MoveIt)"),
                                  ("end_effector", "parent_link", "an SRDF end effector")):
        for element in srdf.root.iterfind(path):
            if element.get(attribute):
                yield element.get(attribute), srdf.at(element.sourceline), what


def _referenced_removals(robot, removed: dict, simulator: str):
    """(where, name, what refers to it, where it went) for each reference to a frame in
    ``removed`` (link -> the link it went into)."""
    for name, where, what in _references(robot, simulator):
        if name in removed and name in robot.links:
            yield where, name, what, removed[name]


def _inverted(robot):
    """(joint, its <limit>, lower, upper) of each revolute or prismatic joint whose lower limit
    is above its upper one (:func:`~urdftool.description.values.limit_range`: a missing bound
    is 0)."""
    for joint in robot.children("joint"):
        limit = first_child(joint, "limit")
        bounds = limit_range(_type(joint), limit)
        if bounds is not None and bounds[0] > bounds[1]:
            yield joint, limit, *bounds


# ==== MuJoCo (U92x) ===========================================================================

def _mujoco_setting(robot, name: str, default: bool) -> bool:
    compiler = facts.mujoco_compiler(robot.root)
    value = compiler.get(name) if compiler is not None else None
    return default if value is None else value.strip().lower() == "true"


def _mujoco_reads(robot, holder) -> bool:
    """Whether MuJoCo reads this <visual>/<collision> (it discards visuals by default)."""
    return holder.tag == "collision" or not _mujoco_setting(robot, "discardvisual",
                                                           facts.MUJOCO_DISCARDS_VISUALS)


def _compiler_fix(robot, where, message: str, attributes: dict, description: str):
    """The finding with a fix adding (or completing) ``<mujoco><compiler .../></mujoco>``, which
    only MuJoCo reads."""
    text = " ".join(f'{key}="{attribute(str(value))}"' for key, value in attributes.items())
    compiler = facts.mujoco_compiler(robot.root)
    from urdftool.lint.fixes import Unfixable, append_child, insert_before, offer, set_attribute

    if compiler is not None:

        edits = []
        for key, value in attributes.items():
            found = set_attribute(robot, compiler, key, value)
            if isinstance(found, Unfixable):
                return offer(where, message, description, found, safe=False)
            edits.extend(found)
        return offer(where, message, description, edits, safe=False)
    block = f"<mujoco>\n  <compiler {text}/>\n</mujoco>"
    first = next(iter(child_list(robot.root)), None)
    edits = insert_before(robot, first, f"<mujoco><compiler {text}/></mujoco>") \
        if first is not None else append_child(robot, robot.root, block)
    return offer(where, message, description, edits, safe=False)


@rule("U920", "mujoco-package-uri", Severity.ERROR)
def mujoco_package_uri(robot):
    """MuJoCo cannot open a mesh named by ``package://`` (or another URI scheme).

    MuJoCo knows no ROS packages. Since 3.7.0 it reads a mesh filename as a path, so
    ``package://robot/meshes/base.stl`` is the relative path ``package:/robot/meshes/base.stl``
    and the load fails ("Error opening file"). Before 3.7.0 it dropped the folders and looked
    for ``base.stl`` in the URDF's folder (``meshdir``). MuJoCo reads <visual> meshes only with
    ``discardvisual="false"``.

    Fix (unsafe): a ``<mujoco><compiler meshdir="..." strippath="true"/></mujoco>`` block,
    read by MuJoCo alone, when every mesh is in one folder under distinct names.

    Bad: ``<mesh filename="package://robot/meshes/base.stl"/>`` loaded with MuJoCo 4.0
    Good: ``<mujoco><compiler meshdir="../meshes" strippath="true"/></mujoco>`` in the robot
    """
    version = _version(robot, "mujoco")
    strips = _mujoco_setting(robot, "strippath", facts.MUJOCO_STRIPS_PATHS.at(version))
    if strips:
        return  # the folders are dropped: U922 judges whether the file is where MuJoCo looks
    found = [(link, holder, mesh, filename) for link, holder, mesh, filename in _meshes(robot)
             if "://" in filename and _mujoco_reads(robot, holder)]
    if not found:
        return
    fix = _meshdir_fix(robot, [filename for *_, filename in found])
    for number, (link, holder, mesh, filename) in enumerate(found):
        message = (f"{_where(link, holder)}: {_as_of(robot, 'mujoco')} cannot open mesh "
                   f"'{filename}': MuJoCo resolves no package:// URI and reads it as a path, "
                   "so the load fails")
        if number == 0 and fix is not None:
            yield _compiler_fix(robot, mesh, message, fix, "add <mujoco><compiler meshdir=... "
                                "strippath=\"true\"/></mujoco>: MuJoCo looks for each mesh in "
                                "that folder by its file name")
        else:
            yield mesh, message


def _meshdir_fix(robot, filenames) -> dict | None:
    """The compiler attributes that make MuJoCo find every mesh by name in one folder, or None
    when the meshes are in several folders (or two share a name, or one is missing)."""
    import os

    folders, names = set(), set()
    for filename in dict.fromkeys(
            f for _, _, _, f in _meshes(robot)):
        found = _exists(robot, filename)
        if found is None or found.name in names:
            return None
        folders.add(found.parent)
        names.add(found.name)
    if len(folders) != 1:
        return None
    base = Path(robot.files[0]).parent if robot.files else robot.base_dir
    relative = os.path.relpath(next(iter(folders)), base)
    return {"meshdir": Path(relative).as_posix(), "strippath": "true"}


@rule("U921", "mujoco-mesh-format", Severity.ERROR)
def mujoco_mesh_format(robot):
    """MuJoCo has no decoder for this mesh format (COLLADA, glTF, PLY...).

    MuJoCo reads STL, OBJ and its own MSH meshes; any other file fails the load ("no decoder
    found for mesh file"): every <collision> mesh, and <visual> meshes when the robot keeps
    them (``<mujoco><compiler discardvisual="false"/></mujoco>``; MuJoCo drops visuals of a
    URDF by default, so a COLLADA visual is then silently lost, see U923).

    Fix (unsafe): the mesh converted to OBJ with trimesh, next to it, and the URDF pointed at
    it (``--unsafe-fixes``).

    Bad: ``<collision><geometry><mesh filename="meshes/base.dae"/></geometry></collision>``
    Good: ``<mesh filename="meshes/base.obj"/>`` (or ``.stl``)
    """
    formats = facts.MUJOCO_MESH_FORMATS.at(_version(robot, "mujoco"))
    for link, holder, mesh, filename in _meshes(robot):
        extension = _extension(filename)
        if _mujoco_reads(robot, holder) and extension not in formats:
            yield _converted(robot, mesh, filename,
                             f"{_where(link, holder)}: {_as_of(robot, 'mujoco')} has no decoder "
                             f"for mesh '{filename}' ({extension or 'no extension'}; it reads "
                             f"{', '.join(sorted(formats))}): the load fails")


def _converted(robot, mesh, filename: str, message: str, target_format: str = ".obj"):
    """The finding with the unsafe fix converting the mesh file (trimesh) and renaming it in
    the URDF; no fix when the file is missing or its name comes from an expression."""
    from urdftool.lint.fixes import converted_mesh, offer

    found = _exists(robot, filename)
    if found is None:
        return mesh, message
    edits, creates = converted_mesh(robot, mesh, found, target_format)
    return offer(mesh, message, f"convert '{found.name}' to {target_format[1:].upper()} with "
                 "trimesh and point the URDF at it", edits, safe=False, creates=creates)


@rule("U922", "mujoco-mesh-not-found", Severity.ERROR)
def mujoco_mesh_not_found(robot):
    """MuJoCo does not find a mesh file that it reads.

    MuJoCo looks for a relative mesh path below ``meshdir`` (the URDF's folder unless the
    robot's ``<mujoco><compiler meshdir=...>`` says otherwise), and with ``strippath`` (forced
    before 3.7.0) for the file name alone there. A <collision> mesh that is not there fails the
    load ("Error opening file"); a <visual> one too when visuals are kept.

    Bad: ``<mesh filename="package://robot/meshes/base.stl"/>`` loaded with MuJoCo 3.6 when
    ``base.stl`` is not beside the URDF
    Good: ``<mujoco><compiler meshdir="../meshes"/></mujoco>``
    """
    version = _version(robot, "mujoco")
    strips = _mujoco_setting(robot, "strippath", facts.MUJOCO_STRIPS_PATHS.at(version))
    compiler = facts.mujoco_compiler(robot.root)
    base = Path(robot.files[0]).parent if robot.files else robot.base_dir
    meshdir = compiler.get("meshdir") if compiler is not None else None
    folder = base / meshdir if meshdir else base
    for link, holder, mesh, filename in _meshes(robot):
        if not _mujoco_reads(robot, holder):
            continue
        if "://" in filename and not strips:
            continue  # U920
        name = filename.replace("\\", "/").rsplit("/", 1)[-1] if strips else filename
        path = Path(name) if Path(name).is_absolute() else folder / name
        if kind_of(path) != "file":
            yield mesh, (f"{_where(link, holder)}: {_as_of(robot, 'mujoco')} looks for mesh "
                         f"'{filename}' at {path}, which {no_file_there(path)}: the load fails")


def _principal(body):
    return sorted(body.principal_moments())


@rule("U923", "mujoco-visual-discarded", Severity.INFO)
def mujoco_visual_discarded(robot):
    """MuJoCo drops every ``<visual>`` of a URDF.

    ``discardvisual`` is "true" for URDF unless the robot says otherwise: what MuJoCo shows is
    the collision geometry, and a visual mesh is never opened (one that is missing, or in a
    format MuJoCo cannot read, goes unnoticed until visuals are kept). Said once per robot, at
    the first visual.

    Fix (unsafe): ``<mujoco><compiler discardvisual="false"/></mujoco>``, once every visual
    mesh is in a format MuJoCo reads.

    Good: ``<mujoco><compiler discardvisual="false"/></mujoco>`` with STL or OBJ visuals
    """
    if _mujoco_setting(robot, "discardvisual", facts.MUJOCO_DISCARDS_VISUALS) is not True:
        return
    visuals = [holder for link in robot.children("link") for holder in child_list(link)
               if holder.tag == "visual"]
    if visuals:
        yield _compiler_fix(robot, visuals[0], (
            f"{_as_of(robot, 'mujoco')} drops all {len(visuals)} <visual> elements of the "
            "robot (discardvisual is \"true\" for URDF): it shows the collision geometry"),
            {"discardvisual": "false"}, "add <mujoco><compiler discardvisual=\"false\"/>")


@rule("U924", "mujoco-inertia-refused", Severity.ERROR)
def mujoco_inertia_refused(robot):
    """MuJoCo refuses this inertia tensor.

    MuJoCo checks every explicit ``<inertial>``, moving or fixed: the principal moments must be
    positive ("inertia must have positive eigenvalues") and satisfy the triangle inequality
    A + B >= C ("inertia must satisfy A + B >= C; use 'balanceinertia' to fix"). A tensor of
    all zeros counts as absent. The load fails at the first such link.

    Fix (unsafe): ``<mujoco><compiler balanceinertia="true"/></mujoco>``, which makes MuJoCo
    replace such a tensor by its mean moment (better: recompute it, ``urdftool inertia``).

    Bad: ``<inertia ixx="0.001" iyy="0.001" izz="0.01" .../>``
    Good: moments where each is at most the sum of the other two
    """
    balance = _mujoco_setting(robot, "balanceinertia", False)
    first = True
    for link in robot.children("link"):
        body = _body(link)
        if body is None or all(abs(v) == 0 for row in body.inertia for v in row):
            continue
        a, b, c = _principal(body)
        why = None
        if a < 1e-14:  # mjEPS: the smallest eigenvalue MuJoCo takes as positive
            why = "inertia must have positive eigenvalues"
        elif a + b < c * (1 - 1e-9) and not balance:
            why = "inertia must satisfy A + B >= C"
        if why is None:
            continue
        where = first_child(first_child(link, "inertial"), "inertia")
        message = (f"link '{_name(link)}': {_as_of(robot, 'mujoco')} refuses its inertia "
                   f"(principal moments {', '.join(number(m) for m in (a, b, c))}): \"{why}\"")
        if first and why.endswith("A + B >= C"):
            yield _compiler_fix(robot, where, message, {"balanceinertia": "true"},
                                "add <mujoco><compiler balanceinertia=\"true\"/>")
        else:
            yield where, message
        first = False


def _fused(robot) -> dict:
    """Link -> the link MuJoCo fuses it into (``world`` for the root), for links MuJoCo fuses:
    every link on a fixed joint (fusestatic), and a root without a "world" link."""
    tree, found = _tree(robot), {}

    def owner(name):
        joint, parent = tree.parent.get(name, (None, None))
        while joint is not None and _type(joint) == "fixed":
            name = parent
            joint, parent = tree.parent.get(name, (None, None))
        return name if joint is not None else "world"

    for name in robot.links:
        if name == "world":
            continue
        joint, _ = tree.parent.get(name, (None, None))
        if joint is None or _type(joint) == "fixed":
            found[name] = owner(name)
    return found


@rule("U925", "mujoco-massless-body", Severity.ERROR)
def mujoco_massless_body(robot):
    """A moving body has no mass (or no inertia) in MuJoCo.

    MuJoCo fuses each link on a fixed joint into its parent, then requires every body that a
    joint moves to have mass and inertia above 1e-15 ("mass and inertia of moving bodies must be
    larger than mjMINVAL"). A link without ``<inertial>`` takes them from its collision
    geometry (at 1000 kg/m^3); one with mass 0, a zero tensor, or neither inertial nor collision
    fails the load.

    Bad: ``<link name="finger"><inertial><mass value="0"/>...</link>`` on a revolute joint
    Good: the finger's real mass and inertia
    """
    tree, fused = _tree(robot), _fused(robot)
    members: dict[str, list[str]] = {}
    for name in robot.links:
        members.setdefault(fused.get(name, name), []).append(name)
    for name, link in robot.links.items():
        joint, _ = tree.parent.get(name, (None, None))
        if joint is None or _type(joint) not in VARIABLE:
            continue
        mass, tensor, geometry = 0.0, False, False
        for member in members.get(name, [name]):
            element = robot.links[member]
            body = _body(element)
            if first_child(element, "inertial") is None:
                geometry = geometry or first_child(element, "collision") is not None
                continue
            if body is None:
                continue
            mass += body.mass
            tensor = tensor or any(abs(v) > 1e-15 for row in body.inertia for v in row)
        if geometry or (mass > facts.MUJOCO_MINVAL and tensor):
            continue
        what = "no mass" if mass <= facts.MUJOCO_MINVAL else "no inertia"
        yield link, (f"link '{name}' moves on joint '{_name(joint)}' but has {what} in "
                     f"{_as_of(robot, 'mujoco')} (with the links fixed to it, and no collision "
                     "geometry to take it from): \"mass and inertia of moving bodies must be "
                     "larger than mjMINVAL\", the load fails")


def _limit_change(joint):
    """How MuJoCo reads this joint's <limit> differently from urdfdom, or None."""
    limit = first_child(joint, "limit")
    if limit is None:
        return None
    lower, upper = limit.get("lower"), limit.get("upper")
    kind = _type(joint)
    if kind == "continuous":
        if lower is not None and upper is not None:
            return (f"continuous joint '{_name(joint)}': MuJoCo limits it to [{lower}, {upper}] "
                    "(urdfdom ignores the range of a continuous joint)")
        return None
    if kind not in LIMITED:
        return None
    if (lower is None) != (upper is None):
        return (f"joint '{_name(joint)}': only {'lower' if lower is not None else 'upper'} is "
                "written (urdfdom takes 0 for the other): MuJoCo makes the joint unlimited")
    numbers = [number_tuple(value, 1)[0] for value in (lower, upper) if value is not None]
    if len(numbers) != 2 or not all(numbers):
        return None
    low, high = numbers[0][0], numbers[1][0]
    if low > high:
        return (f"joint '{_name(joint)}': lower {low:g} > upper {high:g}: MuJoCo makes the "
                "joint unlimited")
    if low == high:
        return (f"joint '{_name(joint)}': lower = upper = {low:g} (a locked joint): MuJoCo "
                "ignores the limit and the joint moves freely")
    return None


@rule("U926", "mujoco-limit-changed", Severity.WARNING)
def mujoco_limit_changed(robot):
    """MuJoCo reads this joint's ``<limit>`` range differently from urdfdom.

    MuJoCo drops the range of a revolute or prismatic joint when only one of ``lower`` and
    ``upper`` is written, when lower > upper, or when lower = upper (4.0 prints "limit
    ignored"): the joint becomes unlimited. It limits a continuous joint whose ``<limit>`` has
    both, which urdfdom and ROS treat as unlimited.

    Bad: ``<limit lower="0.5" upper="0.5" .../>`` (MuJoCo: free), ``<limit upper="1.57" .../>``
    Good: both bounds, lower < upper; a fixed joint for one that never moves
    """
    for joint in robot.children("joint"):
        change = _limit_change(joint)
        if change is not None:
            yield first_child(joint, "limit"), f"{change} ({_as_of(robot, 'mujoco')})"


@rule("U927", "mujoco-fused-frame", Severity.WARNING)
def mujoco_fused_frame(robot):
    """Something refers to a frame that MuJoCo fuses away.

    MuJoCo fuses each link on a fixed joint into its parent, and the root into the world
    (``fusestatic`` is "true" for URDF): the link's name and frame are not in MuJoCo's model.
    A ros2_control sensor's ``frame_id``, or an SRDF chain, group or end effector that names it
    (read by controllers and planners working on MuJoCo's model: mujoco_ros2_control, mink)
    finds no body of that name there.

    Fix (unsafe): ``<mujoco><compiler fusestatic="false"/></mujoco>``, which keeps every link
    a body of its own.

    Bad: ``<end_effector parent_link="tool0" .../>`` with ``tool0`` on a fixed joint
    Good: ``<mujoco><compiler fusestatic="false"/></mujoco>`` in the robot
    """
    if not _mujoco_setting(robot, "fusestatic", True):
        return
    first = True
    for where, name, what, into in _referenced_removals(robot, _fused(robot), "mujoco"):
        message = (f"{what} refers to link '{name}', which {_as_of(robot, 'mujoco')} fuses into "
                   f"'{into}': no body of that name in MuJoCo's model")
        if first:
            yield _compiler_fix(robot, where, message, {"fusestatic": "false"},
                                "add <mujoco><compiler fusestatic=\"false\"/>")
            first = False
        else:
            yield where, message


@rule("U928", "mujoco-welded-root", Severity.WARNING)
def mujoco_welded_root(robot):
    """MuJoCo welds the robot's root to the world, and drops its mass.

    Without a link named "world", MuJoCo fuses the root link into the world: the robot cannot
    move as a whole (a legged or mobile robot stands fixed in the air), and the root's mass is
    not counted. Drake floats the same file (U944), so the two disagree on its degrees of
    freedom.

    Fix (unsafe): say what the robot is: ``<link name="world"/>`` and a fixed joint to the root
    for a fixed base, or a ``floating`` joint for a free one.

    Bad: a quadruped whose root is ``base``, with no world link
    Good: ``<link name="world"/><joint name="world_joint" type="floating">...``
    """
    if _has_world(robot):
        return
    for name in _tree(robot).roots[:1]:
        link = robot.links[name]
        mass = _mass_of(link)
        weight = f", and its {mass:g} kg are not counted" if mass else ""
        yield _world_fix(robot, link, (
            f"root link '{name}': {_as_of(robot, 'mujoco')} welds it to the world (no free "
            f"joint){weight}; Drake floats the same robot. Add a world link with a fixed "
            "joint (fixed base) or a floating joint (free base)"))


def _world_fix(robot, link, message: str):
    """The finding with the unsafe fix adding a world link fixed to ``link``."""
    name = _name(link)
    from urdftool.lint.fixes import insert_before, offer  # (only for a finding)

    edits = insert_before(robot, link, '<link name="world"/>',
                          f'<joint name="world_to_{attribute(name)}" type="fixed"><parent '
                          f'link="world"/><child link="{attribute(name)}"/></joint>')
    return offer(link, message, f"add a world link fixed to '{name}' (a fixed base)", edits,
                 safe=False)


# ==== PyBullet (U93x) =========================================================================

@rule("U930", "pybullet-mesh-format", Severity.ERROR)
def pybullet_mesh_format(robot):
    """PyBullet refuses a mesh whose file name does not end in .stl, .obj, .dae or .cdf.

    PyBullet's URDF importer reads the last four characters of a mesh file name; any other
    ("invalid mesh filename extension": glTF, GLB, PLY) fails the whole load, for a <visual> as
    for a <collision>.

    Fix (unsafe): the mesh converted to OBJ with trimesh and the URDF pointed at it.

    Bad: ``<mesh filename="meshes/base.glb"/>``
    Good: ``<mesh filename="meshes/base.obj"/>``
    """
    for link, holder, mesh, filename in _meshes(robot):
        if filename[-4:].lower() not in facts.PYBULLET_MESH_EXTENSIONS:
            yield _converted(robot, mesh, filename, (
                f"{_where(link, holder)}: {_as_of(robot, 'pybullet')} refuses mesh "
                f"'{filename}' (invalid mesh filename extension; it reads .stl, .obj, .dae, "
                ".cdf): the load fails"))


def _pybullet_finds(robot, filename: str) -> bool | None:
    """Whether PyBullet's search (UrdfFindMeshFile) finds the mesh below a folder above the
    URDF (True); False when the file is nowhere, None when it exists but PyBullet finds it only
    from a working folder that holds it. Each attempt is the folder's path,
    "/" and the name as written with package:// cut off: strings joined, so a name starting
    with "/" (``package:///pkg/...``) is looked for below every folder too."""
    import os

    name = filename
    for prefix in ("package://", "model://"):
        if name.startswith(prefix):
            name = name[len(prefix):]
            break
    if robot.from_xacro:
        # PyBullet reads xacro's output, written where we cannot know: found when it exists
        return _exists(robot, filename) is not None
    urdf = os.path.abspath(robot.files[0] if robot.files else robot.path)
    attempts = [name] if os.path.isabs(name) else []
    attempts += [urdf[:at] + "/" + name for at, char in enumerate(urdf) if char == "/"]
    if any(kind_of(attempt) == "file" for attempt in attempts):
        return True
    return None if _exists(robot, filename) is not None else False


@rule("U931", "pybullet-mesh-not-found", Severity.ERROR)
def pybullet_mesh_not_found(robot):
    """PyBullet does not find a mesh file: the whole load fails.

    PyBullet fails ("cannot find ... in any directory in urdf path", then "Cannot load URDF
    file") on any missing mesh, <visual> included, where MuJoCo and RViz go on without it.

    Bad: ``<visual><geometry><mesh filename="meshes/cover.stl"/></geometry></visual>`` with no
    such file
    Good: the file, or no <visual>
    """
    for link, holder, mesh, filename in _meshes(robot):
        if filename[-4:].lower() in facts.PYBULLET_MESH_EXTENSIONS and \
                _pybullet_finds(robot, filename) is False:
            yield mesh, (f"{_where(link, holder)}: mesh '{filename}' does not exist, and "
                         f"{_as_of(robot, 'pybullet')} fails the whole load on a missing "
                         f"{holder.tag} mesh")


@rule("U932", "pybullet-mesh-search-path", Severity.WARNING)
def pybullet_mesh_search_path(robot):
    """PyBullet finds this mesh only when it runs from a folder that holds it.

    PyBullet cuts ``package://`` off and looks for the rest below the working folder (and its
    parent and grandparent), then below each folder above the URDF file. The paths given to
    ``setAdditionalSearchPath`` are not asked for meshes (PyBullet 3.2.7 fails with them), so
    when the package's folder is not named after the package, or is not beside a folder above
    the URDF, the load depends on the folder the caller runs from.

    Bad: ``package://robot_description/meshes/base.stl`` with the package in a folder ``robot``
    Good: the package in a folder of its own name, beside a folder above the URDF
    """
    for link, holder, mesh, filename in _meshes(robot):
        if filename[-4:].lower() in facts.PYBULLET_MESH_EXTENSIONS and \
                _pybullet_finds(robot, filename) is None:
            yield mesh, (f"{_where(link, holder)}: {_as_of(robot, 'pybullet')} finds mesh "
                         f"'{filename}' from none of the folders above the URDF; the load "
                         "fails unless PyBullet runs from a folder that holds it (setAdditionalSearchPath "
                         "is not asked for meshes)")


@rule("U933", "pybullet-long-line", Severity.ERROR)
def pybullet_long_line(robot):
    """PyBullet breaks a line longer than 8191 bytes, and the XML with it.

    PyBullet reads the URDF line by line into an 8192-byte buffer and adds a line break after
    each piece: a longer line is cut every 8191 bytes, and a cut inside a tag breaks the file
    ("Cannot load URDF file"). Files written by programs on one line fail.

    Bad: a whole robot written on one line
    Good: one element per line (``xmllint --format``)
    """
    if robot.from_xacro or not robot.files:
        return  # PyBullet reads xacro's output, which xacro writes one element a line
    data = robot.sources.get(robot.files[0])
    if not data:
        return
    start = 0
    for line in data.split(b"\n"):  # line ends: PyBullet's (it reads up to each LF)
        if len(line) > facts.PYBULLET_LINE_BUFFER:
            cuts = [cut for cut in range(facts.PYBULLET_LINE_BUFFER, len(line),
                                         facts.PYBULLET_LINE_BUFFER) if _cuts_a_name(line, cut)]
            if cuts:
                from urdftool.diagnostics import Location, display_path, line_at, line_start

                number, at = line_at(data, start), start + cuts[0]
                yield Location(display_path(robot.files[0]), line_at(data, at),
                               column=at - line_start(data, at) + 1), (
                    f"line {number} is {len(line)} bytes long: {_as_of(robot, 'pybullet')} "
                    f"cuts it every {facts.PYBULLET_LINE_BUFFER} bytes, and the cut at byte "
                    f"{cuts[0]} splits a tag or attribute name: the load fails")
        start += len(line) + 1


def _cuts_a_name(line: bytes, cut: int) -> bool:
    """Whether a line break inserted before byte ``cut`` of ``line`` splits the name of an
    element or attribute: inside markup (after a ``<`` not closed yet, out of comments and
    quoted values) between two characters that are not white space. A break between
    attributes is white space XML allows; one in a quoted value changes the value but not the
    parse (not certain to fail: not reported)."""
    before = line[:cut]
    if before.rfind(b"<!--") > before.rfind(b"-->"):
        return False
    start = before.rfind(b"<")
    if start <= before.rfind(b">"):
        return False
    inside = before[start:]
    if (inside.count(b'"') % 2) or (inside.count(b"'") % 2):
        return False
    return not line[cut - 1:cut].isspace() and not line[cut:cut + 1].isspace() and \
        line[cut - 1:cut] not in (b"=", b'"', b"'") and line[cut:cut + 1] not in (b"=", b'"', b"'")


@rule("U934", "pybullet-default-mass", Severity.WARNING)
def pybullet_default_mass(robot):
    """PyBullet gives 1 kg to a link without ``<inertial>``.

    urdfdom, RViz, KDL and Pinocchio take such a link as massless; PyBullet gives it mass 1 kg
    and inertia diag(1, 1, 1) (a root link named "world" excepted). Frames written as empty
    links (``tool0``, ``base_footprint``, camera frames) add kilograms: the PR2 gains 14 kg.

    Bad: ``<link name="camera_optical_frame"/>`` loaded in PyBullet
    Good: an ``<inertial>`` with the link's real mass (a small one for a frame)
    """
    tree = _tree(robot)
    for name, link in robot.links.items():
        if first_child(link, "inertial") is not None:
            continue
        if name == "world" and name in tree.roots:
            continue
        yield link, (f"link '{name}' has no <inertial>: {_as_of(robot, 'pybullet')} gives it "
                     "1 kg and inertia diag(1, 1, 1)")


@rule("U935", "pybullet-inertia-from-collision", Severity.INFO)
def pybullet_inertia_from_collision(robot):
    """PyBullet replaces the inertia tensors of the file unless asked not to.

    ``loadURDF`` without ``flags=p.URDF_USE_INERTIA_FROM_FILE`` keeps each link's mass but
    computes its inertia from its collision shapes (a link without collision gets almost none):
    the dynamics differ from every other loader's. Said once per robot.

    Good: ``p.loadURDF(path, flags=p.URDF_USE_INERTIA_FROM_FILE)``
    """
    for link in robot.children("link"):
        inertial = first_child(link, "inertial")
        if inertial is not None:
            yield inertial, (f"{_as_of(robot, 'pybullet')} replaces every link's inertia with "
                             "one from its collision shapes unless loaded with "
                             "flags=p.URDF_USE_INERTIA_FROM_FILE")
            return


@rule("U936", "pybullet-limit-dropped", Severity.WARNING)
def pybullet_limit_dropped(robot):
    """PyBullet leaves a joint unlimited when its lower limit is above its upper one.

    Bad: ``<limit lower="1" upper="-1" .../>`` (the joint turns freely in PyBullet)
    Good: ``<limit lower="-1" upper="1" .../>``
    """
    for joint, limit, low, high in _inverted(robot):
        yield limit, (f"joint '{_name(joint)}': lower {low:g} > upper {high:g}: "
                      f"{_as_of(robot, 'pybullet')} applies no limit, the joint moves freely")


@rule("U937", "pybullet-mimic-ignored", Severity.WARNING)
def pybullet_mimic_ignored(robot):
    """PyBullet ignores ``<mimic>``: the follower joint moves on its own.

    Fix: couple the joints in the caller, with ``p.createConstraint(..., p.JOINT_GEAR, ...)``
    and ``p.changeConstraint(c, gearRatio=-multiplier)``.

    Bad: a gripper's second finger mimicking the first, simulated in PyBullet as it is
    """
    for joint in robot.children("joint"):
        mimic = first_child(joint, "mimic")
        if mimic is not None and _type(joint) != "fixed":
            yield mimic, (f"joint '{_name(joint)}' mimics '{mimic.get('joint')}': "
                          f"{_as_of(robot, 'pybullet')} ignores <mimic>, the joint moves on its "
                          "own (couple them with a JOINT_GEAR constraint)")


# ==== Drake (U94x) ============================================================================

@rule("U940", "drake-collision-mesh-format", Severity.ERROR)
def drake_collision_mesh_format(robot):
    """Drake cannot make a collision shape from this mesh format (STL, COLLADA...).

    With a SceneGraph (``AddMultibodyPlantSceneGraph``, as every simulation has), Drake turns
    each <collision> mesh into its convex hull, which it computes only from OBJ, VTK and glTF
    files ("MakeConvexHull only applies to .obj, .vtk, and .gltf meshes"): the load fails.

    Fix (unsafe): the mesh converted to OBJ with trimesh and the URDF pointed at it.

    Bad: ``<collision><geometry><mesh filename="meshes/base.stl"/></geometry></collision>``
    Good: ``<mesh filename="meshes/base.obj"/>``
    """
    for link, holder, mesh, filename in _meshes(robot):
        extension = _extension(filename)
        if holder.tag == "collision" and extension not in facts.DRAKE_HULL_FORMATS:
            yield _converted(robot, mesh, filename, (
                f"{_where(link, holder)}: {_as_of(robot, 'drake')} makes collision shapes only "
                f"from .obj, .vtk and .gltf meshes, not '{filename}': the load fails"))


@rule("U941", "drake-file-not-found", Severity.ERROR)
def drake_file_not_found(robot):
    """Drake does not find a mesh or texture file: the load fails.

    Drake resolves every ``<mesh>`` (visual too) and every ``<texture>`` of a material, and
    stops at the first that does not exist ("URI ... which does not exist") or names a package
    it cannot know (``package:///...``, an empty name: "refers to unknown package ''").

    Bad: ``<material name="wood"><texture filename="textures/wood.png"/></material>`` without
    the file
    Good: the file, or no ``<texture>``
    """
    for link, holder, mesh, filename in _meshes(robot):
        if filename.startswith("package:///"):
            yield mesh, (f"{_where(link, holder)}: mesh '{filename}' names an empty package: "
                         f"{_as_of(robot, 'drake')} refuses it (\"refers to unknown package "
                         "''\") and fails the load")
        elif _exists(robot, filename) is None and "://" not in filename.replace("package://",
                                                                                ""):
            yield mesh, (f"{_where(link, holder)}: mesh '{filename}' does not exist: "
                         f"{_as_of(robot, 'drake')} fails the load")
    for texture in robot.root.iter("texture"):
        filename = texture.get("filename")
        if filename and _texture_missing(robot, filename):
            yield texture, (f"texture '{filename}' does not exist: {_as_of(robot, 'drake')} "
                            "fails the load")


def _texture_missing(robot, filename: str) -> bool:
    try:
        return kind_of(robot.resolve_uri(filename)) != "file"
    except Exception:  # noqa: BLE001 - an unknown package: Drake cannot find it either
        return True


@rule("U942", "drake-lower-above-upper", Severity.ERROR)
def drake_lower_above_upper(robot):
    """Drake stops on a joint whose lower limit is above its upper one.

    Drake checks ``lower <= upper`` when it makes the joint, and the load stops there ("condition
    '(pos_lower_limits.array() <= pos_upper_limits.array()).all()' failed").

    Bad: ``<limit lower="1" upper="-1" .../>``
    Good: ``<limit lower="-1" upper="1" .../>``
    """
    for joint, limit, low, high in _inverted(robot):
        yield limit, (f"joint '{_name(joint)}': lower {low:g} > upper {high:g}: "
                      f"{_as_of(robot, 'drake')} stops the load")


@rule("U943", "drake-mimic-dof", Severity.ERROR)
def drake_mimic_dof(robot):
    """Drake refuses a ``<mimic>`` between joints of different degrees of freedom.

    Drake makes a coupler constraint of each ``<mimic>``, which needs two one-degree joints: a
    fixed joint that mimics ("Joint ... which has 0 DOF cannot mimic joint ... which has 1 DOF")
    fails the load, though urdfdom accepts it.

    Bad: ``<joint type="fixed">...<mimic joint="finger"/></joint>``
    Good: no ``<mimic>`` on a fixed joint
    """
    for joint in robot.children("joint"):
        mimic = first_child(joint, "mimic")
        leader = robot.joints.get(mimic.get("joint")) if mimic is not None else None
        if leader is None:
            continue
        mine, theirs = DEGREES.get(_type(joint)), DEGREES.get(_type(leader))
        if mine is not None and theirs is not None and mine != theirs:
            yield mimic, (f"joint '{_name(joint)}' ({_type(joint)}, {mine} DOF) mimics "
                          f"'{_name(leader)}' ({theirs} DOF): {_as_of(robot, 'drake')} refuses "
                          "the file")


@rule("U944", "drake-floating-root", Severity.WARNING)
def drake_floating_root(robot):
    """Drake gives the robot's root a floating joint: 6 more degrees of freedom.

    Without a link named "world", Drake adds a quaternion floating joint to the root (7 more
    positions, 6 more velocities): a robot arm falls, and its state vector is not the one
    MuJoCo and Pinocchio have for the same file (they weld the root).

    Fix (unsafe): ``<link name="world"/>`` and a fixed joint from it to the root.

    Bad: an arm whose root is ``base_link``, with no world link
    Good: ``<link name="world"/><joint name="world_joint" type="fixed">...``
    """
    if _has_world(robot):
        return
    for name in _tree(robot).roots[:1]:
        yield _world_fix(robot, robot.links[name], (
            f"root link '{name}': {_as_of(robot, 'drake')} gives it a floating joint (+6 "
            "degrees of freedom) where MuJoCo and Pinocchio weld it; add a world link with a "
            "fixed joint for a fixed base"))


# ==== sdformat: gz (U95x) and Gazebo Classic (U96x) ===========================================

@dataclass
class _Lumped:
    """The robot after sdformat's fixed-joint lumping.

    owner: link -> the link it was lumped into (itself when kept)
    mass: kept link -> mass after lumping (None: no <inertial> at all)
    nan: (child, parent) of the lump that gave NaN, first
    bodies: kept link -> its lumped Body (link axes), when every part has a full inertial
    dropped: kept link -> why it is not modelled (massless), for the first of each subtree
    """

    owner: dict = field(default_factory=dict)
    mass: dict = field(default_factory=dict)
    nan: list = field(default_factory=list)
    bodies: dict = field(default_factory=dict)
    dropped: dict = field(default_factory=dict)


def _preserved(robot) -> set:
    """Fixed joints sdformat keeps: <gazebo reference="JOINT"> with preserveFixedJoint or
    disableFixedJointLumping true."""
    kept = set()
    for gazebo in robot.children("gazebo"):
        for tag in ("preserveFixedJoint", "disableFixedJointLumping"):
            element = first_child(gazebo, tag)
            if element is not None and (element.text or "").strip().lower() == "true":
                kept.add(gazebo.get("reference"))
    return kept


def _lumped(robot, target: str) -> _Lumped:
    return robot.memo((_lumped, target), lambda: _lump(robot, target))


def _placed(body, joint):
    from urdftool.physics.mass import transformed

    xyz, rpy = origin_pose(joint)
    return transformed(body, xyz, mat3.rpy_matrix(rpy))


def _lump(robot, target: str) -> _Lumped:
    from urdftool.physics.mass import Body, combine

    tree, kept_joints, result = _tree(robot), _preserved(robot), _Lumped()
    mass = {name: _mass_of(link) for name, link in robot.links.items()}
    inertial = {name: first_child(link, "inertial") is not None
                for name, link in robot.links.items()}
    bodies = {name: _body(link) for name, link in robot.links.items()}
    nan = set()

    def reduced(joint) -> bool:
        return _type(joint) == "fixed" and joint.get("name") not in kept_joints

    def reduce(root: str, seen: set) -> None:
        """Each link below ``root`` lumped into its parent, depth first: a link's children
        through fixed joints before it, the others after it. A stack, not recursion: a chain
        of 3,000 links is as deep as it is long."""
        stack = [(root, "enter")]
        while stack:
            name, step = stack.pop()
            if step == "enter":
                if name in seen:
                    continue
                seen.add(name)
                stack += [(name, "others"), (name, "lump")]
                stack += [(child, "enter") for joint, child in reversed(tree.children.get(name, ()))
                          if reduced(joint)]
            elif step == "lump":
                lump(name)
            else:
                stack += [(child, "enter") for joint, child in reversed(tree.children.get(name, ()))
                          if not reduced(joint)]

    def lump(name: str) -> None:
        joint, parent = tree.parent.get(name, (None, None))
        if joint is not None and parent != "world" and reduced(joint):
            into = result.owner.get(parent, parent)
            result.owner[name] = into
            for member, owner in list(result.owner.items()):
                if owner == name:
                    result.owner[member] = into
            if inertial[name]:
                if not inertial[parent]:
                    inertial[parent], mass[parent] = True, 0.0
                total = (mass[parent] or 0.0) + (mass[name] or 0.0)
                if total == 0.0 or name in nan:
                    nan.add(parent)
                    if not result.nan:
                        result.nan.append((name, parent))
                child_body = bodies.get(name)
                parent_body = bodies.get(parent)
                if child_body is not None and (parent_body is not None or not mass[parent]):
                    placed = _placed(child_body, joint)
                    parts = [b for b in (parent_body, placed) if b is not None and b.mass > 0]
                    bodies[parent] = combine(parts) if parts else Body(
                        0.0, (0.0, 0.0, 0.0), mat3.matrix(((0, 0, 0), (0, 0, 0), (0, 0, 0))))
                else:
                    bodies[parent] = None
                mass[parent] = total

    seen: set = set()
    for root in tree.roots:
        reduce(root, seen)
    threshold = facts.SDFORMAT_MASSLESS[target].at(_version(robot, target))
    lumped_too = facts.SDFORMAT_DROPS_LUMPED[target].at(_version(robot, target))

    def created(name: str) -> bool:
        """Whether the link is made (its children are then looked at): not when it is dropped."""
        zero = not inertial[name] or abs(mass[name] or 0.0) <= threshold \
            or (threshold == 0.0 and (mass[name] or 0.0) <= 0.0)
        joint, parent = tree.parent.get(name, (None, None))
        lumped_away = joint is not None and parent != "world" and reduced(joint)
        if name != "world" and zero and (lumped_too or not lumped_away):
            result.dropped[name] = "no <inertial>" if not inertial[name] else \
                f"mass {mass[name] or 0:g}"
            return False
        if not lumped_away:
            result.owner.setdefault(name, name)
            result.mass[name] = mass[name] if inertial[name] else None
            result.bodies[name] = bodies.get(name)
        return True

    stack = list(reversed(tree.roots))  # depth first, parents before children, as sdformat
    while stack:
        name = stack.pop()
        if created(name):
            stack += [child for _, child in reversed(tree.children.get(name, ()))]
    return result


def _sdf_title(robot, target: str) -> str:
    return _as_of(robot, target)


def _massless(robot, target: str, root: bool):
    lumped = _lumped(robot, target)
    tree = _tree(robot)
    for name, why in lumped.dropped.items():
        is_root = tree.parent.get(name) is None or tree.parent[name][1] == "world"
        if is_root != root:
            continue
        link = robot.links[name]
        below = [b for b in _below(tree, name) if lumped.owner.get(b, b) == b]
        joint = tree.parent[name][0] if name in tree.parent else None
        if not root and not below and joint is not None and _type(joint) == "fixed":
            continue  # a lumped link with nothing below: its inertial went to the parent
        if root:
            yield link, (f"root link '{name}' has {why} after fixed joints are lumped: "
                         f"{_sdf_title(robot, target)} does not model it nor anything below "
                         "it, and refuses the model (\"A model must have at least one link\")")
        else:
            joint = tree.parent[name][0]
            yield link, (f"link '{name}' has {why} after fixed joints are lumped: "
                         f"{_sdf_title(robot, target)} leaves it out with its joint "
                         f"'{_name(joint)}'" + (f" and the {len(below)} link(s) below it "
                                                f"({', '.join(below[:4])}"
                                                f"{', ...' if len(below) > 4 else ''})"
                                                if below else ""))


def _below(tree: _Tree, name: str) -> list[str]:
    found, todo = [], [name]
    while todo:
        for _, child in tree.children.get(todo.pop(), ()):
            found.append(child)
            todo.append(child)
    return found


def _nan(robot, target: str):
    lumped = _lumped(robot, target)
    for child, parent in lumped.nan:
        link = robot.links[child]
        final = lumped.owner.get(parent, parent)
        ends = f" (and NaN goes on into '{final}')" if final != parent else ""
        yield first_child(link, "inertial"), (
            f"link '{child}' has an <inertial> of mass 0 and is lumped into '{parent}', which "
            f"has no mass either: {_sdf_title(robot, target)} divides by their total mass "
            f"(0){ends} and refuses the file (\"Pose values must be finite\"); give one of "
            "them its mass, or remove the empty <inertial>")


def _invalid_inertia(robot, target: str):
    lumped = _lumped(robot, target)
    for name, body in lumped.bodies.items():
        if body is None or name in lumped.dropped or body.mass <= 0:
            continue
        moments = sorted(body.principal_moments())
        largest = max(abs(m) for m in moments)
        epsilon = 10 * largest * 2.220446049250313e-16
        a, b, c = moments
        if a < -epsilon or a + b + epsilon < c:
            link = robot.links[name]
            lumped_in = [m for m, o in lumped.owner.items() if o == name and m != name]
            also = f" (with {', '.join(lumped_in)} lumped into it)" if lumped_in else ""
            where = first_child(link, "inertial")
            yield where if where is not None else link, (
                f"link '{name}'{also}: principal moments {', '.join(number(m) for m in (a, b, c))} "
                "break the "
                f"triangle inequality: {_sdf_title(robot, target)} reports \"has invalid "
                "inertia\" and its validity check (gz sdf -k) fails")


def _lumped_frames(robot, target: str):
    lumped = _lumped(robot, target)
    removed = {name: owner for name, owner in lumped.owner.items() if owner != name}
    first = True
    for where, name, what, into in _referenced_removals(robot, removed, target):
        joint = _tree(robot).parent[name][0]
        message = (f"{what} refers to link '{name}', which {_sdf_title(robot, target)} lumps "
                   f"into '{into}' (fixed joint '{_name(joint)}'): no link or frame of that "
                   "name in the simulation")
        if first and where is not None and not isinstance(where, tuple):
            first = False
            block = (f'<gazebo reference="{attribute(_name(joint))}">'
                     '<preserveFixedJoint>true</preserveFixedJoint></gazebo>')
            from urdftool.lint.fixes import append_child, offer  # (only for a finding)
            edits = append_child(robot, robot.root, block)
            yield offer(where, message, f"keep fixed joint '{_name(joint)}' in Gazebo "
                        "(preserveFixedJoint)", edits, safe=False)
        else:
            yield where, message


def _swapped(robot, target: str):
    for joint, limit, low, high in _inverted(robot):
        yield limit, (f"joint '{_name(joint)}': lower {low:g} > upper {high:g}: "
                      f"{_sdf_title(robot, target)} swaps them (\"switching the two\")")


_SDF_DOCS = {
    "massless": """A link left without mass by lumping is not in the {title} model, nor below.

    sdformat first lumps each link on a fixed joint into its parent; then a link (not named
    "world") with no ``<inertial>``, or mass {zero}, is "not modeled in sdf": its joint and
    every link below it vanish from the simulation{warns}.

    Bad: ``<link name="wheel_mount"/>`` on a revolute joint, the wheel below it
    Good: an ``<inertial>`` with the link's mass
    """,
    "root": """The {title} model has no link left: the root has no mass after lumping.

    A root link without ``<inertial>`` or mass {zero}, once the links fixed to it are lumped in,
    is not modelled, nor anything below it: sdformat refuses the model ("A model must have at
    least one link").

    Bad: ``<link name="base_link"/>`` as the root, with no massive link fixed to it
    Good: the root's ``<inertial>``, or a massive link on a fixed joint below it
    """,
    "nan": """{title} refuses the file: lumping a massless ``<inertial>`` gives NaN.

    sdformat lumps a link on a fixed joint into its parent by adding masses and dividing by
    their sum: a child whose ``<inertial>`` has mass 0 lumped into a parent of mass 0 gives a
    NaN centre of mass ("Pose values must be finite"), and the load fails.

    Bad: ``<link name="camera"><inertial><mass value="0"/>...`` fixed to a massless ``base``
    Good: no ``<inertial>`` for a frame, or real masses
    """,
    "inertia": """The validity check of {title} refuses this (lumped) inertia.

    After lumping, each link's tensor must have non-negative principal moments that satisfy
    the triangle inequality; ``gz sdf -k`` reports "A link named ... has invalid inertia" and
    fails.

    Bad: ``<inertia ixx="0.001" iyy="0.001" izz="0.01" .../>``
    Good: a tensor of a real body (``urdftool inertia``)
    """,
    "frame": """A Gazebo plugin looks up a link that {title} lumps away.

    A link on a fixed joint is lumped into its parent: its name is not in the simulation, and a
    plugin parameter that Gazebo looks up as a link (``bodyName``, ``body_name``,
    ``link_name``) finds nothing there. (The link's own ``<gazebo>`` blocks and sensors move to
    the parent with their poses, and a ``frame_name`` is only a TF frame id: both keep
    working.)

    Fix (unsafe): ``<gazebo reference="JOINT"><preserveFixedJoint>true</preserveFixedJoint>
    </gazebo>`` for the fixed joint.

    Bad: ``<bodyName>imu_link</bodyName>`` with ``imu_link`` fixed to ``base_link``
    Good: ``<gazebo reference="imu_joint"><preserveFixedJoint>true</preserveFixedJoint></gazebo>``
    """,
    "swap": """{title} swaps a joint's inverted limits.

    sdformat swaps lower and upper when lower > upper ("switching the two"): the joint moves
    over a range urdfdom does not give it.

    Bad: ``<limit lower="1" upper="-1" .../>``
    Good: ``<limit lower="-1" upper="1" .../>``
    """,
}


def _sdf_check(target: str, kind: str, check):
    """The check of one sdformat fact for ``target``, its docstring that fact's, told for it."""
    zero = "<= 0" if target == "gz" else "0"
    warns = (" (a warning since sdformat 13; silently in 12)" if target == "gz"
             else " (silently; a warning from 9.10 on)")

    def run(robot):
        yield from check(robot, target)

    run.__doc__ = _SDF_DOCS[kind].format(title=facts.SIMULATORS[target].title, zero=zero,
                                         warns=warns)
    return run


def _massless_links(robot, target):
    return _massless(robot, target, False)


def _massless_root(robot, target):
    return _massless(robot, target, True)


gz_massless_link = rule("U950", "gz-massless-link", Severity.WARNING)(
    _sdf_check("gz", "massless", _massless_links))
gz_massless_root = rule("U951", "gz-massless-root", Severity.ERROR)(
    _sdf_check("gz", "root", _massless_root))
gz_lumped_nan = rule("U952", "gz-lumped-nan", Severity.ERROR)(_sdf_check("gz", "nan", _nan))
gz_invalid_inertia = rule("U953", "gz-invalid-inertia", Severity.ERROR)(
    _sdf_check("gz", "inertia", _invalid_inertia))
gz_lumped_frame = rule("U954", "gz-lumped-frame", Severity.WARNING)(
    _sdf_check("gz", "frame", _lumped_frames))
gz_swapped_limits = rule("U955", "gz-swapped-limits", Severity.WARNING)(
    _sdf_check("gz", "swap", _swapped))
gazebo_massless_link = rule("U960", "gazebo-massless-link", Severity.WARNING)(
    _sdf_check("gazebo", "massless", _massless_links))
gazebo_massless_root = rule("U961", "gazebo-massless-root", Severity.ERROR)(
    _sdf_check("gazebo", "root", _massless_root))
gazebo_lumped_nan = rule("U962", "gazebo-lumped-nan", Severity.ERROR)(
    _sdf_check("gazebo", "nan", _nan))
gazebo_lumped_frame = rule("U964", "gazebo-lumped-frame", Severity.WARNING)(
    _sdf_check("gazebo", "frame", _lumped_frames))
gazebo_swapped_limits = rule("U965", "gazebo-swapped-limits", Severity.WARNING)(
    _sdf_check("gazebo", "swap", _swapped))


# ==== Isaac Sim (U97x) ========================================================================

def _usd_identifier(name: str) -> str:
    """The name as the Isaac importer writes it (makeValidUSDIdentifier): TfMakeValidIdentifier
    (each character that is not a letter, digit or _ becomes _, a leading digit too), then "a"
    before a leading _."""
    valid = "".join(c if (c.isascii() and (c.isalnum() or c == "_")) else "_" for c in name)
    if valid and valid[0].isdigit():
        valid = "_" + valid[1:]
    if not valid:
        valid = "_"
    if valid[0] == "_":
        valid = "a" + valid
    return valid


@rule("U970", "isaac-renamed", Severity.WARNING)
def isaac_renamed(robot):
    """Isaac Sim renames a link or joint whose name is not a valid USD prim name.

    The Isaac URDF importer makes each link and joint a USD prim, named by
    ``makeValidUSDIdentifier``: every character other than a letter, digit or ``_`` becomes
    ``_``, a leading digit too, and a name starting with ``_`` gets an ``a`` in front. Joint
    names in configurations, controllers and policies written from the URDF no longer match.

    Bad: ``<joint name="arm-joint.1">`` (Isaac: ``arm_joint_1``), ``<link name="_base">``
    Good: names of letters, digits and ``_``, starting with a letter
    """
    for kind in ("link", "joint"):
        for element in robot.children(kind):
            name = element.get("name")
            if name and _usd_identifier(name) != name:
                yield element, (f"{kind} '{name}' is not a valid USD prim name: "
                                f"{_as_of(robot, 'isaac')} renames it '{_usd_identifier(name)}'")


# ==== Pinocchio (U98x) ========================================================================

@rule("U980", "pinocchio-mimic-ignored", Severity.WARNING)
def pinocchio_mimic_ignored(robot):
    """Pinocchio reads ``<mimic>`` only when asked: by default the follower is a joint of its own.

    ``buildModelFromUrdf(path)`` makes every mimicking joint an independent degree of freedom
    (``nq`` counts it); ``buildModelFromUrdf(path, mimic=True)`` (Pinocchio 3.4 and later)
    makes it follow its leader.

    Good: ``pinocchio.buildModelFromUrdf(path, mimic=True)``
    """
    for joint in robot.children("joint"):
        mimic = first_child(joint, "mimic")
        if mimic is not None and _type(joint) != "fixed":
            yield mimic, (f"joint '{_name(joint)}' mimics '{mimic.get('joint')}': "
                          f"{_as_of(robot, 'pinocchio')} makes it a free joint of its own "
                          "unless the model is built with mimic=True")

