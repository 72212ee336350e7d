"""What changed between two robot descriptions, element by element, as data.

Each link, joint and robot-level material is read into a flat table of fields (``origin.xyz``,
``limit.upper``, ``inertial.mass``, ``visual[0].size``, ...) holding numbers or words, with the
URDF defaults filled in. Two descriptions are compared field by field, so formatting, comments,
attribute order, ``0.10`` against ``0.1`` and an ``<origin>`` written as its default are no
change. Renamed links and joints are recognised by their place in the tree (the same parent
and a joint at the same origin, or the same children), not reported as removed and added.
"""

from __future__ import annotations

import math

from dataclasses import dataclass, field

from urdftool.description.values import parse_numbers
from urdftool.numbers import length

# what a field's numbers are measured in, by the last part of its name
UNITS = {"xyz": "m", "rpy": "rad", "mass": "kg", "ixx": "kg m^2", "ixy": "kg m^2",
         "ixz": "kg m^2", "iyy": "kg m^2", "iyz": "kg m^2", "izz": "kg m^2", "size": "m",
         "radius": "m", "length": "m"}
RELATIVE = ("mass", "ixx", "ixy", "ixz", "iyy", "iyz", "izz")  # reported in percent too


@dataclass
class Change:
    """One difference.

    kind: 'added', 'removed', 'renamed' or 'changed'
    element: 'link', 'joint' or 'material' (companions: 'controller', 'group',
        'disable_collisions')
    name: its name in the new description (the old one when removed)
    field: what changed ('' for a whole element), e.g. 'origin.xyz', 'inertial.mass'
    old, new: the values (numbers as floats or tuples of floats, words as text; None: absent)
    old_name: the old name of a renamed element
    delta: how far apart numeric values are (the norm of the difference), in ``unit``
    percent: the relative change of a mass or an inertia entry, in %
    """

    kind: str
    element: str
    name: str
    field: str = ""
    old: object = None
    new: object = None
    old_name: str | None = None
    delta: float | None = None
    percent: float | None = None
    unit: str = ""


@dataclass
class NotCompared:
    """A file of the same place beside both robots (an SRDF, a controller YAML) that a side
    could not read or parse, so that neither equal nor changed can be said of it.

    element: 'srdf' or 'controllers'
    name: its path relative to the robot's folder (the new side's)
    old, new: why that side's file was not read or parsed (None: it was, or it has none)
    """

    element: str
    name: str
    old: str | None
    new: str | None


@dataclass
class Renames:
    """Old name -> new name of renamed links and joints (unchanged names are not listed)."""

    links: dict[str, str] = field(default_factory=dict)
    joints: dict[str, str] = field(default_factory=dict)

    def link(self, name):
        return self.links.get(name, name)

    def joint(self, name):
        return self.joints.get(name, name)


def _numbers(text, count=None, default=None):
    if text is None:
        return default
    values, _ = parse_numbers(text, count)
    if values is None:
        return text.strip()  # unreadable: compared as written, after trimming
    return tuple(values) if len(values) != 1 or count == 3 else values[0]


def _origin(fields: dict, prefix: str, element) -> None:
    found = element.find("origin") if element is not None else None
    fields[f"{prefix}origin.xyz"] = _numbers(found.get("xyz") if found is not None else None,
                                             3, (0.0, 0.0, 0.0))
    fields[f"{prefix}origin.rpy"] = _numbers(found.get("rpy") if found is not None else None,
                                             3, (0.0, 0.0, 0.0))


def joint_fields(joint, renames: Renames | None = None) -> dict:
    """A ``<joint>`` as {field: value}; parent and child through ``renames`` (old names -> new)."""
    renames = renames or Renames()
    fields = {"type": joint.get("type")}
    for end in ("parent", "child"):
        element = joint.find(end)
        fields[end] = renames.link(element.get("link")) if element is not None else None
    _origin(fields, "", joint)
    axis = joint.find("axis")
    if joint.get("type") not in ("fixed", "floating"):
        fields["axis"] = _numbers(axis.get("xyz") if axis is not None else None, 3,
                                  (1.0, 0.0, 0.0))
    for tag, attributes, defaults in (
            ("limit", ("lower", "upper", "effort", "velocity"), (0.0, 0.0, None, None)),
            ("mimic", ("joint", "multiplier", "offset"), (None, 1.0, 0.0)),
            ("dynamics", ("damping", "friction"), (0.0, 0.0)),
            ("safety_controller", ("soft_lower_limit", "soft_upper_limit", "k_position",
                                   "k_velocity"), (0.0, 0.0, 0.0, None)),
            ("calibration", ("rising", "falling"), (None, None))):
        element = joint.find(tag)
        if element is None:
            continue
        for attribute, default in zip(attributes, defaults):
            if attribute == "joint":
                fields["mimic.joint"] = renames.joint(element.get("joint"))
            else:
                fields[f"{tag}.{attribute}"] = _numbers(element.get(attribute), None, default)
    return fields


