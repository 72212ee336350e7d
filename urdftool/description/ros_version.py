"""Which ROS reads a robot, from what its files say: the one owner of that fact.

Evidence (:func:`ros_versions`), each with the reason it is shown with:

- the package.xml of the robot's package: ``catkin`` (ROS 1) or ``ament_cmake``/``ament_python``
  (ROS 2) as its build tool; a build tool under a ``condition=`` (a package built by both) says
  nothing; a rosbuild manifest.xml in its stead says ROS 1 (ROS 2 has no rosbuild);
- ``<ros2_control>`` in the URDF: ROS 2 (ros2_control reads it; ROS 1's ros_control does not);
- its controller YAML: ROS 2 with ``ros__parameters``, ROS 1 without (MoveIt's lists aside);
- Gazebo's ros_control plugin: ``libgazebo_ros_control.so`` is ROS 1's,
  ``libgazebo_ros2_control.so`` and the gz/ign_ros2_control systems ROS 2's;
- the launch files that describe it: XML with ``type=`` (ROS 1); Python, or ``exec=`` (ROS 2).

:func:`ros_version` is the one version all of it names, or None when it names both or none:
what depends on the version is then not certain.
"""

from __future__ import annotations

import re

from urdftool.description.packages import build_tools, manifest_said, package_of
from urdftool.diagnostics import display_path
from urdftool.records import Frozen



class Evidence(Frozen):
    """One reason to think ROS ``version`` reads the robot; ``kind`` is where it was read:
    'package', 'ros2_control', 'controllers', 'plugin' or 'launch'."""

    version: int
    why: str
    kind: str

    __slots__ = ("version", "why", "kind")

    def __init__(self, version: int, why: str, kind: str) -> None:
        set_field = object.__setattr__
        set_field(self, "version", version)
        set_field(self, "why", why)
        set_field(self, "kind", kind)


class Versions(Frozen):
    """The ROS versions that read the robot, and why each (``evidence``)."""

    versions: frozenset
    evidence: tuple

    __slots__ = ("versions", "evidence")

    def __init__(self, versions: frozenset, evidence: tuple) -> None:
        set_field = object.__setattr__
        set_field(self, "versions", versions)
        set_field(self, "evidence", evidence)

    @property
    def ros2_only(self) -> bool:
        return self.versions == frozenset({2})

    def why(self, version: int) -> str:
        """The evidence for ``version`` in words; of several launch files, the first two and
        how many more (PPI-PUT's A1 named its seven in each of six messages on its IMU)."""
        found = [e for e in self.evidence if e.version == version]
        launches = [e for e in found if e.kind == "launch"]
        if len(launches) > 2:
            found = [e for e in found if e.kind != "launch" or e in launches[:2]]
            found.append(Evidence(version, f"{len(launches) - 2} more launch files launch it",
                                  "launch"))
        return "; ".join(e.why for e in found)


def ros_versions(robot) -> Versions:
    """Every version the robot's files name, with the evidence; read once per robot."""
    return robot.memo(ros_versions, lambda: _versions(robot))


def ros_version(robot) -> tuple[int | None, str]:
    """(1 or 2, the evidence in words) when the evidence names one version, else (None, "")."""
    found = ros_versions(robot)
    if len(found.versions) != 1:
        return None, ""
    version = next(iter(found.versions))
    return version, found.why(version)


def _versions(robot) -> Versions:
    from urdftool.description.actuation import gazebo_plugins
    from urdftool.description.controllers import controller_files  # companions: not at import
    from urdftool.description.runtime import runtime

    evidence = [] if robot.path == "-" else list(package_evidence(robot.path))
    if robot.children("ros2_control"):
        evidence.append(Evidence(2, "the URDF has <ros2_control>", "ros2_control"))
    for read in controller_files(robot):
        if any(c.layout != "moveit" for c in read.controllers):
            version = 2 if read.file.ros2 else 1
            evidence.append(Evidence(version, f"{read.file.display} is a ROS {version} parameter "
                                              "file", "controllers"))
    for plugin in gazebo_plugins(robot):
        library = (plugin.get("filename") or "").strip()
        version = plugin_version(library)
        if version:
            evidence.append(Evidence(version, f"the URDF loads {library}", "plugin"))
    for configuration in runtime(robot).described:
        evidence.append(Evidence(configuration.top.ros, f"{configuration.named} launches it",
                                 "launch"))
    evidence = list(dict.fromkeys(evidence))
    return Versions(frozenset(e.version for e in evidence), tuple(evidence))


def nothing_says_ros(robot) -> str:
    """The condition "nothing says ROS runs this robot", as every message naming it says it
    (the one wording): what the robot's package is, in the words of
    :func:`~urdftool.description.packages.manifest_said` ("no package.xml or manifest.xml",
    or the package.xml there is, naming no ROS build tool: Drake's ``drake_models``; never
    "no package.xml" where there is one), then the evidence of running that is absent. Said
    where :func:`ros_versions` found none."""
    said = manifest_said(package_of(robot.path) if robot.path != "-" else None)
    package = f"{said}; " if said else ""
    return (f"nothing says ROS runs this robot: {package}no launch file, controller file or "
            "ros_control plugin")


def plugin_version(library: str) -> int | None:
    """The ROS version of a Gazebo ros_control plugin library (file name, with or without
    ``lib``/``.so`` and a folder), or None for any other plugin."""
    name = re.sub(r"^lib|\.so$", "", library.rsplit("/", 1)[-1])
    if name == "gazebo_ros_control":
        return 1
    return 2 if "ros2_control" in name else None


def package_evidence(path: str) -> tuple[Evidence, ...]:
    """What the build tool of the package.xml (or rosbuild manifest.xml) above ``path`` says
    (comments removed): nothing when a build tool is conditioned (a package built by both ROS
    versions)."""
    return tuple(Evidence(version, f"its package builds with {tool} ({display_path(manifest)})",
                          "package") for version, tool, manifest in build_tools(path))


def package_build_tool(path: str) -> tuple[int, str] | None:
    """(version, why) from the build tool of the package.xml above ``path``, when it names one
    version; else None."""
    found = package_evidence(path)
    return (found[0].version, found[0].why) if len(found) == 1 else None
