"""U630-U633 and U607: controller parameters against the controllers' own definitions."""

from __future__ import annotations

import textwrap

import pytest

from crossfile_helpers import HEAD_ROBOT, check_folder
from urdftool.description import controllers as model
from urdftool.diagnostics import Severity

ROS2 = """<ros2_control name="s" type="system"><hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="head_joint"><command_interface name="position"/><state_interface name="position"/></joint>
  </ros2_control>"""
MANAGER = """\
    controller_manager:
      ros__parameters:
        update_rate: 100
        joint_state_broadcaster:
          type: joint_state_broadcaster/JointStateBroadcaster
        head_controller:
          type: {type}
    """


def _check(tmp_path, yaml, body=ROS2, select=("U607", "U63")):
    return check_folder(tmp_path, {"robot.urdf": HEAD_ROBOT.format(body=body), "config/c.yaml": yaml},
                        select=select)


def _manager(kind: str, block: str = "") -> str:
    return textwrap.dedent(MANAGER.format(type=kind)) + textwrap.dedent(block)


def _jtc(block: str) -> str:
    return _manager("joint_trajectory_controller/JointTrajectoryController", block)


def test_type_slips_are_warnings_naming_the_condition(tmp_path):
    found, findings = _check(tmp_path, _jtc("""\
        head_controller:
          ros__parameters:
            joints: head_joint
            command_interfaces: [position]
            state_interfaces: [position]
            action_monitor_rate: 20
        """))
    assert found == [("c.yaml", 10, "U630"), ("c.yaml", 13, "U630")]
    assert all(f.severity == Severity.WARNING for f in findings)
    assert "write joints: [head_joint]" in findings[0].message
    assert "if 'head_controller' is started, it fails to configure" in findings[0].message
    assert "write action_monitor_rate: 20.0" in findings[1].message


def test_a_started_controller_fails_to_configure_an_error(tmp_path, monkeypatch):
    monkeypatch.setattr(model, "started", lambda robot, controller: True if controller.name == "head_controller" else None)
    yaml = _jtc("""\
        head_controller:
          ros__parameters:
            joints: head_joint
            command_interfaces: [position]
            state_interfaces: [position]
        other_controller:
          ros__parameters:
            type: joint_trajectory_controller/JointTrajectoryController
            joints: head_joint
            command_interfaces: [position]
            state_interfaces: [position]
        """)
    _, findings = _check(tmp_path, yaml)
    by_name = {f.message.split("'")[1]: f for f in findings}
    assert by_name["head_controller"].severity == Severity.ERROR
    assert "if 'head_controller'" not in by_name["head_controller"].message
    assert by_name["other_controller"].severity == Severity.WARNING
    monkeypatch.setattr(model, "started", lambda robot, controller: False)
    assert _check(tmp_path, yaml)[0] == []  # started by nothing: nothing to say


def test_a_list_mixing_types_breaks_the_whole_file(tmp_path):
    found, findings = _check(tmp_path, _jtc("""\
        head_controller:
          ros__parameters:
            joints: [head_joint]
            command_interfaces: [position]
            state_interfaces: [position]
        odometry:
          ros__parameters:
            covariance: [0.1, 0, 0.1]
        """))
    assert found == [("c.yaml", 15, "U630")]
    assert findings[0].severity == Severity.ERROR and "[0.1, 0.0, 0.1]" in findings[0].message


def test_manager_update_rate_is_an_integer(tmp_path):
    yaml = _jtc("").replace("update_rate: 100", "update_rate: 100.0")
    found, findings = _check(tmp_path, yaml, select=("U630",))
    assert found == [("c.yaml", 3, "U630")] and findings[0].severity == Severity.ERROR


@pytest.mark.parametrize("rate, said", [
    ("9223372036854775808", "9223372036854775808 is past int64"),
    ("-9223372036854775809", "-9223372036854775809 is past int64"),
    ("1" + "0" * 300, "(301 characters) is past int64"),
])
def test_an_integer_past_int64_is_a_double_to_ros_2_and_said(tmp_path, rate, said):
    """rcl_yaml_param_parser reads an integer with strtoll, which refuses one past int64
    (ERANGE), then with strtod: a double, which the controller manager refuses for its
    integer update_rate. PyYAML's reading held a Python int of any size: nothing was said."""
    found, findings = _check(tmp_path, _jtc("").replace("update_rate: 100", f"update_rate: {rate}"),
                             select=("U630",))
    assert found == [("c.yaml", 3, "U630")]
    assert "must be an integer, not a double (" in findings[0].message and said in findings[0].message
    assert "which ROS 2 reads as a double); give it an integer" in findings[0].message
    found, _ = _check(tmp_path, _jtc("").replace("update_rate: 100", "update_rate: 9223372036854775807"),
                      select=("U630",))
    assert found == []


def test_a_word_for_a_number_is_not_said_to_be_quoted(tmp_path):
    """"write update_rate: junk without quotes" was said of a word written without quotes:
    only a string that is a number written plain was one in quotes."""
    found, findings = _check(tmp_path, _jtc("").replace("update_rate: 100", "update_rate: junk"),
                             select=("U630",))
    assert found == [("c.yaml", 3, "U630")] and "give it an integer" in findings[0].message


