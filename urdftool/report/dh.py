"""``urdftool dh``: a Denavit-Hartenberg table as text, JSON or YAML."""

from __future__ import annotations

import sys

from urdftool.report.console import fixed, print_table, wide_console


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
        text(table)


def text(table) -> None:
    from urdftool.kinematics.fk import pose_components

    console = wide_console()
    modified = table.convention == "modified"
    print_table(console, f"D-H parameters ({table.convention}), {table.base_link} -> "
                         f"{table.tip_link}",
                ["joint", "type", "theta [rad]", "d [m]", "a(i-1) [m]" if modified else "a [m]",
                 "alpha(i-1) [rad]" if modified else "alpha [rad]"],
                [[joint.joint, joint.type,
                  *(fixed(v) for v in (joint.theta, joint.d, joint.a, joint.alpha))]
                 for joint in table.joints], left=2)
    for name, matrix in (("base", table.base), ("tool", table.tool)):
        position, rpy, _ = pose_components(matrix)
        console.print(f"{name}: xyz {_triple(position)}  rpy {_triple(rpy)}")
    console.print(f"base * D-H chain * tool reproduces the URDF chain to {table.residual:.1g}")


def _triple(values) -> str:
    return " ".join(fixed(v) for v in values)
