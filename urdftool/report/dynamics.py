"""``urdftool dynamics`` as text: mass, centre of mass, G, M, C, tau and gravity margins."""

from __future__ import annotations

import math

from urdftool.numbers import MILLIMETRE, number, numbers, symmetric_texts
from urdftool.report.escape import text as _text


def weakest(loads):
    """The joint load with the smallest margin relative to its effort limit; None when no joint
    has an effort limit."""
    limited = [load for load in loads if load.limited]
    return min(limited, key=lambda load: load.margin / load.effort if load.effort else 0) \
        if limited else None


def json_document(result, loads) -> dict:
    data = result.as_dict()
    data["gravity_loads"] = [load.as_dict() for load in loads]
    return data


def _row(values, scale: float | None) -> str:
    return " ".join(f"{number(v, scale=scale):>10s}" for v in values)


def _scale(values) -> float | None:
    """The largest finite magnitude among ``values`` (a matrix or a column): the size its
    entries' digits are counted from."""
    import numpy as np

    values = np.abs(np.asarray(values, dtype=float))
    values = values[np.isfinite(values)]
    return float(values.max()) if values.size and values.max() > 0 else None


NO_JOINT = "no moving joint: no gravity load to judge"
# why a joint of <limit effort="0"> is not judged (urdftool.physics.dynamics.judged_effort)
PASSIVE = ("no actuator torque declared: a passive or spring joint, or a limit left unknown; "
           "gravity there is carried by the structure, not a motor")
TORQUE = "[N m, or N for a prismatic joint]"  # the unit of every torque, tau and effort shown


def text(result, loads, samples, matrices: bool = True, relevant=()) -> str:
    """matrices: show G(q) and M(q); relevant: joints whose values in the worst pose matter"""
    joints = [_text(j) for j in result.joints]
    width = max((len(j) for j in joints), default=5)
    frame = "the world frame (free base)" if result.root else "the root frame"
    lines = [f"total mass {number(result.mass)} kg, centre of mass "
             f"({numbers(result.com, floor=MILLIMETRE)}) m in {frame}"]
    if result.fixed_mass > 0:
        lines.append(f"  (every link counted: {number(result.fixed_mass)} kg of it the root link "
                     "and the links fixed to it, which Pinocchio's computeTotalMass and "
                     "centerOfMass leave out)")
    if result.root:
        lines.append(f"free base: the rows {_text(result.root)}.x, .y, .z are the force [N] and "
                     ".roll, .pitch, .yaw the moment [N m] on the root link, in its frame")
    if matrices:
        lines += ["", f"G(q): gravity torque per joint {TORQUE}"]
        lines += [f"  {name:{width}s} {_row([g], _scale(result.G))}"
                  for name, g in zip(joints, result.G)]
        lines += ["", "M(q): joint-space mass matrix [kg m^2; kg between prismatic joints, kg m "
                      "across]"]
        lines += [f"  {name:{width}s} " + " ".join(f"{entry:>10s}" for entry in row)
                  for name, row in zip(joints, symmetric_texts(result.M))]
    if result.C is not None:
        lines += ["", f"C(q, v): Coriolis matrix (C v is a torque {TORQUE})"]
        lines += [f"  {name:{width}s} {_row(row, _scale(result.C))}"
                  for name, row in zip(joints, result.C)]
        lines += ["", "tau = M(q) a + C(q, v) v + G(q), and with the joints' <dynamics>: "
                      f"+ damping v + friction sign(v) {TORQUE}"]
        lines.append(f"  {'':{width}s} {'tau':>10s} {'damping':>10s} {'friction':>10s} "
                     f"{'total':>10s}")
        columns = (result.tau, result.damping, result.friction, result.total)
        scales = [_scale(column) for column in columns]
        lines += [f"  {name:{width}s} "
                  + " ".join(f"{number(v, scale=s):>10s}" for v, s in zip(values, scales))
                  for name, *values in zip(joints, *columns)]
        lines.append(f"  (tau matches rnea to {number(result.rnea_residual, 2)})")
    lines += _leader_lines(result, matrices)
    if matrices or result.C is not None:
        energies = (result.kinetic, result.potential, result.lagrangian)
        kinetic, potential, lagrangian = (number(e, 6, scale=_scale(energies)) for e in energies)
        lines += ["", f"energy: K = {kinetic} J, P = {potential} J "
                      f"(m g z of the centre of mass), L = K - P = {lagrangian} J"]
    if loads:
        refined = any(load.sampled is not None for load in loads)
        title = (f"static gravity load over the joint ranges (the zero pose and {samples} random "
                 "poses, then climbed to a maximum, exact along each joint):" if refined else
                 f"static gravity load over the zero pose and {samples} random poses:")
        lines += [""] + load_lines(loads, title, relevant)
    elif samples:
        lines += ["", NO_JOINT]
    return "\n".join(lines) + "\n"


