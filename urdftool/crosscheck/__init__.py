"""``urdftool crosscheck``: load a robot with every real loader installed and compare what each
made of it.

Each loader (:mod:`.loaders`: Pinocchio, MuJoCo, PyBullet, Drake, sdformat through ``gz sdf``)
runs in a worker process of its own, forked by the pool under the time and memory budget
(:func:`urdftool.lint.pool.run_budgeted`): loaders segfault and abort on bad input, and a
loader that dies, hangs or overruns its memory is reported as failed, with why. A xacro file is
expanded by urdftool and written to a temporary folder; packages are handed to the loaders that
take them (Drake's PackageMap, Pinocchio), and linked beside the expanded file for PyBullet,
which finds meshes only below the folders above the file it reads, as a user would.

For each loader: whether it loaded, or its error mapped back to the line of the file the user
wrote; total mass; degrees of freedom; floating or fixed base; the URDF links it dropped or
fused; frame positions at the zero configuration and a few others; the inertia it holds. The
loaders **disagree** when the positions of a frame two of them keep differ by more than
:data:`TOLERANCE`, or when a loader's total mass is not what its own reading of a URDF makes of
the masses declared (:mod:`.masses`: PyBullet gives a link without ``<inertial>`` 1 kg, MuJoCo
fuses the links welded to the world into it); degrees of freedom and bases are reported side by
side (Drake floats a robot that MuJoCo welds), each difference said in words.
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

from urdftool.budget import Budget
from urdftool.numbers import number
from urdftool.simulators import mujoco_compiler
from urdftool.crosscheck.loaders import LOADERS, Job, available, version

TOLERANCE = 1e-9  # [m]: frame positions of two loaders that keep a frame must agree within it
# [m] PyBullet's frames are off by up to 1.4e-8 m on a 0.4 m arm (measured with 3.2.7 against
# Pinocchio, MuJoCo, Drake and sdformat, which agree to 1e-15 there): single-precision
# arithmetic somewhere in its importer. Compared with it, frames must agree within this.
LOADER_TOLERANCE = {"pybullet": 1e-6}
CONFIGURATIONS = 3  # besides the zero configuration


@dataclass
class LoaderResult:
    """One loader's verdict, as the JSON has it (``as_dict``)."""

    name: str
    version: str | None
    loaded: bool
    error: str | None = None
    location: object = None  # a Location
    mass: float | None = None
    dof: int | None = None
    floating_base: bool | None = None
    links: list = field(default_factory=list)
    dropped_links: list = field(default_factory=list)
    frames: list = field(default_factory=list)
    inertia: dict = field(default_factory=dict)
    output: str = ""
    details: dict = field(default_factory=dict)  # joints' limits, constraints, geoms: as read

    def as_dict(self) -> dict:
        from urdftool.diagnostics import display_path

        where = None if self.location is None else {
            "file": display_path(self.location.file), "line": self.location.line}
        return {"name": self.name, "version": self.version, "loaded": self.loaded,
                "error": self.error, "location": where, "mass": self.mass, "dof": self.dof,
                "floating_base": self.floating_base, "links": self.links,
                "dropped_links": self.dropped_links, "frames": self.frames,
                "inertia": self.inertia, **self.details}


@dataclass
class Crosscheck:
    """What every loader made of one robot.

    loaders: the results, one per loader run; missing: loader -> how to install it
    configurations: joint values the frames were compared at (the first: zero)
    disagreements: sentences, each a difference between loaders that keep the same thing
    """

    path: str
    loaders: list[LoaderResult]
    missing: dict[str, str]
    configurations: list[dict]
    disagreements: list[str] = field(default_factory=list)
    differences: list[str] = field(default_factory=list)

    @property
    def failed(self) -> list[LoaderResult]:
        return [result for result in self.loaders if not result.loaded]

    @property
    def exit_code(self) -> int:
        """1 when a loader failed or the loaders disagree, else 0."""
        return 1 if self.failed or self.disagreements else 0

    def as_dict(self) -> dict:
        return {"file": self.path, "loaders": [r.as_dict() for r in self.loaders],
                "missing": self.missing, "configurations": self.configurations,
                "disagreements": self.disagreements, "differences": self.differences}


