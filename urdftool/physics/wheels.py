"""Which links of a robot are wheels and casters, their axles, and where the ground is.

A **wheel** is the child link of a joint that rolls it:

- a joint a differential drive names (a Gazebo diff-drive plugin's left/right joints, a
  diff_drive_controller's ``left_wheel_names``/``right_wheel_names``): certain;
- a continuous or revolute joint whose own name or child link's name has a wheel word
  (``wheel``, ``tire``, ``tyre`` as a word part: ``left_wheel_joint``, ``wheel_fl``,
  ``WheelLeft``), and none of the words of a joint that steers, hangs or holds a wheel
  (``steer``, ``suspension``, ``hinge``, ``pivot``, ``swivel``, ``hub_mount``...) nor of a
  wheel that is not a ground wheel (``reaction``, ``fly``, ``momentum``, ``steering_wheel``);
- a fixed joint whose child link's name says so: a wheel welded in place (a simplified model)
  still stands on the ground, but has no axle to judge; unless it hangs from a wheel through
  fixed joints: then it is a part of that wheel (a hub or tyre fixed to the rolling link), and
  the wheel's body (:func:`wheel_body`) is what touches the ground; nor when a wheel hangs
  below it: then it holds that wheel (a wheel's motor or carrier, ``left_wheel_motor_Link``),
  as a caster's fork does.

A **caster** is a link whose name has ``caster``/``castor``, that carries no wheel below it
(a caster's swivel fork is not what touches the ground; the wheel in it is), hangs below no
wheel (a caster wheel's hubcap is part of the wheel) and is not named as a caster's mount
(``base``, ``mount``, ``holder``, ``plate``, ``bracket``, ``support``, ``housing``, ``fork``,
``swivel``, ``rotation``, ``hub``, ``cap``: andino's caster_base_link is the block beside the
wheel's swivel). Names decide, not
shapes alone: a continuous joint with a cylinder is also a PR2 wrist or a spinning lidar, and
no arm, gripper or foot is named a wheel. Legged robots' feet are never wheels or casters.

The **ground** (REP 120): the plane z = 0 of ``base_footprint`` when the robot has one, else
the lowest point of its wheels and casters (in the root frame, z up: REP 103). Everything is
at the zero pose (:mod:`urdftool.physics.frames`).
"""

from __future__ import annotations

import re

from urdftool.description.urdf import VARIABLE
from urdftool.physics import mat3
from urdftool.physics.frames import axis, child_joints, joint_frames, link_frames, parent_joints
from urdftool.physics.support import Reach, link_reach
from urdftool.records import Frozen

_WHEEL = re.compile(r"(?:^|[^a-z])(?:wheels?|tires?|tyres?)(?:$|[^a-z])")
_NOT_WHEEL = re.compile(r"steer|suspension|hinge|pivot|swivel|mount|reaction|momentum|fly|"
                        r"knuckle|arm|fork|rocker|bogie|axle_joint_pos")
_CASTER = re.compile(r"caster|castor")
_NOT_CASTER = re.compile(r"base|mount|holder|plate|bracket|support|housing|fork|swivel|"
                         r"rotation|hub|cap")
FOOTPRINT = "base_footprint"


_CAMEL = re.compile(r"(?<=[a-z0-9])(?=[A-Z])")


def _words(name: str) -> str:
    """A name lower-cased with camel case split (``WheelLeft`` -> ``wheel_left``)."""
    return _CAMEL.sub("_", name).lower()


class Wheel(Frozen):
    """A wheel or caster: ``link`` the rolling (or sliding) link, ``joint`` the joint whose
    child it is (None for a caster that is the root), ``kind`` "wheel" or "caster", ``why``:
    what identified it, ``axle``: the unit joint axis in the link's frame (None for a fixed
    joint, or a caster)."""

    link: str
    joint: object
    kind: str
    why: str
    axle: mat3.Vector | None

    __slots__ = ("link", "joint", "kind", "why", "axle")

    def __init__(self, link: str, joint: object, kind: str, why: str,
                 axle: mat3.Vector | None) -> None:
        set_field = object.__setattr__
        set_field(self, "link", link)
        set_field(self, "joint", joint)
        set_field(self, "kind", kind)
        set_field(self, "why", why)
        set_field(self, "axle", axle)


def wheels(robot) -> list[Wheel]:
    """Every wheel and caster of the robot, in document order of their links; once per robot."""
    return robot.memo(wheels, lambda: _identify(robot))


def driven_joints(robot) -> set[str]:
    """The joints a differential drive names (Gazebo plugins and diff_drive_controller)."""
    from urdftool.description.actuation import diff_drive_wheels

    named = set(diff_drive_wheels(robot))
    try:
        from urdftool.description.controllers import controllers, names_at
    except ImportError:  # pragma: no cover - the description always has it
        return named
    for controller in controllers(robot):
        cls = controller.cls
        if cls is None or cls.package != "diff_drive_controller":
            continue
        for key in ("left_wheel_names", "right_wheel_names", "left_wheel", "right_wheel"):
            named.update(name for name, _ in names_at(controller.params or {}, key))
    return named


