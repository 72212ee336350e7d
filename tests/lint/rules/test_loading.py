"""U011 (robot-name-missing) over a folder check: a nameless <robot> is an error where a launch
file of its repository loads it as the robot, and a warning naming the condition in a xacro
file nothing here builds (Autoware's <model>_description/urdf/vehicle.xacro, which
tier4_vehicle_launch's named robot includes)."""

from __future__ import annotations

PACKAGE = """<?xml version="1.0"?>
<package format="3"><name>car_description</name><version>0.1.0</version>
<description>d</description><maintainer email="a@b.c">a</maintainer><license>MIT</license>
<buildtool_depend>ament_cmake</buildtool_depend><exec_depend>xacro</exec_depend></package>
"""
VEHICLE = """<?xml version="1.0"?>
<robot xmlns:xacro="http://ros.org/wiki/xacro">
  <link name="base_link">
    <visual><geometry><box size="4 2 1.5"/></geometry></visual>
  </link>
</robot>
"""
LAUNCH = """<launch>
  <node pkg="robot_state_publisher" exec="robot_state_publisher">
    <param name="robot_description"
           value="$(command 'xacro $(find-pkg-share car_description)/urdf/vehicle.xacro')"/>
  </node>
</launch>
"""


def _package(tmp_path, launched: bool):
    folder = tmp_path / "car_description"
    (folder / "urdf").mkdir(parents=True)
    (folder / ".git").mkdir()
    (folder / "package.xml").write_text(PACKAGE)
    (folder / "urdf" / "vehicle.xacro").write_text(VEHICLE)
    if launched:
        (folder / "launch").mkdir()
        (folder / "launch" / "vehicle.launch.xml").write_text(LAUNCH)
    return folder


def _u011(folder):
    from urdftool.lint.runner import check_paths
    from urdftool.lint.settings import CheckRequest

    run = check_paths([str(folder)], CheckRequest(jobs=1))
    return [finding for result in run.results for finding in result.findings
            if finding.code == "U011"]


def test_a_nameless_xacro_robot_nothing_here_builds_is_a_warning_naming_the_condition(tmp_path):
    found = _u011(_package(tmp_path, launched=False))
    assert [f.severity.value for f in found] == ["warning"]
    assert "no launch file here builds it" in found[0].message
    assert "urdfdom refuses it" in found[0].message


def test_an_empty_name_in_a_xacro_robot_nothing_here_builds_is_not_said_to_be_refused(tmp_path):
    """``<robot name="">`` in a xacro nothing here builds was said as "has no name attribute:
    urdfdom refuses it if it is loaded alone": it has the attribute, and urdfdom takes it. The
    condition said is what holds: the attribute absent, urdfdom refuses it; empty, a robot
    without a name."""
    folder = _package(tmp_path, launched=False)
    vehicle = folder / "urdf" / "vehicle.xacro"
    vehicle.write_text(VEHICLE.replace("<robot ", '<robot name="" '))
    [found] = _u011(folder)
    assert found.severity.value == "warning"
    assert found.message.startswith('<robot> has an empty name (name=""): loaded alone it is '
                                    "a robot without a name (urdfdom takes it")
    assert "refuses" not in found.message and "no name attribute" not in found.message
    assert "no launch file here builds it" in found.message


def test_a_nameless_xacro_robot_a_launch_file_loads_is_an_error(tmp_path):
    found = _u011(_package(tmp_path, launched=True))
    assert [(f.severity.value, f.message) for f in found] == [
        ("error", '<robot> has no name attribute; add name="..."')]


FRAGMENT = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro"{name}>
  <xacro:thruster_macro robot_namespace="${{namespace}}" thruster_id="0">
    <origin xyz="0.1 -0.1 0" rpy="0 0 0.785"/>
  </xacro:thruster_macro>
</robot>
"""


def _u005(tmp_path, name: str):
    folder = tmp_path / "rov_description"
    (folder / "urdf").mkdir(parents=True)
    (folder / ".git").mkdir()
    (folder / "package.xml").write_text(PACKAGE.replace("car_description", "rov_description"))
    (folder / "urdf" / "actuators.xacro").write_text(FRAGMENT.format(name=name))
    from urdftool.lint.runner import check_paths
    from urdftool.lint.settings import CheckRequest

    run = check_paths([str(folder)], CheckRequest(jobs=1))
    return [finding for result in run.results for finding in result.findings
            if finding.code == "U005"]


def test_a_nameless_fragment_calling_a_macro_its_includer_defines_is_a_warning(tmp_path):
    """DTUAqua-ObsTek/bluerov2's urdf/gazebo/actuators.xacro: thruster macro calls inside a
    nameless <robot>, for base.xacro to include inside its macro (which defines ${namespace}
    and includes the thruster macro); base.xacro names it by a path that moved, so nothing
    here reaches it, and alone xacro fails on the macro. A named robot stays an error."""
    found = _u005(tmp_path / "nameless", "")
    assert [f.severity.value for f in found] == ["warning"]
    assert "its <robot> has no name" in found[0].message
    named = _u005(tmp_path / "named", ' name="rov"')
    assert [f.severity.value for f in named] == ["error"]


def test_an_empty_robot_name_is_said_as_empty(tmp_path):
    from urdftool.description.load import load
    from urdftool.lint.rules.loading import robot_name_missing

    path = tmp_path / "r.urdf"
    path.write_text('<robot name=""><link name="a"/></robot>')
    [(_, message)] = robot_name_missing(load(str(path)))
    assert message == '<robot> has an empty name (name=""); give it one'
