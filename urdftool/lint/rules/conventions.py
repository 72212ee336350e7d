"""U417-U421: ROS conventions for frames and wheels (REP 103, REP 105, REP 120).

Everything is judged at the zero pose, in the frame of the robot's root (REP 103: x forward,
y left, z up). Wheels and casters are identified by :mod:`urdftool.physics.wheels` (a diff
drive names them, or their names say so; never an arm, a gripper or a foot). These are
conventions and geometry read from a description: each finding is a warning.
"""

from __future__ import annotations

import math
import re

from urdftool.description.actuation import gazebo_sensors
from urdftool.description.values import parse_numbers
from urdftool.lint.catalogue import Severity, rule
from urdftool.numbers import MILLIMETRE, number, numbers
from urdftool.physics import mat3
from urdftool.physics.frames import child_joints, link_frames, parent_joints, relative
from urdftool.physics.mass import declared
from urdftool.physics.support import link_reach
from urdftool.physics.wheels import FOOTPRINT, footprint, lowest, wheel_body, wheels, world_axle

OPTICAL = mat3.rpy_matrix((-math.pi / 2, 0.0, -math.pi / 2))  # z forward, x right, y down
ANGLE_TOLERANCE = math.radians(1.0)  # printed pi/2 (1.57) is 0.05 deg off; a slip is 90 deg
_OPTICAL_NAME = re.compile(r"optical", re.IGNORECASE)
CAMERA_SENSORS = ("camera", "depth", "depth_camera", "rgbd_camera", "rgbd", "multicamera",
                  "wideanglecamera", "thermal", "thermal_camera", "segmentation",
                  "segmentation_camera", "boundingbox_camera")
CAMERA_FRAME_TAGS = ("frameName", "frame_name", "optical_frame_id", "gz_frame_id",
                     "ignition_frame_id")


def _angle(a, b) -> float:
    """The angle [rad] of the rotation taking ``a`` to ``b``."""
    product = mat3.multiply(mat3.transpose(a), b)
    cosine = (mat3.trace(product) - 1) / 2
    return math.acos(min(1.0, max(-1.0, cosine)))


def _rpy_text(rotation) -> str:
    """Roll, pitch, yaw of a rotation, as URDF writes them [rad], rounded."""
    (r00, _, _), (r10, _, _), (r20, r21, r22) = rotation
    pitch = math.atan2(-r20, math.hypot(r00, r10))
    roll, yaw = math.atan2(r21, r22), math.atan2(r10, r00)
    return " ".join(f"{number(0.0 if abs(v) < 5e-5 else v, 4)}" for v in (roll, pitch, yaw))


def _camera_frames(robot):
    """(element naming the frame, frame name, sensor frame (position, rotation) in the root
    frame, sensor label) for each camera sensor's plugin or sensor that names an image frame."""
    frames = link_frames(robot)
    for gazebo, sensor in gazebo_sensors(robot):
        reference = gazebo.get("reference")
        if reference not in frames:
            continue
        if (sensor.get("type") or "").lower() not in CAMERA_SENSORS:
            continue
        pose = sensor.find("pose")
        values, problem = parse_numbers(pose.text if pose is not None else "0 0 0 0 0 0", 6)
        if problem or not values:
            continue
        position, rotation = frames[reference]
        placed = (mat3.add(position, mat3.apply(rotation, values[:3])),
                  mat3.multiply(rotation, mat3.rpy_matrix(values[3:])))
        lens = sensor.findall("camera")  # its own <pose>, which Gazebo puts after the sensor's
        own = lens[0].find("pose") if len(lens) == 1 else None
        if own is not None:
            values, problem = parse_numbers(own.text, 6)
            if problem or not values:
                continue
            position, rotation = placed
            placed = (mat3.add(position, mat3.apply(rotation, values[:3])),
                      mat3.multiply(rotation, mat3.rpy_matrix(values[3:])))
        for tag in CAMERA_FRAME_TAGS:
            for element in sensor.iter(tag):
                name = (element.text or "").strip().lstrip("/")
                if name:
                    yield element, name, placed, f"{sensor.get('type')} sensor " \
                                                 f"'{sensor.get('name')}' on '{reference}'"


