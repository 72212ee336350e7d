# The packages of the robot and of its controllers are launch arguments (ros2_control_demos'
# and UR's description_package, runtime_config_package): the controller runs against this robot
# when they keep their defaults, so its defect is a warning saying so.
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, FindExecutable, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    description_package = LaunchConfiguration("description_package")
    runtime_config_package = LaunchConfiguration("runtime_config_package")
    robot_description = Command([
        FindExecutable(name="xacro"), " ",
        PathJoinSubstitution([FindPackageShare(description_package), "arm.urdf.xacro"]),
    ])
    controllers = PathJoinSubstitution(
        [FindPackageShare(runtime_config_package), "config", "controllers.yaml"])
    return LaunchDescription([
        DeclareLaunchArgument("description_package", default_value="case_arm_by_argument"),
        DeclareLaunchArgument("runtime_config_package", default_value="case_arm_by_argument"),
        Node(package="controller_manager", executable="ros2_control_node",
             parameters=[{"robot_description": robot_description}, controllers]),
        Node(package="controller_manager", executable="spawner",
             arguments=["joint_state_broadcaster", "arm_controller"]),
    ])
