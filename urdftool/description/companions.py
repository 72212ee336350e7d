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
requests. Each file is read (by :mod:`urdftool.description.documents`) and parsed once per
robot (kept in ``Robot.memo``).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from urdftool.description.documents import SrdfFile, YamlFile, read_srdf, read_yaml

SPEC_NAMES = ("joint_limits.yaml", "joint_spec.yaml")


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
        path = find_srdf(robot)
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


def find_srdf(robot) -> Path | None:
    """The robot's SRDF when none is given: in its folder or config/, named after the robot or
    the file's stem, else the only one there; never a link out of the folder; None for stdin.
    ``check`` and ``collisions`` both find it here."""
    paths = _candidates(_folders(robot), "*.srdf")
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


_CONTROLLER_KEYS = ("controller_manager", "controller_list", "controller_names",
                    "moveit_simple_controller_manager")


def looks_like_controllers(data, depth: int = 0) -> bool:
    """A controller configuration: ``type: pkg/Class`` in some mapping, a ``controller_manager``,
    or MoveIt's ``controller_list``/``controller_names``/``moveit_simple_controller_manager``."""
    if not isinstance(data, dict) or depth > 6:
        return False
    if any(key in data for key in _CONTROLLER_KEYS):
        return True
    kind = data.get("type")
    if isinstance(kind, str) and "/" in kind:
        return True
    return any(looks_like_controllers(value, depth + 1) for value in data.values())