def _colours(robot) -> dict[str, object]:
    """Robot-level materials: name -> rgba (or texture file name)."""
    found = {}
    for material in robot.children("material"):
        found.setdefault(material.get("name"), _material_value(material))
    return found


def _material_value(material):
    colour = material.find("color")
    if colour is not None:
        return _numbers(colour.get("rgba"), 4)
    texture = material.find("texture")
    return texture.get("filename") if texture is not None else None


def link_fields(link, colours: dict) -> dict:
    """A ``<link>`` as {field: value}: its inertial, and each visual and collision in order
    (shape, sizes, mesh file and scale, origin; a visual's material name and its colour)."""
    fields = {}
    inertial = link.find("inertial")
    if inertial is not None:
        mass = inertial.find("mass")
        fields["inertial.mass"] = _numbers(mass.get("value") if mass is not None else None, 1)
        _origin(fields, "inertial.", inertial)
        inertia = inertial.find("inertia")
        for name in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"):
            fields[f"inertial.{name}"] = _numbers(
                inertia.get(name) if inertia is not None else None, 1)
    for kind in ("visual", "collision"):
        for index, element in enumerate(link.findall(kind)):
            prefix = f"{kind}[{index}]."
            _origin(fields, prefix, element)
            geometry = element.find("geometry")
            shape = next((child for child in geometry if isinstance(child.tag, str)), None) \
                if geometry is not None else None
            fields[prefix + "shape"] = shape.tag if shape is not None else None
            if shape is not None:
                for attribute, count in (("size", 3), ("radius", 1), ("length", 1),
                                         ("filename", None), ("scale", 3)):
                    if attribute == "filename":
                        if shape.get("filename") is not None:
                            fields[prefix + "filename"] = shape.get("filename")
                    elif shape.get(attribute) is not None or (
                            attribute == "scale" and shape.tag == "mesh"):
                        fields[prefix + attribute] = _numbers(shape.get(attribute), count,
                                                              (1.0, 1.0, 1.0))
            material = element.find("material") if kind == "visual" else None
            if material is not None:
                fields[prefix + "material"] = material.get("name")
                own = _material_value(material)
                fields[prefix + "colour"] = own if own is not None else \
                    colours.get(material.get("name"))
    return fields


def same_value(old, new, tolerance: float = 0.0) -> bool:
    """Whether a field holds the same value on both sides, numbers within ``tolerance``: the
    one judge of "changed" for every field compared (the URDF's, the companions' keys). A
    ``nan`` is the same as a ``nan`` (the same text, read twice: a file compared with itself
    has no change; ``nan != nan`` said it had)."""
    if isinstance(old, float) and isinstance(new, float):
        return abs(old - new) <= tolerance or old == new or (math.isnan(old) and math.isnan(new))
    if isinstance(old, tuple) and isinstance(new, tuple) and len(old) == len(new) and \
            all(isinstance(x, float) for x in old + new):
        return all(same_value(a, b, tolerance) for a, b in zip(old, new))
    if isinstance(old, tuple) and isinstance(new, tuple):  # a YAML list of mixed scalars
        return len(old) == len(new) and all(same_value(a, b) for a, b in zip(old, new))
    return old == new


def percent_change(old: float, new: float) -> float | None:
    """``new`` relative to ``old`` [%], or None where that is past what a float holds (2 kg
    -> 1e308 kg was "+inf %"): the one percent of a change, of a field and of the mass."""
    import math

    percent = 100.0 * (new - old) / abs(old)  # (Python's floats: inf, never an exception)
    return percent if math.isfinite(percent) else None


def _numeric_change(change: Change) -> Change:
    old, new = change.old, change.new
    last = change.field.rpartition(".")[2]
    change.unit = UNITS.get(last, "")
    if isinstance(old, float) and isinstance(new, float):
        change.delta = new - old
        if last in RELATIVE and old:
            change.percent = percent_change(old, new)
    elif isinstance(old, tuple) and isinstance(new, tuple) and len(old) == len(new) and \
            all(isinstance(x, float) for x in old + new):
        change.delta = length([a - b for a, b in zip(old, new)])
    return change


def _readable(value) -> bool:
    return isinstance(value, tuple) and len(value) == 3 and \
        all(isinstance(x, float) and math.isfinite(x) for x in value)


