from launch import LaunchDescription
from launch.substitutions import Command, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    share = FindPackageShare("case_remapped_arm_py")
    description = {"robot_description": Command(["xacro ", PathJoinSubstitution([share, "arm.urdf"])])}
    controllers = PathJoinSubstitution([share, "config", "arm_controllers.yaml"])
    moveit_controllers = PathJoinSubstitution([share, "config", "moveit_controllers.yaml"])
    return LaunchDescription([
        Node(package="controller_manager", executable="ros2_control_node",
             parameters=[description, controllers]),
        Node(package="controller_manager", executable="spawner",
             arguments=["joint_state_broadcaster", "arm_controller"]),
        Node(package="moveit_ros_move_group", executable="move_group",
             parameters=[description, moveit_controllers],
             remappings=[("scaled_joint_trajectory_controller/follow_joint_trajectory",
                          "arm_controller/follow_joint_trajectory")]),
    ])
