from launch import LaunchDescription
from launch.substitutions import Command, FindExecutable, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    robot_description_content = Command([
        PathJoinSubstitution([FindExecutable(name="xacro")]), " ",
        PathJoinSubstitution([FindPackageShare("case_trolley_unread"), "trolley.xacro.urdf"]),
    ])
    node = Node(package="robot_state_publisher", executable="robot_state_publisher",
                parameters=[{"robot_description": robot_description_content}])
    return LaunchDescription([node])
