"""U640-U643: Gazebo plugins against what each version of each plugin reads.

What a plugin reads is data extracted from its C++ sources, per ROS and Gazebo version (see
:mod:`urdftool.description.gazebo_plugins`); which ROS a robot is written for is read from its
files (:mod:`urdftool.description.ros_version`).
"""

from __future__ import annotations

from pathlib import Path

from urdftool.description import gazebo_plugins as vocabulary
from urdftool.description.actuation import gazebo_plugins, transmissions
from urdftool.description.controllers import controllers
from urdftool.description.ros_version import ros_version
from urdftool.errors import available
from urdftool.lint.catalogue import Said, Severity, rule

_ROS = {"ros1": "ROS 1", "ros2": "ROS 2"}


def _children(element):
    return [child for child in element if isinstance(child.tag, str)]


def _label(element, found) -> str:
    return f"plugin '{element.get('name') or element.get('filename')}' ({found.key})"


@rule("U640", "gazebo-plugin-other-version", Severity.ERROR)
def gazebo_plugin_other_version(robot):
    """A Gazebo plugin's parameter is named as the other ROS version's plugin names it.

    gazebo_ros_pkgs renamed its plugins' parameters for ROS 2 (the diff drive's ``leftJoint``
    is ``left_joint``, ``wheelSeparation`` ``wheel_separation``; the camera's ``cameraName``
    ``camera_name``; ``robotNamespace`` and the topic names went under ``<ros>``); a plugin
    reads its own version's names only and ignores the others: a wheel joint left unnamed,
    the default used instead of the value written. Each version's names are read from the
    plugin sources (gazebo_ros_pkgs noetic-devel and ros2).

    An error when the robot's ROS version is known (``<ros2_control>``, its controller files,
    Gazebo's ros_control plugin, its package's build tool; the message says which) and the
    plugin of that version has the parameter under its own name (the value written is lost),
    unless the value asks for what that plugin does without it (ROS 1's camera computes
    ``<Cx>0</Cx>``, as ROS 2's does with no ``<cx>``; ``<cx>0</cx>`` there would put the
    image's centre in its corner): then a warning;
    a warning when it has no such parameter (ROS 2's camera takes its distortion from the
    sensor's ``<distortion>``), and when the version is not known and one plugin mixes both
    versions' names (some of them are ignored whichever it runs on).

    Bad: ``<leftJoint>left_wheel_joint</leftJoint>`` in ``libgazebo_ros_diff_drive.so`` of a
    robot with ``<ros2_control>``
    Good: ``<left_joint>left_wheel_joint</left_joint>``
    """
    version, why = ros_version(robot)
    for element in gazebo_plugins(robot):
        found = vocabulary.plugin(element)
        if found is None or found.family != vocabulary.CLASSIC or set(found.versions) != {"ros1", "ros2"}:
            continue
        only = {v: found.versions[v] - found.versions[o] for v, o in (("ros1", "ros2"), ("ros2", "ros1"))}
        used = {v: [c for c in _children(element) if c.tag in only[v]] for v in only}
        if version is not None:
            mine = f"ros{version}"
            other = "ros1" if mine == "ros2" else "ros2"
            evidence = (("why", f" ({why})", ""),)  # (each line of a plugin gives it)
            for child in used[other]:
                right = vocabulary.counterpart(child.tag, found.versions[mine], mine)
                said = (f"{_label(element, found)}: <{child.tag}> is the {_ROS[other]} plugin's "
                        f"name, and the robot is {_ROS[mine]} ({why}); the {_ROS[mine]} plugin "
                        "ignores it")
                if right and vocabulary.same_without(found.key, child.tag, child.text):
                    value = child.text.strip()
                    yield child, Said(f"{said}, which loses nothing: {value} asks the "
                                      f"{_ROS[other]} plugin for what the {_ROS[mine]} one does "
                                      f"without it (not what <{right}>{value}</{right}> asks): "
                                      "remove it", evidence), None, Severity.WARNING
                    continue
                yield child, Said(said + (f": write {_tag(right)}" if right else
                                          " and has no such parameter: remove it"), evidence), \
                    None, (Severity.ERROR if right else Severity.WARNING)
        elif used["ros1"] and used["ros2"]:
            names = {v: ", ".join(f"<{c.tag}>" for c in used[v]) for v in used}
            yield used["ros1"][0], (
                f"{_label(element, found)} mixes ROS 1 names ({names['ros1']}) and ROS 2 names "
                f"({names['ros2']}): under ROS 1 the second are ignored, under ROS 2 the first; "
                "write all of them as the ROS version the robot runs on names them"), None, Severity.WARNING


