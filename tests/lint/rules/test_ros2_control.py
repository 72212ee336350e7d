"""U520: the numbers of a ros2_control interface's <param>s, as ros2_control and its hardware read them."""

from __future__ import annotations

import pytest

from crossfile_helpers import HEAD_ROBOT, check_folder
from urdftool.diagnostics import Severity


def _u520(tmp_path, plugin: str, interfaces: str, select=("U520",)) -> list:
    """The findings of head_joint's ros2_control ``interfaces`` under hardware ``plugin``."""
    body = f"""<ros2_control name="s" type="system"><hardware><plugin>{plugin}</plugin></hardware>
      <joint name="head_joint">{interfaces}</joint></ros2_control>"""
    return check_folder(tmp_path, {"robot.urdf": HEAD_ROBOT.format(body=body)}, select=select)[1]


def _said(tmp_path, plugin: str, interfaces: str, severity: Severity) -> str:
    """The message of the one U520 finding of ``interfaces``, which has ``severity``."""
    [finding] = _u520(tmp_path, plugin, interfaces)
    assert finding.severity == severity, finding.message
    return finding.message


def _bounds(low: str, high: str = "1", kind: str = "position", more: str = "") -> str:
    return (f'<command_interface name="{kind}"><param name="min">{low}</param>'
            f'<param name="max">{high}</param>{more}</command_interface>'
            '<state_interface name="position"/>')


def _initial(value: str, tag: str = "state_interface", kind: str = "position", attributes: str = "") -> str:
    return f'<{tag} name="{kind}"{attributes}><param name="initial_value">{value}</param></{tag}>'


def test_a_bound_xacro_left_as_written_is_skipped_by_jazzy_and_unread_by_humble(tmp_path):
    # neuromeka's indy.ros2_control.xacro wrote <param name="min">{-2*pi}</param> (no '$')
    message = _said(tmp_path, "mock_components/GenericSystem", _bounds("{-2*pi}"), Severity.WARNING)
    assert message.startswith("ros2_control joint 'head_joint' command_interface 'position': "
                              "min '{-2*pi}' is not a number: ros2_control (4.10.0 and later")
    assert "prints 'Error parsing the limits for the interface: position' and skips its min and max" in message
    assert "(nothing reads it in Humble)" in message
    assert "'{-2*pi}' is a xacro substitution without its '$' (${-2*pi})" in message


def test_a_bound_of_hardware_that_runs_only_where_ros2_control_reads_bounds_is_an_error(tmp_path):
    message = _said(tmp_path, "gz_ros2_control/GazeboSimSystem", _bounds("-1", "{pi}"), Severity.ERROR)
    assert "max '{pi}' is not a number" in message


def test_a_bound_of_humble_only_hardware_is_a_note_nothing_reads(tmp_path):
    # indy's hardware: fake_components/GenericSystem, Humble's last (nothing there reads min/max)
    message = _said(tmp_path, "fake_components/GenericSystem", _bounds("{-2*pi}"), Severity.INFO)
    assert "though nothing reads it where hardware 'fake_components/GenericSystem' runs (Humble)" in message


@pytest.mark.parametrize("text", ["-1", "-.5", "+1", "-1e0", " -1 ", "\n  -1\n"])
def test_numbers_ros2_control_reads_where_it_reads_bounds_are_not_reported(tmp_path, text):
    # (white space around a bound: Jazzy and later strip it; Humble reads no bound)
    assert _u520(tmp_path, "mock_components/GenericSystem", _bounds(text)) == []


@pytest.mark.parametrize("text", ["inf", "-inf", "nan", "0x10", "1,5", "1e400", "-1 rad", "pi"])
def test_what_ros2_control_cannot_parse_as_a_bound(tmp_path, text):
    # finite decimal numbers only: neither build of hardware_interface::stod takes these
    _said(tmp_path, "gz_ros2_control/GazeboSimSystem", _bounds(text), Severity.ERROR)


def test_a_sign_after_plus_is_read_by_the_cxx20_build_only(tmp_path):
    # from_chars after one '+' reads '-1'; the C++17 build's stream refuses '+-1'
    message = _said(tmp_path, "gz_ros2_control/GazeboSimSystem", _bounds("+-1"), Severity.WARNING)
    assert "(Jazzy and later, C++17 build)" in message
    assert "Jazzy and later, C++20 build read it as -1" in message


