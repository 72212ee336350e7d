"""Synthetic robots of any size, written to a temporary folder (never into the repository).

``chain(n)``: n links, each the child of the one before (depth n); ``star(n)``: one base and
n - 1 links each jointed to it (depth 1). Every link has an inertial and a box visual and
collision, every joint is revolute with limits, so that every rule family has work to do.
"""

from __future__ import annotations

import sys
from pathlib import Path

_LINK = ('<link name="l{i}"><inertial><origin xyz="0 0 0.05"/><mass value="1"/>'
         '<inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>'
         '<visual><origin xyz="0 0 0.05"/><geometry><box size="0.02 0.02 0.1"/></geometry></visual>'
         '<collision><origin xyz="0 0 0.05"/><geometry><box size="0.02 0.02 0.1"/></geometry>'
         '</collision></link>\n')
_JOINT = ('<joint name="j{i}" type="revolute"><parent link="l{parent}"/><child link="l{i}"/>'
          '<origin xyz="{x} 0 {z}"/><axis xyz="{axis}"/>'
          '<limit lower="-1" upper="1" effort="10" velocity="1"/></joint>\n')


def robot(links: int, shape: str) -> str:
    """The URDF text of a ``shape`` ('chain' or 'star') robot with ``links`` links."""
    parts = [f'<?xml version="1.0"?>\n<robot name="{shape}{links}">\n']
    for i in range(links):
        parts.append(_LINK.format(i=i))
        if i:
            parent = i - 1 if shape == "chain" else 0
            x, z = (0, 0.1) if shape == "chain" else (0.05 * (i % 40), 0.1 * (i // 40))
            axis = "0 1 0" if i % 2 else "1 0 0"
            parts.append(_JOINT.format(i=i, parent=parent, x=x, z=z, axis=axis))
    parts.append("</robot>\n")
    return "".join(parts)


def write(folder: Path, links: int, shape: str) -> Path:
    """``folder/<shape><links>.urdf``, written once."""
    path = Path(folder) / f"{shape}{links}.urdf"
    if not path.exists():
        path.write_text(robot(links, shape))
    return path


if __name__ == "__main__":
    # python benchmarks/generate.py FOLDER N chain|star
    print(write(Path(sys.argv[1]), int(sys.argv[2]), sys.argv[3]))
