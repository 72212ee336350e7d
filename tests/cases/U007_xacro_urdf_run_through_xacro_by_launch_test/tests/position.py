# (named without test_/_test so that pytest does not collect it; a tests/ folder makes it a possible launch test)
# A launch test (launch_testing): read, never run, for how it builds the robot; what it starts
# (the controllers) runs for the test alone
import os

from ament_index_python.packages import get_package_share_directory
import launch
from launch_ros.actions import Node
from launch_testing.actions import ReadyToTest
import pytest
import xacro


@pytest.mark.launch_test
def generate_test_description():
    path = os.path.join(get_package_share_directory("case_cart_test"), "cart.xacro.urdf")
    doc = xacro.parse(open(path))
    xacro.process_doc(doc)
    state_publisher = Node(package="robot_state_publisher", executable="robot_state_publisher",
                           parameters=[{"robot_description": doc.toxml()}])
    spawner = Node(package="controller_manager", executable="spawner",
                   arguments=["cart_controller"])
    return launch.LaunchDescription([state_publisher, spawner, ReadyToTest()])
