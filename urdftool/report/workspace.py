"""``urdftool workspace``: the reach envelope as text, JSON and a picture (top and side views,
points shaded by manipulability)."""

from __future__ import annotations

from urdftool.numbers import number, numbers
from urdftool.report.summary import counted

# viridis at five stops: low manipulability light, high dark
_RAMP = ((253, 231, 37), (94, 201, 98), (33, 145, 140), (59, 82, 139), (68, 1, 84))
PANEL = 360  # [px] each view
TOP = 56  # [px] title rows


def text(space) -> str:
    lower, upper = space.lower, space.upper
    m = space.manipulability
    from urdftool.report.escape import text

    size = max(abs(float(v)) for v in (*lower, *upper, space.reach)) or None

    def length(value):  # digits counted from the workspace's size: round-off bounds are 0
        return number(value, scale=size)

    peak = float(m.max()) or None
    lines = [f"workspace of {text(space.tip)} relative to {text(space.base)} "
             f"({counted(len(space.joints), 'joint')}: {', '.join(map(text, space.joints))}), "
             f"{space.samples} samples (seed {space.seed})",
             f"  max reach {length(space.reach)} m from the first joint at "
             f"({numbers(space.centre)}); horizontal {length(space.horizontal_reach)} m",
             f"  x from {length(lower[0])} to {length(upper[0])} m, y from {length(lower[1])} "
             f"to {length(upper[1])} m, z from {length(lower[2])} to {length(upper[2])} m "
             f"(vertical extent {length(upper[2] - lower[2])} m)",
             f"  manipulability: min {number(m.min(), 3, scale=peak)}, mean "
             f"{number(space.mean_manipulability, 3, scale=peak)}, max {number(m.max(), 3)}"]
    return "\n".join(lines) + "\n"


def _colour(value: float) -> str:
    value = min(1.0, max(0.0, value)) * (len(_RAMP) - 1)
    k = min(int(value), len(_RAMP) - 2)
    t = value - k
    rgb = (round(a + (b - a) * t) for a, b in zip(_RAMP[k], _RAMP[k + 1]))
    return "#" + "".join(f"{c:02x}" for c in rgb)


def picture(space, title: str):
    """(width, height, items) for urdftool.report.plot.write_items: the top view (x right,
    y up) and the side view (x right, z up) side by side, on one scale."""
    import numpy as np

    points, centre = space.points, space.centre
    low = np.minimum(points.min(axis=0), centre)
    high = np.maximum(points.max(axis=0), centre)
    span = float(max(high - low)) or 0.1
    pad = 24
    scale = (PANEL - 2 * pad) / span
    middle = (low + high) / 2
    peak = float(space.manipulability.max()) or 1.0
    items = [("text", 8, 18, title, 13, "start", False),
             ("text", 8, 36, f"max reach {number(space.reach, 3)} m, {space.samples} samples; colour: "
                             "manipulability (light low, dark high)", 11, "start", False)]
    order = np.argsort(space.manipulability)  # dark, well-conditioned points on top
    for panel, (axis, name) in enumerate(((1, "top view: x right, y up"),
                                          (2, "side view: x right, z up"))):
        left = panel * PANEL

        def at(x, v, left=left, axis=axis):
            return (left + PANEL / 2 + (x - middle[0]) * scale,
                    TOP + PANEL / 2 - (v - middle[axis]) * scale)

        items.append(("rect", left + 4, TOP, PANEL - 8, PANEL, "#f4f4f4", 1.0, None))
        items.append(("text", left + 10, TOP + 16, name, 11, "start", False))
        for k in order:
            x, v = at(points[k, 0], points[k, axis])
            items.append(("circle", x, v, 1.6, _colour(space.manipulability[k] / peak), 0.8))
        cx, cy = at(centre[0], centre[axis])
        items.append(("line", cx - 7, cy, cx + 7, cy, "#d62728"))
        items.append(("line", cx, cy - 7, cx, cy + 7, "#d62728"))
    bar = 10 ** np.floor(np.log10(span / 2))
    y = TOP + PANEL + 20
    items.append(("line", 10, y, 10 + bar * scale, y, "#000000"))
    items.append(("text", 14 + bar * scale, y + 4, f"{bar:g} m; + first joint", 11, "start",
                  False))
    return 2 * PANEL, TOP + PANEL + 32, items