_CAMERA_BODY = re.compile(r"cam|rgb|depth|stereo|kinect|xtion|realsense|zed|oak|lens|infra",
                          re.IGNORECASE)
_NAME_WORDS = re.compile(r"[a-z]+|[0-9]+")
# words of a link name that say where a part is or which of several it is, not what it is: two
# links sharing one are not one part (the sentry's lower_pitch, a gimbal link, and its
# lower_camera_optical_frame); an index is a number, said apart
_PLACE_WORDS = frozenset({"left", "right", "l", "r", "front", "rear", "back", "fore", "aft",
                          "upper", "lower", "up", "down", "top", "bottom", "middle", "mid",
                          "center", "centre", "side", "inner", "outer"})


def _camera_body(robot, body: str, optical: str) -> bool:
    """Whether link ``body`` is the camera body of optical frame ``optical``, whose axes REP 103
    fixes (x forward): a Gazebo camera sensor sits on it, its name says camera, or it shares a
    word with the optical frame's name (``high_def_frame`` for ``high_def_optical_frame``)
    that says what the part is, not only where or which of several (a side, a position, an
    index: :data:`_PLACE_WORDS`). Any other link above is a part of the robot (a servo of a CAD
    export, a head, a gimbal's pitch link) whose axes say nothing of where the camera looks."""
    if _CAMERA_BODY.search(body) or any(
            gazebo.get("reference") == body and (sensor.get("type") or "").lower()
            in CAMERA_SENSORS for gazebo, sensor in gazebo_sensors(robot)):
        return True
    words = set(_NAME_WORDS.findall(optical.lower())) - {"optical", "frame", "link"}
    shared = words & set(_NAME_WORDS.findall(body.lower()))
    return any(not word.isdigit() and word not in _PLACE_WORDS for word in shared)


def _reference_link(robot, name: str) -> str | None:
    """The nearest link above ``name`` whose name does not say optical (its camera body)."""
    parents = parent_joints(robot)
    current, seen = name, set()
    while current in parents and current not in seen:
        seen.add(current)
        joint = parents[current]
        above = robot.ends()[joint]["parent"][1]
        if above is None or above not in robot.links:
            return None
        if not _OPTICAL_NAME.search(above):
            return above
        current = above
    return None