@rule("U641", "gazebo-plugin-unknown-parameter", Severity.WARNING)
def gazebo_plugin_unknown_parameter(robot):
    """A Gazebo plugin's child element is a near miss of a name the plugin reads, or Gazebo Classic's.

    Gazebo passes the plugin its ``<plugin>`` element and the plugin reads the names it knows:
    a misspelt one (``<wheelSeperation>``, ``<distalostionK1>``) or Gazebo Classic's name in a
    new Gazebo system (gz-sim's DiffDrive reads ``wheel_radius``, not ``wheel_diameter``) is
    ignored without a word. Checked for the plugins whose sources were read: gazebo_ros_pkgs
    (ROS 1 noetic and ROS 2), gazebo_ros2_control, gz_ros2_control and gz-sim's systems
    (Fortress, Harmonic, Ionic), against the version the robot is written for when that is
    known. A name close to none the plugin reads is not reported: older releases read names
    these do not (``<alwaysOn>``, ``<legacyMode>``), harmless where they are ignored.

    Bad: ``<wheel_diameter>0.2</wheel_diameter>`` in ``gz-sim-diff-drive-system``
    Good: ``<wheel_radius>0.1</wheel_radius>``
    """
    from urdftool.errors import close_names

    version, _ = ros_version(robot)
    for element in gazebo_plugins(robot):
        found = vocabulary.plugin(element)
        if found is None:
            continue
        names = found.names
        mine = {f"ros{version}"} & set(found.versions) if version else set()
        versions = {v: found.versions[v] for v in (mine or found.versions)}
        present = {child.tag for child in _children(element)}
        for child in _children(element):
            if child.tag in names:
                continue
            close = {}
            for v, reads in versions.items():
                right = vocabulary.counterpart(child.tag, reads, v) or vocabulary.near(child.tag, reads)
                if right:
                    close.setdefault(right, []).append(v)
            classic = found.family == vocabulary.GZ and child.tag in vocabulary.classic_counterpart(found.key)
            if not close and not classic:
                continue
            given = [right for right in close if right in present]
            for right in given:  # a name the element gives already is no suggestion
                del close[right]
            if given and not close:
                hint = (f"{_tag(given[0])}, the name it reads, is given beside it: remove "
                        f"<{child.tag}>")
            elif close:
                hint = "did you mean " + " or ".join(
                    f"{_tag(right)}{'' if len(close) == 1 and not mine else ' (' + ', '.join(_VERSION.get(v, v) for v in vs) + ')'}"
                    for right, vs in close.items()) + "?"
            else:
                guess = close_names(child.tag, sorted(names), n=1, cutoff=0.6)
                hint = ("it is Gazebo Classic's name" + (f"; the new Gazebo's plugin reads <{guess[0]}>"
                                                          if guess else "") + " (see the system's documentation)")
            yield child, (f"{_label(element, found)} does not read <{child.tag}>, so it is ignored; {hint}")


_VERSION = {"ros1": "ROS 1", "ros2": "ROS 2", "fortress": "Fortress", "harmonic": "Harmonic",
            "ionic": "Ionic"}


def _tag(name: str) -> str:
    return name if name.startswith("<") else f"<{name}>"


