"""Link files: urdftool reports a located error exactly where check_urdf (urdfdom) prints one."""

from __future__ import annotations

import pytest

from conftest import CHECK_URDF, check_urdf
from urdftool.lint.engine import CheckOptions, load_and_check

I6 = 'ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"'
BOX = '<geometry><box size="1 1 1"/></geometry>'
LINK_BODIES = {
    "no-mass": f'<inertial><inertia {I6}/></inertial>',
    "mass-no-value": f'<inertial><mass/><inertia {I6}/></inertial>',
    "no-inertia": '<inertial><mass value="1"/></inertial>',
    "inertia-missing-iyz": '<inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" '
                           'iyy="1" izz="1"/></inertial>',
    "mass-not-number": f'<inertial><mass value="x"/><inertia {I6}/></inertial>',
    "mass-nan": f'<inertial><mass value="nan"/><inertia {I6}/></inertial>',
    "mass-inf": f'<inertial><mass value="inf"/><inertia {I6}/></inertial>',
    "inertia-not-number": '<inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" '
                          'iyy="1" iyz="0" izz="q"/></inertial>',
    "inertial-origin-two-numbers": f'<inertial><origin xyz="0 0"/><mass value="1"/>'
                                   f'<inertia {I6}/></inertial>',
    "visual-rpy-words": f'<visual><origin rpy="a b c"/>{BOX}</visual>',
    "visual-xyz-word": f'<visual><origin xyz="0 0 x"/>{BOX}</visual>',
    "visual-without-geometry": '<visual></visual>',
    "collision-without-geometry": '<collision></collision>',
    "empty-geometry": '<visual><geometry/></visual>',
    "unknown-shape": '<visual><geometry><cone/></geometry></visual>',
    "box-without-size": '<visual><geometry><box/></geometry></visual>',
    "box-two-numbers": '<visual><geometry><box size="1 1"/></geometry></visual>',
    "cylinder-without-length": '<visual><geometry><cylinder radius="1"/></geometry></visual>',
    "cylinder-radius-word": '<visual><geometry><cylinder radius="x" length="1"/></geometry>'
                            '</visual>',
    "sphere-without-radius": '<visual><geometry><sphere/></geometry></visual>',
    "sphere-radius-nan": '<visual><geometry><sphere radius="nan"/></geometry></visual>',
    "mesh-without-filename": '<visual><geometry><mesh/></geometry></visual>',
    "mesh-scale-two-numbers": '<visual><geometry><mesh filename="a.stl" scale="1 1"/>'
                              '</geometry></visual>',
    "material-without-name": f'<visual>{BOX}<material/></visual>',
    "color-word": f'<visual>{BOX}<material name="m"><color rgba="1 x 0 1"/></material></visual>',
    "color-above-one": f'<visual>{BOX}<material name="m"><color rgba="1 0 0 2"/></material>'
                       '</visual>',
    "fine": f'<inertial><mass value="1"/><inertia {I6}/></inertial><visual>{BOX}</visual>',
}
ROBOT_BODIES = {
    "top-material-without-color": '<material name="m"/>',
    "top-material-without-name": '<material><color rgba="1 1 1 1"/></material>',
    "top-material-twice": '<material name="m"><color rgba="1 1 1 1"/></material>'
                          '<material name="m"><color rgba="1 0 1 1"/></material>',
}
CASES = {**{k: f'<link name="a">{v}</link>' for k, v in LINK_BODIES.items()},
         **{k: f'{v}<link name="a"/>' for k, v in ROBOT_BODIES.items()}}


@pytest.mark.parametrize("name", sorted(CASES))
def test_urdftool_errors_wherever_check_urdf_does(name, tmp_path):
    """urdfdom prints "Error:" for a link it cannot read and goes on (exit code 0), so its words,
    not its exit code, tell whether it found an error; both ways are asserted."""
    if CHECK_URDF is None:
        pytest.skip("urdfdom's check_urdf is not installed (the pin wheel of the analysis extra "
                    "has it)")
    path = tmp_path / f"{name}.urdf"
    path.write_text(f'<robot name="r">\n{CASES[name]}\n</robot>\n')
    run = check_urdf(path)
    said = run.stdout + run.stderr
    urdfdom_error = "Error:" in said
    # if urdfdom's wording changes, fail here rather than silently take the other branch
    assert urdfdom_error or (run.returncode == 0 and "Successfully Parsed XML" in run.stdout), said
    errors = [f for f in load_and_check(str(path), CheckOptions()).findings
              if f.severity.value == "error"]
    if urdfdom_error:
        assert errors, f"check_urdf rejects {name} but urdftool reports no error:\n{said}"
        assert all(f.line == 2 for f in errors), [str(f.location) for f in errors]
    else:
        assert not errors, [f"{f.code} {f.message}" for f in errors]