@rule("U417", "optical-frame-rotation", Severity.WARNING)
def optical_frame_rotation(robot):
    """A camera's optical frame is not turned to z forward, x right, y down (REP 103).

    Image consumers (image_geometry, depth_image_proc, every point cloud from a depth image)
    read pixels in the optical frame: z along the view, x to the right of the image, y down.
    From the camera's body frame (x forward, y left, z up) that is ``rpy="-pi/2 0 -pi/2"``.
    Checked for links whose name says optical (``camera_optical_frame``, ``*_optical``),
    against the nearest link above whose name does not (an optical frame fixed to another with
    the same axes is judged through that one) when that link is the camera's body (a Gazebo
    camera sits on it, its name says camera, or it shares a word with the optical frame's
    name that names the part, not only a side, a position or an index: the sentry's
    ``lower_pitch`` is no camera body of ``lower_camera_optical_frame``): an optical frame
    fixed to a servo of a CAD export is right or wrong whatever the servo's axes, and is not
    judged from them; and for the frame a Gazebo camera
    sensor's plugin stamps its images with (``frameName``, ``frame_name``,
    ``optical_frame_id``, ``gz_frame_id``), against the camera itself (its link, the sensor's
    ``<pose>`` and the ``<pose>`` of its ``<camera>``, which Gazebo composes with the
    sensor's: a Gazebo camera looks along its x axis; curiosity_mars_rover turns its cameras
    so that their links are optical frames). Within 1 degree (``1.57`` for pi/2 is 0.05
    degrees off). An optical frame turned from its camera link as REP 103 says but for a pitch
    of the view that no slip gives (not a multiple of 90 degrees: a camera tilted in a mount
    frame, Bit-Bots' head camera at 30 degrees) is a **note**.

    Bad: ``<frameName>camera_link</frameName>`` for a camera on ``camera_link``; an optical
    frame joint with ``rpy="0 0 0"`` or ``rpy="-1.5708 0 1.5708"``
    Good: a ``camera_optical_frame`` fixed to ``camera_link`` by
    ``<origin rpy="${-pi/2} 0 ${-pi/2}"/>``, named by the plugin
    """
    optical = [name for name in robot.links if _OPTICAL_NAME.search(name)]
    cameras = [sensor for _, sensor in gazebo_sensors(robot)
               if (sensor.get("type") or "").lower() in CAMERA_SENSORS]
    if not optical and not cameras:
        return
    frames = link_frames(robot)
    parents = parent_joints(robot)
    judged = set()
    for element, name, sensor, label in _camera_frames(robot):
        if name not in frames:
            continue  # U615 says so
        judged.add(name)
        turn = relative(sensor, frames[name])[1]
        if _angle(OPTICAL, turn) > ANGLE_TOLERANCE:
            yield element, (f"{label} stamps its images with '{name}', which is turned "
                            f"rpy=\"{_rpy_text(turn)}\" from the sensor; image consumers read "
                            "them in an optical frame (z forward, x right, y down: rpy=\"-pi/2 0 "
                            "-pi/2\" from the sensor); name a frame turned so, or add one")
    for name in optical:
        if name in judged or name not in frames:
            continue
        body = _reference_link(robot, name)
        if body is None or body not in frames or not _camera_body(robot, body, name):
            continue
        turn = relative(frames[body], frames[name])[1]
        above = robot.ends()[parents[name]]["parent"][1]
        if above in frames and _OPTICAL_NAME.search(above) and _angle(
                mat3.IDENTITY, relative(frames[above], frames[name])[1]) <= ANGLE_TOLERANCE:
            continue  # an optical frame on another (a depth lens beside the colour one): the
            # one above is judged
        if _angle(OPTICAL, turn) <= ANGLE_TOLERANCE:
            continue
        tilt = _pitched_view(turn)
        joint = parents[name]
        turned = _turn_said(robot, joint, above == body, turn)
        kind = _sensor_kind(robot, (body, name))
        link = f"{kind} link '{body}'" if kind else f"link '{body}'"
        if tilt is not None:  # the camera tilted in a mount frame: the optical frame may be right
            yield joint, (
                f"optical frame '{name}' is turned {turned} from {link}: z along a view "
                f"pitched {number(tilt, 3)} degrees from the link's x axis, as a camera tilted "
                f"in its mount is; REP 103 puts the {kind or 'sensor'}'s body frame along the "
                "view, the optical frame rpy=\"-pi/2 0 -pi/2\" from it"), None, Severity.INFO
            continue
        yield joint, (f"optical frame '{name}' is turned {turned} from {link}; an optical frame "
                      "is z forward, x right, y down: rpy=\"-pi/2 0 -pi/2\" from the "
                      f"{kind or 'sensor'}'s body frame (REP 103)")


LIDAR_SENSORS = ("ray", "gpu_ray", "lidar", "gpu_lidar")  # Gazebo Classic's and gz's


def _sensor_kind(robot, frames) -> str | None:
    """What the file says the sensor of an optical frame is: "camera" or "lidar" when a
    Gazebo sensor of those types sits on one of ``frames`` (its body, the optical frame) or
    stamps its data with one, the first found; None when none says (the message then names
    the frame alone: elkapod's ``lidar_optical``, a gpu_lidar's, was called a camera link)."""
    for gazebo, sensor in gazebo_sensors(robot):
        kind = (sensor.get("type") or "").lower()
        said = "camera" if kind in CAMERA_SENSORS else "lidar" if kind in LIDAR_SENSORS else None
        if said is None:
            continue
        stamped = {(element.text or "").strip().lstrip("/") for tag in CAMERA_FRAME_TAGS
                   for element in sensor.iter(tag)}
        if gazebo.get("reference") in frames or stamped & set(frames):
            return said
    return None


