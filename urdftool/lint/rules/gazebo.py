"""U61x: ``<gazebo>`` extensions: references, the diff-drive plugin, sensors."""

from __future__ import annotations

import math


from urdftool.description.actuation import (WHEEL_JOINT_TAGS, diff_drive_plugins, gazebo_elements,
                                           gazebo_plugins)
from urdftool.description.controllers import controllers, names_at
from urdftool.description.urdf import ROUND
from urdftool.description.values import origin, parse_numbers
from urdftool.errors import available
from urdftool.description import gazebo_plugins as vocabulary
from urdftool.description.ros_version import ros_version, ros_versions
from urdftool.description.runtime import runtime, static_frames
from urdftool.lint.catalogue import Conditional, Severity, rule
from urdftool.description.controllers import runs_of
from urdftool.lint.rules.controllers import hedged
from urdftool.numbers import decimal_slip, number, numbers
from urdftool.physics import mat3
from urdftool.physics.frames import joint_frames, link_frames, world_axis
from urdftool.records import NEW, Record

GEOMETRY_TOLERANCE = 0.05
FRAME_TAGS = ("frame_name", "frameName", "bodyName", "body_name")
SENSOR_FRAME_TAGS = ("frame_name", "frameName")  # (a sensor plugin's: read in a <sensor> only)
ROS1_FRAME_TAGS = ("frameName", "bodyName", "robotBaseFrame", "odometryFrame")


def _frame(name: str, ros1: bool) -> str:
    """A frame name as TF gets it: ROS 1's Gazebo plugins and tf2 strip a leading ``/``
    (``/base_link`` is ``base_link``; ROS 2 keeps it, and TF refuses it)."""
    return name.lstrip("/") if ros1 and name.lstrip("/") else name


class _Drive(Record):
    """A differential drive, as a Gazebo plugin or a diff_drive_controller describes it.

    wheels: (side, joint name, where) for each wheel it names
    numbers: (parameter, value text, where) for wheel_separation/wheel_diameter/wheel_radius
    frames: (parameter, frame name, where, whether it must be a link of the robot)
    """

    label: str
    wheels: list
    controller: object  # the diff_drive_controller, for a controller's drive
    numbers: list
    frames: list

    __slots__ = ("label", "wheels", "controller", "numbers", "frames")

    def __init__(self, label: str, wheels: list = NEW, controller: object = None,
                 numbers: list = NEW, frames: list = NEW) -> None:
        self.label = label
        self.wheels = [] if wheels is NEW else wheels
        self.controller = controller
        self.numbers = [] if numbers is NEW else numbers
        self.frames = [] if frames is NEW else frames

    def side(self, robot, side: str):
        """The first joint of the robot on ``side`` ("left"/"right"), or None."""
        return next((robot.joints[name] for s, name, _ in self.wheels
                     if s == side and name in robot.joints), None)


_PLUGIN_NUMBERS = ("wheel_separation", "wheelSeparation", "wheel_diameter", "wheelDiameter",
                   "wheel_radius")
_PLUGIN_FRAMES = (("robot_base_frame", True), ("robotBaseFrame", True),
                  ("odometry_frame", False), ("odometryFrame", False))
_CONTROLLER_WHEELS = {"left_wheel_names": "left", "right_wheel_names": "right",
                      "left_wheel": "left", "right_wheel": "right"}
_CONTROLLER_FRAMES = (("base_frame_id", True), ("odom_frame_id", False))


def _drives(robot) -> list[_Drive]:
    """Every diff drive of the robot: Gazebo plugins, then diff_drive_controller controllers."""
    return robot.memo(_drives, lambda: [*_plugin_drives(robot), *_controller_drives(robot)])