def turn(key: str, old, new) -> float | None:
    """The angle [rad] between two values of a field that is a rotation (an ``rpy``: its
    triples are compared as the rotations they make, ``0 0 3.14159265`` and ``3.14159265
    3.14159265 0`` being one) or a direction (a joint's ``axis``: ``0 0 2`` is ``0 0 1``);
    None for any other field, or a value that is not three finite numbers (or a zero axis):
    compared as written."""
    if not (key == "axis" or key.endswith("rpy")) or not (_readable(old) and _readable(new)):
        return None
    from urdftool.physics import mat3

    if key == "axis":
        if not any(old) or not any(new):
            return None
        old, new = ([x / length(v) for x in v] for v in (old, new))  # (no overflow: 1e200)
        return math.atan2(length(mat3.cross(old, new)), mat3.dot(old, new))
    import numpy as np

    from urdftool.kinematics.transforms import rotation_angle_between

    return float(rotation_angle_between(np.array(mat3.rpy_matrix(old)),
                                        np.array(mat3.rpy_matrix(new))))


INERTIA_FIELDS = ("inertial.origin.rpy", "inertial.ixx", "inertial.ixy", "inertial.ixz",
                  "inertial.iyy", "inertial.iyz", "inertial.izz")


def _tensor(fields: dict):
    """A link's inertia tensor [kg m^2] in the link frame (its ``<inertial>``'s turned by the
    inertial's rpy), or None when a number of it is missing or unread."""
    from urdftool.physics import mat3

    values = [fields.get(key) for key in INERTIA_FIELDS]
    rpy, (ixx, ixy, ixz, iyy, iyz, izz) = values[0], values[1:]
    if not _readable(rpy) or not all(isinstance(v, float) and math.isfinite(v)
                                     for v in values[1:]):
        return None
    return mat3.rotate(((ixx, ixy, ixz), (ixy, iyy, iyz), (ixz, iyz, izz)),
                       mat3.rpy_matrix(rpy))


def _same_inertia(old: dict, new: dict, tolerance: float) -> bool:
    """Whether two links' inertia is the same tensor in the link frame, however each writes it
    (the principal moments along turned axes, or the full tensor unturned: Pinocchio, Gazebo
    and MuJoCo see one body), entries within ``tolerance`` (and the rounding of the turn)."""
    tensors = _tensor(old), _tensor(new)
    if tensors[0] is None or tensors[1] is None:
        return False
    rounding = 1e-12 * max(abs(x) for tensor in tensors for row in tensor for x in row)
    return all(abs(a - b) <= tolerance + rounding
               for rows in zip(*tensors) for a, b in zip(*rows))


def compare_fields(element: str, name: str, old: dict, new: dict, tolerance: float,
                   old_name: str | None = None) -> list[Change]:
    changes = []
    for key in list(old) + [k for k in new if k not in old]:
        a, b = old.get(key), new.get(key)
        angle = turn(key, a, b)
        if angle is not None:
            if angle > tolerance:
                changes.append(Change("changed", element, name, key, a, b, old_name,
                                      delta=angle, unit="rad"))
        elif not same_value(a, b, tolerance):
            changes.append(_numeric_change(Change("changed", element, name, key, a, b,
                                                  old_name)))
    return changes


def _parent_joints(robot) -> dict[str, object]:
    """Child link -> the joint whose child it is (the first)."""
    found = {}
    for joint in robot.joints.values():
        child = joint.find("child")
        if child is not None:
            found.setdefault(child.get("link"), joint)
    return found


def _children(robot) -> dict[str, set]:
    found: dict[str, set] = {}
    for joint in robot.joints.values():
        parent, child = joint.find("parent"), joint.find("child")
        if parent is not None and child is not None:
            found.setdefault(parent.get("link"), set()).add(child.get("link"))
    return found


MAX_RENAME_WORK = 2_000_000  # removed links looked at over all passes of renames()


def _depths(robot) -> dict[str, int]:
    """Link -> its depth in the tree (roots 0; links in a cycle or unreachable: the count)."""
    parents = {child: joint.find("parent").get("link")
               for child, joint in _parent_joints(robot).items()
               if joint.find("parent") is not None}
    depths: dict[str, int] = {}
    for name in robot.links:
        chain, current = [], name
        while current in parents and current not in depths and len(chain) <= len(parents):
            chain.append(current)
            current = parents[current]
        depth = depths.get(current, 0 if current not in parents else len(parents))
        for link in reversed(chain):
            depth += 1
            depths[link] = depth
        depths.setdefault(name, depth)
    return depths


def _place(joint, renames: Renames) -> tuple:
    """(parent through ``renames``, type) of a ``<joint>``: where its child hangs."""
    parent = joint.find("parent")
    return (renames.link(parent.get("link")) if parent is not None else None,
            joint.get("type"))


def _xyz(joint):
    origin = joint.find("origin")
    return _numbers(origin.get("xyz") if origin is not None else None, 3, (0.0, 0.0, 0.0))