def _turn_said(robot, joint, direct: bool, turn) -> str:
    """How an optical frame's turn from its body frame is said: the ``rpy`` of its joint's
    ``<origin>`` as the file writes it (``rpy="3.14159265359  0 0"``, which a search of the
    file finds, not the -3.142 it was printed as), with its value when written with xacro
    expressions; when frames lie between the two (``direct`` false), the turn in all,
    computed, and the joint's own as written."""
    origin = robot.child(joint, "origin")
    value = origin.get("rpy") if origin is not None else None
    written = _written(robot, origin, "rpy") if value is not None else None
    if written is None:
        own = "no rpy (0 0 0)"
    else:
        values, problem = parse_numbers(value, 3)
        expanded = "" if problem or "$" not in written else \
            f" (= {' '.join(number(v, 4) for v in values)})"
        own = f"rpy=\"{written}\"{expanded}"
    if direct:
        return own
    return (f"rpy=\"{_rpy_text(turn)}\" in all (computed through the frames between; its "
            f"joint '{joint.get('name')}' writes {own})")


def _written(robot, element, attribute: str) -> str:
    """``attribute`` of ``element`` as the file writes it (a xacro expression as written),
    else as loaded."""
    from urdftool.lint.fixes.tags import Unfixable, source_tag  # (only for a finding)

    found = source_tag(robot, element)
    if isinstance(found, Unfixable) or attribute not in found[1].attributes:
        return element.get(attribute)
    return " ".join(found[1].attributes[attribute][2].split("\n"))


def _pitched_view(turn) -> float | None:
    """The angle [deg] by which an optical frame turned ``turn`` from its camera link looks
    up or down from the link's x axis, when that is all that differs from REP 103's turn (a
    rotation about the image's x axis) by an angle no slip gives (not a multiple of 90
    degrees): Bit-Bots' Pi Plus writes its head camera's 30-degree tilt into the optical joints
    (rpy="-2.093 0 -1.57"), its camera_link being a CAD part on the head. Else None."""
    (d00, _, _), (_, d11, _), (_, d21, _) = mat3.multiply(mat3.transpose(OPTICAL), turn)
    if d00 < math.cos(ANGLE_TOLERANCE):
        return None
    angle = math.degrees(math.atan2(d21, d11))
    off = abs(angle) % 90.0
    return None if min(off, 90.0 - off) <= math.degrees(ANGLE_TOLERANCE) else abs(angle)


FOOTPRINT_TOLERANCE = 0.01  # [m]: tyres squash and casters clear by millimetres (the PR2's
# wheels are 4.4 mm above its footprint); a slip is a wheel radius or a missing offset
BELOW_TOLERANCE = 0.001  # [m]: base_footprint is right below base_link, to the millimetre


def _ground_points(robot, frame=None, tags=("collision",)) -> list[tuple[str, float]]:
    """(link, lowest z in ``frame``, the root frame by default) of each wheel and caster whose
    ``tags`` geometry (the first it has) can be measured: of its body, the link and the links
    fixed below it (:func:`~urdftool.physics.wheels.wheel_body`)."""
    found = []
    for wheel in wheels(robot):
        heights = [lowest(robot, member, frame, tags) for member in wheel_body(robot, wheel.link)]
        if heights and all(reach.complete for _, reach in heights) and \
                any(z is not None for z, _ in heights):
            found.append((wheel.link, min(z for z, _ in heights if z is not None)))
    return found


def _robot_lowest(robot, frame) -> tuple[str, float] | None:
    """(link, its lowest z in ``frame``) of the lowest collision geometry of the whole robot,
    None when some of it cannot be measured."""
    best = None
    for name in robot.links:
        if name == FOOTPRINT:
            continue
        z, reach = lowest(robot, name, frame)
        if not reach.complete:
            return None
        if z is not None and (best is None or z < best[1]):
            best = (name, z)
    return best


