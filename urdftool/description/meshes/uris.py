"""Where a mesh URI leads, and whether urdftool may open it.

- the URI resolves (``package://`` through the robot's resolver, ``file://``, relative);
- a ``file://`` or relative path may not leave the containment root (the nearest ancestor of
  the robot file holding ``.git``; without one, the robot's package folder, else its folder);
  a ``package://`` path may not leave its package folder, nor a ``file://`` path made by a
  ``$(find PKG)`` of the robot's xacro (read as ``package://PKG/...``, :func:`_found_by_xacro`);
- only files with a mesh extension are opened (:data:`MESH_EXTENSIONS`).

A URI is resolved and checked once per robot, a path once per run.
"""

from __future__ import annotations

import fnmatch
import os
import re
from dataclasses import replace
from pathlib import Path

from urdftool.description.files import (inside, kind_of, listing,
                                        no_file_there, read_regular, real_inside, real_path,
                                        resolved, walk)
from urdftool.description.packages import (containment_root, declaring_package, installed,
                                          manifest_said, package_name, package_of,
                                          package_uri_parts, written_from_above)
from urdftool.description.run_memo import per_run
from urdftool.diagnostics import display_path
from urdftool.errors import MeshProblem, PackageNotFound, shown_word, similarity

# a file of a ROS distribution's binary install: /opt/ros/DISTRO/share/PACKAGE/PATH
_ROS_INSTALL = re.compile(r"/opt/ros/([^/]+)/share/([^/]+)/(.+)")

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
    windows = _windows_machine(robot, uri)
    if windows is not None:
        raise windows
    if uri.startswith("package://"):
        package, tail = package_uri_parts(uri)
        try:
            folder = robot.resolver.find(package)  # (the robot's resolver: once per robot)
        except PackageNotFound as error:
            raise _no_package(robot, uri, package, tail, error) from None
        found = _in_package(uri, package, os.fspath(folder), tail)
        found = _across(robot, uri, found, os.path.join(os.fspath(folder), tail))
    else:
        if uri.startswith("model://"):
            raise MeshProblem("format", f"mesh '{uri}': a Gazebo model:// URI, which Gazebo finds "
                                        "on its resource path (GZ_SIM_RESOURCE_PATH, "
                                        "GAZEBO_MODEL_PATH) and RViz, MoveIt and other urdfdom "
                                        "users do not; the mesh is not checked")
        if "://" in uri and not uri.startswith("file://"):
            raise MeshProblem("format", f"mesh '{uri}': only package://, file:// and relative "
                                        "paths are supported")
        found_by = _found_by_xacro(robot, uri)
        if found_by is not None:
            return _raised(_in_package(uri, *found_by))
        located = robot.resolver.locate_uri(uri, robot.base_dir)
        found = _doubted(uri, _checked(uri, os.fspath(located.path), os.fspath(robot.base_dir),
                                       None, bool(located.doubt)),
                         located, os.fspath(robot.base_dir))
        if not uri.startswith("file://"):  # (an absolute path names one machine's files)
            found = _across(robot, uri, found, os.path.join(os.fspath(robot.base_dir), uri))
        found = _from_cwd(robot, uri, os.fspath(located.path), found)
        found = _in_mujoco_meshdir(robot, uri, os.fspath(located.path), found)
    return _raised(found)


# a Windows path with its drive letter, as written or as a file:// URI (file:///C:/, file://C:\\)
_DRIVE = re.compile(r"(?:file:///?)?([A-Za-z]):[\\/]")


def _windows_machine(robot, uri: str) -> MeshProblem | None:
    """The problem of a mesh named as only a Windows machine names it (a CAD exporter's URDF):
    by a path with a drive letter (``C:\\Users\\me\\robot\\meshes\\base.STL``,
    ``file:///C:/...``), a file of the exporter's machine, on no other; or by a ``package://``
    URI whose package name holds its backslashes (``package://robot\\meshes\\base.STL``: the
    package's name is all of it, and no package is named so). Said with the URI to write when
    the repository holds the file the path ends with (:func:`_end_in_repository`); None for
    any other URI."""
    drive = _DRIVE.match(uri)
    if drive is not None:
        letter, parts = drive.group(1), re.split(r"[\\/]", uri[drive.end():])
        return MeshProblem("missing", f"mesh '{uri}' is a path of a Windows machine (drive "
                                      f"{letter}:), the one the robot was exported on, there on "
                                      f"no other{_end_in_repository(robot, parts)}")
    if uri.startswith("package://") and "\\" in package_uri_parts(uri)[0]:
        parts = re.split(r"[\\/]", uri[len("package://"):])
        return MeshProblem("missing", f"mesh '{uri}' names a package '{package_uri_parts(uri)[0]}':"
                                      " backslashes are no path separators on Linux, where a "
                                      "backslash is part of a name, and no package is named so"
                                      f"{_end_in_repository(robot, parts)}")
    return None


