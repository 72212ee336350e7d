"""What each loader's reading of a URDF makes of its masses, from the loaders' own sources, so
that a total mass that differs from the URDF's is either accounted for, link by link, or said as
a disagreement (a loader that dropped an inertial: Pinocchio read 1 kg of a robot declaring 2,
and "by design" passed it as agreement).

The rules, each read in the loader's importer:

- Pinocchio (``parsers/urdf``): every link's ``<inertial>`` is appended to the joint that moves
  it (the root's to the universe), a link without one weighs nothing: the URDF's sum.
- Drake (``detail_urdf_parser.cc``, ``ParseBody``): a link without ``<inertial>`` weighs nothing;
  a link named ``world`` is the world body, whose ``<inertial>`` is ignored (with a warning); a
  link marked ``drake_ignore="true"`` is not read.
- PyBullet (``UrdfParser.cpp``, ``parseLink``): a link without ``<inertial>`` weighs 1 kg ("No
  inertial data for link, using mass=1"), but one named ``world``, which weighs nothing.
- MuJoCo (``xml_urdf.cc``, and its compiler): the root is welded to the world and, with
  ``fusestatic`` (on for a URDF), every body with no joint is fused into its parent: the links
  welded to the world are fused into the world body, whose mass is not the model's (but a
  link named ``world``, which is that body: its ``<inertial>`` is the world body's mass); a link
  without ``<inertial>`` has its mass computed from its geoms (``inertiafromgeom="auto"``,
  1000 kg/m^3; its visual geoms weigh nothing): taken as MuJoCo holds it, for a link it keeps
  as its own body, or fused into another (the body's mass beyond its links' ``<inertial>``s;
  a body holding less than those is not accounted for: a disagreement). ``inertiafromgeom=
  "true"`` and ``boundmass`` are not accounted for here (said so).
- sdformat is not accounted for (its conversion lumps and drops links by rules of its own).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from urdftool.numbers import number

# a total that its reading accounts for agrees within this (PyBullet keeps masses as floats of
# its own; a sum of many links rounds)
RELATIVE = 1e-6
ABSOLUTE = 1e-9  # [kg]


@dataclass
class Account:
    """How a loader's reading accounts for the URDF's mass: ``expected`` [kg] (None: not
    accounted for, ``why`` says why), and the changes, each a phrase (what and how much)."""

    expected: float | None
    changes: list[str] = field(default_factory=list)
    why: str = ""


def _links(robot) -> dict:
    """link name -> its declared mass [kg], None without ``<inertial>``; raises ValueError for
    a link whose ``<inertial>`` urdftool does not read as numbers (no total to account for)."""
    from urdftool.physics.mass import declared_of

    masses = {}
    for name, link in robot.links.items():
        if link.find("inertial") is None:
            masses[name] = None
            continue
        body = declared_of(robot, link)
        if body is None:
            raise ValueError(f"link '{name}' has an <inertial> urdftool does not read as numbers")
        masses[name] = float(body.mass)
    return masses


def _without(mass: float, links: list[str], why: str) -> str:
    return f"without the {number(mass, 6)} kg of {_named(links)} ({why})"


def _named(names: list[str]) -> str:
    return ", ".join(names[:6]) + (f" and {len(names) - 6} more" if len(names) > 6 else "")


def account(name: str, result, robot) -> Account:
    """How loader ``name``'s reading of ``robot`` accounts for its total mass, ``result`` its
    LoaderResult (MuJoCo's: which links it dropped, what it holds of the others)."""
    try:
        masses = _links(robot)
    except ValueError as error:
        return Account(None, why=str(error))
    declared = sum(mass for mass in masses.values() if mass is not None)
    without = [link for link, mass in masses.items() if mass is None]
    if name == "pinocchio":
        return Account(declared)
    if name == "drake":
        ignored = [link for link, element in robot.links.items()
                   if element.get("drake_ignore") == "true" and masses[link]]
        world = masses.get("world")
        changes = []
        if world:
            changes.append(_without(world, ["world"], "the world body: its <inertial> is "
                                                      "ignored"))
        if ignored:
            changes.append(_without(sum(masses[i] for i in ignored), ignored, "drake_ignore"))
        return Account(declared - (world or 0.0) - sum(masses[i] for i in ignored), changes)
    if name == "pybullet":
        weighed = [link for link in without if link != "world"]
        return Account(declared + len(weighed), [
            f"1 kg for each link without <inertial>: {_named(weighed)}"] if weighed else [])
    if name == "mujoco":
        return _mujoco(result, robot, masses, declared)
    return Account(None, why=f"{name}'s reading is not accounted for")


def _mujoco(result, robot, masses: dict, declared: float) -> Account:
    from urdftool.simulators import mujoco_compiler

    compiler = mujoco_compiler(robot.root)
    for setting in ("boundmass", "inertiafromgeom"):
        value = compiler.get(setting) if compiler is not None else None
        if value is not None and (setting == "boundmass" or value.strip().lower() == "true"):
            return Account(None, why=f'the robot\'s <mujoco><compiler {setting}="{value}"> '
                                     "changes masses")
    parents = {}
    for joint in robot.joints.values():
        parent, child = joint.find("parent"), joint.find("child")
        if parent is not None and child is not None:
            parents.setdefault(child.get("link"), parent.get("link"))
    kept = set(result.links)
    welded, lost = [], 0.0
    bodies: dict[str, list[str]] = {}  # a body MuJoCo keeps -> its links (itself, those fused)
    for link, mass in masses.items():
        ancestor, seen = link, {link}
        while ancestor is not None and ancestor not in kept:
            ancestor = parents.get(ancestor)
            if ancestor in seen:
                break
            seen.add(ancestor)
        if ancestor is None or ancestor not in kept:  # fused into the world
            if mass and link != "world":  # (a link named world IS MuJoCo's world body: it
                # holds that link's <inertial>, counted in the total; tested against MuJoCo)
                welded.append(link)
                lost += mass
            continue
        bodies.setdefault(ancestor, []).append(link)
    computed, held = [], 0.0
    for body, links in bodies.items():
        without = [link for link in links if masses[link] is None]
        if not without:
            continue
        # each fused link weighs its <inertial>, or without one its geoms (tested against
        # MuJoCo: a link of 2 kg with a fixed child of no <inertial> and a 1 kg box weighs
        # 3): the geoms' part is what the body holds beyond its links' <inertial>s
        held_here = float((result.inertia.get(body) or {}).get("mass") or 0.0)
        geoms = held_here - sum(masses[link] or 0.0 for link in links)
        if geoms < -max(ABSOLUTE, RELATIVE * held_here):  # less than its <inertial>s: the
            continue  # total falls short of the account, a disagreement
        computed += [link if link == body else f"{link} (fused into {body})"
                     for link in without]
        held += max(geoms, 0.0)
    changes = [_without(lost, welded, "welded to the world, fused into it")] if lost else []
    if computed and held > ABSOLUTE:  # (frames fused with no geom weigh nothing: unsaid)
        changes.append(f"{number(held, 6)} kg computed from the geoms of {_named(computed)} "
                       "(no <inertial>)")
    return Account(declared - lost + held, changes)


def compare(report, robot) -> None:
    """Add to ``report`` what each loaded loader's total mass is, against the URDF's: a
    difference its reading accounts for to ``differences`` (with how), one it does not to
    ``disagreements``."""
    loaded = [r for r in report.loaders if r.loaded and r.mass is not None]
    if not loaded:
        return
    try:
        declared = sum(m for m in _links(robot).values() if m is not None)
    except ValueError:
        declared = None
    values = {r.name: r.mass for r in loaded}
    apart = len({round(v, 9) for v in values.values()}) > 1
    off = declared is not None and any(not _close(v, declared) for v in values.values())
    if not apart and not off:
        return
    said = f" (the URDF declares {number(declared, 6)})" if declared is not None else ""
    report.differences.append("total mass [kg]: " + ", ".join(
        f"{name} {number(value, 6)}" for name, value in values.items()) + said)
    for result in loaded:
        held = result.mass
        reading = account(result.name, result, robot)
        if reading.expected is None:
            if declared is None or not _close(held, declared):
                report.differences.append(f"{result.name} holds {number(held, 6)} kg; not "
                                          f"accounted for: {reading.why}")
        elif _close(held, reading.expected):
            if reading.changes:
                report.differences.append(f"{result.name} holds {number(held, 6)} kg: " +
                                          "; ".join(reading.changes))
        else:
            how = f" ({'; '.join(reading.changes)})" if reading.changes else ""
            report.disagreements.append(
                f"{result.name} holds {number(held, 6)} kg of mass, where its reading of the "
                f"URDF{how} accounts for {number(reading.expected, 6)} kg: it read an "
                "<inertial> otherwise ('urdftool check' says which may be misread)")


def _close(value: float, expected: float) -> bool:
    return abs(value - expected) <= max(ABSOLUTE, RELATIVE * max(abs(value), abs(expected)))
