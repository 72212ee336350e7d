"""Which Gazebo plugin a ``<plugin>`` element loads, and the child elements it reads, per version.

The vocabularies are data (``urdftool/data/gazebo_plugins.json``), extracted from the plugins'
C++ sources by ``scripts/extract_gazebo_plugins.py``: gazebo_ros_pkgs for ROS 1 (noetic-devel)
and ROS 2 (ros2), gazebo_ros2_control and gz_ros2_control, and gz-sim's systems (Fortress,
Harmonic, Ionic), each with the repository, branch and commit read. This module names the
plugin an element loads, says what each version reads, and what the other version calls a
name (ROS 1's ``leftJoint`` is ROS 2's ``left_joint``). It judges nothing.
"""

from __future__ import annotations

import functools
import re

from urdftool.description import data
from urdftool.records import Frozen

CLASSIC, GZ = "classic", "gz"
_GZ_SYSTEM = re.compile(r"^(?:lib)?(?:gz-sim|ignition-gazebo|gz-sim-|ignition-gazebo-)\d*-(.+?)-system(?:\.so)?$")
_CAMEL = re.compile(r"(?<=[a-z0-9])([A-Z])")

# What ROS 2's gazebo_ros plugins read instead of a ROS 1 element that has no name of its own
# there (gazebo_ros_pkgs' ROS 2 migration guides): the namespace and topic names go under <ros>.
ROS2_INSTEAD = {"robotNamespace": "<ros><namespace>", "rosDebugLevel": "the --ros-args log level"}
_TOPIC = re.compile(r"(?:[tT]opic(?:Name)?)$")


# A value of the other version's element that asks for what this version's plugin does
# without its own: plugin key -> other version's name -> that value. ROS 1's camera utilities
# compute Cx, Cy and the focal length when given 0, and hackBaseline's default is 0
# (gazebo_ros_camera_utils.cpp, noetic-devel); ROS 2's gazebo_ros_camera computes cx, cy and
# the focal length when they are absent (or the focal length 0) and takes hack_baseline 0
# (gazebo_ros_camera.cpp, ros2). Written under the ROS 1 name on a ROS 2 robot, such a value
# is ignored and nothing changes; under the ROS 2 name, cx 0 would put the image's centre in
# its corner.
SAME_WITHOUT = {"gazebo_ros_camera": {"Cx": 0.0, "Cy": 0.0, "focalLength": 0.0,
                                      "hackBaseline": 0.0}}


def same_without(key: str, name: str, text: str | None) -> bool:
    """Whether ``text``, written under the other version's element ``name`` of plugin ``key``,
    asks for what this version's plugin does without the element (:data:`SAME_WITHOUT`)."""
    value = SAME_WITHOUT.get(key, {}).get(name)
    if value is None or text is None:
        return False
    try:
        return float(text.strip()) == value
    except ValueError:
        return False


class Plugin(Frozen):
    """The plugin a ``<plugin>`` element loads.

    key: its library (``gazebo_ros_diff_drive``) or gz-sim system (``gz-sim:diff-drive``)
    family: "classic" (Gazebo Classic) or "gz" (the new Gazebo)
    versions: version -> the element names it reads there ("ros1"/"ros2" for Gazebo Classic's
        ROS plugins; "fortress", "harmonic", "ionic" for gz-sim's systems, "ros2" for
        gz_ros2_control)
    hardware: the ros2_control hardware classes it can load (the *_ros2_control plugins)
    source: where the vocabularies were read
    """

    key: str
    family: str
    versions: dict
    hardware: tuple
    source: str

    __slots__ = ("key", "family", "versions", "hardware", "source")

    def __init__(self, key: str, family: str, versions: dict, hardware: tuple = (),
                 source: str = "") -> None:
        set_field = object.__setattr__
        set_field(self, "key", key)
        set_field(self, "family", family)
        set_field(self, "versions", versions)
        set_field(self, "hardware", hardware)
        set_field(self, "source", source)

    @property
    def names(self) -> set:
        """Every element name some version reads."""
        return set().union(*self.versions.values()) if self.versions else set()


def _data() -> dict:
    return data.load("gazebo_plugins.json")


