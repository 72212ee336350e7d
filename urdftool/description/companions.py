"""Files that describe a robot beside its URDF: controller YAML, SRDF and the joint spec table.

Which files (first match wins, per kind):

- controllers: every ``--controllers FILE``; else every ``config/*.yaml`` beside the robot and
  every ``*.yaml`` beside it that looks like a controller configuration (a mapping with a
  ``type: package/Class`` entry, or a ``controller_manager`` key).
- SRDF: ``--srdf FILE``; else the ``*.srdf`` beside the robot or in its ``config/`` folder whose
  name matches the robot name or the robot file name, or the only one there.
- spec: ``--spec FILE``; else ``joint_limits.yaml`` or ``joint_spec.yaml`` beside the robot or in
  its ``config/`` folder, when it is a urdftool spec (top-level ``unit:`` and ``joints:``; a ROS
  ``joint_limits.yaml`` has a top-level ``joint_limits:`` and is left alone) or is not valid YAML.

Files found automatically come only from the robot's folder and its ``config/`` subfolder, and
never through a symbolic link leading elsewhere: robot files may come from untrusted pull
requests. Each file is read and parsed once per robot (cached on the robot).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import yaml
from lxml import etree

from urdftool.diagnostics import Location, display_path
from urdftool.description.files import TooLarge, read_regular
from urdftool.description.xml import XmlProblem, start_tag_lines
from urdftool.description.yaml_limits import DepthLimit

MAX_SIZE = 16 * 1024 * 1024
SPEC_NAMES = ("joint_limits.yaml", "joint_spec.yaml")


# --- YAML that remembers where each key and item was written -------------------------------

class YamlMap(dict):
    """A YAML mapping; ``line`` is where it starts, ``lines[key]`` where each key is (1-based)."""

    line: int = 0
    lines: dict


class YamlList(list):
    """A YAML sequence; ``line`` is where it starts, ``lines[i]`` where each item is (1-based)."""

    line: int = 0
    lines: list


class _Loader(DepthLimit, yaml.SafeLoader):
    """SafeLoader keeping line numbers; unknown tags (``!degrees 90``) load as their plain value;
    nesting past yaml_limits.MAX_DEPTH is a YAML error at its line."""

    def construct_yaml_map(self, node):
        data = YamlMap()
        data.line, data.lines = node.start_mark.line + 1, {}
        yield data
        for key_node, value_node in node.value:
            key = self.construct_object(key_node, deep=True)
            try:
                hash(key)
            except TypeError:
                key = str(key)
            data[key] = self.construct_object(value_node, deep=True)
            data.lines[key] = key_node.start_mark.line + 1

    def construct_yaml_seq(self, node):
        data = YamlList()
        data.line = node.start_mark.line + 1
        data.lines = [item.start_mark.line + 1 for item in node.value]
        yield data
        data.extend(self.construct_object(item, deep=True) for item in node.value)

    def construct_unknown(self, suffix, node):
        if isinstance(node, yaml.ScalarNode):
            return self.construct_scalar(node)
        if isinstance(node, yaml.SequenceNode):
            return next(self.construct_yaml_seq(node))
        return next(self.construct_yaml_map(node))


_Loader.add_constructor("tag:yaml.org,2002:map", _Loader.construct_yaml_map)
_Loader.add_constructor("tag:yaml.org,2002:seq", _Loader.construct_yaml_seq)
_Loader.add_multi_constructor("!", _Loader.construct_unknown)


@dataclass
class CompanionFile:
    """A parsed companion: ``data`` (YAML: YamlMap/YamlList/scalar; SRDF: the ``<robot>``
    element), or None with ``problem`` at ``line``."""

    path: Path
    display: str
    data: object = None
    problem: str | None = None
    line: int | None = None

    @property
    def root(self):
        return self.data

    def at(self, line: int | None) -> Location:
        return Location(self.display, line)


YamlFile = SrdfFile = CompanionFile


def read_yaml(path: Path) -> YamlFile:
    """Parse one YAML file; a syntax error becomes ``problem`` at the line YAML reports."""
    result = YamlFile(path, display_path(path))
    text = _read_text(path, result)
    if text is None:
        return result
    try:
        result.data = yaml.load(text, Loader=_Loader)  # noqa: S506 - a SafeLoader subclass
    except yaml.MarkedYAMLError as error:
        mark = error.problem_mark or error.context_mark
        if error.context_mark is not None and (error.context or "").startswith("while parsing a flow"):
            mark = error.context_mark  # an unclosed bracket: point where it opened
        result.line = mark.line + 1 if mark else None
        result.problem = f"{error.problem or error}" + (f" ({error.context})" if error.context else "")
    except (yaml.YAMLError, RecursionError) as error:
        result.problem = f"not valid YAML: {error}"
    return result


def read_srdf(path: Path) -> SrdfFile:
    """Parse one SRDF; a syntax error becomes ``problem`` at its line."""
    result = SrdfFile(path, display_path(path))
    text = _read_text(path, result)
    if text is None:
        return result
    parser = etree.XMLParser(resolve_entities=False, no_network=True, huge_tree=False)
    try:
        result.data = etree.fromstring(text.encode(), parser)
    except etree.XMLSyntaxError as error:
        result.problem, result.line = f"not well-formed XML: {error.msg}", error.lineno
        return result
    _start_tag_lines(result.data, text)
    if result.data.tag != "robot":
        result.problem, result.line = (f"root element is <{result.data.tag}>, not <robot>",
                                       result.data.sourceline)
        result.data = None
    return result


def _start_tag_lines(root, text: str) -> None:
    """Give each element the line of its ``<`` (lxml keeps the line of the closing ``>``)."""
    elements = list(root.iter(etree.Element))
    try:
        lines = start_tag_lines(text.encode())
    except XmlProblem:  # libxml2 accepted what expat refuses (an entity): keep lxml's lines
        return
    if len(lines) == len(elements):
        for element, line in zip(elements, lines):
            element.sourceline = line


def _read_text(path: Path, result) -> str | None:
    """The file's text when it is a regular file of at most MAX_SIZE bytes; else None and
    ``result.problem`` says why (nothing is read from a FIFO or a device)."""
    try:
        return read_regular(path, MAX_SIZE).decode("utf-8")
    except TooLarge:
        result.problem = f"larger than {MAX_SIZE} bytes; not read"
    except OSError as error:
        result.problem = f"cannot be read: {error.strerror}"
    except UnicodeDecodeError as error:
        result.problem = f"cannot be read: {error}"
    return None


# --- discovery --------------------------------------------------------------------------------

@dataclass
class Companions:
    """The companion files of one robot, parsed."""

    controllers: list[YamlFile] = field(default_factory=list)
    srdf: SrdfFile | None = None
    spec: YamlFile | None = None


def companions(robot) -> Companions:
    """The robot's companion files, found and parsed on first use and then cached on it."""
    return robot.memo(companions, lambda: _discover(robot))


