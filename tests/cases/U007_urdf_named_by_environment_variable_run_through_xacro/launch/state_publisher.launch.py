import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.substitutions import Command
from launch_ros.actions import Node


def generate_launch_description():
    # TurtleBot3's way: the model is chosen by an environment variable, not a launch argument
    model = os.environ['ROVER_MODEL']
    urdf = os.path.join(get_package_share_directory('case_rover_description'),
                        'rover_' + model + '.urdf')
    description = Command(['xacro ', urdf, ' namespace:=', os.getenv('ROVER_NAMESPACE', '')])
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': description}])])
