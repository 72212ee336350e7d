"""``urdftool dynamics`` as text: mass, centre of mass, G, M, C, tau and gravity margins."""

from __future__ import annotations


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


def _row(values) -> str:
    return " ".join(f"{v:10.4g}" for v in values)


def text(result, loads, samples, matrices: bool = True, relevant=()) -> str:
    """matrices: show G(q) and M(q); relevant: joints whose values in the worst pose matter"""
    width = max((len(j) for j in result.joints), default=5)
    com = " ".join(f"{c if abs(c) > 1e-12 else 0.0:.4g}" for c in result.com)
    lines = [f"total mass {result.mass:.4g} kg, centre of mass ({com}) m in the root frame"]
    if matrices:
        lines += ["", "G(q): gravity torque per joint [N m or N]"]
        lines += [f"  {name:{width}s} {g:10.4g}" for name, g in zip(result.joints, result.G)]
        lines += ["", "M(q): joint-space mass matrix"]
        lines += [f"  {name:{width}s} {_row(row)}" for name, row in zip(result.joints, result.M)]
    if result.C is not None:
        lines += ["", "C(q, v): Coriolis matrix"]
        lines += [f"  {name:{width}s} {_row(row)}" for name, row in zip(result.joints, result.C)]
        lines += ["", "tau = M(q) a + C(q, v) v + G(q)"]
        lines += [f"  {name:{width}s} {t:10.4g}" for name, t in zip(result.joints, result.tau)]
        lines.append(f"  (matches rnea to {result.rnea_residual:.2g})")
    if loads:
        lines += ["", f"static gravity load over the zero pose and {samples} random poses:",
                  f"  {'joint':{width}s} {'effort':>8s} {'zero pose':>10s} {'worst':>10s} "
                  f"{'margin':>10s}"]
        for load in loads:
            flag = "" if load.holds is not False else "  ERROR: cannot hold itself against gravity"
            effort, margin = (f"{load.effort:8.4g}", f"{load.margin:10.4g}") if load.limited \
                else (f"{'none':>8s}", f"{'-':>10s}")
            lines.append(f"  {load.joint:{width}s} {effort} {load.zero_pose:10.4g} "
                         f"{load.worst:10.4g} {margin}{flag}")
        least = weakest(loads)
        if least is not None:
            # only the joints that change its load: the others' values are noise
            pose = ", ".join(f"{k}={v:.3f}" for k, v in least.worst_pose.items()
                             if v and k in relevant)
            lines.append(f"  smallest margin: {least.joint} ({least.margin:.3g} of "
                         f"{least.effort:.3g}) at {pose or 'the zero pose'}")
        unlimited = [load.joint for load in loads if not load.limited]
        if unlimited:
            lines.append(f"  not judged (no effort limit in the URDF, so no margin): "
                         f"{', '.join(unlimited)}")
        failing = [load.joint for load in loads if load.holds is False]
        every = "every joint with an effort limit" if unlimited else "every joint"
        lines.append(f"  {len(failing)} joint{'s' if len(failing) > 1 else ''} cannot hold "
                     f"{'themselves' if len(failing) > 1 else 'itself'}: {', '.join(failing)}"
                     if failing else f"  {every} holds the robot against gravity"
                     if least is not None else "  no joint has an effort limit: nothing judged")
    return "\n".join(lines) + "\n"