def _plugin_drives(robot):
    for plugin in diff_drive_plugins(robot):
        drive = _Drive(f"diff-drive plugin '{plugin.get('name') or plugin.get('filename')}'")
        for tag in WHEEL_JOINT_TAGS:
            for element in plugin.findall(tag):
                drive.wheels.append(("left" if tag.startswith("left") else "right",
                                     (element.text or "").strip(), element))
        for tag in _PLUGIN_NUMBERS:
            element = plugin.find(tag)
            if element is not None:
                drive.numbers.append((tag, element.text, element))
        for tag, link in _PLUGIN_FRAMES:
            element = plugin.find(tag)
            if element is not None and (element.text or "").strip():
                drive.frames.append((tag, _frame(element.text.strip(), tag in ROS1_FRAME_TAGS),
                                     element, link))
        yield drive


def _said(robot, drive: _Drive, message: str):
    """``message`` as the rule yields it for ``drive``: a controller's is hedged by whether its
    launch files start it (:func:`~urdftool.lint.rules.controllers.hedged`)."""
    return hedged(robot, drive.controller, message) if drive.controller is not None else message


def _controller_drives(robot):
    for controller in controllers(robot):
        if controller.cls is None or controller.cls.package != "diff_drive_controller":
            continue
        if runs_of(robot, controller).state == "never":
            continue
        drive = _Drive(f"controller '{controller.name}' ({controller.type})", controller=controller)
        at, params = controller.file.at, controller.params or {}
        for key, side in _CONTROLLER_WHEELS.items():
            drive.wheels.extend((side, name, at(line)) for name, line in names_at(params, key))
        for key in ("wheel_separation", "wheel_radius"):
            if key in params:
                drive.numbers.append((key, str(params[key]), at(controller.where(key))))
        for key, link in _CONTROLLER_FRAMES:
            if isinstance(params.get(key), str) and params[key].strip():
                name = _frame(params[key].strip(), controller.ros == 1)
                if "$(" not in name or controller.file.substituted is False:
                    drive.frames.append((key, name, at(controller.where(key)), link))
        yield drive


@rule("U611", "gazebo-unknown-reference", Severity.ERROR)
def gazebo_unknown_reference(robot):
    """A ``<gazebo reference="X">`` names no link or joint of the robot.

    Gazebo silently ignores it: friction, colours and sensors in the block never apply.

    Bad: ``<gazebo reference="caster">`` when the link is ``caster_link``
    Good: ``<gazebo reference="caster_link">``
    """
    for gazebo in robot.children("gazebo"):
        reference = gazebo.get("reference")
        if reference is not None and reference not in robot.links and reference not in robot.joints:
            yield gazebo, (f"<gazebo reference='{reference}'> names no link or joint, so "
                           "Gazebo drops the block: its sensors, plugins, friction and colours "
                           "never apply; "
                           + available('links', reference, robot.links, ('joints', robot.joints)))


@rule("U612", "diff-drive-unknown-joint", Severity.ERROR)
def diff_drive_unknown_joint(robot):
    """A diff-drive plugin's wheel joint does not exist.

    The plugin fails to load and the robot does not drive.

    Bad: ``<left_joint>left_wheel</left_joint>`` when the joint is ``left_wheel_joint``
    Good: ``<left_joint>left_wheel_joint</left_joint>``
    """
    for plugin in diff_drive_plugins(robot):
        for tag in WHEEL_JOINT_TAGS:
            for element in plugin.findall(tag):
                name = (element.text or "").strip()
                if name not in robot.joints:
                    yield element, (f"diff-drive <{tag}> '{name}' is not a joint; "
                                    + available('joints', name, robot.joints))


@rule("U613", "diff-drive-joint-not-continuous", Severity.WARNING)
def diff_drive_joint_not_continuous(robot):
    """A diff-drive wheel joint is not continuous.

    A revolute wheel stops at its limit; a fixed one never turns. Checked for the Gazebo
    diff-drive plugins' wheel joints and diff_drive_controller's ``left_wheel_names`` and
    ``right_wheel_names`` (ROS 1: ``left_wheel``, ``right_wheel``).

    Bad: ``<joint name="left_wheel_joint" type="revolute">``
    Good: ``type="continuous"``
    """
    for drive in _drives(robot):
        for _, name, where in drive.wheels:
            joint = robot.joints.get(name)
            if joint is not None and joint.get("type") != "continuous":
                yield where, _said(robot, drive, (
                    f"diff-drive wheel joint '{name}' is {joint.get('type')}, not continuous; make "
                    "it type=\"continuous\" (a wheel turns without limit)"))