def test_numbers_ros_2_reads_but_pyyaml_does_not_are_not_called_strings(tmp_path):
    found, _ = _check(tmp_path, _jtc("""\
        head_controller:
          ros__parameters:
            joints: [head_joint]
            command_interfaces: [position]
            state_interfaces: [position]
            action_monitor_rate: 2e1
            cmd_timeout: "0.5"
        """))
    assert found == [("c.yaml", 14, "U630")]  # "0.5" in quotes is a string; 2e1 is ROS 2's double


def test_validation_and_the_distribution_that_allows_it(tmp_path):
    found, findings = _check(tmp_path, _jtc("""\
        head_controller:
          ros__parameters:
            joints: [head_joint]
            command_interfaces: [position]
            state_interfaces: [position]
            interpolation_method: spline
            state_publish_rate: 50.0
            gains:
              head_joint: {p: 1.0, i_clamp: 0.5}
        """))
    # state_publish_rate is Humble's, i_clamp Humble's and Jazzy's: no finding
    assert found == [("c.yaml", 13, "U631")]
    assert "must be one of splines, none" in findings[0].message
    # the condition joined as every clause is (PAROL6's "(effort is not one) ; if ...")
    assert " ;" not in findings[0].message, findings[0].message


def test_unknown_parameter_with_a_suggestion_once_per_unknown_group(tmp_path):
    found, findings = _check(tmp_path, _jtc("""\
        /**:
          ros__parameters:
            publish_frequency: 50.0
        head_controller:
          ros__parameters:
            joints: [head_joint]
            command_interfaces: [position]
            state_interfaces: [position]
            state_interface: [position]
            velocity_ff:
              head_joint: 1.0
              neck_joint: 1.0
        """))
    assert found == [("c.yaml", 16, "U632"), ("c.yaml", 17, "U632")]
    assert "did you mean 'state_interfaces'?" in findings[0].message
    assert "'velocity_ff' (nor anything under it" in findings[1].message


def test_an_unknown_parameter_another_class_reads_names_that_class(tmp_path):
    # Space ROS's Canadarm and Curiosity: interface_name given to JointTrajectoryController;
    # it is the forward command controllers' parameter, and the message listed JTC's 40
    # parameters without saying where the name comes from
    found, findings = _check(tmp_path, _jtc("""\
        head_controller:
          ros__parameters: {joints: [head_joint], command_interfaces: [position],
                            state_interfaces: [position], interface_name: position}
        """))
    assert [code for _, _, code in found] == ["U632"]
    assert "'interface_name' is a parameter of effort_controllers/JointGroupEffortController, " \
           "forward_command_controller/ForwardCommandController and 2 more, not of this class" \
           in findings[0].message, findings[0].message


def test_a_block_for_another_implementation_of_the_name_is_not_judged(tmp_path):
    # husarion_controllers' mecanum_drive_controller predates ros2_controllers' one
    yaml = _manager("mecanum_drive_controller/MecanumDriveController", """\
        head_controller:
          ros__parameters:
            front_left_wheel_name: a
            front_right_wheel_name: b
            rear_left_wheel_name: c
            rear_right_wheel_name: d
            wheel_separation_x: 0.3
            base_frame_id: base_link
        """)
    assert _check(tmp_path, yaml)[0] == []


def test_blocks_of_one_controller_in_several_namespaces_are_read_together(tmp_path):
    yaml = """\
        /**/controller_manager:
          ros__parameters:
            update_rate: 10
        /**/head_controller:
          ros__parameters:
            type: forward_command_controller/ForwardCommandController
            interface_name: position
        /robot_1/head_controller:
          ros__parameters:
            joints: [head_joint]
        """
    assert _check(tmp_path, yaml, select=("U602", "U607", "U63"))[0] == []


def test_values_outside_ros_parameters_break_the_file(tmp_path):
    found, findings = _check(tmp_path, _jtc("""\
        head_controller:
          joints: [head_joint]
          command_interfaces: [position]
        """))
    assert found == [("c.yaml", 9, "U633")]  # once, not a U607 for the controller too
    assert findings[0].severity == Severity.ERROR and "Cannot have a value before" in findings[0].message


def test_parameters_in_the_managers_declaration_are_read_by_nobody(tmp_path):
    yaml = _jtc("").replace(
        "    type: joint_trajectory_controller/JointTrajectoryController\n",
        "    type: joint_trajectory_controller/JointTrajectoryController\n      joints: [head_joint]\n")
    found, findings = _check(tmp_path, yaml, select=("U633",))
    assert found == [("c.yaml", 8, "U633")] and findings[0].severity == Severity.WARNING


@pytest.mark.parametrize("yaml, expected", [
    # ROS 1 converts an integer to a double; a string is not a number
    ("jsc: {type: joint_state_controller/JointStateController, publish_rate: 50}\n", []),
    ("jsc: {type: joint_state_controller/JointStateController, publish_rate: '50'}\n",
     [("c.yaml", 1, "U630")]),
    ("jsc: {type: joint_state_controller/JointStateController}\n", [("c.yaml", 1, "U607")]),
    ("h:\n  type: effort_controllers/JointPositionController\n  joint: head_joint\n  pid: {p: 10.0}\n", []),
    ("h:\n  type: effort_controllers/JointPositionController\n  joint: head_joint\n", [("c.yaml", 1, "U607")]),
])
def test_ros1_parameters(tmp_path, yaml, expected):
    body = """<transmission name="t"><type>transmission_interface/SimpleTransmission</type>
      <joint name="head_joint"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
      <actuator name="m"/></transmission>"""
    assert _check(tmp_path, yaml, body=body)[0] == expected
