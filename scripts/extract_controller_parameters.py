#!/usr/bin/env python3
"""Extract the parameters of ros2_controllers' controllers into urdftool's data file.

ros2_controllers declares each controller's parameters in a YAML file read by
generate_parameter_library (type, default, validation, read-only). This script reads, for each
ROS 2 distribution (a branch of the repository):

- the controller classes each package exports (its pluginlib XML: ``<class name="pkg/Class"
  type="pkg::Class" base_class_type="controller_interface::...">``);
- the parameter files each class reads: the generate_parameter_library targets of the
  package's CMakeLists.txt whose header the class's header includes, directly or through the
  headers it includes (a steering controller reads steering_controllers_library's too);
- the parameters every controller has (ros2_control's ``controller_interface_base.cpp``:
  ``auto_declare<int>("update_rate", ...)``) and the controller manager's own
  (``controller_manager_parameters.yaml`` where it exists, else the facts listed below);

and writes ``urdftool/data/ros2_controllers.json``: per class and distribution, the
parameters by dotted name (``constraints.goal_time``; ``__map_joints`` for a key per joint),
each with its type, default (absent: none), read_only and validation, and where each fact was
read (repository, path, branch, commit). ros2_controllers and ros2_control are Apache-2.0; the
notice is kept in the data file. Only facts are kept, no upstream text (descriptions are
dropped).

Run once, when a distribution changes, and commit the data::

    python scripts/extract_controller_parameters.py \\
        --ros2-controllers /path/to/ros2_controllers.git --ros2-control /path/to/ros2_control.git \\
        -o urdftool/data/ros2_controllers.json

(bare git directories, such as ``git clone --mirror``; or ``--tree DISTRO=DIR`` and
``--control-tree DISTRO=DIR`` for checked-out folders, which tests/scripts uses with a small
fixture.)
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
from pathlib import Path

import yaml

# ROS 2 distribution -> branch of both repositories ("rolling" is their master).
DISTRIBUTIONS = {"foxy": "foxy", "galactic": "galactic", "humble": "humble", "iron": "iron",
                 "jazzy": "jazzy", "kilted": "kilted", "rolling": "master"}
CONTROLLERS_REPO = "ros-controls/ros2_controllers"
CONTROL_REPO = "ros-controls/ros2_control"
LICENCE = {
    "spdx": "Apache-2.0",
    "notice": ("Facts (parameter names, types, defaults, validations, class names) extracted from "
               "ros-controls/ros2_controllers and ros-controls/ros2_control, Copyright their "
               "authors, licensed under the Apache License, Version 2.0 "
               "(http://www.apache.org/licenses/LICENSE-2.0). Extracted by "
               "scripts/extract_controller_parameters.py; the paths and commits of the files "
               "read are listed under 'sources' and in each entry."),
}
BASES = ("controller_interface::ControllerInterface", "controller_interface::ChainableControllerInterface")
# What the controller manager reads where it has no parameter file (humble, iron): checked against
# the source by the script (the line must be there), so a moved fact fails the extraction.
MANAGER_FACTS = {
    "update_rate": ("int", r'get_parameter\("update_rate", *\w+\)'),
}
MANAGER_SOURCES = "controller_manager/src/"


class GitTree:
    """The files of one ref of a bare git repository."""

    def __init__(self, git_dir: Path, ref: str):
        self.git_dir, self.ref = Path(git_dir), ref
        self.commit = self._git("rev-parse", f"{ref}^{{commit}}").strip()
        listed = self._git("ls-tree", "-r", "--name-only", self.commit)
        self._files = [line for line in listed.splitlines() if line]

    def _git(self, *args) -> str:
        return subprocess.run(["git", f"--git-dir={self.git_dir}", *args], check=True,
                              capture_output=True, text=True).stdout

    def files(self) -> list[str]:
        return self._files

    def read(self, path: str) -> str:
        return self._git("show", f"{self.commit}:{path}")


class DirTree:
    """The files of a folder (a checkout, or a test fixture); ``commit`` is given."""

    def __init__(self, root: Path, ref: str, commit: str = "fixture"):
        self.root, self.ref, self.commit = Path(root), ref, commit
        self._files = sorted(p.relative_to(self.root).as_posix() for p in self.root.rglob("*")
                             if p.is_file())

    def files(self) -> list[str]:
        return self._files

    def read(self, path: str) -> str:
        return (self.root / path).read_text(encoding="utf-8")


# --- generate_parameter_library files ----------------------------------------------------

def _validation(spec) -> dict:
    """{validator: [arguments]}: ``gt_eq<>: [0.1]`` and ``gt_eq: 0.1`` alike; a project's own
    validator (``pkg::function``) is kept under its name."""
    found = {}
    for key, value in (spec or {}).items():
        name = str(key).removesuffix("<>")
        found[name] = [] if value is None else list(value) if isinstance(value, list) else [value]
    return found


def _json_value(value):
    """A default as JSON holds it: infinities as the strings "inf"/"-inf"."""
    if isinstance(value, float) and value in (float("inf"), float("-inf")):
        return "inf" if value > 0 else "-inf"
    if isinstance(value, list):
        return [_json_value(v) for v in value]
    return value


def _is_parameter(value) -> bool:
    return isinstance(value, dict) and isinstance(value.get("type"), str) and (
        "default_value" in value or "description" in value or "validation" in value
        or "read_only" in value or len(value) == 1)


def gpl_parameters(text: str) -> dict:
    """Parameter name (dotted) -> facts, of one generate_parameter_library file."""
    data = yaml.safe_load(text) or {}
    found = {}

    def walk(node, prefix):
        for key, value in node.items():
            name = f"{prefix}{key}"
            if _is_parameter(value):
                entry = {"type": value["type"]}
                if "default_value" in value:
                    entry["default"] = _json_value(value["default_value"])
                if value.get("read_only"):
                    entry["read_only"] = True
                if value.get("validation"):
                    entry["validation"] = _validation(value["validation"])
                found[name] = entry
            elif isinstance(value, dict):
                walk(value, f"{name}.")

    for top in data.values():  # one top key: the name of the generated struct
        if isinstance(top, dict):
            walk(top, "")
    return found


_GPL = re.compile(r"generate_parameter_library\(\s*([\w${}]+)\s+([\w./${}-]+)")


def gpl_targets(tree, package: str) -> dict[str, str]:
    """Header path (``pkg/name.hpp``) -> parameter file, from the package's CMakeLists.txt."""
    path = f"{package}/CMakeLists.txt"
    if path not in tree.files():
        return {}
    text = tree.read(path)
    project = re.search(r"project\(\s*(\w+)", text)
    targets = {}
    for name, yaml_path in _GPL.findall(text):
        if project:
            name = name.replace("${PROJECT_NAME}", project.group(1))
            yaml_path = yaml_path.replace("${PROJECT_NAME}", project.group(1))
        targets[f"{package}/{name}.hpp"] = f"{package}/{yaml_path}"
    return targets


