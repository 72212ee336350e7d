from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, FindExecutable, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    description = Command([
        FindExecutable(name="xacro"), " ",
        PathJoinSubstitution([FindPackageShare("case_together_arm"), "arm.urdf.xacro"]),
        " ", "prefix:=", LaunchConfiguration("prefix"),
    ])
    controllers = PathJoinSubstitution(
        [FindPackageShare("case_together_arm"), "config", "arm_controllers.yaml"])
    spawn = ["joint_state_broadcaster", "joint_trajectory_controller", "forward_position_controller"]
    return LaunchDescription([
        DeclareLaunchArgument("prefix", default_value='""'),
        Node(package="controller_manager", executable="ros2_control_node",
             parameters=[{"robot_description": description}, controllers]),
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": description}]),
        Node(package="controller_manager", executable="spawner", arguments=spawn),
        # switched to when needed: loaded inactive, it claims nothing
        Node(package="controller_manager", executable="spawner",
             arguments=["forward_velocity_controller", "--inactive"]),
    ])