def crosscheck(path: str, loaders=None, *, xacro_args=None, packages=None,
               budget: Budget = Budget(), allow_env: bool | None = None) -> Crosscheck:
    """Load ``path`` (URDF or xacro) with each of ``loaders`` (names; None: every one known)
    that is installed, each in a worker process within ``budget``, and compare.

    allow_env: ``$(env)`` and files outside the repository allowed; None, as every command,
    ``check`` and ``load``: the safe mode when ``CI`` is set
    (:func:`urdftool.description.files.env_allowed`; this was True, and ``crosscheck`` under CI
    expanded ``$(optenv SECRET ...)`` into the names it printed).

    Raises UrdftoolError (LoadError, UsageError) when urdftool itself cannot load the file or
    a loader name is unknown."""
    from urdftool.description.load import load
    from urdftool.errors import UsageError

    names = list(LOADERS) if not loaders else list(dict.fromkeys(loaders))
    unknown = [name for name in names if name not in LOADERS]
    if unknown:
        from urdftool.errors import available as choices

        raise UsageError(f"unknown loader '{unknown[0]}'; "
                         + choices("loaders", unknown[0], LOADERS))
    robot = load(path, xacro_args=xacro_args or {}, packages=packages or {},
                 allow_env=allow_env)
    _refuse_files_urdftool_does_not_open(robot)
    present = [name for name in names if available(name)]
    missing = {name: LOADERS[name].install for name in names if name not in present}
    configurations = joint_configurations(robot)
    from urdftool.description.files import temporary_folder

    given = set(packages or {})
    with temporary_folder("urdftool-crosscheck-") as folder:
        packages = _packages(robot)
        urdf, lines = _urdf_file(robot, folder, in_place=_read_in_place(robot, packages, given))
        if os.path.dirname(urdf) == os.path.abspath(folder):
            _packages_beside(folder, packages, robot)
        job = Job(urdf, packages, tuple(configurations))
        raw = _run(present, job, budget)
    results = [_result(name, raw[index], robot, lines, urdf)
               for index, name in enumerate(present)]
    report = Crosscheck(path, results, missing, configurations)
    _compare(report, robot)
    _mujoco_changes(report, robot)
    return report


def _refuse_files_urdftool_does_not_open(robot) -> None:
    """UsageError, before any loader runs, when the robot names a mesh or texture file that
    urdftool itself does not open (:func:`urdftool.description.meshes.uris.resolve`: a link
    leading outside the repository, a file outside it, a named pipe or a device in its place):
    the loaders open what the URDF names with no such rule (MuJoCo read ``/etc/passwd`` through
    a committed link and quoted its path; a named pipe held PyBullet and MuJoCo to the end of
    their budget). A file simply missing, or of another package, is the loaders' to report."""
    from urdftool.description.meshes.uris import resolve
    from urdftool.errors import MeshProblem, UsageError

    for element in robot.root.iter("mesh", "texture"):
        uri = element.get("filename") or ""
        if not uri:
            continue
        try:
            path = resolve(robot, uri)
        except MeshProblem as problem:
            there = problem.kind in ("missing", "corrupt") and _something_at(robot, uri)
            if problem.kind == "outside" or there:
                why = f"{problem}" if not there else \
                    f"{element.tag} '{uri}' is not a regular file (a named pipe, a device?)"
                raise UsageError(f"{robot.display}:{robot.locate(element).line}: {why}; the "
                                 "loaders would open it: not run") from None
            continue
        why = _named_by_the_mesh(path)
        if why:
            raise UsageError(f"{robot.display}:{robot.locate(element).line}: {element.tag} "
                             f"'{uri}' {why}; the loaders would open it: not run")


# Files a mesh names in turn, which the loaders open (PyBullet, MuJoCo and Drake read OBJ with
# tinyobjloader: its material libraries and their texture maps; Drake reads glTF's buffers and
# images) and urdftool never does (line ends: tinyobjloader's, LF and CR LF)
_MTLLIB = re.compile(rb"^[ \t]*mtllib[ \t]+([^\r\n]*)", re.M)
_MAPS = re.compile(rb"^[ \t]*(?:map_\w+|bump|disp|decal|refl|norm)[ \t]+([^\r\n]*)",  # line ends:
                   re.M | re.I)  # (the same)


