"""Who reads a robot's file when urdfdom does not: the one owner of that fact.

urdfdom (check_urdf, robot_state_publisher, every ROS consumer) refuses shapes other readers of
URDF take. A file is another reader's (:func:`other_reader`) only when its files say so and
nothing says ROS runs it (:func:`~urdftool.description.ros_version.ros_versions`: a package.xml
building with catkin or ament, ``<ros2_control>``, a controller file, a ros_control plugin, a
launch file describing it):

- **drake**: its ``<robot>`` declares Drake's namespace (``xmlns:drake="http://drake.mit.edu"``)
  or it writes Drake's elements (``<drake:proximity_properties>``): Drake's parser reads it
  (RobotLocomotion/models, package ``drake_models``, whose package.xml names no build tool);
- **genesis**: it lies in the ``assets`` folder of the Genesis simulator's Python package
  (a folder ``genesis`` with its ``__init__.py`` and ``utils/urdf.py``, the loader that reads
  those assets with Genesis's fork of urdfpy), in Genesis or a copy of it (Genesis-arter):
  a ``<limit>`` without effort or velocity is 0 there, a missing bound unbounded, a link
  without ``<inertial>`` weighs its mesh's volume times the material's density (1 kg without a
  mesh), and ``package://`` is the file's own folder;
- **browser**: it lies in a web application's folder of files served as they are (``public``
  or ``static`` beside the application's ``package.json``), and a source file of that
  application names it there (mrover's web GUI, whose ``rover-model.ts`` fetches
  ``/urdf/rover/rover.urdf`` for three.js urdf-loader). The package.xml of a ROS package around
  the application says nothing of it (the application is a project of its own, its package
  manifest nearer the file); any other ROS evidence does.

None when nothing in the files says so: a file nobody is known to read is urdfdom's, as every
URDF is (docs/certainty.md).
"""

from __future__ import annotations

import os
import re
from pathlib import Path

from urdftool.description.files import kind_of, read_regular, walk
from urdftool.description.packages import containment_root
from urdftool.description.ros_version import nothing_says_ros, ros_versions
from urdftool.diagnostics import display_path
from urdftool.records import Frozen

__all__ = ["Reader", "other_reader", "DRAKE_NAMESPACE"]

DRAKE_NAMESPACE = "http://drake.mit.edu"
# A web application's folders of files served as they are, under its own root
# (Vite, Create React App, Vue CLI: public/; Svelte, Next's older form: static/)
SERVED = ("public", "static")
# The source files of a web application that may fetch a served file, and folders not its source
_SOURCES = "*.js|*.jsx|*.mjs|*.ts|*.tsx|*.vue|*.svelte|*/"
_NOT_SOURCE = frozenset({"node_modules", "dist", "build", *SERVED})
_MOST_FOLDERS = 2000  # (a web application's source tree; node_modules skipped)
_MAX_SOURCE = 1 << 20  # [bytes] a source file larger is not read (bundled output, not written)
# What says ROS runs a robot besides its package.xml (ros_version.Evidence.kind)
_RUN = frozenset({"ros2_control", "controllers", "plugin", "launch"})


class Reader(Frozen):
    """A reader of a robot's file other than urdfdom: ``kind`` 'drake', 'genesis' or 'browser', and
    ``why``: the evidence in words, as a finding's condition says it."""

    kind: str
    why: str

    __slots__ = ("kind", "why")

    def __init__(self, kind: str, why: str) -> None:
        set_field = object.__setattr__
        set_field(self, "kind", kind)
        set_field(self, "why", why)


def other_reader(robot) -> Reader | None:
    """The reader other than urdfdom that the robot's files say reads it, or None; decided
    once per robot."""
    return robot.memo(other_reader, lambda: _reader(robot))