# --- classes and the parameter files each reads ------------------------------------------

_CLASS = re.compile(r"<class\b([^>]*)>", re.S)
_ATTRIBUTE = re.compile(r'(\w+)\s*=\s*"([^"]*)"')
_INCLUDE = re.compile(r'#include\s*[<"]([\w./]+)[>"]')


def plugin_classes(tree) -> list[tuple[str, str, str]]:
    """(name, C++ type, package) of every controller class the plugin XML files export."""
    found = []
    for path in tree.files():
        if not path.endswith(".xml") or "/test/" in path or path.count("/") != 1:
            continue
        text = tree.read(path)
        for match in _CLASS.finditer(text):
            attributes = dict(_ATTRIBUTE.findall(match.group(1)))
            if attributes.get("base_class_type") in BASES and attributes.get("type"):
                name = attributes.get("name") or attributes["type"].replace("::", "/")
                found.append((name, attributes["type"], path.split("/")[0]))
    return found


def _declaring_header(tree, package: str, cxx_type: str) -> str | None:
    """The header of ``package`` that declares the class (or the alias) ``cxx_type``."""
    short = cxx_type.split("::")[-1]
    declared = re.compile(rf"(?:class|struct)\s+(?:\w+\s+)?{short}\b[^;]*?\{{|using\s+{short}\s*=|"
                          rf"typedef\b[^;]*\b{short}\s*;", re.S)
    for path in tree.files():
        if path.startswith(f"{package}/include/") and path.endswith((".hpp", ".h")):
            if declared.search(tree.read(path)):
                return path
    return None


