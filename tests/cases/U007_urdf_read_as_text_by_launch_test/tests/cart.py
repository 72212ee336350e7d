# (named without test_/_test so that pytest does not collect it; a tests/ folder makes it a possible launch test)
# A launch test reading the file as it is: a consumer that does not run xacro, so the file's
# xacro is an error whatever the launch file does
import os

from ament_index_python.packages import get_package_share_directory
import launch
from launch_ros.actions import Node


def generate_test_description():
    path = os.path.join(get_package_share_directory("case_cart_text"), "cart.xacro.urdf")
    with open(path) as file:
        description = file.read()
    node = Node(package="robot_state_publisher", executable="robot_state_publisher",
                parameters=[{"robot_description": open(path).read()}])
    return launch.LaunchDescription([node])
