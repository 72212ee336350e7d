#!/usr/bin/env python3
"""Extract which child elements each Gazebo plugin reads, per ROS and Gazebo version.

A Gazebo plugin reads its parameters from the children of its ``<plugin>`` element, by name,
in C++ (``_sdf->Get<double>("wheel_separation")``, ``_sdf->HasElement("leftJoint")``, ROS 1's
``gazebo_ros_->getParameter<double>(wheel_separation_, "wheelSeparation", 0.34)``). This script
lists, for each plugin library a CMakeLists.txt builds, the element names its sources (and the
sources of the libraries of the same package it links) read, in:

- ros-simulation/gazebo_ros_pkgs: noetic-devel (ROS 1, Gazebo Classic: gazebo_plugins,
  gazebo_ros_control) and ros2 (ROS 2, Gazebo Classic: gazebo_plugins; every plugin that
  builds a gazebo_ros::Node reads ``<ros>``);
- ros-controls/gazebo_ros2_control (ROS 2, Gazebo Classic) and ros-controls/gz_ros2_control
  (ROS 2, new Gazebo);
- gazebosim/gz-sim (the new Gazebo's systems, Fortress to Ionic);

and writes ``urdftool/data/gazebo_plugins.json``: per plugin, per version, the names and where
they were read (repository, branch, commit, files). Only names are kept, no upstream text.
gazebo_ros_pkgs is BSD-3-Clause (and Apache-2.0 for ROS 2), gz-sim and the *_ros2_control
repositories Apache-2.0.

    python scripts/extract_gazebo_plugins.py --mirror /work/.mirror -o urdftool/data/gazebo_plugins.json

(``--tree LABEL=DIR`` reads a checked-out folder for one of the SOURCES labels instead, as
tests/scripts does with a fixture.)
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from extract_controller_parameters import DirTree, GitTree, dump  # noqa: E402

# label -> (repository, branch, family, version, packages read)
SOURCES = {
    "gazebo_ros_pkgs@noetic-devel": ("ros-simulation/gazebo_ros_pkgs", "noetic-devel", "classic", "ros1",
                                     ("gazebo_plugins", "gazebo_ros_control")),
    "gazebo_ros_pkgs@ros2": ("ros-simulation/gazebo_ros_pkgs", "ros2", "classic", "ros2", ("gazebo_plugins",)),
    "gazebo_ros2_control@humble": ("ros-controls/gazebo_ros2_control", "humble", "classic", "ros2",
                                   ("gazebo_ros2_control",)),
    "gazebo_ros2_control@master": ("ros-controls/gazebo_ros2_control", "master", "classic", "ros2",
                                   ("gazebo_ros2_control",)),
    "gz_ros2_control@humble": ("ros-controls/gz_ros2_control", "humble", "gz", "ros2",
                               ("ign_ros2_control", "gz_ros2_control")),
    "gz_ros2_control@jazzy": ("ros-controls/gz_ros2_control", "jazzy", "gz", "ros2", ("gz_ros2_control",)),
    "gz_ros2_control@rolling": ("ros-controls/gz_ros2_control", "rolling", "gz", "ros2", ("gz_ros2_control",)),
    "gz-sim@ign-gazebo6": ("gazebosim/gz-sim", "ign-gazebo6", "gz", "fortress", ("src/systems",)),
    "gz-sim@gz-sim8": ("gazebosim/gz-sim", "gz-sim8", "gz", "harmonic", ("src/systems",)),
    "gz-sim@gz-sim9": ("gazebosim/gz-sim", "gz-sim9", "gz", "ionic", ("src/systems",)),
}
LICENCES = {"ros-simulation/gazebo_ros_pkgs": "BSD-3-Clause (ROS 1), Apache-2.0 (ROS 2)",
            "ros-controls/gazebo_ros2_control": "Apache-2.0", "ros-controls/gz_ros2_control": "Apache-2.0",
            "gazebosim/gz-sim": "Apache-2.0"}

_READS = re.compile(
    r'(?:HasElement|GetElement|GetNextElement|FindElement|GetElementImpl|Get\s*<[^<>()]*>)\s*\(\s*"(\w+)"'
    r'|(?:getParameter(?:<[^<>()]*>)?|getParameterBoolean|getJoint)\s*\(\s*[^,()]+,\s*"(\w+)"')
# Calls into gazebo_ros (ROS 2) that read elements of the plugin's SDF for it: gazebo_ros's
# node.cpp reads <ros> (namespace, remapping, parameter, argument, qos), utils.cpp's
# SensorFrameID <frame_name>.
HELPERS = {
    re.compile(r"gazebo_ros::Node::Get\s*\(\s*_?sdf"): ("ros", "namespace", "remapping", "parameter",
                                                       "argument", "qos"),
    re.compile(r"SensorFrameID\s*\("): ("frame_name",),
}
_LIBRARY = re.compile(r"add_library\(\s*([\w${}-]+)\s+((?:SHARED|MODULE|STATIC)\s+)?([^)]*)\)")
_LINKS = re.compile(r"target_link_libraries\(\s*([\w${}-]+)\s+([^)]*)\)")
_SYSTEM = re.compile(r"(?:gz|ign)_add_system\(\s*([\w-]+)\s+SOURCES\s+([^)]*?)(?:PUBLIC_LINK_LIBS|PRIVATE_LINK_LIBS|\))",
                     re.S)
_PLUGIN_CLASS = re.compile(r"(?:GZ|IGNITION)_ADD_PLUGIN\(\s*([\w:]+)")


def tags_read(text: str) -> set[str]:
    """The element names a C++ source reads from its plugin's SDF."""
    found = {a or b for a, b in _READS.findall(text)}
    for call, names in HELPERS.items():
        if call.search(text):
            found.update(names)
    return found