@rule("U418", "footprint-not-on-ground", Severity.WARNING)
def footprint_not_on_ground(robot):
    """``base_footprint`` is not on the ground right below ``base_link`` (REP 120, REP 105).

    Navigation (costmaps, the footprint polygon, odometry) takes ``base_footprint`` for the
    robot's projection on the floor: its origin right below ``base_link`` (same x and y, to
    the millimetre), level with it, and at the height of what the robot stands on at the zero
    pose: its wheels and casters when it has them (:mod:`urdftool.physics.wheels`); without
    any, its collision geometry must not reach below the footprint (whatever it stands on may
    not be drawn). Off by more than 1 cm (tyres squash and casters
    clear by millimetres: the PR2's wheels are 4.4 mm above its footprint; a slip is a wheel
    radius or a missing offset) is reported. Skipped when some
    collision geometry cannot be measured.

    Bad: ``base_footprint`` 0.1 m above the wheels' contact with the ground
    Good: ``<joint name="base_footprint_joint"><origin xyz="0 0 ${wheel_radius}"/>`` with
    ``base_link`` as its child
    """
    footprint_frame = footprint(robot)
    if footprint_frame is None:
        return
    frames = link_frames(robot)
    where = _footprint_joint(robot)
    if "base_link" in frames:
        offset, turn = relative(footprint_frame, frames["base_link"])
        if math.hypot(offset[0], offset[1]) > BELOW_TOLERANCE or offset[2] < -BELOW_TOLERANCE:
            yield where, (f"'{FOOTPRINT}' is not right below 'base_link': base_link is at "
                          f"({numbers(offset, 4, ', ', floor=MILLIMETRE)}) m in it; the footprint is "
                          "base_link's projection on the floor (x = y = 0)")
        elif _angle(mat3.IDENTITY, turn) > ANGLE_TOLERANCE:
            tilt = math.degrees(_angle(mat3.IDENTITY, turn))
            yield where, (f"'{FOOTPRINT}' is turned {number(tilt, 3)} degrees from 'base_link'; it is "
                          "base_link's projection on the floor, with the same axes")
    if wheels(robot):
        ground = _ground_points(robot, footprint_frame, ("collision", "visual"))
        if not ground:
            return  # wheels drawn with nothing to measure: the ground is not known
        name, z = min(ground, key=lambda item: item[1])
        what = f"the lowest of its wheels and casters ('{name}')"
    else:
        found = _robot_lowest(robot, footprint_frame)
        if found is None:
            return
        name, z = found
        what = f"its lowest point (on '{name}')"
    if z > FOOTPRINT_TOLERANCE and not wheels(robot):
        return  # the robot's lowest geometry is above the footprint: it may stand on wheels
        # or feet the description does not draw; only geometry below the floor is certain
    if abs(z) > FOOTPRINT_TOLERANCE:
        side = "above" if z < 0 else "below"
        yield where, (f"'{FOOTPRINT}' is {number(abs(z) * 1000, places=0)} mm {side} {what} at the zero pose; "
                      "the footprint is on the ground the robot stands on (REP 120): move it "
                      f"{'down' if z < 0 else 'up'} by {number(abs(z), 4)} m")


CONTACT_TOLERANCE = FOOTPRINT_TOLERANCE