@rule("U614", "diff-drive-geometry", Severity.WARNING)
def diff_drive_geometry(robot):
    """A diff drive's wheel separation or diameter disagrees with the URDF by more than 5 %.

    Odometry then drifts: the plugin or controller turns the wheels by the numbers it was
    given, not by the wheels the robot has. Checked for the Gazebo diff-drive plugins and
    diff_drive_controller (``wheel_separation``, ``wheel_radius``). Separation is measured
    between the wheel joint origins along the wheel axis (across the robot when the axis is
    not horizontal, which U617 reports); the diameter is the wheel link's cylinder or sphere.

    Bad: ``<wheel_separation>0.3</wheel_separation>`` for wheels 0.26 m apart
    Good: ``<wheel_separation>${wheel_separation}</wheel_separation>`` from the same property
    """
    scales = {"wheel_separation": 1.0, "wheelSeparation": 1.0, "wheel_diameter": 1.0,
              "wheelDiameter": 1.0, "wheel_radius": 0.5}
    for drive in _drives(robot):
        left, right = drive.side(robot, "left"), drive.side(robot, "right")
        if left is None or right is None:
            continue
        separation = _separation(robot, left, right)
        diameter = _wheel_diameter(robot, left)
        for tag, text, where in drive.numbers:
            actual = separation if "eparation" in tag else diameter
            values, _ = parse_numbers(text, 1)
            if actual is None or not values:
                continue
            expected = actual * scales[tag]
            if expected > 0 and abs(values[0] - expected) > GEOMETRY_TOLERANCE * expected:
                off = 100 * (values[0] - expected) / expected
                yield where, _said(robot, drive, (f"{drive.label}: {tag} is {values[0]:g} m but the "
                                                  f"URDF gives {number(expected)} m "
                                                  f"({number(off, places=1, plus=True)} %)"
                                                  + decimal_slip(values[0], expected)))


HORIZONTAL = math.sin(math.radians(10))  # a wheel axis tilted less than 10 deg is horizontal


def _separation(robot, left, right) -> float | None:
    """Distance between the two wheel joint origins along the left wheel axis (zero pose);
    across the robot (horizontally) when that axis is not horizontal."""
    poses = joint_frames(robot)
    if left.get("name") not in poses or right.get("name") not in poses:
        return None
    left_position, right_position = poses[left.get("name")][0], poses[right.get("name")][0]
    delta = [a - b for a, b in zip(left_position, right_position)]
    axis = world_axis(robot, left)
    if axis is None or abs(axis[2]) > HORIZONTAL:
        return math.hypot(delta[0], delta[1])
    return abs(sum(d * a for d, a in zip(delta, axis)))


def _wheel_diameter(robot, joint) -> float | None:
    child = joint.find("child")
    link = robot.links.get(child.get("link")) if child is not None else None
    if link is None:
        return None
    for tag in ("collision", "visual"):
        for shape in link.iterfind(f"{tag}/geometry/*"):
            if shape.tag in ROUND:
                values, _ = parse_numbers(shape.get("radius"), 1)
                if values:
                    return 2 * values[0]
    return None


def _inside(element, gazebo, tag: str) -> bool:
    """Whether ``element`` sits in a ``<tag>`` written in ``gazebo``: an SDF ``<link>`` (in a
    referenceless block, which Gazebo copies into the model: a link of its own, with its
    sensors), a ``<sensor>``."""
    parent = element.getparent()
    while parent is not None and parent is not gazebo:
        if parent.tag == tag:
            return True
        parent = parent.getparent()
    return False


