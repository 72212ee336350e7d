from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, FindExecutable, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    declared = [DeclareLaunchArgument("arm_type", choices=["a3", "a5"])]
    content = Command([
        PathJoinSubstitution([FindExecutable(name="xacro")]), " ",
        PathJoinSubstitution([FindPackageShare("case_arm"), "arm.urdf.xacro"]), " ",
        "name:=", "arm", " ",
        "arm_type:=", LaunchConfiguration("arm_type"),
    ])
    node = Node(package="robot_state_publisher", executable="robot_state_publisher",
                parameters=[{"robot_description": content}])
    return LaunchDescription(declared + [node])