_INCLUDE = re.compile(r'#include\s*[<"]([\w./]+)[>"]')


def _read_with_includes(tree, paths) -> set[str]:
    """The element names ``paths`` read, with the headers of the tree they include (ROS 1's
    GazeboRos helper reads <robotNamespace> in gazebo_ros_utils.h)."""
    headers = getattr(tree, "_headers", None)
    if headers is None:
        headers = tree._headers = {}
        for path in tree.files():
            if "/include/" in path:
                headers.setdefault(path.split("/include/", 1)[1], path)
    tags, todo, seen = set(), list(paths), set()
    while todo:
        path = todo.pop()
        if path in seen or path not in tree.files():
            continue
        seen.add(path)
        text = tree.read(path)
        tags |= tags_read(text)
        todo += [headers[included] for included in _INCLUDE.findall(text) if included in headers]
    return tags


def _cmake_libraries(tree, package: str) -> dict[str, dict]:
    """Library name -> {"sources": [...], "links": [...]} of a package's CMakeLists.txt."""
    path = f"{package}/CMakeLists.txt"
    if path not in tree.files():
        return {}
    text = re.sub(r"#[^\n]*", "", tree.read(path))
    project = re.search(r"project\(\s*(\w+)", text)
    if project:
        text = text.replace("${PROJECT_NAME}", project.group(1))
    libraries = {}
    for name, _, body in _LIBRARY.findall(text):
        sources = [f"{package}/{token}" for token in body.split() if token.endswith((".cpp", ".cc"))]
        if sources:
            libraries.setdefault(name, {"sources": [], "links": []})["sources"] += sources
    for name, body in _LINKS.findall(text):
        if name in libraries:
            libraries[name]["links"] += body.split()
    return libraries


def classic_plugins(tree, packages) -> dict[str, dict]:
    """Library -> {"tags", "paths"} for the libraries of ``packages`` (linked ones included)."""
    libraries = {}
    for package in packages:
        libraries.update(_cmake_libraries(tree, package))
    found = {}
    for name, library in libraries.items():
        paths, todo, seen = [], [name], set()
        while todo:
            current = todo.pop()
            if current in seen or current not in libraries:
                continue
            seen.add(current)
            paths += libraries[current]["sources"]
            todo += libraries[current]["links"]
        tags = _read_with_includes(tree, paths)
        if tags:
            found[name] = {"tags": sorted(tags), "paths": sorted(set(paths))}
    return found


