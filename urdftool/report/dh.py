"""``urdftool dh``: a Denavit-Hartenberg table as text, JSON or YAML."""

from __future__ import annotations

import math
import sys

from urdftool.numbers import number
from urdftool.report.console import fixed, plain_tables, print_table, wide_console
from urdftool.report.console import write_table as write_plain_table


def write_table(table, output_format: str, stream=None) -> None:
    """``table`` (urdftool.kinematics.dh.DHTable) in ``output_format``: text, json or yaml."""
    stream = stream or sys.stdout
    if output_format == "json":
        from urdftool.report.json_output import write_json

        write_json(table.as_dict(), stream)
    elif output_format == "yaml":
        from urdftool.report.escape import yaml_text

        stream.write(yaml_text(table.as_dict()))
    else:
        text(table, stream)


PLACES = 6  # decimals of a length [m]: the text table holds the chain to half of 1e-6 m
DIGITS = 17  # significant digits that tell every float apart: more would print noise


def angle_places(table) -> int:
    """Decimals of the text table's angles [rad]: :data:`PLACES`, and one more for each power
    of ten the chain reaches past 1 m, so that the angles printed hold the chain to what its
    lengths' decimals hold however far it reaches (an angle off by e moves what lies r beyond
    it by e r: 6 decimals of a theta 2e7 m from the tip moved it 10 m). The reach is bounded
    by the sum of the table's lengths and the base's and tool's translations."""
    reach = sum(abs(joint.d) + abs(joint.a) for joint in table.joints) + \
        math.hypot(*table.base[:3, 3]) + math.hypot(*table.tool[:3, 3])
    return PLACES + max(0, math.ceil(math.log10(reach))) if reach > 1 else PLACES


def _decimals(value: float, places: int) -> str:
    """``value`` with ``places`` decimals, at most :data:`DIGITS` significant digits."""
    whole = math.floor(math.log10(abs(value))) + 1 if value and math.isfinite(value) else 1
    return fixed(value, max(0, min(places, DIGITS - max(whole, 1))))


def text(table, stream=None) -> None:
    """The table, its base and tool, each length with :data:`PLACES` decimals and each angle
    with :func:`angle_places`: read back, the numbers printed reproduce the chain to 1e-6 m
    wherever it is (JSON and YAML carry every digit)."""
    from urdftool.kinematics.fk import pose_components

    modified = table.convention == "modified"
    title = f"D-H parameters ({table.convention}), {table.base_link} -> {table.tip_link}"
    headers = ["joint", "type", "theta [rad]", "d [m]", "a(i-1) [m]" if modified else "a [m]",
               "alpha(i-1) [rad]" if modified else "alpha [rad]"]
    angles = angle_places(table)
    rows = [[joint.joint, joint.type, _decimals(joint.theta, angles),
             _decimals(joint.d, PLACES), _decimals(joint.a, PLACES),
             _decimals(joint.alpha, angles)] for joint in table.joints]
    lines = []
    for name, matrix in (("base", table.base), ("tool", table.tool)):
        position, rpy, _ = pose_components(matrix)
        lines.append(f"{name}: xyz {_triple(position, PLACES)}  rpy {_triple(rpy, angles)}")
    lines.append(f"base * D-H chain * tool reproduces the URDF chain to {number(table.residual, 1)}")
    if plain_tables(len(rows)):
        from urdftool.report.escape import lines as terminal_lines

        stream = stream or sys.stdout
        write_plain_table(stream, title, headers, rows, left=2)
        stream.write(terminal_lines("\n".join(lines) + "\n"))
        return
    console = wide_console()
    print_table(console, title, headers, rows, left=2)
    for line in lines:
        console.print(line)


def _triple(values, places: int) -> str:
    return " ".join(_decimals(float(v), places) for v in values)