def _identify(robot) -> list[Wheel]:
    parents = parent_joints(robot)
    driven = driven_joints(robot)
    found: dict[str, Wheel] = {}
    ends, kinds = robot.ends(), robot.kinds()
    for name, joint in robot.joints.items():
        child = ends[joint]["child"][1] if joint in ends else None
        if child is None or child not in robot.links or parents.get(child) is not joint:
            continue
        kind = kinds[joint]
        moving = kind in VARIABLE and kind != "prismatic" and kind != "planar" \
            and kind != "floating"
        if name in driven:
            why = "a differential drive names it"
        elif moving and _named_wheel(name, child) or kind == "fixed" and _named_wheel(child):
            why = "its name"  # a fixed joint's name names the mount (caster_wheel_joint
            # holds the hubcap of a caster wheel): its child's name must say wheel
        else:
            continue
        found[child] = Wheel(child, joint, "wheel", why, axis(joint) if moving else None)
    children = child_joints(robot)
    for name in [name for name, wheel in found.items() if wheel.axle is None
                 and (_fixed_below(robot, name, found, parents)
                      or _carries_wheel(robot, name, found, children))]:
        # a part of the wheel above it (Upkie's hub and tyre on the rotor), or what holds the
        # wheel below it (a wheel-legged robot's left_wheel_motor_Link, fixed to the calf,
        # which the continuous left_wheel_joint turns the wheel on)
        del found[name]
    for name in robot.links:
        if name in found or not _CASTER.search(name.lower()) or _NOT_CASTER.search(_words(name)):
            continue
        if _carries_wheel(robot, name, found, children):
            continue  # the fork: the wheel below it touches the ground
        if _below_wheel(robot, name, found, parents):
            continue  # part of a wheel (a caster wheel's hubcap): the wheel is judged
        found[name] = Wheel(name, parents.get(name), "caster", "its name", None)
    order = {name: index for index, name in enumerate(robot.links)}
    return sorted(found.values(), key=lambda wheel: order.get(wheel.link, len(order)))


def _named_wheel(*names: str) -> bool:
    for name in names:
        lower = name.lower()  # _words(name) is it with "_" put in: without a wheel word in
        # it, _WHEEL finds none there (most names: not split, not searched)
        if "wheel" not in lower and "tire" not in lower and "tyre" not in lower:
            continue
        text = _words(name)
        if _WHEEL.search(text) and not _NOT_WHEEL.search(text.replace("wheel", " ")):
            return True
    return False


def _carries_wheel(robot, link: str, found: dict, children) -> bool:
    pending, seen = [link], set()
    while pending:
        current = pending.pop()
        if current in seen:
            continue
        seen.add(current)
        for joint in children.get(current, ()):
            child = robot.ends()[joint]["child"][1]
            if child in found and found[child].kind == "wheel":
                return True
            if child is not None:
                pending.append(child)
    return False


def _fixed_below(robot, link: str, found: dict, parents) -> bool:
    """Whether ``link`` hangs from a wheel of ``found`` through fixed joints only: a part of
    that wheel's body."""
    seen, kinds = set(), robot.kinds()
    while link in parents and link not in seen and kinds.get(parents[link]) == "fixed":
        seen.add(link)
        link = robot.ends()[parents[link]]["parent"][1]
        if link in found:
            return True
    return False


def wheel_body(robot, link: str) -> list[str]:
    """A wheel's link and the links fixed below it (its hub, tyre, hubcap): the body that
    rolls, whose lowest point touches the ground. Not the links it is fixed to above: a wheel
    welded to the chassis (a simplified model) is not the chassis."""
    children, kinds, ends = child_joints(robot), robot.kinds(), robot.ends()
    body, seen = [link], {link}
    for current in body:
        for joint in children.get(current, ()):
            child = ends[joint]["child"][1] if joint in ends else None
            if kinds.get(joint) == "fixed" and child in robot.links and child not in seen:
                seen.add(child)
                body.append(child)
    return body


def _below_wheel(robot, link: str, found: dict, parents) -> bool:
    """Whether a wheel is above ``link`` in the tree."""
    seen = set()
    while link in parents and link not in seen:
        seen.add(link)
        link = robot.ends()[parents[link]]["parent"][1]
        if link in found and found[link].kind == "wheel":
            return True
    return False


class Ground(Frozen):
    """The ground plane: ``frame`` (position, rotation in the root frame) whose z = 0 plane it
    is; ``source``: "base_footprint" or "wheels"."""

    frame: tuple
    source: str

    __slots__ = ("frame", "source")

    def __init__(self, frame: tuple, source: str) -> None:
        set_field = object.__setattr__
        set_field(self, "frame", frame)
        set_field(self, "source", source)


def lowest(robot, link_name: str, frame=None,
           tags=("collision",)) -> tuple[float | None, Reach]:
    """(the lowest z [m] of a link's ``tags`` geometry (the first of them it has) in ``frame``
    (default: the root frame) at the zero pose, or None without measurable geometry; the
    reach measured)."""
    link = robot.links[link_name]
    for tag in tags:
        reach = link_reach(robot, link, (tag,))
        if reach.pieces or not reach.complete:
            break
    placed = link_frames(robot).get(link_name)
    if placed is None or not reach.pieces or not reach.complete:
        return None, reach
    position, rotation = placed
    if frame is not None:
        back = mat3.transpose(frame[1])
        position = mat3.apply(back, tuple(a - b for a, b in zip(position, frame[0])))
        rotation = mat3.multiply(back, rotation)
    down = tuple(-v for v in rotation[2])  # -z of the frame, in the link's axes
    return position[2] - reach.support(down), reach


def footprint(robot) -> tuple | None:
    """(position, rotation) of ``base_footprint`` in the root frame, None without one."""
    return link_frames(robot).get(FOOTPRINT) if FOOTPRINT in robot.links else None


def world_axle(robot, wheel: Wheel) -> mat3.Vector | None:
    """A wheel's axle in the root frame at the zero pose."""
    if wheel.axle is None or wheel.joint is None:
        return None
    frame = joint_frames(robot).get(wheel.joint.get("name"))
    return mat3.apply(frame[1], wheel.axle) if frame is not None else None