def _named_by_the_mesh(path: Path) -> str | None:
    """Why a file the mesh at ``path`` (in the repository) names in turn may not be opened:
    outside the mesh's repository (absolute, ``..``, a link leading out), or a named pipe or a
    device; None when every one stays inside (or is simply missing: the loaders say so).
    PyBullet read ``/etc/passwd`` as an OBJ's texture (``map_Kd /etc/passwd`` in its MTL)."""
    import json

    from urdftool.description.files import inside, kind_of, read_regular, real_path
    from urdftool.description.packages import containment_root

    root = real_path(containment_root(path.parent))

    def refused(folder: Path, name: str) -> str | None:
        place = os.path.join(folder, name)
        if not inside(real_path(place), root):
            return f"names '{name}', outside the repository ({root})"
        if kind_of(place) == "other":
            return f"names '{name}', which is not a regular file (a named pipe, a device?)"
        return None

    def words(found: bytes) -> list[str]:  # the whole remainder, and each word of it
        text = found.decode("utf-8", "replace").strip()
        return [text, *text.split()] if text else []

    suffix = path.suffix.lower()
    try:
        data = read_regular(path, as_="mesh")
    except OSError:
        return None
    if suffix == ".obj":
        for library in (w for found in _MTLLIB.findall(data) for w in words(found)):
            why = refused(path.parent, library)
            if why:
                return f"(an OBJ) {why} as its material library"
            place = Path(path.parent, library)
            if kind_of(place) != "file":
                continue
            try:
                materials = read_regular(place, as_="mesh material library")
            except OSError:
                continue
            for texture in (w for found in _MAPS.findall(materials) for w in words(found)
                            if not w.startswith("-")):
                why = refused(place.parent, texture)
                if why:
                    return f"(an OBJ) names material library '{library}', which {why} " \
                           "as a texture"
    elif suffix in (".gltf", ".glb"):
        if suffix == ".glb":  # the JSON chunk: after the 12-byte header, its length and type
            length = int.from_bytes(data[12:16], "little")
            data = data[20:20 + length] if data[16:20] == b"JSON" else b""
        try:
            document = json.loads(data)
        except (ValueError, RecursionError):
            return None
        named = [item.get("uri") for key in ("buffers", "images")
                 for item in (document.get(key) or [] if isinstance(document, dict) else [])
                 if isinstance(item, dict)]
        for uri in named:
            if isinstance(uri, str) and uri and not uri.startswith("data:"):
                why = refused(path.parent, uri.removeprefix("file://"))
                if why:
                    return f"(a glTF) {why}"
    return None


def _something_at(robot, uri: str) -> bool:
    """Whether something that is neither a regular file nor a folder (a named pipe, a device,
    a socket) is where ``uri`` leads: a mesh said missing because it is no regular file."""
    from urdftool.description.files import kind_of

    if uri.startswith("package://"):
        from urdftool.description.packages import package_uri_parts

        package, tail = package_uri_parts(uri)
        try:
            place = os.path.join(robot.resolver.find(package), tail)
        except Exception:  # noqa: BLE001 - an unknown package: nothing there to open
            return False
    elif "://" in uri and not uri.startswith("file://"):
        return False
    else:
        place = robot.resolver.locate_uri(uri, robot.base_dir).path
    return kind_of(place) == "other"


def joint_configurations(robot) -> list[dict]:
    """The zero configuration and :data:`CONFIGURATIONS` more, each joint inside its limits
    (the same for every loader): deterministic, different for each joint."""
    from urdftool.description.urdf import MOVING
    from urdftool.description.values import limit_range
    from urdftool.description.xml import first_child

    configurations = [{}]
    movable = [j for j in robot.children("joint")
               if j.get("type") in MOVING]
    for index in range(CONFIGURATIONS):
        configuration = {}
        for position, joint in enumerate(movable):
            fraction = ((index + 1) * 0.29 + position * 0.137) % 1.0
            bounds = limit_range(joint.get("type"), first_child(joint, "limit"))
            if bounds is None or not bounds[0] < bounds[1] or \
                    not math.isfinite(bounds[1] - bounds[0]):  # (continuous: None)
                value = -1.2 + 2.4 * fraction if joint.get("type") != "prismatic" else \
                    -0.05 + 0.1 * fraction
            else:
                value = bounds[0] + (bounds[1] - bounds[0]) * fraction
            configuration[joint.get("name")] = round(value, 6)
        configurations.append(configuration)
    return configurations


def _read_in_place(robot, packages: dict, given: set) -> bool:
    """Whether the loaders read the user's own file: always, but for a plain URDF one of whose
    packages the user gave (``--package``) where PyBullet, which looks only above the file,
    cannot find it, and that names no mesh by a path relative to its folder (which a copy
    elsewhere would lose). What a loader does with the file as it is is what U932 and the
    other portability rules predict, so nothing else is moved."""
    if not given & set(packages) or _found_above(robot, packages):
        return True
    return any("://" not in (element.get("filename") or "://")
               for element in robot.root.iter("mesh", "texture"))