def _end_in_repository(robot, parts: list[str]) -> str:
    """Advice for a mesh path written on Windows (its folders and file name ``parts``): the
    longest end of it that is a mesh file of the robot's repository, as the URI to write
    (``package://NAME/...`` in a package, else relative to the robot file); "" when none is."""
    parts = [part for part in parts if part not in ("", ".")]
    if ".." in parts or robot.path == "-":
        return ""
    root = _real(containment_root(Path(robot.base_dir)))
    for start in range(len(parts)):
        path = root.joinpath(*parts[start:])
        if path.suffix.lower() not in MESH_EXTENSIONS or kind_of(path) != "file" or \
                not inside(_real(path), root):
            continue
        folder = package_of(path)
        name = package_name(folder) if folder is not None else None
        written = (f"package://{name}/{Path(os.path.relpath(path, folder)).as_posix()}" if name
                   else Path(os.path.relpath(path, robot.base_dir)).as_posix())
        return f"; the repository holds its end, {'/'.join(parts[start:])}: write '{written}'"
    return ""


def _raised(found: Path | MeshProblem) -> Path:
    if isinstance(found, MeshProblem):
        raise replace(found)  # a new one: raised once per robot
    return found


# [folders] above a mesh that leaves its package looked at for the package it leads into
_ACROSS_DEPTH = 8


def _across(robot, uri: str, found: Path | MeshProblem, written: str) -> Path | MeshProblem:
    """``found``, for a relative mesh path leaving the robot's repository (or package) or a
    ``package://`` path leaving its package by ``..``, read instead as the file of the package
    it leads into when the robot's resolver finds that package there: pkg_a's
    ``../../other_pkg/meshes/x.stl`` and ``package://pkg_a/../other_pkg/meshes/x.stl`` are
    ``package://other_pkg/meshes/x.stl`` where the two packages are side by side, as they are
    here (and as a relative path between two packages of one repository is read: no finding).
    They were errors, "outside the robot's repository", of a file urdftool opens when named by
    its package. Only a folder of the package's name is asked for, so nothing outside is read
    that ``package://`` would not read; ``found`` otherwise (a package the resolver does not
    find: outside, as before)."""
    if not isinstance(found, MeshProblem) or found.kind != "outside" or not found.certain:
        return found
    written = os.path.normpath(written)
    folder = os.path.dirname(written)
    for _ in range(_ACROSS_DEPTH):
        name = os.path.basename(folder)
        if not name:
            break
        try:
            at = robot.resolver.find(name)
        except PackageNotFound:
            at = None
        if at is not None and real_path(os.fspath(at)) == real_path(folder):
            return _in_package(uri, name, os.fspath(at),
                               Path(os.path.relpath(written, folder)).as_posix())
        folder = os.path.dirname(folder)
    return found


def _found_by_xacro(robot, uri: str) -> tuple[str, str, str] | None:
    """The package, its folder and the path below it of a ``file://`` mesh below a package
    the robot's resolver found when the robot's xacro files write ``$(find NAME)`` of that
    package (uuv_simulator's ``file://$(find uuv_sensor_ros_plugins)/meshes/dvl.dae``, used
    by the robots of eca_a9 and rexrov2, other repositories): xacro writes where the package
    is on the machine it runs on, on any machine, as ``package://NAME/...`` names it; so it
    is read and checked as that package's file. None otherwise (an absolute path written as
    such names one machine's files: outside the repository)."""
    if not uri.startswith("file://") or not robot.from_xacro:
        return None
    path = uri[len("file://"):]
    below = robot.resolver.package_at(path) if os.path.isabs(path) else None
    if below is None:
        return None
    name, folder = below
    find = re.compile(rb"\$\(find\s+" + re.escape(os.fsencode(name)) + rb"\s*\)")
    if not any(find.search(data) for data in robot.sources.values()):
        return None
    tail = Path(os.path.relpath(os.path.abspath(path), folder)).as_posix()
    return name, os.fspath(folder), tail


def _from_cwd(robot, uri: str, path: str, found: Path | MeshProblem) -> Path | MeshProblem:
    """``found``, a mesh missing at ``path``, said not certain when xacro's ``$(cwd)`` made the
    path (the robot's files write it, and ``path`` is below the folder urdftool runs from, which
    is what xacro gives it here) and the rest of the path is a file from a folder between the
    robot file's and its repository's root: the mesh is there when xacro runs from that folder
    (pybullet_simplified_fetch's ``file://$(cwd)/meshes/table.stl``, whose README says to run
    xacro in the robot's folder). ``found`` otherwise."""
    here = os.getcwd()
    if not isinstance(found, MeshProblem) or found.kind != "missing" or not found.certain \
            or not robot.from_xacro or not path.startswith(here + os.sep) \
            or not any(b"$(cwd)" in data for data in robot.sources.values()):
        return found
    folder = written_from_above(robot.base_dir, path[len(here) + 1:], skip=here)
    if folder is None:
        return found
    return MeshProblem("missing", (
        f"mesh '{uri}' not found: written with $(cwd), the folder xacro runs from; it is there "
        f"when xacro runs from '{display_path(folder)}'"), certain=False)