# Frames Gazebo itself provides: ground-truth plugins (p3d) report poses in the world frame.
GAZEBO_FRAMES = {"world"}


@rule("U615", "sensor-unknown-link", Severity.ERROR)
def sensor_unknown_link(robot):
    """A Gazebo sensor is not attached to a link of the robot, or its plugin names an unknown frame.

    A ``<sensor>`` must sit in ``<gazebo reference="LINK">``; outside one, or under a joint
    reference (except force_torque sensors, which belong on joints), Gazebo drops it. In an SDF
    ``<link>`` of a ``<gazebo>`` without a reference, which Gazebo copies into the model as a
    link of its own (hamster_gazebo's hokuyo_link with its ray sensor), it is that link's. A sensor
    plugin's ``frame_name``/``frameName`` and any plugin's ``bodyName`` must be a link (or
    Gazebo's ``world``), or the data is stamped with a frame TF does not know. ROS 1's plugins
    (``frameName``, ``bodyName``) strip a leading ``/``: ``/camera_link`` is ``camera_link``;
    ROS 2's tf2 refuses a frame id that starts with ``/``. A name ``NAMESPACE/LINK`` is the link
    under a TF prefix (robot_state_publisher's ``frame_prefix``, ROS 1's ``tf_prefix``) that a
    launch file chooses: not judged. A frame that is no link but that a launch file of the
    robot publishes with a static_transform_publisher (tf2_ros', ROS 1 tf's) is in TF while that
    launch file runs (COEX Clover's ``main_camera_optical``): a note naming it. A ROS 1 ``frameName`` that is ``LINK`` where the robot's
    link is ``NAMESPACE/LINK`` (RotorS writes its links ``${namespace}/...`` and the frames
    without it) is right when the plugin's ``tf_prefix`` parameter is ``NAMESPACE``, which
    ROS 1's sensor plugins prefix the frame with (or, when none is set, with their
    ``<robotNamespace>``: nothing to report when that is ``NAMESPACE``): a warning naming it.
    A frame the plugin of the robot's ROS version does not read stamps nothing, so it is not
    judged: a ROS 1 ``frameName`` in a ROS 2 robot (the ROS 2 plugin ignores it; U640 says so),
    or any frame of a plugin that version has not (ROS 1's ``gazebo_ros_laser`` in a ROS 2
    robot).

    Bad: ``<gazebo> <sensor type="camera" ...>`` (no reference)
    Good: ``<gazebo reference="camera_link"> <sensor type="camera" ...>``
    """
    for gazebo, element in gazebo_elements(robot):
        # the sensors and frames of the one walk of each block (it walked it once for the
        # sensors, then once a tag: 5 walks of each of the corpus's 806 blocks); the engine
        # sorts the findings, so their order here is free
        tag = element.tag
        if tag != "sensor" and tag not in FRAME_TAGS:
            continue  # a plugin (the walk's tags hold FRAME_TAGS: tests/lint/rules/test_gazebo)
        reference = gazebo.get("reference")
        if tag == "sensor":
            if reference is None and not _inside(element, gazebo, "link"):
                yield element, (f"sensor '{element.get('name')}' is in a <gazebo> without a "
                                "reference; put it in <gazebo reference=\"LINK\">")
            elif (reference not in robot.links and reference in robot.joints
                  and element.get("type") != "force_torque"):
                yield element, (f"sensor '{element.get('name')}' is on joint '{reference}', "
                                "not a link; " + available('links', reference, robot.links))
            continue
        if tag in SENSOR_FRAME_TAGS and not _inside(element, gazebo, "sensor"):
            continue  # a sensor plugin's frame: read only in a <sensor>
        if _unread(robot, element):
            continue  # no plugin of the robot's ROS version stamps data with it (U640)
        name = _frame((element.text or "").strip(), tag in ROS1_FRAME_TAGS)
        namespace, _, link = name.rpartition("/")
        if namespace.strip("/") and link in robot.links:
            if name.startswith("/"):  # ROS 2 (ROS 1's tags are stripped above)
                yield element, (
                    f"<{tag}> '{name}' starts with '/': ROS 2's tf2 refuses frame ids "
                    f"that do (\"frame_id should not start with a '/'\"); write "
                    f"'{name.lstrip('/')}'")
            continue  # link '{link}' under a TF prefix the launch gives (frame_prefix)
        prefixed = [link for link in robot.links if link.endswith("/" + name)] \
            if name and tag in ROS1_FRAME_TAGS and name not in robot.links else []
        if len(prefixed) == 1:  # ROS 1's plugins prefix it with their tf_prefix
            prefix = prefixed[0][:-len(name) - 1]
            if _robot_namespace(element) == prefix.strip("/"):
                continue  # the tf_prefix it falls back to, unless a launch sets one
            yield element, Conditional(
                f"unless the plugin's tf_prefix parameter is '{prefix}' (ROS 1's "
                f"sensor plugins prefix <{tag}> with it, or with their "
                f"<robotNamespace> when none is set): <{tag}> '{name}' is not a link, "
                f"'{prefixed[0]}' is, so TF cannot place the data stamped with it")
        elif name and name in static_frames(robot):
            published = static_frames(robot)[name]
            when = f" {published.condition}" if published.condition else ""
            yield element, Conditional(
                f"<{tag}> '{name}' is not a link; {published.where} publishes it with a "
                f"static_transform_publisher from '{published.parent}'{when}, so TF "
                "places the data stamped with it only while that launch file runs",
                Severity.INFO)
        elif name and name not in robot.links and name not in GAZEBO_FRAMES:
            own = (f"use '{reference}', the link it sits on, or add a link '{name}'"
                   if reference in robot.links else available("links", name, robot.links))
            yield element, (f"<{tag}> '{name}' is not a link, so TF cannot place the data "
                            "stamped with it; " + own)