def _found_above(robot, packages: dict) -> bool:
    """Whether PyBullet finds every package of ``packages`` (name -> folder) from the robot's
    own file: it looks for ``package://NAME/rest`` as ``NAME/rest`` in the file's folder and
    those above it, never through ROS_PACKAGE_PATH, so a URDF outside its package's parent
    (``ros2 run xacro`` output in /tmp, a package found by ``--package``) loads nowhere but
    there."""
    from urdftool.description.files import kind_of, real_path

    if robot.from_xacro or robot.path == "-":
        return False
    above = Path(os.path.abspath(robot.path)).parent
    for name, place in packages.items():
        folders = [above, *above.parents]
        if not any(kind_of(folder / name) == "folder" and
                   real_path(folder / name) == real_path(place) for folder in folders):
            return False
    return True


def _as_text(path: str) -> bool:
    """Whether the loaders can be given ``path``: Pinocchio, MuJoCo and PyBullet take a file name
    as UTF-8 text, which a name holding bytes that are not UTF-8 (0xff: U+DCFF to Python) is
    not; each failed with "UnicodeEncodeError" (or a TypeError) for a file it would read."""
    try:
        path.encode("utf-8")
    except UnicodeEncodeError:
        return False
    return True


def _urdf_file(robot, folder: str, in_place: bool = True) -> tuple[str, dict]:
    """The file the loaders read, and its line -> the element there (for the loaders' errors):
    the user's URDF itself (``in_place``: PyBullet finds its packages from there, when its path
    is text the loaders take: :func:`_as_text`), or xacro's output (or the URDF as read)
    written in ``folder``, with its packages linked beside it."""
    from lxml import etree

    if in_place and not robot.from_xacro and robot.path != "-" and \
            _as_text(os.path.abspath(robot.path)):
        lines: dict = {}
        for element in robot.root.iter():
            if isinstance(element.tag, str):
                lines.setdefault(robot.locate(element).line, element)
        return os.path.abspath(robot.path), lines
    text = _mujoco_folders_kept(robot, etree.tostring(robot.root, pretty_print=True,
                                                      encoding="unicode"))
    name = Path(robot.display).name.removesuffix(".xacro")
    target = Path(folder) / (name if name and _as_text(name) else "robot.urdf")
    if not target.name.endswith(".urdf"):
        target = target.with_suffix(".urdf")
    from urdftool.description.files import write_new

    write_new(Path(folder), target.name, text.encode("utf-8"))
    reread = etree.fromstring(text.encode("utf-8"))
    lines = {}
    for mine, theirs in zip(robot.root.iter(), reread.iter()):
        lines.setdefault(theirs.sourceline, mine)
    return os.fspath(target), lines


# <mujoco><compiler> attributes naming a folder, which MuJoCo takes relative to the file it reads
MUJOCO_FOLDERS = ("meshdir", "texturedir", "assetdir")


def _mujoco_folders_kept(robot, text: str) -> str:
    """``text`` (the robot written out) with the relative folders of its ``<mujoco><compiler>``
    made absolute against the robot's own file's folder, which MuJoCo takes them relative to:
    written to a temporary folder (xacro's output), ``meshdir="../meshes"`` pointed nowhere
    and MuJoCo failed ("Error opening file '../meshes/box.stl'") where the expansion written
    beside the xacro file loads. Only the attributes' values change, so lines stay."""
    compiler = mujoco_compiler(robot.root)
    if compiler is None or not any(compiler.get(name) for name in MUJOCO_FOLDERS):
        return text
    from lxml import etree

    base = Path(robot.files[0]).parent if robot.files else robot.base_dir
    copy = etree.fromstring(text.encode("utf-8"))
    for element in copy.iterfind("mujoco/compiler"):
        for name in MUJOCO_FOLDERS:
            value = element.get(name)
            if value and not os.path.isabs(value):
                element.set(name, os.path.normpath(os.path.join(os.path.abspath(base), value)))
    return etree.tostring(copy, encoding="unicode")


def _packages(robot) -> dict:
    """Package name -> folder, for every package:// the robot names that resolves."""
    from urdftool.description.packages import package_uri_parts

    found = {}
    for element in robot.root.iter("mesh", "texture"):
        uri = element.get("filename") or ""
        if uri.startswith("package://"):
            name, _ = package_uri_parts(uri)
            if name and name not in found:
                try:
                    found[name] = os.fspath(robot.resolver.find(name))
                except Exception:  # noqa: BLE001 - the loader will say it is missing
                    pass
    return found