def _in_mujoco_meshdir(robot, uri: str, path: str,
                       found: Path | MeshProblem) -> Path | MeshProblem:
    """``found``, a relative mesh path missing beside the robot file (at ``path``), said not certain when the
    robot's ``<mujoco><compiler meshdir=...>`` (read by MuJoCo alone: :func:`~urdftool.simulators.
    mujoco_compiler`) leads MuJoCo to the file: below that folder as written, or by its file
    name alone (``strippath``, MuJoCo's default for URDF before 3.7.0). Inspire's hand URDF
    writes bare names (``right_base_link.obj``) and ``meshdir="../collision/"``, for MuJoCo,
    which finds every file; a loader reading paths beside the file does not (a warning naming
    that, not an error). ``found`` otherwise."""
    from urdftool.simulators import mujoco_compiler

    if not isinstance(found, MeshProblem) or found.kind != "missing" or not found.certain \
            or uri.startswith("file://") or os.path.isabs(uri):
        return found
    compiler = mujoco_compiler(robot.root) if robot.root is not None else None
    meshdir = compiler.get("meshdir") if compiler is not None else None
    if not meshdir or robot.path == "-":
        return found
    folder = os.path.join(os.fspath(robot.base_dir), meshdir)
    for named in dict.fromkeys((os.path.join(folder, uri),
                                os.path.join(folder, uri.replace("\\", "/").rsplit("/", 1)[-1]))):
        there = _checked(uri, named, os.fspath(robot.base_dir), None)
        if isinstance(there, Path):
            return MeshProblem("missing", (
                f"mesh '{uri}' not found beside the robot file (looked at {path}), where "
                "PyBullet, Pinocchio and other loaders that read a path from the file look; "
                f"MuJoCo, which looks in the robot's <mujoco><compiler meshdir=\"{meshdir}\">, "
                f"finds it at {display_path(there)}"), certain=False)
    return found


def _no_package(robot, uri: str, package: str, tail: str, error) -> MeshProblem:
    """The problem of a ``package://`` mesh whose package is not found. Not certain when the
    path it names, read below the robot's folder or a folder above it in its repository
    (``FOLDER/PACKAGE/TAIL``), is a mesh file, as descriptions with no ROS package write it:
    onshape-to-robot's ``package://assets/part.stl`` beside the robot file, which the loaders
    that drop ``package://`` (PyBullet; Pinocchio given the robot's folder) open; NASA's
    r2_description, a folder of the package's name without a package.xml, which a loader given
    the folder above as a package path (Pinocchio's package_dirs, urdf-loaders' packages)
    opens. ROS's resource_retriever opens neither. A file name written as the package
    (``package://body.stl``, onshape-to-robot's MuJoCo exports) with a file of that name below
    the robot file (``assets/body.stl``) is not certain either: a loader given that folder
    opens it (Pinocchio's package_dirs; MuJoCo before 3.7.0, which keeps the file name only).

    Otherwise the package is not installed here: the environment's (as a ``$(find)``'s is),
    so not certain, unless the robot's package.xml does not declare it and either its name
    is nearly that of a package found here (a misspelt or stale name:
    ``package://moveo_urdf_4/`` beside the package moveo_urdf) or a folder of its name above
    the robot file lacks the file (the loaders that look there find the folder, not the mesh;
    ROS has no such package)."""
    error = PackageNotFound(error.name, error.searched, close=error.close,
                            unchecked="the mesh is not checked")  # (the robot is)
    base = os.fspath(robot.base_dir)
    root, folder = os.path.normpath(os.fspath(containment_root(Path(base)))), base
    seen = None  # the nearest folder of the package's name beside or above the robot file
    while isinstance(_checked(uri, os.path.join(folder, package, tail), base, None), MeshProblem):
        if seen is None and kind_of(os.path.join(folder, package)) == "folder":
            seen = os.path.join(folder, package)
        if os.path.normpath(folder) == root or os.path.dirname(folder) == folder:
            owner, declares, manifest = declaring_package(robot.path, package) \
                if robot.path != "-" else (None, False, "package.xml")
            error = error.declared(owner, declares, manifest=manifest)
            lacking = f"; {seen}{_holding(seen, package)} does not hold '{tail}'" if seen else ""
            misspelt = any(_misspelling(package, close) for close in error.close or ())
            below = _named_below(base, package) if not tail else None
            held = (f"; not certain: '{below}', below the robot file, has that name, where "
                    "loaders given its folder find it (Pinocchio's package_dirs; MuJoCo "
                    "before 3.7.0 given it as meshdir, as it keeps a mesh's file name only)"
                    ) if below else ""
            certain = not declares and not below and (misspelt or bool(seen))
            own = _in_own_package(robot, owner, tail)
            if own:  # the package's name is the slip: no dependency to add, no path to pass
                return MeshProblem("package", f"mesh '{uri}': package '{package}' not found"
                                              f"{own}{lacking}{held}", certain=certain,
                                   declared=error.declared_by is not None)
            return MeshProblem("package", f"mesh '{uri}': {error}{lacking}{held}",
                               certain=certain, declared=error.declared_by is not None,
                               repeated=error.repeated)
        folder = os.path.dirname(folder)
    if folder == base:
        written = os.path.normpath(os.path.join(package, tail))  # (package://NAME.stl: no '/')
        return MeshProblem("package", f"mesh '{uri}': {error}; not certain: '{written}' is "
                                      "beside the robot file, where loaders that drop "
                                      "'package://' (PyBullet; Pinocchio given this folder) "
                                      "find it", certain=False, repeated=error.repeated)
    held = _holding(os.path.join(folder, package), package)
    return MeshProblem("package", f"mesh '{uri}': {error}; not certain: {folder} holds a "
                                  f"folder '{package}'{held} with this file, where "
                                  "PyBullet (which looks in every folder above the robot file) "
                                  "and loaders given it as a package path (Pinocchio's "
                                  "package_dirs) find it", certain=False,
                       repeated=error.repeated)