def _unread(robot, element) -> bool:
    """Whether the plugin holding ``element`` does not read it under the robot's ROS version
    (when that is known): a ROS 1 name (``frameName``) that the ROS 2 plugin ignores, or a
    plugin that ROS version has not (ROS 1's ``gazebo_ros_laser``), so no data is stamped with
    the frame it names."""
    plugin = next((a for a in element.iterancestors() if a.tag == "plugin"), None)
    found = vocabulary.plugin(plugin) if plugin is not None else None
    if found is None or found.family != vocabulary.CLASSIC:
        return False
    version, _ = ros_version(robot)
    if version is None:
        return False
    reads = found.versions.get(f"ros{version}")
    return reads is None or element.tag not in reads


def _robot_namespace(element) -> str:
    """The ``<robotNamespace>`` of the plugin holding ``element``, without its slashes."""
    plugin = next((a for a in element.iterancestors() if a.tag == "plugin"), None)
    found = plugin.find("robotNamespace") if plugin is not None else None
    return (found.text or "").strip().strip("/") if found is not None else ""


@rule("U616", "diff-drive-frame", Severity.ERROR)
def diff_drive_frame(robot):
    """A diff drive's base frame is not a link of the robot, or its odometry frame is one.

    The plugin or controller publishes the transform odometry frame -> base frame. The base
    frame must be a link (diff_drive_controller's ``base_frame_id``, the plugin's
    ``robot_base_frame``/``robotBaseFrame``), or the robot hangs off a frame TF does not
    connect; the odometry frame (``odom_frame_id``, ``odometry_frame``/``odometryFrame``) must
    not be one, or the link gets a second parent and TF breaks. ROS 1 (the plugin's camelCase
    tags, a ROS 1 diff_drive_controller) strips a leading ``/`` from a frame name.

    Bad: ``base_frame_id: base`` when the robot's root link is ``base_link``
    Good: ``base_frame_id: base_link``, ``odom_frame_id: odom``
    """
    for drive in _drives(robot):
        for tag, name, where, must_be_link in drive.frames:
            if must_be_link and name not in robot.links:
                message = (f"{drive.label}: {tag} '{name}' is not a link of the robot; "
                           + available('links', name, robot.links))
            elif not must_be_link and name in robot.links:
                message = (f"{drive.label}: {tag} '{name}' is a link of the robot; the "
                           "odometry frame is published as its parent, so use a frame outside "
                           "the URDF (odom)")
            else:
                continue
            message = _said(robot, drive, message)
            if message is not None:
                yield where, message


