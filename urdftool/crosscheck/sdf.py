"""The model ``gz sdf -p`` prints for a URDF (SDFormat 1.6 to 1.11), read back: its links,
masses and joints, and the links' positions by forward kinematics of its poses.

URDF conversion writes each link's ``<pose relative_to='JOINT'>`` and each joint's
``<pose relative_to='PARENT'>`` (1.7 and later), or poses in the model frame (1.6); a joint's
axis is in the joint frame unless ``expressed_in`` says otherwise. Lumped links are gone: they
are what ``dropped_links`` lists, beside the links left out for having no mass.
"""

from __future__ import annotations

import math

from lxml import etree

from urdftool.description.urdf import MOVING  # SDFormat names these joint types as URDF does


def _pose(element):
    """(xyz, rpy, relative_to) of an element's <pose>; zeros when it has none."""
    pose = element.find("pose") if element is not None else None
    if pose is None or not (pose.text or "").strip():
        return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0), pose.get("relative_to") if pose is not None \
            else None
    values = [float(v) for v in pose.text.split()]
    return tuple(values[:3]), tuple(values[3:6]), pose.get("relative_to")


def _matrix(xyz, rpy):
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), \
        math.sin(y)
    rotation = ((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
                (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
                (-sp, cp * sr, cp * cr))
    return rotation, tuple(xyz)


def _compose(a, b):
    (ra, ta), (rb, tb) = a, b
    rotation = tuple(tuple(sum(ra[i][k] * rb[k][j] for k in range(3)) for j in range(3))
                     for i in range(3))
    translation = tuple(sum(ra[i][k] * tb[k] for k in range(3)) + ta[i] for i in range(3))
    return rotation, translation


def _axis_motion(kind: str, axis, value: float):
    from urdftool.numbers import unit

    x, y, z = unit(axis) or axis  # scaled: an axis of 1e308 is a direction
    if kind == "prismatic":
        return ((1, 0, 0), (0, 1, 0), (0, 0, 1)), (x * value, y * value, z * value)
    c, s, t = math.cos(value), math.sin(value), 1 - math.cos(value)
    return ((t * x * x + c, t * x * y - s * z, t * x * z + s * y),
            (t * x * y + s * z, t * y * y + c, t * y * z - s * x),
            (t * x * z - s * y, t * y * z + s * x, t * z * z + c)), (0.0, 0.0, 0.0)


def model_summary(text: str, configurations) -> dict:
    """What crosscheck reports of the SDF ``text`` (see :mod:`urdftool.crosscheck.loaders`)."""
    # recover: the <gazebo> blocks copied into it may use namespace prefixes it never declares
    root = etree.fromstring(text.encode("utf-8"), etree.XMLParser(
        resolve_entities=False, no_network=True, recover=True, huge_tree=False))
    model = root.find("model")
    if model is None:
        return {"loaded": False, "error": "no <model> in the converted SDF"}
    links = {link.get("name"): link for link in model.findall("link")}
    joints = {joint.get("name"): joint for joint in model.findall("joint")}
    inertia, mass = {}, 0.0
    for name, link in links.items():
        inertial = link.find("inertial")
        value = float(inertial.findtext("mass", "0")) if inertial is not None else 0.0
        moments = [float(inertial.findtext(f"inertia/{k}", "0")) for k in ("ixx", "iyy", "izz")] \
            if inertial is not None else [0.0, 0.0, 0.0]
        inertia[name] = {"mass": value, "inertia": moments}
        mass += value
    parent_of = {j.findtext("child"): j for j in joints.values()}
    movable = [j for j in joints.values() if j.get("type") in MOVING]
    floating = not any(j.findtext("parent") == "world" for j in joints.values())
    frames = []
    for configuration in configurations:
        placed: dict = {}

        def place(name):
            """The link's frame in the model's, its parents' placed first: walked up in a loop
            (a chain of 3,000 links is as deep as it is long), at most one step a link."""
            chain, parent, depth = [], None, 0
            while name not in placed and depth <= len(links) + 1:
                chain.append(name)
                joint = parent_of.get(name)
                if joint is None or joint.findtext("parent") in ("world", None):
                    break
                name, depth = joint.findtext("parent"), depth + 1
            else:
                parent = placed.get(name)
            for name in reversed(chain):
                joint = parent_of.get(name)
                xyz, rpy, _ = _pose(links.get(name))
                own = _matrix(xyz, rpy)
                jxyz, jrpy, _ = _pose(joint)
                if joint is None or joint.findtext("parent") in ("world", None):
                    placed[name] = _compose(_matrix(jxyz, jrpy), own) if joint is not None else own
                else:
                    frame = _compose(parent, _matrix(jxyz, jrpy))
                    kind = joint.get("type")
                    if kind in MOVING:
                        axis = [float(v) for v in (joint.findtext("axis/xyz") or "1 0 0").split()]
                        frame = _compose(frame, _axis_motion(kind, axis,
                                                             configuration.get(joint.get("name"), 0.0)))
                    placed[name] = _compose(frame, own)
                parent = placed[name]
            return parent

        frames.append({name: list(place(name)[1]) for name in links})
    limits = {}
    for joint in movable:
        lower, upper = joint.findtext("axis/limit/lower"), joint.findtext("axis/limit/upper")
        limits[joint.get("name")] = [float(lower), float(upper)] if lower and upper else None
    return {"loaded": True, "error": None, "mass": mass, "joints": limits,
            "dof": len(movable) + (6 if floating else 0), "floating_base": floating,
            "links": list(links), "frames": frames, "inertia": inertia}