def _packages_beside(folder: str, packages: dict, robot) -> None:
    """Each package as a link beside xacro's output: PyBullet (3.2) finds a ``package://``
    mesh only below the folders above the file it reads (its search path is not asked for
    meshes), as they are when a robot is loaded from its own repository; written to a
    temporary folder, the expansion would lose them and PyBullet would fail where a user's
    load does not. A package whose install puts a file the robot names elsewhere than its
    source folder holds it (Bolt's ``package://robot_properties_bolt/resources/...``, in
    ``src/robot_properties_bolt/resources`` installed to ``share``) gets a folder of links to
    each file the robot names, where urdftool resolves it. A name taken (the expanded file's
    own) is left as it is."""
    from urdftool.description.files import link_file_new, link_folder_new, real_path

    for name, place in packages.items():
        named = _package_files(robot, name)
        if all(real_path(path) == real_path(Path(place) / rest) for rest, path in named.items()):
            link_folder_new(Path(folder), name, place)
            continue
        for rest, path in named.items():
            link_file_new(Path(folder), f"{name}/{rest}", os.fspath(path))


def _package_files(robot, name: str) -> dict:
    """``rest`` -> the file urdftool resolves, for each ``package://NAME/rest`` the robot's
    meshes and textures name that resolves to a file."""
    from urdftool.description.files import kind_of
    from urdftool.description.packages import package_uri_parts

    found = {}
    for element in robot.root.iter("mesh", "texture"):
        uri = element.get("filename") or ""
        # (split as _packages names them: package:///NAME/... too)
        package, rest = package_uri_parts(uri) if uri.startswith("package://") else ("", "")
        if package != name or not rest or rest in found:
            continue
        try:
            path = robot.resolve_uri(uri)
        except Exception:  # noqa: BLE001 - the loader will say it is missing
            continue
        if kind_of(path) == "file":
            found[rest] = path
    return found


def _run(names: list[str], job: Job, budget: Budget) -> list:
    """Each loader in a worker of its own (forked, one piece each), within the budget."""
    from urdftool.crosscheck.loaders import LOAD
    from urdftool.lint.pool import run_budgeted

    if not names:
        return []
    # never in this process: a loader that aborts would take urdftool with it
    budget = Budget(budget.seconds or 24 * 3600.0, budget.memory)

    def work(index: int):
        return LOAD[names[index]](job)

    def stopped(index: int, stop) -> dict:
        from urdftool.budget import format_memory

        why = {"time": f"took longer than {stop.budget.seconds:g} s and was stopped",
               "memory": "ran out of its memory budget"
                         + (f" ({format_memory(stop.budget.memory)})" if stop.budget.memory
                            else ""),
               "died": f"the loader's process died: {stop.detail}"}.get(
            stop.kind, (stop.detail.strip().splitlines() or ["crashed"])[-1])
        return {"loaded": False, "error": why}

    return run_budgeted(len(names), work, budget, stopped, jobs=len(names))


_LINE = (re.compile(r"\.urdf:(\d+):"), re.compile(r"Line number=(\d+)"),
         re.compile(r"line (\d+)"))
_FILE = (re.compile(r"Error opening file '([^']+)'"),
         re.compile(r"no decoder found for mesh file '([^']+)'"),
         re.compile(r"cannot find '([^']+)' in any directory"),
         re.compile(r"invalid mesh filename extension"),
         re.compile(r"unsupported extension '[^']+' for geometry data: (\S+?)\.?$",
                    re.M))  # line ends: a loader's messages (LF)
_LINK = (re.compile(r"Element name '([^']+)'"), re.compile(r"link\[@name=\"([^\"]+)\"\]"),
         re.compile(r"A link named (\S+) has"), re.compile(r"Link:\s*(?:b3Error\[[^\]\s]*\]:\s*)?"
                                                             r"((?:(?!Link:)\S)+?)b3"),
         re.compile(r"link \[([^][]+)\]"),  # (a name looked for up to the next opener only:
         # from each to the end of the loader's output was quadratic in them)
         re.compile(r"root links found: \[[^\]\s]+\] and \[([^\]\s]+)\]"))  # urdfdom: the second root


