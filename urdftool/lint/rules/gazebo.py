"""U61x: ``<gazebo>`` extensions: references, the diff-drive plugin, sensors."""

from __future__ import annotations

import math

from urdftool.lint.catalogue import Severity, rule
from urdftool.physics import mat3
from urdftool.errors import available
from urdftool.description.urdf import ROUND
from urdftool.description.values import origin, parse_numbers

DIFF_DRIVE = ("diff_drive", "diff-drive", "DiffDrive")
WHEEL_JOINT_TAGS = ("leftJoint", "rightJoint", "left_joint", "right_joint")
GEOMETRY_TOLERANCE = 0.05
FRAME_TAGS = ("frame_name", "frameName", "bodyName", "body_name")


def _gazebo_plugins(robot):
    for gazebo in robot.children("gazebo"):
        yield from gazebo.iter("plugin")


def _diff_drives(robot):
    for plugin in _gazebo_plugins(robot):
        text = f"{plugin.get('filename', '')} {plugin.get('name', '')}"
        if any(word in text for word in DIFF_DRIVE):
            yield plugin


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
            yield gazebo, (f"<gazebo reference='{reference}'> names no link or joint; "
                           f"{available('links', reference, robot.links)}")


@rule("U612", "diff-drive-unknown-joint", Severity.ERROR)
def diff_drive_unknown_joint(robot):
    """A diff-drive plugin's wheel joint does not exist.

    The plugin fails to load and the robot does not drive.

    Bad: ``<left_joint>left_wheel</left_joint>`` when the joint is ``left_wheel_joint``
    Good: ``<left_joint>left_wheel_joint</left_joint>``
    """
    for plugin in _diff_drives(robot):
        for tag in WHEEL_JOINT_TAGS:
            for element in plugin.findall(tag):
                name = (element.text or "").strip()
                if name not in robot.joints:
                    yield element, (f"diff-drive <{tag}> '{name}' is not a joint; "
                                    f"{available('joints', name, robot.joints)}")


@rule("U613", "diff-drive-joint-not-continuous", Severity.WARNING)
def diff_drive_joint_not_continuous(robot):
    """A diff-drive wheel joint is not continuous.

    A revolute wheel stops at its limit; a fixed one never turns.

    Bad: ``<joint name="left_wheel_joint" type="revolute">``
    Good: ``type="continuous"``
    """
    for plugin in _diff_drives(robot):
        for tag in WHEEL_JOINT_TAGS:
            for element in plugin.findall(tag):
                joint = robot.joints.get((element.text or "").strip())
                if joint is not None and joint.get("type") != "continuous":
                    yield element, (f"diff-drive wheel joint '{joint.get('name')}' is "
                                    f"{joint.get('type')}, not continuous; make it "
                                    "type=\"continuous\" (a wheel turns without limit)")


@rule("U614", "diff-drive-geometry", Severity.WARNING)
def diff_drive_geometry(robot):
    """A diff-drive plugin's wheel separation or diameter disagrees with the URDF by more than 5 %.

    Odometry then drifts: the plugin turns the wheels by the numbers it was given, not by the
    wheels the robot has. Separation is measured between the wheel joint origins along the
    wheel axis; the diameter is the wheel link's cylinder or sphere.

    Bad: ``<wheel_separation>0.3</wheel_separation>`` for wheels 0.26 m apart
    Good: ``<wheel_separation>${wheel_separation}</wheel_separation>`` from the same property
    """
    for plugin in _diff_drives(robot):
        left, right = _wheel_joint(robot, plugin, "left"), _wheel_joint(robot, plugin, "right")
        if left is None or right is None:
            continue
        separation = _separation(robot, left, right)
        diameter = _wheel_diameter(robot, left)
        checks = [(("wheel_separation", "wheelSeparation"), separation, 1.0),
                  (("wheel_diameter", "wheelDiameter"), diameter, 1.0),
                  (("wheel_radius",), diameter, 0.5)]
        for tags, actual, scale in checks:
            for tag in tags:
                element = plugin.find(tag)
                if element is None or actual is None:
                    continue
                values, _ = parse_numbers(element.text, 1)
                expected = actual * scale
                if values and expected > 0 and abs(values[0] - expected) > GEOMETRY_TOLERANCE * expected:
                    off = 100 * (values[0] - expected) / expected
                    yield element, (f"diff-drive <{tag}> is {values[0]:g} m but the URDF gives "
                                    f"{expected:.4g} m ({off:+.1f} %)")