def _holding(folder: str, package: str) -> str:
    """`` (no package.xml or manifest.xml)``, or what else makes the folder ``folder``, named as
    the package ``package``, no package of that name
    (:func:`~urdftool.description.packages.manifest_said`), as a message says it after the
    folder's name; empty when its manifest names that package."""
    said = manifest_said(folder, package)
    return f" ({said})" if said else ""


def _named_below(base: str, name: str) -> str | None:
    """The file named ``name`` (``package://NAME.stl``: a file name written as a package's)
    in a folder below the robot file's, three levels at most, relative to it; None when
    none is (onshape-to-robot's MuJoCo exports write ``package://body.stl`` for
    ``assets/body.stl``)."""
    if not name or "." not in name or any(char in name for char in "*?[]|/\\"):
        return None
    for folder, entries in walk(base, f"{name}|*/", 3, most=200):
        if os.path.normpath(folder) != os.path.normpath(base) and \
                (name, "file") in entries:
            return Path(os.path.relpath(os.path.join(folder, name), base)).as_posix()
    return None


def _in_own_package(robot, owner: str | None, tail: str) -> str:
    """Advice for a mesh of a package not found whose path is in the robot's own package (a
    SolidWorks export names the package after the model: Ausaurus/ranger_1s_urdf's
    ``package://ranger1s_urdf_3/meshes/chassis_link.STL`` in the package robot_urdf, which holds
    meshes/chassis_link.STL); "" otherwise."""
    folder = package_of(robot.path) if owner and robot.path != "-" else None
    if folder is None or kind_of(Path(folder) / tail) != "file":
        return ""
    return (f"; the robot's own package '{owner}' holds '{tail}': write "
            f"'package://{owner}/{tail}'")  # (quoted: a name the text report sets aside)


def _misspelling(name: str, close: str) -> bool:
    """Whether package ``name`` may be ``close`` misspelt or stale: not when both have as many
    words and a word of one is no near spelling of the other's (Shadow's ``ur_description``
    beside its own ``sr_description``: another vendor's package, one letter apart). A word
    added (``moveo_urdf_4`` beside ``moveo_urdf``) is an old export's name."""
    words, others = name.lower().split("_"), close.lower().split("_")
    if len(words) != len(others):
        return True
    return all(similarity(word, other) >= 0.75
               for word, other in zip(words, others) if word != other)


@per_run
def _in_package(uri: str, package: str, folder: str, tail: str) -> Path | MeshProblem:
    """The file of ``uri``, ``tail`` below package ``package``'s folder ``folder`` (or where
    an install rule of its build takes it from), checked (:func:`_checked`); else the
    MeshProblem. Once per run: every robot that names the mesh in a package found in the same
    folder gets the same answer."""
    at = Path(folder)
    located = installed(package, at, at / tail)
    return _doubted(uri, _checked(uri, os.fspath(located.path), os.fspath(located.within),
                                  package, bool(located.doubt)),
                    located, os.fspath(located.within))