def _result(name: str, raw: dict, robot, lines: dict, urdf: str) -> LoaderResult:
    result = LoaderResult(name, version(name), bool(raw.get("loaded")), raw.get("error"),
                          mass=raw.get("mass"), dof=raw.get("dof"),
                          floating_base=raw.get("floating_base"), links=raw.get("links") or [],
                          frames=raw.get("frames") or [], inertia=raw.get("inertia") or {},
                          output=raw.get("output") or "",
                          details={key: raw[key] for key in ("joints", "constraints", "geoms")
                                   if key in raw})
    if result.links:
        result.dropped_links = [link for link in robot.links if link not in set(result.links)]
    if not result.loaded:
        result.location = _located(robot, lines, result.error or "", result.output, urdf)
        unfound = _UNFOUND_MESH.findall(result.output)
        if unfound:
            result.error = f"{(result.error or '').rstrip('.')}: {_unfound_advice(robot, unfound)}"
        if name == "mujoco" and _PACKAGE_OPENED.search(result.error or ""):
            result.error = f"{result.error.rstrip()}; {MUJOCO_PACKAGES}"
    return result


# MuJoCo (3, 4) opens a package:// or file:// URI as a file name, its "//" made one "/"
_PACKAGE_OPENED = re.compile(r"Error opening file '(?:package|file):/")
MUJOCO_PACKAGES = ("MuJoCo's URDF import resolves no package:// or file:// URI (no ROS package "
                   "path): for MuJoCo, put the meshes in one folder and name it with "
                   "<mujoco><compiler meshdir=\"...\" strippath=\"true\"/></mujoco> in the "
                   "<robot> (MuJoCo then looks for each by its file name there), or convert "
                   "the robot to MJCF with its paths resolved")


# PyBullet (3.2)'s warning for a mesh it cannot find, before "Cannot load URDF file."
_UNFOUND_MESH = re.compile(r"cannot find '([^']+)' in any directory in urdf path")


def _unfound_advice(robot, names: list[str]) -> str:
    """What to do about the meshes PyBullet printed it cannot find (``names``, as it cuts
    ``package://`` off): the package urdftool cannot find either (give it), or the file that is
    not there ('urdftool check' says where it was looked for)."""
    from urdftool.description.packages import package_uri_parts

    from urdftool.description.files import kind_of

    names = list(dict.fromkeys(names))
    unknown, missing, elsewhere = [], [], []
    for name in names:
        uri = next((e.get("filename") for e in robot.root.iter("mesh")
                    if _names(robot, e.get("filename") or "", name)), None)
        package = package_uri_parts(uri)[0] if uri and uri.startswith("package://") else None
        try:
            folder = robot.resolver.find(package) if package is not None else None
            known = True
        except Exception:  # noqa: BLE001 - an unknown package
            known, folder = False, None
        if not known:
            unknown.append(package)
        elif folder is not None and Path(folder).name != package and \
                kind_of(Path(folder, package_uri_parts(uri)[1])) == "file":
            elsewhere.append((package, Path(folder)))
        else:
            missing.append(uri or name)
    said = f"it cannot find mesh '{names[0]}'" + (f" and {len(names) - 1} more" if
                                                 len(names) > 1 else "")
    if elsewhere and not unknown:
        package, folder = elsewhere[0]
        return (f"{said}, which is there: PyBullet looks for package://{package}/... as a "
                f"folder named '{package}' above the file it reads, and package '{package}' is "
                f"the folder '{folder.name}' ({folder}), found by its package.xml; a "
                f"workspace whose folder is named '{package}' loads")
    if unknown:
        first = list(dict.fromkeys(unknown))[0]
        return (f"{said}; package '{first}' is not found by urdftool either: give it with "
                f"--package {first}=PATH (urdftool links each package it knows beside the file "
                "PyBullet reads)")
    return (f"{said}, which is not there; 'urdftool check' says where each mesh was looked "
            "for")


def _located(robot, lines: dict, error: str, output: str, urdf: str):
    """Where in the files the user wrote a loader's error points: the line it names (through
    xacro's output, the element there), else the link it names; None when it names neither."""
    from urdftool.crosscheck.loaders import SOURCE_LINE

    text = SOURCE_LINE.sub("", f"{error}\n{output}")  # "at line 274 in model.cpp": urdfdom's own
    for pattern in _LINE:
        for match in pattern.finditer(text):
            line = int(match.group(1))
            # the element starting on that line of the file the loader read, else the last
            # one before it (a loader may count the line where a tag ends)
            starts = [number for number in lines if number is not None and number <= line]
            if starts and line <= max(number for number in lines if number is not None) + 50:
                return robot.locate(lines[max(starts)])
    for pattern in _FILE:
        for match in pattern.finditer(text):
            named = _normalized(match.group(1))
            # a <collision> first: MuJoCo and Drake fail on those, RViz-only visuals later
            elements = sorted(robot.root.iter("mesh", "texture"), key=lambda e: (
                e.getparent() is None or e.getparent().getparent() is None or
                e.getparent().getparent().tag != "collision"))
            for element in elements:
                if _names(robot, element.get("filename") or "", named):
                    return robot.locate(element)
    for pattern in _LINK:  # a link, else a joint of that name (MuJoCo names either)
        for match in pattern.finditer(text):
            element = robot.links.get(match.group(1))
            if element is None:
                element = robot.joints.get(match.group(1))
            if element is not None:
                return robot.locate(element)
    return None