def parameter_files(tree, package: str, cxx_type: str, targets: dict[str, str]) -> list[str]:
    """The parameter files the class reads: the generated headers its header includes,
    following the includes that are headers of this repository."""
    start = _declaring_header(tree, package, cxx_type)
    if start is None:
        return []
    files, seen, todo = [], set(), [start]
    present = set(tree.files())
    while todo:
        path = todo.pop()
        if path in seen:
            continue
        seen.add(path)
        for included in _INCLUDE.findall(tree.read(path)):
            if "/" not in included:  # "name_parameters.hpp": the including package's own
                included = f"{path.split('/')[0]}/{included}"
            if included in targets and targets[included] not in files:
                files.append(targets[included])
            owner = included.split("/")[0]
            local = f"{owner}/include/{included}"
            if local in present:
                todo.append(local)
    return sorted(files)


# --- ros2_control: what every controller and the controller manager read ------------------

_AUTO_DECLARE = re.compile(r'auto_declare<(\w+)>\(\s*"(\w+)"\s*,\s*([^;]*?)\);')
_CXX_TYPES = {"int": "int", "bool": "bool", "double": "double", "std::string": "string"}


def base_parameters(tree) -> dict:
    """The parameters ControllerInterfaceBase declares for every controller."""
    path = "controller_interface/src/controller_interface_base.cpp"
    if path not in tree.files():
        return {}
    found = {}
    for cxx, name, default in _AUTO_DECLARE.findall(tree.read(path)):
        entry = {"type": _CXX_TYPES.get(cxx, cxx)}
        literal = default.strip()
        entry["default"] = (int(literal) if re.fullmatch(r"-?\d+", literal)
                            else literal == "true" if literal in ("true", "false")
                            else None)  # an expression: it has a default, not a literal one
        found[name] = entry
    return {"path": path, "parameters": found} if found else {}


def manager_parameters(tree) -> dict:
    """The controller manager's parameters: its parameter file, or :data:`MANAGER_FACTS`
    (each found in the source, or the extraction fails)."""
    path = "controller_manager/src/controller_manager_parameters.yaml"
    if path in tree.files():
        return {"path": path, "parameters": gpl_parameters(tree.read(path))}
    found, where = {}, None
    sources = [p for p in tree.files() if p.startswith(MANAGER_SOURCES) and p.endswith(".cpp")]
    for name, (kind, evidence) in MANAGER_FACTS.items():
        where = next((p for p in sources if re.search(evidence, tree.read(p))), None)
        if where is None:
            raise SystemExit(f"{tree.ref}: no {evidence} in {MANAGER_SOURCES}: update MANAGER_FACTS")
        found[name] = {"type": kind}
    return {"path": where, "parameters": found}


# --- the data file -----------------------------------------------------------------------