SIDEWAYS = math.cos(math.radians(45))  # an axle closer to x than to y does not point sideways
CASTER_CLEARANCE = 0.005  # [m] a caster this far below the wheels' contact plane lifts a wheel


@rule("U617", "diff-drive-wheel-layout", Severity.WARNING)
def diff_drive_wheel_layout(robot):
    """A diff drive's wheels are laid out in a way it cannot drive.

    Checked at the zero pose, in the robot's root frame (REP-103: x forward, y left, z up): the
    left wheel must be on the +y side of the right one (else the robot turns the wrong way),
    the axles pointing sideways (an axle along x rolls the robot along y: a base link turned 90
    degrees under its footprint, as ros2_jazzy_p3at's); each wheel axis must be horizontal (a
    vertical axis spins the wheel flat on the ground, and the separation measured along it is
    0) and parallel to the other wheel's; each wheel link needs collision geometry (Gazebo's
    wheels touch nothing without it); a caster (a link named ``*caster*`` with a sphere) must
    not reach below the wheels' contact plane, or it lifts the drive wheels.

    Bad: ``<axis xyz="0 0 1"/>`` on a wheel joint whose origin has no rotation
    Good: ``<axis xyz="0 1 0"/>``
    """
    for drive in _drives(robot):
        for where, message in _layout_problems(robot, drive):
            yield where, _said(robot, drive, message)


def _layout_problems(robot, drive: _Drive):
    """(where, message) for each way ``drive``'s wheels cannot drive (see U617)."""
    left, right = drive.side(robot, "left"), drive.side(robot, "right")
    where = {name: place for _, name, place in drive.wheels}
    poses = joint_frames(robot)
    for joint in (left, right):
        if joint is None:
            continue
        name = joint.get("name")
        axis = world_axis(robot, joint)
        if axis is not None and abs(axis[2]) > HORIZONTAL:
            yield where[name], (f"{drive.label}: wheel joint '{name}' turns about "
                                f"({numbers(axis, 3, ', ')}) in the root frame, "
                                "not a horizontal axis; the wheel would spin flat on the ground "
                                "(set its axis or origin rpy so the axis points sideways)")
        link = robot.links.get(joint.find("child").get("link")) if joint.find("child") is not None else None
        if link is not None and link.find("collision") is None:
            yield where[name], (f"{drive.label}: wheel link '{link.get('name')}' has no "
                                "<collision>; the simulated wheel touches nothing")
    if left is None or right is None:
        return
    names = left.get("name"), right.get("name")
    axes = world_axis(robot, left), world_axis(robot, right)
    if axes[0] is not None and left.get("type") in ("continuous", "revolute") and \
            abs(axes[0][2]) <= HORIZONTAL and abs(axes[0][1]) < SIDEWAYS:
        yield where[names[0]], (f"{drive.label}: wheel joint '{names[0]}' turns about "
                                f"({numbers(axes[0], 3, ', ')}) in the root frame, not sideways "
                                "(REP-103: x forward, y left): the wheels roll the robot along "
                                "y while the drive takes x as forward (set the wheels' or the "
                                "base's origin rpy so the axles point along y)")
    offset = [a - b for a, b in zip(poses[names[0]][0], poses[names[1]][0])] \
        if names[0] in poses and names[1] in poses else None
    if offset is not None and abs(offset[1]) >= abs(offset[0]) and offset[1] < 0:
        # (wheels one behind the other, an axle along x under a turned base, have no side)
        yield where[names[0]], (f"{drive.label}: left wheel '{names[0]}' is on the right "
                                f"(y = {number(poses[names[0]][0][1], 3)} m, right wheel at y = "
                                f"{number(poses[names[1]][0][1], 3)} m; REP-103: +y is left); swap them")
    if None not in axes and abs(abs(mat3.dot(*axes)) - 1) > 1 - math.cos(math.radians(5)):
        yield where[names[1]], (f"{drive.label}: wheel axes of '{names[0]}' and '{names[1]}' "
                                "are not parallel; both wheels must turn about the same line")
    yield from _caster_below(robot, drive, left, where[names[0]])