def _reader(robot) -> Reader | None:
    if robot.path == "-":
        return None
    evidence = ros_versions(robot).evidence
    if not evidence:
        drake = _drake(robot)
        if drake:
            return Reader("drake", f"Drake reads it: {drake}; {nothing_says_ros(robot)}")
        genesis = _genesis(robot.path)
        if genesis:
            return Reader("genesis", f"Genesis reads it: {genesis}; {nothing_says_ros(robot)}")
    if any(e.kind in _RUN for e in evidence):
        return None
    served = _served(robot.path)
    if served is None:
        return None
    application, folder, source, name = served
    return Reader("browser", (
        f"a web page reads it: {display_path(folder)} holds the files the web application of "
        f"{display_path(os.path.join(application, 'package.json'))} serves as they are, and "
        f"{display_path(source)} fetches '{name}'; no launch file, controller file or "
        "ros_control plugin says ROS runs this robot"))


def _drake(robot) -> str | None:
    """Drake's mark in the robot's XML, in words, or None."""
    root = robot.root
    for prefix, uri in root.nsmap.items():
        if uri == DRAKE_NAMESPACE:
            return f"its <robot> declares xmlns:{prefix}=\"{DRAKE_NAMESPACE}\""
    marked = "{" + DRAKE_NAMESPACE + "}"
    for element in root.iter():
        if isinstance(element.tag, str) and element.tag.startswith(marked):
            return f"it writes <drake:{element.tag[len(marked):]}>"
    return None


def _genesis(path: str) -> str | None:
    """Where ``path`` lies in the Genesis simulator's assets, in words, or None: a folder
    ``assets`` (at any depth above the file) of a package folder ``genesis`` holding
    ``__init__.py`` and ``utils/urdf.py``, within the file's repository."""
    folder = os.path.dirname(os.path.abspath(path))
    root = os.path.abspath(containment_root(Path(folder)))
    while folder.startswith(root.rstrip(os.sep) + os.sep):
        package = os.path.dirname(folder)
        if os.path.basename(folder) == "assets" and os.path.basename(package) == "genesis" \
                and kind_of(os.path.join(package, "__init__.py")) == "file" \
                and kind_of(os.path.join(package, "utils", "urdf.py")) == "file":
            return (f"it lies in {display_path(folder)}, the assets of the Genesis package "
                    f"whose {display_path(os.path.join(package, 'utils', 'urdf.py'))} loads "
                    "them")
        folder = package
    return None


def _served(path: str) -> tuple[str, str, str, str] | None:
    """(the web application's root, its served folder holding ``path``, the source file naming
    ``path`` there, the name it uses) when ``path`` is a file a web application serves and its
    source fetches; else None."""
    path = os.path.abspath(path)
    folder = os.path.dirname(path)
    # (within the robot's repository: a package.json and sources above it are not its own)
    root = os.path.abspath(containment_root(Path(folder)))
    while True:
        parent = os.path.dirname(folder)
        if parent == folder or not (parent == root or parent.startswith(
                root.rstrip(os.sep) + os.sep)):
            return None
        if os.path.basename(folder) in SERVED and kind_of(os.path.join(parent, "package.json")) \
                == "file" and kind_of(os.path.join(parent, "package.xml")) != "file":
            name = "/" + os.path.relpath(path, folder).replace(os.sep, "/")
            source = _fetching(parent, name)
            return (parent, folder, source, name) if source else None
        if kind_of(os.path.join(folder, "package.xml")) == "file":
            return None  # (a ROS package nearer the file than any web application)
        folder = parent


def _fetching(application: str, name: str) -> str | None:
    """The first source file of the web application at ``application`` that names the served
    file ``name`` (``/urdf/rover/rover.urdf``, with or without its leading slash, as a string
    of its own), or None."""
    written = re.compile(rb"""["'`]\.?/?""" + re.escape(name.lstrip("/").encode()) + rb"""["'`]""")
    for folder, entries in walk(application, _SOURCES, 12, _NOT_SOURCE, most=_MOST_FOLDERS):
        for entry, kind in entries:
            if kind != "file":
                continue
            source = os.path.join(folder, entry)
            try:
                data = read_regular(source, _MAX_SOURCE, as_="web source")
            except OSError:
                continue
            if written.search(data):
                return source
    return None