@rule("U419", "wheel-not-touching-ground", Severity.WARNING)
def wheel_not_touching_ground(robot):
    """A wheel or caster does not touch the ground at the zero pose.

    The ground is ``base_footprint``'s plane (REP 120) when the robot's wheels stand on it,
    else the lowest point of its wheels (of its casters, without wheels; a caster reaching
    below the wheels is U617's). A wheel whose lowest collision point
    (meshes included) is more than 1 cm above it carries no load in simulation: a drive wheel
    spins in the air, a robot on a hovering caster tips onto it. Wheels and casters are
    identified by a diff drive or by their names (never arms, grippers or feet); casters in a
    fork are judged by their wheels. A wheel whose axle stands up (within 45 degrees of the
    ground's normal) rolls on no ground below it: it is not judged, nor taken as the ground
    (a CAD export modelled with y up, fusion2urdf's Basic_Robot: its wheels, side by side
    along z, were said to hover 63 mm above each other). A wheel is the body that rolls: its
    link and the links fixed below it (Upkie's rotor, hub and tyre, each named a wheel, were
    said to hover above the tyre).

    Bad: a caster sphere of radius 0.02 whose centre is 0.03 m above the ground
    Good: the caster's centre at its radius above the ground
    """
    plane, base, source = footprint(robot), None, ""
    upright = _upright_axles(robot, plane)
    ground = [(name, z) for name, z in _ground_points(robot) if name not in upright]
    if not ground:
        return
    heights = {name: z for name, z in ground}
    if plane is not None:
        placed = {name: z for name, z in _ground_points(robot, plane) if name in heights}
        if placed and abs(min(placed.values())) <= FOOTPRINT_TOLERANCE:
            heights, base, source = placed, 0.0, f"'{FOOTPRINT}' (the ground)"
    if base is None:
        # the wheels stand on the ground; a caster below them lifts them (U617 says so)
        kinds = {wheel.link: wheel.kind for wheel in wheels(robot)}
        rolling = [z for name, z in heights.items() if kinds.get(name) == "wheel"]
        base = min(rolling or heights.values())
        source = "the lowest wheel" if rolling else "the lowest caster"
    parents = parent_joints(robot)
    for wheel in wheels(robot):
        if wheel.link not in heights:
            continue
        gap = heights[wheel.link] - base
        if gap > CONTACT_TOLERANCE:
            where = _joint_or_link(robot, wheel.link)
            fix = (f"lower it by {number(gap, 4)} m, or give it its real size"
                   if next(_off_axle(robot, wheel), None) is None else
                   "its collision cylinder is turned off the axle (U420): turn it, and measure "
                   "again")
            yield where, (f"{wheel.kind} '{wheel.link}' is {number(gap * 1000, places=0)} mm above {source} at "
                          f"the zero pose: it does not touch the ground ({fix})")


def _upright_axles(robot, plane) -> set[str]:
    """The wheels whose axle is within 45 degrees of the ground's normal (``plane``'s z, the
    root frame's without one) at the zero pose: they cannot roll on that ground."""
    up = mat3.apply(plane[1], (0.0, 0.0, 1.0)) if plane is not None else (0.0, 0.0, 1.0)
    found = set()
    for wheel in wheels(robot):
        axle = world_axle(robot, wheel)
        if axle is not None and abs(mat3.dot(axle, up)) > math.cos(math.radians(45.0)):
            found.add(wheel.link)
    return found


AXLE_TOLERANCE = math.radians(5.0)


@rule("U420", "wheel-collision-off-axle", Severity.WARNING)
def wheel_collision_off_axle(robot):
    """A wheel's collision cylinder is not turned to its axle.

    A URDF cylinder's axis is its z axis; a wheel rolls about its joint axis. When the two
    differ (a ``rpy="1.5708 0 0"`` given to the visual but not the collision, or to neither)
    the simulated wheel stands on its flat face or rolls on an edge. Within 5 degrees.

    Bad: ``<axis xyz="0 1 0"/>`` and a collision ``<cylinder>`` with ``rpy="0 0 0"``
    Good: the collision ``<origin rpy="1.5708 0 0"/>``, so the cylinder's z is the joint's y
    """
    for wheel in wheels(robot):
        link = robot.links[wheel.link]
        for piece, along, angle in _off_axle(robot, wheel):
            yield _collision_of(link, piece), (
                f"wheel '{wheel.link}': its collision cylinder's axis "
                f"({numbers(along, 3, ', ')}) is {number(math.degrees(angle), places=0)} "
                f"degrees from the axle of joint '{wheel.joint.get('name')}' "
                f"({numbers(wheel.axle, 3, ', ')}); the simulated wheel does "
                "not roll on its rim (turn the collision origin so the cylinder's z is the "
                "axle)")


def _off_axle(robot, wheel):
    """(piece, its axis, its angle to the axle) of each collision cylinder of ``wheel`` more
    than 5 degrees off its axle; none for a wheel without an axle (welded in place)."""
    if wheel.axle is None:
        return
    for piece in link_reach(robot, robot.links[wheel.link], ("collision",)).pieces:
        if piece.kind != "cylinder":
            continue
        along = tuple(piece.rotation[i][2] for i in range(3))
        angle = math.acos(min(1.0, abs(mat3.dot(along, wheel.axle))))
        if angle > AXLE_TOLERANCE:
            yield piece, along, angle


