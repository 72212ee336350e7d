"""``urdftool dynamics`` as text: every matrix and torque table says its unit."""

from __future__ import annotations

from urdftool.description.load import load
from urdftool.physics.dynamics import build, state
from urdftool.physics.gravity_bound import worst_loads
from urdftool.report import dynamics as render

ARM = ('<robot name="a"><link name="base"/><link name="arm"><inertial><origin xyz="0.2 0 0"/>'
       '<mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>'
       '</inertial></link><joint name="j" type="revolute"><parent link="base"/>'
       '<child link="arm"/><axis xyz="0 1 0"/>'
       '<limit lower="-1" upper="1" effort="10" velocity="1"/></joint></robot>')


def test_every_table_says_its_unit(tmp_path):
    path = tmp_path / "a.urdf"
    path.write_text(ARM)
    model = build(load(str(path)))
    result = state(model, {"j": 0.5}, {"j": 1.0}, {"j": 1.0})
    lines = render.text(result, worst_loads(model, 3, 0), 3).splitlines()
    titles = [line for line in lines if line and not line.startswith(" ")]
    torque = "[N m, or N for a prismatic joint]"
    # M, C, tau and the gravity loads had no unit (G alone said [N m or N])
    assert any(t.startswith("M(q): ") and "[kg m^2;" in t for t in titles)
    for start in ("G(q): ", "C(q, v): ", "tau = ", "static gravity load "):
        assert any(t.startswith(start) and torque in t for t in titles), start
