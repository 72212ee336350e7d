# (named without test_/_test so that pytest does not collect it; a tests/ folder makes it a possible launch test)
# A launch test left half-edited (not valid Python): urdftool cannot tell whether it reads
# the file as it is
import os

from ament_index_python.packages import get_package_share_directory
import launch
from launch_ros.actions import Node


def generate_test_description():
    path = os.path.join(get_package_share_directory("case_trolley_unread"), "trolley.xacro.urdf")
    with open(path) as file:
        description = file.read(
    node = Node(package="robot_state_publisher", executable="robot_state_publisher",
                parameters=[{"robot_description": description}])
    return launch.LaunchDescription([node])