def _discover(robot) -> Companions:
    named = robot.companion_paths
    folders = _folders(robot)
    found = Companions()
    if named.controllers:
        found.controllers = [read_yaml(Path(p)) for p in named.controllers]
    else:
        found.controllers = _auto_controllers(folders)
    if named.srdf:
        found.srdf = read_srdf(Path(named.srdf))
    else:
        path = _auto_srdf(robot, folders)
        found.srdf = read_srdf(path) if path else None
    if named.spec:
        found.spec = read_yaml(Path(named.spec))
    else:
        found.spec = _auto_spec(folders)
    return found


def _folders(robot) -> list[Path]:
    """The robot's folder and its config/ subfolder; none for stdin."""
    if robot.path == "-":
        return []
    base = robot.base_dir
    return [base, base / "config"]


def _inside(path: Path, folders: list[Path]) -> bool:
    """``path`` is a regular file whose real location is in the robot's folder (no escaping links).

    Stricter on purpose than :func:`urdftool.description.packages.containment_root` (where files
    a robot names may be): a file nobody named is picked up only beside the robot or in config/."""
    try:
        real = path.resolve(strict=True)
        base = folders[0].resolve(strict=True)
    except OSError:
        return False
    return real.is_file() and (real.parent == base or real.parent == base / "config")


def _candidates(folders: list[Path], pattern: str) -> list[Path]:
    paths = []
    for folder in folders:
        if folder.is_dir() and not folder.is_symlink():
            paths.extend(p for p in sorted(folder.glob(pattern)) if _inside(p, folders))
    return paths


def _auto_controllers(folders: list[Path]) -> list[YamlFile]:
    files = []
    for path in _candidates(folders, "*.yaml"):
        if path.name in SPEC_NAMES:
            continue
        parsed = read_yaml(path)
        in_config = path.parent.name == "config"
        if looks_like_controllers(parsed.data) or (in_config and parsed.problem):
            files.append(parsed)
    return files


def _auto_srdf(robot, folders: list[Path]) -> Path | None:
    paths = _candidates(folders, "*.srdf")
    wanted = {robot.name, Path(robot.path).name.split(".")[0]}
    for path in paths:
        if path.name.split(".")[0] in wanted:
            return path
    return paths[0] if len(paths) == 1 else None


def _auto_spec(folders: list[Path]) -> YamlFile | None:
    for name in SPEC_NAMES:
        for path in _candidates(folders, name):
            parsed = read_yaml(path)
            if is_spec(parsed.data) or parsed.problem:  # a broken file is reported, not skipped
                return parsed
    return None


def is_spec(data) -> bool:
    """A urdftool joint spec: a mapping with top-level ``unit`` and ``joints`` keys."""
    return isinstance(data, dict) and "unit" in data and "joints" in data


def looks_like_controllers(data, depth: int = 0) -> bool:
    """A controller configuration: ``type: pkg/Class`` in some mapping, or ``controller_manager``."""
    if not isinstance(data, dict) or depth > 6:
        return False
    if "controller_manager" in data or "controller_list" in data:
        return True
    kind = data.get("type")
    if isinstance(kind, str) and "/" in kind:
        return True
    return any(looks_like_controllers(value, depth + 1) for value in data.values())