def test_bounds_ros2_control_does_not_read_are_a_note(tmp_path):
    gz = "gz_ros2_control/GazeboSimSystem"
    _said(tmp_path / "a", gz, _bounds("{-2*pi}", more='<limits enable="false"/>'), Severity.INFO)
    # ros2_control reads the bounds of five interfaces only, of command interfaces only
    _said(tmp_path / "b", gz, _bounds("{-2*pi}", kind="kp"), Severity.INFO)
    _said(tmp_path / "c", gz, '<state_interface name="position"><param name="min">x</param>'
          '</state_interface>', Severity.INFO)
    # acceleration's bounds are read with its limits disabled too (set_custom_interface_values)
    _said(tmp_path / "d", gz, _bounds("x", kind="acceleration", more='<limits enable="false"/>'),
          Severity.ERROR)


def test_the_last_param_of_a_name_is_the_one_read(tmp_path):
    twice = ('<command_interface name="position"><param name="min">x</param><param name="min">-1</param>'
             '</command_interface><state_interface name="position"/>')
    assert _u520(tmp_path / "a", "gz_ros2_control/GazeboSimSystem", twice) == []
    reversed_ = twice.replace(">x<", ">-2<").replace(">-1<", ">y<")
    assert "min 'y'" in _said(tmp_path / "b", "gz_ros2_control/GazeboSimSystem", reversed_, Severity.ERROR)


def test_an_initial_value_mock_hardware_cannot_parse_is_an_error(tmp_path):
    message = _said(tmp_path, "mock_components/GenericSystem", _initial("{0.0}"), Severity.ERROR)
    assert "mock_components/GenericSystem (Humble) throws 'Failed converting string to real number'" in message
    assert "(Jazzy and later) throws 'Invalid initial value'" in message


def test_a_command_initial_value_is_read_by_mock_hardware_from_jazzy(tmp_path):
    message = _said(tmp_path, "mock_components/GenericSystem",
                    _initial("x", tag="command_interface") + _initial("0"), Severity.WARNING)
    assert "(nothing reads it in Humble)" in message


def test_white_space_around_an_initial_value_breaks_humble_only(tmp_path):
    message = _said(tmp_path, "mock_components/GenericSystem", _initial("0.5\n      "), Severity.WARNING)
    assert "initial_value '0.5\\n      ' is not a number" in message
    assert "(Jazzy and later read it as 0.5)" in message


def test_gazebo_hardware_reads_initial_values_as_its_version_does(tmp_path):
    # Humble's gazebo_ros2_control reads with std::stod: '1.5rad' is 1.5 there
    assert _u520(tmp_path / "a", "gazebo_ros2_control/GazeboSystem", _initial("1.5rad")) == []
    # ign_ros2_control/IgnitionSystem runs in Humble (std::stod) and Jazzy (gz_ros2_control)
    message = _said(tmp_path / "b", "ign_ros2_control/IgnitionSystem", _initial("1.5rad"), Severity.WARNING)
    assert "Humble read it as 1.5" in message
    message = _said(tmp_path / "c", "gazebo_ros2_control/GazeboSystem", _initial("{-2*pi}"), Severity.ERROR)
    assert "Gazebo starts no controllers" in message
    # the Gazebo hardware reads the initial value of position, velocity and effort states only
    _said(tmp_path / "d", "gazebo_ros2_control/GazeboSystem", _initial("x", kind="temperature"), Severity.INFO)


def test_a_vendor_hardware_reads_an_initial_value_if_it_exports_the_default_way(tmp_path):
    message = _said(tmp_path, "vendor/Driver", _initial("x"), Severity.WARNING)
    assert "if the hardware exports its interfaces from the URDF (the default)" in message


def test_an_initial_value_of_another_data_type_is_not_judged(tmp_path):
    assert _u520(tmp_path, "mock_components/GenericSystem",
                 _initial("false", attributes=' data_type="bool"')) == []


def test_an_empty_param_is_unset(tmp_path):
    assert _u520(tmp_path, "mock_components/GenericSystem", _bounds("", "  ") + _initial("")) == []


def test_a_bound_ros2_control_cannot_read_is_not_compared_with_the_urdf_limit(tmp_path):
    # U515 read 'inf' with urdfdom's grammar and said it was beyond <limit>: ros2_control
    # refuses it (and skips the interface's min and max), which U520 says
    findings = _u520(tmp_path, "mock_components/GenericSystem", _bounds("-1", "inf"), select=("U515", "U520"))
    assert [f.code for f in findings] == ["U520"]
