import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    share = get_package_share_directory('case_rewritten')
    with open(os.path.join(share, 'flyer.urdf'), 'r') as file:
        robot_description = file.read().format_map({'share': share})
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': robot_description}]),
    ])