def _names(robot, filename: str, named: str) -> bool:
    """Whether a loader's file name ``named`` is the file ``filename`` of the robot: as written
    (MuJoCo), as resolved (Drake), or as PyBullet cuts package:// off."""
    if not filename:
        return False
    if _normalized(filename) == named or \
            _normalized(filename.split("://", 1)[-1]).lstrip("/") == named.lstrip("/"):
        return True
    from urdftool.description.files import real_path

    try:
        return real_path(robot.resolve_uri(filename)) == real_path(named)
    except Exception:  # noqa: BLE001 - an unknown package
        return False


def _normalized(name: str) -> str:
    """A file name as MuJoCo prints it: runs of "/" made one ("package:/pkg/...")."""
    return re.sub(r"/+", "/", name)


def _unplaced(loaded: list, robot) -> dict:
    """loader name -> link -> the configurations (indices) at which that loader gives the link
    no finite position (PyBullet normalises a zero axis into NaN): said once, as what it is,
    not as a distance of NaN metres to every other loader."""
    found: dict = {}
    for result in loaded:
        for index, frames in enumerate(result.frames):
            for link in robot.links:
                position = frames.get(link)
                if position is not None and not all(
                        value is not None and math.isfinite(value) for value in position):
                    found.setdefault(result.name, {}).setdefault(link, []).append(index)
    return found


def _compare(report: Crosscheck, robot) -> None:
    """Fill ``disagreements`` (frames two loaders keep, apart by more than TOLERANCE) and
    ``differences`` (masses accounted for, degrees of freedom, base, dropped links: said, not
    failed); a total mass no reading accounts for is a disagreement (:mod:`.masses`)."""
    loaded = [r for r in report.loaders if r.loaded and r.frames]
    unplaced = _unplaced(loaded, robot)
    for result in loaded:
        for link, indices in unplaced.get(result.name, {}).items():
            at = ("every configuration" if len(indices) == len(result.frames) else
                  ", ".join("the zero configuration" if i == 0 else f"configuration {i}"
                            for i in indices))
            report.disagreements.append(
                f"{result.name} gives link '{link}' no finite position (NaN) at {at}")
    for index, configuration in enumerate(report.configurations):
        for first_index, first in enumerate(loaded):
            for second in loaded[first_index + 1:]:
                a, b = first.frames[index], second.frames[index]
                worst, where = 0.0, None
                for link in robot.links:
                    if link in a and link in b and not any(
                            index in unplaced.get(r.name, {}).get(link, ())
                            for r in (first, second)):
                        gap = math.dist(a[link], b[link])
                        if not gap <= worst:  # NaN too
                            worst, where = gap, link
                tolerance = max(LOADER_TOLERANCE.get(first.name, TOLERANCE),
                                LOADER_TOLERANCE.get(second.name, TOLERANCE))
                if where is not None and not worst <= tolerance:
                    at = "the zero configuration" if index == 0 else f"configuration {index}"
                    report.disagreements.append(
                        f"{first.name} and {second.name} place link '{where}' {number(worst, 3)} m "
                        f"apart at {at}")
    from urdftool.crosscheck.masses import compare as masses

    masses(report, robot)
    for label, key in (("degrees of freedom", "dof"), ("floating base", "floating_base")):
        values = {r.name: getattr(r, key) for r in report.loaders if r.loaded}
        shown = {v if not isinstance(v, float) else round(v, 9) for v in values.values()}
        if len(shown) > 1:
            report.differences.append(f"{label}: " + ", ".join(
                f"{name} {number(value, 6)}" if isinstance(value, float) else f"{name} {value}"
                for name, value in values.items()))
    for result in report.loaders:
        if result.loaded and result.dropped_links:
            listed = ", ".join(result.dropped_links[:6])
            more = f" and {len(result.dropped_links) - 6} more" if \
                len(result.dropped_links) > 6 else ""
            report.differences.append(f"{result.name} has no link {listed}{more} "
                                      "(fused, lumped or dropped)")