@rule("U642", "gazebo-ros-control-missing", Severity.WARNING)
def gazebo_ros_control_missing(robot):
    """A ROS 1 robot set up for Gazebo and ros_control has no gazebo_ros_control plugin.

    Its transmissions and its controller YAML describe how the joints are driven, and
    ``<gazebo>`` elements say it is simulated, but no ``libgazebo_ros_control.so`` plugin starts
    ros_control inside Gazebo: the controller spawner waits for a controller manager that never
    comes, and the joints hang limp. A ``<plugin name="gazebo_ros_control">`` without a
    ``filename`` (as older Setup Assistants wrote it) loads nothing either. (ROS 2: U519 for
    ``<ros2_control>``.) A warning: the plugin may be added by a file that includes this one.
    Not reported when the launch files spawn an SDF into Gazebo instead (``spawn_model -sdf``):
    the model Gazebo simulates is then not this URDF.

    Bad: transmissions and ``head_controller`` in the YAML, no ``<gazebo><plugin
    filename="libgazebo_ros_control.so">``
    Good: ``<gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so"/></gazebo>``
    """
    if robot.children("ros2_control") or not robot.children("gazebo") or not transmissions(robot):
        return
    started = [c for c in controllers(robot) if c.layout == "ros1"]
    if not started or _gazebo_spawns_another_model(robot):
        return
    unloaded = None
    for element in gazebo_plugins(robot):
        key = vocabulary.plugin_key(element.get("filename") or "")
        if key == "gazebo_ros_control" or "ros_control" in (element.get("filename") or ""):
            return
        if "ros_control" in (element.get("name") or "") and not element.get("filename"):
            unloaded = element
    first = started[0]
    if unloaded is not None:
        yield unloaded, (f"<plugin name=\"{unloaded.get('name')}\"> has no filename, so Gazebo loads "
                         f"nothing, and ros_control never starts for the controllers in {first.file.display}: "
                         "add filename=\"libgazebo_ros_control.so\"")
        return
    yield first.file.at(first.line), (
        f"{len(started)} ros_control controller{'s' if len(started) > 1 else ''} "
        f"({', '.join(c.name for c in started[:4])}{', ...' if len(started) > 4 else ''}) and "
        f"{len(transmissions(robot))} transmission(s) for a robot simulated in Gazebo, but no "
        "<gazebo><plugin filename=\"libgazebo_ros_control.so\"> starts ros_control there: the "
        "controllers never load in simulation")


def _gazebo_spawns_another_model(robot) -> bool:
    """Whether every launch file describing the robot that spawns a model into Gazebo spawns an
    SDF (``spawn_model -sdf``): Gazebo then simulates that model, with its own plugins, and the
    URDF only feeds robot_state_publisher (quad-sdk spawns robot_description_sdf)."""
    from urdftool.description.runtime import runtime

    spawns = runtime(robot).starts("gazebo_ros", ("spawn_model",))
    return bool(spawns) and all(
        "-sdf" in [word.text for word in start.arguments] for _, start in spawns)


@rule("U643", "gazebo-control-parameters-path", Severity.ERROR)
def gazebo_control_parameters_path(robot):
    """A Gazebo ros2_control plugin's ``<parameters>`` file does not exist, or is a relative path.

    gazebo_ros2_control and gz_ros2_control pass ``<parameters>`` to the controller manager as
    a parameter file: a path into the robot's repository (as ``$(find pkg)`` makes it) that
    does not exist, in the source tree nor where the package's install rules take it from,
    leaves every controller without parameters; a ``package://`` URI is not a
    path; a relative path is resolved against the working directory of whoever launches
    Gazebo (a warning). A path outside the repository is not looked at.

    Bad: ``<parameters>config/controllers.yaml</parameters>``
    Good: ``<parameters>$(find my_robot)/config/controllers.yaml</parameters>``
    """
    from urdftool.description.files import inside, kind_of, no_file_there
    from urdftool.description.packages import containment_root, find_form

    root = containment_root(Path(robot.path).parent) if robot.path != "-" else None
    for element in gazebo_plugins(robot):
        found = vocabulary.plugin(element)
        if found is None or not found.hardware:
            continue
        for child in element.iter("parameters"):
            value = (child.text or "").strip()
            if not value or "$(" in value:
                continue
            if value.startswith("package://"):
                yield child, (f"<parameters> '{value}' is a package:// URI; the controller "
                              f"manager takes a file path: write {find_form(value)}")
            elif not Path(value).is_absolute():
                yield child, (f"<parameters> '{value}' is a relative path, resolved against the working "
                              "directory of whoever launches Gazebo; write $(find PACKAGE)/"
                              f"{value}"), None, Severity.WARNING
            elif root is not None and inside(Path(value).parent, root) and \
                    kind_of(value) != "file":
                # $(find PKG)/config/x.yaml names share/PKG after a build, which the package's
                # install rules may fill from another source folder (bringup/config)
                located = robot.resolver.locate(value)
                if kind_of(located.path) == "file":
                    continue
                if located.doubt:
                    yield child, (f"<parameters> '{value}' is not in the source tree; "
                                  f"{located.doubt}"), None, Severity.WARNING
                    continue
                yield child, (f"<parameters> '{value}' {no_file_there(value)}: the controller "
                              "manager starts without the controllers' parameters")
