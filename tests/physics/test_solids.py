"""A link's geometry as solids and boxes (physics/solids.py)."""

from __future__ import annotations

import pytest

from urdftool.description.load import load
from urdftool.physics.solids import rigid_bounds

# base (1 cm cube) -fixed, 1 m along x and turned 90 deg about z- sensor (a 10 x 20 x 30 cm
# box 0.1 m along the sensor's own x) -fixed- tip; arm moves (not part of base's body).
RIGID = """<robot name="r">
  <link name="base"><collision><geometry><box size="0.01 0.01 0.01"/></geometry></collision></link>
  <link name="sensor"><visual><origin xyz="0.1 0 0"/><geometry><box size="0.1 0.2 0.3"/></geometry></visual></link>
  <link name="tip"/>
  <link name="arm"><visual><geometry><sphere radius="5"/></geometry></visual></link>
  <joint name="f" type="fixed"><parent link="base"/><child link="sensor"/>
    <origin xyz="1 0 0" rpy="0 0 1.5707963267948966"/></joint>
  <joint name="g" type="fixed"><parent link="sensor"/><child link="tip"/></joint>
  <joint name="m" type="revolute"><parent link="base"/><child link="arm"/>
    <limit lower="0" upper="1" effort="1" velocity="1"/></joint>
</robot>"""


def _robot(tmp_path, text=RIGID):
    (tmp_path / "r.urdf").write_text(text)
    return load(tmp_path / "r.urdf")


def test_rigid_bounds_join_links_fixed_either_way_in_the_link_frame(tmp_path):
    robot = _robot(tmp_path)
    base = rigid_bounds(robot, robot.links["base"])
    assert base.links == ["base", "sensor", "tip"] and base.complete
    # the sensor box, turned 90 deg: x in [0.9, 1.1] (its y), y in [0.05, 0.15] (its x)
    assert base.bounds[0] == pytest.approx((-0.005, -0.005, -0.15))
    assert base.bounds[1] == pytest.approx((1.1, 0.15, 0.15))
    tip = rigid_bounds(robot, robot.links["tip"])  # reached through its parent, backwards
    assert tip.links == ["tip", "sensor", "base"]
    assert tip.bounds[0] == pytest.approx((-0.005, -0.1, -0.15))
    assert tip.bounds[1] == pytest.approx((0.15, 1.005, 0.15))


def test_rigid_bounds_say_when_a_mesh_could_not_be_measured(tmp_path):
    robot = _robot(tmp_path, RIGID.replace('<box size="0.1 0.2 0.3"/>',
                                           '<mesh filename="missing.stl"/>'))
    base = rigid_bounds(robot, robot.links["base"])
    assert not base.complete and base.bounds[1] == pytest.approx((0.005,) * 3)