def gz_systems(tree, root: str) -> dict[str, dict]:
    """``gz-sim:NAME`` -> {"tags", "paths", "classes"} of the systems under ``root``."""
    found = {}
    for path in tree.files():
        if not (path.startswith(f"{root}/") and path.endswith("/CMakeLists.txt")):
            continue
        folder = path.rsplit("/", 1)[0]
        for name, body in _SYSTEM.findall(tree.read(path)):
            paths = [f"{folder}/{token}" for token in body.split() if token.endswith((".cc", ".cpp"))]
            tags = _read_with_includes(tree, paths)
            classes = {c.split("::")[-1] for source in paths if source in tree.files()
                       for c in _PLUGIN_CLASS.findall(tree.read(source))}
            if tags:
                found[f"gz-sim:{name}"] = {"tags": sorted(tags), "paths": sorted(paths),
                                           "classes": sorted(classes)}
    return found


_HARDWARE_CLASS = re.compile(r'<class\s+name="([^"]+)"')


def hardware_classes(tree, package: str) -> list[str]:
    """The ros2_control hardware classes a *_ros2_control package exports (its plugin XML):
    what its Gazebo plugin can load from <ros2_control><hardware><plugin>."""
    return sorted({name for path in tree.files() if path.startswith(f"{package}/")
                   and path.endswith("hardware_plugins.xml")
                   for name in _HARDWARE_CLASS.findall(tree.read(path))})


def extract(trees: dict) -> dict:
    """The data file's content from ``{label: tree}`` (labels of SOURCES)."""
    data = {
        "about": ("Child elements each Gazebo plugin reads, per ROS and Gazebo version, generated "
                  "by scripts/extract_gazebo_plugins.py: do not edit."),
        "licence": {"notice": "Element names read from the C++ sources of the repositories under "
                              "'sources', Copyright their authors, under the licences listed there.",
                    "licences": LICENCES},
        "sources": {},
        "plugins": {},
    }
    for label, tree in trees.items():
        repository, ref, family, version, packages = SOURCES[label]
        data["sources"][label] = {"repository": repository, "ref": tree.ref, "commit": tree.commit}
        for package in packages:
            found = (gz_systems(tree, package) if package == "src/systems"
                     else classic_plugins(tree, [package]))
            for name, entry in found.items():
                plugin = data["plugins"].setdefault(name, {"family": family, "versions": {}})
                versions = plugin["versions"].setdefault(version, {"tags": [], "read": []})
                versions["tags"] = sorted(set(versions["tags"]) | set(entry["tags"]))
                versions["read"].append({"source": label, "paths": entry["paths"]})
                if entry.get("classes"):
                    plugin["classes"] = sorted(set(plugin.get("classes", [])) | set(entry["classes"]))
                hardware = hardware_classes(tree, package) if package.endswith("_ros2_control") else []
                if hardware:
                    plugin["hardware"] = sorted(set(plugin.get("hardware", [])) | set(hardware))
    data["plugins"] = dict(sorted(data["plugins"].items()))
    return data


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mirror", type=Path, help="folder of bare git dirs, owner+name/repo")
    parser.add_argument("--tree", action="append", default=[], metavar="LABEL=DIR")
    parser.add_argument("-o", "--output", type=Path, required=True)
    args = parser.parse_args(argv)
    if args.tree:
        trees = {label: DirTree(Path(path), SOURCES[label][1]) for label, path in
                 (pair.split("=", 1) for pair in args.tree)}
    else:
        trees = {}
        for label, (repository, ref, *_) in SOURCES.items():
            git_dir = args.mirror / repository.replace("/", "+") / "repo"
            try:
                trees[label] = GitTree(git_dir, ref)
            except subprocess.CalledProcessError:
                print(f"no {ref} in {git_dir}; {label} skipped", file=sys.stderr)
    args.output.write_text(dump(extract(trees), expand=("plugins",)), encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
