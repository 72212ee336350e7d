"""U3xx inertial rules added for issue 14: inertia far from its geometry (U310) and a mass no
material can have in its volume (U311)."""

from __future__ import annotations

import pytest

from crossfile_helpers import check_folder

LINK = """<robot name="r">
  <link name="base_link"/>
  <joint name="j" type="continuous"><parent link="base_link"/><child link="a"/>
    <axis xyz="0 0 1"/></joint>
  <link name="a">
    <inertial><origin xyz="{com}"/><mass value="{mass}"/>
      <inertia ixx="{i}" ixy="0" ixz="0" iyy="{i}" iyz="0" izz="{i}"/></inertial>
    <collision><geometry>{geometry}</geometry></collision>
    {visual}
  </link>
</robot>
"""


def _check(tmp_path, code, mass, i, geometry, com="0 0 0", visual=""):
    text = LINK.format(mass=mass, i=i, geometry=geometry, com=com, visual=visual)
    return check_folder(tmp_path, {"robot.urdf": text}, select=(code,))


ROD = '<box size="0.02 0.02 1"/>'  # 1 kg uniform: ixx = iyy = 0.0834, izz = 6.7e-5, trace 0.167


CUBE = '<box size="0.1 0.1 0.1"/>'  # 1 kg uniform: 0.001667 on each axis


@pytest.mark.parametrize("i, com, geometry, reported", [
    (0.1, "0 0 0", ROD, False),       # close to the rod's own
    (0.6, "0 0 0", ROD, True),        # trace 1.8, 11 times; over 2 m R^2 (0.5): no mass can
    (0.6, "0 0 0.5", ROD, False),     # 11 times, but with the com at the end 2 m R^2 = 2
    (0.004, "0 0 0", ROD, True),      # 14 times smaller: a placeholder
    (1.667, "0 0 0", CUBE, False),    # 1000 times: U309's unit mistake, not this
])
def test_inertia_far_from_geometry(tmp_path, i, com, geometry, reported):
    found, findings = _check(tmp_path, "U310", 1, i, geometry, com=com)
    assert bool(found) == reported, [f.message for f in findings]


def test_inertia_far_from_an_open_mesh_is_not_judged(tmp_path):
    (tmp_path / "open.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\n")
    found, _ = _check(tmp_path, "U310", 1, 50, '<mesh filename="open.obj" scale="0.1 0.1 0.1"/>')
    assert not found


@pytest.mark.parametrize("mass, geometry, visual, reported", [
    (54, '<box size="0.3 0.2 0.01"/>', "", True),           # 90,000 kg/m^3
    (1.6, '<box size="0.3 0.2 0.01"/>', "", False),         # aluminium
    (2, '<box size="0.2 0.2 0.5"/>', "", False),            # a hollow shell's envelope: 100
    (1e-3, '<box size="1 1 1"/>', "", True),                # lighter than aerogel
    (0.05, '<box size="0.01 0.01 0.01"/>', "", False),      # a 1 cm marker box, not a body
    # a small collision sphere at the foot, the leg drawn by its visual: the bigger counts
    (0.5, '<sphere radius="0.01"/>', '<visual><geometry><box size="0.04 0.04 0.3"/>'
     "</geometry></visual>", False),
])
def test_implausible_density(tmp_path, mass, geometry, visual, reported):
    found, findings = _check(tmp_path, "U311", mass, 1e-3, geometry, visual=visual)
    assert bool(found) == reported, [f.message for f in findings]