def _doubted(uri: str, found: Path | MeshProblem, located, base: str) -> Path | MeshProblem:
    """``found``, the file of mesh ``uri`` missing from the source tree, said not certain when
    the package's build may put it there (``located.doubt``, docs/packages.md), and with
    advice: the file meant by a path written with Windows separators (:func:`_windows_path`),
    else where the repository has a file of its name (:func:`_elsewhere`; ``base``: the folder
    it was looked for from)."""
    if not isinstance(found, MeshProblem) or found.kind != "missing":
        return found
    path = os.fspath(located.path)
    windows = _windows_path(uri, path)
    said = found.message + windows
    hint = "" if windows else _elsewhere(_real(Path(path)), base)
    if located.doubt:  # (said "not found in the source tree": _checked)
        return MeshProblem("missing", f"{said}; {located.doubt}{hint}", certain=False)
    # a folder kept empty first: it says the files are put there later, which a .gitignore
    # only suggests (a file ignored by mistake is never supplied), so it is the note
    kept = _kept_empty(os.path.dirname(path))
    if kept:
        return MeshProblem("missing", f"{said}{hint}: not certain: its folder holds only "
                                      f"{kept}, a folder kept empty in the repository for files "
                                      "put there later (a tool, a download, a build step or a "
                                      "per-robot calibration fills it)", certain=False,
                           kept_empty=True)
    ignored = _git_ignored(path)
    if ignored:
        return MeshProblem("missing", f"{said}{hint}: not certain: {ignored}, so no clone has "
                                      "it: it is there only where a build step, a download or "
                                      "a tool puts it", certain=False)
    searched = "" if windows or hint else _on_a_search_path(uri, base)
    if searched:
        return MeshProblem("missing", f"{said}: not certain: {searched}", certain=False)
    return replace(found, message=said + hint) if windows or hint else found


def _on_a_search_path(uri: str, base: str) -> str:
    """Why mesh ``uri``, missing from ``base`` (the robot file's folder), may still be found,
    when it is a relative path with no scheme that neither starts with ``./`` or ``../`` nor
    names a folder that is beside the robot file: UWSim's scene URDFs write
    ``robot/GIRONA500/g500_March11.osg``, which UWSim looks for on its data path
    (``~/.uwsim/data``, downloaded on its first run, or ``--dataPath``), as a loader given a
    search path does (PyBullet's ``setAdditionalSearchPath``), when the repository holds no
    mesh in a folder of that name anywhere (the tree is another's: a download, a data
    package). "" otherwise: a path anchored at the file, one whose first folder is there (the
    file missing from it), or one into a folder name the repository's meshes are in (Inspire
    hand's ``meshes/...`` where the hand's meshes are in another ``meshes/``: a wrong path)."""
    if "://" in uri or "\\" in uri or os.path.isabs(uri) or "/" not in uri:
        return ""
    first = uri.split("/", 1)[0]
    if first in ("", ".", "..") or kind_of(os.path.join(base, first), follow=False):
        return ""
    root = os.fspath(_real(containment_root(Path(base))))
    if any(first in folder.split(os.sep) for folder in _mesh_folders(root)):
        return ""
    return (f"no folder '{first}' is beside the robot file nor holds any of the repository's "
            "meshes, so the path names a file on a loader's data or search path (UWSim's "
            "~/.uwsim/data or --dataPath, PyBullet's setAdditionalSearchPath), not beside the "
            "file")


def _git_ignored(path: str) -> str:
    """Which ``.gitignore`` of the repository ignores the file ``path`` (a mesh missing from
    the source tree), said as "the repository's FILE ignores it ('PATTERN')"; "" when none does.
    The repository keeps such a file out of git on purpose: audibot's meshes, unpacked from
    meshes.tar.xz by its CMakeLists.txt (``*.dae``, ``*.stl``), K-Scale's robots, whose
    meshes their tools download (``*meshes*``). Decided as git decides (gitignore(5)): each
    folder from the repository's root down, then the file; for each, the deepest .gitignore
    with a pattern matching it, and in it the last such pattern, says whether it is ignored
    (a ``!`` pattern: not); a folder ignored ignores all below it, which no ``!`` pattern
    below takes back (git reads no .gitignore inside it). A .gitignore of more than
    :data:`MAX_IGNORE_PATTERNS` patterns is not matched (60,000 of them stopped a check of 5
    meshes at its budget): it may ignore the file, which is said so, never an error it cannot
    be certain of."""
    root = os.fspath(containment_root(Path(os.path.dirname(path))))
    parts = os.path.relpath(path, root).replace(os.sep, "/").split("/")
    if parts[0] in ("", ".", ".."):
        return ""
    for end in range(1, len(parts) + 1):  # each folder from the root's down, then the file
        folder = end < len(parts)
        for level in range(end - 1, -1, -1):  # the deepest .gitignore first
            name = os.path.join(root, *parts[:level], ".gitignore")
            patterns = _ignore_patterns(name)
            if patterns is None:
                return (f"the repository's {os.path.relpath(name, root)} holds more than "
                        f"{MAX_IGNORE_PATTERNS:,} patterns (not matched), any of which may "
                        "ignore it")
            entry = "/".join(parts[level:end])  # (relative to that .gitignore's folder)
            decided = next(((negated, text) for negated, pattern, folders_only, text in
                            reversed(patterns) if (folder or not folders_only)
                            and pattern.fullmatch(entry)), None)
            if decided is not None:
                break
        else:
            continue
        negated, text = decided
        if not negated:  # (the file, or a folder above it)
            return (f"the repository's {os.path.relpath(name, root)} ignores it "
                    f"('{shown_word(text)}')")
    return ""


