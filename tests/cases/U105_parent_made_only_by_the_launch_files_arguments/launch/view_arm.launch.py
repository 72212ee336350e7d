import os

import xacro
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    path = os.path.join(get_package_share_directory("case_optical_arm"), "arm.urdf.xacro")
    description = xacro.process_file(path, mappings={"frames": "true"}).toxml()
    node = Node(package="robot_state_publisher", executable="robot_state_publisher",
                parameters=[{"robot_description": description}])
    return LaunchDescription([node])