def _caster_below(robot, drive, wheel, where):
    """A caster sphere reaching below the contact plane of ``wheel`` (zero pose)."""
    diameter = _wheel_diameter(robot, wheel)
    frames = link_frames(robot)
    child = wheel.find("child")
    if diameter is None or child is None or child.get("link") not in frames:
        return
    ground = frames[child.get("link")][0][2] - diameter / 2
    for name, (position, rotation) in frames.items():
        link = robot.links.get(name)  # a joint may name a link that is not there (U105 says so)
        if link is None or "caster" not in name.lower():
            continue
        for collision in link.findall("collision"):
            sphere = collision.find("geometry/sphere")
            values, _ = parse_numbers(sphere.get("radius") if sphere is not None else None, 1)
            if not values:
                continue
            offset, _ = mat3.placement(origin(collision))
            bottom = (position[2] + mat3.apply(rotation, offset)[2]) - values[0]
            if bottom < ground - CASTER_CLEARANCE:
                yield where, (f"{drive.label}: caster '{name}' reaches "
                              f"{number(1000 * (ground - bottom), places=0)} mm below the drive "
                              f"wheels' contact plane (z = {number(ground, 3)} m); the "
                              "wheels would hang in the air: raise the caster or shrink it")


# Plugin libraries of gazebo_ros_pkgs (ros-simulation/gazebo_ros_pkgs, gazebo_plugins/CMakeLists.txt
# of the noetic-devel and ros2 branches; older PR2-era ones kept), of gazebo_ros_control
# (ROS 1) and of gazebo_ros2_control (ROS 2).
ROS1_CONTROL, ROS2_CONTROL = "libgazebo_ros_control.so", "libgazebo_ros2_control.so"
GAZEBO_LIBRARIES = frozenset({
    "libgazebo_ros_ackermann_drive.so", "libgazebo_ros_api_plugin.so", "libgazebo_ros_block_laser.so",
    "libgazebo_ros_bumper.so", "libgazebo_ros_camera.so", "libgazebo_ros_controller_manager.so",
    "libgazebo_ros_depth_camera.so", "libgazebo_ros_diff_drive.so", "libgazebo_ros_elevator.so",
    "libgazebo_ros_f3d.so", "libgazebo_ros_factory.so", "libgazebo_ros_force.so",
    "libgazebo_ros_force_system.so", "libgazebo_ros_ft_sensor.so", "libgazebo_ros_gps.so",
    "libgazebo_ros_gps_sensor.so", "libgazebo_ros_gpu_laser.so", "libgazebo_ros_hand_of_god.so",
    "libgazebo_ros_harness.so", "libgazebo_ros_imu.so", "libgazebo_ros_imu_sensor.so",
    "libgazebo_ros_init.so", "libgazebo_ros_joint_pose_trajectory.so",
    "libgazebo_ros_joint_state_publisher.so", "libgazebo_ros_joint_trajectory.so",
    "libgazebo_ros_laser.so", "libgazebo_ros_multicamera.so", "libgazebo_ros_openni_kinect.so",
    "libgazebo_ros_p3d.so", "libgazebo_ros_paths_plugin.so", "libgazebo_ros_planar_move.so",
    "libgazebo_ros_power_monitor.so", "libgazebo_ros_projector.so", "libgazebo_ros_properties.so",
    "libgazebo_ros_prosilica.so", "libgazebo_ros_range.so", "libgazebo_ros_ray_sensor.so",
    "libgazebo_ros_skid_steer_drive.so", "libgazebo_ros_srp.so", "libgazebo_ros_state.so",
    "libgazebo_ros_template.so", "libgazebo_ros_tricycle_drive.so",
    "libgazebo_ros_triggered_camera.so", "libgazebo_ros_triggered_multicamera.so",
    "libgazebo_ros_vacuum_gripper.so", "libgazebo_ros_video.so", "libgazebo_ros_wheel_slip.so",
    ROS1_CONTROL, ROS2_CONTROL,
})
_TYPO = 0.9  # difflib ratio above which an unknown library name is a misspelt known one