MAX_IGNORE_PATTERNS = 5000  # [patterns] of one .gitignore matched (git's own has about 200)


@per_run
def _ignore_patterns(name: str) -> tuple | None:
    """(negated, regular expression, folders only, text) of each pattern of the .gitignore
    ``name``, in its order (none when it is no file), read once a run; None when it holds
    more than :data:`MAX_IGNORE_PATTERNS`. A symbolic link is none, as git (2.32 on) reads a
    .gitignore only without following one: a committed link to a file outside the
    repository was read, and its line that matched a mesh quoted."""
    if kind_of(name, follow=False) != "file":
        return ()
    try:
        text = read_regular(name, 1 << 20).decode("utf-8", "replace").removeprefix("\ufeff")
    except OSError:  # (git skips a UTF-8 byte order mark: its first pattern is a pattern)
        return ()
    if sum(1 for line in text.splitlines() if line.strip() and not line.startswith("#")) > \
            MAX_IGNORE_PATTERNS:
        return None
    found = []
    for line in text.splitlines():
        kept = line.rstrip(" ")  # trailing spaces, unless escaped (a pattern of them from each
        line = kept + " " if kept != line and kept.endswith("\\") else kept  # space: quadratic)
        if not line or line.startswith("#"):
            continue
        negated = line.startswith("!")
        body = line[1:] if negated else line
        folders_only = body.endswith("/")
        body = body.rstrip("/")
        if body:
            found.append((negated, _gitignore_pattern(body), folders_only, line))
    return tuple(found)


def _gitignore_pattern(body: str):
    """A matcher of what gitignore pattern ``body`` (no ``!``, no trailing ``/``) matches,
    for paths relative to its .gitignore's folder with ``/`` (its ``fullmatch``): without a
    ``/`` it matches a name at any depth; ``*``, ``?`` and ``[...]`` match within a name (as
    :func:`fnmatch.fnmatchcase` matches one, in time linear in its stars), ``**`` across
    folders; a leading ``\\`` escapes ``!`` or ``#``. Matched name by name: a regular
    expression of the whole pattern backtracked exponentially on ``*a*a*a*a*b``."""
    if body[:2] in ("\\!", "\\#"):
        body = body[1:]
    parts = tuple(body.removeprefix("/").split("/"))
    if "/" not in body:
        parts = ("**", *parts)
    return _GlobMatcher(tuple(part for i, part in enumerate(parts)
                              if part != "**" or i == 0 or parts[i - 1] != "**"))


class _GlobMatcher:
    """A gitignore pattern's names (``**`` for any folders), matched against a path."""

    __slots__ = ("parts",)

    def __init__(self, parts: tuple) -> None:
        self.parts = parts

    def fullmatch(self, path: str) -> bool:
        names, parts = path.split("/"), self.parts
        # the positions of the path each prefix of the pattern can end at (a set per step:
        # at most len(names) + 1 of them, so len(parts) * len(names) name tests at most)
        reached, last = {0}, len(parts) - 1
        for index, part in enumerate(parts):
            if part == "**":  # (a trailing one, after a name: "foo/**" holds one at least,
                # not foo itself, whose files a "!" pattern may then take back)
                trailing = index == last and index > 0
                reached = set(range(min(reached) + trailing, len(names) + 1))
            else:
                reached = {at + 1 for at in reached
                           if at < len(names) and fnmatch.fnmatchcase(names[at], part)}
            if not reached:
                return False
        return len(names) in reached


_PLACEHOLDERS = (".gitkeep", ".keep", ".gitignore", ".placeholder", ".empty")


def _kept_empty(folder: str) -> str:
    """The placeholder files a folder holds when they are all it holds (Stretch's
    ``stretch_description/meshes/.gitkeep``, filled from a robot's calibration batch by
    Hello Robot's tools), as a listing to quote; "" otherwise."""
    entries = listing(folder)
    if entries and all(kind == "file" and name in _PLACEHOLDERS for name, kind in entries):
        return ", ".join(name for name, _ in entries)
    return ""


