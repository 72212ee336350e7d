# The spawner is in a group inside a group with a condition (husarion_ugv_ros' bringup: a
# TimerAction in GroupAction(condition=IfCondition(hw_config_correct))): the controller runs
# only when the outer condition holds, so its defect is a warning naming it, never a certain
# error.
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, GroupAction
from launch.conditions import IfCondition
from launch.substitutions import Command, FindExecutable, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    robot_description = Command([
        FindExecutable(name="xacro"), " ",
        PathJoinSubstitution([FindPackageShare("case_arm_nested_group"), "arm.urdf.xacro"]),
    ])
    controllers = PathJoinSubstitution(
        [FindPackageShare("case_arm_nested_group"), "config", "controllers.yaml"])
    return LaunchDescription([
        DeclareLaunchArgument("use_hardware", default_value="false"),
        Node(package="controller_manager", executable="ros2_control_node",
             parameters=[{"robot_description": robot_description}, controllers]),
        GroupAction([
            GroupAction([
                Node(package="controller_manager", executable="spawner",
                     arguments=["joint_state_broadcaster", "arm_controller"]),
            ]),
        ], condition=IfCondition(LaunchConfiguration("use_hardware"))),
    ])