def extract(controllers: dict, control: dict) -> dict:
    """The data file's content from ``{distro: tree}`` of ros2_controllers and of ros2_control."""
    data = {
        "about": ("Parameters of ros2_controllers' controllers per ROS 2 distribution, generated "
                  "by scripts/extract_controller_parameters.py: do not edit."),
        "licence": LICENCE,
        "sources": {
            "ros2_controllers": {"repository": CONTROLLERS_REPO, "licence": "Apache-2.0",
                                 "refs": {d: {"ref": t.ref, "commit": t.commit}
                                          for d, t in controllers.items()}},
            "ros2_control": {"repository": CONTROL_REPO, "licence": "Apache-2.0",
                             "refs": {d: {"ref": t.ref, "commit": t.commit}
                                      for d, t in control.items()}},
        },
        "distributions": list(controllers),
        "classes": {},
        "schemas": {},
        "controller": {},
        "controller_manager": {},
    }
    by_content: dict[tuple, str] = {}

    def schema(distro, tree, path, parameters, source):
        key = (source, path, json.dumps(parameters, sort_keys=True))
        if key not in by_content:
            ident = f"{path}@{distro}"
            by_content[key] = ident
            data["schemas"][ident] = {"source": source, "path": path, "distributions": [],
                                      "parameters": parameters}
        ident = by_content[key]
        if distro not in data["schemas"][ident]["distributions"]:
            data["schemas"][ident]["distributions"].append(distro)
        return ident

    for distro, tree in controllers.items():
        targets: dict[str, str] = {}
        parsed: dict[str, dict] = {}
        for name, cxx_type, package in sorted(plugin_classes(tree)):
            if package not in targets:
                targets.update(gpl_targets(tree, package))
            idents = []
            for path in parameter_files(tree, package, cxx_type, _all_targets(tree, targets)):
                if path not in parsed:
                    parsed[path] = gpl_parameters(tree.read(path))
                idents.append(schema(distro, tree, path, parsed[path], "ros2_controllers"))
            data["classes"].setdefault(name, {})[distro] = idents
    for distro, tree in control.items():
        for key, read in (("controller", base_parameters), ("controller_manager", manager_parameters)):
            found = read(tree)
            if found:
                data[key][distro] = schema(distro, tree, found["path"], found["parameters"],
                                           "ros2_control")
    data["classes"] = dict(sorted(data["classes"].items()))
    return data


def _all_targets(tree, known: dict) -> dict:
    """Every package's generated headers (a class may include another package's), read once."""
    if not getattr(tree, "_targets", None):
        packages = {path.split("/")[0] for path in tree.files() if path.endswith("/CMakeLists.txt")
                    and path.count("/") == 1}
        tree._targets = {k: v for p in sorted(packages) for k, v in gpl_targets(tree, p).items()}
    return {**tree._targets, **known}


def dump(data: dict, expand=("classes", "schemas", "parameters")) -> str:
    """The file's text: one line per class, schema and parameter (the mappings under the keys
    ``expand`` names), so that a diff between two extractions reads fact by fact."""
    def render(value, indent: int, key=None) -> str:
        if isinstance(value, dict) and value and (key is None or key in expand):
            pad = " " * (indent + 2)
            items = [f"{pad}{json.dumps(k)}: {render(v, indent + 2, k)}" for k, v in value.items()]
            return "{\n" + ",\n".join(items) + "\n" + " " * indent + "}"
        if isinstance(value, dict) and any(k in expand for k in value):
            return "{" + ", ".join(f"{json.dumps(k)}: {render(v, indent, k)}" for k, v in value.items()) + "}"
        return json.dumps(value, sort_keys=True)

    return render(data, 0) + "\n"


def _trees(pairs, cls, git_dir):
    if pairs:
        return {d: DirTree(Path(p), d) for d, p in (pair.split("=", 1) for pair in pairs)}
    trees = {}
    for distro, ref in DISTRIBUTIONS.items():
        try:
            trees[distro] = cls(git_dir, ref)
        except subprocess.CalledProcessError:
            print(f"no {ref} in {git_dir}; {distro} skipped", file=sys.stderr)
    return trees


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ros2-controllers", type=Path, help="bare git dir of ros2_controllers")
    parser.add_argument("--ros2-control", type=Path, help="bare git dir of ros2_control")
    parser.add_argument("--tree", action="append", default=[], metavar="DISTRO=DIR")
    parser.add_argument("--control-tree", action="append", default=[], metavar="DISTRO=DIR")
    parser.add_argument("-o", "--output", type=Path, required=True)
    args = parser.parse_args(argv)
    controllers = _trees(args.tree, GitTree, args.ros2_controllers)
    control = _trees(args.control_tree, GitTree, args.ros2_control)
    args.output.write_text(dump(extract(controllers, control)), encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