def renames(old, new, tolerance: float = 1e-9) -> Renames:
    """Links and joints of ``old`` that ``new`` has under another name, matched by position in
    the tree: a removed link and an added one hanging from the same (renamed) parent through
    a joint at the same origin of the same type, or with the same children; a removed joint and
    an added one joining the same links.

    The added links are indexed once by where they hang and by their children, and the removed
    ones taken parents first, pass after pass while one more is matched: the cost grows with the
    number of links, not its cube (300 renamed links took minutes), and stops at
    MAX_RENAME_WORK removed links looked at (what is left unmatched is compared as removed and
    added)."""
    result = Renames()
    old_parents, new_parents = _parent_joints(old), _parent_joints(new)
    old_children, new_children = _children(old), _children(new)
    added = [n for n in new.links if n not in old.links]
    roots, by_place, by_children, xyz = [], {}, {}, {}
    for other in added:
        twin = new_parents.get(other)
        if twin is None:
            roots.append(other)
            continue
        by_place.setdefault(_place(twin, Renames()), []).append(other)
        xyz[other] = _xyz(twin)
        if new_children.get(other):
            by_children.setdefault(frozenset(new_children[other]), []).append(other)
    depths = _depths(old)
    removed = sorted((n for n in old.links if n not in new.links), key=lambda n: depths[n])
    removed_xyz = {name: _xyz(old_parents[name]) for name in removed if name in old_parents}
    taken, work, progress = set(), 0, True
    while progress and work < MAX_RENAME_WORK:
        progress = False
        for name in removed:
            if name in result.links:
                continue
            work += 1
            joint = old_parents.get(name)
            if joint is None:
                found = roots
            else:
                found = [other for other in by_place.get(_place(joint, result), ())
                         if same_value(removed_xyz[name], xyz[other], 1e-6)]
                kids = frozenset(result.link(c) for c in old_children.get(name, ()))
                found = found + [other for other in by_children.get(kids, ()) if kids
                                 and other not in found]
            candidates = [other for other in found if other not in taken]
            if len(candidates) == 1:
                result.links[name] = candidates[0]
                taken.add(candidates[0])
                progress = True
    by_ends: dict[tuple, list[str]] = {}
    for other in (n for n in new.joints if n not in old.joints):
        fields = joint_fields(new.joints[other])
        by_ends.setdefault((fields["parent"], fields["child"]), []).append(other)
    matched = set()
    for name, joint in old.joints.items():
        if name in new.joints:
            continue
        ends = joint_fields(joint, result)
        matches = [other for other in by_ends.get((ends["parent"], ends["child"]), ())
                   if other not in matched]
        if len(matches) == 1:
            result.joints[name] = matches[0]
            matched.add(matches[0])
    return result


def structure(old, new, tolerance: float = 1e-9) -> tuple[list[Change], Renames]:
    """Every difference between robots ``old`` and ``new`` (urdftool Robot objects), and the
    renames found."""
    found = renames(old, new, tolerance)
    changes: list[Change] = []
    old_colours, new_colours = _colours(old), _colours(new)
    for element, old_items, new_items, mapping, read in (
            ("link", old.links, new.links, found.links,
             lambda e, side: link_fields(e, old_colours if side == "old" else new_colours)),
            ("joint", old.joints, new.joints, found.joints,
             lambda e, side: joint_fields(e, found if side == "old" else None))):
        for name, item in old_items.items():
            target = mapping.get(name, name)
            if target not in new_items:
                changes.append(Change("removed", element, name))
                continue
            if target != name:
                changes.append(Change("renamed", element, target, old_name=name))
            fields = read(item, "old"), read(new_items[target], "new")
            found_changes = compare_fields(element, target, *fields, tolerance,
                                           name if target != name else None)
            if element == "link" and _same_inertia(*fields, tolerance):
                found_changes = [c for c in found_changes if c.field not in INERTIA_FIELDS]
            if element == "joint":  # limits are angles or lengths by the joint's type
                unit = "m" if new_items[target].get("type") == "prismatic" else "rad"
                for change in found_changes:
                    if change.field.endswith(("lower", "upper", "_limit")):
                        change.unit = unit
            changes += found_changes
        renamed_to = set(mapping.values())
        for name in new_items:
            if name not in old_items and name not in renamed_to:
                changes.append(Change("added", element, name))
    for name in list(old_colours) + [n for n in new_colours if n not in old_colours]:
        if name not in new_colours:
            changes.append(Change("removed", "material", name))
        elif name not in old_colours:
            changes.append(Change("added", "material", name))
        elif not same_value(old_colours[name], new_colours[name], tolerance):
            changes.append(Change("changed", "material", name, "color", old_colours[name],
                                  new_colours[name]))
    return changes, found