@functools.lru_cache(maxsize=4096)
def plugin_key(filename: str) -> str | None:
    """The data's key of a ``<plugin filename>`` (``libgazebo_ros_diff_drive.so``,
    ``gz-sim-diff-drive-system``, ``libignition-gazebo6-diff-drive-system.so``), or None when
    it is no plugin the data knows. Once per process for each name, as :func:`plugin`."""
    name = filename.strip().rsplit("/", 1)[-1]
    system = _GZ_SYSTEM.match(name)
    if system:
        key = f"gz-sim:{system.group(1)}"
    else:
        key = re.sub(r"^lib", "", re.sub(r"\.so$", "", name))
    return key if key in _data()["plugins"] else None


def plugin(element) -> Plugin | None:
    """The plugin a ``<plugin>`` element loads, or None (a vendor's, or a misspelt one)."""
    key = plugin_key(element.get("filename") or "")
    return None if key is None else _plugin(key)


@functools.lru_cache(maxsize=None)  # (one a key of the data: a few hundred at most)
def _plugin(key: str) -> Plugin:
    """The :class:`Plugin` of the data's ``key``, made once per process (the rules ask of each
    ``<plugin>`` element, several times: 613 asks on the corpus; its versions' names made into
    sets, its sources into words, each time); read, never changed, by its callers."""
    entry = _data()["plugins"][key]
    sources = _data()["sources"]
    read = [r for version in entry["versions"].values() for r in version["read"]]
    source = "; ".join(f"{sources[r['source']]['repository']} {sources[r['source']]['ref']} "
                       f"({sources[r['source']]['commit'][:12]})" for r in read)
    return Plugin(key, entry["family"], {v: frozenset(e["tags"]) for v, e in entry["versions"].items()},
                  tuple(entry.get("hardware", ())), source)


def classic_counterpart(key: str) -> frozenset:
    """The names Gazebo Classic's plugin doing the job of gz-sim system ``key`` reads (its
    gazebo_ros_* namesake: ``gz-sim:diff-drive`` and ``gazebo_ros_diff_drive``), in any ROS."""
    name = "gazebo_ros_" + key.split(":", 1)[-1].replace("-", "_")
    entry = _data()["plugins"].get(name) if key.startswith("gz-sim:") else None
    return frozenset(tag for version in entry["versions"].values() for tag in version["tags"]) \
        if entry else frozenset()


def near(name: str, reads) -> str | None:
    """The name of ``reads`` that ``name`` is a slip of: the same but for case, or close (difflib
    0.8) with a close last word (``wheelSeperation``, ``distalostionK1``, ``xyzOffsets``; not
    ``odometry_rate`` for ``odometry_frame``)."""
    from urdftool.errors import close_names, similarity

    folded = {read.lower(): read for read in reads}
    if name.lower() in folded:
        return folded[name.lower()]
    for candidate in close_names(name, sorted(reads), n=3, cutoff=0.8):
        mine, theirs = _last_word(name), _last_word(candidate)
        if similarity(mine, theirs) >= 0.75:
            return candidate
    return None


def _last_word(name: str) -> str:
    return re.split(r"_", snake(name))[-1]


def control_plugins() -> dict[str, tuple[str, ...]]:
    """Key of each Gazebo plugin that loads ros2_control hardware -> the classes it loads."""
    return {key: tuple(entry["hardware"]) for key, entry in _data()["plugins"].items()
            if entry.get("hardware")}


def snake(name: str) -> str:
    """``wheelSeparation`` -> ``wheel_separation``."""
    return _CAMEL.sub(r"_\1", name).lower()


def camel(name: str) -> str:
    """``wheel_separation`` -> ``wheelSeparation``."""
    head, *rest = name.split("_")
    return head + "".join(part[:1].upper() + part[1:] for part in rest)


def counterpart(name: str, reads: set, to: str) -> str | None:
    """What a plugin reading ``reads`` (in version ``to``) calls the element ``name`` of the other
    version, or None when it has no counterpart: ``leftJoint`` -> ``left_joint`` (ROS 2),
    ``robotNamespace`` -> ``<ros><namespace>``, a topic name -> ``<ros><remapping>``."""
    for candidate in (snake(name), camel(name), name.lower()):
        if candidate in reads:
            return candidate
    folded = {read.lower(): read for read in reads}
    if name.lower() in folded:  # <cameraname> for <cameraName>
        return folded[name.lower()]
    if to == "ros2" and "ros" in reads:
        if name in ROS2_INSTEAD:
            return ROS2_INSTEAD[name]
        if _TOPIC.search(name):
            return "<ros><remapping>"
    return None
