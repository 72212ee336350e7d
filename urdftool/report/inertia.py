"""``urdftool inertia``: declared and computed inertials side by side, and corrected blocks."""

from __future__ import annotations

from urdftool.numbers import MILLIMETRE, number, numbers, symmetric_texts
from urdftool.report.escape import text as _text


def xacro_blocks(robot, results) -> str:
    """For xacro input, which cannot be rewritten: each corrected ``<inertial>`` after a comment
    saying where it goes (through the macro calls that made it)."""
    from urdftool.physics.inertia_compare import inertial_xml

    lines = []
    for result in results:
        where = robot.locate(result.element) if result.element is not None else \
            robot.locate(robot.links[result.link])
        what = "replaces the <inertial> at" if result.element is not None else \
            "goes into the link at"
        via = "".join(f", expanded from the macro call at {site}" for site in where.via)
        lines.append(_text(f"<!-- link '{result.link}': {what} {where}{via} -->"))
        lines.append(inertial_xml(result.computed))
    return "".join(line + "\n" for line in lines)


def _fmt(properties) -> tuple[str, str, str]:
    if properties is None:
        return "-", "-", "-"
    t = symmetric_texts(properties.inertia)
    return (number(properties.mass), numbers(properties.com, floor=MILLIMETRE),
            " ".join((t[0][0], t[1][1], t[2][2], t[0][1], t[0][2], t[1][2])))


def text(results) -> str:
    lines = []
    for result in results:
        link = _text(result.link)
        if result.declared is None and result.computed is None and not result.notes:
            lines.append(f"{link}: {result.verdict} (a frame: no inertial, no geometry)")
            continue
        lines.append(f"{link}: {result.verdict} (computed from {result.source} geometry)"
                     if result.source != "none" else f"{link}: {result.verdict} (no geometry)")
        for label, properties in (("declared", result.declared), ("computed", result.computed)):
            mass, com, tensor = _fmt(properties)
            lines.append(f"  {label:9s} mass {mass:>9s} kg  com [m] {com:28s}  "
                         f"ixx iyy izz ixy ixz iyz [kg m^2] {tensor}")
        if result.differences:
            diff = ", ".join(f"{k} {number(100 * v, places=1)}%"
                             for k, v in result.differences.items())
            lines.append(f"  difference {diff}")
        lines.extend(f"  note: {_text(note)}" for note in result.notes)
    from urdftool.physics.inertia_compare import VERDICTS

    counts = {v: sum(r.verdict == v for r in results) for v in VERDICTS}
    plural = "" if len(results) == 1 else "s"
    lines.append(", ".join(f"{n} {v}" for v, n in counts.items() if n) +
                 f" ({len(results)} link{plural})")
    return "\n".join(lines) + "\n"
