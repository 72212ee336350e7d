"""Synthetic robots of any size, written to a temporary folder (never into the repository).

``chain(n)``: n links, each the child of the one before (depth n); ``star(n)``: one base and
n - 1 links each jointed to it (depth 1). Every link has an inertial and a box visual and
collision, every joint is revolute with limits, so that every rule family has work to do.

``meshes(n)``: the inertia rules' work on meshes and rigid bodies. Every other link is fixed
to the base (one rigid body of n / 2 links, some turned), the others each hang on a revolute
joint from the link before; every link has an open mesh (a sphere without its top, so its hull
stands for it) as visual and a closed one as collision, at five scales, written beside the
URDF; some centres of mass are outside their geometry (one of the rigid body's, whose
finding names the body's links), some tensors a thousand times too large, so that the rules
find something.
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


_MESH_LINK = ('<link name="l{i}"><inertial><origin xyz="0 0 {com}"/><mass value="1"/>'
              '<inertia ixx="{moment}" ixy="0" ixz="0" iyy="{moment}" iyz="0" izz="{moment}"/>'
              '</inertial><visual><origin xyz="0 0 0.01" rpy="0 0 {yaw}"/><geometry>'
              '<mesh filename="open.stl" scale="{s} {s} {s}"/></geometry></visual>'
              '<collision><origin xyz="0 0 0.01"/><geometry><mesh filename="closed.stl" '
              'scale="{s} {s} {s}"/></geometry></collision></link>\n')
_FIXED = ('<joint name="j{i}" type="fixed"><parent link="l0"/><child link="l{i}"/>'
          '<origin xyz="{x} {y} {z}" rpy="0 0 {yaw}"/></joint>\n')


def _sphere_stl(radius: float, rings: int, segments: int, open_top: bool) -> bytes:
    """A binary STL of a UV sphere of ``radius`` [m] standing on the origin; ``open_top``
    leaves out its top cap (not closed: its convex hull stands for it)."""
    import math
    import struct

    def point(ring, segment):
        theta, phi = math.pi * ring / rings, 2 * math.pi * (segment % segments) / segments
        return (radius * math.sin(theta) * math.cos(phi), radius * math.sin(theta) *
                math.sin(phi), radius * (1 + math.cos(theta)))

    triangles = []
    for ring in range(rings - 1 if open_top else rings):
        for segment in range(segments):
            a, b = point(ring, segment), point(ring + 1, segment)
            c, d = point(ring + 1, segment + 1), point(ring, segment + 1)
            if ring > 0:
                triangles.append((a, b, d))
            if ring < rings - 1:
                triangles.append((d, b, c))
    body = b"".join(struct.pack("<12fH", 0, 0, 0, *a, *b, *c, 0) for a, b, c in triangles)
    return b"\0" * 80 + struct.pack("<I", len(triangles)) + body


def meshes_robot(links: int) -> str:
    """The URDF text of the ``meshes`` robot (see the module's docstring)."""
    parts = [f'<?xml version="1.0"?>\n<robot name="meshes{links}">\n']
    for i in range(links):
        parts.append(_MESH_LINK.format(i=i, com=5.0 if i == 4 else 0.17 if i % 7 == 3 else 0.05,
                                       moment=1.0 if i % 11 == 5 else 0.001,
                                       yaw=0.1 * (i % 3), s=1 + 0.1 * (i % 5)))
        if i % 2 == 0 and i:
            parts.append(_FIXED.format(i=i, x=0.05 * (i % 40), y=0.05 * (i // 40 % 40),
                                       z=0.1 * (i // 1600), yaw=0.25 * (i % 4)))
        elif i:
            parts.append(_JOINT.format(i=i, parent=i - 1, x=0, z=0.1, axis="0 1 0"))
    parts.append("</robot>\n")
    return "".join(parts)


def write(folder: Path, links: int, shape: str) -> Path:
    """``folder/<shape><links>.urdf``, written once (with its meshes, for ``meshes``)."""
    path = Path(folder) / f"{shape}{links}.urdf"
    if not path.exists():
        if shape == "meshes":
            for name, radius, open_top in (("open.stl", 0.04, True), ("closed.stl", 0.05, False)):
                (Path(folder) / name).write_bytes(_sphere_stl(radius, 16, 24, open_top))
            path.write_text(meshes_robot(links))
        else:
            path.write_text(robot(links, shape))
    return path


if __name__ == "__main__":
    # python benchmarks/generate.py FOLDER N chain|star
    print(write(Path(sys.argv[1]), int(sys.argv[2]), sys.argv[3]))


_XACRO_HEAD = """<?xml version="1.0"?>
<robot name="xbot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="width" value="0.04"/>
  <xacro:property name="density" value="2700"/>
  <xacro:property name="limits" value="${dict(lower=-pi/2, upper=pi/2, effort=30, velocity=2)}"/>
  <xacro:macro name="box_inertia" params="m x y z">
    <inertia ixx="${m*(y*y+z*z)/12}" ixy="0" ixz="0" iyy="${m*(x*x+z*z)/12}" iyz="0"
             izz="${m*(x*x+y*y)/12}"/>
  </xacro:macro>
  <xacro:macro name="segment" params="name parent length:=0.1 *joint_origin flip:=false">
    <xacro:property name="mass" value="${density * width * width * length}"/>
    <link name="${name}">
      <inertial>
        <origin xyz="0 0 ${length/2}" rpy="0 0 0"/>
        <mass value="${mass}"/>
        <xacro:box_inertia m="${mass}" x="${width}" y="${width}" z="${length}"/>
      </inertial>
      <visual>
        <origin xyz="0 0 ${length/2}" rpy="0 0 ${pi if flip else 0}"/>
        <geometry><box size="${width} ${width} ${length}"/></geometry>
        <material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>
      </visual>
      <collision>
        <origin xyz="0 0 ${length/2}" rpy="0 0 0"/>
        <geometry><box size="${width} ${width} ${length}"/></geometry>
      </collision>
    </link>
    <joint name="${name}_joint" type="revolute">
      <parent link="${parent}"/>
      <child link="${name}"/>
      <xacro:insert_block name="joint_origin"/>
      <xacro:if value="${flip}"><axis xyz="1 0 0"/></xacro:if>
      <xacro:unless value="${flip}"><axis xyz="0 1 0"/></xacro:unless>
      <limit lower="${limits['lower']}" upper="${limits['upper']}" effort="${limits['effort']}"
             velocity="${limits['velocity']}"/>
      <dynamics damping="0.1" friction="0.01"/>
    </joint>
  </xacro:macro>
  <link name="s0"/>
"""
_XACRO_CALL = """  <xacro:segment name="s{i}" parent="s{parent}" length="${{0.05 + {i} % 7 * 0.01}}"
                 flip="${{{i} % 2 == 0}}">
    <origin xyz="0 0 ${{0.05 + {parent} % 7 * 0.01}}" rpy="0 0 0"/>
  </xacro:segment>
"""


def xacro_robot(segments: int) -> str:
    """A xacro chain of ``segments`` macro calls (properties, math, nested macros, blocks,
    conditionals): about 1.1 kB of URDF a segment."""
    calls = "".join(_XACRO_CALL.format(i=i, parent=i - 1) for i in range(1, segments + 1))
    return _XACRO_HEAD + calls + "</robot>\n"