@per_run
def _checked(uri: str, named: str, base: str, package: str | None,
             built: bool = False) -> Path | MeshProblem:
    """The path ``named`` for mesh ``uri`` with its links followed, when it stays in package
    ``package``'s folder ``base`` (or, for ``package`` None, in the containment root of the
    robot's folder ``base``) and is a file with a mesh extension; else the MeshProblem.
    ``built``: the package's build may put a file there (a file missing is "not found in the
    source tree"). Once per run: robots of one package name the same meshes."""
    path = real_path(named)  # (a string throughout, the Path made once, of the file found)
    if package is not None:
        folder = real_path(base)
        if not real_inside(path, folder):
            return MeshProblem("outside", f"mesh '{uri}' leaves package '{package}' "
                                          f"({folder}); name a file inside the package")
    else:
        # file:// and relative paths stay where the loader's files stay
        contained = os.fspath(containment_root(Path(base)))
        root = real_path(contained)
        if not real_inside(path, root):
            # as written, never where links lead: that would name what exists outside
            written = os.path.normpath(os.path.join(base, named))
            how = (f"is a symbolic link (or lies in one) leading outside {root}"
                   if written.startswith(contained + os.sep)
                   else f"is an absolute path, outside {root}"
                   if uri.removeprefix("file://") == written  # said once, not twice
                   else f"resolves to {written}, outside {root}")
            installed_at = _ROS_INSTALL.fullmatch(written)
            if installed_at:  # a ROS distribution's install: there wherever it is installed
                distro, package, tail = installed_at.groups()
                return MeshProblem("outside", (
                    f"mesh '{uri}' is in ROS {distro}'s install of '{package}' (outside the "
                    f"repository: not opened), there only where ROS {distro} and {package} are "
                    f"installed; write 'package://{package}/{tail}'"),
                    certain=False)
            return MeshProblem("outside", (
                f"mesh '{uri}' {how}; urdftool does not open files outside the robot's "
                f"repository: {_rooted_by_mistake(named, base) or _as_package_uri(written)}"))
    if kind_of(path) != "file":  # never raises (a name too long for the file system: '')
        # the place looked at, unless the URI already says it (a $(find) expanded by xacro)
        looked = "" if uri.removeprefix("file://") == path else f" (looked at {path})"
        why = no_file_there(path)
        if why.startswith("is "):  # something is there, not a mesh file: never opened
            return MeshProblem("corrupt", f"mesh '{uri}' {why}, not a file{looked}: not opened")
        found = ("not found in the source tree" if built else "not found") \
            if why == "does not exist" else why
        return MeshProblem("missing", f"mesh '{uri}' {found}{looked}")  # (advice: _doubted)
    suffix = _suffix(path)
    if suffix.lower() not in MESH_EXTENSIONS:
        return MeshProblem("format", (f"mesh '{uri}' has extension '{suffix}', not one of "
                                      f"{', '.join(MESH_EXTENSIONS)}; not opened"
                                      + _READ_BY.get(suffix.lower(), "")))
    return Path(path)


# who reads a mesh format urdftool does not open, as a message names them: a reader of the
# file's own simulator sees a warning about a file written for it, not a typo
_READ_BY = {".vtk": " (a VTK volume mesh: Drake reads it, for hydroelastic contact; "
                    "urdfdom's viewers and other simulators do not)",
            ".usd": " (USD: only Isaac Sim reads it)", ".usda": " (USD: only Isaac Sim reads it)",
            ".usdc": " (USD: only Isaac Sim reads it)"}


def _suffix(path: str) -> str:
    """``Path(path).suffix`` of a real path (absolute, normalised: its last part is its name),
    without making the Path: the name's last dot and what follows, '' for a name that starts
    with its only dot (``.stl``) or ends with it."""
    name = os.path.basename(path)  # (os.sep's last part: a Windows path's too)
    dot = name.rfind(".")
    return name[dot:] if 0 < dot < len(name) - 1 else ""


def _as_package_uri(written: str) -> str:
    """Advice for a mesh named by an absolute path outside the repository: the package:// URI
    of a path in a package's install space (``.../install/kortex_description/share/
    kortex_description/arms/...``, a colcon workspace on the machine the robot was exported
    from: Kinova's gen3_2f85.urdf), as loaders find it on any machine with the package; else
    how to name another package's file."""
    shared = _INSTALLED_SHARE.fullmatch(written)
    if shared is None:
        return "use package://PKG/... for files of another package"
    package, tail = shared.groups()
    return (f"it is in the install space of package '{package}' (share/{package}), there only "
            f"where that workspace is built; write 'package://{package}/{tail}'")


# a file of a package's install space: PREFIX/share/PACKAGE/FILE (colcon's, catkin's, ROS's)
_INSTALLED_SHARE = re.compile(r".*/share/([^/]+)/([^/].*)")