def _leader_lines(result, matrices: bool) -> list[str]:
    """G and tau of each joint with mimic joints, as one actuator driving them supplies them."""
    leaders = result.leaders()
    if not leaders or not (matrices or result.C is not None):
        return []
    lines = ["", f"one actuator for a joint and the joints that mimic it (J^T of the columns "
                 f"above, as Pinocchio's mimic model has them) {TORQUE}:"]
    for leader, found in leaders.items():
        terms = " + ".join(f"{number(m)} x {_text(j)}" for j, m in found["followers"].items())
        said = [f"G {number(found['G'])}"] + \
            ([f"total tau {number(found['tau'])}"] if found["tau"] is not None else [])
        lines.append(f"  {_text(leader)} (itself + {terms}): {', '.join(said)}")
    return lines


def load_lines(loads, title: str, relevant=()) -> list[str]:
    """Each joint's worst gravity load against its effort limit, the smallest margin, and
    whether every joint holds; relevant: joints whose values in the worst pose matter. A joint
    without an effort limit has no margin and is listed as not judged."""
    width = max((len(_text(load.joint)) for load in loads), default=5)
    refined = any(load.sampled is not None for load in loads)
    sampled = f" {'sampled':>10s}" if refined else ""
    lines = [f"{title.rstrip(':')} {TORQUE}:",
             f"  {'joint':{width}s} {'effort':>8s} {'zero pose':>10s}{sampled} "
                    f"{'worst':>10s} {'margin':>10s}"]
    scale = _scale([value for load in loads for value in (load.zero_pose, load.worst)])
    for load in loads:
        flag = "" if load.holds is not False else "  ERROR: cannot hold itself against gravity"
        effort, margin = (f"{number(load.effort):>8s}", f"{number(load.margin):>10s}") \
            if load.limited else (f"{number(load.effort) if load.passive else 'none':>8s}",
                                  f"{'-':>10s}")
        drawn = "" if not refined else f" {number(load.sampled, scale=scale):>10s}" \
            if load.sampled is not None else f" {'':10s}"
        lines.append(f"  {_text(load.joint):{width}s} {effort} "
                     f"{number(load.zero_pose, scale=scale):>10s}{drawn} "
                     f"{number(load.worst, scale=scale):>10s} {margin}{flag}")
    least = weakest(loads)
    if least is not None:
        # only the joints that change its load: the others' values are noise
        pose = ", ".join(f"{_text(k)}={number(v, places=3)}" for k, v in least.worst_pose.items()
                         if k in relevant and number(v, places=3) != "0.000")
        lines.append(f"  smallest margin: {_text(least.joint)} ({number(least.margin, 3)} of "
                     f"{number(least.effort, 3)}) at {pose or 'the zero pose'}")
    leading = [load for load in loads if load.followers]
    if leading:
        lines.append("  with the joints that mimic them (one actuator drives them all, so its "
                     "load is its own plus theirs, J^T): " + ", ".join(
                         f"{_text(load.joint)} (itself + " + " + ".join(
                             f"{number(m)} x {_text(j)}" for j, m in load.followers.items()) + ")"
                         for load in leading))
    driven = [load for load in loads if load.driven_by is not None]
    if driven:
        lines.append("  not judged (mimic joints: the actuator of the joint each follows holds "
                     "its load, judged in that joint's row): " + ", ".join(
                         f"{_text(load.joint)} (by {_text(load.driven_by)})" for load in driven))
    unlimited = [_text(load.joint) for load in loads
                 if not load.limited and not load.passive and load.driven_by is None]
    if unlimited:
        lines.append(f"  not judged (no effort limit in the URDF, so no margin): "
                     f"{', '.join(unlimited)}")
    passive = [_text(load.joint) for load in loads if load.passive]
    if passive:
        lines.append(f"  not judged (effort 0 in the URDF: {PASSIVE}): {', '.join(passive)}")
    unlimited += passive + [_text(load.joint) for load in driven]
    failing = [_text(load.joint) for load in loads if load.holds is False]
    motor = [load for load in loads if load.held_at_the_motor]
    if motor:
        lines.append("  effort limits that may be the motor's: URDF's <limit effort> is the "
                     "joint's, and the transmission multiplies a motor's torque by its "
                     "mechanicalReduction: " + ", ".join(
                         f"{_text(load.joint)} {number(load.effort)} x {number(load.reduction)}"
                         f" = {number(load.effort * load.reduction)} would hold "
                         f"{number(load.worst, 3)}" for load in motor))
    every = "every joint with an effort limit" if unlimited else "every joint"
    lines.append(f"  {len(failing)} joint{'s' if len(failing) > 1 else ''} cannot hold "
                 f"{'themselves' if len(failing) > 1 else 'itself'}: {', '.join(failing)}"
                 if failing else f"  {every} holds the robot against gravity"
                 if least is not None else "  no joint has an effort limit above 0: nothing "
                                           "judged")
    return lines


def _vector(values) -> str:
    return numbers(values)


