"""``urdftool inertia`` as text: each link's declared and computed inertial, with its units."""

from __future__ import annotations

from urdftool.description.load import load
from urdftool.physics.inertia_compare import compare
from urdftool.report import inertia as render

BOX = ('<robot name="b"><link name="box"><inertial><origin xyz="0 0 0.1"/><mass value="2"/>'
       '<inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'
       '<collision><origin xyz="0 0 0.1"/><geometry><box size="0.1 0.2 0.3"/></geometry>'
       '</collision></link></robot>')


def test_every_quantity_says_its_unit(tmp_path):
    path = tmp_path / "b.urdf"
    path.write_text(BOX)
    declared, computed = render.text(compare(load(str(path)))).splitlines()[1:3]
    # the centre of mass and the tensor had no unit: [m] and [kg m^2] were left to guess
    for line in (declared, computed):
        assert " kg  com [m] 0 0 0.1 " in line and "ixx iyy izz ixy ixz iyz [kg m^2] " in line
    assert computed.endswith("[kg m^2] 0.02167 0.01667 0.008333 0 0 0")