def _rooted_by_mistake(named: str, base: str) -> str:
    """Advice for an absolute path that, read without its leading '/', names a file beside the
    robot (an exporter's ``/meshes/base_link.stl`` for ``meshes/base_link.stl``: Blind-Us'
    Tancho_URDF, from StackForce SimReady), said instead of how to name another package's
    file (:func:`_as_package_uri`), which it is not; "" otherwise."""
    relative = named.lstrip("/")
    if named == relative or ".." in relative.split("/") or \
            kind_of(Path(base) / relative) != "file":
        return ""
    return (f"the leading '/' makes it absolute: '{relative}', relative to the robot's "
            "folder, is there")


def _windows_path(uri: str, named: str) -> str:
    """Advice for a mesh written with Windows separators (a Windows export's
    ``meshes\\part.stl``) when the file it means is there; "" otherwise, and never for a path
    leading up out of its folder."""
    if "\\" not in uri:
        return ""
    written, meant = uri.replace("\\", "/"), named.replace("\\", "/")
    if ".." in written.split("/") or kind_of(Path(meant)) != "file":
        return ""
    return ("; backslashes are no path separators on Linux, where a backslash is part of a "
            f"file name: write '{written}'")


# Every mesh extension in either case, and folders to enter: a listing's pattern
_MESH_GLOB = "*/|" + "|".join("*" + "".join(f"[{c.lower()}{c.upper()}]" if c.isalpha() else c
                                            for c in suffix) for suffix in MESH_EXTENSIONS)


def _elsewhere(path: Path, base: str) -> str:
    """Advice for a mesh missing where it is named: the one file of its name in other capitals
    beside it (``base.STL`` for ``base.stl``); or, when the folder it was looked for in holds
    no mesh at all (the folder is wrong, not the file: Inspire hand's URDF naming
    right_base_link.obj beside itself, the file moved to collision/), the repository's one file
    of its name, or in other capitals, elsewhere (of several, the one below the folder it was
    looked for in), or (none of its name) in another format; "" otherwise. Never a choice
    among several,
    nor a file of another folder when the mesh's own holds meshes: a repository of many robots
    has a base_link.STL for each, and another robot's is no advice."""
    root = _real(containment_root(Path(base)))
    meshes = _mesh_files(os.fspath(root))
    here = os.path.relpath(path.parent, root)
    paths = meshes.get(path.name.lower(), ())
    if here != "." and not here.startswith("..") and kind_of(path.parent) == "folder":
        # the folder's own subtree too, past the root's depth (allegro_hand_ros2's
        # description/urdf/meshes/palm.stl, six folders down: the one copy named was another)
        paths = tuple(dict.fromkeys(paths + tuple(
            os.path.join(here, p) for p in _mesh_files(os.fspath(path.parent)).get(
                path.name.lower(), ()))))
    beside = [p for p in paths if os.path.dirname(p) == here]
    if len(beside) == 1:
        return (f"; the file beside it is {os.path.basename(beside[0])}, in other capitals "
                "(file names are case-sensitive on Linux)")
    if here in _mesh_folders(os.fspath(root)):
        return ""
    same = [p for p in paths if os.path.basename(p) == path.name]
    below = [p for p in same if p.startswith(here + os.sep)]
    if len(same) > 1 and len(below) == 1:  # the one in the folder's own subtree, of several
        return (f"; of the repository's {len(same)} files of that name, the one below the "
                f"folder looked in is {os.path.relpath(below[0], here)} there")
    if len(same) == 1:
        return f"; the repository's one file of that name is {same[0]}"
    if not same and len(paths) == 1:
        return (f"; the repository's one file of that name in other capitals is {paths[0]} "
                "(file names are case-sensitive on Linux)")
    stem = path.stem.lower()  # Bolt's mesh_ext 'stl' where only meshes/obj/bolt_body.obj is
    other = [] if paths else [p for name, found in meshes.items()
                              if name.rsplit(".", 1)[0] == stem for p in found]
    if len(other) == 1:
        return f"; the repository's one mesh of that name is {other[0]}, in another format"
    return ""


@per_run
def _mesh_folders(root: str) -> frozenset[str]:
    """The folders of :func:`_mesh_files` holding a mesh, from ``root``."""
    return frozenset(os.path.dirname(p) for paths in _mesh_files(root).values() for p in paths)


@per_run
def _mesh_files(root: str) -> dict[str, tuple[str, ...]]:
    """The mesh files of the repository folder ``root`` (6 levels deep, 2,000 folders at
    most), by their name in lower case: their paths from ``root``. Once per run and
    repository, asked only when a mesh is missing."""
    found: dict[str, list[str]] = {}
    for folder, entries in walk(root, _MESH_GLOB, 6, most=2000):
        for name, kind in entries:
            if kind == "file":
                found.setdefault(name.lower(), []).append(
                    os.path.relpath(os.path.join(folder, name), root))
    return {name: tuple(paths) for name, paths in found.items()}


def _real(path: Path) -> Path:
    """``path`` with every symbolic link followed (once per run; a loop is left as it is, and
    is then no file)."""
    return Path(real_path(os.fspath(path)))