def stance_text(stance, standing_load=None) -> str:
    """The robot standing: centre of mass, support polygon and margin, each joint's torque
    standing and with the root fixed against its effort limit, the ground's wrenches."""
    supports = ", ".join(map(_text, stance.supports))
    lines = [f"standing on {supports} (ground frame: {_text(stance.supports[0])}'s, level, on "
             "its lowest point)",
             f"total mass {number(stance.mass)} kg, centre of mass "
             f"({numbers(stance.com, floor=MILLIMETRE)}) m"]
    where = "inside" if stance.stands else "OUTSIDE"
    lines.append(f"support polygon: {len(stance.polygon)} corners from the supports' geometry; "
                 f"the centre of mass is {number(abs(stance.margin) * 1000, places=1)} mm "
                 f"{where} its nearest "
                 "edge" + ("" if stance.stands else " (it tips over)"))
    if stance.assumption:
        lines.append(f"assumption: {_text(stance.assumption)}")
    joints = [_text(j) for j in stance.joints]
    width = max((len(j) for j in joints), default=5)
    lines += ["", f"joint torque holding the robot {TORQUE}:",
              f"  {'joint':{width}s} {'standing':>10s} {'root fixed':>10s} {'effort':>8s}"] \
        if joints else []
    scale = _scale([*stance.torques, *stance.fixed_base])
    for joint, standing, fixed, effort, beyond in zip(joints, stance.torques, stance.fixed_base,
                                                      stance.efforts, stance.beyond):
        flag = "  ERROR: beyond its effort limit" if beyond else ""
        lines.append(f"  {joint:{width}s} {number(standing, scale=scale):>10s} "
                     f"{number(fixed, scale=scale):>10s} {number(effort):>8s}{flag}")
    passive = [joint for joint, effort in zip(joints, stance.efforts) if effort <= 0]
    if passive:
        lines.append(f"  not judged (effort 0 in the URDF: {PASSIVE}): {', '.join(passive)}")
    lines += ["", "ground wrench on each support at its frame origin (force [N], torque [N m]):"]
    for name, wrench in stance.wrenches.items():
        lines.append(f"  {_text(name)}: force ({_vector(wrench[:3])}), "
                     f"torque ({_vector(wrench[3:])})")
    if standing_load is not None:
        tipped = standing_load.poses - standing_load.stable
        which = "the zero pose and " if standing_load.zero_stands else ""
        title = (f"standing gravity load over {which}{standing_load.stable - bool(which)} "
                 f"random poses in which it stands ({tipped} of {standing_load.poses} poses "
                 "tip over or lift a support and are left out):")
        if standing_load.loads:
            lines += [""] + load_lines(standing_load.loads, title,
                                       relevant={load.joint for load in standing_load.loads})
        elif not stance.joints:
            lines += ["", NO_JOINT]
        else:
            lines += ["", f"no pose drawn stands: all {standing_load.poses} tip over or lift a "
                          "support (more --samples, or --q for a pose that stands)"]
    return "\n".join(lines) + "\n"


def stance_picture(stance, title: str, size: int = 420):
    """The support polygon, its contact points and the centre of mass seen from above, as
    primitives for urdftool.report.plot.write_items: (width, height, items)."""
    import numpy as np

    points = np.vstack([stance.polygon.reshape(-1, 2), stance.contacts[:, :2],
                        stance.com[None, :2]])
    low, high = points.min(axis=0), points.max(axis=0)
    span = float(max(high - low)) or 0.1
    pad, top = 40, 50
    scale = (size - 2 * pad) / (1.3 * span)
    centre = (low + high) / 2

    def at(x, y):  # x to the right, y up
        return size / 2 + (x - centre[0]) * scale, top + size / 2 - (y - centre[1]) * scale

    items = [("text", 8, 18, title, 13, "start", False)]
    where = "inside" if stance.stands else "OUTSIDE"
    items.append(("text", 8, 36, f"centre of mass {number(abs(stance.margin) * 1000, places=1)} "
                                 f"mm {where} "
                                 "the support polygon", 11, "start", False))
    if len(stance.polygon) >= 3:
        items.append(("polygon", [at(*p) for p in stance.polygon], "#2ca02c", 0.3, "#2ca02c"))
    elif len(stance.polygon) == 2:
        items.append(("line", *at(*stance.polygon[0]), *at(*stance.polygon[1]), "#2ca02c"))
    for x, y in stance.contacts[:, :2]:
        items.append(("circle", *at(x, y), 2, "#2ca02c", 1.0))
    colour = "#1f77b4" if stance.stands else "#d62728"
    cx, cy = at(*stance.com[:2])
    items.append(("line", cx - 8, cy, cx + 8, cy, colour))
    items.append(("line", cx, cy - 8, cx, cy + 8, colour))
    items.append(("circle", cx, cy, 4, colour, 1.0))
    items.append(("text", cx + 8, cy - 8, "COM", 11, "start", False))
    bar = 10 ** math.floor(math.log10(span / 2))
    x0, y0 = pad, size + top - 20
    items.append(("line", x0, y0, x0 + bar * scale, y0, "#000000"))
    items.append(("text", x0, y0 - 4, f"{bar * 1000:g} mm", 11, "start", False))
    items.append(("text", size - 8, size + top - 8, "seen from above: x right, y up", 11, "end",
                  False))
    return size, size + top, items