@rule("U618", "gazebo-plugin-library", Severity.ERROR)
def gazebo_plugin_library(robot):
    """A Gazebo plugin library is misspelt, of the other ROS, or in another namespace.

    Gazebo prints "Failed to load plugin" and goes on without it. A ``filename`` close to one
    of gazebo_ros_pkgs' libraries but not one of them is a typo (``libgazebo_ros_diffdrive.so``);
    ROS 1's ``libgazebo_ros_control.so`` in a robot with ``<ros2_control>`` does nothing (ROS 2
    uses ``libgazebo_ros2_control.so``, or gz_ros2_control on Gazebo Sim), and
    ``libgazebo_ros2_control.so`` without ``<ros2_control>`` has nothing to load; a
    gazebo_ros_control ``<robotNamespace>`` other than the namespace of the ROS 1 controller
    YAML (``humanoid_robot:`` above the controllers) finds no controller parameters. A robot
    that ROS 1 may run too (a catkin package, a ROS 1 launch file) gets a warning for the
    first, and the namespace of a YAML a launch file loads is the launch file's to choose.

    Bad: ``<plugin filename="libgazebo_ros_control.so">`` beside ``<ros2_control>``
    Good: ``<plugin filename="libgazebo_ros2_control.so" name="gazebo_ros2_control">``
    """
    from urdftool.errors import close_names

    ros2 = bool(robot.children("ros2_control"))
    facts = runtime(robot)
    # a file a launch file loads goes where the launch file puts it (a group's ns): not known
    namespaces = {c.namespace.strip("/") for c in controllers(robot) if c.layout == "ros1"
                  and not facts.loads(c.file.path)}
    ros1 = [e.why for e in ros_versions(robot).evidence if e.version == 1 and e.kind != "plugin"]
    for plugin in gazebo_plugins(robot):
        library = (plugin.get("filename") or "").strip()
        if library == ROS1_CONTROL and ros2:
            message = (f"{library} is ROS 1's gazebo_ros_control, but the robot describes its "
                       f"hardware in <ros2_control> (ROS 2): use {ROS2_CONTROL} "
                       "(gz_ros2_control-system on Gazebo Sim)")
            yield plugin, (Conditional(f"if the robot runs under ROS 2 (it may under ROS 1 too: "
                                       f"{'; '.join(ros1)}): " + message) if ros1 else message)
        elif library == ROS2_CONTROL and not ros2:
            yield plugin, (f"{library} (gazebo_ros2_control) reads the robot's <ros2_control>, and "
                           "it has none: add one, or use ROS 1's "
                           f"{ROS1_CONTROL} with transmissions")
        elif library.startswith("libgazebo_ros") and library not in GAZEBO_LIBRARIES:
            close = close_names(library, sorted(GAZEBO_LIBRARIES), n=1, cutoff=_TYPO)
            if close:
                yield plugin, f"plugin library '{library}' does not exist; did you mean '{close[0]}'?"
        if library == ROS1_CONTROL and len(namespaces) == 1:
            [namespace] = namespaces
            element = plugin.find("robotNamespace")
            given = (element.text or "").strip().strip("/") if element is not None else None
            if given is not None and namespace and given != namespace:
                yield element, (f"gazebo_ros_control looks for controllers in /{given}, but the "
                                f"controller YAML puts them in /{namespace}; make them the same")