def _wheel_joint(robot, plugin, side):
    for tag in (f"{side}Joint", f"{side}_joint"):
        name = plugin.findtext(tag)
        if name and name.strip() in robot.joints:
            return robot.joints[name.strip()]
    return None


def _separation(robot, left, right) -> float | None:
    """Distance between the two wheel joint origins along the left wheel axis (zero pose)."""
    poses = _joint_frames(robot)
    if left.get("name") not in poses or right.get("name") not in poses:
        return None
    (left_position, left_rotation) = poses[left.get("name")]
    right_position, _ = poses[right.get("name")]
    axis, _ = parse_numbers((left.find("axis").get("xyz") if left.find("axis") is not None
                             else "1 0 0"), 3)
    delta = [a - b for a, b in zip(left_position, right_position)]
    if not axis or math.hypot(*axis) == 0:
        return math.hypot(*delta)
    world_axis = mat3.apply(left_rotation, [a / math.hypot(*axis) for a in axis])
    return abs(sum(d * a for d, a in zip(delta, world_axis)))


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


def _joint_frames(robot) -> dict:
    """Joint name -> (position, rotation) of its frame in the root frame at the zero pose."""
    by_child = {}
    for joint in robot.children("joint"):
        child = joint.find("child")
        if child is not None and child.get("link"):
            by_child.setdefault(child.get("link"), joint)
    frames: dict = {}

    def frame(joint, depth=0):
        name = joint.get("name")
        if name in frames:
            return frames[name]
        local = mat3.placement(origin(joint))  # a malformed part counts as 0
        parent = joint.find("parent")
        above = by_child.get(parent.get("link")) if parent is not None else None
        if above is None or depth > len(by_child):
            frames[name] = local
        else:
            position, rotation = frame(above, depth + 1)
            frames[name] = (mat3.add(position, mat3.apply(rotation, local[0])),
                            mat3.multiply(rotation, local[1]))
        return frames[name]

    for joint in robot.children("joint"):
        frame(joint)
    return frames


# Frames Gazebo itself provides: ground-truth plugins (p3d) report poses in the world frame.
GAZEBO_FRAMES = {"world"}


@rule("U615", "sensor-unknown-link", Severity.ERROR)
def sensor_unknown_link(robot):
    """A Gazebo sensor is not attached to a link of the robot, or its plugin names an unknown frame.

    A ``<sensor>`` must sit in ``<gazebo reference="LINK">``; outside one, or under a joint
    reference (except force_torque sensors, which belong on joints), Gazebo drops it. A sensor
    plugin's ``frame_name``/``frameName`` and any plugin's ``bodyName`` must be a link (or
    Gazebo's ``world``), or the data is stamped with a frame TF does not know.

    Bad: ``<gazebo> <sensor type="camera" ...>`` (no reference)
    Good: ``<gazebo reference="camera_link"> <sensor type="camera" ...>``
    """
    for gazebo in robot.children("gazebo"):
        reference = gazebo.get("reference")
        for sensor in gazebo.iter("sensor"):
            if reference is None:
                yield sensor, (f"sensor '{sensor.get('name')}' is in a <gazebo> without a "
                               "reference; put it in <gazebo reference=\"LINK\">")
            elif (reference not in robot.links and reference in robot.joints
                  and sensor.get("type") != "force_torque"):
                yield sensor, (f"sensor '{sensor.get('name')}' is on joint '{reference}', not a "
                               f"link; {available('links', reference, robot.links)}")
        for tag in FRAME_TAGS:
            holders = gazebo.iter("sensor") if tag.startswith("frame") else [gazebo]
            for element in (e for holder in holders for e in holder.iter(tag)):
                name = (element.text or "").strip()
                if name and name not in robot.links and name not in GAZEBO_FRAMES:
                    own = (f"use '{reference}', the link it sits on, or add a link '{name}'"
                           if reference in robot.links else available("links", name, robot.links))
                    yield element, (f"<{tag}> '{name}' is not a link, so TF cannot place the data "
                                    f"stamped with it; {own}")