# <mujoco><compiler> attributes that change what MuJoCo holds of a URDF, and what each does
MUJOCO_SETTINGS = {
    "balanceinertia": ("principal moments that break the triangle inequality raised",
                       "inertias as declared"),
    "inertiafromgeom": ("every body's inertia computed from its geoms", "inertias as declared",
                        "the inertia of a body without <inertial> computed from its geoms"),
    "boundmass": ("masses below it raised",), "boundinertia": ("moments below it raised",),
    "fusestatic": ("a body welded by a fixed joint fused into its parent",
                   "bodies welded by fixed joints kept"),
    "discardvisual": ("<visual> geoms dropped", "<visual> geoms kept"),
}


def _setting(name: str, value: str) -> str:
    """What MuJoCo does with ``name="value"`` of its compiler (:data:`MUJOCO_SETTINGS`)."""
    said = MUJOCO_SETTINGS[name]
    if len(said) == 1:
        return said[0]
    return {"true": said[0], "false": said[1]}.get(value.strip().lower(), said[-1])


def _mujoco_changes(report: Crosscheck, robot) -> None:
    """What MuJoCo changed of the URDF, as ``differences``: the ``<mujoco><compiler>`` settings
    it read (:data:`MUJOCO_SETTINGS`) and the links whose mass or principal moments it holds
    other than the URDF declares (a body something was fused into is not compared: its
    inertia is the sum). A robot's own ``balanceinertia="true"`` changed inertias silently."""
    result = next((r for r in report.loaders if r.name == "mujoco" and r.loaded), None)
    if result is None:
        return
    compiler = mujoco_compiler(robot.root)
    read = {name: compiler.get(name) for name in MUJOCO_SETTINGS
            if compiler is not None and compiler.get(name) is not None}
    if read:
        report.differences.append(
            "mujoco read the robot's <mujoco><compiler>: " + "; ".join(
                f'{name}="{value}" ({_setting(name, value)})' for name, value in read.items()))
    changed = _inertias_changed(result, robot)
    if changed:
        shown = "; ".join(
            f"{link}: URDF {number(urdf[0], 6)} kg, moments {' '.join(number(m, 6) for m in urdf[1])}"
            f", MuJoCo {number(theirs[0], 6)} kg, moments "
            f"{' '.join(number(m, 6) for m in theirs[1])}"
            for link, urdf, theirs in changed[:3])
        more = f" and {len(changed) - 3} more" if len(changed) > 3 else ""
        report.differences.append(
            f"mujoco holds another mass or inertia [kg m^2] than the URDF declares for "
            f"{len(changed)} link(s): {shown}{more}")


def _inertias_changed(result: LoaderResult, robot) -> list:
    """(link, (mass, moments) declared, (mass, moments) MuJoCo holds) for each body MuJoCo
    keeps as the URDF link alone, whose mass or sorted principal moments differ from the
    declared ones by more than 1e-6 of the largest."""
    from urdftool.physics.mass import declared_of, moments_of

    parents = {}
    for joint in robot.joints.values():
        parent, child = joint.find("parent"), joint.find("child")
        if parent is not None and child is not None:
            parents.setdefault(child.get("link"), parent.get("link"))
    fused, dropped = set(), set(result.dropped_links)
    for link in dropped:  # fused into the nearest ancestor MuJoCo keeps
        parent, seen = parents.get(link), {link}
        while parent in dropped and parent not in seen:
            seen.add(parent)
            parent = parents.get(parent)
        fused.add(parent)
    changed = []
    for link, held in result.inertia.items():
        element = robot.links.get(link)
        body = declared_of(robot, element) if element is not None else None
        moments = moments_of(robot, element) if body is not None else None
        if moments is None or link in fused or held.get("inertia") is None:
            continue
        mine = (float(body.mass), sorted(float(m) for m in moments))
        theirs = (float(held["mass"]), sorted(float(m) for m in held["inertia"]))
        scale = max([abs(mine[0]), *map(abs, mine[1]), 1e-12])
        if abs(mine[0] - theirs[0]) > 1e-6 * abs(mine[0]) or any(
                abs(a - b) > 1e-6 * max(scale, 1e-12) for a, b in zip(mine[1], theirs[1])):
            changed.append((link, mine, theirs))
    return changed


__all__ = ["TOLERANCE", "Crosscheck", "LoaderResult", "crosscheck", "joint_configurations"]