def _collision_of(link, piece):
    """The ``<collision>`` whose cylinder ``piece`` is (the first cylinder, if not found)."""
    cylinders = [c for c in link.findall("collision") if c.find("geometry/cylinder") is not None]
    return cylinders[0] if cylinders else link


DISC = 0.6  # width over diameter below which a wheel is a disc: axial moment the largest
AXIAL_SLACK = 0.9  # the axial moment may be 10 % below a transverse one (hubs, rounding)


def _perpendicular(axle) -> tuple:
    """Two unit vectors perpendicular to ``axle`` and to each other."""
    helper = (1.0, 0.0, 0.0) if abs(axle[0]) < 0.9 else (0.0, 1.0, 0.0)
    u = mat3.cross(axle, helper)
    norm = math.sqrt(mat3.dot(u, u))
    u = tuple(v / norm for v in u)
    return u, mat3.cross(axle, u)


@rule("U421", "wheel-inertia-off-axle", Severity.WARNING)
def wheel_inertia_off_axle(robot):
    """A wheel's moment of inertia about its axle is not its largest, though its shape is a disc.

    A disc's moment about its axis is the largest (m r^2 / 2, against m (3 r^2 + w^2) / 12
    about a diameter) whenever it is narrower than it is round. A declared tensor whose
    largest moment is about another axis was written for a cylinder standing along z while
    the wheel turns about y (or x): the simulated wheel spins up and brakes with the wrong
    inertia. Judged for wheels whose collision (or visual) geometry is narrower along the axle
    than 0.6 times its diameter; the axial moment may be up to 10 % below a transverse one.

    Bad: a wheel turning about y with ``ixx="0.001" iyy="0.001" izz="0.002"``
    Good: ``ixx="0.001" iyy="0.002" izz="0.001"``
    """
    for wheel in wheels(robot):
        if wheel.axle is None:
            continue
        link = robot.links[wheel.link]
        properties = declared(link)
        if properties is None or not properties.mass > 0:
            continue
        reach = link_reach(robot, link, ("collision",))
        if not reach.pieces:
            reach = link_reach(robot, link, ("visual",))
        if not reach.pieces or not reach.complete:
            continue
        axle = wheel.axle
        u, v = _perpendicular(axle)
        width = reach.support(axle) + reach.support(tuple(-a for a in axle))
        diameter = min(reach.support(d) + reach.support(tuple(-a for a in d)) for d in (u, v))
        if not (diameter > 0 and width < DISC * diameter):
            continue
        tensor = properties.inertia
        axial = mat3.dot(axle, mat3.apply(tensor, axle))
        uu, vv = mat3.dot(u, mat3.apply(tensor, u)), mat3.dot(v, mat3.apply(tensor, v))
        uv = mat3.dot(u, mat3.apply(tensor, v))
        across = (uu + vv) / 2 + math.hypot((uu - vv) / 2, uv)  # the largest about a diameter
        if axial < AXIAL_SLACK * across:
            yield link.find("inertial/inertia"), (
                f"wheel '{wheel.link}': its moment about the axle "
                f"({', '.join(f'{number(a, 3)}' for a in axle)}) is {number(axial, 3)} kg m^2, below "
                f"{number(across, 3)} about a diameter, but the wheel is a disc ({number(width * 1000, places=0)} mm "
                f"wide, {number(diameter * 1000, places=0)} mm across): the largest moment belongs on the axle "
                "(was the tensor written for a cylinder along z?)")


def _joint_or_link(robot, name: str):
    """The joint whose child link ``name`` is, else the link itself (a root)."""
    joint = parent_joints(robot).get(name)
    return joint if joint is not None else robot.links[name]


def _footprint_joint(robot):
    """The joint that places ``base_footprint``: the one whose child it is, else the one
    joining it to ``base_link``, else the first hanging from it, else the link itself."""
    joint = parent_joints(robot).get(FOOTPRINT)
    if joint is not None:
        return joint
    below = child_joints(robot).get(FOOTPRINT, [])
    for joint in below:
        if robot.ends()[joint]["child"][1] == "base_link":
            return joint
    return below[0] if below else robot.links[FOOTPRINT]
