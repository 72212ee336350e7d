"""``urdftool dh``: a Denavit-Hartenberg table as text, JSON or YAML."""

from __future__ import annotations

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
        import yaml

        stream.write(yaml.safe_dump(table.as_dict(), sort_keys=False))
    else:
        text(table)


def text(table) -> None:
    from urdftool.kinematics.fk import pose_components

    modified = table.convention == "modified"
    title = f"D-H parameters ({table.convention}), {table.base_link} -> {table.tip_link}"
    headers = ["joint", "type", "theta [rad]", "d [m]", "a(i-1) [m]" if modified else "a [m]",
               "alpha(i-1) [rad]" if modified else "alpha [rad]"]
    rows = [[joint.joint, joint.type,
             *(fixed(v) for v in (joint.theta, joint.d, joint.a, joint.alpha))]
            for joint in table.joints]
    lines = []
    for name, matrix in (("base", table.base), ("tool", table.tool)):
        position, rpy, _ = pose_components(matrix)
        lines.append(f"{name}: xyz {_triple(position)}  rpy {_triple(rpy)}")
    lines.append(f"base * D-H chain * tool reproduces the URDF chain to {number(table.residual, 1)}")
    if plain_tables(len(rows)):
        write_plain_table(sys.stdout, title, headers, rows, left=2)
        sys.stdout.write("\n".join(lines) + "\n")
        return
    console = wide_console()
    print_table(console, title, headers, rows, left=2)
    for line in lines:
        console.print(line)


def _triple(values) -> str:
    return " ".join(fixed(v) for v in values)
